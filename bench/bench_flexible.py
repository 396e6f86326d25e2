#!/usr/bin/env python
"""Flexible rocking bodies: speed figures (issue #5, section 8 and the hard cases of section 6).

Usage::

    python bench/bench_flexible.py            # everything, prints the ratios (a few minutes)
    python bench/bench_flexible.py --quick    # 40x40 grid, 4 SciPy cases
    pytest bench/ -k bench_flexible           # the same measurements through pytest-benchmark
                                              # (naming the file itself collects it twice: the
                                              # bench/conftest.py hook plus pytest's own rule)

What it measures (alpha 0.3, p 2 rad/s, one-sine pulses, grid a_p/(g tan alpha) 1..6 x
omega_p/p 0.5..10, rtol 1e-8, t_after 10 s, early decisions on, both threads):

1. A 100x100 flexible spectrum (omega_n/p = 9, zeta = 0.05, full-contact map I3), wall time,
   against the rigid spectrum of the same grid (rigid e = cos^2 alpha, the I3 limit).
2. A plain SciPy ``solve_ivp`` event solver of the same flexible model (below: RK45, same
   rtol/atol, full contact / rocking phases, the signed uplift test of physics.md 3.3, the I3 map
   followed at once by the uplift test, overturning at pi/2, the same exact early decision after
   the pulse) on a random subsample of <= 10 cells; its mean time per run x 10 000 estimates the
   SciPy spectrum.  fastrock runs the same cells one thread, sequentially, for the per-run ratio.
3. The cost of stiff bodies: omega_n/p = 100 (and 9, and the rigid block) under three pulses
   (mode 2, mode 1, safe with many impacts): nfev, steps and time per run (one thread).

Timings are minima over repeats; the machine may be shared, so the load average is printed.
"""
from __future__ import annotations

import argparse
import math
import os
import time
import warnings

import numpy as np
from scipy.integrate import solve_ivp

import fastrock as fr
from fastrock.running import registry
from fastrock.kernels import layout as L
from fastrock.running.outcomes import outcome_of, status_of

ALPHA = 0.3
P = 2.0
WR = 9.0
ZETA = 0.05
RTOL = 1e-8
ATOL = RTOL * 1e-2
T_AFTER = 10.0
HARD_PULSES = {"mode2 (3.0, 1.0)": (3.0, 1.0), "mode1 (2.0, 2.0)": (2.0, 2.0),
               "safe (2.5, 6.0)": (2.5, 6.0)}


def grid(n):
    return np.linspace(1.0, 6.0, n), np.linspace(0.5, 10.0, n)


def flexible_body(wr=WR, zeta=ZETA, impact="full-contact"):
    return fr.FlexibleBody(alpha=ALPHA, p=P, omega_n_over_p=wr, zeta=zeta, impact=impact)


def rigid_body():
    return fr.RigidBlock(alpha=ALPHA, p=P, e=math.cos(ALPHA) ** 2)


def spectrum(body, n):
    a, f = grid(n)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fr.overturning_spectrum(body, a, f, progress=False, t_after=T_AFTER)


def timed(fn, *args, repeat=1):
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args)
        best = min(best, time.perf_counter() - t0)
    return best, out


# ------------------------------------------------------------------ fastrock, rows of a sweep
def sweep_cells(body, cells, threads=1, early_exit=True):
    """Run (amplitude_ratio, frequency_ratio) cells through the body's sweep kernel, one call per
    cell (sequential, like the SciPy loop).  Returns (seconds per run, status, MET)."""
    import numba
    spec = registry.select(body)
    opt = fr.Solver(rtol=RTOL).options(0.0, early_exit)
    old = numba.get_num_threads()
    numba.set_num_threads(threads)
    status, MET, total = [], [], 0.0
    try:
        for A, F in cells:
            om = F * body.p
            hdr = np.zeros((1, L.N_EXC))
            hdr[0, L.X_KIND] = L.EXC_ONE_SINE
            hdr[0, L.X_AMP] = A * body.g * math.tan(body.alpha)
            hdr[0, L.X_OMEGA] = om
            hdr[0, L.X_SIGN] = 1.0
            hdr[0, L.X_DUR] = 2 * math.pi / om
            o = opt.copy()[None, :]
            o[0, L.O_T_END] = hdr[0, L.X_DUR] + T_AFTER
            par = spec.par[None, :].copy()
            y0 = np.zeros((1, spec.n_state))
            st = np.zeros(1, np.int64)
            met = np.zeros((1, L.N_MET))
            yf = np.zeros((1, spec.n_state))
            t0 = time.perf_counter()
            spec.sweep(y0, par, hdr, np.zeros(1), o, st, met, yf)
            total += time.perf_counter() - t0
            status.append(int(st[0]))
            MET.append(met[0])
    finally:
        numba.set_num_threads(old)
    return total / len(cells), status, np.array(MET)


# ------------------------------------------------------------------ SciPy reference solver
class ScipyFlexible:
    """Straightforward solve_ivp (RK45) event solver of physics.md 3 with the I3 map."""

    def __init__(self, body, rtol=RTOL, atol=ATOL):
        self.b = body
        self.g = body.g
        self.B, self.H = body.B, body.H
        self.wn, self.z = body.omega_n, body.zeta
        self.im = body.rotary_inertia_ratio * body.R0 ** 2
        self.rtol, self.atol = rtol, atol
        self.nfev = 0

    def ag(self, t):
        return self.amp * math.sin(self.om * t) if 0.0 <= t <= self.T else 0.0

    def contact(self, t, y):
        self.nfev += 1
        return [y[1], -self.wn ** 2 * y[0] - 2 * self.z * self.wn * y[1] - self.ag(t), 0.0, 0.0]

    def rock(self, t, y, s):
        self.nfev += 1
        u, du, th, dth = y
        a = self.ag(t)
        r = u - s * self.B
        c, sn = math.cos(th), math.sin(th)
        X = r * c + self.H * sn
        Y = -r * sn + self.H * c
        fu = -self.wn ** 2 * u - 2 * self.z * self.wn * du + r * dth * dth + self.g * sn - a * c
        ft = self.g * X - a * Y - 2 * r * dth * du
        M = np.array([[1.0, self.H], [self.H, r * r + self.H ** 2 + self.im]])
        udd, tdd = np.linalg.solve(M, [fu, ft])
        return [du, udd, dth, tdd]

    def margin(self, t, y, s):
        """Uplift test 3.3 per unit mass: uplift about s when <= 0."""
        return self.g * (self.B - s * y[0]) - s * self.H * (self.wn ** 2 * y[0] + 2 * self.z * self.wn * y[1])

    def uplift_corner(self, t, y):
        mp, mm = self.margin(t, y, 1), self.margin(t, y, -1)
        if min(mp, mm) <= 0.0:
            return 1 if mp <= mm else -1
        return 0

    def never_uplifts(self, y):
        E = 0.5 * y[1] ** 2 + 0.5 * self.wn ** 2 * y[0] ** 2
        U, V = math.sqrt(2 * E) / self.wn, math.sqrt(2 * E)
        return self.H * (self.wn ** 2 * U + 2 * self.z * self.wn * V) < self.g * (self.B - U)

    def run(self, A, F, t_after=T_AFTER, max_phases=20000):
        b = self.b
        self.amp = A * b.g * math.tan(b.alpha)
        self.om = F * b.p
        self.T = 2 * math.pi / self.om
        t_end = self.T + t_after
        t, y, s = 0.0, np.zeros(4), 0          # s = 0: full contact
        impacts, uplifted, stuck = 0, False, 0
        for _ in range(max_phases):
            t_stop = self.T if t < self.T else t_end
            if s == 0:
                if t >= self.T and self.never_uplifts(y):
                    return ("safe", impacts)
                evs = []
                for sv in (1, -1):
                    ev = (lambda tt, yy, sv=sv: self.margin(tt, yy, sv))
                    ev.terminal, ev.direction = True, -1
                    evs.append(ev)
                sol = solve_ivp(self.contact, (t, t_stop), y, rtol=self.rtol, atol=self.atol,
                                events=evs)
                hit = [k for k in (0, 1) if sol.t_events[k].size]
                if hit:
                    k = min(hit, key=lambda k: sol.t_events[k][0])
                    t, y = sol.t_events[k][0], sol.y_events[k][0].copy()
                    s, uplifted = (1 if k == 0 else -1), True
                else:
                    t, y = sol.t[-1], sol.y[:, -1].copy()
                    if t >= t_end:
                        return ("safe", impacts)
                continue
            e_imp = (lambda tt, yy, s=s: s * yy[2])
            e_imp.terminal, e_imp.direction = True, -1
            e_over = (lambda tt, yy, s=s: b.theta_over - s * yy[2])
            e_over.terminal, e_over.direction = True, -1
            t_start = t
            sol = solve_ivp(lambda tt, yy: self.rock(tt, yy, s), (t, t_stop), y, rtol=self.rtol,
                            atol=self.atol, events=[e_imp, e_over])
            if sol.t_events[1].size and (not sol.t_events[0].size or sol.t_events[1][0] <= sol.t_events[0][0]):
                return ("mode1" if impacts else "mode2", impacts)
            if sol.t_events[0].size:
                t, y = sol.t_events[0][0], sol.y_events[0][0].copy()
                stuck = stuck + 1 if t == t_start else 0
                if stuck > 50:
                    return ("failed", impacts)
                impacts += 1
                y[1] += self.H * y[3]          # I3: horizontal momentum of the mass kept
                y[2] = y[3] = 0.0
                s = self.uplift_corner(t, y)
            else:
                t, y = sol.t[-1], sol.y[:, -1].copy()
                if t >= t_end:
                    return ("safe", impacts)
        return ("failed", impacts)


def scipy_subsample(body, cells):
    solver = ScipyFlexible(body)
    times, outs = [], []
    for A, F in cells:
        t0 = time.perf_counter()
        outs.append(solver.run(A, F))
        times.append(time.perf_counter() - t0)
    return np.array(times), outs, solver.nfev


def subsample(n, k, seed=5):
    a, f = grid(n)
    rng = np.random.default_rng(seed)
    idx = rng.choice(n * n, size=k, replace=False)
    return [(float(a[i % n]), float(f[i // n])) for i in idx]


# ------------------------------------------------------------------ stiff bodies
def stiff_costs(repeat=3):
    rows = []
    bodies = [("rigid e=cos^2a", rigid_body()), ("flex wn/p=9", flexible_body(9.0)),
              ("flex wn/p=100", flexible_body(100.0)),
              ("flex wn/p=100 zeta=0", flexible_body(100.0, zeta=0.0))]
    for name, b in bodies:
        for label, cell in HARD_PULSES.items():
            best = math.inf
            for _ in range(repeat):
                dt, st, met = sweep_cells(b, [cell])
                best = min(best, dt)
            rows.append(dict(body=name, pulse=label, status=status_of(st[0]),
                             nfev=int(met[0, L.M_NFEV]),
                             steps=int(met[0, L.M_NSTEPS] + met[0, L.M_NREJECT]),
                             impacts=int(met[0, L.M_IMPACTS]), ms=1e3 * best))
    return rows


# ------------------------------------------------------------------ report
def warm():
    """Compile or load from cache every kernel used, outside the timings."""
    t0 = time.perf_counter()
    spectrum(flexible_body(), 2)
    spectrum(rigid_body(), 2)
    sweep_cells(flexible_body(), [(2.0, 2.0)])
    sweep_cells(rigid_body(), [(2.0, 2.0)])
    return time.perf_counter() - t0


def main(quick=False):
    n = 40 if quick else 100
    k = 4 if quick else 10
    print(f"load average {os.getloadavg()}, {os.cpu_count()} cpus")
    print(f"warm-up (compile or cache load): {warm():.1f} s")
    t_flex, df = timed(spectrum, flexible_body(), n)
    t_rig, dr = timed(spectrum, rigid_body(), n, repeat=2)
    print(f"\n1. {n}x{n} one-sine spectrum (alpha {ALPHA}, grid 1..6 x 0.5..10, t_after {T_AFTER} s)")
    print(f"   flexible wn/p={WR:g} zeta={ZETA} I3: {t_flex:7.2f} s  ({n * n / t_flex:,.0f} runs/s, "
          f"mean nfev {df.nfev.mean():,.0f}); statuses {df.status.value_counts().to_dict()}")
    print(f"   rigid e=cos^2(alpha):          {t_rig:7.2f} s  ({n * n / t_rig:,.0f} runs/s, "
          f"mean nfev {dr.nfev.mean():,.0f})")
    print(f"   ratio flexible / rigid: {t_flex / t_rig:.1f}")

    cells = subsample(n, k)
    times, outs, nfev = scipy_subsample(flexible_body(), cells)
    fast, st, met = sweep_cells(flexible_body(), cells)
    est = times.mean() * n * n
    print(f"\n2. SciPy solve_ivp (RK45, rtol {RTOL:g}) on {k} random cells of the grid")
    for (A, F), tt, o, s_, m in zip(cells, times, outs, st, met):
        print(f"   a={A:5.2f} w={F:5.2f}  scipy {o[0]:6s} {o[1]:3d} impacts {tt:7.3f} s | fastrock "
              f"{outcome_of(s_):6s} {int(m[L.M_IMPACTS]):3d} impacts")
    agree = sum(o[0] == outcome_of(s_) for o, s_ in zip(outs, st))
    print(f"   outcomes agree on {agree}/{k} cells")
    print(f"   per run: scipy {times.mean():.3f} s, fastrock (1 thread) {fast * 1e3:.2f} ms -> "
          f"ratio {times.mean() / fast:,.0f}")
    print(f"   scipy {n}x{n} spectrum extrapolated: {est:,.0f} s = {est / 3600:.1f} h -> "
          f"ratio to fastrock's spectrum {est / t_flex:,.0f}")

    print("\n3. stiff bodies: cost per run (1 thread, early decisions on)")
    print(f"   {'body':22s} {'pulse':18s} {'status':18s} {'nfev':>9s} {'steps':>8s} {'impacts':>7s} {'ms':>9s}")
    for r in stiff_costs(2 if quick else 3):
        print(f"   {r['body']:22s} {r['pulse']:18s} {r['status']:18s} {r['nfev']:9,d} {r['steps']:8,d} "
              f"{r['impacts']:7d} {r['ms']:9.2f}")
    return dict(t_flex=t_flex, t_rigid=t_rig, scipy_est=est, per_run_ratio=times.mean() / fast)


# ------------------------------------------------------------------ pytest-benchmark
RESULTS = {}
BN = 100


def test_bench_flexible_spectrum_100x100(benchmark):
    warm()
    df = benchmark.pedantic(spectrum, args=(flexible_body(), BN), rounds=1, iterations=1)
    RESULTS["flex"] = benchmark.stats.stats.min
    benchmark.extra_info["runs_per_s"] = BN * BN / RESULTS["flex"]
    assert not df.status.str.startswith("failed").all()


def test_bench_rigid_spectrum_100x100(benchmark):
    warm()
    benchmark.pedantic(spectrum, args=(rigid_body(), BN), rounds=2, iterations=1)
    RESULTS["rigid"] = benchmark.stats.stats.min
    if "flex" in RESULTS:
        benchmark.extra_info["flexible_over_rigid"] = RESULTS["flex"] / RESULTS["rigid"]
        print(f"\nflexible / rigid 100x100 spectrum: {RESULTS['flex'] / RESULTS['rigid']:.1f}")


def test_bench_solve_ivp_subsample(benchmark):
    cells = subsample(BN, 10)
    times, outs, _ = benchmark.pedantic(scipy_subsample, args=(flexible_body(), cells), rounds=1,
                                        iterations=1)
    est = times.mean() * BN * BN
    benchmark.extra_info["scipy_100x100_estimate_s"] = est
    if "flex" in RESULTS:
        benchmark.extra_info["scipy_over_fastrock"] = est / RESULTS["flex"]
        print(f"\nsolve_ivp 100x100 (extrapolated from 10 cells) / fastrock: {est / RESULTS['flex']:,.0f}")


def test_bench_stiff_body_per_run(benchmark):
    warm()
    b = flexible_body(100.0)
    dt, st, met = benchmark.pedantic(sweep_cells, args=(b, list(HARD_PULSES.values())), rounds=3,
                                     iterations=1)
    benchmark.extra_info["nfev"] = [int(x) for x in met[:, L.M_NFEV]]
    assert all(s > 0 for s in st)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description="flexible-body speed figures")
    ap.add_argument("--quick", action="store_true")
    main(ap.parse_args().quick)
