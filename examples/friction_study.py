#!/usr/bin/env python
"""Sliding of a flexible rocking body: the friction study of Farooghi-Mehr & Wittich (issue #6).
=============================================================================================

Body: alpha = 0.3, omega_n/p = 9, zeta = 0.05, full-contact impact map, rigid base block
m_b = 0.1 m (needed for a well-posed sliding problem, docs: theory/flexible_friction; used for every mu, the
no-sliding reference included), p = 2 rad/s (overturning does not depend on p; the slip d
scales with R0 = g/p^2 = 2.45 m, and with it the slide/safe split, whose 1 mm residual tolerance
is absolute).  One-sine pulses of sign +1,
a_p/(g tan alpha) = 1..10 and omega_p/p = 1..10.  Coulomb friction mu_s in
{0.4, 0.5, 0.6, 0.7, 0.8} with mu_k = mu_s, and mu = inf.

Lift-off.  At omega_n/p = 9 the column vibration often needs a negative normal force at the
pivot while the body rocks.  Three rules, each a map per mu:

* ``lift_off="flight"`` (the default, DEFAULT_LIFT_OFF; issue #13 item 4, kernels/flexible_flight.py):
  the pivot leaves the ground when N reaches 0 and the body (column and base) flies until a
  corner lands (plastic impact with Coulomb friction).  Its no-sliding reference is
  mu = inf with flight (``Friction(inf, lift_off="flight")``: it never slips, but flies).
* ``lift_off="hold"``: the pivot is held on the ground, as the classic model (mu = inf, no
  sliding degree of freedom) implicitly does, and the base slips without friction while N < 0.
  Its reference is the classic model.
* ``lift_off="stop"`` (docs: theory/flexible_friction, lift-off) ends a run with outcome "flight" where N first reaches 0.

Writes to OUT (default ``docs/``); the maps (a)-(d) use DEFAULT_LIFT_OFF:

* ``friction_spectra.png``     (a) outcome maps, one per mu, the reference's boundary dashed
* ``friction_sliding.png``     (b) ``max |d|`` maps (overturned cells grey) and ``max |d|`` against mu
* ``friction_boundaries.png``  (c) overturning and mode-2 boundaries of every mu overlaid
* ``friction_histories.png``   (d) u/u_y, theta/alpha and d at omega_p/p = 1.3 and 1.5,
                                   mu_s = 0.4 (and mu = inf), a_p = 1.6 g tan(alpha)
* ``friction_liftoff.png``     (e) lift_off="stop" maps (where the classic model needs N < 0)
* ``friction_flight_vs_hold.png`` (f) cells whose outcome differs between "flight" and "hold"
* ``friction_summary.csv``     outcome counts and areas per mu and lift-off rule

The committed figures (a), (c) and (e), from the earlier "hold" run of 80 x 80:

.. image:: /friction_spectra.png
   :alt: overturning spectra for each mu

.. image:: /friction_boundaries.png
   :alt: overturning boundaries of every mu

.. image:: /friction_liftoff.png
   :alt: lift-off maps

What it shows (80 x 80; docs: validation/reproductions, friction): under "hold", mu_s = 0.8 agrees with the
classic model on 99.1 % of the cells and mode 2 is unchanged for mu_s >= 0.5, but lower
friction does not lower the vulnerability (overturned 44.9 % at mu = inf, 45.8 % at 0.8,
47.1 % at 0.4); every outcome that changes is in a run where the pivot needs tension (N < 0).
With flight, those runs fly instead (``summarize`` and the docs page give the numbers).

Usage: ``python examples/friction_study.py [--n 80] [--out docs] [--tables DIR [--reuse]]
[--lift-off flight|hold]`` (80 x 80: about 8 minutes on 2 cores; ``--reuse`` redraws from the
tables a previous run wrote).
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

import fastrock as fr
from fastrock.plotting.figures import OUTCOME_COLORS, OUTCOME_LABELS, get_pyplot, plot_spectrum

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
LIFT_OFFS = ("flight", "hold", "stop")
DEFAULT_LIFT_OFF = "flight"
OVERTURNED = ("mode1", "mode2")
MU_COLORS = {0.4: "#d73027", 0.5: "#fc8d59", 0.6: "#91bfdb", 0.7: "#4575b4", 0.8: "#313695",
             math.inf: "k"}


def body():
    return fr.FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=OMEGA_N_OVER_P, zeta=ZETA,
                           base_mass_ratio=BASE_MASS_RATIO)


def friction(mu, lift_off=DEFAULT_LIFT_OFF):
    """Friction(mu_s = mu_k = mu, lift_off).  mu = inf: under "flight" the body that never slips
    but flies (Friction(inf, lift_off="flight")); otherwise None, the classic model (no sliding
    DOF, the pivot never checked)."""
    if math.isfinite(mu):
        return fr.Friction(mu, lift_off=lift_off)
    return fr.Friction(mu, lift_off="flight") if lift_off == "flight" else None


def inf_key(lift_off):
    """Key of the mu = inf map that a lift-off rule is compared with (its no-sliding reference):
    (inf, "flight") for flight, the classic model (inf, "hold") otherwise."""
    return (math.inf, "flight" if lift_off == "flight" else "hold")


def lift_off_label(lift_off):
    return {"flight": "free flight when N = 0", "hold": "pivot held when N<0",
            "stop": "stop when N = 0"}[lift_off]


def mu_label(mu):
    return r"$\mu=\infty$" if math.isinf(mu) else rf"$\mu_s$={mu:g}"


def grid(n_amp, n_freq=None):
    return (np.linspace(*AMP_RANGE, n_amp), np.linspace(*FREQ_RANGE, n_freq or n_amp))


def run_study(amps, freqs, mus=MUS, lift_offs=LIFT_OFFS, progress=False, verbose=False):
    """Overturning spectra of the study body, one table per (mu, lift_off).

    mu = inf runs under "flight" (key (inf, "flight")) if lift_offs has it, and as the classic
    model (key (inf, "hold"); it never checks N) if lift_offs has "hold" or "stop".
    Returns a dict {(mu, lift_off): DataFrame}.  Every table has the columns lift_offs /
    time_unloaded (held lift-offs, "hold") and flights / time_flight ("flight"), 0 where the
    rule has none; sliding columns are NaN for the classic model.
    """
    b = body()
    tables = {}
    for mu in mus:
        los = lift_offs if math.isfinite(mu) else tuple(dict.fromkeys(inf_key(lo)[1] for lo in lift_offs))
        for lo in los:
            t0 = time.perf_counter()
            df = fr.overturning_spectrum(b, amps, freqs, sign=+1, friction=friction(mu, lo),
                                         progress=progress)
            for col in ("max_slide", "residual_slide", "lift_offs", "time_unloaded", "time_sliding",
                        "time_slide_rocking"):
                if col not in df:
                    df[col] = 0 if col == "lift_offs" else np.nan
            if lo == "flight":
                # the flight kernel counts flights in the slot of the held lift-offs
                # (layout.M_N_FLIGHTS = M_N_LIFT_OFF, M_T_FLIGHT = M_T_UNLOADED)
                if "flights" not in df:
                    df["flights"], df["time_flight"] = df.lift_offs, df.time_unloaded
                df["lift_offs"], df["time_unloaded"] = 0, 0.0
            else:
                df["flights"], df["time_flight"] = 0, 0.0
            tables[(mu, lo)] = add_classic_modes(df, mu, lo)
            if verbose:
                print(f"mu_s={mu:g} lift_off={lo}: {time.perf_counter() - t0:5.1f} s  "
                      f"{df.outcome.value_counts().to_dict()}", flush=True)
    return tables


def classic_mode(events):
    """Overturning mode in the classic sense from a run's events: mode 1 if the body came back
    to its base before it overturned (a rocking impact at theta = 0, a flat landing or a landing
    on the other corner than the one it left), mode 2 if every landing was on the corner it had
    lifted off from (it skipped on its pivot while it fell).  Every landing counts as a ground
    impact in the kernel's ``impacts`` (and so in mode 1 / mode 2)."""
    pivot = 0
    for ev, pv in zip(events["event"], events["pivot"]):
        if ev == "impact":
            return "mode1"
        if ev == "flight":
            pivot = pv
        elif ev == "contact" and (pv == 0 or pv != pivot):
            return "mode1"
        elif ev == "overturn":
            break
    return "mode2"


def add_classic_modes(df, mu, lo):
    """Column ``outcome_classic``: the outcome with mode 1 / mode 2 in the classic sense
    (``classic_mode``), from a re-run (simulate) of every mode-1 cell that flew."""
    df["outcome_classic"] = df.outcome
    if lo != "flight":
        return df
    b = body()
    for i in np.flatnonzero(((df.outcome == "mode1") & (df.flights > 0)).to_numpy()):
        row = df.iloc[i]
        r = fr.simulate(b, fr.Pulse(row.amplitude_ratio, row.frequency_ratio, amplitude_unit="g_tan_alpha",
                                    frequency_unit="omega_p/p"), friction=friction(mu, lo), early_exit=True)
        if r.outcome == row.outcome:        # the same run as the sweep's
            df.iloc[i, df.columns.get_loc("outcome_classic")] = classic_mode(r.events)
    return df


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


def classic_view(df):
    """The table with ``outcome`` in the classic sense (``outcome_classic``: mode 2 keeps a body
    that skipped on its pivot while it fell)."""
    return df.assign(outcome=df.outcome_classic) if "outcome_classic" in df else df


def summarize(tables, amps, freqs):
    """One row per (mu, lift_off): outcome counts (as the kernel reports them, every landing an
    impact; mode1_classic / mode2_classic in the classic sense, ``classic_mode``), mode areas
    (in the (omega_p/p, a_p/(g tan alpha)) plane, classic sense), lift-offs and flights, sliding,
    and the cells whose outcome (slide counted as safe, classic modes) differs from the
    mu = inf map of the same lift-off family (``inf_key``) and, for "flight", from "hold"."""
    da = (amps[-1] - amps[0]) / max(amps.size - 1, 1)
    dfq = (freqs[-1] - freqs[0]) / max(freqs.size - 1, 1)
    classic = tables.get((math.inf, "hold"))
    rows = []
    for (mu, lo), df in tables.items():
        o = df.outcome
        oc = classic_view(df).outcome
        ref_df = tables.get(inf_key(lo), classic)
        ref = settled(classic_view(ref_df).outcome) if ref_df is not None else settled(oc)
        lifted = ((df.lift_offs > 0) | (df.flights > 0)).to_numpy()
        low_f = df.frequency_ratio < FREQ_SPLIT
        low_a = df.amplitude_ratio < AMP_SPLIT
        m1 = oc == "mode1"
        stays = o.isin(["safe", "slide"])
        changed = (settled(oc) != ref).to_numpy()
        ms = df.max_slide[stays]
        hold = (tables.get((mu, "hold")) if math.isfinite(mu) else classic) if lo == "flight" else None
        vs_hold = ((settled(oc) != settled(classic_view(hold).outcome)).to_numpy() if hold is not None
                   else np.zeros(len(df), bool))
        over = o.isin(OVERTURNED).to_numpy()
        over_h = hold.outcome.isin(OVERTURNED).to_numpy() if hold is not None else over
        rows.append({
            "mu_s": mu, "mu_k": mu, "lift_off": lo if math.isfinite(mu) or lo == "flight" else "-",
            "cells": len(df),
            **{k: int((o == k).sum()) for k in ("safe", "slide", "mode1", "mode2", "flight", "failed")},
            "mode1_classic": int((oc == "mode1").sum()),
            "mode2_classic": int((oc == "mode2").sum()),
            "overturned_fraction": round(float(o.isin(OVERTURNED).mean()), 4),
            "mode1_area": round(m1.sum() * da * dfq, 2),
            "mode2_area": round((oc == "mode2").sum() * da * dfq, 2),
            f"mode1_area_freq_lt_{FREQ_SPLIT:g}": round((m1 & low_f).sum() * da * dfq, 2),
            f"mode1_area_freq_ge_{FREQ_SPLIT:g}": round((m1 & ~low_f).sum() * da * dfq, 2),
            f"mode1_area_amp_lt_{AMP_SPLIT:g}": round((m1 & low_a).sum() * da * dfq, 2),
            "cells_with_lift_off": int(lifted.sum()),
            "cells_with_flight": int((df.flights > 0).sum()),
            "mean_flights_where_flying": round(float(df.flights[df.flights > 0].mean()), 2)
            if (df.flights > 0).any() else 0.0,
            "median_time_flight_s": round(float(df.time_flight[df.flights > 0].median()), 4)
            if (df.flights > 0).any() else 0.0,
            "changed_vs_hold": int(vs_hold.sum()),
            "overturned_vs_hold_gained": int((over & ~over_h).sum()),
            "overturned_vs_hold_lost": int((~over & over_h).sum()),
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


def _key(mu, lo):
    return inf_key(lo) if math.isinf(mu) else (mu, lo)


def fig_spectra(tables, amps, freqs, path, lo=DEFAULT_LIFT_OFF):
    plt = get_pyplot()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), sharex=True, sharey=True, constrained_layout=True)
    ref = tables[inf_key(lo)]
    classic = tables.get((math.inf, "hold"))
    for ax, mu in zip(axes.ravel(), MUS):
        df = classic_view(tables[_key(mu, lo)])
        plot_spectrum(df, ax=ax, legend=False, title=mu_label(mu) + (r", $\mu_k=\mu_s$" if math.isfinite(mu)
                                                                     else " (flies)" if lo == "flight" else ""))
        if math.isfinite(mu):
            boundary(ax, overturn_matrix(ref, amps, freqs), freqs, amps, "k", "", ls="--", lw=1.1)
        if lo == "flight" and classic is not None:
            boundary(ax, overturn_matrix(classic, amps, freqs), freqs, amps, "#2a9d8f", "", ls=":", lw=1.3)
    present = [k for k in OUTCOME_COLORS if any((classic_view(tables[_key(m, lo)]).outcome == k).any()
                                                for m in MUS)]
    handles = [Patch(color=OUTCOME_COLORS[k], label=OUTCOME_LABELS[k]) for k in present]
    handles.append(Line2D([], [], color="k", ls="--", label=r"overturning boundary, $\mu=\infty$"
                          + (" with flight" if lo == "flight" else "")))
    if lo == "flight" and classic is not None:
        handles.append(Line2D([], [], color="#2a9d8f", ls=":", label="overturning boundary, classic model"))
    axes[0, 0].legend(handles=handles, loc="upper right", fontsize=7.5, framealpha=0.9)
    for ax in axes.ravel():
        ax.label_outer()
    fig.suptitle(rf"(a) Overturning spectra with sliding: $\alpha$={ALPHA}, $\omega_n/p$={OMEGA_N_OVER_P:g}, "
                 rf"$\zeta$={ZETA}, $m_b$={BASE_MASS_RATIO}m, one-sine pulses (+); {lift_off_label(lo)}"
                 + ("\n(mode 2 in the classic sense: a body that skips on its pivot while it falls stays mode 2)"
                    if lo == "flight" else ""))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_sliding(tables, amps, freqs, path, lo=DEFAULT_LIFT_OFF):
    plt = get_pyplot()
    from matplotlib.colors import ListedColormap, LogNorm
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), constrained_layout=True)
    finite = [m for m in MUS if math.isfinite(m)]
    vmax = max(np.nanmax(tables[(m, lo)].max_slide[~tables[(m, lo)].outcome.isin(OVERTURNED)])
               for m in finite)
    norm = LogNorm(vmin=1e-4, vmax=max(vmax, 1e-3))
    grey = ListedColormap(["#bdbdbd"])
    for ax, mu in zip(axes.ravel(), finite):
        df = tables[(mu, lo)]
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
        vals = [tables[(m, lo)].max_slide[~tables[(m, lo)].outcome.isin(OVERTURNED)].quantile(q)
                for m in finite]
        ax.plot(finite, vals, "o" + ls, color="k", label=f"{int(q * 100)}th percentile")
    ax.set_yscale("log")
    ax.set_xlabel(r"$\mu_s$ ($=\mu_k$)")
    ax.set_ylabel(r"max $|d|$ [m], cells not overturned")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("slip against friction")
    fig.suptitle(r"(b) Sliding spectra: max $|d|$ (base slip relative to the ground; with flight: the pivot's "
                 r"displacement, jumps included), " + lift_off_label(lo))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_boundaries(tables, amps, freqs, path, lo=DEFAULT_LIFT_OFF):
    plt = get_pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True, constrained_layout=True)
    for mu in sorted(MUS, reverse=True):          # mu = inf first, underneath
        df = classic_view(tables[_key(mu, lo)])
        lw = 3.5 if math.isinf(mu) else 1.2
        ls = "-"
        color = "#bdbdbd" if math.isinf(mu) else MU_COLORS[mu]
        boundary(axes[0], overturn_matrix(df, amps, freqs), freqs, amps, color, mu_label(mu), ls, lw)
        boundary(axes[1], overturn_matrix(df, amps, freqs, ("mode2",)), freqs, amps, color, mu_label(mu), ls, lw)
    axes[0].set_title("overturning boundary (mode 1 or mode 2)")
    axes[1].set_title("mode-2 region boundary (overturning without impact"
                      + (", classic sense)" if lo == "flight" else ")"))
    for ax in axes:
        ax.set_xlabel(r"$\omega_p/p$")
        ax.set_xlim(*FREQ_RANGE)
        ax.set_ylim(*AMP_RANGE)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    axes[0].set_ylabel(r"$a_p/(g\tan\alpha)$")
    fig.suptitle(r"(c) Boundaries for every $\mu_s$ ($\mu_k=\mu_s$), " + lift_off_label(lo))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def histories(amp=HISTORY_AMP, freqs=HISTORY_FREQS, mu=HISTORY_MU, lo=DEFAULT_LIFT_OFF):
    """{(freq, mu): SimulationResult} at one amplitude, for mu and mu = inf."""
    b = body()
    out = {}
    for f in freqs:
        pulse = fr.Pulse(amp, f, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        for m in (mu, math.inf):
            out[(f, m)] = fr.simulate(b, pulse, friction=friction(m, lo))
    return out


def base_centre(h, b):
    """Horizontal displacement of the base centre O from a history: d in full contact and in
    flight (where the flight kernel stores x_O in d), d + s B (1 - cos theta) on pivot s."""
    rocking = h.contact.isin(["rock", "slide-rock"]).to_numpy()
    return h.d.to_numpy() + np.where(rocking, h["pivot"] * b.B * (1.0 - np.cos(h.theta)), 0.0)


def _shade(ax, t, mask, color):
    ax.fill_between(t, 0, 1, where=mask, transform=ax.get_xaxis_transform(), color=color, alpha=0.18,
                    lw=0, step="post")


def fig_histories(runs, path, amp=HISTORY_AMP, mu=HISTORY_MU, lo=DEFAULT_LIFT_OFF):
    plt = get_pyplot()
    freqs = sorted({f for f, _ in runs})
    fig, axes = plt.subplots(4, len(freqs), figsize=(12, 9), sharex="col", constrained_layout=True)
    inf_label = mu_label(math.inf) + (" (flies)" if lo == "flight" else "")
    for j, f in enumerate(freqs):
        r, r0 = runs[(f, mu)], runs[(f, math.inf)]
        h, h0 = r.history, r0.history
        t = h.t.to_numpy()
        col = axes[:, j]
        col[0].plot(t, h.a_g / (r.body.g * math.tan(r.body.alpha)), "k", lw=1)
        col[0].set_ylabel(r"$a_g/(g\tan\alpha)$")
        col[1].plot(t, h.u_ratio, color=MU_COLORS[mu], lw=1, label=mu_label(mu))
        col[1].plot(h0.t, h0.u_ratio, "k--", lw=0.8, label=inf_label)
        col[1].set_ylabel(r"$u/u_y$")
        col[2].plot(t, h.theta_ratio, color=MU_COLORS[mu], lw=1.2, label=mu_label(mu))
        col[2].plot(h0.t, h0.theta_ratio, "k--", lw=0.8, label=inf_label)
        col[2].set_ylabel(r"$\theta/\alpha$")
        col[2].set_ylim(-2.5, 2.5)
        col[3].plot(t, base_centre(h, r.body) * 100, color=MU_COLORS[mu], lw=1.2)
        col[3].set_ylabel(r"base centre $x_O$ [cm]")
        col[3].set_xlabel("t [s]")
        contact = h.contact.to_numpy()
        ev = r.events
        lifts = list(zip(ev.t[ev.event == "lift-off-held"], ev.t[ev.event == "reload"]))
        for ax in col:
            _shade(ax, t, contact == "slide-rock", "#d73027")
            _shade(ax, t, contact == "slide", "#4575b4")
            _shade(ax, t, contact == "flight", "#6d597a")
            for t0, t1 in lifts:
                ax.axvspan(t0, t1, color="#6d597a", alpha=0.5, lw=0)
            ax.grid(alpha=0.3)
        m = r.metrics
        col[0].set_title(rf"$\omega_p/p$={f:g}, $a_p$={amp:g} $g\tan\alpha$: {mu_label(mu)} {r.outcome} "
                         rf"(t={m['time_overturn']:.2f} s), {inf_label} {r0.outcome} "
                         rf"(t={r0.metrics['time_overturn']:.2f} s)", fontsize=9)
        extra = (f"{m['flights']} flights ({m['time_flight']:.2f} s)" if lo == "flight"
                 else f"{m['lift_offs']} held lift-offs")
        col[3].set_title(f"max |d| = {100 * m['max_slide']:.1f} cm, slide-rocking {m['time_slide_rocking']:.2f} s, "
                         f"{m['stick_slip']} stick-slip, {extra}", fontsize=9)
        col[1].legend(fontsize=8, loc="upper left")
    shade = ("purple in flight" if lo == "flight" else "purple N < 0 (pivot held, no friction)")
    fig.suptitle(rf"(d) {mu_label(mu)} ($\mu_k=\mu_s$, solid) against {inf_label} (dashed), "
                 f"{lift_off_label(lo)}. Shading: red slide-rocking, blue sliding in full contact, {shade}."
                 "\n" r"$u_y$: uplift deflection of the massless-base column", fontsize=10)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fig_liftoff(tables, amps, freqs, path):
    plt = get_pyplot()
    from matplotlib.patches import Patch
    finite = [m for m in MUS if math.isfinite(m)]
    shown = [finite[0], finite[-1]]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), sharey=True, constrained_layout=True)
    for ax, mu in zip(axes, shown):
        df = tables[(mu, "stop")]
        plot_spectrum(df, ax=ax, legend=False, title=mu_label(mu) + r', lift_off="stop"')
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


CHANGE_COLORS = ("#f0f0f0", "#d73027", "#4575b4", "#fdae61", "#91bfdb")
CHANGE_LABELS = ("same outcome", "overturns only with flight", "overturns only with hold",
                 "mode 1 <-> mode 2", "safe <-> slide")


def change_codes(flight, hold):
    """Per cell: 0 same outcome, 1 overturns only with flight, 2 only with hold, 3 both overturn
    in different modes, 4 safe <-> slide."""
    a, b = flight.outcome.to_numpy(), hold.outcome.to_numpy()
    oa, ob = np.isin(a, OVERTURNED), np.isin(b, OVERTURNED)
    code = np.zeros(a.size, int)
    code[(a != b) & oa & ob] = 3
    code[(a != b) & ~oa & ~ob] = 4
    code[oa & ~ob] = 1
    code[~oa & ob] = 2
    return code


def fig_flight_vs_hold(tables, amps, freqs, path):
    plt = get_pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    shown = [m for m in (0.4, 0.8, math.inf) if (m, "flight") in tables or math.isinf(m)]
    fig, axes = plt.subplots(1, len(shown) + 1, figsize=(5 * len(shown) + 5, 4.8), sharey=True,
                             constrained_layout=True)
    cmap = ListedColormap(CHANGE_COLORS)
    for ax, mu in zip(axes, shown):
        fl, ho = classic_view(tables[_key(mu, "flight")]), tables[_key(mu, "hold")]
        code = change_codes(fl, ho)
        ax.pcolormesh(freqs, amps, as_matrix(fl, code, amps, freqs), cmap=cmap, vmin=-0.5, vmax=4.5,
                      shading="nearest")
        boundary(ax, overturn_matrix(ho, amps, freqs), freqs, amps, "k", "", ls="--", lw=1)
        name = "classic model" if math.isinf(mu) else '"hold"'
        ax.set_title(mu_label(mu) + f': "flight" against {name} ({int((code > 0).sum())} cells differ)',
                     fontsize=9)
        ax.set_xlabel(r"$\omega_p/p$")
    axes[0].set_ylabel(r"$a_p/(g\tan\alpha)$")
    axes[0].legend(handles=[Patch(color=c, label=lab) for c, lab in zip(CHANGE_COLORS, CHANGE_LABELS)],
                   loc="upper right", fontsize=7.5, framealpha=0.9)
    ax = axes[-1]
    df = tables[(shown[0], "flight")]
    tf = np.where(df.flights.to_numpy() > 0, df.time_flight.to_numpy(), np.nan)
    im = ax.pcolormesh(freqs, amps, as_matrix(df, tf, amps, freqs), cmap="magma_r", shading="nearest")
    fig.colorbar(im, ax=ax, label="time in flight [s]")
    boundary(ax, overturn_matrix(df, amps, freqs), freqs, amps, "k", "", ls="--", lw=1)
    ax.set_title(mu_label(shown[0]) + ', "flight": time in flight (blank: never flies)', fontsize=9)
    ax.set_xlabel(r"$\omega_p/p$")
    fig.suptitle('(f) Free flight against the held pivot: cells whose outcome changes (modes in the classic '
                 'sense; dashed: overturning boundary with the pivot held)')
    fig.savefig(path, dpi=100)
    plt.close(fig)


def load_tables(folder):
    """The tables ``main`` wrote with ``tables_dir`` (friction_study_mu<mu>_<lift_off>.csv)."""
    tables = {}
    for f in sorted(Path(folder).glob("friction_study_mu*_*.csv")):
        mu, lo = f.stem[len("friction_study_mu"):].rsplit("_", 1)
        tables[(float(mu), lo)] = pd.read_csv(f)
    return tables


def main(n=80, out="docs", tables_dir=None, lift_off=DEFAULT_LIFT_OFF, reuse=False):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    amps, freqs = grid(n)
    t0 = time.perf_counter()
    if reuse and tables_dir:
        tables = load_tables(tables_dir)
        tables_dir = None
    else:
        tables = run_study(amps, freqs, verbose=True)
    print(f"spectra: {time.perf_counter() - t0:.0f} s for {len(tables)} maps of {amps.size}x{freqs.size}")
    summary = summarize(tables, amps, freqs)
    summary.to_csv(out / "friction_summary.csv", index=False)
    with pd.option_context("display.width", 250, "display.max_columns", 60):
        print(summary.to_string(index=False))
    if tables_dir:
        td = Path(tables_dir)
        td.mkdir(parents=True, exist_ok=True)
        for (mu, lo), df in tables.items():
            df.to_csv(td / f"friction_study_mu{mu:g}_{lo}.csv", index=False)
    fig_spectra(tables, amps, freqs, out / "friction_spectra.png", lift_off)
    fig_sliding(tables, amps, freqs, out / "friction_sliding.png", lift_off)
    fig_boundaries(tables, amps, freqs, out / "friction_boundaries.png", lift_off)
    fig_liftoff(tables, amps, freqs, out / "friction_liftoff.png")
    fig_flight_vs_hold(tables, amps, freqs, out / "friction_flight_vs_hold.png")
    runs = histories(lo=lift_off)
    fig_histories(runs, out / "friction_histories.png", lo=lift_off)
    for (f, mu), r in runs.items():
        m = r.metrics
        extra = (f", max|d|={m['max_slide']:.4f} m, slide-rocking {m['time_slide_rocking']:.3f} s, "
                 f"stick-slip {m['stick_slip']}, lift-offs {m['lift_offs']}") if "max_slide" in m else ""
        if "flights" in m:
            extra += f", flights {m['flights']} ({m['time_flight']:.3f} s, max jump {1000 * m['max_jump']:.1f} mm)"
        print(f"history omega_p/p={f:g} a_p={HISTORY_AMP:g} g tan(alpha) mu={mu:g} ({lift_off}): {r.outcome}, "
              f"t_overturn={m['time_overturn']:.3f} s, max u/u_y={m['max_deformation_ratio']:.2f}{extra}")
    print(f"wrote {out}/friction_*.png and friction_summary.csv")
    return tables, summary


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=80, help="grid points per axis (default 80)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent.parent / "docs"),
                    help="output directory for the figures and the summary CSV (default docs/)")
    ap.add_argument("--tables", default=None, help="also write every spectrum table (CSV) to this directory")
    ap.add_argument("--lift-off", default=DEFAULT_LIFT_OFF, choices=("flight", "hold"),
                    help=f"lift-off rule of the maps (a)-(d) (default {DEFAULT_LIFT_OFF})")
    ap.add_argument("--reuse", action="store_true",
                    help="read the tables from --tables instead of running the spectra (figures, summary)")
    a = ap.parse_args()
    main(a.n, a.out, a.tables, a.lift_off, a.reuse)
