"""Figures: overturning spectrum maps and time histories (matplotlib).

matplotlib is imported lazily, with the Agg backend when no display is set.
"""
from __future__ import annotations

import os

import numpy as np

OUTCOME_COLORS = {
    "safe": "#e8eef5",
    "mode1": "#f4a261",
    "mode2": "#9b2226",
    "leaning": "#2a9d8f",
    "slide": "#8ecae6",
    "flight": "#6d597a",
    "failed": "#000000",
}
OUTCOME_LABELS = {
    "safe": "safe",
    "mode1": "overturn, mode 1 (after impact)",
    "mode2": "overturn, mode 2 (no impact)",
    "leaning": "leaning on wall",
    "slide": "slide (residual > tol)",
    "flight": "flight",
    "failed": "failed",
}


def _pyplot():
    import matplotlib
    if not os.environ.get("DISPLAY") and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_spectrum(df, ax=None, x="frequency_ratio", y="amplitude_ratio", title=None, legend=True):
    """Outcome map of a spectrum table (one sign), in the literature's axes
    a_p/(g tan alpha) against omega_p/p by default."""
    plt = _pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.8), constrained_layout=True)
    else:
        fig = ax.figure
    names = [k for k in OUTCOME_COLORS]
    code = {k: i for i, k in enumerate(names)}
    xs = np.unique(df[x].to_numpy())
    ys = np.unique(df[y].to_numpy())
    Z = np.full((ys.size, xs.size), np.nan)
    xi = np.searchsorted(xs, df[x].to_numpy())
    yi = np.searchsorted(ys, df[y].to_numpy())
    Z[yi, xi] = [code[o] for o in df["outcome"]]
    # an interrupted sweep leaves cells that never ran: drawn blank, named in the legend
    not_run = bool(np.isnan(Z).any())
    if Z.size:
        cmap = ListedColormap([OUTCOME_COLORS[k] for k in names])
        ax.pcolormesh(xs, ys, Z, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
    else:
        ax.text(0.5, 0.5, "no run finished", transform=ax.transAxes, ha="center", va="center")
    labels = {"frequency_ratio": r"$\omega_p/p$", "amplitude_ratio": r"$a_p/(g\tan\alpha)$",
              "frequency_hz": "f [Hz]", "amplitude_g": "A [g]"}
    ax.set_xlabel(labels.get(x, x))
    ax.set_ylabel(labels.get(y, y))
    if title:
        ax.set_title(title)
    if legend:
        present = [k for k in names if (df["outcome"] == k).any()]
        handles = [Patch(color=OUTCOME_COLORS[k], label=OUTCOME_LABELS[k]) for k in present]
        if not_run:
            handles.append(Patch(facecolor="white", edgecolor="0.5", label="not run (interrupted)"))
        if handles:
            ax.legend(handles=handles, loc="upper left", fontsize=8, framealpha=0.9)
    return fig


def plot_history(result, axes=None):
    """theta/alpha and ground acceleration against time, events marked."""
    plt = _pyplot()
    h = result.history
    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 5), constrained_layout=True)
    else:
        fig = axes[0].figure
    axes[0].plot(h["t"], h["a_g"] / result.body.g, lw=1)
    axes[0].set_ylabel(r"$a_g$ [g]")
    axes[1].plot(h["t"], h["theta_ratio"], lw=1)
    axes[1].set_ylabel(r"$\theta/\alpha$")
    axes[1].set_xlabel("t [s]")
    ev = result.events
    imp = ev[ev["event"].isin(["impact", "wall-impact"])]
    axes[1].plot(imp["t"], imp["theta"] / result.body.alpha, "k.", ms=3, label="impacts")
    axes[0].set_title(f"{result.status}  (kernel {result.kernel})")
    return fig
