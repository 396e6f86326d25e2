#!/usr/bin/env python
"""Effects cost nothing when off (issue 8): one benchmark for every contact effect.

Usage::

    python bench/bench_effects.py              # report + markdown table (about 5 min)
    python bench/bench_effects.py --quick      # smaller grids, fewer repeats
    pytest bench/bench_effects.py              # the 5% checks (and pytest-benchmark timings)

For each effect, three versions of the same cases:

=========  ===========================  ===================================  ==========================
effect     plain kernel                 effect switched off (same kernel)    effect on but inert
=========  ===========================  ===================================  ==========================
wall       no wall                      ``wall=None``                        an unreachable wall
                                                                             (gap = 2h: theta_w = inf)
friction   no friction                  ``Friction(inf)``                    ``Friction(1e3)`` (nothing
                                                                             slides: checked per cell)
=========  ===========================  ===================================  ==========================

Block b = 0.25 m, h = 1 m (alpha = 0.245, p = 2.67 rad/s), Housner e.  Three levels:

1. **Spectrum** (one-sine pulses toward the wall side, a_p/(g tan alpha) in [1, 6] x omega_p/p
   in [0.5, 10], 100 x 100, 10 s after the pulse, rtol 1e-8, early exit on as in
   ``overturning_spectrum``).  *plain*: ``rigid_sweep`` on inputs built here, through the same
   chunked ``run_sweep`` the front end uses; *off* and *inert*: ``overturning_spectrum`` (front
   end, DataFrame included).  The off ratio is the front end's overhead on the same kernel
   (target <= 1.05; the off scene's kernel is checked to *be* ``rigid_sweep``, and its statuses
   equal the plain kernel's).  Building the DataFrame costs the front end a few ms (3.6 ms at
   20 x 20, 9 ms at 100 x 100), so on grids much smaller than 100 x 100 of early-exit runs
   (about 70 us each) the off ratio exceeds 1.05 without any cost from the effect.
2. **Inert effect, kernel to kernel, early exit off** (40 x 40) (the friction kernel has no early
   decision and the wall kernel's differs, so with early exit the front-end inert ratio mixes
   in different amounts of work): ``rigid_sweep`` against ``rigid_wall_sweep`` /
   ``rigid_friction_sweep`` on the same cells, same statuses checked: the price of the extra
   event function (wall) or of the 4-state kernel (friction).
3. **One run** of the packaged El Centro record (31 s + 5 s): *plain*: ``Scene(block, record)``;
   *off*: the same scene with ``wall=None`` / ``Friction(inf)`` (target <= 1.05); *inert*: with
   the inert effect; and the kernel alone (``rigid_simulate`` on the same inputs, no tables),
   printed for scale.

All timings are CPU time of this process on one Numba thread (``time.process_time``: on a
shared machine it does not count the time other jobs hold the core), minimum over interleaved
repeats; the median is printed too, with the load average at start and end.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import ratios  # noqa: E402  (shared set-up: sweep inputs, threads, load average)

import fastrock as fr  # noqa: E402
from fastrock import Friction, Wall  # noqa: E402
from fastrock.running import registry
from fastrock.kernels import layout as L  # noqa: E402
from fastrock.running.outcomes import status_of  # noqa: E402
from fastrock.io.default_records import load_default_record  # noqa: E402
from fastrock.running.scene import Scene  # noqa: E402
from fastrock.running.sweep import run_sweep  # noqa: E402

BLOCK = fr.RigidBlock.rectangle(b=0.25, h=1.0)
AMPS = (1.0, 6.0)
FREQS = (0.5, 10.0)
T_AFTER = 10.0
RTOL = 1e-8                          # the library default
EFFECTS = {
    # effect: (keyword, switched off, inert)
    "wall": ("wall", None, Wall(gap=2 * BLOCK.h)),
    "friction": ("friction", Friction(math.inf), Friction(1e3)),
}


def grid(n):
    return np.linspace(*AMPS, n), np.linspace(*FREQS, n)


def cells(n):
    """(A, F) of the n x n grid in ``overturning_spectrum``'s order (amplitude fastest)."""
    amps, freqs = grid(n)
    F, A = np.meshgrid(freqs, amps, indexing="ij")
    return A.ravel(), F.ravel()


def kernel_inputs(n, effect_kw=None, early_exit=True):
    """(spec, inputs) of the sweep kernel selected for ``effect_kw`` on the n x n grid."""
    spec = registry.select(BLOCK, **(effect_kw or {}))
    A, F = cells(n)
    Y0, PAR, HDR, smp, OPT = ratios.sweep_inputs(BLOCK, A, F, sign=1, rtol=RTOL, early_exit=early_exit,
                                                 t_after=T_AFTER)
    PAR = np.tile(spec.par, (A.size, 1))
    return spec, (np.zeros((A.size, spec.n_state)), PAR, HDR, smp, OPT)


def chunked(spec, inputs):
    """The kernel through the front end's chunked driver (statuses, metrics)."""
    Y0, PAR, HDR, smp, OPT = inputs
    status, MET, _, _ = run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, None, False)
    return status, MET


def spectrum(n, effect_kw=None):
    amps, freqs = grid(n)
    return fr.overturning_spectrum(BLOCK, amps, freqs, sign=1, rtol=RTOL, t_after=T_AFTER, progress=False,
                                   **(effect_kw or {}))


def interleaved(fns, repeats):
    """``ratios.Timing`` (CPU and wall, min and median) of each callable, repeats interleaved
    so that a change in the machine's load hits every version alike; one warm-up call each."""
    for f in fns:
        f()
    cpu = [[] for _ in fns]
    wall = [[] for _ in fns]
    for _ in range(repeats):
        for i, f in enumerate(fns):
            c0, t0 = time.process_time(), time.perf_counter()
            f()
            wall[i].append(time.perf_counter() - t0)
            cpu[i].append(time.process_time() - c0)
    return [ratios.Timing(min(w), float(np.median(w)), min(c), float(np.median(c))) for w, c in zip(wall, cpu)]


# ---------------------------------------------------------------- 1. spectrum
def spectrum_level(effect, n, repeats, with_inert=True):
    kw, off, inert = EFFECTS[effect]
    spec0, inp0 = kernel_inputs(n)
    spec_off = registry.select(BLOCK, **{kw: off})
    from fastrock.kernels.rigid import rigid_sweep
    assert spec_off.name == "rigid" and spec_off.sweep is rigid_sweep, spec_off.name
    st0, _ = chunked(spec0, inp0)
    df_off = spectrum(n, {kw: off})
    assert df_off.attrs["kernel"] == "rigid"
    assert list(df_off["status"]) == [status_of(c) for c in st0], "off scene and plain kernel disagree"
    fns = [lambda: chunked(spec0, inp0), lambda: spectrum(n, {kw: off})]
    out = dict(n_runs=n * n)
    if with_inert:
        df_inert = spectrum(n, {kw: inert})
        assert df_inert.attrs["kernel"] != "rigid"
        out.update(inert_kernel=df_inert.attrs["kernel"],
                   outcomes_changed=int((df_inert["outcome"] != df_off["outcome"]).sum()))
        fns.append(lambda: spectrum(n, {kw: inert}))
    t = ratios.with_threads(1, lambda: interleaved(fns, repeats))
    out.update(plain=t[0], off=t[1], inert=t[2] if with_inert else None)
    return out


# ---------------------------------------------------------------- 2. inert, kernel to kernel
def inert_kernel_level(effect, n, repeats):
    kw, _off, inert = EFFECTS[effect]
    spec0, inp0 = kernel_inputs(n, early_exit=False)
    spec1, inp1 = kernel_inputs(n, {kw: inert}, early_exit=False)
    st0, met0 = chunked(spec0, inp0)
    st1, met1 = chunked(spec1, inp1)
    keep = np.ones(st0.size, bool)
    if effect == "friction":
        # an overturning block can slip near theta = pi/2 (N -> 0) even at mu = 1e3: drop those
        keep = (np.nan_to_num(met1[:, L.M_N_STICK_SLIP]) == 0) & (met1[:, L.M_MAX_SLIDE] == 0)
        idx = np.flatnonzero(keep)
        inp0 = tuple(a[idx] if a.ndim == 2 else a for a in inp0)
        inp1 = tuple(a[idx] if a.ndim == 2 else a for a in inp1)
    same = bool((st0[keep] == st1[keep]).all())
    t = ratios.with_threads(1, lambda: interleaved([lambda: chunked(spec0, inp0), lambda: chunked(spec1, inp1)],
                                                   repeats))
    nfev = (float(met0[keep, L.M_NFEV].sum()), float(met1[keep, L.M_NFEV].sum()))
    return dict(plain=t[0], inert=t[1], same_status=same, cells=int(keep.sum()), dropped=int((~keep).sum()),
                nfev_ratio=nfev[1] / nfev[0], kernel=spec1.name)


# ---------------------------------------------------------------- 3. one run
def scene(effect_kw=None):
    return Scene(BLOCK, excitation=load_default_record(), t_after=5.0, **(effect_kw or {}))


def direct_simulate(spec, hdr, smp, opt, cap=20000):
    from fastrock.kernels.hybrid import N_COUNTERS
    y = np.zeros(spec.n_state)
    met = np.zeros(L.N_MET)
    return spec.simulate(y, spec.par, hdr, smp, opt, np.empty(0), met, np.empty(cap),
                         np.empty((cap, spec.n_state)), np.empty((cap, 3), np.int64),
                         np.empty((max(1000, cap // 4), L.N_LOG)), np.zeros(N_COUNTERS, np.int64))


def run_level(effect, repeats):
    from fastrock.model import excitation as X
    kw, off, inert = EFFECTS[effect]
    s_plain, s_off, s_inert = scene(), scene({kw: off}), scene({kw: inert})
    assert s_plain.kernel == s_off.kernel == "rigid" and s_inert.kernel != "rigid"
    r0, r1, r2 = s_plain.run(), s_off.run(), s_inert.run()
    assert r0.metrics["nfev"] == r1.metrics["nfev"] and r0.status == r1.status
    spec = registry.select(BLOCK)
    rec = s_plain.excitation
    hdr, smp = X.to_header(BLOCK, rec, None)
    opt = s_plain.solver.options(X.end_time(BLOCK, rec, None) + 5.0, False)
    t = ratios.with_threads(1, lambda: interleaved(
        [lambda: direct_simulate(spec, hdr, smp, opt), s_plain.run, s_off.run, s_inert.run], repeats))
    return dict(kernel=t[0], plain=t[1], off=t[2], inert=t[3], status=r0.status, inert_status=r2.status,
                same_outcome=r0.outcome == r2.outcome)


# ---------------------------------------------------------------- 4. flexible body, friction off
FLEX = fr.FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, base_mass_ratio=0.1)


def flexible_spectrum(n, effect_kw=None):
    amps, freqs = grid(n)
    return fr.overturning_spectrum(FLEX, amps, freqs, sign=1, rtol=RTOL, t_after=T_AFTER, progress=False,
                                   **(effect_kw or {}))


def flexible_level(n, repeats):
    """A flexible body (with a 0.1 m base) without friction against the same body with
    ``Friction(inf)``: the same kernel (``flexible``, checked), the same statuses, and the time.
    No inert version: a large finite mu is not inert for this body, it meets lift-off (N < 0)
    and, at mu >~ 2, Painleve-type inconsistencies (README, flexible bodies with friction)."""
    d0 = flexible_spectrum(n)
    d1 = flexible_spectrum(n, {"friction": Friction(math.inf)})
    assert d0.attrs["kernel"] == d1.attrs["kernel"] == "flexible"
    assert list(d0["status"]) == list(d1["status"])
    t = ratios.with_threads(1, lambda: interleaved([lambda: flexible_spectrum(n),
                                                    lambda: flexible_spectrum(n, {"friction": Friction(math.inf)})],
                                                   repeats))
    return dict(plain=t[0], off=t[1], n_runs=n * n)


# ---------------------------------------------------------------- 5. the newer effects, off and inert
# (body, effect keyword arguments "off" (must select the plain model), "inert" (the effect's own
# model, never touching what it adds), plain model name)
NEWER = {
    "flexible wall": (FLEX, {"wall": None}, {"wall": Wall(gap=2.0 * FLEX.H)}, "flexible"),
    "flight": (BLOCK, {"friction": Friction(math.inf, lift_off="stop")},
               {"friction": Friction(math.inf, lift_off="flight")}, "rigid"),
}


def newer_spectrum(effect, n, kw):
    body = NEWER[effect][0]
    amps, freqs = grid(n)
    amps = amps * 0.5     # below lift-off: the flight effect stays inert (checked: no flights)
    return fr.overturning_spectrum(body, amps, freqs, sign=1, rtol=RTOL, t_after=T_AFTER, progress=False, **kw)


def newer_level(effect, n, repeats):
    """plain (no effect keyword), off (the effect switched off: the plain model, checked) and
    inert (the effect's model on cells where the effect never acts: same statuses, checked)."""
    body, off, inert, plain_model = NEWER[effect]
    d0 = newer_spectrum(effect, n, {})
    d1 = newer_spectrum(effect, n, off)
    d2 = newer_spectrum(effect, n, inert)
    assert d0.attrs["kernel"] == d1.attrs["kernel"] == plain_model
    assert list(d0.status) == list(d1.status)
    same = list(d0.outcome) == list(d2.outcome)
    t = ratios.with_threads(1, lambda: interleaved([lambda: newer_spectrum(effect, n, {}),
                                                    lambda: newer_spectrum(effect, n, off),
                                                    lambda: newer_spectrum(effect, n, inert)], repeats))
    return dict(plain=t[0], off=t[1], inert=t[2], inert_kernel=d2.attrs["kernel"], same_outcome=same)


# ---------------------------------------------------------------- report
def report(n=100, n_kernel=40, repeats=7, run_repeats=30):
    load0 = ratios.loadavg()
    print(f"fastrock {fr.__version__}, {os.cpu_count()} CPUs, load average {load0[0]:.2f} {load0[1]:.2f} "
          f"{load0[2]:.2f}; block b=0.25 h=1.0 (alpha={BLOCK.alpha:.4f}, p={BLOCK.p:.4f}); "
          f"CPU time, 1 thread, minimum of {repeats} (runs: {run_repeats}) interleaved repeats\n", flush=True)
    rows = []
    for effect in EFFECTS:
        s = spectrum_level(effect, n, repeats)
        k = inert_kernel_level(effect, n_kernel, repeats)
        r = run_level(effect, run_repeats)
        f = ratios.fmt_t
        print(f"[{effect}] 1. {n}x{n} spectrum (early exit): plain kernel {f(s['plain'].cpu)}, "
              f"off {f(s['off'].cpu)} (x{s['off'].cpu / s['plain'].cpu:.3f}), inert {f(s['inert'].cpu)} "
              f"(x{s['inert'].cpu / s['plain'].cpu:.3f}, kernel {s['inert_kernel']}, "
              f"outcomes changed {s['outcomes_changed']}); medians {f(s['plain'].cpu_med)}, "
              f"{f(s['off'].cpu_med)}, {f(s['inert'].cpu_med)}", flush=True)
        print(f"[{effect}] 2. inert kernel vs plain kernel, early exit off, {k['cells']} cells "
              f"({k['dropped']} dropped): {f(k['plain'].cpu)} vs {f(k['inert'].cpu)} "
              f"(x{k['inert'].cpu / k['plain'].cpu:.3f}; nfev x{k['nfev_ratio']:.3f}; same statuses "
              f"{k['same_status']})", flush=True)
        print(f"[{effect}] 3. El Centro run ({r['status']}): kernel alone {f(r['kernel'].cpu)}, plain scene "
              f"{f(r['plain'].cpu)}, off {f(r['off'].cpu)} (x{r['off'].cpu / r['plain'].cpu:.3f}), inert "
              f"{f(r['inert'].cpu)} (x{r['inert'].cpu / r['plain'].cpu:.3f}; {r['inert_status']})\n", flush=True)
        rows.append((effect, s, k, r))
    fl = flexible_level(min(n, 40), repeats)
    print(f"[flexible friction] {min(n, 40)}x{min(n, 40)} spectrum of a flexible body (omega_n/p = 9, "
          f"m_b = 0.1 m): no friction {ratios.fmt_t(fl['plain'].cpu)}, Friction(inf) {ratios.fmt_t(fl['off'].cpu)} "
          f"(x{fl['off'].cpu / fl['plain'].cpu:.3f}, same kernel and statuses)\n", flush=True)
    for effect in NEWER:
        nl = newer_level(effect, min(n, 40), repeats)
        f = ratios.fmt_t
        print(f"[{effect}] {min(n, 40)}x{min(n, 40)} spectrum: plain {f(nl['plain'].cpu)}, off "
              f"{f(nl['off'].cpu)} (x{nl['off'].cpu / nl['plain'].cpu:.3f}, same kernel and statuses), inert "
              f"{f(nl['inert'].cpu)} (x{nl['inert'].cpu / nl['plain'].cpu:.2f}, kernel {nl['inert_kernel']}, "
              f"same outcomes {nl['same_outcome']})\n", flush=True)
    load1 = ratios.loadavg()
    print(f"load average at the end {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}\n")
    print(markdown(rows, n, load0, load1))
    return rows


def markdown(rows, n, load0, load1):
    f = ratios.fmt_t
    out = [f"CPU time, 1 thread, minimum of interleaved repeats; load average {load0[0]:.1f} at start, "
           f"{load1[0]:.1f} at end.", "",
           "| effect | case | plain kernel | effect off (same kernel) | off / plain | inert effect | inert / plain |",
           "|---|---|---|---|---|---|---|"]
    for effect, s, k, r in rows:
        off_name, inert_name = {"wall": ("`wall=None`", "wall at gap 2h"),
                                "friction": ("`Friction(inf)`", "`Friction(1e3)`")}[effect]
        out.append(f"| {effect} | {n}×{n} spectrum, early exit | {f(s['plain'].cpu)} | {off_name}: "
                   f"{f(s['off'].cpu)} | **{s['off'].cpu / s['plain'].cpu:.3f}** | {inert_name}: "
                   f"{f(s['inert'].cpu)} | {s['inert'].cpu / s['plain'].cpu:.2f} |")
        out.append(f"| {effect} | {k['cells']} cells, kernels only, no early exit | {f(k['plain'].cpu)} | "
                   f"(same kernel) | – | {f(k['inert'].cpu)} | {k['inert'].cpu / k['plain'].cpu:.2f} |")
        out.append(f"| {effect} | El Centro, one run (`Scene.run`) | {f(r['plain'].cpu)} "
                   f"(kernel alone {f(r['kernel'].cpu)}) | {f(r['off'].cpu)} | "
                   f"**{r['off'].cpu / r['plain'].cpu:.3f}** | {f(r['inert'].cpu)} | "
                   f"{r['inert'].cpu / r['plain'].cpu:.2f} |")
    return "\n".join(out)


# ---------------------------------------------------------------- pytest
@pytest.mark.parametrize("effect", list(EFFECTS))
def test_effect_off_within_5_percent_of_plain_kernel(effect):
    s = spectrum_level(effect, 100, repeats=3, with_inert=False)
    r = run_level(effect, repeats=15)
    off_spec = s["off"].cpu / s["plain"].cpu
    off_run = r["off"].cpu / r["plain"].cpu
    print(f"\n{effect} off / plain (CPU, 1 thread): 100x100 spectrum {off_spec:.3f}, El Centro run {off_run:.3f}; "
          f"inert / plain run {r['inert'].cpu / r['plain'].cpu:.2f}")
    assert off_spec <= 1.05 and off_run <= 1.05


def test_flexible_friction_off_within_5_percent():
    fl = flexible_level(30, repeats=3)
    ratio = fl["off"].cpu / fl["plain"].cpu
    print(f"\nflexible Friction(inf) / no friction (CPU, 1 thread, 30x30 spectrum): {ratio:.3f}")
    assert ratio <= 1.05


@pytest.mark.parametrize("effect", list(NEWER))
def test_newer_effect_off_within_5_percent(effect):
    nl = newer_level(effect, 30, repeats=3)
    ratio = nl["off"].cpu / nl["plain"].cpu
    print(f"\n{effect} off / plain (CPU, 1 thread, 30x30 spectrum): {ratio:.3f}; inert / plain "
          f"{nl['inert'].cpu / nl['plain'].cpu:.2f} ({nl['inert_kernel']}, same outcomes {nl['same_outcome']})")
    assert ratio <= 1.05 and nl["same_outcome"]


@pytest.mark.parametrize("effect", list(EFFECTS))
def test_inert_effect_changes_no_outcome(effect):
    k = inert_kernel_level(effect, 15, repeats=2)
    assert k["same_status"] and k["cells"] > 0
    print(f"\n{effect} inert / plain kernel (no early exit, 1 thread): {k['inert'].cpu / k['plain'].cpu:.2f}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="20x20 grid and fewer repeats")
    a = ap.parse_args()
    report(n=60, n_kernel=20, repeats=3, run_repeats=10) if a.quick else report()
