"""The hand-written normal CDF and probit Newton MLE fastrock used before SciPy (issue #16,
item 4), kept verbatim as the reference that the library fit must reproduce."""
import math

import numpy as np


_SQRT2 = math.sqrt(2.0)
_erfc = np.frompyfunc(math.erfc, 1, 1)


def _ndtr(z):
    """Phi(z) from math.erfc (accurate in both tails)."""
    z = np.asarray(z, float)
    return np.asarray(0.5 * _erfc(-z / _SQRT2), dtype=float)


def _fragility(im, theta, beta):
    with np.errstate(divide="ignore"):
        return _ndtr(np.log(im / theta) / beta)


def _log_ndtr(z):
    """ln Phi(z); the asymptotic series below z = -20 (Phi underflows near -38)."""
    z = np.asarray(z, float)
    out = np.empty_like(z)
    lo = z < -20.0
    out[~lo] = np.log(_ndtr(z[~lo]))
    zl = z[lo]
    out[lo] = -0.5 * zl * zl - np.log(-zl) - 0.5 * math.log(2 * math.pi) + np.log1p(-1 / (zl * zl))
    return out


def _mills(z):
    """phi(z) / Phi(z), stable for very negative z."""
    z = np.asarray(z, float)
    out = np.empty_like(z)
    lo = z < -20.0
    zz = z[~lo]
    out[~lo] = np.exp(-0.5 * zz * zz) / math.sqrt(2 * math.pi) / _ndtr(zz)
    zl = z[lo]
    out[lo] = -zl / (1 - 1 / (zl * zl) + 3 / zl ** 4)
    return out


def _probit_mle(u, n, k, max_iter=100):
    """Maximise sum k ln Phi(a + b u) + (n - k) ln Phi(-(a + b u)) by Newton
    with step halving (the probit log-likelihood is concave).

    Returns (a, b, cov_ab, loglik) on the standardised u; None if the
    outcomes are separated (no finite maximum) or b <= 0.
    """
    def ll(a, b):
        eta = a + b * u
        return float(np.sum(k * _log_ndtr(eta) + (n - k) * _log_ndtr(-eta)))

    if not ((k > 0).any() and (k < n).any()):
        return None
    hi_no = u[k < n].max()        # largest IM with a non-event
    lo_yes = u[k > 0].min()       # smallest IM with an event
    if hi_no <= lo_yes:
        return None               # (quasi-)complete separation: beta -> 0
    a, b = 0.0, 1.0
    f = ll(a, b)
    for _ in range(max_iter):
        eta = a + b * u
        lp, lm = _mills(eta), _mills(-eta)
        s = k * lp - (n - k) * lm
        h = -k * lp * (eta + lp) - (n - k) * lm * (lm - eta)
        g = np.array([s.sum(), (s * u).sum()])
        H = np.array([[h.sum(), (h * u).sum()], [(h * u).sum(), (h * u * u).sum()]])
        try:
            step = -np.linalg.solve(H, g)
        except np.linalg.LinAlgError:
            return None
        t = 1.0
        while True:
            a1, b1 = a + t * step[0], b + t * step[1]
            f1 = ll(a1, b1)
            if f1 >= f - 1e-12 * abs(f) or t < 1e-10:
                break
            t *= 0.5
        a, b, f_old, f = a1, b1, f, f1
        if np.max(np.abs(t * step)) < 1e-10 or abs(f - f_old) < 1e-14 * max(1.0, abs(f)):
            break
    if not (b > 0 and np.isfinite(b)):
        return None
    eta = a + b * u
    lp, lm = _mills(eta), _mills(-eta)
    h = -k * lp * (eta + lp) - (n - k) * lm * (lm - eta)
    H = np.array([[h.sum(), (h * u).sum()], [(h * u).sum(), (h * u * u).sum()]])
    return a, b, np.linalg.inv(-H), f
