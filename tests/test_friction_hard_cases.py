"""Hard cases for the rigid block with Coulomb friction (physics.md 4.1-4.3): mu -> 0 (1e-6: pure
sliding, against the closed form d = -double integral of a_g), very large mu (10 and 1e3: the
frictionless kernel's outcomes), bounded stick-slip chatter near mu g, and a 90 s record at
dt 0.005.  Every run gets a step budget and must end with a definite status and a finite
history.  CI runs this file a second time under ``NUMBA_BOUNDSCHECK=1``.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
import hardcases as H
from fastrock import Friction, Pulse, RigidBlock
from fastrock.bodies import G_STANDARD as G0
from fastrock.solver import Solver
from test_friction import HF_BODY, HF_GRID, SLIDER, definite, one_sine

STATE = ("theta", "theta_dot", "d", "d_dot")


# ---------------------------------------------------------------------------------------------
# mu -> 0: the block stays where it is in absolute space, d = -u_g
# ---------------------------------------------------------------------------------------------
MU_TINY = 1e-6


def free_slide(t, acc, dt):
    """d(t) = -u_g(t) of a frictionless block for a sampled a_g (linear between samples):
    the exact double integral (piecewise cubic), from rest at t = 0."""
    acc = np.asarray(acc, float)
    v = np.concatenate([[0.0], np.cumsum(0.5 * dt * (acc[1:] + acc[:-1]))])
    u = np.concatenate([[0.0], np.cumsum(dt * v[:-1] + dt * dt * (2 * acc[:-1] + acc[1:]) / 6)])
    i = np.clip((np.asarray(t) / dt).astype(int), 0, acc.size - 2)
    tau = np.asarray(t) - i * dt
    da = acc[i + 1] - acc[i]
    return -(u[i] + v[i] * tau + acc[i] * tau ** 2 / 2 + da * tau ** 3 / (6 * dt))


@pytest.mark.parametrize("sign", [1, -1])
def test_mu_tiny_one_sine_pulse_slides_as_double_integral(sign):
    """mu = 1e-6 under a 0.3 g, 1 Hz one-sine pulse: the block slides from the slip onset
    t0 = asin(mu g / a) / w (5.3e-7 s) and never rocks.  Friction changes the relative
    acceleration by at most mu g, so |d - d_free| <= mu g t^2 / 2 at every time, with
    d_free = -sign a (t/w - sin(w t)/w^2) during the pulse and d_free(T) after it (d_free' = 0
    at T); the bound is attained to 1e-12 in the first slip, so it is checked with the
    integrator's own error only (rtol 1e-10 of |d|).  Then the slip speed returns to zero 1 ms
    before the pulse end, the block slips back a little under the tail of the pulse and sticks
    for good (measured 2 slips, 2 sticks, 93 steps)."""
    A, f = 0.3, 1.0
    a, w, T = A * G0, 2 * math.pi * f, 1.0 / f
    r = fr.simulate(SLIDER, Pulse(A, f, sign=sign), friction=Friction(MU_TINY), t_after=2.0, rtol=1e-10,
                    max_steps=10_000)
    H.definite(r, 10_000, STATE)
    assert r.status == "safe:no-uplift" and (r.history["theta"] == 0.0).all()
    t, d = r.history["t"].to_numpy(), r.history["d"].to_numpy()
    tt = np.minimum(t, T)
    d_free = -sign * a * (tt / w - np.sin(w * tt) / w ** 2)
    assert np.all(np.abs(d - d_free) <= MU_TINY * G0 * t ** 2 / 2 + 1e-10 * np.abs(d_free).max())
    assert r.metrics["residual_slide"] == pytest.approx(-sign * a * T / w, rel=1e-4)
    ev = r.events
    slips = ev[ev["event"] == "slip"]
    assert slips["t"].iloc[0] == pytest.approx(math.asin(MU_TINY * G0 / a) / w, rel=1e-6)
    assert 2 <= r.metrics["stick_slip"] <= 6 and ev["event"].iloc[-1] == "stick"


def test_mu_tiny_record_follows_ground_displacement():
    """mu = 1e-6 under 10 s of band-limited noise (2000 samples, 0.35 g): d = -u_g within
    mu g t^2 / 2 (the same bound) at every step, the slip reverses at each zero of the ground
    velocity (stick and slip at once; bounded count), no rocking, inside the budget."""
    rec = H.long_record(duration=10.0, dt=0.005, peak_g=0.35, seed=3)
    r = fr.simulate(SLIDER, rec, friction=Friction(MU_TINY), duration=rec.end_time(SLIDER), rtol=1e-10,
                    max_steps=50_000)
    H.definite(r, 50_000, STATE)
    assert r.outcome in ("safe", "slide") and (r.history["theta"] == 0.0).all()
    t, d = r.history["t"].to_numpy(), r.history["d"].to_numpy()
    d_free = free_slide(t, rec.acc, rec.dt)
    assert np.all(np.abs(d - d_free) <= MU_TINY * G0 * t ** 2 / 2 + 1e-10 * np.abs(d_free).max())
    v_g = np.concatenate([[0.0], np.cumsum(0.5 * rec.dt * (rec.acc[1:] + rec.acc[:-1]))])
    reversals = int(np.sum(np.sign(v_g[1:]) * np.sign(v_g[:-1]) < 0))
    assert reversals > 10
    assert r.metrics["stick_slip"] <= 4 * (reversals + 1)


# ---------------------------------------------------------------------------------------------
# very large mu: the frictionless kernel's outcomes
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("mu", [10.0, 1e3])
def test_large_mu_reproduces_rigid(mu):
    """Same outcomes and impacts on a 4x4 one-sine grid (7 safe, 9 overturn); max|theta|/alpha
    of the safe runs within 1e-7 relative (measured 3.5e-9 at rtol 1e-10, for mu = 10 and 1e3
    alike; 1.6e-7 at 1e-8: the friction kernel's error norm runs over 4 states, the rigid one
    over 2, so the steps differ).  Nothing slides in the safe runs (some overturning runs slip
    near theta = pi/2: N -> 0)."""
    worst = 0.0
    for A, F in HF_GRID:
        r0 = fr.simulate(HF_BODY, one_sine(A, F), t_after=5.0, rtol=1e-10)
        r1 = fr.simulate(HF_BODY, one_sine(A, F), friction=Friction(mu), t_after=5.0, rtol=1e-10)
        assert r1.kernel == "rigid_friction"
        assert r1.outcome == r0.outcome, (A, F)
        assert r1.metrics["impacts"] == r0.metrics["impacts"], (A, F)
        if r0.outcome == "safe":
            rel = abs(r1.metrics["max_rotation_ratio"] / r0.metrics["max_rotation_ratio"] - 1)
            worst = max(worst, rel)
            assert r1.metrics["max_slide"] == 0.0 and r1.metrics["stick_slip"] == 0
            assert (r1.history["d"] == 0.0).all()
        else:
            assert r1.metrics["max_rotation_ratio"] == pytest.approx(r0.metrics["max_rotation_ratio"],
                                                                     rel=1e-12)
    assert worst <= 1e-7


# ---------------------------------------------------------------------------------------------
# stick-slip chatter is bounded
# ---------------------------------------------------------------------------------------------
def harmonic(amp_g, f, ncyc, per_cycle=200):
    dt = 1.0 / (f * per_cycle)
    t = np.arange(0.0, ncyc / f + dt / 2, dt)
    return fr.SampledMotion(amp_g * np.sin(2 * np.pi * f * t), dt, unit="g")


NCYC = 20
BUDGET = 50_000


@pytest.mark.parametrize("k", [1.0, 0.8])
@pytest.mark.parametrize("ratio", [1.000001, 1.001, 1.05, 1.5])
def test_harmonic_near_mu_g(ratio, k):
    """20 cycles of a_g = ratio mu g sin(2 pi 2 t), mu_s = 0.3 < b/h: one slip and one stick per
    half cycle (measured: exactly 80 transitions in every case, <= 4100 steps), a definite
    status, inside a 50 000-step budget."""
    mu = 0.3
    r = fr.simulate(SLIDER, harmonic(ratio * mu, 2.0, NCYC), friction=Friction(mu, k * mu),
                    t_after=2.0, solver=Solver(max_steps=BUDGET))
    assert definite(r.status) and r.status == "safe:no-uplift"
    n = r.metrics["stick_slip"]
    assert 2 * NCYC <= n <= 4 * NCYC + 2
    assert r.metrics["steps"] + r.metrics["rejected_steps"] < BUDGET / 5
    counts = r.events["event"].value_counts()
    assert abs(counts["slip"] - counts["stick"]) <= 1


def test_dither_around_mu_g():
    """Noisy a_g = mu g (1 + 3% noise), 2000 samples: many stick-slip transitions (measured 92),
    at most 4 per sample interval, definite."""
    rng = np.random.default_rng(0)
    dt = 0.005
    a = 0.3 * (1 + 0.033 * rng.standard_normal(2000))
    r = fr.simulate(SLIDER, fr.SampledMotion(a, dt, unit="g"), friction=Friction(0.3), t_after=1.0,
                    solver=Solver(max_steps=BUDGET))
    assert definite(r.status)
    assert 20 <= r.metrics["stick_slip"] <= 4 * a.size


def test_rock_slip_chatter():
    """mu_k = 0.2 <= b/h = 0.25 < mu_s = 0.26 under 0.3 g at 2 Hz: every cycle uplift, slip
    while rocking, stick, hundreds of impacts and rest (measured 40 stick-slip, 840 impacts)."""
    body = RigidBlock.rectangle(b=0.25, h=1.0)
    r = fr.simulate(body, harmonic(0.3, 2.0, 10), friction=Friction(0.26, 0.2), t_after=2.0,
                    solver=Solver(max_steps=BUDGET))
    assert definite(r.status)
    assert 10 <= r.metrics["stick_slip"] <= 4 * 10 * 4
    assert r.metrics["steps"] < BUDGET / 5


# ---------------------------------------------------------------------------------------------
# a long record
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("mu,status", [(0.3, "safe:rest"), (0.2, "safe:no-uplift")])
def test_long_record_90s_at_dt_0005(mu, status):
    """The 90 s record of the rigid hard cases (18 000 breakpoints) at 0.7 g on b/h = 0.25:
    mu = 0.3 rocks and slide-rocks (measured 14 stick-slip transitions, 1291 impacts); mu = 0.2
    < b/h only slides (956 transitions).  Definite, finite, inside the budget, to the end."""
    body = RigidBlock.rectangle(b=0.3, h=1.2)
    rec = H.long_record(peak_g=0.7)
    res = fr.simulate(body, rec, friction=Friction(mu), t_after=2.0, max_steps=2_000_000)
    H.definite(res, 2_000_000, STATE)
    assert res.status == status and res.metrics["stick_slip"] > 0 and res.metrics["max_slide"] > 0
    assert res.metrics["time_end"] == pytest.approx(rec.end_time(body) + 2.0, abs=1e-9)
