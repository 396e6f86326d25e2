"""pytest-benchmark suite for the rigid block (issue 2 section 12, issue 8 section 5).

Run ``pytest bench/ --benchmark-only`` (see bench/README.md).  Set-up: alpha 0.25, p 2 rad/s,
Housner e, one-sine pulses of sign +1, rtol 1e-6 (atol 1e-8), pulse + 10 s.  Groups:

- ``simulate``: ``fastrock.simulate`` (front end, full time history and events, no early exit);
- ``kernel``: the raw ``rigid_simulate`` kernel without history, with and without early exit;
- ``scipy``: the ``solve_ivp`` RK45 event solver of ``ratios.py`` on the same cases;
- ``spectrum``: a 100x100 ``overturning_spectrum`` (2 threads);
- ``first-call``: a fresh interpreter that compiles (fresh ``NUMBA_CACHE_DIR``) or loads the
  cache, then runs one simulation and one spectrum cell.  The tracked time is the whole process;
  ``extra_info`` splits it into import, first call and warm call.

Every steady-state benchmark uses ``benchmark.pedantic`` with a warm-up round, so compilation
never lands in a timed round; compilation is measured only in ``first-call``.
"""
import math

import numpy as np
import pytest

import fastrock
import ratios as R
from fastrock.running.outcomes import status_of
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import N_COUNTERS
from fastrock.kernels.rigid import rigid_simulate

# name: (a_p / (g tan alpha), omega_p / p, outcome without early exit)
CASES = {
    "mode2": (4.5, 2.0, "overturn:mode2"),        # ~100 rhs evaluations
    "mode1": (3.0, 4.0, "overturn:mode1"),        # one impact, then overturns
    "safe-moving": (3.0, 5.5, "safe:moving"),     # 16 impacts, still rocking after 10 s
    "safe-rest": (3.5, 7.5, "safe:rest"),         # ~200 impacts chattering to rest
}


@pytest.fixture(scope="module")
def block():
    return R.body()


def _pulse(name):
    A, F, _ = CASES[name]
    return fastrock.Pulse(A, F, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


# ---- single simulations -------------------------------------------------------------------
@pytest.mark.benchmark(group="simulate")
@pytest.mark.parametrize("case", list(CASES))
def test_simulate(benchmark, block, case):
    pulse = _pulse(case)
    res = benchmark.pedantic(fastrock.simulate, args=(block, pulse), kwargs=dict(rtol=R.RTOL),
                             rounds=15, iterations=1, warmup_rounds=1)
    assert res.status == CASES[case][2]
    benchmark.extra_info.update(status=res.status, nfev=res.metrics["nfev"],
                                history_rows=len(res.history))


def _kernel_args(block, case, early_exit):
    A, F, _ = CASES[case]
    Y0, PAR, HDR, smp, OPT = R.sweep_inputs(block, np.array([A]), np.array([F]),
                                            early_exit=early_exit)
    empty = (np.empty(0), np.empty(0), np.empty((0, 2)), np.empty((0, 3), np.int64),
             np.empty((0, L.N_LOG)))
    return Y0[0], PAR[0], HDR[0], smp, OPT[0], empty


@pytest.mark.benchmark(group="kernel")
@pytest.mark.parametrize("early_exit", [False, True], ids=["full", "early-exit"])
@pytest.mark.parametrize("case", list(CASES))
def test_kernel(benchmark, block, case, early_exit):
    y0, par, hdr, smp, opt, (t_eval, hist_t, hist_y, hist_d, log) = _kernel_args(block, case,
                                                                                 early_exit)
    met = np.empty(L.N_MET)
    cnt = np.zeros(N_COUNTERS, np.int64)

    def one():
        cnt[:] = 0
        return rigid_simulate(y0.copy(), par, hdr, smp, opt, t_eval, met, hist_t, hist_y, hist_d,
                              log, cnt)

    code = benchmark.pedantic(one, rounds=30, iterations=5, warmup_rounds=1)
    if not early_exit:
        assert status_of(code) == CASES[case][2]
    benchmark.extra_info.update(status=status_of(code), nfev=int(met[L.M_NFEV]),
                                steps=int(met[L.M_NSTEPS]))


@pytest.mark.benchmark(group="scipy")
@pytest.mark.parametrize("case", list(CASES))
def test_scipy_solve_ivp(benchmark, block, case):
    """The SciPy baseline of ratios.py on the same case (no early exit)."""
    A, F, status = CASES[case]
    out = benchmark.pedantic(R.scipy_cell, args=(block, A, F), rounds=3, iterations=1,
                             warmup_rounds=1)
    assert out[0] == {"overturn:mode2": "mode2", "overturn:mode1": "mode1"}.get(status, "safe")
    benchmark.extra_info.update(outcome=out[0], nfev=out[3], steps=out[4])


# ---- spectrum -----------------------------------------------------------------------------
@pytest.mark.benchmark(group="spectrum")
@pytest.mark.parametrize("rtol", [R.RTOL, fastrock.running.solver.DEFAULT_RTOL])
def test_spectrum_100x100(benchmark, block, rtol):
    amps, freqs, _, _ = R.grid(100, 100)
    df = benchmark.pedantic(fastrock.overturning_spectrum, args=(block, amps, freqs),
                            kwargs=dict(rtol=rtol, progress=False), rounds=3, iterations=1,
                            warmup_rounds=1)
    assert len(df) == 10_000 and not (df.outcome == "failed").any()
    benchmark.extra_info.update(runs=len(df), rtol=rtol,
                                outcomes=df.outcome.value_counts().to_dict())
    if benchmark.stats is not None:
        benchmark.extra_info["runs_per_s_min"] = len(df) / benchmark.stats.stats.min


# ---- first call: compile and cache load (separate processes) ------------------------------
_COMPILED = {}


@pytest.fixture(scope="module")
def cache_root(tmp_path_factory):
    return tmp_path_factory.mktemp("numba-cache")


@pytest.mark.benchmark(group="first-call")
def test_first_call_compile(benchmark, cache_root):
    """Fresh NUMBA_CACHE_DIR: the child compiles rigid_simulate and rigid_sweep."""
    counter = iter(range(1000))

    def fresh():
        d = cache_root / f"cold{next(counter)}"
        d.mkdir()
        _COMPILED["dir"] = d
        return (d,), {}

    r = benchmark.pedantic(R.run_child, setup=fresh, rounds=1, iterations=1)
    assert r["stats"]["rigid_simulate"]["misses"] >= 1 and r["stats"]["rigid_sweep"]["misses"] >= 1
    benchmark.extra_info.update({k: round(v, 4) for k, v in r.items() if isinstance(v, float)})


@pytest.mark.benchmark(group="first-call")
def test_first_call_cache_load(benchmark, cache_root):
    """Second process on a populated cache: kernels load without recompiling."""
    d = _COMPILED.get("dir")
    if d is None:
        d = cache_root / "warm"
        d.mkdir()
        R.run_child(d)
    r = benchmark.pedantic(R.run_child, args=(d,), rounds=3, iterations=1, warmup_rounds=0)
    assert r["stats"]["rigid_simulate"] == {"hits": 1, "misses": 0}
    assert r["stats"]["rigid_sweep"] == {"hits": 1, "misses": 0}
    benchmark.extra_info.update({k: round(v, 4) for k, v in r.items() if isinstance(v, float)})
    assert math.isfinite(r["first_call_total"])
