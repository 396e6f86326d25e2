"""Rocking spectrum inputs: wall settings, records, grids.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from fastrock import _validate as V
from fastrock.model.bodies import RigidBlock
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.default_records import load_default_record
from fastrock.io.readers import read_record


#: Clear gaps [m] of the one-sided settings (besides two-sided rocking).
DEFAULT_WALL_GAPS = (0.01, 0.10)


# ------------------------------------------------------------------ inputs
def shape_family(shape, e=None):
    """The bodies of a rocking spectrum over one shape: ``body(b, s)`` is the outline ``shape``
    stretched so that its mean half base width (b1 + b2)/2 is ``b`` [m] and tan(alpha) of its
    slenderer side is ``s`` (a plate of uniform density: the mass properties follow the stretched
    polygon exactly). For a rectangle this is ``RigidBlock.rectangle(b, b / s)``.

    ``shape``: vertices (n x 2) [m] or an outline file (:func:`fastrock.read_outline`); the body
    rests on the facet of its convex hull that faces down."""
    from fastrock.model.rigid_body import RigidBody
    if isinstance(shape, (str, os.PathLike)):
        from fastrock.io.outline import read_outline
        shape = read_outline(shape)
    if isinstance(shape, RigidBody):
        raise ValueError("shape must be an outline (vertices [m] or an outline file), not a RigidBody: the "
                         "spectrum stretches the outline, and a body's own inertia (a mesh's) cannot be stretched")
    vertices = np.asarray(shape, float) if not isinstance(shape, np.ndarray) else shape
    template = RigidBody.from_polygon(vertices, mass=1.0)
    pose_outline = template.outline                          # relative to the centre of mass, resting
    k = template.smaller_side
    b_k, h_k = (template.b1, template.h1) if k == 1 else (template.b2, template.h2)
    half_base = 0.5 * (template.b1 + template.b2)

    def body(b, s):
        sx = b / half_base
        sy = sx * (b_k / h_k) / s
        return RigidBody.from_polygon(pose_outline * np.array([sx, sy]), mass=1.0, e=e)

    return body


def default_walls():
    """``(None, Wall(0.01), Wall(0.10))`` if the wall model is installed,
    else ``(None,)`` (two-sided rocking only)."""
    try:
        from fastrock.model.wall import Wall
        import fastrock.kernels.wall  # noqa: F401  (the kernel must exist too)
    except ImportError:
        return (None,)
    return (None,) + tuple(Wall(gap=d) for d in DEFAULT_WALL_GAPS)


def label_of_wall(wall):
    """Label of a wall setting: "two-sided" (None) or "wall d=<gap> m" (plus its side)."""
    if wall is None:
        return "two-sided"
    label = f"wall d={wall.gap:g} m"
    side = getattr(wall, "side", -1)
    if side != -1:
        label += f" side {side:+d}"
    return label


def gap_of_wall(wall):
    """Clear gap [m] of a wall setting, NaN for two-sided rocking (None)."""
    return math.nan if wall is None else float(wall.gap)


def as_walls(walls):
    """Wall settings as a list of Wall or None: None gives default_walls(); gaps [m] become
    rear walls."""
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
    labels = [label_of_wall(w) for w in out]
    if len(set(labels)) != len(labels):
        raise ValueError(f"walls must be distinct settings, got {labels}")
    return tuple(out)


def _wall_class():
    try:
        from fastrock.model.wall import Wall
    except ImportError:
        return ()
    return Wall


def _make_wall(gap):
    try:
        from fastrock.model.wall import Wall
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
    return as_walls([w for w in text.split(",")])


def read_one_record(path, unit=None, dt=None, **layout):
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
            out.append(read_one_record(Path(r), unit, dt, column=column, decimal=decimal))
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


def grid_values(values, name, default):
    """A grid axis: sorted unique finite values > 0 (``default`` when None)."""
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


def check_stable_outcomes(outcomes):
    """The outcomes that count as stable, checked against OUTCOMES."""
    try:
        items = [] if isinstance(outcomes, (str, bytes)) else list(outcomes)
    except TypeError:
        items = []
    if not items or any(not isinstance(o, str) or o not in OUTCOMES for o in items):
        raise ValueError(f"stable_outcomes must be a non-empty list of outcomes among {list(OUTCOMES)}, "
                         f"such as ['safe'], got {outcomes!r}")
    return tuple(items)


def check_record_options(unit, dt):
    """Check --unit / --dt style options before any file is read."""
    if unit is not None:
        from fastrock.io.ground_motion import canonical_unit
        canonical_unit(unit)
    if dt is not None:
        V.positive("dt", dt)


def check_run_length(records, solver, t_after):
    """Refuse runs longer than the solver's fixed-step budget (the longest record plus t_after)."""
    longest = V.run_time("t_after", max(r.duration for r in records) + t_after,
                         "the longest record plus t_after")
    solver.check_fixed_steps(longest, "the longest record plus t_after")


