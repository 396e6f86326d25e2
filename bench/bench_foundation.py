#!/usr/bin/env python
"""Rocking against vibration (flexible foundation, fastrock/foundation.py): speed figures.

Usage::

    pytest bench/bench_foundation.py --benchmark-only      # pytest-benchmark table + the ratio

Set-up (the README's example, "Rocking against vibration"): block b = 0.1 m, h = 0.5 m
(alpha = 0.197, p = 4.37 rad/s), mass 10 kg, each foundation built ``from_vibration`` with
omega = 30 rad/s, zeta = 0.1 (switching: e_f = 0.95), rtol 1e-6 (atol 1e-8) everywhere.

1. ``simulate_foundation`` single runs, DataFrames included, for the three models
   (two_spring, switching, linear_sdof): the free release from theta0 = 0.1 rad (8 s; the
   two-spring block rocks with 15 re-contacts, then vibrates and comes to rest) and a one-sine
   pulse a_p/(g tan alpha) = 3, omega_p/p = 2 (+5 s).
2. The sweep kernels (``two_spring_sweep`` etc.) on a 20 x 20 pulse grid, a_p/(g tan alpha)
   1..6 x omega_p/p 0.5..10, t_after 5 s, all threads: what a spectrum would cost (there is no
   ``overturning_spectrum`` for foundations yet).
3. SciPy baseline, two-spring free release: ``solve_ivp`` RK45 with the same rtol/atol and the
   same model (the 2x2 mass system of physics.md 5.1; tensionless corner spring-dashpots with
   the kernel's contact / lift-off event functions, terminal, state switched at each; theta = 0
   crossings as events; overturning at theta_over).  It must give the same number of re-contacts
   and the same zero-crossing times (to 1e-4 s).  Ratio = SciPy / fastrock, measured in the same
   run, against the bare kernel (one row, one thread, no history) and against
   ``simulate_foundation`` (history and DataFrames).

Timings are minima over rounds (``benchmark.pedantic``, one warm-up round); the load average
goes into ``machine_info`` (bench/conftest.py).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import fastrock as fr
from fastrock.model import excitation as X
from fastrock.model import foundation as FD
from fastrock.running import foundation as RF
from fastrock.analyses.foundation_predictors import foundation_half_cycles
from fastrock.kernels import layout as L
from fastrock.running.solver import Solver
from ratios import one_thread  # shared bench helpers (bench/ is on sys.path)

BODY = fr.RigidBlock.rectangle(b=0.1, h=0.5)
MASS = 10.0
OMEGA, ZETA = 30.0, 0.1
THETA0 = 0.1
DURATION = 8.0
RTOL = 1e-6
ATOL = RTOL * 1e-2
T_AFTER = 5.0
PULSE = fr.Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
RESULTS = {}


def foundation(model):
    if model == "two_spring":
        return fr.TwoSpringFoundation.from_vibration(BODY, OMEGA, ZETA, MASS)
    if model == "switching":
        return fr.SwitchingFoundation.from_vibration(BODY, OMEGA, ZETA, e_f=0.95, mass=MASS)
    return fr.LinearVibration.from_vibration(BODY, OMEGA, ZETA, MASS)


MODELS = ("two_spring", "switching", "linear_sdof")


def free(model):
    return fr.simulate_foundation(BODY, foundation(model), mass=MASS, theta0=THETA0, duration=DURATION,
                                  rtol=RTOL, atol=ATOL)


def pulse(model):
    return fr.simulate_foundation(BODY, foundation(model), PULSE, mass=MASS, t_after=T_AFTER, rtol=RTOL,
                                  atol=ATOL)


# ------------------------------------------------------------------ sweep kernels
def sweep_inputs(model, cells, theta0=0.0, t_end=None):
    """Inputs of ``<model>_sweep`` for excitations ``cells`` (None: free motion for ``t_end``)."""
    fnd = foundation(model)
    spec, blk = RF.foundation_spec(BODY, fnd, MASS)
    rows = [X.to_header(BODY, exc) for exc in cells]
    HDR = np.array([h for h, _ in rows])
    smp = rows[0][1]
    n = len(cells)
    OPT = np.tile(Solver(rtol=RTOL, atol=ATOL).options(0.0, False), (n, 1))
    OPT[:, L.O_T_END] = [t_end if exc is None else X.end_time(BODY, exc) + T_AFTER for exc in cells]
    Y0 = np.tile(fnd.initial_state(blk, theta0, 0.0), (n, 1))
    return spec, (Y0, np.tile(spec.par, (n, 1)), HDR, smp, OPT)


def run_sweep(spec, inputs):
    Y0, PAR, HDR, smp, OPT = inputs
    n = Y0.shape[0]
    st = np.empty(n, np.int64)
    met = np.empty((n, L.N_MET))
    spec.sweep(Y0.copy(), PAR, HDR, smp, OPT, st, met, np.empty_like(Y0))
    return st, met


def pulse_grid(n):
    return [fr.Pulse(a, f, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
            for f in np.linspace(0.5, 10.0, n) for a in np.linspace(1.0, 6.0, n)]


# ------------------------------------------------------------------ SciPy baseline
def scipy_two_spring_free(fnd, theta0=THETA0, t_end=DURATION, rtol=RTOL, atol=ATOL, body=BODY, mass=MASS,
                          method="RK45"):
    """Free release of the two-spring model with solve_ivp (``method``: RK45, or Radau for stiff
    springs; physics.md 5.1, no ground motion).

    Returns (status, re-contacts "from above", zero-crossing times, nfev)."""
    blk = FD.block_inertia(body, mass)
    M, IC, b, h, g = blk.M, blk.I_C, blk.b, blk.h, blk.g
    kv, cv = fnd.k_v, fnd.c_v
    th_over = body.theta_over

    def comp(y, side):
        sq, cq = math.sin(y[2]), math.cos(y[2])
        return -(y[0] - side * b * sq), -(y[1] - side * b * cq * y[3])

    def force(y, side, on):
        if not on:
            return 0.0
        d, dd = comp(y, side)
        return kv * d + cv * dd

    def rhs(t, y):
        fR, fL = force(y, 1.0, on[0]), force(y, -1.0, on[1])
        sq, cq = math.sin(y[2]), math.cos(y[2])
        ry = fR + fL - M * g + M * h * cq * y[3] * y[3]
        rq = M * g * h * sq - b * cq * (fR - fL)
        mh = M * h * sq
        det = M * IC - mh * mh
        return [y[1], (IC * ry + mh * rq) / det, y[3], (mh * ry + M * rq) / det]

    def corner_event(side, slot, on):
        def ev(t, y):
            d, dd = comp(y, side)
            f = kv * d + cv * dd
            if on[slot]:
                return f                       # in contact while the corner pushes
            return -kv * d if cv * dd >= 0.0 else -f
        ev.terminal, ev.direction = True, -1
        return ev

    def cross(t, y):        # (on is the list the closures share)
        return y[2]

    def over(t, y):
        return th_over - abs(y[2])
    over.terminal, over.direction = True, -1

    y = fnd.initial_state(blk, theta0, 0.0)
    on = []
    for side in (1.0, -1.0):
        d, dd = comp(y, side)
        on.append(d >= 0.0 and kv * d + cv * dd > 0.0)
    t, nfev, impacts, crossings, status = 0.0, 0, 0, [], "safe"
    while t < t_end:
        evs = [corner_event(1.0, 0, on), corner_event(-1.0, 1, on), cross, over]
        sol = solve_ivp(rhs, (t, t_end), y, method=method, rtol=rtol, atol=atol, events=evs)
        nfev += sol.nfev
        crossings.extend(sol.t_events[2])
        if sol.status != 1:
            break
        if sol.t_events[3].size:
            status = "overturn"
            break
        k = 0 if sol.t_events[0].size else 1
        t, y = sol.t_events[k][0], sol.y_events[k][0].copy()
        side = 1.0 if k == 0 else -1.0
        if on[k]:
            on[k] = False
        else:
            on[k] = True
            if cv * comp(y, side)[1] >= 0.0:
                impacts += 1                   # landed from above (the kernel's "impact")
    return status, impacts, np.array(crossings), nfev


# ---------------------------------------------------------------- pytest-benchmark
@pytest.mark.parametrize("model", MODELS)
def test_bench_free_release(benchmark, model):
    benchmark.group = "foundation: simulate_foundation, free release theta0 0.1, 8 s"
    r = benchmark.pedantic(free, args=(model,), rounds=20, iterations=1, warmup_rounds=1)
    RESULTS[f"free-{model}"] = benchmark.stats.stats.min
    benchmark.extra_info.update(status=r.status, nfev=int(r.metrics["nfev"]), impacts=int(r.metrics["impacts"]))
    assert r.status == ("safe:no-uplift" if model == "linear_sdof" else "safe:rest")


@pytest.mark.parametrize("model", MODELS)
def test_bench_pulse(benchmark, model):
    benchmark.group = "foundation: simulate_foundation, one-sine 3 x 2, +5 s"
    r = benchmark.pedantic(pulse, args=(model,), rounds=20, iterations=1, warmup_rounds=1)
    benchmark.extra_info.update(status=r.status, nfev=int(r.metrics["nfev"]))
    assert r.outcome != "failed"


@pytest.mark.parametrize("model", MODELS)
def test_bench_sweep_20x20(benchmark, model):
    benchmark.group = "foundation: sweep kernel, 20x20 pulse grid, all threads"
    spec, inp = sweep_inputs(model, pulse_grid(20))
    st, met = benchmark.pedantic(run_sweep, args=(spec, inp), rounds=3, iterations=1, warmup_rounds=1)
    counts = {str(o): int(c) for o, c in zip(*np.unique([fr.outcomes.outcome_of(s) for s in st], return_counts=True))}
    benchmark.extra_info.update(outcomes=counts, runs_per_s=400 / benchmark.stats.stats.min,
                                mean_nfev=float(met[:, L.M_NFEV].mean()))
    print(f"\n{model} 20x20 pulse grid: {400 / benchmark.stats.stats.min:,.0f} runs/s, outcomes {counts}")
    assert (st >= 0).all()


def test_bench_two_spring_free_kernel(benchmark):
    benchmark.group = "foundation: two-spring free release, kernel vs SciPy"
    spec, inp = sweep_inputs("two_spring", [None], theta0=THETA0, t_end=DURATION)
    with one_thread():
        st, met = benchmark.pedantic(run_sweep, args=(spec, inp), rounds=30, iterations=1, warmup_rounds=1)
    RESULTS["kernel"] = benchmark.stats.stats.min
    benchmark.extra_info["nfev"] = int(met[0, L.M_NFEV])
    assert fr.outcomes.status_of(int(st[0])) == "safe:rest"


def test_bench_two_spring_free_scipy(benchmark):
    benchmark.group = "foundation: two-spring free release, kernel vs SciPy"
    fnd = foundation("two_spring")
    status, impacts, crossings, nfev = benchmark.pedantic(scipy_two_spring_free, args=(fnd,), rounds=3,
                                                          iterations=1, warmup_rounds=1)
    t_scipy = benchmark.stats.stats.min
    # the same model: same re-contacts, same zero crossings
    r = free("two_spring")
    hc = foundation_half_cycles(r)["t_end"].to_numpy()
    n = min(len(hc), len(crossings), 10)
    dev = float(np.max(np.abs(hc[:n] - crossings[:n])))
    benchmark.extra_info.update(nfev=nfev, impacts=impacts, fastrock_impacts=int(r.metrics["impacts"]),
                                crossing_dev_s=dev)
    assert status == "safe" and impacts == r.metrics["impacts"] and dev < 1e-4, (impacts, dev)
    lines = [f"\nSciPy solve_ivp two-spring free release: {t_scipy * 1e3:.1f} ms (nfev {nfev}; "
             f"re-contacts {impacts} = fastrock's; first {n} zero crossings within {dev:.1e} s)"]
    if "kernel" in RESULTS:
        ratio = t_scipy / RESULTS["kernel"]
        benchmark.extra_info["scipy_over_kernel"] = ratio
        lines.append(f"SciPy / fastrock kernel (1 thread, no history): {ratio:,.0f}x")
    if "free-two_spring" in RESULTS:
        ratio = t_scipy / RESULTS["free-two_spring"]
        benchmark.extra_info["scipy_over_simulate_foundation"] = ratio
        lines.append(f"SciPy / simulate_foundation (history + DataFrames): {ratio:,.0f}x")
    print("\n".join(lines))
