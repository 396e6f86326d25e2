"""Shared pieces of the hard-case suites (``tests/test_*hard_cases*.py``; CI runs them a second
time under ``NUMBA_BOUNDSCHECK=1``).  Not a test module: pytest does not collect it."""
from __future__ import annotations

import numpy as np

import fastrock as fr


def definite(res, budget, columns=("theta", "theta_dot")):
    """The checks every hard case makes: a definite (non-failure) status, no NaN or inf in the
    history columns, and the run finished inside ``budget`` steps (accepted + rejected)."""
    assert not res.status.startswith("failed"), (res.status, res.metrics["steps"])
    assert np.isfinite(res.history[list(columns)].to_numpy()).all()
    assert res.metrics["steps"] + res.metrics["rejected_steps"] <= budget, res.metrics["steps"]
    return res


def long_record(duration=90.0, dt=0.005, peak_g=0.35, seed=7):
    """A synthetic record of ``duration`` s sampled at ``dt`` (90 s at 0.005 s: 18 000 samples,
    every one a breakpoint): band-limited noise under a sin^2 envelope, ``peak_g`` peak."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, dt)
    white = rng.standard_normal(t.size)
    smooth = np.convolve(white, np.ones(8) / 8, mode="same")
    acc = smooth * np.sin(np.pi * t / duration) ** 2
    acc *= peak_g * 9.80665 / np.abs(acc).max()
    return fr.SampledMotion(acc, dt)


def stand_in_check(t_end, max_steps, dt, outcome):
    """A run and the options for ``outcomes.checked_stable_step`` without a kernel: ``outcome(o,
    tried)`` gives (status code, met) for options ``o``; every try's (dt, budget) is recorded in
    the returned list."""
    from fastrock.kernels import layout as L
    opt = np.zeros(L.N_OPT)
    opt[L.O_T0], opt[L.O_T_END], opt[L.O_MAX_STEPS], opt[L.O_DT_FIXED] = 0.0, t_end, max_steps, dt
    tried = []

    def run(o):
        tried.append((o[L.O_DT_FIXED], o[L.O_MAX_STEPS]))
        return outcome(o, tried)
    return run, opt, tried
