"""Choose the smallest kernel a scene needs and build its parameter vector.

A kernel module is imported only when a scene needs it, so a rigid scene
never imports (let alone compiles) the wall, flexible or friction kernels.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass

import numpy as np

from .bodies import IMPACT_MAPS, FlexibleBody, RigidBlock
from .friction import LIFT_OFF


@dataclass(frozen=True)
class KernelSpec:
    name: str          # e.g. "rigid", "rigid_wall"
    module: str        # fastrock.kernels.<module>
    n_state: int
    par: np.ndarray
    state_names: tuple
    theta_index: int = 0

    @property
    def flexible(self):
        return self.name.startswith("flexible")

    @property
    def friction(self):
        return self.name.endswith("friction")

    @property
    def slide_index(self):
        """Index of d in the state (friction kernels), else None."""
        return self.state_names.index("d") if self.friction else None

    def load(self):
        return importlib.import_module(f"fastrock.kernels.{self.module}")

    @property
    def simulate(self):
        return getattr(self.load(), f"{self.name}_simulate")

    @property
    def sweep(self):
        return getattr(self.load(), f"{self.name}_sweep")


def rigid_par(body: RigidBlock):
    from fastrock.kernels import rigid as K
    par = np.zeros(K.N_PAR)
    par[K.P_ALPHA] = body.alpha
    par[K.P_P] = body.p
    par[K.P_E] = body.e
    par[K.P_G] = body.g
    par[K.P_THETA_OVER] = body.theta_over
    return par


def flexible_par(body: FlexibleBody, sliding=False, n_par=None):
    from fastrock.kernels import flexible as K
    par = np.zeros(n_par or K.N_PAR)
    par[K.F_ALPHA] = body.alpha
    par[K.F_P] = body.p
    par[K.F_E] = body.e
    par[K.F_G] = body.g
    par[K.F_THETA_OVER] = body.theta_over
    par[K.F_B] = body.B
    par[K.F_H] = body.H
    par[K.F_WN] = body.omega_n
    par[K.F_ZETA] = body.zeta
    par[K.F_IM] = body.rotary_inertia_ratio * body.R0 ** 2
    par[K.F_IMPACT] = IMPACT_MAPS[body.impact]
    mb = body.base_mass(sliding)
    par[K.F_MB] = mb
    par[K.F_IB] = mb * body.B ** 2 / 3.0
    par[K.F_HB] = body.base_cm_height
    return par


def flexible_friction_par(body: FlexibleBody, friction):
    from fastrock.kernels import flexible_friction as K
    if body.impact != "full-contact":
        raise ValueError("friction= with a FlexibleBody needs impact='full-contact' (the slide-rock impact "
                         "rule of physics.md 4.4)")
    if body.base_mass(sliding=True) <= 0.0:
        raise ValueError("base_mass_ratio must be > 0 with sliding on: with a massless base the sliding "
                         "problem is a differential-algebraic system (physics.md 4.4); use e.g. 0.1")
    par = flexible_par(body, sliding=True, n_par=K.N_PAR)
    par[K.Q_MU_S] = friction.mu_s
    par[K.Q_MU_K] = friction.mu_k
    par[K.Q_LIFT_OFF] = LIFT_OFF[friction.lift_off]
    return par


def rigid_friction_par(body: RigidBlock, friction):
    from fastrock.kernels import friction as K
    if friction.lift_off != "stop":
        raise ValueError("lift_off='hold' is available for FlexibleBody only; a rigid block with friction "
                         "stops with outcome 'flight' when N reaches 0")
    par = np.zeros(K.N_PAR)
    par[: len(rigid_par(body))] = rigid_par(body)
    if body.b is not None and body.h is not None:
        b, h = body.b, body.h
    else:   # a rectangle of the given alpha and p
        R = 3.0 * body.g / (4.0 * body.p ** 2)
        b, h = R * np.sin(body.alpha), R * np.cos(body.alpha)
    R2 = b * b + h * h
    par[K.Q_B] = b
    par[K.Q_H] = h
    par[K.Q_IG] = body.g * np.sqrt(R2) / body.p ** 2 - R2
    par[K.Q_MU_S] = friction.mu_s
    par[K.Q_MU_K] = friction.mu_k
    return par


def select(body, wall=None, friction=None):
    """KernelSpec for a body and its contact effects (the smallest kernel:
    no wall, infinite friction or a rigid body costs nothing)."""
    if friction is not None:
        from .friction import Friction
        if not isinstance(friction, Friction):
            raise ValueError(f"friction must be a fastrock.Friction, got {type(friction).__name__}")
        if not friction.sliding_possible:
            friction = None
    if friction is not None:
        if wall is not None:
            raise ValueError("friction= together with wall= is not available yet")
        if isinstance(body, FlexibleBody):
            return KernelSpec("flexible_friction", "flexible_friction", 6, flexible_friction_par(body, friction),
                              ("u", "u_dot", "theta", "theta_dot", "d", "d_dot"), theta_index=2)
        if not isinstance(body, RigidBlock):
            raise ValueError(f"body must be a fastrock body (RigidBlock, ...), got {type(body).__name__}")
        return KernelSpec("rigid_friction", "friction", 4, rigid_friction_par(body, friction),
                          ("theta", "theta_dot", "d", "d_dot"))
    if isinstance(body, RigidBlock):
        par = rigid_par(body)
        if wall is None:
            return KernelSpec("rigid", "rigid", 2, par, ("theta", "theta_dot"))
        from .wall import Wall
        if not isinstance(wall, Wall):
            raise ValueError(f"wall must be a fastrock.Wall, got {type(wall).__name__}")
        wall.fill_par(par, body)
        return KernelSpec("rigid_wall", "wall", 2, par, ("theta", "theta_dot"))
    if isinstance(body, FlexibleBody):
        if wall is not None:
            raise ValueError("wall= is not available for FlexibleBody yet")
        return KernelSpec("flexible", "flexible", 4, flexible_par(body), ("u", "u_dot", "theta", "theta_dot"),
                          theta_index=2)
    raise ValueError(f"body must be a fastrock body (RigidBlock, ...), got {type(body).__name__}")
