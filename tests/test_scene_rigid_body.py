"""RigidBody in TOML scenes and studies: [body] type = "rigid-body" with its numbers, a 2D
outline (vertices) or a mesh file relative to the scene file (issue #17: every entry point)."""
import numpy as np
import pytest

import fastrock as fr
from fastrock.studies.definition import Study

BOX_OBJ = """v 0 0 0
v 0.4 0 0
v 0.4 0.3 0
v 0 0.3 0
v 0 0 1.2
v 0.4 0 1.2
v 0.4 0.3 1.2
v 0 0.3 1.2
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""

EXCITATION = '[excitation]\nkind = "one-sine"\namplitude = 0.5\nfrequency = 1.0\n'


def _scene(tmp_path, body):
    path = tmp_path / "rock.toml"
    path.write_text(body + EXCITATION)
    return fr.Scene.from_toml(path)


def test_numbers(tmp_path):
    scene = _scene(tmp_path, '[body]\ntype = "rigid-body"\nmass = 1.0\ninertia = 0.06\n'
                             'b1 = 0.25\nh1 = 0.7\nb2 = 0.12\nh2 = 0.7\n')
    body = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.25, h1=0.7, b2=0.12, h2=0.7)
    assert scene.body == body and scene.kernel == "rigid_body"
    a, b = scene.run(), fr.simulate(body, fr.Pulse(0.5, 1.0))
    assert (a.status, a.metrics["max_rotation"]) == (b.status, b.metrics["max_rotation"])


def test_outline(tmp_path):
    scene = _scene(tmp_path, '[body]\ntype = "rigid-body"\nvertices = [[0, 0], [0.5, 0], [0.3, 1.2], [0.05, 1.0]]\n'
                             'density = 2500\nthickness = 0.4\n')
    body = fr.RigidBody.from_polygon([(0, 0), (0.5, 0), (0.3, 1.2), (0.05, 1.0)], density=2500, thickness=0.4)
    assert (scene.body.alpha1, scene.body.alpha2, scene.body.mass) == (body.alpha1, body.alpha2, body.mass)
    assert scene.run().outcome == fr.simulate(body, fr.Pulse(0.5, 1.0)).outcome


def test_mesh_relative_to_the_scene_file(tmp_path):
    (tmp_path / "box.obj").write_text(BOX_OBJ)
    scene = _scene(tmp_path, '[body]\ntype = "rigid-body"\nmesh = "box.obj"\naxis = [0, 1, 0]\ndensity = 2000\n')
    body = fr.RigidBody.from_mesh(tmp_path / "box.obj", axis=(0, 1, 0), density=2000)
    assert scene.body.mass == pytest.approx(2000 * 0.4 * 0.3 * 1.2) and scene.body.mass == body.mass
    assert scene.body.is_symmetric and scene.kernel == "rigid"


def test_bad_tables(tmp_path):
    with pytest.raises(ValueError, match="vertices"):
        _scene(tmp_path, '[body]\ntype = "rigid-body"\nvertices = [1, 2, 3]\nmass = 1\n')
    with pytest.raises(ValueError, match="unknown key"):
        _scene(tmp_path, '[body]\ntype = "rigid-body"\nmass = 1\ninertia = 1\nb1 = 1\nh1 = 1\nb2 = 1\nh2 = 1\n'
                         'colour = "grey"\n')
    with pytest.raises(ValueError, match="type"):
        _scene(tmp_path, '[body]\ntype = "rock"\n')


def test_study_bodies_keep_their_outline(tmp_path):
    data = {"records": ["default"], "levels": [0.2, 0.4],
            "bodies": [{"type": "rigid-body", "vertices": [[0, 0], [0.5, 0], [0.3, 1.2], [0.05, 1.0]],
                        "mass": [100.0, 200.0]}]}
    prep = Study.from_dict(data, base=tmp_path).prepare()
    assert len(prep.bodies) == 2                      # the mass list expands, the outline does not
    assert [b.mass for b in prep.bodies] == [100.0, 200.0]
    assert np.isclose(prep.bodies[0].alpha1, prep.bodies[1].alpha1)
