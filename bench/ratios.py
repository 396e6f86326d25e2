#!/usr/bin/env python
"""fastrock speed figures and ratios, all measured in one run (issue 2, section 12).

Usage::

    python bench/ratios.py            # full run (several minutes, most of it SciPy and compiling)
    python bench/ratios.py --quick    # fewer SciPy cells and repeats (about a minute plus compiling)

It prints a plain-text report and, at the end, a markdown table for the README.  Sections:

1. Per-simulation time against ``scipy.integrate.solve_ivp`` (RK45, same rtol and atol, events),
   on a subsample of cells of the default one-sine spectrum grid (alpha 0.25, p 2).  The SciPy
   solver below is event-driven, with the same physics and rules as the fastrock kernel.
   fastrock's time per run is measured inside ``rigid_sweep`` calls over the same cells,
   repeated, with 1 thread and with 2 threads, with and without early termination.
2. 100x100 and 200x200 spectrum wall time through ``fastrock.overturning_spectrum``.
3. First-call compile time (a subprocess with a fresh ``NUMBA_CACHE_DIR``) and cache-load time
   (a second subprocess on that cache).
4. Parallel efficiency t1 / (2 t2), in grid order and with the rows shuffled.
5. Work per run (mean nfev, mean accepted steps).

Timings are the minimum over repeats (the median is printed too).  The machine is shared, so
the load average is printed with the results.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from typing import NamedTuple

import numba
import numpy as np
from scipy.integrate import solve_ivp

import fastrock
from fastrock import RigidBlock, Solver
from fastrock.kernels import layout as L
from fastrock.kernels.rigid import rigid_sweep
from fastrock.running.registry import select
from fastrock.running.sweep import run_sweep

# ---- the benchmark set-up (explicit, shared with bench_rigid.py) -------------------------
ALPHA = 0.25                 # rad
P = 2.0                      # rad/s
RTOL = 1e-6                  # the rtol of the issue-2 target
ATOL = RTOL * 1e-2           # fastrock's default atol for this rtol; SciPy gets the same
T_AFTER = 10.0               # s after the pulse
AMP_RANGE = (0.5, 8.0)       # a_p / (g tan alpha), the CLI's default spectrum
FREQ_RANGE = (0.25, 10.0)    # omega_p / p
SIGN = 1
EPS_OMEGA = 1e-9             # chatter-to-rest thresholds (fastrock defaults, physics.md 7)
EPS_T = 1e-9

OUTCOME = {L.SAFE_NO_UPLIFT: "safe", L.SAFE_REST: "safe", L.SAFE_MOVING: "safe",
           L.SAFE_BOUNDED: "safe", L.OVERTURN_MODE1: "mode1", L.OVERTURN_MODE2: "mode2"}


def body():
    return RigidBlock(alpha=ALPHA, p=P)


def grid(n_amp, n_freq):
    """Amplitude and frequency ratios of an n_amp x n_freq spectrum (amplitude fastest,
    the order of ``overturning_spectrum``)."""
    amps = np.linspace(*AMP_RANGE, n_amp)
    freqs = np.linspace(*FREQ_RANGE, n_freq)
    F, A = np.meshgrid(freqs, amps, indexing="ij")
    return amps, freqs, A.ravel(), F.ravel()


def sweep_inputs(blk, A, F, sign=SIGN, rtol=RTOL, early_exit=True, t_after=T_AFTER):
    """Kernel inputs for one-sine cells (A, F), built as ``overturning_spectrum`` builds them."""
    spec = select(blk)
    n = A.size
    omega = F * blk.p
    amp = A * blk.g * math.tan(blk.alpha)
    dur = 2 * np.pi / omega
    HDR = np.zeros((n, L.N_EXC))
    HDR[:, L.X_KIND] = L.EXC_ONE_SINE
    HDR[:, L.X_AMP] = amp
    HDR[:, L.X_OMEGA] = omega
    HDR[:, L.X_SIGN] = sign
    HDR[:, L.X_DUR] = dur
    OPT = np.tile(Solver(rtol=rtol).options(0.0, early_exit), (n, 1))
    OPT[:, L.O_T_END] = dur + t_after
    PAR = np.tile(spec.par, (n, 1))
    Y0 = np.zeros((n, spec.n_state))
    return Y0, PAR, HDR, np.zeros(1), OPT


def run_kernel(inputs):
    """One direct ``rigid_sweep`` call (no chunking).  Returns (status, MET)."""
    Y0, PAR, HDR, smp, OPT = inputs
    n = Y0.shape[0]
    st = np.empty(n, np.int64)
    met = np.empty((n, L.N_MET))
    yf = np.empty_like(Y0)
    rigid_sweep(Y0, PAR, HDR, smp, OPT, st, met, yf)
    return st, met


# ---- SciPy baseline -------------------------------------------------------------------------
def _uplift_time(t, T, omega, a_p, thr):
    """First time >= t in the pulse [0, T] with |a_p sin(omega t)| > thr (inf if none).

    |sin(phi)| > r on (asin r, pi - asin r) and on (pi + asin r, 2 pi - asin r)."""
    if a_p <= 0.0 or thr >= a_p:
        return math.inf
    r = thr / a_p
    a = math.asin(r)
    phi = omega * t
    for lo, hi in ((a, math.pi - a), (math.pi + a, 2 * math.pi - a)):
        if phi <= hi:
            tu = max(phi, lo) / omega
            # round-off: step up until the threshold test holds at tu
            for _ in range(64):
                if abs(a_p * math.sin(omega * tu)) > thr or tu >= T:
                    break
                tu = math.nextafter(tu, math.inf)
            return tu if tu <= T else math.inf
    return math.inf


def scipy_rigid(alpha, p, e, g, a_p, omega, sign, rtol=RTOL, atol=ATOL, t_after=T_AFTER,
                theta_over=math.pi / 2, eps_omega=EPS_OMEGA, eps_t=EPS_T):
    """Event-driven rigid rocking with ``scipy.integrate.solve_ivp`` (RK45), no early exit.

    Same model as ``kernels/rigid.py``: Housner's exact EOM
    theta'' = -p^2 [sin(s alpha - theta) + (a_g/g) cos(s alpha - theta)] (G = g) about pivot s;
    uplift from rest when |a_g| > g tan(alpha) (strictly) with s = -sgn(a_g); impact at theta = 0 with
    theta'+ = e theta'- and s -> -s; chatter to rest when |theta'+| < eps_omega or two impacts are
    closer than eps_t (then the uplift test decides rock or rest); overturning at
    |theta| = theta_over; the pulse end is a breakpoint (never stepped over); the run lasts to
    pulse end + t_after.  Max |theta| is tracked with a peak event (theta' = 0), as fastrock does.

    Returns (outcome, max |theta| / alpha, impacts, nfev, steps).
    """
    T = 2 * math.pi / omega
    t_end = T + t_after
    thr = g * math.tan(alpha)
    amp = sign * a_p
    p2 = p * p
    s = 1.0

    def rhs(t, y):
        ag = amp * math.sin(omega * t) if t <= T else 0.0
        phi = s * alpha - y[0]
        return [y[1], -p2 * (math.sin(phi) + ag * math.cos(phi) / g)]

    def impact(t, y):
        return s * y[0]

    def overturn(t, y):
        return theta_over - s * y[0]

    def peak(t, y):
        return s * y[1]

    impact.terminal, impact.direction = True, -1
    overturn.terminal, overturn.direction = True, -1
    peak.terminal, peak.direction = False, -1
    events = (impact, overturn, peak)

    t = 0.0
    y = [0.0, 0.0]
    rocking = False
    uplifted = False
    impacts = 0
    t_last = -math.inf
    max_abs = 0.0
    nfev = steps = 0
    while True:
        if not rocking:
            tu = _uplift_time(t, T, omega, a_p, thr) if t <= T else math.inf
            if not math.isfinite(tu):
                outcome = "safe"
                break
            t = tu
            ag = amp * math.sin(omega * t)
            s = -1.0 if ag > 0.0 else 1.0
            y = [0.0, 0.0]
            rocking = uplifted = True
        t_stop = T if t < T else t_end
        sol = solve_ivp(rhs, (t, t_stop), y, method="RK45", rtol=rtol, atol=atol, events=events)
        nfev += sol.nfev
        steps += len(sol.t) - 1
        for yp in sol.y_events[2]:
            max_abs = max(max_abs, abs(yp[0]))
        if sol.status == 1 and len(sol.t_events[1]):
            max_abs = max(max_abs, abs(sol.y_events[1][-1][0]))
            outcome = "mode1" if impacts > 0 else "mode2"
            break
        if sol.status == 1:                         # impact
            t = float(sol.t_events[0][-1])
            pre = float(sol.y_events[0][-1][1])
            post = e * pre
            impacts += 1
            s = -s
            y = [0.0, post]
            chatter = abs(post) < eps_omega or t - t_last < eps_t
            t_last = t
            if chatter:
                y = [0.0, 0.0]
                ag = amp * math.sin(omega * t) if t <= T else 0.0
                if abs(ag) > thr:
                    s = -1.0 if ag > 0.0 else 1.0
                else:
                    rocking = False
            continue
        if sol.status != 0:
            outcome = "failed"
            break
        y = [float(sol.y[0, -1]), float(sol.y[1, -1])]
        max_abs = max(max_abs, abs(y[0]))
        t = t_stop
        if t >= t_end:
            outcome = "safe"
            break
    if not uplifted:
        outcome = "safe"
    return outcome, max_abs / alpha, impacts, nfev, steps


def scipy_cell(blk, A, F, **kw):
    return scipy_rigid(blk.alpha, blk.p, blk.e, blk.g, A * blk.g * math.tan(blk.alpha), F * blk.p,
                       SIGN, **kw)


# ---- helpers ----------------------------------------------------------------------------------
class Timing(NamedTuple):
    """Minimum and median over repeats of the wall time and of the CPU time of this process
    (all its threads; ``time.process_time``).  CPU time is what the run costs; wall time is
    what it takes, which on a loaded machine includes waiting for a core."""
    wall: float
    wall_med: float
    cpu: float
    cpu_med: float

    def per(self, n):
        return Timing(*(v / n for v in self))


def timeit(fn, repeats, warmup=1):
    for _ in range(warmup):
        fn()
    w, c = [], []
    for _ in range(repeats):
        c0 = time.process_time()
        t0 = time.perf_counter()
        fn()
        w.append(time.perf_counter() - t0)
        c.append(time.process_time() - c0)
    return Timing(min(w), float(np.median(w)), min(c), float(np.median(c)))


def with_threads(n, fn):
    old = numba.get_num_threads()
    numba.set_num_threads(n)
    try:
        return fn()
    finally:
        numba.set_num_threads(old)


class one_thread:
    """Context manager: Numba on one thread inside the block."""

    def __enter__(self):
        self.n = numba.get_num_threads()
        numba.set_num_threads(1)

    def __exit__(self, *exc):
        numba.set_num_threads(self.n)


def fmt_t(s):
    if s >= 1.0:
        return f"{s:.2f} s"
    if s >= 1e-3:
        return f"{s * 1e3:.2f} ms"
    return f"{s * 1e6:.1f} µs"


def loadavg():
    try:
        return os.getloadavg()
    except OSError:
        return (float("nan"),) * 3


def log(msg=""):
    print(msg, flush=True)


def header(title):
    log(f"\n== {title} ==  (load average {loadavg()[0]:.2f})")


# ---- 1. SciPy ratio ---------------------------------------------------------------------------
def subsample(n_cells, seed=0):
    """n_cells distinct cells of the 100x100 default grid, drawn with a fixed seed."""
    _, _, A, F = grid(100, 100)
    idx = np.sort(np.random.default_rng(seed).choice(A.size, n_cells, replace=False))
    return A[idx], F[idx]


def tile_inputs(inputs, budget=0.4):
    """The rows of ``inputs`` repeated so that one single-thread sweep takes about ``budget`` s."""
    Y0, PAR, HDR, smp, OPT = inputs
    t = with_threads(1, lambda: timeit(lambda: run_kernel(inputs), 1, warmup=1))
    reps = max(1, int(budget / max(t.cpu, t.wall / 4, 1e-6)))
    Y0, PAR, HDR, OPT = (np.ascontiguousarray(np.tile(a, (reps, 1))) for a in (Y0, PAR, HDR, OPT))
    return (Y0, PAR, HDR, smp, OPT), Y0.shape[0]


def section_scipy(blk, n_cells, scipy_repeats, repeats):
    header(f"1. per-simulation time vs scipy.integrate.solve_ivp RK45 (rtol {RTOL:g}, atol {ATOL:g}, "
           f"{n_cells} cells)")
    A, F = subsample(n_cells)
    res = {"cells": A.size}
    # SciPy: every cell run scipy_repeats times; per cell the minimum wall and CPU time is kept
    sp_w = np.full(A.size, np.inf)
    sp_c = np.full(A.size, np.inf)
    sp = []
    for i in range(A.size):
        for _ in range(scipy_repeats):
            c0 = time.process_time()
            t0 = time.perf_counter()
            r = scipy_cell(blk, A[i], F[i])
            sp_w[i] = min(sp_w[i], time.perf_counter() - t0)
            sp_c[i] = min(sp_c[i], time.process_time() - c0)
        sp.append(r)
    sp_out = [r[0] for r in sp]
    sp_rot = np.array([r[1] for r in sp])
    res.update(scipy_wall=sp_w.mean(), scipy_cpu=sp_c.mean(),
               scipy_nfev=float(np.mean([r[3] for r in sp])), scipy_steps=float(np.mean([r[4] for r in sp])),
               scipy_outcomes={k: sp_out.count(k) for k in sorted(set(sp_out))})
    log(f"scipy: {fmt_t(res['scipy_wall'])} wall, {fmt_t(res['scipy_cpu'])} CPU per run (mean over cells of "
        f"the per-cell minimum of {scipy_repeats}); mean nfev {res['scipy_nfev']:.0f}, "
        f"mean steps {res['scipy_steps']:.0f}; outcomes {res['scipy_outcomes']}")
    for early in (True, False):
        inputs = sweep_inputs(blk, A, F, early_exit=early)
        st, met = run_kernel(inputs)
        out = [OUTCOME.get(int(c), "failed") for c in st]
        same = sum(a == b for a, b in zip(out, sp_out))
        rot = met[:, L.M_MAX_ABS_THETA] / blk.alpha
        ok = np.array([a == b == "safe" for a, b in zip(out, sp_out)]) & (sp_rot > 0)
        drot = np.abs(rot[ok] - sp_rot[ok]) / sp_rot[ok] if ok.any() else np.zeros(1)
        big, n = tile_inputs(inputs)
        t1 = with_threads(1, lambda: timeit(lambda: run_kernel(big), repeats)).per(n)
        t2 = with_threads(2, lambda: timeit(lambda: run_kernel(big), repeats)).per(n)
        key = "early" if early else "full"
        res[key] = dict(same=same, t1=t1, t2=t2, n=n, ratio1=res["scipy_wall"] / t1.wall,
                        ratio2=res["scipy_wall"] / t2.wall, ratio_cpu=res["scipy_cpu"] / t1.cpu,
                        drot_max=float(drot.max()), nfev=float(met[:, L.M_NFEV].mean()),
                        steps=float(met[:, L.M_NSTEPS].mean()))
        log(f"fastrock early_exit={early}: identical outcomes {same}/{A.size}; max|theta|/alpha on "
            f"safe cells: median rel. diff {np.median(drot):.1e}, max {drot.max():.1e}; "
            f"mean nfev {res[key]['nfev']:.0f}")
        log(f"  per run ({n} runs per sweep): 1 thread {fmt_t(t1.wall)} wall (median {fmt_t(t1.wall_med)}), "
            f"{fmt_t(t1.cpu)} CPU; 2 threads {fmt_t(t2.wall)} wall (median {fmt_t(t2.wall_med)})")
        log(f"  ratio scipy/fastrock: wall 1 thread {res[key]['ratio1']:,.0f}x, 2 threads "
            f"{res[key]['ratio2']:,.0f}x; CPU time 1 thread {res[key]['ratio_cpu']:,.0f}x")
        for i in range(A.size):
            if out[i] != sp_out[i]:
                log(f"  differs: A={A[i]:.4f} F={F[i]:.4f} fastrock {out[i]} scipy {sp_out[i]}")
    return res


# ---- 2. spectra -------------------------------------------------------------------------------
def section_spectra(blk, repeats, sizes):
    header("2. spectrum wall time (fastrock.overturning_spectrum, 2 threads, front end included)")
    res = {}
    for n, rtol in sizes:
        amps, freqs, _, _ = grid(n, n)
        fn = lambda: fastrock.overturning_spectrum(blk, amps, freqs, rtol=rtol, progress=False)
        t = with_threads(2, lambda: timeit(fn, repeats))
        res[(n, rtol)] = t
        df = fn()
        log(f"{n}x{n} rtol {rtol:g}: {t.wall:.3f} s (median {t.wall_med:.3f} s, CPU {t.cpu:.3f} s), "
            f"{n * n / t.wall:,.0f} runs/s; outcomes {df.outcome.value_counts().to_dict()}")
    return res


# ---- 3. compile and cache load ----------------------------------------------------------------
CHILD = r"""
import json, time
t0 = time.perf_counter()
import fastrock
from fastrock.kernels import rigid
t_import = time.perf_counter() - t0
b = fastrock.RigidBlock(alpha=0.25, p=2.0)
pulse = fastrock.Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
def timed(fn):
    t0 = time.perf_counter(); fn(); return time.perf_counter() - t0
sim = lambda: fastrock.simulate(b, pulse, rtol=1e-6)
spec = lambda: fastrock.overturning_spectrum(b, [3.0], [2.0], rtol=1e-6, progress=False)
r = dict(import_s=t_import, simulate_first=timed(sim), simulate_warm=timed(sim),
         spectrum_first=timed(spec), spectrum_warm=timed(spec))
st = {}
for name in ("rigid_simulate", "rigid_sweep"):
    s = getattr(rigid, name).stats
    st[name] = dict(hits=sum(s.cache_hits.values()), misses=sum(s.cache_misses.values()))
r["stats"] = st
print("RESULT " + json.dumps(r))
"""


def run_child(cache_dir):
    """Run CHILD in a fresh interpreter on NUMBA_CACHE_DIR=cache_dir; returns its timings [s]:
    import, first and warm call of ``simulate`` and of a one-cell ``overturning_spectrum``,
    their differences (the compile or cache-load overhead), the process wall time, and
    Numba's cache hits/misses of the two entry kernels."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    env.pop("NUMBA_DISABLE_JIT", None)
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True,
                         check=True)
    wall = time.perf_counter() - t0
    line = [s for s in out.stdout.splitlines() if s.startswith("RESULT ")][-1]
    r = json.loads(line[7:])
    r["wall"] = wall
    r["simulate_overhead"] = r["simulate_first"] - r["simulate_warm"]
    r["spectrum_overhead"] = r["spectrum_first"] - r["spectrum_warm"]
    r["first_call_total"] = r["simulate_overhead"] + r["spectrum_overhead"]
    return r


def section_compile(n_cold, n_warm):
    header("3. first call: compile (fresh NUMBA_CACHE_DIR) and cache load (second process)")
    cold, warm = [], []
    with tempfile.TemporaryDirectory(prefix="fastrock-bench-cache-") as base:
        for i in range(n_cold):
            d = os.path.join(base, f"c{i}")
            os.makedirs(d)
            cold.append(run_child(d))
        for _ in range(n_warm):
            warm.append(run_child(os.path.join(base, "c0")))
    c = min(cold, key=lambda r: r["first_call_total"])
    w = min(warm, key=lambda r: r["first_call_total"])
    for name, r in (("compile", c), ("cache load", w)):
        log(f"{name}: simulate first call {r['simulate_first']:.2f} s (warm {fmt_t(r['simulate_warm'])}), "
            f"spectrum first call {r['spectrum_first']:.2f} s (warm {fmt_t(r['spectrum_warm'])}), "
            f"import {r['import_s']:.2f} s, process wall {r['wall']:.2f} s; numba stats {r['stats']}")
    if n_cold > 1:
        log("compile, all attempts: " + ", ".join(f"{r['first_call_total']:.1f} s" for r in cold))
    return c, w


# ---- 4. parallel efficiency -------------------------------------------------------------------
def section_parallel(blk, n, repeats):
    header(f"4. parallel speed-up on {n}x{n} (rtol {RTOL:g}, early exit), "
           f"threading layer {numba.threading_layer()}")
    _, _, A, F = grid(n, n)
    inputs = sweep_inputs(blk, A, F)
    perm = np.random.default_rng(1).permutation(A.size)
    Y0, PAR, HDR, smp, OPT = inputs
    shuffled = (Y0[perm], PAR[perm], HDR[perm], smp, OPT[perm])
    variants = {
        "grid order, run_sweep chunks": lambda: run_sweep(rigid_sweep, *inputs, progress=False),
        "grid order, one kernel call": lambda: run_kernel(inputs),
        "shuffled, run_sweep chunks": lambda: run_sweep(rigid_sweep, *shuffled, progress=False),
        "shuffled, one kernel call": lambda: run_kernel(shuffled),
    }
    res = {}
    for name, fn in variants.items():
        t1 = with_threads(1, lambda: timeit(fn, repeats))
        t2 = with_threads(2, lambda: timeit(fn, repeats))
        r = dict(t1=t1, t2=t2, eff=t1.wall / (2 * t2.wall), eff_med=t1.wall_med / (2 * t2.wall_med),
                 share=t2.cpu / (2 * t2.wall), share1=t1.cpu / t1.wall, eff_cpu=t1.cpu / t2.cpu)
        res[name] = r
        log(f"{name:29s} 1 thread {t1.wall:.3f} s (med {t1.wall_med:.3f}, CPU {t1.cpu:.3f}), "
            f"2 threads {t2.wall:.3f} s (med {t2.wall_med:.3f}, CPU {t2.cpu:.3f}): efficiency "
            f"{r['eff']:.0%} (medians {r['eff_med']:.0%}); cores obtained: 1 thread {r['share1']:.0%} "
            f"of 1, 2 threads {r['share']:.0%} of 2; CPU work t1_cpu/t2_cpu {r['eff_cpu']:.0%}")
    # Static scheduling splits each kernel call into two contiguous halves: compare their work
    st, met = run_kernel(inputs)
    cost = met[:, L.M_NFEV] + 1.0
    chunk = max(256, min(4096, A.size // 20 + 1))     # run_sweep's default chunk size

    def busy_half(c):
        h = (c.size + 1) // 2
        return max(c[:h].sum(), c[h:].sum())
    res["imbalance_whole"] = busy_half(cost) / (cost.sum() / 2)
    res["imbalance_chunks"] = sum(busy_half(cost[i:i + chunk]) for i in range(0, A.size, chunk)) / (cost.sum() / 2)
    cs = cost[perm]
    res["imbalance_chunks_shuffled"] = sum(busy_half(cs[i:i + chunk]) for i in range(0, A.size, chunk)) / (cs.sum() / 2)
    log(f"static-split balance (nfev of the busier thread / the mean; 1.00 = balanced): one call "
        f"{res['imbalance_whole']:.3f}, run_sweep chunks of {chunk} {res['imbalance_chunks']:.3f}, "
        f"shuffled chunks {res['imbalance_chunks_shuffled']:.3f}")
    return res


# ---- 5. work per run --------------------------------------------------------------------------
def section_work(blk, n):
    header(f"5. work per run on the {n}x{n} grid (rtol {RTOL:g})")
    _, _, A, F = grid(n, n)
    res = {}
    for early in (True, False):
        st, met = run_kernel(sweep_inputs(blk, A, F, early_exit=early))
        res[early] = (float(met[:, L.M_NFEV].mean()), float(met[:, L.M_NSTEPS].mean()),
                      float(met[:, L.M_NREJECT].mean()), float(met[:, L.M_N_EVENTS].mean()))
        log(f"early_exit={early}: mean nfev {res[early][0]:.0f}, accepted steps {res[early][1]:.0f}, "
            f"rejected {res[early][2]:.1f}, located events {res[early][3]:.1f}")
    return res


# ---- main -------------------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer SciPy cells and repeats")
    ap.add_argument("--no-compile", action="store_true", help="skip section 3 (compile subprocesses)")
    args = ap.parse_args(argv)
    q = args.quick
    n_cells = 12 if q else 40
    scipy_repeats = 1 if q else 2
    repeats = 3 if q else 7
    n_par = 100 if q else 200
    blk = body()
    la0 = loadavg()
    t_start = time.perf_counter()
    log(f"fastrock {fastrock.__version__}, numba {numba.__version__}, numpy {np.__version__}, "
        f"Python {platform.python_version()}, {os.cpu_count()} CPUs, numba threads "
        f"{numba.get_num_threads()}")
    log(f"load average at start: {la0[0]:.2f} {la0[1]:.2f} {la0[2]:.2f}")
    log(f"block alpha={ALPHA} p={P} e={blk.e:.4f}; one-sine, sign {SIGN:+d}; grid a_p/(g tan a) "
        f"{AMP_RANGE}, w_p/p {FREQ_RANGE}; rtol {RTOL:g} atol {ATOL:g}; pulse + {T_AFTER:g} s")
    # compile first (in subprocesses, so this process is untouched), then warm up here
    comp = load = None
    if not args.no_compile:
        comp, load = section_compile(1 if q else 2, 2 if q else 3)
    fastrock.overturning_spectrum(blk, [3.0], [2.0], rtol=RTOL, progress=False)
    run_kernel(sweep_inputs(blk, np.array([3.0]), np.array([2.0])))
    sp = section_scipy(blk, n_cells, scipy_repeats, repeats)
    dr = fastrock.running.solver.DEFAULT_RTOL
    spec = section_spectra(blk, 3 if q else 5, [(100, dr), (200, dr), (100, RTOL), (200, RTOL)])
    par = section_parallel(blk, n_par, repeats)
    work = section_work(blk, 100)
    la1 = loadavg()
    log(f"\nload average at end: {la1[0]:.2f} {la1[1]:.2f} {la1[2]:.2f}; "
        f"total {time.perf_counter() - t_start:.0f} s")

    # ---- markdown ----
    e, f = sp["early"], sp["full"]
    po = par["grid order, run_sweep chunks"]
    ps = par["shuffled, run_sweep chunks"]
    yes = lambda ok: "yes" if ok else "**no**"
    c = sp["cells"]
    rows = [
        ("SciPy `solve_ivp` RK45 + events, per run", f"{fmt_t(sp['scipy_wall'])}",
         f"CPU {fmt_t(sp['scipy_cpu'])}; {c} cells, mean nfev {sp['scipy_nfev']:.0f}", ""),
        ("fastrock per run, early exit, 1 thread", fmt_t(e["t1"].wall),
         f"CPU {fmt_t(e['t1'].cpu)}; identical outcomes {e['same']}/{c}; mean nfev {e['nfev']:.0f}", ""),
        ("**ratio SciPy / fastrock, early exit, 1 thread**", f"**{e['ratio1']:,.0f}×**",
         f"CPU-time ratio {e['ratio_cpu']:,.0f}×; 2 threads (wall) {e['ratio2']:,.0f}×",
         f"≥ 1000×: {yes(e['ratio1'] >= 1000)}"),
        ("fastrock per run, no early exit, 1 thread", fmt_t(f["t1"].wall),
         f"CPU {fmt_t(f['t1'].cpu)}; identical outcomes {f['same']}/{c}; mean nfev {f['nfev']:.0f}", ""),
        ("ratio SciPy / fastrock, no early exit, 1 thread", f"{f['ratio1']:,.0f}×",
         f"CPU-time ratio {f['ratio_cpu']:,.0f}×; early exit buys {f['t1'].wall / e['t1'].wall:.1f}×", ""),
    ]
    for (n, rtol), t in spec.items():
        target = n == 200 and rtol == dr
        name = f"{n}×{n} spectrum, rtol {rtol:g}{' (default)' if rtol == dr else ''}"
        rows.append((f"**{name}**" if target else name, f"**{t.wall:.2f} s**" if target else f"{t.wall:.2f} s",
                     f"{n * n / t.wall:,.0f} runs/s; median {t.wall_med:.2f} s; CPU {t.cpu:.2f} s",
                     f"< 5 s: {yes(t.wall < 5)}" if target else ""))
    if comp is not None:
        rows += [
            ("first call, compile (fresh cache): simulate + spectrum", f"{comp['first_call_total']:.1f} s",
             f"simulate {comp['simulate_overhead']:.1f} s, then sweep {comp['spectrum_overhead']:.1f} s", ""),
            ("first call, cache load (second process)", f"{load['first_call_total']:.2f} s",
             f"`import fastrock` {load['import_s']:.2f} s; whole process {load['wall']:.1f} s", ""),
        ]
    rows += [
        (f"**parallel efficiency t1/(2·t2), {n_par}², grid order**", f"**{po['eff']:.0%}**",
         f"t1 {po['t1'].wall:.2f} s, t2 {po['t2'].wall:.2f} s; cores obtained {po['share']:.0%} of 2; "
         f"CPU work t1/t2 {po['eff_cpu']:.0%}", f"≥ 85%: {yes(po['eff'] >= 0.85)}"),
        ("parallel efficiency, rows shuffled", f"{ps['eff']:.0%}",
         f"t1 {ps['t1'].wall:.2f} s, t2 {ps['t2'].wall:.2f} s; cores obtained {ps['share']:.0%} of 2", ""),
        ("static-split balance (busier thread / mean, nfev)", f"{par['imbalance_chunks']:.3f}",
         f"shuffled {par['imbalance_chunks_shuffled']:.3f}", ""),
        ("work per run, early exit (100² grid)", f"nfev {work[True][0]:.0f}",
         f"steps {work[True][1]:.0f}, events {work[True][3]:.1f}", ""),
        ("work per run, no early exit (100² grid)", f"nfev {work[False][0]:.0f}",
         f"steps {work[False][1]:.0f}, events {work[False][3]:.1f}", ""),
    ]
    log("\n## Measured figures\n")
    log(f"α = {ALPHA}, p = {P} rad/s, Housner e, one-sine (+), a_p/(g tan α) ∈ {list(AMP_RANGE)}, "
        f"ω_p/p ∈ {list(FREQ_RANGE)}, pulse + {T_AFTER:g} s, rtol {RTOL:g} unless stated; "
        f"{os.cpu_count()} cores, numba {numba.__version__} ({numba.threading_layer()}); "
        f"load average {la0[0]:.1f} at start, {la1[0]:.1f} at end; minimum of repeats"
        f"{' (--quick)' if q else ''}.\n")
    log("| figure | value | detail | target met |")
    log("|---|---|---|---|")
    for r in rows:
        log("| " + " | ".join(r) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
