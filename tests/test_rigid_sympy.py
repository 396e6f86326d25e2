"""The rigid kernel's equation of motion against a sympy Lagrangian (physics.md 1).

A block of mass M, centroidal inertia I_G, CM at distance R from the pivot corner s (slenderness
alpha), rocks by theta (clockwise positive).  Coordinates are relative to the ground: the
horizontal ground acceleration a_g enters as the d'Alembert force -M a_g, the vertical one as the
effective gravity G = g + a_v.  Lagrange's equation is solved for theta'' and compared with the
jitted ``fastrock.kernels.rigid.theta_ddot`` at random states, called with a hand-built parameter
vector and an excitation header whose RECTANGULAR channels hold a constant a_g and a_v.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from fastrock.kernels import layout as L
from fastrock.kernels import rigid as K

G_STD = 9.80665


def _derive():
    t = sp.symbols("t")
    M, I_G, R, alpha = sp.symbols("M I_G R alpha", positive=True)
    G, a_g = sp.symbols("G a_g", real=True)
    s = sp.symbols("s", real=True)                     # +1 right corner, -1 left corner
    th = sp.Function("theta")(t)
    b, h = R * sp.sin(alpha), R * sp.cos(alpha)
    # CM relative to the pivot: body-frame (-s b, h) rotated clockwise by theta
    X = -s * b * sp.cos(th) + h * sp.sin(th)
    Y = s * b * sp.sin(th) + h * sp.cos(th)
    T = sp.Rational(1, 2) * M * (sp.diff(X, t) ** 2 + sp.diff(Y, t) ** 2) \
        + sp.Rational(1, 2) * I_G * sp.diff(th, t) ** 2
    V = M * G * Y + M * a_g * X                         # gravity + d'Alembert force -M a_g
    Lag = T - V
    eq = sp.diff(sp.diff(Lag, sp.diff(th, t)), t) - sp.diff(Lag, th)
    thdd = sp.solve(sp.Eq(eq, 0), sp.diff(th, t, 2))[0]
    q, qd = sp.symbols("q qd", real=True)
    thdd = thdd.subs(sp.diff(th, t), qd).subs(th, q)
    thdd = sp.simplify(thdd.subs(s ** 2, 1))
    return thdd, (q, qd, s, M, I_G, R, alpha, G, a_g)


THDD, SYMS = _derive()
THDD_FN = sp.lambdify(SYMS, THDD, "math")


def test_lagrangian_reduces_to_housner_form():
    q, qd, s, M, I_G, R, alpha, G, a_g = SYMS
    I0 = I_G + M * R ** 2
    housner = -M * R * (G * sp.sin(s * alpha - q) + a_g * sp.cos(s * alpha - q)) / I0
    for sv in (1, -1):
        assert sp.simplify(sp.expand_trig((THDD - housner).subs(s, sv))) == 0
    # independent of theta' (no centripetal term about a fixed pivot)
    assert sp.diff(THDD, qd) == 0


def _par(alpha, p, g=G_STD):
    par = np.zeros(K.N_PAR)
    par[K.P_ALPHA] = alpha
    par[K.P_P] = p
    par[K.P_E] = 0.9
    par[K.P_G] = g
    par[K.P_THETA_OVER] = math.pi / 2
    return par


def _hdr(a_g, a_v):
    """Constant a_g, a_v: RECTANGULAR channels over [0, 100] s, amplitude |a|, sign sgn(a)."""
    hdr = np.zeros(L.N_EXC)
    for c, a in ((L.H_CHANNEL, a_g), (L.V_CHANNEL, a_v)):
        hdr[c + L.X_KIND] = L.EXC_RECTANGULAR
        hdr[c + L.X_AMP] = abs(a)
        hdr[c + L.X_SIGN] = 1.0 if a >= 0 else -1.0
        hdr[c + L.X_T0] = 0.0
        hdr[c + L.X_DUR] = 100.0
    return hdr


SMP = np.zeros(1)


def test_header_gives_constant_ground_acceleration():
    from fastrock.kernels.excitation import ground
    for a_g, a_v in ((1.7, -0.4), (-3.0, 2.5), (0.0, 0.0)):
        hdr = _hdr(a_g, a_v)
        for t in (0.0, 1.3, 99.0):
            assert ground(t, hdr, SMP) == (a_g, a_v)


def _random_cases(n, seed):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        M = rng.uniform(0.5, 50.0)
        R = rng.uniform(0.1, 5.0)
        alpha = rng.uniform(0.02, 1.4)
        I_G = M * R * R * rng.uniform(0.05, 2.0)       # any body shape, not only a rectangle
        p = math.sqrt(M * G_STD * R / (I_G + M * R * R))
        theta = rng.uniform(-1.5, 1.5)
        theta_dot = rng.normal(0.0, 2.0)
        a_g = rng.normal(0.0, 8.0)
        a_v = rng.normal(0.0, 4.0)
        yield M, R, alpha, I_G, p, theta, theta_dot, a_g, a_v


@pytest.mark.parametrize("s", [1, -1])
def test_theta_ddot_matches_lagrangian(s):
    n = 0
    for M, R, alpha, I_G, p, theta, theta_dot, a_g, a_v in _random_cases(50, seed=100 + s):
        got = K.theta_ddot(1.0, theta, s, _par(alpha, p), _hdr(a_g, a_v), SMP)
        ref = THDD_FN(theta, theta_dot, s, M, I_G, R, alpha, G_STD + a_v, a_g)
        # scale of the individual terms: p^2 (|G| + |a_g|) / g
        scale = p * p * (abs(G_STD + a_v) + abs(a_g)) / G_STD
        assert abs(got - ref) <= 1e-12 * scale, (theta, s, got, ref)
        n += 1
    assert n == 50


@pytest.mark.parametrize("s", [1, -1])
def test_rhs_matches_lagrangian(s):
    """The state rhs (theta', theta'') uses the discrete pivot, never sgn(theta)."""
    disc = np.zeros(L.N_DISC, dtype=np.int64)
    disc[L.D_PIVOT] = s
    out = np.empty(2)
    for M, R, alpha, I_G, p, theta, theta_dot, a_g, a_v in _random_cases(50, seed=200 + s):
        K.rhs(0.5, np.array([theta, theta_dot]), _par(alpha, p), disc, _hdr(a_g, a_v), SMP, out)
        ref = THDD_FN(theta, theta_dot, s, M, I_G, R, alpha, G_STD + a_v, a_g)
        scale = p * p * (abs(G_STD + a_v) + abs(a_g)) / G_STD
        assert out[0] == theta_dot
        assert abs(out[1] - ref) <= 1e-12 * scale


def test_uplift_threshold_matches_lagrangian():
    """At theta = theta' = 0 the Lagrangian theta'' about s = -sgn(a_g) turns toward s exactly when
    |a_g| > G tan(alpha); the kernel's static margin changes sign at the same a_g."""
    q, qd, s, M, I_G, R, alpha, G, a_g = SYMS
    for sv in (1, -1):
        # root in a_g of s*theta''(0): a_g = -s G tan(alpha)
        root = sp.solve(sp.Eq((sv * THDD).subs({q: 0, s: sv}), 0), a_g)
        assert len(root) == 1
        assert sp.simplify(root[0] + sv * G * sp.tan(alpha)) == 0
    rng = np.random.default_rng(7)
    disc = np.zeros(L.N_DISC, dtype=np.int64)
    y0 = np.zeros(2)
    for _ in range(50):
        alpha_v = rng.uniform(0.02, 1.4)
        p = rng.uniform(0.5, 5.0)
        a_v = rng.uniform(-5.0, 5.0)           # G > 0
        thr = (G_STD + a_v) * math.tan(alpha_v)
        for factor in (0.5, 0.999, 1.001, 2.0):
            a = factor * thr * rng.choice([-1.0, 1.0])
            margin = K.static_margin(0.5, y0, _par(alpha_v, p), disc, _hdr(a, a_v), SMP)
            sv = -1 if a > 0 else 1
            Mv, Rv = 1.0, 1.0
            I_Gv = 1.0 / 3.0
            lag = THDD_FN(0.0, 0.0, sv, Mv, I_Gv, Rv, alpha_v, G_STD + a_v, a)
            uplifts = sv * lag > 0
            assert (margin < 0) == uplifts == (factor > 1), (factor, margin, lag)
