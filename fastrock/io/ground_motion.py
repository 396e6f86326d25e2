"""A recorded accelerogram (GroundMotion), its units and intensity measures.
"""
from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from fastrock.constants import G_STANDARD


#: Canonical unit names and their factor to m/s².
UNITS: dict[str, float] = {
    "g": G_STANDARD,
    "m/s2": 1.0,
    "cm/s2": 1e-2,
    "mm/s2": 1e-3,
}

_UNIT_ALIASES: dict[str, str] = {
    "g": "g",
    "m/s2": "m/s2",
    "m/s^2": "m/s2",
    "m/s/s": "m/s2",
    "m/s**2": "m/s2",
    "m/s²": "m/s2",
    "cm/s2": "cm/s2",
    "cm/s^2": "cm/s2",
    "cm/s/s": "cm/s2",
    "cm/s**2": "cm/s2",
    "cm/s²": "cm/s2",
    "gal": "cm/s2",
    "mm/s2": "mm/s2",
    "mm/s^2": "mm/s2",
    "mm/s/s": "mm/s2",
    "mm/s**2": "mm/s2",
    "mm/s²": "mm/s2",
}

#: PGA range [g] of a plausible accelerogram.  A record read outside it gets
#: a :class:`RecordUnitWarning` naming the units that would bring it inside.
PGA_PLAUSIBLE_G = (1e-4, 5.0)


class RecordFormatError(ValueError):
    """A record file cannot be parsed; the message names the file and line."""


class RecordUnitWarning(UserWarning):
    """A record's PGA in its stated unit is outside :data:`PGA_PLAUSIBLE_G`.

    The message names the file, the unit and where it was stated, the PGA,
    and every other unit of :data:`UNITS` that would make the PGA plausible,
    with its factor.
    """


def canonical_unit(unit: str) -> str:
    """Map a unit string (any accepted alias) to its canonical name.

    Raises
    ------
    ValueError
        If the unit is not recognised; the message names the field ``unit``
        and lists the accepted spellings.
    """
    if not isinstance(unit, str):
        raise ValueError(
            f"unit must be a string, got {unit!r}; accepted: {', '.join(_UNIT_ALIASES)}"
        )
    key = re.sub(r"\s+", "", unit).lower().replace("sec", "s")
    try:
        return _UNIT_ALIASES[key]
    except KeyError:
        raise ValueError(
            f"unit: unknown acceleration unit {unit!r}; accepted: "
            f"{', '.join(_UNIT_ALIASES)}"
        ) from None


def _unit_factor(unit: str) -> float:
    """Factor converting ``unit`` to m/s²."""
    return UNITS[canonical_unit(unit)]


@dataclass(frozen=True, eq=False, repr=False)
class GroundMotion:
    """A uniformly sampled ground acceleration history.

    Parameters
    ----------
    acc : array_like
        Ground acceleration [m/s²], 1-D, finite, at least 2 samples.  The
        first sample is at t = 0.  Stored as a read-only float64 copy.
    dt : float
        Time step [s], finite and > 0.
    name : str, optional
        Label used in summaries and plots.
    unit_in_file : str, optional
        Canonical unit the data had in its source file ('g', 'm/s2',
        'cm/s2', 'mm/s2'); informational only, ``acc`` is always m/s².
    source : str or None, optional
        Path of the file the record was read from, if any.

    Notes
    -----
    Velocity and displacement are obtained by trapezoidal integration from
    zero initial conditions and are cached on first use.
    """

    acc: np.ndarray
    dt: float
    name: str = ""
    unit_in_file: str = "m/s2"
    source: str | None = None

    #: Standard gravity [m/s²] used for conversions to g.
    g: ClassVar[float] = G_STANDARD

    def __post_init__(self) -> None:
        acc = np.array(self.acc, dtype=np.float64)  # copy: caller keeps theirs
        if acc.ndim != 1:
            raise ValueError(f"acc must be 1-D, got shape {acc.shape}")
        if acc.size < 2:
            raise ValueError(f"acc must have at least 2 samples, got {acc.size}")
        bad = np.flatnonzero(~np.isfinite(acc))
        if bad.size:
            raise ValueError(
                f"acc must be finite; first non-finite value {acc[bad[0]]} "
                f"at index {bad[0]}"
            )
        from fastrock import _validate as V
        dt = V.positive("dt", self.dt)
        acc.flags.writeable = False
        object.__setattr__(self, "acc", acc)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "name", str(self.name))
        object.__setattr__(self, "unit_in_file", canonical_unit(self.unit_in_file))
        if self.source is not None:
            object.__setattr__(self, "source", os.fspath(self.source))

    def __repr__(self) -> str:
        return (
            f"GroundMotion(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
            f"pga={self.pga_g:.4g} g)"
        )

    # -- basic geometry ---------------------------------------------------
    @property
    def npts(self) -> int:
        """Number of samples."""
        return int(self.acc.size)

    @property
    def duration(self) -> float:
        """Record length ``(npts - 1) * dt`` [s]."""
        return (self.npts - 1) * self.dt

    @property
    def time(self) -> np.ndarray:
        """Sample times [s], starting at 0."""
        return np.arange(self.npts) * self.dt

    # -- integration (cached; instance __dict__ is writable even if frozen) -
    def _cached(self, key: str, compute) -> np.ndarray:
        cache = self.__dict__
        if key not in cache:
            arr = compute()
            arr.flags.writeable = False
            cache[key] = arr
        return cache[key]

    def velocity(self) -> np.ndarray:
        """Ground velocity [m/s], trapezoidal integral of ``acc`` with v(0) = 0.

        Returns
        -------
        numpy.ndarray
            Read-only array of length ``npts``.
        """
        return self._cached("_vel", lambda: _cumtrapz(self.acc, self.dt))

    def displacement(self) -> np.ndarray:
        """Ground displacement [m], trapezoidal integral of :meth:`velocity`, d(0) = 0.

        Returns
        -------
        numpy.ndarray
            Read-only array of length ``npts``.
        """
        return self._cached("_disp", lambda: _cumtrapz(self.velocity(), self.dt))

    # -- peak values ------------------------------------------------------
    @property
    def pga(self) -> float:
        """Peak ground acceleration max|a| [m/s²]."""
        return float(np.max(np.abs(self.acc)))

    @property
    def pga_g(self) -> float:
        """Peak ground acceleration [g]."""
        return self.pga / self.g

    @property
    def peak_time(self) -> float:
        """Time of the (first) absolute acceleration peak [s]."""
        return float(np.argmax(np.abs(self.acc)) * self.dt)

    @property
    def pgv(self) -> float:
        """Peak ground velocity max|v| [m/s] (see :meth:`velocity`)."""
        return float(np.max(np.abs(self.velocity())))

    @property
    def pgd(self) -> float:
        """Peak ground displacement max|d| [m] (see :meth:`displacement`)."""
        return float(np.max(np.abs(self.displacement())))

    # -- energy / frequency measures --------------------------------------
    def _cumulative_arias(self) -> np.ndarray:
        """Running Arias intensity [m/s] (Husid curve, not normalised)."""
        return self._cached(
            "_husid",
            lambda: (math.pi / (2.0 * self.g)) * _cumtrapz(self.acc**2, self.dt),
        )

    @property
    def arias_intensity(self) -> float:
        """Arias intensity ``pi / (2 g) * integral(a**2 dt)`` [m/s]."""
        return float(self._cumulative_arias()[-1])

    def significant_duration(self, a: float = 0.05, b: float = 0.95) -> float:
        """Time between fractions ``a`` and ``b`` of the Arias intensity [s].

        Parameters
        ----------
        a, b : float
            Fractions of the total Arias intensity, ``0 <= a < b <= 1``.
            The defaults give the usual D5-95.

        Returns
        -------
        float
            ``t_b - t_a`` [s], crossing times found by linear interpolation
            of the Husid curve.

        Raises
        ------
        ValueError
            If the fractions are out of order/range or the record is all zero.
        """
        from fastrock import _validate as V
        a, b = V.in_closed("a", a, 0.0, 1.0), V.in_closed("b", b, 0.0, 1.0)
        if not a < b:
            raise ValueError(f"need 0 <= a < b <= 1, got a={a!r}, b={b!r}")
        husid = self._cumulative_arias()
        total = husid[-1]
        if total <= 0.0:
            raise ValueError("significant_duration undefined: record is all zero")
        frac = husid / total
        return _crossing_time(frac, b, self.dt) - _crossing_time(frac, a, self.dt)

    @property
    def mean_period(self) -> float:
        """Mean period Tm of Rathje et al. (1998) [s].

        ``Tm = sum(C_i**2 / f_i) / sum(C_i**2)`` over the Fourier amplitudes
        ``C_i`` at frequencies 0.25 <= f_i <= 20 Hz.  The record is
        zero-padded to the next power of two (at least 2**14 points, so short
        records still have a fine frequency grid).  NaN if the band holds no
        energy.
        """
        nfft = 1 << max(14, (self.npts - 1).bit_length())
        amp2 = np.abs(np.fft.rfft(self.acc, n=nfft)) ** 2
        f = np.fft.rfftfreq(nfft, self.dt)
        band = (f >= 0.25) & (f <= 20.0)
        den = float(np.sum(amp2[band]))
        if den == 0.0:
            return float("nan")
        return float(np.sum(amp2[band] / f[band]) / den)

    # -- derived records --------------------------------------------------
    def scaled(self, factor: float) -> GroundMotion:
        """Return a copy with acceleration multiplied by ``factor`` [-].

        Parameters
        ----------
        factor : float
            Finite amplitude factor; negative values flip the polarity.
        """
        from fastrock import _validate as V
        factor = V.finite("factor", factor)
        return GroundMotion(
            self.acc * factor,
            self.dt,
            name=f"{self.name} x{factor:.4g}" if self.name else f"x{factor:.4g}",
            unit_in_file=self.unit_in_file,
            source=self.source,
        )

    def scaled_to_pga(self, pga: float, unit: str = "g") -> GroundMotion:
        """Return a copy scaled so that its PGA equals ``pga``.

        Parameters
        ----------
        pga : float
            Target peak ground acceleration, > 0, in ``unit``.
        unit : str, optional
            Unit of ``pga``: 'g' (default), 'm/s2', 'cm/s2' / 'gal', 'mm/s2'.
        """
        from fastrock import _validate as V
        target = V.positive("pga", pga) * _unit_factor(unit)
        if self.pga == 0.0:
            raise ValueError("cannot scale an all-zero record to a target PGA")
        return self.scaled(target / self.pga)

    def baseline_corrected(self, order: int = 1) -> GroundMotion:
        """Return a copy with a polynomial velocity trend removed.

        A polynomial ``p(t)`` of degree ``order`` is fitted by least squares
        to the velocity (trapezoidal integral of ``acc``) and its derivative
        ``p'(t)`` is subtracted from the acceleration.  The corrected
        velocity is therefore ``v(t) - p(t) + p(0)`` (exactly for
        ``order <= 2``, to O(dt**2) otherwise), which removes the drift
        caused by a constant (order 1) or linear (order 2) acceleration offset.

        Parameters
        ----------
        order : int, optional
            Polynomial degree, >= 1 (a degree-0 fit has zero derivative and
            would change nothing).

        Returns
        -------
        GroundMotion
            Corrected record [m/s²], same ``dt`` and name.
        """
        from fastrock import _validate as V
        order = V.integer("order", order, 1)
        if order >= self.npts:
            raise ValueError(f"order must be < npts ({self.npts}), got {order}")
        # Fit on t/T in [0, 1] to keep the Vandermonde matrix well conditioned.
        T = self.duration
        x = self.time / T
        poly = np.polynomial.Polynomial.fit(x, self.velocity(), order, domain=[0.0, 1.0])
        dpdt = poly.deriv()(x) / T
        return GroundMotion(
            self.acc - dpdt,
            self.dt,
            name=self.name,
            unit_in_file=self.unit_in_file,
            source=self.source,
        )

    # -- reporting --------------------------------------------------------
    def summary(self) -> dict[str, Any]:
        """Main intensity measures as a dict of plain Python values.

        Returns
        -------
        dict
            ``name``, ``npts``, ``dt`` [s], ``duration`` [s], ``pga_g`` [g],
            ``pgv`` [m/s], ``pgd`` [m], ``arias`` [m/s], ``mean_period`` [s].
        """
        return {
            "name": self.name,
            "npts": self.npts,
            "dt": self.dt,
            "duration": self.duration,
            "pga_g": self.pga_g,
            "pgv": self.pgv,
            "pgd": self.pgd,
            "arias": self.arias_intensity,
            "mean_period": self.mean_period,
        }

    def to_frame(self):
        """Time histories as a :class:`pandas.DataFrame`.

        Returns
        -------
        pandas.DataFrame
            Columns ``t [s]``, ``acc [m/s²]``, ``vel [m/s]``, ``disp [m]``.
        """
        import pandas as pd

        return pd.DataFrame(
            {
                "t [s]": self.time,
                "acc [m/s²]": np.array(self.acc),
                "vel [m/s]": np.array(self.velocity()),
                "disp [m]": np.array(self.displacement()),
            }
        )

    def plot(self, ax=None):
        """Plot acceleration [g], velocity [m/s] and displacement [m].

        Parameters
        ----------
        ax : sequence of 3 matplotlib Axes, optional
            Axes to draw into (top to bottom).  If omitted, a new
            :class:`matplotlib.figure.Figure` is created without pyplot, so
            this works with any backend (including Agg) and never shows it.

        Returns
        -------
        matplotlib.figure.Figure
        """
        if ax is None:
            from matplotlib.figure import Figure

            fig = Figure(figsize=(8.0, 6.0), layout="constrained")
            axes = fig.subplots(3, 1, sharex=True)
        else:
            axes = list(ax)
            if len(axes) != 3:
                raise ValueError(f"ax must hold 3 Axes, got {len(axes)}")
            fig = axes[0].figure
        t = self.time
        series = [
            (self.acc / self.g, "acc [g]"),
            (self.velocity(), "vel [m/s]"),
            (self.displacement(), "disp [m]"),
        ]
        for a, (y, label) in zip(axes, series):
            a.plot(t, y, lw=0.8)
            a.set_ylabel(label)
            a.grid(True, alpha=0.3)
        axes[-1].set_xlabel("t [s]")
        if self.name:
            axes[0].set_title(self.name)
        return fig


def _cumtrapz(y: np.ndarray, dt: float) -> np.ndarray:
    """Cumulative trapezoidal integral of uniformly sampled ``y``, starting at 0."""
    out = np.empty_like(y, dtype=np.float64)
    out[0] = 0.0
    np.cumsum((y[1:] + y[:-1]) * (0.5 * dt), out=out[1:])
    return out


def _crossing_time(frac: np.ndarray, level: float, dt: float) -> float:
    """First time at which non-decreasing ``frac`` reaches ``level`` [s]."""
    i = int(np.searchsorted(frac, level, side="left"))
    if i == 0:
        return 0.0
    i = min(i, frac.size - 1)
    lo, hi = frac[i - 1], frac[i]
    w = (level - lo) / (hi - lo) if hi > lo else 1.0
    return (i - 1 + w) * dt


