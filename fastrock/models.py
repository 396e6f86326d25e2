"""Choose the smallest kernel a scene needs and build its parameter vector.

A kernel module is imported only when a scene needs it, so a rigid scene
never imports (let alone compiles) the wall, flexible or friction kernels.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass

import numpy as np

from .bodies import RigidBlock


@dataclass(frozen=True)
class KernelSpec:
    name: str          # e.g. "rigid", "rigid_wall"
    module: str        # fastrock.kernels.<module>
    n_state: int
    par: np.ndarray
    state_names: tuple

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


def select(body, wall=None):
    """KernelSpec for a body and its contact effects."""
    if isinstance(body, RigidBlock):
        par = rigid_par(body)
        if wall is None:
            return KernelSpec("rigid", "rigid", 2, par, ("theta", "theta_dot"))
        from .wall import Wall
        if not isinstance(wall, Wall):
            raise ValueError(f"wall must be a fastrock.Wall, got {type(wall).__name__}")
        wall.fill_par(par, body)
        return KernelSpec("rigid_wall", "wall", 2, par, ("theta", "theta_dot"))
    raise ValueError(f"body must be a fastrock body (RigidBlock, ...), got {type(body).__name__}")
