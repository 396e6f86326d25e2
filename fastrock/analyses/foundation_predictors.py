"""Half-cycles of foundation runs, and the foundation models' predictors for
fit_free_rocking (registered with it on import).
"""
from __future__ import annotations

import math

import numpy as np

from fastrock import _validate as V
from fastrock.model import excitation as X
from fastrock.model.bodies import RigidBlock
from fastrock.analyses.freerocking.half_cycles import half_cycles
from fastrock.analyses.freerocking.fitting import register_predictor
from fastrock.analyses.freerocking.periods import rocking_quarter_period
from fastrock.constants import G_STANDARD
from fastrock.running.outcomes import status_of
from fastrock.running.solver import make_solver
from fastrock.kernels import layout as L
from fastrock.model.foundation import SwitchingFoundation, TwoSpringFoundation, block_inertia
from fastrock.running.foundation import integrate_foundation, foundation_spec


def _dedupe(t, *cols):
    """Keep the last of the rows that share a time (the state after a transition)."""
    keep = np.ones(t.size, bool)
    keep[:-1] = t[1:] != t[:-1]
    return (t[keep],) + tuple(c[keep] for c in cols)


def foundation_half_cycles(result, definition="impact", **kw):
    """:func:`fastrock.half_cycles` of a simulated history, classified by lift-off.

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
    code, t, Y, D, _lg, _met, _cnt = integrate_foundation(spec, y0, hdr, smp, opt, np.empty(0), 20000)
    if code < 0:
        # e.g. a fit wandering to an absurdly stiff foundation: make it an invalid point
        raise ValueError(f"{foundation} release failed: {status_of(code)}")
    it = spec.state_names.index("theta")
    lift = D[:, L.D_MODE] != L.MODE_REST
    t, th, lift = _dedupe(t, Y[:, it], lift)
    return code, t, th, lift


def make_predictor(model, body=None, mass=1.0, *, inertia_ratio=0.75, g=G_STANDARD,
                   rtol=1e-10, return_peaks=False, max_duration=600.0, max_steps=300_000):
    """A ``predictor(params, n)`` for :func:`fastrock.fit_free_rocking`.

    It simulates the free release from rest at ``params["theta0"]`` and returns the durations
    [s] of the first ``n`` half-cycles (``params["definition"]``, via
    :func:`fastrock.half_cycles`; fewer if the block overturns or stops), and their
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
