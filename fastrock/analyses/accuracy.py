"""Work-precision: what accuracy costs in time.

For each model family and excitation, runs the same cases with adaptive
tolerances (rtol 1e-3 ... 1e-12) and fixed steps (dt 1e-2 ... 1e-5 s) and
measures, against a much tighter reference (rtol 1e-13):

* ``err_max_rotation``: |max|theta|/alpha - reference| on a case that stays up;
* ``err_t_overturn``: |t_overturn - reference| [s] on a case that overturns;
* ``outcome_mismatch``: share of a spectrum grid whose outcome differs;
* ``time_per_run`` [s] (kernel time, compiled, averaged over the grid, minimum of 3 sweeps on
  ``threads`` threads, default all) and ``cpu_per_run`` [s] (CPU time of the process for the
  same sweeps).  On a shared machine prefer ``threads=1`` and the CPU time: it does not count
  the time other jobs hold the core, and one thread never spin-waits at a barrier for a
  descheduled partner (with 2 threads a small grid can show milliseconds of such waiting);
* friction only: ``err_max_slide`` and ``err_residual_slide`` [m], |max|d| - reference| and
  |d_end - reference| on the case that stays up (it slides), and the grid outcomes include
  "slide" (residual slip above the friction's ``slide_tolerance``).

Families (``FAMILIES``): the rigid block; the flexible body; the rigid block against a rear
wall (the safe case is thrown away from the wall and hits it on the way back, the grid has both
pulse signs); the rigid block with Coulomb friction (mu_s just above b/h: rocking, slide-rocking
and slip at impacts; its safe cases slide); the flexible foundation ("foundation": the
two-spring model, free release only: a block on felt released from an initial lean; its safe
case measures ``err_max_rotation`` on the first rebound peak, max|theta|/alpha after the first
zero crossing, since the release angle itself is exact, and ``err_half_cycles`` [s], the largest
error in the first ten half-cycle durations; the grid is a set of release angles); the flexible
body with friction ("flexible-friction": mu_s = 0.5, lift_off="hold"; its safe pulse case slides).

"""
from __future__ import annotations

import time

import numpy as np
import pandas as pd


RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
DTS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
REFERENCE_RTOL = 1e-13


FAMILIES = ("rigid", "flexible", "wall", "friction", "foundation", "flexible-friction")
#: families with their own excitation: the foundation runs free releases only
FREE_FAMILIES = ("foundation",)
# foundation family: release angles / alpha of the safe and overturning case and of the grid,
# run length [s], and how many half-cycle durations are compared
FOUNDATION_RELEASES = (0.5, 1.02)
FOUNDATION_GRID = tuple(np.linspace(0.2, 1.15, 16))
FOUNDATION_DURATION = 8.0
FOUNDATION_HALF_CYCLES = 10


def _family(model):
    """(body, effects) of a model family: ``effects`` are the keyword arguments of ``simulate``
    and ``registry.select`` (wall=, friction=)."""
    from fastrock.model.bodies import FlexibleBody, RigidBlock
    if model == "rigid":
        return RigidBlock(alpha=0.25, p=2.0), {}
    if model == "flexible":
        return FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05), {}
    if model == "wall":
        # Mennitti et al.'s block (alpha = 0.197, p = 1.70 rad/s) beside an elastic wall at 10 cm
        # (theta_w = 0.1 alpha), on the negative-theta side: sign +1 pulses throw it toward the wall
        from fastrock.model.wall import Wall
        return RigidBlock.rectangle(b=0.5, h=2.5), {"wall": Wall(gap=0.1)}
    if model == "friction":
        # mu_s = 0.27 just above b/h = 0.25: rocks, slide-rocks above Shenton's boundary and
        # slips at impacts; the pulse grid has safe, slide, mode-1 and mode-2 cells
        from fastrock.model.friction import Friction
        return RigidBlock.rectangle(b=0.25, h=1.0), {"friction": Friction(0.27)}
    if model == "foundation":
        # the README's block on felt: b = 0.1 m, h = 0.5 m on corner springs with rocking
        # vibration omega = 30 rad/s, zeta = 0.1 (mass 1 kg; only omega and zeta matter)
        from fastrock.model.foundation import TwoSpringFoundation
        body = RigidBlock.rectangle(b=0.1, h=0.5)
        return body, {"foundation": TwoSpringFoundation.from_vibration(body, 30.0, 0.1)}
    if model == "flexible-friction":
        # mu_s = 0.5 > tan(alpha) = 0.31: rocks, slips at impacts; lift-off held
        from fastrock.model.friction import Friction
        return (FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, base_mass_ratio=0.1),
                {"friction": Friction(0.5, lift_off="hold")})
    raise ValueError(f"model must be one of {', '.join(FAMILIES)}, got {model!r}")


# (amplitude / (g tan alpha), omega_p / p, sign) of the safe and the overturning pulse case
_PULSE_CASES = {"wall": ((2.5, 5.0, -1), (3.0, 3.0, 1))}
_DEFAULT_PULSE_CASES = ((2.5, 5.0, 1), (3.0, 3.0, 1))
_GRID_SIGNS = {"wall": (1, -1)}
# record scale factors (times g tan(alpha) / PGA) of the safe and the overturning record case;
# with friction the safe case must slide (at 1.5 the block rocks without slipping)
_RECORD_CASES = {"friction": (2.0, 6.0)}
_DEFAULT_RECORD_CASES = (1.5, 6.0)


def _cases(body, excitation, model="rigid"):
    """(safe case, overturning case, grid) for one excitation kind ("free": release angles [rad])."""
    from fastrock.model.excitation import Pulse, SampledMotion
    from fastrock.io.default_records import load_default_record
    if excitation == "free":
        return (FOUNDATION_RELEASES[0] * body.alpha, FOUNDATION_RELEASES[1] * body.alpha,
                [k * body.alpha for k in FOUNDATION_GRID])
    if excitation == "pulse":
        def pulse(a, f, sign=1):
            return Pulse(a, f, sign=sign, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        (a_s, f_s, s_s), (a_o, f_o, s_o) = _PULSE_CASES.get(model, _DEFAULT_PULSE_CASES)
        grid = [pulse(a, f, sign) for sign in _GRID_SIGNS.get(model, (1,))
                for a in np.linspace(1.2, 6.0, 8) for f in np.linspace(0.5, 8.0, 8)]
        return pulse(a_s, f_s, s_s), pulse(a_o, f_o, s_o), grid
    if excitation == "record":
        rec = load_default_record()
        scale_up = body.g * np.tan(body.alpha) / rec.pga
        k_safe, k_over = _RECORD_CASES.get(model, _DEFAULT_RECORD_CASES)
        safe = SampledMotion.from_record(rec, scale=k_safe * scale_up)
        over = SampledMotion.from_record(rec, scale=k_over * scale_up)
        grid = [SampledMotion.from_record(rec, scale=s * scale_up) for s in np.linspace(1.1, 8.0, 24)]
        return safe, over, grid
    raise ValueError(f"excitation must be 'pulse', 'record' or 'free', got {excitation!r}")


def _grid_rows(body, grid, solver, t_after, effects=None):
    """Sweep-kernel inputs for a grid of excitations sharing one sample array."""
    from fastrock.model import excitation as X
    from fastrock.running import registry
    from fastrock.kernels import layout as L
    spec = registry.select(body, **(effects or {}))
    rows = [X.to_header(body, exc) for exc in grid]
    HDR = np.array([h for h, _ in rows])
    smp = rows[0][1]
    n = len(grid)
    OPT = np.tile(solver.options(0.0, False), (n, 1))
    OPT[:, L.O_T_END] = [X.end_time(body, exc) + t_after for exc in grid]
    return spec, np.zeros((n, spec.n_state)), np.tile(spec.par, (n, 1)), HDR, smp, OPT


class _threads:
    """Run the timed sweeps on ``n`` Numba threads (None: leave the setting alone)."""

    def __init__(self, n):
        self.n = n

    def __enter__(self):
        if self.n:
            import numba
            self.old = numba.get_num_threads()
            numba.set_num_threads(min(int(self.n), numba.config.NUMBA_NUM_THREADS))

    def __exit__(self, *exc):
        if self.n:
            import numba
            numba.set_num_threads(self.old)


def _run_set(body, safe, over, grid, solver, t_after, repeats=3, effects=None, threads=None):
    from fastrock.running.outcomes import outcome_of
    from fastrock.running.simulate import simulate
    from fastrock.running.sweep import run_sweep
    from fastrock.kernels import layout as L
    effects = effects or {}
    if "foundation" in effects:
        return _run_set_foundation(body, effects["foundation"], safe, over, grid, solver, repeats, threads)
    r_safe = simulate(body, safe, solver=solver, t_after=t_after, history_capacity=10, **effects)
    r_over = simulate(body, over, solver=solver, t_after=t_after, history_capacity=10, **effects)
    spec, Y0, PAR, HDR, smp, OPT = _grid_rows(body, grid, solver, t_after, effects)
    best = best_cpu = np.inf
    with _threads(threads):
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            status, MET, _, done = run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, progress=False,
                                             reraise_when_complete=True)
            if done < len(grid):
                raise KeyboardInterrupt   # a partial grid would make a wrong error and time
            best = min(best, time.perf_counter() - t0)
            best_cpu = min(best_cpu, time.process_time() - c0)
    outcomes = [outcome_of(c) for c in status]
    out = dict(max_rotation=r_safe.metrics["max_rotation_ratio"], safe_status=r_safe.status,
               t_overturn=r_over.metrics["time_overturn"], over_status=r_over.status,
               outcomes=outcomes, time_per_run=best / len(grid), cpu_per_run=best_cpu / len(grid),
               nfev=float(np.mean(MET[:, L.M_NFEV])))
    friction = effects.get("friction")
    if spec.friction:
        # as simulate does it: a safe run that slipped by more than the tolerance is a "slide"
        res = MET[:, L.M_RESIDUAL_SLIDE]
        out["outcomes"] = ["slide" if o == "safe" and abs(d) > friction.slide_tolerance else o
                           for o, d in zip(outcomes, res)]
        out["max_slide"] = r_safe.metrics["max_slide"]
        out["residual_slide"] = r_safe.metrics["residual_slide"]
        out["safe_status"] = f"{r_safe.outcome}:{r_safe.status.split(':', 1)[-1]}"
    return out


def _foundation_peaks(result, alpha):
    """(max |theta|/alpha after the first zero crossing, first half-cycle durations [s])."""
    from fastrock.analyses.foundation_predictors import foundation_half_cycles
    hc = foundation_half_cycles(result)
    peaks = np.abs(hc["peak_angle"].to_numpy(float)[1:])
    return (float(peaks.max()) / alpha if peaks.size else np.nan,
            hc["duration"].to_numpy(float)[:FOUNDATION_HALF_CYCLES])


def _run_set_foundation(body, fnd, safe, over, grid, solver, repeats=3, threads=None):
    """:func:`_run_set` for a foundation: free releases from the angles ``safe``, ``over`` and
    ``grid`` [rad] over FOUNDATION_DURATION; the grid runs through the foundation's sweep kernel."""
    from fastrock.running.foundation import foundation_spec, simulate_foundation
    from fastrock.running.outcomes import outcome_of
    from fastrock.running.sweep import run_sweep
    from fastrock.model import excitation as X
    from fastrock.kernels import layout as L
    kw = dict(duration=FOUNDATION_DURATION, solver=solver, allow_overturn=True)
    r_safe = simulate_foundation(body, fnd, theta0=safe, **kw)
    r_over = simulate_foundation(body, fnd, theta0=over, **kw)
    peak, durations = _foundation_peaks(r_safe, body.alpha)
    spec, blk = foundation_spec(body, fnd)
    n = len(grid)
    hdr, smp = X.to_header(body, None)
    HDR = np.tile(hdr, (n, 1))
    OPT = np.tile(solver.options(FOUNDATION_DURATION, False), (n, 1))
    Y0 = np.array([fnd.initial_state(blk, th, 0.0) for th in grid])
    PAR = np.tile(spec.par, (n, 1))
    best = best_cpu = np.inf
    with _threads(threads):
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            status, MET, _, done = run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, progress=False,
                                             reraise_when_complete=True)
            if done < len(grid):
                raise KeyboardInterrupt   # a partial grid would make a wrong error and time
            best = min(best, time.perf_counter() - t0)
            best_cpu = min(best_cpu, time.process_time() - c0)
    return dict(max_rotation=peak, half_cycles=durations, safe_status=r_safe.status,
                t_overturn=r_over.metrics["time_overturn"], over_status=r_over.status,
                outcomes=[outcome_of(c) for c in status], time_per_run=best / n, cpu_per_run=best_cpu / n,
                nfev=float(np.mean(MET[:, L.M_NFEV])))


def _names(name, values, allowed):
    values = (values,) if isinstance(values, str) else tuple(values)
    bad = [v for v in values if not isinstance(v, str) or v not in allowed]
    if bad or not values:
        raise ValueError(f"{name} must be a non-empty list among {', '.join(allowed)}, got {values!r}")
    return values


def _check_arguments(models, excitations, rtols, dts, t_after, record_breakpoints, grid, threads):
    """work_precision's arguments, each checked and named."""
    from fastrock import _validate as V
    models = _names("models", models, FAMILIES)
    excitations = _names("excitations", excitations, ("pulse", "record"))
    rtols = tuple(V.in_open("rtols", r, 1e-15, 1.0) for r in np.atleast_1d(V.finite_array("rtols", rtols,
                                                                                          np.ndim(rtols))))
    dts = tuple(V.positive("dts", d) for d in np.atleast_1d(V.finite_array("dts", dts, np.ndim(dts))))
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    record_breakpoints = tuple(V.boolean("record_breakpoints", b) for b in (
        (record_breakpoints,) if np.ndim(record_breakpoints) == 0 else record_breakpoints))
    if grid is not None:
        grid = V.integer("grid", grid, 1)
    if threads is not None:
        threads = V.integer("threads", threads, 1)
    return models, excitations, rtols, dts, t_after, record_breakpoints, grid, threads


def work_precision(models=("rigid", "flexible"), excitations=("pulse", "record"), rtols=RTOLS, dts=DTS,
                   t_after=5.0, record_breakpoints=(True, False), progress=True, grid=None, threads=None):
    """Error against run time for each model family, excitation and setting.

    Returns a DataFrame with columns model, excitation, mode ("rtol" /
    "dt"), setting, record_breakpoints, time_per_run [s], nfev,
    err_max_rotation [-], err_t_overturn [s], outcome_mismatch [-], status,
    and for the friction families err_max_slide, err_residual_slide [m], for the
    foundation err_half_cycles [s] (its excitation is always "free": release angles).
    ``grid``: keep only this many runs of each spectrum grid (evenly spaced;
    for quick checks).  ``threads``: Numba threads of the timed sweeps (None:
    all; recorded in the ``threads`` column, 0 meaning all).
    """
    models, excitations, rtols, dts, t_after, record_breakpoints, grid, threads = _check_arguments(
        models, excitations, rtols, dts, t_after, record_breakpoints, grid, threads)
    rows = []
    try:
        _work_precision_rows(rows, models, excitations, rtols, dts, t_after, record_breakpoints, progress,
                             grid, threads)
    except KeyboardInterrupt:
        import warnings
        total = sum((len(rtols) + len(dts)) * (1 if m in FREE_FAMILIES else sum(
            len(record_breakpoints) if e == "record" else 1 for e in excitations)) for m in models)
        warnings.warn(f"interrupted: returning the {len(rows)} of {total} settings that finished",
                      stacklevel=2)
        df = pd.DataFrame(rows)
        df.attrs.update(interrupted=True, settings_total=total)
        return df
    df = pd.DataFrame(rows)
    df.attrs.update(interrupted=False, settings_total=len(rows))
    return df


def _work_precision_rows(rows, models, excitations, rtols, dts, t_after, record_breakpoints, progress, grid,
                         threads):
    """Append one row per setting to ``rows`` (kept when Ctrl-C stops the loop)."""
    from fastrock.running.solver import Solver
    for model in models:
        body, effects = _family(model)
        for excitation in (("free",) if model in FREE_FAMILIES else excitations):
            safe, over, cells = _cases(body, excitation, model)
            if grid is not None and grid < len(cells):
                cells = [cells[i] for i in np.linspace(0, len(cells) - 1, max(int(grid), 1)).astype(int)]
            bps = record_breakpoints if excitation == "record" else (True,)
            for bp in bps:
                ref = _run_set(body, safe, over, cells, Solver(rtol=REFERENCE_RTOL, atol=1e-15,
                                                                record_breakpoints=bp), t_after,
                               effects=effects)
                settings = [("rtol", r) for r in rtols] + [("dt", d) for d in dts]
                for mode, val in settings:
                    sol = Solver(rtol=val, record_breakpoints=bp) if mode == "rtol" else \
                        Solver(dt=val, record_breakpoints=bp, max_steps=50_000_000)
                    res = _run_set(body, safe, over, cells, sol, t_after, effects=effects, threads=threads)
                    mism = np.mean([a != b for a, b in zip(res["outcomes"], ref["outcomes"])])
                    row = dict(model=model, excitation=excitation, mode=mode, setting=val,
                               record_breakpoints=bp, time_per_run=res["time_per_run"],
                               cpu_per_run=res["cpu_per_run"], threads=int(threads or 0), nfev=res["nfev"],
                               err_max_rotation=abs(res["max_rotation"] - ref["max_rotation"]),
                               err_t_overturn=abs(res["t_overturn"] - ref["t_overturn"]),
                               outcome_mismatch=mism,
                               status=f"{res['safe_status']}/{res['over_status']}")
                    if "half_cycles" in res:
                        a, b = res["half_cycles"], ref["half_cycles"]
                        m = min(a.size, b.size)
                        row["err_half_cycles"] = float(np.max(np.abs(a[:m] - b[:m]))) if m else np.nan
                        row["half_cycles_compared"] = m
                    if "max_slide" in res:
                        row["err_max_slide"] = abs(res["max_slide"] - ref["max_slide"])
                        row["err_residual_slide"] = abs(res["residual_slide"] - ref["residual_slide"])
                    rows.append(row)
                    if progress:
                        slide = (f" err_slide={row['err_residual_slide']:.2e}" if "err_residual_slide" in row
                                 else "")
                        print(f"{model:9s} {excitation:7s} bp={int(bp)} {mode}={val:<8g} "
                              f"t/run={row['time_per_run'] * 1e3:8.3f} ms cpu/run={row['cpu_per_run'] * 1e3:8.3f} ms "
                              f"err_rot={row['err_max_rotation']:.2e} "
                              f"err_t={row['err_t_overturn']:.2e}{slide} mismatch={mism:.3f}", flush=True)


MEASURE_LABELS = {
    "err_max_rotation": "error in max|θ|/α",
    "err_t_overturn": "error in overturning time [s]",
    "outcome_mismatch": "share of grid outcomes changed",
    "err_max_slide": "error in max|d| [m]",
    "err_residual_slide": "error in residual slide [m]",
    "err_half_cycles": "error in half-cycle durations [s]",
}
CLOCKS = {"wall": ("time_per_run", "time per run [s]"),
          "cpu": ("cpu_per_run", "CPU time per run [s]")}


def default_measures(df):
    """err_max_rotation, plus the residual-slide error when the table has a friction family and
    the half-cycle error when it has the foundation."""
    out = ("err_max_rotation",)
    for extra in ("err_residual_slide", "err_half_cycles"):
        if extra in df and df[extra].notna().any():
            out += (extra,)
    return out


