"""A scene: one body, its effects, an excitation and solver settings, as a value
(and read from TOML); Scene.run simulates it.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from fastrock import _validate as V
from fastrock.model.bodies import FlexibleBody, RigidBlock
from fastrock.model.excitation import Pulse, SampledMotion, as_excitation
from fastrock.running.solver import DEFAULT_T_AFTER, Solver


try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib


@dataclass
class Scene:
    """A body, contact effects and an excitation.

    ``effects`` lists what the scene switches on ("flexible", "wall",
    "vertical"); ``kernel`` names the compiled kernel that will run.  Effects
    that are off cost nothing: their kernels are neither imported nor
    compiled.
    """

    body: object
    excitation: object = None
    vertical: object = None
    wall: object = None
    friction: object = None
    foundation: object = None
    ground: object = None
    mass: float | None = None
    theta0: float = 0.0
    dtheta0: float = 0.0
    duration: float | None = None
    t_after: float = DEFAULT_T_AFTER
    solver: Solver = field(default_factory=Solver)
    name: str = ""
    outputs: dict = field(default_factory=dict)

    def __post_init__(self):
        from fastrock.model.rigid_body import RigidBody
        if not isinstance(self.body, (RigidBlock, FlexibleBody, RigidBody)):
            raise ValueError(f"body must be a RigidBlock, RigidBody or FlexibleBody, got {type(self.body).__name__}")
        self.excitation = as_excitation(self.excitation)
        self.vertical = as_excitation(self.vertical, "vertical")

    @property
    def effects(self):
        out = []
        if isinstance(self.body, FlexibleBody):
            out.append("flexible")
        if self.foundation is not None:
            out.append(f"foundation:{self.foundation.model}")
        if self.wall is not None:
            out.append("wall")
        if self.friction is not None and self.friction.sliding_possible:
            out.append("friction")
        if self.friction is not None and self.friction.lift_off == "flight":
            out.append("flight")
        if self.vertical is not None:
            out.append("vertical")
        if self.ground is not None and not self.ground.is_level:
            out.append("slope")
        return tuple(out)

    @property
    def kernel(self):
        from fastrock.running.registry import select
        return select(self.body, self.wall, self.friction, self.foundation, self.mass).name

    def run(self, **overrides):
        from fastrock.running.simulate import simulate
        kw = dict(vertical=self.vertical, wall=self.wall, friction=self.friction, ground=self.ground,
                  theta0=self.theta0, dtheta0=self.dtheta0,
                  duration=self.duration, t_after=self.t_after, solver=self.solver)
        if self.foundation is not None:
            kw.update(foundation=self.foundation, mass=self.mass)
        kw.update(overrides)
        return simulate(self.body, self.excitation, **kw)

    # ------------------------------------------------------------------ TOML
    @classmethod
    def from_toml(cls, path):
        path = Path(path)
        try:
            with open(path, "rb") as fh:
                data = tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise ValueError(f"{path}: not valid TOML: {exc}") from None
        except (FileNotFoundError, IsADirectoryError, PermissionError) as exc:
            raise ValueError(f"scene file {path}: {exc.strerror}") from None
        return cls.from_dict(data, base=path.parent, name=path.stem)

    @classmethod
    def from_dict(cls, data, base=None, name=""):
        base = Path(base or ".")
        known = {"body", "excitation", "vertical", "wall", "friction", "foundation", "ground", "solver", "run",
                 "output", "name"}
        unknown = set(data) - known
        if unknown:
            raise ValueError(f"unknown scene section(s) {sorted(unknown)}; known: {sorted(known)}")
        if "body" not in data:
            raise ValueError("scene: a [body] section is required")
        body = body_from_table(as_table(data["body"], "body"), base)
        exc = _excitation(as_table(data["excitation"], "excitation"), base, "excitation") if "excitation" in data \
            else None
        vert = _excitation(as_table(data["vertical"], "vertical"), base, "vertical") if "vertical" in data else None
        wall = None
        if "wall" in data:
            from fastrock.model.wall import Wall
            wall = _build(Wall, only_keys(as_table(data["wall"], "wall"), "wall",
                                      {"gap", "side", "height", "restitution", "friction"}), "wall")
        friction = None
        if "friction" in data:
            from fastrock.model.friction import Friction
            friction = _build(Friction, only_keys(as_table(data["friction"], "friction"), "friction",
                                              {"mu_s", "mu_k", "slide_tolerance", "lift_off"}), "friction")
        ground = None
        if "ground" in data:
            from fastrock.model.ground import Ground
            ground = _build(Ground, only_keys(as_table(data["ground"], "ground"), "ground",
                                              {"slope", "direction"}), "ground")
        foundation, mass = (foundation_from_table(as_table(data["foundation"], "foundation"), body) if "foundation" in data
                            else (None, 1.0))
        solver = Solver(**only_keys(as_table(data.get("solver", {}), "solver"), "solver",
                                {"rtol", "atol", "dt", "max_steps", "max_step", "record_breakpoints",
                                 "eps_omega", "eps_t", "method"}))
        run = only_keys(as_table(data.get("run", {}), "run"), "run", {"theta0", "dtheta0", "duration", "t_after"})
        for k, v in run.items():      # checked here too, so that a bad file fails when it is read
            (V.positive if k == "duration" else V.non_negative if k == "t_after" else V.finite)(f"[run] {k}", v)
        out = only_keys(as_table(data.get("output", {}), "output"), "output", {"csv", "parquet", "events", "png"})
        for k, v in out.items():
            if not isinstance(v, str) or not v:
                raise ValueError(f"[output] {k} must be a file name (a string), got {v!r}")
        out = {k: str(base / v) for k, v in out.items()}
        return cls(body=body, excitation=exc, vertical=vert, wall=wall, friction=friction, foundation=foundation,
                   ground=ground, mass=mass, solver=solver,
                   name=str(data.get("name", name)), outputs=out, **run)


def as_table(value, section):
    """A TOML table (dict) as a new dict, or a ValueError naming the section."""
    if not isinstance(value, dict):
        raise ValueError(f"[{section}] must be a table (key = value lines under [{section}]), got {value!r}")
    return dict(value)


def _build(cls, kw, section):
    """``cls(**kw)``; a missing or unexpected key is a ValueError naming the section."""
    try:
        return cls(**kw)
    except TypeError as exc:
        raise ValueError(f"[{section}]: " + re.sub(r"^[\w.]+\(\) ", "", str(exc))) from None


def only_keys(d, section, allowed):
    """``d`` unchanged, or a ValueError naming the keys of [section] outside ``allowed``."""
    extra = set(d) - allowed
    if extra:
        raise ValueError(f"[{section}]: unknown key(s) {sorted(extra)}; allowed: {sorted(allowed)}")
    return d


_RIGID_BODY_COMMON = {"e", "g", "theta_over"}


def rigid_body_from_table(d, base=None):
    """A RigidBody from a [body] table of type "rigid-body": its numbers (mass, inertia, b1, h1,
    b2, h2, and top, top_radius; ``on_level_ground = true`` turns pivots at different heights
    onto one plane, :meth:`RigidBody.on_level_ground`), a 2D outline (``vertices`` [m], a list of [x, y] pairs or the
    name of an outline file relative to the scene file (:func:`fastrock.read_outline`), with density [kg/m^3] and
    thickness [m], or mass [kg]; pose [rad]) or a mesh file (``mesh``, a path relative to the
    scene file; axis, up, density or mass, pose)."""
    from fastrock.model.rigid_body import RigidBody
    if "vertices" in d:
        kw = only_keys(d, "body", {"vertices", "density", "thickness", "mass", "pose"} | _RIGID_BODY_COMMON)
        vertices = kw.pop("vertices")
        if isinstance(vertices, str) and vertices:          # an outline file beside the scene file
            from fastrock.io.outline import read_outline
            vertices = read_outline(Path(base or ".") / vertices).tolist()
        if not isinstance(vertices, list) or not all(isinstance(v, list) and len(v) == 2 for v in vertices):
            raise ValueError("[body] vertices must be a list of [x, y] pairs [m] or an outline file name")
        return _build(lambda **k: RigidBody.from_polygon(vertices, **k), kw, "body")
    if "mesh" in d:
        kw = only_keys(d, "body", {"mesh", "axis", "up", "density", "mass", "pose"} | _RIGID_BODY_COMMON)
        path = kw.pop("mesh")
        if not isinstance(path, str) or not path:
            raise ValueError(f"[body] mesh must be a file name (a string), got {path!r}")
        for k in ("axis", "up"):
            if k in kw:
                kw[k] = tuple(kw[k])
        return _build(lambda **k: RigidBody.from_mesh(Path(base or ".") / path, **k), kw, "body")
    kw = only_keys(d, "body", {"mass", "inertia", "b1", "h1", "b2", "h2", "top", "top_radius",
                               "on_level_ground"} | _RIGID_BODY_COMMON)
    level = kw.pop("on_level_ground", False)
    if not isinstance(level, bool):
        raise ValueError(f"[body] on_level_ground must be true or false, got {level!r}")
    body = _build(RigidBody, kw, "body")
    return body.on_level_ground() if level else body


def body_from_table(d, base=None):
    """The body of a scene's [body] table (type = "rigid" | "rigid-body" | "flexible"); ``base``:
    the folder a mesh file name is relative to."""
    kind = d.pop("type", "rigid")
    if kind == "rigid-body":
        return rigid_body_from_table(d, base)
    if kind == "rigid":
        if "b" in d or "h" in d:
            return _build(RigidBlock.rectangle, only_keys(d, "body", {"b", "h", "e", "g", "theta_over", "top_radius"}),
                          "body")
        if "I0" in d:
            return _build(RigidBlock.from_inertia,
                          only_keys(d, "body", {"R", "alpha", "I0", "m", "e", "g", "theta_over"}), "body")
        return _build(RigidBlock, only_keys(d, "body", {"alpha", "p", "e", "g", "theta_over"}), "body")
    if kind == "flexible":
        if "K" in d:
            return _build(FlexibleBody.from_dimensions,
                          only_keys(d, "body", {"m", "K", "c", "B", "H", "I_m", "impact", "e", "g", "theta_over",
                                            "m_b", "h_b"}), "body")
        return _build(FlexibleBody, only_keys(d, "body", {"alpha", "p", "omega_n_over_p", "zeta", "e", "impact", "g",
                                                      "theta_over", "rotary_inertia_ratio", "mass",
                                                      "base_mass_ratio", "base_cm_height"}), "body")
    raise ValueError(f"[body] type must be 'rigid', 'rigid-body' or 'flexible', got {kind!r}")


_FOUNDATION_KEYS = {
    "two-spring": ("TwoSpringFoundation", {"k_v", "c_v"}),
    "switching": ("SwitchingFoundation", {"k_t", "c_t", "e_f"}),
    "linear": ("LinearVibration", {"k_t", "c_t"}),
}


def foundation_from_table(d, body):
    """[foundation] type = "two-spring" | "switching" | "linear", with either the model's own
    stiffnesses (k_v, c_v or k_t, c_t) or omega [rad/s] and zeta (``from_vibration``), plus
    e_f (switching) and the block's mass [kg] (default 1; a RigidBody carries its own)."""
    from fastrock.model import foundation as F
    kind = d.pop("type", None)
    if kind not in _FOUNDATION_KEYS:
        raise ValueError(f"[foundation] type must be one of {sorted(_FOUNDATION_KEYS)}, got {kind!r}")
    cls_name, own = _FOUNDATION_KEYS[kind]
    cls = getattr(F, cls_name)
    extra = {"e_f"} if kind == "switching" else set()
    d = only_keys(d, "foundation", own | {"omega", "zeta", "mass"} | extra)
    mass = d.pop("mass", None)
    mass = None if mass is None else V.positive("mass", mass)
    if "omega" in d:
        if own & set(d) - extra:
            raise ValueError(f"[foundation]: give omega/zeta or {sorted(own - extra)}, not both")
        kw = {k: d[k] for k in extra if k in d}
        return cls.from_vibration(body, d["omega"], d.get("zeta", 0.0), mass=mass, **kw), mass
    if "zeta" in d:
        raise ValueError("[foundation]: zeta goes with omega")
    return _build(cls, d, "foundation"), mass


def _excitation(d, base, section):
    kind = d.pop("type", "pulse")
    if kind == "pulse":
        return _build(Pulse, only_keys(d, section, {"amplitude", "frequency", "sign", "kind", "amplitude_unit",
                                                "frequency_unit", "t_start", "duration"}), section)
    if kind == "record":
        from fastrock.io.default_records import load_default_record
        from fastrock.io.readers import read_record
        d = only_keys(d, section, {"file", "unit", "dt", "scale", "pga_g", "t_start", "column", "decimal"})
        f = d.get("file")
        if f not in (None, "default") and (not isinstance(f, str) or not (base / f).is_file()):
            raise ValueError(f"[{section}] file: record file not found: {f if not isinstance(f, str) else base / f}")
        rec = load_default_record() if f in (None, "default") else read_record(
            base / f, unit=d.get("unit"), dt=d.get("dt"), column=d.get("column"), decimal=d.get("decimal", "."))
        scale = V.finite("scale", d.get("scale", 1.0))
        if "pga_g" in d:
            scale = V.positive("pga_g", d["pga_g"]) / rec.pga_g
        return SampledMotion.from_record(rec, scale=scale, t_start=d.get("t_start", 0.0))
    raise ValueError(f"[{section}] type must be 'pulse' or 'record', got {kind!r}")


