#!/usr/bin/env python
"""Cost of the wall effect (issue 3): a scene without a wall pays nothing.

Usage::

    pytest bench/bench_wall.py                 # pytest-benchmark table + the 5% check
    python bench/bench_wall.py                 # plain report of the ratios
    python bench/bench_wall.py --compile       # also first-call compile / cache-load times

Measured, on the Mennitti et al. block (b = 0.5 m, h = 2.5 m), one-sine pulses, an explicit
48 x 48 grid (a_p/(g tan alpha) in [1.3, 25], omega_p/p in [0.2, 9.2]), both signs, early exit
on (the sweep default), rtol 1e-8:

1. ``overturning_spectrum(wall=None)`` against ``rigid_sweep`` called on the same kernel
   inputs, through the same chunked ``run_sweep`` (the wall-free scene runs the plain rigid
   kernel, so the ratio is the front end's table-building overhead; target: within 5%), and
   against one unchunked ``rigid_sweep`` call (printed: the cost of chunking, which gives the
   progress bar and Ctrl-C safety).
2. ``simulate(wall=None)`` against a direct ``rigid_simulate`` call (one run with its time
   history; the front end builds two DataFrames, so this ratio is larger and printed only).
3. An inert wall (gap >= 2h, never reached) against no wall, kernel to kernel, one thread,
   without early exit, so that both do the same work (same statuses, checked): the price of
   the wall kernel's extra event function when the wall plays no part.  With early exit the
   two-sided kernel stops some runs earlier (its early decision does not check |theta| < alpha
   and declares some runs that go on to overturn safe; the wall kernel does), so a comparison
   with early exit mixes in that difference; it is printed too.
4. Real walls, d = 1 cm and 10 cm, through ``overturning_spectrum``: more events (wall
   impacts), printed for information.
5. ``--compile``: first call of the wall kernels in a fresh ``NUMBA_CACHE_DIR`` (compile)
   and in a second process on that cache (load).

Timings are the minimum over interleaved repeats: CPU time of the process for the one-thread
comparisons (robust on a shared machine), wall time otherwise; the load average is printed.
"""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import pytest

import fastrock as fr
from fastrock.running import registry
from fastrock.kernels import layout as L
from fastrock.running.solver import Solver

BLOCK = fr.RigidBlock.rectangle(b=0.5, h=2.5)
AMPS = np.linspace(1.3, 25.0, 48)
FREQS = np.linspace(0.2, 9.2, 48)
SIGNS = (1, -1)
T_AFTER = 10.0
INERT = fr.Wall(gap=2 * BLOCK.h)
WALLS = {"none": None, "inert": INERT, "1cm": fr.Wall(gap=0.01), "10cm": fr.Wall(gap=0.10)}
SIM_PULSE = fr.Pulse(0.3, 1.0)                     # safe, rocks ~10 s: many impacts


def spectrum(wall):
    return fr.overturning_spectrum(BLOCK, AMPS, FREQS, sign=list(SIGNS), wall=wall, progress=False,
                                   t_after=T_AFTER)


def kernel_inputs(wall=None):
    """The arrays ``overturning_spectrum`` hands to the sweep kernel (same order)."""
    spec = registry.select(BLOCK, wall)
    S, F, A = np.meshgrid(np.array(SIGNS, float), FREQS, AMPS, indexing="ij")
    S, F, A = S.ravel(), F.ravel(), A.ravel()
    n = A.size
    omega = F * BLOCK.p
    dur = 2 * np.pi / omega
    HDR = np.zeros((n, L.N_EXC))
    HDR[:, L.X_KIND] = L.EXC_ONE_SINE
    HDR[:, L.X_AMP] = A * BLOCK.g * math.tan(BLOCK.alpha)
    HDR[:, L.X_OMEGA] = omega
    HDR[:, L.X_SIGN] = S
    HDR[:, L.X_DUR] = dur
    OPT = np.tile(Solver().options(0.0, True), (n, 1))
    OPT[:, L.O_T_END] = dur + T_AFTER
    PAR = np.tile(spec.par, (n, 1))
    return spec, (np.zeros((n, 2)), PAR, HDR, np.zeros(1), OPT)


def direct_sweep(spec, inputs):
    Y0, PAR, HDR, smp, OPT = inputs
    n = Y0.shape[0]
    st = np.empty(n, np.int64)
    met = np.empty((n, L.N_MET))
    yf = np.empty_like(Y0)
    spec.sweep(Y0, PAR, HDR, smp, OPT, st, met, yf)
    return st


def direct_simulate(spec, hdr, smp, opt, cap=20000):
    from fastrock.kernels.hybrid import N_COUNTERS
    y = np.zeros(2)
    met = np.zeros(L.N_MET)
    return spec.simulate(y, spec.par, hdr, smp, opt, np.empty(0), met, np.empty(cap), np.empty((cap, 2)),
                         np.empty((cap, 3), np.int64), np.empty((max(1000, cap // 4), L.N_LOG)),
                         np.zeros(N_COUNTERS, np.int64))


def simulate_inputs():
    from fastrock.model import excitation as X
    spec = registry.select(BLOCK)
    hdr, smp = X.to_header(BLOCK, SIM_PULSE, None)
    t_end = X.end_time(BLOCK, SIM_PULSE, None) + T_AFTER
    return spec, hdr, smp, Solver().options(t_end, False)


def best_of(fns, repeats, clock=time.perf_counter):
    """Minimum time of each callable over interleaved repeats (one warm-up call each).
    ``clock=time.process_time`` (CPU time of this process) for one-thread comparisons: it
    does not count the time other processes on a shared machine hold the CPU."""
    for f in fns:
        f()
    best = [math.inf] * len(fns)
    for _ in range(repeats):
        for i, f in enumerate(fns):
            t0 = clock()
            f()
            best[i] = min(best[i], clock() - t0)
    return best


def chunked_sweep(spec, inputs):
    """The kernel through the front end's chunked driver, with its default chunk size."""
    from fastrock.running.sweep import run_sweep
    Y0, PAR, HDR, smp, OPT = inputs
    return run_sweep(spec.sweep, Y0, PAR, HDR, smp, OPT, None, False)[0]


def wall_free_ratios(repeats=7, threads=None):
    """Front end against the kernel; ``threads=1`` removes the thread-scheduling noise of a
    shared machine (the work compared is the same)."""
    import numba
    n_threads = numba.get_num_threads()
    if threads:
        numba.set_num_threads(threads)
    try:
        return _wall_free_ratios(repeats, time.process_time if threads == 1 else time.perf_counter)
    finally:
        numba.set_num_threads(n_threads)


def _wall_free_ratios(repeats, clock):
    spec, inputs = kernel_inputs()
    t_front, t_chunked, t_kernel = best_of([lambda: spectrum(None), lambda: chunked_sweep(spec, inputs),
                                            lambda: direct_sweep(spec, inputs)], repeats, clock)
    sspec, hdr, smp, opt = simulate_inputs()
    t_sim, t_sim_k = best_of([lambda: fr.simulate(BLOCK, SIM_PULSE, t_after=T_AFTER),
                              lambda: direct_simulate(sspec, hdr, smp, opt)], 5 * repeats, clock)
    return dict(spectrum_front=t_front, spectrum_chunked=t_chunked, spectrum_kernel=t_kernel,
                simulate_front=t_sim, simulate_kernel=t_sim_k)


def inert_wall_cost(repeats=5, early_exit=False):
    """Kernel-to-kernel time ratio inert wall / no wall on one thread."""
    import numba
    s0, i0 = kernel_inputs(None)
    s1, i1 = kernel_inputs(INERT)
    for _s, inp in ((s0, i0), (s1, i1)):
        inp[4][:, L.O_EARLY_EXIT] = 1.0 if early_exit else 0.0
    same = bool((direct_sweep(s0, i0) == direct_sweep(s1, i1)).all())
    n_threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        t0, t1 = best_of([lambda: direct_sweep(s0, i0), lambda: direct_sweep(s1, i1)], repeats,
                         time.process_time)
    finally:
        numba.set_num_threads(n_threads)
    return t0, t1, same


def wall_costs(repeats=5):
    names = list(WALLS)
    times = best_of([lambda w=WALLS[k]: spectrum(w) for k in names], repeats)
    return dict(zip(names, times))


def compile_times():
    code = ("import time, fastrock as fr\nt0 = time.perf_counter()\n"
            "b = fr.RigidBlock.rectangle(0.5, 2.5)\n"
            "fr.simulate(b, fr.Pulse(0.5, 0.5), wall=fr.Wall(gap=0.1))\n"
            "fr.overturning_spectrum(b, [2.0], [1.0], wall=fr.Wall(gap=0.1), progress=False)\n"
            "print(time.perf_counter() - t0)\n")
    with tempfile.TemporaryDirectory() as d:
        env = dict(os.environ, NUMBA_CACHE_DIR=d)
        out = [float(subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                                    check=True).stdout) for _ in range(2)]
    return dict(first_call_compile=out[0], first_call_cache_load=out[1])


def report(with_compile=False):
    n = AMPS.size * FREQS.size * len(SIGNS)
    print(f"fastrock {fr.__version__}, {os.cpu_count()} CPUs, load average {os.getloadavg()}")
    print(f"block b=0.5 h=2.5 (alpha={BLOCK.alpha:.4f}, p={BLOCK.p:.4f}), {n} runs per spectrum, early exit\n")
    for threads in (1, None):
        r = wall_free_ratios(threads=threads)
        label = "1 thread, CPU time" if threads else "all threads, wall time"
        print(f"1. [{label}] spectrum wall=None {r['spectrum_front']:.3f} s vs rigid_sweep through run_sweep "
              f"{r['spectrum_chunked']:.3f} s -> ratio {r['spectrum_front'] / r['spectrum_chunked']:.3f} "
              "(target <= 1.05)")
        print(f"   [{label}] one unchunked rigid_sweep call {r['spectrum_kernel']:.3f} s -> ratio of the "
              f"front end to it {r['spectrum_front'] / r['spectrum_kernel']:.3f}")
    print(f"2. simulate wall=None {1e3 * r['simulate_front']:.2f} ms vs direct rigid_simulate "
          f"{1e3 * r['simulate_kernel']:.2f} ms -> ratio {r['simulate_front'] / r['simulate_kernel']:.2f} "
          "(front-end tables)")
    t0, t1, same = inert_wall_cost()
    print(f"3. inert wall, kernels, 1 thread, no early exit: no wall {t0:.3f} s, inert wall {t1:.3f} s -> "
          f"ratio {t1 / t0:.3f} (same statuses: {same})")
    t0, t1, same = inert_wall_cost(early_exit=True)
    print(f"   same with early exit: ratio {t1 / t0:.3f} (same statuses: {same})")
    c = wall_costs()
    base = c["none"]
    for k, v in c.items():
        print(f"4. spectrum wall={k:<6} {v:.3f} s  ({n / v:,.0f} runs/s)  ratio to no wall {v / base:.3f}")
    if with_compile:
        ct = compile_times()
        print(f"5. wall kernels: first call {ct['first_call_compile']:.1f} s (compile), "
              f"{ct['first_call_cache_load']:.2f} s (cache load)")


# ---------------------------------------------------------------- pytest-benchmark
@pytest.mark.parametrize("wall", list(WALLS))
def test_bench_spectrum(benchmark, wall):
    benchmark.group = "wall spectrum (48x48x2 one-sine, early exit)"
    df = benchmark.pedantic(spectrum, args=(WALLS[wall],), rounds=3, iterations=1, warmup_rounds=1)
    assert (df["outcome"] != "failed").all()


def test_bench_direct_rigid_sweep(benchmark):
    benchmark.group = "wall spectrum (48x48x2 one-sine, early exit)"
    spec, inputs = kernel_inputs()
    st = benchmark.pedantic(direct_sweep, args=(spec, inputs), rounds=3, iterations=1, warmup_rounds=1)
    assert (st > 0).all()


def test_bench_simulate_wall_free(benchmark):
    benchmark.group = "single run"
    benchmark.pedantic(fr.simulate, args=(BLOCK, SIM_PULSE), kwargs=dict(t_after=T_AFTER), rounds=20,
                       iterations=1, warmup_rounds=1)


def test_bench_direct_rigid_simulate(benchmark):
    benchmark.group = "single run"
    spec, hdr, smp, opt = simulate_inputs()
    benchmark.pedantic(direct_simulate, args=(spec, hdr, smp, opt), rounds=20, iterations=1, warmup_rounds=1)


def test_wall_free_scene_within_5_percent_of_plain_rigid_kernel():
    spec, _ = kernel_inputs()
    from fastrock.kernels.rigid import rigid_sweep
    assert spec.name == "rigid" and spec.sweep is rigid_sweep
    r = wall_free_ratios(repeats=5, threads=1)
    ratio = r["spectrum_front"] / r["spectrum_chunked"]
    direct = r["spectrum_front"] / r["spectrum_kernel"]
    print(f"\nspectrum wall=None / rigid_sweep (1 thread): through run_sweep {ratio:.3f}, "
          f"one direct call {direct:.3f}")
    assert ratio <= 1.05


def test_inert_wall_cost():
    t0, t1, same = inert_wall_cost(repeats=3)
    print(f"\ninert wall / no wall (kernels, 1 thread, no early exit) = {t1 / t0:.3f}")
    assert same
    assert t1 / t0 < 1.5


def test_wall_free_scene_never_imports_the_wall_kernel():
    code = ("import sys, fastrock as fr\nb = fr.RigidBlock.rectangle(0.5, 2.5)\n"
            "fr.overturning_spectrum(b, [2.0], [1.0], progress=False)\n"
            "print('fastrock.kernels.wall' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--compile", action="store_true", help="also time compile and cache load (subprocesses)")
    report(ap.parse_args().compile)
