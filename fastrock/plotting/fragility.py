"""Fragility curves figure.
"""
from __future__ import annotations

import numpy as np

from fastrock.analyses.fragility import FragilityFit


IM_LABELS = {
    "pga_g": "PGA / g",
    "pgv": "PGV [m/s]",
    "pga_over_g_tan_alpha": r"PGA / (g tan $\alpha$)",
    "scale": "scale factor",
}


def plot_fragility(fits, ax=None, im_max=None, band=True, points=True, title=None):
    """Fragility curves with bootstrap bands and the observed fractions.

    Parameters
    ----------
    fits : FragilityFit or sequence of them
    ax : matplotlib Axes, optional
    im_max : float, optional
        Right end of the IM axis (default 1.1 x the largest level).
    band : bool
        Shade the bootstrap band (coverage ``fit.ci``).
    points : bool
        Mark the observed fraction of events at each IM value (size ~ trials).

    Returns
    -------
    matplotlib Figure
    """
    from fastrock.plotting.figures import get_pyplot
    if isinstance(fits, FragilityFit):
        fits = [fits]
    if ax is None:
        plt = get_pyplot()
        fig, ax = plt.subplots(figsize=(6.4, 4.6), constrained_layout=True)
    else:
        fig = ax.figure
    top = im_max or 1.1 * max(float(f.x.max()) for f in fits)
    grid = np.linspace(top / 400, top, 400)
    for i, f in enumerate(fits):
        color = f"C{i}"
        lab = f.label or f.event
        ax.plot(grid, f.probability(grid), color=color, lw=1.8,
                label=f"{lab}: $\\theta$={f.theta:.3g}, $\\beta$={f.beta:.2f}")
        if band and f.boot_theta.size:
            lo, hi = f.band(grid)
            ax.fill_between(grid, lo, hi, color=color, alpha=0.2, lw=0)
        if points:
            frac = f.k / f.n
            ax.scatter(f.x, frac, s=12 + 60 * f.n / f.n.max(), color=color, alpha=0.7,
                       edgecolor="none")
    ax.set_xlim(0, top)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(IM_LABELS.get(fits[0].im, fits[0].im))
    ax.set_ylabel("P(event | IM)")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    ax.legend(fontsize=8, loc="lower right", title_fontsize=8,
              title=f"bands: {fits[0].ci:.0%} bootstrap over records" if band else None)
    return fig


