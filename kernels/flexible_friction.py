"""Flexible rocking body with Coulomb friction at the base: rest, slide, rock
and slide-rock (physics.md 3 and 4.4; Farooghi-Mehr & Wittich).

State ``y = (u, u', theta, theta', d, d')``: the column deflection u [m],
the rotation theta [rad] and the slip d [m] of the base relative to the
ground.  Per unit mass m, with the rigid base (m_b/m = ``mb`` > 0, I_b, h_b)
of the flexible kernel's parameter vector, pivot s and
Xc = X + mb X_b, Yc = Y + mb Y_b (physics.md 3.1):

    [ 1      H      c     ] [u'']   [ f_u ]
    [ H      m22    Yc    ] [th''] = [ f_th ]
    [ c      Yc     1+mb  ] [d'']   [ F - (1+mb) a_g + Xc th'^2 + 2 sn th' u' ]

    N = (1+mb) G - sn u'' - 2 c th' u' - Xc th'' - Yc th'^2

Stick: d'' = 0 and F follows from the last row; slip toward sigma:
F = -mu_k sigma N, which makes the system a 3x3 solve (N eliminated).  Full
contact is theta = 0 with the same rows.  No regularised friction law:
every transition is an event.  Impacts (theta -> 0) follow Farooghi-Mehr &
Wittich's full-contact rule in its general form: theta'+ = 0,
u'+ = u'- + H theta'-, d'+ = d'- + h_b theta'- (the frictionless plastic
projection; h_b = 0 by default, so the slip velocity is kept).

Events (g > 0 admissible; ids C_* in full contact, R_* while rocking):
  REST        C_UPLIFT (either corner), C_SLIP_STICK slip onset mu_s N - |F|,
              C_U_MAX/C_U_MIN extrema of u (observers), C_FLIGHT G
  SLIDE       C_UPLIFT while slipping (-s theta''), C_SLIP_STICK stick sigma d',
              C_U_MAX/C_U_MIN, C_FLIGHT
  ROCK        R_IMPACT s theta, R_OVERTURN, R_SLIP_STICK slip onset, R_LIFT_OFF N,
              R_PEAK s theta' (obs.), R_PASS_ALPHA (obs.), R_U_MAX/R_U_MIN
  SLIDE_ROCK  as ROCK with R_SLIP_STICK stick sigma d'
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground, ground_rates
from .flexible import (F_ALPHA, F_B, F_G, F_H, F_HB, F_MB, F_THETA_OVER, F_WN,
                       F_ZETA, base_inertia, free_column_bound, never_uplifts_again,
                       positions, track_u, uplift_margin)
from .friction import initial_contact, track_slide
from .hybrid import (undo_uplift, book_time, check_energy, final_status,
                     integrate_hybrid, log_event, sweep_rows)
from .layout import (D_AUX, D_MODE, D_PIVOT, D_SLIP_DIR, D_STATIC, EV_FLIGHT,
                     EV_IMPACT, EV_LIFT_OFF_HELD, EV_RELOAD, EV_REST, EV_SLIP,
                     EV_STICK, EV_UPLIFT, FAIL_INCONSISTENT, FLIGHT,
                     MODE_REST,
                     MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK, M_IMPACTS,
                     M_N_LIFT_OFF, M_N_STICK_SLIP, M_T_LAST_IMPACT,
                     M_T_SLIP_START, M_T_UPLIFT, N_DISC, O_EARLY_EXIT,
                     O_EPS_OMEGA, O_EPS_T, O_T0, RUNNING)
from .rigid import UPLIFT_RTOL, overturned, passed_alpha, track_rotation

from .layout import (F_LIFT_OFF, F_MU_K, F_MU_S, LIFT_OFF_HOLD,  # noqa: E402,F401
                     LIFT_OFF_STOP, N_PAR_FLEXIBLE_FRICTION as N_PAR)
N_EVENTS = 8
# event ids in full contact (REST, SLIDE)
C_UPLIFT = 0        # REST: uplift test of 3.3, either corner; SLIDE: a corner lifts while slipping
C_SLIP_STICK = 1    # REST: slip onset mu_s N - |F|; SLIDE: stick sigma d'
C_U_MAX = 2         # extrema of u (observers)
C_U_MIN = 3
C_FLIGHT = 4        # G = g + a_v reaches 0
# event ids while rocking (ROCK, SLIDE_ROCK)
R_IMPACT = 0        # s theta reaches 0
R_OVERTURN = 1      # s theta reaches theta_over
R_SLIP_STICK = 2    # ROCK: slip onset; SLIDE_ROCK: stick sigma d'
R_LIFT_OFF = 3      # N reaches 0 (or, held unloaded, N back above N_RELOAD)
R_PEAK = 4          # s theta' reaches 0 (observer)
R_PASS_ALPHA = 5    # s theta passes alpha (observer)
R_U_MAX = 6         # extrema of u (observers)
R_U_MIN = 7
SLIP_ATOL = 1e-9     # consistent slip start: sigma d'' > -SLIP_ATOL g
N_LIFT = 1e-6        # N below N_LIFT times the weight at slip onset: lift-off
N_RELOAD = 2e-6      # a held lift-off ends when N exceeds N_RELOAD times it


@jit
def elastic(y, par):
    """Column force per unit mass, -(w^2 u + 2 zeta w u')."""
    wn = par[F_WN]
    return -wn * wn * y[0] - 2.0 * par[F_ZETA] * wn * y[1]


@jit
def rows(t, y, s, par, hdr, smp):
    """Terms shared by the stick and slip solves at pivot s."""
    ag, av = ground(t, hdr, smp)
    G = par[F_G] + av
    u = y[0]
    du = y[1]
    dth = y[3]
    H = par[F_H]
    mb = par[F_MB]
    r = u - s * par[F_B]
    c = math.cos(y[2])
    sn = math.sin(y[2])
    X, Y, Xb, Yb = positions(r, c, sn, s, par)
    Xc = X + mb * Xb
    Yc = Y + mb * Yb
    fu = elastic(y, par) + r * dth * dth + G * sn - ag * c
    ft = G * Xc - ag * Yc - 2.0 * r * dth * du
    m22 = r * r + base_inertia(par) + H * H
    # N without the acceleration terms
    n0 = (1.0 + mb) * G - 2.0 * c * dth * du - Yc * dth * dth
    # d row without F and the acceleration terms
    fd = -(1.0 + mb) * ag + Xc * dth * dth + 2.0 * sn * dth * du
    return ag, G, c, sn, Xc, Yc, fu, ft, m22, n0, fd


@jit
def stick_rock(t, y, s, par, hdr, smp):
    """(u'', theta'', F, N) per unit mass, rocking on s without slip."""
    ag, G, c, sn, Xc, Yc, fu, ft, m22, n0, fd = rows(t, y, s, par, hdr, smp)
    H = par[F_H]
    det = m22 - H * H
    udd = (m22 * fu - H * ft) / det
    tdd = (ft - H * fu) / det
    F = c * udd + Yc * tdd - fd
    N = n0 - sn * udd - Xc * tdd
    return udd, tdd, F, N


@jit
def slip_rock(t, y, s, sigma, par, hdr, smp):
    """(u'', theta'', d'', N) per unit mass, rocking on s and slipping
    toward sigma with F = -mu_k sigma N (Cramer's rule on the 3x3)."""
    return slip_rock_k(t, y, s, par[F_MU_K] * sigma, par, hdr, smp)


@jit
def slip_rock_k(t, y, s, k, par, hdr, smp):
    """``slip_rock`` with F = -k N (k = 0: the frictionless pivot)."""
    ag, G, c, sn, Xc, Yc, fu, ft, m22, n0, fd = rows(t, y, s, par, hdr, smp)
    H = par[F_H]
    a31 = c - k * sn
    a32 = Yc - k * Xc
    a33 = 1.0 + par[F_MB]
    b3 = fd - k * n0
    c1 = m22 * a33 - Yc * a32
    c3 = H * a32 - m22 * a31
    det = c1 - H * (H * a33 - Yc * a31) + c * c3
    udd = (fu * c1 - H * (ft * a33 - Yc * b3) + c * (ft * a32 - m22 * b3)) / det
    tdd = (fu * (Yc * a31 - H * a33) + ft * (a33 - c * a31)
           + b3 * (H * c - Yc)) / det
    dd = (fu * c3 + ft * (H * a31 - a32) + b3 * (m22 - H * H)) / det
    N = n0 - sn * udd - Xc * tdd
    return udd, tdd, dd, N


@jit
def contact_stick(t, y, par, hdr, smp):
    """(u'', F, N) per unit mass in full contact without slip."""
    ag, av = ground(t, hdr, smp)
    mb = par[F_MB]
    fe = elastic(y, par)
    return fe - ag, fe + mb * ag, (1.0 + mb) * (par[F_G] + av)


@jit
def contact_slip(t, y, sigma, par, hdr, smp):
    """(u'', d'', N) per unit mass in full contact, slipping toward sigma."""
    ag, av = ground(t, hdr, smp)
    mb = par[F_MB]
    fe = elastic(y, par)
    N = (1.0 + mb) * (par[F_G] + av)
    dd = (-par[F_MU_K] * sigma * N - fe) / mb - ag
    return fe - ag - dd, dd, N


@jit
def rhs(t, y, par, disc, hdr, smp, out):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    sig = disc[D_SLIP_DIR]
    if mode == MODE_ROCK:
        udd, tdd, _F, _N = stick_rock(t, y, s, par, hdr, smp)
        dd = 0.0
    elif mode == MODE_SLIDE_ROCK:
        udd, tdd, dd, _N = slip_rock(t, y, s, sig, par, hdr, smp)
    elif mode == MODE_SLIDE:
        udd, dd, _N = contact_slip(t, y, sig, par, hdr, smp)
        tdd = 0.0
    else:
        udd, _F, _N = contact_stick(t, y, par, hdr, smp)
        tdd = 0.0
        dd = 0.0
    out[0] = y[1]
    out[1] = udd
    out[2] = y[3]
    out[3] = tdd
    out[4] = y[5]
    out[5] = dd


@jit
def slide_uplift_margin(t, y, sigma, par, hdr, smp):
    """min over s of -s theta'' of slip-rocking from full contact: the body
    lifts off a corner while slipping when it reaches 0."""
    _u, tp, _d, _N = slip_rock(t, y, 1, sigma, par, hdr, smp)
    _u, tm, _d, _N = slip_rock(t, y, -1, sigma, par, hdr, smp)
    return min(-tp, tm)


@jit
def normal_margins(t, y, s, par, hdr, smp):
    """(A, nF) on pivot s: A = N of the frictionless pivot (F = 0), which
    has the sign of the free pivot's normal acceleration into the ground
    (> 0: pressed; flight is consistent iff A <= 0), and nF = dN/dF with
    the normal constraint kept.  With W the pivot's contact-space inverse
    inertia (positive definite), A = A_W / w_nn and nF = -w_tn / w_nn, so
    the slip toward sigma (F = -mu_k sigma N) has N = A / D(sigma) with
    D(sigma) = 1 + mu_k sigma nF = (w_nn - mu_k sigma w_tn) / w_nn: the
    A and D of kernels/friction.py (its docstring's proof holds for any
    positive definite W)."""
    _ag, _G, c, sn, Xc, Yc, _fu, _ft, m22, _n0, _fd = rows(t, y, s, par,
                                                             hdr, smp)
    _u, _t, _d, A = slip_rock_k(t, y, s, 0.0, par, hdr, smp)
    zu, zt, _zd, det = slip_column(c, Yc, m22, par)
    return A, -(sn * zu + Xc * zt) / det


# outcomes of pick_rocking
PICK_ROCK = 0
PICK_SLIP = 1
PICK_FLIGHT = 2
PICK_JAM = 3
# disc[D_AUX] in SLIDE_ROCK: a slip continued at zero slip speed (``stick``)
CREEP = 2


@jit
def pick_rocking(t, y, s, par, hdr, smp, allow_stick):
    """Contact mode of pivot s at zero slip velocity (kernels/friction.py's
    rule, by the signs of A and D alone): stick (if allowed), the slip
    toward sigma1 = -sgn F_s (consistent iff D(sigma1) > 0 and A >= 0),
    flight (A <= 0; with lift_off "hold" the held frictionless pivot,
    whose N = A is then <= 0), the slip toward -sigma1 (A > 0, so D > 0),
    else a jam (only rounding at these boundaries leaves none).  Returns
    (PICK_*, sigma)."""
    _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
    if allow_stick and N >= 0.0 and abs(F) <= par[F_MU_S] * N:
        return PICK_ROCK, 0
    mu_k = par[F_MU_K]
    A, nF = normal_margins(t, y, s, par, hdr, smp)
    sig1 = -1 if F > 0.0 else 1
    D1 = 1.0 + mu_k * sig1 * nF
    if D1 > 0.0 and A >= 0.0:
        return PICK_SLIP, sig1
    if A <= 0.0:
        # before the slip toward -sigma1: with A <= 0 that slip is
        # consistent only with D(-sigma1) < 0 (N = A / D >= 0), Painleve's
        # non-uniqueness; the flight, also consistent, is taken, as at a
        # Painleve slip onset (taking the slip looped slip/stick at one
        # instant: fuzz flexible_friction:2026:110)
        return PICK_FLIGHT, 0
    D2 = 1.0 - mu_k * sig1 * nF
    if D2 > 0.0 and (abs(F) + mu_k * N) <= 0.0:
        return PICK_SLIP, -sig1
    return PICK_JAM, 0


@jit
def stop_slip(t, y, s, par, met):
    """Tangential impact without collision at the slipping pivot s
    (Painleve's dynamic jam, kernels/friction.py): a plastic horizontal
    impulse at the pivot stops the slip, q'+ = q'- + M^-1 e_d lambda with
    d'+ = 0, the kinetic-metric projection onto d' = 0 (the normal impulse
    is the constraint's; it only dissipates)."""
    before = kinetic(y, s, par)
    c, yc, m22 = mass_entries(y, s, par)
    zu, zt, zd, det = slip_column(c, yc, m22, par)
    lam = -y[5] * det / zd
    y[1] += zu / det * lam
    y[3] += zt / det * lam
    y[5] = 0.0
    check_energy(before, kinetic(y, s, par), met)


@jit
def creep_margin(t, y, s, sig, dd, par, hdr, smp):
    """Stick event of a slip continued at zero slip speed (D_AUX = CREEP,
    ``stick``): > 0 while sigma d' > 0 or stick is still inadmissible with
    the stick force against sigma (then sigma d'' >= 0 exactly, so a
    sigma d' below 0 is rounding; physics.md 4.5), as kernels/friction.py."""
    _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
    v = sig * y[5]
    if (-1 if F > 0.0 else 1) == sig:
        ex = abs(F) - par[F_MU_S] * N
        if ex > v:
            return ex, 0.0, True
    return v, sig * dd, True


@jit
def event(k, t, y, par, disc, hdr, smp):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    sig = disc[D_SLIP_DIR]
    if mode == MODE_REST or mode == MODE_SLIDE:
        if k == C_FLIGHT:
            _ag, _dag, av, dav = ground_rates(t, hdr, smp)
            return par[F_G] + av, dav, True
        if k == C_U_MAX or k == C_U_MIN:
            sg = 1.0 if k == C_U_MAX else -1.0
            if mode == MODE_REST:
                udd, _F, _N = contact_stick(t, y, par, hdr, smp)
            else:
                udd, _dd, _N = contact_slip(t, y, sig, par, hdr, smp)
            return sg * y[1], sg * udd, False
        if mode == MODE_REST:
            if k == C_UPLIFT:
                gp, gdp = uplift_margin(t, y, 1, par, hdr, smp)
                gm, gdm = uplift_margin(t, y, -1, par, hdr, smp)
                if gp <= gm:
                    return gp, gdp, True
                return gm, gdm, True
            if k == C_SLIP_STICK:
                ag, dag, av, dav = ground_rates(t, hdr, smp)
                mb = par[F_MB]
                wn = par[F_WN]
                fe = elastic(y, par)
                F = fe + mb * ag
                udd = fe - ag
                dF = -wn * wn * y[1] - 2.0 * par[F_ZETA] * wn * udd + mb * dag
                g = par[F_MU_S] * (1.0 + mb) * (par[F_G] + av) - abs(F)
                gd = par[F_MU_S] * (1.0 + mb) * dav - (dF if F >= 0.0 else -dF)
                return g, gd, True
            return np.inf, 0.0, False
        if k == C_UPLIFT:
            return slide_uplift_margin(t, y, sig, par, hdr, smp), 0.0, True
        if k == C_SLIP_STICK:
            _udd, dd, _N = contact_slip(t, y, sig, par, hdr, smp)
            return sig * y[5], sig * dd, True
        return np.inf, 0.0, False
    if k == R_IMPACT:
        return s * y[2], s * y[3], True
    if k == R_OVERTURN:
        return par[F_THETA_OVER] - s * y[2], -s * y[3], True
    if k == R_PASS_ALPHA:
        return par[F_ALPHA] - s * y[2], -s * y[3], False
    if mode == MODE_ROCK:
        udd, tdd, F, N = stick_rock(t, y, s, par, hdr, smp)
        if k == R_SLIP_STICK:
            # no rate: F and N depend on a_g and the accelerations
            return par[F_MU_S] * N - abs(F), 0.0, True
    else:
        udd, tdd, dd, N = slip_rock(t, y, s, sig, par, hdr, smp)
        if k == R_SLIP_STICK:
            if sig == 0:
                return np.inf, 0.0, True
            if disc[D_AUX] == CREEP:
                return creep_margin(t, y, s, sig, dd, par, hdr, smp)
            return sig * y[5], sig * dd, True
        if k == R_LIFT_OFF and sig == 0:
            # unloaded: contact returns; the band between N_LIFT and
            # N_RELOAD keeps lift-off and reload from ping-ponging
            return N_RELOAD * (1.0 + par[F_MB]) * par[F_G] - N, 0.0, True
        if k == R_LIFT_OFF:
            # N = A / D(sigma) reaches 0 where A does while D > 0.  Where A
            # and D vanish together (the singular point of the slip
            # equations: Genot & Brogliato; Champneys & Varkonyi's "dynamic
            # jam") N stays bounded and never reaches 0, while the
            # accelerations grow as 1 / D and the step underflows
            # (failed:step-underflow, fuzz flexible_friction:2027:331).  The
            # event also fires once both are inside the lift-off band, |A|
            # <= N_LIFT times the weight and |D| <= N_LIFT (D = 1 without
            # friction; not A < 0 and D < 0 alone, where the slip with
            # N > 0 is consistent and goes on, as it did before): there
            # ``transition`` sees A <= N_LIFT W, so the
            # pivot lifts off (the continuation the kernel takes wherever
            # both lift-off and a slip with A < 0, D < 0 are consistent,
            # ``pick_rocking``).  Outside that band the event is N, as
            # before (the same value, so the same roots).
            A, nF = normal_margins(t, y, s, par, hdr, smp)
            D = 1.0 + par[F_MU_K] * sig * nF
            jam = max(abs(A) - N_LIFT * (1.0 + par[F_MB]) * par[F_G],
                      abs(D) - N_LIFT)
            if jam > 0.0:
                return N, 0.0, True
            return min(N, jam), 0.0, True
    if k == R_LIFT_OFF:
        return N, 0.0, True
    if k == R_PEAK:
        return s * y[3], s * tdd, False
    sg = 1.0 if k == R_U_MAX else -1.0
    return sg * y[1], sg * udd, False


@jit
def static_margin(t, y, par, disc, hdr, smp):
    return 1.0   # no static phase: the column vibrates in full contact


@jit
def set_mode(disc, mode, s, sigma):
    disc[D_MODE] = mode
    disc[D_STATIC] = 0
    disc[D_PIVOT] = s
    disc[D_SLIP_DIR] = sigma
    disc[D_AUX] = 0


@jit
def lift(t, y, s, met, log, cnt):
    if np.isnan(met[M_T_UPLIFT]):
        met[M_T_UPLIFT] = t
    log_event(log, cnt, t, EV_UPLIFT, y[1], y[1], 0.0, s)


@jit
def lift_off(t, y, s, par, disc, met, log, cnt):
    """N reached 0 while rocking: stop (FLIGHT) or hold the pivot down and
    let the base slip without friction until N > 0 again (sigma = 0)."""
    if par[F_LIFT_OFF] != LIFT_OFF_HOLD:
        log_event(log, cnt, t, EV_FLIGHT, y[3], y[3], y[2], s)
        return FLIGHT
    log_event(log, cnt, t, EV_LIFT_OFF_HELD, y[3], y[3], y[2], s)
    met[M_N_LIFT_OFF] += 1
    set_mode(disc, MODE_SLIDE_ROCK, s, 0)
    return RUNNING


@jit
def start_slip_rock(t, y, s, F, par, disc, hdr, smp, met, log, cnt,
                    may_lift=True):
    """Stick on pivot s is no longer admissible (friction F required):
    slip-rock in the direction whose solve is consistent, N > 0 and
    sigma d'' > 0 (physics.md 4.2), trying sigma = -sgn(F) first.  With
    mu_k = mu_s, d'' is zero at slip onset up to round-off, hence the
    tolerance.  Friction saturating because N vanishes is lift-off."""
    _u, _t, _F, N = stick_rock(t, y, s, par, hdr, smp)
    if may_lift and N < N_LIFT * (1.0 + par[F_MB]) * par[F_G]:
        return lift_off(t, y, s, par, disc, met, log, cnt)
    sigma = -1 if F > 0.0 else 1
    tol = SLIP_ATOL * par[F_G]
    _A, nF = normal_margins(t, y, s, par, hdr, smp)
    for _ in range(2):
        _u, _t, dd, N = slip_rock(t, y, s, sigma, par, hdr, smp)
        # D(sigma) > 0 as well: with D < 0 and A < 0, N = A / D > 0 and
        # d'' = 0 at the onset pass the test, but the slip reverses its
        # own friction at once (Painleve; module docstring of friction.py)
        if N > 0.0 and sigma * dd > -tol and (
                1.0 + par[F_MU_K] * sigma * nF > 0.0):
            met[M_T_SLIP_START] = t
            set_mode(disc, MODE_SLIDE_ROCK, s, sigma)
            log_event(log, cnt, t, EV_SLIP, y[3], y[3], y[2], sigma)
            return RUNNING
        sigma = -sigma
    # neither slip passes the computed test: the pick by the signs of A
    # and D (a Painleve slip onset lifts off, physics.md 4.6)
    code, sig = pick_rocking(t, y, s, par, hdr, smp, False)
    return apply_pick(code, sig, t, y, s, par, disc, met, log, cnt)


@jit
def apply_pick(code, sig, t, y, s, par, disc, met, log, cnt):
    """Enter the mode chosen by pick_rocking on pivot s (flight: lift_off,
    which stops or holds the pivot; a jam, left only by rounding, ends
    the run FAIL_INCONSISTENT)."""
    if code == PICK_ROCK:
        set_mode(disc, MODE_ROCK, s, 0)
        return RUNNING
    if code == PICK_SLIP:
        met[M_T_SLIP_START] = t
        set_mode(disc, MODE_SLIDE_ROCK, s, sig)
        log_event(log, cnt, t, EV_SLIP, y[3], y[3], y[2], sig)
        return RUNNING
    if code == PICK_FLIGHT:
        return lift_off(t, y, s, par, disc, met, log, cnt)
    return FAIL_INCONSISTENT


@jit
def tangential_impact(t, y, s, par, disc, hdr, smp, met, log, cnt):
    """The slip on pivot s has no consistent continuation with the pivot
    pressed (A > 0, D(sigma) <= 0: Painleve): stop it by a tangential
    impact (``stop_slip``, logged as a stick), then pick the mode at zero
    slip velocity, where one is always consistent."""
    pre = y[3]
    stop_slip(t, y, s, par, met)
    met[M_N_STICK_SLIP] += 1
    log_event(log, cnt, t, EV_STICK, pre, y[3], y[2], s)
    code, sig = pick_rocking(t, y, s, par, hdr, smp, True)
    return apply_pick(code, sig, t, y, s, par, disc, met, log, cnt)


@jit
def slip_or_slide_rock(t, y, s, sigma, par, disc, hdr, smp, met, log, cnt):
    """Start slipping toward sigma from full contact: slide-rock on s if
    the slip-rock solve lifts that corner, else plain sliding."""
    met[M_N_STICK_SLIP] += 1
    log_event(log, cnt, t, EV_SLIP, y[5], y[5], 0.0, sigma)
    if s != 0:
        _u, tdd, _d, N = slip_rock(t, y, s, sigma, par, hdr, smp)
        if s * tdd > 0.0 and N > 0.0:
            set_mode(disc, MODE_SLIDE_ROCK, s, sigma)
            lift(t, y, s, met, log, cnt)
            return RUNNING
    set_mode(disc, MODE_SLIDE, 1, sigma)
    return RUNNING


@jit
def start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt):
    """theta = theta' = 0 (rest, stick or just after an impact): choose REST,
    SLIDE, ROCK or SLIDE_ROCK by the initiation criteria (physics.md 3.3,
    4.2 and 4.4)."""
    ag, av = ground(t, hdr, smp)
    G = par[F_G] + av
    if G <= 0.0:
        log_event(log, cnt, t, EV_FLIGHT, 0.0, 0.0, 0.0, 0)
        return FLIGHT
    y[2] = 0.0
    y[3] = 0.0
    mu_s = par[F_MU_S]
    if y[5] != 0.0:
        sigma = 1 if y[5] > 0.0 else -1
        _u, tp, _d, Np = slip_rock(t, y, 1, sigma, par, hdr, smp)
        _u, tm, _d, Nm = slip_rock(t, y, -1, sigma, par, hdr, smp)
        if tp > 0.0 and tp >= -tm and Np > 0.0:
            set_mode(disc, MODE_SLIDE_ROCK, 1, sigma)
            lift(t, y, 1, met, log, cnt)
        elif tm < 0.0 and Nm > 0.0:
            set_mode(disc, MODE_SLIDE_ROCK, -1, sigma)
            lift(t, y, -1, met, log, cnt)
        else:
            set_mode(disc, MODE_SLIDE, 1, sigma)
        return RUNNING
    gp, _ = uplift_margin(t, y, 1, par, hdr, smp)
    gm, _ = uplift_margin(t, y, -1, par, hdr, smp)
    if min(gp, gm) <= 0.0:
        return uplift_from_rest(t, y, 1 if gp <= gm else -1, par, disc, hdr,
                                smp, met, log, cnt)
    _udd, F, N = contact_stick(t, y, par, hdr, smp)
    if abs(F) > mu_s * N * (1.0 + UPLIFT_RTOL):
        return slip_or_slide_rock(t, y, 0, -1 if F > 0.0 else 1, par, disc,
                                  hdr, smp, met, log, cnt)
    set_mode(disc, MODE_REST, 1, 0)
    return RUNNING


@jit
def uplift_from_rest(t, y, s, par, disc, hdr, smp, met, log, cnt):
    """The uplift test of 3.3 is met on corner s: rock if stick holds,
    else slip (and slide-rock if that lifts the corner)."""
    _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
    if abs(F) <= par[F_MU_S] * N:
        set_mode(disc, MODE_ROCK, s, 0)
        lift(t, y, s, met, log, cnt)
        return RUNNING
    return slip_or_slide_rock(t, y, s, -1 if F > 0.0 else 1, par, disc, hdr,
                              smp, met, log, cnt)


@jit
def stick(t, y, par, disc, hdr, smp, met, log, cnt):
    """Slip velocity reached zero: stick if admissible, else reverse
    (physics.md 4.5)."""
    y[5] = 0.0
    met[M_N_STICK_SLIP] += 1
    s = disc[D_PIVOT]
    if disc[D_MODE] == MODE_SLIDE:
        log_event(log, cnt, t, EV_STICK, 0.0, 0.0, 0.0, 0)
        return start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
    log_event(log, cnt, t, EV_STICK, y[3], y[3], y[2], s)
    if abs(F) <= par[F_MU_S] * N:
        set_mode(disc, MODE_ROCK, s, 0)
        return RUNNING
    sig_old = disc[D_SLIP_DIR]
    code, sig = pick_rocking(t, y, s, par, hdr, smp, False)
    if code == PICK_SLIP and sig == sig_old and sig == (-1 if F > 0.0 else 1):
        # stick inadmissible and the slip goes on the same way, toward
        # sigma1 = -sgn F_s: its sigma d'' >= 0 (the pick's proof), so
        # sigma d' reached 0 by rounding or an integration error below the
        # tolerance; the slip continues until stick is admissible
        # (creep_margin; physics.md 4.5), instead of ending again at once
        set_mode(disc, MODE_SLIDE_ROCK, s, sig)
        disc[D_AUX] = CREEP
        return RUNNING
    if t == met[M_T_SLIP_START]:
        # the slip just started cannot develop and stick cannot hold
        return apply_pick(code, sig, t, y, s, par, disc, met, log, cnt)
    return start_slip_rock(t, y, s, F, par, disc, hdr, smp, met, log, cnt)


@jit
def reload(t, y, par, disc, hdr, smp, met, log, cnt):
    """N back to 0+ after a held lift-off: slip on if the base moves, else
    stick if admissible."""
    s = disc[D_PIVOT]
    log_event(log, cnt, t, EV_RELOAD, y[3], y[3], y[2], s)
    if y[5] != 0.0:
        sig = 1 if y[5] > 0.0 else -1
        _u, _t, _d, N = slip_rock(t, y, s, sig, par, hdr, smp)
        if N > 0.0:
            set_mode(disc, MODE_SLIDE_ROCK, s, sig)
            return RUNNING
        # the pressed pivot (A > 0: it reloaded) cannot slip on with N > 0
        # (D(sigma) < 0, Painleve at a slip speed)
        return tangential_impact(t, y, s, par, disc, hdr, smp, met, log,
                                 cnt)
    _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
    if abs(F) <= par[F_MU_S] * N:
        set_mode(disc, MODE_ROCK, s, 0)
        return RUNNING
    # the unloaded slip solve has N > 0 here: no second lift-off at once
    return start_slip_rock(t, y, s, F, par, disc, hdr, smp, met, log, cnt,
                           False)


@jit
def kinetic(y, s, par):
    """Kinetic energy per unit mass, q'^T M q' / 2 with the mass matrix of
    (u, theta, d) on pivot s (physics.md 4.4)."""
    c, Yc, m22 = mass_entries(y, s, par)
    du = y[1]
    dth = y[3]
    dd = y[5]
    return (0.5 * (du * du + m22 * dth * dth + (1.0 + par[F_MB]) * dd * dd)
            + par[F_H] * du * dth + c * du * dd + Yc * dth * dd)


@jit
def mass_entries(y, s, par):
    """(cos theta, Y_c, m22) of the mass matrix of (u, theta, d) on pivot s,
    M = [[1, H, c], [H, m22, Y_c], [c, Y_c, 1 + m_b]] (physics.md 4.4)."""
    H = par[F_H]
    r = y[0] - s * par[F_B]
    c = math.cos(y[2])
    _X, Y, _Xb, Yb = positions(r, c, math.sin(y[2]), s, par)
    return c, Y + par[F_MB] * Yb, r * r + base_inertia(par) + H * H


@jit
def slip_column(c, Yc, m22, par):
    """M^-1 e_d = (zu, zt, zd) / det, the response of (u, theta, d) to a unit
    horizontal impulse at the pivot (e_d: the slip row of M)."""
    H = par[F_H]
    zu = H * Yc - m22 * c
    zt = H * c - Yc
    zd = m22 - H * H
    return zu, zt, zd, c * zu + Yc * zt + (1.0 + par[F_MB]) * zd


@jit
def rest_speed(par, opt):
    """Slip speed below which a chatter impact leaves the base at rest:
    eps_omega times the largest distance of the mass or the base CM from
    a pivot, i.e. no point of the body rotating at eps_omega about the
    pivot moves faster (the rest rule's threshold, applied to the
    tangential velocity of the contact)."""
    B = par[F_B]
    H = par[F_H]
    hb = par[F_HB]
    return opt[O_EPS_OMEGA] * math.sqrt(B * B + max(H * H, hb * hb))


@jit
def impact(t, y, par, disc, hdr, smp, met, log, cnt, rest_below=0.0):
    """theta -> 0: full contact, theta'+ = 0, d'+ = d'- + h_b theta'-,
    u'+ = u'- + (H - h_b) theta'-, then the initiation test.

    The frictionless plastic impact keeps the base's and the mass's
    horizontal momenta, d' + h_b theta' and d' + u' + H theta' (no
    horizontal impulse, none on u).  physics.md 4.4 writes u'+ = u'- +
    H theta'-, which counts the base's share twice and adds energy when
    h_b != 0 (0.920 -> 0.981 J/kg at H = 2.3, h_b = 0.2, m_b = 0.1); both
    agree at the default h_b = 0.

    A chatter impact (physics.md 7: |theta'-| < eps_omega, or within eps_t
    of the previous impact; ``transition`` then passes ``rest_below`` =
    ``rest_speed``, else 0) that leaves a slip slower than ``rest_below``
    rests the base tangentially too.  Without this rule a base at rest
    that the impact gives d' = h_b theta'- ~ 1e-15 starts slide-rocking:
    the slip solve applies the saturated friction -mu_k sigma N where
    stick needs far less, and its moment lifts a corner that stick-rocking
    (admissible at once) pulls back; each cycle's impact restarts the
    slip, at one instant (fuzz flexible_friction:2026:150).  The slip is
    stopped by a plastic horizontal impulse on the base: in full contact,
    with M = [[1, 1], [1, 1 + m_b]] on (u', d'), the kinetic-metric
    projection onto d' = 0 is u'+ = u' + d', d'+ = 0 (the mass keeps its
    horizontal velocity u' + d'); it removes m_b d'^2 / 2, so energy never
    rises.  The initiation test then sees d' = 0: the uplift test of 3.3
    and |F| <= mu_s N pick a contact mode consistent with the contact
    forces."""
    s = disc[D_PIVOT]
    pre = y[3]
    met[M_IMPACTS] += 1
    met[M_T_LAST_IMPACT] = t
    t_before = kinetic(y, s, par)
    y[1] = y[1] + (par[F_H] - par[F_HB]) * pre
    y[5] = y[5] + par[F_HB] * pre
    y[2] = 0.0
    y[3] = 0.0
    if y[5] != 0.0 and abs(y[5]) < rest_below:
        y[1] += y[5]
        y[5] = 0.0
    check_energy(t_before, kinetic(y, s, par), met)
    log_event(log, cnt, t, EV_IMPACT, pre, 0.0, 0.0, -s)
    st = start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    if rest_below > 0.0 and disc[D_MODE] == MODE_REST:
        log_event(log, cnt, t, EV_REST, pre, 0.0, 0.0, 0)
    return st


@jit
def never_left(t, y, disc, met, log, cnt):
    """An impact with theta'- = 0 exactly: the rocking phase ended where it
    began, so the body never left the ground (kernels/flexible.py's rule of
    the same name).  The uplift was decided at a zero of the uplift margin
    that the margin touches and leaves upward (u at its extremum, the
    margin's minimum at the rounding level): there the margin reads <= 0
    while the rocking equation's s theta'' turns the body back within the
    first step.  Handing this "impact" to the impact map and its initiation
    test repeats the same uplift and landing at one instant for ever
    (failed:transition-loop, fuzz flexible_friction:2027:74, :108, :240,
    :261, :451).  Full contact instead, the uplift undone (its log entry and
    first-uplift time if made at this instant) and no initiation test here:
    REST (or SLIDE on toward sgn d' if the base moves), whose own events take
    the body up or into a slip as soon as the margins are crossed over a
    step.  Nothing changes in the state but theta = 0, which was within the
    root tolerance: no energy is added or removed."""
    y[2] = 0.0
    y[3] = 0.0
    if y[5] != 0.0:
        set_mode(disc, MODE_SLIDE, 1, 1 if y[5] > 0.0 else -1)
    else:
        set_mode(disc, MODE_REST, 1, 0)
    undo_uplift(t, met, log, cnt)
    return RUNNING


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    rocking = mode == MODE_ROCK or mode == MODE_SLIDE_ROCK
    if not rocking:
        if k == C_U_MAX or k == C_U_MIN:
            track_u(y[0], met)
            return RUNNING
        book_time(t, disc, met)
        track_slide(y[4], met)
        if k == C_FLIGHT:
            log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], 0.0, 0)
            return FLIGHT
        if mode == MODE_SLIDE:
            if k == C_SLIP_STICK:
                return stick(t, y, par, disc, hdr, smp, met, log, cnt)
            # the slip-rock solve lifts a corner: follow it (the event,
            # not a re-test at the root, decides)
            sig = disc[D_SLIP_DIR]
            _u, tp, _d, _N = slip_rock(t, y, 1, sig, par, hdr, smp)
            _u, tm, _d, _N = slip_rock(t, y, -1, sig, par, hdr, smp)
            sp = 1 if tp >= -tm else -1
            set_mode(disc, MODE_SLIDE_ROCK, sp, sig)
            lift(t, y, sp, met, log, cnt)
            return RUNNING
        if k == C_UPLIFT:
            gp, _ = uplift_margin(t, y, 1, par, hdr, smp)
            gm, _ = uplift_margin(t, y, -1, par, hdr, smp)
            return uplift_from_rest(t, y, 1 if gp <= gm else -1, par, disc,
                                    hdr, smp, met, log, cnt)
        _udd, F, _N = contact_stick(t, y, par, hdr, smp)      # C_SLIP_STICK in REST
        return slip_or_slide_rock(t, y, 0, -1 if F > 0.0 else 1, par, disc,
                                  hdr, smp, met, log, cnt)
    if k == R_PEAK:
        track_rotation(y[2], met)
        return RUNNING
    if k == R_PASS_ALPHA:
        passed_alpha(t, y[2], y[3], s, met, log, cnt)
        return RUNNING
    if k == R_U_MAX or k == R_U_MIN:
        track_u(y[0], met)
        return RUNNING
    book_time(t, disc, met)
    track_slide(y[4], met)
    # the state at an event counts (a lift-off with lift_off "stop" ends
    # the run here, after the last step's state)
    track_rotation(y[2], met)
    if k == R_LIFT_OFF:
        if disc[D_SLIP_DIR] == 0 and mode == MODE_SLIDE_ROCK:
            return reload(t, y, par, disc, hdr, smp, met, log, cnt)
        if mode == MODE_SLIDE_ROCK:
            A, _nF = normal_margins(t, y, s, par, hdr, smp)
            if A > N_LIFT * (1.0 + par[F_MB]) * par[F_G]:
                # N = A / D changed sign through D = 0 with the pivot
                # pressed: Painleve's dynamic jam, not a lift-off
                return tangential_impact(t, y, s, par, disc, hdr, smp, met,
                                         log, cnt)
        return lift_off(t, y, s, par, disc, met, log, cnt)
    if k == R_SLIP_STICK:
        if mode == MODE_ROCK:
            _u, _t, F, _N = stick_rock(t, y, s, par, hdr, smp)
            met[M_N_STICK_SLIP] += 1
            return start_slip_rock(t, y, s, F, par, disc, hdr, smp, met,
                                   log, cnt)
        return stick(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == R_OVERTURN:
        return overturned(t, y[2], y[3], s, met, log, cnt)
    if y[3] == 0.0:
        return never_left(t, y, disc, met, log, cnt)
    chatter = (abs(y[3]) < opt[O_EPS_OMEGA]
               or t - met[M_T_LAST_IMPACT] < opt[O_EPS_T])
    return impact(t, y, par, disc, hdr, smp, met, log, cnt,
                  rest_speed(par, opt) if chatter else 0.0)


@jit
def settled_for_good(t, y, par, hdr):
    """Exact sufficient test in full contact without slip after the
    excitation: the column can neither lift the base (3.3) nor demand more
    friction than mu_s N (4.4) in any later free motion."""
    if not never_uplifts_again(t, y, par, hdr):
        return False
    _U, fmax = free_column_bound(y, par)
    return fmax < par[F_MU_S] * (1.0 + par[F_MB]) * par[F_G]


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    book_time(t, disc, met)
    track_slide(y[4], met)
    track_u(y[0], met)
    mode = disc[D_MODE]
    if mode == MODE_ROCK or mode == MODE_SLIDE_ROCK:
        track_rotation(y[2], met)
    if at_end or (opt[O_EARLY_EXIT] != 0.0 and mode == MODE_REST
                  and settled_for_good(t, y, par, hdr)):
        return final_status(disc, met)
    return RUNNING


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    initial_contact(t0, y[2], y[3], y[5], False, disc, met)
    track_slide(y[4], met)
    track_u(y[0], met)


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_hybrid(rhs, event, transition, static_margin,
                            after_step, N_EVENTS, y, par, disc, hdr, smp,
                            opt, t_eval, met, hist_t, hist_y, hist_d, log,
                            cnt)


@jit
def flexible_friction_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                               hist_y, hist_d, log, cnt):
    """One run of the flexible body with friction (time history, events)."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def flexible_friction_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Independent runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
