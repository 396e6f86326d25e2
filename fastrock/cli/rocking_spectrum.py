"""``fastrock rocking-spectrum`` and ``fastrock record``.
"""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from fastrock import _validate as V
from fastrock.model.bodies import RigidBlock
from fastrock.io.default_records import load_default_record
from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
from fastrock.analyses.rocking_spectrum.engine import T_AFTER
from fastrock.analyses.rocking_spectrum.inputs import read_one_record, label_of_wall, load_records, parse_walls
from fastrock.analyses.rocking_spectrum.single_runs import simulate_record
from fastrock.plotting.rocking_spectrum import plot_rocking_spectrum


# -------------------------------------------------------------------- CLI
#: Default block of ``fastrock record``: 0.6 m x 3 m (b/h = 0.2).  Under the
#: packaged El Centro record it rocks (max |theta|/alpha = 0.26) and stays up.
DEFAULT_RECORD_BLOCK = (0.3, 1.5)


def _cli_record(args):
    rec = _cli_one_record(args.file, args.unit, args.record_dt, args)
    body = _cli_body(args)
    wall = _cli_wall(args)
    fixed = args.dt_fixed is not None and args.dt_fixed.strip().lower() == "record"
    kw = dict(wall=wall, rtol=args.rtol, atol=args.atol, t_after=args.t_after)
    if args.dt_fixed is not None and not fixed:
        kw["dt"] = V.positive("--dt", _float_arg("--dt", args.dt_fixed))
    r = simulate_record(body, rec, fixed_step=fixed, **kw)
    m = r.metrics
    print(f"record: {rec.name}" + (f"  ({rec.source})" if rec.source else ""))
    print(f"  PGA = {rec.pga_g:.3g} g at t = {rec.peak_time:.3g} s, PGV = {rec.pgv:.3g} m/s, "
          f"PGD = {rec.pgd:.3g} m")
    print(f"  duration = {rec.duration:.4g} s ({rec.npts} points, dt = {rec.dt:g} s), "
          f"Tm = {rec.mean_period:.3g} s, Arias = {rec.arias_intensity:.3g} m/s")
    geom = f"b = {body.b:g} m, h = {body.h:g} m, " if body.b is not None else ""
    print(f"block: {geom}alpha = {body.alpha:.4g} rad, p = {body.p:.4g} rad/s, "
          f"e = {body.e:.4g}, Tp = {2 * math.pi / body.p:.3g} s; "
          f"uplift at {body.uplift_acceleration / body.g:.3g} g"
          + ("" if wall is None else f"; {label_of_wall(wall)}"))
    solver = f"fixed dt = {kw['dt']:g} s" if "dt" in kw else (
        f"fixed dt = record dt = {rec.dt:g} s" if fixed else "adaptive RK45")
    print(f"outcome: {r.outcome} ({r.status}); {solver}")
    print(f"  max |theta|/alpha = {m['max_rotation_ratio']:.4g}, impacts = {m['impacts']}"
          + (f", wall impacts = {m['wall_impacts']}" if wall is not None else "")
          + f", uplift t = {_time(m['time_uplift'])}, overturn t = {_time(m['time_overturn'])}")
    from fastrock.cli.output import wrote, write_table
    wrote(write_table(r.history, args))
    if args.png:
        fig = _record_figure(rec, r)
        fig.savefig(args.png, dpi=120)
        wrote([args.png])
    return 0


def _time(t):
    return "none" if math.isnan(t) else f"{t:.4g} s"


def _record_figure(rec, result):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8.0, 8.0), layout="constrained")
    axes = fig.subplots(4, 1, sharex=True)
    rec.plot(ax=axes[:3])
    axes[2].set_xlabel("")
    h = result.history
    axes[3].plot(h["t"], h["theta_ratio"], lw=0.9)
    axes[3].axhline(1, color="k", lw=0.6, ls=":")
    axes[3].axhline(-1, color="k", lw=0.6, ls=":")
    axes[3].set_ylabel(r"$\theta/\alpha$")
    axes[3].set_xlabel("t [s]")
    axes[3].grid(True, alpha=0.3)
    axes[3].set_title(f"rocking: {result.status}", fontsize=9)
    return fig


def _float_arg(name, text):
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number or 'record', got {text!r}") from None


def _column_arg(text):
    if text is None or text == "all":
        return text
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"--column must be an integer (0-based, negative from the end) or 'all', "
                         f"got {text!r}") from None


def _cli_one_record(path, unit, dt, args=None):
    if path is None:
        return load_default_record()
    return read_one_record(Path(path), unit, dt, column=_column_arg(getattr(args, "column", None)),
                     decimal=getattr(args, "decimal", None))


def _cli_body(args):
    if args.b is not None or args.h is not None:
        if args.b is None or args.h is None:
            raise ValueError("give both --b and --h (half-width and half-height, m)")
        return RigidBlock.rectangle(args.b, args.h, e=args.e)
    if args.alpha is not None or args.p is not None:
        if args.alpha is None or args.p is None:
            raise ValueError("give both --alpha and --p")
        return RigidBlock(alpha=args.alpha, p=args.p, e=args.e)
    return RigidBlock.rectangle(*DEFAULT_RECORD_BLOCK, e=args.e)


def _cli_wall(args):
    if args.wall_gap is None:
        return None
    try:
        from fastrock.model.wall import Wall
    except ImportError:
        raise ValueError("--wall-gap needs fastrock.model.wall, which is not installed") from None
    return Wall(gap=args.wall_gap, side=args.wall_side)


def _cli_rocking_spectrum(args):
    import time
    records = load_records(args.files or None, args.unit, args.record_dt, column=_column_arg(args.column),
                           decimal=args.decimal)
    from fastrock.cli.output import grid_option
    s = grid_option("--slenderness", args.slenderness_min, args.slenderness_max, args.n_slenderness,
                    n_option="--n-slenderness")
    b = grid_option("--b", args.b_min, args.b_max, args.n_sizes, n_option="--n-sizes")
    walls = parse_walls(args.walls) if args.walls else None
    t0 = time.perf_counter()
    table, runs = rocking_spectrum(records, s, b, walls, rtol=args.rtol, dt=args.dt, t_after=args.t_after,
                                   progress=not args.quiet, return_runs=True, shape=args.outline)
    el = time.perf_counter() - t0
    print(f"{len(runs)} runs ({len(records)} records x {len(table.attrs['walls'])} wall settings x "
          f"{args.n_sizes} sizes x {args.n_slenderness} slenderness) in {el:.2f} s "
          f"({len(runs) / el:,.0f} runs/s)")
    for r in records:
        print(f"  {r.name}: PGA = {r.pga_g:.3g} g, Tm = {r.mean_period:.3g} s, "
              f"duration = {r.duration:.4g} s")
    agg = table.groupby(["record", "wall"], sort=False).agg(
        beta_min=("beta", "min"), beta_max=("beta", "max"),
        exact=("beta_bound", lambda x: int((x == "exact").sum())),
        upper=("beta_bound", lambda x: int((x == "upper").sum())),
        lower=("beta_bound", lambda x: int((x == "lower").sum())),
        non_monotone=("non_monotone", "sum"), overturned=("n_overturned", "sum"))
    with pd.option_context("display.width", 160, "display.max_columns", 20):
        print(agg.round(3).to_string())
    from fastrock.cli.output import wrote, write_table
    tables = write_table(table, args)
    fig = plot_rocking_spectrum(table, title=f"{len(records)} record(s), "
                                             f"{args.n_sizes}x{args.n_slenderness} "
                                             f"{'stretched outlines' if args.outline else 'blocks'}")
    fig.savefig(args.png, dpi=130)
    if table.attrs.get("interrupted"):
        from fastrock.cli.output import interrupted_exit
        return interrupted_exit(int((runs["outcome"] != "unfinished").sum()), len(runs), "runs",
                                tables + [args.png])
    wrote(tables + [args.png])
    return 0


def _add_record_options(p):
    p.add_argument("--unit", help="acceleration unit of files whose header does not state it "
                                  "(g, m/s2, cm/s2/gal, mm/s2; default: refuse such files)")
    p.add_argument("--record-dt", type=float, help="sample step [s] of single-column files "
                                                   "(default: refuse such files)")
    p.add_argument("--column", help="data column holding the acceleration in files with several "
                                    "columns (0-based, negative from the end), or 'all' for one "
                                    "record wrapped over rows (default: refuse such files)")
    p.add_argument("--decimal", choices=(".", ","), help="decimal mark of the files (default '.'; "
                                                         "decimal commas are refused unless ',')")


def add_subcommands(subparsers):
    """Register ``fastrock record`` and ``fastrock rocking-spectrum``."""
    s = subparsers.add_parser(
        "record", help="one block under a recorded accelerogram: measures, outcome, plots",
        description="Load an accelerogram (default: the packaged 1940 El Centro N-S), print its "
                    "ground-motion measures, simulate one block and plot record and rocking.")
    s.add_argument("file", nargs="?", help="record file (PEER AT2, two-column or single-column); "
                                           "default: packaged El Centro")
    _add_record_options(s)
    g = s.add_argument_group("block (default: b = 0.3 m, h = 1.5 m; rocks, does not overturn "
                             "under El Centro)")
    g.add_argument("--b", type=float, help="half-width [m] (with --h; default 0.3)")
    g.add_argument("--h", type=float, help="half-height [m] (default 1.5)")
    g.add_argument("--alpha", type=float, help="slenderness angle [rad] (with --p; default: from --b/--h)")
    g.add_argument("--p", type=float, help="frequency parameter [rad/s] (default: from --b/--h)")
    g.add_argument("--e", type=float, help="ground impact restitution e [-] (default Housner)")
    w = s.add_argument_group("rear wall")
    w.add_argument("--wall-gap", type=float, help="clear gap d [m] (default: no wall)")
    w.add_argument("--wall-side", type=int, default=-1, choices=(-1, 1),
                   help="side of the wall (default -1)")
    i = s.add_argument_group("integrator")
    i.add_argument("--rtol", type=float, help="relative tolerance of adaptive RK45 [-] (default 1e-8)")
    i.add_argument("--atol", type=float, help="absolute tolerance [rad, rad/s] (default rtol*1e-2)")
    i.add_argument("--dt", "--dt-fixed", dest="dt_fixed", metavar="DT",
                   help="fixed integration step [s] instead of adaptive RK45, or 'record' to step "
                        "at the record's dt (default: adaptive)")
    s.add_argument("--t-after", type=float, default=T_AFTER,
                   help=f"free rocking after the record [s] (default {T_AFTER:g})")
    from fastrock.cli.output import add_output_options
    add_output_options(s, png="record.png", figure="the figure of the record (acc/vel/disp) and "
                       "theta/alpha", table="the rocking time history")
    s.set_defaults(func=_cli_record)

    s = subparsers.add_parser(
        "rocking-spectrum", help="beta against Tp/Tm over records x blocks x wall settings",
        description="For each record, block size and wall setting, find the minimum stable "
                    "slenderness on a grid and report beta = (b/h)_min g / PGA against Tp/Tm.")
    s.add_argument("files", nargs="*", help="record files, folders (their .AT2 and .dat files, any "
                                           "letter case) or quoted glob patterns (default: "
                                           "packaged El Centro)")
    _add_record_options(s)
    s.add_argument("--n-slenderness", type=int, default=20, help="number of b/h values (default 20)")
    s.add_argument("--slenderness-min", type=float, default=0.1, help="smallest b/h [-] (default 0.1)")
    s.add_argument("--slenderness-max", type=float, default=0.5, help="largest b/h [-] (default 0.5)")
    s.add_argument("--n-sizes", type=int, default=20, help="number of half-widths b (default 20)")
    s.add_argument("--b-min", type=float, default=0.1, help="smallest half-width [m] (default 0.1)")
    s.add_argument("--b-max", type=float, default=1.0, help="largest half-width [m] (default 1)")
    s.add_argument("--outline", metavar="FILE",
                   help="a body outline (x y [m] per row) instead of rectangles: each cell stretches it to "
                        "half base width b and slenderness tan(alpha) of its slenderer side (default: "
                        "rectangles)")
    s.add_argument("--walls", help="comma list of settings, e.g. two-sided,0.01,0.10 (gaps in m; "
                                   "default: these three if the wall model is installed)")
    s.add_argument("--rtol", type=float, help="relative tolerance of adaptive RK45 [-] (default 1e-8)")
    s.add_argument("--dt", type=float, help="fixed integration step [s] instead of adaptive RK45 "
                                            "(default: adaptive)")
    s.add_argument("--t-after", type=float, default=T_AFTER,
                   help=f"free rocking after each record [s] (default {T_AFTER:g})")
    from fastrock.cli.output import add_output_options
    add_output_options(s, png="rocking_spectrum.png", csv="rocking_spectrum.csv",
                       figure="the beta against Tp/Tm figure", table="the table of thresholds")
    s.set_defaults(func=_cli_rocking_spectrum)
