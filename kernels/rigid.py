"""Rigid block, two-sided Housner rocking (physics.md section 1).

State ``y = (theta, theta')`` [rad, rad/s]; discrete state: REST (static)
or ROCK about pivot s.  Parameters ``par`` (indices P_*): alpha [rad],
p [rad/s], e [-], g [m/s^2], theta_over [rad].  Events while rocking:

0 impact        g = s*theta                 terminal
1 overturn      g = theta_over - s*theta    terminal
2 peak          g = s*theta'                observer (max rotation)
3 pass alpha    g = alpha - s*theta         observer (first time)
4 flight        g = G = g + a_v             terminal (inf, inactive,
                                            without a vertical channel)
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground, ground_rates
from .hybrid import integrate_hybrid, log_event, sweep_rows
from .layout import (D_MODE, D_PIVOT, D_STATIC, EV_FLIGHT, EV_IMPACT,
                     EV_OVERTURN, EV_PASS_ALPHA, EV_REST, EV_UPLIFT, EXC_NONE,
                     FLIGHT, M_IMPACTS, M_MAX_ABS_THETA, M_MAX_THETA_NEG,
                     M_MAX_THETA_POS, M_T_EXC_END, M_T_LAST_IMPACT, M_T_OVER,
                     M_T_PASS_ALPHA, M_T_UPLIFT, MODE_REST, MODE_ROCK, N_DISC,
                     N_HDR, N_MET, O_EARLY_EXIT, O_EPS_OMEGA, O_EPS_T, O_T0,
                     OVERTURN_MODE1, OVERTURN_MODE2, RUNNING, SAFE_BOUNDED,
                     SAFE_MOVING, SAFE_NO_UPLIFT, SAFE_REST, X_KIND)

P_ALPHA = 0
P_P = 1
P_E = 2
P_G = 3
P_THETA_OVER = 4
# one-sided rocking (wall), used by kernels.wall
P_WALL_SIDE = 5     # w = +1 / -1
P_THETA_W = 6       # rad, limit angle
P_E_W = 7           # wall restitution
P_HOGAN = 8         # 1: gap d = 0, Hogan's one-sided map
N_PAR = 10

# An exceedance of the uplift threshold G tan(alpha) smaller than this
# (relative) counts as touching it: a record whose peak sits one ulp above
# the threshold would otherwise "uplift" for no time at all.
UPLIFT_RTOL = 1e-14

N_EVENTS = 5
K_IMPACT = 0
K_OVERTURN = 1
K_PEAK = 2
K_PASS_ALPHA = 3
K_FLIGHT = 4


# Hot paths (rhs, event, static_margin, after_step) read the array entries
# they need before calling anything.  Numba increfs every array argument on
# entry and decrefs it after its last use; LLVM's reference-count pruning
# removes such a pair only when no call sits between the two (a call may
# fail and leave through its error path).  An array still alive across a
# call therefore costs two atomic operations on every evaluation.  Reading
# first leaves only the arrays the call itself needs (hdr, smp), and out.


@jit
def housner(theta, s, alpha, p, g, ag, av):
    """Housner's exact EOM about pivot s (physics.md 1), on scalars: a_g
    and a_v are the ground accelerations, G = g + a_v."""
    phi = s * alpha - theta
    return -p * p * ((g + av) * math.sin(phi) + ag * math.cos(phi)) / g


@jit
def theta_ddot(t, theta, s, par, hdr, smp):
    """Housner's exact EOM about pivot s (physics.md 1) at time t."""
    alpha = par[P_ALPHA]
    p = par[P_P]
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    return housner(theta, s, alpha, p, g, ag, av)


@jit
def rhs(t, y, par, disc, hdr, smp, out):
    theta = y[0]
    w = y[1]
    s = disc[D_PIVOT]
    alpha = par[P_ALPHA]
    p = par[P_P]
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    out[0] = w
    out[1] = housner(theta, s, alpha, p, g, ag, av)


@jit
def event(k, t, y, par, disc, hdr, smp):
    s = disc[D_PIVOT]
    theta = y[0]
    w = y[1]
    if k == K_IMPACT:
        return s * theta, s * w, True
    if k == K_OVERTURN:
        return par[P_THETA_OVER] - s * theta, -s * w, True
    if k == K_PASS_ALPHA:
        return par[P_ALPHA] - s * theta, -s * w, False
    if k == K_PEAK:
        alpha = par[P_ALPHA]
        p = par[P_P]
        g = par[P_G]
        ag, av = ground(t, hdr, smp)
        return s * w, s * housner(theta, s, alpha, p, g, ag, av), False
    g = par[P_G]
    if int(hdr[N_HDR + X_KIND]) == EXC_NONE:
        return np.inf, 0.0, True        # G = g > 0 throughout
    _ag, _dag, av, dav = ground_rates(t, hdr, smp)
    return g + av, dav, True


@jit
def static_margin(t, y, par, disc, hdr, smp):
    """Full contact holds while |a_g| <= G tan(alpha) (physics.md 1); the
    static phase ends when this margin becomes negative."""
    alpha = par[P_ALPHA]
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    return (g + av) * math.tan(alpha) * (1.0 + UPLIFT_RTOL) - abs(ag)


@jit
def track_rotation(theta, met):
    a = abs(theta)
    if a > met[M_MAX_ABS_THETA]:
        met[M_MAX_ABS_THETA] = a
    if theta > met[M_MAX_THETA_POS]:
        met[M_MAX_THETA_POS] = theta
    if -theta > met[M_MAX_THETA_NEG]:
        met[M_MAX_THETA_NEG] = -theta


@jit
def start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt):
    """From theta = theta' = 0: uplift test of physics.md 1, else REST."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    if G <= 0.0:
        log_event(log, cnt, t, EV_FLIGHT, 0.0, 0.0, y[0], disc[D_PIVOT])
        return FLIGHT
    if abs(ag) > G * math.tan(par[P_ALPHA]) * (1.0 + UPLIFT_RTOL):
        disc[D_MODE] = MODE_ROCK
        disc[D_STATIC] = 0
        disc[D_PIVOT] = -1 if ag > 0.0 else 1
        if np.isnan(met[M_T_UPLIFT]):
            met[M_T_UPLIFT] = t
        log_event(log, cnt, t, EV_UPLIFT, 0.0, 0.0, y[0], disc[D_PIVOT])
    else:
        disc[D_MODE] = MODE_REST
        disc[D_STATIC] = 1
    return RUNNING


@jit
def ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt, e):
    """Housner impact at theta = 0: pivot switch, theta'+ = e theta'-,
    then the chatter-to-rest rule of physics.md 7."""
    s = disc[D_PIVOT]
    pre = y[1]
    post = e * pre
    y[0] = 0.0
    y[1] = post
    disc[D_PIVOT] = -s
    met[M_IMPACTS] += 1
    log_event(log, cnt, t, EV_IMPACT, pre, post, 0.0, -s)
    chatter = abs(post) < opt[O_EPS_OMEGA] or \
        t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    if chatter:
        y[1] = 0.0
        st = start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, post, 0.0, 0.0, disc[D_PIVOT])
        return st
    return RUNNING


@jit
def overturned(t, y, disc, met, log, cnt):
    met[M_T_OVER] = t
    track_rotation(y[0], met)
    log_event(log, cnt, t, EV_OVERTURN, y[1], y[1], y[0], disc[D_PIVOT])
    if met[M_IMPACTS] > 0:
        return OVERTURN_MODE1
    return OVERTURN_MODE2


@jit
def observe(k, t, y, disc, met, log, cnt):
    """Observer events shared by the rigid models (peak, pass alpha)."""
    if k == K_PEAK:
        track_rotation(y[0], met)
    elif k == K_PASS_ALPHA:
        if np.isnan(met[M_T_PASS_ALPHA]):
            met[M_T_PASS_ALPHA] = t
            log_event(log, cnt, t, EV_PASS_ALPHA, y[1], y[1], y[0],
                      disc[D_PIVOT])


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        return start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == K_IMPACT:
        return ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                             par[P_E])
    if k == K_OVERTURN:
        return overturned(t, y, disc, met, log, cnt)
    if k == K_FLIGHT:
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], disc[D_PIVOT])
        return FLIGHT
    observe(k, t, y, disc, met, log, cnt)
    return RUNNING


@jit
def peak_from_energy(alpha, energy):
    """Rotation at which free rocking with energy E (in units of MgR, zero
    at rest) stops: cos(alpha - theta) = cos(alpha) + E."""
    c = math.cos(alpha) + energy
    if c >= 1.0:
        return alpha
    return alpha - math.acos(c)


@jit
def free_energy(y, s, par):
    """Free-rocking energy / (M g R), zero at rest (physics.md 6.6)."""
    p = par[P_P]
    a = par[P_ALPHA]
    return 0.5 * y[1] * y[1] / (p * p) + math.cos(a - s * y[0]) - math.cos(a)


@jit
def bounded_after_excitation(theta, w, s, alpha, p, e):
    """Early decision once the excitation is over (exact, not a heuristic):
    free rocking conserves energy between impacts and impacts multiply it
    by e^2 <= 1, so a block inside the well (|theta| < alpha) with energy
    below the barrier 1 - cos(alpha) can never pass |theta| = alpha.  The
    next two peaks follow in closed form; later peaks are lower.  State
    (theta, theta' = w) about pivot s, on scalars; returns (safe, peak 1,
    peak 2), the peaks as signed rotations."""
    if not s * theta < alpha:
        return False, 0.0, 0.0   # past the unstable equilibrium
    # free_energy, on scalars
    E = 0.5 * w * w / (p * p) + math.cos(alpha - s * theta) - math.cos(alpha)
    if not E < 1.0 - math.cos(alpha):
        return False, 0.0, 0.0
    e2 = e * e
    if s * w > 0.0:
        side1 = s
        e1 = E
    else:
        side1 = -s
        e1 = e2 * E
    return (True, side1 * peak_from_energy(alpha, e1),
            -side1 * peak_from_energy(alpha, e2 * e1))


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    # Every array entry is read here, before any branch: the arrays other
    # than met then die in the entry block, where their incref/decref pairs
    # are pruned (see "Hot paths" above).
    theta = y[0]
    w = y[1]
    s = disc[D_PIVOT]
    mode = disc[D_MODE]
    alpha = par[P_ALPHA]
    p = par[P_P]
    e = par[P_E]
    early = opt[O_EARLY_EXIT] != 0.0
    track_rotation(theta, met)
    if at_end:
        if mode == MODE_REST:
            if np.isnan(met[M_T_UPLIFT]):
                return SAFE_NO_UPLIFT
            return SAFE_REST
        return SAFE_MOVING
    if not early or mode != MODE_ROCK or t < met[M_T_EXC_END]:
        return RUNNING
    # free rocking from now on: the exact early decision
    safe, pk1, pk2 = bounded_after_excitation(theta, w, s, alpha, p, e)
    if safe:
        track_rotation(pk1, met)
        track_rotation(pk2, met)
        return SAFE_BOUNDED
    return RUNNING


@jit
def init_state(t0, y, par, disc, hdr, smp, met):
    """Initial discrete state from (theta0, theta'0)."""
    for i in range(N_MET):
        met[i] = 0.0
    met[M_T_UPLIFT] = np.nan
    met[M_T_OVER] = np.nan
    met[M_T_PASS_ALPHA] = np.nan
    met[M_T_LAST_IMPACT] = -np.inf
    for i in range(N_DISC):
        disc[i] = 0
    if y[0] != 0.0 or y[1] != 0.0:
        disc[D_MODE] = MODE_ROCK
        disc[D_STATIC] = 0
        if y[0] != 0.0:
            disc[D_PIVOT] = 1 if y[0] > 0.0 else -1
        else:
            disc[D_PIVOT] = 1 if y[1] > 0.0 else -1
        met[M_T_UPLIFT] = t0
        track_rotation(y[0], met)
    else:
        disc[D_MODE] = MODE_REST
        disc[D_STATIC] = 1
        disc[D_PIVOT] = 1


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met)
    return integrate_hybrid(rhs, event, transition, static_margin,
                            after_step, N_EVENTS, y, par, disc, hdr, smp,
                            opt, t_eval, met, hist_t, hist_y, hist_d, log,
                            cnt)


# ---------------------------------------------------------------- entries
@jit
def rigid_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                   hist_d, log, cnt):
    """One rigid-block run with time history and event log (see run)."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def rigid_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent runs in parallel: row i of Y0/PAR/HDR/OPT -> row i
    of status/MET/YF.  No time history, no event log."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
