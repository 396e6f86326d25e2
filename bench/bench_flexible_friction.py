#!/usr/bin/env python
"""Flexible body with Coulomb friction (kernel ``flexible_friction``): speed figures.

Usage::

    pytest bench/bench_flexible_friction.py --benchmark-only

Set-up: ``FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9, zeta=0.05, base_mass_ratio=0.1)``
with ``Friction(0.5, lift_off="hold")`` (mu_s = 0.5 > tan alpha = 0.31: it rocks, slips at
impacts and slide-rocks on strong pulses), one-sine pulses, rtol 1e-8 (the default), t_after 10 s
for spectra, 5 s for single runs.  The same body without friction (kernel ``flexible``) is timed
alongside for scale: what the friction degrees of freedom cost.

1. ``fastrock.simulate`` single runs, DataFrames included: a pulse a_p/(g tan alpha) = 2.5,
   omega_p/p = 5 (stays up; slides about 2 mm: outcome "slide") and 3 x 3 (overturns, mode 1).
2. ``overturning_spectrum`` 20 x 20, a_p/(g tan alpha) 1..6 x omega_p/p 0.5..10, all threads,
   with and without friction (early exit on in both: each kernel stops a run at rest for good).

No SciPy baseline here: an event solver of the 6-state flexible slide-rock model (stick / slip
/ lift-off-hold modes and the full-contact impact rule) is not cheap to write; the flexible
body's SciPy ratio is in bench_flexible.py.
Timings are minima over rounds (``benchmark.pedantic``, one warm-up round).
"""
from __future__ import annotations

import numpy as np
import pytest

import fastrock as fr

BODY = fr.FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, base_mass_ratio=0.1)
FRICTION = fr.Friction(0.5, lift_off="hold")
CASES = {"slide (2.5, 5.0)": (2.5, 5.0), "mode1 (3.0, 3.0)": (3.0, 3.0)}
RESULTS = {}


def pulse(a, f):
    return fr.Pulse(a, f, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


def run(case, friction):
    return fr.simulate(BODY, pulse(*CASES[case]), friction=friction, t_after=5.0)


def spectrum(friction, n):
    return fr.overturning_spectrum(BODY, np.linspace(1.0, 6.0, n), np.linspace(0.5, 10.0, n), friction=friction,
                                   progress=False, t_after=10.0)


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("name", ["friction", "none"])
def test_bench_simulate(benchmark, case, name):
    benchmark.group = f"flexible friction: simulate, pulse {case}"
    fric = FRICTION if name == "friction" else None
    r = benchmark.pedantic(run, args=(case, fric), rounds=10, iterations=1, warmup_rounds=1)
    RESULTS[(case, name)] = benchmark.stats.stats.min
    benchmark.extra_info.update(kernel=r.kernel, outcome=r.outcome, nfev=int(r.metrics["nfev"]),
                                max_slide=float(r.metrics.get("max_slide", 0.0)))
    assert r.kernel == ("flexible_friction" if fric else "flexible")
    if fric is not None:
        assert r.outcome == ("slide" if case.startswith("slide") else "mode1")
    if len([k for k in RESULTS if k[0] == case]) == 2:
        ratio = RESULTS[(case, "friction")] / RESULTS[(case, "none")]
        print(f"\n{case}: friction / no friction = {ratio:.2f}")


@pytest.mark.parametrize("name", ["friction", "none"])
def test_bench_spectrum_20x20(benchmark, name):
    benchmark.group = "flexible friction: overturning_spectrum 20x20, all threads"
    fric = FRICTION if name == "friction" else None
    df = benchmark.pedantic(spectrum, args=(fric, 20), rounds=3, iterations=1, warmup_rounds=1)
    RESULTS[("spectrum", name)] = benchmark.stats.stats.min
    counts = df["outcome"].value_counts().to_dict()
    benchmark.extra_info.update(kernel=df.attrs["kernel"], outcomes=counts,
                                runs_per_s=400 / benchmark.stats.stats.min)
    assert df.attrs["kernel"] == ("flexible_friction" if fric else "flexible")
    assert (df["outcome"] != "failed").all()
    print(f"\n20x20 {name}: {400 / benchmark.stats.stats.min:,.0f} runs/s, {counts}")
    if ("spectrum", "friction") in RESULTS and ("spectrum", "none") in RESULTS:
        print(f"friction / no friction, 20x20 spectrum: "
              f"{RESULTS[('spectrum', 'friction')] / RESULTS[('spectrum', 'none')]:.2f}")
