"""Housner free rocking with impacts: amplitudes, peak ratios, half-cycle durations.
"""
from __future__ import annotations

import numpy as np

from fastrock import _validate as V
from fastrock.analyses.freerocking.checks import (as_float_array, check_alpha, check_e,
    check_positive, check_theta0, scalar_or_array)
from fastrock.analyses.freerocking.periods import quarter_period_unit


#: The half-cycle definitions: "impact" (impact to impact) and "peak" (peak to peak).
HALF_CYCLE_DEFINITIONS = ("impact", "peak")


# ----------------------------------------------------------------------------------------
# Housner free rocking with impacts
# ----------------------------------------------------------------------------------------
def _next_amplitudes(theta: np.ndarray, alpha: float, e: float) -> np.ndarray:
    """Amplitude after one impact from the exact energy relation (docs: theory/closed_forms)."""
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
    (exact energy balance, docs: theory/closed_forms), starting at ``theta_0 = theta0``.

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
    alpha = float(check_alpha(alpha))
    theta0 = float(check_theta0(theta0, alpha))
    e = check_e(e)
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
    a = float(check_alpha(alpha))
    th = check_theta0(theta, a)
    e = check_e(e)
    return scalar_or_array(_next_amplitudes(th, a, e) / th)


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
    a = float(check_alpha(alpha))
    th = check_theta0(theta, a)
    r = as_float_array("ratio", ratio)
    if np.any(r < 0.0) or np.any(r > 1.0):
        raise ValueError(f"ratio must satisfy 0 <= ratio <= 1; got {ratio!r}")
    t1 = r * th
    num = 2.0 * np.sin(a - 0.5 * t1) * np.sin(0.5 * t1)
    den = 2.0 * np.sin(a - 0.5 * th) * np.sin(0.5 * th)
    return scalar_or_array(np.sqrt(num / den))


def first_index(definition: str) -> int:
    """Index of the first half-cycle of a definition: 0 for "impact", 1 for "peak"."""
    if definition not in HALF_CYCLE_DEFINITIONS:
        raise ValueError(f"definition must be one of {HALF_CYCLE_DEFINITIONS}; got {definition!r}")
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
    first = first_index(definition)
    alpha = float(check_alpha(alpha))
    p = float(check_positive("p", p))
    theta0 = float(check_theta0(theta0, alpha))
    e = check_e(e)
    idx = half_cycle_indices(half_cycle, first)
    if idx.size == 0:
        return np.zeros(0)
    amps = housner_amplitudes(theta0, alpha, e, int(idx.max()))
    q = quarter_period_unit(amps, np.full_like(amps, alpha)) / p
    if definition == "impact":
        return np.where(idx == 0, q[0], 2.0 * q[idx])
    return q[idx - 1] + q[idx]


def half_cycle_indices(half_cycle, first: int) -> np.ndarray:
    """Half-cycle indices from a count (``first`` onwards) or an array of non-negative ints."""
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


