#!/usr/bin/env python
"""Sliding of a flexible rocking body: the friction study of Farooghi-Mehr & Wittich (issue #6).

Body: alpha = 0.3, omega_n/p = 9, zeta = 0.05, full-contact impact map, rigid base block
m_b = 0.1 m (needed for a well-posed sliding problem, physics.md 4.4; used for every mu, the
no-sliding reference included), p = 2 rad/s (overturning does not depend on p; the slip d
scales with R0 = g/p^2 = 2.45 m, and with it the slide/safe split, whose 1 mm residual tolerance
is absolute).  One-sine pulses of sign +1,
a_p/(g tan alpha) = 1..10 and omega_p/p = 1..10.  Coulomb friction mu_s in
{0.4, 0.5, 0.6, 0.7, 0.8} with mu_k = mu_s, and mu = inf (no sliding degree of freedom).

Lift-off.  At omega_n/p = 9 the column vibration often needs a negative normal force at the
pivot while the body rocks.  The comparison maps use ``Friction(lift_off="hold")``: the pivot
is held on the ground, as the classic model (mu = inf) implicitly does, and the base slips
without friction while N < 0.  ``lift_off="stop"`` (physics.md 4.6) ends such runs with outcome
"flight"; figure (e) shows where.

Writes to OUT (default ``docs/``):

* ``friction_spectra.png``     (a) outcome maps, one per mu (hold), mu = inf boundary dashed
* ``friction_sliding.png``     (b) max |d| maps (overturned cells grey) and max |d| against mu
* ``friction_boundaries.png``  (c) overturning and mode-2 boundaries of every mu overlaid
* ``friction_histories.png``   (d) u/u_y, theta/alpha and d at omega_p/p = 1.3 and 1.5,
                                   mu_s = 0.4 (and mu = inf), a_p = 1.6 g tan(alpha)
* ``friction_liftoff.png``     (e) lift_off="stop" maps (where the classic model needs N < 0)
* ``friction_summary.csv``     outcome counts and areas per mu and lift-off rule

What it shows (80 x 80; README, "Friction study"): mu_s = 0.8 agrees with mu = inf on 99.1 % of
the cells and mode 2 is unchanged for mu_s >= 0.5, but lower friction does not lower the
vulnerability (overturned 44.9 % at mu = inf, 45.8 % at 0.8, 47.1 % at 0.4): mode 1 grows at
omega_p/p >= 4.  Every outcome that changes is in a run where the pivot needs tension (N < 0).

Usage: ``python examples/friction_study.py [--n 80] [--out docs] [--tables DIR]``
(80 x 80: about 4-5 minutes on 2 cores).
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

import fastrock as fr
from fastrock.plotting import OUTCOME_COLORS, OUTCOME_LABELS, _pyplot, plot_spectrum

ALPHA = 0.3
P = 2.0                      # rad/s; outcomes are independent of p, slip scales with g/p^2
OMEGA_N_OVER_P = 9.0
ZETA = 0.05
BASE_MASS_RATIO = 0.1
MUS = (0.4, 0.5, 0.6, 0.7, 0.8, math.inf)
AMP_RANGE = (1.0, 10.0)      # a_p / (g tan alpha)
FREQ_RANGE = (1.0, 10.0)     # omega_p / p
FREQ_SPLIT = 4.0             # "low" / "high" pulse frequencies for the mode-1 areas
AMP_SPLIT = 3.0              # "low" amplitudes for the mode-1 area
HISTORY_FREQS = (1.3, 1.5)
HISTORY_AMP = 1.6            # a_p / (g tan alpha) of the time histories
HISTORY_MU = 0.4
OVERTURNED = ("mode1", "mode2")
MU_COLORS = {0.4: "#d73027", 0.5: "#fc8d59", 0.6: "#91bfdb", 0.7: "#4575b4", 0.8: "#313695",
             math.inf: "k"}


def body():
    return fr.FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=OMEGA_N_OVER_P, zeta=ZETA,
                           base_mass_ratio=BASE_MASS_RATIO)


def friction(mu, lift_off="hold"):
    """Friction(mu_s = mu_k = mu); None for mu = inf (no sliding DOF at all)."""
    return fr.Friction(mu, lift_off=lift_off) if math.isfinite(mu) else None


def mu_label(mu):
    return r"$\mu=\infty$" if math.isinf(mu) else rf"$\mu_s$={mu:g}"


def grid(n_amp, n_freq=None):
    return (np.linspace(*AMP_RANGE, n_amp), np.linspace(*FREQ_RANGE, n_freq or n_amp))


def run_study(amps, freqs, mus=MUS, lift_offs=("hold", "stop"), progress=False, verbose=False):
    """Overturning spectra of the study body, one table per (mu, lift_off).

    mu = inf runs once, under the key (inf, "hold") (the classic model never checks N).
    Returns a dict {(mu, lift_off): DataFrame}; sliding columns are NaN for mu = inf.
    """
    b = body()
    tables = {}
    for mu in mus:
        for lo in (("hold",) if math.isinf(mu) else lift_offs):
            t0 = time.perf_counter()
            df = fr.overturning_spectrum(b, amps, freqs, sign=+1, friction=friction(mu, lo),
                                         progress=progress)
            for col in ("max_slide", "residual_slide", "lift_offs", "time_unloaded", "time_sliding",
                        "time_slide_rocking"):
                if col not in df:
                    df[col] = 0 if col == "lift_offs" else np.nan
            tables[(mu, lo)] = df
            if verbose:
                print(f"mu_s={mu:g} lift_off={lo}: {time.perf_counter() - t0:5.1f} s  "
                      f"{df.outcome.value_counts().to_dict()}", flush=True)
    return tables


def as_matrix(df, values, amps, freqs):
    """(amplitude x frequency) matrix of a column or of a boolean/array per row."""
    Z = np.full((amps.size, freqs.size), np.nan)
    ai = np.searchsorted(amps, df.amplitude_ratio.to_numpy())
    fi = np.searchsorted(freqs, df.frequency_ratio.to_numpy())
    Z[ai, fi] = np.asarray(values, float)
    return Z


def settled(outcome):
    """Outcome with "slide" counted as not overturned ("safe")."""
    return outcome.replace({"slide": "safe"})


def summarize(tables, amps, freqs):
    """One row per (mu, lift_off): outcome counts, mode areas (in the
    (omega_p/p, a_p/(g tan alpha)) plane), lift-offs, sliding, and the cells
    whose outcome differs from mu = inf."""
    da = (amps[-1] - amps[0]) / max(amps.size - 1, 1)
    dfq = (freqs[-1] - freqs[0]) / max(freqs.size - 1, 1)
    ref = settled(tables[(math.inf, "hold")].outcome)
    rows = []
    for (mu, lo), df in tables.items():
        o = df.outcome
        lifted = df.lift_offs.to_numpy() > 0
        low_f = df.frequency_ratio < FREQ_SPLIT
        low_a = df.amplitude_ratio < AMP_SPLIT
        m1 = o == "mode1"
        stays = o.isin(["safe", "slide"])
        changed = (settled(o) != ref).to_numpy()
        ms = df.max_slide[stays]
        rows.append({
            "mu_s": mu, "mu_k": mu, "lift_off": lo if math.isfinite(mu) else "-",
            "cells": len(df),
            **{k: int((o == k).sum()) for k in ("safe", "slide", "mode1", "mode2", "flight", "failed")},
            "overturned_fraction": round(float(o.isin(OVERTURNED).mean()), 4),
            "mode1_area": round(m1.sum() * da * dfq, 2),
            "mode2_area": round((o == "mode2").sum() * da * dfq, 2),
            f"mode1_area_freq_lt_{FREQ_SPLIT:g}": round((m1 & low_f).sum() * da * dfq, 2),
            f"mode1_area_freq_ge_{FREQ_SPLIT:g}": round((m1 & ~low_f).sum() * da * dfq, 2),
            f"mode1_area_amp_lt_{AMP_SPLIT:g}": round((m1 & low_a).sum() * da * dfq, 2),
            "cells_with_lift_off": int(lifted.sum()),
            "cells_sliding_in_full_contact": int((df.time_sliding.fillna(0) > 0).sum()),
            "cells_slide_rocking": int((df.time_slide_rocking.fillna(0) > 0).sum()),
            "changed_vs_inf": int(changed.sum()),
            "changed_vs_inf_with_lift_off": int((changed & lifted).sum()),
            "mode1_gained_vs_inf": int((m1 & (ref != "mode1")).sum()),
            "mode1_lost_vs_inf": int((~m1 & (ref == "mode1")).sum()),
            "median_max_slide_not_overturned_m": round(float(ms.median()), 5) if ms.notna().any() else np.nan,
            "p90_max_slide_not_overturned_m": round(float(ms.quantile(0.9)), 5) if ms.notna().any() else np.nan,
            "max_slide_not_overturned_m": round(float(ms.max()), 4) if ms.notna().any() else np.nan,
        })
    return pd.DataFrame(rows)


def boundary(ax, Z, freqs, amps, color, label, ls="-", lw=1.4):
    ax.contour(freqs, amps, Z, levels=[0.5], colors=[color], linewidths=lw, linestyles=ls)
    ax.plot([], [], color=color, ls=ls, lw=lw, label=label)


def overturn_matrix(df, amps, freqs, outcomes=OVERTURNED):
    return as_matrix(df, df.outcome.isin(outcomes), amps, freqs)


def fig_spectra(tables, amps, freqs, path):
    plt = _pyplot()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), sharex=True, sharey=True, constrained_layout=True)
    ref = tables[(math.inf, "hold")]
    for ax, mu in zip(axes.ravel(), MUS):
        df = tables[(mu, "hold")]
        plot_spectrum(df, ax=ax, legend=False, title=mu_label(mu) + ("" if math.isinf(mu) else
                                                                     r", $\mu_k=\mu_s$"))
        if math.isfinite(mu):
            boundary(ax, overturn_matrix(ref, amps, freqs), freqs, amps, "k", "", ls="--", lw=1.1)
    present = [k for k in OUTCOME_COLORS if any((tables[(m, "hold")].outcome == k).any() for m in MUS)]
    handles = [Patch(color=OUTCOME_COLORS[k], label=OUTCOME_LABELS[k]) for k in present]
    handles.append(Line2D([], [], color="k", ls="--", label=r"overturning boundary, $\mu=\infty$"))
    axes[0, 0].legend(handles=handles, loc="upper right", fontsize=7.5, framealpha=0.9)
    for ax in axes.ravel():
        ax.label_outer()
    fig.suptitle(rf"(a) Overturning spectra with sliding: $\alpha$={ALPHA}, $\omega_n/p$={OMEGA_N_OVER_P:g}, "
                 rf"$\zeta$={ZETA}, $m_b$={BASE_MASS_RATIO}m, one-sine pulses (+); pivot held when N<0")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_sliding(tables, amps, freqs, path):
    plt = _pyplot()
    from matplotlib.colors import ListedColormap, LogNorm
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), constrained_layout=True)
    finite = [m for m in MUS if math.isfinite(m)]
    vmax = max(np.nanmax(tables[(m, "hold")].max_slide[~tables[(m, "hold")].outcome.isin(OVERTURNED)])
               for m in finite)
    norm = LogNorm(vmin=1e-4, vmax=max(vmax, 1e-3))
    grey = ListedColormap(["#bdbdbd"])
    for ax, mu in zip(axes.ravel(), finite):
        df = tables[(mu, "hold")]
        over = df.outcome.isin(OVERTURNED).to_numpy()
        d = np.where(over, np.nan, np.maximum(df.max_slide.to_numpy(), 1e-4))
        im = ax.pcolormesh(freqs, amps, as_matrix(df, d, amps, freqs), norm=norm, cmap="viridis",
                           shading="nearest")
        ax.pcolormesh(freqs, amps, np.where(overturn_matrix(df, amps, freqs) > 0, 1.0, np.nan), cmap=grey,
                      shading="nearest")
        ax.set_title(mu_label(mu) + r": max $|d|$ (grey: overturned)")
        ax.set_xlabel(r"$\omega_p/p$")
        ax.set_ylabel(r"$a_p/(g\tan\alpha)$")
    fig.colorbar(im, ax=axes[:, :2].ravel().tolist() + [axes[0, 2]], shrink=0.8,
                 label=rf"max $|d|$ [m] (p = {P:g} rad/s; scales with $g/p^2$)")
    ax = axes[1, 2]
    for q, ls in ((0.5, "-"), (0.9, "--")):
        vals = [tables[(m, "hold")].max_slide[~tables[(m, "hold")].outcome.isin(OVERTURNED)].quantile(q)
                for m in finite]
        ax.plot(finite, vals, "o" + ls, color="k", label=f"{int(q * 100)}th percentile")
    ax.set_yscale("log")
    ax.set_xlabel(r"$\mu_s$ ($=\mu_k$)")
    ax.set_ylabel(r"max $|d|$ [m], cells not overturned")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("slip against friction")
    fig.suptitle(r"(b) Sliding spectra: max $|d|$ (base slip relative to the ground), pivot held when N<0")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_boundaries(tables, amps, freqs, path):
    plt = _pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True, constrained_layout=True)
    for mu in sorted(MUS, reverse=True):          # mu = inf first, underneath
        df = tables[(mu, "hold")]
        lw = 3.5 if math.isinf(mu) else 1.2
        ls = "-"
        color = "#bdbdbd" if math.isinf(mu) else MU_COLORS[mu]
        boundary(axes[0], overturn_matrix(df, amps, freqs), freqs, amps, color, mu_label(mu), ls, lw)
        boundary(axes[1], overturn_matrix(df, amps, freqs, ("mode2",)), freqs, amps, color, mu_label(mu), ls, lw)
    axes[0].set_title("overturning boundary (mode 1 or mode 2)")
    axes[1].set_title("mode-2 region boundary (overturning without impact)")
    for ax in axes:
        ax.set_xlabel(r"$\omega_p/p$")
        ax.set_xlim(*FREQ_RANGE)
        ax.set_ylim(*AMP_RANGE)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    axes[0].set_ylabel(r"$a_p/(g\tan\alpha)$")
    fig.suptitle(r"(c) Boundaries for every $\mu_s$ ($\mu_k=\mu_s$), pivot held when N<0")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def histories(amp=HISTORY_AMP, freqs=HISTORY_FREQS, mu=HISTORY_MU):
    """{(freq, mu): SimulationResult} at one amplitude, for mu and mu = inf."""
    b = body()
    out = {}
    for f in freqs:
        pulse = fr.Pulse(amp, f, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        for m in (mu, math.inf):
            out[(f, m)] = fr.simulate(b, pulse, friction=friction(m, "hold"))
    return out


def _shade(ax, t, mask, color):
    ax.fill_between(t, 0, 1, where=mask, transform=ax.get_xaxis_transform(), color=color, alpha=0.18,
                    lw=0, step="post")


def fig_histories(runs, path, amp=HISTORY_AMP, mu=HISTORY_MU):
    plt = _pyplot()
    freqs = sorted({f for f, _ in runs})
    fig, axes = plt.subplots(4, len(freqs), figsize=(12, 9), sharex="col", constrained_layout=True)
    for j, f in enumerate(freqs):
        r, r0 = runs[(f, mu)], runs[(f, math.inf)]
        h, h0 = r.history, r0.history
        t = h.t.to_numpy()
        col = axes[:, j]
        col[0].plot(t, h.a_g / (r.body.g * math.tan(r.body.alpha)), "k", lw=1)
        col[0].set_ylabel(r"$a_g/(g\tan\alpha)$")
        col[1].plot(t, h.u_ratio, color=MU_COLORS[mu], lw=1, label=mu_label(mu))
        col[1].plot(h0.t, h0.u_ratio, "k--", lw=0.8, label=mu_label(math.inf))
        col[1].set_ylabel(r"$u/u_y$")
        col[2].plot(t, h.theta_ratio, color=MU_COLORS[mu], lw=1.2, label=mu_label(mu))
        col[2].plot(h0.t, h0.theta_ratio, "k--", lw=0.8, label=mu_label(math.inf))
        col[2].set_ylabel(r"$\theta/\alpha$")
        col[2].set_ylim(-2.5, 2.5)
        col[3].plot(t, h.d * 100, color=MU_COLORS[mu], lw=1.2)
        col[3].set_ylabel(r"$d$ [cm]")
        col[3].set_xlabel("t [s]")
        contact = h.contact.to_numpy()
        ev = r.events
        lifts = list(zip(ev.t[ev.event == "lift-off-held"], ev.t[ev.event == "reload"]))
        for ax in col:
            _shade(ax, t, contact == "slide-rock", "#d73027")
            _shade(ax, t, contact == "slide", "#4575b4")
            for t0, t1 in lifts:
                ax.axvspan(t0, t1, color="#6d597a", alpha=0.5, lw=0)
            ax.grid(alpha=0.3)
        m = r.metrics
        col[0].set_title(rf"$\omega_p/p$={f:g}, $a_p$={amp:g} $g\tan\alpha$: {mu_label(mu)} {r.outcome} "
                         rf"(t={m['time_overturn']:.2f} s), $\mu=\infty$ {r0.outcome} "
                         rf"(t={r0.metrics['time_overturn']:.2f} s)", fontsize=9)
        col[3].set_title(f"max |d| = {100 * m['max_slide']:.1f} cm, slide-rocking {m['time_slide_rocking']:.2f} s, "
                         f"{m['stick_slip']} stick-slip, {m['lift_offs']} held lift-offs", fontsize=9)
        col[1].legend(fontsize=8, loc="upper left")
    fig.suptitle(rf"(d) {mu_label(mu)} ($\mu_k=\mu_s$, solid) against $\mu=\infty$ (dashed). Shading: "
                 r"red slide-rocking, blue sliding in full contact, purple N < 0 (pivot held, no friction)."
                 "\n" r"$u_y$: uplift deflection of the massless-base column", fontsize=10)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_liftoff(tables, amps, freqs, path):
    plt = _pyplot()
    from matplotlib.patches import Patch
    finite = [m for m in MUS if math.isfinite(m)]
    shown = [finite[0], finite[-1]]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), sharey=True, constrained_layout=True)
    for ax, mu in zip(axes, shown):
        df = tables[(mu, "stop")]
        plot_spectrum(df, ax=ax, legend=False, title=mu_label(mu) + r', lift_off="stop" (physics.md 4.6)')
        boundary(ax, overturn_matrix(tables[(mu, "hold")], amps, freqs), freqs, amps, "k", "", ls="--", lw=1)
    present = [k for k in OUTCOME_COLORS if any((tables[(m, "stop")].outcome == k).any() for m in shown)]
    from matplotlib.lines import Line2D
    axes[0].legend(handles=[Patch(color=OUTCOME_COLORS[k], label=OUTCOME_LABELS[k]) for k in present]
                   + [Line2D([], [], color="k", ls="--", label='overturning boundary, "hold"')],
                   loc="upper right", fontsize=7.5, framealpha=0.9)
    ax = axes[2]
    df = tables[(finite[0], "hold")]
    tu = np.where(df.lift_offs.to_numpy() > 0, df.time_unloaded.to_numpy(), np.nan)
    im = ax.pcolormesh(freqs, amps, as_matrix(df, tu, amps, freqs), cmap="magma_r", shading="nearest")
    fig.colorbar(im, ax=ax, label="time with N < 0 (pivot held) [s]")
    boundary(ax, overturn_matrix(df, amps, freqs), freqs, amps, "k", "", ls="--", lw=1)
    ax.set_title(mu_label(finite[0]) + r', "hold": time the pivot needs tension (blank: never)')
    for ax in axes:
        ax.set_xlabel(r"$\omega_p/p$")
    axes[0].set_ylabel(r"$a_p/(g\tan\alpha)$")
    fig.suptitle('(e) Lift-off: where the rocking flexible body needs a negative normal force (N < 0) at the '
                 'pivot; with lift_off="stop" those runs end in flight')
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(n=80, out="docs", tables_dir=None):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    amps, freqs = grid(n)
    t0 = time.perf_counter()
    tables = run_study(amps, freqs, verbose=True)
    print(f"spectra: {time.perf_counter() - t0:.0f} s for {len(tables)} maps of {amps.size}x{freqs.size}")
    summary = summarize(tables, amps, freqs)
    summary.to_csv(out / "friction_summary.csv", index=False)
    with pd.option_context("display.width", 250, "display.max_columns", 40):
        print(summary.to_string(index=False))
    if tables_dir:
        td = Path(tables_dir)
        td.mkdir(parents=True, exist_ok=True)
        for (mu, lo), df in tables.items():
            df.to_csv(td / f"friction_study_mu{mu:g}_{lo}.csv", index=False)
    fig_spectra(tables, amps, freqs, out / "friction_spectra.png")
    fig_sliding(tables, amps, freqs, out / "friction_sliding.png")
    fig_boundaries(tables, amps, freqs, out / "friction_boundaries.png")
    fig_liftoff(tables, amps, freqs, out / "friction_liftoff.png")
    runs = histories()
    fig_histories(runs, out / "friction_histories.png")
    for (f, mu), r in runs.items():
        m = r.metrics
        extra = (f", max|d|={m['max_slide']:.4f} m, slide-rocking {m['time_slide_rocking']:.3f} s, "
                 f"stick-slip {m['stick_slip']}, lift-offs {m['lift_offs']}") if math.isfinite(mu) else ""
        print(f"history omega_p/p={f:g} a_p={HISTORY_AMP:g} g tan(alpha) mu={mu:g}: {r.outcome}, "
              f"t_overturn={m['time_overturn']:.3f} s, max u/u_y={m['max_deformation_ratio']:.2f}{extra}")
    print(f"wrote {out}/friction_*.png and friction_summary.csv")
    return tables, summary


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=80, help="grid points per axis (default 80)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent.parent / "docs"),
                    help="output directory for the figures and the summary CSV (default docs/)")
    ap.add_argument("--tables", default=None, help="also write every spectrum table (CSV) to this directory")
    a = ap.parse_args()
    main(a.n, a.out, a.tables)
