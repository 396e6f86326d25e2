"""Flexible body on the two-spring foundation (physics.md 3 and 5.1).

The flexible body of kernels/flexible.py (a mass m on an elastic column of
height H, stiffness m w_n^2 and damping 2 zeta m w_n, over a rigid base of
half-width B, mass m_b, inertia I_b about its CM at height h_b; the mass may
carry an inertia I_m that turns with the base) stands on the tensionless
corner spring-dashpots of kernels/foundation.py instead of rigid ground.

State ``y = (y_c, y_c', u, u', q, q')`` [m, m/s, m, m/s, rad, rad/s]: the
vertical displacement of the base centre (held horizontally, as the rigid
block's), the column deflection u (body frame, perpendicular to the column)
and the rotation q.  Body frame (x, z) from the base centre maps to
(x cos q + z sin q, y_c - x sin q + z cos q); the mass sits at (u, H), the
base CM at (0, h_b), corner s at (s B, 0).  Lagrange's equations (sympy:
tests/test_foundation_flexible.py) with G = g + a_v and the ground's a_g as
a horizontal inertial load:

    M(q) (y_c'', u'', q'') = F,   (with c = cos q, s = sin q, X = u c + H s,
                                   Y = H c - u s, the mass from the base centre)
    M = [[m + m_b,        -m s,   -m X - m_b h_b s               ],
         [-m s,            m,      m H                           ],
         [-m X - m_b h_b s, m H,   m (u^2 + H^2) + m_b h_b^2 + I_m + I_b]]
    F_y = f_R + f_L - (m + m_b) G + m (2 u' q' c + Y q'^2) + m_b h_b c q'^2
    F_u = -m w_n^2 u - 2 zeta m w_n u' + m G s - m a_g c + m u q'^2
    F_q = m (G X - a_g Y - 2 u u' q') + m_b h_b (G s - a_g c)
          - c (x_R f_R + x_L f_L)

Eliminating u'' with the u row leaves a 2x2 system in (y_c'', q'') whose
determinant m m_b ((u - h_b s c)^2 + h_b^2 c^4) + (m_b + m c^2) (I_m + I_b)
+ m_b^2 h_b^2 c^2 is positive for m_b > 0 (the front end requires a base
mass: with a massless base the three coordinates move a point mass in two
dimensions, a singular mass matrix).

The corners, their forces, switching (lift-off at zero force, soft
re-contact, the zero-force rule), the rotation's events and observers and
the initial corner states are kernels/foundation.py's (``ts_shared_*``,
rotation at index 4).  Modes: both corners (MODE_REST, "contact"), one
(MODE_ROCK), none (MODE_FLIGHT).  Observers of u' = 0 give the exact
deflection extrema (M_MAX_U, M_MIN_U).

With E = T + m G Y_mass + m_b G Y_base + m w_n^2 u^2 / 2
+ sum_s k_v max(delta_s, 0)^2 / 2 the free motion (a_g = a_v = 0) has
dE/dt = -2 zeta m w_n u'^2 - c_v sum_contact delta_s'^2 (<= 0; a released
corner still pressed has k_v delta delta' < 0), so E never grows.

Rest and early decision (ff_after_step; full contact after the excitation,
symmetric base, level ground), as the rigid block's (kernels/foundation.py,
ts_stays_in_contact and ts_at_rest) with the column: the energy above the
static equilibrium (y_c = -(m + m_b) G / (2 k_v), u = q = 0) in full contact
is dE = T + k_v eta^2 + k_v B^2 sin^2 q - G (m H + m_b h_b) (1 - cos q)
- m G u sin q + m w_n^2 u^2 / 2 (eta = y_c - y_eq), which never grows there.
With 1 - cos q <= sin^2 q it is at least T + k_v eta^2 + Q(sin q, u), Q the
form [[A, -m G / 2], [-m G / 2, m w_n^2 / 2]], A = k_v B^2 - G (m H + m_b
h_b); where Q is positive definite, sin^2 q <= dE / kappa (kappa = det Q /
(m w_n^2 / 2)) and u^2 <= dE A / det Q.  A corner's speed is the base's
corner speed, so delta'^2 <= 2 T (1/m_b + (B^2 + h_b^2) / (I_b + I_m)), and
Cauchy-Schwarz bounds each corner force's distance from (m + m_b) G / 2 as
in ts_never_lifts (k_v w^2 there is k_v B^2 sin^2 q here).
"""

import math

import numpy as np

from .config import jit, jit_parallel
from .excitation import ground
from .flexible import track_u
from .foundation import (D_HOLD_LEFT, D_HOLD_RIGHT, D_LEFT, D_RIGHT,
                         TS_CROSS, TS_LEFT, TS_OVERTURN, TS_PASS_ALPHA,
                         TS_PEAK, TS_RIGHT, corner_arm, corner_force, spring_par, spring_tol,
                         never_static, ts_init_corners, ts_shared_event,
                         ts_shared_transition, within_tolerance)
from .rodas import auto_dense, auto_step, work_rows
from .hybrid import book_time, final_status, integrate_with, sweep_rows
from .layout import (D_MODE, D_STATIC, MODE_REST, M_MAX_THETA_NEG,
                     M_MAX_THETA_POS, M_MAX_U, M_MIN_U, M_T_EXC_END, N_DISC,
                     O_EARLY_EXIT, O_EPS_OMEGA, O_T0, P_B, P_B_SKEW, P_CV,
                     P_G, P_KV, PF_H, PF_HB, PF_IB, PF_IM, PF_M, PF_MB, PF_WN,
                     PF_ZETA, RUNNING, S_ON)
from .rigid import track_rotation

from .layout import N_PAR_FOUNDATION_FLEXIBLE as N_PAR  # noqa: E402,F401

IQ = 4              # the rotation's index in the state
FF_N_EVENTS = 9
# ids 0..5 are the two-spring events (kernels.foundation TS_*)
FF_U_MAX = 6        # observer: u' = 0 from above
FF_U_MIN = 7        # observer: u' = 0 from below
FF_REST = 8         # the rest rule held after a step (ff_after_step)
assert (TS_RIGHT, TS_LEFT, TS_CROSS, TS_OVERTURN, TS_PEAK,
        TS_PASS_ALPHA) == (0, 1, 2, 3, 4, 5)


@jit
def ff_accelerations(t, y, par, disc, hdr, smp):
    """(y_c'', u'', q'') of the module docstring's equations."""
    ag, av = ground(t, hdr, smp)
    G = par[P_G] + av
    m = par[PF_M]
    mb = par[PF_MB]
    H = par[PF_H]
    hb = par[PF_HB]
    wn = par[PF_WN]
    u = y[2]
    du = y[3]
    q = y[4]
    dq = y[5]
    c = math.cos(q)
    s = math.sin(q)
    X = u * c + H * s
    Y = H * c - u * s
    fR = corner_force(y, IQ, 1.0, par, disc[D_RIGHT])
    fL = corner_force(y, IQ, -1.0, par, disc[D_LEFT])
    moment = corner_arm(1.0, par) * fR + corner_arm(-1.0, par) * fL
    Fy = (fR + fL - (m + mb) * G + m * (2.0 * du * dq * c + Y * dq * dq)
          + mb * hb * c * dq * dq)
    Fu = (-m * wn * (wn * u + 2.0 * par[PF_ZETA] * du) + m * G * s
          - m * ag * c + m * u * dq * dq)
    Fq = (m * (G * X - ag * Y - 2.0 * u * du * dq)
          + mb * hb * (G * s - ag * c) - c * moment)
    # u'' = Fu/m + s y'' - H q'' from the u row, into the y and q rows
    a11 = mb + m * c * c
    a12 = -m * u * c - mb * hb * s
    a22 = m * u * u + mb * hb * hb + par[PF_IM] + par[PF_IB]
    r1 = Fy + s * Fu
    r2 = Fq - H * Fu
    det = a11 * a22 - a12 * a12
    ydd = (a22 * r1 - a12 * r2) / det
    qdd = (a11 * r2 - a12 * r1) / det
    return ydd, Fu / m + s * ydd - H * qdd, qdd


@jit
def ff_yq(t, y, par, disc, hdr, smp):
    """(y_c'', q''): the accelerations the two-spring pieces read."""
    ydd, _udd, qdd = ff_accelerations(t, y, par, disc, hdr, smp)
    return ydd, qdd


@jit
def ff_rhs(t, y, par, disc, hdr, smp, out):
    ydd, udd, qdd = ff_accelerations(t, y, par, disc, hdr, smp)
    out[0] = y[1]
    out[1] = ydd
    out[2] = y[3]
    out[3] = udd
    out[4] = y[5]
    out[5] = qdd


@jit
def ff_event(k, t, y, par, disc, hdr, smp):
    if k == FF_REST:
        # fires at once: the phase ends where the static phase begins
        return (-1.0 if disc[D_STATIC] == 1 else np.inf), 0.0, True
    if k == FF_U_MAX or k == FF_U_MIN:
        sg = 1.0 if k == FF_U_MAX else -1.0
        _ydd, udd, _qdd = ff_accelerations(t, y, par, disc, hdr, smp)
        return sg * y[3], sg * udd, False
    return ts_shared_event(ff_yq, IQ, k, t, y, par, disc, hdr, smp)


@jit
def ff_transition(k, t, y, par, disc, hdr, smp, opt, met, log, cnt):
    book_time(t, disc, met)
    if k == FF_REST:
        ff_set_rest(y, par)
        return RUNNING
    if k == FF_U_MAX or k == FF_U_MIN:
        track_u(y[2], met)
        return RUNNING
    return ts_shared_transition(ff_yq, IQ, k, t, y, par, disc, hdr, smp, opt,
                                met, log, cnt)


@jit
def ff_equilibrium(par):
    """y_c of the static equilibrium in full contact (u = q = 0) [m]."""
    return -0.5 * (par[PF_M] + par[PF_MB]) * par[P_G] / par[P_KV]


@jit
def ff_kinetic(y, par):
    """T [J]: the mass at (X, y_c + Y), the base's CM at (h_b s, y_c + h_b c)
    and I_m + I_b turning with q (module docstring)."""
    m = par[PF_M]
    mb = par[PF_MB]
    H = par[PF_H]
    hb = par[PF_HB]
    u, du, dq = y[2], y[3], y[5]
    c = math.cos(y[4])
    s = math.sin(y[4])
    vx = du * c - u * s * dq + H * c * dq
    vy = y[1] - H * s * dq - du * s - u * c * dq
    bx = hb * c * dq
    by = y[1] - hb * s * dq
    return (0.5 * m * (vx * vx + vy * vy) + 0.5 * mb * (bx * bx + by * by)
            + 0.5 * (par[PF_IM] + par[PF_IB]) * dq * dq)


@jit
def ff_rest_bounds(y, par):
    """(dE, never_lifts, sin_max, u_max) of the module docstring's bounds:
    the energy above the static equilibrium [J], whether no corner can
    lift again, and the bounds on |sin q| and |u| [m] for good (never_lifts
    False, the bounds inf, where the form is not positive definite)."""
    m = par[PF_M]
    mb = par[PF_MB]
    G = par[P_G]
    k = par[P_KV]
    c_v = par[P_CV]
    B = par[P_B]
    wn = par[PF_WN]
    q = y[4]
    u = y[2]
    sq = math.sin(q)
    half = math.sin(0.5 * q)
    eta = y[0] - ff_equilibrium(par)
    lever = m * par[PF_H] + mb * par[PF_HB]
    dE = (ff_kinetic(y, par) + k * eta * eta + k * B * B * sq * sq
          - 2.0 * G * lever * half * half - m * G * u * sq
          + 0.5 * m * wn * wn * u * u)
    A = k * B * B - G * max(lever, 0.0)
    q22 = 0.5 * m * wn * wn
    det = A * q22 - 0.25 * (m * G) ** 2
    i_rot = par[PF_IM] + par[PF_IB]
    if not (A > 0.0 and det > 0.0 and i_rot > 0.0):
        return dE, False, np.inf, np.inf
    dE0 = max(dE, 0.0)
    kappa = det / q22
    m_inv = 1.0 / mb + (B * B + par[PF_HB] ** 2) / i_rot
    reach = dE0 * (k + k * k * B * B / kappa + 2.0 * c_v * c_v * m_inv)
    never = reach < 0.25 * ((m + mb) * G) ** 2
    return dE, never, math.sqrt(dE0 / kappa), math.sqrt(dE0 * A / det)


@jit
def ff_within_maxima(sin_max, u_max, met):
    """No later |q| or |u| can pass the maxima so far."""
    return (sin_max < 1.0 and math.asin(sin_max)
            <= min(met[M_MAX_THETA_POS], met[M_MAX_THETA_NEG])
            and u_max <= min(met[M_MAX_U], met[M_MIN_U]))


@jit
def ff_set_rest(y, par):
    y[0] = ff_equilibrium(par)
    for i in range(1, 6):
        y[i] = 0.0


@jit
def ff_after_step(t, y, par, disc, hdr, smp, opt, met, at_end):
    """After the excitation in full contact: the early decision (no corner
    can lift again and no maximum can grow: final) and the rest rule (dE <=
    (I_m + I_b) eps_omega^2 / 2 bounds |q'| by eps_omega for good, or the
    state is the equilibrium to within the tolerance and no maximum can
    grow), both only where no corner can lift (module docstring)."""
    disc[D_HOLD_RIGHT] = 0
    disc[D_HOLD_LEFT] = 0
    track_rotation(y[IQ], met)
    track_u(y[2], met)
    book_time(t, disc, met)
    if at_end:
        return final_status(disc, met)
    if (disc[D_MODE] != MODE_REST or t < met[M_T_EXC_END]
            or hdr[S_ON] != 0.0 or par[P_B_SKEW] != 0.0):
        return RUNNING
    dE, never, sin_max, u_max = ff_rest_bounds(y, par)
    if not never:
        return RUNNING
    early = opt[O_EARLY_EXIT] != 0.0
    bounded = ff_within_maxima(sin_max, u_max, met)
    if early and bounded:
        return final_status(disc, met)
    eps_w = opt[O_EPS_OMEGA]
    if not eps_w > 0.0:
        return RUNNING
    if (dE <= 0.5 * (par[PF_IM] + par[PF_IB]) * eps_w * eps_w
            or bounded and within_tolerance(y, ff_equilibrium(par), opt)):
        if early:
            ff_set_rest(y, par)
            return final_status(disc, met)
        disc[D_STATIC] = 1
    return RUNNING


@jit
def ff_init_state(t0, y, par, disc, hdr, smp, met, log, cnt):
    ts_init_corners(t0, y, IQ, par, disc, met)
    track_u(y[2], met)


@jit
def ff_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d, log,
           cnt):
    disc = np.zeros(N_DISC, dtype=np.int64)
    par = spring_par(par, opt)
    ff_init_state(opt[O_T0], y, par, disc, hdr, smp, met, log, cnt)
    return integrate_with(auto_step, auto_dense, work_rows, spring_tol,
                          ff_rhs, ff_event, ff_transition, never_static,
                          ff_after_step, FF_N_EVENTS, y, par, disc, hdr,
                          smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                          log, cnt)


@jit
def flexible_two_spring_simulate(y, par, hdr, smp, opt, t_eval, met, hist_t,
                                 hist_y, hist_d, log, cnt):
    """One run, y = (y_c, y_c', u, u', q, q'), with history and log."""
    return ff_run(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                  log, cnt)


@jit_parallel
def flexible_two_spring_sweep(Y0, PAR, HDR, smp, OPT, status, MET, YF):
    """Many independent runs in parallel (see rigid_sweep)."""
    sweep_rows(ff_run, Y0, PAR, HDR, smp, OPT, status, MET, YF)
