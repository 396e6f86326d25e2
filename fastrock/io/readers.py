"""Recorded accelerograms: file loading and ground-motion intensity measures.

The loader understands the text formats in which strong-motion records are
usually passed around:

* PEER ``.AT2`` and look-alikes: free header lines, one of which gives the
  number of points and the time step, either as ``NPTS=  4000, DT= .01000 SEC``
  (old PEER, NGA-West2 with a trailing comma, lower-case ``dt=``) or as
  ``4164    0.0100    NPTS, DT`` (NGA 2005-2010), followed by the samples
  read row by row, any number per row.
* Two columns ``time acceleration`` after optional text header lines.
* One value per row without ``NPTS``: the time step must then be given by
  the caller.

Anything else that could be read in more than one way is refused rather than
guessed: decimal commas (unless ``decimal=","``), rows of several numbers that
are not an AT2 body or a time/acceleration pair (unless ``column=`` says which
column, or ``"all"``).  A record whose PGA in the stated unit is implausible
(outside :data:`PGA_PLAUSIBLE_G`) gets a :class:`RecordUnitWarning`.

All accelerations are converted to m/s² with standard gravity
:data:`G_STANDARD`.  Everything here is plain NumPy; nothing is compiled.

"""
from __future__ import annotations

import math
import numbers
import os
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from fastrock.io.ground_motion import (GroundMotion, PGA_PLAUSIBLE_G, RecordFormatError,
    RecordUnitWarning, UNITS, canonical_unit)


#: Largest relative deviation of a time step from the mean step accepted in
#: a two-column file (time values are often printed with few decimals).
TIME_RTOL = 1e-3

#: NPTS/DT lines are searched for only this far into a file.
_MAX_HEADER_LINES = 40

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"

_NPTS_DT_RE = re.compile(
    r"NPTS\s*[=:]?\s*(\d+)\s*[,;]?\s*DT\s*[=:]?\s*(" + _NUM + r")", re.IGNORECASE
)

_NUMBERS_FIRST_RE = re.compile(
    r"^\s*(\d+)\s*,?\s+(" + _NUM + r")\s*,?\s+NPTS\b", re.IGNORECASE
)

_NPTS_RE = re.compile(r"\bNPTS\b", re.IGNORECASE)

_DT_ALONE_RE = re.compile(r"\bDT\s*[=:]\s*(" + _NUM + r")", re.IGNORECASE)

_SPLIT_RE = re.compile(r"[\s,;]+")  # decimal=".": commas separate values

_SPLIT_DECIMAL_COMMA_RE = re.compile(r"[\s;]+")  # decimal=",": they do not

_DIGIT_COMMA_DIGIT_RE = re.compile(r"\d,\d")

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


def _tokens(line: str, decimal: str) -> list[str]:
    """Tokens of a data line: commas separate values only if ``decimal='.'``."""
    split = _SPLIT_RE if decimal == "." else _SPLIT_DECIMAL_COMMA_RE
    return [tok for tok in split.split(line.strip()) if tok]


def _token_values(tok: str, decimal: str) -> list[float] | None:
    """Value(s) of one token (a glued Fortran pair gives two), None if not numeric."""
    if decimal == ",":
        tok = tok.replace(",", ".")
    v = _parse_float(tok)
    if v is not None:
        return [v]
    if _GLUED_RE.fullmatch(tok):
        return [float(p.replace("D", "E").replace("d", "e"))
                for p in _GLUED_PIECE_RE.findall(tok)]
    return None


def _line_numbers(line: str, decimal: str = ".") -> list[float] | None:
    """All values of a data line, or None if a token is not a number."""
    vals: list[float] = []
    for tok in _tokens(line, decimal):
        v = _token_values(tok, decimal)
        if v is None:
            return None
        vals.extend(v)
    return vals


def _bad_token(line: str, decimal: str = ".") -> str:
    for tok in _tokens(line, decimal):
        if _token_values(tok, decimal) is None:
            return tok
    return line.strip()


def _header_unit(header: list[str], where: str) -> tuple[str, int] | None:
    """Unit stated in the header text and its 1-based line, or None."""
    found: list[tuple[str, int]] = []
    for k, line in enumerate(header, start=1):
        for pat in _UNIT_PATTERNS:
            for m in pat.finditer(line):
                found.append((canonical_unit(m.group("unit")), k))
    units = {u for u, _ in found}
    if len(units) > 1:
        desc = ", ".join(f"{u!r} (line {k})" for u, k in found)
        raise RecordFormatError(f"{where}: header states conflicting units: {desc}")
    return found[0] if found else None


def _fmt_where(path: str, lineno: int) -> str:
    return f"{path}, line {lineno}"


def _check_decimal_commas(lines: list[str], first: int, path: str) -> None:
    """Refuse decimal commas when commas are taken as separators (decimal='.').

    A comma between two digits (``0,12345``, ``-1,2E-03;0,5``) inside a
    value group that holds no '.' is a decimal comma, unless the file uses
    commas elsewhere to separate '.'-decimal numbers (``0.01,0.123``); then
    ``0,0`` is just two integer values of a comma-separated file.
    """
    suspect: tuple[int, str] | None = None
    for i in range(first, len(lines)):
        if "," not in lines[i]:
            continue
        for chunk in _SPLIT_DECIMAL_COMMA_RE.split(lines[i].strip()):
            if "," not in chunk:
                continue
            if "." in chunk:
                return  # commas separate '.'-decimal numbers in this file
            if suspect is None and _DIGIT_COMMA_DIGIT_RE.search(chunk):
                suspect = (i + 1, chunk)
    if suspect is not None:
        lineno, chunk = suspect
        raise RecordFormatError(
            f"{_fmt_where(path, lineno)}: {chunk!r} looks like a number with a "
            "decimal comma (a comma between digits, and no '.' decimal mark in the "
            "data); pass decimal=',' if commas are decimal marks, otherwise "
            "separate the values with spaces"
        )


def _collect_rows(
    lines: list[str], first: int, path: str, decimal: str
) -> list[tuple[int, list[float]]]:
    """Numbers of every non-blank line of ``lines[first:]``, with its 1-based line."""
    if decimal == ".":
        _check_decimal_commas(lines, first, path)
    rows: list[tuple[int, list[float]]] = []
    for i in range(first, len(lines)):
        line = lines[i]
        if not line.strip():
            continue
        if decimal == ",":
            dotted = next((t for t in _tokens(line, ",") if "." in t), None)
            if dotted is not None:
                raise RecordFormatError(
                    f"{_fmt_where(path, i + 1)}: {dotted!r} has a '.' decimal mark "
                    "but decimal=',' was passed (commas are the decimal marks and "
                    "only whitespace or ';' separate values); a file must use one "
                    "decimal mark"
                )
        vals = _line_numbers(line, decimal)
        if vals is None:
            bad = _bad_token(line, decimal)
            hint = ""
            if decimal == "," and "," in bad:
                hint = " (with decimal=',' only whitespace or ';' separate values)"
            raise RecordFormatError(
                f"{_fmt_where(path, i + 1)}: non-numeric token {bad!r}{hint}"
            )
        for v in vals:
            if not math.isfinite(v):
                raise RecordFormatError(
                    f"{_fmt_where(path, i + 1)}: non-finite value {v!r} in data"
                )
        rows.append((i + 1, vals))
    return rows


_COLUMN_HINT = (
    "pass column=K to read one column (0-based: column=0 is the first, "
    "column=-1 the last), or column=\"all\" to read every number row by row "
    "as one record written several values per line"
)


def _rectangular(rows: list[tuple[int, list[float]]], path: str) -> np.ndarray:
    """The rows as a 2-D array; every row must hold as many numbers as the first."""
    first_line, first = rows[0]
    k = len(first)
    for lineno, vals in rows:
        if len(vals) != k:
            raise RecordFormatError(
                f"{_fmt_where(path, lineno)}: expected {k} columns as on line "
                f"{first_line}, found {len(vals)}; if the file is one record "
                "written several values per line, pass column=\"all\""
            )
    return np.array([vals for _, vals in rows], dtype=np.float64)


def _time_column(t: np.ndarray) -> tuple[str, float, int]:
    """Classify a column as a time axis.

    Returns ``("uniform", dt, -1)``; ``("uneven", mean_dt, k)`` if it
    increases but step k (from row k to k + 1) is off the mean step by more
    than :data:`TIME_RTOL`; or ``("not", nan, k)`` if it does not increase
    from row k to k + 1.
    """
    steps = np.diff(t)
    down = np.flatnonzero(~(steps > 0.0))
    if down.size:
        return "not", float("nan"), int(down[0])
    mean = float((t[-1] - t[0]) / (t.size - 1))
    bad = np.flatnonzero(np.abs(steps - mean) > TIME_RTOL * mean)
    if bad.size:
        return "uneven", mean, int(bad[0])
    return "uniform", mean, -1


def _uneven_time_error(
    t: np.ndarray, k: int, mean: float, rows: list[tuple[int, list[float]]],
    path: str, col: str = "time column",
) -> RecordFormatError:
    step = float(t[k + 1] - t[k])
    return RecordFormatError(
        f"{_fmt_where(path, rows[k + 1][0])}: {col} is not uniformly spaced: "
        f"step {step:g} s from line {rows[k][0]} differs from the mean step "
        f"{mean:g} s by more than {TIME_RTOL:g} (relative)"
    )


def _column_index(column: int, k: int, path: str) -> int:
    if not -k <= column < k:
        raise ValueError(
            f"column={column!r} is out of range: the data rows of {path} hold {k} "
            f"number(s), so column must be 0..{k - 1} (0-based) or -{k}..-1"
        )
    return column % k


def _pick_column(
    rows: list[tuple[int, list[float]]], column: int, path: str,
    dt_given: float | None,
) -> tuple[np.ndarray, float | None]:
    """Column ``column`` of a table, and the step of its time column if any.

    Another column that increases uniformly is a time column; with several
    such columns of different steps, ``dt_given`` must pick one.  Column 0
    increasing unevenly is a non-uniform time axis and is refused.
    """
    table = _rectangular(rows, path)
    k = table.shape[1]
    j = _column_index(column, k, path)
    steps: dict[int, float] = {}
    if table.shape[0] >= 2:
        for c in range(k):
            if c == j:
                continue
            kind, mean, bad = _time_column(table[:, c])
            if kind == "uniform":
                steps[c] = mean
            elif kind == "uneven" and c == 0:
                raise _uneven_time_error(table[:, 0], bad, mean, rows, path,
                                         "time column (column 0)")
    distinct: list[float] = []
    for s in steps.values():
        if not any(math.isclose(s, d, rel_tol=TIME_RTOL) for d in distinct):
            distinct.append(s)
    if len(distinct) <= 1:
        return table[:, j], (distinct[0] if distinct else None)
    if dt_given is not None:
        for d in distinct:
            if math.isclose(dt_given, d, rel_tol=TIME_RTOL):
                return table[:, j], d
    desc = ", ".join(f"column {c} (step {s:g} s)" for c, s in steps.items())
    raise RecordFormatError(
        f"{_fmt_where(path, rows[0][0])}: several columns increase uniformly and "
        f"could be the time: {desc}; pass the time step as dt=..."
    )


def _parse_record_text(
    text: str, path: str, unit: str | None, dt: float | None,
    decimal: str = ".", column: int | str | None = None,
) -> tuple[np.ndarray, float, str, str]:
    """Parse a record file's text.

    Returns
    -------
    acc_file : numpy.ndarray
        Samples in the file's unit.
    dt : float
        Time step [s].
    unit : str
        Canonical unit of the file's samples.
    unit_origin : str
        Where the unit was stated (header line or ``unit=`` argument).
    """
    user_unit = canonical_unit(unit) if unit is not None else None
    dt_user = None
    if dt is not None:
        from fastrock import _validate as V
        dt_user = V.positive("dt", dt)
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
        # Otherwise the header is the leading lines that are not all-numeric
        # (with decimal=',' a '.' mark still counts as numeric here so that
        # the data reader can name it).
        hdr_end = len(lines)
        for i, line in enumerate(lines):
            if line.strip() and (
                _line_numbers(line, decimal) is not None
                or (decimal == "," and _line_numbers(line, ".") is not None)
            ):
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

    stated = _header_unit(header, path)
    file_unit = stated[0] if stated is not None else None
    if user_unit is not None and file_unit is not None and user_unit != file_unit:
        raise ValueError(
            f"{path}: unit={unit!r} contradicts the file header, which says {file_unit!r}"
        )
    if stated is not None:
        out_unit, origin = stated[0], f"stated in the file header, line {stated[1]}"
    else:
        out_unit, origin = user_unit, f"given as unit={unit!r}"

    if npts_line is not None:
        acc, file_dt = _parse_at2(lines, header, npts_line, hdr_end, path,
                                  decimal, column, dt_user)
    elif hdr_end == len(lines):
        raise RecordFormatError(
            f"{_fmt_where(path, len(header) + 1)}: no numeric data after "
            f"{len(header)} header line(s)"
        )
    else:
        acc, file_dt = _parse_columns(lines, hdr_end, path, decimal, column, dt_user)

    if dt_user is not None:
        if file_dt is not None and not math.isclose(dt_user, file_dt, rel_tol=TIME_RTOL):
            raise ValueError(
                f"{path}: dt={dt_user!r} contradicts the file, which gives dt={file_dt!r}"
            )
        if file_dt is None:
            file_dt = dt_user
    if file_dt is None:
        raise ValueError(
            f"{path}: data without NPTS/DT header or time column; the time step "
            "must be given (dt=..., or --record-dt on the command line)"
        )
    if out_unit is None:
        raise ValueError(
            f"{path}: the file header does not state the acceleration unit; the "
            f"unit must be given (unit=... or --unit, one of {', '.join(UNITS)})"
        )
    return acc, file_dt, out_unit, origin


def _at2_dt(
    line: str, header: list[str], lineno: int, path: str, decimal: str
) -> tuple[int, float]:
    """NPTS and DT from the NPTS header line (DT possibly on another line)."""
    if decimal == ",":
        line = re.sub(r"(\d),(\d)", r"\1.\2", line)
        header = [re.sub(r"(\d),(\d)", r"\1.\2", h) for h in header]
    m = _NPTS_DT_RE.search(line) or _NUMBERS_FIRST_RE.search(line)
    if m is not None:
        npts, dt_txt, dt_line, dt_end = int(m.group(1)), m.group(2), line, m.end(2)
    else:
        nm = re.search(r"NPTS\s*[=:]?\s*(\d+)", line, re.IGNORECASE)
        if nm is None:
            raise RecordFormatError(
                f"{_fmt_where(path, lineno)}: cannot read the number of points "
                f"from {line.strip()!r}"
            )
        npts = int(nm.group(1))
        dm, dt_line = _DT_ALONE_RE.search(line), line
        if dm is None:  # DT on another header line
            for other in header:
                dm, dt_line = _DT_ALONE_RE.search(other), other
                if dm is not None:
                    break
        if dm is None:
            raise RecordFormatError(
                f"{_fmt_where(path, lineno)}: missing DT (time step) in header "
                f"line {line.strip()!r}"
            )
        dt_txt, dt_end = dm.group(1), dm.end(1)
    if decimal == "." and re.match(r",\d", dt_line[dt_end:]):
        raise RecordFormatError(
            f"{_fmt_where(path, lineno)}: DT {dt_txt + dt_line[dt_end:].split()[0]!r} "
            "looks like a number with a decimal comma; pass decimal=',' if commas "
            "are decimal marks"
        )
    dt = float(dt_txt.replace("D", "E").replace("d", "e"))
    if not (math.isfinite(dt) and dt > 0.0):
        raise RecordFormatError(f"{_fmt_where(path, lineno)}: DT must be > 0, got {dt_txt}")
    if npts < 2:
        raise RecordFormatError(
            f"{_fmt_where(path, lineno)}: NPTS must be >= 2, got {npts}"
        )
    return npts, dt


def _parse_at2(
    lines: list[str], header: list[str], npts_line: int, hdr_end: int, path: str,
    decimal: str, column: int | str | None, dt_given: float | None,
) -> tuple[np.ndarray, float]:
    """AT2 body: all numbers row by row ("read horizontally"), or one column."""
    lineno = npts_line + 1
    npts, dt = _at2_dt(header[npts_line], header, lineno, path, decimal)

    rows = _collect_rows(lines, hdr_end, path, decimal)
    if not rows:
        raise RecordFormatError(
            f"{_fmt_where(path, hdr_end + 1)}: no data after the header "
            f"(NPTS={npts} on line {lineno})"
        )
    if isinstance(column, int):
        # A table after an NPTS/DT header: one sample per row.
        acc, col_dt = _pick_column(rows, column, path, dt)
        if col_dt is not None and not math.isclose(col_dt, dt, rel_tol=TIME_RTOL):
            raise RecordFormatError(
                f"{_fmt_where(path, rows[0][0])}: the time column gives dt={col_dt:g} "
                f"s but DT={dt:g} s on line {lineno}"
            )
        if acc.size != npts:
            raise RecordFormatError(
                f"{_fmt_where(path, rows[-1][0])}: {acc.size} data rows but "
                f"NPTS={npts} (line {lineno}); with column={column} each row is "
                "one sample"
            )
        return acc, dt

    values: list[float] = []
    where: list[int] = []
    for ln, vals in rows:
        values.extend(vals)
        where.extend([ln] * len(vals))
    if len(values) > npts:
        hint = ""
        k = len(rows[0][1])
        if k > 1 and len(rows) == npts and all(len(v) == k for _, v in rows):
            hint = (
                f"; each of the {npts} rows holds {k} numbers: if the file is a "
                "table with one sample per row, pass column=K (0-based index of "
                "the acceleration column)"
            )
        raise RecordFormatError(
            f"{_fmt_where(path, where[npts])}: more values than NPTS={npts} "
            f"(line {lineno}); found {len(values)} in total{hint}"
        )
    if len(values) < npts:
        raise RecordFormatError(
            f"{_fmt_where(path, where[-1])}: data end after {len(values)} values "
            f"but NPTS={npts} (line {lineno})"
        )
    return np.asarray(values, dtype=np.float64), dt


def _parse_columns(
    lines: list[str], hdr_end: int, path: str, decimal: str,
    column: int | str | None, dt_given: float | None,
) -> tuple[np.ndarray, float | None]:
    """Data without NPTS header: one column, time/acc pairs, or as ``column`` says."""
    rows = _collect_rows(lines, hdr_end, path, decimal)
    if column == "all":
        acc = np.asarray([v for _, vals in rows for v in vals], dtype=np.float64)
        file_dt = None
    elif column is not None:
        acc, file_dt = _pick_column(rows, column, path, dt_given)
    else:
        table = _rectangular(rows, path)
        k = table.shape[1]
        first = rows[0][0]
        if k == 1:
            acc, file_dt = table[:, 0], None
        elif k == 2 and table.shape[0] >= 2:
            t = table[:, 0]
            kind, mean, bad = _time_column(t)
            if kind == "uneven":
                raise _uneven_time_error(t, bad, mean, rows, path)
            if kind == "not":
                raise RecordFormatError(
                    f"{_fmt_where(path, first)}: each data row holds 2 numbers but "
                    "the first column is not an increasing time column (it does not "
                    f"increase from line {rows[bad][0]} to line {rows[bad + 1][0]}); "
                    + _COLUMN_HINT
                )
            acc, file_dt = table[:, 1], mean
        else:
            raise RecordFormatError(
                f"{_fmt_where(path, first)}: each data row holds {k} numbers, so "
                "which one is the acceleration is not known; " + _COLUMN_HINT
            )
    if acc.size < 2:
        raise RecordFormatError(
            f"{_fmt_where(path, rows[-1][0])}: need at least 2 samples, found {acc.size}"
        )
    return acc, file_dt


def _check_arguments(decimal: Any, column: Any) -> int | str | None:
    """Validate ``decimal`` and ``column``; return ``column`` as int, 'all' or None."""
    if not isinstance(decimal, str) or decimal not in (".", ","):
        raise ValueError(f"decimal must be '.' or ',', got {decimal!r}")
    if column is None or (isinstance(column, str) and column == "all"):
        return column
    if isinstance(column, bool) or not isinstance(column, numbers.Integral):
        raise ValueError(
            "column must be an int (0-based column index, negative counts from "
            f"the last column), 'all' or None, got {column!r}"
        )
    return int(column)


def _implausible_pga(pga_g: float, unit: str, origin: str, path: str) -> str | None:
    """Warning text if ``pga_g`` is outside :data:`PGA_PLAUSIBLE_G`, else None."""
    lo, hi = PGA_PLAUSIBLE_G
    if lo <= pga_g <= hi:
        return None
    head = (
        f"{path}: PGA = {pga_g:.3g} g with the samples read in {unit!r} ({origin}), "
        f"outside the plausible range {lo:g} g to {hi:g} g"
    )
    if pga_g == 0.0:
        return head + "; every sample is zero"
    alternatives = []
    for other, factor in UNITS.items():
        if other == unit:
            continue
        ratio = factor / UNITS[unit]
        alt = pga_g * ratio
        if lo <= alt <= hi:
            text = f"{ratio:.6g}" if ratio >= 1.0 else f"1/{1.0 / ratio:.6g}"
            alternatives.append(
                f"if the samples are in {other} (factor {text}), PGA = {alt:.3g} g"
            )
    if not alternatives:
        return head + f"; no other unit ({', '.join(u for u in UNITS if u != unit)}) " \
            "makes it plausible"
    return head + "; " + "; ".join(alternatives)


def read_record(
    path: str | os.PathLike,
    unit: str | None = None,
    dt: float | None = None,
    name: str | None = None,
    *,
    column: int | str | None = None,
    decimal: str = ".",
) -> GroundMotion:
    """Read an accelerogram file.

    The format is detected from the content:

    * a header line with ``NPTS=.., DT=..`` (any case, optional trailing
      comma or ``SEC``) or ``<npts> <dt> NPTS, DT``: PEER AT2 style; all
      numbers after the header are the samples, read row by row with any
      number per row, and their count must equal NPTS;
    * otherwise, data rows of one number: the samples; ``dt`` must be given;
    * otherwise, data rows of two numbers whose first column increases:
      ``time acceleration``; the time step is the mean step and every step
      must agree with it to ``TIME_RTOL`` (relative); the first sample is put
      at t = 0.

    Anything else that could be read in more than one way is refused with a
    :class:`RecordFormatError` rather than guessed: rows of 3 or more
    numbers, rows of 2 numbers whose first column is not a time column, rows
    of unequal length (unless ``column`` says how to read them), and decimal
    commas (unless ``decimal=","``).

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
        Time step [s].  Required if the file has neither an NPTS/DT header
        nor a time column; must agree with the file otherwise.
    name : str, optional
        Record name; defaults to the file name without extension.
    column : int or "all", optional, keyword-only
        How to read rows of several numbers.  An int picks that column as the
        acceleration, **0-based** (``column=0`` is the first column,
        ``column=1`` the second); negative values count from the last column
        as in Python (``column=-1`` is the last).  Every row must then hold
        the same number of values; if another column increases uniformly it
        is the time column and gives ``dt`` (which must agree with ``dt=``
        and with an NPTS/DT header).  ``"all"`` reads every number row by
        row as one record (a record written several values per line without
        an NPTS header; this is what AT2 files always do).  ``None`` (the
        default) reads only the unambiguous layouts listed above.
    decimal : {".", ","}, optional, keyword-only
        Decimal mark.  With ``"."`` (default) whitespace, commas and
        semicolons separate values, and a comma between digits in data that
        hold no '.' decimal mark (``0,12345``) is refused as a decimal comma.
        With ``","`` commas are decimal marks, only whitespace and semicolons
        separate values, and a '.' decimal mark in the data is refused.

    Returns
    -------
    GroundMotion
        Acceleration converted to m/s².

    Warns
    -----
    RecordUnitWarning
        If the PGA in the stated unit is outside :data:`PGA_PLAUSIBLE_G`
        (1e-4 g to 5 g); the message names every other unit that would make
        it plausible and its factor.

    Raises
    ------
    RecordFormatError
        Malformed or ambiguous file (message gives path and line number):
        value count different from NPTS, NaN/inf or non-numeric token,
        non-uniform time column, no data, missing DT, DT <= 0, decimal
        commas without ``decimal=","``, '.' marks with ``decimal=","``,
        several numbers per row without ``column=``, rows of unequal length.
    ValueError
        Unknown, missing or contradictory ``unit``; missing or contradictory
        ``dt``; ``decimal`` not '.' or ','; ``column`` not an int, "all" or
        None, or out of range for the file's rows.
    """
    column = _check_arguments(decimal, column)
    if not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"path must be a file path (str or os.PathLike), got {path!r}")
    if name is not None and not isinstance(name, str):
        raise ValueError(f"name must be a string, got {name!r}")
    p = Path(path)
    raw = p.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")  # old headers with degree signs etc.
    acc, file_dt, file_unit, origin = _parse_record_text(
        text, str(p), unit, dt, decimal=decimal, column=column
    )
    gm = GroundMotion(
        acc * UNITS[file_unit],
        file_dt,
        name=p.stem if name is None else name,
        unit_in_file=file_unit,
        source=str(p),
    )
    msg = _implausible_pga(gm.pga_g, file_unit, origin, str(p))
    if msg is not None:
        warnings.warn(msg, RecordUnitWarning, stacklevel=2)
    return gm


