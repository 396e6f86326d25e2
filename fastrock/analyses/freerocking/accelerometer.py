"""The reading of a body-mounted accelerometer.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from fastrock.constants import G_STANDARD
from fastrock.analyses.freerocking.checks import as_float_array, check_positive


# ----------------------------------------------------------------------------------------
# 3. accelerometer
# ----------------------------------------------------------------------------------------
def accelerometer(t, theta, dtheta, ddtheta, point, a_g=None, g=G_STANDARD, *,
                  half_width=0.0, pivot_sign=None):
    """Specific force read by an accelerometer fixed to a rocking body.

    The sensor is at body coordinates ``point = (x_p, y_p)`` measured from the centre of the
    base: body ``x`` along the base (toward the right corner when upright), body ``y`` along
    the body axis, upward. The body rotates rigidly by ``theta`` (clockwise positive, docs:
    theory, conventions) about its active pivot, the bottom corner ``(s * half_width, 0)`` (``s = pivot_sign``;
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
    t = as_float_array("t", t)
    th = as_float_array("theta", theta)
    w = as_float_array("dtheta", dtheta)
    wd = as_float_array("ddtheta", ddtheta)
    for name, arr in (("theta", th), ("dtheta", w), ("ddtheta", wd)):
        if arr.shape != t.shape:
            raise ValueError(f"{name} must have the shape of t {t.shape}; got {arr.shape}")
    ag = np.zeros_like(t) if a_g is None else as_float_array("a_g", a_g)
    if ag.shape != t.shape:
        raise ValueError(f"a_g must have the shape of t {t.shape}; got {ag.shape}")
    g = float(check_positive("g", g))
    b = float(as_float_array("half_width", half_width))
    if b < 0.0:
        raise ValueError(f"half_width must be >= 0; got {half_width!r}")
    xp, yp = (float(v) for v in as_float_array("point", point).reshape(2))
    if pivot_sign is None:
        s = np.sign(th)
    else:
        s = as_float_array("pivot_sign", pivot_sign)
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


