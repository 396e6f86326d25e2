"""Dormand-Prince 5(4) step, error control and dense output.

A literal port of ``scipy.integrate._ivp.rk`` (SciPy 1.17, ``rk.py``) and of
``select_initial_step`` (``common.py``), so that SciPy's ``RK45`` is a
step-by-step oracle.  Line references are to those files.  The right-hand
side is passed in as a jitted function ``rhs(t, y, par, disc, hdr, smp, out)``
and is inlined into each entry kernel.
"""
import numpy as np

from .config import jit, jit_generic
from .layout import M_NFEV

# rk.py lines 8-11
SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
ERROR_EXPONENT = -1.0 / (4 + 1)   # rk.py 102: -1/(error_estimator_order + 1)
N_STAGES = 6
ORDER = 5
ERROR_ESTIMATOR_ORDER = 4
ERR_FIXED_MAX = 1e-2      # fixed step: largest relative local error (see
#                           fixed_step_error): beyond it the step is unstable

# rk.py 380-404 (class RK45).  Tuples, not arrays: Numba embeds them as
# constants, whereas global arrays stop the on-disk cache.


def _tup(rows):
    if isinstance(rows[0], (list, tuple)):
        return tuple(tuple(float(v) for v in r) for r in rows)
    return tuple(float(v) for v in rows)


C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0)
A = _tup([
    [0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]])
B = _tup([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
E = _tup([-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200,
              -22 / 525, 1 / 40])
P = _tup([
    [1, -8048581381 / 2820520608, 8663915743 / 2820520608,
     -12715105075 / 11282082432],
    [0, 0, 0, 0],
    [0, 131558114200 / 32700410799, -68118460800 / 10900136933,
     87487479700 / 32700410799],
    [0, -1754552775 / 470086768, 14199869525 / 1410260304,
     -10690763975 / 1880347072],
    [0, 127303824393 / 49829197408, -318862633887 / 49829197408,
     701980252875 / 199316789632],
    [0, -282668133 / 205662961, 2019193451 / 616988883,
     -1453857185 / 822651844],
    [0, 40617522 / 29380423, -110615467 / 29380423,
     69997945 / 29380423]])


@jit
def rms_norm(x, scale):
    """common.py ``norm``: RMS norm of x/scale."""
    s = 0.0
    for i in range(x.shape[0]):
        r = x[i] / scale[i]
        s += r * r
    return np.sqrt(s / x.shape[0])


@jit_generic
def rk_step(rhs, t, y, f, h, K, ytmp, fs, y_new, par, disc, hdr, smp):
    """rk.py 14-71 ``rk_step``: one DP5 step; fills K (7 x n) and y_new.

    K[6] receives f(t + h, y_new) (FSAL).  Returns nothing; 6 rhs calls.
    Each stage is evaluated into the work vector ``fs`` and copied into its
    row of K: passing the row K[s] itself would create an array view (and
    its reference-count traffic) on every stage.
    """
    n = y.shape[0]
    for i in range(n):
        K[0, i] = f[i]
    for s in range(1, N_STAGES):
        for i in range(n):
            dy = 0.0
            for j in range(s):
                dy += K[j, i] * A[s][j]
            ytmp[i] = y[i] + dy * h
        rhs(t + C[s] * h, ytmp, par, disc, hdr, smp, fs)
        for i in range(n):
            K[s, i] = fs[i]
    for i in range(n):
        acc = 0.0
        for j in range(N_STAGES):
            acc += K[j, i] * B[j]
        y_new[i] = y[i] + h * acc
    rhs(t + h, y_new, par, disc, hdr, smp, fs)
    for i in range(n):
        K[N_STAGES, i] = fs[i]


@jit
def error_norm(K, h, y, y_new, rtol, atol, work):
    """rk.py 105-109 and 146-147: scaled RMS norm of the embedded error
    (``rtol``, ``atol``: the tolerances of each component)."""
    n = y.shape[0]
    s = 0.0
    for i in range(n):
        err = 0.0
        for j in range(N_STAGES + 1):
            err += K[j, i] * E[j]
        err *= h
        sc = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol[i]
        r = err / sc
        s += r * r
    return np.sqrt(s / n)


@jit
def step_factor(err_norm, rejected, exponent=ERROR_EXPONENT):
    """rk.py 149-163: step-size factor after an accepted/rejected step
    (``exponent``: -1/(q + 1) for an error estimate of order q)."""
    if err_norm < 1.0:
        if err_norm == 0.0:
            factor = MAX_FACTOR
        else:
            factor = min(MAX_FACTOR, SAFETY * err_norm ** exponent)
        if rejected:
            factor = min(1.0, factor)
        return factor
    return max(MIN_FACTOR, SAFETY * err_norm ** exponent)


@jit_generic
def select_initial_step(rhs, t0, y0, t_bound, max_step, f0, rtol, atol,
                        ytmp, ftmp, par, disc, hdr, smp):
    """common.py 68-134 ``select_initial_step`` (direction = +1)."""
    n = y0.shape[0]
    interval_length = abs(t_bound - t0)
    if interval_length == 0.0:
        return 0.0
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol[i] + abs(y0[i]) * rtol[i]
        d0 += (y0[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = np.sqrt(d0 / n)
    d1 = np.sqrt(d1 / n)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval_length)
    for i in range(n):
        ytmp[i] = y0[i] + h0 * f0[i]
    rhs(t0 + h0, ytmp, par, disc, hdr, smp, ftmp)
    d2 = 0.0
    for i in range(n):
        sc = atol[i] + abs(y0[i]) * rtol[i]
        d2 += ((ftmp[i] - f0[i]) / sc) ** 2
    d2 = np.sqrt(d2 / n) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (ERROR_ESTIMATOR_ORDER + 1))
    return min(100 * h0, h1, interval_length, max_step)


@jit
def dense_coefficients(K, Q):
    """rk.py ``_dense_output_impl``: Q = K.T @ P  (n x 4)."""
    n = K.shape[1]
    for i in range(n):
        for k in range(4):
            acc = 0.0
            for j in range(N_STAGES + 1):
                acc += K[j, i] * P[j][k]
            Q[i, k] = acc


@jit
def dense_eval(t, t_old, h, y_old, Q, out):
    """rk.py 560-574 ``RkDenseOutput._call_impl`` for a scalar t."""
    x = (t - t_old) / h
    x2 = x * x
    x3 = x2 * x
    x4 = x3 * x
    for i in range(y_old.shape[0]):
        out[i] = y_old[i] + h * (Q[i, 0] * x + Q[i, 1] * x2 + Q[i, 2] * x3
                                 + Q[i, 3] * x4)



@jit
def fixed_step_error(K, h, y_new, y_scale, atol):
    """Largest embedded error estimate of a fixed step relative to each
    component's scale (``y_scale``: the largest |y| of the run so far).
    For y' = lambda y it is a function of z = h lambda alone: below 1e-3
    for |z| <= 1, 1e-2 at |z| ~ 1.6, where undamped modes start to grow
    (|R(iy)| > 1), and 0.9 at the real-axis stability limit z = -3.3."""
    worst = 0.0
    for i in range(y_new.shape[0]):
        err = 0.0
        for j in range(N_STAGES + 1):
            err += K[j, i] * E[j]
        r = abs(err * h) / (atol[i] + max(y_scale[i], abs(y_new[i])))
        if not r <= worst:
            worst = r
    return worst


# ---------------------------------------------------------------- the method
# The driver (kernels/hybrid.py) takes its integration method as three
# functions, ``step``, ``dense`` and ``work_rows``, with the signatures below;
# these are plain Dormand-Prince, and kernels/rodas.py has the stiff ones.


@jit_generic
def dopri_step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp, y_new, y_scale,
               tol, opt, par, disc, hdr, smp, met):
    """One DP5 step from (t, y) with f = f(t, y): fills y_new and K (row
    N_STAGES: f(t + h, y_new), the next step's f).  Returns the scaled RMS
    norm of the embedded error and the step-size exponent (adaptive), or
    ``fixed_step_error`` and ERR_FIXED_MAX, its stability limit (``fixed``)."""
    rk_step(rhs, t, y, f, h, K, ytmp, ftmp, y_new, par, disc, hdr, smp)
    met[M_NFEV] += 6
    if fixed:
        return fixed_step_error(K, h, y_new, y_scale, tol[0]), ERR_FIXED_MAX
    return error_norm(K, h, y, y_new, tol[1], tol[0], ytmp), ERROR_EXPONENT


@jit
def dopri_dense(K, h, y_old, y_new, Q):
    """Dense output of the last DP5 step (``dense_coefficients``)."""
    dense_coefficients(K, Q)


@jit
def dopri_work_rows(n):
    """DP5 needs no rows of K beyond its stages."""
    return 0
