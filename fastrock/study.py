"""Studies: record suites x bodies x scene variants x intensity levels,
run in chunks on this machine or on a Dask cluster, with incremental
dynamic analysis (IDA) and lognormal fragility curves.

A :class:`Study` describes every run in one call.  :func:`run_study` cuts it
into chunks (deterministic: the same study and ``chunk_size`` always give the
same chunks), runs each chunk with the parallel Numba sweep kernel of its
model, and writes each finished chunk as one Parquet file of a partitioned
dataset in the output folder (atomically: a temporary name, then
``os.replace``).  A ``manifest.json`` holds the study's hash and its chunk
list; a rerun into the same folder skips the chunks whose file exists, so an
interrupted study resumes where it stopped.  :func:`load_results` reads the
dataset back as one DataFrame.  The hash covers what the runs depend on
(record samples and names, bodies, variants, levels, measure, solver,
``t_after``, ``early_exit``), not the fastrock version: after an upgrade
start a new folder rather than mixing the results of two versions.

Backends
--------
``"local"`` (default) runs the chunks one after the other in this process;
each chunk is one call of the ``prange`` sweep kernel on all cores.
``"dask"`` submits one task per chunk to a ``dask.distributed`` cluster (a
``Client``, a scheduler address, or, with neither, a ``LocalCluster`` started
here).  The task function :func:`run_chunk` is top level, takes plain data
(NumPy arrays and strings), is pure and idempotent, and runs the kernel in
the worker.  The client writes each chunk's file as soon as its future
completes (``as_completed``), so a finished chunk is on disk before anything
else can go wrong, and a worker that dies loses only the chunks it was still
computing: the scheduler reruns them elsewhere (``retries`` covers exceptions
raised by a task).  Both backends run the same payloads through the same
kernels, so their tables are identical bit for bit.

Intensity measures (one row per record x body x variant x level)
----------------------------------------------------------------
The record is scaled by a factor ``scale`` so that the study's measure equals
the level:

* ``"pga"``: the level is the PGA [g];  ``scale = level g / PGA``;
* ``"pgv"``: the level is the PGV [m/s];  ``scale = level / PGV``;
* ``"pga_over_g_tan_alpha"``: the level is PGA / (g tan alpha) of the body
  (dimensionless; 1 is the static uplift threshold), so the scale differs
  from body to body;
* ``"scale"``: the level is the factor itself.

Every row carries all the measures of its scaled record: ``pga_g``, ``pgv``,
``pga_over_g_tan_alpha`` and ``omega_p_over_p`` (= (2 pi / Tm) / p, the
dimensionless frequency of the literature on pulse-like records, Dimitrakopoulos
& DeJong 2012, doi:10.1098/rspa.2012.0026, with the record's mean period Tm
(Rathje et al. 1998) as the proxy of the pulse period: the record is not
decomposed into pulses; ``omega_p_over_p`` does not depend on the scale).

Fragility
---------
:func:`fit_fragility` fits ``P(collapse | IM) = Phi(ln(IM / theta) / beta)``
by maximum likelihood over all rows (each row a Bernoulli trial: Baker 2015,
doi:10.1193/021113EQS025M), for overturning or for exceeding a threshold of
``max |theta| / alpha``, with bootstrap confidence bands that resample whole
records (the rows of one record are correlated).  NumPy only; Phi from
``math.erf``.
"""
from __future__ import annotations

import dataclasses
import glob
import hashlib
import itertools
import json
import math
import os
import threading
import time
import uuid
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from . import _validate as V
from . import models
from .bodies import FlexibleBody, RigidBlock
from .outcomes import outcome_of, status_of
from .constants import G_STANDARD
from .records import GroundMotion, load_default_record
from .solver import DEFAULT_T_AFTER, Solver
from .sweep import Progress, call_kernel
# Reused from the rocking spectrum (private helpers, imported on purpose so
# that records and wall settings are read and labelled the same way there and
# here): _read_one applies --unit/--dt only where a file does not state them;
# _as_walls accepts None / gaps / Wall objects; _wall_label names a setting.
from .rocking_spectrum import _as_walls, _read_one, _wall_gap, _wall_label, load_records
from fastrock.kernels import layout as L

__all__ = [
    "MEASURES", "RESULT_COLUMNS", "DEFAULT_CHUNK_SIZE", "Study", "StudyError", "FragilityFit",
    "run_study", "run_chunk", "load_results", "fit_fragility", "plot_fragility",
    "add_subcommand",
]

#: Intensity measures a study's levels can be given in (module docstring).
MEASURES = ("pga", "pgv", "pga_over_g_tan_alpha", "scale")
#: Rows per chunk.  bench/bench_study.py on the 2-core machine: 20-32 ms of
#: overhead per chunk (packing, kernel launch, Parquet file, Dask round trip)
#: against 9-12 ms of wall time per row (records of 30-40 s), so chunks of
#: 34-64 rows or more keep it under 5 %; 128 (about 2 %) leaves a margin for
#: shorter records and busier machines.
DEFAULT_CHUNK_SIZE = 128
#: Most intensity levels of a {start, stop, num} table and most bodies a study file's
#: [[bodies]] lists may expand to.
MAX_LEVELS = 100_000
MAX_BODIES = 100_000
#: Seconds to wait for a scheduler given by address.
CONNECT_TIMEOUT = 10.0
#: Dask retries of a chunk whose task raised.
RETRIES = 2
#: Version of the on-disk layout (part of the study hash).
FORMAT = "fastrock-study/1"
MANIFEST = "manifest.json"
RESULTS_DIR = "results"
#: Outcomes counted as overturning by :func:`fit_fragility`.
COLLAPSE_OUTCOMES = ("mode1", "mode2")
#: Outcomes left out of a fragility fit (the run did not finish).
EXCLUDED_OUTCOMES = ("failed", "unfinished")

RESULT_COLUMNS = """\
row                   global row id (record-major order: record, body, variant, level)
chunk                 chunk id (file results/chunk-<id>.parquet)
record_index, record  record position in the study and its (unique) name
polarity              sign the record ran with, +1 or -1 (Study.polarities)
body_index, body      body position and label
variant_index, variant  scene variant position and label ("two-sided", "wall d=0.01 m", ...)
wall_gap              clear gap to the rear wall [m] (NaN: no wall)
level_index, level    intensity level and its measure (column "measure")
kernel                compiled kernel that ran the row
alpha [rad], p [rad/s], e [-], b [m], h [m]   body (b, h NaN if unknown)
record_pga_g [g], record_pgv [m/s], mean_period Tm [s], duration [s]   unscaled record
scale                 factor applied to the record [-]
pga_g                 PGA of the scaled record / g [-]  (the study's own measure equals
                      the level exactly; the samples' max differs by an ulp or two)
pgv                   PGV of the scaled record [m/s]
pga_over_g_tan_alpha  PGA / (g tan alpha), g of the body [-]
omega_p_over_p        (2 pi / Tm) / p, Tm as pulse-period proxy [-]
outcome, status, status_code   coarse class, refined status and kernel code
overturned            outcome in (mode1, mode2)
max_rotation_ratio    max |theta| / alpha [-]
impacts, wall_impacts, time_uplift [s], time_overturn [s], time_end [s],
nfev, steps, rejected_steps
"""


class StudyError(ValueError):
    """A study cannot start (bad input, unreachable scheduler, wrong folder)
    or some of its chunks failed.  Finished chunks are never lost."""


# ============================================================== definition
@dataclass
class Study:
    """Records x bodies x scene variants x intensity levels.

    Parameters
    ----------
    records : sequence
        File paths (any format :func:`fastrock.records.read_record` reads;
        ``"default"`` is the packaged El Centro record), :class:`GroundMotion`
        objects, or dicts ``{"file": ..., "unit": ..., "dt": ...}`` (also
        ``"column"`` and ``"decimal"``, as in :func:`fastrock.read_record`).
    bodies : sequence of RigidBlock or FlexibleBody
    levels : sequence of float
        Intensity levels, > 0, in ``measure``.
    measure : str
        One of :data:`MEASURES` (module docstring).
    variants : sequence of dict
        Scene variants, e.g. ``{"wall": None}`` (two-sided rocking) and
        ``{"wall": Wall(0.01)}``; the keys are ``"wall"`` (a Wall, a gap in m
        or None), ``"friction"`` (a Friction or a dict of its arguments),
        ``"foundation"`` (a foundation object, or a dict as a scene's
        ``[foundation]`` table, e.g. ``{"type": "two-spring", "omega": 40,
        "zeta": 0.05}``, built for each body), ``"mass"`` (block mass [kg]
        with a foundation, default 1) and ``"name"`` (label; default from
        the effects).
    solver : Solver or dict, optional
        Integrator settings (default adaptive RK45, rtol 1e-8).
    t_after : float
        Free motion after the end of each record [s].
    early_exit : bool
        Stop a run once its outcome is decided (as the rocking spectrum).
    unit, dt : optional
        Unit / time step for record files that do not state them.
    polarities : tuple of +1/-1
        Signs each record runs with: ``(1,)`` as recorded (default), ``(1, -1)`` both
        polarities (a rocking block, and a one-sided wall above all, is not symmetric in a
        record's sign).  Rows carry ``polarity``; both polarities of a record keep its name, so
        the fragility bootstrap resamples records, not polarity copies.
    name : str
        Label, not part of the hash.
    run : dict
        Run options read from TOML (``output``, ``backend``, ``scheduler``,
        ``chunk_size``); not part of the hash.
    """

    records: list
    bodies: list
    levels: list
    measure: str = "pga"
    variants: list = field(default_factory=lambda: [{"wall": None}])
    solver: object = None
    t_after: float = DEFAULT_T_AFTER
    early_exit: bool = True
    unit: str | None = None
    dt: float | None = None
    name: str = ""
    run: dict = field(default_factory=dict)
    polarities: tuple = (1,)

    # ---------------------------------------------------------------- TOML
    @classmethod
    def from_toml(cls, path):
        """Read a study file (see ``examples/study.toml``).

        Top-level keys ``name``, ``measure``, ``levels`` (a list, or a table
        ``{start, stop, num}`` for evenly spaced levels), ``t_after``,
        ``early_exit``, ``records`` (paths or globs relative to the file,
        ``"default"``, or tables ``{file, unit, dt, column, decimal}``), ``unit``, ``dt``;
        arrays of tables ``[[bodies]]`` (as a scene's ``[body]``; a key given
        a list expands to the product of all its values) and ``[[variants]]``
        (``name``, ``wall = {gap, side, height, restitution}``, ``friction = {mu_s, mu_k, ...}``,
        ``foundation`` as a scene's ``[foundation]`` table without ``mass``, and ``mass`` [kg]
        with a foundation); tables
        ``[solver]`` and ``[run]`` (``output``, ``backend``, ``scheduler``,
        ``chunk_size``; a relative output is relative to the file).
        """
        from .scene import tomllib
        path = Path(path)
        try:
            with open(path, "rb") as fh:
                data = tomllib.load(fh)
        except FileNotFoundError:
            raise StudyError(f"study file not found: {path}") from None
        except tomllib.TOMLDecodeError as exc:
            raise StudyError(f"{path}: not valid TOML: {exc}") from None
        return cls.from_dict(data, base=path.parent, name=path.stem)

    @classmethod
    def from_dict(cls, data, base=".", name=""):
        try:
            return cls._from_dict(data, base, name)
        except StudyError:
            raise
        except ValueError as exc:
            raise StudyError(str(exc)) from None

    @classmethod
    def _from_dict(cls, data, base=".", name=""):
        from .scene import _body, _only, _table
        base = Path(base)
        data = dict(data)
        known = {"name", "measure", "levels", "t_after", "early_exit", "records", "unit", "dt",
                 "bodies", "variants", "solver", "run", "polarities"}
        unknown = set(data) - known
        if unknown:
            raise StudyError(f"unknown study key(s) {sorted(unknown)}; known: {sorted(known)}")
        for key in ("records", "bodies", "levels"):
            if key not in data:
                raise StudyError(f"study: '{key}' is required")
        levels = data["levels"]
        if isinstance(levels, dict):
            lv = _only(dict(levels), "levels", {"start", "stop", "num"})
            missing = sorted({"start", "stop", "num"} - set(lv))
            if missing:
                raise StudyError(f"levels: the table {{start, stop, num}} lacks {missing}")
            levels = np.linspace(V.positive("levels start", lv["start"]), V.positive("levels stop", lv["stop"]),
                                 V.integer("levels num", lv["num"], 1, MAX_LEVELS)).tolist()
        for key in ("records", "bodies"):
            if not isinstance(data[key], (list, tuple)):
                raise StudyError(f"{key} must be a list, got {data[key]!r}")
        if not isinstance(data.get("variants", []), (list, tuple)):
            raise StudyError(f"variants must be a list of tables ([[variants]]), got {data['variants']!r}")
        records = []
        for r in data["records"]:
            if not isinstance(r, (str, dict)):
                raise StudyError(f"records: each entry must be a file name, \"default\" or a table, got {r!r}")
            if isinstance(r, dict):
                r = dict(_only(dict(r), "records", {"file", "unit", "dt", "column", "decimal"}))
                f = r["file"]
                r["file"] = f if f == "default" else str(base / f)
                records.append(r)
            elif r == "default":
                records.append(r)
            else:
                pattern = str(base / r)
                if glob.has_magic(pattern):
                    hits = sorted(glob.glob(pattern))
                    if not hits:
                        raise StudyError(f"no record file matches {pattern!r}")
                    records.extend(hits)
                else:
                    records.append(pattern)
        bodies = []
        for d in data["bodies"]:
            d = _table(d, "[bodies]")
            keys = [k for k, v in d.items() if isinstance(v, list)]
            n = math.prod(len(d[k]) for k in keys)
            if n + len(bodies) > MAX_BODIES:
                raise StudyError(f"[[bodies]]: the lists in {d} expand to {n:,} bodies, more than "
                                 f"{MAX_BODIES:,} in one study")
            for combo in itertools.product(*(d[k] for k in keys)):
                one = dict(d)
                one.update(zip(keys, combo))
                try:
                    bodies.append(_body(one))
                except (TypeError, ValueError) as exc:
                    raise StudyError(f"[[bodies]] {d}: {exc}") from None
        variants = []
        for v in data.get("variants", [{"name": "two-sided"}]):
            v = dict(_only(_table(v, "[variants]"), "variants", VARIANT_KEYS))
            if isinstance(v.get("wall"), dict):
                from .wall import Wall
                v["wall"] = Wall(**_only(dict(v["wall"]), "wall",
                                         {"gap", "side", "height", "restitution", "friction"}))
            variants.append(v)
        solver = Solver(**_only(_table(data.get("solver", {}), "solver"), "solver",
                                {"rtol", "atol", "dt", "max_steps", "max_step",
                                 "record_breakpoints", "eps_omega", "eps_t"}))
        run = dict(_only(_table(data.get("run", {}), "run"), "run",
                         {"output", "backend", "scheduler", "chunk_size"}))
        for key in ("output", "scheduler"):
            if key in run and (not isinstance(run[key], str) or not run[key]):
                raise StudyError(f"[run] {key} must be a string, got {run[key]!r}")
        if "backend" in run and run["backend"] not in ("local", "dask"):
            raise StudyError(f"[run] backend must be 'local' or 'dask', got {run['backend']!r}")
        if "chunk_size" in run:
            run["chunk_size"] = V.integer("[run] chunk_size", run["chunk_size"], 1)
        if "output" in run:
            run["output"] = str(base / run["output"])
        return cls(records=records, bodies=bodies, levels=levels,
                   measure=data.get("measure", "pga"), variants=variants, solver=solver,
                   t_after=data.get("t_after", DEFAULT_T_AFTER),
                   early_exit=data.get("early_exit", True), unit=data.get("unit"),
                   dt=data.get("dt"), name=data.get("name", name), run=run,
                   polarities=tuple(data.get("polarities", (1,))))

    # ---------------------------------------------------------- validation
    def prepare(self):
        """Validate everything and load the records (no simulation).

        Returns
        -------
        _Prepared
            Records (GroundMotion), bodies, variant labels and walls, levels,
            solver and the study hash.

        Raises
        ------
        StudyError
            A missing record file, a record whose PGA is 0, a bad level or
            measure, a body/wall combination no kernel supports, ...
        """
        if not isinstance(self.measure, str) or self.measure not in MEASURES:
            raise StudyError(f"measure must be one of {list(MEASURES)}, got {self.measure!r}")
        levels = _levels(self.levels)
        try:
            early_exit = V.boolean("early_exit", self.early_exit)
            if self.unit is not None:
                from .records import _canonical_unit
                _canonical_unit(self.unit)
            if self.dt is not None:
                V.positive("dt", self.dt)
        except ValueError as exc:
            raise StudyError(str(exc)) from None
        records = _load(self.records, self.unit, self.dt)
        if not self.bodies:
            raise StudyError("bodies is empty")
        bodies = list(self.bodies)
        for i, b in enumerate(bodies):
            if not isinstance(b, (RigidBlock, FlexibleBody)):
                raise StudyError(f"bodies[{i}] must be a RigidBlock or FlexibleBody, "
                                 f"got {type(b).__name__}")
        names, walls, effects = _variants(self.variants)
        solver = self.solver
        if solver is None:
            solver = Solver()
        elif isinstance(solver, dict):
            try:
                solver = Solver(**solver)
            except TypeError as exc:     # an unknown or missing key
                raise StudyError(f"solver: {exc}") from None
        elif not isinstance(solver, Solver):
            raise StudyError(f"solver must be a fastrock.Solver or a dict, got {type(solver).__name__}")
        try:
            t_after = V.run_time("t_after", V.non_negative("t_after", self.t_after))
            longest = V.run_time("t_after", max(r.duration for r in records) + t_after,
                                 "the longest record plus t_after")
            solver.check_fixed_steps(longest, "the longest record plus t_after")
        except ValueError as exc:
            raise StudyError(str(exc)) from None
        _check_intensity(levels, self.measure, records, bodies)
        from .foundation import block_inertia as _block_inertia
        specs, y0s = {}, {}
        for bi, body in enumerate(bodies):
            for vi, wall in enumerate(walls):
                try:
                    friction, foundation, mass = _resolve_effects(body, effects[vi])
                    specs[bi, vi] = models.select(body, wall, friction, foundation, mass)
                except (TypeError, ValueError) as exc:
                    raise StudyError(f"body {bi} with variant {names[vi]!r}: {exc}") from None
                y0s[bi, vi] = (np.zeros(specs[bi, vi].n_state) if foundation is None else
                               foundation.initial_state(_block_inertia(body, mass), 0.0, 0.0))
        prep = _Prepared(records=records, bodies=bodies, body_labels=_body_labels(bodies),
                         variant_names=names, walls=walls, levels=levels, measure=self.measure,
                         solver=solver, t_after=t_after, early_exit=early_exit,
                         specs=specs, effects=effects, y0s=y0s,
                         polarities=_polarities(self.polarities))
        prep.hash = _study_hash(prep)
        return prep

    @property
    def n_runs(self):
        return (len(self.bodies) * len(self.variants) * len(self.levels) * len(self.records)
                * len(_polarities(self.polarities)))


def _polarities(value):
    """The record signs of a study: a non-empty tuple of distinct +1/-1."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise StudyError(f"polarities must be a list of +1/-1, e.g. [1, -1], got {value!r}")
    signs = tuple(value)
    if not signs or len(set(signs)) != len(signs) or any(
            isinstance(v, bool) or v not in (1, -1) for v in signs):
        raise StudyError(f"polarities must be 1, -1 or both, each once, got {list(signs)!r}")
    return tuple(int(v) for v in signs)


@dataclass
class _Prepared:
    records: list
    bodies: list
    body_labels: list
    variant_names: list
    walls: list
    levels: np.ndarray
    measure: str
    solver: Solver
    t_after: float
    early_exit: bool
    specs: dict
    effects: list = field(default_factory=list)    # per variant: friction, foundation, mass
    y0s: dict = field(default_factory=dict)        # (body, variant) -> initial state
    hash: str = ""
    polarities: tuple = (1,)


def _levels(levels):
    try:
        a = V.finite_array("levels", np.atleast_1d(V.finite_array("levels", levels, np.ndim(levels))))
    except (TypeError, ValueError) as exc:
        raise StudyError(str(exc)) from None
    if a.size == 0:
        raise StudyError("levels is empty")
    if (a <= 0).any():
        raise StudyError(f"levels must be > 0, got {a.tolist()}")
    if np.unique(a).size != a.size:
        raise StudyError(f"levels must be distinct, got {a.tolist()}")
    return a


def _check_intensity(levels, measure, records, bodies):
    """Refuse levels that scale some record beyond V.MAX_ACCELERATION_G."""
    pga = np.array([r.pga for r in records])
    top = levels.max()
    if measure == "pga":
        peak = top * G_STANDARD
    elif measure == "pgv":
        pgv = np.array([r.pgv for r in records])
        peak = top * np.max(pga / np.where(pgv > 0, pgv, np.inf))
    elif measure == "pga_over_g_tan_alpha":
        peak = top * max(b.g * math.tan(b.alpha) for b in bodies)
    else:
        peak = top * pga.max()
    try:
        V.acceleration("levels", peak, G_STANDARD,
                       f"the scaled PGA at the largest level ({top:g}, measure {measure})")
    except ValueError as exc:
        raise StudyError(str(exc)) from None


def _load(records, unit, dt):
    """GroundMotion objects with unique names; clear errors first."""
    if isinstance(records, (str, os.PathLike, GroundMotion, dict)):
        records = [records]
    if not records:
        raise StudyError("records is empty")
    out = []
    for r in records:
        if isinstance(r, GroundMotion):
            out.append(r)
            continue
        layout = {}
        if isinstance(r, dict):
            f, u, d = r.get("file"), r.get("unit", unit), r.get("dt", dt)
            layout = {k: r[k] for k in ("column", "decimal") if k in r}
        elif isinstance(r, (str, os.PathLike)):
            f, u, d = r, unit, dt
        else:
            raise StudyError(f"records must be file paths or GroundMotion objects, "
                             f"got {type(r).__name__}")
        if f == "default":
            out.append(load_default_record())
            continue
        p = Path(f)
        if not p.is_file():
            raise StudyError(f"record file not found: {p}")
        try:
            out.append(_read_one(p, u, d, **layout))
        except ValueError as exc:
            raise StudyError(f"cannot read record {p}: {exc}") from None
    for r in out:
        if r.pga == 0.0:
            where = f" ({r.source})" if r.source else ""
            raise StudyError(f"record {r.name!r}{where} has PGA = 0 (all zero): it cannot be "
                             f"scaled to an intensity level")
    return load_records(out)          # unique names


def _variants(variants):
    if isinstance(variants, dict):
        variants = [variants]
    if not variants:
        raise StudyError("variants is empty (use [{'wall': None}] for two-sided rocking)")
    names, walls, effects = [], [], []
    for i, v in enumerate(variants):
        if not isinstance(v, dict):
            raise StudyError(f"variants[{i}] must be a dict such as {{'wall': None}}, got {v!r}")
        extra = set(v) - VARIANT_KEYS
        if extra:
            raise StudyError(f"variants[{i}]: unknown key(s) {sorted(extra)}; known: "
                             f"{', '.join(sorted(VARIANT_KEYS))}")
        try:
            (wall,) = _as_walls([v.get("wall")])
            effects.append(_variant_effects(v))
        except (TypeError, ValueError) as exc:
            raise StudyError(f"variants[{i}]: {exc}") from None
        walls.append(wall)
        label = _wall_label(wall)
        if effects[-1].get("friction") is not None:
            label += f", mu={effects[-1]['friction'].mu_s:g}"
        if effects[-1].get("foundation") is not None:
            fnd = effects[-1]["foundation"]
            label += f", {fnd['type'] if isinstance(fnd, dict) else fnd.model} foundation"
        names.append(str(v.get("name") or label))
    if len(set(names)) != len(names):
        raise StudyError(f"variant names must be distinct, got {names}")
    return names, walls, effects


#: Keys of a scene variant: its name and the effects it switches on.
VARIANT_KEYS = {"name", "wall", "friction", "foundation", "mass"}


def _variant_effects(v):
    """A variant's friction (Friction), foundation (an object, or a scene-style table resolved
    per body) and block mass [kg]; only the keys it gives."""
    out = {}
    fr = v.get("friction")
    if fr is not None:
        from .friction import Friction
        out["friction"] = Friction(**fr) if isinstance(fr, dict) else fr
    if v.get("foundation") is not None:
        fnd = v["foundation"]
        if isinstance(fnd, dict):
            fnd = dict(fnd)
            if "mass" in fnd:
                raise ValueError("give the block mass as the variant's mass, not inside foundation")
        out["foundation"] = fnd
        out["mass"] = V.positive("mass", v.get("mass", 1.0))
    elif "mass" in v:
        raise ValueError("mass goes with a foundation")
    return out


def _resolve_effects(body, fx):
    """The variant's effects for one body: a foundation table becomes its model object."""
    fnd = fx.get("foundation")
    mass = fx.get("mass", 1.0)
    if isinstance(fnd, dict):
        from .scene import _foundation
        fnd, _mass = _foundation({**fnd, "mass": mass}, body)   # omega refers to this block's mass
    return fx.get("friction"), fnd, mass


def _body_labels(bodies):
    labels = []
    for b in bodies:
        if isinstance(b, FlexibleBody):
            s = f"flexible alpha={b.alpha:.4g} p={b.p:.4g} wn/p={b.omega_n_over_p:.4g}"
        elif b.b is not None and b.h is not None:
            s = f"b={b.b:.4g} h={b.h:.4g}"
        else:
            s = f"alpha={b.alpha:.4g} p={b.p:.4g}"
        labels.append(s)
    seen = {}
    out = []
    for s in labels:
        seen[s] = seen.get(s, 0) + 1
        out.append(s if seen[s] == 1 else f"{s} ({seen[s]})")
    return out


def _canon(obj):
    """JSON-able canonical form (floats kept exact by repr)."""
    if dataclasses.is_dataclass(obj):
        d = {"__type__": type(obj).__name__}
        # a field marked hash_default (added after studies were saved) counts only when it is set,
        # so the studies saved before it keep their hash and resume
        d.update({f.name: _canon(getattr(obj, f.name)) for f in dataclasses.fields(obj)
                  if not (f.metadata.get("hash_default") and getattr(obj, f.name) == f.default)})
        return d
    if isinstance(obj, dict):
        return {str(k): _canon(v) for k, v in sorted(obj.items())}
    if isinstance(obj, (list, tuple)):
        return [_canon(x) for x in obj]
    if isinstance(obj, np.ndarray):
        return [_canon(x) for x in obj.tolist()]
    if isinstance(obj, (np.floating, float)):
        return repr(float(obj))
    if isinstance(obj, (np.integer, int, bool, str)) or obj is None:
        return obj if not isinstance(obj, np.integer) else int(obj)
    raise TypeError(f"cannot hash {type(obj).__name__}")


def _study_hash(prep):
    recs = [{"name": r.name, "dt": repr(r.dt), "npts": r.npts,
             "acc": hashlib.sha256(np.ascontiguousarray(r.acc, "<f8").tobytes()).hexdigest()}
            for r in prep.records]
    doc = {"format": FORMAT, "records": recs, "bodies": _canon(prep.bodies),
           # a variant with more than a wall adds its effects; wall-only hashes stay as they were
           "variants": [[n, _canon(w)] + ([_canon(fx)] if fx else [])
                        for n, w, fx in zip(prep.variant_names, prep.walls,
                                            prep.effects or [{}] * len(prep.walls))],
           "levels": _canon(prep.levels), "measure": prep.measure, "solver": _canon(prep.solver),
           "t_after": repr(prep.t_after), "early_exit": prep.early_exit}
    if prep.polarities != (1,):        # studies saved before polarities keep their hash
        doc["polarities"] = list(prep.polarities)
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


# ==================================================================== plan
@dataclass
class _Chunk:
    id: str
    kernel: str
    rows: np.ndarray


class _Plan:
    """Every row of a prepared study, its scale and its chunk."""

    def __init__(self, prep, chunk_size):
        self.prep = prep
        self.chunk_size = int(chunk_size)
        # a record slot is one record with one polarity (record-major: record, then sign)
        npol = len(prep.polarities)
        self.slot_record = np.repeat(np.arange(len(prep.records)), npol)
        self.slot_sign = np.tile(np.array(prep.polarities, float), len(prep.records))
        nr, nb, nv, nl = self.slot_record.size, len(prep.bodies), len(prep.walls), prep.levels.size
        R, B, W, Lv = (a.ravel() for a in np.meshgrid(np.arange(nr), np.arange(nb), np.arange(nv),
                                                      np.arange(nl), indexing="ij"))
        self.rec, self.body, self.var, self.lvl = R, B, W, Lv
        self.n = R.size
        # per-slot record measures, computed once per record (mean_period is an FFT per call)
        sr = self.slot_record
        pga = np.array([r.pga for r in prep.records])[sr]
        pgv = np.array([r.pgv for r in prep.records])[sr]
        tm = np.array([r.mean_period for r in prep.records])[sr]
        self.rec_cols = {"record_pga_g": pga / G_STANDARD, "record_pgv": pgv, "mean_period": tm,
                         "duration": np.array([r.duration for r in prep.records])[sr]}
        self.rec_names = np.array([r.name for r in prep.records], dtype=object)[sr]
        self.body_labels = np.array(prep.body_labels, dtype=object)
        self.variant_names = np.array(prep.variant_names, dtype=object)
        alpha = np.array([b.alpha for b in prep.bodies])
        p = np.array([b.p for b in prep.bodies])
        g_body = np.array([b.g for b in prep.bodies])
        uplift = g_body * np.tan(alpha)
        self.body_cols = {"alpha": alpha, "p": p,
                          "e": np.array([b.e for b in prep.bodies], float),
                          "b": np.array([_nan(getattr(b, "b", None)) for b in prep.bodies]),
                          "h": np.array([_nan(getattr(b, "h", None)) for b in prep.bodies])}
        self.wall_gaps = np.array([_wall_gap(w) for w in prep.walls], float)
        level = prep.levels[Lv]
        if prep.measure == "pga":
            scale = level * G_STANDARD / pga[R]
        elif prep.measure == "pgv":
            if (pgv == 0).any():
                bad = sorted({n for n, v in zip(self.rec_names, pgv) if v == 0})
                raise StudyError(f"record(s) {bad} have PGV = 0: cannot scale to a PGV level")
            scale = level / pgv[R]
        elif prep.measure == "pga_over_g_tan_alpha":
            scale = level * uplift[B] / pga[R]
        else:
            scale = level.copy()
        self.scale = scale
        self.level = level
        self.im = {"pga_g": scale * pga[R] / G_STANDARD, "pgv": scale * pgv[R],
                   "pga_over_g_tan_alpha": scale * pga[R] / uplift[B],
                   "omega_p_over_p": (2.0 * math.pi / tm[R]) / p[B]}
        # the study's own measure is the level itself (the scaled samples'
        # value differs by an ulp or two), so that rows of one level share
        # one IM value: df[df.pga_g == 0.3] selects the level
        own = {"pga": "pga_g", "pgv": "pgv", "pga_over_g_tan_alpha": "pga_over_g_tan_alpha"}
        if prep.measure in own:
            self.im[own[prep.measure]] = level.copy()
        kname = np.array([prep.specs[b, v].name for b, v in zip(B, W)], dtype=object)
        self.kernel = kname
        self.chunks = []
        for k in dict.fromkeys(kname.tolist()):
            rows = np.flatnonzero(kname == k)
            for s in range(0, rows.size, self.chunk_size):
                cid = f"{len(self.chunks):05d}"
                self.chunks.append(_Chunk(cid, k, rows[s:s + self.chunk_size]))

    def payload(self, chunk):
        """Plain data for :func:`run_chunk` (arrays, strings, ints)."""
        prep = self.prep
        rows = chunk.rows
        # shuffle the rows inside the chunk (fixed seed) so that the static
        # prange schedule gives every thread a mix of low and high levels;
        # rows are independent, so the numbers do not depend on the order
        order = np.random.default_rng(int(chunk.id)).permutation(rows.size)
        rows = rows[order]
        recs = list(dict.fromkeys(self.slot_record[self.rec[rows]].tolist()))
        local = {k: i for i, k in enumerate(recs)}
        lens = [prep.records[k].npts for k in recs]
        offsets = np.concatenate([[0], np.cumsum(lens)[:-1]]).astype(float)
        smp = np.concatenate([np.asarray(prep.records[k].acc, float) for k in recs])
        m = rows.size
        spec0 = prep.specs[self.body[rows[0]], self.var[rows[0]]]
        PAR = np.array([prep.specs[self.body[i], self.var[i]].par for i in rows])
        HDR = np.zeros((m, L.N_EXC))
        HDR[:, L.X_KIND] = L.EXC_SAMPLED
        HDR[:, L.X_AMP] = self.scale[rows]           # SAMPLED: X_AMP is the scale factor
        HDR[:, L.X_SIGN] = self.slot_sign[self.rec[rows]]
        ri = self.slot_record[self.rec[rows]]
        HDR[:, L.X_DT] = [prep.records[k].dt for k in ri]
        HDR[:, L.X_N] = [prep.records[k].npts for k in ri]
        HDR[:, L.X_DUR] = [prep.records[k].duration for k in ri]
        HDR[:, L.X_OFFSET] = offsets[[local[k] for k in ri]]
        OPT = np.tile(prep.solver.options(0.0, prep.early_exit), (m, 1))
        OPT[:, L.O_T_END] = HDR[:, L.X_DUR] + prep.t_after
        return {"chunk": chunk.id, "module": spec0.module, "kernel": spec0.name,
                "rows": rows.astype(np.int64),
                "Y0": np.array([prep.y0s[self.body[i], self.var[i]] for i in rows], float).reshape(m, -1),
                "PAR": PAR, "HDR": HDR, "smp": smp, "OPT": OPT, "numba_threads": 0}

    def columns(self, chunk, result):
        """The chunk's table (column name -> array, in :data:`RESULT_COLUMNS`
        order) from the kernel output of :func:`run_chunk`."""
        prep = self.prep
        order = np.argsort(result["rows"], kind="stable")
        rows = result["rows"][order]
        if not np.array_equal(rows, chunk.rows):
            raise StudyError(f"chunk {chunk.id}: the worker returned other rows than asked")
        status = result["status"][order]
        MET = result["met"][order]
        m = rows.size
        R, B, W = self.rec[rows], self.body[rows], self.var[rows]
        alpha = self.body_cols["alpha"][B]
        outcome = np.array([outcome_of(c) for c in status], dtype=object)
        return {
            "row": rows.astype(np.int64),
            "chunk": np.full(m, chunk.id, dtype=object),
            "record_index": self.slot_record[R].astype(np.int64),
            "record": self.rec_names[R],
            "polarity": self.slot_sign[R].astype(np.int64),
            "body_index": B.astype(np.int64),
            "body": self.body_labels[B],
            "variant_index": W.astype(np.int64),
            "variant": self.variant_names[W],
            "wall_gap": self.wall_gaps[W],
            "level_index": self.lvl[rows].astype(np.int64),
            "measure": np.full(m, prep.measure, dtype=object),
            "level": self.level[rows],
            "kernel": np.full(m, chunk.kernel, dtype=object),
            **{k: v[B] for k, v in self.body_cols.items()},
            **{k: v[R] for k, v in self.rec_cols.items()},
            "scale": self.scale[rows],
            **{k: v[rows] for k, v in self.im.items()},
            "outcome": outcome,
            "status": np.array([status_of(c) for c in status], dtype=object),
            "status_code": status.astype(np.int64),
            "overturned": np.isin(outcome, COLLAPSE_OUTCOMES),
            "max_rotation_ratio": MET[:, L.M_MAX_ABS_THETA] / alpha,
            "impacts": MET[:, L.M_IMPACTS], "wall_impacts": MET[:, L.M_WALL_IMPACTS],
            "time_uplift": MET[:, L.M_T_UPLIFT], "time_overturn": MET[:, L.M_T_OVER],
            "time_end": MET[:, L.M_T_FINAL], "nfev": MET[:, L.M_NFEV],
            "steps": MET[:, L.M_NSTEPS], "rejected_steps": MET[:, L.M_NREJECT],
        }

    def frame(self, chunk, result):
        """:meth:`columns` as a DataFrame (as :func:`load_results` reads it)."""
        return _arrow_table(self.columns(chunk, result), "").to_pandas()


def _nan(x):
    return math.nan if x is None else float(x)


# ================================================================= worker
_KERNEL_LOCK = threading.Lock()


def run_chunk(payload):
    """Run one chunk with its model's parallel sweep kernel.

    The Dask task function: top level, plain data in and out, pure (the
    same payload always gives the same arrays), no side effect, so Dask may
    rerun it anywhere.  Kernel calls of one process are serialised by a lock
    (each call already uses every Numba thread; some threading layers do not
    allow concurrent launches from several threads).

    Parameters
    ----------
    payload : dict
        ``module``, ``kernel`` (names in :mod:`fastrock.kernels`), ``rows``
        (int64[m]), kernel inputs ``Y0`` (m, n_state), ``PAR``, ``HDR``
        (m, N_EXC), ``smp`` (samples [m/s^2]), ``OPT`` (m, N_OPT), and
        ``numba_threads`` (> 0: Numba threads for this call).

    Returns
    -------
    dict
        ``rows``, ``status`` (int64[m]), ``met`` (float64[m, N_MET]),
        ``seconds`` (kernel wall time), ``pid``.
    """
    import importlib
    mod = importlib.import_module(f"fastrock.kernels.{payload['module']}")
    sweep = getattr(mod, f"{payload['kernel']}_sweep")
    Y0 = np.ascontiguousarray(payload["Y0"], float)
    m = Y0.shape[0]
    status = np.empty(m, np.int64)
    met = np.empty((m, L.N_MET))
    yf = np.empty_like(Y0)
    with _KERNEL_LOCK:
        nt = int(payload.get("numba_threads") or 0)
        if nt > 0:
            import numba
            numba.set_num_threads(min(nt, numba.config.NUMBA_NUM_THREADS))
        t0 = time.perf_counter()
        opt = np.array(payload["OPT"], float, order="C")
        call_kernel(sweep, Y0, np.ascontiguousarray(payload["PAR"], float),
                    np.ascontiguousarray(payload["HDR"], float), np.ascontiguousarray(payload["smp"], float),
                    opt, status, met, yf, opt=opt)
        seconds = time.perf_counter() - t0
    return {"rows": np.asarray(payload["rows"], np.int64), "status": status, "met": met,
            "seconds": seconds, "pid": os.getpid()}


def _worker_info():
    import fastrock
    import numba
    return {"fastrock": fastrock.__version__, "numba": numba.__version__, "pid": os.getpid()}


# ============================================================ output folder
def _need_pyarrow():
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise StudyError("study results are Parquet files and need pyarrow: "
                         "pip install 'fastrock[distributed]' (or pip install pyarrow)") from None


def _chunk_path(folder, cid):
    return Path(folder) / RESULTS_DIR / f"chunk-{cid}.parquet"


def _atomic_write_bytes(path, data):
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def _arrow_table(cols, study_hash):
    """A pyarrow Table of the chunk columns (object arrays -> string), with
    the study hash in the schema metadata.  Built from the arrays directly:
    going through pandas costs more than the rest of a small chunk."""
    import pyarrow as pa
    arrays = {k: pa.array(v, type=pa.string()) if v.dtype == object else pa.array(v)
              for k, v in cols.items()}
    return pa.table(arrays, metadata={b"fastrock_study": study_hash.encode()})


def _write_chunk(folder, cid, cols, study_hash):
    """Write the chunk's file atomically (temporary name, then os.replace)."""
    import pyarrow.parquet as pq
    path = _chunk_path(folder, cid)
    if isinstance(cols, pd.DataFrame):
        cols = {k: cols[k].to_numpy(dtype=object if cols[k].dtype.kind not in "biuf" else None)
                for k in cols.columns}
    table = _arrow_table(cols, study_hash)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    pq.write_table(table, tmp)
    os.replace(tmp, path)


def _chunk_done(folder, chunk, study_hash):
    """The chunk's file exists, is readable and belongs to this study."""
    import pyarrow.parquet as pq
    path = _chunk_path(folder, chunk.id)
    if not path.is_file():
        return False
    try:
        md = pq.read_metadata(path)
    except Exception:  # noqa: BLE001 - unreadable: rerun the chunk
        return False
    meta = md.metadata or {}
    return md.num_rows == chunk.rows.size and meta.get(b"fastrock_study") == study_hash.encode()


def _manifest(plan, study):
    prep = plan.prep
    return {
        "format": FORMAT,
        "study_hash": prep.hash,
        "name": study.name,
        "chunk_size": plan.chunk_size,
        "n_rows": int(plan.n),
        "records": [r.name for r in prep.records],
        "bodies": prep.body_labels,
        "variants": prep.variant_names,
        "measure": prep.measure,
        "levels": prep.levels.tolist(),
        "solver": prep.solver.name,
        "t_after": prep.t_after,
        "chunks": [{"id": c.id, "kernel": c.kernel, "n_rows": int(c.rows.size),
                    "first_row": int(c.rows[0]), "file": f"{RESULTS_DIR}/chunk-{c.id}.parquet"}
                   for c in plan.chunks],
    }


def _read_manifest(folder):
    path = Path(folder) / MANIFEST
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise StudyError(f"{path}: unreadable manifest ({exc}); remove the folder or choose "
                         f"another output") from None


def _check_folder(folder, prep, chunk_size):
    """Chunk size to use; StudyError if the folder holds another study."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise StudyError(f"output {folder} exists and is not a folder")
    man = _read_manifest(folder)
    if man is None:
        if (folder / RESULTS_DIR).is_dir() and any((folder / RESULTS_DIR).iterdir()):
            raise StudyError(f"output folder {folder} holds results but no {MANIFEST}: "
                             f"choose an empty folder")
        return int(chunk_size or DEFAULT_CHUNK_SIZE)
    if man.get("study_hash") != prep.hash:
        raise StudyError(
            f"output folder {folder} holds a different study (hash {str(man.get('study_hash'))[:12]}"
            f", this study {prep.hash[:12]}): choose a new output folder, or delete that one")
    if chunk_size is not None and int(chunk_size) != int(man["chunk_size"]):
        raise StudyError(f"output folder {folder} was started with chunk_size="
                         f"{man['chunk_size']}; resume with the same chunk size (or omit it)")
    return int(man["chunk_size"])


def load_results(folder):
    """All finished rows of a study folder as one DataFrame.

    Columns as in :data:`RESULT_COLUMNS`, sorted by ``row``.
    ``df.attrs``: ``study_hash``, ``complete`` (every chunk present),
    ``missing_chunks`` (ids).
    """
    _need_pyarrow()
    import pyarrow.parquet as pq
    folder = Path(folder)
    man = _read_manifest(folder)
    if man is None:
        raise StudyError(f"{folder}: no {MANIFEST}; not a study folder")
    frames, missing = [], []
    for c in man["chunks"]:
        path = folder / c["file"]
        if not path.is_file():
            missing.append(c["id"])
            continue
        t = pq.read_table(path)
        if (t.schema.metadata or {}).get(b"fastrock_study") != man["study_hash"].encode():
            raise StudyError(f"{path} belongs to another study")
        frames.append(t.replace_schema_metadata(None))
    if frames:
        import pyarrow as pa
        df = pa.concat_tables(frames).to_pandas()
        df = df.sort_values("row", kind="stable").reset_index(drop=True)
    else:
        df = pd.DataFrame()
    df.attrs.update(study_hash=man["study_hash"], complete=not missing, missing_chunks=missing,
                    n_rows=man["n_rows"])
    return df


# =================================================================== run
def run_study(study, output, backend=None, client=None, scheduler=None, chunk_size=None,
              progress=True, *, retries=RETRIES, connect_timeout=CONNECT_TIMEOUT,
              numba_threads=None, n_workers=None, callback=None):
    """Run (or resume) a study into the folder ``output``.

    Parameters
    ----------
    study : Study
    output : path
        Folder of the partitioned Parquet dataset and ``manifest.json``;
        created if needed.  Rerunning into it skips the finished chunks.
    backend : {"local", "dask"}, optional
        Default: "dask" if ``client`` or ``scheduler`` is given, else "local".
    client : dask.distributed.Client, optional
    scheduler : str, optional
        Scheduler address, e.g. ``"tcp://10.0.0.5:8786"``.  With backend
        "dask" and neither ``client`` nor ``scheduler``, a LocalCluster on
        127.0.0.1 is started for the call (``n_workers`` processes, default
        the CPU count, one thread and one Numba thread each).
    chunk_size : int, optional
        Rows per chunk (default :data:`DEFAULT_CHUNK_SIZE`, or the folder's).
    progress : bool
        Progress bar on stderr (rows done, rate, ETA).
    retries : int
        Dask retries of a chunk whose task raised.
    connect_timeout : float
        Seconds to reach a scheduler given by address.
    numba_threads : int, optional
        Numba threads per chunk on Dask workers (default: Numba's default).
    callback : callable, optional
        ``callback(chunk_id, n_chunks_done, n_chunks)`` after each chunk is
        written.

    Returns
    -------
    pandas.DataFrame
        :func:`load_results` of the folder; ``attrs`` add ``chunks_run``,
        ``chunks_skipped``, ``kernel_seconds``, ``wall_seconds``, ``backend``.

    Raises
    ------
    StudyError
        Before any work: bad input, unreachable scheduler, output folder of
        another study.  After the work: chunks that failed (the others are
        saved; rerun to retry those).
    """
    if not isinstance(study, Study):
        raise StudyError(f"study must be a fastrock.study.Study, got {type(study).__name__}")
    if backend is None:
        backend = "dask" if (client is not None or scheduler is not None) else "local"
    if backend not in ("local", "dask"):
        raise StudyError(f"backend must be 'local' or 'dask', got {backend!r}")
    if backend == "local" and (client is not None or scheduler is not None):
        raise StudyError("client/scheduler given with backend='local'")
    if client is not None and scheduler is not None:
        raise StudyError("give either client= or scheduler=, not both")
    if chunk_size is not None:
        try:
            chunk_size = V.integer("chunk_size", chunk_size, 1)
        except ValueError:
            raise StudyError(f"chunk_size must be a positive integer, got {chunk_size!r}") from None
    _need_pyarrow()
    prep = study.prepare()
    folder = Path(output)
    cs = _check_folder(folder, prep, chunk_size)
    plan = _Plan(prep, cs)
    todo = [c for c in plan.chunks if not _chunk_done(folder, c, prep.hash)]
    own = None
    if backend == "dask":
        client, own = _connect(client, scheduler, connect_timeout, n_workers)
        if own is not None and numba_threads is None:
            numba_threads = 1
    try:
        (folder / RESULTS_DIR).mkdir(parents=True, exist_ok=True)
        _atomic_write_bytes(folder / MANIFEST, json.dumps(_manifest(plan, study), indent=1).encode())
        for tmp in (folder / RESULTS_DIR).glob(".*.tmp"):
            tmp.unlink(missing_ok=True)   # left by a crash mid-write
        stats = {"kernel_seconds": 0.0, "chunks_run": 0}
        t0 = time.perf_counter()
        bar = Progress(sum(c.rows.size for c in todo), progress, "runs")
        n_total = len(plan.chunks)
        done_before = n_total - len(todo)

        def finish(chunk, result):
            _write_chunk(folder, chunk.id, plan.columns(chunk, result), prep.hash)
            stats["kernel_seconds"] += float(result["seconds"])
            stats["chunks_run"] += 1
            bar.update(chunk.rows.size)
            if callback is not None:
                callback(chunk.id, done_before + stats["chunks_run"], n_total)

        interrupted = False
        try:
            if backend == "local":
                for chunk in todo:
                    finish(chunk, run_chunk(plan.payload(chunk)))
            else:
                failed = _run_dask(client, plan, todo, finish, retries, numba_threads)
                if failed:
                    bar.close()
                    msg = "; ".join(f"chunk {cid}: {type(e).__name__}: {e}" for cid, e in failed[:5])
                    raise StudyError(f"{len(failed)} of {len(todo)} chunks failed ({msg}); the "
                                     f"{stats['chunks_run']} others are saved in {folder}; rerun "
                                     f"run_study to retry the failed ones")
        except KeyboardInterrupt:
            interrupted = True
            warnings.warn(f"interrupted: {done_before + stats['chunks_run']} of {n_total} chunks "
                          f"are saved in {folder}; rerun to resume", stacklevel=2)
        finally:
            bar.close()
        wall = time.perf_counter() - t0
    finally:
        if own is not None:
            own()
    df = load_results(folder)
    df.attrs.update(chunks_run=stats["chunks_run"], chunks_skipped=done_before,
                    kernel_seconds=stats["kernel_seconds"], wall_seconds=wall, backend=backend,
                    interrupted=interrupted, chunk_size=cs, n_chunks=n_total)
    return df


def _connect(client, scheduler, timeout, n_workers):
    """(client, closer or None).  Errors before any work."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise StudyError("the Dask backend needs dask.distributed: "
                         "pip install 'fastrock[distributed]'") from None
    closer = None
    if client is None:
        if scheduler is not None:
            if not isinstance(scheduler, str) or not scheduler.strip():
                raise StudyError(f"scheduler must be an address such as 'tcp://host:8786', "
                                 f"got {scheduler!r}")
            try:
                client = Client(scheduler, timeout=timeout, set_as_default=False)
            except (OSError, TimeoutError, ValueError) as exc:
                raise StudyError(f"cannot reach the Dask scheduler at {scheduler} within "
                                 f"{timeout:g} s ({type(exc).__name__}: {exc})") from None
            closer = client.close
        else:
            cluster = LocalCluster(n_workers=n_workers or os.cpu_count() or 1, threads_per_worker=1,
                                   processes=True, host="127.0.0.1", dashboard_address=None)
            client = Client(cluster, set_as_default=False)

            def closer():
                client.close()
                cluster.close()
    elif not hasattr(client, "submit"):
        raise StudyError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
    try:
        info = client.run(_worker_info)
    except Exception as exc:  # noqa: BLE001 - typically fastrock missing on the workers
        if closer is not None:
            closer()
        raise StudyError(f"the Dask workers cannot run fastrock ({type(exc).__name__}: {exc}); "
                         f"install fastrock on every worker") from None
    import fastrock
    versions = {v["fastrock"] for v in info.values()}
    if versions - {fastrock.__version__}:
        warnings.warn(f"workers run fastrock {sorted(versions)}, this client "
                      f"{fastrock.__version__}", stacklevel=3)
    if not info:
        warnings.warn("the Dask scheduler has no workers yet; chunks wait for them", stacklevel=3)
    return client, closer


def _run_dask(client, plan, todo, finish, retries, numba_threads):
    """Submit one task per chunk; write each as it completes.  Returns the
    [(chunk id, exception)] of chunks that failed after their retries."""
    from distributed import as_completed
    by_key = {}
    futures = []
    for chunk in todo:
        payload = plan.payload(chunk)
        payload["numba_threads"] = int(numba_threads or 0)
        key = f"fastrock-study-{plan.prep.hash[:16]}-{chunk.id}"
        fut = client.submit(run_chunk, payload, key=key, pure=True, retries=int(retries))
        by_key[fut.key] = chunk
        futures.append(fut)
    failed = []
    ac = as_completed(futures, loop=client.loop)     # this client, even if not the default
    try:
        for fut in ac:
            chunk = by_key[fut.key]
            if fut.status == "error":
                failed.append((chunk.id, fut.exception()))
            else:
                finish(chunk, fut.result())
            fut.release()
    except BaseException:
        client.cancel([f for f in futures if not f.done()])
        raise
    return failed


# ============================================================== fragility
@dataclass
class FragilityFit:
    """Lognormal fragility ``P(IM) = Phi(ln(IM / theta) / beta)``.

    Attributes
    ----------
    theta : float
        Median capacity, in the unit of ``im``.
    beta : float
        Logarithmic standard deviation [-].
    im : str
        IM column.
    event : str
        "overturning" or "max_rotation_ratio > x".
    se_ln_theta, se_beta : float
        Asymptotic standard errors (inverse observed information; rows taken
        as independent).
    boot_theta, boot_beta : ndarray
        Bootstrap estimates (records resampled with replacement).
    ci : float
        Coverage of :meth:`band` and :meth:`interval`.
    x, n, k : ndarray
        Distinct IM values, trials and events at each (the data fitted).
    """

    theta: float
    beta: float
    im: str
    event: str
    se_ln_theta: float
    se_beta: float
    loglik: float
    n_rows: int
    n_events: int
    n_records: int
    n_excluded: int
    x: np.ndarray
    n: np.ndarray
    k: np.ndarray
    boot_theta: np.ndarray
    boot_beta: np.ndarray
    n_boot_failed: int
    ci: float
    label: str = ""

    def probability(self, im):
        """P(event | IM) of the fitted curve."""
        return _fragility(np.asarray(im, float), self.theta, self.beta)

    def band(self, im, ci=None):
        """Pointwise bootstrap band (lo, hi) of P at ``im``."""
        ci = self.ci if ci is None else ci
        im = np.asarray(im, float)
        if self.boot_theta.size == 0:
            p = self.probability(im)
            return p, p
        curves = _fragility(im[None, :], self.boot_theta[:, None], self.boot_beta[:, None])
        q = 50 * (1 - ci)
        return np.percentile(curves, q, axis=0), np.percentile(curves, 100 - q, axis=0)

    def interval(self, ci=None):
        """Bootstrap percentile intervals {"theta": (lo, hi), "beta": (lo, hi)}."""
        ci = self.ci if ci is None else ci
        q = [50 * (1 - ci), 100 - 50 * (1 - ci)]
        if self.boot_theta.size == 0:
            return {"theta": (math.nan, math.nan), "beta": (math.nan, math.nan)}
        return {"theta": tuple(np.percentile(self.boot_theta, q)),
                "beta": tuple(np.percentile(self.boot_beta, q))}


def _fragility(im, theta, beta):
    from scipy import special
    with np.errstate(divide="ignore"):
        return special.ndtr(np.log(im / theta) / beta)


_LN_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


def _mills(z):
    """phi(z) / Phi(z), stable for very negative z (both in logs)."""
    from scipy import special
    z = np.asarray(z, float)
    return np.exp(-0.5 * z * z - _LN_SQRT_2PI - special.log_ndtr(z))


def _probit_mle(u, n, k):
    """Maximise sum k ln Phi(a + b u) + (n - k) ln Phi(-(a + b u)) (concave) with
    scipy.optimize.minimize, trust-exact, on the analytic gradient and Hessian.  (Not
    least_squares: a binomial likelihood is no sum of squares.)

    Returns (a, b, cov_ab, loglik) on the standardised u; None if the
    outcomes are separated (no finite maximum) or b <= 0.
    """
    from scipy import optimize, special
    if not ((k > 0).any() and (k < n).any()):
        return None
    hi_no = u[k < n].max()        # largest IM with a non-event
    lo_yes = u[k > 0].min()       # smallest IM with an event
    if hi_no <= lo_yes:
        return None               # (quasi-)complete separation: beta -> 0

    def parts(x):
        eta = x[0] + x[1] * u
        lp, lm = _mills(eta), _mills(-eta)
        s = k * lp - (n - k) * lm
        h = -k * lp * (eta + lp) - (n - k) * lm * (lm - eta)
        return eta, s, h

    def neg_ll(x):
        eta = x[0] + x[1] * u
        return -float(np.sum(k * special.log_ndtr(eta) + (n - k) * special.log_ndtr(-eta)))

    def neg_grad(x):
        _, s, _ = parts(x)
        return -np.array([s.sum(), (s * u).sum()])

    def neg_hess(x):
        _, _, h = parts(x)
        return -np.array([[h.sum(), (h * u).sum()], [(h * u).sum(), (h * u * u).sum()]])

    res = optimize.minimize(neg_ll, np.array([0.0, 1.0]), jac=neg_grad, hess=neg_hess,
                            method="trust-exact", options={"gtol": 1e-11, "maxiter": 200})
    a, b = res.x
    if not (b > 0 and np.isfinite(b) and np.isfinite(res.fun)):
        return None
    try:
        cov = np.linalg.inv(neg_hess(res.x))
    except np.linalg.LinAlgError:
        return None
    return a, b, cov, -float(res.fun)


def _fit_weighted(lnx, rec_w, rec_of_row, y, xs_index, nx):
    """MLE from rows weighted by record multiplicity; (ln theta, beta, cov, ll)."""
    w = rec_w[rec_of_row]
    n = np.bincount(xs_index, weights=w, minlength=nx)
    k = np.bincount(xs_index, weights=w * y, minlength=nx)
    keep = n > 0
    u0 = lnx[keep]
    mu, sd = u0.mean(), u0.std()
    sd = sd if sd > 0 else 1.0
    r = _probit_mle((u0 - mu) / sd, n[keep], k[keep])
    if r is None:
        return None
    a_s, b_s, cov_s, f = r
    # eta = a_s + b_s (ln x - mu)/sd = (ln x - ln theta) / beta
    beta = sd / b_s
    ln_theta = mu - a_s * sd / b_s
    # delta method: (a_s, b_s) -> (ln theta, beta)
    J = np.array([[-sd / b_s, a_s * sd / b_s ** 2], [0.0, -sd / b_s ** 2]])
    return ln_theta, beta, J @ cov_s @ J.T, f


#: Most bootstrap resamples of fit_fragility.
MAX_BOOT = 1_000_000


def fit_fragility(df, im="pga_g", threshold=None, *, n_boot=200, seed=0, ci=0.90, label=""):
    """Lognormal fragility curve by maximum likelihood, with a bootstrap band.

    Parameters
    ----------
    df : DataFrame
        Study results (:func:`load_results`), typically one body and variant.
        Needs columns ``record``, ``outcome``, ``im`` (and
        ``max_rotation_ratio`` with ``threshold``).
    im : str
        Intensity-measure column ("pga_g", "pgv", "pga_over_g_tan_alpha",
        "scale", ...); values must be > 0.
    threshold : float, optional
        None: the event is overturning (outcome mode1 or mode2).  A number
        x: the event is ``max |theta| / alpha > x`` or overturning.
    n_boot : int
        Bootstrap resamples of whole records (0: none).
    seed : int
        Seed of the resampling.
    ci : float
        Coverage of the band and intervals (default 0.90).

    Returns
    -------
    FragilityFit

    Raises
    ------
    ValueError
        No event, no non-event, or the events are separated by the IM (every
        non-event below every event): the MLE has beta -> 0 and no finite
        value; add levels or records.

    Notes
    -----
    Rows whose run failed are left out (``n_excluded``).  Each row is a
    Bernoulli trial (Baker 2015, doi:10.1193/021113EQS025M): the
    log-likelihood ``sum y ln P + (1-y) ln(1-P)`` is maximised (scipy.optimize.minimize,
    trust-exact, analytic derivatives) on the probit form ``P = Phi(a + b ln IM)``, where it is concave.
    The standard errors treat rows as independent; the rows of one record are
    not, which the record bootstrap accounts for.
    """
    n_boot = V.integer("n_boot", n_boot, 0, MAX_BOOT)
    ci = V.in_open("ci", ci, 0.0, 1.0)
    if not isinstance(im, str):
        raise ValueError(f"fit_fragility: im must be a column name, got {im!r}")
    for col in ("record", "outcome", im):
        if col not in df.columns:
            raise ValueError(f"fit_fragility: column {col!r} missing")
    ok = ~df["outcome"].isin(EXCLUDED_OUTCOMES).to_numpy()
    d = df[ok]
    x = d[im].to_numpy(float)
    if not (np.isfinite(x).all() and (x > 0).all()):
        raise ValueError(f"fit_fragility: {im} must be finite and > 0")
    over = d["outcome"].isin(COLLAPSE_OUTCOMES).to_numpy()
    if threshold is None:
        y = over.astype(float)
        event = "overturning"
    else:
        threshold = V.positive("threshold", threshold)
        if "max_rotation_ratio" not in d.columns:
            raise ValueError("fit_fragility: column 'max_rotation_ratio' missing")
        y = (over | (d["max_rotation_ratio"].to_numpy(float) > threshold)).astype(float)
        event = f"max_rotation_ratio > {threshold:g}"
    if y.size == 0:
        raise ValueError("fit_fragility: no finished rows")
    # one group per IM value; values a few ulps apart (IMs computed from the
    # scale factor, e.g. PGA/(g tan alpha) of a PGA study) are one group, at
    # their mean
    key = np.round(np.log(x) * 1e10).astype(np.int64)
    _, xi = np.unique(key, return_inverse=True)
    xs = np.bincount(xi, weights=x) / np.bincount(xi)
    rec_codes, rec_of_row = np.unique(d["record"].to_numpy(object).astype(str), return_inverse=True)
    nrec = rec_codes.size
    lnx = np.log(xs)
    r = _fit_weighted(lnx, np.ones(nrec), rec_of_row, y, xi, xs.size)
    if r is None:
        raise ValueError(
            f"fit_fragility: no finite MLE for {event} against {im}: "
            + ("no event in the data" if y.sum() == 0 else
               "every row is an event" if y.sum() == y.size else
               "the events are separated by the IM (every non-event below every event); "
               "add intensity levels or records"))
    ln_theta, beta, cov, f = r
    rng = np.random.default_rng(seed)
    bt, bb = [], []
    failed = 0
    for _ in range(int(n_boot)):
        wts = np.bincount(rng.integers(0, nrec, nrec), minlength=nrec).astype(float)
        rb = _fit_weighted(lnx, wts, rec_of_row, y, xi, xs.size)
        if rb is None:
            failed += 1
            continue
        bt.append(math.exp(rb[0]))
        bb.append(rb[1])
    if n_boot and failed > 0.05 * n_boot:
        warnings.warn(f"{failed} of {n_boot} bootstrap resamples had no finite MLE (separated); "
                      f"the band leaves them out and may be too narrow", stacklevel=2)
    n_x = np.bincount(xi, minlength=xs.size).astype(float)
    k_x = np.bincount(xi, weights=y, minlength=xs.size)
    return FragilityFit(
        theta=math.exp(ln_theta), beta=float(beta), im=im, event=event,
        se_ln_theta=math.sqrt(cov[0, 0]), se_beta=math.sqrt(cov[1, 1]), loglik=f,
        n_rows=int(y.size), n_events=int(y.sum()), n_records=int(nrec),
        n_excluded=int((~ok).sum()), x=xs, n=n_x, k=k_x, boot_theta=np.array(bt),
        boot_beta=np.array(bb), n_boot_failed=failed, ci=float(ci), label=label)


IM_LABELS = {
    "pga_g": "PGA / g",
    "pgv": "PGV [m/s]",
    "pga_over_g_tan_alpha": r"PGA / (g tan $\alpha$)",
    "scale": "scale factor",
}


def plot_fragility(fits, ax=None, im_max=None, band=True, points=True, title=None):
    """Fragility curves with bootstrap bands and the observed fractions.

    Parameters
    ----------
    fits : FragilityFit or sequence of them
    ax : matplotlib Axes, optional
    im_max : float, optional
        Right end of the IM axis (default 1.1 x the largest level).
    band : bool
        Shade the bootstrap band (coverage ``fit.ci``).
    points : bool
        Mark the observed fraction of events at each IM value (size ~ trials).

    Returns
    -------
    matplotlib Figure
    """
    from .plotting import _pyplot
    if isinstance(fits, FragilityFit):
        fits = [fits]
    if ax is None:
        plt = _pyplot()
        fig, ax = plt.subplots(figsize=(6.4, 4.6), constrained_layout=True)
    else:
        fig = ax.figure
    top = im_max or 1.1 * max(float(f.x.max()) for f in fits)
    grid = np.linspace(top / 400, top, 400)
    for i, f in enumerate(fits):
        color = f"C{i}"
        lab = f.label or f.event
        ax.plot(grid, f.probability(grid), color=color, lw=1.8,
                label=f"{lab}: $\\theta$={f.theta:.3g}, $\\beta$={f.beta:.2f}")
        if band and f.boot_theta.size:
            lo, hi = f.band(grid)
            ax.fill_between(grid, lo, hi, color=color, alpha=0.2, lw=0)
        if points:
            frac = f.k / f.n
            ax.scatter(f.x, frac, s=12 + 60 * f.n / f.n.max(), color=color, alpha=0.7,
                       edgecolor="none")
    ax.set_xlim(0, top)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(IM_LABELS.get(fits[0].im, fits[0].im))
    ax.set_ylabel("P(event | IM)")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8, loc="lower right", title_fontsize=8,
              title=f"bands: {fits[0].ci:.0%} bootstrap over records" if band else None)
    return fig


# ==================================================================== CLI
def _cli_study(args):
    if args.chunk_size is not None:
        V.integer("--chunk-size", args.chunk_size, 1)
    V.positive("--connect-timeout", args.connect_timeout)
    V.integer("--n-boot", args.n_boot, 0, MAX_BOOT)
    study = Study.from_toml(args.study)
    opts = study.run
    output = args.output or opts.get("output") or str(Path(args.study).with_suffix("")) + "_results"
    scheduler = args.scheduler or opts.get("scheduler")
    backend = args.backend or opts.get("backend") or ("dask" if scheduler else "local")
    chunk = args.chunk_size or opts.get("chunk_size")
    df = run_study(study, output, backend=backend, scheduler=scheduler if backend == "dask" else None,
                   chunk_size=chunk, progress=not args.quiet, connect_timeout=args.connect_timeout)
    a = df.attrs
    rate = a["chunks_run"] and len(df) / max(a["wall_seconds"], 1e-9)
    print(f"study {study.name or args.study}: {len(df)} runs in {a['n_chunks']} chunks of "
          f"{a['chunk_size']} ({a['chunks_skipped']} already done, {a['chunks_run']} run) in "
          f"{a['wall_seconds']:.1f} s on {backend}" + (f" ({rate:,.0f} runs/s)" if a["chunks_run"]
                                                        else ""))
    print(f"results: {output} (fastrock.study.load_results)")
    print("outcomes:", df["outcome"].value_counts().to_dict())
    im = {"pga": "pga_g", "pgv": "pgv"}.get(study.measure, study.measure)
    rows, table, fits = [], [], []
    for (body, var), grp in df.groupby(["body", "variant"], sort=False):
        try:
            f = fit_fragility(grp, im=im, n_boot=args.n_boot, label=f"{body}, {var}")
            lo, hi = f.interval()["theta"]
            rows.append((body, var, f"{f.theta:.4g}", f"{f.beta:.3f}", f"[{lo:.4g}, {hi:.4g}]"))
            table.append((body, var, im, f.theta, f.beta, lo, hi, ""))
            fits.append(f)
        except ValueError as exc:
            reason = str(exc).split(": ", 2)[-1]
            rows.append((body, var, "-", "-", reason[:40]))
            table.append((body, var, im, math.nan, math.nan, math.nan, math.nan, reason))
    print(f"overturning fragility against {im} (theta, beta; 90% bootstrap interval of theta):")
    print(pd.DataFrame(rows, columns=["body", "variant", "theta", "beta", "theta 90%"]).to_string(
        index=False))
    from .cli import write_table, wrote
    written = write_table(pd.DataFrame(table, columns=FRAGILITY_TABLE_COLUMNS), args)
    if args.png and fits:
        plot_fragility(fits).savefig(args.png, dpi=130)
        written.append(args.png)
    if a["interrupted"]:
        from .cli import interrupted_exit
        return interrupted_exit(a["chunks_skipped"] + a["chunks_run"], a["n_chunks"], "chunks",
                                [output] + written)
    wrote(written)
    return 0


#: Columns of ``fastrock study --csv``: the fragility fit per body and variant; theta in the
#: measure's unit (g for pga_g, m/s for pgv), theta_lo/theta_hi its 90 % bootstrap interval,
#: ``note`` why a fit failed (its numbers are then NaN).
FRAGILITY_TABLE_COLUMNS = ["body", "variant", "measure", "theta", "beta", "theta_lo", "theta_hi", "note"]


def add_subcommand(subparsers):
    """Register ``fastrock study study.toml [--scheduler ADDRESS] ...``."""
    s = subparsers.add_parser(
        "study", help="records x bodies x variants x levels (IDA), local or on Dask",
        description="Run (or resume) a study file: every record scaled to every intensity level "
                    "for every body and scene variant, in chunks written as Parquet; prints an "
                    "overturning fragility per body and variant.")
    s.add_argument("study", help="study file (TOML), see examples/study.toml")
    s.add_argument("--output", help="results folder (default: [run] output, or <study>_results)")
    s.add_argument("--backend", choices=("local", "dask"),
                   help="local (default) or dask (default with --scheduler)")
    s.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786 (default: none; "
                                       "--backend dask then starts a local cluster)")
    s.add_argument("--chunk-size", type=int, help=f"rows per chunk (default {DEFAULT_CHUNK_SIZE})")
    s.add_argument("--connect-timeout", type=float, default=CONNECT_TIMEOUT,
                   help=f"time to reach the scheduler [s] (default {CONNECT_TIMEOUT:g})")
    s.add_argument("--n-boot", type=int, default=200, help="bootstrap resamples (default 200)")
    from .cli import add_output_options
    add_output_options(s, figure="the fragility curves", table="the fragility table (theta, beta "
                       "per body and variant)")
    s.set_defaults(func=_cli_study)
