"""Rodas4 (kernels/rodas.py): order of the step and of its dense output,
L-stability, the stiff Prothero-Robinson problem, and the switch of
``auto_step`` against plain DP5, checked against closed forms and SciPy."""
import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from fastrock.kernels import layout as L
from fastrock.kernels import rodas as R
from fastrock.kernels.dopri import N_STAGES, dense_eval


@njit
def _forced_duffing(t, y, par, disc, hdr, smp, out):
    out[0] = y[1]
    out[1] = -y[0] - par[0] * y[1] ** 3 + np.sin(2.0 * t)


@njit
def _prothero_robinson(t, y, par, disc, hdr, smp, out):
    # y' = lambda (y - cos t) - sin t: y = cos t for any lambda
    out[0] = par[0] * (y[0] - np.cos(t)) - np.sin(t)


@njit
def _linear(t, y, par, disc, hdr, smp, out):
    out[0] = par[0] * y[0]


def _opt(method=L.METHOD_AUTO, rtol=1e-6, atol=1e-8):
    opt = np.zeros(L.N_OPT)
    opt[L.O_RTOL] = rtol
    opt[L.O_ATOL] = atol
    opt[L.O_METHOD] = method
    return opt


@njit
def _fixed_steps(step, dense, rhs, y0, t0, t1, n_steps, par, opt, x_dense):
    """n_steps equal steps of ``step``; returns the end state, the dense
    output at fraction x_dense of the last step, and the counters."""
    n = y0.shape[0]
    K = np.zeros((N_STAGES + 1 + R.work_rows(n), n))
    y = y0.copy()
    f = np.empty(n)
    ytmp = np.empty(n)
    ftmp = np.empty(n)
    y_new = np.empty(n)
    y_scale = np.abs(y0) + 1.0
    Q = np.empty((n, 4))
    yd = np.empty(n)
    met = np.zeros(L.N_MET)
    disc = np.zeros(3, dtype=np.int64)
    hdr = np.zeros(1)
    smp = np.zeros(1)
    tol = np.empty((2, n))
    tol[0, :] = opt[L.O_ATOL]
    tol[1, :] = opt[L.O_RTOL]
    h = (t1 - t0) / n_steps
    t = t0
    worst = 0.0
    for k in range(n_steps):
        rhs(t, y, par, disc, hdr, smp, f)
        err, _e = step(rhs, t, y, f, h, True, True, K, ytmp, ftmp, y_new,
                       y_scale, tol, opt, par, disc, hdr, smp, met)
        worst = max(worst, err)
        dense(K, h, y, y_new, Q)
        dense_eval(t + x_dense * h, t, h, y, Q, yd)
        for i in range(n):
            y[i] = y_new[i]
        t = t0 + (k + 1) * h
    return y, yd, worst, met[L.M_NFEV]


def _reference(fun, y0, t0, t1, par):
    def f(t, y):
        out = np.empty_like(y)
        fun(t, y, par, None, None, None, out)
        return out
    return solve_ivp(f, (t0, t1), y0, method="DOP853", rtol=1e-13, atol=1e-15,
                     dense_output=True).sol


def test_rodas4_is_fourth_order_and_its_dense_output_third_order():
    """Global error of the end point ~ h^4 (a nonlinear, forced problem, so
    the df/dt stage terms count); the dense output's error at x = 0.37
    of the last step ~ h^4 as well (local order 3 + 1 over one step)."""
    par = np.array([0.5])
    y0 = np.array([1.0, 0.0])
    ref = _reference(_forced_duffing.py_func, y0, 0.0, 2.0, par)
    opt = _opt(L.METHOD_RODAS)
    errs, derrs = [], []
    for n in (20, 40, 80, 160):
        y, yd, _w, _nf = _fixed_steps(R.auto_step, R.auto_dense, _forced_duffing, y0, 0.0, 2.0, n,
                                      par, opt, 0.37)
        h = 2.0 / n
        errs.append(np.abs(y - ref(2.0)).max())
        derrs.append(np.abs(yd - ref(2.0 - h + 0.37 * h)).max())
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    dorders = np.log2(np.array(derrs[:-1]) / np.array(derrs[1:]))
    assert np.all(np.abs(orders[1:] - 4.0) < 0.3), orders
    assert np.all(dorders[1:] > 3.7), dorders


def test_rodas4_is_l_stable():
    """R(z) -> 0 as z -> -inf (stiffly accurate), |R(z)| <= 1 on the left
    half plane's real axis: one step of y' = lambda y."""
    opt = _opt(L.METHOD_RODAS)
    for z in (-1e-2, -1.0, -10.0, -1e3, -1e8):
        y, _yd, _w, _nf = _fixed_steps(R.auto_step, R.auto_dense, _linear, np.array([1.0]), 0.0,
                                       1.0, 1, np.array([z]), opt, 0.5)
        assert abs(y[0]) <= 1.0
        if z == -1e-2:
            assert y[0] == pytest.approx(np.exp(z), rel=1e-9)
    assert abs(y[0]) < 1e-6


def test_prothero_robinson_is_stiff_for_dp5_and_easy_for_rodas4():
    """lambda = -1e6, fixed h = 0.01: DP5 is far outside its stability
    region (h lambda = -1e4), so ``auto_step`` turns to Rodas4 at the first
    step and follows cos t; METHOD_DOPRI stays explicit and blows up."""
    par = np.array([-1e6])
    y0 = np.array([1.0])
    y, _yd, _w, _nf = _fixed_steps(R.auto_step, R.auto_dense, _prothero_robinson, y0, 0.0, 1.0,
                                   100, par, _opt(L.METHOD_AUTO), 0.5)
    assert y[0] == pytest.approx(np.cos(1.0), abs=1e-9)
    y, _yd, _w, _nf = _fixed_steps(R.auto_step, R.auto_dense, _prothero_robinson, y0, 0.0, 1.0,
                                   100, par, _opt(L.METHOD_DOPRI), 0.5)
    assert not abs(y[0] - np.cos(1.0)) < 1.0


def test_auto_step_equals_dp5_bit_for_bit_where_not_stiff():
    """On a non-stiff problem ``auto_step`` is DP5: same states, same
    evaluation count as ``dopri_step``."""
    from fastrock.kernels.dopri import dopri_dense, dopri_step
    par = np.array([0.5])
    y0 = np.array([1.0, 0.0])
    a = _fixed_steps(R.auto_step, R.auto_dense, _forced_duffing, y0, 0.0, 2.0, 50, par,
                     _opt(L.METHOD_AUTO), 0.3)
    b = _fixed_steps(dopri_step, dopri_dense, _forced_duffing, y0, 0.0, 2.0, 50, par,
                     _opt(L.METHOD_AUTO), 0.3)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]) and a[3] == b[3]
