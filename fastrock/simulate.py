"""Single runs: time history, events and outcome."""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from . import _validate as V
from . import excitation as X
from . import models
from .outcomes import EVENT_NAMES, MODE_NAMES, outcome_of, status_of, warn_unstable
from .solver import DEFAULT_T_AFTER, make_solver
from .sweep import call_kernel
from fastrock.kernels import layout as L
from fastrock.kernels.config import DEBUG
from fastrock.kernels.hybrid import C_LOG_DROPPED, C_NHIST, C_NLOG, N_COUNTERS

METRIC_COLUMNS = {
    "max_rotation": L.M_MAX_ABS_THETA,
    "max_rotation_pos": L.M_MAX_THETA_POS,
    "max_rotation_neg": L.M_MAX_THETA_NEG,
    "impacts": L.M_IMPACTS,
    "wall_impacts": L.M_WALL_IMPACTS,
    "time_uplift": L.M_T_UPLIFT,
    "time_overturn": L.M_T_OVER,
    "time_pass_alpha": L.M_T_PASS_ALPHA,
    "nfev": L.M_NFEV,
    "steps": L.M_NSTEPS,
    "rejected_steps": L.M_NREJECT,
    "time_end": L.M_T_FINAL,
}
INTEGER_METRICS = ("impacts", "wall_impacts", "nfev", "steps", "rejected_steps")


def metrics_dict(met, body):
    d = {k: float(met[i]) for k, i in METRIC_COLUMNS.items()}
    for k in INTEGER_METRICS:
        d[k] = int(d[k])
    d["max_rotation_ratio"] = d["max_rotation"] / body.alpha
    d["ground_impacts"] = d["impacts"]
    if getattr(body, "kind", "") == "flexible":
        d.update(flexible_metrics(met[None, :], body))
        d = {k: (v[0].item() if isinstance(v, np.ndarray) else v) for k, v in d.items()}
    return d


def friction_metrics(MET, flexible=False):
    """Sliding metrics from rows of kernel metrics (arrays, m and s); a
    flexible body adds the held lift-offs (Friction(lift_off="hold"))."""
    d = {
        "max_slide": MET[:, L.M_MAX_SLIDE],
        "residual_slide": MET[:, L.M_RESIDUAL_SLIDE],
        "time_sliding": MET[:, L.M_T_SLIDE],
        "time_slide_rocking": MET[:, L.M_T_SLIDE_ROCK],
        "stick_slip": np.nan_to_num(MET[:, L.M_N_STICK_SLIP]),
    }
    if flexible:
        d["lift_offs"] = np.nan_to_num(MET[:, L.M_N_LIFT_OFF]).astype(int)
        d["time_unloaded"] = MET[:, L.M_T_UNLOADED]
    return d


def flight_metrics(MET):
    """Free-flight metrics (contact model) from rows of kernel metrics (arrays)."""
    return {
        "flights": np.nan_to_num(MET[:, L.M_N_FLIGHTS]).astype(int),
        "time_flight": MET[:, L.M_T_FLIGHT],
        "max_jump": MET[:, L.M_MAX_JUMP],
    }


def flexible_metrics(MET, body):
    """Flexible-body metrics from rows of kernel metrics (arrays)."""
    umax = np.maximum(MET[:, L.M_MAX_U], MET[:, L.M_MIN_U])
    return {
        "max_deformation": umax,
        "max_deformation_ratio": umax / body.uplift_deformation,
        "time_rocking": MET[:, L.M_T_ROCK],
        "time_contact": MET[:, L.M_T_CONTACT],
        "energy_gains": np.nan_to_num(MET[:, L.M_ENERGY_GAINS]).astype(int),
    }


@dataclass
class SimulationResult:
    """Outcome of :func:`simulate`.

    Attributes
    ----------
    history : DataFrame
        Columns ``t`` [s], ``a_g``, ``a_v`` [m/s^2], ``theta`` [rad],
        ``theta_dot`` [rad/s], ``theta_ratio`` (theta/alpha), ``contact``
        ("rest", "rock", ...), ``pivot`` (+1 right corner, -1 left, 0 at rest).
    events : DataFrame
        Columns ``t`` [s], ``event``, ``pivot``, ``theta`` [rad],
        ``velocity_before``, ``velocity_after`` [rad/s].
    outcome : str
        "safe", "mode1", "mode2", "leaning", "flight" or "failed".
    status : str
        Refined status, e.g. "safe:rest" (see fastrock.outcomes).
    metrics : dict
        max |theta| (``max_rotation`` [rad], ``max_rotation_ratio``), impacts,
        times of uplift / overturning [s], nfev, steps ...
    kernel : str
        Name of the compiled kernel that ran.
    """

    history: pd.DataFrame
    events: pd.DataFrame
    outcome: str
    status: str
    status_code: int
    metrics: dict
    kernel: str
    body: object
    excitation: object = None
    effects: tuple = field(default_factory=tuple)
    vertical: object = None

    def ground_acceleration(self, t):
        """Horizontal and vertical ground acceleration [m/s^2] at times ``t`` [s], from the
        excitation itself (not from the rows the integrator happened to store)."""
        hdr, smp = X.to_header(self.body, self.excitation, self.vertical)
        return _ground_at(np.atleast_1d(np.asarray(t, dtype=float)), hdr, smp)

    def plot(self, **kw):
        from .plotting import plot_history
        return plot_history(self, **kw)


def simulate(body, excitation=None, *, vertical=None, wall=None, friction=None, foundation=None, mass=1.0,
             theta0=0.0, dtheta0=0.0, duration=None, t_after=DEFAULT_T_AFTER, t_eval=None, solver=None,
             rtol=None, atol=None, dt=None, early_exit=False, max_steps=None, record_breakpoints=None,
             history_capacity=None, resample_vertical=False):
    """Simulate one body under a ground excitation (or free rocking).

    Parameters
    ----------
    body : RigidBlock
    excitation : Pulse, SampledMotion or GroundMotion, optional
        Horizontal ground acceleration.  None: free rocking from
        (``theta0``, ``dtheta0``).
    vertical : Pulse, SampledMotion or GroundMotion, optional
        Vertical ground acceleration a_v (effective gravity G = g + a_v).  A
        vertical record beside a horizontal record must have the same dt,
        length and start, unless ``resample_vertical=True`` (linear
        interpolation onto the horizontal samples).
    wall : Wall, optional
        One-sided rocking against a rear wall.
    friction : Friction, optional
        Coulomb friction (sliding and slide-rocking); None or mu_s = inf:
        no sliding degree of freedom at all.
    foundation : TwoSpringFoundation, SwitchingFoundation or LinearVibration, optional
        A flexible foundation under a RigidBlock (rocking against vibration);
        the run is :func:`fastrock.foundation.simulate_foundation`'s, whose
        result documents the extra history columns.
    mass : float
        Block mass [kg] with ``foundation``.
    theta0, dtheta0 : float
        Initial rotation [rad] and angular velocity [rad/s].
    duration : float, optional
        End time [s].  Default: end of the excitation + ``t_after``.
    t_eval : array, optional
        Output times [s]; default: every accepted step and every event.
    solver, rtol, atol, dt :
        Integrator settings (see :class:`fastrock.Solver`); ``dt`` selects the
        fixed-step mode.
    early_exit : bool
        Stop once the outcome is decided (see README, "Early decisions").

    Returns
    -------
    SimulationResult
    """
    kw = {}
    if max_steps is not None:
        kw["max_steps"] = max_steps
    if record_breakpoints is not None:
        kw["record_breakpoints"] = record_breakpoints
    resample_vertical = V.boolean("resample_vertical", resample_vertical)
    spec = models.select(body, wall, friction, foundation, V.positive("mass", mass))
    vertical = X.match_components(excitation, vertical, resample_vertical)
    if foundation is not None:
        from .foundation import simulate_foundation
        return simulate_foundation(body, foundation, excitation, mass=mass, vertical=vertical, theta0=theta0,
                                   dtheta0=dtheta0, duration=duration, t_after=t_after, t_eval=t_eval,
                                   solver=make_solver(solver, rtol, atol, dt, **kw), allow_overturn=True,
                                   history_capacity=history_capacity)
    solver = make_solver(solver, rtol, atol, dt, **kw)
    excitation = X.as_excitation(excitation)
    vertical = X.as_excitation(vertical, "vertical")
    theta0 = V.finite("theta0", theta0)
    dtheta0 = V.finite("dtheta0", dtheta0)
    if abs(theta0) >= body.theta_over:
        raise ValueError(f"theta0 must satisfy |theta0| < theta_over = {body.theta_over}, got {theta0}")
    if wall is not None:
        wall.check_initial(theta0, body)
    hdr, smp, opt, te, cap = run_inputs(body, excitation, vertical, duration, t_after, t_eval,
                                        history_capacity, solver, early_exit)
    y0 = np.zeros(spec.n_state)
    y0[spec.theta_index] = theta0
    y0[spec.theta_index + 1] = dtheta0
    while True:
        y = y0.copy()
        met = np.zeros(L.N_MET)
        hist_t = np.empty(cap)
        hist_y = np.empty((cap, spec.n_state))
        hist_d = np.empty((cap, 3), np.int64)
        log = np.empty((max(1000, cap // 4), L.N_LOG))
        cnt = np.zeros(N_COUNTERS, np.int64)
        code = int(call_kernel(spec.simulate, y, spec.par, hdr, smp, opt, te, met, hist_t, hist_y, hist_d, log,
                               cnt, opt=opt))
        if code == L.FAIL_OUTPUT_FULL and cap < 50_000_000:
            cap *= 4
            continue
        break
    nh = int(cnt[C_NHIST])
    t = hist_t[:nh]
    ag, av = _ground_at(t, hdr, smp)
    ti = spec.theta_index
    th = hist_y[:nh, ti]
    history = pd.DataFrame({
        "t": t, "a_g": ag, "a_v": av, "theta": th, "theta_dot": hist_y[:nh, ti + 1],
        "theta_ratio": th / body.alpha,
        "contact": [MODE_NAMES.get(int(m), str(m)) for m in hist_d[:nh, 0]],
        "pivot": np.where(hist_d[:nh, 0] == L.MODE_REST, 0, hist_d[:nh, 1]),
    })
    if spec.flexible:
        u, du = hist_y[:nh, 0], hist_y[:nh, 1]
        wn = body.omega_n
        history["u"] = u
        history["u_dot"] = du
        history["u_ratio"] = u / body.uplift_deformation
        # elastic column force and the moment it makes at the base
        history["base_shear"] = body.mass * (wn * wn * u + 2 * body.zeta * wn * du)
        history["overturning_moment"] = history["base_shear"] * body.H
    if spec.friction:
        history["d"] = hist_y[:nh, spec.slide_index]
        history["d_dot"] = hist_y[:nh, spec.slide_index + 1]
    if "z" in spec.state_names:     # height of the base above the ground (free flight)
        iz = spec.state_names.index("z")
        history["z"] = hist_y[:nh, iz]
        history["z_dot"] = hist_y[:nh, iz + 1]
    events = events_frame(log[:int(cnt[C_NLOG])], cnt)
    metrics = metrics_dict(met, body)
    outcome = outcome_of(code)
    if spec.friction:
        metrics.update({k: float(v[0]) for k, v in friction_metrics(met[None, :], spec.flexible).items()})
        metrics["stick_slip"] = int(metrics["stick_slip"])
        if "lift_offs" in metrics:
            metrics["lift_offs"] = int(metrics["lift_offs"])
        if outcome == "safe" and abs(metrics["residual_slide"]) > friction.slide_tolerance:
            outcome = "slide"
    if spec.model.flight or spec.name == "contact":
        metrics.update({k: v[0].item() for k, v in flight_metrics(met[None, :]).items()})
    if solver.dt:
        warn_unstable(code, met, solver.dt)
    if DEBUG:
        metrics["energy_gains"] = int(met[L.M_ENERGY_GAINS])
    if metrics.get("energy_gains", 0) > 0:
        if getattr(body, "impact", None) == "pivot-switch":
            warnings.warn(f"the pivot-switch (I1) impact map created energy at {metrics['energy_gains']} "
                          "impact(s) in this run (see README, flexible bodies)", stacklevel=2)
        else:
            warnings.warn(f"{metrics['energy_gains']} impact(s) raised the kinetic energy (FASTROCK_DEBUG "
                          "check): a defect, please report it with this run", RuntimeWarning, stacklevel=2)
    return SimulationResult(history=history, events=events, outcome=outcome,
                            status=status_of(code), status_code=code,
                            metrics=metrics, kernel=spec.name, body=body,
                            excitation=excitation, vertical=vertical,
                            effects=tuple(e for e, on in (("flexible", spec.flexible),
                                                          ("friction", spec.friction),
                                                          ("flight", spec.model.flight),
                                                          ("wall", wall is not None),
                                                          ("vertical", vertical is not None)) if on))


def events_frame(lg, cnt):
    """The events table of a run from its kernel event log rows (and the
    count of rows the full log dropped, in ``attrs["dropped"]``)."""
    events = pd.DataFrame({
        "t": lg[:, L.LOG_T],
        "event": [EVENT_NAMES.get(int(k), str(k)) for k in lg[:, L.LOG_KIND]],
        "pivot": lg[:, L.LOG_PIVOT].astype(int),
        "theta": lg[:, L.LOG_THETA],
        "velocity_before": lg[:, L.LOG_PRE],
        "velocity_after": lg[:, L.LOG_POST],
    })
    if cnt[C_LOG_DROPPED]:
        events.attrs["dropped"] = int(cnt[C_LOG_DROPPED])
    return events


#: Largest history buffer a caller may ask for (rows); the buffer grows by itself up to this size.
MAX_HISTORY = 50_000_000


def run_inputs(body, excitation, vertical, duration, t_after, t_eval, history_capacity, solver,
               early_exit):
    """Kernel inputs of one run: excitation header and samples, solver options
    (end time from ``duration`` or the excitation end + ``t_after``), output
    times and the history capacity."""
    early_exit = V.boolean("early_exit", early_exit)
    if history_capacity is not None:
        history_capacity = V.integer("history_capacity", history_capacity, 1, MAX_HISTORY)
    hdr, smp = X.to_header(body, excitation, vertical)      # checks the excitations first
    t_exc = X.end_time(body, excitation, vertical)
    if duration is None:
        t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
        t_end = V.run_time("t_after", t_exc + t_after, "the excitation plus t_after")
    else:
        t_end = V.run_time("duration", V.positive("duration", duration))
    if t_end <= 0:
        raise ValueError("the run has zero length: give duration or an excitation")
    solver.check_fixed_steps(t_end)
    opt = solver.options(t_end, early_exit)
    if t_eval is None:
        return hdr, smp, opt, np.empty(0), history_capacity or 20000
    te = V.finite_array("t_eval", t_eval)
    if te.size == 0:
        raise ValueError("t_eval is empty; pass t_eval=None for the history at every step and event")
    if (np.diff(te) < 0).any():
        i = int(np.flatnonzero(np.diff(te) < 0)[0])
        raise ValueError(f"t_eval must be sorted (non-decreasing): t_eval[{i + 1}] = {te[i + 1]!r} < "
                         f"t_eval[{i}] = {te[i]!r}")
    t0 = float(opt[L.O_T0])
    if te[0] < t0 or te[-1] > t_end:
        raise ValueError(f"t_eval must lie inside the run [{t0:g}, {t_end:g}] s, got values from {te[0]:g} "
                         f"to {te[-1]:g} s" + ("" if duration is not None else
                                               " (the run ends t_after after the excitation; give duration)"))
    return hdr, smp, opt, te, te.size + 2


def _ground_at(t, hdr, smp):
    from fastrock.kernels.excitation import ground
    ag = np.empty(t.size)
    av = np.empty(t.size)
    for i, ti in enumerate(t):
        ag[i], av[i] = ground(ti, hdr, smp)
    return ag, av
