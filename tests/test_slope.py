"""Sloping ground (issue #17, item 3): Ground(slope=phi).

Oracles: level ground through Ground(0) is the same run bit for bit; the
uplift thresholds g tan(alpha -/+ phi) downhill/uphill in closed form;
Newmark's rigid sliding block in closed form (rectangular pulse) and against
an independent exact integration of a real record.
"""
import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.io.default_records import load_default_record

G = fr.G_STANDARD
PHI = math.radians(10.0)
BLOCK = fr.RigidBlock.rectangle(0.15, 0.6)


def _stout(e=0.0):
    # tan(alpha) = 4: it slides long before it could rock
    return fr.RigidBlock.rectangle(width=2.0, height=0.5, e=e)


def _same(a, b):
    pd_testing = pytest.importorskip("pandas").testing
    pd_testing.assert_frame_equal(a.history, b.history, check_exact=True)
    assert a.outcome == b.outcome
    assert a.metrics == b.metrics


@pytest.mark.parametrize("effects", [{}, {"friction": fr.Friction(0.3)},
                                     {"wall": fr.Wall(gap=0.01, side=1)}])
def test_level_ground_is_bit_identical(effects):
    blk = fr.RigidBlock.rectangle(0.25, 1.0)
    pulse = fr.Pulse(1.5, 0.6, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    a = fr.simulate(blk, pulse, **effects)
    b = fr.simulate(blk, pulse, ground=fr.Ground(0.0), **effects)
    _same(a, b)
    assert "slope" not in b.effects


def test_level_ground_spectrum_is_bit_identical():
    blk = fr.RigidBlock(alpha=0.25, p=2.0)
    a = fr.overturning_spectrum(blk, [2.0, 4.0], [0.5, 2.0], progress=False)
    b = fr.overturning_spectrum(blk, [2.0, 4.0], [0.5, 2.0], ground=fr.Ground(0.0), progress=False)
    pytest.importorskip("pandas").testing.assert_frame_equal(a, b, check_exact=True)


@pytest.mark.parametrize("downhill", [True, False])
def test_uplift_thresholds_downhill_and_uphill(downhill):
    """Rotating gravity by phi: a horizontal pull a_h tips the block downhill
    (theta > 0) beyond g tan(alpha - phi) and uphill beyond g tan(alpha + phi)."""
    alpha = 0.3
    blk = fr.RigidBlock(alpha=alpha, p=2.0)
    ground = fr.Ground(PHI)
    threshold = G * math.tan(alpha - PHI if downhill else alpha + PHI)
    # the ground accelerates uphill (-x) to tip the block downhill (+theta), and vice versa
    sign = -1 if downhill else 1
    rows = []
    for factor in (1 - 1e-6, 1 + 1e-6):
        pulse = fr.Pulse(threshold * factor / G, sign=sign, kind="rectangular", duration=0.2)
        r = fr.simulate(blk, pulse, ground=ground, duration=0.3)
        rows.append((r.metrics["time_uplift"], r.history["theta"].to_numpy()))
    (t_below, th_below), (t_above, th_above) = rows
    assert not np.isfinite(t_below) and np.all(th_below == 0.0)
    assert np.isfinite(t_above)
    moved = th_above[np.abs(th_above) > 0]
    expected = 1 if downhill else -1
    # it lifts off toward the expected side (after the pulse it rocks back and forth)
    assert moved.size and np.sign(moved[0]) == expected


def test_stands_at_rest_without_shaking():
    blk = fr.RigidBlock(alpha=0.3, p=2.0)
    r = fr.simulate(blk, None, ground=fr.Ground(PHI), duration=2.0, friction=fr.Friction(0.5))
    assert r.outcome == "safe"
    assert np.all(r.history["theta"] == 0.0) and np.all(r.history["d"] == 0.0)


def _newmark_mu(ac):
    """mu with Newmark's critical acceleration ac along the slope:
    ac = g (mu cos(phi) - sin(phi)) (the issue's mu = tan(phi) + ac/g holds
    to first order in phi)."""
    return math.tan(PHI) + ac / (G * math.cos(PHI))


def test_newmark_rectangular_pulse_closed_form():
    ac = 0.1 * G
    A, T = 0.3 * G, 0.5
    r = fr.simulate(_stout(), fr.Pulse(A / G, sign=-1, kind="rectangular", duration=T),
                    friction=fr.Friction(_newmark_mu(ac)), ground=fr.Ground(PHI, direction="slope"),
                    rtol=1e-10, atol=1e-12)
    newmark = (A - ac) * A * T ** 2 / (2 * ac)
    assert r.outcome == "slide"
    assert r.metrics["residual_slide"] == pytest.approx(newmark, rel=1e-9)
    assert np.all(np.diff(r.history["d"].to_numpy()) >= -1e-12)      # downslope only
    assert np.all(r.history["theta"] == 0.0)


def newmark_exact(acc, dt, ac):
    """Newmark's rigid block, one-way (downslope), integrated exactly on a
    piecewise-linear record acc [m/s^2] along the slope: while sliding the
    relative acceleration -acc(t) - ac is linear inside each interval, so
    the velocity is quadratic and the displacement cubic; sliding starts
    where -acc rises above ac and stops where the velocity returns to zero."""
    d = v = 0.0
    sliding = False
    for i in range(acc.size - 1):
        a0 = -acc[i] - ac
        k = (-acc[i + 1] - ac - a0) / dt            # a(s) = a0 + k s on [0, dt]
        s0 = 0.0
        while s0 < dt:
            if not sliding:
                if a0 + k * s0 > 0.0:
                    sliding = True
                elif k > 0.0 and s0 < -a0 / k < dt:
                    s0 = -a0 / k
                    sliding = True
                else:
                    break
            # v(s) = c + a0 s + k s^2 / 2 with v(s0) = v
            c = v - a0 * s0 - 0.5 * k * s0 * s0
            roots = np.roots([0.5 * k, a0, c]) if k != 0.0 else np.array([-c / a0])
            stops = sorted(float(r.real) for r in np.atleast_1d(roots)
                           if abs(r.imag) == 0.0 and s0 < r.real <= dt and a0 + k * r.real < 0.0)
            end = stops[0] if stops else dt

            def disp(s):
                return c * s + 0.5 * a0 * s * s + k * s ** 3 / 6.0
            d += disp(end) - disp(s0)
            if stops:
                v = 0.0
                sliding = False
                s0 = end
            else:
                v = c + a0 * dt + 0.5 * k * dt * dt
                break
    return d


def test_newmark_real_record_against_exact_integration():
    rec = load_default_record()
    acc = np.asarray(rec.acc, float)        # m/s^2
    ac = 0.05 * G
    expected = newmark_exact(acc, rec.dt, ac)
    r = fr.simulate(_stout(), fr.SampledMotion(acc, rec.dt), friction=fr.Friction(_newmark_mu(ac)),
                    ground=fr.Ground(PHI, direction="slope"), rtol=1e-11, atol=1e-13)
    assert expected > 0.01         # it does slide, by centimetres
    assert abs(r.metrics["residual_slide"] - expected) < 1e-6
    assert r.history["d"].min() >= -1e-12


def test_horizontal_record_slides_by_the_rotated_balance():
    """A horizontal pull on a slope: sliding downhill starts where
    -a_h cos(phi) + g sin(phi) = mu (g cos(phi) + a_h sin(phi)), i.e. at
    a_h = -g tan(phi_f - phi), phi_f = atan(mu)."""
    mu = 0.4
    threshold = G * math.tan(math.atan(mu) - PHI)
    out = []
    for factor in (1 - 1e-6, 1 + 1e-6):
        r = fr.simulate(_stout(), fr.Pulse(threshold * factor / G, sign=-1, kind="rectangular", duration=0.3),
                        friction=fr.Friction(mu), ground=fr.Ground(PHI), duration=1.0)
        out.append(r.metrics["max_slide"])
    assert out[0] == 0.0 and out[1] > 0.0


@pytest.mark.parametrize("slope", [-0.1, math.pi / 2, float("nan"), "steep"])
def test_bad_slope(slope):
    with pytest.raises(ValueError, match="slope"):
        fr.Ground(slope)


def test_bad_direction():
    with pytest.raises(ValueError, match="direction"):
        fr.Ground(0.1, direction="vertical")


def test_slope_steeper_than_friction_or_slenderness():
    blk = fr.RigidBlock(alpha=0.3, p=2.0)
    pulse = fr.Pulse(0.1, 1.0)
    with pytest.raises(ValueError, match="slope.*mu_s"):
        fr.simulate(blk, pulse, friction=fr.Friction(0.1), ground=fr.Ground(math.atan(0.2)))
    with pytest.raises(ValueError, match="slope.*cannot stand"):
        fr.simulate(blk, pulse, ground=fr.Ground(0.31))
    with pytest.raises(ValueError, match="slope.*cannot stand"):
        fr.overturning_spectrum(blk, [1.0], [1.0], ground=fr.Ground(0.31), progress=False)


def test_flexible_body_starts_at_its_static_deflection():
    """Without shaking a flexible body on a slope stays exactly where it starts: the column at
    u = g sin(phi) / omega_n^2 downhill, the base flat."""
    body = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=8.0, zeta=0.05)
    ground = fr.Ground(math.radians(4.0))
    u_s = ground.static_deflection(body)
    assert u_s == pytest.approx(G * math.sin(ground.slope) / body.omega_n ** 2)
    for friction in (None, fr.Friction(0.5)):
        r = fr.simulate(body, None, ground=ground, duration=3.0, friction=friction)
        assert r.status == "safe:no-uplift"
        assert np.all(r.history["u"] == u_s) and np.all(r.history["theta"] == 0.0)
        if friction is not None:
            assert np.all(r.history["d"] == 0.0)


def test_stiff_flexible_body_on_a_slope_is_the_rigid_block():
    """The stiff limit (omega_n/p = 200) on a 4-degree slope: the same outcomes and max
    rotations (to 1e-3) as its rigid equivalent on a pulse grid, both signs."""
    flex = fr.FlexibleBody(alpha=0.25, p=2.0, omega_n_over_p=200.0, zeta=0.05)
    ground = fr.Ground(math.radians(4.0))
    grid = dict(amplitude_ratios=[0.6, 1.0, 1.5, 2.5, 4.0], frequency_ratios=[0.5, 1.5, 3.0], sign=[1, -1],
                ground=ground, progress=False)
    a = fr.overturning_spectrum(flex, **grid)
    b = fr.overturning_spectrum(flex.rigid_equivalent(), **grid)
    assert list(a["outcome"]) == list(b["outcome"])
    assert set(a["outcome"]) >= {"safe", "mode1", "mode2"}
    np.testing.assert_allclose(a["max_rotation_ratio"], b["max_rotation_ratio"], atol=1e-3)


def test_flexible_body_that_cannot_stand_is_refused():
    soft = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=1.2, zeta=0.05)
    ground = fr.Ground(0.15)
    assert ground.flexible_rest_margin(soft, 0.0) <= 0.0
    with pytest.raises(ValueError, match="slope.*flexible body cannot stand"):
        fr.simulate(soft, fr.Pulse(0.01, 1.0), ground=ground)


def test_lift_off_refused_for_the_rocking_model():
    blk = fr.RigidBlock(alpha=1.2, p=2.0, e=0.0)
    with pytest.raises(ValueError, match="lifts the block off"):
        fr.simulate(blk, fr.Pulse(7.0, 1.0), ground=fr.Ground(0.3))


def test_spectrum_on_a_slope_is_asymmetric():
    """Pulses of either sign are mirror images on level ground (the same
    outcomes); on a slope they are not, and more blocks fall."""
    blk = fr.RigidBlock(alpha=0.25, p=2.0)
    grid = dict(amplitude_ratios=np.linspace(1.0, 4.0, 13), frequency_ratios=[1.0, 2.0, 4.0], progress=False)
    counts = {}
    for phi in (0.0, math.radians(5.0)):
        ground = fr.Ground(phi)
        up = fr.overturning_spectrum(blk, sign=1, ground=ground, **grid)
        down = fr.overturning_spectrum(blk, sign=-1, ground=ground, **grid)
        assert up.attrs["slope"] == phi
        counts[phi] = ((up["outcome"] != down["outcome"]).sum(),
                       (up["outcome"] != "safe").sum() + (down["outcome"] != "safe").sum())
    (diff_level, fell_level), (diff_slope, fell_slope) = counts.values()
    assert diff_level == 0 and diff_slope > 0
    assert fell_slope > fell_level


def test_cli_slope(tmp_path):
    from fastrock.cli.app import main
    csv = tmp_path / "s.csv"
    main(["spectrum", "--quiet", "--slope", "0.05", "--n-amp", "3", "--n-freq", "2", "--csv", str(csv),
          "--png", str(tmp_path / "s.png")])
    import pandas as pd
    df = pd.read_csv(csv, comment="#")
    assert len(df) == 6
    assert main(["spectrum", "--quiet", "--slope", "0.5", "--alpha", "0.25",
                 "--png", str(tmp_path / "x.png")]) == 2


def test_scene_with_ground(tmp_path):
    """A TOML scene's [ground] section reaches the run: the same result as simulate(ground=...)."""
    toml = tmp_path / "slope.toml"
    toml.write_text('[body]\nalpha = 0.25\np = 2.0\n'
                    '[excitation]\nkind = "one-sine"\namplitude = 0.35\nfrequency = 0.5\n'
                    '[friction]\nmu_s = 0.6\n'
                    '[ground]\nslope = 0.05\n')
    scene = fr.Scene.from_toml(toml)
    assert "slope" in scene.effects
    a = scene.run()
    b = fr.simulate(fr.RigidBlock(alpha=0.25, p=2.0), fr.Pulse(0.35, 0.5), friction=fr.Friction(0.6),
                    ground=fr.Ground(0.05))
    _same(a, b)
    toml.write_text('[body]\nalpha = 0.25\np = 2.0\n[ground]\nslope = 0.05\ntilt = 1\n')
    with pytest.raises(ValueError, match=r"\[ground\].*tilt"):
        fr.Scene.from_toml(toml)


def test_study_variant_on_a_slope(tmp_path):
    """A study variant with a ground: every row equals simulate(ground=...) of the same scene."""
    pytest.importorskip("pyarrow")
    from fastrock.studies.definition import Study
    from fastrock.studies.run import run_study
    rec = load_default_record()
    record = type(rec)(rec.acc[:500], rec.dt, name="El Centro, first 10 s")
    body = fr.RigidBlock.rectangle(0.15, 0.6)
    study = Study(records=[record], bodies=[body], levels=[0.2, 0.6], t_after=2.0,
                  variants=[{"name": "level", "wall": None},
                            {"name": "rock", "ground": {"slope": 0.05}},
                            {"name": "slide", "ground": {"slope": 0.05}, "friction": {"mu_s": 0.3}}])
    df = run_study(study, tmp_path / "out", progress=False)
    scenes = {"level": {}, "rock": dict(ground=fr.Ground(0.05)),
              "slide": dict(ground=fr.Ground(0.05), friction=fr.Friction(0.3))}
    for _, row in df.iterrows():
        motion = fr.SampledMotion.from_record(record, scale=row["scale"])
        r = fr.simulate(body, motion, t_after=2.0, early_exit=True, **scenes[row["variant"]])
        assert r.status == row["status"], row["variant"]
        assert r.metrics["max_rotation_ratio"] == row["max_rotation_ratio"]
    with pytest.raises(Exception, match="slope"):
        Study(records=[record], bodies=[body], levels=[0.2],
              variants=[{"ground": {"slope": 0.3}}]).prepare()


def test_asymmetric_body_on_a_slope_uses_its_downhill_side():
    """An asymmetric body (pivots at -b1 and +b2): the downhill (+x) side's
    alpha2 sets both its standing limit and its downhill uplift threshold
    g tan(alpha2 - phi)."""
    body = fr.RigidBody(mass=1.0, inertia=0.05, b1=0.3, h1=0.6, b2=0.15, h2=0.6)
    alpha2 = math.atan2(0.15, 0.6)
    ground = fr.Ground(math.radians(5.0))
    threshold = G * math.tan(alpha2 - ground.slope)
    lifted = []
    for factor in (1 - 1e-6, 1 + 1e-6):
        r = fr.simulate(body, fr.Pulse(threshold * factor / G, sign=-1, kind="rectangular", duration=0.2),
                        ground=ground, duration=0.3)
        lifted.append(bool(np.isfinite(r.metrics["time_uplift"])))
    assert lifted == [False, True]
    with pytest.raises(ValueError, match="downhill side"):
        fr.simulate(body, fr.Pulse(0.01, 1.0), ground=fr.Ground(alpha2 + 0.01))


def test_rocking_spectrum_on_a_slope():
    """The beta spectrum takes ground=: a level Ground is the level run bit for bit; a 3-degree
    slope leaves fewer blocks of the grid standing under El Centro; a grid with blocks that cannot
    stand on the slope is refused naming it."""
    import pandas as pd
    from fastrock.analyses.rocking_spectrum.engine import rocking_spectrum_runs
    kw = dict(slenderness=np.linspace(0.15, 0.5, 8), half_widths=[0.2, 0.5, 1.0], walls=[None], progress=False)
    level = rocking_spectrum_runs(None, **kw)
    pd.testing.assert_frame_equal(level, rocking_spectrum_runs(None, ground=fr.Ground(0.0), **kw))
    sloped = rocking_spectrum_runs(None, ground=fr.Ground(math.radians(3.0)), **kw)
    assert sloped.attrs["slope"] == math.radians(3.0)
    assert sloped["stable"].sum() < level["stable"].sum()
    table = fr.rocking_spectrum(None, ground=fr.Ground(math.radians(3.0)), **kw)
    assert len(table) == 3
    with pytest.raises(ValueError, match="slope.*cannot stand"):
        fr.rocking_spectrum(None, slenderness=[0.05, 0.3], half_widths=[0.5], walls=[None],
                            ground=fr.Ground(math.radians(5.0)), progress=False)
