"""Recorded accelerograms: file loading and ground-motion intensity measures.

The loader understands the text formats in which strong-motion records are
usually passed around:

* PEER ``.AT2`` and look-alikes: free header lines, one of which gives the
  number of points and the time step, either as ``NPTS=  4000, DT= .01000 SEC``
  (old PEER, NGA-West2 with a trailing comma, lower-case ``dt=``) or as
  ``4164    0.0100    NPTS, DT`` (NGA 2005-2010), followed by the samples
  read row by row, any number per row.
* Two columns ``time acceleration`` after optional text header lines.
* One value per row (or any number per row) without ``NPTS``: the time step
  must then be given by the caller.

All accelerations are converted to m/s² with standard gravity
:data:`G_STANDARD`.  Everything here is plain NumPy; nothing is compiled.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

__all__ = [
    "G_STANDARD",
    "UNITS",
    "GroundMotion",
    "RecordFormatError",
    "load_default_record",
    "read_record",
]

#: Standard gravity [m/s²] used for every g <-> m/s² conversion.
G_STANDARD = 9.80665

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

#: Largest relative deviation of a time step from the mean step accepted in
#: a two-column file (time values are often printed with few decimals).
TIME_RTOL = 1e-3

#: NPTS/DT lines are searched for only this far into a file.
_MAX_HEADER_LINES = 40

_DEFAULT_RECORD_NAME = "El Centro 1940 N-S (USC&GS)"

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"
_NPTS_DT_RE = re.compile(
    r"NPTS\s*[=:]?\s*(\d+)\s*[,;]?\s*DT\s*[=:]?\s*(" + _NUM + r")", re.IGNORECASE
)
_NUMBERS_FIRST_RE = re.compile(
    r"^\s*(\d+)\s*,?\s+(" + _NUM + r")\s*,?\s+NPTS\b", re.IGNORECASE
)
_NPTS_RE = re.compile(r"\bNPTS\b", re.IGNORECASE)
_DT_ALONE_RE = re.compile(r"\bDT\s*[=:]\s*(" + _NUM + r")", re.IGNORECASE)
_SPLIT_RE = re.compile(r"[\s,;]+")
# Fortran fixed-width output glues a negative value to the previous one
# ("-.1234E-02-.5678E-02"); split such tokens only at a minus sign.
_GLUED_RE = re.compile(
    r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"
    r"(?:-(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?)+"
)
_GLUED_PIECE_RE = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?")

_UNIT_TOKEN = (
    r"(?P<unit>(?:cm|mm|m)\s*/\s*s(?:ec)?\s*(?:\^\s*2|\*\*\s*2|2|²|/\s*s(?:ec)?)"
    r"|gal|g)(?![a-z0-9/^²])"
)
_UNIT_PATTERNS = [
    # "UNITS OF G", "IN UNITS OF CM/S/S", "The units are (g)", "units: m/s2"
    re.compile(
        r"\bunits?\s*(?:of|are|is|in|:|=)?\s*[\(\[]?\s*" + _UNIT_TOKEN, re.IGNORECASE
    ),
    # "Accel[g]", "Acceleration (cm/s^2)"
    re.compile(r"\bacc\w*\s*[\(\[]\s*" + _UNIT_TOKEN + r"\s*[\)\]]", re.IGNORECASE),
]
_NOT_ACCEL_RE = re.compile(
    r"\b(VELOCITY|DISPLACEMENT)\s+TIME\s+(?:HISTORY|SERIES)", re.IGNORECASE
)


class RecordFormatError(ValueError):
    """A record file cannot be parsed; the message names the file and line."""


def _canonical_unit(unit: str) -> str:
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
    return UNITS[_canonical_unit(unit)]


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
        try:
            dt = float(self.dt)
        except (TypeError, ValueError):
            raise ValueError(f"dt must be a number [s], got {self.dt!r}") from None
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be finite and > 0 [s], got {self.dt!r}")
        acc.flags.writeable = False
        object.__setattr__(self, "acc", acc)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "name", str(self.name))
        object.__setattr__(self, "unit_in_file", _canonical_unit(self.unit_in_file))
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
        if not (0.0 <= a < b <= 1.0):
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
        factor = float(factor)
        if not math.isfinite(factor):
            raise ValueError(f"factor must be finite, got {factor!r}")
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
        target = float(pga) * _unit_factor(unit)
        if not (math.isfinite(target) and target > 0.0):
            raise ValueError(f"pga must be finite and > 0, got {pga!r}")
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
        order = int(order)
        if order < 1:
            raise ValueError(f"order must be >= 1, got {order}")
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


# ---------------------------------------------------------------------------
# file reading
# ---------------------------------------------------------------------------


def _split_lines(text: str) -> list[str]:
    """Split into lines so that line numbers match a text editor.

    ``str.splitlines`` would count the bare ``\\r`` of ``\\r\\r\\n`` endings
    (seen in ARL360.at2) as extra lines.
    """
    if "\n" not in text and "\r" in text:
        lines = text.split("\r")  # classic Mac endings
    else:
        lines = [ln.rstrip("\r") for ln in text.split("\n")]
    if lines and lines[-1] == "":
        lines.pop()  # final newline terminates the last line, no new one
    return lines


def _parse_float(tok: str) -> float | None:
    try:
        return float(tok.replace("D", "E").replace("d", "e"))
    except ValueError:
        return None


def _line_numbers(line: str) -> list[float] | None:
    """All values of a data line, or None if a token is not a number."""
    vals: list[float] = []
    for tok in _SPLIT_RE.split(line.strip()):
        if not tok:
            continue
        v = _parse_float(tok)
        if v is not None:
            vals.append(v)
        elif _GLUED_RE.fullmatch(tok):
            vals.extend(float(p.replace("D", "E").replace("d", "e"))
                        for p in _GLUED_PIECE_RE.findall(tok))
        else:
            return None
    return vals


def _bad_token(line: str) -> str:
    for tok in _SPLIT_RE.split(line.strip()):
        if tok and _parse_float(tok) is None and not _GLUED_RE.fullmatch(tok):
            return tok
    return line.strip()


def _header_unit(header: list[str], where: str) -> str | None:
    """Unit stated in the header text, or None if it does not say."""
    found: list[tuple[str, int]] = []
    for k, line in enumerate(header, start=1):
        for pat in _UNIT_PATTERNS:
            for m in pat.finditer(line):
                found.append((_canonical_unit(m.group("unit")), k))
    units = {u for u, _ in found}
    if len(units) > 1:
        desc = ", ".join(f"{u!r} (line {k})" for u, k in found)
        raise RecordFormatError(f"{where}: header states conflicting units: {desc}")
    return found[0][0] if found else None


def _fmt_where(path: str, lineno: int) -> str:
    return f"{path}, line {lineno}"


def _parse_record_text(
    text: str, path: str, unit: str | None, dt: float | None
) -> tuple[np.ndarray, float, str]:
    """Parse a record file's text.

    Returns
    -------
    acc_file : numpy.ndarray
        Samples in the file's unit.
    dt : float
        Time step [s].
    unit : str
        Canonical unit of the file's samples.
    """
    user_unit = _canonical_unit(unit) if unit is not None else None
    lines = _split_lines(text)

    if not any(ln.strip() for ln in lines):
        raise RecordFormatError(f"{_fmt_where(path, 1)}: file is empty, no data")

    # A PEER-style NPTS/DT line makes it an AT2 file; it is always among the
    # first few lines, and the samples start right after it.
    npts_line = next(
        (k for k, ln in enumerate(lines[:_MAX_HEADER_LINES]) if _NPTS_RE.search(ln)),
        None,
    )
    if npts_line is not None:
        hdr_end = npts_line + 1
    else:
        # Otherwise the header is the leading lines that are not all-numeric.
        hdr_end = len(lines)
        for i, line in enumerate(lines):
            if line.strip() and _line_numbers(line) is not None:
                hdr_end = i
                break
    header = lines[:hdr_end]

    for k, line in enumerate(header, start=1):
        m = _NOT_ACCEL_RE.search(line)
        if m is not None:
            raise RecordFormatError(
                f"{_fmt_where(path, k)}: file holds a {m.group(1).lower()} "
                "history, not an acceleration"
            )

    file_unit = _header_unit(header, path)
    if user_unit is not None and file_unit is not None and user_unit != file_unit:
        raise ValueError(
            f"{path}: unit={unit!r} contradicts the file header, which says {file_unit!r}"
        )
    out_unit = user_unit or file_unit

    if npts_line is not None:
        acc, file_dt = _parse_at2(lines, header, npts_line, hdr_end, path)
    elif hdr_end == len(lines):
        raise RecordFormatError(
            f"{_fmt_where(path, len(header) + 1)}: no numeric data after "
            f"{len(header)} header line(s)"
        )
    else:
        acc, file_dt = _parse_columns(lines, hdr_end, path)

    if dt is not None:
        dt_user = float(dt)
        if not (math.isfinite(dt_user) and dt_user > 0.0):
            raise ValueError(f"dt must be finite and > 0 [s], got {dt!r}")
        if file_dt is not None and not math.isclose(dt_user, file_dt, rel_tol=TIME_RTOL):
            raise ValueError(
                f"{path}: dt={dt_user!r} contradicts the file, which gives dt={file_dt!r}"
            )
        if file_dt is None:
            file_dt = dt_user
    if file_dt is None:
        raise ValueError(
            f"{path}: single-column data without NPTS/DT header; the time step "
            "must be given (dt=...)"
        )
    if out_unit is None:
        raise ValueError(
            f"{path}: the file header does not state the acceleration unit; the "
            f"unit must be given (unit=..., one of {', '.join(UNITS)})"
        )
    return acc, file_dt, out_unit


def _collect_values(
    lines: list[str], first: int, path: str
) -> tuple[list[float], list[int]]:
    """All numbers from ``lines[first:]`` and the 1-based line of each."""
    values: list[float] = []
    where: list[int] = []
    for i in range(first, len(lines)):
        line = lines[i]
        if not line.strip():
            continue
        vals = _line_numbers(line)
        if vals is None:
            raise RecordFormatError(
                f"{_fmt_where(path, i + 1)}: non-numeric token {_bad_token(line)!r}"
            )
        for v in vals:
            if not math.isfinite(v):
                raise RecordFormatError(
                    f"{_fmt_where(path, i + 1)}: non-finite value {v!r} in data"
                )
        values.extend(vals)
        where.extend([i + 1] * len(vals))
    return values, where


def _parse_at2(
    lines: list[str], header: list[str], npts_line: int, hdr_end: int, path: str
) -> tuple[np.ndarray, float]:
    line = header[npts_line]
    m = _NPTS_DT_RE.search(line) or _NUMBERS_FIRST_RE.search(line)
    lineno = npts_line + 1
    if m is not None:
        npts, dt_txt = int(m.group(1)), m.group(2)
    else:
        nm = re.search(r"NPTS\s*[=:]?\s*(\d+)", line, re.IGNORECASE)
        if nm is None:
            raise RecordFormatError(
                f"{_fmt_where(path, lineno)}: cannot read the number of points "
                f"from {line.strip()!r}"
            )
        npts = int(nm.group(1))
        dm = _DT_ALONE_RE.search(line)
        if dm is None:  # DT on another header line
            for other in header:
                dm = _DT_ALONE_RE.search(other)
                if dm is not None:
                    break
        if dm is None:
            raise RecordFormatError(
                f"{_fmt_where(path, lineno)}: missing DT (time step) in header "
                f"line {line.strip()!r}"
            )
        dt_txt = dm.group(1)
    dt = float(dt_txt.replace("D", "E").replace("d", "e"))
    if not (math.isfinite(dt) and dt > 0.0):
        raise RecordFormatError(f"{_fmt_where(path, lineno)}: DT must be > 0, got {dt_txt}")
    if npts < 2:
        raise RecordFormatError(
            f"{_fmt_where(path, lineno)}: NPTS must be >= 2, got {npts}"
        )

    values, where = _collect_values(lines, hdr_end, path)
    if not values:
        raise RecordFormatError(
            f"{_fmt_where(path, hdr_end + 1)}: no data after the header "
            f"(NPTS={npts} on line {lineno})"
        )
    if len(values) > npts:
        raise RecordFormatError(
            f"{_fmt_where(path, where[npts])}: more values than NPTS={npts} "
            f"(line {lineno}); found {len(values)} in total"
        )
    if len(values) < npts:
        raise RecordFormatError(
            f"{_fmt_where(path, where[-1])}: data end after {len(values)} values "
            f"but NPTS={npts} (line {lineno})"
        )
    return np.asarray(values, dtype=np.float64), dt


def _parse_columns(
    lines: list[str], hdr_end: int, path: str
) -> tuple[np.ndarray, float | None]:
    """Two-column time/acc data, or a plain sequence of values (dt unknown)."""
    first = _line_numbers(lines[hdr_end])
    if first is not None and len(first) == 2:
        t: list[float] = []
        a: list[float] = []
        rows: list[int] = []
        for i in range(hdr_end, len(lines)):
            line = lines[i]
            if not line.strip():
                continue
            vals = _line_numbers(line)
            if vals is None:
                raise RecordFormatError(
                    f"{_fmt_where(path, i + 1)}: non-numeric token {_bad_token(line)!r}"
                )
            if len(vals) != 2:
                raise RecordFormatError(
                    f"{_fmt_where(path, i + 1)}: expected 2 columns (time, "
                    f"acceleration), found {len(vals)}"
                )
            for v in vals:
                if not math.isfinite(v):
                    raise RecordFormatError(
                        f"{_fmt_where(path, i + 1)}: non-finite value {v!r} in data"
                    )
            t.append(vals[0])
            a.append(vals[1])
            rows.append(i + 1)
        if len(t) < 2:
            raise RecordFormatError(
                f"{_fmt_where(path, rows[0])}: need at least 2 samples, found 1"
            )
        tt = np.asarray(t)
        steps = np.diff(tt)
        file_dt = (tt[-1] - tt[0]) / (tt.size - 1)
        if not file_dt > 0.0:
            raise RecordFormatError(
                f"{_fmt_where(path, rows[-1])}: time column does not increase "
                f"(dt = {file_dt:g} <= 0)"
            )
        bad = np.flatnonzero(np.abs(steps - file_dt) > TIME_RTOL * file_dt)
        if bad.size:
            k = int(bad[0])
            raise RecordFormatError(
                f"{_fmt_where(path, rows[k + 1])}: time column is not uniformly "
                f"spaced: step {steps[k]:g} s from line {rows[k]} differs from "
                f"the mean step {file_dt:g} s by more than {TIME_RTOL:g} (relative)"
            )
        return np.asarray(a, dtype=np.float64), float(file_dt)

    values, where = _collect_values(lines, hdr_end, path)
    if len(values) < 2:
        raise RecordFormatError(
            f"{_fmt_where(path, where[-1] if where else hdr_end + 1)}: need at "
            f"least 2 samples, found {len(values)}"
        )
    return np.asarray(values, dtype=np.float64), None


def read_record(
    path: str | os.PathLike,
    unit: str | None = None,
    dt: float | None = None,
    name: str | None = None,
) -> GroundMotion:
    """Read an accelerogram file.

    The format is detected from the content:

    * a header line with ``NPTS=.., DT=..`` (any case, optional trailing
      comma or ``SEC``) or ``<npts> <dt> NPTS, DT``: PEER AT2 style; all
      numbers after the header are the samples and their count must equal
      NPTS;
    * otherwise, data rows of two numbers: ``time acceleration``; the time
      step is the mean step and every step must agree with it to
      ``TIME_RTOL`` (relative); the first sample is put at t = 0;
    * otherwise, a plain sequence of samples; ``dt`` must be given.

    Leading non-numeric lines are a header.  The acceleration unit is read
    from it where it says ("UNITS OF G", "IN UNITS OF CM/S/S",
    "Accel[g]", "units are (g)").

    Parameters
    ----------
    path : str or os.PathLike
        File to read (text, any line endings).
    unit : str, optional
        Unit of the samples in the file: 'g', 'm/s2' ('m/s^2', 'm/s/s'),
        'cm/s2' ('gal', 'cm/s^2', 'cm/s/s') or 'mm/s2'.  Required if the
        header does not state it; must agree with the header if it does.
    dt : float, optional
        Time step [s].  Required for single-column data; must agree with the
        file otherwise.
    name : str, optional
        Record name; defaults to the file name without extension.

    Returns
    -------
    GroundMotion
        Acceleration converted to m/s².

    Raises
    ------
    RecordFormatError
        Malformed file (message gives path and line number): value count
        different from NPTS, NaN/inf or non-numeric token, non-uniform time
        column, no data, missing DT, DT <= 0.
    ValueError
        Unknown, missing or contradictory ``unit``; missing or contradictory
        ``dt``.
    """
    p = Path(path)
    raw = p.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")  # old headers with degree signs etc.
    acc, file_dt, file_unit = _parse_record_text(text, str(p), unit, dt)
    return GroundMotion(
        acc * UNITS[file_unit],
        file_dt,
        name=p.stem if name is None else name,
        unit_in_file=file_unit,
        source=str(p),
    )


def load_default_record() -> GroundMotion:
    """The packaged 1940 El Centro N-S record (USC&GS, 1559 points, dt 0.02 s).

    Public-domain US federal data; PGA 0.319 g.  Samples are in g in the
    file and returned in m/s².

    Returns
    -------
    GroundMotion
    """
    res = resources.files("fastrock") / "data" / "elcentro_ns.at2"
    with resources.as_file(res) as path:
        return read_record(path, name=_DEFAULT_RECORD_NAME)
