"""``fastrock accuracy``: the work-precision table and figure.
"""
from __future__ import annotations

import numpy as np

from fastrock.analyses.accuracy import CLOCKS, DTS, FAMILIES, MEASURE_LABELS, RTOLS, work_precision
from fastrock.plotting.accuracy import plot_work_precision


def add_subcommand(sub):
    p = sub.add_parser("accuracy", help="work-precision: error against run time (PNG + CSV)")
    p.add_argument("--models", default=",".join(FAMILIES),
                   help=f"comma-separated model families: {', '.join(FAMILIES)} (default: all)")
    p.add_argument("--excitations", default="pulse,record",
                   help="pulse and/or record (the foundation family always runs free releases; "
                        "default pulse,record)")
    p.add_argument("--quick", action="store_true", help="fewer settings (rtol 1e-3..1e-10, dt 1e-2..1e-4; default: off)")
    p.add_argument("--rtols", default=None, help="comma-separated rtol values [-] (overrides --quick; default 1e-3..1e-12)")
    p.add_argument("--dts", default=None, help="comma-separated fixed integration steps [s] (overrides --quick; default "
                        "1e-2..1e-5)")
    p.add_argument("--grid", type=int, default=None,
                   help="use only this many runs of each spectrum grid (evenly spaced; quick checks; "
                        "default: the whole grid)")
    p.add_argument("--t-after", type=float, default=5.0, help="time simulated after the excitation [s] (default 5)")
    p.add_argument("--measures", default=None,
                   help="comma-separated error columns to plot, one row each (default: err_max_rotation, "
                        "plus err_residual_slide with friction, err_half_cycles with the foundation)")
    p.add_argument("--clock", choices=tuple(CLOCKS), default="wall",
                   help="x axis: wall time per run (default) or CPU time per run (steadier on a busy machine)")
    p.add_argument("--threads", type=int, default=None,
                   help="Numba threads for the timed sweeps (default: all; 1 with --clock cpu on a shared machine)")
    from fastrock.cli.output import add_output_options
    add_output_options(p, png="accuracy.png", csv="accuracy.csv", figure="the work-precision figure",
                       table="the table of settings")
    p.set_defaults(func=_cmd)


def _floats(text, name):
    try:
        vals = tuple(float(v) for v in text.split(",") if v.strip())
    except ValueError:
        raise ValueError(f"--{name}: expected comma-separated numbers, got {text!r}") from None
    if not vals or not all(v > 0 and np.isfinite(v) for v in vals):
        raise ValueError(f"--{name}: expected positive numbers, got {text!r}")
    return vals


def _cmd(args):
    models = tuple(m.strip() for m in args.models.split(",") if m.strip())
    bad = [m for m in models if m not in FAMILIES]
    if bad:
        raise ValueError(f"--models: unknown family {', '.join(bad)} (choose from {', '.join(FAMILIES)})")
    rtols = RTOLS[:-2] if args.quick else RTOLS
    dts = DTS[:5] if args.quick else DTS
    if args.rtols is not None:
        rtols = _floats(args.rtols, "rtols")
    if args.dts is not None:
        dts = _floats(args.dts, "dts")
    if args.threads is not None and args.threads < 1:
        raise ValueError(f"--threads must be >= 1, got {args.threads}")
    excitations = tuple(e.strip() for e in args.excitations.split(",") if e.strip())
    bad = [e for e in excitations if e not in ("pulse", "record")]
    if bad or not excitations:
        raise ValueError(f"--excitations: expected pulse and/or record, got {args.excitations!r}")
    measures = None if args.measures is None else tuple(m.strip() for m in args.measures.split(","))
    bad = [m for m in measures or () if m not in MEASURE_LABELS]
    if bad:
        raise ValueError(f"--measures: unknown {', '.join(bad)} (choose from {', '.join(MEASURE_LABELS)})")
    df = work_precision(models, excitations, rtols, dts, t_after=args.t_after, grid=args.grid,
                        threads=args.threads)
    from fastrock.cli.output import write_table, wrote
    written = write_table(df, args)
    if len(df):
        fig = plot_work_precision(df, measures, clock=args.clock)
        fig.savefig(args.png, dpi=130)
        written.append(args.png)
    if df.attrs.get("interrupted"):
        from fastrock.cli.output import interrupted_exit
        return interrupted_exit(len(df), df.attrs["settings_total"], "settings", written)
    wrote(written)
    return 0
