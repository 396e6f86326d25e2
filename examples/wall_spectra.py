#!/usr/bin/env python
"""One-sided rocking beside a wall: the set-up of Mennitti, Maiorano & Aversa (2021).
==================================================================================

Block b = 0.5 m, h = 2.5 m (half-dimensions: p = 1.70 rad/s, alpha = 0.197 rad), Housner's
restitution e = 1 - 1.5 sin^2(alpha) = 0.942 (energy ratio r = e^2 = 0.888), an elastic tall
wall (e_w = 1) at a gap d = 1 cm or 10 cm, one-sine pulses of amplitude A = 0-5 g and
frequency f = 0-2.5 Hz, both signs.  The wall stands on the negative-theta side
(``Wall(side=-1)``), so a positive pulse (the ground first accelerates toward +x) throws the
block toward the wall and a negative one away from it.

Usage::

    python examples/wall_spectra.py [OUT_DIR] [--n 121]

writes to OUT_DIR (default ``out/``):

* ``wall_spectra_paper_axes.png``   one-sided maps, A [g] against f [Hz] (the paper's axes)
* ``wall_spectra_dimensionless.png`` the same maps, a_p/(g tan alpha) against omega_p/p
* ``wall_vs_two_sided.png``          two-sided and one-sided (1 cm, 10 cm) maps side by side
* ``wall_effect.png``                where the wall adds or removes overturning
* ``wall_gap_trend.png``             overturning and leaning fractions against the gap d (coarser
                                     grid), from 1 mm to d = 2h (the wall is never reached)
* ``wall_spectra.csv``               every run (column ``case``: two-sided, d=1cm, d=10cm)

and prints the overturning area of every case.
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

import fastrock as fr
from fastrock.plotting.figures import get_pyplot, plot_spectrum

BLOCK = fr.RigidBlock.rectangle(b=0.5, h=2.5)           # e: Housner's value
GAPS = {"d=1cm": 0.01, "d=10cm": 0.10}
SIGN_LABEL = {1: "toward the wall (+)", -1: "away from the wall (-)"}


def grid(n):
    """The paper's grid, A in g and f in Hz, without the degenerate zero row / column, as
    the ratios ``overturning_spectrum`` takes."""
    amp_g = np.linspace(5.0 / n, 5.0, n)
    f_hz = np.linspace(2.5 / n, 2.5, n)
    amp_ratio = amp_g / math.tan(BLOCK.alpha)           # a_p / (g tan alpha)
    freq_ratio = 2 * math.pi * f_hz / BLOCK.p           # omega_p / p
    return amp_ratio, freq_ratio


def spectra(n):
    amps, freqs = grid(n)
    out = []
    cases = {"two-sided": None, **{k: fr.Wall(gap=d) for k, d in GAPS.items()}}
    for name, wall in cases.items():
        t0 = time.perf_counter()
        df = fr.overturning_spectrum(BLOCK, amps, freqs, sign="both", wall=wall, progress=False)
        print(f"{name:>10}: {len(df)} runs in {time.perf_counter() - t0:.1f} s")
        df.insert(0, "case", name)
        out.append(df)
    return pd.concat(out, ignore_index=True)


def overturns(df):
    return df["outcome"].isin(["mode1", "mode2"]).to_numpy()


def summary(all_df):
    rows = []
    two = all_df[all_df["case"] == "two-sided"]
    for case, df in all_df.groupby("case", sort=False):
        for s in (1, -1):
            d = df[df["sign"] == s]
            base = overturns(two[two["sign"] == s])
            o = overturns(d)
            rows.append(dict(case=case, pulse=SIGN_LABEL[s], overturn_fraction=o.mean(),
                             mode1=(d["outcome"] == "mode1").mean(), mode2=(d["outcome"] == "mode2").mean(),
                             leaning=(d["outcome"] == "leaning").mean(),
                             added_by_wall=(o & ~base).mean(), removed_by_wall=(base & ~o).mean(),
                             min_overturn_amp_g=d.loc[o, "amplitude_g"].min() if o.any() else np.nan))
    return pd.DataFrame(rows)


def plot_maps(all_df, cases, x, y, path, title):
    plt = get_pyplot()
    fig, axes = plt.subplots(2, len(cases), figsize=(5.2 * len(cases), 8.6), constrained_layout=True,
                             squeeze=False)
    for j, case in enumerate(cases):
        for i, s in enumerate((1, -1)):
            d = all_df[(all_df["case"] == case) & (all_df["sign"] == s)]
            plot_spectrum(d, ax=axes[i, j], x=x, y=y, title=f"{case}, pulse {SIGN_LABEL[s]}",
                          legend=(j == 0))
    fig.suptitle(title)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_effect(all_df, path):
    """Cells where the block overturns only with the wall (the wall widens the region), only
    without it (narrows it), or in both."""
    plt = get_pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    colors = ["#e8eef5", "#9aa5b1", "#d62828", "#2a9d8f"]
    labels = ["safe in both", "overturns in both", "overturns only with the wall",
              "overturns only without the wall"]
    two = all_df[all_df["case"] == "two-sided"]
    fig, axes = plt.subplots(2, len(GAPS), figsize=(5.6 * len(GAPS), 8.6), constrained_layout=True)
    for j, case in enumerate(GAPS):
        for i, s in enumerate((1, -1)):
            a = two[two["sign"] == s]
            b = all_df[(all_df["case"] == case) & (all_df["sign"] == s)]
            code = np.where(overturns(a) & overturns(b), 1,
                            np.where(overturns(b), 2, np.where(overturns(a), 3, 0)))
            xs = np.unique(b["frequency_hz"])
            ys = np.unique(b["amplitude_g"])
            Z = np.full((ys.size, xs.size), np.nan)
            Z[np.searchsorted(ys, b["amplitude_g"]), np.searchsorted(xs, b["frequency_hz"])] = code
            ax = axes[i, j]
            ax.pcolormesh(xs, ys, Z, cmap=ListedColormap(colors), vmin=-0.5, vmax=3.5, shading="nearest")
            ax.set_xlabel("f [Hz]")
            ax.set_ylabel("A [g]")
            ax.set_title(f"{case} vs two-sided, pulse {SIGN_LABEL[s]}")
    axes[0, 0].legend(handles=[Patch(color=c, label=l) for c, l in zip(colors, labels)], loc="upper left",
                      fontsize=8, framealpha=0.9)
    fig.suptitle("Effect of an elastic rear wall on the overturning region (b = 0.5 m, h = 2.5 m)")
    fig.savefig(path, dpi=120)
    plt.close(fig)


TREND_GAPS = (0.001, 0.003, 0.01, 0.03, 0.1, 0.2, 0.4, 0.7, 1.0, 1.5, 2.5, 3.5, 5.0)


def gap_trend(n, path):
    """Fractions of the (A, f) grid that overturn / lean, against the gap."""
    amps, freqs = grid(n)
    kw = dict(sign="both", progress=False)
    two = fr.overturning_spectrum(BLOCK, amps, freqs, **kw)
    rows = []
    for d in TREND_GAPS:
        df = fr.overturning_spectrum(BLOCK, amps, freqs, wall=fr.Wall(gap=d), **kw)
        for s in (1, -1):
            x = df[df["sign"] == s]
            rows.append(dict(gap=d, sign=s, theta_w=fr.Wall(gap=d).limit_angle(BLOCK),
                             overturn=overturns(x).mean(), leaning=(x["outcome"] == "leaning").mean()))
    tr = pd.DataFrame(rows)
    plt = get_pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.6), constrained_layout=True)
    for s, c in ((1, "#d62828"), (-1, "#1d3557")):
        t = tr[tr["sign"] == s]
        ax.plot(t["gap"], t["overturn"], "o-", color=c, label=f"overturn, pulse {SIGN_LABEL[s]}")
        ax.plot(t["gap"], t["leaning"], "s--", color=c, ms=4, label=f"leaning, pulse {SIGN_LABEL[s]}")
        ax.axhline(overturns(two[two["sign"] == s]).mean(), color=c, lw=0.8, ls=":")
    d_alpha = 2 * BLOCK.h * math.sin(BLOCK.alpha)
    ax.axvline(d_alpha, color="0.5", lw=0.8)
    ax.text(d_alpha, 0.02, r" $\theta_w = \alpha$", color="0.4")
    ax.set_xscale("log")
    ax.set_xlabel("gap d [m]  (d = 2h = 5 m: the wall is never reached)")
    ax.set_ylabel("fraction of the (A, f) grid")
    ax.set_title("Gap trend; dotted: two-sided")
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return tr


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default="out", help="output directory (default out/)")
    ap.add_argument("--n", type=int, default=121, help="grid points per axis (default 121)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    print(f"block: alpha = {BLOCK.alpha:.4f} rad, p = {BLOCK.p:.4f} rad/s, e = {BLOCK.e:.4f} "
          f"(r = e^2 = {BLOCK.e ** 2:.4f}); theta_w = "
          + ", ".join(f"{k}: {fr.Wall(gap=d).limit_angle(BLOCK):.5f} rad" for k, d in GAPS.items()))
    all_df = spectra(args.n)
    all_df.to_csv(out / "wall_spectra.csv", index=False)
    setup = "one-sine pulses, b = 0.5 m, h = 2.5 m, Housner e, elastic wall"
    plot_maps(all_df, list(GAPS), "frequency_hz", "amplitude_g", out / "wall_spectra_paper_axes.png",
              f"One-sided rocking, {setup}")
    plot_maps(all_df, list(GAPS), "frequency_ratio", "amplitude_ratio", out / "wall_spectra_dimensionless.png",
              f"One-sided rocking (dimensionless axes), {setup}")
    plot_maps(all_df, ["two-sided", *GAPS], "frequency_hz", "amplitude_g", out / "wall_vs_two_sided.png",
              f"Two-sided and one-sided rocking, {setup}")
    plot_effect(all_df, out / "wall_effect.png")
    trend = gap_trend(max(21, args.n // 2), out / "wall_gap_trend.png")
    with pd.option_context("display.width", 160, "display.precision", 3):
        print(summary(all_df).to_string(index=False))
        print(trend.pivot(index="gap", columns="sign", values=["theta_w", "overturn", "leaning"]).to_string())
    print(f"wrote {out}/wall_spectra_paper_axes.png, wall_spectra_dimensionless.png, wall_vs_two_sided.png, "
          "wall_effect.png, wall_gap_trend.png, wall_spectra.csv")


if __name__ == "__main__":
    main()
