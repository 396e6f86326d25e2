"""Rocking spectrum definitions: the minimum stable slenderness on a grid,
beta and its bound, and rocking_spectrum itself.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from fastrock.model.bodies import RigidBlock
from fastrock.analyses.rocking_spectrum.engine import STABLE_OUTCOMES, T_AFTER, rocking_spectrum_runs


#: Upper-bound curve beta = A exp(-B Tp/Tm) (Maiorano et al., two-sided rocking).
UPPER_BOUND_A = 1.35

UPPER_BOUND_B = 0.12

SPECTRUM_COLUMNS = """\
record                   record name
wall                     wall setting label ("two-sided", "wall d=0.01 m" ...)
wall_gap                 clear gap d to the rear wall [m] (NaN: two-sided)
pga_g                    PGA / g                                           [-]
mean_period              Tm, mean period (Rathje et al. 1998)             [s]
b                        half-width of the block                          [m]
slenderness_min          (b/h)_min on the grid (see beta_bound)           [-]
h_min                    half-height b / (b/h)_min                         [m]
alpha_min                atan((b/h)_min)                                 [rad]
p                        frequency parameter of the block at (b/h)_min [rad/s]
Tp                       2 pi / p                                          [s]
tp_over_tm               Tp / Tm                                           [-]
beta                     (b/h)_min * g / PGA                               [-]
beta_bound               exact | upper | lower | incomplete
non_monotone             a slenderness above the first stable one is not stable
slenderness_first_stable smallest stable grid slenderness (NaN: none)      [-]
n_slenderness            grid points of the size
n_stable, n_overturned, n_leaning, n_failed   run counts of the size
"""


# ------------------------------------------------------------- definitions
@dataclass(frozen=True)
class GridThreshold:
    """Minimum stable slenderness read off one ascending grid.

    Attributes
    ----------
    index : int
        Index of ``(b/h)_min`` in the grid: the smallest k with every
        ``s_j, j >= k`` stable; ``n - 1`` (the last point) when ``bound`` is
        "lower".
    bound : str
        "exact" | "upper" | "lower" (module docstring).
    non_monotone : bool
        A grid point above the first stable one is not stable.
    first_stable : int
        Index of the first stable grid point, -1 if none.
    """

    index: int
    bound: str
    non_monotone: bool
    first_stable: int


def minimum_stable_on_grid(stable):
    """Apply the definition of ``(b/h)_min`` to stability flags on an
    ascending slenderness grid.

    Parameters
    ----------
    stable : sequence of bool
        ``stable[j]`` for slenderness ``s_j``, ``s_0 < s_1 < ...``.

    Returns
    -------
    GridThreshold
    """
    st = np.asarray(stable, bool)
    if st.ndim != 1 or st.size == 0:
        raise ValueError("stable must be a non-empty 1-D sequence")
    n = st.size
    first = int(np.argmax(st)) if st.any() else -1
    if st.all():
        return GridThreshold(0, "upper", False, 0)
    last_unstable = int(np.flatnonzero(~st)[-1])
    non_monotone = bool(st[:last_unstable].any())
    if last_unstable == n - 1:
        return GridThreshold(n - 1, "lower", non_monotone, first)
    return GridThreshold(last_unstable + 1, "exact", non_monotone, first)


def upper_bound_beta(tp_over_tm):
    """Maiorano et al.'s upper bound for two-sided rocking,
    ``beta = 1.35 exp(-0.12 Tp/Tm)``.

    Parameters
    ----------
    tp_over_tm : float or array
        Tp / Tm [-].
    """
    return UPPER_BOUND_A * np.exp(-UPPER_BOUND_B * np.asarray(tp_over_tm, float))


def summarize_runs(runs):
    """The rocking-spectrum table (``SPECTRUM_COLUMNS``) from a per-run table
    (:func:`rocking_spectrum_runs`), one row per record x wall x size."""
    rows = []
    for (rec, wall, b), grp in runs.groupby(["record", "wall", "b"], sort=False):
        grp = grp.sort_values("slenderness")
        s = grp["slenderness"].to_numpy()
        out = grp["outcome"].to_numpy()
        first = grp.iloc[0]
        pga_g = float(first["pga_g"])
        Tm = float(first["mean_period"])
        row = {"record": rec, "wall": wall, "wall_gap": first["wall_gap"], "pga_g": pga_g,
               "mean_period": Tm, "b": b}
        if (out == "unfinished").any():
            thr = None
            s_min = math.nan
            bound = "incomplete"
        else:
            thr = minimum_stable_on_grid(grp["stable"].to_numpy())
            s_min = float(s[thr.index])
            bound = thr.bound
        # the run's own block at (b/h)_min (a shape's body); a table without p holds rectangles
        if math.isnan(s_min):
            p = math.nan
        elif "p" in grp:
            p = float(grp["p"].to_numpy()[thr.index])
        else:
            p = RigidBlock.rectangle(b, b / s_min).p
        Tp = 2 * math.pi / p
        row.update({
            "slenderness_min": s_min, "h_min": b / s_min, "alpha_min": math.atan(s_min),
            "p": p, "Tp": Tp, "tp_over_tm": Tp / Tm, "beta": s_min / pga_g,
            "beta_bound": bound,
            "non_monotone": bool(thr.non_monotone) if thr is not None else False,
            "slenderness_first_stable": (float(s[thr.first_stable]) if thr is not None
                                         and thr.first_stable >= 0 else math.nan),
            "n_slenderness": int(s.size),
            "n_stable": int(grp["stable"].sum()),
            "n_overturned": int(np.isin(out, ("mode1", "mode2")).sum()),
            "n_leaning": int((out == "leaning").sum()),
            "n_failed": int(((out == "failed") | (out == "flight")).sum()),
        })
        rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs.update(runs.attrs)
    return df


def rocking_spectrum(records, slenderness=None, half_widths=None, walls=None, *, e=None,
                     unit=None, solver=None, rtol=None, atol=None, dt=None,
                     record_breakpoints=None, t_after=T_AFTER, early_exit=True,
                     stable_outcomes=STABLE_OUTCOMES, progress=True, chunk_size=None,
                     return_runs=False, ground=None, shape=None):
    """Rocking spectrum (beta against Tp/Tm) of records, in parallel.

    Every record x wall setting x half-width x slenderness block runs in
    one parallel sweep per kernel (two-sided; one-sided), with the records'
    samples concatenated in one array.  See the module docstring for the
    exact definitions of stable, ``(b/h)_min``, ``beta`` and its bounds.

    Parameters
    ----------
    records : GroundMotion, path, or a sequence of them
        None: the packaged El Centro record.
    slenderness : array, optional
        Grid of b/h [-] (default 20 values in [0.1, 0.5]).
    half_widths : array, optional
        Half-widths b [m] (default 20 values in [0.1, 1]); the block is
        ``RigidBlock.rectangle(b, h=b/(b/h))``.
    walls : sequence, optional
        Wall settings: None (two-sided), a :class:`fastrock.Wall`, a gap [m]
        or "two-sided".  Default ``(None, Wall(0.01), Wall(0.10))`` when
        the wall model is installed, else ``(None,)``.
    e : float, optional
        Restitution of every block (default Housner's, per block).
    unit : str, optional
        Unit of record files whose header does not state it.
    solver, rtol, atol, dt, record_breakpoints :
        Integrator settings (:class:`fastrock.Solver`).
    t_after : float
        Free rocking after the end of each record [s] (default 10).
    early_exit : bool
        Stop a run once its outcome is decided (default True).  On records
        the shaking itself dominates the cost, so this saves only a few per
        cent; a "safe:bounded" decision that leaves the block past alpha
        would be rerun to the end (defensive check).
    stable_outcomes : tuple of str
        Outcomes counted as stable (default ``("safe",)``).
    progress : bool
        Progress bar; Ctrl-C keeps finished runs (cells with unfinished
        runs get ``beta_bound = "incomplete"``).
    return_runs : bool
        Also return the per-run table (``RUN_COLUMNS``).
    ground : Ground, optional
        Sloping ground under every block (None: level): the records act as
        the ground says (horizontally by default), the early decisions are
        off, and every block of the grid must stand on the slope
        (tan(alpha) > tan(slope); an error naming ``slope`` otherwise).
    shape : array (n, 2) or path, optional
        A body outline [m] (vertices, or an outline file) instead of
        rectangles: each grid cell runs the outline stretched so that its
        mean half base width is ``b`` and tan(alpha) of its slenderer side is
        the grid's slenderness (``fastrock.analyses.rocking_spectrum.inputs.shape_family``;
        asymmetric outlines run the asymmetric rigid-body model, and as
        walls accept them).

    Returns
    -------
    DataFrame (columns in ``SPECTRUM_COLUMNS``), or (table, runs).
    """
    runs = rocking_spectrum_runs(records, slenderness, half_widths, walls, e=e, unit=unit,
                                 solver=solver, rtol=rtol, atol=atol, dt=dt,
                                 record_breakpoints=record_breakpoints, t_after=t_after,
                                 early_exit=early_exit, stable_outcomes=stable_outcomes,
                                 progress=progress, chunk_size=chunk_size, ground=ground, shape=shape)
    table = summarize_runs(runs)
    return (table, runs) if return_runs else table


