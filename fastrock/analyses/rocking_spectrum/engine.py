"""Rocking spectrum engine: the sweep of blocks under records, one row per run.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.running import registry
from fastrock.model.bodies import RigidBlock
from fastrock.running.outcomes import outcome_of, status_of, warn_unstable
from fastrock.running.solver import DEFAULT_T_AFTER, make_solver
from fastrock.running.sweep import run_sweep
from fastrock.kernels import layout as L
from fastrock.analyses.rocking_spectrum.inputs import (as_walls, check_record_options,
    check_run_length, grid_values, check_stable_outcomes, gap_of_wall, label_of_wall, load_records,
    shape_family)


#: Mennitti et al.'s grid: 20 slenderness values b/h in [0.1, 0.5] ...
DEFAULT_SLENDERNESS = np.linspace(0.1, 0.5, 20)

#: ... times 20 half-widths b [m] in [0.1, 1].
DEFAULT_HALF_WIDTHS = np.linspace(0.1, 1.0, 20)

#: Outcomes that count as "stable".
STABLE_OUTCOMES = ("safe",)

#: Free rocking after the end of the record [s]; with early_exit most runs
#: stop sooner (free-rocking energy below the overturning barrier).
T_AFTER = DEFAULT_T_AFTER

RUN_COLUMNS = """\
record, wall, wall_gap [m], pga_g [-], mean_period [s], b [m], slenderness b/h [-],
h [m], alpha [rad], p [rad/s], e [-] (with a shape: b is the mean half base width,
slenderness tan(alpha) of the slenderer side, h = b / slenderness, alpha, p of that
side, e the restitution e12), outcome, status, stable (bool),
max_rotation_ratio max|theta|/alpha [-], impacts, wall_impacts, time_uplift [s],
time_overturn [s], time_end [s], nfev, steps, rejected_steps
"""


# ------------------------------------------------------------------ engine
def _sweep_arrays(records, rec_idx, specs, solver, t_after, early_exit, progress, chunk_size, ground=None):
    """Kernel calls for rows with prepared KernelSpecs: one sweep per kernel,
    the records' samples concatenated in one array and each row's header
    pointing at its record.  Returns (status, MET, YF, interrupted)."""
    n = rec_idx.size
    smp = np.concatenate([np.asarray(r.acc, float) for r in records])
    offsets = np.concatenate([[0], np.cumsum([r.npts for r in records])[:-1]])
    status = np.full(n, L.RUNNING, np.int64)
    MET = np.full((n, L.N_MET), np.nan)
    YF = np.full((n, 2), np.nan)
    names = np.array([sp.name for sp in specs])
    interrupted = False
    for kname in dict.fromkeys(names):
        rows = np.flatnonzero(names == kname)
        # interleave the rows so that every chunk and thread mixes long and
        # short records (static prange scheduling) and the ETA is honest
        rows = rows[np.random.default_rng(0).permutation(rows.size)]
        m = rows.size
        PAR = np.array([specs[i].par for i in rows])
        HDR = np.zeros((m, L.N_EXC))
        HDR[:, L.X_KIND] = L.EXC_SAMPLED
        HDR[:, L.X_AMP] = 1.0
        HDR[:, L.X_SIGN] = 1.0
        ri = rec_idx[rows]
        HDR[:, L.X_DT] = [records[k].dt for k in ri]
        HDR[:, L.X_N] = [records[k].npts for k in ri]
        HDR[:, L.X_DUR] = [records[k].duration for k in ri]
        HDR[:, L.X_OFFSET] = offsets[ri]
        if ground is not None:
            ground.fill_header(HDR[0], specs[rows[0]].par[L.P_G])
            HDR[:, L.S_BLOCK:] = HDR[0, L.S_BLOCK:]
        OPT = np.tile(solver.options(0.0, early_exit), (m, 1))
        OPT[:, L.O_T_END] = HDR[:, L.X_DUR] + t_after
        Y0 = np.zeros((m, specs[rows[0]].n_state))
        st, met, yf, done = run_sweep(specs[rows[0]].sweep, Y0, PAR, HDR, smp, OPT, chunk_size,
                                      progress, label=f"runs ({kname})", model=kname)
        status[rows[:done]] = st[:done]
        MET[rows[:done]] = met[:done]
        YF[rows[:done]] = yf[:done, :2]
        if done < m:
            interrupted = True
            break
    return status, MET, YF, interrupted


def rows_sweep(records, rec_idx, b, s, wall_idx, walls, *, e, solver, t_after, early_exit,
                progress, chunk_size, ground=None, shape=None):
    """Run rows (record index, half-width, slenderness, wall index), grouped
    so that each kernel runs once; returns the per-run DataFrame.  On a
    sloping ``ground`` the closed-form early decisions are off.  ``shape``:
    a body factory ``shape(b, s)`` (:func:`shape_family`) instead of the
    rectangles."""
    if ground is not None:
        early_exit = False
    n = rec_idx.size
    h = b / s
    alpha = np.arctan2(b, h)
    pvals = np.empty(n)
    evals = np.empty(n)
    bodies = {}
    specs = []
    for i in range(n):
        key = (b[i], s[i])
        body = bodies.get(key)
        if body is None:
            body = bodies[key] = (RigidBlock.rectangle(b[i], h[i], e=e) if shape is None else shape(b[i], s[i]))
            if ground is not None:
                ground.check_scene(body)
                for k in set(rec_idx.tolist()):
                    ground.check_lift_off(body, records[k].pga)
        specs.append(registry.select(body, walls[wall_idx[i]]))
        solver.check_model(specs[-1].model)
        pvals[i] = body.p
        evals[i] = body.e if shape is None else body.e12
        if shape is not None:
            alpha[i] = body.alpha
    args = (records, rec_idx, specs, solver, t_after)
    status, MET, YF, interrupted = _sweep_arrays(*args, early_exit, progress, chunk_size, ground)
    if early_exit:
        # Defensive check: an early "safe:bounded" decision must leave the
        # block inside its potential well (|theta| < alpha).  The kernel
        # checks this since commit 4e2366c (before, its energy test alone
        # declared blocks past alpha safe); should it ever not, such rows are
        # rerun to the end here.
        bad = np.flatnonzero((status == L.SAFE_BOUNDED) & (np.abs(YF[:, 0]) >= alpha))
        if bad.size:
            sub = (records, rec_idx[bad], [specs[i] for i in bad], solver, t_after)
            st2, met2, _yf, _ = _sweep_arrays(*sub, False, False, chunk_size, ground)
            status[bad] = st2
            MET[bad] = met2
    finished = status != L.RUNNING
    if solver.dt:
        warn_unstable(status[finished], MET[finished], solver.dt)
    outcome = np.array([outcome_of(c) if f else "unfinished" for c, f in zip(status, finished)],
                       dtype=object)
    df = pd.DataFrame({
        "record": [records[k].name for k in rec_idx],
        "wall": [label_of_wall(walls[k]) for k in wall_idx],
        "wall_gap": [gap_of_wall(walls[k]) for k in wall_idx],
        "pga_g": np.array([r.pga_g for r in records])[rec_idx],
        "mean_period": np.array([r.mean_period for r in records])[rec_idx],
        "b": b, "slenderness": s, "h": h, "alpha": alpha, "p": pvals, "e": evals,
        "outcome": outcome,
        "status": [status_of(c) if f else "unfinished" for c, f in zip(status, finished)],
        "max_rotation_ratio": MET[:, L.M_MAX_ABS_THETA] / alpha,
        "impacts": MET[:, L.M_IMPACTS], "wall_impacts": MET[:, L.M_WALL_IMPACTS],
        "time_uplift": MET[:, L.M_T_UPLIFT], "time_overturn": MET[:, L.M_T_OVER],
        "time_end": MET[:, L.M_T_FINAL], "nfev": MET[:, L.M_NFEV],
        "steps": MET[:, L.M_NSTEPS], "rejected_steps": MET[:, L.M_NREJECT],
    })
    df.attrs["interrupted"] = interrupted
    return df


def spectrum_solver(solver, rtol, atol, dt, record_breakpoints=None):
    """The Solver of the spectrum's runs (make_solver, with record_breakpoints when given)."""
    kw = {} if record_breakpoints is None else {"record_breakpoints": record_breakpoints}
    return make_solver(solver, rtol, atol, dt, **kw)


def rocking_spectrum_runs(records, slenderness=None, half_widths=None, walls=None, *, e=None,
                          unit=None, solver=None, rtol=None, atol=None, dt=None,
                          record_breakpoints=None, t_after=T_AFTER, early_exit=True,
                          stable_outcomes=STABLE_OUTCOMES, progress=True, chunk_size=None, ground=None,
                          shape=None):
    """Every run of the rocking-spectrum study, one row per record x wall x
    size x slenderness (columns in ``RUN_COLUMNS``).  Arguments as in
    :func:`rocking_spectrum`."""
    check_record_options(unit, None)
    records = load_records(records, unit)
    s_grid = grid_values(slenderness, "slenderness", DEFAULT_SLENDERNESS)
    b_grid = grid_values(half_widths, "half_widths", DEFAULT_HALF_WIDTHS)
    walls = as_walls(walls)
    solver = spectrum_solver(solver, rtol, atol, dt, record_breakpoints)
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    if e is not None:
        e = V.in_closed("e", e, 0.0, 1.0)
    stable_outcomes = check_stable_outcomes(stable_outcomes)
    early_exit = V.boolean("early_exit", early_exit)
    if chunk_size is not None:
        chunk_size = V.integer("chunk_size", chunk_size, 1)
    check_run_length(records, solver, t_after)
    from fastrock.model.ground import as_ground
    ground = as_ground(ground)
    family = None if shape is None else shape_family(shape, e)
    R, W, B, S = np.meshgrid(np.arange(len(records)), np.arange(len(walls)), b_grid, s_grid,
                             indexing="ij")
    df = rows_sweep(records, R.ravel(), B.ravel(), S.ravel(), W.ravel(), walls, e=e,
                     solver=solver, t_after=t_after, early_exit=early_exit, progress=progress,
                     chunk_size=chunk_size, ground=ground, shape=family)
    df.insert(df.columns.get_loc("outcome") + 2, "stable", df["outcome"].isin(stable_outcomes))
    df.attrs.update(solver=solver.name, t_after=t_after, early_exit=early_exit,
                    stable_outcomes=tuple(stable_outcomes),
                    walls=[label_of_wall(w) for w in walls],
                    slope=ground.slope if ground is not None else 0.0, shape=shape is not None)
    return df


