"""Generic event-driven integrator for hybrid (piecewise-smooth) models.

One driver serves every motion mode.  A model supplies five jitted
functions, passed as arguments so that Numba specialises and inlines them
into the model's entry kernel:

``rhs(t, y, par, disc, hdr, smp, out)``
    continuous dynamics of the current discrete state ``disc``.
``event(k, t, y, par, disc, hdr, smp) -> (g, gdot, terminal)``
    event function k.  Convention: ``g > 0`` is the admissible side and the
    event fires when g reaches ``<= 0`` (so every event is direction-aware
    by construction); inactive events return ``g = inf``.  ``gdot`` is dg/dt,
    used to find an interior minimum (grazing) that the step-end signs miss.
    Non-terminal events are observers: their transition may update metrics
    but never the state.
``transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt) -> status``
    applies an impact map / mode switch in place; ``k = -1`` means the end
    of a static phase (``disc[D_STATIC] == 1``: the state is frozen and only
    ``static_margin`` of the excitation can end it).
``static_margin(t, y, par, disc, hdr, smp) -> g``
    the static phase ends when g becomes negative (strictly).
``after_step(t, y, par, disc, hdr, smp, opt, met, at_end) -> status``
    metrics after an accepted step, early decisions, and the final status.

Continuous phases use ``dopri``; breakpoints (pulse ends, record samples)
are never stepped over, and the rhs is re-evaluated just after one.
"""
import numpy as np
from numba import prange

from .config import DEBUG, jit, jit_generic, next_up, ulp
from .dopri import (ERR_FIXED_MAX, N_STAGES, dense_eval, dopri_dense,
                    dopri_step, dopri_work_rows, select_initial_step,
                    step_factor)
from .excitation import (excitation_end, excitation_start, next_breakpoint,
                         scan_origin, scan_step)
from .layout import (D_MODE, D_SLIP_DIR, MODE_REST, MODE_ROCK, MODE_SLIDE,
                     MODE_SLIDE_ROCK, M_T_CONTACT, M_T_ROCK, M_T_SLIDE,
                     M_T_SLIDE_ROCK, M_T_UNLOADED,
                     M_T_LAST_IMPACT, M_T_OVER, M_T_PASS_ALPHA, M_T_PREV,
                     M_T_UPLIFT, D_STATIC, FAIL_EVENT, FAIL_OUTPUT_FULL,
                     FAIL_STEP_BUDGET, FAIL_STEP_UNDERFLOW, FAIL_TRANSITIONS,
                     EV_UPLIFT, LOG_KIND, LOG_PIVOT, LOG_POST, LOG_PRE, LOG_T,
                     LOG_THETA,
                     M_N_EVENTS, M_NFEV, M_NREJECT, M_NSTEPS, M_T_EXC_END, N_LOG, N_MET,
                     M_ENERGY_GAINS, M_T_FINAL, O_ATOL, O_DT_FIXED, O_MAX_STEP, O_MAX_STEPS,
                     FAIL_UNSTABLE, FAIL_INTERRUPTED, M_ERR_FIXED, M_DT_STABLE,
                     O_ABORT, O_EPS_OMEGA, O_EPS_T,
                     O_RECORD_BREAKS, O_RTOL, O_T0, O_T_END, RUNNING,
                     SAFE_MOVING, SAFE_NO_UPLIFT, SAFE_REST)

MAX_BISECT = 200          # iteration cap of every bisection
MAX_FALSI = 4 * MAX_BISECT   # regula falsi: at least MAX_BISECT halvings
EPS = 2.220446049250313e-16
MAX_ZERO_LENGTH = 200     # transitions in a row without time advancing
C_NHIST = 0
C_NLOG = 1
C_LOG_DROPPED = 2
N_COUNTERS = 4


@jit
def init_metrics(t0, met):
    """Metrics at the start of a run: counters 0, times of events not yet
    seen NaN, bookkeeping time t0."""
    for i in range(N_MET):
        met[i] = 0.0
    met[M_T_UPLIFT] = np.nan
    met[M_T_OVER] = np.nan
    met[M_T_PASS_ALPHA] = np.nan
    met[M_T_LAST_IMPACT] = -np.inf
    met[M_T_PREV] = t0
    met[M_DT_STABLE] = np.nan


@jit
def book_time(t, disc, met):
    """Attribute the time since the last bookkeeping to the contact mode
    (the one rule of every model): full contact at rest to M_T_CONTACT,
    rocking to M_T_ROCK, sliding to M_T_SLIDE, slide-rocking to
    M_T_SLIDE_ROCK (and to M_T_UNLOADED while a lift-off is held, slip
    direction 0); other modes book nothing."""
    dt = t - met[M_T_PREV]
    if dt > 0.0:
        m = disc[D_MODE]
        if m == MODE_REST:
            met[M_T_CONTACT] += dt
        elif m == MODE_ROCK:
            met[M_T_ROCK] += dt
        elif m == MODE_SLIDE:
            met[M_T_SLIDE] += dt
        elif m == MODE_SLIDE_ROCK:
            met[M_T_SLIDE_ROCK] += dt
            if disc[D_SLIP_DIR] == 0:
                met[M_T_UNLOADED] += dt
    met[M_T_PREV] = t


@jit
def final_status(disc, met):
    """The status of a run that ends upright (the one rule of every model):
    in full contact at rest, SAFE_NO_UPLIFT if it never lifted off, else
    SAFE_REST; in any other contact mode SAFE_MOVING.  (A model that starts
    lifted off books its uplift at t0, so 'never lifted off' implies rest.)"""
    if disc[D_MODE] == MODE_REST:
        if np.isnan(met[M_T_UPLIFT]):
            return SAFE_NO_UPLIFT
        return SAFE_REST
    return SAFE_MOVING


@jit
def is_chatter(t, post, opt, met):
    """Chatter rule of physics.md 7 at one contact: the velocity after the
    impact is below eps_omega, or two impacts came closer than eps_t; books
    the impact time."""
    c = abs(post) < opt[O_EPS_OMEGA] or t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    return c


@jit
def elastic_below_resolution(r, rebound, scale, opt):
    """An impact elastic at the resolution asked for (restitution r with
    1 - r^2 <= rtol: it dissipates less than rtol of the energy, so the
    bounces do not converge) whose rebound energy is below rtol times the
    energy scale of its model ends as chatter (kernels/wall.py docstring)."""
    rtol = opt[O_RTOL]
    return 1.0 - r * r <= rtol and rebound < rtol * scale


@jit
def check_energy(before, after, met):
    """Debug mode only: count an impact whose kinetic energy ``after``
    exceeds ``before`` (every impact map must dissipate)."""
    if DEBUG and after > before * (1.0 + 1e-12) + 1e-300:
        met[M_ENERGY_GAINS] += 1


@jit
def log_event(log, cnt, t, kind, pre, post, theta, pivot):
    """Append one row to the fixed-capacity event log (drops when full)."""
    i = cnt[C_NLOG]
    if i < log.shape[0]:
        log[i, LOG_T] = t
        log[i, LOG_KIND] = kind
        log[i, LOG_PRE] = pre
        log[i, LOG_POST] = post
        log[i, LOG_THETA] = theta
        log[i, LOG_PIVOT] = pivot
        cnt[C_NLOG] = i + 1
    else:
        cnt[C_LOG_DROPPED] += 1


@jit
def undo_uplift(t, met, log, cnt):
    """Take back an uplift decided at time t that did not happen (the body
    turned back in the first step and never left the ground): the first
    uplift time and the log entry, if either was made at t."""
    if met[M_T_UPLIFT] == t:
        met[M_T_UPLIFT] = np.nan
    i = cnt[C_NLOG] - 1
    if i >= 0 and log[i, LOG_KIND] == EV_UPLIFT and log[i, LOG_T] == t:
        cnt[C_NLOG] = i


@jit
def _store(t, y, disc, hist_t, hist_y, hist_d, cnt):
    i = cnt[C_NHIST]
    if i >= hist_t.shape[0]:
        return False
    hist_t[i] = t
    for j in range(y.shape[0]):
        hist_y[i, j] = y[j]
    for j in range(hist_d.shape[1]):
        hist_d[i, j] = disc[j]
    cnt[C_NHIST] = i + 1
    return True


@jit
def _falsi_point(lo, hi, glo, ghi, tol, bisect):
    """Next trial point strictly inside (lo, hi), for a root bracketed by
    the values glo = g(lo) and ghi = g(hi) on opposite sides: the secant
    (regula falsi) through the two ends, kept tol/2 away from them, or the
    midpoint when ``bisect`` is set or the secant is unusable (NaN)."""
    if not bisect:
        m = hi - ghi * (hi - lo) / (ghi - glo)
        m = min(max(m, lo + 0.5 * tol), hi - 0.5 * tol)
        if lo < m < hi:
            return m
    return 0.5 * (lo + hi)


@jit
def _bracket_tol(lo, hi):
    """Width at which a bracket counts as converged: 4 eps max(|t|, 1), as
    SciPy's brentq xtol."""
    return 4.0 * EPS * max(abs(lo), abs(hi), 1.0)


@jit
def _shrink(lo, hi, glo, ghi, side, m, gm, keep_lo):
    """Illinois update of the bracket (lo, hi) with the trial point m of
    value gm: ``keep_lo`` says m lies on lo's side.  When the same end is
    kept twice in a row its value is halved, so both ends converge
    superlinearly.  With ``_falsi_point`` this is the one root finder of
    the kernels: event roots, static exits and grazing extrema use it."""
    if keep_lo:
        if side == 1:
            ghi *= 0.5
        return m, hi, gm, ghi, 1
    if side == -1:
        glo *= 0.5
    return lo, m, glo, gm, -1


@jit_generic
def _bisect_root(event, k, lo, hi, glo, ghi, t_old, h, y_old, Q, yev, par,
                 disc, hdr, smp):
    """Root of event k on the dense interpolant, bracketed as g(lo) > 0 >=
    g(hi) (glo, ghi: the known values at the ends, used for the secant
    only).  Returns hi, the first point known to be on the event side, and
    a converged flag (hi - lo <= 4 eps max(|t|, 1), as SciPy's brentq xtol).

    Illinois regula falsi: when the same end is kept twice in a row, its
    value is halved, so both ends converge superlinearly (about 10 event
    evaluations against about 50 for bisection).  Every 4th trial point is
    the midpoint, so the bracket halves at least every 4 iterations
    whatever the shape of g: the cap MAX_FALSI allows MAX_BISECT halvings.
    """
    side = 0
    for it in range(MAX_FALSI):
        tol = _bracket_tol(lo, hi)
        if hi - lo <= tol:
            return hi, True
        m = _falsi_point(lo, hi, glo, ghi, tol, it % 4 == 3)
        dense_eval(m, t_old, h, y_old, Q, yev)
        g, _gd, _term = event(k, m, yev, par, disc, hdr, smp)
        lo, hi, glo, ghi, side = _shrink(lo, hi, glo, ghi, side, m, g, g > 0.0)
    return hi, False


@jit_generic
def _bisect_extremum(event, k, lo, hi, sign, t_old, h, y_old, Q, yev, par,
                     disc, hdr, smp):
    """Locate where gdot changes sign: sign*gdot < 0 at lo, > 0 at hi.
    Bisection only (``_falsi_point`` with ``bisect`` set): gdot's values
    at the step ends are not bracketing values of one smooth function
    once the secant is kept away from the ends."""
    side = 0
    glo = -1.0
    ghi = 1.0
    for _ in range(MAX_BISECT):
        tol = _bracket_tol(lo, hi)
        if hi - lo <= tol:
            break
        mid = _falsi_point(lo, hi, glo, ghi, tol, True)
        dense_eval(mid, t_old, h, y_old, Q, yev)
        _g, gd, _term = event(k, mid, yev, par, disc, hdr, smp)
        lo, hi, glo, ghi, side = _shrink(lo, hi, glo, ghi, side, mid, sign * gd,
                                         sign * gd < 0.0)
    return 0.5 * (lo + hi)


# How an event can fire inside one step, judged from its values at the two
# step ends (see _locate).
NO_ROOT = 0
SIGN_CHANGE = 1     # g > 0 at the start, <= 0 at the end
SEARCH_MIN = 2      # g > 0 at both ends, gdot goes - to +: interior minimum
SEARCH_MAX = 3      # started on the surface (terminal, phase start) and
#                     gdot goes + to -: it may have left and come back
AT_START = 4        # started on the surface and never left: fires at once


@jit
def _bracket_kind(terminal, phase_start, g0, gd0, g1, gd1):
    """Classify event k on one step from its end values (scalars only, so
    the driver can skip ``_locate`` for the common no-root case cheaply)."""
    if g0 > 0.0:
        if g1 <= 0.0:
            return SIGN_CHANGE
        if gd0 < 0.0 and gd1 > 0.0:
            return SEARCH_MIN
        return NO_ROOT
    if terminal and phase_start and g1 <= 0.0:
        # gd0 == 0: released from rest (uplift), it may rise and fall back
        if gd0 >= 0.0 and gd1 < 0.0:
            return SEARCH_MAX
        return AT_START
    return NO_ROOT


@jit_generic
def _locate(event, k, kind, ta, tb, g0, g1, y_old, h, Q, yev, par, disc, hdr,
            smp):
    """Root of event k inside [ta, tb] (inf if none) and a converged flag,
    for kind SIGN_CHANGE, SEARCH_MIN or SEARCH_MAX (``_bracket_kind``).

    Besides a sign change at the step ends, an interior minimum of g (gdot
    goes - to +) is located and tested, so that a crossing and its return
    inside one step (grazing) are not missed.  Each helper is called at one
    site only: they are inlined, and fewer copies compile faster.
    """
    lo = ta
    hi = tb
    glo = g0
    ghi = g1
    if kind != SIGN_CHANGE:
        search = 1.0 if kind == SEARCH_MIN else -1.0
        tm = _bisect_extremum(event, k, ta, tb, search, ta, h, y_old, Q, yev,
                              par, disc, hdr, smp)
        dense_eval(tm, ta, h, y_old, Q, yev)
        gm, _gd, _term = event(k, tm, yev, par, disc, hdr, smp)
        if search > 0.0:
            if gm > 0.0:
                return np.inf, True
            hi = tm
            ghi = gm
        else:
            if gm <= 0.0:
                return ta, True     # never left the surface
            lo = tm
            glo = gm
    return _bisect_root(event, k, lo, hi, glo, ghi, ta, h, y_old, Q, yev, par,
                        disc, hdr, smp)


@jit_generic
def _static_exit(static_margin, t, t_stop, y, par, disc, hdr, smp):
    """First time in [t, t_stop] at which the static margin becomes < 0,
    scanning a grid on which pulse extrema and record samples lie; inside
    the first grid interval that ends below zero, the crossing is bracketed
    to 4 eps max(|t|, 1) by Illinois regula falsi (as in ``_bisect_root``)."""
    g = static_margin(t, y, par, disc, hdr, smp)
    if g < 0.0:
        return t
    hs = scan_step(hdr)
    if not np.isfinite(hs) or hs <= 0.0:
        return np.inf
    origin = scan_origin(hdr)
    j = np.floor((t - origin) / hs) + 1.0
    # nothing moves before the excitation starts: jump to the grid point
    # just below its start instead of stepping through the quiet time
    j = max(j, np.floor((excitation_start(hdr) - origin) / hs))
    lo = t
    glo = g
    while True:
        tk = origin + j * hs
        if tk <= lo:
            j += 1.0
            continue
        if tk > t_stop:
            tk = t_stop
        g = static_margin(tk, y, par, disc, hdr, smp)
        if g < 0.0:
            hi = tk
            ghi = g
            side = 0
            for it in range(MAX_FALSI):
                tol = _bracket_tol(lo, hi)
                if hi - lo <= tol:
                    break
                m = _falsi_point(lo, hi, glo, ghi, tol, it % 4 == 3)
                gm = static_margin(m, y, par, disc, hdr, smp)
                lo, hi, glo, ghi, side = _shrink(lo, hi, glo, ghi, side, m, gm, gm >= 0.0)
            return hi
        if tk >= t_stop:
            return np.inf
        lo = tk
        glo = g
        j += 1.0


@jit
def _all_finite(y):
    for i in range(y.shape[0]):
        if not np.isfinite(y[i]):
            return False
    return True


@jit
def uniform_tol(opt, par, n):
    """O_ATOL and O_RTOL for each of the n state components (the
    ``tol_of`` of ``integrate_with`` for states measured in rad and m)."""
    tol = np.empty((2, n))
    for i in range(n):
        tol[0, i] = opt[O_ATOL]
        tol[1, i] = opt[O_RTOL]
    return tol


@jit
def _any_nonzero(y):
    for i in range(y.shape[0]):
        if y[i] != 0.0:
            return True
    return False


@jit_generic
def integrate_hybrid(rhs, event, transition, static_margin, after_step,
                     n_events, y, par, disc, hdr, smp, opt, t_eval, met,
                     hist_t, hist_y, hist_d, log, cnt):
    """Integrate one run of a hybrid model from opt[O_T0] to opt[O_T_END]
    with Dormand-Prince 5(4) (``integrate_with`` and the DP5 method).

    ``y`` (state) and ``disc`` are updated in place and hold the final state.
    ``t_eval`` (sorted) selects output times; if it is empty and ``hist_t``
    has room, every accepted step and every event is stored.  Returns the
    run status (layout codes).
    """
    return integrate_with(dopri_step, dopri_dense, dopri_work_rows,
                          uniform_tol, rhs, event, transition, static_margin,
                          after_step,
                          n_events, y, par, disc, hdr, smp, opt, t_eval, met,
                          hist_t, hist_y, hist_d, log, cnt)


@jit_generic
def integrate_with(step, dense, work_rows, tol_of, rhs, event, transition,
                   static_margin, after_step, n_events, y, par, disc, hdr,
                   smp, opt, t_eval, met, hist_t, hist_y, hist_d, log, cnt):
    """``integrate_hybrid`` with the integration method as three functions
    (``dopri.dopri_step`` / ``dopri_dense`` / ``dopri_work_rows`` have the
    contract) and the model's tolerances as a fourth:

    ``step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp, y_new, y_scale,
    tol, opt, par, disc, hdr, smp, met) -> (err, exponent)``
        one step of size h from (t, y), f = f(t, y) (``tol``: the absolute
        and relative tolerance of each component, rows 0 and 1, from
        ``tol_of``); fills y_new and leaves
        f(t + h, y_new) in ``K[N_STAGES]``; counts its evaluations in
        met[M_NFEV].  ``fresh``: the first try from this (t, y) (a rejected
        try repeats the point with a smaller h).  Adaptive: ``err`` is the
        scaled error norm (accept below 1), ``exponent`` that of the
        step-size factor, -1/(q + 1).  With ``fixed``: the relative local
        error of ``fixed_step_error`` and the value above which it means an
        unstable step (ERR_FIXED_MAX for DP5, inf for an L-stable method).
    ``dense(K, h, y_old, y_new, Q)``
        the last step's dense output as ``dense_eval`` reads it: y_old + h
        (Q0 x + Q1 x^2 + Q2 x^3 + Q3 x^4), x = (t - t_old)/h.
    ``work_rows(n) -> int``
        rows of K the method keeps after the N_STAGES + 1 stage rows (its
        work arrays and state between steps), zeroed at the start of a run.
    ``tol_of(opt, par, n) -> tol``
        the absolute and relative tolerance of each state component (a
        2 x n array): ``uniform_tol`` (O_ATOL, O_RTOL) for states in rad
        and m, a model's own where a component has a scale of its own
        (``foundation.spring_tol``).
    """
    n = y.shape[0]
    t = opt[O_T0]
    t_end = opt[O_T_END]
    tol = tol_of(opt, par, n)
    dt_fixed = opt[O_DT_FIXED]
    max_step = opt[O_MAX_STEP]
    max_steps = opt[O_MAX_STEPS]
    sample_breaks = opt[O_RECORD_BREAKS] != 0.0
    t_exc = excitation_end(hdr)
    met[M_T_EXC_END] = t_exc

    f = np.empty(n)
    y_new = np.empty(n)
    y_old = np.empty(n)
    ytmp = np.empty(n)
    yev = np.empty(n)
    ftmp = np.empty(n)
    # the stages, then the method's work rows, zeroed (its state)
    K = np.empty((N_STAGES + 1 + work_rows(n), n))
    for r in range(N_STAGES + 1, K.shape[0]):
        for i in range(n):
            K[r, i] = 0.0
    Q = np.empty((n, 4))
    g0 = np.empty(n_events)
    gd0 = np.empty(n_events)
    g1 = np.empty(n_events)
    gd1 = np.empty(n_events)
    term = np.empty(n_events, dtype=np.bool_)
    roots = np.empty(n_events)
    y_scale = np.abs(y)
    # a run that has not moved has no scale yet: the error of its first
    # fixed step out of rest is relative to what that step produced (a
    # product of small quantities such as b theta theta' reads 1e-2 at a
    # stable step, contact:2027:437), so divergence is judged from the
    # second step on, once the motion has a scale
    scaled = _any_nonzero(y_scale)

    store = hist_t.shape[0] > 0
    every_step = store and t_eval.shape[0] == 0
    i_eval = 0
    while i_eval < t_eval.shape[0] and t_eval[i_eval] < t:
        i_eval += 1
    if every_step:
        if not _store(t, y, disc, hist_t, hist_y, hist_d, cnt):
            return FAIL_OUTPUT_FULL

    status = RUNNING
    steps_taken = 0.0
    zero_length = 0
    at_break = False
    h_abs = 0.0
    t_phase = np.nan

    while status == RUNNING:
        if opt[O_ABORT] != 0.0:
            status = FAIL_INTERRUPTED
            break
        if t_phase == t:
            zero_length += 1
            if zero_length > MAX_ZERO_LENGTH:
                status = FAIL_TRANSITIONS
                break
        else:
            zero_length = 0
        t_phase = t

        # ---------------- static phase: only the excitation can end it -----
        if disc[D_STATIC] == 1:
            t_stop = min(t_end, t_exc)
            t_hit = np.inf
            if t < t_stop or (t == t_stop and t < t_end):
                t_hit = _static_exit(static_margin, t, t_stop, y, par, disc,
                                     hdr, smp)
            t_next = t_end if not np.isfinite(t_hit) else t_hit
            while i_eval < t_eval.shape[0] and t_eval[i_eval] <= t_next:
                if not _store(t_eval[i_eval], y, disc, hist_t, hist_y,
                              hist_d, cnt):
                    return FAIL_OUTPUT_FULL
                i_eval += 1
            if not np.isfinite(t_hit):
                t = t_end
                if every_step and not _store(t, y, disc, hist_t, hist_y,
                                             hist_d, cnt):
                    return FAIL_OUTPUT_FULL
                status = after_step(t, y, par, disc, hdr, smp, opt, met, True)
                break
            t = t_hit
            if every_step and not _store(t, y, disc, hist_t, hist_y, hist_d,
                                         cnt):
                return FAIL_OUTPUT_FULL
            met[M_N_EVENTS] += 1
            status = transition(-1, t, y, par, disc, hdr, smp, opt, met, log,
                                cnt)
            if every_step and not _store(t, y, disc, hist_t, hist_y, hist_d,
                                         cnt):
                return FAIL_OUTPUT_FULL
            at_break = False
            h_abs = 0.0
            continue

        # ---------------- continuous phase ----------------------------------
        tf = next_up(t) if at_break else t
        rhs(tf, y, par, disc, hdr, smp, f)
        met[M_NFEV] += 1
        t_bound = min(next_breakpoint(t, hdr, sample_breaks), t_end)
        if dt_fixed > 0.0:
            h_abs = dt_fixed
        elif h_abs == 0.0:
            h_abs = select_initial_step(rhs, t, y, t_bound, max_step, f,
                                        tol[1], tol[0], ytmp, ftmp, par, disc,
                                        hdr, smp)
            met[M_NFEV] += 1
        for k in range(n_events):
            g0[k], gd0[k], term[k] = event(k, t, y, par, disc, hdr, smp)
        phase_start = True

        while True:
            t_bp = next_breakpoint(t, hdr, sample_breaks)
            t_bound = min(t_bp, t_end)
            if steps_taken >= max_steps:
                status = FAIL_STEP_BUDGET
                break
            if opt[O_ABORT] != 0.0:
                status = FAIL_INTERRUPTED
                break
            if dt_fixed > 0.0:
                t_new = t + dt_fixed
                if t_new > t_bound or t_bound - t_new < 1e-9 * dt_fixed:
                    t_new = t_bound
                h = t_new - t
                err, err_max = step(rhs, t, y, f, h, True, True, K, ytmp,
                                    ftmp, y_new, y_scale, tol, opt, par,
                                    disc, hdr, smp, met)
                steps_taken += 1.0
                if not err <= met[M_ERR_FIXED]:
                    met[M_ERR_FIXED] = err
                if (scaled and not err <= err_max) or \
                        not _all_finite(y_new):
                    # a diverging step is no physics.  The error grows
                    # about as h^5 up to the limit: suggest a step inside.
                    met[M_DT_STABLE] = (0.5 * h * (ERR_FIXED_MAX / err) ** 0.2
                                        if np.isfinite(err) else 0.1 * h)
                    status = FAIL_UNSTABLE
                    break
                for i in range(n):
                    a = abs(y_new[i])
                    if a > y_scale[i]:
                        y_scale[i] = a
                if not scaled:
                    scaled = _any_nonzero(y_scale)
            else:
                # rk.py 111-171 ``_step_impl``
                min_step = 10.0 * abs(ulp(t))
                if h_abs > max_step:
                    h_abs = max_step
                elif h_abs < min_step:
                    h_abs = min_step
                rejected = False
                failed = False
                while True:
                    if h_abs < min_step:
                        failed = True
                        status = FAIL_STEP_UNDERFLOW
                        break
                    if steps_taken >= max_steps:
                        failed = True
                        status = FAIL_STEP_BUDGET
                        break
                    t_new = t + h_abs
                    if t_new > t_bound:
                        t_new = t_bound
                    h = t_new - t
                    h_abs = abs(h)
                    err, expo = step(rhs, t, y, f, h, not rejected, False, K,
                                     ytmp, ftmp, y_new, y_scale, tol, opt,
                                     par, disc, hdr, smp, met)
                    steps_taken += 1.0
                    if not np.isfinite(err):
                        err = np.inf
                    if err < 1.0:
                        h_abs *= step_factor(err, rejected, expo)
                        break
                    h_abs *= step_factor(err, True, expo)
                    rejected = True
                    met[M_NREJECT] += 1
                if failed:
                    break
            met[M_NSTEPS] += 1

            # ---- events on [t, t_new] ----
            for k in range(n_events):
                g1[k], gd1[k], term[k] = event(k, t_new, y_new, par, disc,
                                               hdr, smp)
            for i in range(n):
                y_old[i] = y[i]
            dense(K, h, y_old, y_new, Q)
            t_term = np.inf
            k_term = -1
            event_failed = False
            for k in range(n_events):
                roots[k] = np.inf
                if not np.isfinite(g0[k]) and not np.isfinite(g1[k]):
                    continue
                kind = _bracket_kind(term[k], phase_start, g0[k], gd0[k],
                                     g1[k], gd1[k])
                if kind == NO_ROOT:
                    continue
                if kind == AT_START:
                    r = t
                    ok = True
                else:
                    r, ok = _locate(event, k, kind, t, t_new, g0[k], g1[k],
                                    y_old, h, Q, yev, par, disc, hdr, smp)
                if not ok:
                    event_failed = True
                roots[k] = r
                if term[k] and r < t_term:
                    t_term = r
                    k_term = k
            if event_failed:
                status = FAIL_EVENT
                break
            for k in range(n_events):
                if (not term[k]) and roots[k] <= t_term and \
                        np.isfinite(roots[k]):
                    dense_eval(roots[k], t, h, y_old, Q, yev)
                    met[M_N_EVENTS] += 1
                    transition(k, roots[k], yev, par, disc, hdr, smp, opt, met,
                               log, cnt)

            t_stop = t_term if k_term >= 0 else t_new
            while i_eval < t_eval.shape[0] and t_eval[i_eval] <= t_stop:
                dense_eval(t_eval[i_eval], t, h, y_old, Q, yev)
                if not _store(t_eval[i_eval], yev, disc, hist_t, hist_y,
                              hist_d, cnt):
                    return FAIL_OUTPUT_FULL
                i_eval += 1

            if k_term >= 0:
                if t_term >= t_new:
                    for i in range(n):
                        y[i] = y_new[i]
                else:
                    dense_eval(t_term, t, h, y_old, Q, y)
                t = t_term
                if every_step and not _store(t, y, disc, hist_t, hist_y,
                                             hist_d, cnt):
                    return FAIL_OUTPUT_FULL
                met[M_N_EVENTS] += 1
                status = transition(k_term, t, y, par, disc, hdr, smp, opt,
                                    met, log, cnt)
                if every_step and not _store(t, y, disc, hist_t, hist_y,
                                             hist_d, cnt):
                    return FAIL_OUTPUT_FULL
                at_break = t == t_bp
                h_abs = 0.0
                break

            t = t_new
            for i in range(n):
                y[i] = y_new[i]
                f[i] = K[N_STAGES, i]
            for k in range(n_events):
                g0[k] = g1[k]
                gd0[k] = gd1[k]
            phase_start = False
            if every_step and not _store(t, y, disc, hist_t, hist_y, hist_d,
                                         cnt):
                return FAIL_OUTPUT_FULL
            if t >= t_end:
                status = after_step(t, y, par, disc, hdr, smp, opt, met, True)
                break
            status = after_step(t, y, par, disc, hdr, smp, opt, met, False)
            if status != RUNNING:
                break
            if t == t_bp:
                # the excitation may jump or kink here: restart from the
                # right limit (FSAL value belongs to the left one)
                rhs(next_up(t), y, par, disc, hdr, smp, f)
                met[M_NFEV] += 1
                for k in range(n_events):
                    g0[k], gd0[k], term[k] = event(k, t, y, par, disc, hdr,
                                                   smp)

    met[M_T_FINAL] = t
    return status


@jit_generic
def sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Body of every model's parallel sweep entry: row i of Y0/PAR/HDR/OPT
    through ``run`` (the model's single-run function) into row i of
    status/MET/YF, with no time history and no event log.  Inlined into a
    ``jit_parallel`` entry kernel, where the prange becomes the parallel
    loop (each iteration writes only its own rows)."""
    n_state = Y0.shape[1]
    for i in prange(Y0.shape[0]):
        y = Y0[i].copy()
        met = np.empty(N_MET)
        t_eval = np.empty(0)
        hist_t = np.empty(0)
        hist_y = np.empty((0, n_state))
        hist_d = np.empty((0, 3), dtype=np.int64)
        log = np.empty((0, N_LOG))
        cnt = np.zeros(N_COUNTERS, dtype=np.int64)
        status[i] = run(y, PAR[i], HDR[i], smp, OPT[i], t_eval, met, hist_t,
                        hist_y, hist_d, log, cnt)
        for j in range(N_MET):
            MET[i, j] = met[j]
        for j in range(n_state):
            YF[i, j] = y[j]
