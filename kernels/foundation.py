"""Rigid block on a flexible foundation: rocking against vibration (physics.md 5).

Three models, each with entry kernels ``<name>_simulate`` (same signature as
``rigid_simulate``) and ``<name>_sweep`` (like ``rigid_sweep``):

``two_spring`` (physics.md 5.1, the reference)
    State ``y = (y_c, y_c', q, q')`` [m, m/s, rad, rad/s]: vertical
    displacement of the base point below the centre of mass (horizontally
    fixed; the base centre of a symmetric block) and rotation.
    Corner spring-dashpots ``k_v, c_v`` at ``x_s = s b + c`` from that point
    (``b`` the mean half-width, ``c = (b2 - b1)/2`` the base centre's offset:
    ``x = -b1`` and ``x = b2`` for an asymmetric body, ``+-b`` when c = 0);
    compression of corner ``s`` (+1 right, -1 left)
    ``delta_s = -(y_c - x_s sin q)``; force
    ``f_s = k_v delta_s + c_v delta_s'`` while the corner is in contact, 0
    while it is free.  A corner in contact becomes free when its force
    reaches 0 (lift-off, possibly with ``delta_s > 0``: the dashpot lets go
    first); a free corner re-contacts when ``delta_s >= 0`` and
    ``k_v delta_s + c_v delta_s' >= 0`` (soft contact, no impact map), to
    within the resolution of the corner forces: it re-contacts once that
    force law exceeds rtol M g (``spring_tol``, ``spring_par``).
    Modes: both corners (MODE_REST, "contact"), one corner (MODE_ROCK,
    D_PIVOT = that corner), none (MODE_FLIGHT; the base centre stays
    horizontally fixed, as in the model).  An "impact" is the re-contact of
    a corner that landed from above (``delta_s`` crossing 0 upward with
    ``delta_s' >= 0``); a released corner that presses again without having
    left the spring's surface is logged as "contact", not as an impact.
    A corner that switches twice between accepted steps at zero force is
    decided by the sign of f' (zero-force rule, ts_corner_transition).  In
    full contact after the excitation the rest rule (ts_at_rest) sets the
    static equilibrium once it bounds theta' by eps_omega for good.
    With ``E = T + M g y_G + sum_s k_v max(delta_s, 0)^2 / 2`` the free
    motion satisfies ``dE/dt = -sum c_v delta_s'^2 <= 0`` in contact and
    ``k_v delta_s delta_s' < 0`` for a released corner, so E never grows.

``switching`` (physics.md 5.2)
    State ``(theta, theta')``.  Contact phase (MODE_REST) about the base
    centre: ``I_C theta'' + c_t theta' + k_t theta - M G h sin theta =
    -M h a_g cos theta``.  Uplift when ``|k_t theta + c_t theta'| >= M G b``
    with pivot ``s = sgn(k_t theta + c_t theta')``; rocking (MODE_ROCK) is
    Housner's equation (``kernels.rigid.theta_ddot``) with the total
    rotation; back to contact when ``s theta <= theta_y`` while
    ``s theta' <= 0``, with ``theta'+ = e_f theta'-`` (an "impact").

``linear_sdof``
    State ``(theta, theta')``: ``I_C theta'' + c_t theta' + k_t theta =
    -M h a_g`` (reference vibration model; never lifts off).

Every model also has a terminal zero-crossing event of the rotation (its
transition snaps the rotation to exactly 0, so a stored history holds the
exact crossing times that half-cycle analysis needs), an overturning event
``|theta| >= theta_over`` (not for linear_sdof), and observers for peaks and
for the first passage of ``|theta| = alpha``.

Parameters ``par`` (indices P_*): the first entries are the rigid layout
(``alpha, p, e, g, theta_over``; ``p^2 = M g R / I_0``, so that
``rigid.theta_ddot`` serves the rocking phase), then the body and the
foundation in SI units (kg, m, N/m, N s/m, N m/rad, N m s/rad).  The front
end fills every entry, derived ones included (``I_C, I_0, theta_y``).  An
asymmetric body (two_spring only) puts its right side's alpha in P_ALPHA and
its left side's in P_ALPHA_LEFT (both alpha for a symmetric block).

Status at the end of a run: SAFE_NO_UPLIFT (never lifted off), SAFE_REST
(lifted off, ended in full contact -- vibrating on the foundation or at
rest), SAFE_MOVING (ended lifted off), OVERTURN_MODE1/2 (after / without a
re-contact impact), FLIGHT (switching model only: G <= 0 while rocking).
"""
import math

import numpy as np

from .config import jit, jit_generic, jit_parallel
from .excitation import ground, ground_rates
from .rodas import auto_dense, auto_step, work_rows
from .hybrid import (EPS, book_time, check_energy, final_status, init_metrics,
                     integrate_with, log_event, sweep_rows, uniform_tol)
from .layout import (D_MODE, D_PIVOT, D_STATIC, EV_CONTACT, EV_FLIGHT,
                     EV_IMPACT, EV_UPLIFT, FLIGHT, MODE_FLIGHT, MODE_REST,
                     MODE_ROCK, MODE_WALL_REST,
                     M_IMPACTS, M_MAX_THETA_NEG, M_MAX_THETA_POS,
                     M_T_EXC_END, M_T_LAST_IMPACT, M_T_PASS_ALPHA, M_T_UPLIFT,
                     N_DISC, O_ATOL, O_EARLY_EXIT, O_EPS_OMEGA, O_RTOL,
                     O_T0, RUNNING, SAFE_BOUNDED, S_ON)
from .rigid import (P_ALPHA, P_G, P_P, P_THETA_OVER,
                    overturned, passed_alpha, theta_ddot, track_rotation)

from .layout import (N_PAR_FOUNDATION as N_PAR, P_ALPHA_LEFT,  # noqa: E402,F401
                     P_B, P_B_SKEW, P_CT, P_CV, P_EF, P_H, P_I_0, P_I_C, P_I_G,
                     P_KT, P_KV, P_MASS, P_THETA_Y)

# ---- discrete state (model-specific use of the free slots) -----------------
D_SIDE = 5       # sign of the rotation for the zero-crossing event (0: none yet)
D_RIGHT = 6      # two_spring: 1 while the right corner is in contact
D_LEFT = 7       # two_spring: 1 while the left corner is in contact
# two_spring, per corner (slots of the wall and slip state, which it has not):
# SWITCHED once it switched since the last accepted step, HELD under the
# zero-force rule (ts_corner_transition)
D_HOLD_RIGHT = 3
D_HOLD_LEFT = 4
SWITCHED = 1
HELD = 2

# below this |theta| [rad] a run that starts exactly upright has no side yet
THETA_SIDE_EPS = 1e-12


# ============================================================== shared pieces
@jit
def cross_event(theta, dtheta, disc):
    """Zero crossing of the rotation: g = side * theta (terminal)."""
    sd = disc[D_SIDE]
    if sd == 0:
        a = abs(theta)
        return THETA_SIDE_EPS - a, -dtheta if theta > 0.0 else dtheta
    return sd * theta, sd * dtheta


@jit
def cross_transition(y, i_theta, disc, opt):
    """Flip the side; snap theta to exactly 0 (the root is within 4 ulp).

    A vibration decayed to rest at the crossing (theta exactly 0, slower
    than eps_omega, the rest rule's threshold of physics.md 7) has no side
    any more, as a run that starts upright at rest, until |theta| >
    THETA_SIDE_EPS: at theta = 0, theta' ~ 1e-320 (underflow) both sides'
    crossings would fire at once, forever (foundation:2027:37)."""
    if disc[D_SIDE] == 0:
        disc[D_SIDE] = 1 if y[i_theta] > 0.0 else -1
    elif y[i_theta] == 0.0 and abs(y[i_theta + 1]) < opt[O_EPS_OMEGA]:
        disc[D_SIDE] = 0
    else:
        disc[D_SIDE] = -disc[D_SIDE]
        y[i_theta] = 0.0


@jit
def init_side(theta, dtheta, disc):
    if theta != 0.0:
        disc[D_SIDE] = 1 if theta > 0.0 else -1
    elif dtheta != 0.0:
        disc[D_SIDE] = 1 if dtheta > 0.0 else -1
    else:
        disc[D_SIDE] = 0


@jit
def observe_rotation(obs, t, theta, dtheta, disc, par, met, log, cnt):
    """Observers: obs 0 = peak (exact maximum), 1 = first |theta| > alpha."""
    if obs == 0:
        track_rotation(theta, met)
    else:
        passed_alpha(t, theta, dtheta, disc[D_PIVOT], met, log, cnt)


@jit
def side_alpha(theta, par):
    """alpha of the side theta leans to (P_ALPHA right, P_ALPHA_LEFT left)."""
    return par[P_ALPHA] if theta >= 0.0 else par[P_ALPHA_LEFT]


@jit
def init_pass_alpha(t0, theta, par, met):
    """A release beyond alpha has passed the unstable equilibrium at t0."""
    if abs(theta) > side_alpha(theta, par):
        met[M_T_PASS_ALPHA] = t0


@jit
def mark_uplift(t, theta, dtheta, pivot, met, log, cnt):
    if np.isnan(met[M_T_UPLIFT]):
        met[M_T_UPLIFT] = t
    log_event(log, cnt, t, EV_UPLIFT, dtheta, dtheta, theta, pivot)


# ============================================================ (a) two springs
TS_N_EVENTS = 7
TS_RIGHT = 0        # corner switch, right
TS_LEFT = 1         # corner switch, left
TS_CROSS = 2        # q = 0
TS_OVERTURN = 3     # |q| = theta_over
TS_PEAK = 4         # observer: q' = 0 on the current side
TS_PASS_ALPHA = 5   # observer: |q| = alpha
TS_REST = 6         # the rest rule held after a step (ts_after_step)


@jit
def corner_arm(side, par):
    """x_s = s b + c: corner ``side`` from the point below the CM [m] (s b when c = 0)."""
    return side * par[P_B] + par[P_B_SKEW]


# The pieces below serve every body on the two springs: the state holds
# (y_c, y_c') first and the rotation (q, q') at index iq (TS_IQ = 2 here;
# kernels/foundation_flexible.py has the column in between), and the body's
# (y_c'', q'') come from an ``accel(t, y, par, disc, hdr, smp)`` argument
# (jit_generic: resolved statically in each model's entry kernel).
TS_IQ = 2


@jit
def corner_compression(y, iq, side, par):
    """(delta, delta') of corner ``side`` [m, m/s]."""
    x = corner_arm(side, par)
    sq = math.sin(y[iq])
    cq = math.cos(y[iq])
    return -(y[0] - x * sq), -(y[1] - x * cq * y[iq + 1])


@jit
def spring_tol(opt, par, n):
    """Tolerances of a state (y_c, y_c', ...) on the two springs: y_c and
    y_c' are held to absolute errors of at most rtol M g / k_v and
    rtol M g / max(c_v, sqrt(k_v M)), with no relative part, so that every
    corner force, k_v delta + c_v delta', is resolved to rtol M g; the
    others have O_ATOL and O_RTOL.  y_c carries the rocking's b sin q, so
    rtol |y_c| is no scale for a deflection either: a tolerance in m
    allowed errors worth 19 N (foundation:2027:109) and rtol |y_c| worth
    100 N (foundation_wall:2027:356) in a corner force near 0, and the
    corner of a grazing lift-off touched and left again at every step."""
    tol = uniform_tol(opt, par, n)
    res = opt[O_RTOL] * par[P_MASS] * par[P_G]
    tol[0, 0] = min(tol[0, 0], res / par[P_KV])
    tol[0, 1] = min(tol[0, 1], res / max(par[P_CV], math.sqrt(par[P_KV] * par[P_MASS])))
    tol[1, 0] = 0.0
    tol[1, 1] = 0.0
    return tol


@jit
def spring_par(par, opt):
    """A two-spring run's parameter vector: ``par`` with, appended, the
    force resolution rtol M g [N] that ``spring_tol`` holds the corner
    forces to (read by ts_corner_event)."""
    p = np.empty(par.shape[0] + 1)
    p[:-1] = par
    p[-1] = opt[O_RTOL] * par[P_MASS] * par[P_G]
    return p


@jit
def corner_force(y, iq, side, par, in_contact):
    if in_contact == 0:
        return 0.0
    d, dd = corner_compression(y, iq, side, par)
    return par[P_KV] * d + par[P_CV] * dd


@jit
def ts_loads(t, y, par, disc, hdr, smp):
    """(r_y, r_q, M h sin q): the right-hand sides of the 2x2 mass system
    [[M, -M h sin q], [-M h sin q, I_C]] (y_c'', q'') = (r_y, r_q) of
    physics.md 5.1, and its off-diagonal term."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    M = par[P_MASS]
    h = par[P_H]
    b = par[P_B]
    fR = corner_force(y, TS_IQ, 1.0, par, disc[D_RIGHT])
    fL = corner_force(y, TS_IQ, -1.0, par, disc[D_LEFT])
    sq = math.sin(y[2])
    cq = math.cos(y[2])
    ry = fR + fL - M * G + M * h * cq * y[3] * y[3]
    # moment cq (x_R f_R + x_L f_L) = cq (b (f_R - f_L) + c (f_R + f_L)): the
    # c term adds exactly 0 for a symmetric block
    rq = (M * G * h * sq - M * h * ag * cq - b * cq * (fR - fL)
          - par[P_B_SKEW] * cq * (fR + fL))
    return ry, rq, M * h * sq


@jit
def ts_accelerations(t, y, par, disc, hdr, smp):
    """(y_c'', q'') from the 2x2 mass system of physics.md 5.1."""
    ry, rq, mh = ts_loads(t, y, par, disc, hdr, smp)
    M = par[P_MASS]
    IC = par[P_I_C]
    det = M * IC - mh * mh
    return (IC * ry + mh * rq) / det, (mh * ry + M * rq) / det


@jit
def ts_rhs(t, y, par, disc, hdr, smp, out):
    ydd, qdd = ts_accelerations(t, y, par, disc, hdr, smp)
    out[0] = y[1]
    out[1] = ydd
    out[2] = y[3]
    out[3] = qdd


@jit_generic
def ts_force_rate(accel, iq, side, t, y, par, disc, hdr, smp):
    """(f, f') of corner ``side``'s force law f = k_v delta + c_v delta' [N,
    N/s], f' with the accelerations of the contact state in disc."""
    d, dd = corner_compression(y, iq, side, par)
    ydd, qdd = accel(t, y, par, disc, hdr, smp)
    x = corner_arm(side, par)
    q = y[iq]
    dq = y[iq + 1]
    ddd = -(ydd - x * (math.cos(q) * qdd - math.sin(q) * dq * dq))
    return par[P_KV] * d + par[P_CV] * dd, par[P_KV] * dd + par[P_CV] * ddd


@jit
def ts_force_resolution(t, y, iq, side, fdot, par):
    """eps_f [N]: what a corner's force law f is known to at a located
    switch, the rounding of its terms (and of the static load; P_MASS is
    the whole carried mass) plus what f moves in two brackets of the root
    finder (4 eps max(|t|, 1) each)."""
    d, dd = corner_compression(y, iq, side, par)
    return 4.0 * EPS * (par[P_MASS] * par[P_G] + abs(par[P_KV] * d)
                        + abs(par[P_CV] * dd)) \
        + 8.0 * EPS * max(abs(t), 1.0) * abs(fdot)


@jit_generic
def ts_corner_event(accel, iq, side, in_contact, held, t, y, par, disc, hdr,
                    smp):
    f, fdot = ts_force_rate(accel, iq, side, t, y, par, disc, hdr, smp)
    if in_contact != 0:
        # a held corner switches 2 eps_f past the surface (ts_corner_transition)
        if held == HELD:
            return f + 2.0 * ts_force_resolution(t, y, iq, side, fdot, par), fdot
        return f, fdot
    # free: stays free while delta < 0, or the spring-dashpot would pull, or
    # its force law is below the resolution of the corner forces, rtol M g
    # (spring_par; a grazing lift-off, foundation:2027:139, touched and left
    # again on forces of 1e-10 N at every step); a held corner twice that
    off = max(ts_force_resolution(t, y, iq, side, fdot, par),
              par[par.shape[0] - 1])
    if held == HELD:
        off = 2.0 * off
    d, dd = corner_compression(y, iq, side, par)
    if held == HELD and d > 0.0:
        # pressed: the force law itself (no force over 2 off is missed)
        return off - f, -fdot
    if par[P_CV] * dd >= 0.0:
        return off - par[P_KV] * d, -par[P_KV] * dd
    return off - f, -fdot


@jit_generic
def ts_shared_event(accel, iq, k, t, y, par, disc, hdr, smp):
    """Events TS_RIGHT ... TS_PASS_ALPHA of any body on the two springs."""
    q = y[iq]
    dq = y[iq + 1]
    if k == TS_RIGHT:
        g, gd = ts_corner_event(accel, iq, 1.0, disc[D_RIGHT],
                                disc[D_HOLD_RIGHT], t, y, par, disc, hdr, smp)
        return g, gd, True
    if k == TS_LEFT:
        g, gd = ts_corner_event(accel, iq, -1.0, disc[D_LEFT],
                                disc[D_HOLD_LEFT], t, y, par, disc, hdr, smp)
        return g, gd, True
    if k == TS_CROSS:
        g, gd = cross_event(q, dq, disc)
        return g, gd, True
    if k == TS_OVERTURN:
        sg = 1.0 if q >= 0.0 else -1.0
        return par[P_THETA_OVER] - sg * q, -sg * dq, True
    if k == TS_PEAK:
        sd = disc[D_SIDE]
        if sd == 0:
            return np.inf, 0.0, False
        _ydd, qdd = accel(t, y, par, disc, hdr, smp)
        return sd * dq, sd * qdd, False
    sg = 1.0 if q >= 0.0 else -1.0           # TS_PASS_ALPHA
    return side_alpha(q, par) - sg * q, -sg * dq, False


@jit
def ts_event(k, t, y, par, disc, hdr, smp):
    if k == TS_REST:
        # fires at once: the phase ends where the static phase begins
        return (-1.0 if disc[D_STATIC] == 1 else np.inf), 0.0, True
    return ts_shared_event(ts_accelerations, TS_IQ, k, t, y, par, disc, hdr,
                           smp)


@jit
def ts_set_mode(disc):
    """Mode and pivot from the corner states; a block resting on the wall
    (MODE_WALL_REST, two_spring_wall) keeps that mode, its pivot follows."""
    r = disc[D_RIGHT]
    lf = disc[D_LEFT]
    if r != 0 and lf != 0:
        mode = MODE_REST
        pivot = 0
    elif r != 0:
        mode = MODE_ROCK
        pivot = 1
    elif lf != 0:
        mode = MODE_ROCK
        pivot = -1
    else:
        mode = MODE_FLIGHT
        pivot = 0
    if disc[D_MODE] != MODE_WALL_REST:
        disc[D_MODE] = mode
    disc[D_PIVOT] = pivot


@jit_generic
def ts_corner_transition(accel, iq, side, slot, hold, t, y, par, disc, hdr,
                         smp, met, log, cnt):
    """Switch corner ``side``, or keep it under the zero-force rule.

    Zero-force rule: the corner switched already since the last accepted
    step (a chatter: foundation:2027:463 lifted and re-touched at one
    instant, forever), it is pressed (delta > 0, so no landing) and its
    force law is within eps_f of 0.  The force max(f, 0) is continuous
    there and both contact states share f' at f = 0 (the corner's force
    does not act at f = 0), so the motion leaves into contact if f' > 0
    and into the free state if f' < 0: the corner takes that state, f'
    computed with it free.  It is held so for the next step, its event 2
    eps_f past the surface: the driver cannot fire it at once again from
    the surface it leaves (a held free corner that is pressed watches f
    itself, not k_v delta).  While held, the force applied differs from
    the model's max(f, 0) by at most 2 eps_f, what the located switch
    cannot resolve anyway; a held corner that switches does so beyond
    eps_f, by the ordinary rule, and every hold ends with the next accepted
    step.  So the rule changes no motion beyond a force error of 2 eps_f."""
    d, dd = corner_compression(y, iq, side, par)
    f = par[P_KV] * d + par[P_CV] * dd
    if disc[hold] != 0 and d > 0.0:
        was = disc[slot]
        disc[slot] = 0
        _f, fdot = ts_force_rate(accel, iq, side, t, y, par, disc, hdr, smp)
        disc[slot] = was
        if abs(f) <= ts_force_resolution(t, y, iq, side, fdot, par):
            disc[hold] = HELD
            if (fdot > 0.0) == (was != 0):
                return RUNNING
        else:
            disc[hold] = SWITCHED
    else:
        disc[hold] = SWITCHED
    if disc[slot] != 0:
        disc[slot] = 0
        ts_set_mode(disc)
        if disc[D_MODE] == MODE_FLIGHT:
            log_event(log, cnt, t, EV_FLIGHT, y[iq + 1], y[iq + 1], y[iq],
                      side)
        else:
            mark_uplift(t, y[iq], y[iq + 1], disc[D_PIVOT], met, log, cnt)
        return RUNNING
    disc[slot] = 1
    ts_set_mode(disc)
    if par[P_CV] * dd >= 0.0:
        # landed from above: the analogue of a Housner impact
        met[M_IMPACTS] += 1
        met[M_T_LAST_IMPACT] = t
        log_event(log, cnt, t, EV_IMPACT, y[iq + 1], y[iq + 1], y[iq], side)
    else:
        log_event(log, cnt, t, EV_CONTACT, y[iq + 1], y[iq + 1], y[iq], side)
    return RUNNING


@jit_generic
def ts_shared_transition(accel, iq, k, t, y, par, disc, hdr, smp, opt, met,
                         log, cnt):
    """Transitions of the events of ts_shared_event (time booked already)."""
    if k == TS_RIGHT:
        return ts_corner_transition(accel, iq, 1.0, D_RIGHT, D_HOLD_RIGHT, t,
                                    y, par, disc, hdr, smp, met, log, cnt)
    if k == TS_LEFT:
        return ts_corner_transition(accel, iq, -1.0, D_LEFT, D_HOLD_LEFT, t,
                                    y, par, disc, hdr, smp, met, log, cnt)
    if k == TS_CROSS:
        cross_transition(y, iq, disc, opt)
        return RUNNING
    if k == TS_OVERTURN:
        return overturned(t, y[iq], y[iq + 1], disc[D_PIVOT], met, log, cnt)
    observe_rotation(k - TS_PEAK, t, y[iq], y[iq + 1], disc, par, met, log,
                     cnt)
    return RUNNING


@jit
def ts_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    book_time(t, disc, met)
    if k == TS_REST:
        ts_set_rest(y, par)
        return RUNNING
    return ts_shared_transition(ts_accelerations, TS_IQ, k, t, y, par, disc,
                                hdr, smp, opt, met, log, cnt)


@jit
def never_static(t, y, par, disc, hdr, smp):
    return np.inf


@jit
def ts_kinetic(y, par):
    """Kinetic energy of the block [J]: the centre of mass moves at
    (y' - h sin q q', h cos q q') over the point below it."""
    h = par[P_H]
    vx = y[1] - h * math.sin(y[2]) * y[3]
    vy = h * math.cos(y[2]) * y[3]
    return 0.5 * par[P_MASS] * (vx * vx + vy * vy) + 0.5 * par[P_I_G] * y[3] * y[3]


@jit
def ts_energy_above_rest(y, par):
    """(dE, kappa) of ts_stays_in_contact [J, N/m]: the energy above the
    static equilibrium in full contact, and k_v - M g h / b^2."""
    M = par[P_MASS]
    g = par[P_G]
    h = par[P_H]
    b = par[P_B]
    k = par[P_KV]
    half = math.sin(0.5 * y[2])
    du = -y[0] - 0.5 * M * g / k
    w = b * math.sin(y[2])
    dE = (ts_kinetic(y, par) + k * du * du + k * w * w
          - 2.0 * M * g * h * half * half)
    return dE, k - M * g * h / (b * b)


@jit
def ts_never_lifts(dE, kappa, par):
    """The Cauchy-Schwarz test of ts_stays_in_contact: no corner force can
    reach 0 again with the energy dE above the static equilibrium."""
    M = par[P_MASS]
    g = par[P_G]
    b = par[P_B]
    h = par[P_H]
    k = par[P_KV]
    c = par[P_CV]
    if not kappa > 0.0:
        return False
    m_inv = 1.0 / M + (b * b + h * h) / par[P_I_G]
    return dE * (k + k * k / kappa + 2.0 * c * c * m_inv) < 0.25 * (M * g) ** 2


@jit
def ts_at_rest(y, par, opt, met):
    """Rest rule in full contact (physics.md 7), symmetric block after the
    excitation, level ground: with dE <= I_G eps_omega^2 / 2 and no lift
    possible (ts_never_lifts), dE never grows (ts_stays_in_contact), so at
    every later time I_G q'^2 / 2 <= T <= dE: |q'| <= eps_omega, the rest
    rule's threshold, |sin q| <= sqrt(dE / kappa) / b and |y_c + delta_eq|
    <= sqrt(dE / k_v), for good.  The run is at rest, as a rigid block whose
    chatter the rule stops: the static equilibrium (ts_set_rest).  (A
    velocity threshold at rounding level would never hold: the explicit
    step, at its stability limit on the stiff corners, keeps y_c' jittering
    at about atol, foundation:2027:411.)  The rule also holds where the state
    is the equilibrium to within the solver's tolerance
    (within_tolerance), no lift is possible and the bound on |q| does not
    pass the rotation maxima so far: dE, which never grows, bounds the rest
    of the motion as above, no metric changes, and the integration resolves
    none of it (there its explicit step pumps more energy into the jitter
    than dE holds).  eps_omega = 0 turns the rule off."""
    eps_w = opt[O_EPS_OMEGA]
    if not eps_w > 0.0:
        return False
    dE, kappa = ts_energy_above_rest(y, par)
    if dE <= 0.5 * par[P_I_G] * eps_w * eps_w and \
            ts_never_lifts(dE, kappa, par):
        return True
    y_eq = -0.5 * par[P_MASS] * par[P_G] / par[P_KV]
    return within_tolerance(y, y_eq, opt) and \
        ts_stays_in_contact(y, par, met)


@jit
def within_tolerance(y, y_eq, opt):
    """The state is the static equilibrium (y_c = y_eq, every other
    component 0) to within the solver's tolerance: each component within
    atol + rtol |its equilibrium value|.  On
    stiff, damped springs the explicit step sits at its stability limit and
    keeps y_c' jittering at about atol for good, far above the energy that
    eps_omega asks for, so that rule alone never fires on a motion the
    integration no longer resolves (foundation_friction:14:15: 2e6 steps
    in 3.8 s with y_c' ~ 1e-7 m/s on a 1e-9 m static deflection)."""
    atol = opt[O_ATOL]
    if abs(y[0] - y_eq) > atol + opt[O_RTOL] * abs(y_eq):
        return False
    for i in range(1, y.shape[0]):
        if abs(y[i]) > atol:
            return False
    return True


@jit
def ts_set_rest(y, par):
    """The static equilibrium in full contact: y_c = -M g / (2 k_v), at rest."""
    y[0] = -0.5 * par[P_MASS] * par[P_G] / par[P_KV]
    y[1] = 0.0
    y[2] = 0.0
    y[3] = 0.0


@jit
def ts_stays_in_contact(y, par, met):
    """Exact sufficient test (early decision): a symmetric block in full
    contact after the excitation, on level ground, never lifts a corner again
    and never exceeds its rotation maxima so far.

    With u = -y_c, w = b sin q, delta_eq = M g / (2 k_v) and the energy above
    the static equilibrium dE = T + k (u - delta_eq)^2 + k w^2
    - M g h (1 - cos q), free motion in full contact has
    d(dE)/dt = -c_v (delta_R'^2 + delta_L'^2) <= 0.  As 1 - cos q <= sin^2 q,
    dE >= k (u - delta_eq)^2 + kappa w^2 + T with kappa = k - M g h / b^2 > 0,
    and a corner's vertical speed obeys delta'^2 <= 2 T (1/M + R^2/I_G).  A
    corner force k delta + c delta' = 0 means k (delta - delta_eq) + c delta'
    = -M g / 2, which by Cauchy-Schwarz needs
    dE (k + k^2/kappa + 2 c^2 (1/M + R^2/I_G)) >= (M g / 2)^2; and
    |sin q| <= sqrt(dE / kappa) / b bounds the rotation for good."""
    dE, kappa = ts_energy_above_rest(y, par)
    if not ts_never_lifts(dE, kappa, par):
        return False
    s_max = math.sqrt(max(dE, 0.0) / kappa) / par[P_B]
    return s_max < 1.0 and math.asin(s_max) <= min(met[M_MAX_THETA_POS],
                                                  met[M_MAX_THETA_NEG])


@jit
def ts_cannot_overturn(y, par, met):
    """Exact sufficient test (early decision, any contact mode, symmetric
    block after the excitation, level ground): the free motion never
    overturns and never exceeds its rotation maxima so far.

    E = T + M g y_G + k/2 sum max(delta_s, 0)^2 never grows in free motion
    (module docstring).  At rotation q (|q| <= alpha) the lower corner's
    spring alone gives E >= M g R cos(alpha - |q|) - (M g)^2 / (2 k), the
    minimum over y_c: so from |q| < alpha the rotation stays below q_b with
    cos(alpha - q_b) = (E + (M g)^2 / (2 k)) / (M g R) < 1."""
    M = par[P_MASS]
    g = par[P_G]
    h = par[P_H]
    b = par[P_B]
    k = par[P_KV]
    alpha = par[P_ALPHA]
    q = y[2]
    if not abs(q) < alpha:
        return False
    dR, _ = corner_compression(y, TS_IQ, 1, par)
    dL, _ = corner_compression(y, TS_IQ, -1, par)
    spring = 0.5 * k * (max(dR, 0.0) ** 2 + max(dL, 0.0) ** 2)
    E = ts_kinetic(y, par) + M * g * (y[0] + h * math.cos(q)) + spring
    Mg = M * g
    # relative margin: E and the barrier are sums of terms of size M g R
    c_b = (E + 0.5 * Mg * Mg / k) / (Mg * math.hypot(b, h)) + 1e-12
    if not c_b < 1.0:
        return False
    q_b = alpha - math.acos(c_b)
    return q_b <= min(met[M_MAX_THETA_POS], met[M_MAX_THETA_NEG])


@jit
def ts_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    disc[D_HOLD_RIGHT] = 0
    disc[D_HOLD_LEFT] = 0
    track_rotation(y[2], met)
    book_time(t, disc, met)
    if at_end:
        return final_status(disc, met)
    if t < met[M_T_EXC_END] or hdr[S_ON] != 0.0 or par[P_B_SKEW] != 0.0:
        return RUNNING
    early = opt[O_EARLY_EXIT] != 0.0
    if disc[D_MODE] == MODE_REST:
        if early and ts_stays_in_contact(y, par, met):
            return final_status(disc, met)
        if ts_at_rest(y, par, opt, met):
            if early:
                ts_set_rest(y, par)
                return final_status(disc, met)
            # TS_REST ends the phase and sets the rest state; the driver's
            # static phase then goes to t_end (no excitation is left)
            disc[D_STATIC] = 1
    elif early and ts_cannot_overturn(y, par, met):
        return SAFE_BOUNDED
    return RUNNING


@jit
def ts_initial_contact(y, iq, side, par):
    d, dd = corner_compression(y, iq, side, par)
    if d >= 0.0 and par[P_KV] * d + par[P_CV] * dd > 0.0:
        return 1
    return 0


@jit
def ts_init_corners(t0, y, iq, par, disc, met):
    """Corner states from the initial y: a corner is in contact iff
    delta >= 0 and k_v delta + c_v delta' > 0."""
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    disc[D_RIGHT] = ts_initial_contact(y, iq, 1.0, par)
    disc[D_LEFT] = ts_initial_contact(y, iq, -1.0, par)
    ts_set_mode(disc)
    init_side(y[iq], y[iq + 1], disc)
    if disc[D_MODE] != MODE_REST:
        met[M_T_UPLIFT] = t0
    init_pass_alpha(t0, y[iq], par, met)
    track_rotation(y[iq], met)


@jit
def ts_init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    ts_init_corners(t0, y, TS_IQ, par, disc, met)


@jit
def two_spring_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                   hist_d, log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    par = spring_par(par, opt)
    ts_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, spring_tol,
                          ts_rhs, ts_event, ts_transition, never_static,
                          ts_after_step, TS_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


# ========================================================== (b) switching
SW_N_EVENTS = 6
SW_SWITCH = 0       # contact: uplift; rock: return to contact
SW_CROSS = 1
SW_OVERTURN = 2
SW_FLIGHT = 3       # G <= 0 while rocking
SW_PEAK = 4
SW_PASS_ALPHA = 5


@jit
def sw_contact_ddot(t, theta, dtheta, par, hdr, smp):
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    M = par[P_MASS]
    h = par[P_H]
    return (-par[P_CT] * dtheta - par[P_KT] * theta
            + M * G * h * math.sin(theta)
            - M * h * ag * math.cos(theta)) / par[P_I_C]


@jit
def sw_ddot(t, y, par, disc, hdr, smp):
    if disc[D_MODE] == MODE_ROCK:
        return theta_ddot(t, y[0], disc[D_PIVOT], par, hdr, smp)
    return sw_contact_ddot(t, y[0], y[1], par, hdr, smp)


@jit
def sw_rhs(t, y, par, disc, hdr, smp, out):
    out[0] = y[1]
    out[1] = sw_ddot(t, y, par, disc, hdr, smp)


@jit
def sw_event(k, t, y, par, disc, hdr, smp):
    if k == SW_SWITCH:
        if disc[D_MODE] == MODE_ROCK:
            s = disc[D_PIVOT]
            # back to contact once s theta <= theta_y while s theta' <= 0
            g1 = s * y[0] - par[P_THETA_Y]
            g2 = s * y[1] / par[P_P]
            if g1 >= g2:
                return g1, s * y[1], True
            return g2, s * sw_ddot(t, y, par, disc, hdr, smp) / par[P_P], True
        ag, dag, av, dav = ground_rates(t, hdr, smp)
        m = par[P_KT] * y[0] + par[P_CT] * y[1]
        dm = par[P_KT] * y[1] + par[P_CT] * sw_ddot(t, y, par, disc, hdr, smp)
        sm = 1.0 if m >= 0.0 else -1.0
        Mb = par[P_MASS] * par[P_B]
        return Mb * (par[P_G] + av) - sm * m, Mb * dav - sm * dm, True
    if k == SW_CROSS:
        g, gd = cross_event(y[0], y[1], disc)
        return g, gd, True
    if k == SW_OVERTURN:
        sg = 1.0 if y[0] >= 0.0 else -1.0
        return par[P_THETA_OVER] - sg * y[0], -sg * y[1], True
    if k == SW_FLIGHT:
        if disc[D_MODE] != MODE_ROCK:
            return np.inf, 0.0, True
        _ag, _dag, av, dav = ground_rates(t, hdr, smp)
        return par[P_G] + av, dav, True
    if k == SW_PEAK:
        sd = disc[D_SIDE]
        if sd == 0:
            return np.inf, 0.0, False
        return sd * y[1], sd * sw_ddot(t, y, par, disc, hdr, smp), False
    sg = 1.0 if y[0] >= 0.0 else -1.0
    return par[P_ALPHA] - sg * y[0], -sg * y[1], False


@jit
def sw_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    book_time(t, disc, met)
    if k == SW_SWITCH:
        if disc[D_MODE] == MODE_ROCK:
            pre = y[1]
            y[1] = par[P_EF] * pre
            disc[D_MODE] = MODE_REST
            met[M_IMPACTS] += 1
            check_energy(pre * pre, y[1] * y[1], met)
            met[M_T_LAST_IMPACT] = t
            log_event(log, cnt, t, EV_IMPACT, pre, y[1], y[0], disc[D_PIVOT])
            disc[D_PIVOT] = 0
            return RUNNING
        m = par[P_KT] * y[0] + par[P_CT] * y[1]
        disc[D_MODE] = MODE_ROCK
        disc[D_PIVOT] = 1 if m >= 0.0 else -1
        mark_uplift(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)
        return RUNNING
    if k == SW_CROSS:
        cross_transition(y, 0, disc, opt)
        return RUNNING
    if k == SW_OVERTURN:
        return overturned(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)
    if k == SW_FLIGHT:
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], disc[D_PIVOT])
        return FLIGHT
    observe_rotation(k - SW_PEAK, t, y[0], y[1], disc, par, met, log, cnt)
    return RUNNING


@jit
def sdof_stays_in_contact(y, par, met, uplift):
    """Exact sufficient test (early decision) for the contact phase of the
    switching model (``uplift``) and for the linear model, after the
    excitation on level ground: no uplift ever again, and no rotation past
    the maxima so far.

    With E = I_C q'^2 / 2 + k_t q^2 / 2 - M g h (1 - cos q) the free contact
    motion has dE/dt = -c_t q'^2 <= 0, and 1 - cos q <= q^2 / 2 gives
    E >= I_C q'^2 / 2 + kappa q^2 / 2, kappa = k_t - M g h > 0: |q| <=
    sqrt(2 E / kappa) for good, and by Cauchy-Schwarz (k_t q + c_t q')^2
    <= 2 E (k_t^2 / kappa + c_t^2 / I_C), below the uplift moment's
    (M g b)^2.  (The linear model has no gravity term and no uplift.)"""
    I = par[P_I_C]
    k = par[P_KT]
    c = par[P_CT]
    Mgh = par[P_MASS] * par[P_G] * par[P_H] if uplift else 0.0
    kappa = k - Mgh
    if not kappa > 0.0:
        return False
    q = y[0]
    half = math.sin(0.5 * q)
    E = max(0.5 * I * y[1] * y[1] + 0.5 * k * q * q
            - 2.0 * Mgh * half * half, 0.0)
    if uplift:
        Mgb = par[P_MASS] * par[P_G] * par[P_B]
        if not 2.0 * E * (k * k / kappa + c * c / I) < Mgb * Mgb:
            return False
    return math.sqrt(2.0 * E / kappa) <= min(met[M_MAX_THETA_POS],
                                             met[M_MAX_THETA_NEG])


@jit
def sdof_decided(t, y, par, disc, hdr, opt, met, uplift):
    return (opt[O_EARLY_EXIT] != 0.0 and disc[D_MODE] == MODE_REST
            and t >= met[M_T_EXC_END] and hdr[S_ON] == 0.0
            and sdof_stays_in_contact(y, par, met, uplift))


@jit
def sw_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    track_rotation(y[0], met)
    book_time(t, disc, met)
    if at_end or sdof_decided(t, y, par, disc, hdr, opt, met, True):
        return final_status(disc, met)
    return RUNNING


@jit
def sw_init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    """Rocking from the start iff the uplift test holds at the initial state."""
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    _ag, av = ground(t0, hdr, smp)
    m = par[P_KT] * y[0] + par[P_CT] * y[1]
    if abs(m) >= par[P_MASS] * (par[P_G] + av) * par[P_B] and m != 0.0:
        disc[D_MODE] = MODE_ROCK
        disc[D_PIVOT] = 1 if m > 0.0 else -1
        met[M_T_UPLIFT] = t0
    else:
        disc[D_MODE] = MODE_REST
    init_side(y[0], y[1], disc)
    init_pass_alpha(t0, y[0], par, met)
    track_rotation(y[0], met)


@jit
def switching_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                  log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    sw_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, uniform_tol,
                          sw_rhs, sw_event, sw_transition, never_static,
                          sw_after_step, SW_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


# ====================================================== (c) linear vibration
LS_N_EVENTS = 2
LS_CROSS = 0
LS_PEAK = 1


@jit
def ls_ddot(t, theta, dtheta, par, hdr, smp):
    ag, _av = ground(t, hdr, smp)
    return (-par[P_CT] * dtheta - par[P_KT] * theta
            - par[P_MASS] * par[P_H] * ag) / par[P_I_C]


@jit
def ls_rhs(t, y, par, disc, hdr, smp, out):
    out[0] = y[1]
    out[1] = ls_ddot(t, y[0], y[1], par, hdr, smp)


@jit
def ls_event(k, t, y, par, disc, hdr, smp):
    if k == LS_CROSS:
        g, gd = cross_event(y[0], y[1], disc)
        return g, gd, True
    sd = disc[D_SIDE]
    if sd == 0:
        return np.inf, 0.0, False
    return sd * y[1], sd * ls_ddot(t, y[0], y[1], par, hdr, smp), False


@jit
def ls_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    book_time(t, disc, met)
    if k == LS_CROSS:
        cross_transition(y, 0, disc, opt)
    else:
        track_rotation(y[0], met)
    return RUNNING


@jit
def ls_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    track_rotation(y[0], met)
    book_time(t, disc, met)
    if at_end or sdof_decided(t, y, par, disc, hdr, opt, met, False):
        return final_status(disc, met)
    return RUNNING


@jit
def ls_init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    init_metrics(t0, met)
    disc[D_MODE] = MODE_REST
    init_side(y[0], y[1], disc)
    track_rotation(y[0], met)


@jit
def linear_sdof_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                    hist_d, log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    ls_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, uniform_tol,
                          ls_rhs, ls_event, ls_transition, never_static,
                          ls_after_step, LS_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


# ---------------------------------------------------------------- entries
@jit
def two_spring_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                        hist_d, log, cnt):
    """One two-spring run, y = (y_c, y_c', q, q'), with history and log."""
    return two_spring_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                          hist_d, log, cnt)


@jit
def switching_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                       hist_d, log, cnt):
    """One switching-SDOF run, y = (theta, theta'), with history and log."""
    return switching_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                         hist_d, log, cnt)


@jit
def linear_sdof_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                         hist_d, log, cnt):
    """One linear-SDOF run, y = (theta, theta'), with history and log."""
    return linear_sdof_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                           hist_d, log, cnt)


@jit_parallel
def two_spring_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent two-spring runs in parallel (see rigid_sweep)."""
    sweep_rows(two_spring_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)


@jit_parallel
def switching_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent switching-SDOF runs in parallel (see rigid_sweep)."""
    sweep_rows(switching_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)


@jit_parallel
def linear_sdof_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent linear-SDOF runs in parallel (see rigid_sweep)."""
    sweep_rows(linear_sdof_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
