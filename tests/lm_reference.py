"""The hand-written Levenberg-Marquardt fitter fastrock used before SciPy's least_squares
(issue #16, item 4), kept verbatim as the reference that the library fit must reproduce."""
import numpy as np


def _levenberg_marquardt(fun, z0, *, max_nfev=200, xtol=1e-10, ftol=1e-12, gtol=1e-12):
    """Minimise ``0.5 ||fun(z)||^2`` (Levenberg-Marquardt, Marquardt diagonal scaling).

    The Jacobian is approximated by central differences. Returns
    ``(z, r, nfev, success, message)``.
    """
    z = np.asarray(z0, dtype=float).copy()
    r = fun(z)
    nfev = 1
    if not np.all(np.isfinite(r)):
        return z, r, nfev, False, "model is not finite at the initial guess"
    cost = 0.5 * float(r @ r)
    lam = None
    n = z.size

    def jac(z):
        nonlocal nfev
        J = np.empty((r.size, n))
        for j in range(n):
            h = 1e-6 * max(1.0, abs(z[j]))
            zp, zm = z.copy(), z.copy()
            zp[j] += h
            zm[j] -= h
            J[:, j] = (fun(zp) - fun(zm)) / (2.0 * h)
            nfev += 2
        return J

    J = jac(z)
    while True:
        A = J.T @ J
        gvec = J.T @ r
        if np.max(np.abs(gvec)) <= gtol * max(1.0, cost):
            return z, r, nfev, True, "gradient below gtol"
        d = np.maximum(np.diag(A), 1e-12 * max(1.0, np.max(np.diag(A))))
        if lam is None:
            lam = 1e-3
        while True:
            if nfev >= max_nfev:
                return z, r, nfev, False, "maximum number of model evaluations reached"
            try:
                step = np.linalg.solve(A + lam * np.diag(d), -gvec)
            except np.linalg.LinAlgError:
                lam *= 10.0
                if lam > 1e16:       # a bound: singular however much the step is damped
                    return z, r, nfev, False, "singular normal equations"
                continue
            z_new = z + step
            r_new = fun(z_new)
            nfev += 1
            cost_new = 0.5 * float(r_new @ r_new) if np.all(np.isfinite(r_new)) else np.inf
            if cost_new < cost:
                rel = (cost - cost_new) / max(cost, 1e-300)
                small_step = np.linalg.norm(step) <= xtol * (np.linalg.norm(z) + xtol)
                z, r, cost = z_new, r_new, cost_new
                lam = max(lam / 3.0, 1e-12)
                if rel <= ftol:
                    return z, r, nfev, True, "relative cost reduction below ftol"
                if small_step:
                    return z, r, nfev, True, "step below xtol"
                J = jac(z)
                break
            lam *= 4.0
            if lam > 1e16 or np.linalg.norm(step) <= xtol * (np.linalg.norm(z) + xtol):
                return z, r, nfev, True, "no further decrease possible (local minimum)"
