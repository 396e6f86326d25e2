"""Flexible body with friction and free flight (physics.md 3, 4.4 and 4.6;
issue #13 item 4): the flexible body of :mod:`.flexible_friction` in its
contact modes (REST, SLIDE, ROCK, SLIDE_ROCK, the same functions), plus
MODE_FLIGHT where :mod:`.flexible_friction` stops with FLIGHT (lift-off of
the pivot, N = 0 while rocking, or G = g + a_v <= 0 in full contact).

State ``y = (u, u', theta, theta', d, d', z, z')``.  In contact modes the
first six entries are those of :mod:`.flexible_friction` (d, d': slip of
the base, the pivot's horizontal displacement while rocking) and z = z' = 0.
In flight y[4], y[5] are the horizontal displacement x of O, the bottom
centre of the base, from its rest position and its rate, and y[6], y[7]
the height z of O above the ground and its rate (m, m/s; all relative to
the ground).  Flat (theta = 0), x is d; on pivot s,
``x = d + s B (1 - cos theta)``, ``z = s B sin theta``.

Flight dynamics (per unit mass m; q = (x, z, theta, u); e1 = (cos, -sin),
e2 = (sin, cos); the mass at O + u e1 + H e2, the base CM at O + h_b e2;
mb = m_b/m, rotary inertia i_m, base inertia I_b; body forces -a_g and -G
per unit mass in the ground's frame), a symmetric 4x4 system M q'' = f
(Lagrange; re-derived with sympy in tests/test_flexible_flight.py):

    (1+mb) x'' + c u'' + (H c - u sn + mb h_b c) th''
        = -a_g (1+mb) + 2u'th' sn + u th'^2 c + H th'^2 sn + mb h_b th'^2 sn
    (1+mb) z'' - sn u'' + (-H sn - u c - mb h_b sn) th''
        = -G (1+mb) + 2u'th' c - u th'^2 sn + H th'^2 c + mb h_b th'^2 c
    (H c - u sn + mb h_b c) x'' + (-H sn - u c - mb h_b sn) z'' + H u''
        + (H^2 + u^2 + i_m + I_b + mb h_b^2) th''
        = G (u c + H sn) - a_g (H c - u sn) + mb h_b (G sn - a_g c) - 2 u u' th'
    c x'' - sn z'' + H th'' + u'' = -w^2 u - 2 zeta w u' + G sn - a_g c + u th'^2

solved by eliminating x'' and z'' (a 2x2 Schur complement, positive
definite for mb > 0).  The centre of mass of mass + base moves as
x_cm'' = -a_g, z_cm'' = -G.

Lift-off.  The contact state is rewritten in flight coordinates; the
corner(s) that touched the ground are left on it with zero normal velocity.
In full contact the base lifts off flat when G reaches 0 (flexible_friction's
C_FLIGHT, or its uplift and slip margins, which vanish with N = (1 + mb) G
when the column is at rest: G <= G_FLAT g there counts as lift-off).
The flight is taken only where it is consistent: the free normal
acceleration of the pivot must not point into the ground (beyond A_TOL g).
Where it does (a slip onset of :mod:`.flexible_friction` with N just above
0, its N_LIFT rule; or N = 0 with a friction force that the free body
lacks, mu_s = inf) the body slide-rocks if a slip direction is consistent,
else the pivot is held sticking (jam, disc[D_AUX] = JAM, as
kernels/contact.py's; logged as lift-off-held) until the flight becomes
consistent (free normal acceleration >= A_TOL g) or stick is admissible
again (N above N_RELOAD times the weight and |F| <= mu_s N; logged as
reload).  The same rule resolves a slip start that flexible_friction finds
inconsistent in both directions (Painleve-type, its FAIL_INCONSISTENT):
flight if consistent, else jam.  A jam that starts while the pivot slips
first stops the slip by a plastic horizontal impulse at the pivot (the
kinetic-metric projection onto d' = 0); so does a slip that
flexible_friction's impact rule leaves (d'+ = d'- + h_b theta'-) with
mu_s = inf, or after an impact within eps_t of the previous one (impact
chatter at zero slip speed).  No flight of a flat body is
refused: a corner that sinks lands at once.

Events in flight (terminal: landing, overturning; the rest observers):
  L_LAND_P, L_LAND_M  height of the base corner sigma = +1 / -1,
                      z - sigma B sin(theta), while it moves down
  L_OVERTURN          theta_over - |theta|
  L_U_MAX, L_U_MIN    extrema of u
  L_APEX              vertical velocity of the centre of mass (max_jump)
  L_PASS_ALPHA        alpha - |theta|
  L_PEAK              extrema of |theta|

Landing at corner sigma: a plastic normal impact with Coulomb friction,
impulse (L_t, L_n) at the corner, q'+ = q'- + M^-1 J^T L with J the
corner's velocity Jacobian (tangential x, normal z).  With the contact-space
inverse inertia W = J M^-1 J^T: stick (both corner velocities 0,
L = -W^-1 v) if L_n >= 0 and |L_t| <= mu_s L_n, else Routh's incremental
impact (:func:`.friction.routh_general`, mu_s / mu_k).  mu_s = inf: stick;
if that would pull (L_n < 0) a tangential impulse alone stops the corner's
slip and the corner leaves the ground (a new flight).  Else the corner
becomes the pivot: ROCK if it sticks, SLIDE_ROCK (slip direction: its
tangential velocity) if it slips, where that mode is consistent (N >= 0,
and |F| <= mu_s N for stick, else a slip start); where it is not and the
corner's free normal acceleration is upward, a new flight starts at once
(every landing ends a flight: M_N_FLIGHTS counts the flights); else as at
a lift-off (slide-rock or jam).

Flat landing: the other corner is within FLAT_RTOL B of the ground
(|sin theta| <= FLAT_RTOL) and the single-corner impact above would leave
it moving down, or the landing is a chatter landing (below).  Then theta = z = 0 and a plastic two-point impact:
z'+ = theta'+ = 0, the column's momentum p_u = u' + H theta' + x' kept
(no impulse acts on u), friction on the total tangential impulse: stick
(x'+ = 0) if the impulse it needs, P_x = -mb (x' + h_b theta'), satisfies
|P_x| <= mu_s P_z with P_z = -(1+mb) z' + u theta' the total normal
impulse; else P_x = -mu_k sgn(x' + h_b theta') P_z.  (mu = 0 is the
frictionless plastic projection, x'+ = x' + h_b theta'.)  Both corners'
normal impulses must come out >= 0, else the single-corner landing stands.
Then flexible_friction's start-from-flat rule picks REST, SLIDE, ROCK,
SLIDE_ROCK (or flight again if G <= 0).  Every landing counts as a ground
impact (M_IMPACTS) and dissipates.

Chatter.  A landing within eps_t (O_EPS_T) of the previous impact, or whose
corner comes down slower than eps_omega (O_EPS_OMEGA) times B, lands for
good: near flat (|sin theta| <= FLAT_RTOL) it is a flat landing; else a
new flight starts from it only if the corner's free normal acceleration is
clearly upward (>= A_TOL g, as a jam ends), else the body slide-rocks or
jams.  So a flight that starts with the corner sinking by
rounding cannot repeat in zero time.  Every loop is bounded: the phases of
one run (MAX_PHASES) and zero-time phase switches (the driver's
MAX_ZERO_LENGTH) end in FAIL_TRANSITIONS.

Phases.  ``run`` calls the driver once per contact phase, on the first six
entries of y (N_CONTACT) exactly as flexible_friction does, and once per
flight phase on all eight; a transition that switches ends its phase
(SEG_FLIGHT, SEG_CONTACT).  A run that never lifts off therefore takes
flexible_friction's steps and gives its results to the last bit.

Metrics: those of :mod:`.flexible_friction` (the slide tracked in contact
modes only: after a landing d is the pivot's displacement, flights
included) plus M_N_FLIGHTS (flights), M_T_FLIGHT (s in flight) and
M_MAX_JUMP (m, largest rise of the centre of mass of mass + base above its
rest height, tracked in flight).  mu_s = inf is allowed: it never slips.
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground
from .flexible import track_u
from .flexible_friction import after_step as ff_after_step
from .flexible_friction import event as ff_event
from .flexible_friction import init_state as ff_init_state
from .flexible_friction import rhs as ff_rhs
from .flexible_friction import transition as ff_transition
from .flexible_friction import (C_SLIP_STICK, C_UPLIFT, N_RELOAD, R_IMPACT,
                                R_LIFT_OFF, R_SLIP_STICK,
                                set_mode, slip_rock, start_from_flat,
                                start_slip_rock, stick_rock, stop_slip)
from .friction import routh_general, track_slide
from .hybrid import (C_NHIST, MAX_ZERO_LENGTH, book_time, check_energy,
                     final_status, init_metrics, integrate_hybrid,
                     log_event, sweep_rows)
from .layout import (D_AUX, D_MODE, D_PIVOT, D_SLIP_DIR, EV_CONTACT, EV_FLIGHT,
                     EV_LIFT_OFF_HELD, EV_RELOAD, FAIL_INCONSISTENT,
                     FAIL_TRANSITIONS, FLIGHT, F_ALPHA, F_B, F_G, F_H, F_HB,
                     F_IB, F_IM, F_MB, F_MU_K, F_MU_S, F_THETA_OVER, F_WN,
                     F_ZETA, MODE_FLIGHT, MODE_REST, MODE_ROCK, MODE_SLIDE,
                     MODE_SLIDE_ROCK, M_IMPACTS, M_MAX_JUMP, M_N_FLIGHTS,
                     M_NREJECT, M_NSTEPS, M_T_FINAL, M_T_FLIGHT, M_T_LAST_IMPACT,
                     M_T_PREV, M_T_UPLIFT,
                     N_DISC, N_MET, O_EPS_OMEGA, O_EPS_T, O_MAX_STEPS, O_T0,
                     RUNNING)
from .rigid import overturned, passed_alpha, track_rotation

from .layout import N_PAR_FLEXIBLE_FLIGHT as N_PAR  # noqa: E402,F401

assert M_MAX_JUMP < N_MET
N_STATE = 8
N_CONTACT = 6       # contact phases integrate (u, u', theta, theta', d, d')
N_EVENTS = 8
# a transition ends its driver phase with these (never returned by run)
SEG_FLIGHT = 101
SEG_CONTACT = 102
MAX_PHASES = 1000000   # contact and flight phases of one run
# event ids in flight (contact modes: those of flexible_friction)
L_LAND_P = 0        # right base corner (sigma = +1) reaches the ground
L_LAND_M = 1        # left base corner (sigma = -1)
L_OVERTURN = 2
L_U_MAX = 3         # extrema of u (observers)
L_U_MIN = 4
L_APEX = 5          # vertical velocity of the centre of mass (observer)
L_PASS_ALPHA = 6    # |theta| passes alpha (observer)
L_PEAK = 7          # extremum of |theta| (observer)
# the other corner counts as on the ground at a landing when
# |sin theta| <= FLAT_RTOL (its height over the base width)
FLAT_RTOL = 1e-9
# a flight is consistent while no ground corner's free normal acceleration
# is below -A_TOL g
A_TOL = 1e-9
# in full contact, G below G_FLAT g counts as 0: the base lifts off flat
G_FLAT = 1e-9
# disc[D_AUX] in ROCK: the pivot is held although N < 0 (no consistent mode)
JAM = 1


# ---------------------------------------------------------------- dynamics
@jit
def lever(sg, B, v):
    """(sg B) v, always in this order: corner heights and velocities are
    then exact zeros where they are set so."""
    return (sg * B) * v


@jit
def mass_matrix(u, th, par):
    """(m0, m_x_theta, m_z_theta, m_theta_theta, cos, sin) of the flight
    mass matrix (the other entries: m_xx = m_zz = m0 = 1 + mb, m_xz = 0,
    m_xu = cos, m_zu = -sin, m_theta_u = H, m_uu = 1)."""
    H = par[F_H]
    mb = par[F_MB]
    hb = par[F_HB]
    c = math.cos(th)
    sn = math.sin(th)
    mxt = H * c - u * sn + mb * hb * c
    mzt = -H * sn - u * c - mb * hb * sn
    mtt = H * H + u * u + par[F_IM] + par[F_IB] + mb * hb * hb
    return 1.0 + mb, mxt, mzt, mtt, c, sn


@jit
def solve4(m0, mxt, mzt, mtt, H, mb, c, sn, bx, bz, bt, bu):
    """M q'' = (bx, bz, bt, bu) for q = (x, z, theta, u): x'' and z''
    eliminated, the 2x2 Schur complement in (theta, u) solved."""
    a11 = mtt - (mxt * mxt + mzt * mzt) / m0
    a12 = H - (mxt * c - mzt * sn) / m0
    a22 = mb / m0
    r1 = bt - (mxt * bx + mzt * bz) / m0
    r2 = bu - (c * bx - sn * bz) / m0
    det = a11 * a22 - a12 * a12
    tdd = (r1 * a22 - a12 * r2) / det
    udd = (a11 * r2 - a12 * r1) / det
    xdd = (bx - mxt * tdd - c * udd) / m0
    zdd = (bz - mzt * tdd + sn * udd) / m0
    return xdd, zdd, tdd, udd


@jit
def flight_acc(t, u, du, th, dth, par, hdr, smp):
    """(x'', z'', theta'', u'') in flight (they depend on u, u', theta,
    theta' only)."""
    ag, av = ground(t, hdr, smp)
    G = par[F_G] + av
    H = par[F_H]
    mb = par[F_MB]
    hb = par[F_HB]
    wn = par[F_WN]
    m0, mxt, mzt, mtt, c, sn = mass_matrix(u, th, par)
    w2 = dth * dth
    bx = -ag * m0 + 2.0 * du * dth * sn + (u * c + H * sn + mb * hb * sn) * w2
    bz = -G * m0 + 2.0 * du * dth * c + (-u * sn + H * c + mb * hb * c) * w2
    bt = (G * (u * c + H * sn) - ag * (H * c - u * sn)
          + mb * hb * (G * sn - ag * c) - 2.0 * u * du * dth)
    bu = (-wn * wn * u - 2.0 * par[F_ZETA] * wn * du + G * sn - ag * c
          + u * w2)
    return solve4(m0, mxt, mzt, mtt, H, mb, c, sn, bx, bz, bt, bu)


@jit
def corner_normal_acc(sg, t, y, par, hdr, smp):
    """Free (flight) normal acceleration of base corner sg."""
    _x, zdd, tdd, _u = flight_acc(t, y[0], y[1], y[2], y[3], par, hdr, smp)
    th = y[2]
    return zdd - lever(sg, par[F_B], math.cos(th) * tdd
                       - math.sin(th) * y[3] * y[3])


@jit
def corner_kin(sg, y, par):
    """(height, normal velocity, tangential velocity) of base corner sg in
    flight coordinates."""
    B = par[F_B]
    c = math.cos(y[2])
    sn = math.sin(y[2])
    return (y[6] - lever(sg, B, sn), y[7] - lever(sg, B, c * y[3]),
            y[5] - lever(sg, B, sn * y[3]))


@jit
def kinetic_flight(y, par):
    """Kinetic energy per unit mass in flight, q'^T M q' / 2."""
    m0, mxt, mzt, mtt, c, sn = mass_matrix(y[0], y[2], par)
    xd = y[5]
    zd = y[7]
    td = y[3]
    ud = y[1]
    return (0.5 * (m0 * (xd * xd + zd * zd) + mtt * td * td + ud * ud)
            + mxt * xd * td + c * xd * ud + mzt * zd * td - sn * zd * ud
            + par[F_H] * td * ud)


@jit
def rise(y, par):
    """Height of the centre of mass of mass + base above its rest height."""
    H = par[F_H]
    mb = par[F_MB]
    hb = par[F_HB]
    c = math.cos(y[2])
    sn = math.sin(y[2])
    zm = y[6] - y[0] * sn + H * c
    zb = y[6] + hb * c
    return (zm + mb * zb - H - mb * hb) / (1.0 + mb)


@jit
def track_jump(y, par, met):
    r = rise(y, par)
    if r > met[M_MAX_JUMP]:
        met[M_MAX_JUMP] = r


# ---------------------------------------------------------------- coordinates
@jit
def to_flight(y, s, par):
    """Contact state on pivot s (or flat) -> flight coordinates."""
    B = par[F_B]
    th = y[2]
    c = math.cos(th)
    sn = math.sin(th)
    y[4] = y[4] + lever(s, B, 1.0 - c)
    y[5] = y[5] + lever(s, B, sn * y[3])
    y[6] = lever(s, B, sn)
    y[7] = lever(s, B, c * y[3])


@jit
def to_contact(y, s, par):
    """Flight coordinates -> contact state on pivot s (z = z' = 0)."""
    B = par[F_B]
    th = y[2]
    c = math.cos(th)
    sn = math.sin(th)
    y[4] = y[4] - lever(s, B, 1.0 - c)
    y[5] = y[5] - lever(s, B, sn * y[3])
    y[6] = 0.0
    y[7] = 0.0


# ---------------------------------------------------------------- model functions
@jit
def rhs(t, y, par, disc, hdr, smp, out):
    if disc[D_MODE] == MODE_FLIGHT:
        xdd, zdd, tdd, udd = flight_acc(t, y[0], y[1], y[2], y[3], par, hdr,
                                        smp)
        out[0] = y[1]
        out[1] = udd
        out[2] = y[3]
        out[3] = tdd
        out[4] = y[5]
        out[5] = xdd
        out[6] = y[7]
        out[7] = zdd
        return
    ff_rhs(t, y, par, disc, hdr, smp, out)


@jit
def event(k, t, y, par, disc, hdr, smp):
    if disc[D_MODE] != MODE_FLIGHT:
        if disc[D_AUX] == JAM:
            s = disc[D_PIVOT]
            if k == R_LIFT_OFF:
                # the jam ends in flight once the pivot's free normal
                # acceleration is clearly upward ...
                return (A_TOL * par[F_G]
                        - corner_normal_acc(s, t, y, par, hdr, smp), 0.0, True)
            if k == R_SLIP_STICK:
                # ... or in contact once stick is admissible again
                _u, _t, F, N = stick_rock(t, y, s, par, hdr, smp)
                g = N_RELOAD * (1.0 + par[F_MB]) * par[F_G] - N
                if np.isfinite(par[F_MU_S]):
                    g = max(g, abs(F) - par[F_MU_S] * N)
                return g, 0.0, True
        if not np.isfinite(par[F_MU_S]) and (
                (k == R_SLIP_STICK and disc[D_MODE] == MODE_ROCK)
                or (k == C_SLIP_STICK and disc[D_MODE] == MODE_REST)):
            return np.inf, 0.0, True        # mu_s = inf: stick never fails
        return ff_event(k, t, y, par, disc, hdr, smp)
    if k == L_LAND_P or k == L_LAND_M:
        sg = 1 if k == L_LAND_P else -1
        gap, vn, _vt = corner_kin(sg, y, par)
        if vn < 0.0:
            return gap, vn, True
        return np.inf, 0.0, True
    th = y[2]
    sth = 1.0 if th >= 0.0 else -1.0
    if k == L_OVERTURN:
        return par[F_THETA_OVER] - abs(th), -sth * y[3], True
    if k == L_PASS_ALPHA:
        return par[F_ALPHA] - abs(th), -sth * y[3], False
    xdd, zdd, tdd, udd = flight_acc(t, y[0], y[1], th, y[3], par, hdr, smp)
    if k == L_U_MAX or k == L_U_MIN:
        sg = 1.0 if k == L_U_MAX else -1.0
        return sg * y[1], sg * udd, False
    if k == L_PEAK:
        return sth * y[3], sth * tdd, False
    # L_APEX: vertical velocity of the centre of mass; its rate is -G
    _ag, av = ground(t, hdr, smp)
    H = par[F_H]
    mb = par[F_MB]
    c = math.cos(th)
    sn = math.sin(th)
    vz = (y[7] - y[1] * sn - (y[0] * c + H * sn) * y[3]
          + mb * (y[7] - par[F_HB] * sn * y[3])) / (1.0 + mb)
    return vz, -(par[F_G] + av), False


@jit
def effective_g(t, par, hdr, smp):
    """G = g + a_v at t."""
    _ag, av = ground(t, hdr, smp)
    return par[F_G] + av


@jit
def static_margin(t, y, par, disc, hdr, smp):
    return 1.0   # no static phase: the column vibrates in every mode


@jit
def book_flight(t, met):
    dt = t - met[M_T_PREV]
    if dt > 0.0:
        met[M_T_FLIGHT] += dt
    met[M_T_PREV] = t


@jit
def start_flight(t, y, par, disc, met):
    """Flight from now on (y in flight coordinates)."""
    disc[D_MODE] = MODE_FLIGHT
    disc[D_SLIP_DIR] = 0
    disc[D_AUX] = 0
    met[M_N_FLIGHTS] += 1
    if np.isnan(met[M_T_UPLIFT]):
        met[M_T_UPLIFT] = t
    track_jump(y, par, met)


@jit
def stop_slip_and_pick(t, y, par, disc, hdr, smp, met, log, cnt):
    """flexible_friction left the base slipping where it cannot: mu_s = inf
    (its impact keeps d'+ = d'- + h_b theta'-, nonzero for h_b != 0), or
    after an impact within eps_t of the previous one (chatter: a residual
    slip restarts slide-rocking and the next impact at once).  The slip
    stops by a plastic horizontal impulse at the base (the kinetic-metric
    projection onto d' = 0), and the mode is picked again."""
    if disc[D_MODE] == MODE_SLIDE_ROCK:
        stop_slip(t, y, disc[D_PIVOT], par, met)
        set_mode(disc, MODE_ROCK, disc[D_PIVOT], 0)
        return RUNNING
    # full contact, (u, d) with M = [[1, 1], [1, 1 + mb]]: the mass keeps
    # its horizontal velocity u' + d'
    y[1] += y[5]
    y[5] = 0.0
    return start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)


@jit
def fly_slip_or_jam(t, y, s, a_min, try_slip, par, disc, hdr, smp, met, log,
                    cnt):
    """Rocking on s (contact coordinates, theta != 0) where no contact mode
    is consistent so far: stick-rock needs N < 0 or more than mu_s N.
    SEG_FLIGHT if the pivot's free normal acceleration is at least a_min;
    else slide-rock if ``try_slip`` and a slip direction is consistent;
    else jam: the pivot is held, sticking, until the flight becomes
    consistent or stick is admissible again (as kernels/contact.py's JAM;
    logged as a held lift-off and a reload)."""
    if corner_normal_acc(s, t, y, par, hdr, smp) >= a_min:
        return SEG_FLIGHT
    if try_slip and np.isfinite(par[F_MU_S]):
        _u, _t, F, _N = stick_rock(t, y, s, par, hdr, smp)
        if start_slip_rock(t, y, s, F, par, disc, hdr, smp, met, log, cnt,
                           False) == RUNNING:
            return RUNNING
    if y[5] != 0.0:
        stop_slip(t, y, s, par, met)
    set_mode(disc, MODE_ROCK, s, 0)
    disc[D_AUX] = JAM
    log_event(log, cnt, t, EV_LIFT_OFF_HELD, y[3], y[3], y[2], s)
    return RUNNING


@jit
def lift_off_check(t, y, par, disc, hdr, smp, met, log, cnt):
    """flexible_friction stopped with FLIGHT (N = 0 while rocking, or
    G <= 0 flat; it logged the lift-off).  SEG_FLIGHT if the flight is
    consistent (y still in contact coordinates), else
    ``fly_slip_or_jam``."""
    mode = disc[D_MODE]
    s = disc[D_PIVOT]
    if mode == MODE_ROCK and y[2] != 0.0:
        return fly_slip_or_jam(t, y, s, -A_TOL * par[F_G], True, par, disc,
                               hdr, smp, met, log, cnt)
    if mode != MODE_SLIDE_ROCK or y[2] == 0.0:
        y[2] = 0.0
        y[3] = 0.0
    return SEG_FLIGHT


@jit
def corner_impact(sg, y, par):
    """Plastic frictional impact at base corner sg (flight coordinates,
    velocities updated in place).  Returns the corner's tangential velocity
    after it and whether it leaves the ground (mu_s = inf, pulling)."""
    H = par[F_H]
    mb = par[F_MB]
    B = par[F_B]
    m0, mxt, mzt, mtt, c, sn = mass_matrix(y[0], y[2], par)
    jt = -lever(sg, B, sn)            # theta entries of the Jacobian rows
    jn = -lever(sg, B, c)
    tx, tz, tt, tu = solve4(m0, mxt, mzt, mtt, H, mb, c, sn, 1.0, 0.0, jt,
                            0.0)
    nx, nz, nt, nu = solve4(m0, mxt, mzt, mtt, H, mb, c, sn, 0.0, 1.0, jn,
                            0.0)
    wtt = tx + jt * tt
    wtn = nx + jt * nt
    wnn = nz + jn * nt
    _gap, vn, vt = corner_kin(sg, y, par)
    mu_s = par[F_MU_S]
    det = wtt * wnn - wtn * wtn
    pt = (-wnn * vt + wtn * vn) / det
    pn = (wtn * vt - wtt * vn) / det
    vt_post = 0.0
    leaves = False
    if not (pn >= 0.0 and (abs(pt) <= mu_s * pn or not np.isfinite(mu_s))):
        if np.isfinite(mu_s):
            pt, pn, vt_post = routh_general(wtt, wtn, wnn, vt, vn, mu_s,
                                            par[F_MU_K])
        else:
            pt = -vt / wtt
            pn = 0.0
            leaves = True
    y[5] += tx * pt + nx * pn
    y[7] += tz * pt + nz * pn
    y[3] += tt * pt + nt * pn
    y[1] += tu * pt + nu * pn
    return vt_post, leaves


@jit
def flat_impact(y, par):
    """Plastic two-point impact at theta = 0 (module docstring); False (y
    untouched) where a corner's normal impulse would pull."""
    H = par[F_H]
    mb = par[F_MB]
    hb = par[F_HB]
    B = par[F_B]
    u = y[0]
    xd = y[5]
    zd = y[7]
    td = y[3]
    ud = y[1]
    pu = xd + H * td + ud
    v = xd + hb * td
    pz = -(1.0 + mb) * zd + u * td
    px = -mb * v
    xd1 = 0.0
    mu_s = par[F_MU_S]
    if not abs(px) <= mu_s * pz:
        px = -par[F_MU_K] * (1.0 if v > 0.0 else -1.0) * pz
        xd1 = v + px / mb
    dx = xd1 - xd
    mtt0 = u * u + par[F_IM] + par[F_IB] + mb * hb * hb
    pth = mb * hb * dx + u * zd - mtt0 * td
    if not (pz > 0.0 and pz - pth / B >= 0.0 and pz + pth / B >= 0.0):
        return False
    y[2] = 0.0
    y[3] = 0.0
    y[6] = 0.0
    y[7] = 0.0
    y[5] = xd1
    y[1] = pu - xd1
    return True


@jit
def contact_status(st):
    """A contact mode was picked inside a flight phase: end the phase."""
    return SEG_CONTACT if st == RUNNING else st


@jit
def new_flight(t, y, sg, par, disc, met, log, cnt):
    log_event(log, cnt, t, EV_FLIGHT, y[3], y[3], y[2], sg)
    start_flight(t, y, par, disc, met)
    disc[D_PIVOT] = sg
    return RUNNING


@jit
def pick_after_landing(sg, vt, chatter, t, y, par, disc, hdr, smp, met, log,
                       cnt):
    """Corner sg is on the ground with zero normal velocity (flight
    coordinates): rock on it (stick, vt = 0) or slide-rock (vt != 0) where
    the mode is consistent, else ``fly_slip_or_jam`` (a new flight needs
    the corner's free normal acceleration >= -A_TOL g, after a chatter
    landing >= A_TOL g).  Returns SEG_CONTACT, RUNNING (a new flight) or a
    failure."""
    B = par[F_B]
    # on the ground exactly, normal velocity 0 (the landing event is then
    # inactive if a new flight starts)
    y[6] = lever(sg, B, math.sin(y[2]))
    y[7] = lever(sg, B, math.cos(y[2]) * y[3])
    flight = y.copy()
    to_contact(y, sg, par)
    a_min = (A_TOL if chatter else -A_TOL) * par[F_G]
    st = SEG_FLIGHT
    if vt == 0.0:
        y[5] = 0.0
        _u, _t, F, N = stick_rock(t, y, sg, par, hdr, smp)
        mu_s = par[F_MU_S]
        if N >= 0.0 and (abs(F) <= mu_s * N or not np.isfinite(mu_s)):
            set_mode(disc, MODE_ROCK, sg, 0)
            return SEG_CONTACT
        if N >= 0.0:
            st = start_slip_rock(t, y, sg, F, par, disc, hdr, smp, met, log,
                                 cnt, False)
            if st == RUNNING:
                return SEG_CONTACT
            st = fly_slip_or_jam(t, y, sg, a_min, False, par, disc, hdr, smp,
                                 met, log, cnt)
        else:
            st = fly_slip_or_jam(t, y, sg, a_min, True, par, disc, hdr, smp,
                                 met, log, cnt)
    else:
        sigma = 1 if vt > 0.0 else -1
        _u, _t, _d, N = slip_rock(t, y, sg, sigma, par, hdr, smp)
        if N >= 0.0:
            set_mode(disc, MODE_SLIDE_ROCK, sg, sigma)
            return SEG_CONTACT
        st = fly_slip_or_jam(t, y, sg, a_min, False, par, disc, hdr, smp, met,
                             log, cnt)
    if st != SEG_FLIGHT:
        return contact_status(st)
    # the landing ended a flight, a new one starts at once
    for i in range(N_STATE):
        y[i] = flight[i]
    return new_flight(t, y, sg, par, disc, met, log, cnt)


@jit
def landing(sg, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    """Base corner sg reached the ground moving down: the landing of the
    module docstring, then the contact mode (SEG_CONTACT) or a new flight
    (RUNNING)."""
    before = kinetic_flight(y, par)
    _gap, vn, _vt = corner_kin(sg, y, par)
    chatter = (t - met[M_T_LAST_IMPACT] < opt[O_EPS_T]
               or -vn < opt[O_EPS_OMEGA] * par[F_B])
    met[M_IMPACTS] += 1
    met[M_T_LAST_IMPACT] = t
    track_jump(y, par, met)
    pre = y.copy()
    vt, leaves = corner_impact(sg, y, par)
    if abs(math.sin(pre[2])) <= FLAT_RTOL:
        _g, vn_o, _v = corner_kin(-sg, y, par)
        if vn_o < 0.0 or chatter:
            trial = pre.copy()
            if flat_impact(trial, par):
                for i in range(N_STATE):
                    y[i] = trial[i]
                check_energy(before, kinetic_flight(y, par), met)
                log_event(log, cnt, t, EV_CONTACT, pre[3], 0.0, 0.0, 0)
                track_slide(y[4], met)
                disc[D_MODE] = MODE_REST
                st = start_from_flat(t, y, par, disc, hdr, smp, met, log, cnt)
                if st != FLIGHT:
                    return contact_status(st)
                st = lift_off_check(t, y, par, disc, hdr, smp, met, log, cnt)
                if st == SEG_FLIGHT:
                    to_flight(y, disc[D_PIVOT], par)
                    start_flight(t, y, par, disc, met)
                    return RUNNING
                return contact_status(st)
    check_energy(before, kinetic_flight(y, par), met)
    log_event(log, cnt, t, EV_CONTACT, pre[3], y[3], y[2], sg)
    if leaves:
        # the corner moves up again: a new flight
        return new_flight(t, y, sg, par, disc, met, log, cnt)
    st = pick_after_landing(sg, vt, chatter, t, y, par, disc, hdr, smp, met,
                            log, cnt)
    if disc[D_MODE] != MODE_FLIGHT:
        track_slide(y[4], met)
    return st


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    if disc[D_MODE] != MODE_FLIGHT:
        if disc[D_AUX] == JAM and k <= R_LIFT_OFF:
            disc[D_AUX] = 0
            s = disc[D_PIVOT]
            if k == R_LIFT_OFF:
                book_time(t, disc, met)
                track_slide(y[4], met)
                log_event(log, cnt, t, EV_FLIGHT, y[3], y[3], y[2], s)
                return SEG_FLIGHT
            if k == R_SLIP_STICK:
                log_event(log, cnt, t, EV_RELOAD, y[3], y[3], y[2], s)
                return RUNNING
        m = disc[D_MODE]
        if (m == MODE_REST or m == MODE_SLIDE) and (
                k == C_UPLIFT or k == C_SLIP_STICK) and not effective_g(
                    t, par, hdr, smp) > G_FLAT * par[F_G]:
            # at G = 0 the uplift and friction margins of a body at rest
            # vanish with N = (1 + mb) G: the whole base leaves the ground
            book_time(t, disc, met)
            track_slide(y[4], met)
            log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], 0.0, 0)
            return lift_off_check(t, y, par, disc, hdr, smp, met, log, cnt)
        m = disc[D_MODE]
        chatter = (k == R_IMPACT and (m == MODE_ROCK or m == MODE_SLIDE_ROCK)
                   and t - met[M_T_LAST_IMPACT] < opt[O_EPS_T])
        st = ff_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt)
        if st == RUNNING and y[5] != 0.0 and (
                chatter or not np.isfinite(par[F_MU_S])):
            st = stop_slip_and_pick(t, y, par, disc, hdr, smp, met, log, cnt)
        if st == FLIGHT:
            return lift_off_check(t, y, par, disc, hdr, smp, met, log, cnt)
        m = disc[D_MODE]
        if st == FAIL_INCONSISTENT and y[2] != 0.0 and (
                m == MODE_ROCK or m == MODE_SLIDE_ROCK):
            # no slip direction is consistent (Painleve-type): fly or jam
            st = fly_slip_or_jam(t, y, disc[D_PIVOT], -A_TOL * par[F_G],
                                 False, par, disc, hdr, smp, met, log, cnt)
            if st == SEG_FLIGHT:
                log_event(log, cnt, t, EV_FLIGHT, y[3], y[3], y[2],
                          disc[D_PIVOT])
            return st
        return st
    th = y[2]
    sth = 1 if th >= 0.0 else -1
    if k == L_U_MAX or k == L_U_MIN:
        track_u(y[0], met)
        return RUNNING
    if k == L_APEX:
        track_jump(y, par, met)
        return RUNNING
    if k == L_PEAK:
        track_rotation(th, met)
        return RUNNING
    if k == L_PASS_ALPHA:
        passed_alpha(t, th, y[3], sth, met, log, cnt)
        return RUNNING
    book_flight(t, met)
    if k == L_OVERTURN:
        return overturned(t, th, y[3], sth, met, log, cnt)
    return landing(1 if k == L_LAND_P else -1, t, y, par, disc, hdr, smp, opt,
                   met, log, cnt)


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    if disc[D_MODE] != MODE_FLIGHT:
        return ff_after_step(t, y, par, disc, hdr, smp, opt, met, at_end)
    book_flight(t, met)
    track_u(y[0], met)
    track_rotation(y[2], met)
    track_jump(y, par, met)
    if at_end:
        return final_status(disc, met)
    return RUNNING


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    """flexible_friction's initial mode, or flight if z or z' is nonzero
    (y[4:8] then flight coordinates; both corners at or above the
    ground)."""
    if y[6] == 0.0 and y[7] == 0.0:
        ff_init_state(t0, y, par, disc, hdr, smp, met, log, cnt)
        return
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    disc[D_PIVOT] = 1 if y[2] >= 0.0 else -1
    start_flight(t0, y, par, disc, met)
    track_rotation(y[2], met)
    track_u(y[0], met)


@jit
def run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
        cnt):
    """Phases of contact (the first N_CONTACT entries of y, exactly as
    flexible_friction integrates them) and of flight (all N_STATE), each
    by one call of the driver: a transition that switches ends its phase
    with SEG_FLIGHT / SEG_CONTACT.  opt[O_T0] and opt[O_MAX_STEPS] are
    set per phase and restored at the end."""
    disc = np.zeros(N_DISC, dtype=np.int64)
    t0 = opt[O_T0]
    max_steps = opt[O_MAX_STEPS]
    for i in range(hist_y.shape[0]):
        for j in range(N_CONTACT, N_STATE):
            hist_y[i, j] = 0.0          # z, z' in contact rows
    init_state(t0, y, par, disc, hdr, smp, met, log, cnt)
    every_step = hist_t.shape[0] > 0 and t_eval.shape[0] == 0
    t = t0
    i_eval = 0
    repeats = 0
    status = RUNNING
    for phase in range(MAX_PHASES):
        n = N_STATE if disc[D_MODE] == MODE_FLIGHT else N_CONTACT
        ht = hist_t
        if phase > 0:
            if every_step and cnt[C_NHIST] > 0:
                cnt[C_NHIST] -= 1       # the phase's first row replaces the
                #                         last one (same t, old coordinates)
            while i_eval < t_eval.shape[0] and t_eval[i_eval] <= t:
                i_eval += 1
            if t_eval.shape[0] > 0 and i_eval == t_eval.shape[0]:
                ht = hist_t[:0]         # every output time stored already
        opt[O_T0] = t
        opt[O_MAX_STEPS] = max_steps - met[M_NSTEPS] - met[M_NREJECT]
        status = integrate_hybrid(rhs, event, transition, static_margin,
                                  after_step, N_EVENTS, y[:n], par, disc, hdr,
                                  smp, opt, t_eval[i_eval:], met, ht, hist_y,
                                  hist_d, log, cnt)
        if status != SEG_FLIGHT and status != SEG_CONTACT:
            break
        t_new = met[M_T_FINAL]
        repeats = repeats + 1 if t_new == t else 0
        t = t_new
        if repeats > MAX_ZERO_LENGTH:
            status = FAIL_TRANSITIONS
            break
        if status == SEG_FLIGHT:
            to_flight(y, disc[D_PIVOT], par)
            start_flight(t, y, par, disc, met)
        status = RUNNING
    if status == RUNNING:
        status = FAIL_TRANSITIONS       # MAX_PHASES phases
    opt[O_T0] = t0
    opt[O_MAX_STEPS] = max_steps
    return status


@jit
def flexible_flight_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                             hist_y, hist_d, log, cnt):
    """One run of the flexible body with friction and free flight."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def flexible_flight_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Independent runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
