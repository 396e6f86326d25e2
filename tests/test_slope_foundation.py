"""A block on a flexible foundation on sloping ground (issue #17, item 3: every model runs on an
inclined plane). The run starts at rest in the static equilibrium on the slope; stiff
foundations give the rigid block on the same slope."""
import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.model.foundation import block_inertia

BODY = fr.RigidBlock.rectangle(b=0.3, h=1.0)
PHI = math.radians(5.0)
SLOPE = fr.Ground(slope=PHI)
BLK = block_inertia(BODY, 1.0)
MGH = BLK.M * BLK.g * BLK.h


def _foundations(omega=20.0, zeta=0.05):
    return [fr.TwoSpringFoundation.from_vibration(BODY, omega, zeta),
            fr.SwitchingFoundation.from_vibration(BODY, omega, zeta, e_f=BODY.e),
            fr.LinearVibration.from_vibration(BODY, omega, zeta)]


def test_static_equilibrium_closed_forms():
    ts, sw, lin = _foundations()
    yc, _, q, _ = ts.initial_state(BLK, 0.0, 0.0, SLOPE)
    assert yc == pytest.approx(-BLK.M * BLK.g * math.cos(PHI) / (2 * ts.k_v), rel=1e-15)
    assert ts.k_v * BLK.b ** 2 * math.sin(2 * q) == pytest.approx(MGH * math.sin(q + PHI), rel=1e-13)
    th = sw.initial_state(BLK, 0.0, 0.0, SLOPE)[0]
    assert sw.k_t * th == pytest.approx(MGH * math.sin(th + PHI), rel=1e-13)
    assert lin.initial_state(BLK, 0.0, 0.0, SLOPE)[0] == MGH * math.sin(PHI) / lin.k_t
    assert 0.0 < q < BODY.alpha and 0.0 < th < BODY.alpha        # tilted downhill


@pytest.mark.parametrize("k", [0, 1, 2], ids=["two_spring", "switching", "linear"])
def test_the_block_stays_at_rest_without_shaking(k):
    fnd = _foundations()[k]
    r = fr.simulate(BODY, None, foundation=fnd, ground=SLOPE, duration=5.0, rtol=1e-10)
    theta = r.history["theta"].to_numpy()
    th0 = fnd.initial_state(BLK, 0.0, 0.0, SLOPE)[2 if k == 0 else 0]
    assert r.status == "safe:no-uplift"
    assert np.max(np.abs(theta - th0)) < 1e-9 * th0


@pytest.mark.parametrize("sign", [1, -1])
def test_stiff_foundations_uplift_like_the_rigid_block_on_the_slope(sign):
    """Before uplift both foundation models are the rigid block on the slope in the stiff limit:
    the uplift time converges to the rigid one (about 1/omega^2), which differs from level
    ground by 30 % (g tan(alpha -+ phi) thresholds)."""
    pulse = fr.Pulse(3.0, 2.0, sign=sign)
    rigid = fr.simulate(BODY, pulse, ground=SLOPE, duration=4.0).metrics["time_uplift"]
    level = fr.simulate(BODY, pulse, duration=4.0).metrics["time_uplift"]
    assert abs(level / rigid - 1.0) > 0.2
    for fnd_of in (fr.TwoSpringFoundation.from_vibration, fr.SwitchingFoundation.from_vibration):
        err = [abs(fr.simulate(BODY, pulse, foundation=fnd_of(BODY, om, 0.3), ground=SLOPE, duration=4.0,
                               rtol=1e-10).metrics["time_uplift"] / rigid - 1.0) for om in (1e3, 3e3, 1e4)]
        assert err[0] > err[1] > err[2] and err[2] < 1e-5, err


def test_stiff_switching_spectrum_is_the_rigid_spectrum_on_the_slope():
    """The switching model rocks as Housner's block once it lifts off; with e_f = e and stiff
    springs its spectrum on the slope is the rigid block's, cell by cell. (The two-spring model
    is not: it holds its base centre, not the pivot, so along the slope gravity works on the
    pivot's slide b(1 - cos q); 4 of these 72 cells differ at omega = 1e4, none on level ground.)
    The uplift rotation theta_y = M g b / k_t is about 1e-6 rad here, so the uplift time needs an
    atol well below it: the default (1e-10) resolves theta_y to 1e-4, which the stiff method, whose
    steps follow the tolerance, shows (DP5's steps were far shorter, bound by the springs)."""
    amps, freqs = np.linspace(0.8, 5, 6), np.linspace(0.5, 6, 6)
    rigid = fr.overturning_spectrum(BODY, amps, freqs, sign=[1, -1], ground=SLOPE, progress=False)
    fnd = fr.SwitchingFoundation.from_vibration(BODY, 1e4, 0.3, e_f=BODY.e)
    soft = fr.overturning_spectrum(BODY, amps, freqs, sign=[1, -1], ground=SLOPE, foundation=fnd, progress=False,
                                   solver=fr.Solver(atol=1e-14))
    assert list(soft["outcome"].astype(str)) == list(rigid["outcome"].astype(str))
    assert set(rigid["outcome"].astype(str)) >= {"safe", "mode1", "mode2"}
    np.testing.assert_allclose(soft["time_uplift"], rigid["time_uplift"], rtol=0, atol=2e-6)
    # the spectrum's cells are simulate's runs
    for i in (3, 40):
        r = fr.simulate(BODY, fr.Pulse(soft["amplitude_ratio"][i], soft["frequency_ratio"][i],
                                       sign=int(soft["sign"][i])), foundation=fnd, ground=SLOPE,
                        solver=fr.Solver(atol=1e-14))
        assert r.outcome == soft["outcome"][i]
        assert r.metrics["max_rotation"] == pytest.approx(soft["max_rotation"][i], rel=1e-12)


def test_scene_and_batch_on_a_slope(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('[body]\ntype = "rigid"\nb = 0.3\nh = 1.0\n[foundation]\ntype = "switching"\n'
                    'omega = 20.0\nzeta = 0.05\n[ground]\nslope = 0.0872664626\n'
                    '[excitation]\nkind = "one-sine"\namplitude = 1.5\nfrequency = 2.0\n')
    scene = fr.Scene.from_toml(path)
    one = scene.run()
    ref = fr.simulate(BODY, fr.Pulse(1.5, 2.0), foundation=scene.foundation, ground=scene.ground)
    assert one.status == ref.status and one.metrics["max_rotation"] == ref.metrics["max_rotation"]
    table = fr.run_batch([scene], progress=False)
    assert table["outcome"][0] == ref.outcome
    assert table["max_rotation"][0] == pytest.approx(ref.metrics["max_rotation"], rel=1e-12)


def test_bad_input_on_a_slope():
    ts = fr.TwoSpringFoundation.from_vibration(BODY, 20.0, 0.05)
    with pytest.raises(ValueError, match="theta0"):
        fr.simulate(BODY, None, foundation=ts, ground=SLOPE, theta0=0.01)
    soft = fr.SwitchingFoundation.from_vibration(BODY, 1.6)    # its tilt on 5 deg reaches uplift (0.23 rad)
    with pytest.raises(ValueError, match=r"slope = .*rocks at once"):
        fr.simulate(BODY, fr.Pulse(1.0, 2.0), foundation=soft, ground=SLOPE)
    for omega, why in ((1.7, "leaves its spring"), (1.5, "no stable resting tilt")):
        with pytest.raises(ValueError, match=f"slope = .*{why}"):
            fr.overturning_spectrum(BODY, [1.0], [2.0], foundation=fr.TwoSpringFoundation.from_vibration(BODY, omega),
                                    ground=SLOPE, progress=False)
