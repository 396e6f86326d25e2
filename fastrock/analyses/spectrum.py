"""Overturning spectra under pulses (grid of amplitude x frequency x sign)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.model import excitation as X
from fastrock.model.friction import Friction
from fastrock.model.ground import as_ground
from fastrock.model.rigid_body import RigidBody
from fastrock.running import registry
from fastrock.running.outcomes import STATUS, outcome_of, status_of, warn_unstable
from fastrock.running.solver import DEFAULT_T_AFTER, make_solver
from fastrock.running.sweep import run_chunks
from fastrock.kernels import layout as L

SPECTRUM_COLUMNS = """\
amplitude_ratio     a_p / (g tan alpha)                      [-]
frequency_ratio     omega_p / p                              [-]
sign                pulse sign (+1: ground first accelerates toward +x)
amplitude           a_p                                      [m/s^2]
amplitude_g         a_p / g                                  [-]
frequency_hz        f_p = omega_p / (2 pi)                   [Hz]
outcome             safe | slide | mode1 | mode2 | leaning | flight | failed (categorical)
status              refined status (e.g. safe:rest, safe:bounded) (categorical)
max_rotation_ratio  max |theta| / alpha                      [-]
side                the side the body overturned to: +1 (theta > 0, onto the right pivot), -1, 0 if
                    it did not overturn
max_rotation        max |theta|                              [rad]
impacts             ground impacts (up to the decision when early_exit)
ground_impacts      same as impacts
wall_impacts        wall impacts (0 without a wall)
max_rotation_toward_wall, max_rotation_away_from_wall  [rad] (with a wall)
toward_wall         True if the pulse first throws the block toward the wall
time_uplift         first uplift                             [s]
time_overturn       overturning time (NaN if safe)           [s]
time_end            time at which the run stopped            [s]
theta_end, theta_dot_end  state when the run stopped          [rad, rad/s]
nfev                right-hand-side evaluations
max_slide, residual_slide  max |d| and final d (with friction)  [m]
time_sliding, time_slide_rocking, stick_slip  (with friction)
time_rocking, time_contact  time lifted off / in full contact (flexible body, foundation)  [s]
flights, time_flight, max_jump  free flights, time in flight [s] and the largest rise of the
                    centre of mass above its rest height [m] (contact model: wall and
                    friction, or Friction(lift_off="flight"))
max_deformation     max |u|, the column's deflection (flexible body)  [m]
max_deformation_ratio  max |u| / the deflection at uplift (flexible body)  [-]
energy_gains        pivot-switch impacts that would have raised the kinetic energy and took the
                    full-contact map instead (flexible body)
lift_offs, time_unloaded  held lift-offs and their time (flexible body with friction)  [-, s]
boundary            outcome changes when the tolerance is halved (boundary_check=True)
"""


#: Largest grid of one call (runs): its arrays take about 1 kB per run.
MAX_GRID_RUNS = 10_000_000

#: Compact columns (a 1000 x 1000 grid is a million rows): outcome and status are categoricals of
#: these labels (one byte per row; every table holds all of them, so that the outcomes of two
#: tables compare cell by cell; ``value_counts()`` lists the unused ones with 0), the pulse sign
#: and the overturning side int8, the impact counts int32. Every value is exact.
CATEGORIES = {"outcome": ("safe", "slide", "mode1", "mode2", "leaning", "flight", "failed"),
              "status": tuple(dict.fromkeys(STATUS.values()))}
COMPACT_INTEGERS = {"sign": np.int8, "side": np.int8, "impacts": np.int32, "ground_impacts": np.int32,
                    "wall_impacts": np.int32}


def _codes(name, values):
    """Category codes (int8) of a text column, refusing a label outside CATEGORIES."""
    cat = pd.Categorical(values, categories=CATEGORIES[name])
    if (cat.codes < 0).any():
        bad = sorted(set(np.asarray(values, object)[cat.codes < 0].tolist()))
        raise AssertionError(f"{name}: labels {bad} are not in CATEGORIES")
    return cat.codes.astype(np.int8)


def _label_codes(name, status, label_of):
    """Category codes (int8) of each run's label (``label_of``: outcome_of or status_of), the
    label found once per distinct status code: no Python string per row of a big grid."""
    distinct, inverse = np.unique(np.asarray(status, np.int64), return_inverse=True)
    return _codes(name, [label_of(c) for c in distinct])[inverse.ravel()]


def compact_table(df, codes=None):
    """The spectrum table with its compact columns (CATEGORIES, COMPACT_INTEGERS); ``codes``:
    category codes already computed, by column name."""
    codes = codes or {}
    for name, cats in CATEGORIES.items():
        if name in codes:
            df[name] = pd.Categorical.from_codes(codes[name], categories=cats)
        elif name in df and not isinstance(df[name].dtype, pd.CategoricalDtype):
            df[name] = pd.Categorical.from_codes(_codes(name, df[name].to_numpy(object)), categories=cats)
    for name, dtype in COMPACT_INTEGERS.items():
        if name in df:
            df[name] = df[name].to_numpy().astype(dtype)
    return df


def _grid(values, name):
    if isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be an array of numbers, got the string {values!r}")
    a = np.atleast_1d(V.finite_array(name, np.atleast_1d(values)))
    if a.size == 0:
        raise ValueError(f"{name} is empty")
    if (a < 0).any():
        raise ValueError(f"{name} must be >= 0")
    for v in a:
        V.finite(name, v)   # magnitude and denormal checks
    return a


def _signs(sign):
    if isinstance(sign, str):
        if sign != "both":
            raise ValueError(f"sign must be +1, -1, 'both' or a list, got {sign!r}")
        return [1, -1]
    if np.ndim(sign) == 0:
        return [V.sign("sign", sign)]
    out = [V.sign("sign", s) for s in sign]
    if not out:
        raise ValueError("sign is empty; give +1, -1, 'both' or a list of them")
    return out


def overturning_spectrum(body, amplitude_ratios, frequency_ratios, sign=+1, *, pulse="one-sine",
                         wall=None, friction=None, foundation=None, ground=None, mass=None, vertical=None,
                         solver=None,
                         rtol=None, atol=None, dt=None, t_after=DEFAULT_T_AFTER,
                         early_exit=True, chunk_size=None, progress=True, boundary_check=False,
                         amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p", kind=None, out=None,
                         columns=None):
    """Overturning spectrum of a body under pulses, in parallel.

    Parameters
    ----------
    body : RigidBlock, RigidBody or FlexibleBody
        An asymmetric :class:`RigidBody` runs the two-sided rocking model with
        each side's alpha and p; the ratios (a_p / (g tan alpha), omega_p / p,
        max_rotation_ratio) then refer to its smaller side (the smaller alpha,
        ``RigidBody.alpha``), and ``df.attrs`` holds both sides (alpha1,
        alpha2, p1, p2, e12, e21, ratio_side).  A symmetric RigidBody runs as
        its RigidBlock.
    amplitude_ratios : array
        a_p / (g tan alpha) values, or amplitudes in ``amplitude_unit``.
    frequency_ratios : array
        omega_p / p values (> 0), or frequencies in ``frequency_unit``.
    sign : +1, -1, "both" or list
        Pulse sign(s); a_g = sign * a_p * sin(omega_p t).
    pulse : str
        "one-sine" (default), "half-sine", "one-cosine"; ``kind`` is the same option under
        the name :class:`Pulse` gives it (give one of them).
    amplitude_unit, frequency_unit : str
        Units of the two axes, as in :class:`Pulse`: "g_tan_alpha" (default), "g" or
        "m/s2"; "omega_p/p" (default), "Hz" or "rad/s".  The table always holds both the
        ratios and the physical values (amplitude_g, frequency_hz).
    wall : Wall, optional
    friction : Friction, optional
        Adds the outcome "slide" and the columns max_slide, residual_slide [m]
        (with a TwoSpringFoundation too: the base slides on the corner springs).
    foundation : TwoSpringFoundation, SwitchingFoundation or LinearVibration, optional
        The block stands on a flexible foundation instead of rigid ground
        (``body`` a RigidBlock with b and h); every run starts at rest in
        static equilibrium on it.  Adds the columns time_rocking and
        time_contact [s].
    ground : Ground, optional
        Sloping ground, the same in every run; None: level ground.  The
        ratios keep their level-ground meaning (a_p / (g tan alpha)); sign
        +1 pulses start toward +x, downhill.
    mass : float, optional
        Block mass [kg] with ``foundation`` (the foundation's stiffnesses
        are absolute): a RigidBody carries its own mass (a different
        ``mass`` is refused), a RigidBlock 1 kg unless given.
    vertical : Pulse, SampledMotion or GroundMotion, optional
        Vertical ground acceleration, the same in every run (effective
        gravity G = g + a_v); each run lasts until both excitations end,
        plus ``t_after``.
    early_exit : bool
        Stop a run once its outcome is decided (exact; docs: guide/outcomes).
    progress : bool
        Progress bar on stderr for long sweeps.  Ctrl-C returns the finished
        rows (``df.attrs["interrupted"]`` is True).
    out : str or Path, optional
        A folder to stream the table to, chunk by chunk, as Parquet files
        (``part-*.parquet``, each with the grid's ``row`` ids, and
        ``spectrum.json`` describing the call): for grids whose table does
        not fit in memory.  Calling again with the same arguments and
        ``out`` resumes: only the rows no file holds yet are run.  Returns
        the folder; :func:`load_spectrum` reads it back as one table.
    columns : list of str, optional
        The result columns to keep, by name (``SPECTRUM_COLUMNS``); the grid
        columns amplitude_ratio, frequency_ratio and sign are always kept,
        and the table keeps its column order.  None (default): every column.
        For big grids: a million-row table takes 114 MB with every column of
        the rigid block, 26 MB with ``columns=["outcome", "max_rotation_ratio"]``;
        the values are the same.
    boundary_check : bool
        Run the grid a second time with the tolerance (or the fixed step)
        halved and add the column ``boundary``: True where the outcome
        changes, i.e. the cell sits on an outcome boundary closer than the
        integration error can resolve (about twice the cost).

    Returns
    -------
    DataFrame, one row per run; columns in ``SPECTRUM_COLUMNS``.

    Examples
    --------
    >>> from fastrock import RigidBlock, overturning_spectrum
    >>> block = RigidBlock.rectangle(b=0.2, h=0.8)
    >>> df = overturning_spectrum(block, [1.0, 3.0, 6.0], [1.0, 4.0], progress=False)
    >>> list(df.outcome)        # a_p/(g tan alpha) 1, 3, 6 at omega_p/p = 1, then at 4
    ['safe', 'mode2', 'mode2', 'safe', 'mode1', 'mode2']
    """
    mass = registry.carried_mass(body, foundation, mass)
    body = registry.model_body(body)
    solver = make_solver(solver, rtol, atol, dt)
    if kind is not None:
        if pulse != "one-sine" and pulse != kind:
            raise ValueError(f"give the pulse shape once: kind={kind!r} and pulse={pulse!r}")
        pulse = kind
    V.choice("pulse", pulse, ("one-sine", "half-sine", "one-cosine"))
    V.choice("amplitude_unit", amplitude_unit, X.AMPLITUDE_UNITS)
    V.choice("frequency_unit", frequency_unit, X.FREQUENCY_UNITS)
    early_exit = V.boolean("early_exit", early_exit)
    boundary_check = V.boolean("boundary_check", boundary_check)
    if chunk_size is not None:
        chunk_size = V.integer("chunk_size", chunk_size, 1)
    amps = _grid(amplitude_ratios, "amplitude_ratios")
    freqs = _grid(frequency_ratios, "frequency_ratios")
    if (freqs <= 0).any():
        raise ValueError("frequency_ratios must be > 0")
    amps, freqs = _to_ratios(body, amps, freqs, amplitude_unit, frequency_unit)
    spec = registry.select(body, wall, friction, foundation, None if mass is None else V.positive("mass", mass))
    solver.check_model(spec.model)
    ground = as_ground(ground)
    if ground is not None:
        ground.check_scene(body, friction=friction, flexible=spec.flexible, foundation=foundation)
        early_exit = False      # the early decisions assume level ground
    vertical = X.as_excitation(vertical, "vertical")
    signs = _signs(sign)
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    n = len(signs) * freqs.size * amps.size
    if n > MAX_GRID_RUNS:
        raise ValueError(f"amplitude_ratios x frequency_ratios x sign: {amps.size} x {freqs.size} x "
                         f"{len(signs)} = {n:,} runs, more than {MAX_GRID_RUNS:,} in one call; split the grid")
    V.acceleration("amplitude_ratios", amps.max() * body.g * np.tan(body.alpha), body.g,
                   "the largest pulse amplitude a_p = amplitude_ratio g tan(alpha)")
    t_longest = V.run_time("frequency_ratios", (np.pi if pulse == "half-sine" else 2 * np.pi) /
                           (freqs.min() * body.p), "the longest pulse")
    kind = X.PULSE_KINDS[pulse]
    sign_values = np.array(signs, float)
    half_turns = np.pi if pulse == "half-sine" else 2 * np.pi

    # A row's grid values from its id, row = (sign * n_freq + freq) * n_amp + amp: a 1000 x 1000
    # grid never holds its six full-grid input arrays (48 MB) beside the table's columns.
    def grid(rows):
        i = np.arange(rows.start, rows.stop) if isinstance(rows, slice) else rows
        A = amps[i % amps.size]
        F = freqs[i // amps.size % freqs.size]
        S = sign_values[i // (amps.size * freqs.size)]
        omega = F * body.p
        return S, F, A, omega, A * body.g * np.tan(body.alpha), half_turns / omega
    hdr0 = np.zeros(L.N_EXC)            # what every run shares: the vertical and slope blocks
    smp = np.zeros(1)
    t_vertical = 0.0
    if vertical is not None:
        vhdr, smp = X.to_header(body, None, vertical)
        hdr0[L.V_CHANNEL:] = vhdr[L.V_CHANNEL:]
        t_vertical = X.end_time(body, None, vertical)
    if ground is not None:
        ground.fill_header(hdr0, body.g)
        # the product rounds monotonically: the largest ratio gives the largest amplitude
        ground.check_lift_off(body, float(amps.max() * body.g * np.tan(body.alpha)), spec.name, vertical)
    solver.check_fixed_steps(V.run_time("t_after", max(t_longest, t_vertical) + t_after,
                                        "the longest run (pulse plus t_after)"), "the longest run")
    opt = solver.options(0.0, early_exit)
    if foundation is not None:
        from fastrock.model.foundation import block_inertia
        from fastrock.running.foundation import check_wall_start, with_slide
        y0 = check_wall_start(spec, with_slide(spec, foundation.initial_state(block_inertia(body, mass), 0.0, 0.0,
                                                                              ground)), wall)
    else:
        y0 = np.zeros(spec.n_state)
        if ground is not None:
            ground.initial_state(body, spec, y0)      # a flexible column at its static deflection

    # Inputs and results one chunk at a time: a 1000 x 1000 grid never holds
    # the kernels' inputs or their full metric rows (N_MET floats per run).
    def inputs(start, stop):
        return inputs_at(slice(start, stop), stop - start)

    def inputs_at(sl, m):
        S, _, _, omega, amp, dur = grid(sl)
        HDR = np.tile(hdr0, (m, 1))
        HDR[:, L.X_KIND] = kind
        HDR[:, L.X_AMP] = amp
        HDR[:, L.X_OMEGA] = omega
        HDR[:, L.X_SIGN] = S
        HDR[:, L.X_DUR] = dur
        OPT = np.tile(opt, (m, 1))
        OPT[:, L.O_T_END] = np.maximum(dur, t_vertical) + t_after
        return np.tile(y0, (m, 1)), np.tile(spec.par, (m, 1)), HDR, OPT

    columns_asked, columns = columns, {}
    unstable = []
    keep = None         # the columns asked for, in table order (None: all)

    def table(sl, st, met, yf):
        S, F, A, omega, amp, _ = grid(sl)
        part = pd.DataFrame({
            "amplitude_ratio": A, "frequency_ratio": F, "sign": S.astype(int),
            "amplitude": amp, "amplitude_g": amp / body.g, "frequency_hz": omega / (2 * np.pi),
        })
        # a model with a slip state and no friction= (an asymmetric body beside a wall): never slips
        part = _add_results(part, st, met, body, wall,
                            (friction or Friction.never_slipping()) if spec.friction else None)
        if spec.model.flight or spec.name == "contact":
            from fastrock.running.result import flight_metrics
            for k, v in flight_metrics(met).items():
                part[k] = v
        if foundation is not None:
            part["time_rocking"] = met[:, L.M_T_ROCK]
            part["time_contact"] = met[:, L.M_T_CONTACT]
        part["theta_end"] = yf[:, spec.theta_index]
        part["theta_dot_end"] = yf[:, spec.theta_index + 1]
        overturned = (st == L.OVERTURN_MODE1) | (st == L.OVERTURN_MODE2)
        part["side"] = np.where(overturned, np.sign(yf[:, spec.theta_index]), 0.0).astype(int)
        return part if keep is None else part[keep]

    def consume(start, st, met, yf):
        part = table(slice(start, start + st.size), st, met, yf)
        if not columns:
            for k in part.columns:
                dtype = (np.int8 if k in CATEGORIES else COMPACT_INTEGERS.get(k, part[k].to_numpy().dtype))
                columns[k] = np.empty(n, dtype=dtype if np.dtype(dtype).kind in "biuf" else object)
        for k in part.columns:
            columns[k][start:start + st.size] = (part[k].cat.codes.to_numpy() if k in CATEGORIES
                                                 else part[k].to_numpy())
        if solver.dt and (st == L.FAIL_UNSTABLE).any():
            bad = np.flatnonzero(st == L.FAIL_UNSTABLE)
            unstable.append((start + bad, met[bad]))

    attrs = dict(kernel=spec.name, alpha=body.alpha, p=body.p, e=body.e, pulse=pulse, solver=solver.name,
                 amplitude_unit=amplitude_unit, frequency_unit=frequency_unit,
                 slope=ground.slope if ground is not None else 0.0)
    if isinstance(body, RigidBody) and not body.is_symmetric:   # in any of its models
        attrs.update(alpha1=body.alpha1, alpha2=body.alpha2, p1=body.p1, p2=body.p2, e12=body.e12,
                     e21=body.e21, ratio_side=body.smaller_side)
    if columns_asked is not None:
        keep = _kept_columns(columns_asked, table(slice(0, 0), np.empty(0, np.int64), np.empty((0, L.N_MET)),
                                                  np.empty((0, spec.n_state))).columns, boundary_check)
    if out is not None:
        if boundary_check:
            raise ValueError("out: boundary_check does not stream to files; run it without out")
        call = dict(body=body, amplitude_ratios=amps, frequency_ratios=freqs, signs=signs, pulse=pulse,
                    wall=wall, friction=friction, foundation=foundation, ground=ground, mass=mass,
                    vertical=vertical, solver=solver, t_after=t_after, early_exit=early_exit)
        if keep is not None:
            call["columns"] = keep
        return _stream(out, call, attrs, n, spec, inputs_at, table, smp, chunk_size, progress)
    done = run_chunks(spec.sweep, n, inputs, smp, consume, chunk_size, progress, label="runs",
                      model=spec.name)
    if not columns:                   # interrupted before the first chunk finished
        empty = np.empty(0)
        df = compact_table(table(slice(0, 0), empty.astype(np.int64), np.empty((0, L.N_MET)),
                                 np.empty((0, spec.n_state))))
    else:
        # the filled columns become the table's without a copy (a million-row table is 100 MB)
        df = pd.DataFrame({k: (pd.Categorical.from_codes(v[:done], categories=CATEGORIES[k]) if k in CATEGORIES
                               else v[:done]) for k, v in columns.items()}, copy=False)
    columns.clear()
    if unstable:
        # the unstable rows' suggested steps, placed as warn_unstable reads them
        rows = np.concatenate([u[0] for u in unstable])
        status = np.full(done, L.RUNNING, np.int64)
        status[rows] = L.FAIL_UNSTABLE
        MET = np.full((done, L.N_MET), np.nan)
        MET[rows] = np.concatenate([u[1] for u in unstable])
        warn_unstable(status, MET, solver.dt)
    df.attrs.update(interrupted=done < n, **attrs)
    if boundary_check:
        import dataclasses
        half = (dataclasses.replace(solver, dt=solver.dt / 2) if solver.dt else
                dataclasses.replace(solver, rtol=solver.rtol / 2,
                                    atol=(solver.atol if solver.atol is not None else solver.rtol * 1e-2) / 2))
        df2 = overturning_spectrum(body, amplitude_ratios, frequency_ratios, sign, pulse=pulse,
                                   amplitude_unit=amplitude_unit, frequency_unit=frequency_unit, wall=wall,
                                   friction=friction, foundation=foundation, ground=ground, mass=mass,
                                   vertical=vertical, solver=half, t_after=t_after, early_exit=early_exit,
                                   chunk_size=chunk_size, progress=progress, columns=["outcome"])
        m = min(len(df), len(df2))
        df = df.iloc[:m].copy()
        df["boundary"] = df["outcome"].to_numpy() != df2["outcome"].to_numpy()[:m]
        df.attrs["interrupted"] = df.attrs["interrupted"] or df2.attrs["interrupted"]
    return df


#: Columns every table keeps (``columns=``): the grid point of each row.
GRID_COLUMNS = ("amplitude_ratio", "frequency_ratio", "sign")


def _kept_columns(asked, available, boundary_check):
    """The table's columns (in table order) for ``columns=asked``, refusing a name it has not."""
    if isinstance(asked, str):
        asked = [asked]
    try:
        asked = list(asked)
    except TypeError:
        raise ValueError(f"columns must be a list of column names, got {asked!r}") from None
    available = list(available)
    unknown = [c for c in asked if c not in available]
    if unknown:
        raise ValueError(f"columns: {unknown} are not columns of this spectrum; its columns are {available}")
    if boundary_check and "outcome" not in asked:
        raise ValueError("columns: boundary_check compares the outcomes; keep 'outcome'")
    return [c for c in available if c in GRID_COLUMNS or c in asked]


def _to_ratios(body, amps, freqs, amplitude_unit, frequency_unit):
    """Axes in the literature's ratios a_p/(g tan alpha) and omega_p/p from the given units."""
    uplift = body.g * np.tan(body.alpha)
    amps = {"g_tan_alpha": amps, "g": amps * X.G_STANDARD / uplift, "m/s2": amps / uplift}[amplitude_unit]
    freqs = {"omega_p/p": freqs, "Hz": 2 * np.pi * freqs / body.p, "rad/s": freqs / body.p}[frequency_unit]
    return amps, freqs


def _add_results(df, status, MET, body, wall=None, friction=None):
    outcome = _label_codes("outcome", status, outcome_of)
    df["outcome"] = pd.Categorical.from_codes(outcome, categories=CATEGORIES["outcome"])
    if friction is not None:
        from fastrock.running.result import friction_metrics
        for k, v in friction_metrics(MET, getattr(body, "kind", "") == "flexible").items():
            df[k] = v
        labels = CATEGORIES["outcome"]
        outcome[(outcome == labels.index("safe")) &
                (np.abs(df["residual_slide"].to_numpy()) > friction.slide_tolerance)] = labels.index("slide")
        df["outcome"] = pd.Categorical.from_codes(outcome, categories=labels)
    df["status"] = pd.Categorical.from_codes(_label_codes("status", status, status_of),
                                             categories=CATEGORIES["status"])
    df["max_rotation_ratio"] = MET[:, L.M_MAX_ABS_THETA] / body.alpha
    df["max_rotation"] = MET[:, L.M_MAX_ABS_THETA]
    df["impacts"] = np.nan_to_num(MET[:, L.M_IMPACTS]).astype(int)
    df["ground_impacts"] = df["impacts"]
    df["wall_impacts"] = np.nan_to_num(MET[:, L.M_WALL_IMPACTS]).astype(int)
    if wall is not None:
        # a positive ground acceleration tips the block toward -theta
        df["toward_wall"] = df["sign"] == -wall.side
        toward = L.M_MAX_THETA_POS if wall.side > 0 else L.M_MAX_THETA_NEG
        away = L.M_MAX_THETA_NEG if wall.side > 0 else L.M_MAX_THETA_POS
        df["max_rotation_toward_wall"] = MET[:, toward]
        df["max_rotation_away_from_wall"] = MET[:, away]
    if getattr(body, "kind", "") == "flexible":
        from fastrock.running.result import flexible_metrics
        for k, v in flexible_metrics(MET, body).items():
            df[k] = v
    df["time_uplift"] = MET[:, L.M_T_UPLIFT]
    df["time_overturn"] = MET[:, L.M_T_OVER]
    df["time_end"] = MET[:, L.M_T_FINAL]
    df["nfev"] = np.nan_to_num(MET[:, L.M_NFEV]).astype(np.int64)
    return df


def _fingerprint(obj):
    """A stable text of a call's arguments (arrays by their SHA-256), so that
    a streamed spectrum resumes only into a folder of the same call."""
    import dataclasses
    import hashlib
    if isinstance(obj, np.ndarray):
        return f"array{obj.shape}:{hashlib.sha256(np.ascontiguousarray(obj).tobytes()).hexdigest()}"
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return type(obj).__name__ + "(" + ",".join(f"{f.name}={_fingerprint(getattr(obj, f.name))}"
                                                   for f in dataclasses.fields(obj)) + ")"
    if isinstance(obj, dict):
        return "{" + ",".join(f"{k}:{_fingerprint(v)}" for k, v in sorted(obj.items())) + "}"
    if isinstance(obj, (list, tuple)):
        return "[" + ",".join(_fingerprint(v) for v in obj) + "]"
    if isinstance(obj, (float, np.floating)):
        return repr(float(obj))
    return repr(obj)


def _stream(out, call, attrs, n, spec, inputs_at, table, smp, chunk_size, progress):
    """Run the rows no Parquet part in ``out`` holds yet, writing one part per chunk."""
    import hashlib
    import json
    import os
    import uuid
    from pathlib import Path
    from fastrock.constants import VERSION
    folder = Path(out)
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"out: {folder} exists and is not a folder")
    folder.mkdir(parents=True, exist_ok=True)
    key = hashlib.sha256((VERSION + _fingerprint(call)).encode()).hexdigest()
    manifest = folder / "spectrum.json"
    if manifest.exists():
        try:
            saved = json.loads(manifest.read_text())
        except ValueError:
            raise ValueError(f"out: {manifest} is not a spectrum manifest (not valid JSON)") from None
        if saved.get("key") != key:
            raise ValueError(f"out: {folder} holds the results of another spectrum call (other arguments "
                             "or fastrock version); give a new folder")
    else:
        manifest.write_text(json.dumps({"key": key, "runs": n, "fastrock": VERSION, "attrs": attrs}, indent=1))
    done_rows = np.zeros(n, bool)
    for part in sorted(folder.glob("part-*.parquet")):
        done_rows[pd.read_parquet(part, columns=["row"])["row"].to_numpy()] = True
    rows = np.flatnonzero(~done_rows)

    def inputs(start, stop):
        return inputs_at(rows[start:stop], stop - start)

    def consume(start, st, met, yf):
        idx = rows[start:start + st.size]
        part = table(idx, st, met, yf)
        part.insert(0, "row", idx)
        tmp = folder / f".part-{uuid.uuid4().hex}.tmp"
        part.to_parquet(tmp, index=False)
        os.replace(tmp, folder / f"part-{idx[0]:010d}-{uuid.uuid4().hex[:8]}.parquet")   # whole parts only

    if rows.size:
        run_chunks(spec.sweep, rows.size, inputs, smp, consume, chunk_size, progress,
                   label="runs", model=spec.name)
    return folder


def load_spectrum(out):
    """The table a streamed :func:`overturning_spectrum` (``out=``) wrote,
    in grid order, with its ``attrs`` (``interrupted`` True while rows are
    missing; run the same call again to resume)."""
    import json
    from pathlib import Path
    folder = Path(out)
    manifest = folder / "spectrum.json"
    if not manifest.exists():
        raise ValueError(f"out: {folder} holds no streamed spectrum (no spectrum.json)")
    info = json.loads(manifest.read_text())
    parts = sorted(folder.glob("part-*.parquet"))
    if parts:
        df = pd.concat([pd.read_parquet(p) for p in parts], ignore_index=True)
        df = compact_table(df.sort_values("row", kind="stable").drop(columns="row").reset_index(drop=True))
    else:
        df = pd.DataFrame()
    df.attrs.update(info.get("attrs", {}), interrupted=len(df) < info["runs"])
    return df
