"""Work-precision figure (fastrock.analyses.accuracy).
"""
from __future__ import annotations

import numpy as np

from fastrock.analyses.accuracy import CLOCKS, MEASURE_LABELS, default_measures


def plot_work_precision(df, measure=None, clock="wall"):
    """Log-log error against time per run: one column per model/excitation, one row per
    measure (``measure``: a column name or a list of them; default :func:`default_measures`).
    ``clock``: "wall" (time_per_run) or "cpu" (cpu_per_run) on the x axis.  Zero errors are
    drawn at 1e-16; a measure a family does not have leaves its panel empty."""
    from fastrock.plotting.figures import get_pyplot
    plt = get_pyplot()
    measures = default_measures(df) if measure is None else \
        ((measure,) if isinstance(measure, str) else tuple(measure))
    for m in measures:
        if m not in df:
            raise ValueError(f"unknown measure {m!r}: the table has {', '.join(c for c in df if c.startswith('err_') or c == 'outcome_mismatch')}")
    if clock not in CLOCKS:
        raise ValueError(f"clock must be 'wall' or 'cpu', got {clock!r}")
    tcol, tlabel = CLOCKS[clock]
    if "threads" in df and df["threads"].nunique() == 1 and int(df["threads"].iloc[0]) > 0:
        n = int(df["threads"].iloc[0])
        tlabel += f", {n} thread" + ("s" if n > 1 else "")
    keys = list(df.groupby(["model", "excitation"], sort=False).groups)
    fig, axes = plt.subplots(len(measures), len(keys), figsize=(4.6 * len(keys), 4 * len(measures)),
                             squeeze=False, constrained_layout=True)
    for row, meas in zip(axes, measures):
        for ax, (model, exc) in zip(row, keys):
            sub = df[(df.model == model) & (df.excitation == exc)]
            ax.set_title(f"{model}, {exc}")
            ax.set_xlabel(tlabel)
            ax.set_ylabel(MEASURE_LABELS.get(meas, meas))
            if sub[meas].isna().all():
                ax.text(0.5, 0.5, "n/a", transform=ax.transAxes, ha="center")
                continue
            for (mode, bp), g in sub.groupby(["mode", "record_breakpoints"]):
                lab = ("adaptive rtol" if mode == "rtol" else "fixed dt") + (
                    "" if exc in ("pulse", "free") else (" (breakpoints)" if bp else " (no bp)"))
                err = np.maximum(g[meas].to_numpy(dtype=float), 1e-16)
                ax.loglog(g[tcol], err, "o-" if mode == "rtol" else "s--", label=lab, ms=4)
                for x, y, v in zip(g[tcol], err, g["setting"]):
                    ax.annotate(f"{v:g}", (x, y), fontsize=6, alpha=0.7)
            ax.legend(fontsize=7)
    return fig


