"""The half-cycle definition of free-rocking data (issue #16, item 9): stated by the data, given
by the user, or chosen by the smaller residual with a warning, never silently assumed."""
import math
import warnings

import numpy as np
import pytest

from fastrock.analyses.freerocking import csv_input
from fastrock.analyses.freerocking import housner
from fastrock.analyses.freerocking import yu2019
from fastrock.analyses.freerocking.fitting import DefinitionWarning, fit_free_rocking
from fastrock.analyses.freerocking.csv_input import read_half_cycles_csv

ALPHA, THETA0, P, E = 0.25, 0.15, 3.0, 0.9


def _series(definition, n=10, first=None):
    first = housner.first_index(definition) if first is None else first
    idx = np.arange(first, first + n)
    return housner.housner_half_cycle_durations(THETA0, ALPHA, P, E, idx, definition), idx


@pytest.mark.parametrize("truth", ["impact", "peak"])
def test_unstated_definition_is_the_better_fit_with_a_warning(truth):
    d, _ = _series(truth, first=1)      # indices 1.. exist under both definitions
    with pytest.warns(DefinitionWarning, match="definition not given"):
        fit = fit_free_rocking(d, THETA0, ALPHA, half_cycle=np.arange(1, 11))
    assert fit.definition == truth and fit.definition_source.startswith("not given")
    assert fit.p == pytest.approx(P, rel=1e-6) and fit.e == pytest.approx(E, rel=1e-6)
    other = "peak" if truth == "impact" else "impact"
    assert fit_free_rocking(d, THETA0, ALPHA, half_cycle=np.arange(1, 11), definition=other).rms > 10 * fit.rms


def test_indices_that_admit_one_definition_decide_it_without_a_warning():
    d, idx = _series("impact", first=0)     # index 0, release to first impact, exists only for "impact"
    with warnings.catch_warnings():
        warnings.simplefilter("error", DefinitionWarning)
        fit = fit_free_rocking(d, THETA0, ALPHA, half_cycle=idx)
    assert fit.definition == "impact" and "indices" in fit.definition_source


def test_a_given_definition_is_used_as_given():
    d, idx = _series("peak")
    fit = fit_free_rocking(d, THETA0, ALPHA, half_cycle=idx, definition="peak")
    assert fit.definition_source == "given" and fit.p == pytest.approx(P, rel=1e-6)


def _csv(tmp_path, definition_line="", column=None, truth="peak"):
    d, idx = _series(truth, first=1)
    head = "half_cycle,duration" + (",definition" if column else "")
    rows = [f"{i},{float(x)!r}" + (f",{column}" if column else "") for i, x in zip(idx, d)]
    f = tmp_path / "hc.csv"
    f.write_text(definition_line + head + "\n" + "\n".join(rows) + "\n")
    return f


def test_the_csv_states_its_definition_by_comment_or_column(tmp_path):
    for kw in (dict(definition_line="# definition: peak\n"), dict(column="peak")):
        f = _csv(tmp_path, **kw)
        assert read_half_cycles_csv(f).attrs["definition"] == "peak"
        with warnings.catch_warnings():
            warnings.simplefilter("error", DefinitionWarning)
            fit = csv_input.fit_from_csv(f, theta0=THETA0, alpha=ALPHA)
        assert fit.definition == "peak" and fit.p == pytest.approx(P, rel=1e-6)
    assert read_half_cycles_csv(_csv(tmp_path)).attrs["definition"] is None
    with pytest.warns(DefinitionWarning, match="overrides"):
        csv_input.fit_from_csv(_csv(tmp_path, "# definition: peak\n"), theta0=THETA0, alpha=ALPHA, definition="impact")


@pytest.mark.parametrize("kw", [dict(definition_line="# definition: zigzag\n"),
                                dict(definition_line="# definition: peak\n", column="impact")])
def test_a_bad_or_contradictory_statement_is_refused(tmp_path, kw):
    with pytest.raises(ValueError, match="definition"):
        read_half_cycles_csv(_csv(tmp_path, **kw))


def test_the_packaged_measurements_state_impact():
    df = read_half_cycles_csv(yu2019._DATA_DIR / "yu2019_halfcycles.csv")
    assert df.attrs["definition"] == "impact"
    with warnings.catch_warnings():
        warnings.simplefilter("error", DefinitionWarning)
        fit = csv_input.fit_from_csv(yu2019._DATA_DIR / "yu2019_halfcycles.csv", alpha=math.radians(14.8))
    assert fit.definition == "impact" and fit.definition_source == "given"
