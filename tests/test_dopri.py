"""Dormand-Prince 5(4) kernel: tableau identities and lockstep agreement with SciPy's RK45.

Oracles: the Butcher tableau order conditions (exact rational identities, checked in float64),
SciPy's ``RK45`` tableau, and SciPy's ``RK45`` stepped by hand (``step()``), which the kernel
claims to port literally (STYLE.md habit 4, numbakit-ode's lockstep test).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import RK45, OdeSolution

import fastrock as fr
from fastrock.kernels import dopri as D

# fast, and every test here runs the kernel helpers: CI runs them again with NUMBA_DISABLE_JIT=1
pytestmark = pytest.mark.nojit

EPS = np.finfo(float).eps

A = np.array(D.A)                      # 6 x 5 (row 0 is zero)
B = np.array(D.B)                      # 6
C = np.array(D.C)                      # 6
E = np.array(D.E)                      # 7
P = np.array(D.P)                      # 7 x 4
B7 = np.append(B, 0.0)                 # FSAL: the 7th stage has weight 0 in the 5th-order solution
C7 = np.append(C, 1.0)                 # 7th stage is evaluated at t + h


# ---------------------------------------------------------------- tableau identities

def test_tableau_shapes():
    assert A.shape == (D.N_STAGES, D.N_STAGES - 1)
    assert B.shape == (D.N_STAGES,)
    assert C.shape == (D.N_STAGES,)
    assert E.shape == (D.N_STAGES + 1,)
    assert P.shape == (D.N_STAGES + 1, 4)
    # explicit method: A strictly lower triangular
    for i in range(D.N_STAGES):
        assert np.all(A[i, i:] == 0.0), f"row {i}"


def test_weights_sum_to_one():
    assert math.isclose(B.sum(), 1.0, rel_tol=0.0, abs_tol=4 * EPS)


def test_row_sums_equal_nodes():
    np.testing.assert_allclose(A.sum(axis=1), C, rtol=0.0, atol=4 * EPS)


def test_error_weights_sum_to_zero():
    # both embedded solutions are consistent (order >= 1), so their difference sums to 0
    assert abs(E.sum()) < 4 * EPS


def test_dense_output_at_step_end_reproduces_b():
    # y(t_old + x h) = y_old + h sum_j K_j (P_j1 x + P_j2 x^2 + P_j3 x^3 + P_j4 x^4): at x = 1
    # this must be the 5th-order step, i.e. P.sum(axis=1) == (B, 0)
    np.testing.assert_allclose(P.sum(axis=1), B7, rtol=0.0, atol=8 * EPS)
    assert P[-1].sum() == pytest.approx(0.0, abs=8 * EPS)


def test_dense_output_derivative_at_step_start_is_f():
    # d/dx at x=0 is h*K_0: first column of P is the unit vector e_0
    np.testing.assert_array_equal(P[:, 0], np.eye(D.N_STAGES + 1)[0])


@pytest.mark.parametrize("k", range(5))
def test_fifth_order_quadrature_conditions(k):
    # sum_j b_j c_j^k = 1/(k+1), k = 0..4 (the bushy-tree order conditions up to order 5)
    assert math.isclose(np.dot(B, C ** k), 1.0 / (k + 1), rel_tol=0.0, abs_tol=8 * EPS)


@pytest.mark.parametrize("k", range(4))
def test_embedded_fourth_order_conditions(k):
    # the embedded 4th-order weights are B7 - E (SciPy: error = h K^T E = y5 - y4)
    bhat = B7 - E
    assert math.isclose(np.dot(bhat, C7 ** k), 1.0 / (k + 1), rel_tol=0.0, abs_tol=8 * EPS)


def test_tableau_equals_scipy_rk45():
    np.testing.assert_array_equal(A, RK45.A[:, : D.N_STAGES - 1])
    np.testing.assert_array_equal(B, RK45.B)
    np.testing.assert_array_equal(C, RK45.C)
    np.testing.assert_array_equal(E, RK45.E)
    np.testing.assert_array_equal(P, RK45.P)
    assert (D.ORDER, D.ERROR_ESTIMATOR_ORDER, D.N_STAGES) == (RK45.order, RK45.error_estimator_order,
                                                                RK45.n_stages)


# ---------------------------------------------------------------- lockstep with SciPy
#
# Two oracles:
# * stock ``scipy.integrate.RK45`` on the textbook right-hand side.  Same step count and nfev,
#   and the solutions agree where they are compared at the same time.  The step *times* drift
#   apart by rounding: the error estimate h*sum(E_j K_j) cancels to ~rtol*|y|, so a last-bit
#   difference in K (BLAS summation order, or (g*sin)/g vs sin) changes err_norm by ~eps/rtol
#   relative and every later step size with it (measured 1e-7 relative at rtol=1e-12).
# * the same RK45 class with its two dot products (stages and error estimate) summed left to
#   right, on the right-hand side written as physics.md 1 states it, (G sin + a_g cos)/g with
#   G = g + a_v.  Then every floating-point operation is determined and the kernel must agree
#   at every step to 1e-12 relative (measured: bit-identical).

ALPHA, PP = 0.25, 2.0
G_STD = 9.80665
THETA0 = 0.15
# first impact of free rocking from 0.15 rad is at T/4 = 0.7845 s (physics.md 6.2): stop before it
T_END = 0.75
TOLERANCES = [(1e-6, 1e-8), (1e-9, 1e-11), (1e-12, 1e-14)]


def housner_rhs(t, y):
    """Housner's EOM about the right corner (theta > 0), no excitation."""
    return np.array([y[1], -PP * PP * math.sin(ALPHA - y[0])])


def housner_rhs_spec_form(t, y):
    """physics.md 1: theta'' = -p^2 [G sin(s alpha - theta) + a_g cos(s alpha - theta)] / g."""
    a_g, a_v, s = 0.0, 0.0, 1
    phi = s * ALPHA - y[0]
    return np.array([y[1], -PP * PP * ((G_STD + a_v) * math.sin(phi) + a_g * math.cos(phi)) / G_STD])


def _sequential_rk_step(fun, t, y, f, h, A_, B_, C_, K):
    """scipy rk.py ``rk_step`` with each dot product summed left to right."""
    n = y.size
    K[0] = f
    for s in range(1, len(C_)):
        dy = np.array([sum_lr(K[:s, i], A_[s, :s]) * h for i in range(n)])
        K[s] = fun(t + C_[s] * h, y + dy)
    y_new = np.array([y[i] + h * sum_lr(K[:-1, i], B_) for i in range(n)])
    f_new = fun(t + h, y_new)
    K[-1] = f_new
    return y_new, f_new


def sum_lr(u, v):
    acc = 0.0
    for a, b in zip(u, v):
        acc += a * b
    return acc


class SequentialRK45(RK45):
    """RK45 whose error estimate is summed left to right (rk.py ``_estimate_error[_norm]``)."""

    def _estimate_error(self, K, h):
        return np.array([sum_lr(K[:, i], self.E) * h for i in range(K.shape[1])])

    def _estimate_error_norm(self, K, h, scale):
        x = self._estimate_error(K, h) / scale
        return math.sqrt(sum_lr(x, x) / x.size)


def run_scipy(cls, fun, rtol, atol):
    solver = cls(fun, 0.0, np.array([THETA0, 0.0]), t_bound=T_END, rtol=rtol, atol=atol)
    ts, ys, dense = [solver.t], [solver.y.copy()], []
    while solver.status == "running":
        msg = solver.step()
        assert msg is None, msg
        ts.append(solver.t)
        ys.append(solver.y.copy())
        dense.append(solver.dense_output())
    assert solver.status == "finished"
    return np.array(ts), np.array(ys), dense, solver.nfev


def run_fastrock(rtol, atol, t_eval=None):
    body = fr.RigidBlock(alpha=ALPHA, p=PP)
    res = fr.simulate(body, theta0=THETA0, duration=T_END, rtol=rtol, atol=atol, t_eval=t_eval)
    assert res.events.empty, "no event may fire before the first impact"
    assert res.status == "safe:moving"
    return res


@pytest.fixture
def sequential_scipy(monkeypatch):
    from scipy.integrate._ivp import rk
    monkeypatch.setattr(rk, "rk_step", _sequential_rk_step)
    return SequentialRK45


@pytest.mark.parametrize("rtol,atol", TOLERANCES)
def test_lockstep_with_scipy_rk45(rtol, atol, sequential_scipy):
    ts, ys, _dense, nfev = run_scipy(sequential_scipy, housner_rhs_spec_form, rtol, atol)
    res = run_fastrock(rtol, atol)
    h = res.history
    assert len(h) == len(ts), "same number of accepted steps (+ the initial row)"
    assert res.metrics["steps"] == len(ts) - 1
    assert res.metrics["nfev"] == nfev, "same number of rhs evaluations (rejections included)"
    t_fr = h["t"].to_numpy()
    y_fr = h[["theta", "theta_dot"]].to_numpy()
    for i in range(len(ts)):
        np.testing.assert_allclose(t_fr[i], ts[i], rtol=1e-12, atol=0, err_msg=f"Step: {i}")
        np.testing.assert_allclose(y_fr[i], ys[i], rtol=1e-12, atol=0, err_msg=f"Step: {i}")
    assert t_fr[-1] == T_END == ts[-1], "the last step is clipped exactly onto t_bound"


@pytest.mark.parametrize("rtol,atol", TOLERANCES)
def test_stock_scipy_rk45_same_steps_same_solution(rtol, atol):
    ts, _ys, dense, nfev = run_scipy(RK45, housner_rhs, rtol, atol)
    res = run_fastrock(rtol, atol)
    h = res.history
    assert len(h) == len(ts)
    assert res.metrics["nfev"] == nfev
    t_fr = h["t"].to_numpy()
    y_fr = h[["theta", "theta_dot"]].to_numpy()
    # step times: rounding-level drift, amplified by eps/rtol (see the comment above)
    np.testing.assert_allclose(t_fr, ts, rtol=10 * EPS / rtol, atol=0)
    # the solutions, compared at the same time: SciPy's own dense output (the step that contains
    # each time) at the kernel's step times
    sol = OdeSolution(ts, dense)
    for i in range(len(ts)):
        np.testing.assert_allclose(y_fr[i], sol(t_fr[i]), rtol=1e-12, atol=0, err_msg=f"Step: {i}")


@pytest.mark.parametrize("rtol,atol", TOLERANCES[:2])
def test_lockstep_dense_output_at_t_eval(rtol, atol, sequential_scipy):
    """With t_eval the kernel samples its dense interpolant: must equal SciPy's dense output."""
    ts, _ys, dense, _nfev = run_scipy(sequential_scipy, housner_rhs_spec_form, rtol, atol)
    frac = np.array([0.2, 0.5, 0.9])          # inside every step, never on a step end
    t_eval = np.concatenate([ts[i] + frac * (ts[i + 1] - ts[i]) for i in range(len(ts) - 1)])
    ref = np.array([dense[i // 3](t) for i, t in enumerate(t_eval)])
    res = run_fastrock(rtol, atol, t_eval=t_eval)
    h = res.history
    np.testing.assert_array_equal(h["t"].to_numpy(), t_eval)
    got = h[["theta", "theta_dot"]].to_numpy()
    for i in range(len(t_eval)):
        np.testing.assert_allclose(got[i], ref[i], rtol=1e-12, atol=0, err_msg=f"Sample: {i}")


def test_kernel_helpers_on_scipy_stages(sequential_scipy):
    """dense_coefficients / dense_eval / error_norm / step_factor, fed SciPy's own stages K.

    Reference sums are exactly rounded (math.fsum); a left-to-right sum of m products may differ
    from it by at most m*eps*sum|terms| (standard error bound), which is what is asserted.
    """
    from scipy.integrate._ivp.rk import MAX_FACTOR, MIN_FACTOR, SAFETY
    assert (D.SAFETY, D.MAX_FACTOR, D.MIN_FACTOR) == (SAFETY, MAX_FACTOR, MIN_FACTOR)
    rtol, atol = 1e-7, 1e-9
    solver = sequential_scipy(housner_rhs_spec_form, 0.0, np.array([THETA0, 0.0]), t_bound=T_END,
                              rtol=rtol, atol=atol)
    Q = np.empty((2, 4))
    out = np.empty(2)
    work = np.empty(2)
    i = 0
    while solver.status == "running":
        y_old, t_old = solver.y.copy(), solver.t
        solver.step()
        K, h, y_new = solver.K, solver.t - t_old, solver.y
        D.dense_coefficients(K, Q)
        for r in range(2):
            for c in range(4):
                terms = K[:, r] * RK45.P[:, c]
                bound = 8 * EPS * np.abs(terms).sum()
                assert abs(Q[r, c] - math.fsum(terms)) <= bound, f"Step: {i}"
        D.dense_eval(t_old + h, t_old, h, y_old, Q, out)
        np.testing.assert_allclose(out, y_new, rtol=1e-14, atol=0, err_msg=f"Step: {i}")
        for x in (0.25, 0.5, 0.75):
            D.dense_eval(t_old + x * h, t_old, h, y_old, Q, out)
            np.testing.assert_allclose(out, solver.dense_output()(t_old + x * h), rtol=1e-14,
                                       atol=0, err_msg=f"Step: {i}")
        scale = atol + np.maximum(np.abs(y_old), np.abs(y_new)) * rtol
        err_terms = [K[:, r] * RK45.E * h / scale[r] for r in range(2)]
        ref = math.sqrt(sum(math.fsum(t) ** 2 for t in err_terms) / 2)
        bound = 8 * EPS * math.sqrt(sum(np.abs(t).sum() ** 2 for t in err_terms))
        got = D.error_norm(K, h, y_old, y_new, np.full(2, rtol), np.full(2, atol), work)
        assert abs(got - ref) <= bound + 4 * EPS * ref, f"Step: {i}"
        i += 1
    assert i > 5
    for err in (0.0, 1e-9, 0.3, 0.99):
        ref = MAX_FACTOR if err == 0 else min(MAX_FACTOR, SAFETY * err ** (-1 / 5))
        assert D.step_factor(err, False) == pytest.approx(ref, rel=4 * EPS)
        assert D.step_factor(err, True) == pytest.approx(min(1.0, ref), rel=4 * EPS)
    for err in (1.0, 3.0, 1e6):
        ref = max(MIN_FACTOR, SAFETY * err ** (-1 / 5))
        assert D.step_factor(err, False) == pytest.approx(ref, rel=4 * EPS)
        assert D.step_factor(err, True) == pytest.approx(ref, rel=4 * EPS)
