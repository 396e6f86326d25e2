"""run_batch (issue #15, item 6): heterogeneous single cases in one parallel call, one table;
every row equals the same scene's own run."""

import pytest

import fastrock as fr
from fastrock.io.default_records import load_default_record
from fastrock.model.foundation import TwoSpringFoundation

BLOCK = fr.RigidBlock.rectangle(0.15, 0.6)


def _scenes():
    rec = load_default_record()
    first = fr.SampledMotion(rec.acc[:400], rec.dt, scale=1.5)
    later = fr.SampledMotion(rec.acc[300:900], rec.dt, scale=2.0)     # another record: other samples
    flex = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=8.0, zeta=0.05)
    return [
        fr.Scene(BLOCK, fr.Pulse(0.05, 1.0), name="quiet"),
        fr.Scene(BLOCK, fr.Pulse(0.4, 1.2)),
        fr.Scene(BLOCK, first, name="record A"),
        fr.Scene(BLOCK, later, friction=fr.Friction(0.3), name="record B, sliding"),
        fr.Scene(BLOCK, fr.Pulse(0.35, 1.0, sign=-1), wall=fr.Wall(gap=0.01), name="wall"),
        fr.Scene(BLOCK, fr.Pulse(0.3, 1.0), friction=fr.Friction(0.5), ground=fr.Ground(0.05), name="slope"),
        fr.Scene(flex, fr.Pulse(0.3, 1.0), name="flexible"),
        fr.Scene(BLOCK, first, name="record A again"),
        fr.Scene(BLOCK, fr.Pulse(0.2, 2.0), foundation=TwoSpringFoundation.from_vibration(BLOCK, 40.0, 0.05,
                                                                                          mass=50.0),
                 mass=50.0, name="foundation"),
        fr.Scene(BLOCK, None, theta0=0.1, duration=3.0, name="free"),
    ]


@pytest.mark.parametrize("early_exit", [True, False])
def test_each_row_is_the_scene_run(early_exit):
    scenes = _scenes()
    df = fr.run_batch(scenes, early_exit=early_exit, progress=False)
    assert len(df) == len(scenes) and not df.attrs["interrupted"]
    assert df["scene"].tolist()[:2] == ["quiet", 1]
    assert len(set(df["kernel"])) >= 5
    for (_, row), scene in zip(df.iterrows(), scenes):
        r = scene.run(early_exit=early_exit)
        assert (row["kernel"], row["outcome"], row["status"]) == (r.kernel, r.outcome, r.status), scene.name
        assert row["max_rotation"] == r.metrics["max_rotation"], scene.name
        assert row["nfev"] == r.metrics["nfev"], scene.name
        if "residual_slide" in r.metrics:
            assert row["residual_slide"] == r.metrics["residual_slide"], scene.name
    assert set(df["outcome"]) >= {"safe", "mode1"}
    over = df["outcome"].isin(["mode1", "mode2"])
    assert (df.loc[over, "side"] != 0).all() and (df.loc[~over, "side"] == 0).all()


def test_dicts_and_bad_scenes():
    df = fr.run_batch([{"body": BLOCK, "excitation": fr.Pulse(0.05, 1.0)}], progress=False)
    assert df["outcome"].tolist() == ["safe"]
    with pytest.raises(ValueError, match=r"scenes\[1\].*slope"):
        fr.run_batch([fr.Scene(BLOCK, fr.Pulse(0.05, 1.0)),
                      fr.Scene(BLOCK, fr.Pulse(0.05, 1.0), ground=fr.Ground(0.3))], progress=False)
    with pytest.raises(ValueError, match=r"scenes\[0\]"):
        fr.run_batch([3.0], progress=False)
    with pytest.raises(ValueError, match="empty"):
        fr.run_batch([], progress=False)


def test_rigid_bodies_in_a_batch():
    wedge = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.25, h1=0.7, b2=0.12, h2=0.7)
    twin = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.15, h1=0.7, b2=0.15, h2=0.7)
    scenes = [fr.Scene(wedge, fr.Pulse(0.35, 1.0, sign=s)) for s in (1, -1)] + [fr.Scene(twin, fr.Pulse(0.35, 1.0))]
    df = fr.run_batch(scenes, progress=False)
    assert df["kernel"].tolist() == ["rigid_body", "rigid_body", "rigid"]
    for (_, row), scene in zip(df.iterrows(), scenes):
        r = scene.run(early_exit=True)
        assert (row["outcome"], row["status"], row["max_rotation"]) == (r.outcome, r.status, r.metrics["max_rotation"])
