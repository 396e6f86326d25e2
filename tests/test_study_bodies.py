"""Studies take RigidBody (issue #17): a symmetric one runs as its RigidBlock, an asymmetric one the
two-sided rocking model; every row equals simulate() of the same scene, and the side column
names the side it overturned to."""
import numpy as np
import pytest

import fastrock as fr
from fastrock.io.default_records import load_default_record
from fastrock.studies.definition import Study
from fastrock.studies.run import run_study

pytest.importorskip("pyarrow")


def test_rigid_bodies_in_a_study(tmp_path):
    rec = load_default_record()
    record = type(rec)(rec.acc[:600], rec.dt, name="El Centro, first 12 s")
    wedge = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.25, h1=0.7, b2=0.12, h2=0.7)
    twin = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.15, h1=0.7, b2=0.15, h2=0.7)
    study = Study(records=[record], bodies=[wedge, twin], levels=[0.1, 0.25, 0.5, 1.0], t_after=2.0,
                  polarities=(1, -1))
    df = run_study(study, tmp_path / "out", progress=False)
    assert set(df["kernel"]) == {"rigid_body", "rigid"}
    bodies = {0: wedge, 1: twin}
    for _, row in df.iterrows():
        motion = fr.SampledMotion.from_record(record, scale=row["scale"] * row["polarity"])
        r = fr.simulate(bodies[row["body_index"]], motion, t_after=2.0, early_exit=True)
        assert (r.kernel, r.status) == (row["kernel"], row["status"])
        assert r.metrics["max_rotation_ratio"] == row["max_rotation_ratio"]
        over = r.outcome in ("mode1", "mode2")
        assert row["side"] == (int(np.sign(r.history["theta"].iloc[-1])) if over else 0)
    assert (df["side"] != 0).any() and (df["side"] == 0).any()
