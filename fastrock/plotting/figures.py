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


def get_pyplot():
    """matplotlib.pyplot, with the Agg backend when no display is set (imported on first use)."""
    import matplotlib
    if not os.environ.get("DISPLAY") and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_spectrum(df, ax=None, x="frequency_ratio", y="amplitude_ratio", title=None, legend=True):
    """Outcome map of a spectrum table (one sign), in the literature's axes
    a_p/(g tan alpha) against omega_p/p by default."""
    plt = get_pyplot()
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
    labels = {"frequency_ratio": r"$\omega_p/p$ [-]", "amplitude_ratio": r"$a_p/(g\tan\alpha)$ [-]",
              "frequency_hz": "f [Hz]", "amplitude_g": "A [g]", "omega_p": r"$\omega_p$ [rad/s]",
              "amplitude": r"$a_p$ [m/s$^2$]"}
    ax.set_xlabel(labels.get(x, x))
    ax.set_ylabel(labels.get(y, y))
    if title:
        ax.set_title(title, fontsize=9, wrap=True)
    if legend:
        # every class, so that maps side by side read with one legend; the count says which occur
        counts = df["outcome"].value_counts()
        handles = [Patch(facecolor=OUTCOME_COLORS[k], edgecolor="0.6",
                         label=f"{OUTCOME_LABELS[k]} ({int(counts.get(k, 0))})") for k in names]
        if not_run:
            handles.append(Patch(facecolor="white", edgecolor="0.5", label="not run (interrupted)"))
        if handles:
            ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                      framealpha=0.9, borderaxespad=0.0)
    return fig


def describe_body(body):
    """One line naming a body and its parameters, for figure titles."""
    kind = type(body).__name__
    if kind == "FlexibleBody":
        return (f"flexible body: alpha = {body.alpha:.3g} rad, p = {body.p:.3g} rad/s, "
                f"omega_n/p = {body.omega_n_over_p:.3g}, zeta = {body.zeta:.3g}")
    if kind == "RigidBody" and not body.is_symmetric:
        return (f"rigid body: alpha1/2 = {body.alpha1:.3g}/{body.alpha2:.3g} rad, "
                f"p1/2 = {body.p1:.3g}/{body.p2:.3g} rad/s, e12/21 = {body.e12:.3g}/{body.e21:.3g}")
    if kind == "RigidBody":
        body = body.to_block()
    size = (f"{2 * body.b:.3g} m x {2 * body.h:.3g} m, " if getattr(body, "b", None) and getattr(body, "h", None)
            else "")
    return f"rigid block {size}alpha = {body.alpha:.3g} rad, p = {body.p:.3g} rad/s, e = {body.e:.3g}"


def describe_excitation(exc):
    """One line naming an excitation, for figure titles."""
    if exc is None:
        return "free rocking"
    if type(exc).__name__ == "Pulse":
        unit = {"g_tan_alpha": "g tan(alpha)", "m/s2": "m/s$^2$"}.get(exc.amplitude_unit, exc.amplitude_unit)
        funit = {"omega_p/p": "p"}.get(exc.frequency_unit, exc.frequency_unit)
        sign = "" if exc.sign > 0 else "negative "
        return f"{sign}{exc.kind} pulse, {exc.amplitude:.3g} {unit}, {exc.frequency:.3g} {funit}"
    name = getattr(exc, "name", "") or type(exc).__name__
    pga = getattr(exc, "pga_g", None)
    return f"record {name}" + (f" (PGA {pga:.3g} g)" if pga is not None else "")


def _excitation_times(result, t0, t1):
    """Times that resolve the excitation over [t0, t1]: a fine grid, the record's samples and
    the stored rows."""
    t = [np.linspace(t0, t1, 4001), result.history["t"].to_numpy()]
    for exc in (result.excitation, getattr(result, "vertical", None)):
        dt = getattr(exc, "dt", None)
        if dt:
            start = getattr(exc, "t_start", 0.0)
            k0 = max(0, int(np.floor((t0 - start) / dt)))
            k1 = int(np.ceil((t1 - start) / dt))
            if k1 - k0 < 2_000_000:
                t.append(start + dt * np.arange(k0, k1 + 1))
    t = np.unique(np.concatenate(t))
    return t[(t >= t0) & (t <= t1)]


#: Event markers of the time-history figure: event name -> (label, marker style).
IMPACT_MARKERS = {
    "impact": ("ground impact", dict(marker="o", color="k", ms=3.5, ls="none")),
    "wall-impact": ("wall impact", dict(marker="s", color="#2a9d8f", ms=4, ls="none")),
    "landing": ("landing", dict(marker="v", color="#6d597a", ms=4, ls="none")),
}


def plot_history(result, axes=None):
    """Time history of one run: the ground acceleration (drawn from the excitation itself),
    theta/alpha with the impacts marked, and the base slip d [m] and the column deflection u [m]
    when the model has them.  The title names the body, the excitation and the outcome."""
    plt = get_pyplot()
    h = result.history
    panels = ["ground", "theta"] + [c for c in ("d", "u") if c in h.columns]
    if axes is None:
        fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(7.5, 2.0 + 1.6 * len(panels)),
                                 constrained_layout=True)
    else:
        fig = axes[0].figure
    axes = dict(zip(panels, np.atleast_1d(axes)))
    g = result.body.g
    t = h["t"].to_numpy()
    tg = _excitation_times(result, t[0], t[-1]) if t.size else t
    ag, av = result.ground_acceleration(tg)
    ax = axes["ground"]
    ax.plot(tg, ag / g, lw=0.9, label="horizontal $a_g$")
    if np.any(av != 0):
        ax.plot(tg, av / g, lw=0.9, label="vertical $a_v$")
        ax.legend(fontsize=7, loc="upper right")
    ax.set_ylabel("ground acc. [g]")
    ax = axes["theta"]
    ax.plot(t, h["theta_ratio"], lw=1, color="C0", label=r"$\theta/\alpha$")
    ax.axhline(1, color="0.6", lw=0.6, ls=":")
    ax.axhline(-1, color="0.6", lw=0.6, ls=":")
    ev = result.events
    for name, (label, style) in IMPACT_MARKERS.items():
        sel = ev[ev["event"] == name]
        if len(sel):
            ax.plot(sel["t"], sel["theta"] / result.body.alpha, label=f"{label} ({len(sel)})", **style)
    ax.set_ylabel(r"$\theta/\alpha$ [-]")
    ax.legend(fontsize=7, loc="upper right")
    if "d" in axes:
        axes["d"].plot(t, h["d"], lw=1, color="C2")
        axes["d"].set_ylabel("slip d [m]")
    if "u" in axes:
        axes["u"].plot(t, h["u"], lw=1, color="C3")
        axes["u"].set_ylabel("deflection u [m]")
    for ax in axes.values():
        ax.grid(True, alpha=0.3)
    axes[panels[-1]].set_xlabel("t [s]")
    axes["ground"].set_title(f"{describe_body(result.body)}\n{describe_excitation(result.excitation)}: "
                             f"{result.status}", fontsize=9)
    return fig
