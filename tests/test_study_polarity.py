"""Study.polarities (issue #16, item 7): a record run with both signs is one record with two
polarities, and the fragility bootstrap resamples records, not polarity copies."""
import numpy as np
import pandas as pd
import pytest

from fastrock import RigidBlock, Wall
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.default_records import load_default_record
from fastrock.studies.definition import Study, StudyError
from fastrock.analyses.fragility import fit_fragility
from fastrock.studies.run import run_study

pytest.importorskip("pyarrow")

BODY = RigidBlock.rectangle(0.2, 1.0)
LEVELS = [0.15, 0.3, 0.5]


@pytest.fixture(scope="module")
def rec():
    return load_default_record()


def test_the_negative_polarity_is_the_flipped_record(rec, tmp_path):
    """Rows of polarity -1 are bit for bit the runs of the record with its sign flipped."""
    kw = dict(bodies=[BODY], levels=LEVELS, t_after=3.0, variants=[{"wall": None}, {"wall": Wall(0.01)}])
    both = run_study(Study(records=[rec], polarities=(1, -1), **kw), tmp_path / "both", progress=False)
    flipped = run_study(Study(records=[GroundMotion(-rec.acc, rec.dt, name=rec.name)], **kw),
                        tmp_path / "flip", progress=False)
    plain = run_study(Study(records=[rec], **kw), tmp_path / "plain", progress=False)
    assert len(both) == 2 * len(plain) and set(both["polarity"]) == {1, -1}
    assert set(both["record"]) == {rec.name} and set(both["record_index"]) == {0}
    cols = ["variant", "level", "outcome", "max_rotation_ratio", "impacts", "wall_impacts", "time_end"]
    neg = both[both.polarity == -1][cols].reset_index(drop=True)
    pos = both[both.polarity == 1][cols].reset_index(drop=True)
    pd.testing.assert_frame_equal(neg, flipped[cols].reset_index(drop=True), check_exact=True)
    pd.testing.assert_frame_equal(pos, plain[cols].reset_index(drop=True), check_exact=True)
    assert (plain["polarity"] == 1).all()
    # the wall makes the two signs differ, or this test would not tell them apart
    assert not neg.equals(pos)


def test_default_polarity_keeps_the_study_hash(rec):
    kw = dict(records=[rec], bodies=[BODY], levels=LEVELS)
    assert Study(**kw).prepare().hash == Study(polarities=[1], **kw).prepare().hash
    assert Study(**kw).prepare().hash != Study(polarities=(1, -1), **kw).prepare().hash


def test_the_bootstrap_resamples_records_not_polarities():
    """Two polarities of 6 records: the fit counts 6 records, and every bootstrap resample
    carries both polarities of each record it draws."""
    rng = np.random.default_rng(5)
    rows = []
    for r in range(6):
        for pol in (1, -1):
            for lv in np.linspace(0.1, 1.0, 8):
                p = 1 / (1 + np.exp(-(np.log(lv / 0.4) / 0.3)))
                rows.append({"record": f"r{r}", "polarity": pol, "pga_g": lv,
                             "outcome": "mode1" if rng.random() < p else "safe"})
    df = pd.DataFrame(rows)
    fit = fit_fragility(df, n_boot=50, seed=1)
    assert fit.n_records == 6
    # the same data with the polarities named as records counts 12: what the copies did
    copies = df.assign(record=df.record + np.where(df.polarity > 0, "", " (-)"))
    assert fit_fragility(copies, n_boot=0).n_records == 12


@pytest.mark.parametrize("bad", [(), (1, 1), (2,), ("1",), "both", (True,)])
def test_bad_polarities_name_the_field(rec, bad):
    with pytest.raises(StudyError, match="polarities"):
        Study(records=[rec], bodies=[BODY], levels=LEVELS, polarities=bad).prepare()


def test_toml_polarities(tmp_path):
    (tmp_path / "s.toml").write_text('records = ["default"]\nlevels = [0.2]\npolarities = [1, -1]\n'
                                     '[[bodies]]\nb = 0.2\nh = 1.0\n')
    st = Study.from_toml(tmp_path / "s.toml")
    assert st.polarities == (1, -1) and st.n_runs == 2
