"""Asymmetric rigid bodies in the contact core (issue #17 item 1: "every model ... accepts it:
walls, friction and flight"; kernels/contact.py with b1 != b2 on a level base).

Oracles:
- a symmetric RigidBody given through the asymmetric body's parameters equals the RigidBlock's
  contact runs;
- mu = inf, no wall: the two-sided rocking model of the asymmetric body (kernels/rigid.py,
  rigid_body entries): outcomes on a pulse grid, max rotations to integration tolerance;
- the ground impact with mu = inf is e12 / e21 exactly, and e12 / e21 keep the angular momentum
  about the new pivot (computed here from the vectors);
- energy never increases at impacts and transitions, nor in the free motion (hypothesis);
- mirror symmetry: b1 <-> b2 with the excitation (and the wall side) flipped gives theta -> -theta;
- a wall out of reach equals no wall;
- bad input: h1 != h2, a wall without an outline or with an overhang toward it, and the front
  end's refusal of wall= for an asymmetric body, each with a clear error.
"""
import math
import os
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fastrock as fr
from fastrock import Friction, Pulse, RigidBlock, RigidBody, Wall
from fastrock.running.models import contact_par
from fastrock.kernels import contact as C
from fastrock.kernels import layout as L

sys.path.insert(0, os.path.dirname(__file__))
from test_contact_core import impact_pairs, kinetic, mechanical, run  # noqa: E402
from test_contact_wall_friction import run_any  # noqa: E402

WEDGE = [(0.0, 0.0), (1.0, 0.0), (0.3, 2.0)]        # centre of mass left of the middle
ASYM = RigidBody(mass=1.0, inertia=0.12, b1=0.15, h1=0.8, b2=0.3, h2=0.8,
                 outline=[(-0.15, -0.8), (0.3, -0.8), (0.3, 0.9), (-0.15, 0.9)])
INF = math.inf


def mirrored(body):
    """The body reflected about its vertical axis (b1 <-> b2, the outline flipped)."""
    out = None if body.outline is None else np.asarray(body.outline) * [-1.0, 1.0]
    return RigidBody(mass=body.mass, inertia=body.inertia, b1=body.b2, h1=body.h2, b2=body.b1,
                     h2=body.h1, e=body.e, g=body.g, outline=out)


# ------------------------------------------------------------------ parameters
def test_parameters_hold_each_side():
    par = contact_par(ASYM, Friction(0.5))
    assert par[C.C_B1] == ASYM.b1 and par[C.C_B2] == ASYM.b2
    assert par[C.C_H1] == par[C.C_H2] == ASYM.h1
    assert par[C.P_ALPHA] == ASYM.alpha2 and par[C.C_ALPHA_NEG] == ASYM.alpha1
    assert par[C.P_E] == ASYM.e21 and par[C.C_E_NEG] == ASYM.e12
    assert par[C.C_IG] == pytest.approx(ASYM.inertia / ASYM.mass, rel=1e-15)
    # a polygon's lowest facet is a level base: the contact model takes it
    wedge = RigidBody.from_polygon(WEDGE, mass=1.0)
    assert not wedge.is_symmetric
    p = contact_par(wedge, Friction(0.5))
    assert p[C.C_B1] < p[C.C_B2]


# ------------------------------------------------------------------ symmetric case
SYM_GRID = [(0.3, 0.3, 2.0, 1), (0.3, 0.5, 1.5, -1), (0.15, 0.4, 2.5, 1), (0.6, 0.35, 1.0, -1)]


@pytest.mark.parametrize("mu,amp,f,sg", SYM_GRID)
def test_symmetric_body_through_the_asymmetric_parameters_equals_the_block(mu, amp, f, sg):
    block = RigidBlock.rectangle(0.2, 1.0)
    body = RigidBody.from_block(block)
    pulse = Pulse(amp * 9.81, f, sign=sg)
    ref = run(contact_par(block, Friction(mu)), body=block, pulse=pulse)
    new = run(contact_par(body, Friction(mu)), body=block, pulse=pulse)
    assert new["status"] == ref["status"]
    for m in (L.M_MAX_ABS_THETA, L.M_MAX_SLIDE, L.M_RESIDUAL_SLIDE):
        assert new["met"][m] == pytest.approx(ref["met"][m], rel=1e-6, abs=1e-9), m
    assert new["met"][L.M_IMPACTS] == ref["met"][L.M_IMPACTS]


# ------------------------------------------------------------------ mu = inf: rigid_body
RIGID_GRID = [(a, f, sg) for a in (1.5, 2.0, 2.5, 3.0) for f in (1.0, 2.0, 3.0, 4.0) for sg in (1, -1)]


@pytest.mark.parametrize("body", [ASYM, RigidBody.from_polygon(WEDGE, mass=1.0)],
                         ids=["numbers", "wedge"])
def test_mu_inf_reproduces_the_two_sided_rocking_model(body):
    """Every run that never leaves the ground: the rocking model's outcome, impacts and maximum
    rotations on each side.  (The rocking model holds the pivot down when its normal force would
    turn negative; the contact model lets the body fly there: those runs differ by design.)"""
    seen = set()
    compared = 0
    flight = Friction(INF, lift_off="flight")
    for amp, f, sg in RIGID_GRID:
        pulse = Pulse(amp, f, sign=sg)
        ref = fr.simulate(body, pulse, duration=8.0, early_exit=False, rtol=1e-10)
        r = fr.simulate(body, pulse, duration=8.0, friction=flight, rtol=1e-10)
        assert ref.kernel == "rigid_body" and r.kernel == "contact_body"
        if r.metrics["flights"] > 0:
            continue
        compared += 1
        assert r.outcome == ref.outcome, (amp, f, sg)
        assert r.metrics["impacts"] == ref.metrics["impacts"], (amp, f, sg)
        for k in ("max_rotation", "max_rotation_pos", "max_rotation_neg"):
            assert r.metrics[k] == pytest.approx(ref.metrics[k], rel=1e-9, abs=1e-10), (amp, f, sg, k)
        seen.add(ref.outcome)
    assert compared >= 0.6 * len(RIGID_GRID)
    assert {"safe", "mode1", "mode2"} <= seen


def test_ground_impact_with_infinite_friction_is_the_angular_momentum_map_exactly():
    par = contact_par(ASYM, Friction(INF))
    b1, b2, h, iG = ASYM.b1, ASYM.b2, ASYM.h1, ASYM.inertia / ASYM.mass
    for s, e, bk, bj in ((1, ASYM.e21, b2, b1), (-1, ASYM.e12, b1, b2)):
        for pre in (-2.3, -0.4, -1e-3):
            pre = s * pre           # rocking on s toward theta = 0
            post, dpost = C.corner_impact(pre, 0.0, s, bk, bj, h, iG, e, INF, INF)
            assert post == e * pre and dpost == 0.0
            # angular momentum about the new pivot j = -s, from the vectors: before, rotation
            # about pivot s; after, about j
            pk = np.array([s * bk, -h])
            pj = np.array([-s * bj, -h])
            # rocking about pivot s: v_G = theta' (ry, -rx), (rx, ry) = pivot - G
            vg = pre * np.array([-pk[1], pk[0]])
            d = -pj                                         # G - new pivot
            L_before = iG * pre - (d[0] * vg[1] - d[1] * vg[0])
            assert post * (iG + bj * bj + h * h) == pytest.approx(L_before, rel=1e-13)
    # through the kernel: every impact of free rocking logs post = e * pre, e of the side it
    # leaves, up to the sticking pivot's slip velocity, integration drift of order rtol
    r = run(par, body=ASYM, y0=[0.05, 0, 0, 0, 0, 0], t_end=3.0, rtol=1e-10)
    log = r["log"][r["log"][:, L.LOG_KIND] == L.EV_IMPACT]
    assert len(log) >= 5
    sides = set()
    for row in log:
        pre, post, new = row[L.LOG_PRE], row[L.LOG_POST], row[L.LOG_PIVOT]
        e = par[C.P_E] if new < 0 else par[C.C_E_NEG]
        assert post == pytest.approx(e * pre, rel=1e-10)
        sides.add(new)
    assert sides == {-1.0, 1.0}


# ------------------------------------------------------------------ energy
def run_kept(par, body, pulse=None, vertical=None, y0=None, t_end=4.0):
    """One contact_simulate run that keeps a failed run's history (``run_any``)."""
    return run_any(par, pulse=pulse, y0=y0, t_end=t_end, body=body, vertical=vertical)


def check_energy(r, par, scale, t_free):
    t, y = r["t"], r["y"]
    E = mechanical(y, par)
    T = kinetic(y, par)
    for i in impact_pairs(r):
        assert T[i + 1] <= T[i] + 1e-12 * scale, (t[i], T[i], T[i + 1])
    for i in impact_pairs(r, impacts_only=False):
        assert E[i + 1] <= E[i] + 1e-9 * scale, (t[i], E[i], E[i + 1])
    free = t >= t_free
    assert np.diff(E[free]).max(initial=0.0) <= 1e-7 * scale


@settings(max_examples=200, deadline=None, suppress_health_check=list(HealthCheck))
@given(b1=st.floats(0.08, 0.4), b2=st.floats(0.08, 0.4), h=st.floats(0.4, 1.2),
       k2=st.floats(0.05, 0.6), theta0=st.floats(-0.15, 0.15), vx0=st.floats(-0.4, 0.4),
       mu=st.sampled_from([0.1, 0.3, 0.8, INF]), amp=st.sampled_from([0.0, 2.0, 5.0]),
       f=st.floats(1.0, 4.0), sg=st.sampled_from([1, -1]), av=st.sampled_from([0.0, 12.0]))
def test_energy_never_increases(b1, b2, h, k2, theta0, vx0, mu, amp, f, sg, av):
    """Random asymmetric bodies released tilted and sliding, under pulses (some with a vertical
    pulse above g, so that they fly): the kinetic energy never grows at an impact or landing, the
    mechanical energy never at a transition, and never in the free motion after the pulses."""
    body = RigidBody(mass=1.0, inertia=k2 * (b1 * b1 + h * h), b1=b1, h1=h, b2=b2, h2=h)
    par = contact_par(body, Friction(mu))
    pulse = Pulse(amp, f, sign=sg) if amp > 0 else None
    vertical = Pulse(av, f, sign=1) if (av > 0 and pulse) else None
    r = run_kept(par, body, pulse, vertical, [theta0, 0.0, 0.0, vx0, 0.0, 0.0])
    check_energy(r, par, body.g * h, 1.0 / f if pulse else 0.0)


@settings(max_examples=500, deadline=None)
@given(bk=st.floats(0.05, 0.5), bj=st.floats(0.05, 0.5), h=st.floats(0.3, 1.5), k2=st.floats(0.05, 0.6),
       pre=st.floats(0.01, 5.0), vs=st.floats(-2.0, 2.0), s=st.sampled_from([1, -1]),
       mu=st.sampled_from([0.05, 0.2, 0.5, 1.0, INF]), e_given=st.sampled_from([None, 0.0, 0.5, 0.9]))
def test_ground_impact_map_never_adds_energy(bk, bj, h, k2, pre, vs, s, mu, e_given):
    """The impact from pivot s onto -s alone, any sides, slip and restitution: the kinetic energy
    never grows; with mu = inf the new corner sticks."""
    iG = k2 * (bk * bk + h * h)
    iok, ioj = iG + bk * bk + h * h, iG + bj * bj + h * h
    # a given e as RigidBody admits it: e^2 I_O,j / I_O,k <= 1 both ways
    cap = math.sqrt(min(iok / ioj, ioj / iok))
    e = (iG + h * h - bk * bj) / ioj if e_given is None else min(e_given, cap)
    pre = -s * pre                       # rocking on s back toward theta = 0
    if mu == INF:
        vs = 0.0                         # a pivot that never slips
    post, dpost = C.corner_impact(pre, vs, s, bk, bj, h, iG, e, mu, 0.8 * mu)
    before = C.fr_kinetic(pre, vs, s, bk, h, iG)
    after = C.fr_kinetic(post, dpost, -s, bj, h, iG)
    assert after <= before * (1.0 + 1e-12) + 1e-15
    if mu == INF:
        assert dpost == 0.0


# ------------------------------------------------------------------ mirror symmetry
# theta0 <= 0.005: clear of the wall on side +1 (it touches at about 0.0118 rad)
MIRROR = [(0.3, 2.0, 1.2, 1, 0.005), (0.5, 4.0, 2.0, -1, -0.05), (INF, 3.0, 1.5, 1, 0.0),
          (0.2, 5.0, 2.5, -1, -0.1)]


@pytest.mark.parametrize("mu,amp,f,sg,theta0", MIRROR)
@pytest.mark.parametrize("gap", [INF, 0.02])
def test_mirror_symmetry(mu, amp, f, sg, theta0, gap):
    """The mirrored body (b1 <-> b2) under the flipped pulse, tilted the other way, with the wall
    on the other side: theta -> -theta, the slide -> -slide, same outcome and counts."""
    wall = None if gap == INF else Wall(gap=gap, side=1)
    wall_m = None if gap == INF else Wall(gap=gap, side=-1)
    a = run_kept(contact_par(ASYM, Friction(mu), wall), ASYM, Pulse(amp, f, sign=sg),
                 y0=[theta0, 0, 0, 0, 0, 0], t_end=6.0)
    M = mirrored(ASYM)
    b = run_kept(contact_par(M, Friction(mu), wall_m), M, Pulse(amp, f, sign=-sg),
                 y0=[-theta0, 0, 0, 0, 0, 0], t_end=6.0)
    assert a["status"] == b["status"] and a["status"] > 0
    ma, mb = a["met"], b["met"]
    for k in (L.M_IMPACTS, L.M_WALL_IMPACTS, L.M_N_FLIGHTS):
        assert np.nan_to_num(ma[k]) == np.nan_to_num(mb[k]), k
    assert ma[L.M_MAX_THETA_POS] == pytest.approx(mb[L.M_MAX_THETA_NEG], rel=1e-6, abs=1e-10)
    assert ma[L.M_MAX_THETA_NEG] == pytest.approx(mb[L.M_MAX_THETA_POS], rel=1e-6, abs=1e-10)
    assert ma[L.M_MAX_SLIDE] == pytest.approx(mb[L.M_MAX_SLIDE], rel=1e-6, abs=1e-10)
    assert a["y_end"][0] == pytest.approx(-b["y_end"][0], rel=1e-6, abs=1e-9)
    assert a["y_end"][2] == pytest.approx(-b["y_end"][2], rel=1e-6, abs=1e-9)


def test_mirror_cases_touch_the_wall_and_rock_both_ways():
    hit = 0
    for mu, amp, f, sg, theta0 in MIRROR:
        r = run_kept(contact_par(ASYM, Friction(mu), Wall(gap=0.02, side=1)), ASYM,
                     Pulse(amp, f, sign=sg), y0=[theta0, 0, 0, 0, 0, 0], t_end=6.0)
        hit += r["met"][L.M_WALL_IMPACTS] > 0
    assert hit >= 2


# ------------------------------------------------------------------ wall out of reach
@pytest.mark.parametrize("side", [1, -1])
@pytest.mark.parametrize("amp,f,sg", [(2.5, 2.0, 1), (2.5, 2.0, -1), (4.0, 1.5, 1), (1.5, 3.0, -1)])
def test_wall_out_of_reach_equals_no_wall(side, amp, f, sg):
    """mu = inf: tilting about the wall-side pivot the top corner reaches at most h + h_top; the
    body may also fly and land elsewhere, so the wall stands three times that far: never touched,
    it changes nothing."""
    pulse = Pulse(amp, f, sign=sg)
    top = float(np.max(np.asarray(ASYM.outline)[:, 1]))
    far = Wall(gap=3.0 * (ASYM.h1 + top), side=side)
    ref = run_kept(contact_par(ASYM, Friction(INF)), ASYM, pulse, y0=np.zeros(6), t_end=6.0)
    r = run_kept(contact_par(ASYM, Friction(INF), far), ASYM, pulse, y0=np.zeros(6), t_end=6.0)
    assert r["status"] == ref["status"] and r["status"] > 0
    assert r["met"][L.M_WALL_IMPACTS] == 0
    assert r["met"][L.M_MAX_ABS_THETA] == ref["met"][L.M_MAX_ABS_THETA]
    assert np.array_equal(r["t"], ref["t"])


# ------------------------------------------------------------------ front end
def test_simulate_and_spectrum_run_an_asymmetric_body_with_friction():
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    r = fr.simulate(body, Pulse(3.0, 2.0, sign=1), friction=Friction(0.3))
    assert r.kernel == "contact_body" and not r.status.startswith("failed")
    assert {"max_slide", "residual_slide", "time_sliding"} <= set(r.metrics)
    r = fr.simulate(body, Pulse(3.0, 2.0, sign=1), friction=Friction(0.6, lift_off="flight"),
                    vertical=Pulse(12.0, 2.0))
    assert r.kernel == "contact_body" and not r.status.startswith("failed")
    df = fr.overturning_spectrum(body, [1.0, 3.0], [0.5, 2.0], sign="both", friction=Friction(0.5),
                                 progress=False)
    assert df.attrs["kernel"] == "contact_body" and len(df) == 8
    over = df["outcome"].isin(["mode1", "mode2"])
    assert (df["side"] == np.where(over, np.sign(df["theta_end"]), 0)).all()
    assert "max_slide" in df.columns


def test_scene_and_run_batch_take_an_asymmetric_body_with_friction(tmp_path):
    toml = tmp_path / "scene.toml"
    toml.write_text('[body]\ntype = "rigid-body"\nvertices = [[0.0, 0.0], [1.0, 0.0], [0.3, 2.0]]\n'
                    'mass = 1.0\n[friction]\nmu_s = 0.4\n'
                    '[excitation]\nkind = "one-sine"\namplitude = 3.0\nfrequency = 2.0\n')
    scene = fr.Scene.from_toml(toml)
    assert scene.kernel == "contact_body"
    r = scene.run()
    direct = fr.simulate(scene.body, Pulse(3.0, 2.0), friction=Friction(0.4))
    assert r.outcome == direct.outcome
    assert r.metrics["max_rotation"] == direct.metrics["max_rotation"]
    batch = fr.run_batch([scene], progress=False)
    assert batch["outcome"].iloc[0] == direct.outcome
    assert batch["max_rotation"].iloc[0] == pytest.approx(direct.metrics["max_rotation"], rel=1e-12)


# ------------------------------------------------------------------ bad input
def test_bad_input_errors_name_the_field():
    tilted = RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.9)
    with pytest.raises(ValueError, match=r"^h1 = 0.8 m and h2 = 0.9 m differ: .*level base"):
        fr.simulate(tilted, Pulse(3.0, 2.0), friction=Friction(0.4))
    # the wall in the contact model: an outline is needed, and no overhang toward the wall
    plain = RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.8)
    with pytest.raises(ValueError, match="^wall: a RigidBody needs its outline"):
        contact_par(plain, Friction(0.4), Wall(gap=0.02))
    over = RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.8,
                     outline=[(-0.2, -0.8), (0.3, -0.8), (0.5, 0.9), (-0.2, 0.9)])
    with pytest.raises(ValueError, match=r"^wall: the outline reaches 0.5 m .*side=\+1"):
        contact_par(over, Friction(0.4), Wall(gap=0.02, side=1))
    contact_par(over, Friction(0.4), Wall(gap=0.02, side=-1))
    # the front end runs the same checks for wall= (tests/test_wall_rigid_body.py)
    with pytest.raises(ValueError, match=r"^wall: the outline reaches 0.5 m .*side=\+1"):
        fr.simulate(over, Pulse(3.0, 2.0), wall=Wall(gap=0.02, side=1))
    with pytest.raises(ValueError, match="foundation= is not available for it yet"):
        fr.simulate(ASYM, Pulse(3.0, 2.0), foundation=fr.LinearVibration(1e5))


def test_study_runs_an_asymmetric_body_with_friction(tmp_path):
    from fastrock import SampledMotion
    from fastrock.io.default_records import load_default_record
    from fastrock.studies.definition import Study
    from fastrock.studies.run import run_study
    rec = load_default_record()
    rec = type(rec)(rec.acc[:400], rec.dt, name="El Centro, first 8 s")
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    study = Study(records=[rec], bodies=[body], levels=[0.2, 0.6], t_after=2.0,
                  variants=[{"name": "sliding", "friction": {"mu_s": 0.3}}])
    df = run_study(study, tmp_path / "out", progress=False)
    assert set(df["kernel"]) == {"contact_body"} and len(df) == 2
    for _, row in df.iterrows():
        r = fr.simulate(body, SampledMotion.from_record(rec, scale=row["scale"]), t_after=2.0,
                        friction=Friction(0.3))
        assert r.status == row["status"]
        assert r.metrics["max_rotation_ratio"] == row["max_rotation_ratio"]
