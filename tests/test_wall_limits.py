"""Two limits of the wall models (issue #14, kernels/wall.py and kernels/flexible_wall.py docstrings).

* Small gaps: a rigid block whose wall is closer than ``SMALL_GAP_ANGLE`` (theta_w < 1e-7 rad)
  rocks as Hogan's one-sided block with r = e^2 e_w (a ground impact, a wall impact and a second
  ground impact become one map).  The d > 0 model converges to it as the gap shrinks: same
  safe/overturned answer, max rotations within a few theta_w.  The fuzz cells ``wall:2026:136``
  and ``:206`` (gaps of 1.7 and 9.3 nm) cycled through the three impacts every ~9 us to the step
  budget; they now end definite.
* Elastic bounces below the resolution: an impact elastic at the tolerance (1 - r^2 <= rtol)
  whose rebound energy is below rtol times the energy scale (the barrier) ends as chatter.  The
  fuzz cells ``wall:2026:13`` (Hogan, r = 1, after the pulse) and ``flexible_wall:2026:59``,
  ``:60`` (e_w = 1, a long pulse pressing the body on the wall) bounced at a constant 1e-6 rad/s
  to the step budget; they now end definite with the outcome of e_w = 1 - small, and the energy
  never rises after the pulse.  Motion above the resolution is untouched (the elastic Hogan block
  of test_wall_hard_cases still rocks for ever).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.analyses.spectrum import overturning_spectrum
from fastrock.kernels.wall import SMALL_GAP_ANGLE

BUDGET = 200_000
TALL_H = 0.8
BLOCK = fr.RigidBlock.rectangle(b=0.2, h=TALL_H)


def fuzz_pulse(amp, freq, sign, kind):
    return fr.Pulse(amp, freq, sign, kind, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


def rigid_energy(res, body):
    """Free-rocking energy / (M g R) along the history (zero at rest)."""
    h = res.history
    return (h["theta_dot"] ** 2 / (2 * body.p ** 2) + np.cos(body.alpha - np.abs(h["theta"]))
            - math.cos(body.alpha)).to_numpy()


# ----------------------------------------------------------------------------------------
# small gaps
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("ew", [1.0, 0.6])
def test_small_gap_map_is_hogan_with_r_e2_ew(ew):
    """Released away from the wall, the block comes back to theta = 0: in the limit one impact
    with theta'+ = -e^2 e_w theta'- and the pivot kept; at theta_w = 1e-6 rad the d > 0 model's
    three impacts give the same velocity to O(theta_w) (measured 2e-5 apart for e_w = 0.6)."""
    theta0 = 0.3 * BLOCK.alpha
    runs = {}
    for tw in (1e-9, 1e-6):
        wall = fr.Wall(gap=2 * TALL_H * math.sin(tw), side=-1, restitution=ew)
        runs[tw] = fr.simulate(BLOCK, None, wall=wall, theta0=theta0, duration=1.0, rtol=1e-10,
                               max_steps=BUDGET)
    lim = runs[1e-9].events
    lim = lim[lim["event"].isin(["impact", "wall-impact"])]
    first = lim.iloc[0]
    assert first["event"] == "wall-impact" and first["pivot"] == 1
    assert first["velocity_after"] == pytest.approx(-BLOCK.e ** 2 * ew * first["velocity_before"], rel=1e-15)
    ev = runs[1e-6].events
    triple = ev[ev["event"].isin(["impact", "wall-impact"])].iloc[:3]
    assert list(triple["event"]) == ["impact", "wall-impact", "impact"]
    assert triple["pivot"].iloc[-1] == 1
    assert triple["velocity_after"].iloc[-1] == pytest.approx(first["velocity_after"], rel=1e-4)
    assert triple["t"].iloc[-1] - triple["t"].iloc[0] < 1e-4


@pytest.mark.parametrize("ew", [1.0, 0.6])
def test_small_gap_converges_to_the_limit(ew):
    """Spectra (one-sine, both signs, rtol 1e-8, no early exit) at gaps 2h x 1e-4 .. 1e-6 against
    the limit (2h x 1e-9): every cell definite, the same safe/overturned answer, and max
    rotations within 25 theta_w of the limit's, the error shrinking with the gap (measured
    2.6e-3, 9.3e-5, 9.3e-6 of alpha for e_w = 1).  The one label that differs is mode1 (d > 0)
    against mode2 (limit) for blocks pressed on the wall before they overturn away from it: at
    d > 0 they bounce inside the gap (impacts of energy O(theta_w)) and the limit, as Hogan's
    d = 0 block, stays in contact."""
    amps = [1.2, 2.0, 3.5, 6.0]
    freqs = [0.5, 1.0, 2.0, 4.0]

    def run(k):
        df = overturning_spectrum(BLOCK, amps, freqs, "both", pulse="one-sine", early_exit=False,
                                  wall=fr.Wall(gap=2 * TALL_H * k, side=-1, restitution=ew),
                                  solver=fr.Solver(rtol=1e-8), progress=False)
        assert not df["status"].str.startswith("failed").any()
        return df

    lim = run(1e-9)
    assert fr.Wall(gap=2 * TALL_H * 1e-9).limit_angle(BLOCK) < SMALL_GAP_ANGLE
    errs = []
    for k in (1e-4, 1e-5, 1e-6):
        df = run(k)
        assert fr.Wall(gap=2 * TALL_H * k).limit_angle(BLOCK) > SMALL_GAP_ANGLE
        over = df["outcome"].str.startswith("mode").to_numpy()
        assert (over == lim["outcome"].str.startswith("mode").to_numpy()).all()
        differ = df["outcome"].to_numpy() != lim["outcome"].to_numpy()
        assert (df["outcome"][differ] == "mode1").all() and (lim["outcome"][differ] == "mode2").all()
        err = np.abs(df["max_rotation_ratio"] - lim["max_rotation_ratio"]).max()
        assert err <= 25 * k / BLOCK.alpha
        errs.append(err)
    assert errs[2] <= errs[1] <= errs[0]


@pytest.mark.parametrize("cell", [
    # fuzz wall:2026:136, the simulate cell of bench/README.md
    dict(b=2.435420700793361, h=6.15956340631055, e=0.6105929848224951, gap=1.6559791260739474e-09,
         kind="one-cosine", rtol=1.6904392612785286e-09, amps=[37.574657819928774, 9.769821126497739,
                                                              1.1380879726622228, 4.229347921192752],
         freqs=[0.16901662989773616, 1.7752395056070969, 0.5165981189276528, 0.17286643715680416]),
    # fuzz wall:2026:206
    dict(b=2.0739218031478313, h=1.872629985132892, e=None, gap=9.325860319814214e-09, kind="half-sine",
         rtol=1.2202861501543402e-07, amps=[13.519705303348982, 17.688628241128153, 0.40418641263304733,
                                            1.0033505069794446],
         freqs=[0.1572073554689913, 50.90099002023352, 30.66046728345879, 6.614294981716296]),
], ids=["wall:2026:136", "wall:2026:206"])
def test_fuzz_nanometre_gaps_end_definite(cell):
    """The batches' spectra (early exit, as the fuzz runs them) and simulate() of every cell
    end definite, each within 2 000 steps (the budget stopped them at 2e6 before)."""
    body = fr.RigidBlock.rectangle(cell["b"], cell["h"], e=cell["e"])
    wall = fr.Wall(cell["gap"], side=-1, restitution=1.0)
    solver = fr.Solver(rtol=cell["rtol"])
    df = overturning_spectrum(body, cell["amps"], cell["freqs"], "both", pulse=cell["kind"], wall=wall,
                              solver=solver, t_after=10.0, progress=False)
    assert len(df) == 32 and not df["status"].str.startswith("failed").any()
    for a in cell["amps"]:
        for f in cell["freqs"]:
            for s in (1, -1):
                res = fr.simulate(body, fuzz_pulse(a, f, s, cell["kind"]), wall=wall, solver=solver,
                                  t_after=10.0)
                assert not res.status.startswith("failed"), (a, f, s, res.status)
                assert res.metrics["steps"] + res.metrics["rejected_steps"] < 2000
                row = df[(df["amplitude_ratio"] == a) & (df["frequency_ratio"] == f) & (df["sign"] == s)]
                assert res.outcome == row["outcome"].iloc[0]


# ----------------------------------------------------------------------------------------
# elastic bounces below the resolution
# ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("above", [False, True])
def test_elastic_hogan_bounce_threshold(above):
    """Free rocking at d = 0 with r = 1 released at theta0: the rebound energy is the released
    energy E0 = cos(alpha - theta0) - cos(alpha).  Below rtol (1 - cos alpha) the first impact
    ends at rest (safe:rest, one impact); at twice the threshold the block rocks on (safe:moving,
    an impact every half period)."""
    rtol = 1e-6
    a = BLOCK.alpha
    target = (2.0 if above else 0.5) * rtol * (1 - math.cos(a))
    theta0 = a - math.acos(math.cos(a) + target)
    wall = fr.Wall(gap=0.0, side=-1, restitution=1.0)
    res = fr.simulate(BLOCK, None, wall=wall, theta0=theta0, duration=5.0, rtol=rtol, max_steps=BUDGET)
    if above:
        assert res.status == "safe:moving" and res.metrics["wall_impacts"] > 10
    else:
        assert res.status == "safe:rest" and res.metrics["wall_impacts"] == 1
        assert res.history["theta_dot"].iloc[-1] == 0.0


SCENES = {
    # fuzz wall:2026:13: Hogan's block, r = 1, a pulse just above uplift, then free rocking of
    # amplitude 1.7e-11 rad
    "wall:2026:13": dict(body=fr.RigidBlock.rectangle(0.021775322086049004, 0.2365386295353142),
                         wall=dict(gap=0.0, side=-1), rtol=6.4246566429373344e-09,
                         pulse=(1.0000178008353233, 2.7782911539557595, -1, "half-sine")),
    # flexible_wall:2026:59 and :60: a long one-sine pulse presses the body on an elastic wall
    "flexible_wall:2026:59": dict(
        body=fr.FlexibleBody(alpha=0.2833744466241405, p=1.166538208498569, omega_n_over_p=56.92251914582799,
                             zeta=0.0061213227779431285, base_mass_ratio=0.4162810570288623),
        wall=dict(gap=0.0003967202168825035, side=1), rtol=1.464358660286464e-09,
        pulse=(2.426023888666112, 0.1358998848567801, -1, "one-sine")),
    "flexible_wall:2026:60": dict(
        body=fr.FlexibleBody(alpha=0.3356368104858135, p=2.3373041269198445, omega_n_over_p=2.8019855984299507,
                             zeta=0.09242987662077393, rotary_inertia_ratio=0.06254829189103883),
        wall=dict(gap=0.0038610382518156705, side=1), rtol=4.4188219037035245e-05,
        pulse=(19.555994828317353, 0.27519300104473565, -1, "one-sine")),
}


@pytest.mark.parametrize("name", list(SCENES))
def test_elastic_wall_ends_as_an_almost_elastic_one(name):
    """e_w = 1 ends definite (before: the step budget), with the status and max rotation of
    e_w = 0.999 and 0.99 (which end by the chatter rule, as before) and their end time to 1e-6
    (the flexible bodies overturn; the bounces of e_w < 1 lose energy: measured up to 2.3e-7
    apart); the rigid block's energy never rises after the pulse."""
    sc = SCENES[name]
    body = sc["body"]
    exc = fuzz_pulse(*sc["pulse"])
    runs = {}
    for ew in (1.0, 0.999, 0.99):
        runs[ew] = fr.simulate(body, exc, wall=fr.Wall(restitution=ew, **sc["wall"]),
                               solver=fr.Solver(rtol=sc["rtol"]), t_after=10.0)
        assert not runs[ew].status.startswith("failed"), (ew, runs[ew].status)
    el = runs[1.0]
    assert el.metrics["steps"] + el.metrics["rejected_steps"] < 100_000
    for ew in (0.999, 0.99):
        assert runs[ew].status == el.status
        assert runs[ew].metrics["time_end"] == pytest.approx(el.metrics["time_end"], rel=1e-6)
        assert runs[ew].metrics["max_rotation"] == pytest.approx(el.metrics["max_rotation"], rel=1e-12)
    if isinstance(body, fr.RigidBlock):
        assert el.status == "safe:rest"
        t = el.history["t"].to_numpy()
        E = rigid_energy(el, body)
        free = t >= exc.end_time(body)
        assert np.all(np.diff(E[free]) <= 1e-12 * (1 - math.cos(body.alpha)))


@pytest.mark.parametrize("ew", [1.0, 0.9])
def test_flexible_release_at_a_grazing_reaction_ends(ew):
    """fuzz flexible_wall:2026:180 (pivot-switch, zeta = 0, omega_n/p = 281): the body rests on
    the wall, is released where the wall's reaction reaches 0, and the undamped column brings the
    reaction back within one step, so the wall is met again at the same t with theta' = 0.  That
    impact keeps the body on the wall; before, it rocked again and met the wall at the same t
    until failed:transition-loop (e_w = 0.9 on the old kernels, e_w = 1 once elastic bounces
    below the resolution end at the wall).  Now both end safe:rest, as e_w = 0.5 and 0.99 did."""
    body = fr.FlexibleBody(alpha=0.14026876684597478, p=0.5667949614328123, omega_n_over_p=281.3431085655247,
                           zeta=0.0, impact="pivot-switch", e=0.9534142860649281)
    exc = fuzz_pulse(2.4345093653446, 0.12594426270962567, 1, "half-sine")
    res = fr.simulate(body, exc, wall=fr.Wall(0.11161774045994016, side=-1, restitution=ew),
                      solver=fr.Solver(rtol=1.884246682014534e-05), t_after=10.0, early_exit=True)
    assert res.status == "safe:rest"
    ev = res.events
    assert (ev["event"] == "wall-rest").sum() > 0
