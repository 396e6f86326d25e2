"""A wall lower than the body in the contact model (issue #13 item 3, issue #17 item 1): the wall's
top edge E is a fixed point that the body's wall-side face touches (kernels/contact.py
``wall_geom``: gap = E's signed distance to the face line, normal = the face's, turning with the
body; past the top corner, the top corner against the wall's face below E, or E itself).

Oracles:
- mu = inf, no flight: the wall model's short-wall results (``Wall.limit_angle``: tan theta_w =
  d / h_w), run for run, both wall sides, both pulse signs, two restitutions, an edge below and one
  above the centre of mass, and a small spectrum;
- a wall out of reach (a gap beyond the face's reach, plus the slide) is no wall;
- the mode solve keeps a closed edge contact closed: the second derivative of E's distance to the
  face, by finite differences of an independent geometry along the solved motion, is 0 (the
  velocity-product term of the turning normal is in the wall row);
- ``wall_geom``'s gap, contact point and normal are E's distance, nearest point and direction to
  the body's outline (random states, independent geometry), the face's line ending at the corners;
- at every wall impact E lies on the body's outline (or the wall-side base corner on the wall) to
  1e-9 m, and at no stored state is E inside the body by more than 1e-9 m;
- no transition raises the mechanical energy;
- an asymmetric RigidBody runs with a short wall, friction and flight; a symmetric RigidBody
  equals its block.
"""
from __future__ import annotations

import itertools
import math
import os
import sys
import warnings

import numpy as np
import pytest

from fastrock import (Friction, Pulse, RigidBlock, RigidBody, Wall, overturning_spectrum,
                      simulate)
from fastrock.kernels import contact as C
from fastrock.kernels import layout as L
from fastrock.model.excitation import to_header
from fastrock.running.models import contact_par

sys.path.insert(0, os.path.dirname(__file__))
from test_contact_core import run  # noqa: E402
from test_contact_gap0 import _same  # noqa: E402
from test_contact_small_gap import ENERGY_TOL  # noqa: E402

BLOCK = RigidBlock.rectangle(0.2, 0.8)              # face 1.6 m
STICKY = Friction(math.inf, lift_off="flight")      # the contact model (lift_off="stop": the wall model)
LOW = dict(gap=0.05, height=0.5)                    # edge below the CM: theta_w = atan(0.1)
HIGH = dict(gap=0.1, height=1.2)                    # edge above the CM
PULSES = ((0.3, 1.0), (0.5, 2.0), (1.0, 3.0), (3.0, 5.0))
ASYM = RigidBody(mass=1.0, inertia=0.12, b1=0.15, h1=0.8, b2=0.3, h2=0.8,
                 outline=[(-0.15, -0.8), (0.3, -0.8), (0.3, 0.9), (-0.15, 0.9)])
TOL_GEOM = 1e-9


@pytest.mark.parametrize("geo", [LOW, HIGH], ids=["edge-below-cm", "edge-above-cm"])
@pytest.mark.parametrize("side", [1, -1])
def test_mu_inf_equals_wall_model(side, geo):
    wall_kinds = set()
    impacts = 0
    for e_w in (1.0, 0.7):
        wall = Wall(side=side, restitution=e_w, **geo)
        assert wall.contact(BLOCK) == "short"
        for sign in (1, -1):
            for a, f in PULSES:
                p = Pulse(a, f, sign=sign)
                ref = simulate(BLOCK, p, wall=wall, duration=8.0)
                c = simulate(BLOCK, p, wall=wall, friction=STICKY, duration=8.0)
                _same(c, ref, (side, e_w, sign, a, f))
                impacts += ref.metrics["wall_impacts"]
                wall_kinds.add(ref.outcome)
    assert impacts > 0 and "safe" in wall_kinds and wall_kinds - {"safe"}, (impacts, wall_kinds)


def test_mu_inf_spectrum_equals_wall_model():
    amps, freqs = np.linspace(1.2, 8.0, 5), np.linspace(0.5, 6.0, 4)
    for side in (1, -1):
        kw = dict(sign="both", wall=Wall(side=side, restitution=0.8, **LOW), progress=False,
                  early_exit=False)
        ref = overturning_spectrum(BLOCK, amps, freqs, **kw)
        c = overturning_spectrum(BLOCK, amps, freqs, friction=STICKY, **kw)
        # where the pivot's normal force reaches 0 the contact model's block flies (the wall model
        # has none): those cells are left out, as in tests/test_contact_gap0.py
        ok = c["flights"].to_numpy() == 0
        assert ok.sum() >= 0.75 * len(ok), ok.sum()
        for col in ("outcome", "status", "wall_impacts", "ground_impacts"):
            np.testing.assert_array_equal(c[col][ok], ref[col][ok], err_msg=f"{col} side {side}")
        np.testing.assert_allclose(c["max_rotation"][ok], ref["max_rotation"][ok], rtol=1e-6)
        assert (ref["wall_impacts"][ok] > 0).any() and (ref["outcome"][ok] != "safe").any()


@pytest.mark.parametrize("side", [1, -1])
def test_wall_out_of_reach_is_no_wall(side):
    """Beyond the face's reach plus the slide (0.71 m at most here, tests/test_contact_scenes.py) and
    the flight of a block falling over a short wall is never touched: the runs equal those without
    a wall."""
    for a, f in PULSES:
        for sign in (1, -1):
            p = Pulse(a, f, sign=sign)
            for fr_ in (STICKY, Friction(0.35, 0.3)):
                w = simulate(BLOCK, p, wall=Wall(gap=2.0 * BLOCK.h + 1.0, height=0.5, side=side),
                             friction=fr_,
                             duration=8.0)
                n = simulate(BLOCK, p, friction=fr_, duration=8.0)
                key = (a, f, sign, fr_.mu_s)
                assert w.metrics["wall_impacts"] == 0, key
                assert w.status == n.status, key
                # the run without a wall is another kernel (rigid_friction for finite mu): to the
                # tolerance of tests/test_contact_scenes.py's out-of-reach check
                assert w.metrics["max_rotation"] == pytest.approx(n.metrics["max_rotation"],
                                                                  rel=1e-6), key
                assert w.metrics["max_slide"] == pytest.approx(n.metrics["max_slide"], abs=1e-6), key


# ------------------------------------------------------------------ independent geometry
def _edge(par, y):
    """(distance of E to the face line, outside > 0; E's depth inside the body, < 0 outside) for
    state rows y, from the body's outline alone."""
    y = np.atleast_2d(y)
    w = par[L.P_WALL_SIDE]
    b1, b2, h = par[L.C_B1], par[L.C_B2], par[L.C_H1]
    bw = b2 if w > 0 else b1
    ht = par[L.C_HT2] if w > 0 else par[L.C_HT1]
    th = y[:, 0]
    gx = y[:, 2] + h * np.sin(th)
    gy = y[:, 4] + h * np.cos(th)
    ex = w * (bw + par[L.C_GAP]) - gx
    ey = par[C.C_H_WALL] - gy
    a = ex * np.cos(th) - ey * np.sin(th)           # E in the body frame
    c = ex * np.sin(th) + ey * np.cos(th)
    depth = np.minimum.reduce([a + b1, b2 - a, c + h, ht - c])
    return w * a - bw, depth


def _edge_to_body(par, y):
    """E's distance to the body for state rows y (outside > 0, inside minus its depth), from the
    body's outline alone: E on the face's line past a corner is not on the body."""
    y = np.atleast_2d(y)
    w = par[L.P_WALL_SIDE]
    b1, b2, h = par[L.C_B1], par[L.C_B2], par[L.C_H1]
    ht = par[L.C_HT2] if w > 0 else par[L.C_HT1]
    th = y[:, 0]
    gx = y[:, 2] + h * np.sin(th)
    gy = y[:, 4] + h * np.cos(th)
    ex = w * ((b2 if w > 0 else b1) + par[L.C_GAP]) - gx
    ey = par[C.C_H_WALL] - gy
    a = ex * np.cos(th) - ey * np.sin(th)
    c = ex * np.sin(th) + ey * np.cos(th)
    out = np.hypot(np.maximum.reduce([a - b2, -b1 - a, 0 * a]), np.maximum.reduce([c - ht, -h - c, 0 * c]))
    depth = np.minimum.reduce([a + b1, b2 - a, c + h, ht - c])
    return np.where(out > 0.0, out, -depth)


def _near_gap(par, y):
    w = par[L.P_WALL_SIDE]
    bw = par[L.C_B2] if w > 0 else par[L.C_B1]
    h = par[L.C_H1]
    th = y[:, 0]
    x_near = y[:, 2] + h * np.sin(th) + w * bw * np.cos(th) - h * np.sin(th)
    return bw + par[L.C_GAP] - w * x_near


def test_closed_edge_keeps_its_gap_at_second_order():
    """The face slipping (and turning) on E with the base corner slipping on the ground and in
    flight: with the mode solve's accelerations the distance of E to the face, from ``_edge``,
    has second derivative 0 (without the term 2 w theta' v_t it would be that term)."""
    rng = np.random.default_rng(7)
    hdr, smp = to_header(BLOCK, Pulse(1.0, 2.0), None)
    checked = 0
    for side, mu_w in itertools.product((1, -1), (0.0, 0.3)):
        par = contact_par(BLOCK, Friction(0.3, lift_off="flight"),
                          Wall(side=side, friction=mu_w, **LOW))
        j = 1 if side > 0 else 0
        for _ in range(10):
            th = side * (math.atan(0.1) + rng.uniform(-0.05, 0.05))
            y = np.array([th, rng.uniform(-1, 1), 0.0, rng.uniform(-0.5, 0.5), 0.0, 0.0])
            C.project_single(j, y, par, False)
            g, _vn, _vt = C.point_kin(2, y, par)
            y[2] += side * g / math.cos(th)         # E on the face
            for flying in (False, True):
                yy = _closing_rates(y, par, j, flying)
                _g, vn2, vt2 = C.point_kin(2, yy, par)
                assert abs(vn2) < 1e-12
                if abs(vt2) < 1e-3:
                    continue
                sw = 2 if vt2 > 0 else -2
                st = C.wall_state(2, sw) if mu_w > 0 else C.CS_FREE
                _g, _vn, vtj = C.point_kin(j, yy, par)
                sj = C.CS_OPEN if flying else C.slip_state(1 if vtj > 0 else -1)
                acc = np.empty(3)
                ok, *_f = C.mode_solve(0.1, yy, par, sj if j == 0 else C.CS_OPEN,
                                       sj if j == 1 else C.CS_OPEN, st, hdr, smp, acc)
                assert ok
                out = np.empty(6)
                disc = np.zeros(L.N_DISC, np.int64)
                C.set_contacts(disc, sj if j == 0 else C.CS_OPEN, sj if j == 1 else C.CS_OPEN, st)
                C.rhs(0.1, yy, par, disc, hdr, smp, out)
                dt = 1e-4
                gs = [_edge(par, yy + k * dt * out + 0.5 * (k * dt) ** 2 * _second(out))[0][0]
                      for k in (-1, 0, 1)]
                g2 = (gs[0] - 2 * gs[1] + gs[2]) / dt ** 2
                coriolis = 2 * side * yy[1] * vt2
                assert abs(g2) < 1e-5 * (1 + abs(coriolis)), (g2, coriolis)
                checked += 1
    assert checked >= 20


def _closing_rates(y, par, j, flying):
    """y with (x', z') chosen so that E's normal velocity on the face (and, on the ground, pivot j's)
    is 0: both are affine in (x', z')."""
    def vn(vx, vz):
        yy = y.copy()
        yy[3], yy[5] = vx, vz
        return np.array([C.point_kin(2, yy, par)[1], C.point_kin(j, yy, par)[1]])
    v0 = vn(0.0, 0.0)
    A = np.column_stack([vn(1.0, 0.0) - v0, vn(0.0, 1.0) - v0])
    yy = y.copy()
    if flying:
        # the least (x', z') that closes the edge alone
        a = A[0]
        yy[3], yy[5] = -a * v0[0] / (a @ a)
    else:
        yy[3], yy[5] = np.linalg.solve(A, -v0)
    return yy


def _second(out):
    """(theta'', 0, x'', 0, z'', 0) from rhs output: the second-order part of the Taylor step."""
    return np.array([out[1], 0.0, out[3], 0.0, out[5], 0.0])


# ------------------------------------------------------------------ the wall contact's geometry
def _nearest_on_body(a, c, b_near, b_far, h, ht):
    """(distance, nearest point) of the body-frame point (a, c) (a toward the wall side) to the
    rectangle [-b_far, b_near] x [-h, ht]: outside, the Euclidean distance and the nearest point
    of the outline; inside, minus the depth below the nearest of the wall-side face, the top and
    the bottom (the far face is never the wall's)."""
    pa, pc = min(max(a, -b_far), b_near), min(max(c, -h), ht)
    d = math.hypot(a - pa, c - pc)
    if d > 0.0:
        return d, pa, pc
    depths = {(b_near, c): b_near - a, (a, -h): c + h, (a, ht): ht - c}
    (pa, pc), depth = min(depths.items(), key=lambda kv: kv[1])
    return -depth, pa, pc


@pytest.mark.parametrize("body", [BLOCK, ASYM], ids=["block", "asymmetric"])
@pytest.mark.parametrize("side", [1, -1])
def test_wall_geometry_is_the_distance_of_the_edge_to_the_body(body, side):
    """``wall_geom`` on random states against independent geometry: with the short wall's edge E
    anywhere on the wall-side half of the body's frame, the gap is E's distance to the body
    outside it (the wall-side face, the top, the bottom, either wall-side corner) and minus its
    depth inside; the contact point is the body's nearest point and the normal points from E to
    it.  Only with the top corner past the face and below E is the contact the corner against the
    wall's face (the horizontal clear distance).  Before, the face's line continued past the base
    corner, so E below the base read gap 0 from the face (contact:2027:251)."""
    wall = Wall(side=side, **LOW)
    par = contact_par(body, Friction(0.5, lift_off="flight"), wall)
    w = side
    b_near = par[L.C_B2] if w > 0 else par[L.C_B1]
    b_far = par[L.C_B1] if w > 0 else par[L.C_B2]
    h = par[L.C_H1]
    ht = par[L.C_HT2] if w > 0 else par[L.C_HT1]
    ex, ey = w * (b_near + par[L.C_GAP]), par[C.C_H_WALL]
    rng = np.random.default_rng(20261207)
    kinds = {}
    for _ in range(3000):
        th = rng.uniform(-1.6, 1.6)
        a = rng.uniform(0.0, b_near + 0.4)            # E's place, toward the wall side
        c = rng.uniform(-h - 0.4, ht + 0.4)
        cs, sn = math.cos(th), math.sin(th)
        # E = G + w a (cos, -sin) + c (sin, cos): the CM from E
        gx = ex - w * a * cs - c * sn
        gy = ey + w * a * sn - c * cs
        y = np.array([th, 0.0, gx - h * sn, 0.0, gy - h * cs, 0.0])
        gap, rx, ry, nx, ny, _tx, _ty, kind = C.wall_geom(y, par)
        kinds[kind] = kinds.get(kind, 0) + 1
        # the wall-side top corner in the world
        kx = gx + w * b_near * cs + ht * sn
        ky = gy - w * b_near * sn + ht * cs
        if a > b_near and c > ht and ky <= ey:
            assert kind == C.WG_CORNER, (th, a, c, kind)
            assert gap == pytest.approx(b_near + par[L.C_GAP] - w * kx, abs=1e-12)
            continue
        dist, pa, pc = _nearest_on_body(a, c, b_near, b_far, h, ht)
        assert gap == pytest.approx(dist, abs=1e-12), (th, a, c, kind)
        # the nearest point in the world, relative to the CM
        px, py = w * pa * cs + pc * sn, -w * pa * sn + pc * cs
        assert (rx, ry) == pytest.approx((px, py), abs=1e-12), (th, a, c, kind)
        if dist > 1e-6:
            # E's offset from the CM is (ex - gx, ey - gy); n from E toward the body
            assert (nx, ny) == pytest.approx(((px - (ex - gx)) / dist, (py - (ey - gy)) / dist),
                                             abs=1e-9), (th, a, c, kind)
    assert set(kinds) == {C.WG_CORNER, C.WG_EDGE, C.WG_VERTEX, C.WG_TOP, C.WG_BOTTOM, C.WG_BASE}, kinds
    assert min(kinds.values()) > 20, kinds


# ------------------------------------------------------------------ runs: contact and energy
FRICTIONS = (Friction(0.5, lift_off="flight"), Friction(0.15, lift_off="flight"), STICKY)
WALLS = (dict(LOW), dict(HIGH), dict(LOW, friction=0.3), dict(HIGH, friction=0.6, restitution=0.5))


def _mech(par, y, g):
    h, iG = par[L.C_H1], par[L.C_IG]
    th, om = y[:, 0], y[:, 1]
    vx = y[:, 3] + h * np.cos(th) * om
    vy = y[:, 5] - h * np.sin(th) * om
    return 0.5 * (vx * vx + vy * vy + iG * om * om) + g * (y[:, 4] + h * np.cos(th) - h)


def _runs(body):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for fr_, geo, side, (a, f), sign in itertools.product(
                FRICTIONS, WALLS, (1, -1), ((0.6, 1.5), (1.2, 3.0), (3.0, 6.0)), (1, -1)):
            wall = Wall(side=side, **geo)
            par = contact_par(body, fr_, wall)
            p = Pulse(a, f, sign=sign)
            yield (fr_.mu_s, tuple(geo.items()), side, a, f, sign), par, run(
                par, body=BLOCK if isinstance(body, RigidBody) else body, pulse=p, t_end=6.0)


@pytest.mark.parametrize("body", [BLOCK, ASYM], ids=["block", "asymmetric"])
def test_contact_condition_and_energy(body):
    n_edge = 0
    statuses = set()
    barrier = body.g * 0.1
    for key, par, r in _runs(body):
        statuses.add(r["status"])
        y, t = r["y"], r["t"]
        _line, depth = _edge(par, y)
        assert depth.max() <= TOL_GEOM, (key, depth.max())
        dist = _edge_to_body(par, y)
        near = _near_gap(par, y)
        wall_t = r["log"][r["log"][:, L.LOG_KIND] == L.EV_WALL_IMPACT, L.LOG_T]
        for ti in wall_t:
            rows = np.nonzero(t == ti)[0]
            if len(rows) == 0:
                continue
            i = rows[0]
            on_body = abs(dist[i]) <= TOL_GEOM
            assert on_body or abs(near[i]) <= TOL_GEOM, (key, ti, dist[i], near[i])
            n_edge += on_body and abs(near[i]) > TOL_GEOM
        E = _mech(par, y, body.g)
        same = np.nonzero(t[1:] == t[:-1])[0]
        if len(same):
            gain = float(np.max(E[same + 1] - E[same])) / barrier
            assert gain <= ENERGY_TOL, (key, gain)
    assert n_edge > 20, n_edge
    assert len(statuses) > 1, statuses


# ------------------------------------------------------------------ bodies
@pytest.mark.parametrize("side", [1, -1])
def test_symmetric_rigid_body_equals_its_block(side):
    """The symmetric RigidBody through the asymmetric body's parameters (``_contact_body_geometry``;
    ``simulate`` itself hands a symmetric body to the block's entry) equals the block."""
    body = RigidBody.from_block(BLOCK)
    n_wall = 0
    for geo, fr_ in ((LOW, Friction(0.5, lift_off="flight")), (HIGH, Friction(0.3)), (LOW, STICKY)):
        wall = Wall(side=side, **geo)
        for a, f, sign in ((0.6, 1.5, 1), (1.2, 3.0, -1), (3.0, 6.0, 1)):
            p = Pulse(a, f, sign=sign)
            ref = run(contact_par(BLOCK, fr_, wall), body=BLOCK, pulse=p, t_end=6.0)
            new = run(contact_par(body, fr_, wall), body=BLOCK, pulse=p, t_end=6.0)
            assert new["status"] == ref["status"], (geo, a, f, sign)
            for m in (L.M_MAX_ABS_THETA, L.M_MAX_SLIDE, L.M_RESIDUAL_SLIDE):
                assert new["met"][m] == pytest.approx(ref["met"][m], rel=1e-6, abs=1e-9), m
            assert new["met"][L.M_WALL_IMPACTS] == ref["met"][L.M_WALL_IMPACTS]
            n_wall += ref["met"][L.M_WALL_IMPACTS]
    assert n_wall > 0


def test_asymmetric_body_runs_with_a_short_wall_friction_and_flight():
    hit = 0
    for side in (1, -1):
        wall = Wall(gap=0.05, height=0.9, side=side, friction=0.2)
        assert wall.contact(ASYM) == "short"
        for a, f, sign in ((0.6, 1.5, 1), (1.2, 3.0, -1), (2.0, 2.0, 1), (2.0, 2.0, -1)):
            r = simulate(ASYM, Pulse(a, f, sign=sign), wall=wall,
                         friction=Friction(0.4, lift_off="flight"), duration=6.0)
            assert r.kernel == "contact_body" and not r.status.startswith("failed"), r.status
            hit += r.metrics["wall_impacts"]
    assert hit > 0
