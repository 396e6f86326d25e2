"""Free rocking of a rigid block: periods, half-cycle analysis and parameter fitting.

This module is the "rocking against vibration" toolbox (Yu, Gutschmidt & MacRae):

* closed-form and quadrature periods of free rocking, of a linear oscillator and of a
  pendulum (:func:`rocking_period_linear`, :func:`rocking_period_exact`,
  :func:`vibration_period`, :func:`pendulum_period`, :func:`pendulum_period_small`);
* extraction of half-cycles (durations, peaks, peak ratios) from any rotation history
  (:func:`half_cycles`);
* the reading of a body-mounted accelerometer (:func:`accelerometer`);
* least-squares identification of the frequency parameter ``p`` and the restitution ``e``
  from measured half-cycle durations (:func:`fit_free_rocking`, :func:`fit_from_csv`), with a
  pluggable ``predictor`` so that foundation models (two-spring, switching; physics.md §5) can
  be fitted with the same machinery later;
* the measured half-cycle durations of Yu et al. (:func:`load_yu2019`);
* plot helpers and the ``fastrock fit`` sub-command (:func:`add_fit_subcommand`,
  :func:`run_fit_command`).

Conventions follow ``physics.md`` §0–§1: SI units, angles in radians unless a name ends in
``_deg``, ``theta > 0`` = tilted to the right, pivot sign ``s = +1`` right corner, ``-1`` left.
``alpha`` is the slenderness angle, ``p = sqrt(M g R / I_0)`` [rad/s] the frequency parameter
and ``e`` Housner's (angular-velocity) coefficient of restitution, ``theta'+ = e theta'-``.

Only numpy, pandas and (lazily) matplotlib are used at run time.

References
----------
Housner, G. W. (1963). The behavior of inverted pendulum structures during earthquakes.
Bull. Seismol. Soc. Am. 53(2), 403-417.

Yu, Gutschmidt & MacRae: experiments on rocking against vibration of a block on felt
(half-cycle durations reproduced in ``fastrock/data/yu2019_halfcycles.csv``).
"""

from __future__ import annotations

import argparse
import csv
import io
import math
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
import numpy as np
import pandas as pd
from numpy.polynomial.legendre import leggauss

from . import _validate as V
from .constants import G_STANDARD

__all__ = [
    "rocking_period_linear",
    "rocking_period_exact",
    "rocking_quarter_period",
    "vibration_period",
    "pendulum_period",
    "pendulum_period_small",
    "ellipk_agm",
    "housner_amplitudes",
    "housner_half_cycle_durations",
    "peak_ratio_from_restitution",
    "restitution_from_peak_ratio",
    "half_cycles",
    "accelerometer",
    "FreeRockingFit",
    "fit_free_rocking",
    "read_half_cycles_csv",
    "fit_from_csv",
    "load_yu2019",
    "YU2019_BLOCK",
    "plot_period_vs_angle",
    "plot_fit",
    "add_fit_subcommand",
    "run_fit_command",
]


# Gauss-Legendre rule for the composite quadrature of the exact quarter period: the
# integrand (see _quarter_period_unit) is analytic with a variation scale of O(1) in u,
# so 24 nodes on panels of width <= 1 give ~1e-14 relative accuracy.
_GL_NODES, _GL_WEIGHTS = leggauss(24)
_PANEL_WIDTH = 1.0

_HALF_CYCLE_COLUMNS = [
    "index", "t_start", "t_end", "duration", "peak_angle", "t_peak", "peak_ratio", "kind",
]
_DEFINITIONS = ("impact", "peak")
_FOUNDATION_MODELS = ("two-spring", "switching")


# ----------------------------------------------------------------------------------------
# validation helpers
# ----------------------------------------------------------------------------------------
def _as_float_array(name: str, value) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be numeric; got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite; got {value!r}")
    return arr


def _check_alpha(alpha) -> np.ndarray:
    a = _as_float_array("alpha", alpha)
    if np.any(a <= 0.0) or np.any(a >= 0.5 * np.pi):
        raise ValueError(f"alpha must satisfy 0 < alpha < pi/2 [rad]; got {alpha!r}")
    return a


def _check_positive(name: str, value) -> np.ndarray:
    arr = _as_float_array(name, value)
    if np.any(arr <= 0.0):
        raise ValueError(f"{name} must be > 0; got {value!r}")
    return arr


def _check_theta0(theta0, alpha) -> np.ndarray:
    t0 = _as_float_array("theta0", theta0)
    if np.any(t0 <= 0.0):
        raise ValueError(f"theta0 must be > 0 [rad]; got {theta0!r}")
    if np.any(t0 >= alpha):
        raise ValueError(
            f"theta0 must be < alpha (a release at theta0 >= alpha overturns); "
            f"got theta0={theta0!r}, alpha={alpha!r}")
    return t0


def _check_e(e) -> float:
    e = float(_as_float_array("e", e))
    if not 0.0 <= e <= 1.0:
        raise ValueError(f"e must satisfy 0 <= e <= 1; got {e!r}")
    return e


def _scalar_or_array(x: np.ndarray):
    return float(x) if np.ndim(x) == 0 else x


# ----------------------------------------------------------------------------------------
# 1. periods
# ----------------------------------------------------------------------------------------
def _acosh1p(w):
    """acosh(1 + w) for w >= 0 without cancellation for small w."""
    w = np.asarray(w, dtype=float)
    return np.log1p(w + np.sqrt(w * (w + 2.0)))


def rocking_period_linear(theta0, alpha, p):
    """Full free-rocking period of the linearised rigid block (Housner; Yu et al.'s ``T_C``).

    ``T = (4/p) acosh(1 / (1 - theta0/alpha))`` (physics.md §6.1): four times the time the
    linearised block ``theta'' = p^2 (theta - alpha)`` released from rest at ``theta0`` needs to
    reach ``theta = 0``. Impacts are ignored (``e = 1``).

    Parameters
    ----------
    theta0 : float or array_like
        Release (amplitude) angle [rad], ``0 < theta0 < alpha``.
    alpha : float or array_like
        Slenderness [rad], ``0 < alpha < pi/2``.
    p : float or array_like
        Frequency parameter [rad/s], ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Period [s], broadcast shape of the inputs.

    Raises
    ------
    ValueError
        Naming the offending field for non-finite input, ``theta0 <= 0``, ``theta0 >= alpha``
        (overturns), ``alpha`` outside ``(0, pi/2)`` or ``p <= 0``.
    """
    a = _check_alpha(alpha)
    pp = _check_positive("p", p)
    t0 = _check_theta0(theta0, a)
    t0, a, pp = np.broadcast_arrays(t0, a, pp)
    r = t0 / a
    # 1/(1-r) - 1 = r/(1-r): avoids cancellation for small theta0.
    return _scalar_or_array(4.0 * _acosh1p(r / (1.0 - r)) / pp)


def _quarter_period_unit(theta0: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """Exact quarter period times ``p`` (i.e. for ``p = 1``), elementwise; 0 where theta0 == 0.

    Derivation (inverted pendulum ``phi = alpha - theta``, ``phi'' = sin phi``): with
    ``x = sin(phi/2)``, ``k0 = sin((alpha - theta0)/2)`` the quarter period
    ``int_0^theta0 dtheta / sqrt(2[cos(alpha-theta0) - cos(alpha-theta)])`` becomes
    ``int_{k0}^{sin(alpha/2)} dx / sqrt((1-x^2)(x^2-k0^2))`` and with ``x = k0 cosh u``
    ``int_0^U du / sqrt(1 - k0^2 cosh^2 u)``, ``U = acosh(sin(alpha/2)/k0)``. The integrand is
    smooth and bounded (between 1 and 1/cos(alpha/2)), so composite Gauss-Legendre converges
    exponentially; the endpoint singularity of the original form has been removed exactly.
    For ``k0 -> sin(alpha/2)`` the integrand -> 1 and ``U`` -> the linearised value.
    """
    theta0 = np.asarray(theta0, dtype=float)
    alpha = np.asarray(alpha, dtype=float)
    theta0, alpha = np.broadcast_arrays(theta0, alpha)
    k0 = np.sin(0.5 * (alpha - theta0))
    # sin(alpha/2)/k0 - 1 computed without cancellation (sum-to-product).
    w = 2.0 * np.cos(0.25 * (2.0 * alpha - theta0)) * np.sin(0.25 * theta0) / k0
    U = _acosh1p(w)
    out = np.zeros(theta0.shape)
    if U.size == 0:
        return out
    n_panels = max(1, int(np.ceil(np.max(U) / _PANEL_WIDTH)))
    j = np.arange(n_panels)[:, None]
    s = ((j + 0.5 * (_GL_NODES[None, :] + 1.0)) / n_panels).ravel()   # in [0, 1]
    wts = np.tile(_GL_WEIGHTS, n_panels) / (2.0 * n_panels)
    Uf = U.reshape(-1, 1)
    kf = k0.reshape(-1, 1)
    u = Uf * s[None, :]
    integrand = 1.0 / np.sqrt(1.0 - (kf * np.cosh(u)) ** 2)
    out = (Uf[:, 0] * (integrand @ wts)).reshape(theta0.shape)
    return np.where(theta0 > 0.0, out, 0.0)


def rocking_quarter_period(theta0, alpha, p, linear: bool = False):
    """Time from release at rest at ``theta0`` to the first impact (``theta = 0``) [s].

    Parameters
    ----------
    theta0, alpha, p : float or array_like
        As in :func:`rocking_period_exact`.
    linear : bool, optional
        Use the linearised closed form instead of the exact quadrature.

    Returns
    -------
    float or numpy.ndarray
        Quarter period [s].
    """
    if linear:
        return rocking_period_linear(theta0, alpha, p) / 4.0
    return rocking_period_exact(theta0, alpha, p) / 4.0


def rocking_period_exact(theta0, alpha, p):
    """Full free-rocking period of the exact (nonlinear) rigid block, without impact losses.

    ``T = 4 int_0^theta0 dtheta / (p sqrt(2[cos(alpha - theta0) - cos(alpha - theta)]))``
    (physics.md §6.2). The integrable endpoint singularity is removed exactly by the change of
    variables ``sin((alpha-theta)/2) = sin((alpha-theta0)/2) cosh(u)`` and the remaining smooth
    integral is evaluated by composite Gauss-Legendre quadrature
    (:func:`numpy.polynomial.legendre.leggauss`, 24 nodes per unit panel in ``u``); relative
    accuracy ~1e-13 for ``1e-8 < theta0/alpha < 1 - 1e-8``. Check value (physics.md §6):
    ``p = 2, alpha = 0.25, theta0 = 0.15`` gives a quarter period of 0.7844874371 s.

    Parameters
    ----------
    theta0 : float or array_like
        Release (amplitude) angle [rad], ``0 < theta0 < alpha``.
    alpha : float or array_like
        Slenderness [rad], ``0 < alpha < pi/2``.
    p : float or array_like
        Frequency parameter [rad/s], ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Period [s].

    Raises
    ------
    ValueError
        As :func:`rocking_period_linear`.
    """
    a = _check_alpha(alpha)
    pp = _check_positive("p", p)
    t0 = _check_theta0(theta0, a)
    t0, a, pp = np.broadcast_arrays(t0, a, pp)
    return _scalar_or_array(4.0 * _quarter_period_unit(t0, a) / pp)


def vibration_period(omega):
    """Period of linear vibration ``T_L = 2 pi / omega`` [s].

    Parameters
    ----------
    omega : float or array_like
        Natural circular frequency [rad/s], ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Period [s].
    """
    w = _check_positive("omega", omega)
    return _scalar_or_array(2.0 * np.pi / w)


def ellipk_agm(k):
    """Complete elliptic integral of the first kind ``K(k)`` (modulus ``k``, not ``m = k^2``).

    ``scipy.special.ellipkm1`` of the complementary parameter ``1 - k^2 = (1 - k)(1 + k)``,
    accurate up to ``k -> 1``.  (The name stays from the arithmetic-geometric mean it once used.)

    Parameters
    ----------
    k : float or array_like
        Modulus, ``0 <= k < 1``.

    Returns
    -------
    float or numpy.ndarray
        ``K(k)`` [-].
    """
    k = _as_float_array("k", k)
    if np.any(k < 0.0) or np.any(k >= 1.0):
        raise ValueError(f"k must satisfy 0 <= k < 1; got {k!r}")
    from scipy import special
    return _scalar_or_array(special.ellipkm1((1.0 - k) * (1.0 + k)))


def _check_pendulum(theta0, omega):
    w = _check_positive("omega", omega)
    t0 = _as_float_array("theta0", theta0)
    if np.any(t0 <= 0.0) or np.any(t0 >= np.pi):
        raise ValueError(f"theta0 must satisfy 0 < theta0 < pi [rad]; got {theta0!r}")
    return np.broadcast_arrays(t0, w)


def pendulum_period(theta0, omega):
    """Period of the nonlinear pendulum ``theta'' = -omega^2 sin(theta)`` (Yu et al.'s ``T_NL``).

    ``T = 4 K(sin(theta0/2)) / omega`` with ``K`` from :func:`ellipk_agm`.

    Parameters
    ----------
    theta0 : float or array_like
        Amplitude [rad], ``0 < theta0 < pi``.
    omega : float or array_like
        Small-amplitude circular frequency [rad/s], ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Period [s].
    """
    t0, w = _check_pendulum(theta0, omega)
    return _scalar_or_array(4.0 * ellipk_agm(np.sin(0.5 * t0)) / w)


def pendulum_period_small(theta0, omega):
    """Small-amplitude series of the pendulum period [s].

    ``T = (1 + theta0^2/16 + 11 theta0^4/3072) 2 pi / omega``; the truncation error is
    ``173/737280 theta0^6 * 2 pi/omega + O(theta0^8)``.

    Parameters
    ----------
    theta0 : float or array_like
        Amplitude [rad], ``0 < theta0 < pi``.
    omega : float or array_like
        Circular frequency [rad/s], ``> 0``.

    Returns
    -------
    float or numpy.ndarray
        Period [s].
    """
    t0, w = _check_pendulum(theta0, omega)
    return _scalar_or_array(
        (1.0 + t0 ** 2 / 16.0 + 11.0 * t0 ** 4 / 3072.0) * 2.0 * np.pi / w)


# ----------------------------------------------------------------------------------------
# Housner free rocking with impacts
# ----------------------------------------------------------------------------------------
def _next_amplitudes(theta: np.ndarray, alpha: float, e: float) -> np.ndarray:
    """Amplitude after one impact from the exact energy relation (physics.md §6.3)."""
    # D = cos(alpha - theta) - cos(alpha) = 2 sin(alpha - theta/2) sin(theta/2)
    D = e * e * 2.0 * np.sin(alpha - 0.5 * theta) * np.sin(0.5 * theta)
    c = np.minimum(np.cos(alpha) + D, 1.0)
    th = alpha - np.arccos(c)
    # one Newton step on f(th) = 2 sin(alpha - th/2) sin(th/2) - D, f' = sin(alpha - th),
    # restores full relative precision for small amplitudes.
    f = 2.0 * np.sin(alpha - 0.5 * th) * np.sin(0.5 * th) - D
    th = th - f / np.sin(alpha - th)
    return np.clip(th, 0.0, theta)


#: Most impacts housner_amplitudes computes (its loop and array).
MAX_IMPACTS = 10_000_000


def housner_amplitudes(theta0, alpha, e, n):
    """Successive rocking amplitudes of a freely rocking rigid block.

    ``cos(alpha - theta_{k+1}) - cos(alpha) = e^2 [cos(alpha - theta_k) - cos(alpha)]``
    (exact energy balance, physics.md §6.3), starting at ``theta_0 = theta0``.

    Parameters
    ----------
    theta0 : float
        Release angle [rad], ``0 < theta0 < alpha``.
    alpha : float
        Slenderness [rad].
    e : float
        Housner restitution (angular-velocity ratio) ``0 <= e <= 1``.
    n : int
        Number of impacts.

    Returns
    -------
    numpy.ndarray, shape (n + 1,)
        ``theta_0 ... theta_n`` [rad] (all positive).
    """
    alpha = float(_check_alpha(alpha))
    theta0 = float(_check_theta0(theta0, alpha))
    e = _check_e(e)
    n = V.integer("n", n, 0, MAX_IMPACTS)
    out = np.empty(n + 1)
    out[0] = theta0
    for k in range(n):
        out[k + 1] = _next_amplitudes(np.asarray(out[k]), alpha, e)
    return out


def peak_ratio_from_restitution(theta, alpha, e):
    """Displacement restitution ``theta_{k+1}/theta_k`` implied by Housner's ``e`` [-].

    Parameters
    ----------
    theta : float or array_like
        Amplitude before the impact [rad], ``0 < theta < alpha``.
    alpha : float
        Slenderness [rad].
    e : float
        Restitution (angular-velocity ratio).

    Returns
    -------
    float or numpy.ndarray
        Peak ratio (amplitude dependent: the displacement restitution is *not* ``e``).
    """
    a = float(_check_alpha(alpha))
    th = _check_theta0(theta, a)
    e = _check_e(e)
    return _scalar_or_array(_next_amplitudes(th, a, e) / th)


def restitution_from_peak_ratio(ratio, theta, alpha):
    """Housner ``e`` that produces a displacement restitution ``ratio`` at amplitude ``theta``.

    ``e^2 = (cos(alpha - r theta) - cos alpha) / (cos(alpha - theta) - cos alpha)``.

    Parameters
    ----------
    ratio : float or array_like
        ``theta_{k+1} / theta_k``, in ``[0, 1]``.
    theta : float or array_like
        Amplitude before the impact [rad].
    alpha : float
        Slenderness [rad].

    Returns
    -------
    float or numpy.ndarray
        ``e`` [-].
    """
    a = float(_check_alpha(alpha))
    th = _check_theta0(theta, a)
    r = _as_float_array("ratio", ratio)
    if np.any(r < 0.0) or np.any(r > 1.0):
        raise ValueError(f"ratio must satisfy 0 <= ratio <= 1; got {ratio!r}")
    t1 = r * th
    num = 2.0 * np.sin(a - 0.5 * t1) * np.sin(0.5 * t1)
    den = 2.0 * np.sin(a - 0.5 * th) * np.sin(0.5 * th)
    return _scalar_or_array(np.sqrt(num / den))


def _first_index(definition: str) -> int:
    if definition not in _DEFINITIONS:
        raise ValueError(f"definition must be one of {_DEFINITIONS}; got {definition!r}")
    return 0 if definition == "impact" else 1


def housner_half_cycle_durations(theta0, alpha, p, e, half_cycle, definition="impact"):
    """Half-cycle durations of a rigid block released from rest (exact Housner model).

    With amplitudes ``theta_k`` from :func:`housner_amplitudes` and the exact quarter period
    ``q(theta)`` (:func:`rocking_quarter_period`), half-cycle ``k`` lasts

    * ``definition="impact"`` (impact to impact): ``k = 0``: ``q(theta_0)`` (release to the
      first impact); ``k >= 1``: ``2 q(theta_k)`` (impact ``k`` to impact ``k + 1``);
    * ``definition="peak"`` (peak to peak): ``k >= 1``: ``q(theta_{k-1}) + q(theta_k)``
      (from the ``k-1``-th extreme, the release being extreme 0, to the ``k``-th).

    This is exactly what :func:`half_cycles` extracts from the simulated history, and the
    contract a ``predictor`` for :func:`fit_free_rocking` must follow.

    Parameters
    ----------
    theta0 : float
        Release angle [rad].
    alpha : float
        Slenderness [rad].
    p : float
        Frequency parameter [rad/s].
    e : float
        Restitution ``0 <= e <= 1``.
    half_cycle : int or array_like of int
        Half-cycle indices; an ``int`` ``n`` means the first ``n`` indices of the definition
        (``0..n-1`` for "impact", ``1..n`` for "peak").
    definition : {"impact", "peak"}
        Half-cycle definition, see :func:`half_cycles`.

    Returns
    -------
    numpy.ndarray
        Durations [s], one per requested index.
    """
    first = _first_index(definition)
    alpha = float(_check_alpha(alpha))
    p = float(_check_positive("p", p))
    theta0 = float(_check_theta0(theta0, alpha))
    e = _check_e(e)
    idx = _half_cycle_indices(half_cycle, first)
    if idx.size == 0:
        return np.zeros(0)
    amps = housner_amplitudes(theta0, alpha, e, int(idx.max()))
    q = _quarter_period_unit(amps, np.full_like(amps, alpha)) / p
    if definition == "impact":
        return np.where(idx == 0, q[0], 2.0 * q[idx])
    return q[idx - 1] + q[idx]


def _half_cycle_indices(half_cycle, first: int) -> np.ndarray:
    if np.ndim(half_cycle) == 0:
        n = int(half_cycle)
        if n < 0 or n != half_cycle:
            raise ValueError(f"half_cycle count must be a non-negative int; got {half_cycle!r}")
        return np.arange(first, first + n)
    idx = np.asarray(half_cycle)
    if idx.size and (not np.all(np.isfinite(idx.astype(float)))
                     or np.any(idx.astype(float) != np.round(idx.astype(float)))):
        raise ValueError(f"half_cycle indices must be integers; got {half_cycle!r}")
    idx = idx.astype(int)
    if np.any(idx < first):
        raise ValueError(f"half_cycle indices must be >= {first} for this definition; "
                         f"got {half_cycle!r}")
    return idx


# ----------------------------------------------------------------------------------------
# 2. half-cycle analysis
# ----------------------------------------------------------------------------------------
def _parabolic_vertex(t3: np.ndarray, y3: np.ndarray):
    """Vertex of the parabola through 3 points (clamped to their time span)."""
    t0, t1, t2 = t3
    y0, y1, y2 = y3
    d01 = (y1 - y0) / (t1 - t0)
    d12 = (y2 - y1) / (t2 - t1)
    a = (d12 - d01) / (t2 - t0)
    if a == 0.0 or not np.isfinite(a):
        return t1, y1
    b = d01 - a * (t0 + t1)
    tv = min(max(-b / (2.0 * a), t0), t2)
    yv = y0 + d01 * (tv - t0) + a * (tv - t0) * (tv - t1)
    return tv, yv


def _crossing_time(t: np.ndarray, theta: np.ndarray, k: int) -> float:
    """Time of the zero crossing of ``theta`` between samples ``k`` and ``k + 1``.

    Linear interpolation between the two bracketing samples is first-order accurate only
    when the slope is continuous; at an impact ``theta'`` jumps (``theta'+ = e theta'-``) and
    the plain interpolant is biased by O((1 - e) dt). The two one-sided linear
    extrapolations (samples ``k-1, k`` and ``k+1, k+2``) are each second-order accurate up to
    the crossing whether or not the slope jumps there, so their mean is used when both are
    consistent (moving toward / away from zero and inside the bracket); otherwise the plain
    interpolant.
    """
    tk, tk1 = t[k], t[k + 1]
    yk, yk1 = theta[k], theta[k + 1]
    if yk == 0.0:
        return float(tk)
    plain = tk + (tk1 - tk) * yk / (yk - yk1)
    est = []
    if k >= 1:
        y0 = theta[k - 1]
        if (y0 - yk) * yk > 0.0:     # approaching zero from the same side
            tl = tk + (tk - t[k - 1]) * yk / (y0 - yk)
            if tk <= tl <= tk1:
                est.append(tl)
    if k + 2 < t.size:
        y2 = theta[k + 2]
        if (y2 - yk1) * yk1 > 0.0:   # leaving zero on the other side
            tr = tk1 - (t[k + 2] - tk1) * yk1 / (y2 - yk1)
            if tk <= tr <= tk1:
                est.append(tr)
    return float(np.mean(est)) if est else float(plain)


def half_cycles(t, theta, lift_off=None, definition="impact", *, theta_y=None,
                t_switch=None, zero_tol=0.0):
    """Split a rotation history into half-cycles.

    Works on simulated or measured ``theta(t)`` (any body, any model). Two definitions:

    ``"impact"`` (default) -- impact to impact. Zero crossings of ``theta`` are located by
    linear interpolation: the mean of the two one-sided linear extrapolations from the
    samples on either side (exact to second order in the sampling interval even across the
    velocity jump of an impact; plain interpolation between the bracketing samples where
    the neighbours are inconsistent). Half-cycle ``k >= 1`` is
    the interval between crossing ``k`` and crossing ``k + 1``; half-cycle ``0`` is the leading
    segment from ``t[0]`` to the first crossing (for a release from rest at ``t[0]`` it is the
    quarter period ``q(theta0)``). The trailing segment after the last crossing is incomplete and
    not reported. For rigid rocking every zero crossing is an impact, so ``k >= 1`` lasts
    ``2 q(theta_k)``.

    ``"peak"`` -- peak to peak. In every lobe (the part of the record between two crossings)
    the extreme of ``|theta|`` is located by parabolic interpolation of the three samples
    around the largest ``|theta|`` sample. Extreme 0 is the peak of the leading lobe (the
    release at ``t[0]`` if ``|theta|`` decreases from the first sample -- a record that starts
    mid-swing is thus treated as released at ``t[0]``); half-cycle ``k >= 1`` runs from extreme
    ``k - 1`` to extreme ``k``. The last lobe contributes only if its extreme is a true local
    maximum inside the record.

    The default is ``"impact"`` because it is the definition that matches the measured data of
    Yu et al. (see :func:`load_yu2019`): their half-cycle 1, counted from the release, lasts
    0.478 s at ``theta0 = 8 deg``. The exact Housner model of the published block
    (``p = sqrt(M g R / I_0) = 4.652 rad/s``; ``e = 0.902`` from the rectangle formula or
    0.939 from the stated ``I_0``) gives 0.475 s / 0.518 s for impact 1 to impact 2 (our
    index 1), but only 0.304 s for release to first impact (our index 0) and 0.542 s /
    0.563 s for release peak to next peak ("peak" index 1). A joint fit of all the data is
    also better with "impact" (RMS 0.025 s) than with "peak" (0.038 s). Their half-cycle ``n``
    is therefore our ``"impact"`` index ``n``; the release quarter is not in their list.

    Parameters
    ----------
    t : array_like, shape (N,)
        Strictly increasing times [s].
    theta : array_like, shape (N,)
        Rotation [rad] (sign convention of physics.md §0).
    lift_off : array_like of bool, shape (N,), optional
        True where the body is lifted off (rocking on a corner). When given, a half-cycle is
        ``"rocking"`` iff any sample in ``[t_start, t_end]`` is lifted off.
    definition : {"impact", "peak"}
        See above.
    theta_y : float, optional
        Static uplift rotation [rad] (e.g. ``M g b / k_t`` of the switching model, physics.md
        §5.2). Used when ``lift_off`` is not given: a half-cycle is ``"rocking"`` iff the largest
        ``|theta|`` it reaches exceeds ``theta_y`` (for "peak" the larger of its two extremes).
    t_switch : float, optional
        Duration threshold [s], used when neither ``lift_off`` nor ``theta_y`` is given:
        ``"rocking"`` iff ``duration >= t_switch`` (rocking half-cycles shorten with amplitude,
        vibration half-cycles do not; Yu et al. observe the switch near 0.15 s).
        If none of the three is given every half-cycle is ``"rocking"`` (rigid model).
    zero_tol : float, optional
        Dead band [rad] against noise: ``theta`` must leave ``[-zero_tol, zero_tol]`` on the
        other side for a crossing to count; the crossing time is the last sign change before.

    Returns
    -------
    pandas.DataFrame
        One row per half-cycle with columns

        ========== ===== ======================================================================
        index      -     half-cycle number (0 = leading segment for "impact"; from 1 for "peak")
        t_start    s     start time
        t_end      s     end time
        duration   s     ``t_end - t_start``
        peak_angle rad   signed extreme of the half-cycle ("impact": extreme of the lobe;
                         "peak": the extreme at ``t_end``)
        t_peak     s     time of ``peak_angle``
        peak_ratio -     ``|peak_angle| / |previous peak_angle|`` (displacement restitution);
                         NaN if there is no previous extreme ("impact" row 0)
        kind       -     "rocking" or "vibration", see ``lift_off``, ``theta_y``, ``t_switch``
        ========== ===== ======================================================================
    """
    first = _first_index(definition)
    t = _as_float_array("t", t)
    theta = _as_float_array("theta", theta)
    if t.ndim != 1 or theta.shape != t.shape:
        raise ValueError(f"t and theta must be 1-D arrays of equal length; "
                         f"got shapes {t.shape} and {theta.shape}")
    if t.size < 3:
        raise ValueError("t and theta need at least 3 samples")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("t must be strictly increasing")
    if lift_off is not None:
        lift_off = np.asarray(lift_off)
        if lift_off.shape != t.shape:
            raise ValueError(f"lift_off must have the shape of t {t.shape}; got {lift_off.shape}")
        lift_off = lift_off.astype(bool)
    zero_tol = float(zero_tol)
    if not zero_tol >= 0.0:
        raise ValueError(f"zero_tol must be >= 0; got {zero_tol!r}")

    N = t.size
    sg = np.where(theta > zero_tol, 1, np.where(theta < -zero_tol, -1, 0))
    nz = np.flatnonzero(sg)
    # lobes: maximal runs of equal sign among the samples outside the dead band
    lobes = []          # (first sample, last sample, sign)
    crossings = []      # crossing time between lobe j-1 and lobe j
    if nz.size:
        start = nz[0]
        prev = nz[0]
        for i in nz[1:]:
            if sg[i] != sg[prev]:
                lobes.append((start, prev, sg[prev]))
                s_new = sg[i]
                # last raw sign change toward s_new between samples prev and i
                k = i - 1
                while k > prev and theta[k] * s_new > 0.0:
                    k -= 1
                crossings.append(_crossing_time(t, theta, k))
                start = i
            prev = i
        lobes.append((start, prev, sg[prev]))

    # extremes of every lobe; valid = a real extreme (interior local max of |theta|,
    # or the release at t[0] for the leading lobe)
    peaks = []
    for j, (i0, i1, _s) in enumerate(lobes):
        seg = np.abs(theta[i0:i1 + 1])
        im = i0 + int(np.argmax(seg))
        valid = True
        if im == 0:
            tp, yp = t[0], theta[0]
            valid = j == 0
        elif im == N - 1:
            tp, yp = t[im], theta[im]
            valid = False
        else:
            tp, yp = _parabolic_vertex(t[im - 1:im + 2], theta[im - 1:im + 2])
            if j == len(lobes) - 1 and abs(theta[im + 1]) > abs(theta[im]):
                valid = False
        peaks.append((tp, yp, valid))

    rows = []
    if definition == "impact":
        for j in range(len(crossings)):
            t_start = t[0] if j == 0 else crossings[j - 1]
            t_end = crossings[j]
            tp, yp, _ = peaks[j]
            ratio = abs(yp) / abs(peaks[j - 1][1]) if j >= 1 else np.nan
            rows.append((j, t_start, t_end, t_end - t_start, yp, tp, ratio, abs(yp)))
    else:
        for j in range(1, len(peaks)):
            tp0, yp0, v0 = peaks[j - 1]
            tp, yp, v = peaks[j]
            if not (v0 and v):
                break
            rows.append((j, tp0, tp, tp - tp0, yp, tp, abs(yp) / abs(yp0),
                         max(abs(yp), abs(yp0))))

    df = pd.DataFrame(rows, columns=_HALF_CYCLE_COLUMNS[:-1] + ["_amax"])
    if lift_off is not None:
        kinds = [
            "rocking" if np.any(lift_off[(t >= r.t_start) & (t <= r.t_end)]) else "vibration"
            for r in df.itertuples()]
    elif theta_y is not None:
        theta_y = float(_check_positive("theta_y", theta_y))
        kinds = ["rocking" if a > theta_y else "vibration" for a in df["_amax"]]
    elif t_switch is not None:
        t_switch = float(_check_positive("t_switch", t_switch))
        kinds = ["rocking" if d >= t_switch else "vibration" for d in df["duration"]]
    else:
        kinds = ["rocking"] * len(df)
    df = df.drop(columns="_amax")
    df["kind"] = pd.Series(kinds, dtype=object, index=df.index)
    df["index"] = df["index"].astype(int)
    if first == 1 and len(df):
        assert df["index"].iloc[0] == 1
    return df[_HALF_CYCLE_COLUMNS]


# ----------------------------------------------------------------------------------------
# 3. accelerometer
# ----------------------------------------------------------------------------------------
def accelerometer(t, theta, dtheta, ddtheta, point, a_g=None, g=G_STANDARD, *,
                  half_width=0.0, pivot_sign=None):
    """Specific force read by an accelerometer fixed to a rocking body.

    The sensor is at body coordinates ``point = (x_p, y_p)`` measured from the centre of the
    base: body ``x`` along the base (toward the right corner when upright), body ``y`` along
    the body axis, upward. The body rotates rigidly by ``theta`` (clockwise positive, physics.md
    §0) about its active pivot, the bottom corner ``(s * half_width, 0)`` (``s = pivot_sign``;
    ``s = 0`` means rotation about the base centre, e.g. the contact phase of the switching
    model). With ``rho = (x_p - s b, y_p)`` the pivot-to-sensor vector in the body frame
    (``b = half_width``) the specific force ``f = a - g_vec`` (what an accelerometer measures;
    at rest it reads ``+g`` along body ``y``) is, in body components,

    ``f = theta'' (rho_y, -rho_x) - theta'^2 (rho_x, rho_y) + g (-sin theta, cos theta)
    + a_g (cos theta, sin theta)``.

    Tangential and normal components refer to the pivot-to-sensor line:
    ``t_hat = (rho_y, -rho_x)/r`` (direction of motion for ``theta' > 0``),
    ``n_hat = -rho/r`` (toward the pivot, so a pure circular motion gives ``+r theta'^2``).

    Notes
    -----
    *Is the tangential reading constant during free rocking?* With no ground motion and
    Housner's equation ``I_0 theta'' = M g X_G`` (``X_G`` horizontal offset pivot -> centre
    of mass), and ``rho_G = (-s b, h)`` the body vector pivot -> centre of mass, the
    tangential reading is exactly
    ``f_t = g (cos theta, sin theta) . (r M rho_G / I_0 - rho / r)``, ``r = |rho|``,
    a fixed body vector dotted with a rotating unit vector. It is constant over a half-cycle
    only if that vector vanishes, i.e. at the **centre of percussion** about the pivot
    (``rho = (I_0/(M R^2)) rho_G``, distance ``I_0/(M R)`` along the pivot -> CM line), where it
    reads exactly 0; everywhere else it varies with ``theta``. (For a uniform rectangle the
    centre of percussion is ``(-s b/3, 4h/3)``, a different body point for each pivot.)

    A related exact identity: a sensor on the vertical edge above the pivot
    (``x_p = s b``) at height ``y_p = I_0/(M h)`` reads along body ``x``
    ``f_x = -s g tan(alpha) cos(theta)``, i.e. the quasi-static uplift acceleration
    ``g tan alpha`` to within ``1 - cos(theta)``. For Yu et al.'s block ``g tan alpha = 0.264 g``
    (``b/h = 0.263``) -- the "about 0.26 g" -- but with their stated ``I_0 = 0.3268 kg m^2`` that
    height is 0.469 m, above the 0.41 m top (for a uniform block it would be 0.292 m). A
    sensor at the top centre (``point = (0, 2h)``) reads along body ``x`` between 0.225 g
    (at impact) and 0.246 g (at the release) in the first half-cycle from 8 deg, so no natural
    sensor location of their block gives exactly 0.26 g; 0.26 g is most plausibly
    ``g tan alpha``, the uplift threshold.

    Parameters
    ----------
    t : array_like, shape (N,)
        Times [s] (only checked for shape; kept for a tidy output table).
    theta, dtheta, ddtheta : array_like, shape (N,)
        Rotation [rad], angular velocity [rad/s], angular acceleration [rad/s^2].
    point : tuple of float
        Sensor position ``(x_p, y_p)`` [m] in the body frame from the base centre.
    a_g : array_like, shape (N,), optional
        Horizontal ground acceleration [m/s^2] (default 0).
    g : float, optional
        Gravity [m/s^2].
    half_width : float, optional
        Half base width ``b`` [m]; 0 places the pivot at the base centre.
    pivot_sign : array_like of {-1, 0, 1}, shape (N,), optional
        Active pivot; default ``sign(theta)`` (0 where ``theta == 0``).

    Returns
    -------
    pandas.DataFrame
        Columns ``t`` [s]; ``a_x``, ``a_y`` [m/s^2] body-frame components of the specific
        force; ``a_tangential``, ``a_normal`` [m/s^2] components along ``t_hat`` and ``n_hat``
        (NaN if the sensor is at the pivot).
    """
    t = _as_float_array("t", t)
    th = _as_float_array("theta", theta)
    w = _as_float_array("dtheta", dtheta)
    wd = _as_float_array("ddtheta", ddtheta)
    for name, arr in (("theta", th), ("dtheta", w), ("ddtheta", wd)):
        if arr.shape != t.shape:
            raise ValueError(f"{name} must have the shape of t {t.shape}; got {arr.shape}")
    ag = np.zeros_like(t) if a_g is None else _as_float_array("a_g", a_g)
    if ag.shape != t.shape:
        raise ValueError(f"a_g must have the shape of t {t.shape}; got {ag.shape}")
    g = float(_check_positive("g", g))
    b = float(_as_float_array("half_width", half_width))
    if b < 0.0:
        raise ValueError(f"half_width must be >= 0; got {half_width!r}")
    xp, yp = (float(v) for v in _as_float_array("point", point).reshape(2))
    if pivot_sign is None:
        s = np.sign(th)
    else:
        s = _as_float_array("pivot_sign", pivot_sign)
        if s.shape != t.shape or np.any(~np.isin(s, (-1.0, 0.0, 1.0))):
            raise ValueError("pivot_sign must be an array of -1, 0, +1 with the shape of t")
    rx = xp - s * b
    ry = np.full_like(t, yp)
    c, sn = np.cos(th), np.sin(th)
    fx = wd * ry - w ** 2 * rx - g * sn + ag * c
    fy = -wd * rx - w ** 2 * ry + g * c + ag * sn
    r = np.hypot(rx, ry)
    with np.errstate(invalid="ignore", divide="ignore"):
        ft = np.where(r > 0.0, (fx * ry - fy * rx) / r, np.nan)
        fn = np.where(r > 0.0, -(fx * rx + fy * ry) / r, np.nan)
    return pd.DataFrame({"t": t, "a_x": fx, "a_y": fy, "a_tangential": ft, "a_normal": fn})


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
#: that provide them register here (fastrock.foundation: "two-spring", "switching"), so that this
#: module does not import them.
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
    first = _first_index(definition)
    alpha = float(_check_alpha(alpha))
    durs = _as_groups(half_cycle_durations, "half_cycle_durations")
    t0s = np.atleast_1d(_as_float_array("theta0", theta0)).astype(float)
    if len(durs) != t0s.size:
        raise ValueError(f"got {len(durs)} duration group(s) but {t0s.size} theta0 value(s)")
    _check_theta0(t0s, alpha)
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
            idxs.append(_half_cycle_indices(h, first))
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
    for d in _DEFINITIONS:
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


# ----------------------------------------------------------------------------------------
# CSV input
# ----------------------------------------------------------------------------------------
_NUMERIC_COLUMNS = ("half_cycle", "duration", "peak", "peak_deg", "theta0_deg", "alpha_deg")


def read_half_cycles_csv(path) -> pd.DataFrame:
    """Read measured half-cycles from a CSV file.

    Accepted columns (header required, ``#`` starts a comment line):

    ============= ====== ====================================================================
    duration      s      required, > 0
    half_cycle    -      optional integer index >= 0 (definition as in :func:`half_cycles`);
                         unique within a ``theta0_deg`` group
    peak          rad    optional peak angle of the half-cycle (sign ignored by the fit)
    peak_deg      deg    optional, alternative to ``peak`` (converted to ``peak`` in rad)
    theta0_deg    deg    optional release angle; several values = several release tests
    alpha_deg     deg    optional slenderness (must be a single value)
    definition    -      optional, "impact" or "peak" (must be a single value)
    ============= ====== ====================================================================

    Other columns are kept unchanged. Empty cells are allowed only in ``peak``/``peak_deg``.
    The half-cycle definition of the data may also be stated by a comment line
    ``# definition: impact`` (or ``peak``); it is returned in ``df.attrs["definition"]``
    (None when the file does not say) and used by :func:`fit_from_csv`.

    Parameters
    ----------
    path : str or os.PathLike
        CSV file.

    Returns
    -------
    pandas.DataFrame
        The validated table, numeric columns as float (``half_cycle`` as int), sorted by
        ``theta0_deg`` (if present) and ``half_cycle`` (if present).

    Raises
    ------
    ValueError
        Naming the file, the column and the row (1-based data row; line = row + 1 counting
        the header) for a missing ``duration`` column, non-numeric, non-finite or
        negative/zero values, non-integer or duplicate ``half_cycle``, or an unreadable file.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: malformed CSV (not text: {exc})") from exc
    stated = set()
    for line in text.splitlines():
        m = re.match(r"\s*#\s*definition\s*[:=]\s*(\S+)", line, re.IGNORECASE)
        if m:
            stated.add(m.group(1).strip().strip("'\"").lower())
    # ragged rows: pandas would silently turn extra fields into an index
    rows = [r for r in csv.reader(line for line in text.splitlines()
                                  if line.strip() and not line.lstrip().startswith("#"))]
    if rows:
        for i, r in enumerate(rows[1:], start=1):
            if len(r) != len(rows[0]):
                raise ValueError(f"{path}: malformed CSV: row {i} has {len(r)} fields, the "
                                 f"header has {len(rows[0])}")
    try:
        raw = pd.read_csv(io.StringIO(text), dtype=str, comment="#", skipinitialspace=True,
                          keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise ValueError(f"{path}: malformed CSV ({exc})") from exc
    raw.columns = [str(c).strip() for c in raw.columns]
    if "duration" not in raw.columns:
        raise ValueError(f"{path}: missing required column 'duration' "
                         f"(columns found: {list(raw.columns)})")
    if len(raw) == 0:
        raise ValueError(f"{path}: no data rows")
    if "peak" in raw.columns and "peak_deg" in raw.columns:
        raise ValueError(f"{path}: give either column 'peak' (rad) or 'peak_deg', not both")
    df = raw.copy()
    for col in _NUMERIC_COLUMNS:
        if col not in raw.columns:
            continue
        s = raw[col].astype(str).str.strip()
        empty = s == ""
        vals = pd.to_numeric(s.where(~empty, None), errors="coerce").astype(float)
        bad = (vals.isna() & ~empty) | np.isinf(vals)
        if col not in ("peak", "peak_deg"):
            bad |= empty
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            raise ValueError(f"{path}: column '{col}', row {i + 1}: value {raw[col].iloc[i]!r} "
                             f"is not a finite number")
        if col == "duration" and (vals <= 0).any():
            i = int(np.flatnonzero((vals <= 0).to_numpy())[0])
            raise ValueError(f"{path}: column 'duration', row {i + 1}: duration must be > 0 s; "
                             f"got {vals.iloc[i]!r}")
        if col == "half_cycle":
            nonint = (vals != np.round(vals)) | (vals < 0)
            if nonint.any():
                i = int(np.flatnonzero(nonint.to_numpy())[0])
                raise ValueError(f"{path}: column 'half_cycle', row {i + 1}: must be an integer "
                                 f">= 0; got {raw[col].iloc[i]!r}")
        if col in ("theta0_deg", "alpha_deg") and (vals <= 0).any():
            i = int(np.flatnonzero((vals <= 0).to_numpy())[0])
            raise ValueError(f"{path}: column '{col}', row {i + 1}: must be > 0; "
                             f"got {vals.iloc[i]!r}")
        df[col] = vals
    if "half_cycle" in df.columns:
        df["half_cycle"] = df["half_cycle"].astype(int)
        keys = ["theta0_deg", "half_cycle"] if "theta0_deg" in df.columns else ["half_cycle"]
        dup = df.duplicated(keys)
        if dup.any():
            i = int(np.flatnonzero(dup.to_numpy())[0])
            raise ValueError(f"{path}: column 'half_cycle', row {i + 1}: duplicate half-cycle "
                             f"{df['half_cycle'].iloc[i]} within its group")
    if "alpha_deg" in df.columns and df["alpha_deg"].nunique() > 1:
        raise ValueError(f"{path}: column 'alpha_deg' must hold a single value; got "
                         f"{sorted(df['alpha_deg'].unique())}")
    if "peak_deg" in df.columns:
        df["peak"] = np.radians(df["peak_deg"])
    sort = [c for c in ("theta0_deg", "half_cycle") if c in df.columns]
    if sort:
        df = df.sort_values(sort, kind="stable").reset_index(drop=True)
    if "definition" in df.columns:
        stated |= set(df.pop("definition").astype(str).str.strip().str.lower())
    bad = stated - set(_DEFINITIONS)
    if bad or len(stated) > 1:
        raise ValueError(f"{path}: definition must be one of {_DEFINITIONS} and a single value, "
                         f"got {sorted(stated)}")
    df.attrs["definition"] = stated.pop() if stated else None
    return df


def _fit_table(df: pd.DataFrame, theta0=None, alpha=None, model="housner", source="data",
               **options) -> FreeRockingFit:
    """Fit a table as returned by :func:`read_half_cycles_csv` (groups by ``theta0_deg``)."""
    if alpha is None:
        if "alpha_deg" not in df.columns:
            raise ValueError(f"{source}: alpha not given and no 'alpha_deg' column")
        alpha = math.radians(float(df["alpha_deg"].iloc[0]))
    if "theta0_deg" in df.columns:
        if theta0 is not None:
            t0deg = math.degrees(float(theta0))
            sel = np.isclose(df["theta0_deg"].to_numpy(), t0deg, rtol=0, atol=1e-6)
            if not sel.any():
                raise ValueError(f"{source}: no group with theta0_deg = {t0deg:g}; available: "
                                 f"{sorted(df['theta0_deg'].unique())}")
            df = df[sel]
        groups = [g for _, g in df.groupby("theta0_deg", sort=True)]
        t0s = [math.radians(float(g["theta0_deg"].iloc[0])) for g in groups]
    else:
        if theta0 is None:
            raise ValueError(f"{source}: theta0 not given and no 'theta0_deg' column")
        groups = [df]
        t0s = [float(theta0)]
    stated = df.attrs.get("definition")
    given = options.pop("definition", None)
    if given is not None and stated is not None and given != stated:
        import warnings
        warnings.warn(f"{source}: the file states half-cycles '{stated}' to '{stated}'; the given "
                      f"definition {given!r} overrides it", DefinitionWarning, stacklevel=3)
    options["definition"] = given or stated
    durs = [g["duration"].to_numpy(float) for g in groups]
    hcs = ([g["half_cycle"].to_numpy(int) for g in groups]
           if "half_cycle" in df.columns else None)
    pks = [g["peak"].to_numpy(float) for g in groups] if "peak" in df.columns else None
    return fit_free_rocking(durs, t0s, alpha, peaks=pks, model=model, half_cycle=hcs,
                            **options)


def fit_from_csv(path, theta0=None, alpha=None, model="housner", **options) -> FreeRockingFit:
    """Read a half-cycle CSV (:func:`read_half_cycles_csv`) and fit it.

    Parameters
    ----------
    path : str or os.PathLike
        CSV file.
    theta0 : float, optional
        Release angle [rad]. If the file has a ``theta0_deg`` column, selects that group
        (default: joint fit of all groups with shared parameters); otherwise required.
    alpha : float, optional
        Slenderness [rad]; default from the ``alpha_deg`` column.
    model : str
        See :func:`fit_free_rocking`.
    **options
        Passed to :func:`fit_free_rocking` (``definition``, ``min_duration``, ``predictor``...).

    Returns
    -------
    FreeRockingFit
    """
    df = read_half_cycles_csv(path)
    return _fit_table(df, theta0=theta0, alpha=alpha, model=model, source=str(path),
                      **options)


# ----------------------------------------------------------------------------------------
# 5. Yu et al. data
# ----------------------------------------------------------------------------------------
#: Block of Yu et al. as stated (SI units): half-width ``b`` and half-height ``h`` [m],
#: corner-to-CM distance ``R`` [m], slenderness [deg], mass [kg], inertia about a corner [kg m^2].
#: Note: ``I0 = 0.3268`` exceeds ``2 M R^2 = 0.306`` (the largest value any body inside the
#: ``2b x 2h`` rectangle can have) and the uniform value ``4/3 M R^2 = 0.204``; the rig
#: presumably carries attachments. ``p`` below uses the stated ``I0``.
YU2019_BLOCK = {
    "half_width": 0.054,
    "half_height": 0.205,
    "R": 0.212,
    "alpha_deg": 14.8,
    "mass": 3.40,
    "I0": 0.3268,
    "g": 9.81,  # the paper's g: its published p = 4.6516 rad/s uses it
}
YU2019_BLOCK["p"] = math.sqrt(YU2019_BLOCK["mass"] * YU2019_BLOCK["g"] * YU2019_BLOCK["R"]
                              / YU2019_BLOCK["I0"])
YU2019_BLOCK["e_housner"] = 1.0 - (YU2019_BLOCK["mass"] * YU2019_BLOCK["R"] ** 2
                                   / YU2019_BLOCK["I0"]) * (
    1.0 - math.cos(2.0 * math.radians(YU2019_BLOCK["alpha_deg"])))
YU2019_BLOCK["e_housner_rectangle"] = 1.0 - 1.5 * math.sin(
    math.radians(YU2019_BLOCK["alpha_deg"])) ** 2

_DATA_DIR = Path(__file__).resolve().parent / "data"


def load_yu2019() -> pd.DataFrame:
    """Measured half-cycle durations of Yu et al. (block on light felt, free release).

    Half-cycles 1-20 after releases from ``theta0 = 8, 10, 12.8 deg``. Their half-cycle ``n``
    (counted from the release) corresponds to our ``"impact"`` index ``n`` (impact ``n`` to
    impact ``n + 1``; see :func:`half_cycles` for the evidence); the release-to-first-impact
    segment (index 0) is not in the data.

    Notes
    -----
    Consecutive values come in nearly equal pairs (0.478/0.471, 0.386/0.380, ...): the
    duration drops by 15-20 % every *second* half-cycle and by only 1-3 % in between. A
    symmetric block -- rigid or on any symmetric foundation -- loses the same fraction at
    every impact, so its durations decay steadily under either definition ("impact" or
    "peak"); the pairing therefore indicates that dissipation alternates between the two
    corners (asymmetric contact on the felt), which none of the symmetric models reproduces.
    A symmetric fit averages over each pair (residuals alternate in sign), and its ``e`` is
    an effective per-impact value.

    The rigid model also over-predicts how strongly the first durations grow with ``theta0``
    (measured 0.478 / 0.519 / 0.579 s at 8 / 10 / 12.8 deg, exact Housner with the published
    ``p`` and ``e = 0.939``: 0.518 / 0.609 / 0.716 s), presumably the felt foundation. Joint
    Housner fit (shared ``p``, ``e``, ``alpha`` fixed at 14.8 deg): all 60 durations
    ``p = 4.72 +/- 0.11 rad/s``, ``e = 0.928 +/- 0.003``, RMS 0.025 s; rocking part only
    (durations > 0.15 s) ``p = 5.04 +/- 0.14 rad/s``, ``e = 0.939 +/- 0.003``, RMS 0.024 s.

    Returns
    -------
    pandas.DataFrame
        Columns ``theta0_deg`` [deg], ``half_cycle`` [-], ``duration`` [s];
        ``df.attrs`` holds :data:`YU2019_BLOCK` (with ``p`` [rad/s] = 4.652 from the stated
        ``I0``, and Housner's ``e``), ``alpha`` [rad] and ``definition = "impact"``.
    """
    df = read_half_cycles_csv(_DATA_DIR / "yu2019_halfcycles.csv")
    df.attrs.update(YU2019_BLOCK)
    df.attrs["alpha"] = math.radians(YU2019_BLOCK["alpha_deg"])
    df.attrs["definition"] = "impact"
    return df


# ----------------------------------------------------------------------------------------
# 6. plots
# ----------------------------------------------------------------------------------------
def _new_axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt
        _, ax = plt.subplots()
    return ax


def plot_period_vs_angle(alpha, p, omega=None, ax=None, n=200):
    """Period against initial angle (cf. Yu et al., Fig. 4).

    Draws the exact (:func:`rocking_period_exact`) and linearised
    (:func:`rocking_period_linear`) rocking periods ``T_C`` for ``0 < theta0 < alpha`` and,
    if ``omega`` is given, the linear vibration period ``T_L = 2 pi/omega`` (constant) and the
    pendulum period ``T_NL`` (:func:`pendulum_period`).

    Parameters
    ----------
    alpha : float
        Slenderness [rad].
    p : float
        Frequency parameter [rad/s].
    omega : float, optional
        Vibration circular frequency [rad/s].
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    n : int
        Number of angles.

    Returns
    -------
    matplotlib.axes.Axes
        Axes with x = initial angle [deg], y = period [s].
    """
    alpha = float(_check_alpha(alpha))
    p = float(_check_positive("p", p))
    ax = _new_axes(ax)
    th = np.linspace(0.005, 0.98, int(n)) * alpha
    ax.plot(np.degrees(th), rocking_period_exact(th, alpha, p), "-",
            label=r"rocking $T_C$ (exact)")
    ax.plot(np.degrees(th), rocking_period_linear(th, alpha, p), "--",
            label=r"rocking $T_C$ (linearised)")
    if omega is not None:
        omega = float(_check_positive("omega", omega))
        ax.axhline(vibration_period(omega), color="k", ls=":", label=r"vibration $T_L$")
        ax.plot(np.degrees(th), pendulum_period(th, omega), "-.",
                label=r"pendulum $T_{NL}$")
    ax.set_xlabel(r"initial angle $\theta_0$ [deg]")
    ax.set_ylabel("period [s]")
    ax.legend()
    return ax


def plot_fit(fit: FreeRockingFit, measured=None, published=None, ax=None):
    """Measured, published-parameter and fitted half-cycle durations in one figure.

    Parameters
    ----------
    fit : FreeRockingFit
        Result of :func:`fit_free_rocking`.
    measured : array_like, optional
        Measured durations [s] in the order of ``fit.half_cycle`` (default ``fit.measured``).
    published : dict, optional
        ``{"p": ..., "e": ...}`` for a Housner prediction with published parameters (e.g.
        ``{"p": YU2019_BLOCK["p"], "e": YU2019_BLOCK["e_housner"]}``), drawn dashed.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes
        x = half-cycle index, y = duration [s]; one colour per release angle.
    """
    ax = _new_axes(ax)
    meas = fit.measured if measured is None else np.asarray(measured, dtype=float)
    if meas.shape != fit.measured.shape:
        raise ValueError(f"measured must have {fit.measured.size} entries")
    for gi, t0 in enumerate(fit.theta0):
        sel = fit.group == gi
        order = np.argsort(fit.half_cycle[sel])
        hc = fit.half_cycle[sel][order]
        lab = rf"$\theta_0$ = {np.degrees(t0):.3g}$^\circ$"
        line = ax.plot(hc, meas[sel][order], "o", ms=4, label=f"measured, {lab}")[0]
        c = line.get_color()
        ax.plot(hc, fit.predicted[sel][order], "-", color=c,
                label=f"fit ({fit.model}: p={fit.p:.3g}, e={fit.e:.3g})" if gi == 0 else None)
        if published is not None:
            pub = housner_half_cycle_durations(t0, fit.alpha, published["p"], published["e"],
                                               hc, fit.definition)
            ax.plot(hc, pub, "--", color=c,
                    label=(f"published (p={published['p']:.3g}, e={published['e']:.3g})"
                           if gi == 0 else None))
    ax.set_xlabel(f"half-cycle ({fit.definition} definition)")
    ax.set_ylabel("duration [s]")
    ax.legend(fontsize="small")
    return ax


# ----------------------------------------------------------------------------------------
# 7. CLI
# ----------------------------------------------------------------------------------------
def add_fit_subcommand(subparsers):
    """Register ``fit`` on an :mod:`argparse` sub-parsers object.

    ``fastrock fit FILE [--theta0-deg X] [--alpha-deg Y] [--model housner]
    [--definition impact|peak] [--min-duration S] [--png out.png] [--csv out.csv] [--parquet out.parquet]``

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From ``parser.add_subparsers()``.

    Returns
    -------
    argparse.ArgumentParser
        The ``fit`` parser (its default ``func`` is :func:`run_fit_command`).
    """
    p = subparsers.add_parser(
        "fit", help="fit p and e of free rocking to measured half-cycle durations",
        description="Fit the frequency parameter p and restitution e to half-cycle durations "
                    "read from FILE (columns: duration [s] required; half_cycle, peak or "
                    "peak_deg, theta0_deg, alpha_deg optional). Several theta0_deg groups are "
                    "fitted jointly with shared (p, e) unless --theta0-deg selects one.")
    p.add_argument("file", metavar="FILE", help="half-cycle CSV file")
    th = p.add_mutually_exclusive_group()
    th.add_argument("--theta0", type=float, default=None,
                    help="release angle [rad]; selects a group if FILE has theta0_deg (default: "
                         "the file's theta0_deg column, every group)")
    th.add_argument("--theta0-deg", type=float, default=None, help="the same in degrees [deg] (default: none)")
    al = p.add_mutually_exclusive_group()
    al.add_argument("--alpha", type=float, default=None,
                    help="slenderness [rad] (default: the file's alpha_deg column)")
    al.add_argument("--alpha-deg", type=float, default=None, help="the same in degrees [deg] (default: none)")
    p.add_argument("--model", default="housner", help="model (default: housner)")
    p.add_argument("--definition", choices=_DEFINITIONS, default=None,
                   help="half-cycle definition of the data: impact to impact or peak to peak "
                        "(default: what FILE states, else the better-fitting one, with a warning)")
    p.add_argument("--min-duration", type=float, default=None,
                   help="exclude measured durations below this [s] from the fit (default: none)")
    p.add_argument("--param", metavar="NAME=VALUE", action="append", default=[],
                   help="starting value of a fitted parameter, repeatable; the foundation "
                        "models need them, e.g. --model two-spring --param p=4.7 "
                        "--param omega=40 --param zeta=0.05 (default: the model's own starts)")
    from .cli import add_output_options
    add_output_options(p, figure="a figure of the fit", table="the fit table")
    p.add_argument("--plot", dest="png", metavar="FILE", help=argparse.SUPPRESS)  # the old name of --png
    p.set_defaults(func=run_fit_command)
    return p


def _parse_params(items):
    """``["p=4.7", "omega=40"]`` -> ``{"p": 4.7, "omega": 40.0}``; errors name the item."""
    out = {}
    for it in items:
        name, sep, value = it.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--param must look like NAME=VALUE, got {it!r}")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"--param {name.strip()}: {value!r} is not a number") from None
        if not math.isfinite(out[name.strip()]):
            raise ValueError(f"--param {name.strip()} must be finite, got {value!r}")
    return out


def run_fit_command(args) -> int:
    """Run ``fastrock fit`` with parsed ``args`` (see :func:`add_fit_subcommand`).

    Prints ``p`` and ``e`` with standard errors, the RMS residual (overall and per
    ``theta0`` group) and optionally writes a plot and the fit table.

    Returns
    -------
    int
        0 on success, 2 on invalid input (message on stderr).
    """
    try:
        theta0 = args.theta0 if args.theta0_deg is None else math.radians(args.theta0_deg)
        alpha = args.alpha if args.alpha_deg is None else math.radians(args.alpha_deg)
        extra = {}
        params0 = _parse_params(getattr(args, "param", []) or [])
        if params0:
            extra["params0"] = params0
        fit = fit_from_csv(args.file, theta0=theta0, alpha=alpha, model=args.model,
                           definition=args.definition, min_duration=args.min_duration, **extra)
    except (ValueError, NotImplementedError, FileNotFoundError) as exc:
        print(f"fastrock fit: error: {exc}", file=sys.stderr)
        return 2
    print(fit.summary())
    from .cli import write_table, wrote
    wrote(write_table(fit.to_frame(), args))
    if args.png:
        from matplotlib.figure import Figure
        fig = Figure(figsize=(7, 4.5))
        ax = fig.add_subplot()
        plot_fit(fit, ax=ax)
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        wrote([args.png])
    return 0
