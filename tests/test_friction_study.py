"""The friction study of issue #6 (examples/friction_study.py) on a 10 x 10 grid.

The example's core (``run_study``, ``summarize``) runs the study body (alpha = 0.3,
omega_n/p = 9, zeta = 0.05, m_b = 0.1 m) under one-sine pulses for mu_s = 0.4, 0.8 and inf,
with lift_off "flight" (the default), "hold" and "stop".  Each assertion below also holds on the
80 x 80 grid of docs/validation/reproductions.md.
"""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "friction_study.py"


def _load_example():
    spec = importlib.util.spec_from_file_location("friction_study", EXAMPLE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


S = _load_example()
MUS = (0.4, 0.8)
CLASSIC = (math.inf, "hold")
INF_FLIGHT = (math.inf, "flight")


@pytest.fixture(scope="module")
def study():
    amps, freqs = S.grid(10)
    return amps, freqs, S.run_study(amps, freqs, mus=MUS + (math.inf,))


def _settled(df):
    return S.settled(S.classic_view(df).outcome)


def test_the_study_runs_every_lift_off_rule_and_flight_is_the_default(study):
    _, _, T = study
    assert S.DEFAULT_LIFT_OFF == "flight"
    assert set(T) == {(mu, lo) for mu in MUS for lo in ("flight", "hold", "stop")} | {CLASSIC, INF_FLIGHT}
    assert S.friction(math.inf, "flight").lift_off == "flight" and S.friction(math.inf, "hold") is None
    for (mu, lo), df in T.items():
        assert not df.outcome.isin(["failed"]).any(), (mu, lo)
        assert (df.flights > 0).any() == (lo == "flight")


def test_high_friction_reproduces_no_sliding(study):
    # hold: mu_s = 0.8 agrees with the classic model on 99 % of a 10 x 10 grid (80 x 80: 99.1 %);
    # flight: mu_s = 0.8 gives the outcomes of mu = inf with flight on every cell (80 x 80 too)
    # and agrees with the classic model on 99.8 % of the 80 x 80 cells
    _, _, T = study
    ref = T[CLASSIC].outcome
    assert (S.settled(T[(0.8, "hold")].outcome) == ref).mean() >= 0.9
    assert (_settled(T[(0.8, "flight")]) == _settled(T[INF_FLIGHT])).all()
    assert (_settled(T[(0.8, "flight")]) == ref).mean() >= 0.95


@pytest.mark.parametrize("lo", ["hold", "flight"])
@pytest.mark.parametrize("mu", MUS)
def test_runs_that_never_slip_follow_the_rigid_base_model(study, mu, lo):
    """A run that never slips, never needs tension at the pivot and never flies is the
    no-sliding run: same outcome and the same peak rotation (to the integration tolerance)."""
    _, _, T = study
    h, ref = T[(mu, lo)], T[CLASSIC]
    clean = ((h.max_slide == 0) & (h.lift_offs == 0) & (h.flights == 0) & (h.time_slide_rocking == 0)
             & (h.time_sliding == 0)).to_numpy()
    assert clean.sum() >= 10
    assert (h.max_rotation_ratio[clean] > 0.01).sum() >= 5      # rocking runs among them
    assert (h.outcome[clean] == ref.outcome[clean]).all()
    np.testing.assert_allclose(h.max_rotation_ratio[clean], ref.max_rotation_ratio[clean], rtol=0, atol=1e-6)


@pytest.mark.parametrize("mu", MUS)
def test_stop_ends_exactly_the_runs_that_need_tension(study, mu):
    """lift_off="stop", "hold" and "flight" are the same model until N first reaches 0: runs
    without a held lift-off are identical, runs with one end in flight under "stop" and fly
    under "flight"."""
    _, _, T = study
    hold, stop, flight = T[(mu, "hold")], T[(mu, "stop")], T[(mu, "flight")]
    lifted = (hold.lift_offs > 0).to_numpy()
    assert 0 < lifted.sum() < lifted.size
    assert (stop.outcome[lifted] == "flight").all()
    assert (stop.outcome[~lifted] == hold.outcome[~lifted]).all()
    np.testing.assert_allclose(stop.max_slide[~lifted], hold.max_slide[~lifted], rtol=1e-9, atol=1e-12)
    assert ((flight.flights > 0).to_numpy() == lifted).all()
    assert (flight.outcome[~lifted] == stop.outcome[~lifted]).all()
    np.testing.assert_array_equal(flight.max_slide[~lifted], stop.max_slide[~lifted])
    np.testing.assert_array_equal(flight.max_rotation[~lifted], stop.max_rotation[~lifted])


@pytest.mark.parametrize("lo", ["hold", "flight"])
def test_lower_friction_slides_more(study, lo):
    # mean max |d| over the cells that overturn at neither mu (80 x 80, hold: 16.1 mm against
    # 1.2 mm; flight: 15.9 mm against 0.35 mm)
    _, _, T = study
    h4, h8 = T[(0.4, lo)], T[(0.8, lo)]
    both = (~h4.outcome.isin(S.OVERTURNED) & ~h8.outcome.isin(S.OVERTURNED)).to_numpy()
    assert both.sum() >= 20
    assert h4.max_slide[both].mean() > h8.max_slide[both].mean() > 0


def test_flight_changes_only_runs_that_needed_tension_and_mode_2_keeps_its_cells(study):
    """Against "hold", flight changes outcomes only in runs that fly (80 x 80: 46-51 cells per
    mu, each a mode-1 cell of "hold" that survives).  In the classic sense (a body that skips on
    its pivot while it falls stays mode 2) the mode-2 cells are those of "hold" (80 x 80: the
    classic model's 1997 for mu_s >= 0.5); counting every landing as an impact, the kernel
    reports fewer (80 x 80 at mu_s = 0.8: 909)."""
    _, _, T = study
    for mu in MUS:
        fl, ho = T[(mu, "flight")], T[(mu, "hold")]
        changed = (_settled(fl) != S.settled(ho.outcome)).to_numpy()
        assert (fl.flights[changed] > 0).all()
        assert ((S.classic_view(fl).outcome == "mode2") == (ho.outcome == "mode2")).all()
        assert (fl.outcome == "mode2").sum() <= (fl.outcome_classic == "mode2").sum()
        over, over_h = fl.outcome.isin(S.OVERTURNED).to_numpy(), ho.outcome.isin(S.OVERTURNED).to_numpy()
        assert not (over & ~over_h).any()            # flight never overturns where "hold" survives
    assert ((S.classic_view(T[(0.8, "flight")]).outcome == "mode2") == (T[CLASSIC].outcome == "mode2")).all()


def test_classic_mode_of_an_event_log():
    ev = pd.DataFrame({"event": ["uplift", "flight", "contact", "flight", "contact", "overturn"],
                       "pivot": [1, 1, 1, 1, 1, 1]})
    assert S.classic_mode(ev) == "mode2"                            # skipped on its pivot
    assert S.classic_mode(ev.assign(pivot=[1, 1, -1, -1, -1, -1])) == "mode1"   # landed on the other corner
    assert S.classic_mode(ev.assign(pivot=[1, 0, 0, 1, 1, 1])) == "mode1"      # flat landing
    ev2 = pd.DataFrame({"event": ["uplift", "impact", "uplift", "overturn"], "pivot": [1, -1, -1, -1]})
    assert S.classic_mode(ev2) == "mode1"


def test_summary_counts(study):
    amps, freqs, T = study
    s = S.summarize(T, amps, freqs)
    assert len(s) == len(T)
    outcomes = ["safe", "slide", "mode1", "mode2", "flight", "failed"]
    assert (s[outcomes].sum(axis=1) == s.cells).all()
    assert (s.mode1 + s.mode2 == s.mode1_classic + s.mode2_classic).all()
    inf = s[np.isinf(s.mu_s)]
    assert (inf.slide == 0).all() and (inf.flight == 0).all() and (inf.changed_vs_inf == 0).all()
    hold = s[s.lift_off == "hold"]
    assert (hold.flight == 0).all() and (hold.failed == 0).all()
    flight = s[s.lift_off == "flight"]
    assert (flight.flight == 0).all() and (flight.failed == 0).all()
    stop = s[s.lift_off == "stop"].set_index("mu_s")
    assert (stop.flight == hold.set_index("mu_s").cells_with_lift_off).all()
    assert (stop.flight == flight[np.isfinite(flight.mu_s)].set_index("mu_s").cells_with_flight).all()
