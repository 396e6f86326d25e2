"""Hard cases for the flexible body (physics.md 3): stiff columns (omega_n/p = 100 and 300, both
impact maps, with and without damping) and a 90 s record at dt 0.005.  Every run gets a step
budget and must end with a definite status and a finite history; the stiff bodies must also give
the outcome of the rigid limit.  CI runs this file a second time under ``NUMBA_BOUNDSCHECK=1``.
"""
from __future__ import annotations


import numpy as np
import pytest

import fastrock as fr
import hardcases as H
from test_flexible import I1, I3, body, definite, pulse

HARD_PULSES = [(3.0, 1.0), (2.0, 2.0), (2.5, 6.0)]   # mode 2, mode 1, safe with many impacts
HARD_BUDGET = 400_000    # steps (accepted + rejected); most measured: 152 495 (I3, 300, zeta 0, 2.5x6, 1026 impacts)


@pytest.mark.filterwarnings("ignore:the pivot-switch")
@pytest.mark.parametrize("a,f", HARD_PULSES)
@pytest.mark.parametrize("zeta", [0.0, 0.05])
@pytest.mark.parametrize("impact", [I3, I1])
@pytest.mark.parametrize("wr", [100, 300])
def test_stiff_body_finishes_within_budget(wr, impact, zeta, a, f):
    """Stiff bodies finish with a definite status inside a step budget, no NaN, and the outcome
    of the rigid limit for these clear-cut pulses."""
    r = fr.simulate(body(wr, impact, zeta), pulse(a, f), max_steps=HARD_BUDGET, early_exit=True)
    h = r.history
    assert np.isfinite(h[["u", "u_dot", "theta", "theta_dot"]].to_numpy()).all()
    assert definite(r.status), (r.status, r.metrics["steps"], r.metrics["impacts"])
    assert r.metrics["steps"] + r.metrics["rejected_steps"] <= HARD_BUDGET
    expected = {1.0: "mode2", 2.0: "mode1", 6.0: "safe"}[f]
    assert r.outcome == expected


def test_step_budget_is_reported():
    r = fr.simulate(body(100), pulse(2.0, 2.0), max_steps=500)
    assert r.status == "failed:step-budget"


def test_long_record_90s_at_dt_0005():
    """The 90 s record of the rigid hard cases (18 000 breakpoints), at 0.7 g so that the body
    rocks (measured: about 170 impacts, 50 000 steps, rest at the end) on a column of
    omega_n/p = 9, zeta = 0.05: definite, finite, inside the budget, and the run reaches the
    record's end."""
    rigid = fr.RigidBlock.rectangle(b=0.3, h=1.2)
    flex = fr.FlexibleBody(alpha=rigid.alpha, p=rigid.p, omega_n_over_p=9.0, zeta=0.05)
    rec = H.long_record(peak_g=0.7)
    res = fr.simulate(flex, rec, t_after=2.0, max_steps=HARD_BUDGET)
    H.definite(res, HARD_BUDGET, columns=("u", "u_dot", "theta", "theta_dot"))
    assert res.outcome == "safe" and res.metrics["impacts"] > 0
    assert res.metrics["time_end"] == pytest.approx(rec.end_time(flex) + 2.0, abs=1e-9)


# Fuzz reproductions (issue #14, bench/README.md "Fuzz baseline"): undamped columns on a massless
# base (m_b = 0, I_m = 0) whose deflection reaches u = sB while the body falls, where the mass
# matrix is singular (det = (u - sB)^2).  They ended failed:step-underflow.  The kernel passes the
# fold as the limit of a vanishing base inertia (kernels/flexible.py docstring); the reference is
# that regular model itself, rotary_inertia_ratio = 1e-8 (its difference from the limit is O(1e-8)).
FOLD_CASES = [
    # batch, (alpha, p, omega_n/p), pulse kind, (a_p/(g tan alpha), omega_p/p), outcome
    ("flexible:2027:207", (0.3733829167663731, 6.233212561948374, 2.5465219458159343), "one-sine",
     (15.70084003280347, 5.094461768818649), "mode2"),
    ("flexible:2027:385", (0.4762662676993316, 0.6966136692797811, 2.11370798033852), "one-sine",
     (22.42402832448681, 8.004874324793034), "mode2"),
    ("flexible:2027:528", (0.45922501273288224, 7.394673097477244, 3.082660656960758), "one-cosine",
     (30.62917196890513, 4.672797883381405), "mode1"),
]


@pytest.mark.parametrize("case", FOLD_CASES, ids=[c[0] for c in FOLD_CASES])
def test_massless_base_passes_the_fold(case):
    _bid, (alpha, p, wr), kind, (a, f), outcome = case
    runs = {}
    for im in (0.0, 1e-8):
        b = fr.FlexibleBody(alpha=alpha, p=p, omega_n_over_p=wr, zeta=0.0, rotary_inertia_ratio=im)
        for sign in (1, -1):
            pul = fr.Pulse(a, f, sign, kind, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
            runs[im, sign] = fr.simulate(b, pul, t_after=10.0, solver=fr.Solver(rtol=1e-10))
    for (im, sign), r in runs.items():
        assert r.outcome == outcome, (im, sign, r.status)
        assert np.isfinite(r.history[["u", "u_dot", "theta", "theta_dot"]].to_numpy()).all()
    for sign in (1, -1):
        lim, ref = runs[0.0, sign].metrics, runs[1e-8, sign].metrics
        assert lim["time_end"] == pytest.approx(ref["time_end"], rel=1e-6)
        assert lim["max_deformation"] == pytest.approx(ref["max_deformation"], rel=1e-6)
        assert lim["impacts"] == ref["impacts"]


# Fuzz reproductions of failed:transition-loop: the uplift test met within rounding at a zero of
# the margin that the margin leaves upward; the rocking equation turned the body back at once and
# it landed with theta' = 0 at the same instant, 200 times.  Such a landing now means the body
# never left the ground (kernels/flexible.py, never_left).  Reference: the same kernel at rtol 1e-10.
LOOP_CASES = [
    # batch, FlexibleBody keywords, pulse kind, (a_p/(g tan alpha), omega_p/p), rtol, max|theta|/alpha at 1e-10
    ("flexible:2027:160", dict(alpha=0.454565227750566, p=1.1343590715507315,
                               omega_n_over_p=82.32182027475393, zeta=0.0), "half-sine",
     (0.996607, 0.236032), 4.367493901483954e-05, 0.0),
    ("flexible:2027:476", dict(alpha=0.289128941682358, p=7.080971870507101,
                               omega_n_over_p=113.78082976912013, zeta=0.03239198957329227,
                               impact="pivot-switch", e=0.8071243993761532), "one-cosine",
     (1.002366, 0.203659), 9.13352496401772e-05, 0.0114722486),
]


@pytest.mark.filterwarnings("ignore:the pivot-switch")
@pytest.mark.parametrize("case", LOOP_CASES, ids=[c[0] for c in LOOP_CASES])
def test_uplift_within_rounding_does_not_loop(case):
    _bid, kw, kind, (a, f), rtol, ref_ratio = case
    b = fr.FlexibleBody(**kw)
    for sign in (1, -1):
        pul = fr.Pulse(a, f, sign, kind, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        r = fr.simulate(b, pul, t_after=10.0, solver=fr.Solver(rtol=rtol))
        tight = fr.simulate(b, pul, t_after=10.0, solver=fr.Solver(rtol=1e-10))
        assert definite(r.status) and r.outcome == "safe" == tight.outcome, (r.status, tight.status)
        assert np.isfinite(r.history[["u", "u_dot", "theta", "theta_dot"]].to_numpy()).all()
        assert tight.metrics["max_rotation_ratio"] == pytest.approx(ref_ratio, rel=1e-6, abs=1e-12)
        # the loose run's max rotation is within its integration error of the tight one
        assert abs(r.metrics["max_rotation_ratio"] - ref_ratio) <= 1e-3 * max(ref_ratio, 1e-3)
