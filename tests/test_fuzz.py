"""Short seeded sample of the fuzz suite (issue #14, item 2): ``bench/fuzz.py``.

Each family runs a fixed sample (seed 14, 32 runs per batch) through the same functions as the
long run: every case must end with a definite status, finite results and within the time
bound ("status"), and every invariant checked on it must hold ("invariants"; the rules are in
the docstring of bench/fuzz.py).  Where the baseline sample has failures, the check is marked
``xfail(strict=True)`` with the failure kind and count, so it turns into a hard failure the day
the kernels are fixed (then remove the mark).  About 45 s after compilation (one thread), plus
about 30 s for flexible_wall and contact.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

_FUZZ_PATH = Path(__file__).resolve().parent.parent / "bench" / "fuzz.py"
_spec = importlib.util.spec_from_file_location("fastrock_bench_fuzz", _FUZZ_PATH)
fuzz = importlib.util.module_from_spec(_spec)
sys.modules[_spec.name] = fuzz
_spec.loader.exec_module(fuzz)

pytestmark = pytest.mark.slow

SEED = 14
CHUNK = 32
TIME_LIMIT = 60.0
SAMPLE = {"rigid": 512, "wall": 512, "friction": 512, "flexible": 128, "flexible_friction": 256,
          "foundation": 128, "flexible_wall": 64, "contact": 256}

# failures of the baseline sample (seed 14) on commit 26893d8; see bench/README.md
KNOWN = {
    ("wall", "invariants"): "issue #14: violated:energy:fall, 1 of 512 cases (energy rises by more than "
                            "1e-6 + 100 rtol between two history rows of an overturning fall)",
    ("friction", "invariants"): "issue #14: violated:mu_inf, 32 of 512 cases (Friction(1e6) slides or "
                                "fails where the frictionless block does not)",
    # contact, commit cfdb6a0 (replayed): walls at small gaps end failed:transition-loop / face-contact:
    # contact:14:7 15 cells (gap 3.9e-9 m, Friction(inf, lift_off="flight"), e = 0.8, one-sine),
    # contact:14:2 3 cells (gap 9.4e-4 * 2h, Friction(0.507, lift_off="flight"), one-cosine, from
    # a_p/(g tan alpha) = 1.56), contact:14:5 3 cells (gap 1e-5 * 2h, Friction(0.37), a_p/(g tan alpha) = 30)
    ("contact", "status"): "issue #14: failed:transition-loop 20 + failed:face-contact 1, 21 of 256 cases "
                           "(contact:14:7, :2, :5: a wall at a small gap, see bench/README.md)",
}

_RESULTS = {}


def _sample(family):
    if family not in _RESULTS:
        _RESULTS[family] = fuzz.run_family(family, SAMPLE[family], SEED, CHUNK, TIME_LIMIT)
    return _RESULTS[family]


def _failures(rows, group):
    prefixes = ("violated",) if group == "invariants" else ("failed", "nan", "hang", "error")
    bad = [r for r in rows if any(k.startswith(prefixes) for k in r["result"].split(";"))]
    return bad


def _params():
    out = []
    for fam in SAMPLE:
        for group in ("status", "invariants"):
            reason = KNOWN.get((fam, group))
            marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
            out.append(pytest.param(fam, group, marks=marks, id=f"{fam}-{group}"))
    return out


@pytest.mark.parametrize("family,group", _params())
def test_fuzz_sample(family, group):
    rows, summ = _sample(family)
    assert summ["cases"] >= SAMPLE[family]
    bad = _failures(rows, group)
    msg = "\n".join(f"{r['batch']} a={r['amplitude_ratio']:.6g} f={r['frequency_ratio']:.6g} "
                    f"sign={r['sign']:+d}: {r['result']} {r['detail'][:200]}" for r in bad[:5])
    assert not bad, f"{len(bad)} of {summ['cases']} {family} cases failed ({group}):\n{msg}"


def test_fuzz_draws_are_reproducible():
    """A batch is a pure function of (family, seed, batch): the replay command depends on it."""
    for fam in fuzz.FAMILIES:
        assert fuzz.draw_batch(fam, SEED, 3) == fuzz.draw_batch(fam, SEED, 3)
        assert fuzz.draw_batch(fam, SEED, 3) != fuzz.draw_batch(fam, SEED, 4)


def test_energy_of_free_rocking_is_conserved_between_impacts():
    """The energy formula of the fuzz check on a history the kernel integrates tightly."""
    import numpy as np
    import fastrock as fr
    body = fr.RigidBlock.rectangle(0.2, 1.0)
    run = fr.simulate(body, theta0=0.15, duration=3.0, rtol=1e-11)
    E = fuzz.energy(run.history, body, {}, "rigid")
    up, fall = fuzz.energy_growth(run.history["t"].to_numpy(), E, -1.0, float(np.max(np.abs(E))),
                                  run.history["theta"].to_numpy(), body.alpha)
    assert run.metrics["impacts"] >= 2
    assert up < 1e-9 and fall == 0.0
