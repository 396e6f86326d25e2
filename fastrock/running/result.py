"""The result of a single run (SimulationResult) and the pieces of a run shared by
simulate and simulate_foundation: kernel inputs, metrics, events, ground motion.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.model import excitation as X
from fastrock.running.outcomes import EVENT_NAMES
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import C_LOG_DROPPED


class _BuiltOnFirstUse:
    """A field that may be given as a zero-argument function: the table is built from the
    kernel's arrays the first time it is read (a run whose history nobody reads pays nothing
    for its DataFrames)."""

    def __set_name__(self, owner, name):
        self.slot = "_" + name

    def __get__(self, obj, objtype=None):
        if obj is None:
            raise AttributeError(self.slot[1:])      # no class-level default (dataclass fields)
        value = obj.__dict__[self.slot]
        if callable(value):
            value = value()
            obj.__dict__[self.slot] = value
        return value

    def __set__(self, obj, value):
        obj.__dict__[self.slot] = value


#: Figure makers by name, filled by fastrock.plotting on import (fastrock's __init__ imports
#: it): running sits below plotting and must not import it.
PLOTTERS = {}

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
#: What the metrics that are not spectrum columns (SPECTRUM_COLUMNS) mean, with units.
METRIC_DESCRIPTIONS = """\
max_rotation_pos    largest theta, toward +x (rocking on the right pivot); 0 if never   [rad]
max_rotation_neg    largest -theta, toward -x (rocking on the left pivot); 0 if never   [rad]
time_pass_alpha     first time |theta| exceeded alpha (of the pivot it rocks on): the centre of
                    mass beyond the pivot; NaN if never                                 [s]
steps               accepted integrator steps
rejected_steps      integrator steps rejected by the error control and retried smaller
"""


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
        Refined status, e.g. "safe:rest" (see fastrock.running.outcomes).
    metrics : dict
        ``max |theta|`` (``max_rotation`` [rad], ``max_rotation_ratio``), impacts,
        times of uplift / overturning [s], nfev, steps ...
    kernel : str
        Name of the compiled kernel that ran.
    ground : Ground or None
        The sloping ground of the run (None: level).
    """

    history: pd.DataFrame = _BuiltOnFirstUse()
    events: pd.DataFrame = _BuiltOnFirstUse()
    outcome: str
    status: str
    status_code: int
    metrics: dict
    kernel: str
    body: object
    excitation: object = None
    effects: tuple = field(default_factory=tuple)
    vertical: object = None
    ground: object = None

    def ground_acceleration(self, t):
        """Horizontal and vertical ground acceleration [m/s^2] at times ``t`` [s], from the
        excitation itself (not from the rows the integrator happened to store)."""
        hdr, smp = X.to_header(self.body, self.excitation, self.vertical)
        return ground_at(np.atleast_1d(np.asarray(t, dtype=float)), hdr, smp)

    def plot(self, **kw):
        """The time-history figure, :func:`fastrock.plotting.plot_history` (see there)."""
        return PLOTTERS["history"](self, **kw)


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


def initial_state(spec, body, theta0, dtheta0, wall=None, ground=None):
    """The kernel's initial state of a run released at (theta0, dtheta0), checked against the
    body and the wall; on a slope a flexible column starts at its static deflection."""
    theta0 = V.finite("theta0", theta0)
    dtheta0 = V.finite("dtheta0", dtheta0)
    if abs(theta0) >= body.theta_over:
        raise ValueError(f"theta0 must satisfy |theta0| < theta_over = {body.theta_over}, got {theta0}")
    if wall is not None:
        wall.check_initial(theta0, body)
    y0 = np.zeros(spec.n_state)
    y0[spec.theta_index] = theta0
    y0[spec.theta_index + 1] = dtheta0
    if ground is not None:
        ground.initial_state(body, spec, y0)
    return y0


def run_inputs(body, excitation, vertical, duration, t_after, t_eval, history_capacity, solver,
               early_exit, ground=None):
    """Kernel inputs of one run: excitation header and samples, solver options
    (end time from ``duration`` or the excitation end + ``t_after``), output
    times and the history capacity."""
    early_exit = V.boolean("early_exit", early_exit)
    if history_capacity is not None:
        history_capacity = V.integer("history_capacity", history_capacity, 1, MAX_HISTORY)
    hdr, smp = X.to_header(body, excitation, vertical, ground)      # checks the excitations first
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


def ground_at(t, hdr, smp):
    """Horizontal and vertical ground acceleration [m/s^2] at times ``t`` [s], from a kernel
    header and its samples."""
    from fastrock.kernels.excitation import ground
    ag = np.empty(t.size)
    av = np.empty(t.size)
    for i, ti in enumerate(t):
        ag[i], av[i] = ground(ti, hdr, smp)
    return ag, av
