"""One-sided rocking against a rear wall (physics.md section 2, issue #3).

Oracles: the wall geometry re-derived by rotating the block's outline, energy
bookkeeping across impacts, the two-sided kernel (a wall that is never reached must
change nothing, bit for bit), Hogan's d = 0 map in closed form, an independent
event-driven solver built on scipy.integrate.solve_ivp, mirror symmetry, the analytic
release instant of a block resting on the wall, and the full runs as an oracle for the
early decisions.  Hard cases (gap -> 0 and the small-gap limit, an elastic wall at d = 0, a 90 s
record) are in ``tests/test_wall_hard_cases.py``.
"""
from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

import fastrock as fr
from fastrock.kernels import layout as L

BLOCK = fr.RigidBlock.rectangle(b=0.5, h=2.5)        # Mennitti et al.: p = 1.70 rad/s, alpha = 0.197
SLENDER = fr.RigidBlock.rectangle(b=0.2, h=1.0)
G_TAN = BLOCK.g * math.tan(BLOCK.alpha)


def energy(theta, dtheta, s, body):
    """Free-rocking energy / (M g R) about pivot s, zero at rest (physics.md 6.6)."""
    a = body.alpha
    return 0.5 * np.asarray(dtheta) ** 2 / body.p ** 2 + np.cos(a - s * np.asarray(theta)) - math.cos(a)


def pulse(amp_g, f_hz, sign=1, kind="one-sine"):
    return fr.Pulse(amp_g, f_hz, sign=sign, kind=kind)


def impacts(res):
    ev = res.events
    return ev[ev["event"].isin(["impact", "wall-impact"])].reset_index(drop=True)


# ----------------------------------------------------------------------------------------
# geometry
# ----------------------------------------------------------------------------------------
def rotate_about_near_corner(points, theta):
    """Rotate body-frame points (x toward the wall, y up, origin at the near bottom
    corner) by theta toward the wall."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[x * c + y * s, -x * s + y * c] for x, y in points])


def rear_face_clearance(theta, d, hw, h):
    """Signed clearance between the rotated rear face (x = 0 at rest, from y = 0 to 2h)
    and the wall (x = d, 0 <= y <= hw): > 0 free, 0 touching."""
    ys = np.linspace(0.0, 2 * h, 20001)
    face = rotate_about_near_corner([(0.0, y) for y in ys], theta)
    below = face[:, 1] <= hw
    return float(np.min(d - face[below, 0]))


@pytest.mark.parametrize("gap", [0.01, 0.1, 0.5, 1.5, 4.9])
def test_limit_angle_tall_wall(gap):
    w = fr.Wall(gap=gap)
    tw = w.limit_angle(BLOCK)
    assert w.contact(BLOCK) == "tall"
    assert math.sin(tw) == pytest.approx(gap / (2 * BLOCK.h), rel=1e-14)
    # the top rear corner touches the wall at theta_w
    top = rotate_about_near_corner([(0.0, 2 * BLOCK.h)], tw)[0]
    assert top[0] == pytest.approx(gap, rel=1e-12)
    assert rear_face_clearance(tw, gap, 10.0, BLOCK.h) == pytest.approx(0.0, abs=1e-12)
    assert rear_face_clearance(0.999 * tw, gap, 10.0, BLOCK.h) > 0


@pytest.mark.parametrize("gap, hw", [(0.1, 1.0), (0.5, 3.0), (1.0, 0.5), (2.0, 1.0)])
def test_limit_angle_short_wall(gap, hw):
    w = fr.Wall(gap=gap, height=hw)
    tw = w.limit_angle(BLOCK)
    assert w.contact(BLOCK) == "short"
    assert math.tan(tw) == pytest.approx(gap / hw, rel=1e-14)
    assert hw < 2 * BLOCK.h * math.cos(tw)          # the branch's own admissibility condition
    # the rear face touches the wall's top edge, and is clear of the wall just before
    assert rear_face_clearance(tw, gap, hw, BLOCK.h) == pytest.approx(0.0, abs=1e-3 * gap)
    assert rear_face_clearance(0.999 * tw, gap, hw, BLOCK.h) > 0
    # a tall wall at the same gap is reached earlier (if at all)
    assert tw > fr.Wall(gap=gap).limit_angle(BLOCK) or fr.Wall(gap=gap).limit_angle(BLOCK) == math.inf


def test_limit_angle_branches_meet_and_edge_cases():
    h = BLOCK.h
    d = 0.8
    hw_switch = math.sqrt(4 * h * h - d * d)           # h_w = 2h cos(theta_w)
    tall = fr.Wall(gap=d).limit_angle(BLOCK)
    assert fr.Wall(gap=d, height=hw_switch * (1 + 1e-12)).limit_angle(BLOCK) == pytest.approx(tall, rel=1e-9)
    assert fr.Wall(gap=d, height=hw_switch * (1 - 1e-12)).limit_angle(BLOCK) == pytest.approx(tall, rel=1e-9)
    assert fr.Wall(gap=d, height=100.0).limit_angle(BLOCK) == tall
    assert fr.Wall(gap=0.0).limit_angle(BLOCK) == 0.0
    assert fr.Wall(gap=0.0).contact(BLOCK) == "hogan"
    for gap in (2 * h, 2 * h + 1, 50.0):
        assert fr.Wall(gap=gap).limit_angle(BLOCK) == math.inf
        assert fr.Wall(gap=gap).contact(BLOCK) == "none"
        assert fr.Wall(gap=gap, height=0.3).limit_angle(BLOCK) == math.inf
    # from_inertia bodies carry b, h as well
    body = fr.RigidBlock.from_inertia(R=BLOCK.size, alpha=BLOCK.alpha, I0=4 / 3 * BLOCK.size ** 2, m=1.0)
    assert fr.Wall(gap=0.1).limit_angle(body) == pytest.approx(fr.Wall(gap=0.1).limit_angle(BLOCK), rel=1e-12)


@pytest.mark.nojit
@pytest.mark.parametrize("wall", [fr.Wall(gap=0.1), fr.Wall(gap=0.1, height=1.0, side=1)])
def test_block_meets_the_wall_at_the_limit_angle(wall):
    tw = wall.limit_angle(BLOCK)
    r = fr.simulate(BLOCK, pulse(0.5, 0.5, sign=wall.toward_sign), wall=wall)
    hits = r.events[r.events["event"] == "wall-impact"]
    assert len(hits) > 0
    np.testing.assert_allclose(hits["theta"], wall.side * tw, rtol=0, atol=1e-15)
    assert (hits["pivot"] == wall.side).all()
    assert (wall.side * r.history["theta"] <= tw * (1 + 1e-9)).all()
    toward = r.metrics["max_rotation_neg"] if wall.side < 0 else r.metrics["max_rotation_pos"]
    assert toward == pytest.approx(tw, rel=1e-12)


# ----------------------------------------------------------------------------------------
# impact maps and energy
# ----------------------------------------------------------------------------------------
@pytest.mark.nojit
@pytest.mark.parametrize("side", [-1, 1])
def test_elastic_wall_conserves_energy_across_a_wall_impact(side):
    wall = fr.Wall(gap=0.2, side=side)                       # e_w = 1
    tw = wall.limit_angle(BLOCK)
    theta0 = side * 0.5 * tw
    r = fr.simulate(BLOCK, None, wall=wall, theta0=theta0, dtheta0=side * 0.2, duration=3.0)
    ev = impacts(r)
    assert ev.loc[0, "event"] == "wall-impact"
    assert ev.loc[0, "velocity_after"] == -ev.loc[0, "velocity_before"]
    t_ground = ev.loc[ev["event"] == "impact", "t"].iloc[0]
    h = r.history
    seg = h[h["t"] < t_ground]
    E = energy(seg["theta"], seg["theta_dot"], side, BLOCK)
    E0 = energy(theta0, side * 0.2, side, BLOCK)
    assert seg["t"].iloc[-1] > ev.loc[0, "t"]                  # the segment spans the wall impact
    np.testing.assert_allclose(E, E0, rtol=0, atol=1e-9)
    assert r.metrics["wall_impacts"] >= 1 and r.metrics["ground_impacts"] >= 1


@pytest.mark.nojit
@pytest.mark.parametrize("ew", [0.0, 0.3, 0.8])
def test_inelastic_wall_removes_kinetic_energy_only(ew):
    wall = fr.Wall(gap=0.2, restitution=ew)
    tw = wall.limit_angle(BLOCK)
    r = fr.simulate(BLOCK, None, wall=wall, theta0=-0.5 * tw, dtheta0=-0.2, duration=2.0)
    hit = impacts(r).iloc[0]
    assert hit["event"] == "wall-impact"
    assert hit["velocity_after"] == pytest.approx(-ew * hit["velocity_before"], rel=1e-15, abs=0)
    pe = math.cos(BLOCK.alpha - tw) - math.cos(BLOCK.alpha)
    e_before = energy(-tw, hit["velocity_before"], -1, BLOCK)
    e_after = energy(-tw, hit["velocity_after"], -1, BLOCK)
    assert e_after - pe == pytest.approx(ew ** 2 * (e_before - pe), rel=1e-12)


@pytest.mark.nojit
def test_ground_impacts_keep_housner_map():
    wall = fr.Wall(gap=0.1)
    r = fr.simulate(BLOCK, pulse(0.3, 1.0), wall=wall, duration=8.0)
    ev = r.events[r.events["event"] == "impact"]
    assert len(ev) > 3
    np.testing.assert_allclose(ev["velocity_after"], BLOCK.e * ev["velocity_before"], rtol=1e-15)
    assert r.metrics["ground_impacts"] == len(ev)
    assert r.metrics["wall_impacts"] == (r.events["event"] == "wall-impact").sum()


# ----------------------------------------------------------------------------------------
# a wall that is never reached changes nothing
# ----------------------------------------------------------------------------------------
def assert_same_run(a, b):
    for c in ("t", "theta", "theta_dot", "contact", "pivot"):
        np.testing.assert_array_equal(a.history[c].to_numpy(), b.history[c].to_numpy(), err_msg=c)
    pd.testing.assert_frame_equal(a.events, b.events)
    assert a.status == b.status
    for k, v in a.metrics.items():
        np.testing.assert_equal(v, b.metrics[k], err_msg=k)


@pytest.mark.parametrize("exc", [pulse(0.5, 0.5), pulse(0.5, 0.5, -1), pulse(0.3, 1.0), pulse(0.25, 1.2, -1),
                                 pulse(1.0, 2.0, kind="one-cosine")])
def test_unreachable_wall_reproduces_two_sided_rocking_exactly(exc):
    plain = fr.simulate(BLOCK, exc)
    for wall in (fr.Wall(gap=2 * BLOCK.h), fr.Wall(gap=7.0, side=1), fr.Wall(gap=6.0, height=0.5)):
        assert wall.limit_angle(BLOCK) == math.inf
        run = fr.simulate(BLOCK, exc, wall=wall)
        assert run.kernel == "rigid_wall" and plain.kernel == "rigid"
        assert_same_run(run, plain)
    # a finite gap beyond the largest rotation toward the wall: also identical
    toward = plain.metrics["max_rotation_neg"]
    if toward < 0.9:
        d = 2 * BLOCK.h * math.sin(toward) * 1.01 + 1e-6
        assert_same_run(fr.simulate(BLOCK, exc, wall=fr.Wall(gap=d)), plain)


def test_unreachable_wall_spectrum_matches_two_sided():
    amps = np.linspace(1.3, 12, 9)
    freqs = np.linspace(0.5, 6, 8)
    kw = dict(sign="both", progress=False, early_exit=False)
    plain = fr.overturning_spectrum(BLOCK, amps, freqs, **kw)
    wall = fr.overturning_spectrum(BLOCK, amps, freqs, wall=fr.Wall(gap=5.5), **kw)
    cols = ["outcome", "status", "max_rotation", "impacts", "time_uplift", "time_overturn", "time_end", "nfev"]
    pd.testing.assert_frame_equal(wall[cols], plain[cols])
    assert (wall["wall_impacts"] == 0).all()


# ----------------------------------------------------------------------------------------
# d = 0: Hogan's one-sided rocking
# ----------------------------------------------------------------------------------------
@pytest.mark.nojit
@pytest.mark.parametrize("side, r", [(-1, 0.9), (1, 0.7), (-1, 1.0)])
def test_hogan_map(side, r):
    wall = fr.Wall(gap=0.0, side=side, restitution=r)
    theta0 = -side * 0.1                               # tilted away from the wall
    res = fr.simulate(BLOCK, None, wall=wall, theta0=theta0, duration=6.0)
    dense = fr.simulate(BLOCK, None, wall=wall, theta0=theta0, duration=6.0, t_eval=np.linspace(0, 6, 60001))
    ev = impacts(res)
    assert len(ev) >= 2
    assert (ev["event"] == "wall-impact").all()
    assert (ev["pivot"] == -side).all()                # pivot stays on the far corner
    np.testing.assert_allclose(ev["velocity_after"], -r * ev["velocity_before"], rtol=1e-15)
    assert (res.history["pivot"].isin([-side, 0])).all()
    assert (side * res.history["theta"] <= 1e-15).all()    # never tilts toward the wall
    # amplitude after the impact, same side: cos(a - th1) - cos a = r^2 (cos(a - th0) - cos a)
    a = BLOCK.alpha
    rhs_ = math.cos(a) + r * r * (math.cos(a - 0.1) - math.cos(a))
    th1 = a - math.acos(rhs_)
    h = dense.history
    between = h[(h["t"] > ev.loc[0, "t"]) & (h["t"] < ev.loc[1, "t"])]
    assert abs(between["theta"]).max() == pytest.approx(th1, rel=1e-6)
    assert res.metrics["ground_impacts"] == res.metrics["wall_impacts"] == len(ev)


@pytest.mark.nojit
def test_hogan_uplift_only_away_from_the_wall():
    wall = fr.Wall(gap=0.0)                              # side -1: a positive pulse presses the block on it
    toward = fr.simulate(BLOCK, pulse(3.0, 1.0, kind="half-sine"), wall=wall)
    assert toward.status == "safe:no-uplift"
    away = fr.simulate(BLOCK, pulse(3.0, 1.0, sign=-1, kind="half-sine"), wall=wall)
    assert away.metrics["time_uplift"] == pytest.approx(
        math.asin(G_TAN / (3.0 * BLOCK.g)) / (2 * math.pi), rel=1e-12)
    assert (away.history["theta"] >= 0).all()
    # a start at theta = 0 moving toward the wall bounces off it at once
    kick = fr.simulate(BLOCK, None, wall=fr.Wall(gap=0.0, restitution=0.5), dtheta0=-0.2, duration=1.0)
    first = impacts(kick).iloc[0]
    assert first["t"] == 0.0 and first["velocity_after"] == pytest.approx(0.1, rel=1e-15)


# ----------------------------------------------------------------------------------------
# independent solver (scipy.integrate.solve_ivp with terminal events)
# ----------------------------------------------------------------------------------------
def reference_one_sided(body, wall, amp, omega, sign, t_end, n_events):
    """Event-driven one-sided rocking written from physics.md 1-2 only."""
    a, p, g, e = body.alpha, body.p, body.g, body.e
    w, ew, tw = wall.side, wall.restitution, wall.limit_angle(body)
    hogan = wall.gap == 0.0
    t_exc = 2 * math.pi / omega

    def ag(t):
        return sign * amp * math.sin(omega * t) if t <= t_exc else 0.0

    def f(t, y, s):
        phi = s * a - y[0]
        return [y[1], -p * p * (math.sin(phi) + ag(t) / g * math.cos(phi))]

    t = math.asin(g * math.tan(a) / amp) / omega      # uplift
    s = -sign
    if hogan and s == w:
        raise ValueError("no uplift toward the wall with d = 0")
    y = np.array([0.0, 0.0])
    out = []
    while t < t_end and len(out) < n_events:
        ground = lambda tt, yy, s=s: s * yy[0]
        ground.terminal, ground.direction = True, -1
        wallev = lambda tt, yy, s=s: (tw - w * yy[0]) if s == w else 1.0
        wallev.terminal, wallev.direction = True, -1
        over = lambda tt, yy, s=s: body.theta_over - s * yy[0]
        over.terminal, over.direction = True, -1
        t_stop = t_exc if t < t_exc else t_end
        sol = solve_ivp(f, (t, t_stop), y, args=(s,), method="DOP853", rtol=1e-12, atol=1e-14,
                        events=(ground, wallev, over))
        hit = [(ev[0], k) for k, ev in enumerate(sol.t_events) if ev.size]
        if not hit:
            t, y = sol.t[-1], sol.y[:, -1]
            continue
        t, k = min(hit)
        y = sol.y_events[k][0].copy()
        if k == 2:
            out.append((t, "overturn", y[1], y[1]))
            break
        pre = y[1]
        if k == 1:
            y = np.array([w * tw, -ew * pre])
            out.append((t, "wall-impact", pre, y[1]))
        elif hogan:
            y = np.array([0.0, -ew * pre])
            out.append((t, "wall-impact", pre, y[1]))
        else:
            y = np.array([0.0, e * pre])
            s = -s
            out.append((t, "impact", pre, y[1]))
    return out


@pytest.mark.parametrize("wall, amp_g, f_hz, sign", [
    (fr.Wall(gap=0.1, restitution=0.8), 0.3, 1.0, 1),
    (fr.Wall(gap=0.1, restitution=0.8), 0.4, 1.5, -1),
    (fr.Wall(gap=0.01), 0.5, 0.5, 1),
    (fr.Wall(gap=0.02, height=0.3, side=1, restitution=0.6), 0.35, 1.2, -1),
    (fr.Wall(gap=0.0, restitution=0.85), 0.4, 1.0, -1),
])
def test_matches_independent_solve_ivp_solver(wall, amp_g, f_hz, sign):
    omega = 2 * math.pi * f_hz
    ref = reference_one_sided(BLOCK, wall, amp_g * BLOCK.g, omega, sign, 8.0, 12)
    res = fr.simulate(BLOCK, pulse(amp_g, f_hz, sign), wall=wall, duration=8.0, rtol=1e-10)
    ev = res.events[res.events["event"].isin(["impact", "wall-impact", "overturn"])].head(len(ref))
    assert len(ev) == len(ref)
    assert any(k == "wall-impact" for _t, k, _a, _b in ref)
    for (t, kind, pre, post), (_, row) in zip(ref, ev.iterrows()):
        assert row["event"] == kind
        assert row["t"] == pytest.approx(t, abs=1e-7)
        assert row["velocity_before"] == pytest.approx(pre, rel=1e-6, abs=1e-9)
        assert row["velocity_after"] == pytest.approx(post, rel=1e-6, abs=1e-9)


# ----------------------------------------------------------------------------------------
# mirror symmetry
# ----------------------------------------------------------------------------------------
@settings(max_examples=12, deadline=None)
@given(gap=st.sampled_from([0.0, 0.01, 0.1, 0.7, 1.5]), amp=st.floats(0.21, 1.5), f=st.floats(0.2, 2.5),
       ew=st.sampled_from([0.0, 0.5, 1.0]), height=st.sampled_from([None, 0.4]))
def test_mirror_symmetry(gap, amp, f, ew, height):
    left = fr.simulate(BLOCK, pulse(amp, f, sign=1), wall=fr.Wall(gap, side=-1, height=height, restitution=ew),
                       duration=2 * math.pi / (2 * math.pi * f) + 4)
    right = fr.simulate(BLOCK, pulse(amp, f, sign=-1), wall=fr.Wall(gap, side=1, height=height, restitution=ew),
                        duration=2 * math.pi / (2 * math.pi * f) + 4)
    assert left.status == right.status
    np.testing.assert_array_equal(left.history["t"], right.history["t"])
    np.testing.assert_array_equal(left.history["theta"], -right.history["theta"])
    np.testing.assert_array_equal(left.history["pivot"], -right.history["pivot"])
    np.testing.assert_array_equal(left.events["event"], right.events["event"])
    np.testing.assert_array_equal(left.events["velocity_after"], -right.events["velocity_after"])
    m, n = left.metrics, right.metrics
    assert (m["max_rotation_pos"], m["max_rotation_neg"]) == (n["max_rotation_neg"], n["max_rotation_pos"])
    assert (m["ground_impacts"], m["wall_impacts"]) == (n["ground_impacts"], n["wall_impacts"])


def test_mirror_symmetry_of_spectra():
    amps, freqs = np.linspace(1.3, 20, 8), np.linspace(0.3, 8, 7)
    left = fr.overturning_spectrum(BLOCK, amps, freqs, sign=1, wall=fr.Wall(gap=0.1, side=-1), progress=False)
    right = fr.overturning_spectrum(BLOCK, amps, freqs, sign=-1, wall=fr.Wall(gap=0.1, side=1), progress=False)
    for c in ("outcome", "status", "max_rotation", "ground_impacts", "wall_impacts",
              "max_rotation_toward_wall", "max_rotation_away_from_wall"):
        np.testing.assert_array_equal(left[c], right[c], err_msg=c)


# ----------------------------------------------------------------------------------------
# chatter against the wall, resting on it, release
# ----------------------------------------------------------------------------------------
@pytest.mark.nojit
@pytest.mark.parametrize("ew", [0.0, 0.5, 0.8])
def test_chatter_settles_on_the_wall_and_releases_at_the_pulse_end(ew):
    wall = fr.Wall(gap=0.05, restitution=ew)
    tw = wall.limit_angle(BLOCK)
    press = fr.Pulse(1.5 * G_TAN, kind="rectangular", duration=3.0, amplitude_unit="m/s2")
    r = fr.simulate(BLOCK, press, wall=wall)
    ev = r.events
    names = ev["event"].tolist()
    assert r.status == "safe:rest"
    assert names.count("wall-rest") == 1 and names.count("wall-release") == 1
    n_wall = names.index("wall-rest") - 1
    assert 1 <= n_wall == r.metrics["wall_impacts"] <= 200
    t_rest = ev.loc[ev["event"] == "wall-rest", "t"].item()
    t_rel = ev.loc[ev["event"] == "wall-release", "t"].item()
    assert t_rel == 3.0                                   # the pressing stops with the pulse
    h = r.history
    on = h[(h["t"] > t_rest) & (h["t"] < t_rel)]
    assert len(on) == 0 or ((on["theta"] == -tw).all() and (on["theta_dot"] == 0).all())
    assert (h.loc[h["contact"] == "wall-rest", "theta"] == -tw).all()
    # accumulation point of the Zeno sequence: intervals shrink by e_w
    hits = ev[ev["event"] == "wall-impact"]
    assert t_rest == hits["t"].iloc[-1]
    if ew > 0:
        # free flights between wall impacts: the block comes back with the speed it left
        # (to the integrator's atol), ever shorter flights, a finite number of impacts
        back, left = hits["velocity_before"].to_numpy()[1:], hits["velocity_after"].to_numpy()[:-1]
        np.testing.assert_allclose(back, -left, rtol=1e-6, atol=1e-9)
        assert (np.diff(hits["t"].to_numpy(), 2) < 0).all()
        v1 = abs(hits["velocity_after"].iloc[0])
        assert n_wall <= 3 + math.log(1e-9 / v1) / math.log(ew)


@pytest.mark.nojit
def test_release_when_the_moments_stop_pressing():
    """Under a slow half-sine the block rests on the wall until
    w theta''(w theta_w, 0) = 0, i.e. a_g = -w g tan(alpha - theta_w) (physics.md 2)."""
    for side in (-1, 1):
        wall = fr.Wall(gap=0.05, side=side, restitution=0.5)
        tw = wall.limit_angle(BLOCK)
        amp, f = 3 * G_TAN, 0.1
        r = fr.simulate(BLOCK, fr.Pulse(amp, f, sign=-side, kind="half-sine", amplitude_unit="m/s2"), wall=wall)
        t_rel = r.events.loc[r.events["event"] == "wall-release", "t"].item()
        omega = 2 * math.pi * f
        expected = (math.pi - math.asin(BLOCK.g * math.tan(BLOCK.alpha - tw) / amp)) / omega
        assert t_rel == pytest.approx(expected, abs=1e-9)
        assert r.outcome == "safe"


@pytest.mark.nojit
def test_no_rest_on_the_wall_without_pressing():
    """theta_w < alpha and no excitation: the block cannot stay on the wall."""
    wall = fr.Wall(gap=0.1, restitution=0.0)
    tw = wall.limit_angle(BLOCK)
    r = fr.simulate(BLOCK, None, wall=wall, theta0=-tw, duration=3.0)
    assert "wall-rest" not in r.events["event"].tolist()
    assert r.history["theta"].iloc[-1] > -tw
    r = fr.simulate(BLOCK, None, wall=wall, theta0=-0.5 * tw, dtheta0=-0.1, duration=3.0)
    assert "wall-rest" not in r.events["event"].tolist()


# ----------------------------------------------------------------------------------------
# leaning
# ----------------------------------------------------------------------------------------
LEAN_WALL = 1.2                                  # theta_w = 0.242 > alpha = 0.197


@pytest.mark.nojit
@pytest.mark.parametrize("ew", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("early_exit", [False, True])
def test_leaning(ew, early_exit):
    wall = fr.Wall(gap=LEAN_WALL, restitution=ew)
    tw = wall.limit_angle(BLOCK)
    assert tw > BLOCK.alpha
    r = fr.simulate(BLOCK, None, wall=wall, theta0=-(BLOCK.alpha + 0.01), duration=20.0, early_exit=early_exit)
    assert r.status == "leaning" and r.outcome == "leaning"
    assert r.metrics["max_rotation_neg"] == pytest.approx(tw, rel=1e-12)
    assert math.isnan(r.metrics["time_overturn"])
    if ew < 1 and not early_exit:
        assert r.events["event"].iloc[-1] == "wall-rest"
        assert r.history["theta"].iloc[-1] == -tw


def test_leaning_is_decided_only_after_the_excitation():
    wall = fr.Wall(gap=LEAN_WALL, restitution=0.5)
    tw = wall.limit_angle(BLOCK)
    # starts leaning, the ground pulls it back over alpha: comes back to rest upright
    back = fr.simulate(BLOCK, pulse(0.1, 0.5, sign=-1, kind="half-sine"), wall=wall, theta0=-tw, duration=30.0)
    names = back.events["event"].tolist()
    assert names[:3] == ["wall-impact", "wall-rest", "wall-release"]
    assert back.status == "safe:rest"
    # a weaker pull releases it, but it falls back on the wall: leaning
    weak = fr.simulate(BLOCK, pulse(0.05, 0.5, sign=-1, kind="half-sine"), wall=wall, theta0=-tw, duration=30.0)
    assert "wall-release" in weak.events["event"].tolist() and weak.status == "leaning"
    # rests on the wall during the pulse, is thrown off and overturns away from it
    thrown = fr.simulate(BLOCK, fr.Pulse(3.0, 1.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                         wall=fr.Wall(gap=LEAN_WALL, restitution=0.3))
    ev = thrown.events
    assert ev.loc[ev["event"] == "wall-rest", "t"].iloc[0] < 2 * math.pi / BLOCK.p
    assert thrown.outcome == "mode1" and thrown.metrics["max_rotation_pos"] > 1.5


def test_leaning_in_spectrum_and_early_exit_agrees_with_full_runs():
    amps, freqs = np.linspace(1.3, 20, 10), np.linspace(0.5, 9, 9)
    for wall in (fr.Wall(gap=LEAN_WALL, restitution=0.5), fr.Wall(gap=1.5), fr.Wall(gap=0.01),
                 fr.Wall(gap=0.1, height=0.8), fr.Wall(gap=0.0, restitution=0.9)):
        fast = fr.overturning_spectrum(BLOCK, amps, freqs, sign="both", wall=wall, progress=False)
        full = fr.overturning_spectrum(BLOCK, amps, freqs, sign="both", wall=wall, progress=False,
                                       early_exit=False)
        np.testing.assert_array_equal(fast["outcome"], full["outcome"])
        assert (fast["outcome"] != "failed").all()
        np.testing.assert_allclose(fast["max_rotation"], full["max_rotation"], rtol=1e-6)
        np.testing.assert_allclose(fast["max_rotation_toward_wall"], full["max_rotation_toward_wall"], rtol=1e-6)
        np.testing.assert_allclose(fast["max_rotation_away_from_wall"], full["max_rotation_away_from_wall"],
                                   rtol=1e-6)
        assert (fast["time_end"] <= full["time_end"]).all()
        if wall.limit_angle(BLOCK) > BLOCK.alpha:
            assert (fast["outcome"] == "leaning").any()


# ----------------------------------------------------------------------------------------
# spectra
# ----------------------------------------------------------------------------------------
def test_spectrum_columns():
    wall = fr.Wall(gap=0.1, restitution=0.9)
    df = fr.overturning_spectrum(BLOCK, [2.0, 8.0], [1.0, 3.0], sign="both", wall=wall, progress=False)
    for c in ("ground_impacts", "wall_impacts", "max_rotation_toward_wall", "max_rotation_away_from_wall"):
        assert c in df.columns
    assert df.attrs["kernel"] == "rigid_wall"
    assert (df["wall_impacts"] > 0).any()
    tw = wall.limit_angle(BLOCK)
    assert (df["max_rotation_toward_wall"] <= tw * (1 + 1e-12)).all()
    assert (df["max_rotation"] == np.maximum(df["max_rotation_toward_wall"],
                                             df["max_rotation_away_from_wall"])).all()
    plain = fr.overturning_spectrum(BLOCK, [2.0], [1.0], progress=False)
    assert (plain["wall_impacts"] == 0).all() and "max_rotation_toward_wall" not in plain.columns


def test_wall_widens_the_overturning_region_for_pulses_toward_it():
    """Mennitti et al. (2021), physics.md 2: for pulses that throw the block toward the
    wall the overturning region grows, more for a 10 cm gap than for 1 cm."""
    amps = np.linspace(1.3, 25, 12)
    freqs = np.linspace(0.2, 9, 12)
    kw = dict(progress=False, early_exit=False)
    def overturned(**k):
        d = fr.overturning_spectrum(BLOCK, amps, freqs, sign=1, **kw, **k)
        return d["outcome"].isin(["mode1", "mode2"]).to_numpy()
    two = overturned()
    one_cm = overturned(wall=fr.Wall(gap=0.01))
    ten_cm = overturned(wall=fr.Wall(gap=0.10))
    assert one_cm.sum() > two.sum()
    assert ten_cm.sum() > one_cm.sum()


# ----------------------------------------------------------------------------------------
# properties
# ----------------------------------------------------------------------------------------
@settings(max_examples=25, deadline=None)
@given(gap=st.sampled_from([0.0, 0.001, 0.01, 0.1, 0.5, 1.2, 3.0, 6.0]), ew=st.floats(0.0, 1.0, allow_subnormal=False),
       height=st.sampled_from([None, 0.2, 2.0]), side=st.sampled_from([-1, 1]),
       amp=st.floats(0.0, 3.0, allow_subnormal=False), f=st.floats(0.1, 3.0), sign=st.sampled_from([-1, 1]),
       kind=st.sampled_from(["one-sine", "half-sine", "one-cosine"]))
def test_invariants(gap, ew, height, side, amp, f, sign, kind):
    wall = fr.Wall(gap=gap, side=side, height=height, restitution=ew)
    tw = wall.limit_angle(BLOCK)
    r = fr.simulate(BLOCK, fr.Pulse(amp, f, sign=sign, kind=kind), wall=wall, t_after=6.0)
    assert r.outcome in ("safe", "mode1", "mode2", "leaning"), r.status
    h = r.history
    assert np.isfinite(h[["theta", "theta_dot"]].to_numpy()).all()
    assert (side * h["theta"] <= tw + 1e-12).all()
    ev = r.events
    hits = ev[ev["event"] == "wall-impact"]
    assert (hits["velocity_after"].abs() <= hits["velocity_before"].abs() * (1 + 1e-15)).all()
    if tw == math.inf:
        assert len(hits) == 0
    if r.outcome == "leaning":
        assert tw > BLOCK.alpha
    if r.outcome in ("mode1", "mode2") and tw < BLOCK.theta_over:
        assert -side * h["theta"].iloc[-1] == pytest.approx(BLOCK.theta_over)     # away from the wall
    assert r.metrics["wall_impacts"] == len(hits)


# ----------------------------------------------------------------------------------------
# bad input, API
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, field", [
    (dict(gap=-0.01), "gap"), (dict(gap=float("nan")), "gap"), (dict(gap=float("inf")), "gap"),
    (dict(gap="x"), "gap"), (dict(gap=0.1, height=0.0), "height"), (dict(gap=0.1, height=-1.0), "height"),
    (dict(gap=0.1, height=float("nan")), "height"), (dict(gap=0.1, restitution=1.01), "restitution"),
    (dict(gap=0.1, restitution=-0.1), "restitution"), (dict(gap=0.1, restitution=float("nan")), "restitution"),
    (dict(gap=0.1, side=0), "side"), (dict(gap=0.1, side=2), "side"), (dict(gap=0.1, side=True), "side"),
])
def test_bad_wall_input(kwargs, field):
    with pytest.raises(ValueError, match=field):
        fr.Wall(**kwargs)


def test_bad_scene_input():
    no_h = fr.RigidBlock(alpha=0.2, p=2.0)
    with pytest.raises(ValueError, match="half-height"):
        fr.simulate(no_h, pulse(0.5, 1.0), wall=fr.Wall(gap=0.1))
    with pytest.raises(ValueError, match="half-height"):
        fr.overturning_spectrum(no_h, [2.0], [1.0], wall=fr.Wall(gap=0.1), progress=False)
    tw = fr.Wall(gap=0.1).limit_angle(BLOCK)
    with pytest.raises(ValueError, match="penetrates the wall"):
        fr.simulate(BLOCK, None, wall=fr.Wall(gap=0.1), theta0=-1.01 * tw, duration=1.0)
    with pytest.raises(ValueError, match="penetrates the wall"):
        fr.simulate(BLOCK, None, wall=fr.Wall(gap=0.0, side=1), theta0=0.01, duration=1.0)
    with pytest.raises(ValueError, match="wall must be"):
        fr.simulate(BLOCK, pulse(0.5, 1.0), wall=0.1)
    # touching the wall is allowed
    fr.simulate(BLOCK, None, wall=fr.Wall(gap=0.1), theta0=-tw, duration=0.5)


def test_wall_api():
    w = fr.Wall(0.1)
    assert (w.gap, w.side, w.height, w.restitution) == (0.1, -1, None, 1.0)
    assert w.toward_sign == 1 and fr.Wall(0.1, side=1).toward_sign == -1
    assert "Wall" in fr.__all__
    with pytest.raises(Exception):
        w.gap = 0.2                                    # frozen
    par = np.zeros(10)
    from fastrock.kernels import rigid as K
    fr.Wall(0.0, side=1, restitution=0.7).fill_par(par, BLOCK)
    assert (par[K.P_WALL_SIDE], par[K.P_THETA_W], par[K.P_E_W], par[K.P_HOGAN]) == (1.0, 0.0, 0.7, 1.0)


def test_cli_wall_options(tmp_path, capsys):
    from fastrock.cli.app import main
    assert main(["simulate", "--b", "0.5", "--h", "2.5", "--amplitude", "0.5", "--amplitude-unit", "g",
                 "--frequency", "0.5", "--frequency-unit", "Hz", "--wall-gap", "0.1", "--wall-restitution",
                 "0.8", "--events", str(tmp_path / "ev.csv")]) == 0
    out = capsys.readouterr().out
    assert "kernel rigid_wall" in out
    ev = pd.read_csv(tmp_path / "ev.csv")
    assert (ev["event"] == "wall-impact").any()
    assert main(["spectrum", "--b", "0.5", "--h", "2.5", "--wall-gap", "0.01", "--wall-side", "1",
                 "--n-amp", "4", "--n-freq", "3", "--sign", "both", "--quiet",
                 "--png", str(tmp_path / "s.png"), "--csv", str(tmp_path / "s.csv")]) == 0
    df = pd.read_csv(tmp_path / "s.csv")
    assert {"ground_impacts", "wall_impacts", "max_rotation_toward_wall"} <= set(df.columns)
    assert main(["simulate", "--wall-gap", "-1", "--b", "0.5", "--h", "2.5"]) == 2
    assert "gap" in capsys.readouterr().err


# ----------------------------------------------------------------------------------------
# effect selection: a scene without a wall never touches the wall kernel
# ----------------------------------------------------------------------------------------
def _run_py(code):
    env = dict(os.environ)
    # not in the repository root: there `python -c` imports the source tree, whose kernels a
    # non-editable install caches apart (a compile per model); elsewhere, the installed fastrock
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True,
                          cwd=tempfile.gettempdir(),
                          timeout=600).stdout


@pytest.mark.slow
def test_scene_without_wall_does_not_import_the_wall_kernel():
    out = _run_py(
        "import sys, fastrock as fr\n"
        "b = fr.RigidBlock.rectangle(0.5, 2.5)\n"
        "r = fr.simulate(b, fr.Pulse(0.5, 0.5))\n"
        "fr.overturning_spectrum(b, [2.0], [1.0], progress=False)\n"
        "print(r.kernel, 'fastrock.kernels.wall' in sys.modules)\n")
    assert out.split() == ["rigid", "False"]


@pytest.mark.slow
@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1" or os.environ.get("FASTROCK_CACHE") == "0",
                    reason="needs the on-disk cache")
def test_wall_kernels_load_from_the_disk_cache():
    fr.simulate(BLOCK, pulse(0.5, 0.5), wall=fr.Wall(gap=0.1))              # populate the cache
    fr.overturning_spectrum(BLOCK, [2.0], [1.0], wall=fr.Wall(gap=0.1), progress=False)
    out = _run_py(
        "import fastrock as fr\n"
        "from fastrock.kernels import wall as K\n"
        "b = fr.RigidBlock.rectangle(0.5, 2.5)\n"
        "fr.simulate(b, fr.Pulse(0.5, 0.5), wall=fr.Wall(gap=0.1))\n"
        "fr.overturning_spectrum(b, [2.0], [1.0], wall=fr.Wall(gap=0.1), progress=False)\n"
        "for f in (K.rigid_wall_simulate, K.rigid_wall_sweep):\n"
        "    print(len(f.stats.cache_hits), len(f.stats.cache_misses))\n")
    for line in out.strip().splitlines():
        hits, misses = map(int, line.split())
        assert hits >= 1 and misses == 0
