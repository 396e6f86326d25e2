"""Solver settings and their translation to the kernels' option vector."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from fastrock import _validate as V
from fastrock.kernels import layout as L

DEFAULT_RTOL = 1e-8
DEFAULT_T_AFTER = 10.0
#: Solver.method -> the kernels' O_METHOD code
METHODS = {"auto": L.METHOD_AUTO, "RK45": L.METHOD_DOPRI, "Rodas4": L.METHOD_RODAS}


@dataclass(frozen=True)
class Solver:
    """Integrator settings.

    Parameters
    ----------
    rtol, atol : float
        Tolerances of the adaptive Dormand-Prince 5(4) integrator (SciPy's
        RK45 error control).  ``atol`` defaults to ``rtol * 1e-2`` (state in
        rad and rad/s).  On the two-spring foundation the base's vertical
        displacement y_c and velocity y_c' are held to absolute errors of
        ``rtol M g / k_v`` and ``rtol M g / max(c_v, sqrt(k_v M))`` (or
        ``atol`` if smaller), with no relative part, so that the corner
        forces are resolved to ``rtol M g`` (docs: theory/numerics).
    dt : float, optional
        Fixed step [s]; switches to fixed-step DP5 (events are still located
        on the dense output).
    max_steps : int
        Step budget (accepted + rejected); exceeding it is reported as the
        status "failed:step-budget", never silently.
    max_step : float
        Largest adaptive step [s].
    record_breakpoints : bool
        Treat every record sample as a breakpoint (no step straddles a kink of
        the interpolated record).
    eps_omega, eps_t : float
        Chatter-to-rest thresholds [rad/s, s] (docs: theory/numerics).
    method : {"auto", "RK45", "Rodas4"}
        Integration method.  ``"auto"``: Dormand-Prince 5(4); on the
        flexible-foundation models it turns to the stiff method Rodas4
        (L-stable Rosenbrock, order 4(3)) where the problem is stiff (a stiff,
        damped spring) and back where it is not.  ``"RK45"``: Dormand-Prince
        only.  ``"Rodas4"``: Rodas4 only (foundation models; the others refuse
        it).  With ``dt``, "auto" takes a step at which DP5 is unstable again
        with Rodas4.
    """

    rtol: float = DEFAULT_RTOL
    atol: float | None = None
    dt: float | None = None
    max_steps: int = 2_000_000
    max_step: float = math.inf
    record_breakpoints: bool = True
    eps_omega: float = 1e-9
    eps_t: float = 1e-9
    # studies saved before this field keep their hash (studies.definition._canon)
    method: str = field(default="auto", metadata={"hash_default": True})

    def __post_init__(self):
        V.in_open("rtol", self.rtol, 1e-15, 1.0)
        if self.atol is not None:
            V.positive("atol", self.atol)
        if self.dt is not None:
            V.positive("dt", self.dt)
        V.integer("max_steps", self.max_steps, 1, V.MAX_STEPS)
        if not (self.max_step == math.inf or V._is_number(self.max_step)
                and V.positive("max_step", self.max_step)):
            raise ValueError(f"max_step must be > 0 (inf: no limit), got {self.max_step!r}")
        V.boolean("record_breakpoints", self.record_breakpoints)
        V.non_negative("eps_omega", self.eps_omega)
        V.non_negative("eps_t", self.eps_t)
        if self.method not in METHODS:
            raise ValueError(f"method must be one of {', '.join(map(repr, METHODS))}, got {self.method!r}")

    def check_model(self, model):
        """Refuse ``method="Rodas4"`` for a registry model that has no stiff method."""
        if self.method == "Rodas4" and not model.stiff:
            raise ValueError(f"method='Rodas4' is available on the flexible-foundation models only; the "
                             f"model {model.name!r} runs Dormand-Prince (method='auto' or 'RK45')")

    def check_fixed_steps(self, span, what="the run"):
        """With a fixed step, refuse a run of ``span`` seconds that needs more steps than
        ``max_steps`` (it could only end in failed:step-budget, after the whole budget)."""
        if not self.dt:
            return
        n = span / self.dt
        if n > self.max_steps:
            raise ValueError(f"dt = {self.dt:g} s needs {n:.3g} fixed steps for {what} of {span:.4g} s, more "
                             f"than the step budget max_steps = {int(self.max_steps):,}; use a larger dt, a "
                             f"shorter run or a larger max_steps (at most {V.MAX_STEPS:.0e})")

    @property
    def name(self):
        if self.dt:
            return ("" if self.method == "auto" else f"{self.method} ") + f"fixed dt={self.dt:g}"
        return f"{'RK45' if self.method == 'auto' else self.method} rtol={self.rtol:g}"

    def options(self, t_end, early_exit, t0=0.0):
        opt = np.zeros(L.N_OPT)
        opt[L.O_RTOL] = self.rtol
        opt[L.O_ATOL] = self.atol if self.atol is not None else self.rtol * 1e-2
        opt[L.O_DT_FIXED] = self.dt or 0.0
        opt[L.O_MAX_STEP] = self.max_step
        opt[L.O_MAX_STEPS] = float(self.max_steps)
        opt[L.O_T_END] = t_end
        opt[L.O_EARLY_EXIT] = 1.0 if early_exit else 0.0
        opt[L.O_RECORD_BREAKS] = 1.0 if self.record_breakpoints else 0.0
        opt[L.O_EPS_OMEGA] = self.eps_omega
        opt[L.O_EPS_T] = self.eps_t
        opt[L.O_T0] = t0
        opt[L.O_METHOD] = METHODS[self.method]
        return opt


def make_solver(solver=None, rtol=None, atol=None, dt=None, **kw):
    """A Solver from keyword shortcuts (``rtol=``, ``dt=`` ...)."""
    if solver is not None:
        if any(v is not None for v in (rtol, atol, dt)) or kw:
            raise ValueError("give either solver= or rtol/atol/dt/..., not both")
        if not isinstance(solver, Solver):
            raise ValueError(f"solver must be a fastrock.Solver, got {type(solver).__name__}")
        return solver
    args = {k: v for k, v in dict(rtol=rtol, atol=atol, dt=dt, **kw).items() if v is not None}
    return Solver(**args)
