"""Hard cases for the rigid kernel: grazing uplift, chatter to rest (Zeno), release at the
unstable equilibrium, very slender and squat blocks, violent pulses, lift-off, and a grazing
impact that a fixed step straddles.  Every run gets a step budget and must end with a definite,
non-failure status.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

import fastrock as fr
from hardcases import definite, long_record
from test_rigid_vs_solve_ivp import Reference

G = 9.80665
BUDGET = 200_000
ALPHA, P = 0.2, 2.0


def run(body, excitation=None, **kw):
    kw.setdefault("max_steps", BUDGET)
    res = fr.simulate(body, excitation, **kw)
    assert not res.status.startswith("failed"), res.status
    h = res.history
    assert np.isfinite(h[["t", "theta", "theta_dot"]].to_numpy()).all()
    return res


def pulse(ratio, w_ratio, sign=1, kind="one-sine"):
    return fr.Pulse(ratio, w_ratio, sign=sign, kind=kind, amplitude_unit="g_tan_alpha",
                    frequency_unit="omega_p/p")


def quarter_period(alpha, p, theta0):
    """physics.md 6.2 (singularity removed by theta = theta0 - w^2)."""
    def integrand(w):
        s = 0.5 * w * w
        sinc = math.sin(s) / s if s > 0 else 1.0
        return math.sqrt(2.0 / sinc) / (p * math.sqrt(math.sin(alpha - theta0 + s)))
    return quad(integrand, 0.0, math.sqrt(theta0), epsabs=0.0, epsrel=1e-13)[0]


# ---------------------------------------------------------------- grazing uplift

@pytest.mark.parametrize("w_ratio", [0.5, 2.0, 7.0])
@pytest.mark.parametrize("kind", ["one-sine", "one-cosine"])
def test_grazing_below_uplift_level(w_ratio, kind):
    res = run(fr.RigidBlock(ALPHA, P), pulse(1 - 1e-9, w_ratio, kind=kind))
    assert res.status == "safe:no-uplift"
    assert res.metrics["max_rotation"] == 0.0
    assert res.events.empty




@pytest.mark.parametrize("w_ratio", [
    0.5,
    2.0,
    7.0,
])
def test_grazing_uplift_comes_back_to_rest(w_ratio):
    ratio = 1 + 1e-9
    body = fr.RigidBlock(ALPHA, P)
    res = fr.simulate(body, pulse(ratio, w_ratio), max_steps=BUDGET)
    assert res.status == "safe:rest", res.status
    # rotation bound: theta'' <= p^2 (ratio - 1) tan(alpha) while uplifted, for at most the pulse
    t_p = 2 * math.pi / (w_ratio * P)
    bound = 0.5 * P ** 2 * (ratio - 1) * math.tan(ALPHA) * t_p ** 2
    assert res.metrics["max_rotation"] <= bound
    assert 0 < res.metrics["time_uplift"] < t_p


@pytest.mark.parametrize("ratio", [
    1.0,
    1 + 1e-12,
])
def test_uplift_level_exactly(ratio):
    """At |a_g| = G tan(alpha) (or a hair above) the run must still end definitely; at exactly
    the level physics.md 1 says the block stays in contact (uplift needs |a_g| > G tan(alpha))."""
    res = fr.simulate(fr.RigidBlock(ALPHA, P), pulse(ratio, 2.0), max_steps=BUDGET)
    assert res.status in ("safe:no-uplift", "safe:rest"), res.status
    if ratio == 1.0:
        assert res.status == "safe:no-uplift"


# ---------------------------------------------------------------- chatter to rest (Zeno)

def test_chatter_to_rest_matches_zeno_time_and_impact_count():
    """Free rocking from 0.5 alpha with e = 0.5.  The impacts follow
    cos(alpha - theta_k) - cos(alpha) = e^{2k} [cos(alpha - theta_0) - cos(alpha)] and the motion
    ends at the Zeno time T4(theta_0) + sum_k 2 T4(theta_k) (physics.md 6.2/6.3).  The kernel
    declares rest at the first impact with |theta'+| < eps_omega = 1e-9 rad/s; the remaining Zeno
    time after it is ~ 2 |theta'| / (p^2 sin alpha) / (1 - e) < 1e-8 s."""
    e, theta0 = 0.5, 0.5 * ALPHA
    body = fr.RigidBlock(ALPHA, P, e=e)
    res = run(body, theta0=theta0, duration=20.0, rtol=1e-10)
    assert res.status == "safe:rest"
    ev = res.events
    assert ev["event"].iloc[-1] == "rest"
    e0 = math.cos(ALPHA - theta0) - math.cos(ALPHA)
    zeno = quarter_period(ALPHA, P, theta0)
    k = 1
    while True:
        ek = e ** (2 * k) * e0
        theta_k = ALPHA - math.acos(math.cos(ALPHA) + ek)
        if theta_k < 1e-300:
            break
        term = 2 * quarter_period(ALPHA, P, theta_k)
        zeno += term
        if term < 1e-16:
            break
        k += 1
    t_rest = ev["t"].iloc[-1]
    assert abs(t_rest - zeno) <= 1e-7, (t_rest, zeno)
    # impact count: first k with e^k v1 < eps_omega (the eps_t rule would fire later here:
    # the interval 2 v / (p^2 sin alpha) exceeds 1e-9 s until v < 4e-10 rad/s)
    v1 = P * math.sqrt(2 * e0)
    n_expected = math.ceil(math.log(1e-9 / v1) / math.log(e))
    assert e ** n_expected * v1 < 1e-9 < e ** (n_expected - 1) * v1
    assert res.metrics["impacts"] == n_expected
    assert res.metrics["time_end"] == 20.0
    # at rest for the rest of the run
    after = res.history[res.history["t"] > t_rest]
    assert (after["theta"] == 0).all() and (after["contact"] == "rest").all()


# ---------------------------------------------------------------- unstable equilibrium

def test_release_at_alpha_exactly():
    body = fr.RigidBlock(ALPHA, P)
    res = run(body, theta0=ALPHA, duration=20.0)
    # theta'' = -p^2 sin(alpha - theta) = 0 exactly: the block balances on its corner
    assert res.status == "safe:moving"
    assert (res.history["theta"] == ALPHA).all()
    assert res.metrics["max_rotation_ratio"] == 1.0
    assert res.metrics["impacts"] == 0


@pytest.mark.parametrize("sign", [1, -1])
def test_release_just_inside_and_outside_alpha(sign):
    body = fr.RigidBlock(ALPHA, P)
    delta = ALPHA * 1e-6
    inside = run(body, theta0=sign * (ALPHA - delta), duration=20.0, rtol=1e-13, atol=1e-15)
    assert inside.outcome == "safe" and inside.metrics["impacts"] >= 1
    t1 = inside.events[inside.events["event"] == "impact"]["t"].iloc[0]
    # near the unstable equilibrium the deviation grows like delta cosh(p t), so a state error
    # ~ rtol*alpha shifts the impact by ~ rtol*alpha / (p delta) = 5e-8 s
    tol = 1e-13 * ALPHA / (P * delta)
    assert abs(t1 - quarter_period(ALPHA, P, ALPHA - delta)) <= tol
    outside = run(body, theta0=sign * ALPHA * (1 + 1e-6), duration=20.0, rtol=1e-10)
    assert outside.status == "overturn:mode2"
    assert np.sign(outside.history["theta"].iloc[-1]) == sign


# ---------------------------------------------------------------- extreme slenderness

@pytest.mark.parametrize("alpha,e", [(0.01, None), (1.2, 0.5)])
@pytest.mark.parametrize("ratio,w_ratio,sign", [(1.3, 0.7, 1), (2.5, 2.0, -1), (8.0, 6.0, 1),
                                                (3.0, 1.0, 1)])
def test_extreme_alpha_against_reference(alpha, e, ratio, w_ratio, sign):
    body = fr.RigidBlock(alpha, P, e=e)
    res = run(body, pulse(ratio, w_ratio, sign), rtol=1e-10, t_after=10.0)
    ref = Reference(alpha, P, body.e, ratio, w_ratio, sign, t_after=10.0).run()
    assert res.outcome == ref["outcome"]
    if ref["outcome"] == "safe":
        assert res.metrics["max_rotation_ratio"] == pytest.approx(ref["max_rotation"] / alpha,
                                                                  abs=1e-6)
    else:
        assert res.metrics["time_overturn"] == pytest.approx(ref["time_overturn"], abs=1e-6)


def test_squat_block_needs_large_acceleration():
    body = fr.RigidBlock(1.2, P, e=0.5)
    below = run(body, fr.Pulse(0.99 * math.tan(1.2), 1.0, amplitude_unit="g"))
    assert below.status == "safe:no-uplift"
    above = run(body, fr.Pulse(1.01 * math.tan(1.2), 1.0, amplitude_unit="g"))
    assert above.metrics["impacts"] >= 0 and not np.isnan(above.metrics["time_uplift"])


# ---------------------------------------------------------------- violent excitation

@pytest.mark.parametrize("freq_hz", [0.5, 5.0, 50.0])
@pytest.mark.parametrize("sign", [1, -1])
def test_50g_pulse(freq_hz, sign):
    body = fr.RigidBlock.rectangle(b=0.2, h=1.0)
    res = run(body, fr.Pulse(50.0, freq_hz, sign=sign, amplitude_unit="g"))
    m = res.metrics
    assert res.outcome in ("safe", "mode1", "mode2")
    assert 0 <= m["time_uplift"] < 1 / freq_hz
    if res.outcome != "safe":
        assert m["time_uplift"] < m["time_overturn"] == m["time_end"]
        assert m["max_rotation"] == pytest.approx(body.theta_over)
    # the first motion is away from the pulse direction: a_g > 0 tips to theta < 0
    first = res.events[res.events["event"] == "uplift"]["pivot"].iloc[0]
    assert first == -sign


# ---------------------------------------------------------------- lift-off (free flight)

def test_vertical_below_minus_g_from_rest_is_flight():
    body = fr.RigidBlock(ALPHA, P)
    vert = fr.Pulse(kind="rectangular", amplitude=1.5, amplitude_unit="g", sign=-1, duration=0.5)
    res = run(body, None, vertical=vert, duration=2.0)
    assert res.outcome == "flight" and res.status == "flight"
    assert res.metrics["time_end"] == 0.0
    assert list(res.events["event"]) == ["flight"]


def test_vertical_below_minus_g_while_rocking_is_flight():
    body = fr.RigidBlock(ALPHA, P)
    vert = fr.Pulse(kind="rectangular", amplitude=1.5, amplitude_unit="g", sign=-1, duration=0.5,
                    t_start=0.3)
    res = run(body, None, vertical=vert, theta0=0.1, duration=2.0)
    assert res.outcome == "flight"
    assert res.metrics["time_end"] == pytest.approx(0.3, abs=1e-12)


@pytest.mark.parametrize("theta0", [0.0, 0.1])
def test_vertical_sine_crossing_minus_g_is_flight_at_the_crossing(theta0):
    """a_v = -1.5 g sin(w t): G = g + a_v reaches 0 at sin(w t) = 2/3."""
    body = fr.RigidBlock(ALPHA, P)
    w = 2 * math.pi * 1.0
    vert = fr.Pulse(1.5, 1.0, sign=-1, amplitude_unit="g")
    res = run(body, None, vertical=vert, theta0=theta0, duration=3.0, rtol=1e-10)
    assert res.outcome == "flight"
    assert res.metrics["time_end"] == pytest.approx(math.asin(2 / 3) / w, abs=1e-9)


# ---------------------------------------------------------------- grazing impact in one step

def test_grazing_impact_inside_one_fixed_step():
    """Under a constant a_g = -A g the block (pivot s = +1) approaches theta = 0 with
    theta'' ~= c = p^2 (A cos(alpha) - sin(alpha)) = 1 rad/s^2: theta(t) ~= d - v t + c t^2/2
    dips to -1e-5 rad around t = 0.025 s and is back at ~d > 0 at t = 0.05 s.  A fixed step of
    0.05 s sees theta > 0 at both ends; only the dense output's interior minimum reveals the
    impact.  The reference is DOP853 with max_step 1e-3 (without it solve_ivp steps over this
    very crossing: its events are sign changes at step ends)."""
    c = 1.0
    A = (c / P ** 2 + math.sin(ALPHA)) / math.cos(ALPHA)
    v, depth = 0.025 * c, 1e-5
    d = v * v / (2 * c) - depth
    body = fr.RigidBlock(ALPHA, P)
    exc = fr.Pulse(A, kind="rectangular", amplitude_unit="g", sign=-1, duration=10.0)

    def f(t, y):
        return [y[1], -P * P * (math.sin(ALPHA - y[0]) - A * math.cos(ALPHA - y[0]))]

    def hit(t, y):
        return y[0]
    hit.terminal, hit.direction = True, -1
    ref = solve_ivp(f, (0, 0.05), [d, -v], method="DOP853", rtol=1e-13, atol=1e-16, events=hit,
                    max_step=1e-3)
    assert ref.t_events[0].size == 1
    t_ref, w_ref = ref.t_events[0][0], ref.y_events[0][0][1]

    coarse = run(body, exc, theta0=d, dtheta0=-v, duration=1.0, dt=0.05)
    fine = run(body, exc, theta0=d, dtheta0=-v, duration=1.0, rtol=1e-12)
    assert coarse.history["t"].iloc[1] == pytest.approx(t_ref, abs=1e-6)   # an event row, not 0.05
    for res, tol in ((coarse, 1e-6), (fine, 1e-10)):
        imp = res.events[res.events["event"] == "impact"]
        assert len(imp) == 2                      # back to theta = 0 once more, then away (s = +1)
        # dense output of one DP5 step of h = 0.05: error ~ p^4 h^5 |theta| ~ 1e-9 rad, divided
        # by |theta'| ~ 4e-3 rad/s at the crossing: ~ 3e-7 s
        assert imp["t"].iloc[0] == pytest.approx(t_ref, abs=tol)
        assert imp["velocity_before"].iloc[0] == pytest.approx(w_ref, abs=tol)
    assert coarse.status == fine.status
    assert coarse.metrics["max_rotation"] == pytest.approx(fine.metrics["max_rotation"], rel=1e-4)


@pytest.mark.parametrize("factor", [1.0, 1 + 1e-15, 1 + 1e-13, 1 + 1e-9])
def test_record_peak_at_the_uplift_threshold(factor):
    """A record scaled so that its peak sits on g tan(alpha) (up to a few ulp) must not
    end in a transition loop: a touch is no uplift, a real exceedance rocks and settles."""
    from fastrock.io.default_records import load_default_record
    rec = load_default_record()
    body = fr.RigidBlock.rectangle(b=0.25, h=1.25)
    scale = body.g * math.tan(body.alpha) / rec.pga * factor
    res = fr.simulate(body, fr.SampledMotion.from_record(rec, scale=scale), t_after=2.0,
                      max_steps=BUDGET)
    assert not res.status.startswith("failed"), res.status
    assert res.outcome == "safe"
    if factor <= 1 + 1e-15:
        assert res.status == "safe:no-uplift"


def test_long_record_90s_at_dt_0005():
    """A 90 s record sampled at 0.005 s (18 000 samples, every one a breakpoint): the run ends
    with a definite status inside the step budget, and the history has no NaN.  The wall, friction
    and flexible kernels run the same record in their own hard-case files."""
    body, rec = fr.RigidBlock.rectangle(b=0.3, h=1.2), long_record()
    res = fr.simulate(body, rec, t_after=2.0, max_steps=2_000_000)
    definite(res, 2_000_000)
    # 0.35 g against g tan(alpha) = 0.25 g: uplifts at 40.5 s, rocks and chatters to rest
    assert res.outcome == "safe" and res.metrics["impacts"] > 0
    assert res.metrics["time_end"] == pytest.approx(rec.end_time(body) + 2.0, abs=1e-9)
