"""Single runs: time history, events and outcome.
"""
from __future__ import annotations

import warnings
from functools import partial

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.model import excitation as X
from fastrock.running import registry
from fastrock.running.outcomes import (MODE_NAMES, checked_stable_step, outcome_of, status_of, warn_budget,
                                       warn_unstable)
from fastrock.model.ground import as_ground
from fastrock.running.solver import DEFAULT_T_AFTER, make_solver
from fastrock.running.sweep import call_kernel
from fastrock.kernels import layout as L
from fastrock.kernels.config import DEBUG
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS
from fastrock.running.result import (SimulationResult, ground_at, events_frame, flight_metrics,
    friction_metrics, initial_state, metrics_dict, run_inputs)


def _history(hist, hdr, smp, spec, body):
    """The history table of a run from its kernel output rows."""
    t, y, d = hist
    level = hdr.copy()
    level[L.S_ON] = 0.0         # the channels as given, not their slope-frame parts
    ag, av = ground_at(t, level, smp)
    ti = spec.theta_index
    th = y[:, ti]
    history = pd.DataFrame({
        "t": t, "a_g": ag, "a_v": av, "theta": th, "theta_dot": y[:, ti + 1],
        "theta_ratio": th / body.alpha,
        "contact": [MODE_NAMES.get(int(m), str(m)) for m in d[:, 0]],
        "pivot": np.where(d[:, 0] == L.MODE_REST, 0, d[:, 1]),
    })
    if spec.flexible:
        u, du = y[:, 0], y[:, 1]
        wn = body.omega_n
        history["u"] = u
        history["u_dot"] = du
        history["u_ratio"] = u / body.uplift_deformation
        # elastic column force and the moment it makes at the base
        history["base_shear"] = body.mass * (wn * wn * u + 2 * body.zeta * wn * du)
        history["overturning_moment"] = history["base_shear"] * body.H
    if spec.friction:
        history["d"] = y[:, spec.slide_index]
        history["d_dot"] = y[:, spec.slide_index + 1]
    if "z" in spec.state_names:     # height of the base above the ground (free flight)
        iz = spec.state_names.index("z")
        history["z"] = y[:, iz]
        history["z_dot"] = y[:, iz + 1]
    return history


def simulate(body, excitation=None, *, vertical=None, wall=None, friction=None, foundation=None, ground=None,
             mass=None,
             theta0=0.0, dtheta0=0.0, duration=None, t_after=DEFAULT_T_AFTER, t_eval=None, solver=None,
             rtol=None, atol=None, dt=None, early_exit=False, max_steps=None, record_breakpoints=None,
             history_capacity=None, resample_vertical=False):
    """Simulate one body under a ground excitation (or free rocking).

    Parameters
    ----------
    body : RigidBlock, RigidBody or FlexibleBody
        An asymmetric :class:`RigidBody` runs the two-sided rocking model,
        each side with its own alpha and p (``theta_ratio`` and
        ``max_rotation_ratio`` refer to the smaller alpha); a symmetric one
        runs as its RigidBlock.
    excitation : Pulse, SampledMotion or GroundMotion, optional
        Horizontal ground acceleration.  None: free rocking from
        (``theta0``, ``dtheta0``).
    vertical : Pulse, SampledMotion or GroundMotion, optional
        Vertical ground acceleration a_v (effective gravity G = g + a_v).  A
        vertical record beside a horizontal record must have the same dt,
        length and start, unless ``resample_vertical=True`` (linear
        interpolation onto the horizontal samples).
    wall : Wall, optional
        One-sided rocking against a rear wall; with ``foundation`` (TwoSpringFoundation or
        SwitchingFoundation) the wall stands beside the block on its foundation.
    friction : Friction, optional
        Coulomb friction (sliding and slide-rocking); None or mu_s = inf:
        no sliding degree of freedom at all.  With a TwoSpringFoundation the
        base slides on the corner springs (model two_spring_friction).
    foundation : TwoSpringFoundation, SwitchingFoundation or LinearVibration, optional
        A flexible foundation under a RigidBlock or RigidBody (rocking against
        vibration; an asymmetric body on TwoSpringFoundation only);
        the run is :func:`fastrock.simulate_foundation`'s, whose
        result documents the extra history columns.
    ground : Ground, optional
        Sloping ground (``Ground(slope=phi)``); None: level ground.  On a
        slope x and the slip d run along the surface, positive downhill,
        and the history's ``a_g``, ``a_v`` are the channels as given.
    mass : float, optional
        Block mass [kg] with ``foundation`` (its stiffnesses are absolute):
        a RigidBody carries its own mass (a different ``mass`` is refused),
        a RigidBlock 1 kg unless given.
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
        Stop once the outcome is decided (docs: guide/outcomes, "Early decisions").

    Returns
    -------
    SimulationResult

    Examples
    --------
    >>> from fastrock import Pulse, RigidBlock, simulate
    >>> block = RigidBlock.rectangle(b=0.2, h=0.8)
    >>> run = simulate(block, Pulse(amplitude=0.4, frequency=1.5))   # 0.4 g, 1.5 Hz
    >>> run.outcome, run.status, run.metrics["impacts"]
    ('mode1', 'overturn:mode1', 1)
    >>> list(run.events.event)
    ['uplift', 'impact', 'pass-alpha', 'overturn']
    """
    mass = registry.carried_mass(body, foundation, mass)
    body = registry.model_body(body)
    kw = {}
    if max_steps is not None:
        kw["max_steps"] = max_steps
    if record_breakpoints is not None:
        kw["record_breakpoints"] = record_breakpoints
    resample_vertical = V.boolean("resample_vertical", resample_vertical)
    spec = registry.select(body, wall, friction, foundation, None if mass is None else V.positive("mass", mass))
    ground = as_ground(ground)
    if ground is not None:
        ground.check_scene(body, friction=friction, flexible=spec.flexible, foundation=foundation)
        early_exit = False      # the early decisions assume level ground
    vertical = X.match_components(excitation, vertical, resample_vertical)
    if foundation is not None:
        from fastrock.running.foundation import simulate_foundation
        return simulate_foundation(body, foundation, excitation, mass=mass, vertical=vertical, friction=friction,
                                   theta0=theta0,
                                   dtheta0=dtheta0, duration=duration, t_after=t_after, t_eval=t_eval,
                                   solver=make_solver(solver, rtol, atol, dt, **kw), allow_overturn=True,
                                   history_capacity=history_capacity, ground=ground, early_exit=early_exit,
                                   wall=wall)
    solver = make_solver(solver, rtol, atol, dt, **kw)
    solver.check_model(spec.model)
    excitation = X.as_excitation(excitation)
    vertical = X.as_excitation(vertical, "vertical")
    y0 = initial_state(spec, body, theta0, dtheta0, wall, ground)
    hdr, smp, opt, te, cap = run_inputs(body, excitation, vertical, duration, t_after, t_eval,
                                        history_capacity, solver, early_exit, ground)
    if ground is not None:
        ground.check_lift_off(body, X.channel_peak(hdr, smp), spec.name, vertical)

    def run(opt, cap, te=te):
        while True:
            y = y0.copy()
            met = np.zeros(L.N_MET)
            hist_t = np.empty(cap)
            hist_y = np.empty((cap, spec.n_state))
            hist_d = np.empty((cap, 3), np.int64)
            log = np.empty((max(1000, cap // 4), L.N_LOG))
            cnt = np.zeros(N_COUNTERS, np.int64)
            code = int(call_kernel(spec.simulate, y, spec.par, hdr, smp, opt, te, met, hist_t, hist_y, hist_d,
                                   log, cnt, opt=opt))
            if code == L.FAIL_OUTPUT_FULL and cap < 50_000_000:
                cap *= 4
                continue
            return code, met, hist_t, hist_y, hist_d, log, cnt

    code, met, hist_t, hist_y, hist_d, log, cnt = run(opt, cap, te)
    nh = int(cnt[C_NHIST])
    hist = (hist_t[:nh].copy(), hist_y[:nh].copy(), hist_d[:nh].copy())
    history = partial(_history, hist, hdr, smp, spec, body)       # built when first read
    events = partial(events_frame, log[:int(cnt[C_NLOG])].copy(), cnt)
    metrics = metrics_dict(met, body)
    outcome = outcome_of(code)
    if spec.friction:
        metrics.update({k: float(v[0]) for k, v in friction_metrics(met[None, :], spec.flexible).items()})
        metrics["stick_slip"] = int(metrics["stick_slip"])
        if "lift_offs" in metrics:
            metrics["lift_offs"] = int(metrics["lift_offs"])
        # (friction None: an asymmetric body beside a wall, run with a pivot that never slips)
        if outcome == "safe" and friction is not None and abs(metrics["residual_slide"]) > friction.slide_tolerance:
            outcome = "slide"
    if spec.model.flight or spec.name == "contact":
        metrics.update({k: v[0].item() for k, v in flight_metrics(met[None, :]).items()})
    if solver.dt:
        checked = None
        if code == L.FAIL_UNSTABLE:
            # the check keeps no history: one output time
            te_end = np.array([opt[L.O_T_END]])
            checked = checked_stable_step(lambda o: run(o, 16, te_end)[0:2], opt, solver.dt, met[L.M_DT_STABLE])
        warn_unstable(code, met, solver.dt, checked=checked)
    warn_budget(code, met, opt)
    if DEBUG:
        metrics["energy_gains"] = int(met[L.M_ENERGY_GAINS])
    if metrics.get("energy_gains", 0) > 0:
        if getattr(body, "impact", None) == "pivot-switch":
            warnings.warn(f"the pivot-switch (I1) impact map would have added energy at {metrics['energy_gains']} "
                          "impact(s) in this run; those took the full-contact map, which never does (see the "
                          "docs' user guide, 'Flexible bodies', 'Impact maps')", stacklevel=2)
        else:
            warnings.warn(f"{metrics['energy_gains']} impact(s) raised the kinetic energy (FASTROCK_DEBUG "
                          "check): a defect, please report it with this run", RuntimeWarning, stacklevel=2)
    return SimulationResult(history=history, events=events, outcome=outcome,
                            status=status_of(code), status_code=code,
                            metrics=metrics, kernel=spec.name, body=body,
                            excitation=excitation, vertical=vertical, ground=ground,
                            effects=tuple(e for e, on in (("flexible", spec.flexible),
                                                          ("friction", spec.friction),
                                                          ("flight", spec.model.flight),
                                                          ("wall", wall is not None),
                                                          ("slope", ground is not None),
                                                          ("vertical", vertical is not None)) if on))

