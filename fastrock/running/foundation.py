"""Runs of a rigid block on a flexible foundation (simulate_foundation).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.model import excitation as X
from fastrock.model.bodies import FlexibleBody, RigidBlock
from fastrock.model.rigid_body import RigidBody
from fastrock.running.outcomes import checked_stable_step, outcome_of, status_of, warn_budget, warn_unstable
from fastrock.running.result import (SimulationResult, events_frame, flexible_metrics, friction_metrics,
                                     ground_at, metrics_dict,
                                     run_inputs)
from fastrock.running.solver import DEFAULT_T_AFTER, make_solver
from fastrock.running.sweep import call_kernel
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS
from fastrock.model.foundation import D_LEFT, D_RIGHT, block_inertia
from fastrock.model.ground import as_ground


#: Contact names of the history's ``contact`` column, by kernel mode.
CONTACT_NAMES = {L.MODE_REST: "contact", L.MODE_ROCK: "rock", L.MODE_FLIGHT: "flight",
                 L.MODE_SLIDE: "slide", L.MODE_SLIDE_ROCK: "slide-rock", L.MODE_WALL_REST: "wall"}



def foundation_spec(body, foundation, mass=None, friction=None, wall=None):
    """KernelSpec (registry entry, parameter vector) and the block's mass properties."""
    from fastrock.running.registry import select
    if not isinstance(body, (RigidBlock, RigidBody, FlexibleBody)):
        raise ValueError(f"foundation models carry a RigidBlock, RigidBody or FlexibleBody, got "
                         f"{type(body).__name__}")
    spec = select(body, wall=wall, friction=friction, foundation=foundation, mass=mass)
    return spec, block_inertia(body, mass)


def with_slide(spec, y0):
    """The foundation's initial state, with (d, d') = (0, 0) appended for a sliding model: the
    base starts at rest where it stands."""
    y0 = np.asarray(y0, float)
    return np.concatenate([y0, np.zeros(2)]) if spec.friction else y0


# ------------------------------------------------------------------------- simulation
def integrate_foundation(spec, y0, hdr, smp, opt, te, cap):
    """Run the kernel, growing the history buffer until it fits."""
    while True:
        y = y0.copy()
        met = np.zeros(L.N_MET)
        hist_t = np.empty(cap)
        hist_y = np.empty((cap, spec.n_state))
        hist_d = np.empty((cap, L.N_DISC), np.int64)
        log = np.empty((max(1000, cap // 4), L.N_LOG))
        cnt = np.zeros(N_COUNTERS, np.int64)
        code = int(call_kernel(spec.simulate, y, spec.par, hdr, smp, opt, te, met, hist_t, hist_y,
                               hist_d, log, cnt, opt=opt))
        if code == L.FAIL_OUTPUT_FULL and cap < 50_000_000:
            cap *= 4
            continue
        nh = int(cnt[C_NHIST])
        nl = int(cnt[C_NLOG])
        return code, hist_t[:nh], hist_y[:nh], hist_d[:nh], log[:nl], met, cnt


def check_wall_start(spec, y0, wall):
    """Reject a start on the foundation (the release, a static tilt on a slope or an asymmetric
    body's rest tilt) that penetrates the wall (theta_w of the spec's parameter vector)."""
    if wall is not None:
        _check_wall_start(y0[spec.theta_index], wall, spec.par[L.P_THETA_W])
    return y0


def _check_wall_start(theta0, wall, theta_w):
    if wall.side * theta0 > theta_w:
        raise ValueError(f"theta0 = {theta0!r} penetrates the wall: on the foundation, with the wall on side "
                         f"{wall.side:+d}, the block must satisfy side*theta0 <= theta_w = {theta_w:.6g} rad")


def _check_release(body, theta0, allow_overturn):
    if abs(theta0) >= body.theta_over:
        raise ValueError(f"theta0 must satisfy |theta0| < theta_over = {body.theta_over}, "
                         f"got {theta0}")
    alpha = body.alpha
    if isinstance(body, RigidBody):         # the side it leans to
        alpha = body.alpha2 if theta0 >= 0.0 else body.alpha1
    if abs(theta0) >= alpha and not allow_overturn:
        raise ValueError(f"theta0 = {theta0} rad is at or beyond alpha = {alpha} rad: a "
                         f"release there overturns; pass allow_overturn=True to simulate it")


def simulate_foundation(body, foundation, excitation=None, *, mass=None, vertical=None,
                        friction=None, theta0=0.0, dtheta0=0.0, duration=None, t_after=DEFAULT_T_AFTER,
                        t_eval=None, solver=None, rtol=None, atol=None, dt=None,
                        max_steps=None, allow_overturn=False, history_capacity=None, ground=None,
                        early_exit=False, wall=None):
    """Simulate a rigid block on a flexible foundation (or its free rocking).

    Parameters
    ----------
    body : RigidBlock, RigidBody or FlexibleBody
        Block with known ``b`` and ``h`` (``RigidBlock.rectangle`` / ``from_inertia``), or a
        RigidBody (an asymmetric one on ``TwoSpringFoundation`` only, with a level base; it
        starts at rest at its static tilt unless theta0 or dtheta0 is given), or a
        FlexibleBody (on ``TwoSpringFoundation`` only, level ground; its column starts
        undeflected; it carries its own ``mass`` and a base of ``base_mass_ratio``, default 0.1).
    foundation : TwoSpringFoundation, SwitchingFoundation or LinearVibration
    excitation, vertical : Pulse, SampledMotion or GroundMotion, optional
        Horizontal and vertical ground acceleration (None: free motion).
    friction : Friction, optional
        Coulomb friction at the base (TwoSpringFoundation only; None or mu_s = inf: the base
        is held horizontally). The base point below the centre of mass then sticks or slides
        (the two_spring_friction model, docs: theory/foundation_friction), and the block
        flies, horizontally too, while no corner touches, whatever ``lift_off`` says.
    mass : float, optional
        Block mass ``M`` [kg] of a RigidBlock (default 1); a RigidBody carries its own mass and
        inertia (a different ``mass`` is refused).
    theta0, dtheta0 : float
        Initial rotation [rad] and angular velocity [rad/s]. The two-spring block starts
        in vertical equilibrium on the corner(s) that touch (see
        :meth:`TwoSpringFoundation.initial_state`). On a slope both must be 0: the block
        starts at rest in its static equilibrium (a tilt downhill).
    allow_overturn : bool
        Allow ``|theta0| >= alpha`` (a release that overturns); otherwise ValueError.
    wall : Wall, optional
        A rigid rear wall, gap > 0 and frictionless (docs: theory/foundation, "Rear wall").
        TwoSpringFoundation: a wall at least as tall as the body, touched by the top corner at
        ``fastrock.model.foundation.wall_limit_angle``. SwitchingFoundation: the rigid wall
        model's wall while rocking (``fastrock.model.foundation.switching_wall_par``).
        LinearVibration takes none.
    duration, t_after, t_eval, solver, rtol, atol, dt, max_steps, ground, early_exit :
        As in :func:`fastrock.simulate` (the two-spring model's early decisions: after the
        excitation, on level ground, a symmetric block that can no longer lift off or overturn).

    Returns
    -------
    SimulationResult
        ``history`` columns: ``t`` [s], ``a_g``, ``a_v`` [m/s^2], ``theta`` [rad],
        ``theta_dot`` [rad/s], ``theta_ratio`` (theta/alpha), ``contact`` ("contact": full
        contact, "rock": on one corner, "flight"), ``pivot`` (+1/-1 corner carrying the
        block while it rocks, 0 in full contact), ``lift_off`` (bool, contact != "contact");
        two-spring only: ``y`` [m] (vertical displacement of the base centre; of the base
        point below the centre of mass for an asymmetric body), ``y_dot``
        [m/s], ``force_right``, ``force_left`` [N] (corner forces); with friction ``d``,
        ``d_dot`` [m, m/s] (the base point's slide relative to the ground), and ``contact``
        also "slide" / "slide-rock" (slipping on both corners / on one); a FlexibleBody also
        ``u``, ``u_dot``, ``u_ratio``, ``base_shear``, ``overturning_moment`` as in
        :func:`fastrock.simulate` (and its metrics ``max_deformation`` ...). At every event the history
        holds two rows with the same ``t`` (before and after the transition); zero crossings
        of ``theta`` are events, so the history holds them exactly.
        ``metrics`` as for :func:`fastrock.simulate`, with ``impacts`` = re-contacts after a
        lift-off (two-spring: a corner landing from above; switching: return to the contact
        phase), ``time_uplift`` = first lift-off, plus ``time_rock`` / ``time_contact`` [s].
        ``status``: "safe:no-uplift" (never lifted off), "safe:rest" (lifted off and ended in
        full contact, vibrating or at rest on the foundation), "safe:moving" (ended lifted
        off), "overturn:mode1/mode2" (overturned after / without a re-contact), "flight"
        (switching model, G <= 0 while rocking).
    """
    kw = {} if max_steps is None else {"max_steps": max_steps}
    solver = make_solver(solver, rtol, atol, dt, **kw)
    excitation = X.as_excitation(excitation)
    vertical = X.as_excitation(vertical, "vertical")
    theta0 = V.finite("theta0", theta0)
    dtheta0 = V.finite("dtheta0", dtheta0)
    spec, blk = foundation_spec(body, foundation, mass, friction, wall)
    ground = as_ground(ground)
    if ground is not None:
        ground.check_scene(body, foundation=foundation)
    _check_release(body, theta0, V.boolean("allow_overturn", allow_overturn))
    hdr, smp, opt, te, cap = run_inputs(body, excitation, vertical, duration, t_after, t_eval,
                                        history_capacity, solver, V.boolean("early_exit", early_exit), ground)
    y0 = with_slide(spec, foundation.initial_state(blk, theta0, dtheta0, ground))
    check_wall_start(spec, y0, wall)
    code, t, Y, D, lg, met, cnt = integrate_foundation(spec, y0, hdr, smp, opt, te, cap)
    if solver.dt:
        checked = None
        if code == L.FAIL_UNSTABLE:
            def rerun(o):
                r = integrate_foundation(spec, y0, hdr, smp, o, np.array([opt[L.O_T_END]]), 16)
                return r[0], r[5]
            checked = checked_stable_step(rerun, opt, solver.dt, met[L.M_DT_STABLE])
        warn_unstable(code, met, solver.dt, checked=checked)
    warn_budget(code, met, opt)
    ag, av = ground_at(t, hdr, smp)
    it = spec.state_names.index("theta")
    th = Y[:, it]
    mode = D[:, L.D_MODE]
    cols = {
        "t": t, "a_g": ag, "a_v": av, "theta": th, "theta_dot": Y[:, it + 1],
        "theta_ratio": th / body.alpha,
        "contact": [CONTACT_NAMES.get(int(m), str(m)) for m in mode],
        "pivot": np.where((mode == L.MODE_ROCK) | (mode == L.MODE_SLIDE_ROCK) | (mode == L.MODE_WALL_REST),
                          D[:, L.D_PIVOT], 0),
        "lift_off": (mode != L.MODE_REST) & (mode != L.MODE_SLIDE),
    }
    if spec.name in ("two_spring", "two_spring_friction", "flexible_two_spring", "two_spring_wall"):
        cols["y"] = Y[:, 0]
        cols["y_dot"] = Y[:, 1]
        for side, slot, name in ((1.0, D_RIGHT, "force_right"), (-1.0, D_LEFT, "force_left")):
            x = side * blk.b + blk.skew         # the corner from the point below the CM
            d = -(Y[:, 0] - x * np.sin(th))
            dd = -(Y[:, 1] - x * np.cos(th) * Y[:, it + 1])
            cols[name] = np.where(D[:, slot] != 0, foundation.k_v * d + foundation.c_v * dd,
                                  0.0)
    if spec.flexible:
        u, du = Y[:, 2], Y[:, 3]
        wn = body.omega_n
        cols.update(u=u, u_dot=du, u_ratio=u / body.uplift_deformation)
        cols["base_shear"] = body.mass * (wn * wn * u + 2 * body.zeta * wn * du)
        cols["overturning_moment"] = cols["base_shear"] * body.H
    history = pd.DataFrame(cols)
    events = events_frame(lg, cnt)
    metrics = metrics_dict(met, body)
    if spec.flexible:
        metrics.update({k: v[0].item() for k, v in flexible_metrics(met[None, :], body).items()})
    metrics["time_rock"] = float(met[L.M_T_ROCK])
    metrics["time_contact"] = float(met[L.M_T_CONTACT])
    outcome = outcome_of(code)
    if spec.friction:
        cols_d = {"d": Y[:, spec.slide_index], "d_dot": Y[:, spec.slide_index + 1]}
        history = history.assign(**cols_d)
        metrics.update({k: float(v[0]) for k, v in friction_metrics(met[None, :]).items()})
        metrics["stick_slip"] = int(metrics["stick_slip"])
        if outcome == "safe" and abs(metrics["residual_slide"]) > friction.slide_tolerance:
            outcome = "slide"
    effects = (("flexible",) if spec.flexible else ()) + (f"foundation:{foundation.model}",) + \
        (("wall",) if wall is not None else ()) + (("vertical",) if vertical is not None else ())
    if spec.friction:
        effects = effects + ("friction",)
    return SimulationResult(history=history, events=events, outcome=outcome,
                            status=status_of(code), status_code=code, metrics=metrics,
                            kernel=spec.name, body=body, excitation=excitation,
                            effects=effects, vertical=vertical)


