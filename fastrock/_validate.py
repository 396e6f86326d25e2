"""Input checks shared by the front end.  Every error names the field."""
import math

import numpy as np


def finite(name, value):
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a real number, got the boolean {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if v != 0.0 and abs(v) < np.finfo(float).tiny:
        raise ValueError(f"{name} = {value!r} is denormal; use 0 or a normal number")
    if abs(v) > 1e12:
        raise ValueError(f"{name} = {value!r} is out of the physically meaningful range (|x| <= 1e12)")
    return v


def positive(name, value):
    v = finite(name, value)
    if v <= 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return v


def non_negative(name, value):
    v = finite(name, value)
    if v < 0.0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return v


def in_closed(name, value, lo, hi):
    v = finite(name, value)
    if not lo <= v <= hi:
        raise ValueError(f"{name} must lie in [{lo}, {hi}], got {value!r}")
    return v


def in_open(name, value, lo, hi, lo_label=None, hi_label=None):
    v = finite(name, value)
    if not lo < v < hi:
        raise ValueError(f"{name} must lie in ({lo_label or lo}, {hi_label or hi}), got {value!r}")
    return v


def finite_array(name, values, ndim=1):
    a = np.asarray(values, dtype=float)
    if a.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"{name} contains NaN or inf (first at index {i})")
    return a


def sign(name, value):
    if value in (1, -1, 1.0, -1.0):
        return int(value)
    raise ValueError(f"{name} must be +1 or -1, got {value!r}")


def choice(name, value, options):
    if value not in options:
        raise ValueError(f"{name} must be one of {sorted(options)}, got {value!r}")
    return value
