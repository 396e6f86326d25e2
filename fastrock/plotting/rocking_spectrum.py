"""The rocking-spectrum figure (beta against Tp/Tm).
"""
from __future__ import annotations

import numpy as np

from fastrock.analyses.rocking_spectrum.definitions import upper_bound_beta


# ------------------------------------------------------------------- plot
WALL_STYLE = [("#1d3557", "o"), ("#e76f51", "s"), ("#2a9d8f", "D"), ("#8d5fd3", "P"),
              ("#6c757d", "X")]


def plot_rocking_spectrum(df, ax=None, curve=True, title=None, legend=True):
    """beta against Tp/Tm: one colour per record, one marker per wall setting.

    Exact points are filled.  Censored points (the grid gives only a bound) are hollow with an
    arrow toward the true value: down for an upper bound, up for a lower bound.  Maiorano et
    al.'s upper-bound curve for two-sided rocking, ``1.35 exp(-0.12 Tp/Tm)``, is drawn and named.

    Returns
    -------
    matplotlib Figure
    """
    from matplotlib.lines import Line2D
    from fastrock.plotting.figures import get_pyplot
    if ax is None:
        plt = get_pyplot()
        fig, ax = plt.subplots(figsize=(8.4, 5.2), constrained_layout=True)
    else:
        fig = ax.figure
    d = df[df["beta_bound"] != "incomplete"]
    xmax = float(np.nanmax(d["tp_over_tm"])) if len(d) else 10.0
    ymax = float(np.nanmax(d["beta"])) if len(d) else 1.5
    records = list(dict.fromkeys(d["record"])) if "record" in d else [""]
    walls = list(dict.fromkeys(d["wall"]))
    colors = {r: f"C{i % 10}" for i, r in enumerate(records)}
    markers = {w: WALL_STYLE[i % len(WALL_STYLE)][1] for i, w in enumerate(walls)}
    arrow = 0.06 * max(ymax, 1.0)
    censored = False
    for (rec, wall), grp in d.groupby(["record", "wall"], sort=False):
        color, marker = colors[rec], markers[wall]
        ex = grp[grp["beta_bound"] == "exact"]
        ax.plot(ex["tp_over_tm"], ex["beta"], ls="none", marker=marker, ms=5, color=color)
        for bound, sign in (("upper", -1.0), ("lower", 1.0)):
            bd = grp[grp["beta_bound"] == bound]
            if not len(bd):
                continue
            censored = True
            ax.plot(bd["tp_over_tm"], bd["beta"], ls="none", marker=marker, ms=5, mfc="white", color=color)
            for x, y in zip(bd["tp_over_tm"], bd["beta"]):
                ax.annotate("", xy=(x, max(y + sign * arrow, 0.0)), xytext=(x, y),
                            arrowprops=dict(arrowstyle="->", color=color, lw=0.8, shrinkA=3, shrinkB=0))
    handles = [Line2D([], [], ls="none", marker="o", color=colors[r], label=str(r)) for r in records]
    handles += [Line2D([], [], ls="none", marker=markers[w], color="0.35", label=str(w)) for w in walls]
    if censored:
        handles.append(Line2D([], [], ls="none", marker="o", mfc="white", color="0.35",
                              label="censored: bound only (arrow toward the true value)"))
    if curve:
        x = np.linspace(0.0, max(xmax * 1.05, 1.0), 300)
        line, = ax.plot(x, upper_bound_beta(x), "k--", lw=1.2)
        handles.append(Line2D([], [], color="k", ls="--", lw=1.2,
                              label=r"Maiorano et al. upper bound, $1.35\,e^{-0.12\,T_p/T_m}$"))
    ax.set_xlabel(r"$T_p/T_m$ [-]")
    ax.set_ylabel(r"$\beta = (b/h)_{min}\,g/\mathrm{PGA}$ [-]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title, fontsize=9)
    if legend:
        ax.legend(handles=handles, fontsize=7, framealpha=0.9, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0.0)
    return fig


