"""Hard cases for one-sided rocking against a rear wall (physics.md 2): the gap-0 limit (Hogan's
map, with an elastic wall e_w = 1 that never dissipates), tiny gaps (1e-7 m, 1e-6 m and
theta_w = 1e-6 rad, where a ground impact, a wall impact and a second ground impact follow each
other within microseconds), and a 90 s record at dt 0.005.  Every run gets a step budget and must
end with a definite status and a finite history; the block must never pass through the wall, and
every logged impact must follow its map exactly.  CI runs this file a second time under
``NUMBA_BOUNDSCHECK=1``.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
import hardcases as H
from fastrock.kernels.wall import SMALL_GAP_ANGLE
from test_rigid_hard_cases import quarter_period
from test_wall import BLOCK, pulse

BUDGET = 200_000
EPS = np.finfo(float).eps


def check(res, wall, body, budget=BUDGET):
    """Definite, finite, inside the budget; never past the wall; impact maps exact."""
    H.definite(res, budget)
    tw = wall.limit_angle(body)
    h = res.history
    # event location returns the first point on the event side of the root, to 4 ulp in t, so
    # theta may pass the wall by |theta'| * 4 eps t (measured 1.2e-14 rad at t = 40 s)
    slack = 8 * EPS * (np.maximum(h["t"], 1.0) * np.abs(h["theta_dot"]) + tw)
    assert (wall.side * h["theta"] - tw <= slack).all()
    ev = res.events
    w = ev[ev["event"] == "wall-impact"]
    # the small-gap limit (0 < theta_w < SMALL_GAP_ANGLE) logs Hogan's combined map, r = e^2 e_w
    r = body.e ** 2 * wall.restitution if 0.0 < tw < SMALL_GAP_ANGLE else wall.restitution
    np.testing.assert_allclose(w["velocity_after"], -r * w["velocity_before"], rtol=1e-15, atol=0.0)
    g = ev[ev["event"] == "impact"]
    np.testing.assert_allclose(g["velocity_after"], body.e * g["velocity_before"], rtol=1e-15, atol=0.0)
    return res


def theta_w_gap(body, theta_w):
    """Gap [m] of a tall wall touched at theta_w [rad]: sin(theta_w) = d / (2h)."""
    return 2.0 * body.h * math.sin(theta_w)


# ----------------------------------------------------------------------------------------
# gap -> 0
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("ew", [0.9, 1.0])
@pytest.mark.parametrize("gap", [1e-7, 1e-6])
def test_small_gap_tends_to_hogan_with_r_equal_e2_ew(gap, ew):
    """d -> 0: a ground impact (e), a wall impact (e_w) and a second ground impact (e)
    follow each other: the limit map is Hogan's with r = e^2 e_w.  The difference is O(d)
    (measured 5.3e-5 of the amplitude at d = 1e-6 m, theta_w = 2e-7 rad; d = 1e-7 m,
    theta_w = 2e-8 rad, is below SMALL_GAP_ANGLE and runs that limit itself)."""
    exc = pulse(0.4, 1.0, sign=-1)
    wall = fr.Wall(gap=gap, restitution=ew)
    small = check(fr.simulate(BLOCK, exc, wall=wall, duration=6.0, max_steps=BUDGET), wall, BLOCK)
    hogan = fr.simulate(BLOCK, exc, wall=fr.Wall(gap=0.0, restitution=BLOCK.e ** 2 * ew), duration=6.0)
    t = np.linspace(0.5, 6.0, 200)
    th_s = np.interp(t, small.history["t"], small.history["theta"])
    th_h = np.interp(t, hogan.history["t"], hogan.history["theta"])
    assert np.max(np.abs(th_s - th_h)) < 1e-4 * np.max(np.abs(th_h)) + 1e-6
    assert small.metrics["max_rotation_pos"] == pytest.approx(hogan.metrics["max_rotation_pos"], rel=1e-5)
    assert small.metrics["wall_impacts"] > 0


@pytest.mark.parametrize("side", [-1, 1])
def test_gap_zero_elastic_wall_rocks_for_ever_at_the_same_amplitude(side):
    """Hogan's map with r = e_w = 1 dissipates nothing: released at theta0 away from the wall,
    the block bounces off the wall at t_k = (2k + 1) T4(theta0) with the same speed every time,
    for as long as the run lasts (physics.md 6.2 for T4)."""
    theta0 = 0.5 * BLOCK.alpha
    wall = fr.Wall(gap=0.0, side=side, restitution=1.0)
    res = check(fr.simulate(BLOCK, None, wall=wall, theta0=-side * theta0, duration=30.0, rtol=1e-12,
                            max_steps=BUDGET), wall, BLOCK)
    assert res.status == "safe:moving"
    t4 = quarter_period(BLOCK.alpha, BLOCK.p, theta0)
    w = res.events[res.events["event"] == "wall-impact"]
    k = np.arange(len(w))
    assert len(w) == math.floor((30.0 / t4 - 1) / 2) + 1
    np.testing.assert_allclose(w["t"], (2 * k + 1) * t4, rtol=0, atol=1e-9)
    v0 = BLOCK.p * math.sqrt(2 * (math.cos(BLOCK.alpha - theta0) - math.cos(BLOCK.alpha)))
    np.testing.assert_allclose(np.abs(w["velocity_before"]), v0, rtol=1e-9)
    assert res.metrics["max_rotation"] == pytest.approx(theta0, rel=1e-12)
    assert res.metrics["ground_impacts"] == res.metrics["wall_impacts"] == len(w)


# ----------------------------------------------------------------------------------------
# tiny gaps under a pulse, elastic and inelastic wall, both directions
# ----------------------------------------------------------------------------------------
TINY = {"gap 0": 0.0, "gap 1e-6 m": 1e-6, "theta_w 1e-6 rad": theta_w_gap(BLOCK, 1e-6)}


@pytest.mark.parametrize("sign", [1, -1])
@pytest.mark.parametrize("ew", [1.0, 0.5])
@pytest.mark.parametrize("gap", list(TINY))
def test_tiny_gap_pulse(gap, ew, sign):
    """A 0.4 g, 1 Hz one-sine pulse toward (+1) and away from (-1) the wall: hundreds of ground
    and wall impacts microseconds apart (measured up to 545 + 320 in 1800 steps), a definite
    status, the block never behind the wall, every impact on its map.  With d > 0 the ground
    dissipates and the block comes to rest; at d = 0 with e_w = 1 nothing dissipates."""
    wall = fr.Wall(gap=TINY[gap], restitution=ew)
    res = check(fr.simulate(BLOCK, pulse(0.4, 1.0, sign=sign), wall=wall, t_after=10.0, max_steps=BUDGET),
                wall, BLOCK)
    assert res.metrics["wall_impacts"] > 0
    if TINY[gap] > 0.0:
        assert res.status == "safe:rest"
    elif ew == 1.0:
        assert res.status == "safe:moving"
    assert res.metrics["steps"] + res.metrics["rejected_steps"] < 5000


# ----------------------------------------------------------------------------------------
# a long record
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("gap,ew,outcome", [(0.01, 1.0, "safe"), (1e-6, 1.0, "safe"), (0.0, 1.0, "mode1"),
                                            (0.0, 0.7, "safe")])
def test_long_record_90s_at_dt_0005(gap, ew, outcome):
    """The 90 s record of the rigid hard cases (18 000 breakpoints) at 0.7 g, so that the
    block reaches the wall (measured 85 wall impacts at d = 1 cm, 1381 at 1e-6 m, 3274 at d = 0).
    At d = 0 with e_w = 1 no impact dissipates anything, and the record pumps the block over
    (away from the wall) at 40.6 s; with r = e_w = 0.7 it survives."""
    body = fr.RigidBlock.rectangle(b=0.3, h=1.2)
    wall = fr.Wall(gap=gap, restitution=ew)
    rec = H.long_record(peak_g=0.7)
    res = check(fr.simulate(body, rec, wall=wall, t_after=2.0, max_steps=2_000_000), wall, body,
                budget=2_000_000)
    assert res.outcome == outcome and res.metrics["wall_impacts"] > 0
    if outcome == "safe":
        assert res.metrics["time_end"] == pytest.approx(rec.end_time(body) + 2.0, abs=1e-9)
    else:
        assert res.history["theta"].iloc[-1] == pytest.approx(-wall.side * body.theta_over, abs=1e-12)
