"""Rocking against vibration: a rigid block on a flexible foundation (physics.md §5).

Three foundation models, each a scene effect passed to :func:`simulate_foundation`:

* :class:`TwoSpringFoundation` ``(k_v, c_v)`` -- tensionless vertical spring-dashpots at the two
  bottom corners (physics.md §5.1, the reference model). Lift-off and re-contact happen
  smoothly (soft contact, no impact map); dissipation comes from ``c_v`` only.
* :class:`SwitchingFoundation` ``(k_t, c_t, e_f)`` -- the switching SDOF model used by Yu,
  Gutschmidt & MacRae (physics.md §5.2, with the P-Delta term kept): linear rotational spring
  while in contact, Housner rocking once ``|k_t theta + c_t theta'| >= M G b``, back to contact
  at ``|theta| <= theta_y = M g b / k_t``, optional restitution ``e_f`` at re-contact.
* :class:`LinearVibration` ``(k_t, c_t)`` -- a linear SDOF ``I_C theta'' + c_t theta' + k_t theta
  = -M h a_g`` that never lifts off (reference).

A rigid-ground scene is :func:`fastrock.simulate` and never imports this module's kernels.

The body is a :class:`fastrock.RigidBlock` with known half-width ``b`` and centre-of-mass
height ``h`` (:meth:`RigidBlock.rectangle` or :meth:`RigidBlock.from_inertia`) plus its mass
``M`` [kg] (default 1 kg; absolute stiffnesses scale with it). The inertia follows from the
block's ``p``: ``I_0 = M g R / p^2`` about a corner, ``I_G = I_0 - M R^2``,
``I_C = I_G + M h^2`` about the base centre.

Small-amplitude vibration in full contact (both models, P-Delta kept):
``I_C theta'' + c_t theta' + (k_t - M g h) theta = 0`` with ``k_t = 2 k_v b^2``,
``c_t = 2 c_v b^2`` for the two-spring foundation, so ``omega^2 = (k_t - M g h)/I_C`` and
``zeta = c_t / (2 I_C omega)``; the vibration period is ``T_L = 2 pi/omega`` (undamped).
:meth:`TwoSpringFoundation.from_vibration` and friends build a foundation from ``omega``
and ``zeta``.

The predictors :func:`two_spring_predictor` and :func:`switching_predictor` (and
:func:`make_predictor` for a given body) let :func:`fastrock.freerocking.fit_free_rocking`
fit these models to measured half-cycle durations.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from . import excitation as X
from .bodies import RigidBlock
from .freerocking import get_predictor, half_cycles, register_predictor, rocking_quarter_period
from .constants import G_STANDARD
from .outcomes import outcome_of, status_of
from .simulate import SimulationResult, _ground_at, events_frame, metrics_dict, run_inputs
from .solver import DEFAULT_T_AFTER, make_solver
from .sweep import call_kernel
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS

__all__ = [
    "TwoSpringFoundation", "SwitchingFoundation", "LinearVibration", "block_inertia",
    "simulate_foundation", "foundation_half_cycles", "make_predictor",
    "two_spring_predictor", "switching_predictor", "get_predictor", "PREDICTOR_MODELS",
]

#: Contact names of the history's ``contact`` column, by kernel mode.
CONTACT_NAMES = {L.MODE_REST: "contact", L.MODE_ROCK: "rock", L.MODE_FLIGHT: "flight"}

# the kernels' parameter layout (kernels/layout.py imports no kernel); discrete-state slots of
# the two-spring model (kept here as plain ints, checked against the kernel in the tests)
from fastrock.kernels.layout import (N_PAR_FOUNDATION as N_PAR, P_B, P_CT, P_CV, P_EF,  # noqa: E402,F401
                                     P_H, P_I_0, P_I_C, P_I_G, P_KT, P_KV, P_MASS, P_THETA_Y)
D_RIGHT = 6
D_LEFT = 7


# ------------------------------------------------------------------------------ body
@dataclass(frozen=True)
class BlockInertia:
    """Mass properties of a block: ``M`` [kg], ``b``, ``h``, ``R`` [m], inertias [kg m^2]."""

    M: float
    b: float
    h: float
    R: float
    I_0: float
    I_G: float
    I_C: float
    g: float


def block_inertia(body, mass=1.0):
    """Mass properties of ``body`` with mass ``mass`` [kg].

    ``I_0 = M g R / p^2`` (from the block's ``p``), ``I_G = I_0 - M R^2``, ``I_C = I_G + M h^2``.

    Raises
    ------
    ValueError
        If the body is not a :class:`RigidBlock` with known ``b`` and ``h``, or its ``p``
        implies ``I_0 < M R^2``.
    """
    if not isinstance(body, RigidBlock):
        raise ValueError(f"body must be a fastrock.RigidBlock, got {type(body).__name__}")
    if body.b is None or body.h is None:
        raise ValueError("body must have known b and h (use RigidBlock.rectangle(b, h) or "
                         "RigidBlock.from_inertia(R, alpha, I0, m))")
    M = V.positive("mass", mass)
    b, h, g = float(body.b), float(body.h), float(body.g)
    if abs(math.atan2(b, h) - body.alpha) > 1e-9 * max(1.0, body.alpha):
        raise ValueError(f"body.alpha = {body.alpha} does not match atan(b/h) = "
                         f"{math.atan2(b, h)}")
    R = math.hypot(b, h)
    I0 = M * g * R / body.p ** 2
    I_G = I0 - M * R * R
    if I_G < -1e-12 * I0:
        raise ValueError(f"body.p = {body.p} rad/s implies I_0 = M g R/p^2 < M R^2 "
                         f"(p must be <= sqrt(g/R) = {math.sqrt(g / R)})")
    I_G = max(I_G, 0.0)
    return BlockInertia(M=M, b=b, h=h, R=R, I_0=I0, I_G=I_G, I_C=I_G + M * h * h, g=g)


# ------------------------------------------------------------------------ foundations
def _rotational_from_vibration(body, omega, zeta, mass, p_delta):
    blk = block_inertia(body, mass)
    omega = V.positive("omega", omega)
    zeta = V.non_negative("zeta", zeta)
    k_t = omega ** 2 * blk.I_C + (blk.M * blk.g * blk.h if p_delta else 0.0)
    c_t = 2.0 * zeta * omega * blk.I_C
    return blk, k_t, c_t


def _vibration_of(blk, k_t, c_t, p_delta):
    k_eff = k_t - (blk.M * blk.g * blk.h if p_delta else 0.0)
    if k_eff <= 0.0:
        return float("nan"), float("nan")
    omega = math.sqrt(k_eff / blk.I_C)
    return omega, c_t / (2.0 * blk.I_C * omega)


@dataclass(frozen=True)
class TwoSpringFoundation:
    """Tensionless spring-dashpots at the two bottom corners (physics.md §5.1).

    Parameters
    ----------
    k_v : float
        Stiffness of each corner spring [N/m], > 0.
    c_v : float
        Viscous coefficient of each corner dashpot [N s/m], >= 0.
    """

    k_v: float
    c_v: float = 0.0
    model = "two-spring"
    kernel = "two_spring"

    def __post_init__(self):
        V.positive("k_v", self.k_v)
        V.non_negative("c_v", self.c_v)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, mass=1.0):
        """Corner springs giving rocking vibration ``omega`` [rad/s] with damping ratio ``zeta``.

        ``k_v = (omega^2 I_C + M g h) / (2 b^2)``, ``c_v = 2 zeta omega I_C / (2 b^2)``.
        """
        blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, True)
        return cls(k_v=k_t / (2 * blk.b ** 2), c_v=c_t / (2 * blk.b ** 2))

    def rotational(self, body, mass=1.0):
        """Small-rotation rotational stiffness and damping ``(k_t, c_t) = 2 b^2 (k_v, c_v)``."""
        b = block_inertia(body, mass).b
        return 2 * self.k_v * b * b, 2 * self.c_v * b * b

    def vibration(self, body, mass=1.0):
        """``(omega [rad/s], zeta)`` of small rocking vibration in full contact (P-Delta kept);
        NaN if ``k_t <= M g h`` (unstable on the foundation)."""
        k_t, c_t = self.rotational(body, mass)
        return _vibration_of(block_inertia(body, mass), k_t, c_t, True)

    def uplift_rotation(self, body, mass=1.0):
        """Static lift-off rotation ``theta_y = M g / (2 k_v b)`` [rad] (small angles)."""
        blk = block_inertia(body, mass)
        return blk.M * blk.g / (2 * self.k_v * blk.b)

    def fill_par(self, par, blk):
        par[P_KV] = self.k_v
        par[P_CV] = self.c_v
        k_t = 2 * self.k_v * blk.b ** 2
        par[P_KT] = k_t
        par[P_CT] = 2 * self.c_v * blk.b ** 2
        par[P_THETA_Y] = blk.M * blk.g * blk.b / k_t

    def initial_state(self, blk, theta0, dtheta0):
        """(y_c, y_c', q, q') of a release from rest in vertical equilibrium: both corners
        share the weight if they both touch, else the lower corner carries it alone."""
        d_s = blk.M * blk.g / (2 * self.k_v)
        lift = blk.b * math.sin(abs(theta0))
        yc = -d_s if lift <= d_s else lift - 2 * d_s
        return np.array([yc, 0.0, theta0, dtheta0], float)


@dataclass(frozen=True)
class SwitchingFoundation:
    """Switching SDOF foundation (physics.md §5.2, Yu et al.'s model with P-Delta kept).

    Parameters
    ----------
    k_t : float
        Rotational stiffness in the contact phase [N m/rad], > 0.
    c_t : float
        Rotational damping in the contact phase [N m s/rad], >= 0.
    e_f : float
        Angular-velocity restitution applied at re-contact, in [0, 1] (default 1: none).
    """

    k_t: float
    c_t: float = 0.0
    e_f: float = 1.0
    model = "switching"
    kernel = "switching"

    def __post_init__(self):
        V.positive("k_t", self.k_t)
        V.non_negative("c_t", self.c_t)
        V.in_closed("e_f", self.e_f, 0.0, 1.0)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, e_f=1.0, mass=1.0):
        """Contact phase with vibration ``omega`` [rad/s] and damping ratio ``zeta``:
        ``k_t = omega^2 I_C + M g h``, ``c_t = 2 zeta omega I_C``."""
        _blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, True)
        return cls(k_t=k_t, c_t=c_t, e_f=e_f)

    def vibration(self, body, mass=1.0):
        """``(omega [rad/s], zeta)`` of the contact phase (P-Delta kept)."""
        return _vibration_of(block_inertia(body, mass), self.k_t, self.c_t, True)

    def uplift_rotation(self, body, mass=1.0):
        """``theta_y = M g b / k_t`` [rad]."""
        blk = block_inertia(body, mass)
        return blk.M * blk.g * blk.b / self.k_t

    def fill_par(self, par, blk):
        par[P_KT] = self.k_t
        par[P_CT] = self.c_t
        par[P_EF] = self.e_f
        par[P_THETA_Y] = blk.M * blk.g * blk.b / self.k_t

    def initial_state(self, blk, theta0, dtheta0):
        return np.array([theta0, dtheta0], float)


@dataclass(frozen=True)
class LinearVibration:
    """Linear rotational SDOF ``I_C theta'' + c_t theta' + k_t theta = -M h a_g`` (reference).

    Parameters
    ----------
    k_t : float
        Rotational stiffness [N m/rad], > 0.
    c_t : float
        Rotational damping [N m s/rad], >= 0.
    """

    k_t: float
    c_t: float = 0.0
    model = "linear"
    kernel = "linear_sdof"

    def __post_init__(self):
        V.positive("k_t", self.k_t)
        V.non_negative("c_t", self.c_t)

    @classmethod
    def from_vibration(cls, body, omega, zeta=0.0, mass=1.0):
        """``k_t = omega^2 I_C``, ``c_t = 2 zeta omega I_C``."""
        _blk, k_t, c_t = _rotational_from_vibration(body, omega, zeta, mass, False)
        return cls(k_t=k_t, c_t=c_t)

    def vibration(self, body, mass=1.0):
        return _vibration_of(block_inertia(body, mass), self.k_t, self.c_t, False)

    def fill_par(self, par, blk):
        par[P_KT] = self.k_t
        par[P_CT] = self.c_t
        par[P_THETA_Y] = np.inf

    def initial_state(self, blk, theta0, dtheta0):
        return np.array([theta0, dtheta0], float)


FOUNDATIONS = (TwoSpringFoundation, SwitchingFoundation, LinearVibration)


def foundation_par(body, foundation, mass=1.0):
    """Parameter vector of a block on a foundation (registry ``build_par``)."""
    blk = block_inertia(body, mass)
    par = np.zeros(N_PAR)
    par[0] = body.alpha          # rigid layout: alpha, p, e, g, theta_over
    par[1] = body.p
    par[2] = body.e
    par[3] = body.g
    par[4] = body.theta_over
    par[P_MASS] = blk.M
    par[P_I_G] = blk.I_G
    par[P_B] = blk.b
    par[P_H] = blk.h
    par[P_I_C] = blk.I_C
    par[P_I_0] = blk.I_0
    par[P_EF] = 1.0
    foundation.fill_par(par, blk)
    return par


def foundation_spec(body, foundation, mass=1.0):
    """KernelSpec (registry entry, parameter vector) and the block's mass properties."""
    from .registry import select
    if not isinstance(body, RigidBlock):
        raise ValueError(f"foundation models carry a RigidBlock, got {type(body).__name__}")
    spec = select(body, foundation=foundation, mass=mass)
    return spec, block_inertia(body, mass)


# ------------------------------------------------------------------------- simulation
def _integrate(spec, y0, hdr, smp, opt, te, cap):
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


def _check_release(body, theta0, allow_overturn):
    if abs(theta0) >= body.theta_over:
        raise ValueError(f"theta0 must satisfy |theta0| < theta_over = {body.theta_over}, "
                         f"got {theta0}")
    if abs(theta0) >= body.alpha and not allow_overturn:
        raise ValueError(f"theta0 = {theta0} rad is at or beyond alpha = {body.alpha} rad: a "
                         f"release there overturns; pass allow_overturn=True to simulate it")


def simulate_foundation(body, foundation, excitation=None, *, mass=1.0, vertical=None,
                        theta0=0.0, dtheta0=0.0, duration=None, t_after=DEFAULT_T_AFTER,
                        t_eval=None, solver=None, rtol=None, atol=None, dt=None,
                        max_steps=None, allow_overturn=False, history_capacity=None):
    """Simulate a rigid block on a flexible foundation (or its free rocking).

    Parameters
    ----------
    body : RigidBlock
        Block with known ``b`` and ``h`` (``RigidBlock.rectangle`` / ``from_inertia``).
    foundation : TwoSpringFoundation, SwitchingFoundation or LinearVibration
    excitation, vertical : Pulse, SampledMotion or GroundMotion, optional
        Horizontal and vertical ground acceleration (None: free motion).
    mass : float
        Block mass ``M`` [kg] (default 1).
    theta0, dtheta0 : float
        Initial rotation [rad] and angular velocity [rad/s]. The two-spring block starts
        in vertical equilibrium on the corner(s) that touch (see
        :meth:`TwoSpringFoundation.initial_state`).
    allow_overturn : bool
        Allow ``|theta0| >= alpha`` (a release that overturns); otherwise ValueError.
    duration, t_after, t_eval, solver, rtol, atol, dt, max_steps :
        As in :func:`fastrock.simulate`.

    Returns
    -------
    SimulationResult
        ``history`` columns: ``t`` [s], ``a_g``, ``a_v`` [m/s^2], ``theta`` [rad],
        ``theta_dot`` [rad/s], ``theta_ratio`` (theta/alpha), ``contact`` ("contact": full
        contact, "rock": on one corner, "flight"), ``pivot`` (+1/-1 corner carrying the
        block while it rocks, 0 in full contact), ``lift_off`` (bool, contact != "contact");
        two-spring only: ``y`` [m] (vertical displacement of the base centre), ``y_dot``
        [m/s], ``force_right``, ``force_left`` [N] (corner forces). At every event the history
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
    spec, blk = foundation_spec(body, foundation, mass)
    _check_release(body, theta0, V.boolean("allow_overturn", allow_overturn))
    hdr, smp, opt, te, cap = run_inputs(body, excitation, vertical, duration, t_after, t_eval,
                                        history_capacity, solver, False)
    y0 = foundation.initial_state(blk, theta0, dtheta0)
    code, t, Y, D, lg, met, cnt = _integrate(spec, y0, hdr, smp, opt, te, cap)
    ag, av = _ground_at(t, hdr, smp)
    it = spec.state_names.index("theta")
    th = Y[:, it]
    mode = D[:, L.D_MODE]
    cols = {
        "t": t, "a_g": ag, "a_v": av, "theta": th, "theta_dot": Y[:, it + 1],
        "theta_ratio": th / body.alpha,
        "contact": [CONTACT_NAMES.get(int(m), str(m)) for m in mode],
        "pivot": np.where(mode == L.MODE_ROCK, D[:, L.D_PIVOT], 0),
        "lift_off": mode != L.MODE_REST,
    }
    if spec.name == "two_spring":
        cols["y"] = Y[:, 0]
        cols["y_dot"] = Y[:, 1]
        for side, slot, name in ((1.0, D_RIGHT, "force_right"), (-1.0, D_LEFT, "force_left")):
            d = -(Y[:, 0] - side * blk.b * np.sin(th))
            dd = -(Y[:, 1] - side * blk.b * np.cos(th) * Y[:, 3])
            cols[name] = np.where(D[:, slot] != 0, foundation.k_v * d + foundation.c_v * dd,
                                  0.0)
    history = pd.DataFrame(cols)
    events = events_frame(lg, cnt)
    metrics = metrics_dict(met, body)
    metrics["time_rock"] = float(met[L.M_T_ROCK])
    metrics["time_contact"] = float(met[L.M_T_CONTACT])
    effects = (f"foundation:{foundation.model}",) + (("vertical",) if vertical is not None
                                                     else ())
    return SimulationResult(history=history, events=events, outcome=outcome_of(code),
                            status=status_of(code), status_code=code, metrics=metrics,
                            kernel=spec.name, body=body, excitation=excitation,
                            effects=effects, vertical=vertical)


def _dedupe(t, *cols):
    """Keep the last of the rows that share a time (the state after a transition)."""
    keep = np.ones(t.size, bool)
    keep[:-1] = t[1:] != t[:-1]
    return (t[keep],) + tuple(c[keep] for c in cols)


def foundation_half_cycles(result, definition="impact", **kw):
    """:func:`fastrock.freerocking.half_cycles` of a simulated history, classified by lift-off.

    Rows that share a time (before/after an event) are reduced to the later one; zero
    crossings are events, so their times are exact. Works for :func:`simulate_foundation`
    results and for :func:`fastrock.simulate` (rigid: every half-cycle is "rocking").
    """
    h = result.history
    t = h["t"].to_numpy()
    th = h["theta"].to_numpy()
    lift = h["lift_off"].to_numpy() if "lift_off" in h else np.ones(t.size, bool)
    t, th, lift = _dedupe(t, th, lift)
    return half_cycles(t, th, lift_off=lift, definition=definition, **kw)


# ------------------------------------------------------------------------- predictors
PREDICTOR_MODELS = ("two-spring", "switching")


def _predictor_body(params, body, mass, inertia_ratio, g):
    alpha = float(params["alpha"])
    if body is not None:
        if abs(body.alpha - alpha) > 1e-6:
            raise ValueError(f"the fit's alpha = {alpha} differs from the body's "
                             f"{body.alpha}")
        p = float(params.get("p", body.p))
        if p <= 0:
            raise ValueError(f"p must be > 0, got {p}")
        blk = RigidBlock(alpha=body.alpha, p=p, e=body.e, g=body.g, b=body.b, h=body.h)
        return blk, mass
    if "p" not in params:
        raise NotImplementedError("the built-in two-spring/switching predictor without a body "
                                  "needs 'p' [rad/s] in params0")
    p = float(params["p"])
    if "e" in params:
        e = float(params["e"])
        gamma = (1.0 - e) / (1.0 - math.cos(2 * alpha))
    else:
        gamma = inertia_ratio
    if not 0.0 < gamma <= 1.0 or not p > 0:
        raise ValueError(f"inertia ratio M R^2/I_0 = {gamma} must lie in (0, 1] (e >= "
                         f"cos 2 alpha) and p > 0")
    R = gamma * g / p ** 2
    blk = RigidBlock(alpha=alpha, p=p, g=g, b=R * math.sin(alpha), h=R * math.cos(alpha))
    return blk, 1.0


def _predictor_foundation(model, params, blk, mass):
    if model == "two-spring":
        if "k_v" in params:
            return TwoSpringFoundation(params["k_v"], params.get("c_v", 0.0))
        if "omega" in params:
            return TwoSpringFoundation.from_vibration(blk, params["omega"],
                                                      params.get("zeta", 0.0), mass)
        raise NotImplementedError(
            "the built-in two-spring predictor needs the foundation parameters 'omega' [rad/s] "
            "(and 'zeta') or 'k_v' [N/m] (and 'c_v' [N s/m]): pass e.g. params0={'p': ..., "
            "'omega': ..., 'zeta': ...} to fit_free_rocking")
    if "k_t" in params:
        return SwitchingFoundation(params["k_t"], params.get("c_t", 0.0),
                                   params.get("e_f", 1.0))
    if "omega" in params:
        return SwitchingFoundation.from_vibration(blk, params["omega"], params.get("zeta", 0.0),
                                                  params.get("e_f", 1.0), mass)
    raise NotImplementedError(
        "the built-in switching predictor needs the foundation parameters 'omega' [rad/s] (and "
        "'zeta', 'e_f') or 'k_t' [N m/rad] (and 'c_t', 'e_f'): pass e.g. params0={'p': ..., "
        "'omega': ..., 'e_f': ...} to fit_free_rocking")


def _release_history(body, foundation, mass, theta0, t_end, rtol, max_steps):
    spec, blk = foundation_spec(body, foundation, mass)
    hdr, smp = X.to_header(body, None, None)
    opt = make_solver(rtol=rtol, max_steps=max_steps).options(t_end, False)
    y0 = foundation.initial_state(blk, theta0, 0.0)
    code, t, Y, D, _lg, _met, _cnt = _integrate(spec, y0, hdr, smp, opt, np.empty(0), 20000)
    if code < 0:
        # e.g. a fit wandering to an absurdly stiff foundation: make it an invalid point
        raise ValueError(f"{foundation} release failed: {status_of(code)}")
    it = spec.state_names.index("theta")
    lift = D[:, L.D_MODE] != L.MODE_REST
    t, th, lift = _dedupe(t, Y[:, it], lift)
    return code, t, th, lift


def make_predictor(model, body=None, mass=1.0, *, inertia_ratio=0.75, g=G_STANDARD,
                   rtol=1e-10, return_peaks=False, max_duration=600.0, max_steps=300_000):
    """A ``predictor(params, n)`` for :func:`fastrock.freerocking.fit_free_rocking`.

    It simulates the free release from rest at ``params["theta0"]`` and returns the durations
    [s] of the first ``n`` half-cycles (``params["definition"]``, via
    :func:`fastrock.freerocking.half_cycles`; fewer if the block overturns or stops), and their
    peak angles [rad] too if ``return_peaks``.

    Parameters understood in ``params`` (the fitted ones are the keys of ``params0``; the
    others take the defaults below):

    ============ ========== ===================================================================
    p            rad/s      frequency parameter ``sqrt(M g R / I_0)``; default the body's
    e            -          (no body only) sets the inertia ratio ``M R^2/I_0 = (1-e)/(1-cos
                            2 alpha)`` -- the block whose Housner restitution is ``e``
    omega, zeta  rad/s, -   small-amplitude vibration in full contact (P-Delta kept) and its
                            damping ratio (zeta default 0)
    k_v, c_v     N/m, N s/m two-spring alternative to omega/zeta (c_v default 0)
    k_t, c_t     N m/rad,.. switching alternative to omega/zeta (c_t default 0)
    e_f          -          switching: restitution at re-contact (default 1)
    ============ ========== ===================================================================

    Parameters
    ----------
    model : {"two-spring", "switching"}
    body : RigidBlock, optional
        Fixes ``b``, ``h`` (and ``p`` unless fitted). Without a body the block is the one
        with the fit's ``alpha``, ``p`` and inertia ratio (``e`` or ``inertia_ratio``), of
        size ``R = (M R^2/I_0) g / p^2`` and mass 1 kg; half-cycle durations depend on
        ``alpha, p``, the inertia ratio, ``omega`` and ``zeta`` only.
    mass : float
        Body mass [kg] with ``body`` (matters for ``k_v``/``k_t`` in SI).
    inertia_ratio : float
        ``M R^2/I_0`` without a body and without ``e`` (0.75: uniform rectangle).
    rtol : float
        Integrator tolerance (tight, so that finite-difference Jacobians are clean).
    max_steps : int
        Step budget of one release; a release that needs more (e.g. a fit wandering to an
        absurdly stiff foundation) raises ValueError, which the fit treats as an invalid
        point. Weakly identified parameters (a switching ``omega`` when the data has no
        vibration tail) are better fixed: wrap the predictor,
        ``lambda prm, n: pred({**prm, "omega": 40.0}, n)``, or bound them.
    """
    V.choice("model", model, PREDICTOR_MODELS)
    if body is not None:
        block_inertia(body, mass)       # validates b, h, p
    V.positive("inertia_ratio", inertia_ratio)
    V.positive("g", g)
    make_solver(rtol=rtol, max_steps=max_steps)     # validates rtol and max_steps
    V.run_time("max_duration", V.positive("max_duration", max_duration))
    return_peaks = V.boolean("return_peaks", return_peaks)

    def predictor(params, n):
        blk, M = _predictor_body(params, body, mass, inertia_ratio, g)
        fnd = _predictor_foundation(model, params, blk, M)
        theta0 = float(params["theta0"])
        definition = params.get("definition", "impact")
        n = int(n)
        omega, _z = fnd.vibration(blk, M)
        q0 = rocking_quarter_period(min(abs(theta0), 0.999 * blk.alpha), blk.alpha, blk.p)
        half = max(2.0 * q0, 1.5 * math.pi / omega if np.isfinite(omega) else 0.0)
        # durations shrink: start at a quarter of the no-decay bound, double if short
        t_end = q0 + 0.25 * (n + 2) * half
        while True:
            code, t, th, lift = _release_history(blk, fnd, M, theta0, t_end, rtol, max_steps)
            hc = half_cycles(t, th, lift_off=lift, definition=definition)
            done = len(hc) >= n or code not in (L.SAFE_REST, L.SAFE_MOVING, L.SAFE_NO_UPLIFT)
            if done or t_end >= max_duration:
                break
            t_end = min(2.0 * t_end, max_duration)
        hc = hc.iloc[:n]
        d = hc["duration"].to_numpy(float)
        if return_peaks:
            return d, np.abs(hc["peak_angle"].to_numpy(float))
        return d

    predictor.model = model
    return predictor


two_spring_predictor = make_predictor("two-spring")
two_spring_predictor.__doc__ = ("Default two-spring predictor for fit_free_rocking: "
                                "make_predictor('two-spring') (see there for the parameters).")
switching_predictor = make_predictor("switching")
switching_predictor.__doc__ = ("Default switching predictor for fit_free_rocking: "
                               "make_predictor('switching') (see there for the parameters).")
register_predictor("two-spring", two_spring_predictor)
register_predictor("switching", switching_predictor)
