"""Flexible rocking body: lumped mass on an elastic column on a rigid rocking
base (physics.md section 3; Acikgoz & DeJong 2012, Vassiliou et al. 2014/17).

State ``y = (u, u', theta, theta')`` [m, m/s, rad, rad/s]: u is the elastic
deflection of the mass perpendicular to the column.  Everything is per unit
mass m (I_m/m = ``i_m``).  Discrete state: full contact (theta = 0, u
oscillates) or rocking about pivot s, with the exact equations of 3.4,
including an optional rigid base (mass m_b, inertia I_b, CM height h_b; the
classic model has m_b = 0).

Events (ids C_* in full contact, R_* while rocking): C_UPLIFT (signed test
of 3.3, either corner), C_U_MAX/C_U_MIN extrema of u (observers), C_FLIGHT;
R_IMPACT s*theta, R_OVERTURN, R_PEAK s*theta', R_PASS_ALPHA, R_U_MAX/R_U_MIN
extrema of u, R_FLIGHT, R_FOLD (massless base only, below).

Fold of a massless base (m_b = 0, I_m = 0).  The mass matrix of 3.4 has
det = (u - sB)^2: at r = u - sB = 0 the mass lies on the line from the
pivot along the column, at its least distance H from the pivot, and the
base angle is no longer fixed by the mass's position (the mass at distance
rho = sqrt(r^2 + H^2) >= H, angle phi = theta + atan(r/H) from the
vertical; both signs of r give the same point).  Undamped, the mass reaches
that circle in finite time with a finite radial speed (the column force's
radial part is dV/drho with V = w^2 u^2/2, a 1/sqrt(rho - H) pull that is
integrable), while u' and theta' grow like 1/r: no step size resolves it.
The limit of a small base inertia I (det = r^2 + I, regular; r passes
through 0 monotonically, since r's kinetic coefficient stays positive)
is an elastic reflection of the mass off that circle, r changing sign:
at |r| = FOLD_WIDTH B the run maps to the mirror configuration (-r,
theta + 2 atan(r/H)), same mass position, same phi', and the radial speed
reversed with its kinetic energy changed by V(r) - V(-r) (energy kept; if
that is negative beyond the radial energy, the mass turns back before the
fold: reflection on the same branch).  Skipping the layer |r| < FOLD_WIDTH B
costs O(FOLD_WIDTH^2) (its transit time and the bounded forces over it)
while the radial speed is well above sqrt(2 w^2 B FOLD_WIDTH B), the
speed the strain's pull changes across the layer; a slower mass lingers
in the layer (flexible_wall:2026:152, a base rattling between ground and
wall with the mass near the fold: FOLD_WIDTH 1e-4 gave an overturning
time 8 % off the limit of vanishing base inertia, 1e-5 gives 3e-7).
Much smaller widths are not reachable: at rtol 1e-11 the step underflows
before |r| = 1e-6 B (flexible:2027:207).
With a dashpot (zeta > 0) the dissipation c u'^2 diverges like ln at the
fold, so the mass arrives with no radial speed, on the creep where the
column's shear w^2 u + 2 zeta w u' vanishes (a massless base takes no
moment, and the axial force's arm r goes to 0): the map then puts u' on
that creep, u' = -w u / (2 zeta), outward, crossing the fold where the
column's potential pulls the mass in (V(r) > V(-r)).
"""
import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import excitation_end, ground, ground_rates
from .hybrid import (undo_uplift, book_time, check_energy, final_status,
                     init_metrics, integrate_hybrid, log_event, sweep_rows)
from .layout import (D_MODE, D_PIVOT, EV_CONTACT, EV_FLIGHT, EV_IMPACT,
                     EV_UPLIFT, FLIGHT, MODE_REST, MODE_ROCK,
                     M_ENERGY_GAINS,
                     M_IMPACTS, M_MAX_THETA_NEG, M_MAX_THETA_POS, M_MAX_U,
                     M_MIN_U, M_T_LAST_IMPACT, M_T_UPLIFT, N_DISC,
                     O_EARLY_EXIT, O_EPS_OMEGA, O_T0, RUNNING, SAFE_BOUNDED)
from .rigid import initial_pivot, overturned, passed_alpha, track_rotation

from .layout import (F_ALPHA, F_B, F_E, F_G, F_H, F_HB, F_IB, F_IM,  # noqa: E402,F401
                     F_IMPACT, F_MB, F_P, F_THETA_OVER, F_WN, F_ZETA,
                     IMPACT_FULL_CONTACT, IMPACT_PIVOT_SWITCH,
                     N_PAR_FLEXIBLE as N_PAR)

N_EVENTS = 8
# event ids in full contact
C_UPLIFT = 0        # signed uplift test of 3.3, either corner (terminal)
C_U_MAX = 1         # u' = 0 from above: extremum of u (observer)
C_U_MIN = 2         # u' = 0 from below (observer)
C_FLIGHT = 3        # G = g + a_v reaches 0 (terminal)
# event ids while rocking
R_IMPACT = 0        # s theta reaches 0 (terminal)
R_OVERTURN = 1      # s theta reaches theta_over (terminal)
R_PEAK = 2          # s theta' reaches 0 (observer)
R_PASS_ALPHA = 3    # s theta passes alpha (observer)
R_U_MAX = 4         # extrema of u (observers)
R_U_MIN = 5
R_FLIGHT = 6        # G reaches 0 (terminal)
R_FOLD = 7          # massless base: |u - sB| reaches FOLD_WIDTH B (terminal)
FOLD_WIDTH = 1e-5


@jit
def accelerations(t, y, s, rocking, par, hdr, smp):
    """(u'', theta'') in full contact (rocking False) or rocking on s."""
    ag, av = ground(t, hdr, smp)
    G = par[F_G] + av
    wn = par[F_WN]
    u = y[0]
    du = y[1]
    fe = -wn * wn * u - 2.0 * par[F_ZETA] * wn * du
    if not rocking:
        return fe - ag, 0.0
    th = y[2]
    dth = y[3]
    H = par[F_H]
    r = u - s * par[F_B]
    c = math.cos(th)
    sn = math.sin(th)
    X, Y, Xb, Yb = positions(r, c, sn, s, par)
    mb = par[F_MB]
    fu = fe + r * dth * dth + G * sn - ag * c
    ft = G * (X + mb * Xb) - ag * (Y + mb * Yb) - 2.0 * r * dth * du
    det = r * r + base_inertia(par)
    m22 = det + H * H
    return (m22 * fu - H * ft) / det, (ft - H * fu) / det


@jit
def positions(r, c, sn, s, par):
    """Mass (X, Y) and base CM (X_b, Y_b) relative to the pivot s
    (physics.md 3.1), r = u - s B."""
    H = par[F_H]
    hb = par[F_HB]
    sB = s * par[F_B]
    return (r * c + H * sn, -r * sn + H * c, -sB * c + hb * sn,
            sB * sn + hb * c)


@jit
def base_inertia(par):
    """I_m + I_b + m_b (B^2 + h_b^2) per unit mass: the theta-row inertia
    beyond the point mass (physics.md 3.4)."""
    B = par[F_B]
    hb = par[F_HB]
    return par[F_IM] + par[F_IB] + par[F_MB] * (B * B + hb * hb)


@jit
def rhs(t, y, par, disc, hdr, smp, out):
    udd, tdd = accelerations(t, y, disc[D_PIVOT], disc[D_MODE] == MODE_ROCK,
                             par, hdr, smp)
    out[0] = y[1]
    out[1] = udd
    out[2] = y[3]
    out[3] = tdd


@jit
def uplift_margin(t, y, s, par, hdr, smp):
    """G (B - s u) + m_b/m (G B + s a_g h_b) - s H (w^2 u + 2 zeta w u')
    (physics.md 3.3, per unit mass) and its time derivative; uplift about
    s when it reaches 0."""
    ag, dag, av, dav = ground_rates(t, hdr, smp)
    G = par[F_G] + av
    wn = par[F_WN]
    z = par[F_ZETA]
    B = par[F_B]
    H = par[F_H]
    u = y[0]
    du = y[1]
    udd = -wn * wn * u - 2.0 * z * wn * du - ag
    mb = par[F_MB]
    hb = par[F_HB]
    g = G * (B - s * u) - s * H * (wn * wn * u + 2.0 * z * wn * du) + \
        mb * (G * B + s * ag * hb)
    gd = dav * (B - s * u) - G * s * du - s * H * (wn * wn * du +
                                                   2.0 * z * wn * udd) + \
        mb * (dav * B + s * dag * hb)
    return g, gd


@jit
def event(k, t, y, par, disc, hdr, smp):
    rocking = disc[D_MODE] == MODE_ROCK
    s = disc[D_PIVOT]
    if not rocking:
        if k == C_UPLIFT:
            gp, gdp = uplift_margin(t, y, 1, par, hdr, smp)
            gm, gdm = uplift_margin(t, y, -1, par, hdr, smp)
            if gp <= gm:
                return gp, gdp, True
            return gm, gdm, True
        if k == C_U_MAX or k == C_U_MIN:
            sg = 1.0 if k == C_U_MAX else -1.0
            udd, _ = accelerations(t, y, s, False, par, hdr, smp)
            return sg * y[1], sg * udd, False
        if k == C_FLIGHT:
            _ag, _dag, av, dav = ground_rates(t, hdr, smp)
            return par[F_G] + av, dav, True
        return np.inf, 0.0, False
    if k == R_IMPACT:
        return s * y[2], s * y[3], True
    if k == R_OVERTURN:
        return par[F_THETA_OVER] - s * y[2], -s * y[3], True
    if k == R_PEAK:
        _udd, tdd = accelerations(t, y, s, True, par, hdr, smp)
        return s * y[3], s * tdd, False
    if k == R_PASS_ALPHA:
        return par[F_ALPHA] - s * y[2], -s * y[3], False
    if k == R_U_MAX or k == R_U_MIN:
        sg = 1.0 if k == R_U_MAX else -1.0
        udd, _ = accelerations(t, y, s, True, par, hdr, smp)
        return sg * y[1], sg * udd, False
    if k == R_FOLD:
        if base_inertia(par) > 0.0:
            return np.inf, 0.0, True
        r = y[0] - s * par[F_B]
        d = FOLD_WIDTH * par[F_B]
        return r * r - d * d, 2.0 * r * y[1], True
    _ag, _dag, av, dav = ground_rates(t, hdr, smp)
    return par[F_G] + av, dav, True


@jit
def static_margin(t, y, par, disc, hdr, smp):
    return 1.0   # no static phase: full contact is a dynamic phase here


@jit
def track_u(u, met):
    if u > met[M_MAX_U]:
        met[M_MAX_U] = u
    if -u > met[M_MIN_U]:
        met[M_MIN_U] = -u


@jit
def kinetic(y, s, rocking, par):
    """Kinetic energy per unit mass, rocking on s (or full contact)."""
    if not rocking:
        return 0.5 * y[1] * y[1]
    r = y[0] - s * par[F_B]
    H = par[F_H]
    du = y[1]
    dth = y[3]
    return 0.5 * (du * du + 2.0 * H * du * dth
                  + (r * r + H * H + base_inertia(par)) * dth * dth)


@jit
def contact_or_uplift(t, y, par, disc, hdr, smp, met, log, cnt):
    """theta = theta' = 0: full contact, then the uplift test at once."""
    disc[D_MODE] = MODE_REST
    gp, _ = uplift_margin(t, y, 1, par, hdr, smp)
    gm, _ = uplift_margin(t, y, -1, par, hdr, smp)
    if min(gp, gm) <= 0.0:
        disc[D_MODE] = MODE_ROCK
        disc[D_PIVOT] = 1 if gp <= gm else -1
        if np.isnan(met[M_T_UPLIFT]):
            met[M_T_UPLIFT] = t
        log_event(log, cnt, t, EV_UPLIFT, y[1], y[1], 0.0, disc[D_PIVOT])
    else:
        log_event(log, cnt, t, EV_CONTACT, y[1], y[1], 0.0, 0)
    return RUNNING


@jit
def never_left(t, y, disc, met, log, cnt):
    """An impact with theta'- = 0 can only come at the instant of an uplift:
    the rocking equation turned the body back at once, so the uplift test
    was met within rounding at a zero of the margin that the margin leaves
    upward (at the same state s theta'' has the other sign).  The body never
    left the ground: full contact, the uplift undone, and no new uplift test
    at this instant (it would repeat the same uplift and landing for ever);
    the uplift event takes the body up once the margin is negative over a
    step."""
    disc[D_MODE] = MODE_REST
    y[2] = 0.0
    undo_uplift(t, met, log, cnt)
    return RUNNING


@jit
def transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    rocking = disc[D_MODE] == MODE_ROCK
    s = disc[D_PIVOT]
    if not rocking:
        if k == C_UPLIFT:
            book_time(t, disc, met)
            y[2] = 0.0
            y[3] = 0.0
            return contact_or_uplift(t, y, par, disc, hdr, smp, met, log, cnt)
        if k == C_U_MAX or k == C_U_MIN:
            track_u(y[0], met)
            return RUNNING
        log_event(log, cnt, t, EV_FLIGHT, y[1], y[1], 0.0, 0)   # C_FLIGHT
        return FLIGHT
    if k == R_IMPACT:
        book_time(t, disc, met)
        if y[3] == 0.0:
            return never_left(t, y, disc, met, log, cnt)
        pre = y[3]
        met[M_IMPACTS] += 1
        met[M_T_LAST_IMPACT] = t
        y[2] = 0.0
        if par[F_IMPACT] == IMPACT_PIVOT_SWITCH:
            u = y[0]
            H = par[F_H]
            B = par[F_B]
            im = par[F_IM]
            t_before = kinetic(y, s, True, par)
            post = par[F_E] * (H * H + u * u - B * B + im) / \
                (H * H + (u + s * B) ** 2 + im) * pre
            y[3] = post
            if kinetic(y, -s, True, par) <= t_before * (1.0 + 1e-12):
                disc[D_PIVOT] = -s
                log_event(log, cnt, t, EV_IMPACT, pre, post, 0.0, -s)
                if abs(post) < opt[O_EPS_OMEGA]:
                    y[3] = 0.0
                    return contact_or_uplift(t, y, par, disc, hdr, smp, met,
                                             log, cnt)
                return RUNNING
            # I1 would add energy here (u' and theta' large and of opposite
            # sign): an impact must not, so this one takes the full-contact
            # map below, which never does (counted in energy_gains)
            met[M_ENERGY_GAINS] += 1
            y[3] = pre
        # I3: plastic impact onto theta' = 0, horizontal momentum of the mass
        t_before = kinetic(y, s, True, par)
        y[1] = y[1] + par[F_H] * pre
        y[3] = 0.0
        check_energy(t_before, kinetic(y, s, False, par), met)
        log_event(log, cnt, t, EV_IMPACT, pre, 0.0, 0.0, -s)
        return contact_or_uplift(t, y, par, disc, hdr, smp, met, log, cnt)
    if k == R_OVERTURN:
        book_time(t, disc, met)
        return overturned(t, y[2], y[3], s, met, log, cnt)
    if k == R_PEAK:
        track_rotation(y[2], met)
        return RUNNING
    if k == R_PASS_ALPHA:
        passed_alpha(t, y[2], y[3], s, met, log, cnt)
        return RUNNING
    if k == R_U_MAX or k == R_U_MIN:
        track_u(y[0], met)
        return RUNNING
    if k == R_FOLD:
        book_time(t, disc, met)
        fold_passage(y, s, par)
        track_u(y[0], met)
        track_rotation(y[2], met)
        return RUNNING
    log_event(log, cnt, t, EV_FLIGHT, y[3], y[3], y[2], s)   # R_FLIGHT
    return FLIGHT


@jit
def fold_passage(y, s, par):
    """The massless base's passage of the fold r = u - sB = 0 (module
    docstring), applied in place at |r| = FOLD_WIDTH B."""
    H = par[F_H]
    sB = s * par[F_B]
    wn = par[F_WN]
    z = par[F_ZETA]
    r = y[0] - sB
    rho2 = r * r + H * H
    dphi = y[3] + H * y[1] / rho2
    drho2 = (r * y[1]) ** 2 / rho2
    gain = 2.0 * wn * wn * sB * r        # V(r) - V(-r)
    cross = gain > 0.0 if z > 0.0 else drho2 + 2.0 * gain >= 0.0
    if cross:
        y[0] = sB - r
        y[2] += 2.0 * math.atan(r / H)
        r = -r
    if z > 0.0:
        du = -wn * y[0] / (2.0 * z)
    else:
        # outward radial speed rho' = r u' / rho
        du = math.sqrt(drho2 + 2.0 * gain if cross else drho2) * \
            math.sqrt(rho2) / r
    y[1] = du
    y[3] = dphi - H * du / rho2


@jit
def free_column_bound(y, par):
    """(U, f): bounds on |u| and on the column force |w^2 u + 2 zeta w u'|
    for all later free motion in full contact.  The oscillator energy
    E = u'^2/2 + w^2 u^2/2 never grows (zeta >= 0), so |u| <= sqrt(2E)/w
    and |u'| <= sqrt(2E)."""
    wn = par[F_WN]
    V = math.sqrt(y[1] * y[1] + wn * wn * y[0] * y[0])
    U = V / wn
    return U, wn * wn * U + 2.0 * par[F_ZETA] * wn * V


@jit
def never_uplifts_again(t, y, par, hdr):
    """Exact sufficient test in full contact after the excitation: if even
    the bounds of ``free_column_bound`` cannot meet the uplift test of 3.3,
    the body stays in contact for good."""
    if t < excitation_end(hdr):
        return False
    U, fmax = free_column_bound(y, par)
    return par[F_H] * fmax < par[F_G] * (par[F_B] * (1.0 + par[F_MB]) - U)


@jit
def total_energy(y, s, rocking, par):
    """Kinetic + gravity (heights from the pivot) + column strain, per unit
    mass; in full contact the same with theta = 0 (either s)."""
    g = par[F_G]
    wn = par[F_WN]
    c = math.cos(y[2])
    sn = math.sin(y[2])
    _X, Y, _Xb, Yb = positions(y[0] - s * par[F_B], c, sn, s, par)
    return kinetic(y, s, rocking, par) + g * (Y + par[F_MB] * Yb) + \
        0.5 * wn * wn * y[0] * y[0]


@jit
def barrier_profile(phi, a, c, k, g):
    """m(phi) = min over u of the potential (gravity + strain, zero upright
    at rest) at s theta = phi, per unit mass: with v = s u,
    V = w^2 v^2/2 + g (a sin phi + c (cos phi - 1) - v sin phi), least at
    v = k sin phi (k = g/w^2); a = B (1 + m_b), c = H + m_b h_b.  Returns
    (m, m')."""
    sp = math.sin(phi)
    cp = math.cos(phi)
    return (g * (a * sp + c * (cp - 1.0) - 0.5 * k * sp * sp),
            g * (a * cp - c * sp - k * sp * cp))


@jit
def bounded_free_rocking(y, s, par, limit):
    """Exact sufficient test for free rocking on s after the excitation:
    (safe, Phi, U), safe only with Phi <= ``limit``.  The total energy E
    (``total_energy``, zero upright at rest) never grows in free motion:
    damping, impacts (both maps, capped) and the fold passage of an
    undamped massless base never add energy, and E is continuous at uplift
    and at theta = 0.  V >= m(s theta) (``barrier_profile``), so while
    E < m(phi_c) the rotation can never reach phi_c on either side (the
    body is symmetric); phi_c is the top of m (Newton on m' from
    atan(a/c), where m' <= 0), cut at theta_over.  Where m is concave on
    [0, phi_c] (checked), the future |theta| stays <= Phi, m(Phi) = E
    (bisection), and |u| <= k sin Phi + sqrt(2 E)/w_n (V = w^2 (v - k sin
    phi)^2/2 + m(phi) with m >= 0 there).  A damped massless base gains
    energy at the fold (u' set on the creep): there the test also needs U
    below the fold u = s B.  Two cheap rejections by the rigid profile
    g (a sin + c (cos - 1)) >= m come first: its top g (hypot(a, c) - c),
    and its Phi, a lower bound of Phi, against ``limit``."""
    g = par[F_G]
    wn = par[F_WN]
    B = par[F_B]
    mb = par[F_MB]
    a = B * (1.0 + mb)
    c = par[F_H] + mb * par[F_HB]
    k = g / (wn * wn)
    E = total_energy(y, s, True, par) - g * c
    R = math.hypot(a, c)
    if not E < g * (R - c):
        return False, 0.0, 0.0
    if math.atan2(a, c) - math.acos(min(E / g + c, R) / R) > limit:
        return False, 0.0, 0.0
    # the top of m by Newton from the rigid top (m' <= 0 there), kept in
    # [0, atan(a/c)]: any phi_c is a valid certificate, the top the best
    top = math.atan2(a, c)
    if not s * y[2] < top:
        return False, 0.0, 0.0
    phi_c = top
    for _ in range(8):
        sp = math.sin(phi_c)
        cp = math.cos(phi_c)
        d2 = a * sp + c * cp + k * (cp * cp - sp * sp)
        prev = phi_c
        phi_c = min(max(phi_c + (a * cp - c * sp - k * sp * cp) / d2, 0.0),
                    top)
        if abs(phi_c - prev) <= 1e-15 * top:
            break
    phi_c = min(phi_c, par[F_THETA_OVER])
    if not s * y[2] < phi_c:
        return False, 0.0, 0.0
    # concave on [0, phi_c]: a sin + c cos (concave, least at an end) > -k cos 2 phi
    if not min(c, a * math.sin(phi_c) + c * math.cos(phi_c)) > \
            k * max(0.0, -math.cos(2.0 * phi_c)):
        return False, 0.0, 0.0
    # relative margin: the pivot-switch map may keep 1e-12 of a gain
    if not E < barrier_profile(phi_c, a, c, k, g)[0] * (1.0 - 1e-9):
        return False, 0.0, 0.0
    lo = 0.0
    hi = phi_c
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if barrier_profile(mid, a, c, k, g)[0] > E:
            hi = mid
        else:
            lo = mid
    if not hi <= limit:
        return False, 0.0, 0.0
    U = k * math.sin(hi) + math.sqrt(2.0 * max(E, 0.0)) / wn
    if base_inertia(par) == 0.0 and par[F_ZETA] > 0.0 and \
            not U < B * (1.0 - FOLD_WIDTH):
        return False, 0.0, 0.0
    return True, hi, U


@jit
def rotation_limit(met, side, wall, theta_w):
    """The largest future peak on ``side`` that leaves its max rotation as
    it is: the max so far, or any on the side of a wall (w = ``wall``)
    that has stopped the body there already (theta_w <= the max)."""
    m = met[M_MAX_THETA_POS] if side > 0 else met[M_MAX_THETA_NEG]
    if wall == side and theta_w <= m:
        return np.inf
    return m


@jit
def rocking_decided(t, y, par, disc, hdr, met, wall, theta_w):
    """Early decision while rocking after the excitation
    (``bounded_free_rocking``), taken only once its bounds keep |theta|
    within the maxima so far on both sides and |u| within the largest
    deflection so far, so that the rotation and deflection maxima are the
    full run's.  The deflection's bound U holds the rocking energy in
    sqrt(2E)/w_n and can stay far above the deflections that rocking
    reaches (flexible:2027:214: U = 7.2e-5 m against a max |u| of 7.1e-6
    m over 3.3 s): such a run is not decided.  A wall that the body could
    lean on (theta_w > alpha) must stay out of the bound's reach (else
    the full run may end leaning)."""
    if t < excitation_end(hdr):
        return False
    limit = min(rotation_limit(met, 1, wall, theta_w),
                rotation_limit(met, -1, wall, theta_w))
    safe, phi, U = bounded_free_rocking(y, disc[D_PIVOT], par, limit)
    return safe and U <= max(met[M_MAX_U], met[M_MIN_U]) and \
        not (theta_w > par[F_ALPHA] and not phi < theta_w)


@jit
def decide_after_step(t, y, par, disc, hdr, opt, met, at_end, wall, theta_w):
    """after_step of the flexible body, and of the body with a wall on side
    ``wall`` at theta_w (no wall: 0, inf)."""
    book_time(t, disc, met)
    track_u(y[0], met)
    if disc[D_MODE] == MODE_ROCK:
        track_rotation(y[2], met)
    if at_end:
        return final_status(disc, met)
    if opt[O_EARLY_EXIT] != 0.0:
        if disc[D_MODE] == MODE_REST and never_uplifts_again(t, y, par, hdr):
            return final_status(disc, met)
        if disc[D_MODE] == MODE_ROCK and \
                rocking_decided(t, y, par, disc, hdr, met, wall, theta_w):
            return SAFE_BOUNDED
    return RUNNING


@jit
def after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    return decide_after_step(t, y, par, disc, hdr, opt, met, at_end, 0.0,
                             np.inf)


@jit
def init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    init_metrics(t0, met)
    for i in range(N_DISC):
        disc[i] = 0
    disc[D_PIVOT] = 1
    if y[2] != 0.0 or y[3] != 0.0:
        disc[D_MODE] = MODE_ROCK
        disc[D_PIVOT] = initial_pivot(y[2], y[3])
        met[M_T_UPLIFT] = t0
        track_rotation(y[2], met)
    else:
        disc[D_MODE] = MODE_REST
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
def flexible_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
                      hist_d, log, cnt):
    """One flexible-body run with time history and event log."""
    return run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
               log, cnt)


@jit_parallel
def flexible_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Independent flexible-body runs in parallel (rows of Y0/PAR/HDR/OPT)."""
    sweep_rows(run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
