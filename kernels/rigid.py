"""Rigid block, two-sided Housner rocking (physics.md section 1).

State ``y = (theta, theta')`` [rad, rad/s]; discrete state: REST (static)
or ROCK about pivot s.  Parameters ``par`` (indices P_*): alpha [rad],
p [rad/s], e [-], g [m/s^2], theta_over [rad].

Two sets of entries: ``rigid_simulate``/``rigid_sweep``, the symmetric
block, and ``rigid_body_simulate``/``rigid_body_sweep``, a body whose two
base corners have their own alpha_k, p_k (p_k^2 = M g R_k / I_O,k) and each
impact its own restitution (layout P_ALPHA_NEG ..., N_PAR_RIGID_BODY; see
"Asymmetric body" below).  With equal sides the two give bit-identical runs.
Events while rocking (both):

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
from .hybrid import (check_energy, final_status, init_metrics,
                     integrate_hybrid, log_event, sweep_rows)
from .layout import (D_MODE, D_PIVOT, D_STATIC, EV_FLIGHT, EV_IMPACT,
                     EV_OVERTURN, EV_PASS_ALPHA, EV_REST, EV_UPLIFT, EXC_NONE,
                     FLIGHT, MODE_REST, MODE_ROCK, M_IMPACTS, M_MAX_ABS_THETA,
                     M_MAX_THETA_NEG, M_MAX_THETA_POS, M_T_EXC_END, M_T_FINAL,
                     M_T_LAST_IMPACT, M_T_OVER, M_T_PASS_ALPHA, M_T_UPLIFT,
                     N_DISC, N_HDR, OVERTURN_MODE1, OVERTURN_MODE2,
                     O_EARLY_EXIT, O_EPS_OMEGA, O_EPS_T, O_T0, O_T_END,
                     RUNNING, SAFE_BOUNDED, X_KIND)

from .layout import (N_PAR_RIGID as N_PAR, P_ALPHA, P_E, P_E_W, P_G,  # noqa: E402,F401
                     P_HOGAN, P_P, P_THETA_OVER, P_THETA_W, P_WALL_SIDE)
from .layout import (N_PAR_RIGID_BODY, P_ALPHA_NEG, P_E_NEG,  # noqa: E402,F401
                     P_IO_RATIO, P_P_NEG)

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
    check_energy(pre * pre, post * post, met)   # same inertia about both
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
def overturned(t, theta, dtheta, s, met, log, cnt):
    """|theta| reached theta_over on pivot s: mode 1 after an impact, else
    mode 2 (every rocking model)."""
    met[M_T_OVER] = t
    track_rotation(theta, met)
    log_event(log, cnt, t, EV_OVERTURN, dtheta, dtheta, theta, s)
    if met[M_IMPACTS] > 0:
        return OVERTURN_MODE1
    return OVERTURN_MODE2


@jit
def passed_alpha(t, theta, dtheta, s, met, log, cnt):
    """Observer: the first time |theta| passes alpha (every rocking model)."""
    if np.isnan(met[M_T_PASS_ALPHA]):
        met[M_T_PASS_ALPHA] = t
        log_event(log, cnt, t, EV_PASS_ALPHA, dtheta, dtheta, theta, s)


@jit
def initial_pivot(theta, dtheta):
    """Pivot of a run released at (theta, theta') != 0."""
    if theta != 0.0:
        return 1 if theta > 0.0 else -1
    return 1 if dtheta > 0.0 else -1


@jit
def observe(k, t, y, disc, met, log, cnt):
    """Observer events shared by the rigid models (peak, pass alpha)."""
    if k == K_PEAK:
        track_rotation(y[0], met)
    elif k == K_PASS_ALPHA:
        passed_alpha(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        return start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == K_IMPACT:
        return ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt,
                             par[P_E])
    if k == K_OVERTURN:
        return overturned(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)
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
def carlson_rf(x, y, z):
    """Carlson's symmetric elliptic integral of the first kind R_F(x, y, z),
    for x, y, z >= 0 with at most one zero: duplication theorem and the
    fifth-order series (Carlson 1995, Numer. Algorithms 10, 13-26,
    doi:10.1007/BF02198293); ERRTOL 0.0025 bounds the truncation error by
    ERRTOL**6 / 4 < 1e-16 (relative)."""
    mu = 1.0
    dx = dy = dz = 0.0
    for _ in range(64):
        mu = (x + y + z) / 3.0
        dx = 1.0 - x / mu
        dy = 1.0 - y / mu
        dz = 1.0 - z / mu
        if max(abs(dx), abs(dy), abs(dz)) < 0.0025:
            break
        sx = math.sqrt(x)
        sy = math.sqrt(y)
        sz = math.sqrt(z)
        lam = sx * (sy + sz) + sy * sz
        x = 0.25 * (x + lam)
        y = 0.25 * (y + lam)
        z = 0.25 * (z + lam)
    e2 = dx * dy - dz * dz
    e3 = dx * dy * dz
    return (1.0 + (e2 / 24.0 - 0.1 - 3.0 * e3 / 44.0) * e2 + e3 / 14.0) \
        / math.sqrt(mu)


@jit
def within_max(peak, met):
    """The signed rotation ``peak`` does not exceed the largest one reached
    on its side, so it changes no max-rotation metric."""
    if peak >= 0.0:
        return peak <= met[M_MAX_THETA_POS]
    return -peak <= met[M_MAX_THETA_NEG]


@jit
def swing_time(phi, k2, p):
    """Time of free rocking from phi = (alpha - s theta) / 2 out to the peak
    sin(phi_pk) = k, k^2 = (1 - cos alpha - E) / 2 > 0 (E as in
    rigid.free_energy, below the barrier).  theta'^2 = 4 p^2 (sin^2 phi -
    k^2) makes it (1/p) int dphi / sqrt(sin^2 phi - k^2) from phi_pk; with
    cos phi = sqrt(m) cos psi, m = 1 - k^2, that is (1/p) (K(m) -
    F(pi/2 - psi | m)), and in Carlson's form K(m) = R_F(0, k^2, 1),
    F = cos(phi) / sqrt(m) R_F((sin^2 phi - k^2) / m, sin^2 phi, 1)."""
    m = 1.0 - k2
    sp2 = math.sin(phi) ** 2
    x = max(sp2 - k2, 0.0) / m
    return (carlson_rf(0.0, k2, 1.0)
            - math.cos(phi) / math.sqrt(m) * carlson_rf(x, sp2, 1.0)) / p


@jit
def peak_times(theta, w, s, alpha, p, e):
    """Times from now to the next two peaks of ``bounded_after_excitation``
    (free rocking below the barrier, theta'+ = e theta'- at impacts): a
    swing out to a peak and back to the impact take the same time."""
    return peak_times_sides(theta, w, s, alpha, p, e, alpha, p, e)


@jit
def peak_times_sides(theta, w, s, alpha_s, p_s, e_s, alpha_o, p_o, e_o):
    """``peak_times`` of ``bounded_after_excitation_sides``: each swing
    with the alpha and p of its side, the energy carried across an impact
    as there (rho = e^2 p_from^2 / p_to^2, E in units of the side's
    M g R)."""
    c_s = 1.0 - math.cos(alpha_s)
    c_o = 1.0 - math.cos(alpha_o)
    E = 0.5 * w * w / (p_s * p_s) + math.cos(alpha_s - s * theta) - math.cos(alpha_s)
    rho_s = impact_energy_factor(e_s, p_s, p_o)
    rho_o = impact_energy_factor(e_o, p_o, p_s)
    to_peak = swing_time(0.5 * (alpha_s - s * theta), 0.5 * (c_s - E), p_s)
    if s * w > 0.0:
        e2 = rho_s * E
        t1 = to_peak
        return t1, (t1 + swing_time(0.5 * alpha_s, 0.5 * (c_s - E), p_s)
                    + swing_time(0.5 * alpha_o, 0.5 * (c_o - e2), p_o))
    e1 = rho_s * E
    e2 = rho_o * e1
    t1 = (swing_time(0.5 * alpha_s, 0.5 * (c_s - E), p_s) - to_peak
          + swing_time(0.5 * alpha_o, 0.5 * (c_o - e1), p_o))
    return t1, (t1 + swing_time(0.5 * alpha_o, 0.5 * (c_o - e1), p_o)
                + swing_time(0.5 * alpha_s, 0.5 * (c_s - e2), p_s))


@jit
def count_peaks(t, t1, t2, pk1, pk2, t_end, met):
    """Complete the max rotations of a ``safe:bounded`` decision with the
    next two peaks (at t + t1, t + t2) that come before t_end; later peaks
    are lower.  A peak after t_end that would raise the max leaves the run
    undecided (returns False): the state at t_end would count instead."""
    if not (within_max(pk1, met) or t + t1 <= t_end):
        return False
    if not (within_max(pk2, met) or t + t2 <= t_end):
        return False
    if t + t1 <= t_end:
        track_rotation(pk1, met)
    if t + t2 <= t_end:
        track_rotation(pk2, met)
    return True


@jit
def outward_fall_integral(phi, c, beyond):
    """Antiderivative of 1 / sqrt(c + sin(phi)^2), zero at the reference
    point: phi = 0 (``beyond`` False; needs c > 0) or phi = pi/2 (``beyond``
    True: phi in [0, pi/2], c > -1, c + sin(phi)^2 > 0).  Both are
    incomplete elliptic integrals of the first kind in Carlson's form:
    F(phi | m) = sin(phi) R_F(cos^2 phi, 1 - m sin^2 phi, 1)."""
    if not beyond:
        sp = math.sin(phi)
        cp = math.cos(phi)
        return sp * carlson_rf(c * cp * cp, c + sp * sp, c)
    # psi = pi/2 - phi: sin(phi) = cos(psi)
    sq = math.cos(phi)      # sin(psi)
    cq = math.sin(phi)      # cos(psi)
    return -sq * carlson_rf((1.0 + c) * cq * cq, c + cq * cq, 1.0 + c)


@jit
def overturns_after_excitation(theta, w, s, alpha, p, theta_over):
    """Early overturning decision once the excitation is over (exact, the
    counterpart of ``bounded_after_excitation``): a block rocking outward
    (s theta' > 0) that is past alpha, or inside the well with energy above
    the barrier 1 - cos(alpha), reaches theta_over without any impact: free
    rocking conserves energy and the speed never vanishes on the way
    (physics.md 1, overturning).

    The fall is known in closed form.  With u = s theta - alpha and
    c = (theta' / 2p)^2 - sin^2(u/2) = (E - (1 - cos alpha)) / 2 (E as in
    free_energy), free rocking gives theta'^2 = 4 p^2 (c + sin^2(u/2)), so
    the time from u0 to u1 is (1/p) int dphi / sqrt(c + sin^2 phi) over
    phi = u/2, an elliptic integral (``outward_fall_integral``).
    Returns (falls, c, time to reach alpha (NaN if past it already), time
    to reach theta_over), the times from now."""
    if not s * w > 0.0:
        return False, 0.0, np.nan, np.nan
    u0 = s * theta - alpha               # rotation past the unstable point
    if not u0 < theta_over - alpha:
        return False, 0.0, np.nan, np.nan
    q = 0.5 * w / p
    phi0 = 0.5 * u0
    sh = math.sin(phi0)
    c = q * q - sh * sh
    beyond = phi0 >= 0.0
    if not (beyond or c > 0.0):
        return False, c, np.nan, np.nan
    f0 = outward_fall_integral(phi0, c, beyond)
    f1 = outward_fall_integral(0.5 * (theta_over - alpha), c, beyond)
    dt_alpha = np.nan if beyond else -f0 / p     # the integral is 0 at alpha
    return True, c, dt_alpha, (f1 - f0) / p


@jit
def fall_to_overturn(t, y, par, disc, met, log, cnt):
    """Complete in closed form a run that after_step stopped at time t by
    ``overturns_after_excitation``: log the first passage of alpha (if it is
    still to come) and the overturning as the integrated run does, and leave
    y and met[M_T_FINAL] at the overturning state."""
    fall_on_side(t, y, disc[D_PIVOT], par[P_ALPHA], par[P_P],
                 par[P_THETA_OVER], disc, met, log, cnt)


@jit
def fall_on_side(t, y, s, alpha, p, theta_over, disc, met, log, cnt):
    """``fall_to_overturn`` on pivot s of slenderness alpha and frequency
    parameter p (scalars)."""
    _falls, c, dt_alpha, dt_over = overturns_after_excitation(
        y[0], y[1], s, alpha, p, theta_over)
    if np.isfinite(dt_alpha):
        y[0] = s * alpha
        y[1] = s * 2.0 * p * math.sqrt(c)
        observe(K_PASS_ALPHA, t + dt_alpha, y, disc, met, log, cnt)
    sh = math.sin(0.5 * (theta_over - alpha))
    y[0] = s * theta_over
    y[1] = s * 2.0 * p * math.sqrt(c + sh * sh)
    met[M_T_FINAL] = t + dt_over
    overturned(t + dt_over, y[0], y[1], s, met, log, cnt)


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
    theta_over = par[P_THETA_OVER]
    early = opt[O_EARLY_EXIT] != 0.0
    t_end = opt[O_T_END]
    track_rotation(theta, met)
    if at_end:
        return final_status(disc, met)
    if not early or mode != MODE_ROCK or t < met[M_T_EXC_END]:
        return RUNNING
    # free rocking from now on: the exact early decisions
    safe, pk1, pk2 = bounded_after_excitation(theta, w, s, alpha, p, e)
    if safe:
        t1, t2 = peak_times(theta, w, s, alpha, p, e)
        return SAFE_BOUNDED if count_peaks(t, t1, t2, pk1, pk2, t_end, met) else RUNNING
    falls, _c, _dt_alpha, dt_over = overturns_after_excitation(
        theta, w, s, alpha, p, theta_over)
    if falls and t + dt_over <= t_end:
        # run completes the fall in closed form (fall_to_overturn); one
        # that would end after t_end is integrated on (safe:moving)
        if met[M_IMPACTS] > 0:
            return OVERTURN_MODE1
        return OVERTURN_MODE2
    return RUNNING


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    """Initial discrete state from (theta0, theta'0)."""
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    if y[0] != 0.0 or y[1] != 0.0:
        disc[D_MODE] = MODE_ROCK
        disc[D_STATIC] = 0
        disc[D_PIVOT] = initial_pivot(y[0], y[1])
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
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    status = integrate_hybrid(rhs, event, transition, static_margin,
                              after_step, N_EVENTS, y, par, disc, hdr, smp,
                              opt, t_eval, met, hist_t, hist_y, hist_d, log,
                              cnt)
    if (status == OVERTURN_MODE1 or status == OVERTURN_MODE2) and \
            np.isnan(met[M_T_OVER]):
        # decided early by after_step: the fall is known in closed form
        fall_to_overturn(met[M_T_FINAL], y, par, disc, met, log, cnt)
    return status


# ------------------------------------------------------- asymmetric body
# A body whose base corners sit at (-b1, -h1) and (b2, -h2) from the centre
# of mass rocks on pivot s with that corner's alpha_s, p_s (Housner's EOM
# holds about either corner with its own values), and an impact from pivot s
# onto -s keeps the angular momentum about the new pivot:
#     theta'+ = e_s theta'-,  e_s = (I_G + M r_s . r_-s) / I_O,-s
# (r_k the vector from corner k to the centre of mass; the front end computes
# e_s, or takes a given e).  The rigid entries of ``par`` hold pivot +1,
# P_ALPHA_NEG, P_P_NEG, P_E_NEG pivot -1 (kernels/layout.py).  Each function
# below performs, for equal sides, the same floating-point operations as its
# symmetric counterpart above, so the runs are bit-identical.

@jit
def body_rhs(t, y, par, disc, hdr, smp, out):
    theta = y[0]
    w = y[1]
    s = disc[D_PIVOT]
    if s > 0:
        alpha = par[P_ALPHA]
        p = par[P_P]
    else:
        alpha = par[P_ALPHA_NEG]
        p = par[P_P_NEG]
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    out[0] = w
    out[1] = housner(theta, s, alpha, p, g, ag, av)


@jit
def body_event(k, t, y, par, disc, hdr, smp):
    s = disc[D_PIVOT]
    theta = y[0]
    w = y[1]
    if k == K_IMPACT:
        return s * theta, s * w, True
    if k == K_OVERTURN:
        return par[P_THETA_OVER] - s * theta, -s * w, True
    if s > 0:
        alpha = par[P_ALPHA]
        p = par[P_P]
    else:
        alpha = par[P_ALPHA_NEG]
        p = par[P_P_NEG]
    g = par[P_G]
    if k == K_PASS_ALPHA:
        return alpha - s * theta, -s * w, False
    if k == K_PEAK:
        ag, av = ground(t, hdr, smp)
        return s * w, s * housner(theta, s, alpha, p, g, ag, av), False
    if int(hdr[N_HDR + X_KIND]) == EXC_NONE:
        return np.inf, 0.0, True        # G = g > 0 throughout
    _ag, _dag, av, dav = ground_rates(t, hdr, smp)
    return g + av, dav, True


@jit
def body_static_margin(t, y, par, disc, hdr, smp):
    """Full contact holds while the ground acceleration stays below the
    uplift threshold of the side it tips the body to: a_g > 0 tips it onto
    pivot -1 (a_g <= G tan alpha_1), a_g < 0 onto pivot +1
    (-a_g <= G tan alpha_2)."""
    alpha_pos = par[P_ALPHA]
    alpha_neg = par[P_ALPHA_NEG]
    g = par[P_G]
    ag, av = ground(t, hdr, smp)
    G = g + av
    return min(G * math.tan(alpha_neg) * (1.0 + UPLIFT_RTOL) - ag,
               G * math.tan(alpha_pos) * (1.0 + UPLIFT_RTOL) + ag)


@jit
def body_start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log, cnt):
    """From theta = theta' = 0: the uplift test on the side the ground
    acceleration tips the body to, else REST."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    if G <= 0.0:
        log_event(log, cnt, t, EV_FLIGHT, 0.0, 0.0, y[0], disc[D_PIVOT])
        return FLIGHT
    s = -1 if ag > 0.0 else 1
    alpha = par[P_ALPHA] if s > 0 else par[P_ALPHA_NEG]
    if abs(ag) > G * math.tan(alpha) * (1.0 + UPLIFT_RTOL):
        disc[D_MODE] = MODE_ROCK
        disc[D_STATIC] = 0
        disc[D_PIVOT] = s
        if np.isnan(met[M_T_UPLIFT]):
            met[M_T_UPLIFT] = t
        log_event(log, cnt, t, EV_UPLIFT, 0.0, 0.0, y[0], disc[D_PIVOT])
    else:
        disc[D_MODE] = MODE_REST
        disc[D_STATIC] = 1
    return RUNNING


@jit
def body_ground_impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """Impact at theta = 0 from pivot s onto -s: theta'+ = e_s theta'-
    (P_E for s = +1, P_E_NEG for s = -1), then the chatter-to-rest rule of
    physics.md 7.  The kinetic energies about the two pivots differ by the
    inertia ratio I_O,1 / I_O,2 (FASTROCK_DEBUG check)."""
    s = disc[D_PIVOT]
    e = par[P_E] if s > 0 else par[P_E_NEG]
    ratio = par[P_IO_RATIO]
    pre = y[1]
    post = e * pre
    y[0] = 0.0
    y[1] = post
    disc[D_PIVOT] = -s
    met[M_IMPACTS] += 1
    if s > 0:
        check_energy(pre * pre, ratio * post * post, met)
    else:
        check_energy(ratio * pre * pre, post * post, met)
    log_event(log, cnt, t, EV_IMPACT, pre, post, 0.0, -s)
    chatter = abs(post) < opt[O_EPS_OMEGA] or \
        t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    if chatter:
        y[1] = 0.0
        st = body_start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log,
                                        cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, post, 0.0, 0.0, disc[D_PIVOT])
        return st
    return RUNNING


@jit
def body_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        return body_start_rocking_or_rest(t, y, par, disc, hdr, smp, met, log,
                                          cnt)
    if k == K_IMPACT:
        return body_ground_impact(t, y, par, disc, hdr, smp, opt, met, log,
                                  cnt)
    if k == K_OVERTURN:
        return overturned(t, y[0], y[1], disc[D_PIVOT], met, log, cnt)
    if k == K_FLIGHT:
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], disc[D_PIVOT])
        return FLIGHT
    observe(k, t, y, disc, met, log, cnt)
    return RUNNING


@jit
def impact_energy_factor(e, p_from, p_to):
    """rho: an impact of restitution e from a pivot of p_from onto one of
    p_to turns the energy E (in units of M g R of the side it rocks on)
    into rho E, rho = e^2 p_from^2 / p_to^2 (= e^2 I_O,to / I_O,from)."""
    return (e * e) * ((p_from * p_from) / (p_to * p_to))


@jit
def bounded_after_excitation_sides(theta, w, s, alpha_s, p_s, e_s, alpha_o,
                                   p_o, e_o):
    """``bounded_after_excitation`` per side (exact as well): pivot s with
    alpha_s, p_s, e_s (the restitution of the impact leaving it), the other
    pivot with alpha_o, p_o, e_o.

    Energies are counted in units of M g R_k on the side k the body rocks on
    (``free_energy``).  An impact from k onto j turns E into
    e_k^2 (p_k / p_j)^2 E: theta'^2 / (2 p^2) with the post-impact speed and
    the new side's p.  Impacts never add energy (the front end checks
    e_k^2 I_O,j / I_O,k <= 1 for a given e; the angular-momentum map
    satisfies it by Cauchy-Schwarz), so once the body is inside the well
    with energy below the barrier 1 - cos(alpha_k) of the side of its next
    half-cycle and of the one after, no later half-cycle on either side can
    reach its alpha.  Returns (safe, peak 1, peak 2), signed rotations."""
    if not s * theta < alpha_s:
        return False, 0.0, 0.0   # past the unstable equilibrium
    E = 0.5 * w * w / (p_s * p_s) + math.cos(alpha_s - s * theta) \
        - math.cos(alpha_s)
    if not E < 1.0 - math.cos(alpha_s):
        return False, 0.0, 0.0
    rho_s = impact_energy_factor(e_s, p_s, p_o)
    rho_o = impact_energy_factor(e_o, p_o, p_s)
    if s * w > 0.0:
        side1 = s
        a1 = alpha_s
        a2 = alpha_o
        e1 = E
        e2 = rho_s * e1
        e_other = e2
    else:
        side1 = -s
        a1 = alpha_o
        a2 = alpha_s
        e1 = rho_s * E
        e2 = rho_o * e1
        e_other = e1
    if not e_other < 1.0 - math.cos(alpha_o):
        return False, 0.0, 0.0
    return (True, side1 * peak_from_energy(a1, e1),
            -side1 * peak_from_energy(a2, e2))


@jit
def body_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    # every array entry read first (see "Hot paths" above)
    theta = y[0]
    w = y[1]
    s = disc[D_PIVOT]
    mode = disc[D_MODE]
    if s > 0:
        alpha = par[P_ALPHA]
        p = par[P_P]
        e = par[P_E]
        alpha_o = par[P_ALPHA_NEG]
        p_o = par[P_P_NEG]
        e_o = par[P_E_NEG]
    else:
        alpha = par[P_ALPHA_NEG]
        p = par[P_P_NEG]
        e = par[P_E_NEG]
        alpha_o = par[P_ALPHA]
        p_o = par[P_P]
        e_o = par[P_E]
    theta_over = par[P_THETA_OVER]
    early = opt[O_EARLY_EXIT] != 0.0
    t_end = opt[O_T_END]
    track_rotation(theta, met)
    if at_end:
        return final_status(disc, met)
    if not early or mode != MODE_ROCK or t < met[M_T_EXC_END]:
        return RUNNING
    safe, pk1, pk2 = bounded_after_excitation_sides(theta, w, s, alpha, p, e,
                                                    alpha_o, p_o, e_o)
    if safe:
        t1, t2 = peak_times_sides(theta, w, s, alpha, p, e, alpha_o, p_o, e_o)
        return SAFE_BOUNDED if count_peaks(t, t1, t2, pk1, pk2, t_end, met) else RUNNING
    falls, _c, _dt_alpha, dt_over = overturns_after_excitation(
        theta, w, s, alpha, p, theta_over)
    if falls and t + dt_over <= t_end:
        if met[M_IMPACTS] > 0:
            return OVERTURN_MODE1
        return OVERTURN_MODE2
    return RUNNING


@jit
def body_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
             log, cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    status = integrate_hybrid(body_rhs, body_event, body_transition,
                              body_static_margin, body_after_step, N_EVENTS,
                              y, par, disc, hdr, smp, opt, t_eval, met,
                              hist_t, hist_y, hist_d, log, cnt)
    if (status == OVERTURN_MODE1 or status == OVERTURN_MODE2) and \
            np.isnan(met[M_T_OVER]):
        s = disc[D_PIVOT]
        if s > 0:
            fall_on_side(met[M_T_FINAL], y, s, par[P_ALPHA], par[P_P],
                         par[P_THETA_OVER], disc, met, log, cnt)
        else:
            fall_on_side(met[M_T_FINAL], y, s, par[P_ALPHA_NEG],
                         par[P_P_NEG], par[P_THETA_OVER], disc, met, log, cnt)
    return status


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


@jit
def rigid_body_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                        hist_d, log, cnt):
    """One run of the asymmetric body (``par`` of length N_PAR_RIGID_BODY),
    as ``rigid_simulate``."""
    return body_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                    hist_d, log, cnt)


@jit_parallel
def rigid_body_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many runs of the asymmetric body in parallel, as ``rigid_sweep``."""
    sweep_rows(body_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
