"""Fragility curves (lognormal) fitted to study results, with a record bootstrap.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from fastrock import _validate as V


#: Outcomes counted as overturning by :func:`fit_fragility`.
COLLAPSE_OUTCOMES = ("mode1", "mode2")

#: Outcomes left out of a fragility fit (the run did not finish).
EXCLUDED_OUTCOMES = ("failed", "unfinished")


# ============================================================== fragility
@dataclass
class FragilityFit:
    """Lognormal fragility ``P(IM) = Phi(ln(IM / theta) / beta)``.

    Attributes
    ----------
    theta : float
        Median capacity, in the unit of ``im``.
    beta : float
        Logarithmic standard deviation [-].
    im : str
        IM column.
    event : str
        "overturning" or "max_rotation_ratio > x".
    se_ln_theta, se_beta : float
        Asymptotic standard errors (inverse observed information; rows taken
        as independent).
    boot_theta, boot_beta : ndarray
        Bootstrap estimates (records resampled with replacement).
    ci : float
        Coverage of :meth:`band` and :meth:`interval`.
    x, n, k : ndarray
        Distinct IM values, trials and events at each (the data fitted).
    """

    theta: float
    beta: float
    im: str
    event: str
    se_ln_theta: float
    se_beta: float
    loglik: float
    n_rows: int
    n_events: int
    n_records: int
    n_excluded: int
    x: np.ndarray
    n: np.ndarray
    k: np.ndarray
    boot_theta: np.ndarray
    boot_beta: np.ndarray
    n_boot_failed: int
    ci: float
    label: str = ""

    def probability(self, im):
        """P(event | IM) of the fitted curve."""
        return _fragility(np.asarray(im, float), self.theta, self.beta)

    def band(self, im, ci=None):
        """Pointwise bootstrap band (lo, hi) of P at ``im``."""
        ci = self.ci if ci is None else ci
        im = np.asarray(im, float)
        if self.boot_theta.size == 0:
            p = self.probability(im)
            return p, p
        curves = _fragility(im[None, :], self.boot_theta[:, None], self.boot_beta[:, None])
        q = 50 * (1 - ci)
        return np.percentile(curves, q, axis=0), np.percentile(curves, 100 - q, axis=0)

    def interval(self, ci=None):
        """Bootstrap percentile intervals {"theta": (lo, hi), "beta": (lo, hi)}."""
        ci = self.ci if ci is None else ci
        q = [50 * (1 - ci), 100 - 50 * (1 - ci)]
        if self.boot_theta.size == 0:
            return {"theta": (math.nan, math.nan), "beta": (math.nan, math.nan)}
        return {"theta": tuple(np.percentile(self.boot_theta, q)),
                "beta": tuple(np.percentile(self.boot_beta, q))}


def _fragility(im, theta, beta):
    from scipy import special
    with np.errstate(divide="ignore"):
        return special.ndtr(np.log(im / theta) / beta)


_LN_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


def _mills(z):
    """phi(z) / Phi(z), stable for very negative z (both in logs)."""
    from scipy import special
    z = np.asarray(z, float)
    return np.exp(-0.5 * z * z - _LN_SQRT_2PI - special.log_ndtr(z))


def _probit_mle(u, n, k):
    """Maximise sum k ln Phi(a + b u) + (n - k) ln Phi(-(a + b u)) (concave) with
    scipy.optimize.minimize, trust-exact, on the analytic gradient and Hessian.  (Not
    least_squares: a binomial likelihood is no sum of squares.)

    Returns (a, b, cov_ab, loglik) on the standardised u; None if the
    outcomes are separated (no finite maximum) or b <= 0.
    """
    from scipy import optimize, special
    if not ((k > 0).any() and (k < n).any()):
        return None
    hi_no = u[k < n].max()        # largest IM with a non-event
    lo_yes = u[k > 0].min()       # smallest IM with an event
    if hi_no <= lo_yes:
        return None               # (quasi-)complete separation: beta -> 0

    def parts(x):
        eta = x[0] + x[1] * u
        lp, lm = _mills(eta), _mills(-eta)
        s = k * lp - (n - k) * lm
        h = -k * lp * (eta + lp) - (n - k) * lm * (lm - eta)
        return eta, s, h

    def neg_ll(x):
        eta = x[0] + x[1] * u
        return -float(np.sum(k * special.log_ndtr(eta) + (n - k) * special.log_ndtr(-eta)))

    def neg_grad(x):
        _, s, _ = parts(x)
        return -np.array([s.sum(), (s * u).sum()])

    def neg_hess(x):
        _, _, h = parts(x)
        return -np.array([[h.sum(), (h * u).sum()], [(h * u).sum(), (h * u * u).sum()]])

    res = optimize.minimize(neg_ll, np.array([0.0, 1.0]), jac=neg_grad, hess=neg_hess,
                            method="trust-exact", options={"gtol": 1e-11, "maxiter": 200})
    a, b = res.x
    if not (b > 0 and np.isfinite(b) and np.isfinite(res.fun)):
        return None
    try:
        cov = np.linalg.inv(neg_hess(res.x))
    except np.linalg.LinAlgError:
        return None
    return a, b, cov, -float(res.fun)


def _fit_weighted(lnx, rec_w, rec_of_row, y, xs_index, nx):
    """MLE from rows weighted by record multiplicity; (ln theta, beta, cov, ll)."""
    w = rec_w[rec_of_row]
    n = np.bincount(xs_index, weights=w, minlength=nx)
    k = np.bincount(xs_index, weights=w * y, minlength=nx)
    keep = n > 0
    u0 = lnx[keep]
    mu, sd = u0.mean(), u0.std()
    sd = sd if sd > 0 else 1.0
    r = _probit_mle((u0 - mu) / sd, n[keep], k[keep])
    if r is None:
        return None
    a_s, b_s, cov_s, f = r
    # eta = a_s + b_s (ln x - mu)/sd = (ln x - ln theta) / beta
    beta = sd / b_s
    ln_theta = mu - a_s * sd / b_s
    # delta method: (a_s, b_s) -> (ln theta, beta)
    J = np.array([[-sd / b_s, a_s * sd / b_s ** 2], [0.0, -sd / b_s ** 2]])
    return ln_theta, beta, J @ cov_s @ J.T, f


#: Most bootstrap resamples of fit_fragility.
MAX_BOOT = 1_000_000


def fit_fragility(df, im="pga_g", threshold=None, *, n_boot=200, seed=0, ci=0.90, label=""):
    """Lognormal fragility curve by maximum likelihood, with a bootstrap band.

    Parameters
    ----------
    df : DataFrame
        Study results (:func:`load_results`), typically one body and variant.
        Needs columns ``record``, ``outcome``, ``im`` (and
        ``max_rotation_ratio`` with ``threshold``).
    im : str
        Intensity-measure column ("pga_g", "pgv", "pga_over_g_tan_alpha",
        "scale", ...); values must be > 0.
    threshold : float, optional
        None: the event is overturning (outcome mode1 or mode2).  A number
        x: the event is ``max |theta| / alpha > x`` or overturning.
    n_boot : int
        Bootstrap resamples of whole records (0: none).
    seed : int
        Seed of the resampling.
    ci : float
        Coverage of the band and intervals (default 0.90).

    Returns
    -------
    FragilityFit

    Raises
    ------
    ValueError
        No event, no non-event, or the events are separated by the IM (every
        non-event below every event): the MLE has beta -> 0 and no finite
        value; add levels or records.

    Notes
    -----
    Rows whose run failed are left out (``n_excluded``).  Each row is a
    Bernoulli trial (Baker 2015, doi:10.1193/021113EQS025M): the
    log-likelihood ``sum y ln P + (1-y) ln(1-P)`` is maximised (scipy.optimize.minimize,
    trust-exact, analytic derivatives) on the probit form ``P = Phi(a + b ln IM)``, where it is concave.
    The standard errors treat rows as independent; the rows of one record are
    not, which the record bootstrap accounts for.
    """
    n_boot = V.integer("n_boot", n_boot, 0, MAX_BOOT)
    ci = V.in_open("ci", ci, 0.0, 1.0)
    if not isinstance(im, str):
        raise ValueError(f"fit_fragility: im must be a column name, got {im!r}")
    for col in ("record", "outcome", im):
        if col not in df.columns:
            raise ValueError(f"fit_fragility: column {col!r} missing")
    ok = ~df["outcome"].isin(EXCLUDED_OUTCOMES).to_numpy()
    d = df[ok]
    x = d[im].to_numpy(float)
    if not (np.isfinite(x).all() and (x > 0).all()):
        raise ValueError(f"fit_fragility: {im} must be finite and > 0")
    over = d["outcome"].isin(COLLAPSE_OUTCOMES).to_numpy()
    if threshold is None:
        y = over.astype(float)
        event = "overturning"
    else:
        threshold = V.positive("threshold", threshold)
        if "max_rotation_ratio" not in d.columns:
            raise ValueError("fit_fragility: column 'max_rotation_ratio' missing")
        y = (over | (d["max_rotation_ratio"].to_numpy(float) > threshold)).astype(float)
        event = f"max_rotation_ratio > {threshold:g}"
    if y.size == 0:
        raise ValueError("fit_fragility: no finished rows")
    # one group per IM value; values a few ulps apart (IMs computed from the
    # scale factor, e.g. PGA/(g tan alpha) of a PGA study) are one group, at
    # their mean
    key = np.round(np.log(x) * 1e10).astype(np.int64)
    _, xi = np.unique(key, return_inverse=True)
    xs = np.bincount(xi, weights=x) / np.bincount(xi)
    rec_codes, rec_of_row = np.unique(d["record"].to_numpy(object).astype(str), return_inverse=True)
    nrec = rec_codes.size
    lnx = np.log(xs)
    r = _fit_weighted(lnx, np.ones(nrec), rec_of_row, y, xi, xs.size)
    if r is None:
        raise ValueError(
            f"fit_fragility: no finite MLE for {event} against {im}: "
            + ("no event in the data" if y.sum() == 0 else
               "every row is an event" if y.sum() == y.size else
               "the events are separated by the IM (every non-event below every event); "
               "add intensity levels or records"))
    ln_theta, beta, cov, f = r
    rng = np.random.default_rng(seed)
    bt, bb = [], []
    failed = 0
    for _ in range(int(n_boot)):
        wts = np.bincount(rng.integers(0, nrec, nrec), minlength=nrec).astype(float)
        rb = _fit_weighted(lnx, wts, rec_of_row, y, xi, xs.size)
        if rb is None:
            failed += 1
            continue
        bt.append(math.exp(rb[0]))
        bb.append(rb[1])
    if n_boot and failed > 0.05 * n_boot:
        warnings.warn(f"{failed} of {n_boot} bootstrap resamples had no finite MLE (separated); "
                      f"the band leaves them out and may be too narrow", stacklevel=2)
    n_x = np.bincount(xi, minlength=xs.size).astype(float)
    k_x = np.bincount(xi, weights=y, minlength=xs.size)
    return FragilityFit(
        theta=math.exp(ln_theta), beta=float(beta), im=im, event=event,
        se_ln_theta=math.sqrt(cov[0, 0]), se_beta=math.sqrt(cov[1, 1]), loglik=f,
        n_rows=int(y.size), n_events=int(y.sum()), n_records=int(nrec),
        n_excluded=int((~ok).sum()), x=xs, n=n_x, k=k_x, boot_theta=np.array(bt),
        boot_beta=np.array(bb), n_boot_failed=failed, ci=float(ci), label=label)


