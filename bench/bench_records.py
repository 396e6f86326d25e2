#!/usr/bin/env python
"""Rocking spectrum over recorded earthquakes: the full study, timed (issue 4, Bench).

Usage::

    python bench/bench_records.py            # full study + SciPy estimate (a few minutes)
    python bench/bench_records.py --quick    # 2 records, 10x10 blocks, 3 SciPy cases
    pytest bench/bench_records.py            # pytest-benchmark, reduced grid

What it measures
----------------
1. First call (compile or cache load) of the sweep kernels, apart.
2. The full study: every record in ``../shared/data/records/`` (the Sylmar file
   is in m/s^2, the others state g) x 400 blocks (20 b/h in [0.1, 0.5] x 20
   half-widths in [0.1, 1] m) x the wall settings (two-sided, d = 1 cm and
   10 cm when ``fastrock.wall`` is installed, else two-sided only -- printed).
   One ``fastrock.rocking_spectrum`` call; wall time, runs/s, work per run.
3. Record samples as breakpoints: work-precision on El Centro, RK45 with and
   without breakpoints and fixed steps that follow the record's dt.
4. A SciPy ``solve_ivp`` estimate: a plain event-driven rocking solver
   (RK45, same rtol/atol, same impact, chatter, overturning and wall rules,
   the record linearly interpolated, no breakpoints and no early exit -- the
   way such a solver is usually written) runs a random subsample of the
   study's rows; its mean time per run x the number of runs estimates the
   SciPy study, compared with fastrock's measured study time.  fastrock on
   the same subsample with one thread and without early exit gives the
   like-for-like per-run ratio too.

The machine may be shared: the load average is printed with the results.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RECORDS_DIR = Path(os.environ.get("FASTROCK_RECORDS_DIR",
                                  HERE.parents[1] / "shared" / "data" / "records"))
UNITS = {"Northridge_Sylmar_County.dat": "m/s2"}   # header does not state it
RTOL = 1e-8                     # fastrock's default, used by the study
ATOL = RTOL * 1e-2
T_AFTER = 10.0
EPS_OMEGA = 1e-9                # chatter-to-rest thresholds (fastrock defaults)
EPS_T = 1e-9


# ---------------------------------------------------------------- inputs
def record_files(directory=RECORDS_DIR):
    files = sorted(p for p in Path(directory).iterdir()
                   if p.is_file() and p.suffix.lower() in (".at2", ".dat"))
    if not files:
        raise SystemExit(f"no records in {directory} (set FASTROCK_RECORDS_DIR)")
    return files


def load(files):
    from fastrock.io.readers import read_record
    return [read_record(f, unit=UNITS.get(f.name)) for f in files]


# ------------------------------------------------------- SciPy baseline
def scipy_record_rocking(acc, dt, alpha, p, e, g=9.80665, wall_side=0, theta_w=math.inf,
                         e_w=1.0, rtol=RTOL, atol=ATOL, t_after=T_AFTER,
                         theta_over=math.pi / 2):
    """Rigid rocking under a sampled record with ``scipy.integrate.solve_ivp``.

    Same model as ``kernels/rigid.py`` (and ``kernels/wall.py`` for a tall
    wall with gap > 0): Housner's EOM
    theta'' = -p^2 [sin(s alpha - theta) + (a_g/g) cos(s alpha - theta)];
    uplift from rest when |a_g| >= g tan(alpha), s = -sgn(a_g), found exactly
    on the piecewise-linear record; ground impact theta'+ = e theta'-, s -> -s;
    chatter to rest when |theta'+| < eps_omega or impacts closer than eps_t;
    wall impact at w theta = theta_w (pivot w) with theta'+ = -e_w theta'-;
    overturning at |theta| = theta_over.  The record is interpolated inside
    the right-hand side and integrated across its samples (no breakpoints);
    the run lasts to the record end + t_after (no early exit).

    Returns (outcome, max|theta|/alpha, impacts, nfev).
    """
    from scipy.integrate import solve_ivp
    acc = np.asarray(acc, float)
    n = acc.size
    T = (n - 1) * dt
    t_end = T + t_after
    thr = g * math.tan(alpha)
    p2 = p * p
    state = {"s": 1.0}

    def ag_at(t):
        if t < 0.0 or t > T:
            return 0.0
        x = t / dt
        i = min(int(x), n - 2)
        fr = x - i
        return acc[i] + fr * (acc[i + 1] - acc[i])

    def rhs(t, y):
        s = state["s"]
        phi = s * alpha - y[0]
        return [y[1], -p2 * (math.sin(phi) + ag_at(t) * math.cos(phi) / g)]

    def impact(t, y):
        return state["s"] * y[0]

    def overturn(t, y):
        return theta_over - state["s"] * y[0]

    def peak(t, y):
        return state["s"] * y[1]

    def wall(t, y):
        if state["s"] != wall_side:
            return 1.0
        return theta_w - wall_side * y[0]

    for ev, term in ((impact, True), (overturn, True), (peak, False), (wall, True)):
        ev.terminal, ev.direction = term, -1
    events = (impact, overturn, peak, wall) if wall_side else (impact, overturn, peak)

    def uplift_after(t):
        """First time >= t with |a_g| >= thr on the linear interpolant."""
        if t > T:
            return math.inf
        if abs(ag_at(t)) >= thr:
            return t
        i0 = int(t / dt) + 1
        big = np.flatnonzero(np.abs(acc[i0:]) >= thr)
        if big.size == 0:
            return math.inf
        j = i0 + int(big[0])
        a0, a1 = (ag_at(t), acc[j]) if j == i0 else (acc[j - 1], acc[j])
        t0 = t if j == i0 else (j - 1) * dt
        target = math.copysign(thr, a1)
        fr = (target - a0) / (a1 - a0)
        return min(max(t0 + fr * (j * dt - t0), t), j * dt)

    t, y = 0.0, [0.0, 0.0]
    rocking = False
    impacts, t_last, max_abs, nfev = 0, -math.inf, 0.0, 0
    while True:
        if not rocking:
            tu = uplift_after(t)
            if not math.isfinite(tu):
                return "safe", max_abs / alpha, impacts, nfev
            t = tu
            state["s"] = -1.0 if ag_at(t) > 0.0 else 1.0
            y = [0.0, 0.0]
            rocking = True
        t_stop = T if t < T else t_end
        sol = solve_ivp(rhs, (t, t_stop), y, method="RK45", rtol=rtol, atol=atol, events=events)
        nfev += sol.nfev
        for yp in sol.y_events[2]:
            max_abs = max(max_abs, abs(yp[0]))
        if sol.status == 1 and len(sol.t_events[1]):
            return ("mode1" if impacts else "mode2"), theta_over / alpha, impacts, nfev
        if sol.status == 1 and wall_side and len(sol.t_events[3]):
            t = float(sol.t_events[3][-1])
            yw = sol.y_events[3][-1]
            max_abs = max(max_abs, abs(yw[0]))
            y = [float(yw[0]), -e_w * float(yw[1])]
            continue
        if sol.status == 1:
            t = float(sol.t_events[0][-1])
            post = e * float(sol.y_events[0][-1][1])
            impacts += 1
            state["s"] = -state["s"]
            y = [0.0, post]
            chatter = abs(post) < EPS_OMEGA or t - t_last < EPS_T
            t_last = t
            if chatter:
                y = [0.0, 0.0]
                ag = ag_at(t)
                if abs(ag) >= thr and ag != 0.0:
                    state["s"] = -1.0 if ag > 0.0 else 1.0
                else:
                    rocking = False
            continue
        if sol.status != 0:
            return "failed", max_abs / alpha, impacts, nfev
        y = [float(sol.y[0, -1]), float(sol.y[1, -1])]
        max_abs = max(max_abs, abs(y[0]))
        t = t_stop
        if t >= t_end:
            return "safe", max_abs / alpha, impacts, nfev


def _wall_args(gap, h):
    if gap is None or not np.isfinite(gap):
        return {}
    return {"wall_side": -1, "theta_w": math.asin(gap / (2 * h)) if gap < 2 * h else math.inf}


# -------------------------------------------------------------- sections
def first_call(records):
    from fastrock.analyses.rocking_spectrum.inputs import default_walls
    from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
    t0 = time.perf_counter()
    rocking_spectrum(records[:1], [0.2], [0.3], walls=default_walls(), progress=False)
    return time.perf_counter() - t0


def full_study(records, n_s=20, n_b=20, progress=True):
    from fastrock.analyses.rocking_spectrum.inputs import default_walls
    from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
    walls = default_walls()
    s = np.linspace(0.1, 0.5, n_s)
    b = np.linspace(0.1, 1.0, n_b)
    t0, c0 = time.perf_counter(), time.process_time()
    table, runs = rocking_spectrum(records, s, b, walls, progress=progress, return_runs=True)
    table.attrs["cpu_seconds"] = time.process_time() - c0
    return time.perf_counter() - t0, table, runs, walls


def work_precision(record):
    """max|theta|/alpha error against a tight reference, El Centro, 3 blocks."""
    from fastrock import RigidBlock, simulate
    from fastrock.analyses.rocking_spectrum.single_runs import simulate_record
    rows = []
    for b, h in [(0.3, 1.5), (0.25, 1.25), (0.5, 2.5)]:
        body = RigidBlock.rectangle(b, h)
        ref = simulate(body, record, rtol=1e-13, atol=1e-15, duration=20.0)
        m_ref = ref.metrics["max_rotation_ratio"]
        for label, kw in [("RK45 rtol 1e-4, breakpoints", dict(rtol=1e-4)),
                          ("RK45 rtol 1e-4, no breakpoints", dict(rtol=1e-4, record_breakpoints=False)),
                          ("RK45 rtol 1e-6, breakpoints", dict(rtol=1e-6)),
                          ("RK45 rtol 1e-6, no breakpoints", dict(rtol=1e-6, record_breakpoints=False)),
                          ("RK45 rtol 1e-8, breakpoints", dict(rtol=1e-8)),
                          ("RK45 rtol 1e-8, no breakpoints", dict(rtol=1e-8, record_breakpoints=False)),
                          ("fixed dt = record dt", dict(fixed=1)),
                          ("fixed dt = record dt / 4", dict(fixed=4))]:
            if "fixed" in kw:
                r = simulate_record(body, record, fixed_step=True, substeps=kw["fixed"], duration=20.0)
            else:
                r = simulate(body, record, duration=20.0, **kw)
            rows.append((label, b, h, abs(r.metrics["max_rotation_ratio"] - m_ref),
                         r.metrics["nfev"], r.metrics["rejected_steps"]))
    return rows


def fastrock_single_thread(records, sample, early_exit, repeats=3, copies=10):
    """Per-run CPU time of fastrock on the subsample rows, one thread: the
    rows ``copies`` times in one sweep call (amortising the Python packing),
    best of ``repeats``, ``time.process_time`` (robust on a shared machine)."""
    import numba
    from fastrock.analyses.rocking_spectrum.inputs import as_walls
    from fastrock.analyses.rocking_spectrum.engine import rows_sweep
    from fastrock.running.solver import make_solver
    names = [r.name for r in records]
    gaps = sorted({g for g in sample["wall_gap"] if np.isfinite(g)})
    walls = as_walls([None] + gaps)
    wall_idx = np.array([0 if not np.isfinite(g) else 1 + gaps.index(g) for g in sample["wall_gap"]])
    rec_idx = np.array([names.index(r) for r in sample["record"]])
    wall_idx, rec_idx = np.tile(wall_idx, copies), np.tile(rec_idx, copies)
    b = np.tile(sample["b"].to_numpy(), copies)
    s = np.tile(sample["slenderness"].to_numpy(), copies)
    old = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        best = math.inf
        for _ in range(repeats):
            t0 = time.process_time()
            rows_sweep(records, rec_idx, b, s, wall_idx, walls, e=None,
                        solver=make_solver(rtol=RTOL), t_after=T_AFTER, early_exit=early_exit,
                        progress=False, chunk_size=None)
            best = min(best, time.process_time() - t0)
        return best / b.size
    finally:
        numba.set_num_threads(old)


def scipy_subsample(records, runs, n_cases, seed=4):
    rng = np.random.default_rng(seed)
    # uplifting runs only: a run that never uplifts costs both codes ~nothing
    moving = runs[runs["status"] != "safe:no-uplift"]
    sample = moving.iloc[rng.choice(len(moving), size=min(n_cases, len(moving)), replace=False)]
    out = []
    for _, row in sample.iterrows():
        rec = next(r for r in records if r.name == row["record"])
        t0 = time.process_time()
        res = scipy_record_rocking(rec.acc, rec.dt, row["alpha"], row["p"], row["e"],
                                   **_wall_args(row["wall_gap"], row["h"]))
        out.append((time.process_time() - t0, res))
    return sample, out


# ---------------------------------------------------------------- report
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="2 records, 10x10 blocks, 3 SciPy cases")
    ap.add_argument("--scipy-cases", type=int, default=6, help="SciPy subsample size (default 6)")
    ap.add_argument("--no-progress", action="store_true")
    args = ap.parse_args(argv)
    import numba
    import fastrock
    files = record_files()
    if args.quick:
        files = [f for f in files if f.name in ("elCentro.AT2", "Northridge_Sylmar_County.dat")]
    records = load(files)
    n_s = n_b = 10 if args.quick else 20
    n_cases = 3 if args.quick else args.scipy_cases
    print(f"fastrock {fastrock.__version__}, numba {numba.__version__}, "
          f"{numba.get_num_threads()} threads, load average {os.getloadavg()[0]:.2f}")
    print(f"records ({RECORDS_DIR}):")
    for r in records:
        print(f"  {r.name:<28} PGA {r.pga_g:.3g} g  Tm {r.mean_period:.3g} s  "
              f"{r.npts} pts x {r.dt:g} s = {r.duration:.4g} s")

    t_first = first_call(records)
    print(f"\n== 1. first call (compile or cache load): {t_first:.2f} s")

    el, table, runs, walls = full_study(records, n_s, n_b, progress=not args.no_progress)
    n = len(runs)
    labels = [("two-sided" if w is None else f"wall d={w.gap:g} m") for w in walls]
    print(f"\n== 2. full study: {len(records)} records x {n_s * n_b} blocks x {len(walls)} wall "
          f"settings ({', '.join(labels)}) = {n} runs")
    if len(walls) == 1:
        print("   (fastrock.wall not installed: two-sided only)")
    print(f"   wall time {el:.2f} s (CPU {table.attrs['cpu_seconds']:.2f} s over all threads), "
          f"{n / el:,.0f} runs/s, "
          f"mean nfev/run {runs['nfev'].mean():,.0f}, load average {os.getloadavg()[0]:.2f}")
    print(f"   statuses: {runs['status'].value_counts().to_dict()}")
    print(f"   beta bounds: {table['beta_bound'].value_counts().to_dict()}, "
          f"non-monotone cells {int(table['non_monotone'].sum())} of {len(table)}")
    per_wall = runs.groupby("wall", sort=False).agg(runs=("nfev", "size"), nfev=("nfev", "sum"),
                                                    overturned=("outcome", lambda o: int(o.isin(["mode1", "mode2"]).sum())))
    print(per_wall.to_string())

    el_centro = next((r for r in records if r.name == "elCentro"), records[0])
    print(f"\n== 3. record samples as breakpoints (work-precision, {el_centro.name}, 20 s, "
          "error of max|theta|/alpha against rtol 1e-13)")
    wp = work_precision(el_centro)
    print(f"   {'integrator':<32} {'mean error':>10} {'mean nfev':>10} {'rejected':>9}")
    for label in dict.fromkeys(r[0] for r in wp):
        sel = [r for r in wp if r[0] == label]
        print(f"   {label:<32} {np.mean([r[3] for r in sel]):>10.1e} "
              f"{np.mean([r[4] for r in sel]):>10,.0f} {np.mean([r[5] for r in sel]):>9,.0f}")

    print(f"\n== 4. SciPy solve_ivp estimate ({n_cases} random uplifting runs of the study; "
          "CPU times)")
    sample, sp = scipy_subsample(records, runs, n_cases)
    fr_ee = fastrock_single_thread(records, sample, early_exit=True)
    fr_full = fastrock_single_thread(records, sample, early_exit=False)
    agree = 0
    print(f"   {'record':<26} {'wall':<14} {'b':>5} {'b/h':>6} {'fastrock':>9} {'scipy':>9} "
          f"{'scipy s':>8} {'nfev fr':>8} {'nfev sp':>8}")
    for (_, row), (ts, res) in zip(sample.iterrows(), sp):
        agree += res[0] == row["outcome"]
        print(f"   {row['record']:<26} {row['wall']:<14} {row['b']:>5.2f} {row['slenderness']:>6.3f} "
              f"{row['outcome']:>9} {res[0]:>9} {ts:>8.3f} {row['nfev']:>8,.0f} {res[3]:>8,}")
    t_sp = np.mean([x[0] for x in sp])
    # the subsample holds uplifting runs only; runs that never uplift cost ~0
    n_moving = int((runs["status"] != "safe:no-uplift").sum())
    est = t_sp * n_moving
    print(f"   outcomes agree in {agree} of {len(sp)} (SciPy steps over the record's kinks)")
    print(f"   SciPy mean per uplifting run {t_sp:.3f} s x {n_moving} uplifting runs "
          f"= {est:,.0f} s estimated ({est / 3600:.2f} h), serial")
    print(f"   fastrock, same runs, 1 thread: {fr_full * 1e3:.2f} ms/run without early exit "
          f"(x{t_sp / fr_full:,.0f} vs SciPy), {fr_ee * 1e3:.2f} ms/run with it")
    cpu = table.attrs["cpu_seconds"]
    print(f"   full study: SciPy estimate / fastrock measured = {est:,.0f} s / {el:.2f} s "
          f"= x{est / el:,.0f} (wall time, {numba.get_num_threads()} threads)")
    print(f"   by CPU time (robust to a loaded machine): {est:,.0f} s / {cpu:.2f} s = x{est / cpu:,.0f}")

    print("\n| quantity | value |\n|---|---|")
    print(f"| runs (records x blocks x walls) | {len(records)} x {n_s * n_b} x {len(walls)} = {n} |")
    print(f"| fastrock full study | {el:.1f} s wall ({n / el:,.0f} runs/s, {numba.get_num_threads()} "
          f"threads), {cpu:.1f} s CPU; load average {os.getloadavg()[0]:.1f} |")
    print(f"| first call (compile / cache load) | {t_first:.1f} s |")
    print(f"| SciPy solve_ivp estimate (serial) | {est:,.0f} s |")
    print(f"| ratio SciPy / fastrock, full study, wall time | x{est / el:,.0f} |")
    print(f"| ratio SciPy / fastrock, full study, CPU time | x{est / cpu:,.0f} |")
    print(f"| ratio per run, 1 thread, no early exit | x{t_sp / fr_full:,.0f} |")
    return 0


# ---------------------------------------------------- pytest-benchmark
def test_bench_rocking_spectrum_reduced(benchmark):
    """Reduced grid (2 records x 5 x 4 blocks x default walls), compile apart."""
    import pytest
    if not RECORDS_DIR.is_dir():
        pytest.skip(f"{RECORDS_DIR} absent (set FASTROCK_RECORDS_DIR)")
    from fastrock.analyses.rocking_spectrum.inputs import default_walls
    from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
    records = load([RECORDS_DIR / "elCentro.AT2", RECORDS_DIR / "RIO270.AT2"])
    s = np.linspace(0.1, 0.5, 5)
    b = np.linspace(0.1, 1.0, 4)
    walls = default_walls()
    table = benchmark.pedantic(rocking_spectrum, args=(records, s, b, walls),
                               kwargs={"progress": False}, rounds=3, warmup_rounds=1)
    assert len(table) == 2 * 4 * len(walls)
    benchmark.extra_info["runs"] = 2 * 20 * len(walls)


if __name__ == "__main__":
    sys.exit(main())
