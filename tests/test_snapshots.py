"""The snapshot strip (issue #17, item 4): the drawn outline is the body's
pose, so its geometry is checked, not only that it renders."""
import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.plotting.snapshots import block_outline, pose


def test_rocking_pose_keeps_the_pivot_on_the_ground():
    b, h = 0.2, 0.8
    blk = fr.RigidBlock.rectangle(b, h)
    r = fr.simulate(blk, None, theta0=0.5 * blk.alpha, duration=1.5)
    R = math.hypot(b, h)
    rows = r.history[r.history["pivot"] != 0]
    assert len(rows) > 10
    for _, row in rows.iterrows():
        world, cm = pose(blk, row.to_dict())
        s = int(row["pivot"])
        corner = world[1] if s > 0 else world[0]       # (b, -h) or (-b, -h)
        assert corner == pytest.approx([s * b, 0.0], abs=1e-12)
        assert cm[1] == pytest.approx(R * math.cos(blk.alpha - abs(row["theta"])), rel=1e-12)
        assert np.all(world[:, 1] >= -1e-12)            # nothing below the ground
        # a positive theta leans the top toward +x
        assert np.sign(cm[0] - 0.0) == np.sign(row["theta"]) or abs(row["theta"]) < 1e-12


def test_slip_shifts_the_body():
    blk = fr.RigidBlock.rectangle(0.5, 0.25, e=0.0)     # stout: slides
    r = fr.simulate(blk, fr.Pulse(0.5, 1.0, kind="rectangular", duration=0.3), friction=fr.Friction(0.2))
    last = r.history.iloc[-1].to_dict()
    world, cm = pose(blk, last)
    assert abs(last["d"]) > 0.01
    assert cm[0] == pytest.approx(last["d"], abs=1e-12)


def test_outline_of_a_block_from_alpha_and_p():
    blk = fr.RigidBlock(alpha=0.25, p=2.0)
    verts, pivots = block_outline(blk)
    b, h = pivots[1][0], -pivots[1][1]
    assert pivots[-1] == (-b, -h)
    R = 3 * blk.g / (4 * blk.p ** 2)
    assert math.hypot(b, h) == pytest.approx(R) and math.atan2(b, h) == pytest.approx(0.25)


def test_strip_renders(tmp_path):
    blk = fr.RigidBlock.rectangle(0.15, 0.6)
    r = fr.simulate(blk, fr.Pulse(0.4, 1.5), friction=fr.Friction(0.5), ground=fr.Ground(0.05))
    ax = fr.plot_snapshots(r, n=5)
    assert len(ax.patches) == 5
    ax.figure.savefig(tmp_path / "strip.png", dpi=80)
    assert (tmp_path / "strip.png").stat().st_size > 1000


@pytest.mark.parametrize("with_outline", [True, False])
def test_asymmetric_body_pivots_on_its_own_corners(with_outline, tmp_path):
    """A RigidBody rocks on (b2, -h2) or (-b1, -h1): that corner stays on the ground."""
    if with_outline:
        body = fr.RigidBody.from_polygon([(0, 0), (0.5, 0), (0.3, 1.2), (0.05, 1.0)], mass=100.0)
    else:
        body = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.25, h1=0.7, b2=0.12, h2=0.7)
    r = fr.simulate(body, fr.Pulse(0.7, 1.0, sign=-1), duration=4.0)
    _verts, pivots = block_outline(body)
    rows = r.history[r.history["pivot"] != 0]
    assert len(rows) > 5
    for _, row in rows.iterrows():
        world, cm = pose(body, row.to_dict())
        s = int(row["pivot"])
        corner = np.asarray(pivots[s])
        # the pivot's world position is where it rests, and no outline point is below the ground
        k = int(np.argmin(np.hypot(*(world - [corner[0], 0.0]).T)))
        assert world[k] == pytest.approx([corner[0], 0.0], abs=1e-12)
        assert world[:, 1].min() >= -1e-9
    ax = fr.plot_snapshots(r, n=4)
    ax.figure.savefig(tmp_path / "s.png", dpi=60)
