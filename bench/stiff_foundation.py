#!/usr/bin/env python
"""Stiff, damped springs: what Rodas4 (``Solver(method="auto")``) buys on the two-spring model.

Usage::

    python bench/stiff_foundation.py

The slender block of the foundation fuzz (b = 7.8 mm, h = 0.70 m, b/h = 0.011, 10 kg) on corner
springs ``from_vibration`` with omega/p = 82, zeta = 0.17 (the dashpots damp the base at ~1e5 1/s),
released from theta0 = alpha/2 and free for 2 s, rtol 1e-6 (atol 1e-8).  Runs, one thread:

- fastrock ``method="RK45"`` (DP5 alone: its step sits at the dashpots' stability limit);
- fastrock ``method="auto"`` (DP5, turning to Rodas4);
- SciPy ``solve_ivp`` Radau (implicit, stiff) on the same model (bench_foundation.py's event
  solver), and SciPy RK45 over the first 0.2 s only (its cost per simulated second is the figure).

Printed: steps / nfev / CPU time of each, the ratios, and a check that RK45, auto and Radau give
the same number of re-contacts and the same zero-crossing times (to 1e-5 s).
"""
from __future__ import annotations

import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import fastrock as fr  # noqa: E402
from fastrock.analyses.foundation_predictors import foundation_half_cycles  # noqa: E402
from bench_foundation import scipy_two_spring_free  # noqa: E402
from ratios import one_thread  # noqa: E402

BODY = fr.RigidBlock.rectangle(b=0.0078, h=0.70)
MASS = 10.0
FND = fr.TwoSpringFoundation.from_vibration(BODY, 82 * BODY.p, 0.17, MASS)
RTOL, ATOL = 1e-6, 1e-8
THETA0 = BODY.alpha / 2
T_END = 2.0


def cpu(fn, repeat=3):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def fastrock_run(method):
    return fr.simulate(BODY, foundation=FND, mass=MASS, theta0=THETA0, duration=T_END,
                       solver=fr.Solver(rtol=RTOL, atol=ATOL, method=method))


def main():
    print(f"load average {os.getloadavg()}")
    rows = {}
    with one_thread():
        for method in ("RK45", "auto"):
            fastrock_run(method)                     # compile / warm
            t, r = cpu(lambda: fastrock_run(method))
            rows[method] = (t, r.metrics["steps"], r.metrics["nfev"], r.metrics["impacts"],
                            foundation_half_cycles(r)["t_end"].to_numpy())
    t, (st, imp, cross, nfev) = cpu(lambda: scipy_two_spring_free(FND, THETA0, T_END, RTOL, ATOL, BODY, MASS,
                                                                  "Radau"), repeat=1)
    rows["SciPy Radau"] = (t, np.nan, nfev, imp, cross)
    t, (_st, _imp, _cross, nfev) = cpu(lambda: scipy_two_spring_free(FND, THETA0, 0.2, RTOL, ATOL, BODY, MASS,
                                                                      "RK45"), repeat=1)
    rows["SciPy RK45 (0.2 s)"] = (t, np.nan, nfev, np.nan, None)
    print(f"{'run':<22}{'CPU s':>10}{'steps':>10}{'nfev':>10}{'re-contacts':>13}")
    for k, (t, steps, nfev, imp, _c) in rows.items():
        print(f"{k:<22}{t:>10.4f}{steps:>10.0f}{nfev:>10.0f}{imp:>13.0f}")
    t_rk, t_auto = rows["RK45"][0], rows["auto"][0]
    print(f"fastrock RK45 / auto: {t_rk / t_auto:,.0f}x CPU, {rows['RK45'][1] / rows['auto'][1]:,.0f}x steps")
    print(f"SciPy Radau / fastrock auto: {rows['SciPy Radau'][0] / t_auto:,.0f}x")
    print(f"SciPy RK45 per simulated second / fastrock auto per simulated second: "
          f"{rows['SciPy RK45 (0.2 s)'][0] / 0.2 / (t_auto / T_END):,.0f}x")
    ref = rows["RK45"][4]
    for k in ("auto", "SciPy Radau"):
        c = rows[k][4]
        n = min(len(ref), len(c))
        dev = float(np.max(np.abs(ref[:n] - c[:n]))) if n else 0.0
        same = rows[k][3] == rows["RK45"][3]
        print(f"{k}: re-contacts {'equal' if same else 'DIFFER'} to RK45's, {n} zero crossings within {dev:.1e} s")
        assert same and dev < 1e-5, (k, dev)


if __name__ == "__main__":
    main()
