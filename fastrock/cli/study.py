"""``fastrock study``: run a study file, fit fragility curves.
"""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from fastrock import _validate as V
from fastrock.analyses.fragility import MAX_BOOT, fit_fragility
from fastrock.plotting.fragility import plot_fragility
from fastrock.studies.definition import Study
from fastrock.studies.output import DEFAULT_CHUNK_SIZE
from fastrock.studies.run import CONNECT_TIMEOUT, run_study


# ==================================================================== CLI
def _cli_study(args):
    if args.chunk_size is not None:
        V.integer("--chunk-size", args.chunk_size, 1)
    V.positive("--connect-timeout", args.connect_timeout)
    V.integer("--n-boot", args.n_boot, 0, MAX_BOOT)
    study = Study.from_toml(args.study)
    opts = study.run
    output = args.output or opts.get("output") or str(Path(args.study).with_suffix("")) + "_results"
    scheduler = args.scheduler or opts.get("scheduler")
    backend = args.backend or opts.get("backend") or ("dask" if scheduler else "local")
    chunk = args.chunk_size or opts.get("chunk_size")
    df = run_study(study, output, backend=backend, scheduler=scheduler if backend == "dask" else None,
                   chunk_size=chunk, progress=not args.quiet, connect_timeout=args.connect_timeout)
    a = df.attrs
    rate = a["chunks_run"] and len(df) / max(a["wall_seconds"], 1e-9)
    print(f"study {study.name or args.study}: {len(df)} runs in {a['n_chunks']} chunks of "
          f"{a['chunk_size']} ({a['chunks_skipped']} already done, {a['chunks_run']} run) in "
          f"{a['wall_seconds']:.1f} s on {backend}" + (f" ({rate:,.0f} runs/s)" if a["chunks_run"]
                                                        else ""))
    print(f"results: {output} (fastrock.studies.output.load_results)")
    print("outcomes:", df["outcome"].value_counts().to_dict())
    im = {"pga": "pga_g", "pgv": "pgv"}.get(study.measure, study.measure)
    rows, table, fits = [], [], []
    for (body, var), grp in df.groupby(["body", "variant"], sort=False):
        try:
            f = fit_fragility(grp, im=im, n_boot=args.n_boot, label=f"{body}, {var}")
            lo, hi = f.interval()["theta"]
            rows.append((body, var, f"{f.theta:.4g}", f"{f.beta:.3f}", f"[{lo:.4g}, {hi:.4g}]"))
            table.append((body, var, im, f.theta, f.beta, lo, hi, ""))
            fits.append(f)
        except ValueError as exc:
            reason = str(exc).split(": ", 2)[-1]
            rows.append((body, var, "-", "-", reason[:40]))
            table.append((body, var, im, math.nan, math.nan, math.nan, math.nan, reason))
    print(f"overturning fragility against {im} (theta, beta; 90% bootstrap interval of theta):")
    print(pd.DataFrame(rows, columns=["body", "variant", "theta", "beta", "theta 90%"]).to_string(
        index=False))
    from fastrock.cli.output import write_table, wrote
    written = write_table(pd.DataFrame(table, columns=FRAGILITY_TABLE_COLUMNS), args)
    if args.png and fits:
        plot_fragility(fits).savefig(args.png, dpi=130)
        written.append(args.png)
    if a["interrupted"]:
        from fastrock.cli.output import interrupted_exit
        return interrupted_exit(a["chunks_skipped"] + a["chunks_run"], a["n_chunks"], "chunks",
                                [output] + written)
    wrote(written)
    return 0


#: Columns of ``fastrock study --csv``: the fragility fit per body and variant; theta in the
#: measure's unit (g for pga_g, m/s for pgv), theta_lo/theta_hi its 90 % bootstrap interval,
#: ``note`` why a fit failed (its numbers are then NaN).
FRAGILITY_TABLE_COLUMNS = ["body", "variant", "measure", "theta", "beta", "theta_lo", "theta_hi", "note"]


def add_subcommand(subparsers):
    """Register ``fastrock study study.toml [--scheduler ADDRESS] ...``."""
    s = subparsers.add_parser(
        "study", help="records x bodies x variants x levels (IDA), local or on Dask",
        description="Run (or resume) a study file: every record scaled to every intensity level "
                    "for every body and scene variant, in chunks written as Parquet; prints an "
                    "overturning fragility per body and variant.")
    s.add_argument("study", help="study file (TOML), see examples/study.toml")
    s.add_argument("--output", help="results folder (default: [run] output, or <study>_results)")
    s.add_argument("--backend", choices=("local", "dask"),
                   help="local (default) or dask (default with --scheduler)")
    s.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786 (default: none; "
                                       "--backend dask then starts a local cluster)")
    s.add_argument("--chunk-size", type=int, help=f"rows per chunk (default {DEFAULT_CHUNK_SIZE})")
    s.add_argument("--connect-timeout", type=float, default=CONNECT_TIMEOUT,
                   help=f"time to reach the scheduler [s] (default {CONNECT_TIMEOUT:g})")
    s.add_argument("--n-boot", type=int, default=200, help="bootstrap resamples (default 200)")
    from fastrock.cli.output import add_output_options
    add_output_options(s, figure="the fragility curves", table="the fragility table (theta, beta "
                       "per body and variant)")
    s.set_defaults(func=_cli_study)
