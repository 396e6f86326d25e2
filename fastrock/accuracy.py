"""Work-precision: what accuracy costs in time.

For each model family and excitation, runs the same cases with adaptive
tolerances (rtol 1e-3 ... 1e-12) and fixed steps (dt 1e-2 ... 1e-5 s) and
measures, against a much tighter reference (rtol 1e-13):

* ``err_max_rotation``: |max|theta|/alpha - reference| on a case that stays up;
* ``err_t_overturn``: |t_overturn - reference| [s] on a case that overturns;
* ``outcome_mismatch``: share of a spectrum grid whose outcome differs;
* ``time_per_run`` [s] (kernel time, compiled, averaged over the grid).
"""
from __future__ import annotations

import time

import numpy as np
import pandas as pd

RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
DTS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
REFERENCE_RTOL = 1e-13


def _family(model):
    from .bodies import FlexibleBody, RigidBlock
    if model == "rigid":
        return RigidBlock(alpha=0.25, p=2.0)
    if model == "flexible":
        return FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05)
    raise ValueError(f"model must be 'rigid' or 'flexible', got {model!r}")


def _cases(body, excitation):
    """(safe case, overturning case, grid) for one excitation kind."""
    from .excitation import Pulse, SampledMotion
    from .records import load_default_record
    if excitation == "pulse":
        safe = Pulse(2.5, 5.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        over = Pulse(3.0, 3.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        grid = [Pulse(a, f, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
                for a in np.linspace(1.2, 6.0, 8) for f in np.linspace(0.5, 8.0, 8)]
        return safe, over, grid
    if excitation == "record":
        rec = load_default_record()
        scale_up = body.g * np.tan(body.alpha) / rec.pga
        safe = SampledMotion.from_record(rec, scale=1.5 * scale_up)
        over = SampledMotion.from_record(rec, scale=6.0 * scale_up)
        grid = [SampledMotion.from_record(rec, scale=s * scale_up) for s in np.linspace(1.1, 8.0, 24)]
        return safe, over, grid
    raise ValueError(f"excitation must be 'pulse' or 'record', got {excitation!r}")


def _grid_rows(body, grid, solver, t_after):
    """Sweep-kernel inputs for a grid of excitations sharing one sample array."""
    from . import excitation as X
    from . import models
    from fastrock.kernels import layout as L
    spec = models.select(body)
    rows = [X.to_header(body, exc) for exc in grid]
    HDR = np.array([h for h, _ in rows])
    smp = rows[0][1]
    n = len(grid)
    OPT = np.tile(solver.options(0.0, False), (n, 1))
    OPT[:, L.O_T_END] = [X.end_time(body, exc) + t_after for exc in grid]
    return spec, np.zeros((n, spec.n_state)), np.tile(spec.par, (n, 1)), HDR, smp, OPT


def _run_set(body, safe, over, grid, solver, t_after, repeats=3):
    from .outcomes import outcome_of
    from .simulate import simulate
    from .sweep import run_sweep
    from fastrock.kernels import layout as L
    r_safe = simulate(body, safe, solver=solver, t_after=t_after, history_capacity=10)
    r_over = simulate(body, over, solver=solver, t_after=t_after, history_capacity=10)
    spec, Y0, PAR, HDR, smp, OPT = _grid_rows(body, grid, solver, t_after)
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        status, MET, _, _ = run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, progress=False)
        best = min(best, time.perf_counter() - t0)
    return dict(max_rotation=r_safe.metrics["max_rotation_ratio"], safe_status=r_safe.status,
                t_overturn=r_over.metrics["time_overturn"], over_status=r_over.status,
                outcomes=[outcome_of(c) for c in status], time_per_run=best / len(grid),
                nfev=float(np.mean(MET[:, L.M_NFEV])))


def work_precision(models=("rigid", "flexible"), excitations=("pulse", "record"), rtols=RTOLS, dts=DTS,
                   t_after=5.0, record_breakpoints=(True, False), progress=True):
    """Error against run time for each model family, excitation and setting.

    Returns a DataFrame with columns model, excitation, mode ("rtol" /
    "dt"), setting, record_breakpoints, time_per_run [s], nfev,
    err_max_rotation [-], err_t_overturn [s], outcome_mismatch [-], status.
    """
    from .solver import Solver
    rows = []
    for model in models:
        body = _family(model)
        for excitation in excitations:
            safe, over, grid = _cases(body, excitation)
            bps = record_breakpoints if excitation == "record" else (True,)
            for bp in bps:
                ref = _run_set(body, safe, over, grid, Solver(rtol=REFERENCE_RTOL, atol=1e-15,
                                                               record_breakpoints=bp), t_after)
                settings = [("rtol", r) for r in rtols] + [("dt", d) for d in dts]
                for mode, val in settings:
                    sol = Solver(rtol=val, record_breakpoints=bp) if mode == "rtol" else \
                        Solver(dt=val, record_breakpoints=bp, max_steps=50_000_000)
                    res = _run_set(body, safe, over, grid, sol, t_after)
                    mism = np.mean([a != b for a, b in zip(res["outcomes"], ref["outcomes"])])
                    rows.append(dict(model=model, excitation=excitation, mode=mode, setting=val,
                                     record_breakpoints=bp, time_per_run=res["time_per_run"], nfev=res["nfev"],
                                     err_max_rotation=abs(res["max_rotation"] - ref["max_rotation"]),
                                     err_t_overturn=abs(res["t_overturn"] - ref["t_overturn"]),
                                     outcome_mismatch=mism,
                                     status=f"{res['safe_status']}/{res['over_status']}"))
                    if progress:
                        r = rows[-1]
                        print(f"{model:9s} {excitation:7s} bp={int(bp)} {mode}={val:<8g} "
                              f"t/run={r['time_per_run'] * 1e3:8.3f} ms  err_rot={r['err_max_rotation']:.2e} "
                              f"err_t={r['err_t_overturn']:.2e} mismatch={mism:.3f}", flush=True)
    return pd.DataFrame(rows)


def plot_work_precision(df, measure="err_max_rotation"):
    """Log-log error against time per run, one panel per model/excitation."""
    from .plotting import _pyplot
    plt = _pyplot()
    keys = list(df.groupby(["model", "excitation"]).groups)
    fig, axes = plt.subplots(1, len(keys), figsize=(4.6 * len(keys), 4), squeeze=False, constrained_layout=True)
    for ax, (model, exc) in zip(axes[0], keys):
        sub = df[(df.model == model) & (df.excitation == exc)]
        for (mode, bp), g in sub.groupby(["mode", "record_breakpoints"]):
            lab = ("adaptive rtol" if mode == "rtol" else "fixed dt") + ("" if exc == "pulse" else
                                                                        (" (breakpoints)" if bp else " (no bp)"))
            err = np.maximum(g[measure].to_numpy(), 1e-16)
            ax.loglog(g["time_per_run"], err, "o-" if mode == "rtol" else "s--", label=lab, ms=4)
            for x, y, v in zip(g["time_per_run"], err, g["setting"]):
                ax.annotate(f"{v:g}", (x, y), fontsize=6, alpha=0.7)
        ax.set_title(f"{model}, {exc}")
        ax.set_xlabel("time per run [s]")
        ax.set_ylabel(measure)
        ax.legend(fontsize=7)
    return fig


def add_subcommand(sub):
    p = sub.add_parser("accuracy", help="work-precision: error against run time (PNG + CSV)")
    p.add_argument("--models", default="rigid,flexible")
    p.add_argument("--excitations", default="pulse,record")
    p.add_argument("--quick", action="store_true", help="fewer settings (rtol 1e-3..1e-10, dt 1e-2..1e-4)")
    p.add_argument("--csv", default="accuracy.csv")
    p.add_argument("--png", default="accuracy.png")
    p.set_defaults(func=_cmd)


def _cmd(args):
    rtols = RTOLS[:-2] if args.quick else RTOLS
    dts = DTS[:5] if args.quick else DTS
    df = work_precision(tuple(args.models.split(",")), tuple(args.excitations.split(",")), rtols, dts)
    df.to_csv(args.csv, index=False)
    fig = plot_work_precision(df)
    fig.savefig(args.png, dpi=130)
    print(f"wrote {args.csv} and {args.png}")
    return 0
