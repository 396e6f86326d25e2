"""Rodas4, a stiff method for the driver, and the switching method built on it.

Rodas4 (Hairer & Wanner, *Solving ODEs II*, sec. IV.7, code ``rodas.f``) is
an L-stable, stiffly accurate Rosenbrock method of order 4 with an embedded
order-3 solution and a dense output of order 3.  It is linearly implicit:
each step solves six linear systems with the one matrix
E = I/(h gamma) - J, J = df/dy, so a stiff mode (the dashpot of a stiff,
damped spring) costs nothing in step size.  J and df/dt are finite
differences (2 n + 2 evaluations per new point; a rejected try reuses them).

``auto_step`` / ``auto_dense`` are the method the foundation models pass to
``hybrid.integrate_with``.  They run DP5 (bit for bit the explicit driver)
until the problem is stiff, then Rodas4:

- adaptive steps: Hairer's stiffness test of DOPRI5, h |lambda| estimated
  as h ||f(y_7) - f(y_6)|| / ||y_7 - y_6|| (two stages at t + h), above 3.25
  on 15 accepted steps with no 6 non-stiff ones in a row between;
- a fixed step at which DP5 is unstable (``fixed_step_error`` above
  ERR_FIXED_MAX, or a non-finite state): the same step is taken again with
  Rodas4, and so are the run's later steps.

Back to DP5 where Rodas4 does not pay: its step, on 15 accepted steps in a
row, no longer than DP5's stability-bound step, 3.25/rho (rho: the Perron
root of |J|, a bound of J's spectral radius), times the cost ratio,
(6 + 2 n + 2)/6 evaluations.  Where the accuracy, not the
stiffness, sets the step (an oscillating column), DP5 is the cheaper method;
a switch back after a stint in which Rodas4 never paid doubles the stiff
steps the next switch needs, so the methods cannot alternate often; after
one that paid somewhere (stiff rocking between impacts whose transients
accuracy resolves with short steps) the next switch needs 15 again.  ``opt[O_METHOD]`` can pin either method.

The tableau below is that of ``rodas.f`` (transformed form: stages k_i are
the increments, the C_ij carry 1/h).  Oracles (tests/test_rodas.py): order
4 of the step, order 3 of the dense output, and L-stability on y' = lambda y.
"""
import numpy as np

from .config import jit, jit_generic, next_up
from .dopri import ERR_FIXED_MAX, N_STAGES, dopri_dense, dopri_step
from .hybrid import EPS, _all_finite
from .layout import M_NFEV, METHOD_DOPRI, METHOD_RODAS, O_METHOD

GAMMA = 0.25
EXPONENT = -0.25             # error estimate of order 3: -1/(3 + 1)
N_DETECT = 15                # steps that decide a switch (see auto_step)
N_RESET = 6                  # DOPRI5: non-stiff steps in a row that reset it
H_LAMBDA_STIFF = 3.25        # DOPRI5's stiffness threshold on h |lambda|

# stage s (0-based) starts from y + sum_j A[s][j] k_j at t + CT[s] h, and its
# right-hand side adds sum_j CC[s][j] k_j / h + D[s] h f_t
A = ((0.0, 0.0, 0.0, 0.0, 0.0),
     (1.544, 0.0, 0.0, 0.0, 0.0),
     (0.9466785280815826, 0.2557011698983284, 0.0, 0.0, 0.0),
     (3.314825187068521, 2.896124015972201, 0.9986419139977817, 0.0, 0.0),
     (1.221224509226641, 6.019134481288629, 12.53708332932087,
      -0.6878860361058950, 0.0),
     (1.221224509226641, 6.019134481288629, 12.53708332932087,
      -0.6878860361058950, 1.0))
CC = ((0.0, 0.0, 0.0, 0.0, 0.0),
      (-5.6688, 0.0, 0.0, 0.0, 0.0),
      (-2.430093356833875, -0.2063599157091915, 0.0, 0.0, 0.0),
      (-0.1073529058151375, -9.594562251023355, -20.47028614809616, 0.0, 0.0),
      (7.496443313967647, -10.24680431464352, -33.99990352819905,
       11.70890893206160, 0.0),
      (8.083246795921522, -7.981132988064893, -31.52159432874371,
       16.31930543123136, -6.058818238834054))
CT = (0.0, 0.386, 0.21, 0.63, 1.0, 1.0)
D = (0.25, -0.1043, 0.1035, -0.03620000000000023, 0.0, 0.0)
# dense output: y(x) = (1 - x) y0 + x (y1 + (1 - x)(k1d + x k2d))
H2 = (10.12623508344586, -7.487995877610167, -34.80091861555747,
      -7.992771707568823, 1.025137723295662)
H3 = (-0.6762803392801253, 6.087714651680015, 16.43084320892478,
      24.76722511418386, -6.594389125716872)
N_ROS = 6

# work rows of K after the DP5 stages (``work_rows``): the LU of E (n rows),
# J (n rows), then these
R_E = N_STAGES + 1
N_WORK = 7
W_FT = 0          # df/dt
W_FREF = 1        # f at the point of J
W_PIV = 2         # row swaps of the LU
W_STATE = 3       # four rows: [stiff, count], [last step Rodas4, J valid],
S_STIFF = 0       # [non-stiff count, -], [steps to switch, Rodas4 paid]
S_COUNT = 1
S_LAST = 0        # in row W_STATE + 1
S_JOK = 1         # in row W_STATE + 1
S_NONSTIFF = 0    # in row W_STATE + 2
S_DETECT = 0      # in row W_STATE + 3 (0: N_DETECT)
S_PAID = 1        # in row W_STATE + 3


@jit
def _row(n, w):
    return R_E + 2 * n + w


@jit
def work_rows(n):
    """Rows of K that Rodas4 and ``auto_step`` keep after the DP5 stages."""
    return 2 * n + N_WORK


@jit_generic
def jacobian(rhs, t, y, h, K, ytmp, ftmp, par, disc, hdr, smp, met):
    """J = df/dy (rows R_E + n ...) by central differences and df/dt by a
    forward difference, at t1 = next_up(t), the side of t on which the step
    lies (a breakpoint at t belongs to the previous step); the time
    difference stays inside the step.  Increments as rodas.f,
    sqrt(eps max(1e-5, |y_j|)); central, not forward, so that a mirrored
    state gets the mirrored J bit for bit (the two-sided models' mirror
    symmetry is exact, and the tests hold them to it)."""
    n = y.shape[0]
    r_j = R_E + n
    r_f = _row(n, W_FREF)
    t1 = next_up(t)
    rhs(t1, y, par, disc, hdr, smp, ftmp)
    for i in range(n):
        K[r_f, i] = ftmp[i]
        ytmp[i] = y[i]
    r_t = _row(n, W_FT)
    for j in range(n):
        yj = y[j]
        d = np.sqrt(EPS * max(1e-5, abs(yj)))
        ytmp[j] = yj + d
        rhs(t1, ytmp, par, disc, hdr, smp, ftmp)
        for i in range(n):
            K[r_j + i, j] = ftmp[i]
        ytmp[j] = yj - d
        rhs(t1, ytmp, par, disc, hdr, smp, ftmp)
        dj = (yj + d) - (yj - d)
        for i in range(n):
            K[r_j + i, j] = (K[r_j + i, j] - ftmp[i]) / dj
        ytmp[j] = yj
    dt = min(np.sqrt(EPS * max(1e-5, abs(t1))), 0.5 * h)
    t2 = t1 + dt
    dt = t2 - t1
    rhs(t2, y, par, disc, hdr, smp, ftmp)
    for i in range(n):
        K[r_t, i] = (ftmp[i] - K[r_f, i]) / dt
    met[M_NFEV] += 2 * n + 2


@jit
def factor(K, n, fac):
    """LU with partial pivoting of E = fac I - J into rows R_E...; False if
    E is singular."""
    r_j = R_E + n
    r_p = _row(n, W_PIV)
    for i in range(n):
        for j in range(n):
            K[R_E + i, j] = -K[r_j + i, j]
        K[R_E + i, i] += fac
    for k in range(n):
        p = k
        big = abs(K[R_E + k, k])
        for i in range(k + 1, n):
            a = abs(K[R_E + i, k])
            if a > big:
                big = a
                p = i
        if not big > 0.0 or not np.isfinite(big):
            return False
        K[r_p, k] = p
        if p != k:
            for j in range(n):
                tmp = K[R_E + k, j]
                K[R_E + k, j] = K[R_E + p, j]
                K[R_E + p, j] = tmp
        piv = K[R_E + k, k]
        for i in range(k + 1, n):
            m = K[R_E + i, k] / piv
            K[R_E + i, k] = m
            if m != 0.0:
                for j in range(k + 1, n):
                    K[R_E + i, j] -= m * K[R_E + k, j]
    return True


@jit
def solve(K, n, s):
    """Row s of K := E^-1 row s (E factored by ``factor``)."""
    r_p = _row(n, W_PIV)
    for k in range(n):
        p = int(K[r_p, k])
        if p != k:
            tmp = K[s, k]
            K[s, k] = K[s, p]
            K[s, p] = tmp
    for i in range(1, n):
        acc = K[s, i]
        for j in range(i):
            acc -= K[R_E + i, j] * K[s, j]
        K[s, i] = acc
    for i in range(n - 1, -1, -1):
        acc = K[s, i]
        for j in range(i + 1, n):
            acc -= K[R_E + i, j] * K[s, j]
        K[s, i] = acc / K[R_E + i, i]


@jit_generic
def rodas_step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp, y_new, y_scale,
               tol, opt, par, disc, hdr, smp, met):
    """One Rodas4 step (the ``step`` contract of ``hybrid.integrate_with``).
    The error estimate is the last stage k6 (y_new minus the embedded
    solution)."""
    n = y.shape[0]
    r_s = _row(n, W_STATE) + 1
    if fresh or K[r_s, S_JOK] == 0.0:
        jacobian(rhs, t, y, h, K, ytmp, ftmp, par, disc, hdr, smp, met)
        K[r_s, S_JOK] = 1.0
    if not factor(K, n, 1.0 / (h * GAMMA)):
        for i in range(n):
            y_new[i] = y[i]
        return np.inf, EXPONENT
    r_t = _row(n, W_FT)
    for i in range(n):
        K[0, i] = f[i] + h * D[0] * K[r_t, i]
    solve(K, n, 0)
    for s in range(1, N_ROS):
        for i in range(n):
            acc = y[i]
            for j in range(s):
                acc += A[s][j] * K[j, i]
            ytmp[i] = acc
        rhs(t + CT[s] * h, ytmp, par, disc, hdr, smp, ftmp)
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += CC[s][j] * K[j, i]
            K[s, i] = ftmp[i] + acc / h + h * D[s] * K[r_t, i]
        solve(K, n, s)
    last = N_ROS - 1
    for i in range(n):
        y_new[i] = ytmp[i] + K[last, i]
    rhs(t + h, y_new, par, disc, hdr, smp, ftmp)
    for i in range(n):
        K[N_STAGES, i] = ftmp[i]
    met[M_NFEV] += N_ROS
    if fixed:
        worst = 0.0
        for i in range(n):
            r = abs(K[last, i]) / (tol[0, i] + max(y_scale[i], abs(y_new[i])))
            if not r <= worst:
                worst = r
        return worst, np.inf       # L-stable: no step size is unstable
    acc = 0.0
    for i in range(n):
        r = K[last, i] / (tol[0, i] + max(abs(y[i]), abs(y_new[i])) * tol[1, i])
        acc += r * r
    return np.sqrt(acc / n), EXPONENT


@jit
def rodas_dense(K, h, y_old, y_new, Q):
    """Rodas4's dense output in the layout of ``dopri.dense_eval``."""
    for i in range(y_old.shape[0]):
        k1 = 0.0
        k2 = 0.0
        for j in range(N_ROS - 1):
            k1 += H2[j] * K[j, i]
            k2 += H3[j] * K[j, i]
        Q[i, 0] = (y_new[i] - y_old[i] + k1) / h
        Q[i, 1] = (k2 - k1) / h
        Q[i, 2] = -k2 / h
        Q[i, 3] = 0.0


@jit
def _h_lambda(K, h, y_new, ytmp):
    """DOPRI5's estimate of h |lambda| from its last two stages, both at
    t + h: ytmp holds stage 6's state, K[5] and K[6] their f."""
    num = 0.0
    den = 0.0
    for i in range(y_new.shape[0]):
        a = K[N_STAGES, i] - K[N_STAGES - 1, i]
        b = y_new[i] - ytmp[i]
        num += a * a
        den += b * b
    if den > 0.0:
        return h * np.sqrt(num / den)
    return 0.0


@jit
def _rho_bound(K, n, v, w):
    """The Perron root of |J| (power iteration, 30 steps from ones): a bound
    of J's spectral radius, tight for the springs' damped modes (within a
    factor 1 + zeta for one of damping ratio zeta).  |J| is the same for a
    mirrored state, so mirrored runs switch alike.  v, w: work vectors."""
    r_j = R_E + n
    for i in range(n):
        v[i] = 1.0
    lam = 0.0
    for _ in range(30):
        lam = 0.0
        for i in range(n):
            acc = 0.0
            for j in range(n):
                acc += abs(K[r_j + i, j]) * v[j]
            w[i] = acc
            if acc > lam:
                lam = acc
        if not lam > 0.0 or not np.isfinite(lam):
            return lam
        for i in range(n):
            v[i] = w[i] / lam
    return lam


@jit_generic
def auto_step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp, y_new, y_scale,
              tol, opt, par, disc, hdr, smp, met):
    """DP5 until the problem is stiff, then Rodas4 (module docstring)."""
    n = y.shape[0]
    r_s = _row(n, W_STATE)
    if fresh:
        K[r_s + 1, S_JOK] = 0.0
    method = opt[O_METHOD]
    stiff = method == METHOD_RODAS or (method != METHOD_DOPRI and
                                       K[r_s, S_STIFF] != 0.0)
    if not stiff:
        err, expo = dopri_step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp,
                               y_new, y_scale, tol, opt, par, disc, hdr, smp, met)
        K[r_s + 1, S_LAST] = 0.0
        if method == METHOD_DOPRI:
            return err, expo
        if fixed:
            if err <= ERR_FIXED_MAX and _all_finite(y_new):
                return err, expo
            K[r_s, S_STIFF] = 1.0
            K[r_s, S_COUNT] = 0.0
        else:
            if err < 1.0:
                # DOPRI5's counts: 15 stiff steps, unless 6 non-stiff ones
                # in a row come first (more after each switch back)
                if _h_lambda(K, h, y_new, ytmp) > H_LAMBDA_STIFF:
                    K[r_s + 2, S_NONSTIFF] = 0.0
                    K[r_s, S_COUNT] += 1.0
                    if K[r_s, S_COUNT] >= max(N_DETECT, K[r_s + 3, S_DETECT]):
                        K[r_s, S_STIFF] = 1.0
                        K[r_s, S_COUNT] = 0.0
                        K[r_s + 3, S_PAID] = 0.0
                else:
                    K[r_s + 2, S_NONSTIFF] += 1.0
                    if K[r_s + 2, S_NONSTIFF] >= N_RESET:
                        K[r_s, S_COUNT] = 0.0
            return err, expo
    err, expo = rodas_step(rhs, t, y, f, h, fresh, fixed, K, ytmp, ftmp,
                           y_new, y_scale, tol, opt, par, disc, hdr, smp, met)
    K[r_s + 1, S_LAST] = 1.0
    if method != METHOD_RODAS and not fixed and err < 1.0:
        # Rodas4 pays where its step beats DP5's stability-bound one,
        # 3.25/rho, by more than its cost per step: 6 + 2 n + 2
        # evaluations against 6
        if h * _rho_bound(K, n, ytmp, ftmp) * 6.0 < H_LAMBDA_STIFF * (N_ROS + 2 * n + 2):
            K[r_s, S_COUNT] += 1.0
            if K[r_s, S_COUNT] >= N_DETECT:
                K[r_s, S_STIFF] = 0.0
                K[r_s, S_COUNT] = 0.0
                K[r_s + 2, S_NONSTIFF] = 0.0
                # a stint that paid somewhere (stiff phases between transients that
                # accuracy resolves) may come back at once; one that never did waits longer
                K[r_s + 3, S_DETECT] = (N_DETECT if K[r_s + 3, S_PAID] != 0.0 else
                                        2.0 * max(N_DETECT, K[r_s + 3, S_DETECT]))
        else:
            K[r_s, S_COUNT] = 0.0
            K[r_s + 3, S_PAID] = 1.0
    return err, expo


@jit
def auto_dense(K, h, y_old, y_new, Q):
    """Dense output of whichever method took the last step."""
    n = y_old.shape[0]
    if K[_row(n, W_STATE) + 1, S_LAST] != 0.0:
        rodas_dense(K, h, y_old, y_new, Q)
    else:
        dopri_dense(K, h, y_old, y_new, Q)
