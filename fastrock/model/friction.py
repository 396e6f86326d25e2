"""Coulomb friction at the base (docs: theory/friction, theory/flexible_friction)."""
from __future__ import annotations

import math
from dataclasses import dataclass

from fastrock import _validate as V
from fastrock.kernels import layout as _L

DEFAULT_SLIDE_TOLERANCE = 1e-3   # m

LIFT_OFF = {"stop": _L.LIFT_OFF_STOP, "hold": _L.LIFT_OFF_HOLD, "flight": _L.LIFT_OFF_FLIGHT}


@dataclass(frozen=True)
class Friction:
    """Static and kinetic friction coefficients.

    ``Friction(mu_s, mu_k=None)``: ``mu_k`` defaults to ``mu_s``; mu_k <= mu_s.
    ``mu_s = inf`` means no sliding: the scene then runs the frictionless
    kernel and pays nothing for friction.  ``slide_tolerance`` [m]: a safe run
    whose residual slip exceeds it has outcome "slide" (default 1 mm).

    ``lift_off``: what happens when the normal force N reaches 0.  "stop"
    (default): the run ends with outcome "flight" (a rigid block with a
    wall and friction always runs the contact model, which flies).
    "flight": the body leaves the ground and flies as a free body until it
    lands on a corner or flat (plastic normal impact with Coulomb friction),
    in the contact model for a RigidBlock and in ``flexible_flight`` for a
    FlexibleBody (column and base fly together); it reports
    ``flights``, ``time_flight`` and ``max_jump``.  With ``mu_s = inf`` it
    never slips but still flies.  "hold" (FlexibleBody): the pivot is held
    on the ground, as the classic rocking models implicitly do (they never
    check N), and the base slips without friction while N < 0; the time
    spent so is reported as ``time_unloaded``.

    Examples
    --------
    With mu_s = 0.2 below b/h = 0.25 the block slides instead of rocking:

    >>> from fastrock import Friction, Pulse, RigidBlock, simulate
    >>> block = RigidBlock.rectangle(b=0.2, h=0.8)
    >>> run = simulate(block, Pulse(amplitude=0.4, frequency=1.5), friction=Friction(0.2))
    >>> run.outcome, run.status, round(float(run.metrics["max_slide"]), 3)
    ('slide', 'safe:no-uplift', 0.056)
    """

    mu_s: float
    mu_k: float | None = None
    slide_tolerance: float = DEFAULT_SLIDE_TOLERANCE
    lift_off: str = "stop"

    def __post_init__(self):
        for name in ("mu_s", "mu_k", "slide_tolerance"):
            v = getattr(self, name)
            if v is None and name == "mu_k":
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise ValueError(f"{name} must be a number, got {v!r}")
            object.__setattr__(self, name, float(v))
        if not (isinstance(self.mu_s, (int, float)) and math.isinf(self.mu_s) and self.mu_s > 0):
            V.non_negative("mu_s", self.mu_s)
        if self.mu_k is None:
            object.__setattr__(self, "mu_k", float(self.mu_s))
        elif not (math.isinf(self.mu_k) and math.isinf(self.mu_s)):
            V.non_negative("mu_k", self.mu_k)
        if self.mu_k > self.mu_s:
            raise ValueError(f"mu_k must be <= mu_s, got mu_k={self.mu_k}, mu_s={self.mu_s}")
        V.non_negative("slide_tolerance", self.slide_tolerance)
        V.choice("lift_off", self.lift_off, LIFT_OFF)

    @classmethod
    def never_slipping(cls):
        """``Friction(inf, lift_off="flight")``: a base that never slips but may
        leave the ground, what the contact model runs when a scene gives no
        ``friction=`` (an asymmetric body beside a wall)."""
        return cls(math.inf, lift_off="flight")

    @property
    def sliding_possible(self):
        return math.isfinite(self.mu_s)
