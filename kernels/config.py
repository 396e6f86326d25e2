"""All Numba compiler options live here, with environment overrides.

``FASTROCK_CACHE=0`` disables the on-disk cache (``NUMBA_CACHE_DIR`` moves it;
the kernels go into a subfolder named by the hash of all kernel sources).
``FASTROCK_DEBUG=1`` compiles the impact energy checks in (never cached).
``NUMBA_BOUNDSCHECK=1`` and ``NUMBA_DISABLE_JIT=1`` are honoured by Numba itself.
"""
import math
import os

from numba import njit

#: ``FASTROCK_DEBUG=1``: kernels check that no impact raises the kinetic
#: energy (counted in the energy_gains metric).  A compile-time constant, so
#: release kernels carry no trace of it; debug kernels are never cached.
DEBUG = os.environ.get("FASTROCK_DEBUG", "0") == "1"
CACHE = os.environ.get("FASTROCK_CACHE", "1") != "0" and not DEBUG
# error_model="numpy": a division by zero gives inf/nan instead of raising
# inside a kernel (an exception in nopython code leaks and cannot be handled
# per run in a prange sweep).
_OPTIONS = dict(cache=CACHE, nogil=True, error_model="numpy", fastmath=False)


def _kernel_cache_dir(here=None):
    """A cache folder keyed by the hash of every kernel source file.

    Numba stamps a cached entry kernel with its own source file only, but
    the entry kernels inline the driver (hybrid.py), the integrator and
    the shared pieces of other modules: an edit there would load stale
    machine code.  Keying the folder by all the sources makes any edit (or
    a new release) compile afresh.  The folder lives under
    ``NUMBA_CACHE_DIR`` if set, else under the user's cache folder."""
    import hashlib
    from pathlib import Path
    here = Path(here or Path(__file__).resolve().parent)
    digest = hashlib.sha256()
    for src in sorted(here.glob("*.py")):
        digest.update(src.name.encode())
        digest.update(src.read_bytes())
    base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "fastrock")
    return os.path.join(base, "kernels-" + digest.hexdigest()[:16])


if CACHE:
    import numba
    numba.config.CACHE_DIR = _kernel_cache_dir()


def jit(func):
    """Compile a kernel helper (inlined into its callers by LLVM)."""
    return njit(**_OPTIONS)(func)


def jit_generic(func):
    """Compile a generic helper that receives model functions as arguments.

    It is inlined at the Numba-IR level into each model's entry kernel, so
    that the model functions are resolved statically: passing a dispatcher
    into a function that stays a separate call makes Numba emit its address
    as a "dynamic global", which disables the on-disk cache.
    """
    return njit(inline="always", **_OPTIONS)(func)


def jit_parallel(func):
    """Compile a parallel sweep kernel (only sweeps use ``prange``)."""
    return njit(parallel=True, **_OPTIONS)(func)


@jit
def ulp(t):
    """Spacing of float64 at |t| (np.nextafter goes through a ctypes
    pointer, which stops Numba's on-disk cache)."""
    a = abs(t)
    if a == 0.0:
        return 5e-324
    m, e = math.frexp(a)
    if m == 0.5:
        # at a power of two the spacing upward is the larger one
        return math.ldexp(1.0, e - 53)
    return math.ldexp(1.0, e - 53)


@jit
def next_up(t):
    """Smallest float64 greater than t (for finite t >= 0)."""
    return t + ulp(t)
