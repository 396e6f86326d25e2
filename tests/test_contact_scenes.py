"""Scenes that run the contact model (issue #13): a rigid block with a wall and friction, and
free flight (Friction(lift_off="flight")), through the public entry points.  The kernel's own
oracles (ballistic flight, landings, the SciPy reference) are in tests/test_contact_core.py."""
from __future__ import annotations

import math

import numpy as np
import pytest

from fastrock import Friction, FlexibleBody, Pulse, RigidBlock, Wall, overturning_spectrum, simulate
from fastrock.running import registry

BLOCK = RigidBlock.rectangle(0.2, 1.0)
PULSES = [(amp, f, sign) for amp in (1.5, 3.0, 5.0) for f in (0.5, 2.0, 4.0) for sign in (1, -1)]


def _pulse(amp, f, sign):
    return Pulse(amp, f, sign=sign, amplitude_unit="g_tan_alpha")


@pytest.mark.parametrize("kw", [
    {"wall": Wall(gap=0.02), "friction": Friction(0.5)},
    {"friction": Friction(math.inf, lift_off="flight")},
    {"friction": Friction(0.4, lift_off="flight")},
    {"wall": Wall(gap=0.02), "friction": Friction(math.inf, lift_off="flight")},
])
def test_these_scenes_run_the_contact_model(kw):
    assert registry.select(BLOCK, **kw).name == "contact"


@pytest.mark.parametrize("kw", [{"friction": Friction(0.4, lift_off="flight")},
                                {"friction": Friction(math.inf, lift_off="flight")}])
def test_flight_of_the_flexible_body_selects_its_own_model(kw):
    """Free flight of the flexible body is a model of its own (tests/test_flexible_flight.py);
    with a wall it is still refused, with the reason."""
    assert registry.select(FlexibleBody(0.2, 2.0, 10.0), **kw).name == "flexible_flight"
    with pytest.raises(ValueError, match="no model runs a flexible body with .*wall"):
        registry.select(FlexibleBody(0.2, 2.0, 10.0), wall=Wall(gap=0.3), **kw)


def test_a_short_wall_runs_the_contact_model():
    """A wall lower than the block with friction runs the contact model (tests/test_contact_short_wall.py
    checks it)."""
    r = simulate(BLOCK, _pulse(2, 1, 1), wall=Wall(gap=0.02, height=0.5), friction=Friction(0.5))
    assert r.kernel == "contact" and not r.status.startswith("failed")


def test_gap_zero_runs_the_contact_model():
    """A wall at gap 0 with friction (the block standing against a cliff) runs the contact model
    (tests/test_contact_gap0.py checks it)."""
    r = simulate(BLOCK, _pulse(2, 1, 1), wall=Wall(gap=0.0), friction=Friction(0.5))
    assert r.kernel == "contact" and not r.status.startswith("failed")


@pytest.mark.slow
def test_infinite_friction_with_a_wall_is_the_wall_model():
    """mu = inf (the pivot held, as the wall model's single-degree-of-freedom map assumes) gives the
    wall model's answers, except where the block truly leaves the ground while it falls over.  A
    large finite mu does not: at a tall-wall impact below alpha the held-pivot map needs the pivot
    to pull on the ground, which no friction provides (the pivot lifts off instead)."""
    for amp, f, sign in PULSES:
        a = simulate(BLOCK, _pulse(amp, f, sign), wall=Wall(gap=0.02), friction=Friction(math.inf, lift_off="flight"))
        b = simulate(BLOCK, _pulse(amp, f, sign), wall=Wall(gap=0.02))
        assert a.kernel == "contact" and b.kernel == "rigid_wall"
        if a.metrics["flights"]:
            assert a.outcome in ("mode1", "mode2") and b.outcome in ("mode1", "mode2"), (amp, f, sign)
            continue
        assert a.status == b.status, (amp, f, sign, a.status, b.status)
        assert a.metrics["max_rotation_ratio"] == pytest.approx(b.metrics["max_rotation_ratio"], rel=1e-6)


@pytest.mark.slow
def test_a_wall_out_of_reach_is_the_friction_model():
    # out of reach: farther than the block's height plus how far it slides (0.71 m at most here; at
    # gap 2.5 m the block sliding 0.53 m toward the wall while it falls does touch it)
    fr = Friction(0.35, 0.3)
    for amp, f, sign in PULSES:
        a = simulate(BLOCK, _pulse(amp, f, sign), wall=Wall(gap=2 * BLOCK.h + 1.0), friction=fr)
        b = simulate(BLOCK, _pulse(amp, f, sign), friction=fr)
        assert a.kernel == "contact" and b.kernel == "rigid_friction"
        assert a.outcome == b.outcome, (amp, f, sign, a.status, b.status)
        assert a.metrics["max_slide"] == pytest.approx(b.metrics["max_slide"], abs=1e-6)


def test_frictionless_ground_slides_by_minus_the_ground_displacement():
    """mu = 0: the block keeps still in space, so it slides by -(double integral of a_g) relative to
    the ground until it reaches the wall."""
    pulse = Pulse(0.3, 2.0, amplitude_unit="m/s2", frequency_unit="rad/s")
    r = simulate(BLOCK, pulse, wall=Wall(gap=0.5), friction=Friction(0.0), duration=2.0)
    h = r.history.drop_duplicates("t", keep="last")
    t = h["t"].to_numpy()
    exact = -0.3 / 2.0 ** 2 * (2.0 * t - np.sin(2.0 * t))         # -double integral of 0.3 sin(2t)
    np.testing.assert_allclose(h["d"].to_numpy(), exact, atol=1e-7)
    assert r.metrics["wall_impacts"] == 0 and r.metrics["impacts"] == 0


def test_a_block_thrown_up_flies_and_lands():
    up = Pulse(1.5, 12.0, amplitude_unit="g", frequency_unit="rad/s", sign=-1)
    r = simulate(BLOCK, None, vertical=up, friction=Friction(math.inf, lift_off="flight"), duration=3.0)
    assert r.kernel == "contact" and r.status == "safe:rest"
    m = r.metrics
    assert m["flights"] >= 1 and m["time_flight"] > 0.0 and m["max_jump"] > 0.0
    # a flat throw: the CM rise is z; on a 0.1 ms grid its maximum is within g dt^2/8 of the apex
    dense = simulate(BLOCK, None, vertical=up, friction=Friction(math.inf, lift_off="flight"), duration=3.0,
                     t_eval=np.arange(0.0, 0.6, 1e-4))
    assert dense.history["z"].max() == pytest.approx(m["max_jump"], abs=2e-8)
    assert (dense.history["theta"] == 0.0).all()
    # the rigid model cannot fly: it stops
    assert simulate(BLOCK, None, vertical=up, duration=3.0).outcome == "flight"


def test_a_spectrum_with_a_wall_and_friction():
    df = overturning_spectrum(BLOCK, np.linspace(1, 5, 4), np.linspace(0.5, 4, 4), wall=Wall(gap=0.02),
                              friction=Friction(0.6), progress=False)
    assert df.attrs["kernel"] == "contact"
    for col in ("max_slide", "residual_slide", "flights", "time_flight", "max_jump", "max_rotation_toward_wall"):
        assert col in df
    # the face against the wall is modelled: no failures
    failed = df["status"].str.startswith("failed")
    assert not failed.any(), df.loc[failed, "status"]
    row = df[~failed].iloc[-1]
    r = simulate(BLOCK, Pulse(row["amplitude"], 2 * math.pi * row["frequency_hz"], sign=int(row["sign"]),
                              amplitude_unit="m/s2", frequency_unit="rad/s"),
                 wall=Wall(gap=0.02), friction=Friction(0.6), early_exit=True, duration=row["time_end"])
    assert r.status == row["status"]


def test_a_block_sliding_flat_into_the_wall_stops_there_and_leaves_when_pulled_away():
    """mu = 0.1 < b/h: the block slides flat (a_g = A sin(w t) pushes it toward the wall at the left
    once A sin(w t) > mu g), reaches the wall (e_w = 0: a plastic face impact), rests against it
    while the ground pushes it there, and slides away exactly when the pull beats friction
    (A sin(w t) = -mu g)."""
    from scipy.integrate import quad
    from scipy.optimize import brentq
    A, f, mu, gap = 3.0, 1.0, 0.1, 0.02
    w, g = 2 * math.pi * f, BLOCK.g
    r = simulate(BLOCK, Pulse(A, f, amplitude_unit="m/s2"), wall=Wall(gap=gap, side=-1, restitution=0.0),
                 friction=Friction(mu), duration=3.0)
    assert r.status == "safe:no-uplift" and r.metrics["wall_impacts"] == 1
    ev = r.events
    t_hit = ev.loc[ev["event"] == "wall-impact", "t"].iloc[0]
    t0 = math.asin(mu * g / A) / w

    def d(t):      # d'' = -a_g + mu g from rest at t0 (sliding left, friction to the right)
        return quad(lambda s: (t - s) * (-A * math.sin(w * s) + mu * g), t0, t)[0]

    assert t_hit == pytest.approx(brentq(lambda t: d(t) + gap, t0 + 1e-3, 0.5 / f), abs=1e-7)
    t_leave = (math.pi + math.asin(mu * g / A)) / w
    assert ev.loc[ev["event"] == "slip", "t"].iloc[1] == pytest.approx(t_leave, abs=1e-9)
    h = simulate(BLOCK, Pulse(A, f, amplitude_unit="m/s2"), wall=Wall(gap=gap, side=-1, restitution=0.0),
                 friction=Friction(mu), duration=3.0, t_eval=np.linspace(0.0, 3.0, 301)).history
    rest = h[(h["t"] > t_hit) & (h["t"] < t_leave)]
    assert len(rest) >= 25 and (rest["d"] == -gap).all() and (rest["d_dot"] == 0.0).all()
    assert (rest["contact"] == "rest").all()
    after = h[h["t"] > t_leave + 0.01]
    assert (after["d"] > -gap).all() and r.metrics["residual_slide"] > 0.0


@pytest.mark.parametrize("rel", [0.0, 1e-12, -1e-12])
def test_mu_equal_to_b_over_h_neither_loops_nor_differs_from_the_friction_model(rel):
    """mu_s = b/h: slide and rock thresholds coincide.  The slide keeps both corners down while
    mu_k <= b/h (the trailing corner's N = G (b - mu h) / (2b) >= 0) and tips only for mu_k h > b, as
    in kernels/friction.py; the front end's flight variant ran into a transition loop here."""
    mu = BLOCK.b / BLOCK.h * (1.0 + rel)
    p = Pulse(1.5, 0.5, sign=1, amplitude_unit="g_tan_alpha")
    a = simulate(BLOCK, p, friction=Friction(mu, lift_off="flight"))
    b = simulate(BLOCK, p, friction=Friction(mu))
    assert a.kernel == "contact" and b.kernel == "rigid_friction"
    assert a.status == b.status, (a.status, b.status)
    assert not a.status.startswith("failed")
    assert a.metrics["max_slide"] == pytest.approx(b.metrics["max_slide"], abs=1e-6)
    assert a.metrics["max_rotation"] == pytest.approx(b.metrics["max_rotation"], abs=1e-9)


@pytest.mark.parametrize("amp,freq,lift_off", [(3.909091, 1.7, "stop"), (5.0, None, "flight")])
def test_top_corner_ladder_ends_the_zero_velocity_wall_loop(amp, freq, lift_off):
    """A block pushed into the wall tips onto it with its top corner while its pivot cannot
    stick (mu = 0.3): before the top-corner ladder (the pivot slipping with the top corner on the
    wall) it repeated wall impacts at 1e-15 rad/s and slip starts until the step budget
    (failed:step-budget after 1.6e7 evaluations).  Both cases now end definite and fast."""
    from fastrock import Wall
    body = RigidBlock.rectangle(0.2, 1.0)
    if freq is None:        # the probe cell of tests/test_contact_core.py (its default units)
        pulse = Pulse(amp, 1.0, sign=1, amplitude_unit="g_tan_alpha")
    else:
        pulse = Pulse(amp, freq, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    r = simulate(body, pulse, wall=Wall(gap=0.02), friction=Friction(0.3, lift_off=lift_off))
    assert not r.status.startswith("failed"), r.status
    assert r.metrics["nfev"] < 100_000


@pytest.mark.parametrize("lift_off", ["stop", "flight"])
@pytest.mark.parametrize("sign", [1, -1])
def test_the_wall_and_friction_grid_has_no_failed_cell(lift_off, sign):
    """The 12 x 12 one-sine grid of the top-corner ladder's commit (block 0.2 x 1.0 m, a wall at 2
    cm, mu = 0.3, a/(g tan alpha) 0.5-8, omega_p/p 0.3-8): 4 cells ended failed:transition-loop or
    failed:face-contact there, with the base corner grazing the wall in flight; with the later
    fixes every cell is definite, and the statuses are those of a block beside a wall."""
    import warnings
    body = RigidBlock.rectangle(0.2, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = overturning_spectrum(body, np.linspace(0.5, 8, 12), np.linspace(0.3, 8, 12), sign=sign,
                                 wall=Wall(gap=0.02), friction=Friction(0.3, lift_off=lift_off),
                                 progress=False)
    assert len(s) == 144
    assert not s["status"].astype(str).str.startswith("failed").any()
    # below uplift no cell moves; above it some overturn and some come to rest
    assert set(s["status"].astype(str)) >= {"safe:no-uplift", "safe:rest"}
    assert s["status"].astype(str).str.startswith("overturn").sum() > 40
