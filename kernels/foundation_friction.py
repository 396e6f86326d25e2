"""Rigid block sliding on the two-spring foundation: Coulomb friction at the
base (physics.md 5.1 with the stick/slip rules of section 4).

State ``y = (y_c, y_c', q, q', d, d')`` [m, m/s, rad, rad/s, m, m/s]: the
two-spring state of ``kernels/foundation.py`` (its pieces are reused with
this model's accelerations: corner forces, corner switching with the
zero-force rule, the rotation events, the rest rule) plus the horizontal
displacement d of the base point below the centre of mass relative to the
ground.  The corner spring-dashpots are vertical and move with the base;
the horizontal reaction H acts at the base point (where the two-spring
model's holding reaction acts) and is bounded by the normal force
``N = f_R + f_L >= 0``.  In the ground's frame (a_g: its horizontal
acceleration, G = g + a_v; sympy check in tests/test_foundation_friction.py):

    M (d'' + h cos q q'' - h sin q q'^2) = H - M a_g
    M (y_c'' - h sin q q'' - h cos q q'^2) = N - M G
    I_G q'' = h sin q N - h cos q H - cos q (x_R f_R + x_L f_L)

(the last row: the moment about the centre of mass; ``x_s = s b + c`` as in
kernels/foundation.py).  Friction states (slot D_FRIC past the shared disc
slots):

``STICK`` (d' = 0)
    d'' = 0: the (y_c, q) motion is the two-spring model's
    (``ts_accelerations``) and H = H_s = M a_g + M h (cos q q'' - sin q q'^2)
    is what holds the base.  It holds while |H_s| <= mu_s N (event
    ``FF_SLIP``: mu_s N - |H_s| reaches 0).
``SLIP`` sigma = +-1
    H = -sigma mu_k N: the three rows above are explicit (no solve).  d''
    is affine in H with slope w = 1/M + h^2 cos^2 q / I_G > 0, and d'' = 0
    at H = H_s, so a slip from rest toward sigma1 = -sgn(H_s) has
    sigma1 d'' = w (|H_s| - mu_k N) > 0 whenever stick fails (|H_s| >
    mu_s N >= mu_k N): the slip direction at zero slip speed is always
    consistent (the normal force is compliant, so no Painleve case).  A
    slip whose speed reaches 0 (event ``FF_SLIP``: sigma d' reaches 0)
    sticks if |H_s| <= mu_s N, else slips toward -sgn(H_s).
``FREE``
    no corner in contact (N = 0): H = 0, the block flies horizontally too
    (the two-spring model holds it).  Stick needs N > 0, so a lift-off of
    the last corner frees d; a corner that lands starts a slip toward
    sgn(d'), or, at d' = 0, sticks or slips by the rule above.

Contact modes: MODE_REST / MODE_ROCK (stick on both / one corner),
MODE_SLIDE / MODE_SLIDE_ROCK (slip), MODE_FLIGHT.  With
``E = T + M g y_G + k_v/2 sum max(delta_s, 0)^2`` (T with d') the free
motion loses energy to the dashpots and to friction (H d' <= 0 in slip, 0
in stick and flight), so E never grows.  The two-spring model's early
decisions (no further lift-off, no overturning) say nothing about a later
slip, so they decide a run here only in stick on both corners after the
excitation where the stick also holds for good (``ff_sticks_for_good``, an
energy bound on |H_s| / N): no further lift-off (``ts_stays_in_contact``,
with ``early_exit``) and the rest rule (``ts_at_rest``).  Then d and the
slip metrics are final.  A run that rocks, slides or flies is integrated.

Parameters: the two-spring vector (``kernels/layout.py``, N_PAR_FOUNDATION
entries) followed by P_MU_S, P_MU_K.  Status codes as the two-spring model.
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground
from .foundation import (D_HOLD_LEFT, D_HOLD_RIGHT, D_LEFT, D_RIGHT, TS_IQ,
                         TS_LEFT, TS_N_EVENTS, TS_REST, TS_RIGHT,
                         corner_force, never_static, spring_par, spring_tol, ts_accelerations,
                         ts_at_rest, ts_energy_above_rest, ts_event,
                         ts_init_corners, ts_never_lifts, ts_set_mode,
                         ts_set_rest, ts_shared_event, ts_shared_transition,
                         ts_stays_in_contact)
from .friction import track_slide
from .rodas import auto_dense, auto_step, work_rows
from .hybrid import (book_time, final_status, integrate_with, log_event,
                     sweep_rows)
from .layout import (D_MODE, D_STATIC, EV_SLIP, EV_STICK, MODE_FLIGHT,
                     MODE_REST, MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK,
                     M_N_STICK_SLIP, M_T_EXC_END, N_DISC, N_PAR_FOUNDATION,
                     O_EARLY_EXIT, O_T0, RUNNING, S_ON)
from .rigid import P_G, track_rotation

from .layout import P_B, P_B_SKEW, P_CV, P_H, P_I_G, P_KV, P_MASS  # noqa: E402

P_MU_S = N_PAR_FOUNDATION
P_MU_K = N_PAR_FOUNDATION + 1
N_PAR = N_PAR_FOUNDATION + 2

# friction state, in a slot past the shared ones (the run's disc is longer)
D_FRIC = N_DISC
N_DISC_FF = N_DISC + 1
STICK = 0               # slip: the direction sigma = +-1
FREE = 2

I_D = 4                 # d, d' in the state vector
FF_SLIP = TS_N_EVENTS   # stick: mu_s N - |H_s|; slip: sigma d'
FF_N_EVENTS = TS_N_EVENTS + 1
# the stop event's value at the start of a slip [m/s]: positive, below any
# speed the integration resolves
SLIP_START = 1e-300
# time step of the central difference that gives the stick margin's rate
# (used only to spot a margin's interior minimum inside a step)
FD_REL = 1e-7


@jit
def normal_forces(y, par, disc):
    return (corner_force(y, TS_IQ, 1.0, par, disc[D_RIGHT]),
            corner_force(y, TS_IQ, -1.0, par, disc[D_LEFT]))


@jit
def stick_force(t, y, par, disc, hdr, smp):
    """(H_s, N) [N]: the horizontal reaction that holds d'' = 0, and N."""
    ag, _av = ground(t, hdr, smp)
    _ydd, qdd = ts_accelerations(t, y, par, disc, hdr, smp)
    fR, fL = normal_forces(y, par, disc)
    q = y[2]
    h = par[P_H]
    H = par[P_MASS] * (ag + h * (math.cos(q) * qdd
                                 - math.sin(q) * y[3] * y[3]))
    return H, fR + fL


@jit
def sliding_accelerations(t, y, par, disc, H, hdr, smp):
    """(y_c'', q'', d'') [m/s^2, rad/s^2, m/s^2] under a given horizontal
    reaction H [N] at the base point (module docstring's rows)."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    M = par[P_MASS]
    h = par[P_H]
    fR, fL = normal_forces(y, par, disc)
    N = fR + fL
    sq = math.sin(y[2])
    cq = math.cos(y[2])
    w2 = y[3] * y[3]
    moment = par[P_B] * (fR - fL) + par[P_B_SKEW] * N
    qdd = (h * sq * N - h * cq * H - cq * moment) / par[P_I_G]
    ydd = (N - M * G) / M + h * (sq * qdd + cq * w2)
    ddd = (H - M * ag) / M - h * (cq * qdd - sq * w2)
    return ydd, qdd, ddd


@jit
def ff_all(t, y, par, disc, hdr, smp):
    """(y_c'', q'', d'') of the friction state in disc."""
    fs = disc[D_FRIC]
    if fs == STICK and (disc[D_RIGHT] != 0 or disc[D_LEFT] != 0):
        ydd, qdd = ts_accelerations(t, y, par, disc, hdr, smp)
        return ydd, qdd, 0.0
    # no stick without a corner in contact (the zero-force rule asks with a
    # corner switched off): free, as with N = 0 in a slip
    H = 0.0
    if fs != FREE and fs != STICK:
        fR, fL = normal_forces(y, par, disc)
        H = -fs * par[P_MU_K] * (fR + fL)
    return sliding_accelerations(t, y, par, disc, H, hdr, smp)


@jit
def ff_accel(t, y, par, disc, hdr, smp):
    """The body's (y_c'', q''), the ``accel`` of the shared two-spring pieces."""
    ydd, qdd, _ddd = ff_all(t, y, par, disc, hdr, smp)
    return ydd, qdd


@jit
def ff_rhs(t, y, par, disc, hdr, smp, out):
    ydd, qdd, ddd = ff_all(t, y, par, disc, hdr, smp)
    out[0] = y[1]
    out[1] = ydd
    out[2] = y[3]
    out[3] = qdd
    out[4] = y[5]
    out[5] = ddd


@jit
def stick_margin(t, y, par, disc, hdr, smp):
    H, N = stick_force(t, y, par, disc, hdr, smp)
    return par[P_MU_S] * N - abs(H)


@jit
def ff_slip_event(t, y, par, disc, hdr, smp):
    fs = disc[D_FRIC]
    if fs == FREE:
        return np.inf, 0.0
    if fs != STICK:
        _ydd, _qdd, ddd = ff_all(t, y, par, disc, hdr, smp)
        v = fs * y[I_D + 1]
        if v == 0.0:
            # a slip that starts (d' = 0) leaves toward sigma (sigma d'' > 0,
            # module docstring): it starts on the admissible side, not on
            # the surface, which a step's end past another event (a corner
            # about to lift, foundation_friction:fuzz:31) would misjudge
            v = SLIP_START
        return v, fs * ddd
    g = stick_margin(t, y, par, disc, hdr, smp)
    # its rate by a central difference along the flow: an exact one needs
    # q''' of the corner system, and the rate only flags an interior minimum
    dt = FD_REL * max(abs(t), 1.0)
    f = np.empty(y.shape[0])
    z = np.empty(y.shape[0])
    ff_rhs(t, y, par, disc, hdr, smp, f)
    for i in range(y.shape[0]):
        z[i] = y[i] + dt * f[i]
    gp = stick_margin(t + dt, z, par, disc, hdr, smp)
    for i in range(y.shape[0]):
        z[i] = y[i] - dt * f[i]
    gm = stick_margin(t - dt, z, par, disc, hdr, smp)
    return g, (gp - gm) / (2.0 * dt)


@jit
def ff_event(k, t, y, par, disc, hdr, smp):
    if k == FF_SLIP:
        g, gd = ff_slip_event(t, y, par, disc, hdr, smp)
        return g, gd, True
    if k == TS_REST:
        return ts_event(k, t, y, par, disc, hdr, smp)
    return ts_shared_event(ff_accel, TS_IQ, k, t, y, par, disc, hdr, smp)


@jit
def ff_set_mode(disc):
    """Contact mode from the corners (ts_set_mode) and the friction state."""
    ts_set_mode(disc)
    fs = disc[D_FRIC]
    if fs == STICK or fs == FREE:
        return
    if disc[D_MODE] == MODE_REST:
        disc[D_MODE] = MODE_SLIDE
    elif disc[D_MODE] == MODE_ROCK:
        disc[D_MODE] = MODE_SLIDE_ROCK


@jit
def pick_at_zero_speed(t, y, par, disc, hdr, smp):
    """STICK, or the slip direction -sgn(H_s), for d' = 0 (module docstring)."""
    H, N = stick_force(t, y, par, disc, hdr, smp)
    if abs(H) <= par[P_MU_S] * N:
        return STICK
    return -1 if H > 0.0 else 1


@jit
def set_friction(fs, t, y, disc, met, log, cnt):
    """Enter friction state fs (log and count stick <-> slip switches)."""
    was = disc[D_FRIC]
    disc[D_FRIC] = fs
    if fs == STICK:
        y[I_D + 1] = 0.0
    if fs == was or fs == FREE or was == FREE:
        return
    if was == STICK or fs == STICK:
        met[M_N_STICK_SLIP] += 1
    log_event(log, cnt, t, EV_STICK if fs == STICK else EV_SLIP,
              y[I_D + 1], y[I_D + 1], y[2], fs)


@jit
def friction_after_corner(t, y, par, disc, hdr, smp, met, log, cnt):
    """A corner switched: free the base at the last lift-off, or engage
    friction when a corner lands from flight."""
    ts_set_mode(disc)
    if disc[D_MODE] == MODE_FLIGHT:
        disc[D_FRIC] = FREE
    elif disc[D_FRIC] == FREE:
        v = y[I_D + 1]
        if v != 0.0:
            disc[D_FRIC] = 1 if v > 0.0 else -1
        else:
            disc[D_FRIC] = pick_at_zero_speed(t, y, par, disc, hdr, smp)


@jit
def ff_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    book_time(t, disc, met)
    status = RUNNING
    if k == FF_SLIP:
        if disc[D_FRIC] == STICK:
            H, _N = stick_force(t, y, par, disc, hdr, smp)
            set_friction(-1 if H > 0.0 else 1, t, y, disc, met, log, cnt)
        else:
            y[I_D + 1] = 0.0
            set_friction(pick_at_zero_speed(t, y, par, disc, hdr, smp), t, y,
                         disc, met, log, cnt)
    elif k == TS_REST:
        ts_set_rest(y, par)
    else:
        status = ts_shared_transition(ff_accel, TS_IQ, k, t, y, par, disc,
                                      hdr, smp, opt, met, log, cnt)
        if k == TS_RIGHT or k == TS_LEFT:
            friction_after_corner(t, y, par, disc, hdr, smp, met, log, cnt)
    ff_set_mode(disc)
    track_slide(y[I_D], met)
    return status


@jit
def ff_sticks_for_good(y, par):
    """Stick on both corners after the excitation (a_g = a_v = 0, symmetric
    block, level ground) holds for good: |H_s| < mu_s N at every state the
    energy dE above the static equilibrium still reaches (ts_never_lifts
    holds, so both corners stay in contact and the motion is the two-spring
    model's).  ts_never_lifts' Cauchy-Schwarz bound gives each corner force
    within F = sqrt(dE (k + k^2/kappa + 2 c^2 (1/M + R^2/I_G))) of M g / 2,
    so N >= M g - 2 F, N <= M g + 2 F and |f_R - f_L| <= 2 F; with
    S = sqrt(dE / kappa) / b >= |sin q| and W = 2 dE / I_G >= q'^2, the
    moment row with H = H_s, (I_G + M h^2 cos^2 q) q'' = h sin q N
    + M h^2 sin q cos q q'^2 - b cos q (f_R - f_L), bounds |q''| by
    Q = (h S N_max + M h^2 S W + 2 b F) / I_G, and |H_s| = M h |cos q q''
    - sin q q'^2| <= M h (Q + S W)."""
    dE, kappa = ts_energy_above_rest(y, par)
    if not ts_never_lifts(dE, kappa, par):
        return False
    M = par[P_MASS]
    g = par[P_G]
    h = par[P_H]
    b = par[P_B]
    k = par[P_KV]
    c = par[P_CV]
    iG = par[P_I_G]
    dE = max(dE, 0.0)
    m_inv = 1.0 / M + (b * b + h * h) / iG
    F = math.sqrt(dE * (k + k * k / kappa + 2.0 * c * c * m_inv))
    S = math.sqrt(dE / kappa) / b
    W = 2.0 * dE / iG
    Q = (h * S * (M * g + 2.0 * F) + M * h * h * S * W + 2.0 * b * F) / iG
    return par[P_MU_S] * (M * g - 2.0 * F) > M * h * (Q + S * W)


@jit
def ff_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    """ts_after_step's decisions in full contact, where the stick also
    holds for good (ff_sticks_for_good): then the rest of the motion is the
    two-spring model's, and d and the slip metrics are final.  In the
    other modes no decision: a later slip is not bounded (module
    docstring)."""
    disc[D_HOLD_RIGHT] = 0
    disc[D_HOLD_LEFT] = 0
    track_rotation(y[2], met)
    track_slide(y[I_D], met)
    book_time(t, disc, met)
    if at_end:
        return final_status(disc, met)
    if t < met[M_T_EXC_END] or hdr[S_ON] != 0.0 or par[P_B_SKEW] != 0.0:
        return RUNNING
    if disc[D_MODE] != MODE_REST or not ff_sticks_for_good(y, par):
        return RUNNING
    early = opt[O_EARLY_EXIT] != 0.0
    if early and ts_stays_in_contact(y, par, met):
        return final_status(disc, met)
    if ts_at_rest(y, par, opt, met):
        if early:
            ts_set_rest(y, par)
            return final_status(disc, met)
        disc[D_STATIC] = 1
    return RUNNING


@jit
def ff_init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    ts_init_corners(t0, y, TS_IQ, par, disc, met)
    disc[D_FRIC] = FREE
    friction_after_corner(t0, y, par, disc, hdr, smp, met, log, cnt)
    ff_set_mode(disc)
    track_slide(y[I_D], met)


@jit
def two_spring_friction_run(y, par, hdr, smp, opt, t_eval, met, hist_t,
                            hist_y, hist_d, log, cnt):
    disc = np.zeros(N_DISC_FF, dtype=np.int64)
    par = spring_par(par, opt)
    ff_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, spring_tol,
                          ff_rhs, ff_event, ff_transition, never_static,
                          ff_after_step, FF_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


@jit
def two_spring_friction_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                                 hist_y, hist_d, log, cnt):
    """One run, y = (y_c, y_c', q, q', d, d'), with history and log."""
    return two_spring_friction_run(y, par, hdr, smp, opt, t_eval, met, hist_t,
                                   hist_y, hist_d, log, cnt)


@jit_parallel
def two_spring_friction_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent runs in parallel (see rigid_sweep)."""
    sweep_rows(two_spring_friction_run, Y0, PAR, HDR, smp, OPT, status, MET,
               YF)
