"""Free flight of the flexible body (issue #13 item 4; kernels/flexible_flight.py, physics.md 4.6).

Oracles, none of them the kernel under test:

1. a sympy Lagrangian of the free body (column mass + rigid base) in q = (x, z, theta, u): its
   mass matrix and forces against the rows written in the kernel's docstring, its accelerations
   against the kernel at random states, and its rocking limit (pivot fixed) against
   flexible_friction's stick-rock solve (accelerations and contact forces);
2. momentum: the centre of mass of column mass + base is ballistic in flight (x'' = -a_g,
   z'' = -G), at random states and along a simulated flight (closed form);
3. energy (kinetic + gravity + column strain, ground frame, constant g, no a_g) never grows over
   flights, landings and what follows, from random releases in flight;
4. a frictionless plastic landing conserves the angular momentum about the landing corner (and
   the horizontal momentum); a sticking landing stops the corner; neither adds energy;
5. an independent SciPy solve_ivp integration of one flight (the sympy equations, its own
   ground acceleration and landing event) against the kernel: landing time and state;
6. where nothing lifts off, lift_off="flight" gives flexible_friction's results exactly (same
   steps, statuses and maxima), and it flies exactly where lift_off="stop" stops; with
   mu_s = inf (flexible_friction's kernel called directly) the histories agree up to the first
   lift-off;
7. the front end: simulate, overturning_spectrum, the registry and the reported metrics.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

import fastrock as fr
from fastrock import FlexibleBody, Friction, Pulse, Solver
from fastrock.model import excitation as X
from fastrock.running import registry
from fastrock.kernels import flexible_flight as K
from fastrock.kernels import flexible_friction as KF
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS
from fastrock.running.models import flexible_flight_par, flexible_friction_par

ALPHA = 0.3
P = 2.0
WR = 9.0
ZETA = 0.05


def body(mb=0.1, hb=0.0, zeta=ZETA, **kw):
    return FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=WR, zeta=zeta, base_mass_ratio=mb,
                        base_cm_height=hb, **kw)


def pulse(amplitude_ratio, frequency_ratio, sign=1):
    return Pulse(amplitude_ratio, frequency_ratio, sign=sign, amplitude_unit="g_tan_alpha",
                 frequency_unit="omega_p/p")


def fpar(b, mu, mu_k=None):
    return flexible_flight_par(b, Friction(mu, mu_k, lift_off="flight"))


def run_kernel(b, par, y0, excitation=None, vertical=None, t_end=3.0, rtol=1e-10, cap=200_000,
               kernel=None, t_eval=None):
    """One run with every step stored: (status, t, Y, D, met, events)."""
    kernel = kernel or K.flexible_flight_simulate
    hdr, smp = X.to_header(b, excitation, vertical)
    opt = Solver(rtol=rtol, max_steps=2_000_000).options(t_end, False)
    y = np.array(y0, float)
    n = y.size
    met = np.zeros(L.N_MET)
    te = np.empty(0) if t_eval is None else np.asarray(t_eval, float)
    ht, hy, hd = np.empty(cap), np.empty((cap, n)), np.empty((cap, 3), np.int64)
    log = np.empty((20000, L.N_LOG))
    cnt = np.zeros(N_COUNTERS, np.int64)
    st = kernel(y, par, hdr, smp, opt, te, met, ht, hy, hd, log, cnt)
    k = int(cnt[C_NHIST])
    return int(st), ht[:k], hy[:k], hd[:k], met, log[:int(cnt[C_NLOG])]


# ---------------------------------------------------------------- 1. sympy Lagrangian
@functools.lru_cache(maxsize=1)
def flight_lagrangian():
    """Per unit mass: q = (x, z, theta, u) of O, the bottom centre of the base; returns the
    symbolic mass matrix and forces (M q'' = f), and their lambdified forms."""
    t = sp.symbols("t")
    H, mb, hb, ib, im, wn, z, G, ag = sp.symbols("H m_b h_b I_b i_m w_n zeta G a_g", real=True)
    x, y, th, u = (sp.Function(n)(t) for n in ("x", "z", "theta", "u"))
    q = [x, y, th, u]
    dq = [sp.diff(v, t) for v in q]
    c, sn = sp.cos(th), sp.sin(th)
    xm, ym = x + u * c + H * sn, y - u * sn + H * c          # O + u e1 + H e2
    xb, yb = x + hb * sn, y + hb * c                        # O + h_b e2
    T = ((sp.diff(xm, t) ** 2 + sp.diff(ym, t) ** 2) / 2 + im * dq[2] ** 2 / 2
         + mb * (sp.diff(xb, t) ** 2 + sp.diff(yb, t) ** 2) / 2 + ib * dq[2] ** 2 / 2)
    V = G * (ym + mb * yb) + ag * (xm + mb * xb) + wn ** 2 * u ** 2 / 2
    R = z * wn * dq[3] ** 2                                  # Rayleigh: c/m = 2 zeta w_n
    Lg = T - V
    acc = sp.symbols("xdd zdd tdd udd")
    vel = sp.symbols("xd zd td ud")
    pos = sp.symbols("X Z TH U")
    sub = {}
    for v, a, w in zip(q, acc, vel):
        sub[sp.diff(v, t, 2)] = a
        sub[sp.diff(v, t)] = w
    sub2 = dict(zip(q, pos))
    eqs = [sp.expand((sp.diff(sp.diff(Lg, d), t) - sp.diff(Lg, v) + sp.diff(R, d)).subs(sub).subs(sub2))
           for v, d in zip(q, dq)]
    M = sp.Matrix([[sp.diff(e, a) for a in acc] for e in eqs])
    f = sp.Matrix([-(e.subs({a: 0 for a in acc})) for e in eqs])
    prm = (H, mb, hb, ib, im, wn, z, G, ag)
    args = prm + (pos[2], pos[3]) + vel
    return (M, f, prm, pos, vel, sp.lambdify(args, M, "numpy"), sp.lambdify(args, f, "numpy"))


def test_sympy_flight_equations_are_the_rows_of_the_kernel_docstring():
    M, f, (H, mb, hb, ib, im, wn, z, G, ag), (_X, _Z, TH, U), (xd, zd, td, ud), *_ = flight_lagrangian()
    c, sn = sp.cos(TH), sp.sin(TH)
    mxt = H * c - U * sn + mb * hb * c
    mzt = -H * sn - U * c - mb * hb * sn
    M_doc = sp.Matrix([[1 + mb, 0, mxt, c], [0, 1 + mb, mzt, -sn],
                       [mxt, mzt, H ** 2 + U ** 2 + im + ib + mb * hb ** 2, H], [c, -sn, H, 1]])
    f_doc = sp.Matrix([
        -ag * (1 + mb) + 2 * ud * td * sn + U * td ** 2 * c + H * td ** 2 * sn + mb * hb * td ** 2 * sn,
        -G * (1 + mb) + 2 * ud * td * c - U * td ** 2 * sn + H * td ** 2 * c + mb * hb * td ** 2 * c,
        G * (U * c + H * sn) - ag * (H * c - U * sn) + mb * hb * (G * sn - ag * c) - 2 * U * ud * td,
        -wn ** 2 * U - 2 * z * wn * ud + G * sn - ag * c + U * td ** 2])
    assert sp.simplify(M - M_doc) == sp.zeros(4, 4)
    assert sp.simplify(f - f_doc) == sp.zeros(4, 1)


def constant_ground(b, a_g, a_v=0.0):
    h = Pulse(kind="rectangular", amplitude=abs(a_g), sign=1 if a_g >= 0 else -1, amplitude_unit="m/s2",
              duration=100.0)
    v = Pulse(kind="rectangular", amplitude=abs(a_v), sign=1 if a_v >= 0 else -1, amplitude_unit="m/s2",
              duration=100.0) if a_v else None
    return X.to_header(b, h, v)


def _random_state(rng, b):
    uy = b.uplift_deformation
    return (rng.uniform(-3, 3) * uy, rng.uniform(-0.5, 0.5), rng.uniform(-1.2, 1.2), rng.uniform(-2, 2))


def _prm(b, par, G, ag):
    return (b.H, par[L.F_MB], par[L.F_HB], par[L.F_IB], par[L.F_IM], b.omega_n, b.zeta, G, ag)


@pytest.mark.parametrize("hb", [0.0, 0.3])
def test_kernel_flight_accelerations_match_the_sympy_lagrangian(hb):
    *_, Mf, ff = flight_lagrangian()
    rng = np.random.default_rng(3)
    b = body(hb=hb)
    par = fpar(b, 0.5)
    for _ in range(25):
        ag, av = rng.uniform(-5, 5), rng.uniform(-4, 4)
        hdr, smp = constant_ground(b, ag, av)
        u, du, th, dth = _random_state(rng, b)
        args = _prm(b, par, b.g + av, ag) + (th, u, rng.uniform(-1, 1), rng.uniform(-1, 1), dth, du)
        M = np.array(Mf(*args), float)
        f = np.array(ff(*args), float).ravel()
        expected = np.linalg.solve(M, f)
        got = K.flight_acc(1.0, u, du, th, dth, par, hdr, smp)
        np.testing.assert_allclose(got, expected, rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize("hb", [0.0, 0.3])
def test_rocking_limit_is_flexible_frictions_stick_rock(hb):
    """Pivot s fixed on the ground (x = s B (1 - cos), z = s B sin): the flight rows hold with the
    ground's force (F, N) at the pivot, i.e. M q'' - f = J^T (F, N), where q'' follows from
    flexible_friction's stick-rock (u'', theta'') and (F, N) are its contact forces."""
    *_, Mf, ff = flight_lagrangian()
    rng = np.random.default_rng(5)
    b = body(hb=hb)
    par = fpar(b, 0.5)
    for _ in range(25):
        ag = rng.uniform(-5, 5)
        hdr, smp = constant_ground(b, ag)
        s = int(rng.choice([-1, 1]))
        u, du, th, dth = _random_state(rng, b)
        th = s * abs(th)
        y = np.array([u, du, th, dth, 0.0, 0.0])
        udd, tdd, F, N = KF.stick_rock(1.0, y, s, par, hdr, smp)
        c, sn, sB = math.cos(th), math.sin(th), s * b.B
        xd, zd = sB * sn * dth, sB * c * dth
        xdd = sB * (c * dth ** 2 + sn * tdd)
        zdd = sB * (c * tdd - sn * dth ** 2)
        args = _prm(b, par, b.g, ag) + (th, u, xd, zd, dth, du)
        M = np.array(Mf(*args), float)
        f = np.array(ff(*args), float).ravel()
        lhs = M @ np.array([xdd, zdd, tdd, udd]) - f
        JT = np.array([[1.0, 0.0], [0.0, 1.0], [-sB * sn, -sB * c], [0.0, 0.0]])
        np.testing.assert_allclose(lhs, JT @ np.array([F, N]), rtol=1e-9, atol=1e-9)


# ---------------------------------------------------------------- 2. ballistic centre of mass
def _cm(y, b, par):
    """(x_cm, z_cm) of column mass + base from flight coordinates (rows of Y)."""
    u, th, x, z = y[..., 0], y[..., 2], y[..., 4], y[..., 6]
    mb, hb = par[L.F_MB], par[L.F_HB]
    c, sn = np.cos(th), np.sin(th)
    xm, zm = x + u * c + b.H * sn, z - u * sn + b.H * c
    return (xm + mb * (x + hb * sn)) / (1 + mb), (zm + mb * (z + hb * c)) / (1 + mb)


def _cm_velocity(y, b, par):
    u, du, th, dth, xd, zd = y[0], y[1], y[2], y[3], y[5], y[7]
    mb, hb = par[L.F_MB], par[L.F_HB]
    c, sn = math.cos(th), math.sin(th)
    vxm = xd + du * c + (-u * sn + b.H * c) * dth
    vzm = zd - du * sn + (-u * c - b.H * sn) * dth
    return (vxm + mb * (xd + hb * c * dth)) / (1 + mb), (vzm + mb * (zd - hb * sn * dth)) / (1 + mb)


@pytest.mark.parametrize("hb", [0.0, 0.3])
def test_centre_of_mass_is_ballistic_at_random_states(hb):
    rng = np.random.default_rng(11)
    b = body(hb=hb)
    par = fpar(b, 0.5)
    mb = par[L.F_MB]
    for _ in range(25):
        ag, av = rng.uniform(-5, 5), rng.uniform(-4, 4)
        hdr, smp = constant_ground(b, ag, av)
        u, du, th, dth = _random_state(rng, b)
        xdd, zdd, tdd, udd = K.flight_acc(1.0, u, du, th, dth, par, hdr, smp)
        c, sn = math.cos(th), math.sin(th)
        # second derivatives of u e1 + H e2 and h_b e2 (chain rule)
        axm = xdd + udd * c - 2 * du * sn * dth + (-u * sn + b.H * c) * tdd - (u * c + b.H * sn) * dth ** 2
        azm = zdd - udd * sn - 2 * du * c * dth + (-u * c - b.H * sn) * tdd + (u * sn - b.H * c) * dth ** 2
        axb = xdd + hb * (c * tdd - sn * dth ** 2)
        azb = zdd - hb * (sn * tdd + c * dth ** 2)
        np.testing.assert_allclose([(axm + mb * axb) / (1 + mb), (azm + mb * azb) / (1 + mb)],
                                   [-ag, -(b.g + av)], rtol=1e-11, atol=1e-11)


def _release(b, u=0.0, du=0.2, th=0.05, dth=0.8, xd=0.1, zd=1.0, z_extra=0.0):
    """A flight state (both corners at or above the ground)."""
    z = b.B * abs(math.sin(th)) + z_extra
    return np.array([u, du, th, dth, 0.0, xd, z, zd])


def test_centre_of_mass_is_ballistic_along_a_simulated_flight():
    b = body()
    par = fpar(b, 0.5)
    y0 = _release(b, u=0.3 * b.uplift_deformation, du=0.3, th=0.05, dth=0.6, xd=0.2, zd=0.9)
    st, t, Y, D, met, log = run_kernel(b, par, y0, t_end=1.0)
    assert st > 0, st
    first = np.flatnonzero(D[:, 0] != L.MODE_FLIGHT)[0]          # the first landing ends the flight
    tf, Yf = t[:first], Y[:first]
    assert first > 20 and tf[-1] > 0.05
    xc, zc = _cm(Yf, b, par)
    vx0, vz0 = _cm_velocity(Yf[0], b, par)
    np.testing.assert_allclose(xc, xc[0] + vx0 * tf, rtol=0, atol=1e-8)
    np.testing.assert_allclose(zc, zc[0] + vz0 * tf - b.g * tf ** 2 / 2, rtol=0, atol=1e-8)
    assert met[L.M_N_FLIGHTS] >= 1 and met[L.M_T_FLIGHT] >= tf[-1] - 1e-12
    # the apex observer books the jump, the largest rise of the CM above its rest height: at
    # least the first flight's apex (closed form) and every stored flight row
    rest = (b.H + par[L.F_MB] * par[L.F_HB]) / (1 + par[L.F_MB])
    apex = zc[0] + vz0 ** 2 / (2 * b.g) - rest
    rise = _cm(Y[D[:, 0] == L.MODE_FLIGHT], b, par)[1] - rest
    assert vz0 > 0 and apex <= met[L.M_MAX_JUMP] + 1e-9
    assert rise.max() <= met[L.M_MAX_JUMP] + 1e-12 and met[L.M_MAX_JUMP] <= rise.max() + 1e-3


# ---------------------------------------------------------------- 3. energy
def _to_flight(Y, D, b):
    """Every history row in flight coordinates (contact rows converted from their pivot)."""
    F = Y.copy()
    contact = D[:, 0] != L.MODE_FLIGHT
    s = np.where(D[:, 0] == L.MODE_REST, 1, D[:, 1])[contact]
    th, dth = Y[contact, 2], Y[contact, 3]
    F[contact, 4] = Y[contact, 4] + s * b.B * (1 - np.cos(th))
    F[contact, 5] = Y[contact, 5] + s * b.B * np.sin(th) * dth
    F[contact, 6] = s * b.B * np.sin(th)
    F[contact, 7] = s * b.B * np.cos(th) * dth
    return F


def _energy(F, b, par):
    """Kinetic + gravity + strain per unit mass (constant g, no a_g), flight coordinates."""
    u, du, th, dth, xd, zd = F[:, 0], F[:, 1], F[:, 2], F[:, 3], F[:, 5], F[:, 7]
    mb, hb = par[L.F_MB], par[L.F_HB]
    c, sn = np.cos(th), np.sin(th)
    vxm = xd + du * c + (-u * sn + b.H * c) * dth
    vzm = zd - du * sn + (-u * c - b.H * sn) * dth
    vxb, vzb = xd + hb * c * dth, zd - hb * sn * dth
    T = 0.5 * (vxm ** 2 + vzm ** 2 + mb * (vxb ** 2 + vzb ** 2) + (par[L.F_IM] + par[L.F_IB]) * dth ** 2)
    _xc, zc = _cm(F, b, par)
    return T + b.g * (1 + mb) * zc + 0.5 * b.omega_n ** 2 * u ** 2


@pytest.mark.parametrize("mu", [0.3, 1.0, math.inf])
@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_energy_never_grows_over_flights_and_landings(mu, zeta):
    rng = np.random.default_rng(17 + int(10 * zeta))
    b = body(zeta=zeta)
    par = fpar(b, mu)
    uy = b.uplift_deformation
    landings = 0
    for _ in range(6):
        y0 = _release(b, u=rng.uniform(-2, 2) * uy, du=rng.uniform(-0.3, 0.3), th=rng.uniform(-0.2, 0.2),
                      dth=rng.uniform(-1.5, 1.5), xd=rng.uniform(-0.5, 0.5), zd=rng.uniform(0.0, 1.0),
                      z_extra=rng.uniform(0.0, 0.05))
        st, t, Y, D, met, log = run_kernel(b, par, y0, t_end=1.5)
        assert st in (L.SAFE_MOVING, L.SAFE_REST, L.OVERTURN_MODE1), st
        E = _energy(_to_flight(Y, D, b), b, par)
        scale = E.max() - E.min() + 1.0
        assert np.diff(E).max() <= 1e-8 * scale, np.diff(E).max()
        # and at each landing in particular (rows just before and after it)
        land = np.flatnonzero((D[:-1, 0] == L.MODE_FLIGHT) & (np.diff(t) == 0.0))
        landings += land.size
        assert (E[land + 1] <= E[land] + 1e-12 * scale).all()
    assert landings >= 6


# ---------------------------------------------------------------- 4. landing impact
def _landing_state(rng, b, sg):
    """A flight state with corner sg on the ground moving down, the other above it."""
    uy = b.uplift_deformation
    th = sg * rng.uniform(0.01, 0.5)
    y = np.array([rng.uniform(-2, 2) * uy, rng.uniform(-0.5, 0.5), th, rng.uniform(-2, 2), 0.3,
                  rng.uniform(-1, 1), 0.0, 0.0])
    y[6] = sg * b.B * math.sin(th)
    vn = -rng.uniform(0.05, 1.5)
    y[7] = vn + sg * b.B * math.cos(th) * y[3]
    return y


def _angular_momentum_about(F, b, par, px, pz):
    """Counter-clockwise angular momentum per unit mass about the ground point (px, pz)."""
    u, du, th, dth, x, xd, z, zd = F
    mb, hb = par[L.F_MB], par[L.F_HB]
    c, sn = math.cos(th), math.sin(th)
    xm, zm = x + u * c + b.H * sn, z - u * sn + b.H * c
    xb, zb = x + hb * sn, z + hb * c
    vxm = xd + du * c + (-u * sn + b.H * c) * dth
    vzm = zd - du * sn + (-u * c - b.H * sn) * dth
    vxb, vzb = xd + hb * c * dth, zd - hb * sn * dth
    return ((xm - px) * vzm - (zm - pz) * vxm + mb * ((xb - px) * vzb - (zb - pz) * vxb)
            - (par[L.F_IM] + par[L.F_IB]) * dth)       # theta is clockwise


@pytest.mark.parametrize("hb", [0.0, 0.3])
def test_frictionless_plastic_landing_conserves_angular_momentum_about_the_corner(hb):
    rng = np.random.default_rng(23)
    b = body(hb=hb)
    par = fpar(b, 0.0)
    for _ in range(40):
        sg = int(rng.choice([-1, 1]))
        y = _landing_state(rng, b, sg)
        th = y[2]
        px, pz = y[4] + sg * b.B * math.cos(th), 0.0                # the corner, on the ground
        L0 = _angular_momentum_about(y, b, par, px, pz)
        p0 = _cm_velocity(y, b, par)
        E0 = _energy(y[None, :], b, par)[0]
        post = y.copy()
        K.corner_impact(sg, post, par)
        gap, vn, _vt = K.corner_kin(sg, post, par)
        assert abs(vn) < 1e-12 and abs(gap) < 1e-15
        np.testing.assert_allclose(_angular_momentum_about(post, b, par, px, pz), L0, rtol=1e-11, atol=1e-12)
        assert abs(_cm_velocity(post, b, par)[0] - p0[0]) < 1e-12           # no tangential impulse
        assert _energy(post[None, :], b, par)[0] <= E0 + 1e-12


@pytest.mark.parametrize("mu", [0.2, 0.6, math.inf])
def test_frictional_landing_dissipates_and_sticks_or_slips_consistently(mu):
    rng = np.random.default_rng(29)
    b = body()
    par = fpar(b, mu)
    sticks = 0
    for _ in range(60):
        sg = int(rng.choice([-1, 1]))
        y = _landing_state(rng, b, sg)
        E0 = _energy(y[None, :], b, par)[0]
        post = y.copy()
        vt, leaves = K.corner_impact(sg, post, par)
        _g, vn, vt_now = K.corner_kin(sg, post, par)
        assert _energy(post[None, :], b, par)[0] <= E0 + 1e-12
        if leaves:                  # mu = inf and the stick impulse would pull: the corner rises
            assert math.isinf(mu) and vn > 0 and abs(vt_now) < 1e-12
            continue
        assert abs(vn) < 1e-12 and abs(vt_now - vt) < 1e-12
        sticks += vt == 0.0
        # the impulse (from the CM velocity change, per unit mass) lies in the friction cone
        v0, v1 = np.array(_cm_velocity(y, b, par)), np.array(_cm_velocity(post, b, par))
        lt, ln = (1 + par[L.F_MB]) * (v1 - v0)
        assert ln > 0 and abs(lt) <= mu * ln * (1 + 1e-9) + 1e-12
    assert sticks > 0


# ---------------------------------------------------------------- 5. SciPy solve_ivp
def test_one_flight_against_an_independent_solve_ivp():
    """The first flight of the study body under a one-sine pulse (a_p = 1.6 g tan(alpha),
    omega_p/p = 1.3, mu = inf): the pivot lifts off while the pulse still acts.  solve_ivp
    integrates the sympy equations with its own a_g(t) from the kernel's lift-off state until a
    base corner reaches the ground."""
    *_, Mf, ff = flight_lagrangian()
    b = body()
    par = fpar(b, math.inf)
    exc = pulse(1.6, 1.3)
    st, t, Y, D, met, log = run_kernel(b, par, np.zeros(8), excitation=exc, t_end=2.4, rtol=1e-11,
                                       cap=400_000)
    fl = np.flatnonzero(D[:, 0] == L.MODE_FLIGHT)
    i0 = fl[0]
    i1 = i0 + np.flatnonzero(D[i0:, 0] != L.MODE_FLIGHT)[0] - 1          # last flight row (pre-landing)
    t0, t1 = t[i0], t[i1]
    assert 0.05 < t1 - t0 < 0.5 and t1 < exc.pulse_duration(b)
    a_p = 1.6 * b.g * math.tan(ALPHA)
    w_p = 1.3 * P

    def f(tt, q):
        ag = a_p * math.sin(w_p * tt)
        x, z, th, u, xd, zd, td, ud = q
        args = _prm(b, par, b.g, ag) + (th, u, xd, zd, td, ud)
        acc = np.linalg.solve(np.array(Mf(*args), float), np.array(ff(*args), float).ravel())
        return np.concatenate(([xd, zd, td, ud], acc))

    def corner(sg):
        def ev(tt, q):
            return q[1] - sg * b.B * math.sin(q[2])
        ev.terminal = True
        ev.direction = -1
        return ev

    y = Y[i0]
    q0 = [y[4], y[6], y[2], y[0], y[5], y[7], y[3], y[1]]
    sol = solve_ivp(f, (t0, t0 + 1.0), q0, method="DOP853", rtol=1e-12, atol=1e-14,
                    events=[corner(1), corner(-1)])
    hit = [e.size for e in sol.t_events]
    assert sol.status == 1 and sum(hit) == 1
    k = 0 if hit[0] else 1
    tl, ql = sol.t_events[k][0], sol.y_events[k][0]
    assert abs(tl - t1) < 1e-7
    yk = Y[i1]
    got = np.array([yk[4], yk[6], yk[2], yk[0], yk[5], yk[7], yk[3], yk[1]])
    scale = np.array([1e-3, 1e-3, 1e-2, 1e-3, 1e-2, 1e-2, 1e-1, 1e-1])
    np.testing.assert_allclose(got, ql, rtol=0, atol=1e-6 * scale.max())
    # the corner that lands is the kernel's (the landing log row names it)
    land = log[(log[:, L.LOG_KIND] == L.EV_CONTACT) & (log[:, L.LOG_T] == t1)]
    assert land.shape[0] == 1 and int(land[0, L.LOG_PIVOT]) == (1 if k == 0 else -1)


# ---------------------------------------------------------------- 6. flexible_friction where nothing flies
AMPS = np.linspace(1.0, 10.0, 7)
FREQS = np.linspace(1.0, 10.0, 7)


@pytest.mark.parametrize("mu", [0.4, 0.8])
def test_flight_is_flexible_friction_until_the_first_lift_off(mu):
    b = body()
    stop = fr.overturning_spectrum(b, AMPS, FREQS, friction=Friction(mu, lift_off="stop"), progress=False)
    flight = fr.overturning_spectrum(b, AMPS, FREQS, friction=Friction(mu, lift_off="flight"), progress=False)
    assert stop.attrs["kernel"] == "flexible_friction" and flight.attrs["kernel"] == "flexible_flight"
    lifted = (stop.outcome == "flight").to_numpy()
    assert 0 < lifted.sum() < lifted.size
    # flights happen exactly where lift_off="stop" stops (its slot M_N_LIFT_OFF counts flights)
    assert (flight.lift_offs.to_numpy() > 0).tolist() == lifted.tolist()
    assert not flight.outcome.isin(["flight", "failed"]).any()
    same = ~lifted
    for col in ("status", "impacts", "nfev"):
        assert (flight[col][same] == stop[col][same]).all(), col
    for col in ("max_rotation", "max_slide", "residual_slide", "max_deformation", "time_end"):
        np.testing.assert_allclose(flight[col][same], stop[col][same], rtol=1e-12, atol=1e-15)


def test_infinite_friction_follows_flexible_friction_until_it_flies():
    """mu_s = inf: flexible_friction's kernel (called directly, lift_off="stop") and the flight
    kernel take the same steps until the pivot lifts off; there the first stops with FLIGHT."""
    b = body()
    par = fpar(b, math.inf)
    par_ff = flexible_friction_par(b, Friction(math.inf))      # lift_off="stop"
    flown = 0
    for a, w in ((1.6, 1.3), (3.0, 2.5), (6.0, 4.0), (1.2, 1.0)):
        exc = pulse(a, w)
        st0, t0, Y0, D0, met0, _ = run_kernel(b, par_ff, np.zeros(6), excitation=exc, t_end=6.0, rtol=1e-8,
                                              kernel=KF.flexible_friction_simulate)
        st1, t1, Y1, D1, met1, log1 = run_kernel(b, par, np.zeros(8), excitation=exc, t_end=6.0, rtol=1e-8)
        if st0 == L.FLIGHT:
            flown += 1
            n = t0.size - 1                     # up to the lift-off (the last row is the stop)
            # it flies there, or holds the pivot (jam) where the free body would sink into the
            # ground: at N = 0 infinite friction may still push (F != 0)
            assert t1[n] == t0[-1]
            held = (log1[:, L.LOG_KIND] == L.EV_LIFT_OFF_HELD) & (log1[:, L.LOG_T] == t0[-1])
            assert D1[n, 0] == L.MODE_FLIGHT or held.any()
        else:
            n = t0.size
            assert st1 == st0 and met1[L.M_N_FLIGHTS] == 0
        np.testing.assert_array_equal(t1[:n], t0[:n])
        np.testing.assert_array_equal(Y1[:n, :6], Y0[:n])
        np.testing.assert_array_equal(D1[:n], D0[:n])
    assert flown >= 2


# ---------------------------------------------------------------- 7. front end
def test_the_registry_runs_flight_of_the_flexible_body():
    b = body()
    for fric in (Friction(0.5, lift_off="flight"), Friction(math.inf, lift_off="flight")):
        spec = registry.select(b, friction=fric)
        assert spec.name == "flexible_flight" and spec.model.flight and spec.friction
        assert spec.state_names == ("u", "u_dot", "theta", "theta_dot", "d", "d_dot", "z", "z_dot")
        assert spec.par[L.F_LIFT_OFF] == L.LIFT_OFF_FLIGHT
    assert registry.select(b, friction=Friction(0.5, lift_off="hold")).name == "flexible_friction"
    with pytest.raises(ValueError, match="impact='full-contact'"):
        registry.select(body(mb=0.0, impact="pivot-switch"), friction=Friction(0.5, lift_off="flight"))


@pytest.mark.parametrize("mu", [0.5, math.inf])
def test_simulate_reports_flights(mu):
    b = body()
    r = fr.simulate(b, pulse(1.6, 1.3), friction=Friction(mu, lift_off="flight"))
    assert r.kernel == "flexible_flight" and "flight" in r.effects
    m = r.metrics
    assert r.outcome == "mode1"
    assert m["flights"] >= 1 and m["time_flight"] > 0.05 and m["max_jump"] > 0.01
    h = r.history
    fl = h[h.contact == "flight"]
    assert len(fl) > 10 and (fl.z >= -1e-9).all() and {"z", "z_dot", "d", "u"} <= set(h.columns)
    assert (h.z[h.contact != "flight"] == 0).all()
    ev = r.events
    assert (ev.event == "flight").sum() == m["flights"]
    assert (ev.event == "contact").sum() >= 1             # landings
    # a vertical pulse beyond 1 g throws the body off the ground: a flat flight and a landing
    up = Pulse(kind="one-sine", amplitude=1.6, frequency=4.0, sign=-1, amplitude_unit="g")
    v = fr.simulate(b, None, vertical=up, friction=Friction(mu, lift_off="flight"), duration=2.0)
    assert v.metrics["flights"] >= 1 and v.metrics["max_jump"] > 0.0 and v.outcome in ("safe", "slide")
    assert fr.simulate(b, None, vertical=up, friction=Friction(mu if math.isfinite(mu) else 0.5),
                       duration=2.0).outcome == "flight"


def test_spectrum_runs_the_flight_kernel_and_agrees_with_simulate():
    b = body()
    fric = Friction(0.5, lift_off="flight")
    df = fr.overturning_spectrum(b, [1.6, 4.0], [1.3, 3.0], friction=fric, progress=False)
    assert df.attrs["kernel"] == "flexible_flight"
    for _, row in df.iterrows():
        r = fr.simulate(b, pulse(row.amplitude_ratio, row.frequency_ratio), friction=fric, early_exit=True)
        assert r.outcome == row.outcome
        assert r.metrics["flights"] == row.lift_offs          # the flights' slot (M_N_FLIGHTS)
        assert r.metrics["time_flight"] == pytest.approx(row.time_unloaded, rel=1e-12)


def test_no_failed_runs_over_random_scenes():
    """Random bodies (base mass and CM height, damping, frequency ratio), friction (mu_k <= mu_s,
    mu_s = inf included), pulses and vertical pulses: flight mode runs them all.  (A random
    sample of 7500 such runs: 6 failed with flight against 738 with "hold" and 464 with
    "stop", most of those inconsistent-contact, Painleve-type, at mu_s >= 1 or a heavy base.)"""
    rng = np.random.default_rng(12)
    n = 0
    for _ in range(8):
        b = FlexibleBody(alpha=rng.uniform(0.15, 0.4), p=rng.uniform(1, 4), omega_n_over_p=rng.uniform(3, 30),
                         zeta=rng.uniform(0, 0.1), base_mass_ratio=rng.uniform(0.05, 0.4),
                         base_cm_height=float(rng.choice([0.0, 0.2])))
        mu = float(rng.choice([0.2, 0.5, 1.0, math.inf]))
        fric = Friction(mu, rng.uniform(0.6, 1.0) * mu if math.isfinite(mu) else None, lift_off="flight")
        vert = Pulse(amplitude=rng.uniform(0.3, 1.6), frequency=rng.uniform(1, 6), sign=int(rng.choice([-1, 1])),
                     amplitude_unit="g") if rng.random() < 0.5 else None
        df = fr.overturning_spectrum(b, np.linspace(1, 8, 4), np.linspace(1, 8, 4), sign=[1, -1], friction=fric,
                                     vertical=vert, progress=False)
        assert not (df.outcome == "failed").any(), (b, mu, vert, df.status.value_counts().to_dict())
        n += int((df.lift_offs > 0).sum())
    assert n > 20                                                   # many of them fly
