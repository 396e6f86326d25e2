"""A run that exhausts its step budget says so (issue #14: failed:* stays only for a numerical
limit the user set, and the error says which): the warning names max_steps, the time the run
reached and the steps the whole run would need at the rate so far."""
import re
import warnings

import pytest

import fastrock as fr

BLOCK = fr.RigidBlock(alpha=0.2, p=2.0)
PULSE = fr.Pulse(3.0, 2.5, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


def _budget_message(fn):
    with pytest.warns(RuntimeWarning, match="failed:step-budget") as rec:
        r = fn()
    assert r.status == "failed:step-budget"
    return r, " ".join(str(w.message) for w in rec if "step-budget" in str(w.message))


def test_simulate_names_the_budget_and_the_steps_needed():
    r, msg = _budget_message(lambda: fr.simulate(BLOCK, PULSE, solver=fr.Solver(max_steps=20),
                                                 early_exit=False))
    assert "max_steps = 20 steps" in msg
    t = float(re.search(r"ran out at t = ([0-9.e+-]+) s", msg).group(1))
    assert t == pytest.approx(r.metrics["time_end"], rel=1e-5)
    need = float(re.search(r"needs about ([0-9.e+-]+) steps", msg).group(1))
    assert need > 20
    # the estimate is the rate so far: a run with that budget (and a margin) finishes
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        full = fr.simulate(BLOCK, PULSE, solver=fr.Solver(max_steps=int(3 * need)), early_exit=False)
    assert not full.status.startswith("failed")


def test_simulate_foundation_names_the_budget():
    body = fr.RigidBlock.rectangle(0.1, 0.5)
    fnd = fr.TwoSpringFoundation.from_vibration(body, 40.0, 0.05)
    _r, msg = _budget_message(lambda: fr.simulate(body, PULSE, foundation=fnd, solver=fr.Solver(max_steps=30)))
    assert "max_steps = 30 steps" in msg


def test_a_run_within_its_budget_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = fr.simulate(BLOCK, PULSE)
    assert not r.status.startswith("failed")
