"""Periods of free rocking, of a linear oscillator and of a pendulum.
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

from fastrock.analyses.freerocking.checks import (as_float_array, check_alpha, check_positive,
    check_theta0, scalar_or_array)


# Gauss-Legendre rule for the composite quadrature of the exact quarter period: the
# integrand (see quarter_period_unit) is analytic with a variation scale of O(1) in u,
# so 24 nodes on panels of width <= 1 give ~1e-14 relative accuracy.
_GL_NODES, _GL_WEIGHTS = leggauss(24)

_PANEL_WIDTH = 1.0


# ----------------------------------------------------------------------------------------
# 1. periods
# ----------------------------------------------------------------------------------------
def _acosh1p(w):
    """acosh(1 + w) for w >= 0 without cancellation for small w."""
    w = np.asarray(w, dtype=float)
    return np.log1p(w + np.sqrt(w * (w + 2.0)))


def rocking_period_linear(theta0, alpha, p):
    """Full free-rocking period of the linearised rigid block (Housner; Yu et al.'s ``T_C``).

    ``T = (4/p) acosh(1 / (1 - theta0/alpha))`` (docs: theory/closed_forms): four times the time the
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
    a = check_alpha(alpha)
    pp = check_positive("p", p)
    t0 = check_theta0(theta0, a)
    t0, a, pp = np.broadcast_arrays(t0, a, pp)
    r = t0 / a
    # 1/(1-r) - 1 = r/(1-r): avoids cancellation for small theta0.
    return scalar_or_array(4.0 * _acosh1p(r / (1.0 - r)) / pp)


def quarter_period_unit(theta0: np.ndarray, alpha: np.ndarray) -> np.ndarray:
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
    (docs: theory/closed_forms). The integrable endpoint singularity is removed exactly by the change of
    variables ``sin((alpha-theta)/2) = sin((alpha-theta0)/2) cosh(u)`` and the remaining smooth
    integral is evaluated by composite Gauss-Legendre quadrature
    (:func:`numpy.polynomial.legendre.leggauss`, 24 nodes per unit panel in ``u``); relative
    accuracy ~1e-13 for ``1e-8 < theta0/alpha < 1 - 1e-8``. Check value (docs: theory/closed_forms):
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
    a = check_alpha(alpha)
    pp = check_positive("p", p)
    t0 = check_theta0(theta0, a)
    t0, a, pp = np.broadcast_arrays(t0, a, pp)
    return scalar_or_array(4.0 * quarter_period_unit(t0, a) / pp)


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
    w = check_positive("omega", omega)
    return scalar_or_array(2.0 * np.pi / w)


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
    k = as_float_array("k", k)
    if np.any(k < 0.0) or np.any(k >= 1.0):
        raise ValueError(f"k must satisfy 0 <= k < 1; got {k!r}")
    from scipy import special
    return scalar_or_array(special.ellipkm1((1.0 - k) * (1.0 + k)))


def _check_pendulum(theta0, omega):
    w = check_positive("omega", omega)
    t0 = as_float_array("theta0", theta0)
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
    return scalar_or_array(4.0 * ellipk_agm(np.sin(0.5 * t0)) / w)


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
    return scalar_or_array(
        (1.0 + t0 ** 2 / 16.0 + 11.0 * t0 ** 4 / 3072.0) * 2.0 * np.pi / w)


