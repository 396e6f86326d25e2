"""Rocking spectrum of recorded earthquakes: beta against Tp/Tm.

For every record, every block size (half-width ``b``) and every wall
setting, the blocks of a grid of slenderness values ``b/h`` are run under
the record, and the minimum stable slenderness ``(b/h)_min`` of that size is
read off the grid (Mennitti et al. 2021, after Maiorano et al.).  It is
reported as

    beta = (b/h)_min * g / PGA          against          Tp / Tm,

where ``Tp = 2 pi / p`` is the period parameter of the block at
``(b, (b/h)_min)`` and ``Tm`` the record's mean period (Rathje et al. 1998).
``beta = 1`` is the pseudo-static rule ``b/h >= PGA/g`` (a block that
satisfies it never uplifts); ``beta < 1`` means the dynamic analysis needs a
smaller base than that rule.

Definitions (the same in the table, the plot and the README)
------------------------------------------------------------
* **Stable**: the run's outcome is in ``stable_outcomes`` (default only
  ``"safe"``: never uplifted, came back to rest, or proven unable to
  overturn).  "leaning" (resting against a wall) is *not* stable by default
  and is counted apart in ``n_leaning``; "failed" runs are not stable and are
  counted in ``n_failed``.
* **(b/h)_min on a grid** ``s_1 < ... < s_n``: the smallest grid value
  ``s_k`` such that every block with ``s_j >= s_k`` is stable ("stable from
  there up").  This is the threshold a designer can use; it is
  conservative when stability is not monotone.
* ``beta_bound``:

  - ``"exact"``: ``s_{k-1}`` is unstable and ``s_k..s_n`` are stable, so the
    true threshold lies in ``(s_{k-1}, s_k]``; ``beta`` is exact to the grid
    resolution.
  - ``"upper"``: every block of the grid is stable, so the true
    ``(b/h)_min <= s_1``; ``slenderness_min = s_1`` and ``beta`` are upper
    bounds.
  - ``"lower"``: the stoutest block ``s_n`` is not stable, so
    ``(b/h)_min > s_n``; ``slenderness_min = s_n`` and ``beta`` are (strict)
    lower bounds.
  - ``"incomplete"``: some runs of the cell did not finish (Ctrl-C);
    ``beta`` is NaN.

  ``beta = slenderness_min * g / PGA`` holds in every row (except
  "incomplete"), and ``Tp`` is always that of the block at
  ``slenderness_min``.
* ``non_monotone``: some grid slenderness above the first stable one is not
  stable (a block survives at one b/h and falls at a larger one).  Then
  ``slenderness_first_stable < slenderness_min``.

References
----------
Mennitti, Maiorano, Aversa (2021), rocking of rigid blocks with a rear wall.
Rathje, Abrahamson, Bray (1998), J. Geotech. Geoenviron. Eng. 124(2):150-159,
doi:10.1061/(ASCE)1090-0241(1998)124:2(150).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from . import _validate as V
from . import models
from .bodies import RigidBlock
from .outcomes import outcome_of, status_of, warn_unstable
from .records import GroundMotion, load_default_record, read_record
from .solver import DEFAULT_T_AFTER, make_solver
from .sweep import run_sweep
from fastrock.kernels import layout as L

__all__ = [
    "DEFAULT_SLENDERNESS", "DEFAULT_HALF_WIDTHS", "DEFAULT_WALL_GAPS", "GridThreshold",
    "MinimumStableSlenderness", "RUN_COLUMNS", "SPECTRUM_COLUMNS", "add_subcommands",
    "default_walls", "load_records", "minimum_stable_on_grid", "minimum_stable_slenderness",
    "plot_rocking_spectrum", "rocking_spectrum", "rocking_spectrum_runs", "simulate_record",
    "summarize_runs", "upper_bound_beta",
]

#: Mennitti et al.'s grid: 20 slenderness values b/h in [0.1, 0.5] ...
DEFAULT_SLENDERNESS = np.linspace(0.1, 0.5, 20)
#: ... times 20 half-widths b [m] in [0.1, 1].
DEFAULT_HALF_WIDTHS = np.linspace(0.1, 1.0, 20)
#: Clear gaps [m] of the one-sided settings (besides two-sided rocking).
DEFAULT_WALL_GAPS = (0.01, 0.10)
#: Outcomes that count as "stable".
STABLE_OUTCOMES = ("safe",)
#: Upper-bound curve beta = A exp(-B Tp/Tm) (Maiorano et al., two-sided rocking).
UPPER_BOUND_A = 1.35
UPPER_BOUND_B = 0.12
#: Free rocking after the end of the record [s]; with early_exit most runs
#: stop sooner (free-rocking energy below the overturning barrier).
T_AFTER = DEFAULT_T_AFTER

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

RUN_COLUMNS = """\
record, wall, wall_gap [m], pga_g [-], mean_period [s], b [m], slenderness b/h [-],
h [m], alpha [rad], p [rad/s], e [-], outcome, status, stable (bool),
max_rotation_ratio max|theta|/alpha [-], impacts, wall_impacts, time_uplift [s],
time_overturn [s], time_end [s], nfev, steps, rejected_steps
"""


# ------------------------------------------------------------------ inputs
def default_walls():
    """``(None, Wall(0.01), Wall(0.10))`` if the wall model is installed,
    else ``(None,)`` (two-sided rocking only)."""
    try:
        from .wall import Wall
        import fastrock.kernels.wall  # noqa: F401  (the kernel must exist too)
    except ImportError:
        return (None,)
    return (None,) + tuple(Wall(gap=d) for d in DEFAULT_WALL_GAPS)


def _wall_label(wall):
    if wall is None:
        return "two-sided"
    label = f"wall d={wall.gap:g} m"
    side = getattr(wall, "side", -1)
    if side != -1:
        label += f" side {side:+d}"
    return label


def _wall_gap(wall):
    return math.nan if wall is None else float(wall.gap)


def _as_walls(walls):
    if walls is None:
        return default_walls()
    if not isinstance(walls, (list, tuple)):
        walls = (walls,)
    out = []
    for w in walls:
        if isinstance(w, str):
            w = _parse_wall(w)
        elif isinstance(w, (int, float)) and not isinstance(w, bool):
            w = _make_wall(float(w))
        elif w is not None and not isinstance(w, _wall_class()):
            raise ValueError(f"walls: a wall setting must be None (two-sided), a fastrock.Wall, a gap in m "
                             f"or 'two-sided', got {w!r}")
        out.append(w)
    if not out:
        raise ValueError("walls must hold at least one setting (None = two-sided)")
    labels = [_wall_label(w) for w in out]
    if len(set(labels)) != len(labels):
        raise ValueError(f"walls must be distinct settings, got {labels}")
    return tuple(out)


def _wall_class():
    try:
        from .wall import Wall
    except ImportError:
        return ()
    return Wall


def _make_wall(gap):
    try:
        from .wall import Wall
    except ImportError:
        raise ValueError("wall settings need fastrock.wall, which is not installed; "
                         "use walls=(None,) for two-sided rocking") from None
    return Wall(gap=gap)


def _parse_wall(text):
    t = text.strip().lower()
    if t in ("two-sided", "twosided", "none", "free", ""):
        return None
    try:
        gap = float(t)
    except ValueError:
        raise ValueError(f"walls: a wall setting must be 'two-sided' or a gap in m, got {text!r}") from None
    return _make_wall(gap)


def parse_walls(text):
    """``"two-sided,0.01,0.10"`` -> ``(None, Wall(0.01), Wall(0.10))``."""
    return _as_walls([w for w in text.split(",")])


def _read_one(path, unit=None, dt=None, **layout):
    """read_record, with ``unit``/``dt`` used only where the file does not
    state them (so one --unit serves a mixed set of files); ``layout``
    (``column=``, ``decimal=``) applies to every file."""
    layout = {k: v for k, v in layout.items() if v is not None}
    try:
        return read_record(path, **layout)
    except ValueError as exc:
        if unit is None and dt is None:
            raise
        first = exc
    tries = [kw for kw in ({"unit": unit, "dt": dt}, {"unit": unit}, {"dt": dt})
             if all(v is not None for v in kw.values())]
    for kw in tries:
        try:
            return read_record(path, **kw, **layout)
        except ValueError as exc:
            first = exc if kw is tries[0] else first
    raise first


#: File suffixes a folder of records contributes (any letter case).
RECORD_SUFFIXES = (".at2", ".dat")


def _expand_paths(path):
    """A folder gives its record files (RECORD_SUFFIXES, any letter case), a glob pattern its
    matches (the file-name part matched without regard to case); any other path itself."""
    text = os.fspath(path)
    p = Path(text)
    if p.is_dir():
        found = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in RECORD_SUFFIXES)
        if not found:
            raise ValueError(f"records: no record files ({', '.join(RECORD_SUFFIXES)}, any case) in "
                             f"the folder {text}")
        return found
    if not p.exists() and any(c in text for c in "*?["):
        import fnmatch
        import glob
        folder, pattern = os.path.split(text)
        if any(c in folder for c in "*?["):
            found = sorted(Path(f) for f in glob.glob(text) if os.path.isfile(f))
        else:
            base = Path(folder or ".")
            found = sorted(f for f in base.iterdir() if f.is_file()
                           and fnmatch.fnmatchcase(f.name.lower(), pattern.lower())) if base.is_dir() else []
        if not found:
            raise ValueError(f"records: no file matches {text}")
        return found
    return [path]


def load_records(records, unit=None, dt=None, *, column=None, decimal=None):
    """Records as a list of GroundMotion with unique names.

    Parameters
    ----------
    records : GroundMotion, SampledMotion, path, or a sequence of them
        None: the packaged El Centro record.  A folder stands for its ``.AT2`` and ``.dat``
        files (any letter case), a glob pattern (``"records/*.at2"``) for its matches.
    unit : str, optional
        Unit of files whose header does not state it ('g', 'm/s2', ...).
    dt : float, optional
        Time step [s] of single-column files.
    column, decimal : optional
        As in :func:`fastrock.read_record`, for every file.
    """
    if records is None:
        records = [load_default_record()]
    elif isinstance(records, (GroundMotion, str, os.PathLike)) or hasattr(records, "acc"):
        records = [records]
    records = [f for r in records for f in (_expand_paths(r) if isinstance(r, (str, os.PathLike)) else [r])]
    out = []
    for r in records:
        if isinstance(r, GroundMotion):
            out.append(r)
        elif isinstance(r, (str, os.PathLike)):
            if not Path(r).is_file():
                raise ValueError(f"records: record file not found: {r}")
            out.append(_read_one(Path(r), unit, dt, column=column, decimal=decimal))
        elif hasattr(r, "samples_si"):     # SampledMotion
            if getattr(r, "t_start", 0.0) != 0.0:
                raise ValueError("records must start at t = 0 (SampledMotion.t_start != 0)")
            body = RigidBlock(alpha=0.1, p=1.0)  # only for the unit conversion (g)
            out.append(GroundMotion(r.samples_si(body) * r.scale, r.dt, name=r.name or "sampled"))
        else:
            raise ValueError(f"records must be GroundMotion objects or file paths, got {type(r).__name__}")
    if not out:
        raise ValueError("records is empty")
    seen = {}
    named = []
    for i, r in enumerate(out):
        nm = r.name or f"record{i}"
        if nm in seen:
            seen[nm] += 1
            nm = f"{nm} ({seen[nm]})"
        else:
            seen[nm] = 1
        if nm != r.name:
            r = GroundMotion(r.acc, r.dt, name=nm, unit_in_file=r.unit_in_file, source=r.source)
        named.append(r)
    for r in named:
        if r.pga == 0.0:
            raise ValueError(f"record {r.name!r} is all zero (PGA = 0): beta is undefined")
    return named


def _grid(values, name, default):
    if values is None:
        return default.copy()
    if isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be an array of numbers, got the string {values!r}")
    a = np.unique(V.finite_array(name, np.atleast_1d(values)))
    if a.size == 0:
        raise ValueError(f"{name} is empty")
    if (a <= 0).any():
        raise ValueError(f"{name} must be > 0")
    for v in a[[0, -1]]:
        V.finite(name, v)      # magnitude and denormal checks
    return a


#: Outcome names a run of the rocking spectrum can have (fastrock.outcomes).
OUTCOMES = ("safe", "mode1", "mode2", "leaning", "flight", "slide", "failed", "unfinished")


def _stable_outcomes(outcomes):
    try:
        items = [] if isinstance(outcomes, (str, bytes)) else list(outcomes)
    except TypeError:
        items = []
    if not items or any(not isinstance(o, str) or o not in OUTCOMES for o in items):
        raise ValueError(f"stable_outcomes must be a non-empty list of outcomes among {list(OUTCOMES)}, "
                         f"such as ['safe'], got {outcomes!r}")
    return tuple(items)


def _check_record_options(unit, dt):
    if unit is not None:
        from .records import _canonical_unit
        _canonical_unit(unit)
    if dt is not None:
        V.positive("dt", dt)


def _check_run_length(records, solver, t_after):
    longest = V.run_time("t_after", max(r.duration for r in records) + t_after,
                         "the longest record plus t_after")
    solver.check_fixed_steps(longest, "the longest record plus t_after")


# ------------------------------------------------------------------ engine
def _sweep_arrays(records, rec_idx, specs, solver, t_after, early_exit, progress, chunk_size):
    """Kernel calls for rows with prepared KernelSpecs: one sweep per kernel,
    the records' samples concatenated in one array and each row's header
    pointing at its record.  Returns (status, MET, YF, interrupted)."""
    n = rec_idx.size
    smp = np.concatenate([np.asarray(r.acc, float) for r in records])
    offsets = np.concatenate([[0], np.cumsum([r.npts for r in records])[:-1]])
    status = np.full(n, L.RUNNING, np.int64)
    MET = np.full((n, L.N_MET), np.nan)
    YF = np.full((n, 2), np.nan)
    names = np.array([sp.name for sp in specs])
    interrupted = False
    for kname in dict.fromkeys(names):
        rows = np.flatnonzero(names == kname)
        # interleave the rows so that every chunk and thread mixes long and
        # short records (static prange scheduling) and the ETA is honest
        rows = rows[np.random.default_rng(0).permutation(rows.size)]
        m = rows.size
        PAR = np.array([specs[i].par for i in rows])
        HDR = np.zeros((m, L.N_EXC))
        HDR[:, L.X_KIND] = L.EXC_SAMPLED
        HDR[:, L.X_AMP] = 1.0
        HDR[:, L.X_SIGN] = 1.0
        ri = rec_idx[rows]
        HDR[:, L.X_DT] = [records[k].dt for k in ri]
        HDR[:, L.X_N] = [records[k].npts for k in ri]
        HDR[:, L.X_DUR] = [records[k].duration for k in ri]
        HDR[:, L.X_OFFSET] = offsets[ri]
        OPT = np.tile(solver.options(0.0, early_exit), (m, 1))
        OPT[:, L.O_T_END] = HDR[:, L.X_DUR] + t_after
        Y0 = np.zeros((m, specs[rows[0]].n_state))
        st, met, yf, done = run_sweep(specs[rows[0]].sweep, Y0, PAR, HDR, smp, OPT, chunk_size,
                                      progress, label=f"runs ({kname})", model=kname)
        status[rows[:done]] = st[:done]
        MET[rows[:done]] = met[:done]
        YF[rows[:done]] = yf[:done, :2]
        if done < m:
            interrupted = True
            break
    return status, MET, YF, interrupted


def _rows_sweep(records, rec_idx, b, s, wall_idx, walls, *, e, solver, t_after, early_exit,
                progress, chunk_size):
    """Run rows (record index, half-width, slenderness, wall index), grouped
    so that each kernel runs once; returns the per-run DataFrame."""
    n = rec_idx.size
    h = b / s
    alpha = np.arctan2(b, h)
    pvals = np.empty(n)
    evals = np.empty(n)
    bodies = {}
    specs = []
    for i in range(n):
        key = (b[i], s[i])
        body = bodies.get(key)
        if body is None:
            body = bodies[key] = RigidBlock.rectangle(b[i], h[i], e=e)
        specs.append(models.select(body, walls[wall_idx[i]]))
        pvals[i] = body.p
        evals[i] = body.e
    args = (records, rec_idx, specs, solver, t_after)
    status, MET, YF, interrupted = _sweep_arrays(*args, early_exit, progress, chunk_size)
    if early_exit:
        # Defensive check: an early "safe:bounded" decision must leave the
        # block inside its potential well (|theta| < alpha).  The kernel
        # checks this since commit 4e2366c (before, its energy test alone
        # declared blocks past alpha safe); should it ever not, such rows are
        # rerun to the end here.
        bad = np.flatnonzero((status == L.SAFE_BOUNDED) & (np.abs(YF[:, 0]) >= alpha))
        if bad.size:
            sub = (records, rec_idx[bad], [specs[i] for i in bad], solver, t_after)
            st2, met2, _yf, _ = _sweep_arrays(*sub, False, False, chunk_size)
            status[bad] = st2
            MET[bad] = met2
    finished = status != L.RUNNING
    if solver.dt:
        warn_unstable(status[finished], MET[finished], solver.dt)
    outcome = np.array([outcome_of(c) if f else "unfinished" for c, f in zip(status, finished)],
                       dtype=object)
    df = pd.DataFrame({
        "record": [records[k].name for k in rec_idx],
        "wall": [_wall_label(walls[k]) for k in wall_idx],
        "wall_gap": [_wall_gap(walls[k]) for k in wall_idx],
        "pga_g": np.array([r.pga_g for r in records])[rec_idx],
        "mean_period": np.array([r.mean_period for r in records])[rec_idx],
        "b": b, "slenderness": s, "h": h, "alpha": alpha, "p": pvals, "e": evals,
        "outcome": outcome,
        "status": [status_of(c) if f else "unfinished" for c, f in zip(status, finished)],
        "max_rotation_ratio": MET[:, L.M_MAX_ABS_THETA] / alpha,
        "impacts": MET[:, L.M_IMPACTS], "wall_impacts": MET[:, L.M_WALL_IMPACTS],
        "time_uplift": MET[:, L.M_T_UPLIFT], "time_overturn": MET[:, L.M_T_OVER],
        "time_end": MET[:, L.M_T_FINAL], "nfev": MET[:, L.M_NFEV],
        "steps": MET[:, L.M_NSTEPS], "rejected_steps": MET[:, L.M_NREJECT],
    })
    df.attrs["interrupted"] = interrupted
    return df


def _solver(solver, rtol, atol, dt, record_breakpoints=None):
    kw = {} if record_breakpoints is None else {"record_breakpoints": record_breakpoints}
    return make_solver(solver, rtol, atol, dt, **kw)


def rocking_spectrum_runs(records, slenderness=None, half_widths=None, walls=None, *, e=None,
                          unit=None, solver=None, rtol=None, atol=None, dt=None,
                          record_breakpoints=None, t_after=T_AFTER, early_exit=True,
                          stable_outcomes=STABLE_OUTCOMES, progress=True, chunk_size=None):
    """Every run of the rocking-spectrum study, one row per record x wall x
    size x slenderness (columns in ``RUN_COLUMNS``).  Arguments as in
    :func:`rocking_spectrum`."""
    _check_record_options(unit, None)
    records = load_records(records, unit)
    s_grid = _grid(slenderness, "slenderness", DEFAULT_SLENDERNESS)
    b_grid = _grid(half_widths, "half_widths", DEFAULT_HALF_WIDTHS)
    walls = _as_walls(walls)
    solver = _solver(solver, rtol, atol, dt, record_breakpoints)
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    if e is not None:
        e = V.in_closed("e", e, 0.0, 1.0)
    stable_outcomes = _stable_outcomes(stable_outcomes)
    early_exit = V.boolean("early_exit", early_exit)
    if chunk_size is not None:
        chunk_size = V.integer("chunk_size", chunk_size, 1)
    _check_run_length(records, solver, t_after)
    R, W, B, S = np.meshgrid(np.arange(len(records)), np.arange(len(walls)), b_grid, s_grid,
                             indexing="ij")
    df = _rows_sweep(records, R.ravel(), B.ravel(), S.ravel(), W.ravel(), walls, e=e,
                     solver=solver, t_after=t_after, early_exit=early_exit, progress=progress,
                     chunk_size=chunk_size)
    df.insert(df.columns.get_loc("outcome") + 2, "stable", df["outcome"].isin(stable_outcomes))
    df.attrs.update(solver=solver.name, t_after=t_after, early_exit=early_exit,
                    stable_outcomes=tuple(stable_outcomes),
                    walls=[_wall_label(w) for w in walls])
    return df


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
        body = None if math.isnan(s_min) else RigidBlock.rectangle(b, b / s_min)
        p = math.nan if body is None else body.p
        Tp = 2 * math.pi / p if body is not None else math.nan
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
                     return_runs=False):
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

    Returns
    -------
    DataFrame (columns in ``SPECTRUM_COLUMNS``), or (table, runs).
    """
    runs = rocking_spectrum_runs(records, slenderness, half_widths, walls, e=e, unit=unit,
                                 solver=solver, rtol=rtol, atol=atol, dt=dt,
                                 record_breakpoints=record_breakpoints, t_after=t_after,
                                 early_exit=early_exit, stable_outcomes=stable_outcomes,
                                 progress=progress, chunk_size=chunk_size)
    table = summarize_runs(runs)
    return (table, runs) if return_runs else table


# ------------------------------------------------------------- bisection
@dataclass
class MinimumStableSlenderness:
    """Result of :func:`minimum_stable_slenderness`.

    Attributes
    ----------
    value : float
        (b/h)_min [-]: the upper (stable) end of the final bracket
        ("exact"), ``lo`` ("upper": every scanned block is stable) or ``hi``
        ("lower": the stoutest block is not stable).
    bracket : (float, float)
        Unstable and stable slenderness enclosing the threshold, width <=
        ``tol`` for "exact"; (0, lo) for "upper", (hi, inf) for "lower".
    bound : str
        "exact" (to ``tol``), "upper" or "lower".
    non_monotone : bool
        Among all evaluated blocks, a stable one lies below an unstable one.
    beta : float
        value * g / PGA [-].
    Tp : float
        2 pi / p of the block (b, value) [s].
    runs : DataFrame
        Every evaluated block: ``round`` (0 = coarse scan), slenderness,
        outcome, status, stable, max_rotation_ratio.
    """

    value: float
    bracket: tuple
    bound: str
    non_monotone: bool
    beta: float
    Tp: float
    tol: float
    runs: pd.DataFrame = field(repr=False)

    @property
    def n_runs(self):
        return len(self.runs)

    @property
    def scan(self):
        """The coarse scan (round 0)."""
        return self.runs[self.runs["round"] == 0].reset_index(drop=True)


#: minimum_stable_slenderness: smallest tol relative to hi, most points of a scan or round, and
#: most refinement rounds (bisection from a bracket of width hi down to MIN_TOL hi takes 40).
MIN_TOL = 1e-12
MAX_SCAN = 100_000
MAX_ROUNDS = 200


def minimum_stable_slenderness(record, b, lo=0.05, hi=0.6, tol=1e-3, *, wall=None, scan=20,
                               sections=2, e=None, unit=None, solver=None, rtol=None, atol=None,
                               dt=None, t_after=T_AFTER, stable_outcomes=STABLE_OUTCOMES):
    """Minimum stable slenderness of blocks of half-width ``b`` by bisection.

    1. A coarse scan of ``scan`` slenderness values in [lo, hi] (one
       parallel sweep) applies the grid definition of the module docstring
       ("stable from there up") and gives a bracket (last unstable, next
       stable) -- or a bound if every / no scanned block is stable.
    2. The bracket is cut in ``sections`` parts per round (2: bisection;
       more: k-section, the ``sections - 1`` interior blocks run in one
       parallel sweep) until it is narrower than ``tol``.  Each round applies
       the same "stable from there up" rule to its points, so with
       ``sections > 2`` non-monotone stability inside the bracket is seen
       and followed upwards.

    ``non_monotone`` reports a stable block below an unstable one among all
    evaluated blocks.  On recorded motions stability is often non-monotone on
    fine scales: bisection then finds *a* threshold of the bracket that the
    coarse scan isolated, and an unstable slenderness may still hide between
    coarse points above it; a denser ``scan`` (and ``sections``) narrows
    that gap.  ``value`` is always the "stable from there up" threshold of
    all evaluated blocks.

    Parameters
    ----------
    record : GroundMotion or path
    b : float
        Half-width [m].
    lo, hi : float
        Slenderness range b/h [-], 0 < lo < hi.
    tol : float
        Width of the final bracket in b/h [-].
    wall : Wall, optional
    scan : int
        Points of the coarse scan (>= 2).
    sections : int
        Parts per refinement round (>= 2; 2 is bisection).

    Returns
    -------
    MinimumStableSlenderness
    """
    _check_record_options(unit, None)
    (rec,) = load_records(record, unit)
    b = V.positive("b", b)
    lo = V.positive("lo", lo)
    hi = V.positive("hi", hi)
    if not lo < hi:
        raise ValueError(f"need lo < hi, got lo={lo}, hi={hi}")
    tol = V.positive("tol", tol)
    if tol < MIN_TOL * hi:
        raise ValueError(f"tol = {tol!r} is below {MIN_TOL:g} hi = {MIN_TOL * hi:.3g}: float64 slenderness "
                         f"values cannot be bisected that finely")
    scan = V.integer("scan", scan, 2, MAX_SCAN)
    sections = V.integer("sections", sections, 2, MAX_SCAN)
    solver = _solver(solver, rtol, atol, dt)
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    if e is not None:
        e = V.in_closed("e", e, 0.0, 1.0)
    stable_outcomes = _stable_outcomes(stable_outcomes)
    _check_run_length([rec], solver, t_after)
    walls = (wall,)
    cols = ["round", "slenderness", "outcome", "status", "stable", "max_rotation_ratio"]
    done = []

    def run(svals, rnd):
        svals = np.asarray(svals, float)
        k = svals.size
        df = _rows_sweep([rec], np.zeros(k, int), np.full(k, b), svals, np.zeros(k, int), walls,
                         e=e, solver=solver, t_after=t_after, early_exit=True, progress=False,
                         chunk_size=None)
        df["stable"] = df["outcome"].isin(stable_outcomes)
        df["round"] = rnd
        done.append(df[cols])
        return df["stable"].to_numpy()

    grid = np.linspace(lo, hi, int(scan))
    thr = minimum_stable_on_grid(run(grid, 0))
    if thr.bound == "upper":
        value, bracket = lo, (0.0, lo)
    elif thr.bound == "lower":
        value, bracket = hi, (hi, math.inf)
    else:
        a, c = float(grid[thr.index - 1]), float(grid[thr.index])
        rnd = 0
        while c - a > tol and rnd < MAX_ROUNDS:     # each round narrows the bracket by `sections`
            rnd += 1
            pts = np.linspace(a, c, int(sections) + 1)
            st = np.concatenate([[False], run(pts[1:-1], rnd), [True]])
            k = minimum_stable_on_grid(st).index
            a, c = float(pts[k - 1]), float(pts[k])
        value, bracket = c, (a, c)
    runs = pd.concat(done, ignore_index=True)
    allpts = runs.sort_values("slenderness", kind="stable")
    non_monotone = minimum_stable_on_grid(allpts["stable"].to_numpy()).non_monotone
    body = RigidBlock.rectangle(b, b / value, e=e)
    return MinimumStableSlenderness(
        value=value, bracket=bracket, bound=thr.bound, non_monotone=bool(non_monotone),
        beta=value / rec.pga_g, Tp=2 * math.pi / body.p, tol=tol, runs=runs)


# ------------------------------------------------------------ single runs
#: Most fixed steps per record interval in simulate_record.
MAX_SUBSTEPS = 1_000_000


def simulate_record(body, record, fixed_step=False, *, substeps=1, unit=None, **kw):
    """Simulate ``body`` under a record; the fixed step can follow the record.

    Parameters
    ----------
    body : RigidBlock
    record : GroundMotion, SampledMotion or path
    fixed_step : bool
        True: fixed-step DP5 with ``dt = record.dt / substeps`` (steps end
        on the record samples, where the interpolated signal has its kinks).
        False: adaptive RK45 (``rtol``...).
    substeps : int
        Fixed steps per record interval (with ``fixed_step``).
    **kw
        Passed to :func:`fastrock.simulate` (wall, rtol, t_after, ...).

    Returns
    -------
    SimulationResult
    """
    from .simulate import simulate
    (rec,) = load_records(record, unit)
    if fixed_step:
        if kw.get("dt") is not None or kw.get("solver") is not None:
            raise ValueError("give either fixed_step=True or dt=/solver=, not both")
        substeps = V.integer("substeps", substeps, 1, MAX_SUBSTEPS)
        kw["dt"] = rec.dt / substeps
    return simulate(body, rec, **kw)


# ------------------------------------------------------------------- plot
WALL_STYLE = [("#1d3557", "o"), ("#e76f51", "s"), ("#2a9d8f", "D"), ("#8d5fd3", "P"),
              ("#6c757d", "X")]


def plot_rocking_spectrum(df, ax=None, curve=True, title=None, legend=True):
    """beta against Tp/Tm: one colour per record, one marker per wall setting.

    Exact points are filled.  Censored points (the grid gives only a bound) are hollow with an
    arrow toward the true value: down for an upper bound, up for a lower bound.  Maiorano et
    al.'s upper-bound curve for two-sided rocking, ``1.35 exp(-0.12 Tp/Tm)``, is drawn and named.

    Returns
    -------
    matplotlib Figure
    """
    from matplotlib.lines import Line2D
    from .plotting import _pyplot
    if ax is None:
        plt = _pyplot()
        fig, ax = plt.subplots(figsize=(8.4, 5.2), constrained_layout=True)
    else:
        fig = ax.figure
    d = df[df["beta_bound"] != "incomplete"]
    xmax = float(np.nanmax(d["tp_over_tm"])) if len(d) else 10.0
    ymax = float(np.nanmax(d["beta"])) if len(d) else 1.5
    records = list(dict.fromkeys(d["record"])) if "record" in d else [""]
    walls = list(dict.fromkeys(d["wall"]))
    colors = {r: f"C{i % 10}" for i, r in enumerate(records)}
    markers = {w: WALL_STYLE[i % len(WALL_STYLE)][1] for i, w in enumerate(walls)}
    arrow = 0.06 * max(ymax, 1.0)
    censored = False
    for (rec, wall), grp in d.groupby(["record", "wall"], sort=False):
        color, marker = colors[rec], markers[wall]
        ex = grp[grp["beta_bound"] == "exact"]
        ax.plot(ex["tp_over_tm"], ex["beta"], ls="none", marker=marker, ms=5, color=color)
        for bound, sign in (("upper", -1.0), ("lower", 1.0)):
            bd = grp[grp["beta_bound"] == bound]
            if not len(bd):
                continue
            censored = True
            ax.plot(bd["tp_over_tm"], bd["beta"], ls="none", marker=marker, ms=5, mfc="white", color=color)
            for x, y in zip(bd["tp_over_tm"], bd["beta"]):
                ax.annotate("", xy=(x, max(y + sign * arrow, 0.0)), xytext=(x, y),
                            arrowprops=dict(arrowstyle="->", color=color, lw=0.8, shrinkA=3, shrinkB=0))
    handles = [Line2D([], [], ls="none", marker="o", color=colors[r], label=str(r)) for r in records]
    handles += [Line2D([], [], ls="none", marker=markers[w], color="0.35", label=str(w)) for w in walls]
    if censored:
        handles.append(Line2D([], [], ls="none", marker="o", mfc="white", color="0.35",
                              label="censored: bound only (arrow toward the true value)"))
    if curve:
        x = np.linspace(0.0, max(xmax * 1.05, 1.0), 300)
        line, = ax.plot(x, upper_bound_beta(x), "k--", lw=1.2)
        handles.append(Line2D([], [], color="k", ls="--", lw=1.2,
                              label=r"Maiorano et al. upper bound, $1.35\,e^{-0.12\,T_p/T_m}$"))
    ax.set_xlabel(r"$T_p/T_m$ [-]")
    ax.set_ylabel(r"$\beta = (b/h)_{min}\,g/\mathrm{PGA}$ [-]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title, fontsize=9)
    if legend:
        ax.legend(handles=handles, fontsize=7, framealpha=0.9, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0.0)
    return fig


# -------------------------------------------------------------------- CLI
#: Default block of ``fastrock record``: 0.6 m x 3 m (b/h = 0.2).  Under the
#: packaged El Centro record it rocks (max |theta|/alpha = 0.26) and stays up.
DEFAULT_RECORD_BLOCK = (0.3, 1.5)


def _cli_record(args):
    rec = _cli_one_record(args.file, args.unit, args.record_dt, args)
    body = _cli_body(args)
    wall = _cli_wall(args)
    fixed = args.dt_fixed is not None and args.dt_fixed.strip().lower() == "record"
    kw = dict(wall=wall, rtol=args.rtol, atol=args.atol, t_after=args.t_after)
    if args.dt_fixed is not None and not fixed:
        kw["dt"] = V.positive("--dt", _float_arg("--dt", args.dt_fixed))
    r = simulate_record(body, rec, fixed_step=fixed, **kw)
    m = r.metrics
    print(f"record: {rec.name}" + (f"  ({rec.source})" if rec.source else ""))
    print(f"  PGA = {rec.pga_g:.3g} g at t = {rec.peak_time:.3g} s, PGV = {rec.pgv:.3g} m/s, "
          f"PGD = {rec.pgd:.3g} m")
    print(f"  duration = {rec.duration:.4g} s ({rec.npts} points, dt = {rec.dt:g} s), "
          f"Tm = {rec.mean_period:.3g} s, Arias = {rec.arias_intensity:.3g} m/s")
    geom = f"b = {body.b:g} m, h = {body.h:g} m, " if body.b is not None else ""
    print(f"block: {geom}alpha = {body.alpha:.4g} rad, p = {body.p:.4g} rad/s, "
          f"e = {body.e:.4g}, Tp = {2 * math.pi / body.p:.3g} s; "
          f"uplift at {body.uplift_acceleration / body.g:.3g} g"
          + ("" if wall is None else f"; {_wall_label(wall)}"))
    solver = f"fixed dt = {kw['dt']:g} s" if "dt" in kw else (
        f"fixed dt = record dt = {rec.dt:g} s" if fixed else "adaptive RK45")
    print(f"outcome: {r.outcome} ({r.status}); {solver}")
    print(f"  max |theta|/alpha = {m['max_rotation_ratio']:.4g}, impacts = {m['impacts']}"
          + (f", wall impacts = {m['wall_impacts']}" if wall is not None else "")
          + f", uplift t = {_time(m['time_uplift'])}, overturn t = {_time(m['time_overturn'])}")
    from .cli import wrote, write_table
    wrote(write_table(r.history, args))
    if args.png:
        fig = _record_figure(rec, r)
        fig.savefig(args.png, dpi=120)
        wrote([args.png])
    return 0


def _time(t):
    return "none" if math.isnan(t) else f"{t:.4g} s"


def _record_figure(rec, result):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8.0, 8.0), layout="constrained")
    axes = fig.subplots(4, 1, sharex=True)
    rec.plot(ax=axes[:3])
    axes[2].set_xlabel("")
    h = result.history
    axes[3].plot(h["t"], h["theta_ratio"], lw=0.9)
    axes[3].axhline(1, color="k", lw=0.6, ls=":")
    axes[3].axhline(-1, color="k", lw=0.6, ls=":")
    axes[3].set_ylabel(r"$\theta/\alpha$")
    axes[3].set_xlabel("t [s]")
    axes[3].grid(True, alpha=0.3)
    axes[3].set_title(f"rocking: {result.status}", fontsize=9)
    return fig


def _float_arg(name, text):
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number or 'record', got {text!r}") from None


def _column_arg(text):
    if text is None or text == "all":
        return text
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"--column must be an integer (0-based, negative from the end) or 'all', "
                         f"got {text!r}") from None


def _cli_one_record(path, unit, dt, args=None):
    if path is None:
        return load_default_record()
    return _read_one(Path(path), unit, dt, column=_column_arg(getattr(args, "column", None)),
                     decimal=getattr(args, "decimal", None))


def _cli_body(args):
    if args.b is not None or args.h is not None:
        if args.b is None or args.h is None:
            raise ValueError("give both --b and --h (half-width and half-height, m)")
        return RigidBlock.rectangle(args.b, args.h, e=args.e)
    if args.alpha is not None or args.p is not None:
        if args.alpha is None or args.p is None:
            raise ValueError("give both --alpha and --p")
        return RigidBlock(alpha=args.alpha, p=args.p, e=args.e)
    return RigidBlock.rectangle(*DEFAULT_RECORD_BLOCK, e=args.e)


def _cli_wall(args):
    if args.wall_gap is None:
        return None
    try:
        from .wall import Wall
    except ImportError:
        raise ValueError("--wall-gap needs fastrock.wall, which is not installed") from None
    return Wall(gap=args.wall_gap, side=args.wall_side)


def _cli_rocking_spectrum(args):
    import time
    records = load_records(args.files or None, args.unit, args.record_dt, column=_column_arg(args.column),
                           decimal=args.decimal)
    from .cli import grid_option
    s = grid_option("--slenderness", args.slenderness_min, args.slenderness_max, args.n_slenderness,
                    n_option="--n-slenderness")
    b = grid_option("--b", args.b_min, args.b_max, args.n_sizes, n_option="--n-sizes")
    walls = parse_walls(args.walls) if args.walls else None
    t0 = time.perf_counter()
    table, runs = rocking_spectrum(records, s, b, walls, rtol=args.rtol, dt=args.dt, t_after=args.t_after,
                                   progress=not args.quiet, return_runs=True)
    el = time.perf_counter() - t0
    print(f"{len(runs)} runs ({len(records)} records x {len(table.attrs['walls'])} wall settings x "
          f"{args.n_sizes} sizes x {args.n_slenderness} slenderness) in {el:.2f} s "
          f"({len(runs) / el:,.0f} runs/s)")
    for r in records:
        print(f"  {r.name}: PGA = {r.pga_g:.3g} g, Tm = {r.mean_period:.3g} s, "
              f"duration = {r.duration:.4g} s")
    agg = table.groupby(["record", "wall"], sort=False).agg(
        beta_min=("beta", "min"), beta_max=("beta", "max"),
        exact=("beta_bound", lambda x: int((x == "exact").sum())),
        upper=("beta_bound", lambda x: int((x == "upper").sum())),
        lower=("beta_bound", lambda x: int((x == "lower").sum())),
        non_monotone=("non_monotone", "sum"), overturned=("n_overturned", "sum"))
    with pd.option_context("display.width", 160, "display.max_columns", 20):
        print(agg.round(3).to_string())
    from .cli import wrote, write_table
    tables = write_table(table, args)
    fig = plot_rocking_spectrum(table, title=f"{len(records)} record(s), "
                                             f"{args.n_sizes}x{args.n_slenderness} blocks")
    fig.savefig(args.png, dpi=130)
    if table.attrs.get("interrupted"):
        from .cli import interrupted_exit
        return interrupted_exit(int((runs["outcome"] != "unfinished").sum()), len(runs), "runs",
                                tables + [args.png])
    wrote(tables + [args.png])
    return 0


def _add_record_options(p):
    p.add_argument("--unit", help="acceleration unit of files whose header does not state it "
                                  "(g, m/s2, cm/s2/gal, mm/s2; default: refuse such files)")
    p.add_argument("--record-dt", type=float, help="sample step [s] of single-column files "
                                                   "(default: refuse such files)")
    p.add_argument("--column", help="data column holding the acceleration in files with several "
                                    "columns (0-based, negative from the end), or 'all' for one "
                                    "record wrapped over rows (default: refuse such files)")
    p.add_argument("--decimal", choices=(".", ","), help="decimal mark of the files (default '.'; "
                                                         "decimal commas are refused unless ',')")


def add_subcommands(subparsers):
    """Register ``fastrock record`` and ``fastrock rocking-spectrum``."""
    s = subparsers.add_parser(
        "record", help="one block under a recorded accelerogram: measures, outcome, plots",
        description="Load an accelerogram (default: the packaged 1940 El Centro N-S), print its "
                    "ground-motion measures, simulate one block and plot record and rocking.")
    s.add_argument("file", nargs="?", help="record file (PEER AT2, two-column or single-column); "
                                           "default: packaged El Centro")
    _add_record_options(s)
    g = s.add_argument_group("block (default: b = 0.3 m, h = 1.5 m; rocks, does not overturn "
                             "under El Centro)")
    g.add_argument("--b", type=float, help="half-width [m] (with --h; default 0.3)")
    g.add_argument("--h", type=float, help="half-height [m] (default 1.5)")
    g.add_argument("--alpha", type=float, help="slenderness angle [rad] (with --p; default: from --b/--h)")
    g.add_argument("--p", type=float, help="frequency parameter [rad/s] (default: from --b/--h)")
    g.add_argument("--e", type=float, help="ground impact restitution e [-] (default Housner)")
    w = s.add_argument_group("rear wall")
    w.add_argument("--wall-gap", type=float, help="clear gap d [m] (default: no wall)")
    w.add_argument("--wall-side", type=int, default=-1, choices=(-1, 1),
                   help="side of the wall (default -1)")
    i = s.add_argument_group("integrator")
    i.add_argument("--rtol", type=float, help="relative tolerance of adaptive RK45 [-] (default 1e-8)")
    i.add_argument("--atol", type=float, help="absolute tolerance [rad, rad/s] (default rtol*1e-2)")
    i.add_argument("--dt", "--dt-fixed", dest="dt_fixed", metavar="DT",
                   help="fixed integration step [s] instead of adaptive RK45, or 'record' to step "
                        "at the record's dt (default: adaptive)")
    s.add_argument("--t-after", type=float, default=T_AFTER,
                   help=f"free rocking after the record [s] (default {T_AFTER:g})")
    from .cli import add_output_options
    add_output_options(s, png="record.png", figure="the figure of the record (acc/vel/disp) and "
                       "theta/alpha", table="the rocking time history")
    s.set_defaults(func=_cli_record)

    s = subparsers.add_parser(
        "rocking-spectrum", help="beta against Tp/Tm over records x blocks x wall settings",
        description="For each record, block size and wall setting, find the minimum stable "
                    "slenderness on a grid and report beta = (b/h)_min g / PGA against Tp/Tm.")
    s.add_argument("files", nargs="*", help="record files, folders (their .AT2 and .dat files, any "
                                           "letter case) or quoted glob patterns (default: "
                                           "packaged El Centro)")
    _add_record_options(s)
    s.add_argument("--n-slenderness", type=int, default=20, help="number of b/h values (default 20)")
    s.add_argument("--slenderness-min", type=float, default=0.1, help="smallest b/h [-] (default 0.1)")
    s.add_argument("--slenderness-max", type=float, default=0.5, help="largest b/h [-] (default 0.5)")
    s.add_argument("--n-sizes", type=int, default=20, help="number of half-widths b (default 20)")
    s.add_argument("--b-min", type=float, default=0.1, help="smallest half-width [m] (default 0.1)")
    s.add_argument("--b-max", type=float, default=1.0, help="largest half-width [m] (default 1)")
    s.add_argument("--walls", help="comma list of settings, e.g. two-sided,0.01,0.10 (gaps in m; "
                                   "default: these three if the wall model is installed)")
    s.add_argument("--rtol", type=float, help="relative tolerance of adaptive RK45 [-] (default 1e-8)")
    s.add_argument("--dt", type=float, help="fixed integration step [s] instead of adaptive RK45 "
                                            "(default: adaptive)")
    s.add_argument("--t-after", type=float, default=T_AFTER,
                   help=f"free rocking after each record [s] (default {T_AFTER:g})")
    from .cli import add_output_options
    add_output_options(s, png="rocking_spectrum.png", csv="rocking_spectrum.csv",
                       figure="the beta against Tp/Tm figure", table="the table of thresholds")
    s.set_defaults(func=_cli_rocking_spectrum)
