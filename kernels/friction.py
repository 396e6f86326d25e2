"""Rigid block with Coulomb friction: rest, slide, rock, slide-rock
(physics.md 4.1-4.3; Shenton 1996, Taniguchi 2002).

State ``y = (theta, theta', d, d')``: rotation [rad] and the slip d [m] of
the base relative to the ground.  Per unit mass, with the CM offset from the
pivot s, X_G = -s b cos(theta) + h sin(theta), Y_G = s b sin(theta) + h
cos(theta) (physics.md 4.3):

    a_g + d'' + Y_G theta'' - X_G theta'^2 = F
    -X_G theta'' - Y_G theta'^2          = N - G
    i_G theta''                          = -Y_G F + X_G N

Stick: d'' = 0 and F unknown; slip: F = -mu_k sigma N.  Modes: REST
(static), SLIDE (theta = 0), ROCK (stick) and SLIDE_ROCK.  No regularised
friction law: every transition is an event.

Events (g > 0 admissible; ids E_*):
  ROCK        E_IMPACT s*theta, E_OVERTURN, E_SLIP_STICK slip onset mu_s N - |F|,
              E_LIFT_OFF N, E_PEAK s*theta' (observer), E_PASS_ALPHA (obs.)
  SLIDE_ROCK  E_IMPACT, E_OVERTURN, E_SLIP_STICK stick sigma*d', E_LIFT_OFF N,
              E_PEAK, E_PASS_ALPHA
  SLIDE       E_SLIP_STICK stick sigma*d', E_LIFT_OFF flight G
  ROCK, jammed (D_AUX = 1, below): E_SLIP_STICK the jam's end, E_LIFT_OFF off
  SLIDE_ROCK continued at zero slip speed (D_AUX = 2, ``stick``):
              E_SLIP_STICK max(sigma*d', |F_s| - mu_s N_s) (``creep_margin``)

Contact mode at zero slip velocity (``pick_rocking``).  With the corner's
contact accelerations a = a0 + W (F, N) (W the positive definite inverse
mass matrix of the corner, a0 the free accelerations), the stick forces
(F_s, N_s) = -W^-1 a0 and, for a slip toward sigma (F = -mu_k sigma N),
D(sigma) = i_G + X (X + mu_k sigma Y) (= i_G (w22 - mu_k sigma w12)),
A = G - Y theta'^2 (= -a_n0, > 0: the free corner is pressed into the
ground), one finds N_slip = A i_G / D(sigma) and, for sigma1 = -sgn F_s,

    sigma1 a_t = det W (|F_s| - mu_k N_s) / D(sigma1) * i_G.

So when stick fails (|F_s| > mu_s N_s >= mu_k N_s or N_s < 0) the slip
toward sigma1 is consistent (N >= 0, slip not reversed) iff D(sigma1) > 0
and A >= 0, whatever the rounding of the computed slip acceleration (which
is 0 at the slip onset); flight (F = N = 0) is consistent iff A <= 0.  At a
slip onset from stick (N_s > 0, F_s = -sigma1 mu_s N_s), A = w12 F_s + w22
N_s = N_s (w22 - mu_s sigma1 w12) <= N_s D(sigma1) / i_G because mu_k <=
mu_s, so D(sigma1) < 0 (Painleve: mu large) implies A < 0: the block lifts
off, and that is the only consistent mode (the slip toward -sigma1 has
D = 2 i_G w22 - D(sigma1) > 0 and so N < 0).  Some mode is always
consistent at zero slip velocity: if A > 0 and D(sigma1) <= 0, then
mu_k sigma1 w12 >= w22 > 0 and w22 N_s > sigma1 w12 |F_s|, so N_s > 0 and
|F_s| < w22 N_s / (sigma1 w12) <= mu_k N_s: stick holds.  Only rounding at
these boundaries can leave none; then the pivot is held as with mu = inf (a
jam, the impulsive-limit friction of kernels/contact.py) until stick, slip
or flight is consistent again.  While slipping, N = A i_G / D reaches 0
either with A <= 0 (lift-off) or with A > 0 through D = 0 (Painleve's
dynamic jam): a tangential impact without collision then stops the slip
(Darboux-Keller / Routh from v_n = 0: the corner slips until v_t = 0, then
sticks while v_n returns to 0, so the result is the plastic stick impulse,
with P_n > 0; angular momentum about the corner is conserved).
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground, ground_rates
from .hybrid import (book_time, check_energy, final_status, init_metrics,
                     integrate_hybrid, log_event, sweep_rows)
from .layout import (D_AUX, D_MODE, D_PIVOT, D_SLIP_DIR, D_STATIC, EV_FLIGHT,
                     EV_IMPACT, EV_REST, EV_SLIP, EV_STICK, EV_UPLIFT, FLIGHT,
                     MODE_REST, MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK,
                     M_IMPACTS, M_MAX_SLIDE,
                     M_N_EVENTS, M_N_STICK_SLIP,
                     M_RESIDUAL_SLIDE, M_T_EXC_END, M_T_FINAL, M_T_LAST_IMPACT,
                     M_T_UPLIFT, N_DISC, O_EARLY_EXIT, O_EPS_OMEGA, O_EPS_T,
                     O_T0, O_T_END, RUNNING, SAFE_BOUNDED, S_ON)
from .rigid import (P_ALPHA, P_E, P_G, P_P, P_THETA_OVER, UPLIFT_RTOL,
                    bounded_after_excitation, count_peaks, initial_pivot, peak_times,
                    overturned, passed_alpha, track_rotation)

from .layout import N_PAR_FRICTION as N_PAR, Q_B, Q_H, Q_IG, Q_MU_K, Q_MU_S  # noqa: E402,F401
N_EVENTS = 6
# event ids (the same number keeps one meaning in every mode that has it)
E_IMPACT = 0        # ROCK/SLIDE_ROCK: s theta reaches 0
E_OVERTURN = 1      # ROCK/SLIDE_ROCK: s theta reaches theta_over
E_SLIP_STICK = 2    # ROCK: slip onset mu_s N - |F|; SLIDE/SLIDE_ROCK: stick sigma d'
E_LIFT_OFF = 3      # ROCK/SLIDE_ROCK: N reaches 0; SLIDE: G reaches 0 (flight)
E_PEAK = 4          # ROCK/SLIDE_ROCK: s theta' reaches 0 (observer)
E_PASS_ALPHA = 5    # ROCK/SLIDE_ROCK: s theta passes alpha (observer)


@jit
def offsets(theta, s, par):
    b = par[Q_B]
    h = par[Q_H]
    c = math.cos(theta)
    sn = math.sin(theta)
    return -s * b * c + h * sn, s * b * sn + h * c


@jit
def stick_rock(t, theta, dtheta, s, par, hdr, smp):
    """(theta'', F, N) per unit mass, rocking on s without slip."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    X, Y = offsets(theta, s, par)
    i0 = par[Q_IG] + X * X + Y * Y
    tdd = (G * X - ag * Y) / i0
    F = ag + Y * tdd - X * dtheta * dtheta
    N = G - X * tdd - Y * dtheta * dtheta
    return tdd, F, N


@jit
def stick_force_rates(t, theta, dtheta, s, par, hdr, smp):
    """(F, N, dF/dt, dN/dt) per unit mass, rocking on s without slip: with
    dX/dtheta = Y, dY/dtheta = -X and i_0 constant, the rate of theta'' is
    (G' X + G Y w - a_g' Y + a_g X w) / i_0."""
    ag, dag, av, dav = ground_rates(t, hdr, smp)
    G = par[P_G] + av
    X, Y = offsets(theta, s, par)
    w = dtheta
    i0 = par[Q_IG] + X * X + Y * Y
    tdd = (G * X - ag * Y) / i0
    t3 = (dav * X + G * Y * w - dag * Y + ag * X * w) / i0
    F = ag + Y * tdd - X * w * w
    N = G - X * tdd - Y * w * w
    dF = dag - X * w * tdd + Y * t3 - Y * w * w * w - 2.0 * X * w * tdd
    dN = dav - Y * w * tdd - X * t3 + X * w * w * w - 2.0 * Y * w * tdd
    return F, N, dF, dN


@jit
def slip_rock(t, theta, dtheta, s, sigma, par, hdr, smp):
    """(theta'', d'', N) per unit mass, rocking on s and slipping toward
    sigma with F = -mu_k sigma N."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    X, Y = offsets(theta, s, par)
    k = par[Q_MU_K] * sigma * Y + X
    tdd = k * (G - Y * dtheta * dtheta) / (par[Q_IG] + k * X)
    N = G - X * tdd - Y * dtheta * dtheta
    dd = -par[Q_MU_K] * sigma * N - ag - Y * tdd + X * dtheta * dtheta
    return tdd, dd, N


@jit
def rhs(t, y, par, disc, hdr, smp, out):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    out[0] = y[1]
    out[2] = y[3]
    if mode == MODE_ROCK:
        tdd, _F, _N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
        out[1] = tdd
        out[3] = 0.0
    elif mode == MODE_SLIDE_ROCK:
        tdd, dd, _N = slip_rock(t, y[0], y[1], s, disc[D_SLIP_DIR], par, hdr,
                                smp)
        out[1] = tdd
        out[3] = dd
    else:   # SLIDE
        ag, av = ground(t, hdr, smp)
        out[1] = 0.0
        out[3] = -ag - par[Q_MU_K] * disc[D_SLIP_DIR] * (par[P_G] + av)


@jit
def event(k, t, y, par, disc, hdr, smp):
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    sig = disc[D_SLIP_DIR]
    if mode == MODE_SLIDE:
        if k == E_SLIP_STICK:
            ag, av = ground(t, hdr, smp)
            dd = -ag - par[Q_MU_K] * sig * (par[P_G] + av)
            return sig * y[3], sig * dd, True
        if k == E_LIFT_OFF:
            _ag, _dag, av, dav = ground_rates(t, hdr, smp)
            return par[P_G] + av, dav, True
        return np.inf, 0.0, False
    if k == E_IMPACT:
        return s * y[0], s * y[1], True
    if k == E_OVERTURN:
        return par[P_THETA_OVER] - s * y[0], -s * y[1], True
    if k == E_PASS_ALPHA:
        return par[P_ALPHA] - s * y[0], -s * y[1], False
    if mode == MODE_ROCK:
        if disc[D_AUX] == 1:
            # jam (module docstring): ends when stick, the slip toward
            # sigma1 or flight becomes consistent; N is not checked
            if k == E_SLIP_STICK:
                g, _a, _b, _c = jam_margin(t, y, s, par, hdr, smp)
                return g, 0.0, True
            if k == E_LIFT_OFF:
                return np.inf, 0.0, True
        if k == E_SLIP_STICK:
            # the rate lets the driver find a dip of the cone margin between
            # two step ends (grazing); N <= 0 implies a margin <= 0, so
            # this also finds every dip of N, and E_LIFT_OFF needs no rate
            F, N, dF, dN = stick_force_rates(t, y[0], y[1], s, par, hdr, smp)
            g = par[Q_MU_S] * N - abs(F)
            dg = par[Q_MU_S] * dN - (dF if F > 0.0 else -dF)
            return g, dg, True
        tdd, _F, N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
        if k == E_LIFT_OFF:
            return N, 0.0, True
        return s * y[1], s * tdd, False      # E_PEAK
    tdd, dd, N = slip_rock(t, y[0], y[1], s, sig, par, hdr, smp)
    if k == E_SLIP_STICK:
        if disc[D_AUX] == 2:
            return creep_margin(t, y, s, sig, dd, par, hdr, smp)
        if y[3] == 0.0:
            # a slip just picked from zero speed runs forward: sigma a_t =
            # det W (|F_s| - mu_k N_s) i_G / D >= 0 exactly (module
            # docstring); the computed sigma d'' is 0 up to rounding there,
            # and a negative rounding would end the slip at once
            return 0.0, max(sig * dd, 0.0), True
        return sig * y[3], sig * dd, True
    if k == E_LIFT_OFF:
        # N = A i_G / D: its rate from A' = G' + X w^3 - 2 Y w theta'' and
        # D' = w (2 X Y + mu_k sigma (Y^2 - X^2)) (grazing, as in ROCK)
        _ag, _dag, av, dav = ground_rates(t, hdr, smp)
        X, Y = offsets(y[0], s, par)
        w = y[1]
        A = par[P_G] + av - Y * w * w
        D = par[Q_IG] + X * (X + par[Q_MU_K] * sig * Y)
        dA = dav + X * w * w * w - 2.0 * Y * w * tdd
        dD = w * (2.0 * X * Y + par[Q_MU_K] * sig * (Y * Y - X * X))
        return N, par[Q_IG] * (dA * D - A * dD) / (D * D), True
    return s * y[1], s * tdd, False          # E_PEAK


@jit
def creep_margin(t, y, s, sig, dd, par, hdr, smp):
    """Stick event of a slip continued at zero slip speed (D_AUX = 2, see
    ``stick``): > 0 while the slip toward sigma goes on, i.e. while it moves
    forward (sigma d' > 0) or stick is still inadmissible with the stick
    friction force pointing against sigma (|F_s| - mu_s N_s > 0, sigma =
    -sgn F_s): then sigma d'' >= 0 exactly (module docstring), so a sigma d'
    below 0 is rounding and must not end the slip (physics.md 4.5: accept
    stick iff |F| <= mu_s N, else continue slipping).  Returns (g, dg/dt)."""
    F, N, dF, dN = stick_force_rates(t, y[0], y[1], s, par, hdr, smp)
    v = sig * y[3]
    if (-1 if F > 0.0 else 1) == sig:
        ex = abs(F) - par[Q_MU_S] * N
        if ex > v:
            return ex, (dF if F > 0.0 else -dF) - par[Q_MU_S] * dN, True
    return v, sig * dd, True


@jit
def static_margin(t, y, par, disc, hdr, smp):
    """REST holds while |a_g| <= mu_s G and |a_g| <= G b/h (physics.md 4.3)."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    lim = min(par[Q_MU_S], par[Q_B] / par[Q_H]) * G * (1.0 + UPLIFT_RTOL)
    return min(lim - abs(ag), G)


@jit
def track_slide(d, met):
    if abs(d) > met[M_MAX_SLIDE]:
        met[M_MAX_SLIDE] = abs(d)
    met[M_RESIDUAL_SLIDE] = d


@jit
def set_mode(disc, mode, s, sigma):
    disc[D_MODE] = mode
    disc[D_STATIC] = 1 if mode == MODE_REST else 0
    disc[D_PIVOT] = s
    disc[D_SLIP_DIR] = sigma
    disc[D_AUX] = 0


# outcomes of pick_rocking
PICK_ROCK = 0
PICK_SLIP = 1
PICK_FLIGHT = 2
PICK_JAM = 3


@jit
def normal_margins(t, theta, dtheta, s, sigma, par, hdr, smp):
    """(A, D): A = G - Y theta'^2, the normal force the corner needs per
    unit mass when nothing else acts (> 0: the free corner is pressed into
    the ground; flight is consistent iff A <= 0), and D = i_G + X (X + mu_k
    sigma Y), the slip toward sigma's denominator (N_slip = A i_G / D;
    D <= 0 is Painleve's case).  See the module docstring."""
    _ag, av = ground(t, hdr, smp)
    X, Y = offsets(theta, s, par)
    A = par[P_G] + av - Y * dtheta * dtheta
    D = par[Q_IG] + X * (X + par[Q_MU_K] * sigma * Y)
    return A, D


@jit
def pick_rocking(t, y, s, par, hdr, smp, allow_stick):
    """Contact mode of the corner s at zero slip velocity (module docstring):
    stick (if allowed: a slip onset has left the cone), slip toward sigma1 =
    -sgn F_s, slip toward -sigma1, flight, else a jam.  Returns (PICK_*,
    sigma).  Every mode returned is consistent (N >= 0, slip not reversed,
    free corner not pressed) by the signs of A and D alone, so the rounding
    of a computed slip acceleration (0 at a slip onset) cannot make the
    next phase end at once."""
    _tdd, F, N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
    mu_k = par[Q_MU_K]
    if allow_stick and N >= 0.0 and abs(F) <= par[Q_MU_S] * N:
        return PICK_ROCK, 0
    sig1 = -1 if F > 0.0 else 1
    A, D1 = normal_margins(t, y[0], y[1], s, sig1, par, hdr, smp)
    if D1 > 0.0 and A >= 0.0:
        return PICK_SLIP, sig1
    _A, D2 = normal_margins(t, y[0], y[1], s, -sig1, par, hdr, smp)
    # toward -sigma1: N = A i_G / D2 >= 0 and -sigma1 a_t proportional to
    # -(|F_s| + mu_k N_s) / D2 >= 0
    if D2 != 0.0 and A * D2 >= 0.0 and (abs(F) + mu_k * N) * D2 <= 0.0:
        return PICK_SLIP, -sig1
    if A <= 0.0:
        return PICK_FLIGHT, 0
    return PICK_JAM, 0


@jit
def jam_margin(t, y, s, par, hdr, smp):
    """> 0 while a jam lasts: stick inadmissible (|F| > mu_s N), the slip
    toward sigma1 inconsistent (D(sigma1) <= 0) and flight inconsistent
    (A > 0).  Returns (margin, its three parts)."""
    _tdd, F, N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
    sig1 = -1 if F > 0.0 else 1
    A, D1 = normal_margins(t, y[0], y[1], s, sig1, par, hdr, smp)
    c_stick = abs(F) - par[Q_MU_S] * N
    c_slip = -(par[P_G] * D1 / par[Q_IG])
    return min(c_stick, c_slip, A), c_stick, c_slip, A


@jit
def apply_pick(code, sig, t, y, s, disc, met, log, cnt, count_slip):
    """Enter the mode chosen by pick_rocking on corner s."""
    if code == PICK_ROCK:
        set_mode(disc, MODE_ROCK, s, 0)
        return RUNNING
    if code == PICK_SLIP:
        set_mode(disc, MODE_SLIDE_ROCK, s, sig)
        if count_slip:
            met[M_N_STICK_SLIP] += 1
            log_event(log, cnt, t, EV_SLIP, y[1], y[1], y[0], sig)
        return RUNNING
    if code == PICK_FLIGHT:
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], s)
        return FLIGHT
    # jam: the pivot held as with mu = inf (logged as a stick)
    set_mode(disc, MODE_ROCK, s, 0)
    disc[D_AUX] = 1
    log_event(log, cnt, t, EV_STICK, y[1], y[1], y[0], s)
    return RUNNING


@jit
def kinetic_at(theta, w, v, s, par):
    """Kinetic energy per unit mass rocking at w on pivot s at any theta with
    base slip velocity v: v_G = (v + Y w, -X w)."""
    X, Y = offsets(theta, s, par)
    vx = v + Y * w
    return 0.5 * (vx * vx + X * X * w * w + par[Q_IG] * w * w)


@jit
def stop_slip(t, y, s, par, met):
    """Tangential impact without collision at the slipping corner s (module
    docstring): the plastic stick impulse, angular momentum about the corner
    conserved, i_0 theta'+ = i_0 theta'- + Y d'-, d'+ = 0 (dissipative)."""
    X, Y = offsets(y[0], s, par)
    before = kinetic_at(y[0], y[1], y[3], s, par)
    y[1] = y[1] + Y * y[3] / (par[Q_IG] + X * X + Y * Y)
    y[3] = 0.0
    check_energy(before, kinetic_at(y[0], y[1], 0.0, s, par), met)


@jit
def slip_from_flat(t, F, par, disc, hdr, smp, met, log, cnt):
    """theta = theta' = 0 and stick-rock fails (|F| > mu_s N): slip toward
    sigma = -sgn F, rocking on the corner sigma only if that lifts it
    (mu_k > b/h and sigma theta'' > 0), else flat (both corners down: a
    flat slide cannot tip when mu_k <= b/h, physics.md 4.3)."""
    sigma = -1 if F > 0.0 else 1
    tdd, _dd, _N = slip_rock(t, 0.0, 0.0, sigma, sigma, par, hdr, smp)
    if par[Q_MU_K] > par[Q_B] / par[Q_H] and sigma * tdd > 0.0:
        set_mode(disc, MODE_SLIDE_ROCK, sigma, sigma)
        if np.isnan(met[M_T_UPLIFT]):
            met[M_T_UPLIFT] = t
        met[M_N_STICK_SLIP] += 1
        log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sigma)
        return RUNNING
    set_mode(disc, MODE_SLIDE, 1, sigma)
    met[M_N_STICK_SLIP] += 1
    log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sigma)
    return RUNNING


@jit
def start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt):
    """theta = theta' = 0 (rest or just after an impact): choose REST, SLIDE,
    ROCK or SLIDE_ROCK by the initiation criteria of physics.md 4.3."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    if G <= 0.0:
        log_event(log, cnt, t, EV_FLIGHT, 0.0, 0.0, 0.0, 0)
        return FLIGHT
    y[0] = 0.0
    y[1] = 0.0
    b_h = par[Q_B] / par[Q_H]
    mu_s = par[Q_MU_S]
    mu_k = par[Q_MU_K]
    moving = y[3] != 0.0
    if moving:
        sigma = 1 if y[3] > 0.0 else -1
        if mu_k > b_h:
            set_mode(disc, MODE_SLIDE_ROCK, sigma, sigma)
        else:
            set_mode(disc, MODE_SLIDE, 1, sigma)
        return RUNNING
    rock_demand = abs(ag) > G * b_h * (1.0 + UPLIFT_RTOL)
    if rock_demand:
        s = -1 if ag > 0.0 else 1
        _tdd, F, N = stick_rock(t, 0.0, 0.0, s, par, hdr, smp)
        if abs(F) <= mu_s * N:
            set_mode(disc, MODE_ROCK, s, 0)
            if np.isnan(met[M_T_UPLIFT]):
                met[M_T_UPLIFT] = t
            log_event(log, cnt, t, EV_UPLIFT, 0.0, 0.0, 0.0, s)
            return RUNNING
        return slip_from_flat(t, F, par, disc, hdr, smp, met, log, cnt)
    if abs(ag) > mu_s * G * (1.0 + UPLIFT_RTOL):
        sigma = -1 if ag > 0.0 else 1
        set_mode(disc, MODE_SLIDE, 1, sigma)
        met[M_N_STICK_SLIP] += 1
        log_event(log, cnt, t, EV_SLIP, 0.0, 0.0, 0.0, sigma)
        return RUNNING
    set_mode(disc, MODE_REST, 1, 0)
    return RUNNING


@jit
def kinetic(w, v, s, b, h, iG):
    """Kinetic energy per unit mass at theta = 0, rocking at w on pivot s
    with base slip velocity v: v_G = (v + h w, s b w)."""
    vx = v + h * w
    vy = s * b * w
    return 0.5 * (vx * vx + vy * vy + iG * w * w)


@jit
def routh_general(wtt, wtn, wnn, vt, vn, mu_s, mu_k):
    """Plastic frictional point impact by Routh's incremental method
    (Stronge, Impact Mechanics, 2000, ch. 5) for a 2x2 contact-space inverse
    inertia W = [[wtt, wtn], [wtn, wnn]] and contact velocity (vt, vn),
    vn < 0: the contact velocity evolves linearly in the normal impulse with
    friction -mu_k sgn(v_t) while slipping; when v_t reaches 0 the contact
    sticks if mu_s holds, else slips the other way; the impact ends at
    v_n = 0.  A slip that cannot raise v_n (impulsive jam) ends as a stick.
    Returns the impulses (pt, pn) and the final tangential velocity."""
    pt = 0.0
    pn = 0.0
    for _phase in range(4):
        if vn >= 0.0:
            break
        if vt == 0.0:
            if abs(wtn) <= mu_s * wtt:
                at = 0.0
                an = wnn - wtn * wtn / wtt
                rate_t = -wtn / wtt
            else:
                sig = 1.0 if wtn > 0.0 else -1.0
                rate_t = -mu_k * sig
                at = rate_t * wtt + wtn
                an = rate_t * wtn + wnn
        else:
            sig = 1.0 if vt > 0.0 else -1.0
            rate_t = -mu_k * sig
            at = rate_t * wtt + wtn
            an = rate_t * wtn + wnn
        if an <= 0.0:
            # jam: both contact velocities to zero, P = -W^-1 (vt, vn)
            det = wtt * wnn - wtn * wtn
            pt += (-wnn * vt + wtn * vn) / det
            pn += (wtn * vt - wtt * vn) / det
            vt = 0.0
            vn = 0.0
            break
        dp = -vn / an
        if vt * at < 0.0 and -vt / at < dp:
            dp = -vt / at
            pt += rate_t * dp
            pn += dp
            vn += an * dp
            vt = 0.0
            continue
        pt += rate_t * dp
        pn += dp
        vt += at * dp
        vn = 0.0
    return pt, pn, vt


@jit
def routh_impact(pre, vs, s, b, h, iG, mu_s, mu_k):
    """Plastic frictional impact of the new corner -s by Routh's method
    (``routh_general``) with the contact velocity (v_t, v_n) = (vs, 2 s b
    pre).  Friction then only dissipates.  Returns (theta'+, d'+)."""
    w11 = 1.0 + h * h / iG
    w12 = -s * b * h / iG
    w22 = 1.0 + b * b / iG
    pt, pn, vt = routh_general(w11, w12, w22, vs, 2.0 * s * b * pre, mu_s, mu_k)
    post = pre + (-h * pt + s * b * pn) / iG
    return post, vt


@jit
def corner_impact(pre, vs, s, b, h, iG, i0, e, mu_s, mu_k):
    """(theta'+, d'+) of the ground impact at the new corner -s, per unit
    mass, from theta'- = pre and the slip velocity vs: a plastic impact with
    stick at the new corner (in ROCK vs = 0 and this is Housner's map), then
    the impulse-ratio check: the impact slips when friction cannot supply
    the tangential impulse.  With a slip velocity, a given e that would
    raise the kinetic energy is replaced by the plastic stick."""
    post = e * pre + (h / i0) * vs
    if vs != 0.0 and kinetic(post, 0.0, -s, b, h, iG) > kinetic(pre, vs, s, b, h, iG):
        # a given e unlike the plastic one turns the slip's momentum into
        # more rotation than the impact can give: the plastic stick (angular
        # momentum about the new corner kept), which always dissipates
        post = ((iG + h * h - b * b) / i0) * pre + (h / i0) * vs
    lam_x = h * post - (vs + h * pre)
    lam_y = -s * b * (post + pre)
    dpost = 0.0
    if abs(lam_x) > mu_s * lam_y:
        sigma = -1.0 if lam_x > 0.0 else 1.0
        k = mu_k * sigma * h + s * b
        post = pre * (iG - k * s * b) / (iG + k * s * b)
        lam_y = -s * b * (post + pre)
        dpost = vs + h * pre - h * post - mu_k * sigma * lam_y
        # the algebraic slip rule (physics.md 4.3) presumes the slip
        # direction; where the contact itself would slip otherwise it can
        # contradict sigma and create energy: Routh's incremental impact
        if (sigma * dpost < 0.0 or lam_y <= 0.0
                or kinetic(post, dpost, -s, b, h, iG)
                > kinetic(pre, vs, s, b, h, iG)):
            post, dpost = routh_impact(pre, vs, s, b, h, iG, mu_s, mu_k)
    return post, dpost


@jit
def impact(t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """Ground impact at theta = 0 (physics.md 1 and 4.3)."""
    s = disc[D_PIVOT]
    pre = y[1]
    e = par[P_E]
    b = par[Q_B]
    h = par[Q_H]
    iG = par[Q_IG]
    i0 = iG + b * b + h * h
    met[M_IMPACTS] += 1
    chatter = t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
    met[M_T_LAST_IMPACT] = t
    y[0] = 0.0
    vs = y[3]
    post, dpost = corner_impact(pre, vs, s, b, h, iG, i0, e, par[Q_MU_S],
                                par[Q_MU_K])
    y[1] = post
    y[3] = dpost
    check_energy(kinetic(pre, vs, s, b, h, iG), kinetic(post, dpost, -s, b, h, iG),
                 met)
    log_event(log, cnt, t, EV_IMPACT, pre, post, 0.0, -s)
    if abs(post) < opt[O_EPS_OMEGA] or chatter:
        y[1] = 0.0
        st = start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
        if disc[D_MODE] == MODE_REST:
            log_event(log, cnt, t, EV_REST, post, 0.0, 0.0, 0)
        return st
    if dpost != 0.0:
        sig = 1 if dpost > 0.0 else -1
        set_mode(disc, MODE_SLIDE_ROCK, -s, sig)
    else:
        set_mode(disc, MODE_ROCK, -s, 0)
    return RUNNING


@jit
def stick(t, y, par, disc, hdr, smp, met, log, cnt):
    """Slip velocity reached zero: stick if admissible, else reverse."""
    y[3] = 0.0
    mode = disc[D_MODE]
    met[M_N_STICK_SLIP] += 1
    if mode == MODE_SLIDE:
        log_event(log, cnt, t, EV_STICK, 0.0, 0.0, 0.0, 0)
        return start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    s = disc[D_PIVOT]
    log_event(log, cnt, t, EV_STICK, y[1], y[1], y[0], s)
    sig_old = disc[D_SLIP_DIR]
    code, sig = pick_rocking(t, y, s, par, hdr, smp, True)
    st = apply_pick(code, sig, t, y, s, disc, met, log, cnt, False)
    _tdd, F, _N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
    if code == PICK_SLIP and sig == sig_old and sig == (-1 if F > 0.0 else 1):
        # stick inadmissible and the slip goes on the same way, toward
        # sigma1 = -sgn F_s: its sigma d'' >= 0 (the pick's proof), so sigma
        # d' reached 0 only by rounding or an integration error below the
        # tolerance (at mu = 1e6 the slip acceleration near N = 0 is mu
        # times the rounding of N); the slip continues until stick is
        # admissible (creep_margin), instead of ending again at once (a
        # transition loop at one instant)
        disc[D_AUX] = 2
    return st


@jit
def end_jam(t, y, s, par, disc, hdr, smp, met, log, cnt):
    """The jam's margin reached 0: the mode that became consistent (by the
    margin's own parts where the pick still finds none, so that the state
    always changes)."""
    code, sig = pick_rocking(t, y, s, par, hdr, smp, True)
    if code == PICK_JAM:
        _g, c_stick, c_slip, A = jam_margin(t, y, s, par, hdr, smp)
        if A <= min(c_stick, c_slip):
            code = PICK_FLIGHT
        elif c_stick <= c_slip:
            code = PICK_ROCK
        else:
            _tdd, F, _N = stick_rock(t, y[0], y[1], s, par, hdr, smp)
            code = PICK_SLIP
            sig = -1 if F > 0.0 else 1
    return apply_pick(code, sig, t, y, s, disc, met, log, cnt, True)


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if k < 0:
        book_time(t, disc, met)
        return start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    if k == E_PEAK:
        track_rotation(y[0], met)
        return RUNNING
    if k == E_PASS_ALPHA:
        passed_alpha(t, y[0], y[1], s, met, log, cnt)
        return RUNNING
    book_time(t, disc, met)
    track_slide(y[2], met)
    # the state at an event counts (a flight ends the run here)
    track_rotation(y[0], met)
    if k == E_LIFT_OFF:
        if mode == MODE_SLIDE_ROCK:
            A, _D = normal_margins(t, y[0], y[1], s, disc[D_SLIP_DIR], par,
                                   hdr, smp)
            if A > 0.0:
                # N = A i_G / D reached 0 through D = 0 with the corner
                # pressed: Painleve's dynamic jam stops the slip
                pre = y[1]
                stop_slip(t, y, s, par, met)
                met[M_N_STICK_SLIP] += 1
                log_event(log, cnt, t, EV_STICK, pre, y[1], y[0], s)
                code, sig = pick_rocking(t, y, s, par, hdr, smp, True)
                return apply_pick(code, sig, t, y, s, disc, met, log, cnt,
                                  True)
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], y[0], s)
        return FLIGHT
    if k == E_SLIP_STICK:
        if mode == MODE_ROCK:
            if disc[D_AUX] == 1:
                return end_jam(t, y, s, par, disc, hdr, smp, met, log, cnt)
            if y[0] == 0.0 and y[1] == 0.0:
                # the block has not lifted yet (a rocking start at the tie
                # mu_s ~ b/h, where the stick-rock margin falls from ~0):
                # both corners are down, so the flat slide rule applies
                y[3] = 0.0
                _tdd, F, _N = stick_rock(t, 0.0, 0.0, s, par, hdr, smp)
                return slip_from_flat(t, F, par, disc, hdr, smp, met, log,
                                      cnt)
            # slip onset: stick has left its cone
            code, sig = pick_rocking(t, y, s, par, hdr, smp, False)
            return apply_pick(code, sig, t, y, s, disc, met, log, cnt, True)
        return stick(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == E_OVERTURN:
        return overturned(t, y[0], y[1], s, met, log, cnt)
    return impact(t, y, par, disc, hdr, smp, opt, met, log, cnt)


# ----------------------------------------------------- early decisions
# Once the excitation is over (level ground) the ground frame is inertial,
# Coulomb friction and every impact map dissipate, and the normal force does
# no work: the mechanical energy can only fall.  Two states are then decided
# exactly, with every metric either completed or final (``decide``).


@jit
def sticks_for_good(theta, w, s, par):
    """ROCK after the excitation: True when the rest of the motion is
    provably Housner free rocking with theta'+ = e theta'- (no slip, no
    lift-off, ever).  With E = i_0 w^2 / 2 + g (Y - h) (per unit mass, zero
    at rest) below the barrier the block stays in 0 <= s theta < alpha,
    where h <= Y <= R and |X| <= b, and w^2 <= 2 E / i_0 from now on.  Stick
    (free: theta'' = g X / i_0) has F = X (g Y / i_0 - w^2) and N = g (i_G +
    Y^2) / i_0 - Y w^2, so |F| <= b (g R / i_0 + w^2) and N >= g (i_G + h^2)
    / i_0 - R w^2 bound them on every state still reachable.  An impact
    without slip velocity (post = e pre) needs the tangential impulse
    h (1 - e) |pre| and gets the normal one b (1 + e) |pre| (corner_impact):
    it sticks for any speed when h (1 - e) < mu_s b (1 + e)."""
    b = par[Q_B]
    h = par[Q_H]
    iG = par[Q_IG]
    g = par[P_G]
    mu_s = par[Q_MU_S]
    e = par[P_E]
    if not (0.0 <= e <= 1.0 and h * (1.0 - e) < mu_s * b * (1.0 + e)):
        return False
    _X, Y = offsets(theta, s, par)
    i0 = iG + b * b + h * h
    R = math.sqrt(b * b + h * h)
    w2 = w * w + 2.0 * g * (Y - h) / i0
    n_min = g * (iG + h * h) / i0 - R * w2
    f_max = b * (g * R / i0 + w2)
    return n_min > 0.0 and mu_s * n_min > f_max


@jit
def decide(t, y, par, disc, hdr, opt, met):
    """Early decision at an accepted step end (``early_exit``, level ground):

    * SLIDE after the excitation: d'' = -mu_k g sigma until stick, then rest
      for good (start_from_flat with a_g = 0), so the run is completed in
      closed form (``finish_slide``) with the integrated run's status and
      metrics.  Returns SAFE_BOUNDED as the marker ``run`` completes.
    * ROCK (no jam) after the excitation, below the overturning barrier and
      sticking for good (``sticks_for_good``): SAFE_BOUNDED, with the max
      rotations completed and the slip metrics final (no slip is left).
      The next two peaks (``bounded_after_excitation``; later ones are
      lower) count if they come before t_end (``peak_times``).  A peak
      that would come after t_end and exceed the max so far is not
      decided: the state at t_end would count instead.  Impacts and the
      time columns count up to the decision, as in the rigid kernel.
    """
    if opt[O_EARLY_EXIT] == 0.0 or t < met[M_T_EXC_END] or hdr[S_ON] != 0.0:
        return RUNNING
    mode = disc[D_MODE]
    if mode == MODE_SLIDE:
        return SAFE_BOUNDED
    if mode != MODE_ROCK or disc[D_AUX] != 0:
        return RUNNING
    s = disc[D_PIVOT]
    if not sticks_for_good(y[0], y[1], s, par):
        return RUNNING
    safe, pk1, pk2 = bounded_after_excitation(y[0], y[1], s, par[P_ALPHA],
                                              par[P_P], par[P_E])
    if not safe:
        return RUNNING
    t1, t2 = peak_times(y[0], y[1], s, par[P_ALPHA], par[P_P], par[P_E])
    if not count_peaks(t, t1, t2, pk1, pk2, opt[O_T_END], met):
        return RUNNING
    return SAFE_BOUNDED


@jit
def finish_slide(y, par, disc, opt, met, log, cnt):
    """Complete a run decided in SLIDE at met[M_T_FINAL] as the integrated
    run ends it: the stick at t + |d'| / (mu_k g) (book, log, REST) and rest
    to t_end, or still sliding at t_end.  Returns the final status."""
    t = met[M_T_FINAL]
    t_end = opt[O_T_END]
    sig = disc[D_SLIP_DIR]
    a = par[Q_MU_K] * par[P_G]
    v = max(sig * y[3], 0.0)          # slip speed, > 0 up to rounding
    dt_stop = v / a if a > 0.0 else np.inf
    if t + dt_stop <= t_end:
        t_stop = t + dt_stop
        y[2] += 0.5 * sig * v * dt_stop
        y[3] = 0.0
        book_time(t_stop, disc, met)
        track_slide(y[2], met)
        met[M_N_STICK_SLIP] += 1
        met[M_N_EVENTS] += 1
        log_event(log, cnt, t_stop, EV_STICK, 0.0, 0.0, 0.0, 0)
        set_mode(disc, MODE_REST, 1, 0)
    else:
        dt = t_end - t
        y[2] += sig * (v - 0.5 * a * dt) * dt
        y[3] = sig * (v - a * dt)
    book_time(t_end, disc, met)
    track_slide(y[2], met)
    met[M_T_FINAL] = t_end
    return final_status(disc, met)


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    book_time(t, disc, met)
    track_slide(y[2], met)
    if disc[D_MODE] != MODE_SLIDE:
        track_rotation(y[0], met)
    if at_end:
        return final_status(disc, met)
    return decide(t, y, par, disc, hdr, opt, met)


@jit
def initial_contact(t0, theta, dtheta, dslip, static_rest, disc, met):
    """Metrics and contact mode at the start of a run from the rotation, its
    rate and the slip rate (rigid and flexible bodies with friction); REST
    is a static phase only where nothing moves in it (``static_rest``)."""
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    disc[D_PIVOT] = 1
    if dslip != 0.0:
        disc[D_SLIP_DIR] = 1 if dslip > 0.0 else -1
    if theta != 0.0 or dtheta != 0.0:
        disc[D_MODE] = MODE_SLIDE_ROCK if dslip != 0.0 else MODE_ROCK
        disc[D_PIVOT] = initial_pivot(theta, dtheta)
        met[M_T_UPLIFT] = t0
        track_rotation(theta, met)
    elif dslip != 0.0:
        disc[D_MODE] = MODE_SLIDE
    else:
        disc[D_MODE] = MODE_REST
        disc[D_STATIC] = 1 if static_rest else 0


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    initial_contact(t0, y[0], y[1], y[3], True, disc, met)
    track_slide(y[2], met)


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    status = integrate_hybrid(rhs, event, transition, static_margin,
                              after_step, N_EVENTS, y, par, disc, hdr, smp,
                              opt, t_eval, met, hist_t, hist_y, hist_d, log,
                              cnt)
    if status == SAFE_BOUNDED and disc[D_MODE] == MODE_SLIDE:
        status = finish_slide(y, par, disc, opt, met, log, cnt)
    return status


@jit
def rigid_friction_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                            hist_y, hist_d, log, cnt):
    """One run of the rigid block with friction (time history, events)."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def rigid_friction_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Independent runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
