"""Many single runs in one parallel call: a list of scenes, one table.

A spectrum varies one pulse over a grid; a batch runs whatever the user
lists: different bodies, excitations (pulses, records), walls, friction,
slopes and solver settings.  The scenes are grouped by the model that runs
them and each group goes through that model's parallel sweep kernel once,
so a thousand mixed cases cost a few kernel calls, not a thousand.
"""
from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from fastrock.kernels import layout as L
from fastrock.model import excitation as X
from fastrock.model.ground import as_ground
from fastrock.running import registry
from fastrock.running.outcomes import outcome_of, status_of, warn_unstable
from fastrock.running.result import (METRIC_COLUMNS, INTEGER_METRICS, flexible_metrics, flight_metrics,
                                     friction_metrics, initial_state, run_inputs)
from fastrock.running.scene import Scene
from fastrock.running.solver import make_solver
from fastrock.running.sweep import run_sweep

#: Columns of :func:`run_batch`'s table, with units.
BATCH_COLUMNS = """\
scene               the scene's name, or its position in the list when it has none
kernel              the model that ran it (a model of the registry: fastrock.running.registry)
outcome, status     as in simulate(): safe | mode1 | mode2 | leaning | slide | flight | failed,
                    and the refined status
max_rotation        max |theta|                                          [rad]
max_rotation_ratio  max_rotation / alpha                                 [-]
max_rotation_pos, max_rotation_neg  largest theta and largest -theta  [rad]
impacts, ground_impacts, wall_impacts   impact counts (ground_impacts = impacts)
time_uplift, time_overturn, time_pass_alpha, time_end   first uplift, overturning, first
                    |theta| > alpha, end of the run; NaN: never  [s]
nfev, steps, rejected_steps   right-hand-side evaluations, accepted and rejected steps
theta_end, theta_dot_end    state when the run stopped   [rad, rad/s]
side                +1 / -1: the side it overturned to (theta > 0 / < 0), 0 if it did not
max_slide, residual_slide, time_sliding, time_slide_rocking, stick_slip  with friction, as
                    in the spectrum table (these and the columns below: NaN in the rows whose
                    model has none)
lift_offs, time_unloaded  held lift-offs and their time (flexible body with friction)  [-, s]
flights, time_flight, max_jump  free flight (contact model), as in the spectrum table
max_deformation, max_deformation_ratio, energy_gains  a flexible body, as in the spectrum table
time_rocking, time_contact  time lifted off / in full contact (flexible body, foundation)  [s]
"""


def _as_scene(i, item):
    if isinstance(item, Scene):
        return item
    if isinstance(item, dict):
        try:
            return Scene(**item)
        except TypeError as exc:
            raise ValueError(f"scenes[{i}]: {exc}") from None
    raise ValueError(f"scenes[{i}] must be a fastrock.Scene or a dict of its fields, got {type(item).__name__}")


def _prepare(i, scene, early_exit):
    """Kernel inputs of one scene: (spec, y0, hdr, smp, opt)."""
    mass = registry.carried_mass(scene.body, scene.foundation, scene.mass)
    body = registry.model_body(scene.body)      # a symmetric RigidBody runs as its RigidBlock
    spec = registry.select(body, scene.wall, scene.friction, scene.foundation, mass)
    ground = as_ground(scene.ground)
    if ground is not None:
        ground.check_scene(body, friction=scene.friction, flexible=spec.flexible, foundation=scene.foundation)
        early_exit = False      # the early decisions assume level ground
    solver = make_solver(scene.solver, None, None, None)
    solver.check_model(spec.model)
    vertical = X.match_components(scene.excitation, scene.vertical)
    hdr, smp, opt, _te, _cap = run_inputs(body, scene.excitation, vertical, scene.duration, scene.t_after,
                                          None, None, solver, early_exit, ground)
    if ground is not None:
        ground.check_lift_off(body, X.channel_peak(hdr, smp), spec.name, vertical)
    if scene.foundation is not None:
        from fastrock.model.foundation import block_inertia
        from fastrock.running.foundation import check_wall_start, with_slide
        y0 = check_wall_start(spec, with_slide(spec, scene.foundation.initial_state(
            block_inertia(body, mass), scene.theta0, scene.dtheta0, ground)), scene.wall)
    else:
        y0 = initial_state(spec, body, scene.theta0, scene.dtheta0, scene.wall, ground)
    return spec, y0, hdr, smp, opt, solver


def run_batch(scenes, *, early_exit=True, chunk_size=None, progress=True):
    """Run a list of single scenes in parallel and return one table.

    Parameters
    ----------
    scenes : sequence of Scene or dict
        Each a :class:`fastrock.Scene` (body, excitation, vertical, wall,
        friction, foundation, ground, solver, theta0, dtheta0, duration,
        t_after, name) or a dict of those fields.
    early_exit : bool
        Stop each run once its outcome is decided (exact, as in spectra);
        False runs every scene to its end time, as ``simulate`` does by
        default.
    chunk_size : int, optional
        Runs per kernel call inside a group (progress and Ctrl-C granularity).
    progress : bool
        Show progress.

    Returns
    -------
    DataFrame
        One row per scene, in the order given; columns in ``BATCH_COLUMNS``.
        Each row equals ``scene.run(early_exit=early_exit)``'s outcome,
        status and metrics.  After Ctrl-C the rows that finished
        (``df.attrs["interrupted"]``).

    Examples
    --------
    >>> import fastrock as fr
    >>> blk = fr.RigidBlock(alpha=0.25, p=2.0)
    >>> df = fr.run_batch([fr.Scene(blk, fr.Pulse(0.05, 1.0)),
    ...                    fr.Scene(blk, fr.Pulse(0.5, 0.3), friction=fr.Friction(0.5))], progress=False)
    >>> df["outcome"].tolist()
    ['safe', 'mode2']
    """
    from fastrock import _validate as V
    early_exit = V.boolean("early_exit", early_exit)
    scenes = [_as_scene(i, s) for i, s in enumerate(scenes)]
    if not scenes:
        raise ValueError("scenes is empty")
    prepared = []
    for i, scene in enumerate(scenes):
        try:
            prepared.append(_prepare(i, scene, early_exit))
        except ValueError as exc:
            raise ValueError(f"scenes[{i}]" + (f" ({scene.name})" if scene.name else "") + f": {exc}") from None
    groups = {}
    for i, (spec, *_rest) in enumerate(prepared):
        groups.setdefault(spec.name, []).append(i)
    n = len(scenes)
    status = np.full(n, L.RUNNING, np.int64)
    MET = np.full((n, L.N_MET), np.nan)
    theta_end = np.full(n, np.nan)
    theta_dot_end = np.full(n, np.nan)
    finished = np.zeros(n, bool)
    interrupted = False
    for name, rows in groups.items():
        spec = prepared[rows[0]][0]
        PAR = np.array([prepared[i][0].par for i in rows])
        Y0 = np.array([prepared[i][1] for i in rows])
        OPT = np.array([prepared[i][4] for i in rows])
        HDR = np.array([prepared[i][2] for i in rows])
        parts, offset = [], 0
        for j, i in enumerate(rows):
            smp = prepared[i][3]
            for c in (L.H_CHANNEL, L.V_CHANNEL):
                if int(HDR[j, c + L.X_KIND]) == L.EXC_SAMPLED:
                    HDR[j, c + L.X_OFFSET] += offset
            parts.append(smp)
            offset += smp.size
        smp = np.concatenate(parts)
        try:
            st, met, yf, done = run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, chunk_size, progress,
                                          label=f"{name} runs", model=name, reraise_when_complete=True)
        except KeyboardInterrupt:
            st, met, yf, done = None, None, None, 0
            interrupted = True
        if done:
            idx = np.asarray(rows[:done])
            status[idx] = st[:done]
            MET[idx] = met[:done]
            theta_end[idx] = yf[:done, spec.theta_index]
            theta_dot_end[idx] = yf[:done, spec.theta_index + 1]
            finished[idx] = True
        if done < len(rows):
            interrupted = True
        if interrupted:
            break
    if interrupted:
        warnings.warn(f"interrupted: returning the {int(finished.sum())} of {n} scenes that finished",
                      stacklevel=2)
    return _table(scenes, prepared, status, MET, theta_end, theta_dot_end, finished, interrupted)


def _table(scenes, prepared, status, MET, theta_end, theta_dot_end, finished, interrupted):
    keep = np.flatnonzero(finished)
    rows = []
    for i in keep:
        scene, spec, solver = scenes[i], prepared[i][0], prepared[i][5]
        met = MET[i]
        row = {"scene": scene.name or i, "kernel": spec.name, "outcome": outcome_of(status[i]),
               "status": status_of(status[i])}
        for k, j in METRIC_COLUMNS.items():
            row[k] = float(met[j])
        for k in INTEGER_METRICS:
            row[k] = int(np.nan_to_num(row[k]))
        row["max_rotation_ratio"] = row["max_rotation"] / scene.body.alpha
        row["ground_impacts"] = row["impacts"]
        if spec.flexible:
            row.update({k: v[0].item() for k, v in flexible_metrics(met[None, :], scene.body).items()})
        if spec.friction:
            row.update({k: v[0].item() for k, v in friction_metrics(met[None, :], spec.flexible).items()})
            if (row["outcome"] == "safe" and scene.friction is not None
                    and abs(row["residual_slide"]) > scene.friction.slide_tolerance):
                row["outcome"] = "slide"
        if spec.model.flight or spec.name == "contact":
            row.update({k: v[0].item() for k, v in flight_metrics(met[None, :]).items()})
        if scene.foundation is not None:
            row["time_rocking"] = float(met[L.M_T_ROCK])
            row["time_contact"] = float(met[L.M_T_CONTACT])
        row["theta_end"] = theta_end[i]
        row["theta_dot_end"] = theta_dot_end[i]
        over = status[i] in (L.OVERTURN_MODE1, L.OVERTURN_MODE2)
        row["side"] = int(np.sign(theta_end[i])) if over else 0
        rows.append(row)
        if solver.dt:
            warn_unstable(status[i:i + 1], MET[i:i + 1], solver.dt)
    df = pd.DataFrame(rows)
    df.attrs.update(interrupted=bool(interrupted))
    return df
