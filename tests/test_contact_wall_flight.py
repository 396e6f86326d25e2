"""Flight with the wall contact closed (issue #14 item 1, kernels/contact.py ``close_wall_in_flight``):
a Zeno sequence of wall impacts in flight ends with the wall contact closed by the rest rule of
physics.md 7 (impacts closer than eps_t, or a rebound slower than eps_omega times the size), and the
body flies on with that contact until the wall's force reaches 0.

Oracles:
- the motion with the top corner on a frictionless wall against an independent SciPy solve_ivp
  integration of the hand-derived two-degree-of-freedom equations (``contact_reference.flight_on_wall``);
- the fuzz reproductions (contact:2026:69, :61: wall impacts at one instant until the step budget)
  end with a definite status in few events, never inside the wall, and never gain energy at a
  transition or after the pulse.
"""
import math
import os
import sys
import warnings

import numpy as np
import pytest

from fastrock import Friction, Pulse, RigidBlock, Wall, simulate
from fastrock.kernels import contact as C
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS
from fastrock.model.excitation import to_header
from fastrock.running.models import contact_par
from fastrock.running.solver import Solver

sys.path.insert(0, os.path.dirname(__file__))
import contact_reference as REF  # noqa: E402
from test_contact_core import cpar, mechanical, start_in_flight  # noqa: E402

BODY = RigidBlock.rectangle(0.2, 1.0)


def run_eval(par, pulse, y0, t_eval, t_end, rtol=1e-11):
    hdr, smp = to_header(BODY, pulse, None)
    opt = Solver(rtol=rtol, max_steps=100_000).options(t_end, False)
    y = np.array(y0, float)
    met = np.zeros(L.N_MET)
    n = len(t_eval)
    ht, hy, hd = np.empty(n), np.empty((n, C.N_STATE)), np.empty((n, 3), np.int64)
    log = np.empty((2000, L.N_LOG))
    cnt = np.zeros(N_COUNTERS, np.int64)
    code = C.contact_simulate(y, par, hdr, smp, opt, np.asarray(t_eval, float), met, ht, hy, hd, log,
                              cnt)
    k = int(cnt[C_NHIST])
    return int(code), ht[:k], hy[:k], hd[:k], log[:int(cnt[C_NLOG])]


def _released_at_the_wall(e_w):
    """At rest in flight at theta0 = 0.1 (toward a frictionless wall on the right, e_w given) with
    the top corner touching it and the base 1 m above the ground; a rectangular pulse of 0.5 g for
    2 s pushes the block toward the wall."""
    b, h = BODY.b, BODY.h
    th0 = 0.1
    gap = b * math.cos(th0) + h * math.sin(th0) - b
    par = cpar(BODY, 0.5, gap=gap, side=1, e_w=e_w)
    yg0 = b * math.sin(th0) + h * math.cos(th0) + 1.0
    y0 = start_in_flight(par, th0, 0.0, 0.0, 0.0, yg0)
    return th0, gap, par, yg0, y0, Pulse(0.5, sign=-1, kind="rectangular", duration=2.0)


def test_flight_on_a_frictionless_wall_matches_solve_ivp():
    """Released in flight at rest with the top corner touching the wall, pushed toward it by a
    rectangular pulse (a_g = -0.5 g): the first wall impact is at zero speed, the rule closes the
    contact, and theta, theta', x_G, y_G follow the reference to 1e-7 until the face nears the wall."""
    b, h, g = BODY.b, BODY.h, BODY.g
    th0, gap, par, yg0, y0, pulse = _released_at_the_wall(0.5)
    t_out = [0.03, 0.06, 0.09, 0.12, 0.15]
    ref = REF.flight_on_wall(b, h, g, th0, yg0, -0.5 * g, t_out)
    assert ref["N_w"].min() > 0.0 and ref["theta"][-1] > 0.02
    _code, t, y, d, log = run_eval(par, pulse, y0, t_out, 0.16)
    assert np.allclose(t, t_out)
    hm = 0.5 * (par[C.C_H1] + par[C.C_H2])
    assert np.all(d[:, 0] == L.MODE_FLIGHT)
    assert np.allclose(y[:, 0], ref["theta"], rtol=1e-7, atol=1e-10)
    assert np.allclose(y[:, 1], ref["omega"], rtol=1e-7, atol=1e-10)
    assert np.allclose(y[:, 2] + hm * np.sin(y[:, 0]), ref["x_G"], rtol=1e-7, atol=1e-10)
    assert np.allclose(y[:, 4] + hm * np.cos(y[:, 0]), ref["y_G"], rtol=1e-7, atol=1e-10)
    kinds = log[:, L.LOG_KIND]
    # one closing, no chatter
    assert (kinds == L.EV_WALL_IMPACT).sum() <= 2 and (kinds == L.EV_WALL_REST).sum() == 1


def test_face_reaching_the_wall_in_flight_slides_down_it_and_lands_flat():
    """The same release at a plastic wall (e_w = 0), run on: the face reaches the wall in flight
    (theta = 0) with the base above the ground; it stops turning and, still pushed, slides down the frictionless wall (face
    flight: y_G'' = -g throughout, as in the free fall, since the wall's force is horizontal), lands
    flat at t = sqrt(2 (y_G0 - h) / g) and rests against the wall.  (Formerly the face impact put the
    block on the ground at once, whatever its height.)"""
    h, g = BODY.h, BODY.g
    _th0, gap, par, yg0, y0, pulse = _released_at_the_wall(0.0)
    t_land = math.sqrt(2 * (yg0 - h) / g)
    code, t, y, d, log = run_eval(par, pulse, y0, [0.9 * t_land, 3.0], 3.0)
    kinds = log[:, L.LOG_KIND]
    face = log[(kinds == L.EV_WALL_IMPACT) & (log[:, L.LOG_THETA] == 0.0)]
    assert len(face) == 1 and face[0, L.LOG_T] < 0.9 * t_land
    assert d[0, 0] == L.MODE_FLIGHT and y[0, 0] == 0.0 and y[0, 2] == gap
    assert y[0, 4] + h == pytest.approx(yg0 - 0.5 * g * (0.9 * t_land) ** 2, rel=1e-9)
    landing = log[kinds == L.EV_CONTACT]
    assert len(landing) == 1 and landing[0, L.LOG_T] == pytest.approx(t_land, rel=1e-9)
    assert code == L.SAFE_REST and np.all(y[1] == [0.0, 0.0, gap, 0.0, 0.0, 0.0])



def test_face_stopped_at_the_wall_in_flight_with_no_push_falls_and_lands_flat():
    """Released toward a plastic wall (e_w = 0) with no excitation: the top corner's impact throws
    the block into flight, whose base swings into the wall; the face impact stops it flat at the
    wall (theta = 0, v_x = 0), its base above the ground.  Nothing pushes it there, so it falls
    freely with the face touching the wall (gap 0, not approaching) and lands flat.  The wall-side
    base corner's event fired again at once at zero approach velocity: zero-velocity face impacts
    at one instant until failed:transition-loop (issue #14)."""
    body = RigidBlock.rectangle(0.3, 1.0)
    wall = Wall(0.02, side=1, restitution=0.0)
    run = simulate(body, None, wall=wall, friction=Friction(0.8, lift_off="flight"),
                   theta0=0.5 * wall.limit_angle(body), dtheta0=1.0, solver=Solver(rtol=1e-10), duration=4.0)
    assert run.status == "safe:rest", run.status
    ev = run.events.reset_index(drop=True)
    face = ev.index[(ev["event"] == "wall-impact") & (ev["theta"] == 0.0)]
    assert len(face) == 1 and ev.loc[face[0], "velocity_after"] == 0.0
    after = ev.loc[face[0] + 1:]
    assert list(after["event"]) == ["contact", "rest"]
    # the fall from the face impact to the flat landing is free: y_G'' = -g from its state there
    h = run.history
    fall = h[(h["t"] > ev.loc[face[0], "t"]) & (h["t"] < after["t"].iloc[0])]
    assert len(fall) > 0 and (fall["theta"] == 0.0).all() and (fall["d"] == wall.gap).all()
    assert run.metrics["residual_slide"] == wall.gap


def _fuzz_cell(b, h, pulse_kind, wall, friction, rtol, a, f, sign):
    body = RigidBlock.rectangle(b, h)
    p = Pulse(a, f, sign, pulse_kind, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = simulate(body, p, wall=wall, friction=friction, solver=Solver(rtol=rtol, max_steps=200_000))
    return body, p, r


# bench/README.md: contact:2026:69 (the hang: 12 of its 32 cells ended failed:step-budget, wall
# impacts at one instant in flight) and contact:2026:61 (failed:transition-loop 9: the wall-side
# base corner in flight)
CELLS = [
    ("69", (11.8927, 12.9918, "half-sine", (0.00131793, -1, 0.4972), (1.17859, 1.0543), 1.99e-7),
     [(2.3403779384631953, 3.0043473736666844, 1), (2.3403779384631953, 0.13346227562664106, 1),
      (38.698418205108815, 32.63722022075, 1), (7.0557292041525725, 0.166586266169997, 1)]),
    ("61", (2.67104, 5.78562, "one-cosine", (7.71003e-07, 1, 0.2755), (1.49692, 1.49692), 5.85e-9),
     [(9.117288184327137, 11.418747447358827, -1), (7.042183989835864, 11.418747447358827, -1),
      (9.117288184327137, 2.975166920292519, 1), (11.486439329053292, 6.130636030718851, 1)]),
]


@pytest.mark.parametrize("name,scene,cells", CELLS, ids=[c[0] for c in CELLS])
def test_fuzz_reproductions_end_definite_and_never_gain_energy(name, scene, cells):
    b, h, kind, (gap, side, e_w), (mu_s, mu_k), rtol = scene
    wall = Wall(gap=gap, side=side, restitution=e_w)
    fr = Friction(mu_s, mu_k, lift_off="stop")
    for a, f, sign in cells:
        body, p, r = _fuzz_cell(b, h, kind, wall, fr, rtol, a, f, sign)
        assert not r.status.startswith("failed"), (a, f, sign, r.status)
        assert r.metrics["wall_impacts"] < 200
        hist = r.history
        y = hist[["theta", "theta_dot", "d", "d_dot", "z", "z_dot"]].to_numpy()
        assert np.isfinite(y).all()
        par = contact_par(body, fr, wall)
        for k in (2, C.K_NEAR):
            gaps = np.array([C.point_kin(k, row, par)[0] for row in y])
            assert gaps.min() > -1e-6 * b, (a, f, sign, k, gaps.min())
        t = hist["t"].to_numpy()
        E = mechanical(y, par)
        scale = body.g * (math.hypot(b, h) - h)
        same = np.nonzero(t[1:] == t[:-1])[0]
        assert (E[same + 1] - E[same]).max(initial=0.0) <= 1e-6 * scale
        free = t >= p.end_time(body)
        assert np.diff(E[free]).max(initial=0.0) <= (1e-6 + 100 * rtol) * scale


def test_flat_landing_after_a_face_impact_in_flight_is_mirror_symmetric():
    """contact:2026:61 (9.117, 11.419): the face reaches the wall in flight moving away from it and
    the block lands flat while sliding.  Both base corners reach the ground together; the landing is
    the two-point impact whichever corner's event fired first, so (wall side s, sign +1) and (side -s,
    sign -1) are mirror images (formerly the left corner's single impact first: rocking on one side,
    flat on the other)."""
    b, h, kind, (gap, side, e_w), (mu_s, mu_k), rtol = CELLS[1][1]
    fr = Friction(mu_s, mu_k, lift_off="stop")
    a, f = 9.117288184327137, 11.418747447358827
    _body, _p, r1 = _fuzz_cell(b, h, kind, Wall(gap=gap, side=side, restitution=e_w), fr, rtol, a, f, 1)
    _body, _p, r2 = _fuzz_cell(b, h, kind, Wall(gap=gap, side=-side, restitution=e_w), fr, rtol, a, f, -1)
    assert r1.status == r2.status and not r1.status.startswith("failed")
    assert r1.metrics["max_rotation"] == pytest.approx(r2.metrics["max_rotation"], rel=1e-6)
