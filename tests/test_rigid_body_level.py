"""Pivots at different heights (issue #17): RigidBody.on_level_ground() turns such a body onto one
ground plane, the pose in which sliding, flight, walls and flexible foundations take it.

Oracles:
- the turn is a rigid rotation about the centre of mass: mass, I_G, |r_k| (so R_k, I_O,k, p_k) and
  the angular-momentum restitutions e12, e21 (which depend on r_1 . r_2 only) are unchanged;
- a body given by numbers in a tilted pose equals the body of the same outline laid flat by
  ``from_polygon`` (an independent construction: the convex hull's lowest facet);
- a level body is returned as it is; one that cannot stand on level ground, and a rounded top,
  are refused naming the field;
- the models that need a level base say why and name ``on_level_ground``; the turned body runs
  there, also from a TOML scene."""
import math

import numpy as np
import pytest

import fastrock as fr
from fastrock import Friction, Pulse, RigidBody
from fastrock.model import geometry as geo

STEP = RigidBody(mass=2.0, inertia=0.15, b1=0.2, h1=0.8, b2=0.3, h2=0.9)
WEDGE = [(0.0, 0.0), (1.0, 0.0), (0.7, 1.6), (0.1, 1.9)]


def test_the_turn_keeps_the_rigid_body_invariants():
    flat = STEP.on_level_ground()
    assert flat.has_level_base and not STEP.has_level_base
    assert flat.h1 == flat.h2
    assert (flat.mass, flat.inertia, flat.e, flat.g, flat.theta_over) == \
        (STEP.mass, STEP.inertia, STEP.e, STEP.g, STEP.theta_over)
    for name in ("R1", "R2", "inertia_about_pivot1", "inertia_about_pivot2", "p1", "p2", "e12", "e21"):
        assert getattr(flat, name) == pytest.approx(getattr(STEP, name), rel=1e-13), name
    # the distance between the pivots, and the turn is clockwise for a higher right pivot
    assert flat.b1 + flat.b2 == pytest.approx(math.hypot(0.5, 0.1), rel=1e-14)
    assert flat.alpha2 > STEP.alpha2 and flat.alpha1 < STEP.alpha1


@pytest.mark.parametrize("tilt", [-0.2, -0.05, 0.03, 0.15])
def test_a_tilted_pose_given_by_numbers_equals_the_outline_laid_flat(tilt):
    body = RigidBody.from_polygon(WEDGE, mass=3.0)
    assert body.has_level_base
    # the same body described in a frame turned by tilt: its pivots at different heights
    (x1, y1), (x2, y2) = geo.rotate(np.array(body.pivots), tilt)
    tilted = RigidBody(mass=3.0, inertia=body.inertia, b1=-x1, h1=-y1, b2=x2, h2=-y2,
                       outline=geo.rotate(body.outline, tilt))
    assert not tilted.has_level_base
    back = tilted.on_level_ground()
    for name in ("b1", "h1", "b2", "h2", "alpha1", "alpha2"):
        assert getattr(back, name) == pytest.approx(getattr(body, name), rel=1e-12, abs=1e-14), name
    np.testing.assert_allclose(back.outline, body.outline, rtol=0, atol=1e-12)


def test_a_level_body_is_returned_as_it_is():
    body = RigidBody.from_polygon(WEDGE, mass=3.0)
    assert body.on_level_ground() is body


def test_bad_input_names_the_field():
    # turned onto the plane, the centre of mass falls outside the support
    with pytest.raises(ValueError, match=r"^h1, h2: the body cannot stand on level ground"):
        RigidBody(mass=1.0, inertia=0.1, b1=0.05, h1=0.2, b2=0.3, h2=1.5).on_level_ground()
    with pytest.raises(ValueError, match=r"^top: a rounded top"):
        RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.9, top="rounded",
                  top_radius=0.05).on_level_ground()


@pytest.mark.parametrize("kw, needs", [
    ({"friction": Friction(0.5)}, "friction=, wall= and flight need"),
    ({"foundation": fr.TwoSpringFoundation.from_vibration(fr.RigidBlock.rectangle(0.25, 0.85), 40.0, 0.05)},
     "foundation= needs"),
])
def test_the_models_on_one_plane_say_why_and_name_the_turn(kw, needs):
    with pytest.raises(ValueError) as exc:
        fr.simulate(STEP, Pulse(1.0, 1.0), **kw)
    msg = str(exc.value)
    assert msg.startswith("h1 = 0.8 m and h2 = 0.9 m differ: " + needs)
    assert "stand on a step" in msg and "body.on_level_ground()" in msg
    # the turned body runs there to a definite status
    run = fr.simulate(STEP.on_level_ground(), Pulse(1.0, 1.0), **kw)
    assert not run.status.startswith("failed"), run.status


def test_scene_key_on_level_ground(tmp_path):
    toml = tmp_path / "scene.toml"
    body = ('[body]\ntype = "rigid-body"\nmass = 2.0\ninertia = 0.15\nb1 = 0.2\nh1 = 0.8\nb2 = 0.3\n'
            'h2 = 0.9\n{}\n[excitation]\ntype = "pulse"\namplitude = 1.0\nfrequency = 1.0\n\n'
            '[friction]\nmu_s = 0.5\n')
    toml.write_text(body.format("on_level_ground = true\n"))
    scene = fr.Scene.from_toml(toml)
    assert scene.body == STEP.on_level_ground()
    got = scene.run()
    ref = fr.simulate(STEP.on_level_ground(), Pulse(1.0, 1.0), friction=Friction(0.5))
    assert got.status == ref.status and got.metrics["max_rotation"] == ref.metrics["max_rotation"]
    toml.write_text(body.format("on_level_ground = 1\n"))
    with pytest.raises(ValueError, match=r"on_level_ground must be true or false"):
        fr.Scene.from_toml(toml)
    toml.write_text(body.format(""))
    with pytest.raises(ValueError, match=r"on_level_ground = true"):
        fr.Scene.from_toml(toml).run()
