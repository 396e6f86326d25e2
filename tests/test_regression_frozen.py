"""Frozen results of every model family: today's outputs must not change.

The grids (case definitions) live in ``tests/regression/freeze.py``, the frozen results in
``tests/data/regression/<case id>.csv.gz``.  Each case is recomputed here from the same
definitions and compared row by row with its frozen file.

Contract (``test_frozen_results``, the one refactors are held to):

* the same number of rows, and every frozen column still produced (new columns are ignored);
* text columns (``outcome``, ``status``, ``kernel``, ``event_counts``, the ``in_*`` input
  descriptions ...) and bool columns identical on every row;
* integer columns (``impacts``, ``wall_impacts``, ``status_code``, ``events`` ...) identical;
* every float column (max rotations, times of uplift/overturning, final states, maximum slide
  and deformation ...) within ``|a - b| <= 1e-12 * max(1, |b|)``, ``b`` the frozen value;
  NaN equals NaN and an infinity equals the same infinity.

Integration cost is apart: ``nfev``, ``steps``, ``rejected_steps`` and ``history_rows`` (the
rows of a simulate() history, one per accepted step and event) are compared exactly by
``test_step_counts_unchanged``, which a speed refactor may fail legitimately (a different step
sequence).  Deselect it with ``-k "not step_counts"`` and say so in the commit; note that a
changed step sequence almost always moves the floats by more than 1e-12 as well.

On failure the message names each changed row (by its inputs) and column, frozen -> new.
Never re-freeze to make this test pass: ``freeze.py`` refuses to overwrite without
``--overwrite``, which is meant only for a deliberate, announced change of results.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

_FREEZE_PATH = Path(__file__).resolve().parent / "regression" / "freeze.py"
_spec = importlib.util.spec_from_file_location("fastrock_regression_freeze", _FREEZE_PATH)
freeze = importlib.util.module_from_spec(_spec)
sys.modules[_spec.name] = freeze
_spec.loader.exec_module(freeze)

CASES = {c.id: c for c in freeze.CASES}
_RESULTS = {}


def _fresh(case):
    """Each case runs once per session; both tests below reuse the result."""
    if case.id not in _RESULTS:
        _RESULTS[case.id] = case.run()
    return _RESULTS[case.id]


def _frozen(case):
    if not case.path.exists():
        pytest.fail(f"{case.id} has no frozen file {case.path}; freeze a NEW case with "
                    f"`python tests/regression/freeze.py --missing {case.id}`")
    return freeze.read_frozen(case.path)


@pytest.mark.parametrize("case_id", list(CASES))
def test_frozen_results(case_id):
    case = CASES[case_id]
    frozen = _frozen(case)
    report = freeze.compare(_fresh(case), frozen)
    if report:
        pytest.fail(f"{case_id} ({case.setup}) changed against {case.path.name}:\n{report}",
                    pytrace=False)


@pytest.mark.parametrize("case_id", list(CASES))
def test_step_counts_unchanged(case_id):
    case = CASES[case_id]
    frozen = _frozen(case)
    report = freeze.compare(_fresh(case), frozen, cost=True)
    if report:
        pytest.fail(f"{case_id}: integration cost counters {freeze.COST_COLUMNS} changed (allowed "
                    f"for a deliberate speed change only):\n{report}", pytrace=False)


def test_every_case_is_frozen_and_every_file_is_a_case():
    files = {p.name for p in freeze.DATA_DIR.glob("*.csv.gz")}
    expected = {c.path.name for c in CASES.values()}
    assert not expected - files, f"cases without a frozen file: {sorted(expected - files)}"
    assert not files - expected, f"frozen files without a case definition: {sorted(files - expected)}"
    assert set(freeze.FAMILIES) == {"rigid", "wall", "friction", "contact", "flexible",
                                    "flexible_friction", "foundation", "records", "vertical"}


def test_compare_reports_changed_rows_and_columns():
    """The comparison itself: tolerance rule, NaN, strings, and a readable report."""
    import numpy as np
    import pandas as pd
    frozen = pd.DataFrame({"in_x": ["a", "b", "c"], "outcome": ["safe", "mode1", "safe"],
                           "impacts": np.array([1, 2, 3]), "max_rotation": [0.1, 2.0e3, np.nan],
                           "nfev": np.array([10, 20, 30])})
    same = frozen.copy()
    same["max_rotation"] = [0.1 + 0.9e-12, 2.0e3 * (1 + 0.9e-12), np.nan]
    same["nfev"] = [11, 20, 30]
    same["new_column"] = 1.0
    assert freeze.compare(same, frozen) == ""
    assert "nfev" in freeze.compare(same, frozen, cost=True)
    bad = frozen.copy()
    bad["max_rotation"] = [0.1 + 2e-12, 2.0e3, 0.0]
    bad["outcome"] = ["safe", "mode2", "safe"]
    report = freeze.compare(bad, frozen)
    assert "row 0 (x=a): max_rotation" in report
    assert "row 1 (x=b): outcome: 'mode1' -> 'mode2'" in report
    assert "row 2 (x=c): max_rotation: nan -> 0.0" in report
    assert "columns missing" in freeze.compare(frozen.drop(columns="impacts"), frozen)
    assert "row count" in freeze.compare(frozen.iloc[:2], frozen)
    text = freeze.to_csv_text(frozen)
    back = freeze.from_csv_text(text)
    assert freeze.compare(back, frozen) == "" and freeze.compare(back, frozen, cost=True) == ""
    assert list(back.dtypes.astype(str))[2:] == ["int64", "float64", "int64"]
