"""Input checks shared by the front end.  Every error names the field."""
import math
import numbers

import numpy as np

from .constants import G_STANDARD

#: Largest ground acceleration accepted anywhere [g]: the strongest recorded
#: motions peak near 4-5 g; beyond 100 g a rigid block on the ground is no
#: longer a meaningful model (and the integrator's step shrinks with 1/a).
MAX_ACCELERATION_G = 100.0
#: Largest step budget (Solver.max_steps) and number of fixed steps in one
#: run: 1e12 steps take weeks of CPU time.
MAX_STEPS = 10 ** 12
#: Longest run [s]: float64 still resolves time to 0.2 us at its end
#: (earthquake records and free rocking last minutes).
MAX_RUN_TIME = 1e9


def _is_number(value):
    return isinstance(value, numbers.Real) or (isinstance(value, np.ndarray) and value.ndim == 0
                                               and value.dtype.kind in "iuf")


def finite(name, value):
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a real number, got the boolean {value!r}")
    if not _is_number(value):
        what = "the string" if isinstance(value, (str, bytes)) else f"a {type(value).__name__}"
        raise ValueError(f"{name} must be a real number, got {what} {_short(value)}")
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


def _short(value, n=60):
    r = repr(value)
    return r if len(r) <= n else r[:n - 3] + "..."


def boolean(name, value):
    """True or False (also NumPy booleans and the integers 0 and 1)."""
    if isinstance(value, (bool, np.bool_)) or (isinstance(value, numbers.Integral) and value in (0, 1)):
        return bool(value)
    raise ValueError(f"{name} must be True or False, got {_short(value)}")


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
    if isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be an array of numbers, got the string {values!r}")
    try:
        a = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of real numbers, got {_short(values)}") from None
    if a.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"{name} contains NaN or inf (first at index {i})")
    return a


def sign(name, value):
    if not isinstance(value, (bool, np.bool_)) and _is_number(value) and value in (1, -1, 1.0, -1.0):
        return int(value)
    raise ValueError(f"{name} must be +1 or -1, got {value!r}")


def choice(name, value, options):
    try:
        ok = value in options
    except TypeError:          # unhashable (a list or dict)
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {sorted(options)}, got {value!r}")
    return value


def integer(name, value, lo=None, hi=None):
    """An integer (an int, or a float with an integral value such as 1e6 from
    TOML) in [lo, hi]; returns an int."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer, got the boolean {value!r}")
    if isinstance(value, numbers.Integral):
        v = int(value)
    elif _is_number(value) and math.isfinite(float(value)) and float(value).is_integer():
        v = int(float(value))
    else:
        raise ValueError(f"{name} must be an integer, got {_short(value)}")
    if lo is not None and v < lo:
        raise ValueError(f"{name} must be >= {lo}, got {value!r}")
    if hi is not None and v > hi:
        raise ValueError(f"{name} must be <= {hi:.3g}, got {value!r}")
    return v


def acceleration(name, value_si, g=G_STANDARD, what=None):
    """Refuse a ground acceleration [m/s^2] above MAX_ACCELERATION_G."""
    if abs(value_si) > MAX_ACCELERATION_G * g:
        raise ValueError(f"{name}: {what or 'the ground acceleration'} = {abs(value_si) / g:.4g} g is above "
                         f"the bound {MAX_ACCELERATION_G:g} g (real earthquakes peak below 5 g; a rigid "
                         f"body on the ground is no model of a stronger shock)")
    return value_si


def run_time(name, value, what="the run"):
    """Refuse a run (or a part of it) longer than MAX_RUN_TIME seconds."""
    if value > MAX_RUN_TIME:
        raise ValueError(f"{name}: {what} would last {value:.3g} s, beyond the bound {MAX_RUN_TIME:.0e} s "
                         f"(about 30 years; float64 time then resolves only {np.spacing(value):.1g} s)")
    return value
