"""Options and helpers shared by the subcommands: output files, grids, Ctrl-C.
"""
from __future__ import annotations

import sys

import numpy as np


#: Exit code of a command stopped by Ctrl-C (128 + SIGINT), in every command.
EXIT_INTERRUPTED = 130
#: Most points of one grid option (--n-amp ...) and most runs of one grid.
MAX_GRID_POINTS = 100_000
MAX_GRID_RUNS = 10_000_000


def interrupted_exit(done, total, what="runs", written=()):
    """Close a command that Ctrl-C stopped: one line on stderr naming how many
    of the ``total`` ``what`` finished and the files written with them (the
    command writes its table and figure of the finished part before calling
    this).  Returns EXIT_INTERRUPTED."""
    files = [str(f) for f in written if f]
    tail = f"; wrote {' and '.join(files)} with them" if files and done else "; nothing written"
    print(f"fastrock: interrupted: {done} of {total} {what} finished{tail}", file=sys.stderr)
    return EXIT_INTERRUPTED


def add_output_options(p, *, png=None, csv=None, figure="the figure", table="the table", parquet=True):
    """The same output options on every command that writes: ``--png`` (a figure), ``--csv``
    and ``--parquet`` (its table).  ``png``/``csv`` are the defaults (None: not written)."""
    p.add_argument("--png", default=png, metavar="FILE",
                   help=f"write {figure} as PNG (default: {png or 'not written'})")
    if csv is not False:
        p.add_argument("--csv", default=csv, metavar="FILE",
                       help=f"write {table} as CSV (default: {csv or 'not written'})")
    if parquet:
        p.add_argument("--parquet", default=None, metavar="FILE",
                       help=f"write {table} as Parquet, needs pyarrow (default: not written)")


def write_table(df, args, csv=None, parquet=None):
    """Write ``df`` to the ``--csv`` and ``--parquet`` files of ``args`` (or the given paths);
    returns the paths written."""
    csv = csv if csv is not None else getattr(args, "csv", None)
    parquet = parquet if parquet is not None else getattr(args, "parquet", None)
    out = []
    if csv:
        df.to_csv(csv, index=False)
        out.append(str(csv))
    if parquet:
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise ValueError("--parquet needs pyarrow (pip install pyarrow)") from None
        flat = df.copy(deep=False)
        flat.attrs = {}          # attrs may hold objects Parquet metadata cannot store
        flat.to_parquet(parquet, index=False)
        out.append(str(parquet))
    return out


def wrote(paths):
    """One line naming the files written (nothing with --quiet: stdout is closed then)."""
    paths = [str(f) for f in paths if f]
    if paths:
        print(f"wrote {' and '.join(paths)}")


def grid_option(prefix, lo, hi, n, positive=True, n_option=None):
    """``np.linspace(lo, hi, n)`` from the options ``{prefix}-min``, ``{prefix}-max`` and
    ``n_option`` (default ``--n-{prefix}``), each checked and named in the error."""
    from fastrock import _validate as V
    n_option = n_option or "--n-" + prefix.lstrip("-")
    check = V.positive if positive else V.non_negative
    lo, hi = check(f"{prefix}-min", lo), check(f"{prefix}-max", hi)
    if lo > hi:
        raise ValueError(f"{prefix}-min = {lo:g} is above {prefix}-max = {hi:g}")
    return np.linspace(lo, hi, V.integer(n_option, n, 1, MAX_GRID_POINTS))


