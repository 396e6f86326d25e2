"""``fastrock fit``: fit free-rocking parameters to half-cycle durations.
"""
from __future__ import annotations

import argparse
import math
import sys

from fastrock.analyses.freerocking.csv_input import fit_from_csv
from fastrock.analyses.freerocking.housner import HALF_CYCLE_DEFINITIONS
from fastrock.plotting.freerocking import plot_fit


# ----------------------------------------------------------------------------------------
# 7. CLI
# ----------------------------------------------------------------------------------------
def add_fit_subcommand(subparsers):
    """Register ``fit`` on an :mod:`argparse` sub-parsers object.

    ``fastrock fit FILE [--theta0-deg X] [--alpha-deg Y] [--model housner]
    [--definition impact|peak] [--min-duration S] [--png out.png] [--csv out.csv] [--parquet out.parquet]``

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        From ``parser.add_subparsers()``.

    Returns
    -------
    argparse.ArgumentParser
        The ``fit`` parser (its default ``func`` is :func:`run_fit_command`).
    """
    p = subparsers.add_parser(
        "fit", help="fit p and e of free rocking to measured half-cycle durations",
        description="Fit the frequency parameter p and restitution e to half-cycle durations "
                    "read from FILE (columns: duration [s] required; half_cycle, peak or "
                    "peak_deg, theta0_deg, alpha_deg optional). Several theta0_deg groups are "
                    "fitted jointly with shared (p, e) unless --theta0-deg selects one.")
    p.add_argument("file", metavar="FILE", help="half-cycle CSV file")
    th = p.add_mutually_exclusive_group()
    th.add_argument("--theta0", type=float, default=None,
                    help="release angle [rad]; selects a group if FILE has theta0_deg (default: "
                         "the file's theta0_deg column, every group)")
    th.add_argument("--theta0-deg", type=float, default=None, help="the same in degrees [deg] (default: none)")
    al = p.add_mutually_exclusive_group()
    al.add_argument("--alpha", type=float, default=None,
                    help="slenderness [rad] (default: the file's alpha_deg column)")
    al.add_argument("--alpha-deg", type=float, default=None, help="the same in degrees [deg] (default: none)")
    p.add_argument("--model", default="housner", help="model (default: housner)")
    p.add_argument("--definition", choices=HALF_CYCLE_DEFINITIONS, default=None,
                   help="half-cycle definition of the data: impact to impact or peak to peak "
                        "(default: what FILE states, else the better-fitting one, with a warning)")
    p.add_argument("--min-duration", type=float, default=None,
                   help="exclude measured durations below this [s] from the fit (default: none)")
    p.add_argument("--param", metavar="NAME=VALUE", action="append", default=[],
                   help="starting value of a fitted parameter, repeatable; the foundation "
                        "models need them, e.g. --model two-spring --param p=4.7 "
                        "--param omega=40 --param zeta=0.05 (default: the model's own starts)")
    from fastrock.cli.output import add_output_options
    add_output_options(p, figure="a figure of the fit", table="the fit table")
    p.add_argument("--plot", dest="png", metavar="FILE", help=argparse.SUPPRESS)  # the old name of --png
    p.set_defaults(func=run_fit_command)
    return p


def _parse_params(items):
    """``["p=4.7", "omega=40"]`` -> ``{"p": 4.7, "omega": 40.0}``; errors name the item."""
    out = {}
    for it in items:
        name, sep, value = it.partition("=")
        if not sep or not name.strip():
            raise ValueError(f"--param must look like NAME=VALUE, got {it!r}")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise ValueError(f"--param {name.strip()}: {value!r} is not a number") from None
        if not math.isfinite(out[name.strip()]):
            raise ValueError(f"--param {name.strip()} must be finite, got {value!r}")
    return out


def run_fit_command(args) -> int:
    """Run ``fastrock fit`` with parsed ``args`` (see :func:`add_fit_subcommand`).

    Prints ``p`` and ``e`` with standard errors, the RMS residual (overall and per
    ``theta0`` group) and optionally writes a plot and the fit table.

    Returns
    -------
    int
        0 on success, 2 on invalid input (message on stderr).
    """
    try:
        theta0 = args.theta0 if args.theta0_deg is None else math.radians(args.theta0_deg)
        alpha = args.alpha if args.alpha_deg is None else math.radians(args.alpha_deg)
        extra = {}
        params0 = _parse_params(getattr(args, "param", []) or [])
        if params0:
            extra["params0"] = params0
        fit = fit_from_csv(args.file, theta0=theta0, alpha=alpha, model=args.model,
                           definition=args.definition, min_duration=args.min_duration, **extra)
    except (ValueError, NotImplementedError, FileNotFoundError) as exc:
        print(f"fastrock fit: error: {exc}", file=sys.stderr)
        return 2
    print(fit.summary())
    from fastrock.cli.output import write_table, wrote
    wrote(write_table(fit.to_frame(), args))
    if args.png:
        from matplotlib.figure import Figure
        fig = Figure(figsize=(7, 4.5))
        ax = fig.add_subplot()
        plot_fit(fit, ax=ax)
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        wrote([args.png])
    return 0
