"""An asymmetric RigidBody beside a rear wall (issue #17 item 1: walls): with wall= alone the wall
model (entry wall_body, tests/test_wall_body.py), with friction= or a pivot that never slips but
may fly (Friction.never_slipping()) the contact model; the wall's contact angle from the body's
wall-side face (RigidBody.wall_face_top)."""
import math

import numpy as np
import pytest

import fastrock as fr

OUTLINE = [(0.0, 0.0), (1.0, 0.0), (0.8, 2.2), (0.0, 2.2)]     # right face leaning back
BODY = fr.RigidBody.from_polygon(OUTLINE, mass=1.0)
MIRROR = fr.RigidBody.from_polygon([(-x, y) for x, y in OUTLINE], mass=1.0)
AMPS, FREQS = np.array([1.2, 2.5, 5.0]), np.array([0.8, 2.5, 6.0])
NEVER_SLIPS = fr.Friction.never_slipping()


def test_contact_angle_from_the_wall_side_face():
    assert not BODY.is_symmetric
    top = BODY.wall_face_top(+1)
    assert top == pytest.approx(2.2 - BODY.h2, rel=1e-12)        # the outline's top above the CM
    for side, h in ((+1, BODY.h2), (-1, BODY.h1)):
        w = fr.Wall(0.05, side=side)
        assert w.limit_angle(BODY) == pytest.approx(math.asin(0.05 / (h + BODY.wall_face_top(side))), rel=1e-15)
    block = fr.RigidBody.from_polygon([(0, 0), (0.6, 0), (0.6, 2.0), (0, 2.0)], mass=1.0)
    assert fr.Wall(0.05).limit_angle(block) == fr.Wall(0.05).limit_angle(block.to_block())


@pytest.mark.parametrize("friction, kernel", [(None, "wall_body"), (NEVER_SLIPS, "contact_body")])
@pytest.mark.parametrize("side", [1, -1])
def test_the_wall_catches_the_body(side, friction, kernel):
    df = fr.overturning_spectrum(BODY, AMPS, FREQS, sign="both", wall=fr.Wall(0.05, side=side), progress=False,
                                 friction=friction)
    assert df.attrs["kernel"] == kernel
    assert not (df["side"] == side).any()                 # never over toward the wall
    toward = df[df["sign"] == -side]
    assert (toward["wall_impacts"] > 0).any() and {"mode1", "safe"} <= set(toward["outcome"].astype(str))
    free = fr.overturning_spectrum(BODY, AMPS, FREQS, sign="both", progress=False)
    assert (free["side"] == side).any()                   # without the wall it does fall that way


def test_mirror_body_mirror_wall_mirror_pulse():
    a = fr.overturning_spectrum(BODY, AMPS, FREQS, sign=1, wall=fr.Wall(0.05, side=1), progress=False,
                                friction=NEVER_SLIPS)
    b = fr.overturning_spectrum(MIRROR, AMPS, FREQS, sign=-1, wall=fr.Wall(0.05, side=-1), progress=False,
                                friction=NEVER_SLIPS)
    assert a.attrs["kernel"] == "contact_body"
    assert list(a["outcome"].astype(str)) == list(b["outcome"].astype(str))
    assert list(a["wall_impacts"]) == list(b["wall_impacts"])
    np.testing.assert_allclose(a["max_rotation"], b["max_rotation"], rtol=1e-9, atol=1e-12)


def test_wall_out_of_reach_is_no_wall():
    """A wall farther than the face height is never touched by a body that rocks: the same runs
    as the contact model without a wall (a pivot that never slips, following lift-off into
    flight). A body that flies moves sideways and may touch it while falling (3 of these 18 runs,
    each after a flight; the outcome and max rotation stay those without the wall)."""
    far = BODY.h2 + BODY.wall_face_top(1)
    a = fr.overturning_spectrum(BODY, AMPS, FREQS, sign="both", wall=fr.Wall(1.01 * far, side=1), progress=False,
                                friction=NEVER_SLIPS)
    b = fr.overturning_spectrum(BODY, AMPS, FREQS, sign="both", friction=fr.Friction(math.inf, lift_off="flight"),
                                progress=False)
    assert a.attrs["kernel"] == "contact_body"
    assert list(a["outcome"].astype(str)) == list(b["outcome"].astype(str))
    # the same runs up to rounding (the regression suites' contract)
    np.testing.assert_allclose(a["max_rotation"], b["max_rotation"], rtol=1e-12, atol=0)
    assert (a.loc[a["flights"] == 0, "wall_impacts"] == 0).all()


def test_simulate_scene_and_bad_input(tmp_path):
    w = fr.Wall(0.05, side=1)
    r = fr.simulate(BODY, fr.Pulse(2.5, 2.5, sign=-1, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                    wall=w)
    assert r.kernel == "wall_body" and r.metrics["wall_impacts"] > 0
    path = tmp_path / "rock.toml"
    path.write_text('[body]\ntype = "rigid-body"\nvertices = [[0, 0], [1, 0], [0.8, 2.2], [0, 2.2]]\nmass = 1.0\n'
                    '[wall]\ngap = 0.05\nside = 1\n[excitation]\nkind = "one-sine"\namplitude = 2.5\n'
                    'frequency = 2.5\nsign = -1\namplitude_unit = "g_tan_alpha"\nfrequency_unit = "omega_p/p"\n')
    one = fr.Scene.from_toml(path).run()
    assert (one.status, one.metrics["max_rotation"]) == (r.status, r.metrics["max_rotation"])
    with pytest.raises(ValueError, match="penetrates the wall"):
        fr.simulate(BODY, None, wall=w, theta0=0.9 * BODY.alpha2)
    overhang = fr.RigidBody.from_polygon([(0, 0), (1, 0), (1.3, 2.0), (0, 2.0)], mass=1.0)
    if overhang.outline[:, 0].max() > overhang.b2 * (1 + 1e-9):
        with pytest.raises(ValueError, match="overhang"):
            fr.simulate(overhang, None, wall=fr.Wall(0.05, side=1), duration=1.0)


def test_a_rounded_top_runs_the_wall_model_and_the_contact_model():
    """A rounded top touches the wall with its arc in both models (the wall model:
    tests/test_wall_rounded_top.py; the contact model: tests/test_contact_rounded_top.py), which
    catch the body at the arc's contact angle."""
    import dataclasses
    rounded = dataclasses.replace(BODY, top="rounded", top_radius=0.2)
    fr.simulate(rounded, None, theta0=0.01, duration=0.5)                 # without a wall it runs
    wall = fr.Wall(0.05, side=1)
    pulse = fr.Pulse(1.3 * math.tan(BODY.alpha2), 1.0, sign=-1)          # toward the wall
    run = fr.simulate(rounded, pulse, wall=wall, rtol=1e-10, duration=2.0)
    assert run.kernel == "wall_body"
    contact = fr.simulate(rounded, pulse, wall=wall, friction=NEVER_SLIPS, rtol=1e-10, duration=2.0)
    assert contact.kernel == "contact_body"
    for r in (run, contact):
        hits = r.events[r.events.event == "wall-impact"]
        assert hits.theta.iloc[0] == pytest.approx(wall.limit_angle(rounded), abs=1e-9)
    with pytest.raises(ValueError, match="top_radius"):                # the arc must fit on the face
        fr.simulate(dataclasses.replace(BODY, top="rounded", top_radius=5.0), None, wall=wall,
                    friction=NEVER_SLIPS, duration=0.5)