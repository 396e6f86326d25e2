"""An asymmetric RigidBody beside a rear wall in the wall model (issue #17, "every model accepts
it": walls): the wall kernels with each pivot's own alpha, p and impact map (registry entry
``wall_body``), so Hogan's one-sided rocking at gap 0, short walls and the small-gap limit work
for it as for the block (kernels/wall.py, "Asymmetric body").

Oracles: the RigidBlock (a symmetric body is it, bit for bit), the mirror image, Housner's exact
quarter period per side and Hogan's map at gap 0 (E -> e_w^2 E per cycle, the pivot kept), the
contact model with a pivot that never slips (the same physics at a gap d > 0), the two-sided
model (a wall out of reach), the block's short-wall geometry, and the energy of every impact."""
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fastrock as fr
from fastrock.kernels import layout as L
from fastrock.running import registry
from test_rigid_body import quarter_period_exact  # noqa: E402  (Housner's quarter period, one side)

OUTLINE = [(0.0, 0.0), (1.0, 0.0), (0.8, 2.2), (0.0, 2.2)]     # right face leaning back
BODY = fr.RigidBody.from_polygon(OUTLINE, mass=1.0)
MIRROR = fr.RigidBody.from_polygon([(-x, y) for x, y in OUTLINE], mass=1.0)
AMPS, FREQS = np.array([1.2, 2.5, 5.0]), np.array([0.8, 2.5, 6.0])


def side_numbers(body, s):
    """alpha, p, R, I_O of pivot s (+1: side 2, -1: side 1)."""
    if s > 0:
        return body.alpha2, body.p2, body.R2, body.inertia_about_pivot2
    return body.alpha1, body.p1, body.R1, body.inertia_about_pivot1


def restitution_leaving(body, s):
    return body.e21 if s > 0 else body.e12


def spectrum(body, **kw):
    return fr.overturning_spectrum(body, AMPS, FREQS, sign="both", progress=False, **kw)


def test_the_registry_runs_the_wall_model():
    assert registry.select(BODY, fr.Wall(0.05, side=1)).name == "wall_body"
    assert registry.select(BODY, fr.Wall(0.0)).name == "wall_body"
    assert registry.select(BODY, fr.Wall(0.05), fr.Friction(0.5)).name == "contact_body"
    assert registry.select(BODY, fr.Wall(0.05), fr.Friction.never_slipping()).name == "contact_body"
    # the block's wall module, with its own entries: the per-side rhs and events (the block's
    # entries keep rigid.rhs and rigid.event, which read one alpha and p)
    from fastrock.kernels import wall as W
    assert registry.MODELS["wall_body"].module == registry.MODELS["rigid_wall"].module == "wall"
    assert W.wall_body_simulate is not W.rigid_wall_simulate
    # both sides in the parameter vector; a block fills both with its own numbers
    par = registry.select(BODY, fr.Wall(0.05, side=1)).par
    assert par.size == L.N_PAR_WALL
    assert (par[L.P_ALPHA], par[L.P_ALPHA_NEG], par[L.P_P], par[L.P_P_NEG]) == (
        BODY.alpha2, BODY.alpha1, BODY.p2, BODY.p1)
    assert (par[L.P_E], par[L.P_E_NEG]) == (BODY.e21, BODY.e12)
    block = fr.RigidBlock.rectangle(0.2, 0.8)
    bp = registry.select(block, fr.Wall(0.05)).par
    assert (bp[L.P_ALPHA_NEG], bp[L.P_P_NEG], bp[L.P_E_NEG], bp[L.P_IO_RATIO]) == (
        bp[L.P_ALPHA], bp[L.P_P], bp[L.P_E], 1.0)


@pytest.mark.parametrize("wall", [fr.Wall(0.05, side=1), fr.Wall(0.0, side=-1, restitution=0.8),
                                  fr.Wall(0.05, side=1, height=1.0)])
def test_a_symmetric_body_is_the_block_bit_for_bit(wall):
    sym = fr.RigidBody.from_polygon([(0, 0), (0.6, 0), (0.6, 2.0), (0, 2.0)], mass=1.0)
    assert sym.is_symmetric
    a = spectrum(sym, wall=wall)
    b = spectrum(sym.to_block(), wall=wall)
    assert a.attrs["kernel"] == b.attrs["kernel"] == "rigid_wall"
    pd.testing.assert_frame_equal(a, b)
    # the body's own per-side vector (wall_body's) is the block's: the same kernel input
    from fastrock.running.models import wall_par
    exact = fr.RigidBody(mass=2.0, inertia=0.3, b1=0.3, h1=1.0, b2=0.3, h2=1.0,
                         outline=[(-0.3, -1.0), (0.3, -1.0), (0.3, 1.0), (-0.3, 1.0)])
    assert np.array_equal(wall_par(exact, wall), wall_par(exact.to_block(), wall))
    # frozen wall grids and tests/test_wall*.py: the per-side kernel gives the block's old runs


def test_mirror_body_mirror_wall_mirror_pulse():
    for gap in (0.0, 0.05):
        a = fr.overturning_spectrum(BODY, AMPS, FREQS, sign=1, wall=fr.Wall(gap, side=1, restitution=0.9),
                                    progress=False)
        b = fr.overturning_spectrum(MIRROR, AMPS, FREQS, sign=-1, wall=fr.Wall(gap, side=-1, restitution=0.9),
                                    progress=False)
        assert a.attrs["kernel"] == b.attrs["kernel"] == "wall_body"
        assert list(a["outcome"].astype(str)) == list(b["outcome"].astype(str))
        assert list(a["wall_impacts"]) == list(b["wall_impacts"])
        assert list(a["side"]) == list(-b["side"])
        np.testing.assert_allclose(a["max_rotation"], b["max_rotation"], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("w", [1, -1])
def test_gap_zero_free_rocking_closed_form(w):
    """Released at rest at theta0 away from the wall (gap 0, restitution r): the body rocks on the
    far pivot -w only.  Each return to theta = 0 is Hogan's impact theta'+ = -r theta'- on the
    same pivot: the energy E = cos(alpha - theta_peak) - cos(alpha) (units M g R of that side)
    drops to r^2 E per cycle, and the impacts come at T/4(theta0) and then every 2 T/4(theta_k)
    (Housner's quarter period with that side's alpha and p)."""
    r = 0.8
    alpha, p, _R, _io = side_numbers(BODY, -w)
    theta0 = 0.6 * alpha
    E = math.cos(alpha - theta0) - math.cos(alpha)
    times, pre = [], []
    t, th = 0.0, theta0
    for k in range(4):
        t += quarter_period_exact(alpha, p, th) * (1 if k == 0 else 2)
        times.append(t)
        pre.append(p * math.sqrt(2.0 * E))      # |theta'| at theta = 0
        E *= r * r
        th = alpha - math.acos(math.cos(alpha) + E)
    res = fr.simulate(BODY, None, wall=fr.Wall(0.0, side=w, restitution=r), theta0=-w * theta0,
                      duration=times[-1] * 1.0001, rtol=1e-12)
    assert res.kernel == "wall_body"
    ev = res.events
    imp = ev[ev["event"] == "wall-impact"]
    assert len(imp) == 4
    np.testing.assert_allclose(imp["t"], times, rtol=1e-9)
    np.testing.assert_allclose(np.abs(imp["velocity_before"]), pre, rtol=1e-8)
    np.testing.assert_allclose(imp["velocity_after"] / imp["velocity_before"], -r, rtol=1e-12)
    assert (imp["pivot"] == -w).all()                              # the pivot is kept
    assert res.metrics["wall_impacts"] == res.metrics["ground_impacts"] == 4
    h = res.history
    assert (w * h["theta"] <= 1e-12).all()                         # never toward the wall
    assert res.metrics["max_rotation"] == pytest.approx(theta0, rel=1e-12)


@pytest.mark.parametrize("w", [1, -1])
def test_gap_zero_uplifts_only_away_from_the_wall(w):
    """From rest at gap 0 the body lifts off only onto the far pivot -w, above g tan(alpha_-w)
    (a ground acceleration a_g with w a_g > 0 tips it there); toward the wall even four times
    g tan of the other side lifts nothing."""
    alpha_far = side_numbers(BODY, -w)[0]
    thr = BODY.g * math.tan(alpha_far)
    wall = fr.Wall(0.0, side=w, restitution=0.8)

    def first_half(amp, sign):
        pulse = fr.Pulse(amp, 2.0, sign=sign, amplitude_unit="m/s2", frequency_unit="Hz")
        return fr.simulate(BODY, pulse, wall=wall, duration=0.24)    # the first half-cycle only

    lifted = first_half(thr * (1 + 1e-6), w)
    assert not math.isnan(lifted.metrics["time_uplift"]) and (w * lifted.history["theta"]).min() < 0.0
    assert math.isnan(first_half(thr * (1 - 1e-6), w).metrics["time_uplift"])
    alpha_near = side_numbers(BODY, w)[0]
    toward = first_half(4.0 * BODY.g * math.tan(alpha_near), -w)
    assert math.isnan(toward.metrics["time_uplift"]) and (toward.history["theta"] == 0.0).all()


def test_small_gap_limit_composes_the_three_impacts():
    """A wall closer than 1e-7 rad runs Hogan's map with r = e_-w e_w e_w(wall) (a ground impact onto
    the near pivot, the wall, a ground impact back: the angular-momentum maps of both sides), and
    a gap of 1e-4 rad resolved by the d > 0 model gives nearly that over its three impacts."""
    w, ew = 1, 0.9
    face = BODY.h2 + BODY.wall_face_top(w)
    alpha = BODY.alpha1
    theta0 = 0.5 * alpha
    limit = fr.simulate(BODY, None, wall=fr.Wall(face * 1e-9, side=w, restitution=ew), theta0=-w * theta0,
                        duration=1.5, rtol=1e-11)
    imp = limit.events[limit.events["event"] == "wall-impact"]
    r = BODY.e12 * BODY.e21 * ew
    np.testing.assert_allclose(imp["velocity_after"] / imp["velocity_before"], -r, rtol=1e-12)
    resolved = fr.simulate(BODY, None, wall=fr.Wall(face * math.sin(1e-4), side=w, restitution=ew),
                           theta0=-w * theta0, duration=1.5, rtol=1e-11)
    ev = resolved.events
    first = ev[ev["event"].isin(["impact", "wall-impact"])].iloc[:3]
    assert list(first["event"]) == ["impact", "wall-impact", "impact"]
    # the moments act over the 2e-4 rad swing to the wall and back: a relative O(1e-4) change
    ratio = first["velocity_after"].iloc[2] / first["velocity_before"].iloc[0]
    assert ratio == pytest.approx(-r, rel=1e-3)


def test_gap_against_the_contact_model():
    """At a gap d > 0 the wall model and the contact model with a pivot that never slips model
    the same physics: on the cells where the contact model never flies, run to the end (the two
    models' early decisions book impacts differently), the same outcomes, ground and wall impact
    counts, and max rotations to the integration tolerance (rtol 1e-10 on both; they differ by
    9e-10 at most here)."""
    solver = fr.Solver(rtol=1e-10)
    amps, freqs = np.array([0.9, 1.5, 2.5, 4.0]), np.array([1.0, 2.5, 5.0])
    for side in (1, -1):
        wall = fr.Wall(0.05, side=side, restitution=0.8)
        kw = dict(sign="both", wall=wall, solver=solver, progress=False, early_exit=False)
        a = fr.overturning_spectrum(BODY, amps, freqs, **kw)
        b = fr.overturning_spectrum(BODY, amps, freqs, friction=fr.Friction.never_slipping(), **kw)
        assert a.attrs["kernel"] == "wall_body" and b.attrs["kernel"] == "contact_body"
        keep = (b["flights"] == 0).to_numpy()
        assert keep.sum() >= 15 and (a["wall_impacts"][keep] > 0).sum() >= 8
        for col in ("outcome", "wall_impacts", "ground_impacts"):
            assert list(a[col].astype(str)[keep]) == list(b[col].astype(str)[keep]), col
        np.testing.assert_allclose(a["max_rotation"][keep], b["max_rotation"][keep], rtol=1e-8, atol=0)


def test_short_wall():
    """A wall lower than the body's wall-side face: its top edge stops the face at
    tan(theta_w) = d / h_w (the block's rule), so the body leans at most theta_w toward it; a tall
    wall at the gap that gives the same theta_w is the same run."""
    w, d, hw = 1, 0.05, 0.8
    face = BODY.h2 + BODY.wall_face_top(w)
    short = fr.Wall(d, side=w, height=hw)
    assert hw < face and short.contact(BODY) == "short"
    tw = math.atan2(d, hw)
    assert short.limit_angle(BODY) == tw
    par = registry.select(BODY, short).par
    assert par[L.P_THETA_W] == tw
    pulse = fr.Pulse(3.0, 2.0, sign=-w, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    a = fr.simulate(BODY, pulse, wall=short, rtol=1e-10)
    assert a.metrics["wall_impacts"] > 0
    assert a.metrics["max_rotation_pos" if w > 0 else "max_rotation_neg"] == pytest.approx(tw, rel=1e-12)
    tall = fr.Wall(face * math.sin(tw), side=w)
    assert tall.contact(BODY) == "tall" and tall.limit_angle(BODY) == pytest.approx(tw, rel=1e-14)
    b = fr.simulate(BODY, pulse, wall=tall, rtol=1e-10)
    assert (a.outcome, a.metrics["wall_impacts"]) == (b.outcome, b.metrics["wall_impacts"])
    assert a.metrics["max_rotation"] == pytest.approx(b.metrics["max_rotation"], rel=1e-9)
    # with friction it runs the contact model (tests/test_contact_short_wall.py).  This pulse
    # throws the body away from the wall onto its far side, where it overturns: the short wall's
    # edge, below the wall-side face's line continued past the base corner, is no contact there
    # (before fc6a5fc a phantom wall impact held the body; contact:2027:251 in
    # tests/test_contact_fuzz_cases.py).  A weaker pulse leaves it standing.
    c = fr.simulate(BODY, pulse, wall=short, friction=fr.Friction(0.5))
    assert c.kernel == "contact_body" and c.status == "overturn:mode1", c.status
    assert c.history.iloc[-1]["theta"] < 0.0 and c.metrics["wall_impacts"] > 0
    weak = fr.Pulse(1.5, 2.0, sign=-w, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    c = fr.simulate(BODY, weak, wall=short, friction=fr.Friction(0.5))
    assert c.kernel == "contact_body" and not c.status.startswith("failed"), c.status


def test_wall_out_of_reach_is_no_wall():
    """A wall farther than the wall-side face's height is never reached: the two-sided model's
    runs, bit for bit without the early decisions (which differ between the models' bookkeeping),
    the same outcomes with them."""
    far = BODY.h2 + BODY.wall_face_top(1)
    wall = fr.Wall(1.01 * far, side=1)
    assert wall.contact(BODY) == "none"
    a = spectrum(BODY, wall=wall, early_exit=False)
    b = spectrum(BODY, early_exit=False)
    assert a.attrs["kernel"] == "wall_body" and b.attrs["kernel"] == "rigid_body"
    for col in ("outcome", "status", "side", "max_rotation", "ground_impacts"):
        if col in b:
            assert list(a[col]) == list(b[col]), col
    assert (a["wall_impacts"] == 0).all()
    assert list(spectrum(BODY, wall=wall)["outcome"]) == list(spectrum(BODY)["outcome"])


def _impacts_never_add_energy(body, res):
    ev = res.events
    for _i, row in ev[ev["event"].isin(["impact", "wall-impact"])].iterrows():
        if row["event"] == "impact":      # ground impact onto the logged pivot j from -j
            j = int(row["pivot"])
            io_from, io_to = side_numbers(body, -j)[3], side_numbers(body, j)[3]
            assert io_to * row["velocity_after"] ** 2 <= io_from * row["velocity_before"] ** 2 * (1 + 1e-12)
        else:                             # the pivot is kept
            assert abs(row["velocity_after"]) <= abs(row["velocity_before"])


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(b1=st.floats(0.15, 0.6), b2=st.floats(0.15, 0.6), top=st.floats(1.2, 2.5),
       side=st.sampled_from([1, -1]), gap=st.sampled_from([0.0, 1e-9, 0.01, 0.08]),
       ew=st.floats(0.5, 1.0), theta_frac=st.floats(0.2, 0.9))
def test_energy_never_grows(b1, b2, top, side, gap, ew, theta_frac):
    """Free rocking from rest (any gap, wall restitution, body): the total energy
    M g y_cm + I_O,k theta'^2 / 2 about the current pivot k never grows along the history, and no
    impact under a pulse adds kinetic energy."""
    body = fr.RigidBody.from_polygon([(0.0, 0.0), (b1 + b2, 0.0), (b1 + b2, top), (0.0, 0.7 * top)], mass=1.0)
    wall = fr.Wall(gap, side=side, restitution=ew)
    a_far = side_numbers(body, -side)[0]
    res = fr.simulate(body, None, wall=wall, theta0=-side * theta_frac * a_far, duration=3.0, rtol=1e-10)
    assert res.kernel == ("rigid_wall" if body.is_symmetric else "wall_body")
    h = res.history
    energy = np.empty(len(h))
    for k, (th, om, s) in enumerate(zip(h["theta"], h["theta_dot"], h["pivot"])):
        alpha, _p, R, io = side_numbers(body, s)
        energy[k] = body.mass * body.g * R * math.cos(alpha - s * th) + 0.5 * io * om * om
    scale = body.mass * body.g * max(body.R1, body.R2)
    assert np.all(np.diff(energy) <= 1e-7 * scale)
    _impacts_never_add_energy(body, res)
    pulse = fr.Pulse(2.5, 2.0, sign=-side, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    _impacts_never_add_energy(body, fr.simulate(body, pulse, wall=wall))


# ------------------------------------------------------------------ entry points
def test_spectrum_reports_sides():
    """Gap 0: the body never falls toward the wall; away from it, it does."""
    for w in (1, -1):
        df = spectrum(BODY, wall=fr.Wall(0.0, side=w, restitution=0.8))
        assert df.attrs["kernel"] == "wall_body" and "side" in df
        assert not (df["side"] == w).any() and (df["side"] == -w).any()
        assert (df.loc[df["side"] != 0, "outcome"].astype(str).isin(["mode1", "mode2"])).all()
        assert (df["max_rotation_toward_wall"] == 0.0).all()


def test_scene_toml(tmp_path):
    path = tmp_path / "rock.toml"
    path.write_text('[body]\ntype = "rigid-body"\nvertices = [[0, 0], [1, 0], [0.8, 2.2], [0, 2.2]]\nmass = 1.0\n'
                    '[wall]\ngap = 0.0\nside = 1\nrestitution = 0.8\n[excitation]\nkind = "one-sine"\n'
                    'amplitude = 2.5\nfrequency = 2.5\nsign = 1\namplitude_unit = "g_tan_alpha"\n'
                    'frequency_unit = "omega_p/p"\n')
    scene = fr.Scene.from_toml(path)
    one = scene.run()
    ref = fr.simulate(BODY, fr.Pulse(2.5, 2.5, sign=1, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                      wall=fr.Wall(0.0, side=1, restitution=0.8))
    assert ref.kernel == "wall_body" and ref.metrics["wall_impacts"] > 0
    assert (one.status, one.metrics["max_rotation"]) == (ref.status, ref.metrics["max_rotation"])


def test_cli_outline_at_gap_zero(tmp_path, capsys):
    from fastrock.cli import app as cli
    (tmp_path / "rock.csv").write_text("0 0\n1 0\n0.8 2.2\n0 2.2\n")
    assert cli.main(["simulate", "--outline", str(tmp_path / "rock.csv"), "--wall-gap", "0", "--wall-side", "1",
                     "--wall-restitution", "0.8", "--amplitude", "0.6", "--amplitude-unit", "g",
                     "--frequency", "1.5", "--frequency-unit", "Hz", "--png", ""]) == 0
    out = capsys.readouterr().out
    ref = fr.simulate(BODY, fr.Pulse(0.6, 1.5, amplitude_unit="g", frequency_unit="Hz"),
                      wall=fr.Wall(0.0, side=1, restitution=0.8))
    assert "kernel wall_body" in out and f"outcome {ref.outcome} ({ref.status})" in out
