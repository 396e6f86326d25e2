"""Study variants with friction and a flexible foundation (issue #13: studies go through the
model registry): every row equals simulate() of the same scene, and wall-only studies keep
their hash (so their saved results still resume)."""
from __future__ import annotations

import hashlib
import json

import numpy as np
import pytest

from fastrock import Friction, RigidBlock, SampledMotion, Wall, simulate
from fastrock.model.foundation import TwoSpringFoundation
from fastrock.constants import G_STANDARD
from fastrock.io.default_records import load_default_record
from fastrock.studies.definition import FORMAT, Study, StudyError, _canon, _study_hash
from fastrock.studies.run import run_study

pytest.importorskip("pyarrow")

BODY = RigidBlock.rectangle(0.15, 0.6)
LEVELS = [0.15, 0.7]


@pytest.fixture(scope="module")
def record():
    rec = load_default_record()
    return type(rec)(rec.acc[:700], rec.dt, name="El Centro, first 14 s")


def test_each_row_is_the_simulated_scene(record, tmp_path):
    fnd = {"type": "two-spring", "omega": 40.0, "zeta": 0.05}
    study = Study(records=[record], bodies=[BODY], levels=LEVELS, t_after=3.0,
                  variants=[{"name": "sliding", "friction": {"mu_s": 0.25}},
                            {"name": "felt", "foundation": fnd, "mass": 50.0},
                            {"name": "wall", "wall": 0.02}])
    df = run_study(study, tmp_path / "out", progress=False)
    assert sorted(set(df["kernel"])) == ["rigid_friction", "rigid_wall", "two_spring"]
    scenes = {"sliding": dict(friction=Friction(0.25)),
              "felt": dict(foundation=TwoSpringFoundation.from_vibration(BODY, 40.0, 0.05, mass=50.0),
                           mass=50.0),
              "wall": dict(wall=Wall(gap=0.02))}
    for _, row in df.iterrows():
        motion = SampledMotion.from_record(record, scale=row["scale"])
        kw = scenes[row["variant"]]
        r = simulate(BODY, motion, t_after=3.0, early_exit="foundation" not in kw, **kw)
        assert r.status == row["status"], row["variant"]
        assert r.metrics["max_rotation_ratio"] == row["max_rotation_ratio"]
    assert (df["outcome"] != "safe").any() and (df["outcome"] == "safe").any()


def test_toml_variants_take_friction_and_a_foundation(tmp_path):
    data = {"records": ["default"], "levels": [0.3], "bodies": [{"b": 0.15, "h": 0.6}],
            "variants": [{"name": "mu", "friction": {"mu_s": 0.4, "mu_k": 0.35}},
                         {"name": "felt", "foundation": {"type": "switching", "omega": 30.0, "e_f": 0.9},
                          "mass": 20.0}]}
    prep = Study.from_dict(data, base=tmp_path).prepare()
    assert [prep.specs[0, v].name for v in range(2)] == ["rigid_friction", "switching"]
    bad = dict(data, variants=[{"foundation": {"type": "linear", "k_t": 1e4}, "mass": -1.0}])
    with pytest.raises(StudyError, match="mass must be > 0"):
        Study.from_dict(bad, base=tmp_path).prepare()
    bad = dict(data, variants=[{"friction": {"mu": 0.4}}])
    with pytest.raises(StudyError, match="variants\\[0\\]"):
        Study.from_dict(bad, base=tmp_path).prepare()
    both = dict(data, variants=[{"friction": {"mu_s": 0.4}, "wall": 0.01}])
    assert Study.from_dict(both, base=tmp_path).prepare().specs[0, 0].name == "contact"
    at_wall = dict(data, variants=[{"friction": {"mu_s": 0.4}, "wall": 0.0}])      # gap 0: a block on a cliff
    assert Study.from_dict(at_wall, base=tmp_path).prepare().specs[0, 0].name == "contact"


def test_a_wall_only_study_keeps_its_hash(record):
    prep = Study(records=[record], bodies=[BODY], levels=LEVELS,
                 variants=[{"wall": None}, {"wall": 0.01, "name": "near"}]).prepare()
    recs = [{"name": r.name, "dt": repr(r.dt), "npts": r.npts,
             "acc": hashlib.sha256(np.ascontiguousarray(r.acc, "<f8").tobytes()).hexdigest()}
            for r in prep.records]
    doc = {"format": FORMAT, "records": recs, "bodies": _canon(prep.bodies),
           "variants": [[n, _canon(w)] for n, w in zip(prep.variant_names, prep.walls)],
           "levels": _canon(prep.levels), "measure": prep.measure, "solver": _canon(prep.solver),
           "t_after": repr(prep.t_after), "early_exit": prep.early_exit}
    before = hashlib.sha256(json.dumps(doc, sort_keys=True, separators=(",", ":")).encode()).hexdigest()
    assert _study_hash(prep) == before


def test_a_wall_field_added_later_leaves_saved_hashes_alone():
    # the canonical form of a wall as studies hashed it before Wall.friction existed
    assert _canon(Wall(0.01)) == {"__type__": "Wall", "gap": "0.01", "side": -1, "height": None,
                                  "restitution": "1.0"}
    assert _canon(Wall(0.01, friction=0.2))["friction"] == "0.2"
