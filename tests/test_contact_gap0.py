"""The contact model with a wall at gap 0 (issue #13 item 3: a block standing against a cliff
that can slide).  The block starts with its wall-side face on the wall (face rest); a push
toward the wall is taken by the wall (no slide into it, no rocking toward it), a pull away
slides or rocks it away, and rocking on the far corner back to theta = 0 is Hogan's combined
ground and wall impact (pivot kept, theta'+ = -e_w theta'-; kernels/contact.py
``hogan_impact``).

Oracles:
- mu = inf, no flight: the wall model's gap-0 (Hogan) results, run for run (status, max
  rotation, ground and wall impacts), both wall sides, both pulse signs, e_w = 1 and 0.6, and a
  small spectrum;
- a push toward the wall (half-sine) leaves the block at rest: no slide, no rotation;
- at every stored row the wall-side base corner and the top corner are outside the wall;
- no transition raises the mechanical energy (tests/test_contact_small_gap.py's measure);
- bad input names the field.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

from fastrock import (Friction, Pulse, RigidBlock, RigidBody, Wall, overturning_spectrum,
                      simulate)
from fastrock.kernels import contact as C
from fastrock.running.models import contact_par

sys.path.insert(0, os.path.dirname(__file__))
from test_contact_small_gap import ENERGY_TOL, _transition_gain  # noqa: E402

BODY = RigidBlock.rectangle(0.2, 1.0)
STICKY = Friction(math.inf, lift_off="flight")      # the contact model (lift_off="stop" is the wall model)
PULSES = ((0.25, 1.0), (0.35, 1.0), (0.8, 2.0), (3.0, 5.0))


def _same(a, b, key):
    assert a.kernel in ("contact", "contact_body") and b.kernel in ("rigid_wall", "wall_body"), key
    assert a.metrics["flights"] == 0, key
    assert a.status == b.status, key
    # the contact model integrates (theta, x, z) and their rates: max rotations to the tolerance
    # of tests/test_contact_core.py's wall-kernel comparison
    assert a.metrics["max_rotation"] == pytest.approx(b.metrics["max_rotation"], rel=1e-6), key
    assert a.metrics["wall_impacts"] == b.metrics["wall_impacts"], key
    assert a.metrics["impacts"] == b.metrics["impacts"], key


@pytest.mark.parametrize("e_w", [1.0, 0.6])
@pytest.mark.parametrize("side", [1, -1])
def test_mu_inf_equals_wall_model(side, e_w):
    wall = Wall(gap=0.0, side=side, restitution=e_w)
    outcomes = set()
    for sign in (1, -1):
        for a, f in PULSES:
            p = Pulse(a, f, sign=sign)
            ref = simulate(BODY, p, wall=wall, duration=11.0)
            c = simulate(BODY, p, wall=wall, friction=STICKY, duration=11.0)
            _same(c, ref, (side, e_w, sign, a, f))
            outcomes.add(ref.outcome)
    # the grid rocks away and back (Hogan impacts) and overturns away from the wall
    assert "mode2" in outcomes and ({"safe"} & outcomes), outcomes


def test_mu_inf_spectrum_equals_wall_model():
    amps, freqs = np.linspace(1.2, 8.0, 5), np.linspace(0.5, 6.0, 4)
    for side in (1, -1):
        kw = dict(sign="both", wall=Wall(gap=0.0, side=side, restitution=0.8), progress=False,
                  early_exit=False)
        ref = overturning_spectrum(BODY, amps, freqs, **kw)
        c = overturning_spectrum(BODY, amps, freqs, friction=STICKY, **kw)
        # where the pivot's normal force reaches 0 the contact model's block flies (the wall
        # model has no flight; tests/test_contact_core.py's probe at gap 0.02 alike): both
        # overturn there; every other cell is the same run
        fly = c["flights"].to_numpy() > 0
        assert fly.sum() <= 8, fly.sum()
        assert set(c["outcome"][fly]) <= {"mode1", "mode2"}
        assert set(ref["outcome"][fly]) <= {"mode1", "mode2"}
        ok = ~fly
        for col in ("outcome", "status", "wall_impacts", "ground_impacts"):
            np.testing.assert_array_equal(c[col][ok], ref[col][ok], err_msg=f"{col} side {side}")
        np.testing.assert_allclose(c["max_rotation"][ok], ref["max_rotation"][ok], rtol=1e-6)
        assert (ref["wall_impacts"][ok] > 0).any() and (ref["outcome"][ok] != "safe").any()


ASYM = RigidBody.from_polygon([(0, 0), (1, 0), (0.2, 2)], mass=1.0)


@pytest.mark.parametrize("side", [1, -1])
def test_mu_inf_asymmetric_body_equals_wall_model(side):
    """An asymmetric RigidBody (each pivot its own alpha, p, e) at gap 0: the wall model's
    ``wall_body`` results (Hogan's map keeps the far pivot, r = e_w)."""
    for e_w in (1.0, 0.7):
        wall = Wall(gap=0.0, side=side, restitution=e_w)
        for sign in (1, -1):
            for a, f in ((0.5, 1.5), (1.0, 3.0)):
                p = Pulse(a, f, sign=sign)
                _same(simulate(ASYM, p, wall=wall, friction=STICKY, duration=10.0),
                      simulate(ASYM, p, wall=wall, duration=10.0), (side, e_w, sign, a, f))


def _push_pulse(side, a_over_g):
    """A half-sine whose d'Alembert force -a_g points toward the wall on ``side``."""
    return Pulse(a_over_g, 2.0, sign=-side, kind="half-sine")


@pytest.mark.parametrize("mu", [0.3, 0.8, math.inf])
@pytest.mark.parametrize("side", [1, -1])
def test_push_toward_wall_keeps_block_at_rest(side, mu):
    """a_g / g = 2 toward the wall: beyond friction (mu g) and beyond uplift (g b/h = 0.2 g)
    without the wall, which takes it all: the block never moves."""
    p = _push_pulse(side, 2.0)
    r = simulate(BODY, p, wall=Wall(gap=0.0, side=side), friction=Friction(mu, lift_off="flight"))
    assert r.outcome == "safe", r.status
    assert r.metrics["max_rotation"] == 0.0
    assert r.metrics["max_slide"] == 0.0
    assert r.metrics["wall_impacts"] == 0 and r.metrics["impacts"] == 0
    h = r.history
    assert (h["theta"] == 0.0).all() and (h["d"] == 0.0).all()
    # the same push with no wall slides (mu = 0.3, 0.8) or rocks (mu = inf) the block
    free = simulate(BODY, p, friction=Friction(mu, lift_off="flight"))
    assert free.metrics["max_rotation"] > 0.0 or free.metrics["max_slide"] > 0.0


def _wall_gaps(run, friction, wall):
    """Clear distance to the wall of the wall-side base corner and of the top corner, per row."""
    par = contact_par(BODY, friction, wall)
    h = run.history
    Y = np.column_stack([h[c].to_numpy() for c in ("theta", "theta_dot", "d", "d_dot", "z", "z_dot")])
    near = np.array([C.point_kin(C.K_NEAR, y, par)[0] for y in Y])
    top = np.array([C.point_kin(2, y, par)[0] for y in Y])
    return near, top


PULL = [(mu, a) for mu in (0.15, 0.3, 0.6) for a in (0.5, 1.5)]


@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("mu,a", PULL)
def test_pull_away_moves_block_away(side, mu, a):
    """A half-sine pulling away from the wall (a_g / g = 0.5 or 1.5): the block slides (mu below
    a_g / g) or rocks away (mu above b/h = 0.2); it never enters the wall."""
    p = _push_pulse(-side, a)
    fr = Friction(mu, lift_off="flight")
    wall = Wall(gap=0.0, side=side)
    r = simulate(BODY, p, wall=wall, friction=fr)
    assert not r.status.startswith("failed"), r.status
    moved_away = -side * r.metrics["residual_slide"] > 0.0 or r.metrics["max_rotation"] > 0.0
    assert moved_away, (r.metrics["residual_slide"], r.metrics["max_rotation"])
    near, top = _wall_gaps(r, fr, wall)
    tol = C.FACE_RTOL * BODY.b
    assert near.min() >= -tol and top.min() >= -tol
    if mu < a:
        assert r.metrics["max_slide"] > 0.0


@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("mu,e_w", [(0.3, 1.0), (0.6, 0.6), (1.0, 1.0), (math.inf, 1.0)])
def test_one_sine_no_penetration_no_energy_gain(side, mu, e_w):
    """One-sine pulses both signs: the body stays out of the wall at every row and no
    transition adds energy."""
    fr = Friction(mu, lift_off="flight")
    wall = Wall(gap=0.0, side=side, restitution=e_w)
    moved = 0
    for sign in (1, -1):
        for a, f in ((0.35, 1.0), (0.8, 2.0), (3.0, 5.0)):
            r = simulate(BODY, Pulse(a, f, sign=sign), wall=wall, friction=fr, duration=8.0)
            key = (sign, a, f)
            assert not r.status.startswith("failed"), (key, r.status)
            near, top = _wall_gaps(r, fr, wall)
            tol = C.FACE_RTOL * BODY.b
            assert near.min() >= -tol and top.min() >= -tol, key
            assert _transition_gain(r, BODY, fr, wall) <= ENERGY_TOL, key
            # the impact maps' own count (FASTROCK_DEBUG=1 only, as .ci/run's debug pass)
            assert r.metrics.get("energy_gains", 0) == 0, key
            moved += r.metrics["max_rotation"] > 0.0 or r.metrics["max_slide"] > 0.0
    assert moved >= 4


def test_wall_model_hogan_impacts_logged_as_wall_impacts():
    """Rocking back onto the wall at gap 0 is one ground and one wall impact each (the wall
    model's count), not a face impact ending the rocking."""
    wall = Wall(gap=0.0, side=1, restitution=1.0)
    r = simulate(BODY, Pulse(0.35, 1.0, sign=1), wall=wall, friction=Friction(0.8, lift_off="flight"))
    assert r.metrics["wall_impacts"] >= 2
    assert r.metrics["impacts"] >= r.metrics["wall_impacts"]


@pytest.mark.parametrize("kwargs,field", [
    (dict(wall=Wall(gap=0.0, side=1), theta0=0.01), "theta0"),
    (dict(wall=Wall(gap=0.0, side=-1), theta0=-0.01), "theta0"),
])
def test_release_into_wall_names_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        simulate(BODY, friction=Friction(0.5, lift_off="flight"), duration=1.0, **kwargs)


@pytest.mark.parametrize("make,field", [
    (lambda: Wall(gap=-0.01), "gap"),
    (lambda: Friction(-0.2), "mu"),
    (lambda: Wall(gap=0.0, friction=-0.1), "friction"),
])
def test_bad_input_names_field(make, field):
    with pytest.raises(ValueError, match=field):
        make()
