"""A rounded top in the contact model (issue #17, "Real rock shapes"): the wall-side top corner
is a quarter circle of radius rho, centre C = (w (b_w - rho), ht - rho) from the centre of mass.
Against the wall's face the gap is C's minus rho and the contact point the arc's front point;
against a short wall's top edge E the gap is |C - E| - rho (kernels/contact.py ``wall_geom``,
docs/theory/wall.md).

Oracles:
- with a pivot that never slips and no flight, the wall model's rounded-top runs
  (tests/test_wall_rounded_top.py): outcome, ground and wall impacts, max rotation, and the first
  wall impact at the rounded contact angle (Wall.limit_angle) at the wall model's time;
- at every wall impact the contact model logs, the arc touches the wall (C at rho from it),
  computed here from the recorded state, not by the kernel's geometry;
- rho -> 0 tends to the square corner;
- no energy gain in free runs (hypothesis);
- the mirror scene is the same run; a symmetric RigidBody is its RigidBlock bit for bit;
- a frictional wall and a run in flight end with a definite status.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fastrock as fr

B, H, RHO = 0.3, 1.0, 0.25
BLOCK = fr.RigidBlock.rectangle(B, H, top_radius=RHO)
FLAT = fr.RigidBlock.rectangle(B, H)
OUTLINE = [(0.0, 0.0), (1.0, 0.0), (0.8, 2.2), (0.0, 2.2)]      # tests/test_wall_rigid_body.py
RBODY = dataclasses.replace(fr.RigidBody.from_polygon(OUTLINE, mass=1.0), top="rounded", top_radius=0.3)
RMIRROR = dataclasses.replace(fr.RigidBody.from_polygon([(-x, y) for x, y in OUTLINE], mass=1.0),
                              top="rounded", top_radius=0.3)
NEVER_SLIPS = fr.Friction.never_slipping()
TIGHT = fr.Solver(rtol=1e-10)


def _geometry(body, wall):
    """(b_w, h, ht, rho): the wall-side half-width, CM height above the base, top height above
    the CM and the arc's radius, from the body's own attributes."""
    if isinstance(body, fr.RigidBody):
        bw = body.b2 if wall.side > 0 else body.b1
        h = body.h2 if wall.side > 0 else body.h1
        return bw, h, body.wall_face_top(wall.side), body.top_radius
    return body.b, body.h, body.h, body.top_radius


def _arc_centre(row, body, wall):
    """World position of the arc's centre C and of the centre of mass G for one history row."""
    bw, h, ht, rho = _geometry(body, wall)
    th, x, z = row["theta"], row["d"], row["z"]
    gx, gy = x + h * math.sin(th), z + h * math.cos(th)
    a, c = wall.side * (bw - rho), ht - rho               # C in the body frame
    return gx + a * math.cos(th) + c * math.sin(th), gy - a * math.sin(th) + c * math.cos(th), gx, gy


def _arc_distance(row, body, wall):
    """Distance from the arc's centre C to the wall (its face, or its top edge E when C is above
    it) minus rho, and the wall-side base corner's clear gap, for one history row."""
    bw, h, ht, rho = _geometry(body, wall)
    w = wall.side
    th = row["theta"]
    cx, cy, gx, gy = _arc_centre(row, body, wall)
    face = w * (bw + wall.gap)                            # the wall's face: x = w (b_w + d)
    if wall.height is not None and cy > wall.height:
        arc = math.hypot(face - cx, wall.height - cy) - rho
    else:
        arc = w * (face - cx) - rho
    nx = gx + w * bw * math.cos(th) - h * math.sin(th)    # the wall-side base corner
    return arc, w * (face - nx)


def _wall_contacts(run, body, wall):
    """(arc, base) gaps at each logged wall impact (the history's rows at that time)."""
    hist = run.history
    out = []
    for t in run.events.t[run.events.event == "wall-impact"]:
        rows = hist[hist.t == t]
        assert len(rows) > 0, t
        out.append(min((_arc_distance(r, body, wall) for _, r in rows.iterrows()), key=lambda p: abs(p[0])))
    return out


# --------------------------------------------------------------------- the wall model's runs
WALLS = [fr.Wall(0.05, restitution=0.8), fr.Wall(0.2, restitution=1.0),
         fr.Wall(0.5, height=1.7, restitution=0.8),        # a short wall whose edge meets the block's arc
         fr.Wall(0.2, height=1.4, restitution=0.8),        # ... and one whose edge meets the face
         fr.Wall(0.6, height=1.85, restitution=0.8)]       # the edge on the arc of both bodies
AMPS, FREQS = np.array([1.2, 1.5, 2.0, 3.0]), np.array([1.0, 2.0, 3.0])


def _pulse(amp, freq, sign):
    """A one-sine pulse of amplitude ``amp`` g tan(alpha) and frequency ``freq`` omega_p / p."""
    return fr.Pulse(amp, freq, sign=sign, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


@pytest.mark.parametrize("body", [BLOCK, RBODY], ids=["block", "body"])
@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("wall", WALLS, ids=["tall-0.05", "tall-0.2", "short-arc", "short-face", "short-arc-2"])
def test_never_slipping_no_flight_equals_the_wall_model(body, side, wall):
    """On the cells where the contact model's body never flies, run to the end, the wall model and
    the contact model are the same physics: outcomes and impact counts equal, max rotations to
    1e-8 relative (both at rtol 1e-10; the two integrate different states, theta alone and
    (theta, x, z), and agreed to 9e-10 for the square corner, tests/test_wall_body.py)."""
    wall = dataclasses.replace(wall, side=side)
    branch = wall.contact(body)
    kw = dict(sign="both", wall=wall, solver=TIGHT, progress=False, early_exit=False)
    a = fr.overturning_spectrum(body, AMPS, FREQS, **kw)
    b = fr.overturning_spectrum(body, AMPS, FREQS, friction=NEVER_SLIPS, **kw)
    assert a.attrs["kernel"] in ("rigid_wall", "wall_body")
    assert b.attrs["kernel"] in ("contact", "contact_body")
    keep = (b["flights"] == 0).to_numpy()
    assert keep.sum() >= 12 and (a["wall_impacts"][keep] > 0).sum() >= 3, (branch, keep.sum())
    for col in ("outcome", "wall_impacts", "ground_impacts"):
        assert list(a[col].astype(str)[keep]) == list(b[col].astype(str)[keep]), col
    np.testing.assert_allclose(a["max_rotation"][keep], b["max_rotation"][keep], rtol=1e-8, atol=0)


@pytest.mark.parametrize("body", [BLOCK, RBODY], ids=["block", "body"])
@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("wall", WALLS, ids=["tall-0.05", "tall-0.2", "short-arc", "short-face", "short-arc-2"])
def test_first_wall_impact_at_the_rounded_contact_angle(body, side, wall):
    """The first wall impact: at theta = w theta_w (Wall.limit_angle, the arc's closed form), at the
    wall model's time; the recorded state puts C at rho from the wall (or, on the face branch of
    a short wall, the face on the edge)."""
    wall = dataclasses.replace(wall, side=side)
    pulse = _pulse(2.0, 1.0, -side)
    a = fr.simulate(body, pulse, wall=wall, solver=TIGHT, duration=3.0)
    b = fr.simulate(body, pulse, wall=wall, friction=NEVER_SLIPS, solver=TIGHT, duration=3.0)
    ea = a.events[a.events.event == "wall-impact"]
    eb = b.events[b.events.event == "wall-impact"]
    assert len(ea) > 0 and len(eb) > 0
    assert b.metrics["flights"] == 0 or eb.t.iloc[0] < b.events.t[b.events.event == "flight"].min()
    tw = wall.limit_angle(body)
    assert ea.theta.iloc[0] == pytest.approx(side * tw, abs=1e-12)
    # the contact model locates the wall's gap in (theta, x, z): theta to its event tolerance
    assert eb.theta.iloc[0] == pytest.approx(side * tw, abs=1e-9)
    assert eb.t.iloc[0] == pytest.approx(ea.t.iloc[0], rel=1e-8)
    arc, base = _wall_contacts(b, body, wall)[0]
    if wall.contact(body) == "tall" or math.hypot(wall.gap, wall.height) > _face_straight(body, wall):
        assert abs(arc) < 1e-9, arc
    else:
        assert arc > 0.0                     # the straight face meets the edge below the arc


def _face_straight(body, wall):
    bw, h, ht, rho = _geometry(body, wall)
    return h + ht - rho


# --------------------------------------------------------------------- contact condition
SCENES = [      # amplitudes in units of the uplift acceleration g tan(alpha)
    ("tall-sticky", BLOCK, fr.Wall(0.05, side=1, restitution=0.6), NEVER_SLIPS, 1.5),
    ("tall-slip", BLOCK, fr.Wall(0.08, side=-1, restitution=0.8), fr.Friction(0.4, lift_off="flight"), 2.0),
    ("tall-wallfriction", BLOCK, fr.Wall(0.05, side=1, restitution=0.8, friction=0.4),
     fr.Friction(0.8, lift_off="flight"), 2.0),
    ("short-arc", BLOCK, fr.Wall(0.5, side=1, height=1.7), NEVER_SLIPS, 2.0),
    ("body-tall", RBODY, fr.Wall(0.05, side=1, restitution=0.8), fr.Friction(0.6, lift_off="flight"), 2.0),
    ("body-left", RBODY, fr.Wall(0.05, side=-1, restitution=0.8, friction=0.3), NEVER_SLIPS, 2.0),
]


@pytest.mark.parametrize("name, body, wall, friction, amp", SCENES, ids=[s[0] for s in SCENES])
def test_every_wall_impact_is_the_arc_or_the_base_corner_on_the_wall(name, body, wall, friction, amp):
    run = fr.simulate(body, _pulse(amp, 1.0, -wall.side), wall=wall,
                      friction=friction, duration=6.0)
    assert not run.status.startswith("failed"), run.status
    gaps = _wall_contacts(run, body, wall)
    assert len(gaps) > 0
    arcs = 0
    for arc, base in gaps:
        # the arc (C at rho from the wall) or the wall-side base corner (a face impact) touches it
        assert min(abs(arc), abs(base)) < 1e-9, (arc, base)
        assert arc > -1e-9 and base > -1e-9
        arcs += abs(arc) < 1e-9
    assert arcs > 0


# --------------------------------------------------------------------- rho -> 0
def test_small_radius_tends_to_the_square_corner():
    """The wall impacts (times, and the rotation at the first) converge to the square corner's as
    rho -> 0, linearly (the contact angle moves by O(rho)): errors shrink with rho, not equal at
    any rho.  (The max rotation is reached before the wall is touched here: not a measure.)"""
    wall = fr.Wall(0.05, side=1, restitution=0.8)
    pulse = _pulse(1.2, 2.0, -1)                          # safe, two wall impacts

    def run(body):
        r = fr.simulate(body, pulse, wall=wall, friction=NEVER_SLIPS, solver=TIGHT, duration=3.0)
        hits = r.events[r.events.event == "wall-impact"]
        assert r.status == "safe:moving" and len(hits) == 2 and r.metrics["flights"] == 0
        return np.array([hits.t.iloc[0], hits.t.iloc[1], hits.theta.iloc[0]])

    square = run(FLAT)
    rhos = (0.1, 0.01, 1e-3, 1e-4)
    errs = np.array([np.abs(run(fr.RigidBlock.rectangle(B, H, top_radius=rho)) - square) for rho in rhos])
    assert (errs > 0.0).all()                             # convergence, not the same run
    assert (errs[1:] < errs[:-1]).all()
    assert (errs[-1] < 2e-3 * errs[0]).all()              # rho / 1000: about 1/1000 of the error


# --------------------------------------------------------------------- energy
def _energy(run, body, wall, friction):
    from fastrock.kernels import layout as L
    from fastrock.running.models import contact_par
    par = contact_par(body, friction, wall)
    hm, iG = 0.5 * (par[L.C_H1] + par[L.C_H2]), par[L.C_IG]
    h = run.history
    th, om = h["theta"].to_numpy(), h["theta_dot"].to_numpy()
    vx = h["d_dot"].to_numpy() + hm * np.cos(th) * om
    vy = h["z_dot"].to_numpy() - hm * np.sin(th) * om
    return 0.5 * (vx * vx + vy * vy) + 0.5 * iG * om * om + body.g * (h["z"].to_numpy() + hm * np.cos(th))


@settings(max_examples=30, deadline=None)
@given(rho=st.floats(0.02, 0.5), gap=st.sampled_from([0.0, 0.02, 0.1]), side=st.sampled_from([1, -1]),
       height=st.sampled_from([None, 1.8, 1.2]), e_w=st.sampled_from([1.0, 0.7, 0.0]),
       mu_w=st.sampled_from([0.0, 0.3]), mu=st.sampled_from([math.inf, 0.8, 0.3]),
       frac=st.floats(0.05, 0.9), rate=st.floats(-3.0, 3.0, allow_subnormal=False))
def test_free_runs_never_gain_energy(rho, gap, side, height, e_w, mu_w, mu, frac, rate):
    """Released without excitation, rocking toward the wall or away: the mechanical energy never
    rises, over a wall impact or in a free phase, beyond 1e-7 of the barrier (rtol 1e-10)."""
    body = fr.RigidBlock.rectangle(B, H, top_radius=rho)
    wall = fr.Wall(gap, side=side, height=height, restitution=e_w, friction=mu_w)
    friction = fr.Friction(mu, lift_off="flight")
    tw = wall.limit_angle(body)
    theta0 = side * frac * min(tw, body.alpha) if gap > 0 else -side * frac * body.alpha
    run = fr.simulate(body, None, wall=wall, friction=friction, theta0=theta0, dtheta0=rate * np.sign(theta0),
                      solver=TIGHT, duration=4.0)
    assert not run.status.startswith("failed"), run.status
    E = _energy(run, body, wall, friction)
    barrier = body.g * (math.hypot(B, H) - H)
    assert np.max(np.diff(E)) <= 1e-7 * barrier, (np.max(np.diff(E)) / barrier, run.status)


# --------------------------------------------------------------------- symmetry
@pytest.mark.parametrize("wall", [fr.Wall(0.05, restitution=0.8, friction=0.3), fr.Wall(0.5, height=1.7)])
def test_mirror_scene_is_the_same_run(wall):
    friction = fr.Friction(0.6, lift_off="flight")
    for body, mirror in ((BLOCK, BLOCK), (RBODY, RMIRROR)):
        runs = []
        for side in (1, -1):
            b = body if side == 1 else mirror
            runs.append(fr.simulate(b, _pulse(2.0, 1.0, -side), wall=dataclasses.replace(wall, side=side),
                                    friction=friction, solver=TIGHT, duration=5.0))
        a, m = runs
        assert a.status == m.status and a.metrics["wall_impacts"] == m.metrics["wall_impacts"] > 0
        assert list(a.events.event) == list(m.events.event)
        np.testing.assert_allclose(a.events.theta, -m.events.theta, rtol=1e-8, atol=1e-12)
        np.testing.assert_allclose(a.events.t, m.events.t, rtol=1e-9, atol=1e-12)
        assert a.metrics["max_rotation"] == pytest.approx(m.metrics["max_rotation"], rel=1e-9)


def test_symmetric_body_equals_its_block_bit_for_bit():
    from fastrock.running.models import contact_par
    body = dataclasses.replace(fr.RigidBody.from_block(FLAT), top="rounded", top_radius=RHO)
    assert body.is_symmetric and body.to_block() == BLOCK
    friction = fr.Friction(0.6, lift_off="flight")
    for wall in (fr.Wall(0.05, side=1, friction=0.2), fr.Wall(0.5, side=-1, height=1.7)):
        assert np.array_equal(contact_par(body, friction, wall), contact_par(BLOCK, friction, wall))
        kw = dict(sign="both", wall=wall, friction=friction, progress=False)
        sa = fr.overturning_spectrum(body, [1.5, 3.0, 6.0], [1.0, 3.0], **kw)
        sb = fr.overturning_spectrum(BLOCK, [1.5, 3.0, 6.0], [1.0, 3.0], **kw)
        assert list(sa.outcome) == list(sb.outcome)
        assert np.array_equal(sa.max_rotation.to_numpy(), sb.max_rotation.to_numpy())
        assert np.array_equal(sa.wall_impacts.to_numpy(), sb.wall_impacts.to_numpy())


# --------------------------------------------------------------------- examples
def test_frictional_wall_example():
    """A block thrown at a frictional wall (mu_w = 0.5) with a base that slips (mu = 0.4): it hits
    the wall with its arc, and the run ends safe, at rest."""
    wall = fr.Wall(0.05, side=1, restitution=0.8, friction=0.5)
    run = fr.simulate(BLOCK, _pulse(1.2, 2.0, -1), wall=wall,
                      friction=fr.Friction(0.4, lift_off="flight"), duration=8.0)
    assert run.kernel == "contact"
    assert run.status == "safe:rest", run.status
    assert run.metrics["wall_impacts"] > 0 and run.metrics["max_slide"] > 0.0
    assert any(abs(arc) < 1e-9 for arc, _ in _wall_contacts(run, BLOCK, wall))


def test_flight_example():
    """A strong short pulse throws the block into flight toward the wall; the arc strikes the wall
    (in flight or after landing) and the run ends with a definite status."""
    wall = fr.Wall(0.1, side=1, restitution=0.8, friction=0.2)
    run = fr.simulate(BLOCK, fr.Pulse(3.0, 4.0, sign=-1), wall=wall,
                      friction=fr.Friction(0.8, lift_off="flight"), duration=6.0)
    assert run.metrics["flights"] > 0 and run.metrics["wall_impacts"] > 0
    assert not run.status.startswith("failed"), run.status
    gaps = _wall_contacts(run, BLOCK, wall)
    assert all(min(abs(a), abs(b)) < 1e-9 for a, b in gaps)


# --------------------------------------------------------------------- the wall row
def _state_at(y0, acc, t, par):
    """The state at time t of a motion with constant CM and angular accelerations ``acc``."""
    from fastrock.kernels import contact as C
    hm = C.hmid(par)
    th0, om = y0[0], y0[1]
    vgx, vgy = C.cm_velocity(y0, par)
    th = th0 + om * t + 0.5 * acc[2] * t * t
    gx = y0[2] + hm * math.sin(th0) + vgx * t + 0.5 * acc[0] * t * t
    gy = y0[4] + hm * math.cos(th0) + vgy * t + 0.5 * acc[1] * t * t
    y = np.array([th, 0.0, gx - hm * math.sin(th), 0.0, gy - hm * math.cos(th), 0.0])
    C.set_cm_velocity(y, par, vgx + acc[0] * t, vgy + acc[1] * t, om + acc[2] * t)
    return y


@pytest.mark.parametrize("wall", [fr.Wall(0.05, side=1), fr.Wall(0.05, side=-1), fr.Wall(0.5, side=1, height=1.7),
                                  fr.Wall(0.5, side=-1, height=1.7)])
def test_wall_row_is_the_gaps_second_derivative(wall):
    """The mode solve's wall row (``contact_acc``: the contact point's normal acceleration plus
    ``wall_normal_rate``) equals the second difference of the gap along a motion of constant
    accelerations, at contact, for each feature the arc meets (the wall's face: the centripetal
    -rho theta'^2; the edge E: the curvature term).  Central differences with h = 1e-4 s are
    good to ~1e-5 here; leaving out rho theta'^2 would be off by O(1)."""
    from fastrock.kernels import contact as C
    from fastrock.running.models import contact_par
    par = contact_par(BLOCK, NEVER_SLIPS, wall)
    rng = np.random.default_rng(7)
    kinds = set()
    for _ in range(60):
        y = np.array([wall.side * rng.uniform(0.0, 0.8), rng.uniform(-2, 2), 0.0, rng.uniform(-1, 1),
                      rng.uniform(0.0, 0.6), rng.uniform(-1, 1)])
        for _ in range(60):                               # x onto the contact (Newton, numeric slope)
            g0 = C.wall_geom(y, par)[0]
            if abs(g0) < 1e-15:
                break
            y1 = y.copy()
            y1[2] += 1e-7
            y[2] -= g0 * 1e-7 / (C.wall_geom(y1, par)[0] - g0)
        kind = C.wall_geom(y, par)[7]
        acc = rng.uniform(-3.0, 3.0, 3)
        h = 1e-4
        around = [C.wall_geom(_state_at(y, acc, t, par), par) for t in (-h, 0.0, h)]
        if abs(around[1][0]) > 1e-12 or any(a[7] != kind for a in around) or kind == C.WG_TOP:
            continue
        fd = (around[0][0] - 2.0 * around[1][0] + around[2][0]) / (h * h)
        an, _at = C.contact_acc(2, y, par, acc)
        assert an == pytest.approx(fd, abs=1e-4 * (1.0 + abs(fd))), (kind, an, fd)
        kinds.add(int(kind))
    assert C.WG_CORNER in kinds
    if wall.height is not None:
        assert C.WG_VERTEX in kinds and C.WG_EDGE in kinds


# --------------------------------------------------------------------- leaning on an edge, gap 0
@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("mu, mu_w", [(math.inf, 0.0), (0.6, 0.0), (0.6, 0.4), (0.2, 0.0), (0.2, 0.4)])
def test_leans_on_a_short_walls_edge_with_its_arc(side, mu, mu_w):
    """Released at rest past alpha toward a short wall whose edge meets the arc past alpha
    (theta_w = 0.347 > alpha = 0.291): both models end leaning; the contact model's block
    rests with the arc on the edge (|C - E| = rho to 1e-9 m at the end, the arc's closed contact
    held by the mode solve with the curvature term), having bounced on it, in flight too."""
    wall = fr.Wall(0.6, side=side, height=1.66, restitution=0.5, friction=mu_w)
    assert wall.limit_angle(BLOCK) > BLOCK.alpha
    theta0 = side * (BLOCK.alpha + 0.02)
    ref = fr.simulate(BLOCK, None, wall=dataclasses.replace(wall, friction=0.0), theta0=theta0, solver=TIGHT,
                      duration=6.0)
    run = fr.simulate(BLOCK, None, wall=wall, friction=fr.Friction(mu, lift_off="flight"), theta0=theta0,
                      solver=TIGHT, duration=6.0)
    assert ref.outcome == run.outcome == "leaning", (ref.status, run.status)
    assert run.metrics["wall_impacts"] > 1 and "wall-rest" in set(run.events.event)
    last = run.history.iloc[-1]
    arc, _base = _arc_distance(last, BLOCK, wall)
    assert abs(arc) < 1e-9 and last.theta_dot == 0.0
    # E on the arc, not on the face or the top: E - C in the body frame points up and out
    cx, cy, _gx, _gy = _arc_centre(last, BLOCK, wall)
    ex, ey = side * (B + wall.gap) - cx, wall.height - cy
    th = last.theta
    assert side * (ex * math.cos(th) - ey * math.sin(th)) > 0.0 and ex * math.sin(th) + ey * math.cos(th) > 0.0


@pytest.mark.parametrize("side", [1, -1])
def test_gap_zero_equals_the_wall_model(side):
    """Gap 0 (the face on the wall at rest: Hogan's one-sided rocking in the wall model, the
    arc never reaching the wall first): with a pivot that never slips and no flight, the runs
    of tests/test_contact_gap0.py's oracle (status, impact counts, max rotation to 1e-6)."""
    wall = fr.Wall(0.0, side=side, restitution=0.8)
    checked = 0
    for sign in (1, -1):
        for amp, freq in ((1.2, 1.0), (1.5, 2.0), (2.5, 3.0)):
            p = _pulse(amp, freq, sign)
            ref = fr.simulate(BLOCK, p, wall=wall, duration=8.0)
            run = fr.simulate(BLOCK, p, wall=wall, friction=NEVER_SLIPS, duration=8.0)
            if run.metrics["flights"]:
                continue
            assert run.status == ref.status
            assert run.metrics["wall_impacts"] == ref.metrics["wall_impacts"]
            assert run.metrics["impacts"] == ref.metrics["impacts"]
            assert run.metrics["max_rotation"] == pytest.approx(ref.metrics["max_rotation"], rel=1e-6)
            checked += 1
    assert checked >= 4
