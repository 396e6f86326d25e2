"""The friction study of issue #6 (examples/friction_study.py) on a 10 x 10 grid.

The example's core (``run_study``, ``summarize``) runs the study body (alpha = 0.3,
omega_n/p = 9, zeta = 0.05, m_b = 0.1 m) under one-sine pulses for mu_s = 0.4, 0.8 and inf,
with lift_off "hold" and "stop".  Each assertion below also holds on the README's 80 x 80 grid.
"""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "friction_study.py"


def _load_example():
    spec = importlib.util.spec_from_file_location("friction_study", EXAMPLE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


S = _load_example()
MUS = (0.4, 0.8)


@pytest.fixture(scope="module")
def study():
    amps, freqs = S.grid(10)
    return amps, freqs, S.run_study(amps, freqs, mus=MUS + (math.inf,))


def test_high_friction_reproduces_no_sliding(study):
    # mu_s = 0.8: 99 % of a 10 x 10 grid and 99.1 % of the 80 x 80 grid agree with mu = inf
    _, _, T = study
    ref = T[(math.inf, "hold")].outcome
    agree = (S.settled(T[(0.8, "hold")].outcome) == ref).mean()
    assert agree >= 0.9, agree


@pytest.mark.parametrize("mu", MUS)
def test_runs_that_never_slip_follow_the_rigid_base_model(study, mu):
    """A run that never slips and never needs tension at the pivot is the no-sliding run:
    same outcome and the same peak rotation (to the integration tolerance)."""
    _, _, T = study
    h, ref = T[(mu, "hold")], T[(math.inf, "hold")]
    clean = ((h.max_slide == 0) & (h.lift_offs == 0) & (h.time_slide_rocking == 0)
             & (h.time_sliding == 0)).to_numpy()
    assert clean.sum() >= 10
    assert (h.max_rotation_ratio[clean] > 0.01).sum() >= 5      # rocking runs among them
    assert (h.outcome[clean] == ref.outcome[clean]).all()
    np.testing.assert_allclose(h.max_rotation_ratio[clean], ref.max_rotation_ratio[clean], rtol=0, atol=1e-6)


@pytest.mark.parametrize("mu", MUS)
def test_stop_ends_exactly_the_runs_that_need_tension(study, mu):
    """lift_off="stop" and "hold" are the same model until N first reaches 0: runs without a
    held lift-off are identical, runs with one end in flight."""
    _, _, T = study
    hold, stop = T[(mu, "hold")], T[(mu, "stop")]
    lifted = (hold.lift_offs > 0).to_numpy()
    assert 0 < lifted.sum() < lifted.size
    assert (stop.outcome[lifted] == "flight").all()
    assert (stop.outcome[~lifted] == hold.outcome[~lifted]).all()
    np.testing.assert_allclose(stop.max_slide[~lifted], hold.max_slide[~lifted], rtol=1e-9, atol=1e-12)


def test_lower_friction_slides_more(study):
    # mean max |d| over the cells that overturn at neither mu (80 x 80: 16.1 mm against 1.2 mm)
    _, _, T = study
    h4, h8 = T[(0.4, "hold")], T[(0.8, "hold")]
    both = (~h4.outcome.isin(S.OVERTURNED) & ~h8.outcome.isin(S.OVERTURNED)).to_numpy()
    assert both.sum() >= 20
    assert h4.max_slide[both].mean() > h8.max_slide[both].mean() > 0


def test_summary_counts(study):
    amps, freqs, T = study
    s = S.summarize(T, amps, freqs)
    assert len(s) == len(T)
    outcomes = ["safe", "slide", "mode1", "mode2", "flight", "failed"]
    assert (s[outcomes].sum(axis=1) == s.cells).all()
    inf = s[np.isinf(s.mu_s)].iloc[0]
    assert inf.slide == 0 and inf.flight == 0 and inf.changed_vs_inf == 0
    hold = s[s.lift_off == "hold"]
    assert (hold.flight == 0).all() and (hold.failed == 0).all()
    stop = s[s.lift_off == "stop"].set_index("mu_s")
    assert (stop.flight == hold.set_index("mu_s").cells_with_lift_off).all()
