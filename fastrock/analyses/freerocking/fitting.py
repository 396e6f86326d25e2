"""Least-squares identification of p and e from half-cycle durations
(fit_free_rocking) and the registry of predictors of other models.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.analyses.freerocking.checks import as_float_array, check_alpha, check_theta0
from fastrock.analyses.freerocking.housner import (HALF_CYCLE_DEFINITIONS, first_index, half_cycle_indices,
    housner_amplitudes, housner_half_cycle_durations)


_FOUNDATION_MODELS = ("two-spring", "switching")


# ----------------------------------------------------------------------------------------
# 4. fitting
# ----------------------------------------------------------------------------------------
@dataclass
class FreeRockingFit:
    """Result of :func:`fit_free_rocking`.

    Attributes
    ----------
    p, e : float
        Fitted frequency parameter [rad/s] and restitution [-] (NaN if not fitted).
    p_std, e_std : float
        Standard errors from ``cov = s^2 (J^T J)^-1``, ``s^2 = sum(r_w^2) / (m - n)`` with the
        weighted residual vector ``r_w`` (m entries, n parameters) and its Jacobian ``J`` with
        respect to the parameters at the solution.
    residuals : numpy.ndarray
        Measured minus predicted duration [s], one per half-cycle given (also those excluded
        from the objective by ``min_duration``).
    predicted : numpy.ndarray
        Predicted durations [s].
    model : str
        Model name.
    cost : float
        ``0.5 * sum(r_w^2)`` over the residuals used in the objective.
    success : bool
        Convergence flag of the least-squares iteration (scipy.optimize.least_squares).
    message : str
        Why the iteration stopped.
    measured : numpy.ndarray
        Measured durations [s].
    half_cycle : numpy.ndarray of int
        Half-cycle index of each duration.
    group : numpy.ndarray of int
        Group (release test) of each duration, ``0..n_groups-1``.
    theta0 : numpy.ndarray
        Release angle of every group [rad].
    alpha : float
        Slenderness [rad].
    definition : str
        Half-cycle definition.
    used : numpy.ndarray of bool
        Whether each duration entered the objective.
    params, params_std : dict
        All fitted parameters and their standard errors.
    covariance : numpy.ndarray
        Parameter covariance, ordered as ``params``.
    measured_peaks, predicted_peaks : numpy.ndarray or None
        Peak amplitudes [rad] if peaks were fitted.
    nfev : int
        Number of model evaluations.
    """

    p: float
    e: float
    p_std: float
    e_std: float
    residuals: np.ndarray
    predicted: np.ndarray
    model: str
    cost: float
    success: bool
    message: str
    measured: np.ndarray = field(default_factory=lambda: np.zeros(0))
    half_cycle: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    group: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    theta0: np.ndarray = field(default_factory=lambda: np.zeros(0))
    alpha: float = float("nan")
    definition: str = "impact"
    definition_source: str = "given"
    used: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    params: dict = field(default_factory=dict)
    params_std: dict = field(default_factory=dict)
    covariance: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    measured_peaks: np.ndarray | None = None
    predicted_peaks: np.ndarray | None = None
    nfev: int = 0

    @property
    def rms(self) -> float:
        """RMS duration residual [s] over the half-cycles used in the objective."""
        r = self.residuals[self.used]
        return float(np.sqrt(np.mean(r ** 2))) if r.size else float("nan")

    def rms_by_group(self, min_duration: float | None = None) -> pd.Series:
        """RMS duration residual [s] per group (``theta0`` in degrees as index).

        Parameters
        ----------
        min_duration : float, optional
            Only half-cycles whose *measured* duration exceeds this [s] (e.g. 0.15 for the
            rocking part of Yu et al.'s data); default: the ones used in the fit.
        """
        mask = self.used if min_duration is None else self.measured > min_duration
        out = {}
        for gi, t0 in enumerate(self.theta0):
            r = self.residuals[(self.group == gi) & mask]
            out[round(float(np.degrees(t0)), 6)] = (
                float(np.sqrt(np.mean(r ** 2))) if r.size else float("nan"))
        return pd.Series(out, name="rms_s").rename_axis("theta0_deg")

    def to_frame(self) -> pd.DataFrame:
        """Tidy table, one row per half-cycle.

        Returns
        -------
        pandas.DataFrame
            Columns ``group``, ``theta0_deg`` [deg], ``half_cycle``, ``measured`` [s],
            ``predicted`` [s], ``residual`` [s], ``used`` and, if peaks were fitted,
            ``measured_peak``, ``predicted_peak`` [rad]. ``df.attrs`` holds the fitted
            parameters, their standard errors, the model, definition and ``alpha`` [rad].
        """
        df = pd.DataFrame({
            "group": self.group,
            "theta0_deg": np.degrees(self.theta0[self.group]) if self.group.size else [],
            "half_cycle": self.half_cycle,
            "measured": self.measured,
            "predicted": self.predicted,
            "residual": self.residuals,
            "used": self.used,
        })
        if self.measured_peaks is not None:
            df["measured_peak"] = self.measured_peaks
            df["predicted_peak"] = self.predicted_peaks
        df.attrs.update({
            "model": self.model, "definition": self.definition, "alpha": self.alpha,
            **{k: v for k, v in self.params.items()},
            **{f"{k}_std": v for k, v in self.params_std.items()},
            "cost": self.cost, "rms": self.rms, "success": self.success,
        })
        return df

    def summary(self) -> str:
        """Human-readable summary (what ``fastrock fit`` prints)."""
        lines = [f"model: {self.model} (half-cycle definition: {self.definition}, "
                 f"alpha = {np.degrees(self.alpha):.4g} deg)"]
        if self.definition_source != "given":
            lines.append(f"half-cycle definition: {self.definition_source}")
        for k, v in self.params.items():
            unit = " rad/s" if k == "p" else ""
            lines.append(f"{k} = {v:.6g} +/- {self.params_std.get(k, float('nan')):.2g}{unit}")
        lines.append(f"RMS residual = {self.rms:.4g} s over {int(self.used.sum())} "
                     f"half-cycles ({'converged' if self.success else 'NOT converged'}: "
                     f"{self.message})")
        if self.theta0.size > 1:
            for t0deg, v in self.rms_by_group().items():
                lines.append(f"  theta0 = {t0deg:g} deg: RMS residual = {v:.4g} s")
        return "\n".join(lines)


# Parameter transforms used inside the optimiser: bounded (lo, hi) -> logit, (lo, inf) -> log.
def _to_internal(x, lo, hi):
    if np.isfinite(lo) and np.isfinite(hi):
        u = (x - lo) / (hi - lo)
        return math.log(u / (1.0 - u))
    if np.isfinite(lo):
        return math.log(x - lo)
    if np.isfinite(hi):
        return math.log(hi - x)
    return x


def _to_external(z, lo, hi):
    if np.isfinite(lo) and np.isfinite(hi):
        return lo + (hi - lo) / (1.0 + math.exp(-z)) if z > -700 else lo
    if np.isfinite(lo):
        return lo + math.exp(min(z, 700.0))
    if np.isfinite(hi):
        return hi - math.exp(min(z, 700.0))
    return z


def _minimise(fun, z0, *, max_nfev=200, xtol=1e-10, ftol=1e-12, gtol=1e-12):
    """Minimise ``0.5 ||fun(z)||^2`` by :func:`scipy.optimize.least_squares` (trust-region
    reflective, central-difference Jacobian; a non-finite residual shrinks the trust region).
    Returns ``(z, r, nfev, success, message)``."""
    from scipy.optimize import least_squares
    res = least_squares(fun, np.asarray(z0, dtype=float), jac="3-point", method="trf",
                        xtol=xtol, ftol=ftol, gtol=gtol, max_nfev=max_nfev)
    return res.x, res.fun, int(res.nfev + (res.njev or 0) * 2 * res.x.size), bool(res.status > 0), res.message


def _as_groups(values, name, n_groups=None, allow_nan=False):
    """Normalise one array or a sequence of arrays into a list of 1-D float arrays."""
    if values is None:
        return None
    if isinstance(values, np.ndarray) and values.dtype != object:
        groups = [values] if values.ndim <= 1 else list(values)
    elif len(values) and all(np.ndim(v) == 0 for v in values):
        groups = [values]
    else:
        groups = list(values)
    out = []
    for gi, v in enumerate(groups):
        try:
            a = np.atleast_1d(np.asarray(v, dtype=float))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name} must be numeric (group {gi})") from exc
        if a.ndim != 1:
            raise ValueError(f"{name} must be 1-D per group; got shape {a.shape}")
        bad = ~np.isfinite(a) if not allow_nan else np.isinf(a)
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{name} must be finite; group {gi} entry {i} is {a[i]!r}")
        out.append(a)
    if n_groups is not None and len(out) != n_groups:
        raise ValueError(f"{name} has {len(out)} groups but theta0 has {n_groups}")
    return out


#: Built-in predictors of fit_free_rocking's models other than "housner", by name; the models
#: that provide them register here (fastrock.analyses.foundation_predictors: "two-spring",
#: "switching"), so that this module does not import them.
_PREDICTORS = {}


def register_predictor(model, predictor):
    """Make ``predictor(params, n)`` the built-in predictor of ``model`` for fit_free_rocking."""
    if not isinstance(model, str) or model == "housner" or not callable(predictor):
        raise ValueError(f"register_predictor needs a model name other than 'housner' and a "
                         f"callable, got {model!r}, {predictor!r}")
    _PREDICTORS[model] = predictor


def get_predictor(model):
    """The built-in predictor of a model name (e.g. "two-spring", "switching")."""
    if model not in _PREDICTORS:
        raise NotImplementedError(f"unknown model {model!r}: built in are 'housner', "
                                  f"{', '.join(repr(m) for m in _PREDICTORS)}; pass a "
                                  f"predictor callable to fit other models")
    return _PREDICTORS[model]


class DefinitionWarning(UserWarning):
    """The half-cycle definition was not given and was chosen by the smaller residual."""


def fit_free_rocking(half_cycle_durations, theta0, alpha, peaks=None, model="housner",
                     e0=None, p0=None, predictor=None, *, half_cycle=None,
                     definition=None, peak_weight=None, min_duration=None,
                     params0=None, bounds=None, max_nfev=400, xtol=1e-10, ftol=1e-14):
    """Fit ``p`` and ``e`` (or other parameters) to measured half-cycle durations.

    Model ``"housner"``: the exact nonlinear rigid block released from rest at ``theta0``
    with restitution ``e``; amplitudes from the exact energy relation, half-cycle durations as
    in :func:`housner_half_cycle_durations` (impact to impact: ``2 q(theta_k)``, release to
    first impact ``q(theta_0)``; peak to peak: ``q(theta_{k-1}) + q(theta_k)``). The
    least-squares objective is ``0.5 sum r_w^2`` with

    * duration residuals ``measured - predicted`` [s] (unweighted), and, if ``peaks`` are given,
    * peak residuals ``peak_weight * (|measured peak| - predicted amplitude)``: ``peak_weight``
      [s/rad] defaults to ``mean(duration) / mean(|peak|)``, so that a given *relative* error of
      a peak costs as much as the same relative error of an average duration.

    It is minimised by scipy.optimize.least_squares in transformed parameters
    (``log p``, ``logit e``), so ``p > 0`` and ``0 < e < 1`` always hold.

    Several release tests can be fitted jointly with shared parameters: pass a sequence of
    duration arrays and a sequence of ``theta0`` (one per test).

    Parameters
    ----------
    half_cycle_durations : array_like or sequence of array_like
        Measured durations [s], > 0.
    theta0 : float or sequence of float
        Release angle(s) [rad], ``0 < theta0 < alpha``.
    alpha : float
        Slenderness [rad] (kept fixed).
    peaks : array_like or sequence of array_like, optional
        Measured peak angle of every half-cycle [rad] (sign ignored; NaN = missing).
    model : str
        ``"housner"``; other names (``"two-spring"``, ``"switching"``, ...) need ``predictor``.
    e0, p0 : float, optional
        Initial guesses. Default ``e0``: Housner's rectangle value ``1 - 1.5 sin^2 alpha``;
        default ``p0``: the best ``1/p`` scale of the ``housner`` prediction at ``e0``.
    predictor : callable, optional
        ``predictor(params, n_half_cycles) -> durations`` (or ``(durations, peaks)`` when
        ``peaks`` are fitted). ``params`` is a dict with the fitted parameters (``"p"``,
        ``"e"`` or the keys of ``params0``) plus ``"theta0"``, ``"alpha"`` [rad] and
        ``"definition"``; it must return the durations [s] of half-cycles
        ``first, ..., first + n_half_cycles - 1`` (``first = 0`` for "impact", 1 for
        "peak"), i.e. what :func:`half_cycles` returns for the simulated release test. Shorter
        outputs are padded with 0 (the body came to rest).
    half_cycle : array_like or sequence of array_like of int, optional
        Index of each duration; default ``first, first+1, ...`` per group.
    definition : {"impact", "peak"}, optional
        Half-cycle definition of the measurement: impact to impact or peak to peak.  It is a
        property of how the data were measured and the fitted ``p`` differs by tens of percent
        between the two, so give it.  Default None: both are fitted; where the indices admit
        only one (``half_cycle`` 0 exists only for "impact") that one is used, otherwise the one
        with the smaller RMS residual, with a :class:`DefinitionWarning` naming both residuals.
        ``fit.definition_source`` says which rule applied.
    peak_weight : float, optional
        See above [s/rad].
    min_duration : float, optional
        Measured durations below this [s] are excluded from the objective (e.g. 0.15 to fit
        only the rocking regime of Yu et al.'s data); they still get predictions and residuals.
    params0 : dict, optional
        Initial values of the parameters to fit with a ``predictor`` (default
        ``{"p": p0, "e": e0}``).
    bounds : dict, optional
        ``name -> (lo, hi)``; defaults ``p: (0, inf)``, ``e: (0, 1)``, others unbounded.
    max_nfev : int
        Maximum number of model evaluations.
    xtol, ftol : float
        Convergence tolerances on the step and the relative cost reduction.

    Returns
    -------
    FreeRockingFit

    Raises
    ------
    ValueError
        Non-positive or non-finite durations, ``theta0 >= alpha``, fewer used durations than
        parameters + 1, malformed indices.
    NotImplementedError
        ``model`` is not ``"housner"`` and no ``predictor`` is given.

    Examples
    --------
    Half-cycles of a simulated free-rocking run give back the block's p and e:

    >>> import numpy as np
    >>> from fastrock import RigidBlock, fit_free_rocking, half_cycles, simulate
    >>> block = RigidBlock.rectangle(b=0.2, h=0.8)
    >>> run = simulate(block, None, theta0=0.1, duration=6.0, t_eval=np.linspace(0, 6, 6001))
    >>> hc = half_cycles(run.history.t, run.history.theta)
    >>> fit = fit_free_rocking(hc.duration.to_numpy()[:10], 0.1, block.alpha, definition="impact")
    >>> round(float(fit.p), 3), round(float(fit.e), 3), round(block.p, 3), round(block.e, 3)
    (2.987, 0.912, 2.987, 0.912)
    """
    if not isinstance(model, str):
        raise ValueError(f"model must be a string; got {model!r}")
    if definition is None:
        return _fit_either_definition(
            half_cycle_durations, theta0, alpha, peaks=peaks, model=model, e0=e0, p0=p0,
            predictor=predictor, half_cycle=half_cycle, peak_weight=peak_weight,
            min_duration=min_duration, params0=params0, bounds=bounds, max_nfev=max_nfev,
            xtol=xtol, ftol=ftol)
    max_nfev = V.integer("max_nfev", max_nfev, 1, 10 ** 7)
    V.positive("xtol", xtol)
    V.positive("ftol", ftol)
    if predictor is None and model != "housner":
        predictor = get_predictor(model)          # raises NotImplementedError if unknown
    first = first_index(definition)
    alpha = float(check_alpha(alpha))
    durs = _as_groups(half_cycle_durations, "half_cycle_durations")
    t0s = np.atleast_1d(as_float_array("theta0", theta0)).astype(float)
    if len(durs) != t0s.size:
        raise ValueError(f"got {len(durs)} duration group(s) but {t0s.size} theta0 value(s)")
    check_theta0(t0s, alpha)
    for gi, d in enumerate(durs):
        if np.any(d <= 0.0):
            i = int(np.flatnonzero(d <= 0.0)[0])
            raise ValueError(f"half_cycle_durations must be > 0; group {gi} entry {i} "
                             f"is {d[i]!r}")
    if half_cycle is None:
        idxs = [np.arange(first, first + d.size) for d in durs]
    else:
        hc = _as_groups(half_cycle, "half_cycle", len(durs))
        idxs = []
        for gi, (h, d) in enumerate(zip(hc, durs)):
            if h.size != d.size:
                raise ValueError(f"half_cycle group {gi} has {h.size} entries, durations "
                                 f"{d.size}")
            idxs.append(half_cycle_indices(h, first))
    pk = _as_groups(peaks, "peaks", len(durs), allow_nan=True)
    if pk is not None:
        for gi, (q, d) in enumerate(zip(pk, durs)):
            if q.size != d.size:
                raise ValueError(f"peaks group {gi} has {q.size} entries, durations {d.size}")
        pk = [np.abs(q) for q in pk]

    measured = np.concatenate(durs)
    index = np.concatenate(idxs)
    group = np.concatenate([np.full(d.size, gi) for gi, d in enumerate(durs)])
    used = np.ones(measured.size, bool)
    if min_duration is not None:
        used = measured > float(min_duration)
    meas_peaks = np.concatenate(pk) if pk is not None else None
    peak_used = (np.isfinite(meas_peaks) & used) if pk is not None else None

    # ---- parameters
    if e0 is None:
        e0 = min(max(1.0 - 1.5 * math.sin(alpha) ** 2, 0.05), 0.995)
    e0 = float(e0)
    if not 0.0 < e0 < 1.0:
        raise ValueError(f"e0 must satisfy 0 < e0 < 1; got {e0!r}")
    if p0 is None and (params0 is None or "p" not in params0):
        qsum = np.concatenate([
            housner_half_cycle_durations(t0, alpha, 1.0, e0, ix, definition)
            for t0, ix in zip(t0s, idxs)])
        m = used & (qsum > 0)
        p0 = float(np.sum(qsum[m] ** 2) / np.sum(qsum[m] * measured[m])) if m.any() else 1.0
    if params0 is None:
        params0 = {"p": float(p0), "e": e0}
    params0 = {k: float(v) for k, v in params0.items()}
    if model == "housner" and predictor is None and set(params0) != {"p", "e"}:
        raise ValueError("the housner model fits exactly the parameters 'p' and 'e'")
    names = list(params0)
    bnds = {"p": (0.0, np.inf), "e": (0.0, 1.0)}
    bnds.update({k: tuple(map(float, v)) for k, v in (bounds or {}).items()})
    lims = [bnds.get(k, (-np.inf, np.inf)) for k in names]
    for k, (lo, hi) in zip(names, lims):
        if not lo < params0[k] < hi:
            raise ValueError(f"initial {k} = {params0[k]!r} outside its bounds ({lo}, {hi})")

    n_fit = int(used.sum()) + (int(peak_used.sum()) if pk is not None else 0)
    if n_fit <= len(names):
        raise ValueError(f"need more than {len(names)} data points to fit {names}; "
                         f"got {n_fit}")

    if peak_weight is None and pk is not None:
        mp = np.nanmean(meas_peaks[peak_used]) if peak_used.any() else np.nan
        peak_weight = float(np.mean(measured[used]) / mp) if mp > 0 else 1.0

    def _predict(par: dict):
        pred_d = np.empty(measured.size)
        pred_p = np.empty(measured.size) if pk is not None else None
        for gi, (t0, ix) in enumerate(zip(t0s, idxs)):
            sel = group == gi
            n_needed = int(ix.max()) - first + 1 if ix.size else 0
            if predictor is None:
                d_all = housner_half_cycle_durations(t0, alpha, par["p"], par["e"], n_needed,
                                                     definition)
                if pk is not None:
                    amps = housner_amplitudes(t0, alpha, par["e"], int(ix.max()))
                    pk_all = amps[np.arange(first, first + n_needed)]
            else:
                out = predictor({**par, "theta0": float(t0), "alpha": alpha,
                                 "definition": definition}, n_needed)
                if pk is not None:
                    if not (isinstance(out, tuple) and len(out) == 2):
                        raise TypeError("with peaks, predictor must return "
                                         "(durations, peaks)")
                    d_all, pk_all = (np.asarray(o, dtype=float).ravel() for o in out)
                    pk_all = np.abs(np.pad(pk_all[:n_needed], (0, max(0, n_needed
                                                                     - pk_all.size))))
                else:
                    d_all = np.asarray(out, dtype=float).ravel()
                d_all = np.pad(d_all[:n_needed], (0, max(0, n_needed - d_all.size)))
            pred_d[sel] = d_all[ix - first]
            if pk is not None:
                pred_p[sel] = pk_all[ix - first]
        return pred_d, pred_p

    def _ext(z):
        return {k: _to_external(zi, lo, hi) for k, zi, (lo, hi) in zip(names, z, lims)}

    def _weighted(par):
        pd_, pp_ = _predict(par)
        r = (measured - pd_)[used]
        if pk is not None:
            r = np.concatenate([r, peak_weight * (meas_peaks - pp_)[peak_used]])
        return r

    def fun(z):
        try:
            return _weighted(_ext(z))
        except (ValueError, FloatingPointError, ZeroDivisionError, OverflowError):
            return np.full(n_fit, np.inf)

    z0 = np.array([_to_internal(params0[k], lo, hi) for k, (lo, hi) in zip(names, lims)])
    if not np.all(np.isfinite(fun(z0))):
        raise ValueError(f"model {model!r} is not finite at the initial guess {params0}")
    z, r, nfev, success, message = _minimise(fun, z0, max_nfev=max_nfev, xtol=xtol, ftol=ftol)
    par = _ext(z)
    cost = 0.5 * float(r @ r)

    # covariance in external parameters: central-difference Jacobian at the solution
    x = np.array([par[k] for k in names])
    J = np.empty((n_fit, len(names)))
    for j, k in enumerate(names):
        lo, hi = lims[j]
        h = 1e-6 * max(abs(x[j]), 1e-3)
        h = min(h, 0.5 * (x[j] - lo), 0.5 * (hi - x[j])) if np.isfinite(hi) else min(
            h, 0.5 * (x[j] - lo))
        pp_, pm_ = dict(par), dict(par)
        pp_[k] += h
        pm_[k] -= h
        J[:, j] = -(_weighted(pp_) - _weighted(pm_)) / (2.0 * h)
    dof = n_fit - len(names)
    s2 = float(r @ r) / dof
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.full((len(names), len(names)), np.nan)
    std = {k: float(np.sqrt(cov[j, j])) if cov[j, j] >= 0 else float("nan")
           for j, k in enumerate(names)}

    pred_d, pred_p = _predict(par)
    return FreeRockingFit(
        p=float(par.get("p", np.nan)), e=float(par.get("e", np.nan)),
        p_std=std.get("p", float("nan")), e_std=std.get("e", float("nan")),
        residuals=measured - pred_d, predicted=pred_d, model=model, cost=cost,
        success=bool(success and np.isfinite(cost)), message=message, measured=measured,
        half_cycle=index, group=group, theta0=t0s, alpha=alpha, definition=definition,
        used=used, params=par, params_std=std, covariance=cov,
        measured_peaks=meas_peaks, predicted_peaks=pred_p, nfev=nfev)


def _fit_either_definition(*args, **kw):
    """fit_free_rocking with the definition the data admit, or the better-fitting one."""
    import warnings
    fits, errors = {}, {}
    for d in HALF_CYCLE_DEFINITIONS:
        try:
            fits[d] = fit_free_rocking(*args, definition=d, **kw)
        except ValueError as exc:
            errors[d] = exc
    if not fits:
        raise errors["impact"]
    if len(fits) == 1:
        (d, fit), = fits.items()
        fit.definition_source = f"the only one the half-cycle indices admit ({errors.popitem()[1]})"
        return fit
    best = min(fits, key=lambda d: fits[d].rms if np.isfinite(fits[d].rms) else np.inf)
    other = next(d for d in fits if d != best)
    fit = fits[best]
    fit.definition_source = (f"not given: chosen by the smaller RMS residual ({best} "
                             f"{fits[best].rms:.3g} s, {other} {fits[other].rms:.3g} s)")
    warnings.warn(f"half-cycle definition not given: '{best}' fits with RMS {fits[best].rms:.3g} s, "
                  f"'{other}' with {fits[other].rms:.3g} s (p = {fits[best].p:.4g} against "
                  f"{fits[other].p:.4g} rad/s); say which your data use (definition=, --definition, "
                  f"or '# definition: ...' in the CSV)", DefinitionWarning, stacklevel=3)
    return fit


