"""Argument checks shared by the free-rocking analyses.
"""
from __future__ import annotations

import numpy as np


# ----------------------------------------------------------------------------------------
# validation helpers
# ----------------------------------------------------------------------------------------
def as_float_array(name: str, value) -> np.ndarray:
    """``value`` as a float array, refusing non-numeric and non-finite input."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be numeric; got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite; got {value!r}")
    return arr


def check_alpha(alpha) -> np.ndarray:
    """Slenderness angle(s) alpha [rad] in (0, pi/2)."""
    a = as_float_array("alpha", alpha)
    if np.any(a <= 0.0) or np.any(a >= 0.5 * np.pi):
        raise ValueError(f"alpha must satisfy 0 < alpha < pi/2 [rad]; got {alpha!r}")
    return a


def check_positive(name: str, value) -> np.ndarray:
    """Value(s) of ``name`` as a float array, all > 0."""
    arr = as_float_array(name, value)
    if np.any(arr <= 0.0):
        raise ValueError(f"{name} must be > 0; got {value!r}")
    return arr


def check_theta0(theta0, alpha) -> np.ndarray:
    """Release angle(s) theta0 [rad] in (0, alpha)."""
    t0 = as_float_array("theta0", theta0)
    if np.any(t0 <= 0.0):
        raise ValueError(f"theta0 must be > 0 [rad]; got {theta0!r}")
    if np.any(t0 >= alpha):
        raise ValueError(
            f"theta0 must be < alpha (a release at theta0 >= alpha overturns); "
            f"got theta0={theta0!r}, alpha={alpha!r}")
    return t0


def check_e(e) -> float:
    """Restitution e in [0, 1], as a float."""
    e = float(as_float_array("e", e))
    if not 0.0 <= e <= 1.0:
        raise ValueError(f"e must satisfy 0 <= e <= 1; got {e!r}")
    return e


def scalar_or_array(x: np.ndarray):
    """A 0-d result as a float, else the array."""
    return float(x) if np.ndim(x) == 0 else x


