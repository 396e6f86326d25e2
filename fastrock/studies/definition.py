"""A study's definition: records x bodies x scene variants x intensity levels.
"""
from __future__ import annotations

import dataclasses
import glob
import hashlib
import itertools
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fastrock import _validate as V
from fastrock.running import registry
from fastrock.model.bodies import FlexibleBody, RigidBlock
from fastrock.model.rigid_body import RigidBody
from fastrock.constants import G_STANDARD
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.default_records import load_default_record
from fastrock.running.solver import DEFAULT_T_AFTER, Solver
from fastrock.analyses.rocking_spectrum.inputs import as_walls, read_one_record, label_of_wall, load_records


#: Intensity measures a study's levels can be given in (module docstring).
MEASURES = ("pga", "pgv", "pga_over_g_tan_alpha", "scale")

#: Most intensity levels of a {start, stop, num} table and most bodies a study file's
#: [[bodies]] lists may expand to.
MAX_LEVELS = 100_000

MAX_BODIES = 100_000

#: Version of the on-disk layout (part of the study hash).
FORMAT = "fastrock-study/1"

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
        File paths (any format :func:`fastrock.read_record` reads;
        ``"default"`` is the packaged El Centro record), :class:`GroundMotion`
        objects, or dicts ``{"file": ..., "unit": ..., "dt": ...}`` (also
        ``"column"`` and ``"decimal"``, as in :func:`fastrock.read_record`).
    bodies : sequence of RigidBlock, RigidBody or FlexibleBody
        An asymmetric RigidBody runs the two-sided rocking model; its
        ``alpha``, ``p`` columns are those of its smaller side.
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
        with a foundation, default 1), ``"ground"`` (a :class:`fastrock.Ground`
        or a dict of its arguments, e.g. ``{"slope": 0.1}``: sloping ground)
        and ``"name"`` (label; default from the effects).
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
        from fastrock.running.scene import tomllib
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
        from fastrock.running.scene import body_from_table, only_keys, as_table
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
            lv = only_keys(dict(levels), "levels", {"start", "stop", "num"})
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
                r = dict(only_keys(dict(r), "records", {"file", "unit", "dt", "column", "decimal"}))
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
            d = as_table(d, "[bodies]")
            # a list expands to one body per value; an outline (vertices) or an axis is one value
            keys = [k for k, v in d.items() if isinstance(v, list) and k not in ("vertices", "axis", "up")]
            n = math.prod(len(d[k]) for k in keys)
            if n + len(bodies) > MAX_BODIES:
                raise StudyError(f"[[bodies]]: the lists in {d} expand to {n:,} bodies, more than "
                                 f"{MAX_BODIES:,} in one study")
            for combo in itertools.product(*(d[k] for k in keys)):
                one = dict(d)
                one.update(zip(keys, combo))
                try:
                    bodies.append(body_from_table(one, base))
                except (TypeError, ValueError) as exc:
                    raise StudyError(f"[[bodies]] {d}: {exc}") from None
        variants = []
        for v in data.get("variants", [{"name": "two-sided"}]):
            v = dict(only_keys(as_table(v, "[variants]"), "variants", VARIANT_KEYS))
            if isinstance(v.get("wall"), dict):
                from fastrock.model.wall import Wall
                v["wall"] = Wall(**only_keys(dict(v["wall"]), "wall",
                                         {"gap", "side", "height", "restitution", "friction"}))
            variants.append(v)
        solver = Solver(**only_keys(as_table(data.get("solver", {}), "solver"), "solver",
                                {"rtol", "atol", "dt", "max_steps", "max_step",
                                 "record_breakpoints", "eps_omega", "eps_t", "method"}))
        run = dict(only_keys(as_table(data.get("run", {}), "run"), "run",
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
                from fastrock.io.ground_motion import canonical_unit
                canonical_unit(self.unit)
            if self.dt is not None:
                V.positive("dt", self.dt)
        except ValueError as exc:
            raise StudyError(str(exc)) from None
        records = _load(self.records, self.unit, self.dt)
        if not self.bodies:
            raise StudyError("bodies is empty")
        bodies = list(self.bodies)
        for i, b in enumerate(bodies):
            if not isinstance(b, (RigidBlock, FlexibleBody, RigidBody)):
                raise StudyError(f"bodies[{i}] must be a RigidBlock, RigidBody or FlexibleBody, "
                                 f"got {type(b).__name__}")
        # a symmetric RigidBody runs as its RigidBlock, as in simulate and spectra
        given = bodies
        bodies = [registry.model_body(b) for b in bodies]
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
        from fastrock.model.foundation import block_inertia as _block_inertia
        from fastrock.running.foundation import check_wall_start as _check_wall_start
        from fastrock.running.foundation import with_slide
        specs, y0s = {}, {}
        for bi, body in enumerate(bodies):
            for vi, wall in enumerate(walls):
                try:
                    friction, foundation, mass = _resolve_effects(given[bi], effects[vi])
                    mass = registry.carried_mass(given[bi], foundation, mass)
                    specs[bi, vi] = registry.select(body, wall, friction, foundation, mass)
                    solver.check_model(specs[bi, vi].model)
                    if effects[vi].get("ground") is not None:
                        effects[vi]["ground"].check_scene(body, friction=friction, flexible=specs[bi, vi].flexible,
                                                          foundation=foundation)
                    y0s[bi, vi] = (np.zeros(specs[bi, vi].n_state) if foundation is None else
                                   _check_wall_start(specs[bi, vi], with_slide(specs[bi, vi], foundation.initial_state(
                                       _block_inertia(body, mass), 0.0, 0.0, effects[vi].get("ground"))), wall))
                except (TypeError, ValueError) as exc:
                    raise StudyError(f"body {bi} with variant {names[vi]!r}: {exc}") from None
                if effects[vi].get("ground") is not None:     # a flexible column at its static deflection
                    effects[vi]["ground"].initial_state(body, specs[bi, vi], y0s[bi, vi])
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
            out.append(read_one_record(p, u, d, **layout))
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
            (wall,) = as_walls([v.get("wall")])
            effects.append(_variant_effects(v))
        except (TypeError, ValueError) as exc:
            raise StudyError(f"variants[{i}]: {exc}") from None
        walls.append(wall)
        label = label_of_wall(wall)
        if effects[-1].get("friction") is not None:
            label += f", mu={effects[-1]['friction'].mu_s:g}"
        if effects[-1].get("foundation") is not None:
            fnd = effects[-1]["foundation"]
            label += f", {fnd['type'] if isinstance(fnd, dict) else fnd.model} foundation"
        if effects[-1].get("ground") is not None:
            label += f", slope {effects[-1]['ground'].slope_deg:.3g} deg"
        names.append(str(v.get("name") or label))
    if len(set(names)) != len(names):
        raise StudyError(f"variant names must be distinct, got {names}")
    return names, walls, effects


#: Keys of a scene variant: its name and the effects it switches on.
VARIANT_KEYS = {"name", "wall", "friction", "foundation", "mass", "ground"}


def _variant_effects(v):
    """A variant's friction (Friction), foundation (an object, or a scene-style table resolved
    per body) and block mass [kg]; only the keys it gives."""
    out = {}
    fr = v.get("friction")
    if fr is not None:
        from fastrock.model.friction import Friction
        out["friction"] = Friction(**fr) if isinstance(fr, dict) else fr
    if v.get("ground") is not None:
        from fastrock.model.ground import Ground, as_ground
        gnd = as_ground(Ground(**v["ground"]) if isinstance(v["ground"], dict) else v["ground"])
        if gnd is not None:
            out["ground"] = gnd
    if v.get("foundation") is not None:
        fnd = v["foundation"]
        if isinstance(fnd, dict):
            fnd = dict(fnd)
            if "mass" in fnd:
                raise ValueError("give the block mass as the variant's mass, not inside foundation")
        out["foundation"] = fnd
        if "mass" in v:
            out["mass"] = V.positive("mass", v["mass"])
    elif "mass" in v:
        raise ValueError("mass goes with a foundation")
    return out


def _resolve_effects(body, fx):
    """The variant's effects for one body: a foundation table becomes its model object."""
    fnd = fx.get("foundation")
    mass = fx.get("mass")
    if isinstance(fnd, dict):
        from fastrock.running.scene import foundation_from_table
        fnd, _mass = foundation_from_table(fnd if mass is None else {**fnd, "mass": mass}, body)   # omega refers to this block's mass
    return fx.get("friction"), fnd, mass


def _body_labels(bodies):
    labels = []
    for b in bodies:
        if isinstance(b, FlexibleBody):
            s = f"flexible alpha={b.alpha:.4g} p={b.p:.4g} wn/p={b.omega_n_over_p:.4g}"
        elif isinstance(b, RigidBody):
            s = f"b1={b.b1:.4g} h1={b.h1:.4g} b2={b.b2:.4g} h2={b.h2:.4g}"
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


