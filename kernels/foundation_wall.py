"""Block on the two-spring foundation beside a rigid rear wall (docs: theory/foundation).

The two-spring model of :mod:`.foundation` (state ``y = (y_c, y_c', q, q')``,
base point below the centre of mass held horizontally, tensionless corner
spring-dashpots) with a frictionless rigid wall on side ``w =
par[P_WALL_SIDE]``.  Since the base point is held horizontally, the top
corner on the wall side (``(w a, H)`` in the body frame from that point; a
the base's half-width on that side, H the face height) has
``w x = a cos(wq) + H sin(wq)``, a function of q alone: it touches the wall at
``w q = theta_w = par[P_THETA_W]`` (the front end solves
``a cos theta_w + H sin theta_w = a + d``), whatever y_c and the corner
states.  The wall is a constraint on q only.

Wall impact (``w q = theta_w``, ``w q' > 0``): a horizontal impulse at the
corner, with the corner's normal velocity reversed and scaled by
``e_w = par[P_E_W]``.  With the mass matrix A(q) of the (y_c, q) system and
the constraint gradient (0, J_q), the impulse changes the velocities by
A^-1 (0, -P J_q): ``q'+ = -e_w q'-`` and ``y_c'+ = y_c'- + h sin q (q'+ -
q'-)``, i.e. the vertical velocity of the centre of mass, ``y_c' - h sin q
q'``, is kept (the wall and the holding force at the base point are both
horizontal).  The kinetic energy ``M v_G,y^2 / 2 + (I_G + M h^2 cos^2 q) q'^2
/ 2`` is scaled in its q' part by e_w^2: it never grows, and e_w = 1 keeps it.
The corner springs carry no impulse (soft contact).

Resting on the wall (mode MODE_WALL_REST): after a chatter (physics.md 7:
``|q'+| < eps_omega`` or two impacts within eps_t, or a bounce whose rebound
energy is below rtol M g h, at any e_w) q is held at ``w theta_w`` with
``q' = 0`` (a plastic wall impact of the last rebound: the CM's vertical
velocity is kept) while y_c moves on its springs (``M y_c'' = r_y``, :func:`.foundation.ts_accelerations`).
The wall force is ``lambda = det A (w q''_free) / (M |J_q|)`` with q''_free
the free rotation acceleration in the same state, so the block stays on the
wall while ``w q''_free >= 0`` and is released (``q' = 0``) when it becomes
negative beyond its rounding (event FW_WALL, located with its exact rate; in
free flight on the wall the margin is 0 up to rounding and both motions are
q'' = 0, :func:`fw_margin`).  The corner events run
as before, with the constrained accelerations.

Outcomes: as the two-spring model, plus LEANING: at rest on the wall at the
end of the run with theta_w above the wall side's alpha, or (level ground,
after the excitation, an exact sufficient test also used as an early
decision) past that alpha toward the wall with an energy that cannot bring it
back: ``E = T + M g y_G + k_v/2 sum max(delta_s, 0)^2`` never grows in free
motion (wall impacts and the wall rest only remove energy), and at
``w q = alpha_w`` the wall-side corner's spring alone gives
``E >= M g R_w - (M g)^2 / (2 k_v)`` (R_w the distance from that corner to
the centre of mass), so a block below that energy never comes back over
alpha_w.

Switching model beside the wall (``switching_wall``)
----------------------------------------------------
The switching SDOF of :mod:`.foundation` (state ``(theta, theta')``) rocks by
Housner's equation, so its wall is the rigid wall model's (:mod:`.wall`):
while rocking on the pivot near the wall (``s = w``) the block touches it at
``w theta = theta_w`` (the rigid model's angle, tall or short wall), the
impact keeps the pivot with ``theta'+ = -e_w theta'-``, a chatter ends at
rest on the wall (a static phase whose margin is Housner's ``w theta''`` on
the wall, :func:`.wall.wall_rest_margin`) and the release rocks on again.
The contact phase (rotation about the base centre, ``w theta <= theta_y``
while turning toward the wall) never reaches the wall: the front end requires
``theta_w > theta_y``.  LEANING: at rest on the wall at the end with theta_w >
alpha, or after the excitation rocking on the near pivot past alpha with
Housner's energy below the barrier (:func:`.wall.trapped_on_wall`; the
contact phase lies below theta_y < alpha, so such a block never returns).
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import excitation_end, ground_rates
from .foundation import (D_HOLD_LEFT, D_HOLD_RIGHT, D_LEFT, D_RIGHT,
                         TS_IQ, TS_N_EVENTS, TS_REST, corner_arm,
                         ts_corner_transition, corner_compression,
                         corner_force, side_alpha, spring_par, spring_tol,
                         ts_accelerations,
                         ts_after_step, ts_event, ts_force_rate,
                         ts_init_state, ts_kinetic, ts_loads, ts_set_mode,
                         ts_shared_event, ts_shared_transition, ts_transition,
                         never_static)
from .rodas import auto_dense, auto_step, work_rows
from .hybrid import (EPS, book_time, check_energy,
                     integrate_with, is_chatter, log_event, sweep_rows,
                     uniform_tol)
from .layout import (D_MODE, D_PIVOT, EV_WALL_IMPACT, EV_WALL_RELEASE, EV_WALL_REST,
                     LEANING, MODE_ROCK, MODE_WALL_REST, M_WALL_IMPACTS,
                     N_DISC, O_EARLY_EXIT, O_RTOL, O_T0, RUNNING, S_ON, SAFE_REST)
from .layout import (P_ALPHA, P_B, P_B_SKEW, P_CV, P_E_W, P_G, P_H, P_I_C, P_KV, P_MASS,
                     P_THETA_OVER, P_THETA_W, P_WALL_SIDE)
from .foundation import (SW_N_EVENTS, sw_after_step, sw_event,
                         sw_init_state, sw_rhs, sw_transition)
from .rigid import track_rotation
from .wall import (block_alpha_p, release_from_wall, trapped_on_wall,
                   wall_impact_of, wall_rest_margin)

FW_N_EVENTS = TS_N_EVENTS + 1
FW_WALL = TS_N_EVENTS   # free: wall contact; on the wall: release


@jit
def fw_accelerations(t, y, par, disc, hdr, smp):
    """(y_c'', q''): the two-spring model's, and resting on the wall (q
    held, q' = 0) the y-row alone: the wall force acts on q only."""
    if disc[D_MODE] == MODE_WALL_REST:
        ry, _rq, _mh = ts_loads(t, y, par, disc, hdr, smp)
        return ry / par[P_MASS], 0.0
    return ts_accelerations(t, y, par, disc, hdr, smp)


@jit
def fw_rhs(t, y, par, disc, hdr, smp, out):
    ydd, qdd = fw_accelerations(t, y, par, disc, hdr, smp)
    out[0] = y[1]
    out[1] = ydd
    out[2] = y[3]
    out[3] = qdd


@jit
def fw_margin(t, y, par, disc, hdr, smp):
    """(w q''_free + its rounding, the rate) [rad/s^2, rad/s^3] with q' = 0:
    the block is pressed on the wall while it is > 0 (the wall force has the
    sign of w q''_free).

    q''_free = (m r_y + M r_q) / det with m = M h sin q; q is held, so m and
    det are constant and only the loads move: r_y' = f_R' + f_L' - M a_v',
    r_q' = M h (a_v' sin q - a_g' cos q) - cos q (b (f_R' - f_L') + c (f_R'
    + f_L')), f' of a corner in contact by :func:`.foundation.ts_force_rate`
    (the constrained accelerations in MODE_WALL_REST)."""
    w = par[P_WALL_SIDE]
    M = par[P_MASS]
    h = par[P_H]
    ry, rq, mh = ts_loads(t, y, par, disc, hdr, smp)
    det = M * par[P_I_C] - mh * mh
    ag, dag, av, dav = ground_rates(t, hdr, smp)
    dR = 0.0
    dL = 0.0
    if disc[D_RIGHT] != 0:
        _f, dR = ts_force_rate(fw_accelerations, TS_IQ, 1.0, t, y, par, disc, hdr, smp)
    if disc[D_LEFT] != 0:
        _f, dL = ts_force_rate(fw_accelerations, TS_IQ, -1.0, t, y, par, disc, hdr, smp)
    sq = math.sin(y[2])
    cq = math.cos(y[2])
    dry = dR + dL - M * dav
    drq = (M * h * (dav * sq - dag * cq) - par[P_B] * cq * (dR - dL)
           - par[P_B_SKEW] * cq * (dR + dL))
    # what the margin is known to: the rounding of its terms.  In free flight
    # on the wall (no corner force) gravity turns nothing, the margin is 0 up
    # to that rounding, and the constrained and free motions agree (q'' = 0):
    # the margin counts as negative only beyond it, or a rounding-level sign
    # would release and re-catch the block at one instant, forever.
    fs = abs(corner_force(y, TS_IQ, 1.0, par, disc[D_RIGHT])) + \
        abs(corner_force(y, TS_IQ, -1.0, par, disc[D_LEFT]))
    MG = M * abs(par[P_G] + av)
    res = 8.0 * EPS * (abs(mh) * (fs + MG) + M * (
        M * h * (abs(par[P_G] + av) + abs(ag)) + (par[P_B] + abs(par[P_B_SKEW])) * fs)) / det
    return w * (mh * ry + M * rq) / det + res, w * (mh * dry + M * drq) / det


@jit
def fw_event(k, t, y, par, disc, hdr, smp):
    if k == FW_WALL:
        if disc[D_MODE] == MODE_WALL_REST:
            g, gd = fw_margin(t, y, par, disc, hdr, smp)
            return g, gd, True
        w = par[P_WALL_SIDE]
        g = par[P_THETA_W] - w * y[2]
        gd = -w * y[3]
        if abs(g) <= 1e-12 and gd >= 0.0:
            # at the wall, not approaching and not accelerating into it: no
            # root.  Released where the wall force only touched 0 (its
            # margin -3e-17 and rising), the block's q'' = 7.5e-16 away
            # drifted g to -1e-19 and zero-velocity wall impacts repeated at
            # the release instant (foundation_wall:2026:15)
            _ydd, qdd = fw_accelerations(t, y, par, disc, hdr, smp)
            if -w * qdd >= 0.0:
                return np.inf, 0.0, True
        return g, gd, True
    if k == TS_REST:
        return ts_event(k, t, y, par, disc, hdr, smp)
    return ts_shared_event(fw_accelerations, TS_IQ, k, t, y, par, disc, hdr, smp)


@jit
def fw_kick(y, par, dq):
    """Change q' by dq with the CM's vertical velocity y_c' - h sin q q' kept
    (what a horizontal impulse at the corner does)."""
    y[1] += par[P_H] * math.sin(y[2]) * dq
    y[3] += dq


@jit
def fw_resolve_corners(t, y, par, disc, hdr, smp, met, log, cnt):
    """After a velocity jump the dashpots' forces jump too: a corner in
    contact whose law now pulls lets go, a free one pressed (delta >= 0, law
    > 0) touches, each by :func:`.foundation.ts_corner_transition` (what the
    driver would do at the next phase start, but also when the law would
    come back within the first step)."""
    for i in range(2):
        side = 1.0 if i == 0 else -1.0
        slot = D_RIGHT if i == 0 else D_LEFT
        d, dd = corner_compression(y, TS_IQ, side, par)
        f = par[P_KV] * d + par[P_CV] * dd
        if (disc[slot] != 0 and f < 0.0) or (disc[slot] == 0 and d >= 0.0 and f > 0.0):
            ts_corner_transition(fw_accelerations, TS_IQ, side, slot, D_HOLD_RIGHT if i == 0 else D_HOLD_LEFT,
                                 t, y, par, disc, hdr, smp, met, log, cnt)


@jit
def fw_settle(t, y, par, disc, hdr, smp, met, log, cnt):
    """End of a chatter at the wall: q' -> 0 (plastic), rest on it if pressed."""
    fw_kick(y, par, -y[3])
    fw_resolve_corners(t, y, par, disc, hdr, smp, met, log, cnt)
    m, _md = fw_margin(t, y, par, disc, hdr, smp)
    if m > 0.0:
        disc[D_MODE] = MODE_WALL_REST
        log_event(log, cnt, t, EV_WALL_REST, 0.0, 0.0, y[2], disc[D_PIVOT])


@jit
def fw_wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """Frictionless wall impact at the top corner: q'+ = -e_w q'-, CM's
    vertical velocity kept (module docstring)."""
    w = par[P_WALL_SIDE]
    y[2] = w * par[P_THETA_W]
    pre = y[3]
    before = ts_kinetic(y, par)
    fw_kick(y, par, -(1.0 + par[P_E_W]) * pre)
    post = y[3]
    met[M_WALL_IMPACTS] += 1
    check_energy(before, ts_kinetic(y, par), met)
    track_rotation(y[2], met)
    log_event(log, cnt, t, EV_WALL_IMPACT, pre, post, y[2], disc[D_PIVOT])
    fw_resolve_corners(t, y, par, disc, hdr, smp, met, log, cnt)
    # a bounce below the resolution: its rebound energy (the q' part, I_G +
    # M h^2 cos^2 q) below rtol times the rocking barrier's scale M g h, at
    # any e_w.  On the springs the chatter rule alone need not end a
    # chatter: a block that creeps into the wall in full contact (its q'
    # set by the dashpots) is brought back to the wall at the same speed
    # after every impact, so the impacts neither slow down nor come closer
    # (foundation_wall:2027:222 and :336, 5e4 impacts 1e-6 s apart)
    rebound = 0.5 * (par[P_I_C] - par[P_MASS] * (par[P_H] * math.sin(y[2])) ** 2) * post * post
    scale = par[P_MASS] * par[P_G] * par[P_H]
    if is_chatter(t, post, opt, met) or rebound < opt[O_RTOL] * scale:
        fw_settle(t, y, par, disc, hdr, smp, met, log, cnt)
    return RUNNING


@jit
def fw_release(t, y, par, disc, log, cnt):
    disc[D_MODE] = MODE_ROCK        # any mode but MODE_WALL_REST: the corners decide
    ts_set_mode(disc)
    y[2] = par[P_WALL_SIDE] * par[P_THETA_W]
    y[3] = 0.0
    log_event(log, cnt, t, EV_WALL_RELEASE, 0.0, 0.0, y[2], disc[D_PIVOT])


@jit
def fw_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k == FW_WALL:
        if disc[D_MODE] == MODE_WALL_REST:
            fw_release(t, y, par, disc, log, cnt)
            return RUNNING
        return fw_wall_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)
    if k == TS_REST:
        return ts_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt)
    book_time(t, disc, met)
    return ts_shared_transition(fw_accelerations, TS_IQ, k, t, y, par, disc, hdr, smp, opt, met,
                                log, cnt)


@jit
def fw_trapped(t, y, par, disc, hdr):
    """Exact sufficient test (module docstring): level ground, after the
    excitation, past the wall side's alpha toward the wall (which stands
    before theta_over) with E below M g R_w - (M g)^2 / (2 k_v)."""
    if hdr[S_ON] != 0.0 or t < excitation_end(hdr):
        return False
    w = par[P_WALL_SIDE]
    if not par[P_THETA_W] < par[P_THETA_OVER]:
        return False
    a_w = side_alpha(w, par)
    if not w * y[2] > a_w:
        return False
    M = par[P_MASS]
    g = par[P_G]
    h = par[P_H]
    k = par[P_KV]
    dR, _ = corner_compression(y, TS_IQ, 1.0, par)
    dL, _ = corner_compression(y, TS_IQ, -1.0, par)
    spring = 0.5 * k * (max(dR, 0.0) ** 2 + max(dL, 0.0) ** 2)
    E = ts_kinetic(y, par) + M * g * (y[0] + h * math.cos(y[2])) + spring
    Mg = M * g
    barrier = Mg * math.hypot(corner_arm(w, par), h) - 0.5 * Mg * Mg / k
    # relative margin: E and the barrier are sums of terms of size M g R
    return E < barrier - 1e-12 * Mg * h


@jit
def fw_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    st = ts_after_step(t, y, par, disc, hdr, smp, opt, met, at_end)
    if not (at_end or (st == RUNNING and opt[O_EARLY_EXIT] != 0.0)):
        return st
    w = par[P_WALL_SIDE]
    if at_end and disc[D_MODE] == MODE_WALL_REST:
        if par[P_THETA_W] > side_alpha(w, par):
            return LEANING
        return SAFE_REST
    if fw_trapped(t, y, par, disc, hdr):
        track_rotation(w * par[P_THETA_W], met)
        return LEANING
    return st


@jit
def two_spring_wall_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                        hist_d, log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    par = spring_par(par, opt)
    ts_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, spring_tol,
                          fw_rhs, fw_event, fw_transition, never_static,
                          fw_after_step, FW_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


# ================================================ switching model and wall
SWW_N_EVENTS = SW_N_EVENTS + 1
SWW_WALL = SW_N_EVENTS


@jit
def sww_event(k, t, y, par, disc, hdr, smp):
    if k == SWW_WALL:
        w = par[P_WALL_SIDE]
        if disc[D_MODE] == MODE_ROCK and disc[D_PIVOT] == w:
            return par[P_THETA_W] - w * y[0], -w * y[1], True
        return np.inf, 0.0, True
    return sw_event(k, t, y, par, disc, hdr, smp)


@jit
def sww_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        # end of the rest on the wall: rock on from it
        release_from_wall(t, y, par, disc, log, cnt)
        return RUNNING
    if k == SWW_WALL:
        return wall_impact_of(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                              block_alpha_p)
    return sw_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt)


@jit
def sww_static_margin(t, y, par, disc, hdr, smp):
    if disc[D_MODE] == MODE_WALL_REST:
        return wall_rest_margin(t, par, hdr, smp, block_alpha_p)
    return np.inf


@jit
def sww_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    st = sw_after_step(t, y, par, disc, hdr, smp, opt, met, at_end)
    if not (at_end or (st == RUNNING and opt[O_EARLY_EXIT] != 0.0)):
        return st
    w = par[P_WALL_SIDE]
    if disc[D_MODE] == MODE_WALL_REST:
        if not at_end:
            return st
        if par[P_THETA_W] > par[P_ALPHA]:
            return LEANING
        return SAFE_REST
    if disc[D_MODE] == MODE_ROCK and t >= excitation_end(hdr) and \
            hdr[S_ON] == 0.0 and trapped_on_wall(y, par, disc, block_alpha_p):
        track_rotation(w * par[P_THETA_W], met)
        return LEANING
    return st


@jit
def switching_wall_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                       hist_d, log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    sw_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, uniform_tol,
                          sw_rhs, sww_event, sww_transition,
                          sww_static_margin, sww_after_step, SWW_N_EVENTS,
                          y, par, disc, hdr, smp, opt, t_eval, met, hist_t,
                          hist_y, hist_d, log, cnt)


# ---------------------------------------------------------------- entries
@jit
def two_spring_wall_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                             hist_y, hist_d, log, cnt):
    """One two-spring run beside a wall, y = (y_c, y_c', q, q')."""
    return two_spring_wall_run(y, par, hdr, smp, opt, t_eval, met, hist_t,
                               hist_y, hist_d, log, cnt)


@jit_parallel
def two_spring_wall_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many two-spring runs beside a wall in parallel (see rigid_sweep)."""
    sweep_rows(two_spring_wall_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)


@jit
def switching_wall_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                            hist_y, hist_d, log, cnt):
    """One switching-SDOF run beside a wall, y = (theta, theta')."""
    return switching_wall_run(y, par, hdr, smp, opt, t_eval, met, hist_t,
                              hist_y, hist_d, log, cnt)


@jit_parallel
def switching_wall_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many switching-SDOF runs beside a wall in parallel (see rigid_sweep)."""
    sweep_rows(switching_wall_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
