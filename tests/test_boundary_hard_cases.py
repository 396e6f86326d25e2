"""Hard cases (issue #8): cells beside an overturning boundary, and denormal / huge parameters.

A cell next to an outcome boundary is either stable when the tolerance is halved or reported
as a boundary cell (``overturning_spectrum(..., boundary_check=True)``).  Denormal and huge
parameters are refused by validation with the field's name (never reach a kernel).  The file
name matches ``tests/test_*hard_cases*.py``, so CI runs it again under NUMBA_BOUNDSCHECK=1.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr

DENORMAL = 1e-310
HUGE = 1e300
BLOCK = fr.RigidBlock(alpha=0.2, p=2.0)


def boundary_amplitude(freq, lo=1.0, hi=6.0, rtol=1e-8, tol=1e-12):
    """Smallest overturning amplitude a_p/(g tan alpha) at omega_p/p = freq, by bisection."""
    def over(a):
        df = fr.overturning_spectrum(BLOCK, [a], [freq], rtol=rtol, progress=False)
        return df.outcome.iloc[0] in ("mode1", "mode2")
    assert not over(lo) and over(hi)
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if over(mid) else (mid, hi)
    return lo, hi


@pytest.mark.parametrize("freq", [2.0, 5.0])
def test_cells_beside_the_overturning_boundary(freq):
    lo, hi = boundary_amplitude(freq)
    # 1e-4 away from the boundary the outcome does not move when the tolerance is halved
    amps = [lo * (1 - 1e-4), hi * (1 + 1e-4)]
    df = fr.overturning_spectrum(BLOCK, amps, [freq], progress=False, boundary_check=True)
    assert list(df.outcome.iloc[:1]) == ["safe"] and df.outcome.iloc[1] in ("mode1", "mode2")
    assert not df.boundary.any()
    # on the boundary itself (within 1e-12): each cell is definite, and a cell whose outcome
    # moves with the tolerance is flagged instead of silently reported
    df = fr.overturning_spectrum(BLOCK, [lo, hi], [freq], progress=False, boundary_check=True)
    assert set(df.outcome) <= {"safe", "mode1", "mode2"}
    half = fr.overturning_spectrum(BLOCK, [lo, hi], [freq], rtol=5e-9, atol=5e-11, progress=False)
    np.testing.assert_array_equal(df.boundary.to_numpy(), df.outcome.to_numpy() != half.outcome.to_numpy())


def test_boundary_check_with_fixed_steps():
    df = fr.overturning_spectrum(BLOCK, np.linspace(1.0, 4.0, 6), [2.0, 4.0], dt=0.002, progress=False,
                                 boundary_check=True)
    half = fr.overturning_spectrum(BLOCK, np.linspace(1.0, 4.0, 6), [2.0, 4.0], dt=0.001, progress=False)
    np.testing.assert_array_equal(df.boundary.to_numpy(), df.outcome.to_numpy() != half.outcome.to_numpy())


@pytest.mark.parametrize("value", [DENORMAL, HUGE, -DENORMAL, math.nan, math.inf])
@pytest.mark.parametrize("build", [
    lambda v: fr.RigidBlock(alpha=v, p=2.0),
    lambda v: fr.RigidBlock(alpha=0.2, p=v),
    lambda v: fr.FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=v),
    lambda v: fr.FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, base_mass_ratio=-abs(v) - 1.0),
    lambda v: fr.Friction(-abs(v) if v == v else v),
    lambda v: fr.Pulse(v if v != DENORMAL else -1.0, 1.0),
])
def test_denormal_and_huge_parameters_are_refused(value, build):
    with pytest.raises(ValueError):
        build(value)
