"""The model registry: one entry per compiled model.

A *scene* is a body (rigid block, flexible body) plus the effects it calls
for (a rear wall, Coulomb friction, a flexible foundation).  :func:`select`
maps a scene to the one registry entry that simulates exactly those effects
and to that entry's parameter vector, and nothing else is imported or
compiled: a scene without a wall, with infinite friction or with a rigid body
never touches the wall, friction or flexible kernels.

Plug-in contract
----------------
A model is one kernel module under ``kernels/`` plus one :class:`Model`
entry here (``register``).  The rules, numbered as SciPy's ``OdeSolver``
states its own:

1. The kernel module never imports the front end, pandas or matplotlib.  It
   supplies the five jitted functions of ``kernels/hybrid.py`` (``rhs``,
   ``event``, ``transition``, ``static_margin``, ``after_step``) and drives
   them through ``hybrid.integrate_hybrid``, after an ``init_state(t0, y,
   par, disc, hdr, smp, met, log, cnt)`` that sets the metrics
   (``hybrid.init_metrics``) and the initial contact mode.  Time is booked
   with ``hybrid.book_time`` and a run that ends upright gets
   ``hybrid.final_status``; event ids are named module constants.
2. It defines two entry kernels named ``<name>_simulate`` and
   ``<name>_sweep`` (``Model.simulate_entry`` / ``sweep_entry``), with the
   signatures of ``kernels.rigid.rigid_simulate`` /
   ``rigid_sweep``: ``(y, par, hdr, smp, opt, t_eval, met, hist_t, hist_y,
   hist_d, log, cnt) -> status`` and ``(Y0, PAR, HDR, smp, OPT, status,
   MET, YF)``; the sweep inlines ``hybrid.sweep_rows``.
3. The state vector holds ``theta`` and ``theta_dot`` next to each other
   (``state_names``); a sliding model holds ``d`` and ``d_dot`` likewise.
4. It reports through the layout of ``kernels/layout.py`` only: status
   codes, the metrics vector (``M_*``), the event log (``EV_*``) and the
   discrete state (``D_MODE``, ``D_PIVOT``).
5. ``build_par(body, effects)`` (front end, Numba-free) validates what the
   model needs and returns its parameter vector; its first entries are the
   rigid layout (alpha, p, e, g, theta_over), which the shared kernel pieces
   (``rigid.overturned``, ``rigid.passed_alpha``) read.
6. ``columns`` names the result columns the model adds to the common ones
   (``fastrock.analyses.spectrum.SPECTRUM_COLUMNS``); ``outcomes`` lists the outcome
   classes it can return.
7. ``cli_options`` and ``toml_keys`` list the command-line options and
   scene (TOML) sections that describe the model's body and effects; ``tests/test_registry.py``
   checks that the CLI and the scene reader accept every one of them.

``docs/adding_a_model.md`` walks through an example.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

#: Effects a scene can call for, besides the body.
EFFECTS = ("wall", "friction", "foundation")


@dataclass(frozen=True)
class Model:
    """One registry entry (see the plug-in contract in the module docstring)."""

    name: str
    module: str
    body: str                       # "rigid", "flexible" or "rigid_body" (an asymmetric RigidBody)
    effects: frozenset
    state_names: tuple
    build_par: Callable = field(repr=False, compare=False)
    columns: tuple = ()
    outcomes: tuple = ("safe", "mode1", "mode2", "failed")
    cli_options: tuple = ()
    toml_keys: tuple = ()
    summary: str = ""
    also: tuple = ()                # further effect sets (frozensets) the model runs

    @property
    def simulate_entry(self):
        return f"{self.name}_simulate"

    @property
    def sweep_entry(self):
        return f"{self.name}_sweep"

    @property
    def n_state(self):
        return len(self.state_names)

    @property
    def theta_index(self):
        return self.state_names.index("theta")

    @property
    def slide_index(self):
        return self.state_names.index("d") if "d" in self.state_names else None

    @property
    def flexible(self):
        return self.body == "flexible"

    @property
    def friction(self):
        return "d" in self.state_names

    @property
    def flight(self):
        return "flight" in self.effects

    @property
    def stiff(self):
        """The kernel integrates with ``rodas.auto_step`` (Solver.method)."""
        return "foundation" in self.effects

    def load(self):
        return importlib.import_module(f"fastrock.kernels.{self.module}")


@dataclass(frozen=True)
class KernelSpec:
    """A registry entry with the parameter vector of one scene."""

    model: Model
    par: np.ndarray

    # the entry's description, for callers that hold only the spec
    name = property(lambda self: self.model.name)
    module = property(lambda self: self.model.module)
    n_state = property(lambda self: self.model.n_state)
    state_names = property(lambda self: self.model.state_names)
    theta_index = property(lambda self: self.model.theta_index)
    slide_index = property(lambda self: self.model.slide_index)
    flexible = property(lambda self: self.model.flexible)
    friction = property(lambda self: self.model.friction)

    @property
    def simulate(self):
        return getattr(self.model.load(), self.model.simulate_entry)

    @property
    def sweep(self):
        return getattr(self.model.load(), self.model.sweep_entry)


MODELS: dict[str, Model] = {}
_BY_SCENE: dict[tuple, Model] = {}

#: Combinations that no model runs yet, with the reason the error gives.
NOT_AVAILABLE = {
    ("flexible", frozenset({"wall", "friction"})):
        "a wall together with friction is available for RigidBlock only (the contact model); a "
        "FlexibleBody takes wall= or friction=, not both yet (issue #13)",
    ("rigid", frozenset({"foundation", "wall"})):
        "a wall beside a block on a flexible foundation runs with foundation=TwoSpringFoundation(...) or "
        "SwitchingFoundation(...); LinearVibration with wall= is not available (it never lifts off and "
        "turns about its base centre; issue #13)",
    ("rigid", frozenset({"foundation", "friction"})):
        "sliding on a flexible foundation is available on TwoSpringFoundation only "
        "(two_spring_friction); the switching and linear SDOF models turn the block about its "
        "base centre, held horizontally (issue #13)",
    ("rigid", frozenset({"foundation", "friction", "flight"})):
        "sliding on a flexible foundation is available on TwoSpringFoundation only "
        "(two_spring_friction); the switching and linear SDOF models turn the block about its "
        "base centre, held horizontally (issue #13)",
    ("rigid", frozenset({"foundation", "flight"})):
        "Friction(inf, lift_off='flight') on a flexible foundation is not available: a base that "
        "never slips would need an impulsive stick at a landing with a horizontal velocity; give a "
        "finite mu_s (TwoSpringFoundation: the block flies when no corner touches) or omit friction "
        "(the foundation models hold the base horizontally)",
    ("rigid", frozenset({"foundation", "wall", "friction"})):
        "a wall and friction on a flexible foundation are not available yet (issue #13)",
}


def register(model: Model):
    """Add a model; its (body, effects) combination must be new."""
    keys = [(model.body, fx) for fx in (model.effects,) + tuple(model.also)]
    if model.name in MODELS:
        raise ValueError(f"model {model.name!r} is registered already")
    for key in keys:
        if key in _BY_SCENE:
            raise ValueError(f"{_BY_SCENE[key].name!r} already runs a {model.body} body with "
                             f"{sorted(key[1]) or 'no effects'}")
    MODELS[model.name] = model
    for key in keys:
        _BY_SCENE[key] = model
    return model


def _body_kind(body):
    from fastrock.model.bodies import FlexibleBody, RigidBlock
    from fastrock.model.rigid_body import RigidBody
    if isinstance(body, FlexibleBody):
        return "flexible"
    if isinstance(body, RigidBlock):
        return "rigid"
    if isinstance(body, RigidBody):
        return "rigid" if body.is_symmetric else "rigid_body"
    raise ValueError(f"body must be a fastrock body (RigidBlock, RigidBody, FlexibleBody), got "
                     f"{type(body).__name__}")


def model_body(body):
    """The body the models run: a symmetric :class:`~fastrock.RigidBody` is its
    :class:`~fastrock.RigidBlock` (``RigidBody.to_block``); any other body as it is.
    A block has no mass: resolve a foundation's mass first (:func:`carried_mass`)."""
    from fastrock.model.rigid_body import RigidBody
    if isinstance(body, RigidBody) and body.is_symmetric:
        return body.to_block()
    return body


#: How the error for an asymmetric body names each effect.
_EFFECT_FIELDS = {"wall": "wall=", "friction": "friction=", "flight": "friction=Friction(lift_off='flight')",
                  "foundation": "foundation="}


def scene_effects(wall=None, friction=None, foundation=None):
    """The effects a scene calls for, each validated; friction that can
    never slip (mu_s = inf) is no effect at all."""
    effects = {}
    if wall is not None:
        from fastrock.model.wall import Wall
        if not isinstance(wall, Wall):
            raise ValueError(f"wall must be a fastrock.Wall, got {type(wall).__name__}")
        effects["wall"] = wall
    if friction is not None:
        from fastrock.model.friction import Friction
        if not isinstance(friction, Friction):
            raise ValueError(f"friction must be a fastrock.Friction, got {type(friction).__name__}")
        if friction.sliding_possible:
            effects["friction"] = friction
        if friction.lift_off == "flight":
            effects["flight"] = friction
    if foundation is not None:
        from fastrock.model.foundation import FOUNDATIONS
        if not isinstance(foundation, FOUNDATIONS):
            raise ValueError(f"foundation must be a TwoSpringFoundation, SwitchingFoundation or "
                             f"LinearVibration, got {type(foundation).__name__}")
        effects["foundation"] = foundation
    return effects


def effect_names(effects):
    """Registry names of a scene's effects: a foundation names its model
    ("foundation:two_spring"), since each foundation model is its own kernel."""
    return frozenset(f"foundation:{v.kernel}" if k == "foundation" else k for k, v in effects.items())


def lookup(body, effects):
    """The registry entry for a body and its validated effects (:func:`scene_effects`)."""
    kind = _body_kind(body)
    model = _BY_SCENE.get((kind, effect_names(effects)))
    if model is None:
        generic = frozenset(effects)
        if kind == "rigid_body":
            if "foundation" in generic and len(generic) == 1:
                raise ValueError(
                    "an asymmetric RigidBody (b1 != b2 or h1 != h2) stands on a flexible foundation as "
                    f"foundation=TwoSpringFoundation(...); a {type(effects['foundation']).__name__} as "
                    "foundation= is not available for it yet: Yu et al.'s switching and linear SDOF models "
                    "turn a symmetric block about its base centre, while an asymmetric body rests tilted, "
                    "carried unequally by its two corners")
            raise ValueError(
                "an asymmetric RigidBody (b1 != b2 or h1 != h2) runs the two-sided rocking model, with "
                "wall= alone the wall model, with friction= or Friction(lift_off='flight') (and a wall) the "
                "contact model, and with foundation=TwoSpringFoundation (and a wall) the two-spring model; "
                f"{', '.join(_EFFECT_FIELDS[k] for k in sorted(generic))} together is not available for it "
                "yet; a symmetric RigidBody runs everywhere as its RigidBlock")
        if "foundation" in generic and kind == "flexible" and len(generic) == 1:
            raise ValueError(
                f"a FlexibleBody stands on foundation=TwoSpringFoundation(...); a "
                f"{type(effects['foundation']).__name__} as foundation= is not available for it: Yu et al.'s "
                "switching and linear SDOF models turn a rigid block about its base centre")
        if "foundation" in generic and kind == "flexible":
            raise ValueError(
                "a FlexibleBody on a foundation takes no wall= or friction= yet (issue #13): the two-spring "
                "model holds the base horizontally and has no wall contact")
        reason = NOT_AVAILABLE.get((kind, generic))
        if reason is None:
            reason = f"no model runs a {kind} body with {', '.join(sorted(generic))}"
        raise ValueError(reason)
    return model


def carried_mass(body, foundation, mass):
    """The block mass on a foundation (:func:`fastrock.model.foundation.carried_mass`: a
    RigidBody's own); ``mass`` as it is without a foundation."""
    if foundation is None:
        return mass
    from fastrock.model.foundation import carried_mass as on_foundation
    return on_foundation(body, mass)


def select(body, wall=None, friction=None, foundation=None, mass=None):
    """KernelSpec of the smallest model that runs this scene (``mass``: the block
    mass on a foundation, :func:`fastrock.model.foundation.carried_mass`)."""
    effects = scene_effects(wall, friction, foundation)
    model = lookup(body, effects)
    mass = carried_mass(body, foundation, mass)    # before a symmetric RigidBody becomes its block
    return KernelSpec(model, model.build_par(model_body(body), effects, mass))


# ------------------------------------------------------------------ entries
def _rigid(body, fx, mass):
    from fastrock.running.models import rigid_par
    return rigid_par(body)


def _rigid_body(body, fx, mass):
    from fastrock.running.models import rigid_body_par
    return rigid_body_par(body)


def _rigid_wall(body, fx, mass):
    from fastrock.running.models import wall_par
    return wall_par(body, fx["wall"])


def _rigid_friction(body, fx, mass):
    from fastrock.running.models import rigid_friction_par
    return rigid_friction_par(body, fx["friction"])


def _flexible(body, fx, mass):
    from fastrock.running.models import flexible_par
    return flexible_par(body)


def _flexible_wall(body, fx, mass):
    from fastrock.running.models import flexible_wall_par
    return flexible_wall_par(body, fx["wall"])


def _flexible_friction(body, fx, mass):
    from fastrock.running.models import flexible_friction_par
    return flexible_friction_par(body, fx["friction"])


def _flexible_flight(body, fx, mass):
    from fastrock.running.models import flexible_flight_par
    return flexible_flight_par(body, fx.get("friction") or fx.get("flight"))


def _contact(body, fx, mass):
    from fastrock.running.models import contact_par
    return contact_par(body, fx.get("friction") or fx.get("flight"), fx.get("wall"))


def _foundation(body, fx, mass):
    from fastrock.model.foundation import foundation_par
    return foundation_par(body, fx["foundation"], mass)


def _foundation_friction(body, fx, mass):
    from fastrock.model.foundation import foundation_friction_par
    return foundation_friction_par(body, fx["foundation"], fx.get("friction") or fx.get("flight"), mass)


def _foundation_wall(body, fx, mass):
    from fastrock.model.foundation import foundation_wall_par
    return foundation_wall_par(body, fx["foundation"], fx["wall"], mass)


def _switching_wall(body, fx, mass):
    from fastrock.model.foundation import switching_wall_par
    return switching_wall_par(body, fx["foundation"], fx["wall"], mass)


_RIGID_CLI = ("--alpha", "--p", "--b", "--h", "--e")
_RIGID_TOML = ("body",)
_FLEX_CLI = ("--omega-n-over-p", "--zeta", "--base-mass-ratio")
_FLEX_TOML = ("body",)
_WALL_CLI = ("--wall-gap", "--wall-side", "--wall-height", "--wall-restitution")
_FRICTION_CLI = ("--mu-s", "--mu-k", "--lift-off")
_FRICTION_COLUMNS = ("max_slide", "residual_slide", "time_sliding", "time_slide_rocking",
                     "stick_slip")
_FLEX_COLUMNS = ("max_deformation", "max_deformation_ratio", "time_rocking", "time_contact",
                 "energy_gains")
_FOUNDATION_COLUMNS = ("time_rocking", "time_contact")

register(Model(
    "rigid", "rigid", "rigid", frozenset(), ("theta", "theta_dot"), _rigid,
    outcomes=("safe", "mode1", "mode2", "flight", "failed"),
    cli_options=_RIGID_CLI, toml_keys=_RIGID_TOML,
    summary="Housner's rigid block rocking on rigid ground (two-sided)"))
register(Model(
    "rigid_body", "rigid", "rigid_body", frozenset(), ("theta", "theta_dot"), _rigid_body,
    outcomes=("safe", "mode1", "mode2", "flight", "failed"),
    summary="asymmetric rigid body (RigidBody: each pivot its own alpha, p and impact restitution) "
            "rocking on rigid ground (two-sided)"))
register(Model(
    "rigid_wall", "wall", "rigid", frozenset({"wall"}), ("theta", "theta_dot"), _rigid_wall,
    columns=("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall"),
    outcomes=("safe", "mode1", "mode2", "leaning", "flight", "failed"),
    cli_options=_RIGID_CLI + _WALL_CLI, toml_keys=_RIGID_TOML + ("wall",),
    summary="rigid block rocking against a rear wall at a gap (one-sided)"))
register(Model(
    "wall_body", "wall", "rigid_body", frozenset({"wall"}), ("theta", "theta_dot"), _rigid_wall,
    columns=("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall"),
    outcomes=("safe", "mode1", "mode2", "leaning", "flight", "failed"),
    cli_options=_WALL_CLI, toml_keys=("body", "wall"),
    summary="asymmetric rigid body (RigidBody) rocking against a rear wall: the wall model with each "
            "pivot its own alpha, p and impact restitution, gap 0 and short walls included"))
register(Model(
    "rigid_friction", "friction", "rigid", frozenset({"friction"}),
    ("theta", "theta_dot", "d", "d_dot"), _rigid_friction, columns=_FRICTION_COLUMNS,
    outcomes=("safe", "slide", "mode1", "mode2", "flight", "failed"),
    cli_options=_RIGID_CLI + _FRICTION_CLI, toml_keys=_RIGID_TOML + ("friction",),
    summary="rigid block with Coulomb friction: rest, slide, rock, slide-rock"))
register(Model(
    "contact", "contact", "rigid", frozenset({"wall", "friction"}),
    ("theta", "theta_dot", "d", "d_dot", "z", "z_dot"), _contact,
    columns=("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall") + _FRICTION_COLUMNS
    + ("flights", "time_flight", "max_jump"),
    outcomes=("safe", "slide", "mode1", "mode2", "leaning", "failed"),
    cli_options=_RIGID_CLI + _WALL_CLI + _FRICTION_CLI, toml_keys=_RIGID_TOML + ("wall", "friction"),
    summary="rigid block with contact points (base corners, wall corner): rest, slide, rock, "
            "slide-rock, free flight and landing, wall impacts; the generic mode solve",
    also=(frozenset({"flight"}), frozenset({"friction", "flight"}), frozenset({"wall", "flight"}),
          frozenset({"wall", "friction", "flight"}))))
# the contact kernel flies at lift-off whatever Friction.lift_off says: "flight" is among the
# entry's own effects, so its results carry the flight metrics
register(Model(
    "contact_body", "contact", "rigid_body", frozenset({"friction", "flight"}),
    ("theta", "theta_dot", "d", "d_dot", "z", "z_dot"), _contact,
    toml_keys=("body", "wall", "friction"),
    summary="asymmetric rigid body (RigidBody, level base) in the contact model: rest, slide, rock, "
            "slide-rock, free flight and landing, wall impacts, each pivot its own alpha and impact map",
    columns=_FRICTION_COLUMNS + ("flights", "time_flight", "max_jump", "toward_wall", "max_rotation_toward_wall",
                                 "max_rotation_away_from_wall"),
    outcomes=("safe", "slide", "mode1", "mode2", "leaning", "failed"),
    also=(frozenset({"friction"}), frozenset({"flight"}), frozenset({"wall", "friction"}),
          frozenset({"wall", "flight"}), frozenset({"wall", "friction", "flight"}))))
register(Model(
    "flexible", "flexible", "flexible", frozenset(), ("u", "u_dot", "theta", "theta_dot"),
    _flexible, columns=_FLEX_COLUMNS, outcomes=("safe", "mode1", "mode2", "flight", "failed"),
    cli_options=("--alpha", "--p", "--e") + _FLEX_CLI,
    toml_keys=_FLEX_TOML,
    summary="elastic column on a rocking base (SDOF oscillator on a rigid block)"))
register(Model(
    "flexible_wall", "flexible_wall", "flexible", frozenset({"wall"}), ("u", "u_dot", "theta", "theta_dot"),
    _flexible_wall,
    columns=_FLEX_COLUMNS + ("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall"),
    outcomes=("safe", "mode1", "mode2", "leaning", "flight", "failed"),
    cli_options=("--alpha", "--p", "--e") + _FLEX_CLI + _WALL_CLI, toml_keys=_FLEX_TOML + ("wall",),
    summary="flexible body rocking against a rear wall (its 2B x 2H outline touches the wall)"))
register(Model(
    "flexible_friction", "flexible_friction", "flexible", frozenset({"friction"}),
    ("u", "u_dot", "theta", "theta_dot", "d", "d_dot"), _flexible_friction,
    columns=_FLEX_COLUMNS + _FRICTION_COLUMNS + ("lift_offs", "time_unloaded"),
    outcomes=("safe", "slide", "mode1", "mode2", "flight", "failed"),
    cli_options=("--alpha", "--p", "--e") + _FLEX_CLI + _FRICTION_CLI,
    toml_keys=_FLEX_TOML + ("friction",),
    summary="flexible body whose base can slide: rest, slide, rock, slide-rock"))
register(Model(
    "flexible_flight", "flexible_flight", "flexible", frozenset({"friction", "flight"}),
    ("u", "u_dot", "theta", "theta_dot", "d", "d_dot", "z", "z_dot"), _flexible_flight,
    columns=_FLEX_COLUMNS + _FRICTION_COLUMNS + ("flights", "time_flight", "max_jump"),
    outcomes=("safe", "slide", "mode1", "mode2", "failed"),
    cli_options=("--alpha", "--p", "--e") + _FLEX_CLI + _FRICTION_CLI,
    toml_keys=_FLEX_TOML + ("friction",),
    summary="flexible body whose base can slide and leave the ground: rest, slide, rock, slide-rock, "
            "free flight of column and base, landing (plastic, Coulomb friction)",
    also=(frozenset({"flight"}),)))
for _name, _states, _what in (
        ("two_spring", ("y", "y_dot", "theta", "theta_dot"),
         "rigid block on two tensionless corner spring-dashpots (Winkler-type foundation)"),
        ("switching", ("theta", "theta_dot"),
         "rigid block switching between a rotational spring (contact) and Housner rocking"),
        ("linear_sdof", ("theta", "theta_dot"),
         "linear rotational oscillator that never lifts off (reference)")):
    register(Model(
        _name, "foundation", "rigid", frozenset({f"foundation:{_name}"}), _states, _foundation,
        columns=_FOUNDATION_COLUMNS,
        outcomes=("safe", "mode1", "mode2", "flight", "failed") if _name != "linear_sdof"
        else ("safe", "failed"),
        cli_options=_RIGID_CLI + ("--foundation", "--foundation-omega", "--foundation-zeta", "--mass"),
        toml_keys=("body", "foundation"), summary=_what))
# an asymmetric RigidBody (level base) stands on the two-spring foundation in the same kernel: its
# corners at -b1 and b2 (kernels/foundation.py); the SDOF models refuse it (lookup says why)
_BY_SCENE[("rigid_body", frozenset({"foundation:two_spring"}))] = MODELS["two_spring"]
# the block slides (and flies when no corner touches) whatever Friction.lift_off says, so
# lift_off="flight" runs the same kernel
register(Model(
    "two_spring_friction", "foundation_friction", "rigid",
    frozenset({"foundation:two_spring", "friction"}),
    ("y", "y_dot", "theta", "theta_dot", "d", "d_dot"), _foundation_friction,
    columns=_FOUNDATION_COLUMNS + _FRICTION_COLUMNS,
    outcomes=("safe", "slide", "mode1", "mode2", "failed"),
    cli_options=_RIGID_CLI + ("--foundation", "--foundation-omega", "--foundation-zeta", "--mass")
    + _FRICTION_CLI,
    toml_keys=("body", "foundation", "friction"),
    summary="rigid block on two tensionless corner spring-dashpots whose base slides (Coulomb friction "
            "at the base point): stick, slip, rocking, free flight when no corner touches",
    also=(frozenset({"foundation:two_spring", "friction", "flight"}),)))
for _fx in (frozenset({"foundation:two_spring", "friction"}),
            frozenset({"foundation:two_spring", "friction", "flight"})):
    _BY_SCENE[("rigid_body", _fx)] = MODELS["two_spring_friction"]
register(Model(
    "flexible_two_spring", "foundation_flexible", "flexible", frozenset({"foundation:two_spring"}),
    ("y", "y_dot", "u", "u_dot", "theta", "theta_dot"), _foundation,
    columns=_FLEX_COLUMNS, outcomes=("safe", "mode1", "mode2", "failed"),
    cli_options=("--alpha", "--p") + _FLEX_CLI + ("--foundation", "--foundation-omega", "--foundation-zeta",
                                                  "--mass"),
    toml_keys=("body", "foundation"),
    summary="flexible body (elastic column on a rigid base with mass) on two tensionless corner "
            "spring-dashpots: vertical and rocking motion of the base with the column's vibration"))
register(Model(
    "two_spring_wall", "foundation_wall", "rigid", frozenset({"wall", "foundation:two_spring"}),
    ("y", "y_dot", "theta", "theta_dot"), _foundation_wall,
    columns=_FOUNDATION_COLUMNS + ("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall"),
    outcomes=("safe", "mode1", "mode2", "leaning", "failed"),
    cli_options=_RIGID_CLI + _WALL_CLI + ("--foundation", "--foundation-omega", "--foundation-zeta", "--mass"),
    toml_keys=("body", "wall", "foundation"),
    summary="rigid block on two tensionless corner spring-dashpots beside a rear wall (its top corner "
            "touches a tall wall at a gap > 0)"))
# the asymmetric RigidBody (level base, outline for its wall-side face) in the same kernel
_BY_SCENE[("rigid_body", frozenset({"wall", "foundation:two_spring"}))] = MODELS["two_spring_wall"]
register(Model(
    "switching_wall", "foundation_wall", "rigid", frozenset({"wall", "foundation:switching"}),
    ("theta", "theta_dot"), _switching_wall,
    columns=_FOUNDATION_COLUMNS + ("toward_wall", "max_rotation_toward_wall", "max_rotation_away_from_wall"),
    outcomes=("safe", "mode1", "mode2", "leaning", "flight", "failed"),
    cli_options=_RIGID_CLI + _WALL_CLI + ("--foundation", "--foundation-omega", "--foundation-zeta", "--mass"),
    toml_keys=("body", "wall", "foundation"),
    summary="rigid block switching between a rotational spring and Housner rocking beside a rear wall "
            "(the rigid wall model's contact and impact while rocking toward it)"))
