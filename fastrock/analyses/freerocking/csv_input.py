"""Half-cycle durations from CSV files, and fits of them.
"""
from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd

from fastrock.analyses.freerocking.fitting import DefinitionWarning, FreeRockingFit, fit_free_rocking
from fastrock.analyses.freerocking.housner import HALF_CYCLE_DEFINITIONS


# ----------------------------------------------------------------------------------------
# CSV input
# ----------------------------------------------------------------------------------------
_NUMERIC_COLUMNS = ("half_cycle", "duration", "peak", "peak_deg", "theta0_deg", "alpha_deg")


def read_half_cycles_csv(path) -> pd.DataFrame:
    """Read measured half-cycles from a CSV file.

    Accepted columns (header required, ``#`` starts a comment line):

    ============= ====== ====================================================================
    duration      s      required, > 0
    half_cycle    -      optional integer index >= 0 (definition as in :func:`half_cycles`);
                         unique within a ``theta0_deg`` group
    peak          rad    optional peak angle of the half-cycle (sign ignored by the fit)
    peak_deg      deg    optional, alternative to ``peak`` (converted to ``peak`` in rad)
    theta0_deg    deg    optional release angle; several values = several release tests
    alpha_deg     deg    optional slenderness (must be a single value)
    definition    -      optional, "impact" or "peak" (must be a single value)
    ============= ====== ====================================================================

    Other columns are kept unchanged. Empty cells are allowed only in ``peak``/``peak_deg``.
    The half-cycle definition of the data may also be stated by a comment line
    ``# definition: impact`` (or ``peak``); it is returned in ``df.attrs["definition"]``
    (None when the file does not say) and used by :func:`fit_from_csv`.

    Parameters
    ----------
    path : str or os.PathLike
        CSV file.

    Returns
    -------
    pandas.DataFrame
        The validated table, numeric columns as float (``half_cycle`` as int), sorted by
        ``theta0_deg`` (if present) and ``half_cycle`` (if present).

    Raises
    ------
    ValueError
        Naming the file, the column and the row (1-based data row; line = row + 1 counting
        the header) for a missing ``duration`` column, non-numeric, non-finite or
        negative/zero values, non-integer or duplicate ``half_cycle``, or an unreadable file.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: malformed CSV (not text: {exc})") from exc
    stated = set()
    for line in text.splitlines():
        m = re.match(r"\s*#\s*definition\s*[:=]\s*(\S+)", line, re.IGNORECASE)
        if m:
            stated.add(m.group(1).strip().strip("'\"").lower())
    # ragged rows: pandas would silently turn extra fields into an index
    rows = [r for r in csv.reader(line for line in text.splitlines()
                                  if line.strip() and not line.lstrip().startswith("#"))]
    if rows:
        for i, r in enumerate(rows[1:], start=1):
            if len(r) != len(rows[0]):
                raise ValueError(f"{path}: malformed CSV: row {i} has {len(r)} fields, the "
                                 f"header has {len(rows[0])}")
    try:
        raw = pd.read_csv(io.StringIO(text), dtype=str, comment="#", skipinitialspace=True,
                          keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise ValueError(f"{path}: malformed CSV ({exc})") from exc
    raw.columns = [str(c).strip() for c in raw.columns]
    if "duration" not in raw.columns:
        raise ValueError(f"{path}: missing required column 'duration' "
                         f"(columns found: {list(raw.columns)})")
    if len(raw) == 0:
        raise ValueError(f"{path}: no data rows")
    if "peak" in raw.columns and "peak_deg" in raw.columns:
        raise ValueError(f"{path}: give either column 'peak' (rad) or 'peak_deg', not both")
    df = raw.copy()
    for col in _NUMERIC_COLUMNS:
        if col not in raw.columns:
            continue
        s = raw[col].astype(str).str.strip()
        empty = s == ""
        vals = pd.to_numeric(s.where(~empty, None), errors="coerce").astype(float)
        bad = (vals.isna() & ~empty) | np.isinf(vals)
        if col not in ("peak", "peak_deg"):
            bad |= empty
        if bad.any():
            i = int(np.flatnonzero(bad.to_numpy())[0])
            raise ValueError(f"{path}: column '{col}', row {i + 1}: value {raw[col].iloc[i]!r} "
                             f"is not a finite number")
        if col == "duration" and (vals <= 0).any():
            i = int(np.flatnonzero((vals <= 0).to_numpy())[0])
            raise ValueError(f"{path}: column 'duration', row {i + 1}: duration must be > 0 s; "
                             f"got {vals.iloc[i]!r}")
        if col == "half_cycle":
            nonint = (vals != np.round(vals)) | (vals < 0)
            if nonint.any():
                i = int(np.flatnonzero(nonint.to_numpy())[0])
                raise ValueError(f"{path}: column 'half_cycle', row {i + 1}: must be an integer "
                                 f">= 0; got {raw[col].iloc[i]!r}")
        if col in ("theta0_deg", "alpha_deg") and (vals <= 0).any():
            i = int(np.flatnonzero((vals <= 0).to_numpy())[0])
            raise ValueError(f"{path}: column '{col}', row {i + 1}: must be > 0; "
                             f"got {vals.iloc[i]!r}")
        df[col] = vals
    if "half_cycle" in df.columns:
        df["half_cycle"] = df["half_cycle"].astype(int)
        keys = ["theta0_deg", "half_cycle"] if "theta0_deg" in df.columns else ["half_cycle"]
        dup = df.duplicated(keys)
        if dup.any():
            i = int(np.flatnonzero(dup.to_numpy())[0])
            raise ValueError(f"{path}: column 'half_cycle', row {i + 1}: duplicate half-cycle "
                             f"{df['half_cycle'].iloc[i]} within its group")
    if "alpha_deg" in df.columns and df["alpha_deg"].nunique() > 1:
        raise ValueError(f"{path}: column 'alpha_deg' must hold a single value; got "
                         f"{sorted(df['alpha_deg'].unique())}")
    if "peak_deg" in df.columns:
        df["peak"] = np.radians(df["peak_deg"])
    sort = [c for c in ("theta0_deg", "half_cycle") if c in df.columns]
    if sort:
        df = df.sort_values(sort, kind="stable").reset_index(drop=True)
    if "definition" in df.columns:
        stated |= set(df.pop("definition").astype(str).str.strip().str.lower())
    bad = stated - set(HALF_CYCLE_DEFINITIONS)
    if bad or len(stated) > 1:
        raise ValueError(f"{path}: definition must be one of {HALF_CYCLE_DEFINITIONS} and a single value, "
                         f"got {sorted(stated)}")
    df.attrs["definition"] = stated.pop() if stated else None
    return df


def _fit_table(df: pd.DataFrame, theta0=None, alpha=None, model="housner", source="data",
               **options) -> FreeRockingFit:
    """Fit a table as returned by :func:`read_half_cycles_csv` (groups by ``theta0_deg``)."""
    if alpha is None:
        if "alpha_deg" not in df.columns:
            raise ValueError(f"{source}: alpha not given and no 'alpha_deg' column")
        alpha = math.radians(float(df["alpha_deg"].iloc[0]))
    if "theta0_deg" in df.columns:
        if theta0 is not None:
            t0deg = math.degrees(float(theta0))
            sel = np.isclose(df["theta0_deg"].to_numpy(), t0deg, rtol=0, atol=1e-6)
            if not sel.any():
                raise ValueError(f"{source}: no group with theta0_deg = {t0deg:g}; available: "
                                 f"{sorted(df['theta0_deg'].unique())}")
            df = df[sel]
        groups = [g for _, g in df.groupby("theta0_deg", sort=True)]
        t0s = [math.radians(float(g["theta0_deg"].iloc[0])) for g in groups]
    else:
        if theta0 is None:
            raise ValueError(f"{source}: theta0 not given and no 'theta0_deg' column")
        groups = [df]
        t0s = [float(theta0)]
    stated = df.attrs.get("definition")
    given = options.pop("definition", None)
    if given is not None and stated is not None and given != stated:
        import warnings
        warnings.warn(f"{source}: the file states half-cycles '{stated}' to '{stated}'; the given "
                      f"definition {given!r} overrides it", DefinitionWarning, stacklevel=3)
    options["definition"] = given or stated
    durs = [g["duration"].to_numpy(float) for g in groups]
    hcs = ([g["half_cycle"].to_numpy(int) for g in groups]
           if "half_cycle" in df.columns else None)
    pks = [g["peak"].to_numpy(float) for g in groups] if "peak" in df.columns else None
    return fit_free_rocking(durs, t0s, alpha, peaks=pks, model=model, half_cycle=hcs,
                            **options)


def fit_from_csv(path, theta0=None, alpha=None, model="housner", **options) -> FreeRockingFit:
    """Read a half-cycle CSV (:func:`read_half_cycles_csv`) and fit it.

    Parameters
    ----------
    path : str or os.PathLike
        CSV file.
    theta0 : float, optional
        Release angle [rad]. If the file has a ``theta0_deg`` column, selects that group
        (default: joint fit of all groups with shared parameters); otherwise required.
    alpha : float, optional
        Slenderness [rad]; default from the ``alpha_deg`` column.
    model : str
        See :func:`fit_free_rocking`.
    **options
        Passed to :func:`fit_free_rocking` (``definition``, ``min_duration``, ``predictor``...).

    Returns
    -------
    FreeRockingFit
    """
    df = read_half_cycles_csv(path)
    return _fit_table(df, theta0=theta0, alpha=alpha, model=model, source=str(path),
                      **options)


