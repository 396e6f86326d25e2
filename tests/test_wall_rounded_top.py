"""A rounded top beside a wall (issue #17: "optionally a flat or rounded top profile for wall
contact"): the top corner on the wall side is a quarter circle of radius rho, which touches a tall
wall with its front point and a short wall's top edge with the face or the arc (Wall.limit_angle).
Oracles: the contact conditions in closed form, an independent sampled-outline search, the flat
top as rho -> 0, the first wall impact of a run at theta_w, and a symmetric RigidBody equal to its
RigidBlock."""
import dataclasses
import math

import numpy as np
import pytest

import fastrock as fr

B, H, RHO = 0.3, 1.0, 0.25                 # face 2H = 2.0 m, straight part 1.75 m
BLOCK = fr.RigidBlock.rectangle(B, H, top_radius=RHO)
FLAT = fr.RigidBlock.rectangle(B, H)
A = 2.0 * H - RHO


def arc_centre(theta):
    """The arc's centre, turned by theta toward the wall about the pivot (x toward the wall)."""
    return (-RHO * math.cos(theta) + A * math.sin(theta), RHO * math.sin(theta) + A * math.cos(theta))


def sampled_contact_angle(d, height):
    """First rotation at which the sampled wall-side outline (face, arc, flat top) enters the wall
    {x >= d, y <= height}: bisection on a boolean, independent of the closed forms."""
    face = np.c_[np.zeros(400001), np.linspace(0.0, A, 400001)]
    phi = np.linspace(0.0, math.pi / 2, 200001)
    arc = np.c_[-RHO + RHO * np.cos(phi), A + RHO * np.sin(phi)]
    top = np.c_[-np.linspace(RHO, 2 * B, 2001), np.full(2001, 2 * H)]
    P = np.vstack([face, arc, top])
    top_y = math.inf if height is None else height

    def inside(t):
        x = P[:, 0] * math.cos(t) + P[:, 1] * math.sin(t)
        y = -P[:, 0] * math.sin(t) + P[:, 1] * math.cos(t)
        return bool(((x >= d) & (y <= top_y)).any())

    lo, hi = 0.0, 1.2
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if inside(mid) else (mid, hi)
    return hi


@pytest.mark.parametrize("d, height, branch", [
    (0.05, None, "tall"), (0.3, None, "tall"), (0.1, 1.9, "tall"),
    (0.5, 1.7, "short"), (0.6, 1.66, "short"), (0.4, 1.72, "short"),   # the arc meets the edge
    (0.05, 1.5, "short"), (0.2, 1.0, "short"),                          # the straight face meets it
])
def test_contact_angle_meets_the_contact_condition(d, height, branch):
    w = fr.Wall(d, side=1, height=height)
    t = w.limit_angle(BLOCK)
    assert w.contact(BLOCK) == branch
    cx, cy = arc_centre(t)
    if branch == "tall":
        assert cx + RHO - d == pytest.approx(0.0, abs=1e-14)        # the arc's front point on the wall
        assert height is None or cy <= height
    elif math.hypot(d, height) > A:
        assert math.hypot(d - cx, height - cy) - RHO == pytest.approx(0.0, abs=1e-14)   # arc on the edge
        direction = math.atan2(height - cy, d - cx) + t            # in the body's frame
        assert 0.0 <= direction <= math.pi / 2                     # on the quarter arc
    else:
        assert t == math.atan2(d, height)                           # the straight face through the edge
    # the sampled outline's first contact (samples 4.4e-6 m apart on the face, 7.9e-6 rad on the arc)
    assert t == pytest.approx(sampled_contact_angle(d, height), abs=1e-6)


def test_rounded_top_touches_later_and_tends_to_the_flat_top():
    for d, height in ((0.05, None), (0.3, None), (0.5, 1.7), (0.2, 1.0)):
        w = fr.Wall(d, side=-1, height=height)
        assert w.limit_angle(BLOCK) >= w.limit_angle(FLAT)
        nearly_flat = fr.RigidBlock.rectangle(B, H, top_radius=1e-9)
        assert w.limit_angle(nearly_flat) == pytest.approx(w.limit_angle(FLAT), abs=1e-8)
    # a flat top is bit for bit the formula it had: asin(d / 2h) and atan(d / h_w)
    assert fr.Wall(0.05).limit_angle(FLAT) == math.asin(0.05 / 2.0)
    assert fr.Wall(0.05, height=1.0).limit_angle(FLAT) == math.atan2(0.05, 1.0)


@pytest.mark.parametrize("side", [1, -1])
def test_first_wall_impact_of_a_run_is_at_the_rounded_contact_angle(side):
    wall = fr.Wall(0.08, side=side)
    run = fr.simulate(BLOCK, fr.Pulse(0.5, 1.0, sign=-side), wall=wall)
    hits = run.events[run.events.event == "wall-impact"]
    assert len(hits) > 0
    assert hits.theta.iloc[0] == pytest.approx(side * wall.limit_angle(BLOCK), abs=1e-12)
    flat = fr.simulate(FLAT, fr.Pulse(0.5, 1.0, sign=-side), wall=wall)
    first_flat = flat.events[flat.events.event == "wall-impact"].theta.iloc[0]
    assert abs(hits.theta.iloc[0]) > abs(first_flat)               # later than the square corner


def test_symmetric_rigid_body_with_a_rounded_top_equals_its_block():
    body = dataclasses.replace(fr.RigidBody.from_block(FLAT), top="rounded", top_radius=RHO)
    assert body.is_symmetric and body.to_block() == BLOCK
    assert fr.RigidBody.from_block(BLOCK).top == "rounded"
    assert fr.RigidBody.from_block(BLOCK).to_block() is BLOCK
    wall = fr.Wall(0.05, side=1)
    a = fr.simulate(body, fr.Pulse(0.6, 1.2, sign=-1), wall=wall)
    b = fr.simulate(BLOCK, fr.Pulse(0.6, 1.2, sign=-1), wall=wall)
    assert a.outcome == b.outcome and a.metrics["max_rotation"] == b.metrics["max_rotation"]
    amps, freqs = [1.5, 3.0, 6.0], [1.0, 3.0]
    sa = fr.overturning_spectrum(body, amps, freqs, sign="both", wall=wall, progress=False)
    sb = fr.overturning_spectrum(BLOCK, amps, freqs, sign="both", wall=wall, progress=False)
    assert list(sa.outcome) == list(sb.outcome)
    assert np.array_equal(sa.max_rotation.to_numpy(), sb.max_rotation.to_numpy())


def test_a_scene_file_takes_top_radius(tmp_path):
    toml = tmp_path / "scene.toml"
    toml.write_text('[body]\ntype = "rigid"\nb = 0.3\nh = 1.0\ntop_radius = 0.25\n[wall]\ngap = 0.05\nside = 1\n'
                    '[excitation]\nkind = "one-sine"\namplitude = 0.5\nfrequency = 1.0\nsign = -1\n')
    scene = fr.Scene.from_toml(toml)
    assert scene.body == BLOCK


def test_bad_top_radius_names_the_field():
    with pytest.raises(ValueError, match="top_radius"):
        fr.RigidBlock.rectangle(B, H, top_radius=-0.1)
    with pytest.raises(ValueError, match="top_radius"):
        fr.RigidBlock.rectangle(B, H, top_radius=0.7)             # > min(2b, 2h)
    with pytest.raises(ValueError, match="top_radius"):
        fr.RigidBlock(alpha=0.3, p=2.0, top_radius=0.1)            # no b, h
    # the contact model takes it (tests/test_contact_rounded_top.py)
    run = fr.simulate(BLOCK, fr.Pulse(0.5, 1.0), wall=fr.Wall(0.05), friction=fr.Friction(0.5), duration=0.5)
    assert run.kernel == "contact" and not run.status.startswith("failed")
