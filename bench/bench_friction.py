#!/usr/bin/env python
"""Cost of friction (issue #6, "Effect selection"): mu = inf pays nothing, inert friction pays
for the 4-state kernel, and a real friction spectrum.

Usage::

    pytest bench/bench_friction.py             # pytest-benchmark table + the 5% check
    python bench/bench_friction.py             # plain report of the ratios
    python bench/bench_friction.py --quick     # fewer repeats, 30x30 instead of 50x50
    python bench/bench_friction.py --early     # only 4., the early decisions against full runs and SciPy

Measured on a rectangular block b = 0.25 m, h = 1 m (b/h = 0.25, alpha = 0.245, p = 2.67 rad/s),
one-sine pulses a_p/(g tan alpha) in [1, 6] x omega_p/p in [0.5, 10], t_after 10 s, rtol 1e-8:

1. ``Friction(inf)`` against no friction: the scene selects the plain rigid kernel (checked:
   ``Scene.kernel == "rigid"``, no ``fastrock.kernels.friction`` import), so the two must time
   the same.  Measured anyway, as CPU time on one thread (robust on a shared machine), for a
   single run of the packaged El Centro record through ``Scene.run`` and for a 40 x 40 spectrum
   through ``overturning_spectrum``.  Target: within 5%.
2. Inert but finite friction, mu = 10 (nothing slides: checked per cell, stick_slip == 0 and
   max_slide == 0): ``rigid_friction_sweep`` against ``rigid_sweep`` on the same cells, one
   thread, early exit off in both (the two kernels' early decisions reach different states, so
   with them on the ratio would mix in that difference; that front-end ratio is printed too).  This is the price of the 4-state kernel (4 states in DP5, 6 event
   functions including mu_s N - |F| and N, the mode logic).
3. A 50 x 50 friction spectrum (mu_s = 0.4 > b/h: rocking and slide-rocking; and mu_s = 0.2 <
   b/h: sliding), wall time on all threads, with the rigid 50 x 50 for reference.
4. Early decisions (issue #15): per-run CPU time with and without them on a 24 x 24 x 2 pulse
   grid, outcomes compared cell by cell, and the ratio to a SciPy reference (see
   ``early_decisions``).

Timings are minima over interleaved repeats; the load average is printed.
"""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import fastrock as fr
from fastrock import Friction
from fastrock.running import registry
from fastrock.kernels import layout as L
from fastrock.io.default_records import load_default_record
from fastrock.running.scene import Scene
from fastrock.running.solver import Solver
from ratios import one_thread  # shared bench helpers (bench/ is on sys.path)

BLOCK = fr.RigidBlock.rectangle(b=0.25, h=1.0)
T_AFTER = 10.0
INF = Friction(math.inf)
INERT = Friction(10.0)
REAL = {"mu0.4": Friction(0.4), "mu0.2": Friction(0.2)}


def grid(n):
    return np.linspace(1.0, 6.0, n), np.linspace(0.5, 10.0, n)


def spectrum(friction, n, early_exit=True):
    a, f = grid(n)
    return fr.overturning_spectrum(BLOCK, a, f, friction=friction, progress=False, t_after=T_AFTER,
                                   early_exit=early_exit)


def record_scene(friction):
    return Scene(BLOCK, excitation=load_default_record(), friction=friction, t_after=5.0)


def best_of(fns, repeats, clock=time.perf_counter):
    """Minimum time of each callable over interleaved repeats (one warm-up call each)."""
    for f in fns:
        f()
    best = [math.inf] * len(fns)
    for _ in range(repeats):
        for i, f in enumerate(fns):
            t0 = clock()
            f()
            best[i] = min(best[i], clock() - t0)
    return best


# ------------------------------------------------------------------ 1. mu = inf vs none
def inf_vs_none(repeats=5, n=40):
    s0, si = record_scene(None), record_scene(INF)
    assert s0.kernel == si.kernel == "rigid" and "friction" not in si.effects
    r0, ri = s0.run(), si.run()
    assert r0.metrics["nfev"] == ri.metrics["nfev"] and r0.outcome == ri.outcome
    with one_thread():
        t_run0, t_runi = best_of([s0.run, si.run], 10 * repeats, time.process_time)
        t_sp0, t_spi = best_of([lambda: spectrum(None, n), lambda: spectrum(INF, n)], repeats,
                               time.process_time)
    return dict(scene_none=t_run0, scene_inf=t_runi, spectrum_none=t_sp0, spectrum_inf=t_spi, n=n)


# ------------------------------------------------------------------ 2. inert friction
def kernel_inputs(friction, cells):
    """The arrays overturning_spectrum hands to the sweep kernel, for (A, F) cells."""
    A = np.array([c[0] for c in cells])
    F = np.array([c[1] for c in cells])
    return pulse_inputs(friction, A, F, np.ones(A.size), False, BLOCK, Solver())


def pulse_inputs(friction, A, F, S, early_exit, block, solver):
    """Sweep-kernel inputs for one-sine cells (A, F, sign S), as overturning_spectrum builds them."""
    spec = registry.select(block, friction=friction)
    n = A.size
    omega = F * block.p
    dur = 2 * np.pi / omega
    HDR = np.zeros((n, L.N_EXC))
    HDR[:, L.X_KIND] = L.EXC_ONE_SINE
    HDR[:, L.X_AMP] = A * block.g * math.tan(block.alpha)
    HDR[:, L.X_OMEGA] = omega
    HDR[:, L.X_SIGN] = S
    HDR[:, L.X_DUR] = dur
    OPT = np.tile(solver.options(0.0, early_exit), (n, 1))
    OPT[:, L.O_T_END] = dur + T_AFTER
    PAR = np.tile(spec.par, (n, 1))
    return spec, (np.zeros((n, spec.n_state)), PAR, HDR, np.zeros(1), OPT)


def direct_sweep(spec, inputs):
    Y0, PAR, HDR, smp, OPT = inputs
    n = Y0.shape[0]
    st = np.empty(n, np.int64)
    met = np.empty((n, L.N_MET))
    yf = np.empty_like(Y0)
    spec.sweep(Y0, PAR, HDR, smp, OPT, st, met, yf)
    return st, met


def inert_cells(n=30):
    """Cells of an n x n grid on which mu = 10 never slips (near pi/2 an overturning block can:
    N -> 0; those cells are dropped), and the number dropped."""
    a, f = grid(n)
    cells = [(x, y) for y in f for x in a]
    spec, inp = kernel_inputs(INERT, cells)
    _st, met = direct_sweep(spec, inp)
    keep = (met[:, L.M_N_STICK_SLIP] == 0) & (met[:, L.M_MAX_SLIDE] == 0)
    return [c for c, k in zip(cells, keep) if k], int((~keep).sum())


def inert_cost(repeats=3, n=30):
    cells, dropped = inert_cells(n)
    s0, i0 = kernel_inputs(None, cells)
    s1, i1 = kernel_inputs(INERT, cells)
    st0, met0 = direct_sweep(s0, i0)
    st1, met1 = direct_sweep(s1, i1)
    same = bool((st0 == st1).all())
    up = met0[:, L.M_MAX_ABS_THETA] > 0          # cells that uplift (the rest: both exactly 0)
    peak = np.abs(met1[up, L.M_MAX_ABS_THETA] / met0[up, L.M_MAX_ABS_THETA] - 1)
    same = same and bool((met1[~up, L.M_MAX_ABS_THETA] == 0).all())
    with one_thread():
        t0, t1 = best_of([lambda: direct_sweep(s0, i0), lambda: direct_sweep(s1, i1)], repeats,
                         time.process_time)
    nfev = (met0[:, L.M_NFEV].sum(), met1[:, L.M_NFEV].sum())
    return dict(rigid=t0, inert=t1, same_status=same, max_peak_rel=float(peak.max()) if peak.size else 0.0,
                cells=len(cells), dropped=dropped, nfev_rigid=nfev[0], nfev_inert=nfev[1])


def inert_front_end(repeats=3, n=30):
    """overturning_spectrum(friction=Friction(10)) vs no friction, default early exit, all threads."""
    t0, t1 = best_of([lambda: spectrum(None, n), lambda: spectrum(INERT, n)], repeats)
    return t0, t1


# ------------------------------------------------------------------ 3. friction spectra
def spectra_50(n=50, repeats=1):
    names = ["none"] + list(REAL)
    fr_of = {"none": None, **REAL}
    times = best_of([lambda k=k: spectrum(fr_of[k], n) for k in names], repeats)
    dfs = {k: spectrum(fr_of[k], n) for k in names}
    return {k: (t, dfs[k]) for k, t in zip(names, times)}


def report(quick=False):
    rep = 2 if quick else 5
    n50 = 30 if quick else 50
    print(f"fastrock {fr.__version__}, {os.cpu_count()} CPUs, load average {os.getloadavg()}")
    print(f"block b=0.25 h=1.0 (alpha={BLOCK.alpha:.4f}, p={BLOCK.p:.4f}), one-sine, t_after {T_AFTER} s\n")
    r = inf_vs_none(rep, 30 if quick else 40)
    print(f"1. Friction(inf) vs none (kernel 'rigid' both; 1 thread, CPU time):")
    print(f"   El Centro scene run   none {1e3 * r['scene_none']:.2f} ms  inf {1e3 * r['scene_inf']:.2f} ms"
          f"  ratio {r['scene_inf'] / r['scene_none']:.3f} (target <= 1.05)")
    print(f"   {r['n']}x{r['n']} spectrum      none {r['spectrum_none']:.3f} s   inf {r['spectrum_inf']:.3f} s"
          f"   ratio {r['spectrum_inf'] / r['spectrum_none']:.3f} (target <= 1.05)")
    c = inert_cost(max(2, rep - 2), 20 if quick else 30)
    print(f"2. inert friction mu=10 vs rigid kernel (1 thread, CPU time, no early exit, {c['cells']} cells, "
          f"{c['dropped']} dropped because mu=10 slips near pi/2):")
    print(f"   rigid_sweep {c['rigid']:.3f} s  rigid_friction_sweep {c['inert']:.3f} s  ratio "
          f"{c['inert'] / c['rigid']:.3f};  nfev ratio {c['nfev_inert'] / c['nfev_rigid']:.3f}; "
          f"same statuses {c['same_status']}; max |peak ratio - 1| {c['max_peak_rel']:.1e}")
    t0, t1 = inert_front_end(max(2, rep - 2), 20 if quick else 30)
    print(f"   front end, early exit on (each kernel's own early decisions): {t0:.3f} s vs {t1:.3f} s, "
          f"ratio {t1 / t0:.2f}")
    s = spectra_50(n50)
    base = s["none"][0]
    print(f"3. {n50}x{n50} spectra (all threads, wall time, early exit on):")
    for k, (t, df) in s.items():
        counts = df["outcome"].value_counts().to_dict()
        print(f"   {k:<6} {t:7.2f} s  ({n50 * n50 / t:7.0f} runs/s)  ratio to rigid {t / base:5.2f}  {counts}")


# ------------------------------------------------------------------ 4. early decisions (issue #15)
# The rigid block of bench/ratios.py (alpha 0.25, p 2: b/h 0.255), one-sine pulses of both signs
# on a 24 x 24 grid a_p/(g tan alpha) in [1, 6] x omega_p/p in [0.5, 10], 10 s after the pulse,
# rtol 1e-6 (atol 1e-8), the SciPy baseline's tolerances.  Three frictions: mu 1 (rocks without
# ever slipping on the cells kept: the SciPy reference is then ratios.scipy_rigid, Housner's
# model), mu 0.15 < b/h (slides only: the SciPy reference is scipy_slide below), mu 0.3 (rocks
# and slide-rocks: no SciPy reference of that model here, early against full only).
EARLY_BLOCK = fr.RigidBlock(alpha=0.25, p=2.0)
EARLY_CASES = {"stick mu=1.0": Friction(1.0), "slide mu=0.15": Friction(0.15),
               "slide-rock mu=0.3": Friction(0.3)}
E_RTOL, E_ATOL = 1e-6, 1e-8


def early_grid(n=24):
    a, f = np.linspace(1.0, 6.0, n), np.linspace(0.5, 10.0, n)
    S, F, A = np.meshgrid([1.0, -1.0], f, a, indexing="ij")
    return A.ravel(), F.ravel(), S.ravel()


def early_inputs(friction, A, F, S, early_exit, block=EARLY_BLOCK):
    return pulse_inputs(friction, A, F, S, early_exit, block, Solver(rtol=E_RTOL, atol=E_ATOL))


def outcomes(st, met, friction):
    """The front end's outcome: safe with |residual slide| above the tolerance is 'slide'."""
    from fastrock.running.outcomes import outcome_of
    out = np.array([outcome_of(c) for c in st], dtype=object)
    slid = (out == "safe") & (np.abs(met[:, L.M_RESIDUAL_SLIDE]) > friction.slide_tolerance)
    out[slid] = "slide"
    return out


def scipy_slide(mu_s, mu_k, g, a_p, omega, sign, rtol=E_RTOL, atol=E_ATOL, t_after=T_AFTER,
                tol=1e-3):
    """Event-driven flat sliding with ``solve_ivp`` (RK45), mu_s < b/h so the block never rocks
    (physics.md 4.3): rest until |a_g| > mu_s g, then d'' = -a_g - mu_k sigma g with sigma =
    -sgn(a_g) until d' = 0, where it rests if |a_g| <= mu_s g and else slips the other way; the
    pulse end is a breakpoint.  Returns (outcome, residual slip, nfev)."""
    from scipy.integrate import solve_ivp
    from ratios import _uplift_time
    T = 2 * math.pi / omega
    t_end = T + t_after
    amp = sign * a_p

    def ag(t):
        return amp * math.sin(omega * t) if t <= T else 0.0

    t, d, v, sig, sliding, nfev = 0.0, 0.0, 0.0, 0.0, False, 0

    def rhs(t, y):
        return [y[1], -ag(t) - mu_k * sig * g]

    def stick(t, y):
        return sig * y[1]
    stick.terminal, stick.direction = True, -1
    while True:
        if not sliding:
            tu = _uplift_time(t, T, omega, a_p, mu_s * g) if t <= T else math.inf
            if not math.isfinite(tu):
                break
            t, v, sliding = tu, 0.0, True
            sig = -1.0 if ag(t) > 0.0 else 1.0
        t_stop = T if t < T else t_end
        sol = solve_ivp(rhs, (t, t_stop), [d, v], method="RK45", rtol=rtol, atol=atol, events=stick)
        nfev += sol.nfev
        if sol.status == 1:
            t = float(sol.t_events[0][-1])
            d, v = float(sol.y_events[0][-1][0]), 0.0
            a = ag(t)
            if abs(a) > mu_s * g:
                sig = -1.0 if a > 0.0 else 1.0
            else:
                sliding = False
            continue
        if sol.status != 0:
            return "failed", d, nfev
        d, v, t = float(sol.y[0, -1]), float(sol.y[1, -1]), t_stop
        if t >= t_end:
            break
    return ("slide" if abs(d) > tol else "safe"), d, nfev


def scipy_reference(name, friction, a, f, s, block=EARLY_BLOCK):
    """(outcome, residual slip or NaN) of one cell by the SciPy reference of the case."""
    a_p = a * block.g * math.tan(block.alpha)
    if name.startswith("stick"):
        from ratios import scipy_rigid
        out = scipy_rigid(block.alpha, block.p, block.e, block.g, a_p, f * block.p, s,
                          rtol=E_RTOL, atol=E_ATOL, t_after=T_AFTER)
        return out[0], 0.0
    out = scipy_slide(friction.mu_s, friction.mu_k, block.g, a_p, f * block.p, s)
    return out[0], out[1]


def early_decisions(n=24, n_scipy=40, repeats=3, scipy_repeats=2):
    """Per-run CPU time (1 thread) with and without early decisions on the 2 n^2 grid, outcomes
    compared cell by cell, and the ratio to SciPy on n_scipy cells drawn from it (seed 0)."""
    A, F, S = early_grid(n)
    res = {}
    for name, fric in EARLY_CASES.items():
        spec, i_e = early_inputs(fric, A, F, S, True)
        _, i_f = early_inputs(fric, A, F, S, False)
        st_e, met_e = direct_sweep(spec, i_e)
        st_f, met_f = direct_sweep(spec, i_f)
        out_e, out_f = outcomes(st_e, met_e, fric), outcomes(st_f, met_f, fric)
        with one_thread():
            t_e, t_f = best_of([lambda: direct_sweep(spec, i_e), lambda: direct_sweep(spec, i_f)],
                               repeats, time.process_time)
        r = dict(cells=A.size, same=int((out_e == out_f).sum()), per_early=t_e / A.size,
                 per_full=t_f / A.size, nfev_early=met_e[:, L.M_NFEV].mean(),
                 nfev_full=met_f[:, L.M_NFEV].mean(),
                 bounded=int((st_e == L.SAFE_BOUNDED).sum()),
                 drot=float(np.abs(met_e[:, L.M_MAX_ABS_THETA] - met_f[:, L.M_MAX_ABS_THETA]).max()),
                 dres=float(np.abs(met_e[:, L.M_RESIDUAL_SLIDE] - met_f[:, L.M_RESIDUAL_SLIDE]).max()),
                 outcomes={k: int(v) for k, v in zip(*np.unique(out_f, return_counts=True))})
        if not name.startswith("slide-rock"):
            idx = np.sort(np.random.default_rng(0).choice(A.size, n_scipy, replace=False))
            if name.startswith("stick"):     # Housner's model holds where the block never slips
                idx = idx[(met_f[idx, L.M_N_STICK_SLIP] == 0) & (met_f[idx, L.M_MAX_SLIDE] == 0)]
            sp_c = np.full(idx.size, np.inf)
            sp = []
            for j, i in enumerate(idx):
                for _ in range(scipy_repeats):
                    c0 = time.process_time()
                    o = scipy_reference(name, fric, A[i], F[i], S[i])
                    sp_c[j] = min(sp_c[j], time.process_time() - c0)
                sp.append(o)
            sp_out = np.array([o[0] for o in sp], dtype=object)
            sp_res = np.array([o[1] for o in sp])
            reps = 20
            sub = [early_inputs(fric, np.tile(A[idx], reps), np.tile(F[idx], reps),
                                np.tile(S[idx], reps), e)[1] for e in (True, False)]
            with one_thread():
                s_e, s_f = best_of([lambda: direct_sweep(spec, sub[0]),
                                    lambda: direct_sweep(spec, sub[1])], repeats, time.process_time)
            per_e, per_f = s_e / (reps * idx.size), s_f / (reps * idx.size)
            r.update(scipy_cells=int(idx.size), scipy_per=float(sp_c.mean()),
                     scipy_same=int((sp_out == out_e[idx]).sum()),
                     scipy_dres=float(np.abs(sp_res - met_e[idx, L.M_RESIDUAL_SLIDE]).max()),
                     sub_early=per_e, sub_full=per_f, ratio_early=sp_c.mean() / per_e,
                     ratio_full=sp_c.mean() / per_f)
        res[name] = r
    return res


def early_report(n=24, n_scipy=40, repeats=3):
    print(f"4. early decisions (issue #15): alpha 0.25 p 2, one-sine both signs {n}x{n}x2, a_p/(g tan a) "
          f"[1, 6] x w_p/p [0.5, 10], t_after {T_AFTER} s, rtol {E_RTOL:g} atol {E_ATOL:g}; 1 thread CPU time")
    for name, r in early_decisions(n, n_scipy, repeats).items():
        print(f"   {name:<18} outcomes {r['outcomes']}; early vs full: identical {r['same']}/{r['cells']}, "
              f"{r['bounded']} safe:bounded, max |d max_rotation| {r['drot']:.1e} rad, "
              f"max |d residual| {r['dres']:.1e} m")
        print(f"   {'':<18} per run {1e6 * r['per_early']:.1f} us early, {1e6 * r['per_full']:.1f} us full "
              f"({r['per_full'] / r['per_early']:.2f}x); mean nfev {r['nfev_early']:.0f} vs {r['nfev_full']:.0f}")
        if "scipy_per" in r:
            print(f"   {'':<18} SciPy on {r['scipy_cells']} cells: {1e3 * r['scipy_per']:.2f} ms per run, "
                  f"identical outcomes {r['scipy_same']}/{r['scipy_cells']}, max |d residual| "
                  f"{r['scipy_dres']:.1e} m; fastrock there {1e6 * r['sub_early']:.1f} us early / "
                  f"{1e6 * r['sub_full']:.1f} us full: ratio SciPy/fastrock {r['ratio_early']:,.0f}x early, "
                  f"{r['ratio_full']:,.0f}x full")


# ---------------------------------------------------------------- pytest-benchmark
@pytest.mark.parametrize("name", ["none", "inf", "mu10", "mu0.4"])
def test_bench_spectrum_30x30(benchmark, name):
    benchmark.group = "friction spectrum 30x30 one-sine (early exit where the kernel has it)"
    fric = {"none": None, "inf": INF, "mu10": INERT, "mu0.4": REAL["mu0.4"]}[name]
    df = benchmark.pedantic(spectrum, args=(fric, 30), rounds=2, iterations=1, warmup_rounds=1)
    assert (df["outcome"] != "failed").all()


@pytest.mark.parametrize("name", ["none", "inf"])
def test_bench_record_scene(benchmark, name):
    benchmark.group = "El Centro scene, one run"
    sc = record_scene(None if name == "none" else INF)
    benchmark.pedantic(sc.run, rounds=10, iterations=1, warmup_rounds=1)


def test_bench_friction_spectrum_50x50(benchmark):
    benchmark.group = "friction spectrum 50x50"
    df = benchmark.pedantic(spectrum, args=(REAL["mu0.4"], 50), rounds=1, iterations=1, warmup_rounds=1)
    assert (df["outcome"] != "failed").all()
    assert df.attrs["kernel"] == "rigid_friction"
    print(f"\n50x50 friction spectrum (mu_s 0.4): outcomes {df['outcome'].value_counts().to_dict()}")


def test_inf_friction_within_5_percent_of_no_friction():
    r = inf_vs_none(repeats=4, n=30)
    scene = r["scene_inf"] / r["scene_none"]
    spec = r["spectrum_inf"] / r["spectrum_none"]
    print(f"\nFriction(inf)/none, 1 thread CPU time: scene run {scene:.3f}, 30x30 spectrum {spec:.3f}")
    assert spec <= 1.05 and scene <= 1.05


def test_inert_friction_cost():
    c = inert_cost(repeats=2, n=20)
    print(f"\nmu=10 / rigid (kernels, 1 thread, no early exit, {c['cells']} cells): "
          f"{c['inert'] / c['rigid']:.3f} (nfev ratio {c['nfev_inert'] / c['nfev_rigid']:.3f})")
    assert c["same_status"] and c["max_peak_rel"] < 1e-5
    assert c["inert"] / c["rigid"] < 3.0


def test_inf_friction_scene_never_imports_the_friction_kernel():
    code = ("import sys, math, fastrock as fr\nfrom fastrock.running.scene import Scene\n"
            "b = fr.RigidBlock.rectangle(0.25, 1.0)\n"
            "Scene(b, excitation=fr.Pulse(0.3, 1.0), friction=fr.Friction(math.inf)).run()\n"
            "print('fastrock.kernels.friction' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_early_decisions_equal_outcomes():
    r = early_decisions(n=12, n_scipy=10, repeats=1)
    for name, c in r.items():
        print(f"\n{name}: identical {c['same']}/{c['cells']}, per run {1e6 * c['per_early']:.1f} us early "
              f"vs {1e6 * c['per_full']:.1f} us full" + (f", SciPy {c['ratio_early']:,.0f}x" if "ratio_early" in c
                                                       else ""))
        assert c["same"] == c["cells"]
        assert c.get("scipy_same", 0) == c.get("scipy_cells", 0)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats, 30x30 instead of 50x50")
    ap.add_argument("--early", action="store_true", help="only section 4, the early decisions")
    args = ap.parse_args()
    if args.early:
        print(f"fastrock {fr.__version__}, {os.cpu_count()} CPUs, load average {os.getloadavg()}")
        early_report(12 if args.quick else 24, 10 if args.quick else 40, 2 if args.quick else 3)
    else:
        report(args.quick)
        early_report(12 if args.quick else 24, 10 if args.quick else 40, 2 if args.quick else 3)
