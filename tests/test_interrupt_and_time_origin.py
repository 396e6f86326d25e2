"""No unbounded loop and Ctrl-C inside a run (issue #18, item 4).

A static phase before a late pulse jumps to the pulse start instead of
scanning the quiet time; a t_start so late that float64 cannot resolve the
motion is refused; SIGINT stops a running kernel within one step."""
import os
import signal
import threading
import time
import warnings

import numpy as np
import pytest

from fastrock import FlexibleBody, Pulse, RigidBlock, SampledMotion, overturning_spectrum, simulate
from fastrock.io.default_records import load_default_record


def test_late_pulse_gives_the_shifted_answer():
    body = RigidBlock(0.25, 2.0)
    r0 = simulate(body, Pulse(1.0, 1.0))
    r1 = simulate(body, Pulse(1.0, 1.0, t_start=5e4))
    assert r1.outcome == r0.outcome == "mode2"
    assert r1.metrics["time_uplift"] - 5e4 == pytest.approx(r0.metrics["time_uplift"], abs=1e-9)
    assert r1.metrics["max_rotation_ratio"] == pytest.approx(r0.metrics["max_rotation_ratio"], rel=1e-9)
    # the quiet 5e4 s cost no integration: the same number of rhs evaluations
    assert abs(r1.metrics["nfev"] - r0.metrics["nfev"]) <= 0.05 * r0.metrics["nfev"]


def test_late_record_gives_the_shifted_answer():
    body = RigidBlock(0.25, 2.0)
    rec = load_default_record()
    r0 = simulate(body, SampledMotion.from_record(rec))
    r1 = simulate(body, SampledMotion.from_record(rec, t_start=1e4))
    assert r1.outcome == r0.outcome
    assert r1.metrics["max_rotation_ratio"] == pytest.approx(r0.metrics["max_rotation_ratio"], rel=1e-8)


@pytest.mark.parametrize("make", [lambda: Pulse(1.0, 1.0, t_start=1e11),
                                  lambda: SampledMotion.from_record(load_default_record(), t_start=1e11)])
def test_unresolvable_t_start_is_refused_at_once(make):
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"t_start = 1e\+11 s is too late.*resolves time only"):
        simulate(RigidBlock(0.25, 2.0), make())
    assert time.perf_counter() - t0 < 5.0     # a hang guard, not a speed target


def _sigint_after(seconds):
    def fire():
        time.sleep(seconds)
        os.kill(os.getpid(), signal.SIGINT)
    th = threading.Thread(target=fire, daemon=True)
    th.start()
    return th


def test_ctrl_c_stops_a_single_long_run():
    body = FlexibleBody(0.2, 2.0, 10.0, zeta=0.02)
    acc = np.random.default_rng(0).normal(0, 0.01, 2_000_000)       # 2000 s at 1 ms: seconds of work
    motion = SampledMotion(acc, 0.001, unit="g")
    simulate(body, SampledMotion(acc[:100], 0.001, unit="g"))        # compile outside the timing
    th = _sigint_after(0.5)
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        simulate(body, motion, t_eval=[1.0])
    th.join()
    assert time.perf_counter() - t0 < 3.0


def test_ctrl_c_inside_one_chunk_keeps_the_finished_rows():
    body = RigidBlock(0.05, 2.0)
    amps, freqs = np.linspace(0.5, 8, 300), np.linspace(0.3, 8, 300)
    full = overturning_spectrum(body, amps[:3], freqs[:3], progress=False, early_exit=False)
    th = _sigint_after(0.5)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        df = overturning_spectrum(body, amps, freqs, progress=False, chunk_size=90_000, early_exit=False)
    th.join()
    assert df.attrs["interrupted"]
    assert 0 < len(df) < 90_000          # one chunk of 90,000 rows, stopped inside it
    assert any("interrupted" in str(w.message) for w in rec)
    assert not (df["status"] == "failed:interrupted").any()
    # the kept rows are finished runs: the first ones equal an uninterrupted run
    k = min(3, len(df))
    np.testing.assert_array_equal(df["max_rotation"].to_numpy()[:k], full["max_rotation"].to_numpy()[:k])


def test_ctrl_c_during_a_run_calls_the_callers_own_handler():
    """SIGINT is deferred while a kernel runs (never raised inside the wait,
    where it could break the future's lock) and then handed to the handler
    the caller had installed."""
    body = FlexibleBody(0.2, 2.0, 10.0, zeta=0.02)
    acc = np.random.default_rng(0).normal(0, 0.01, 2_000_000)
    simulate(body, SampledMotion(acc[:100], 0.001, unit="g"))
    seen = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: seen.append(signum))
    try:
        th = _sigint_after(0.5)
        res = simulate(body, SampledMotion(acc, 0.001, unit="g"), t_eval=[1.0])
        th.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert seen == [signal.SIGINT]
    assert res.status == "failed:interrupted"
    assert signal.getsignal(signal.SIGINT) is previous
