"""Rigid block against the closed forms of physics.md section 6.

Oracles: scipy.integrate.quad of the exact quarter-period integral, the exact energy map across
an impact, Housner's restitution derived here from angular momentum about the impacting corner,
and the linearised mode-2 thresholds (one-sine table of 6.5, rectangular-pulse formula of 6.4)
approached by the exact kernel on very flat blocks, with the O(alpha^2) linearisation error
bounded and then removed by Richardson extrapolation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

import fastrock as fr

G = 9.80665
ALPHA, P, THETA0 = 0.25, 2.0, 0.15


def quarter_period_exact(alpha, p, theta0):
    """physics.md 6.2, T/4 = int_0^theta0 dtheta / (p sqrt(2[cos(alpha-theta0) - cos(alpha-theta)])).

    The 1/sqrt singularity at theta = theta0 is removed with theta = theta0 - w^2 and
    cos X - cos Y = 2 sin(alpha - theta0 + w^2/2) sin(w^2/2).
    """
    def integrand(w):
        s = 0.5 * w * w
        sinc = math.sin(s) / s if s > 0 else 1.0
        return math.sqrt(2.0 / sinc) / (p * math.sqrt(math.sin(alpha - theta0 + s)))

    val, err = quad(integrand, 0.0, math.sqrt(theta0), epsabs=0.0, epsrel=1e-13)
    assert err < 1e-12 * val
    return val


def quarter_period_linear(alpha, p, theta0):
    """physics.md 6.1, T/4 = acosh(1/(1 - theta0/alpha)) / p."""
    return math.acosh(1.0 / (1.0 - theta0 / alpha)) / p


def amplitude_after_impact(alpha, e, theta0):
    """physics.md 6.3, cos(alpha - theta1) - cos(alpha) = e^2 [cos(alpha - theta0) - cos(alpha)]."""
    return alpha - math.acos(math.cos(alpha) + e * e * (math.cos(alpha - theta0) - math.cos(alpha)))


def free_rocking(body, theta0, duration, rtol):
    res = fr.simulate(body, theta0=theta0, duration=duration, rtol=rtol, atol=rtol * 1e-2)
    assert not res.status.startswith("failed"), res.status
    return res


def impacts(res):
    ev = res.events
    return ev[ev["event"] == "impact"].reset_index(drop=True)


# ---------------------------------------------------------------- 6.1 / 6.2 quarter period

def test_quarter_period_check_values():
    assert quarter_period_exact(ALPHA, P, THETA0) == pytest.approx(0.7844874371, abs=1e-10)
    assert quarter_period_linear(ALPHA, P, THETA0) == pytest.approx(0.7833996185, abs=1e-10)


@pytest.mark.nojit
@pytest.mark.parametrize("rtol", [1e-8, 1e-10, 1e-12])
def test_quarter_period_exact_from_first_impact(rtol):
    body = fr.RigidBlock(alpha=ALPHA, p=P)
    res = free_rocking(body, THETA0, 1.0, rtol)
    t1 = impacts(res)["t"].iloc[0]
    ref = quarter_period_exact(ALPHA, P, THETA0)
    # global error of an rtol-controlled RK45 run over ~1 time unit: a small multiple of rtol
    assert abs(t1 - ref) <= 10 * rtol * ref, (t1, ref)


@pytest.mark.nojit
@pytest.mark.parametrize("alpha", [0.01, 0.05])
@pytest.mark.parametrize("ratio", [0.3, 0.6, 0.9])
def test_quarter_period_tends_to_linearised(alpha, ratio):
    """sin(alpha - theta) = (alpha - theta)(1 - (alpha - theta)^2/6 + ...), |alpha - theta| <= alpha:
    the restoring term is weakened by at most alpha^2/6, which lengthens the quarter period by a
    relative amount in (0, alpha^2/6]."""
    body = fr.RigidBlock(alpha=alpha, p=P)
    theta0 = ratio * alpha
    res = free_rocking(body, theta0, 4.0, 1e-12)
    t1 = impacts(res)["t"].iloc[0]
    lin = quarter_period_linear(alpha, P, theta0)
    rel = (t1 - lin) / lin
    assert 0.0 < rel <= alpha ** 2 / 6, rel
    # and the exact integral holds at any alpha
    assert t1 == pytest.approx(quarter_period_exact(alpha, P, theta0), rel=1e-11)


# ---------------------------------------------------------------- 6.3 amplitude after an impact

def test_amplitude_after_one_impact_check_value():
    body = fr.RigidBlock(alpha=ALPHA, p=P)
    assert amplitude_after_impact(ALPHA, body.e, THETA0) == pytest.approx(0.1115636539, abs=1e-10)


@pytest.mark.nojit
@pytest.mark.parametrize("alpha,theta0,e", [(ALPHA, THETA0, None), (0.1, 0.09, 0.7), (0.4, 0.1, 1.0)])
def test_amplitude_after_one_impact(alpha, theta0, e):
    body = fr.RigidBlock(alpha=alpha, p=P, e=e)
    t4 = quarter_period_exact(alpha, P, theta0)
    theta1 = amplitude_after_impact(alpha, body.e, theta0)
    # stop between the first negative peak and the second impact: T/4 + T1/4 + a little
    dur = t4 + quarter_period_exact(alpha, P, theta1) * 1.5
    res = free_rocking(body, theta0, dur, 1e-12)
    assert len(impacts(res)) == 1
    assert res.metrics["max_rotation_neg"] == pytest.approx(theta1, rel=1e-10)
    assert res.metrics["max_rotation_pos"] == theta0
    assert res.metrics["max_rotation"] == pytest.approx(max(theta0, theta1), rel=1e-10)
    # the linearised form of 6.3 is the alpha -> 0 limit (sanity of the formula itself)
    lin = alpha * (1 - math.sqrt(1 - body.e ** 2 * (1 - (1 - theta0 / alpha) ** 2)))
    assert abs(theta1 - lin) <= alpha ** 3


# ---------------------------------------------------------------- Housner restitution

def restitution_from_angular_momentum(b, h, m, I_G):
    """Angular momentum about the impacting corner is conserved (Housner 1963).

    Block rocking about its right corner (b, 0) reaches theta = 0 with theta' = w (clockwise
    positive); the CM (0, h) moves with v = w (h, b) (clockwise rotation about the right corner).
    After impact it rotates about the left corner Q = (-b, 0) with w+ and L_Q = I_0 w+.
    Clockwise angular momentum of a point mass at r (from Q) with velocity v: r_y v_x - r_x v_y.
    """
    w = 1.0
    rx, ry = 0.0 - (-b), h - 0.0          # CM relative to Q
    vx, vy = w * h, w * b
    L_before = I_G * w + m * (ry * vx - rx * vy)
    I0 = I_G + m * (b * b + h * h)
    return L_before / I0


@pytest.mark.parametrize("b,h", [(0.2, 1.0), (0.5, 0.6), (0.05, 2.0), (1.0, 1.0)])
def test_housner_restitution_rectangle(b, h):
    body = fr.RigidBlock.rectangle(b, h)
    alpha = math.atan(b / h)
    assert body.alpha == pytest.approx(alpha, rel=1e-15)
    e_ref = 1 - 1.5 * math.sin(alpha) ** 2
    assert body.e == pytest.approx(e_ref, rel=1e-14, abs=1e-15)
    assert body.housner_e == pytest.approx(e_ref, rel=1e-14, abs=1e-15)
    m = 3.0
    I_G = m * (b * b + h * h) / 3.0          # rectangle 2b x 2h: I_G = m((2b)^2 + (2h)^2)/12
    assert body.e == pytest.approx(restitution_from_angular_momentum(b, h, m, I_G), rel=1e-13,
                                   abs=1e-15)
    R = math.hypot(b, h)
    assert body.p == pytest.approx(math.sqrt(3 * G / (4 * R)), rel=1e-15)


@pytest.mark.parametrize("R,alpha,k", [(1.0, 0.2, 1.2), (0.7, 0.35, 4 / 3), (2.0, 0.1, 2.5)])
def test_housner_restitution_from_inertia(R, alpha, k):
    m = 2.5
    I0 = k * m * R * R
    body = fr.RigidBlock.from_inertia(R, alpha, I0, m)
    e_ref = 1 - (m * R * R / I0) * (1 - math.cos(2 * alpha))
    assert body.e == pytest.approx(e_ref, rel=1e-14)
    b, h = R * math.sin(alpha), R * math.cos(alpha)
    assert body.e == pytest.approx(restitution_from_angular_momentum(b, h, m, I0 - m * R * R),
                                   rel=1e-13)
    assert body.p == pytest.approx(math.sqrt(m * G * R / I0), rel=1e-15)
    if k == 4 / 3:      # a rectangle's inertia: the same body as RigidBlock.rectangle
        rect = fr.RigidBlock.rectangle(b, h)
        assert body.e == pytest.approx(rect.e, rel=1e-13)
        assert body.p == pytest.approx(rect.p, rel=1e-13)


@pytest.mark.nojit
@pytest.mark.parametrize("e", [None, 0.6, 0.95])
def test_energy_ratio_per_impact_is_e_squared(e):
    """At theta = 0 the energy is purely kinetic, theta'^2/(2 p^2) (units of M g R); per impact it
    is multiplied by e^2, and between impacts free rocking conserves it (|theta'| on return to
    theta = 0 equals |theta'| after the previous impact)."""
    body = fr.RigidBlock.from_inertia(1.0, 0.2, 1.5 * 1.0, 1.0, e=e)
    res = free_rocking(body, 0.15, 8.0, 1e-11)
    imp = impacts(res)
    assert len(imp) >= 4
    vb = imp["velocity_before"].to_numpy()
    va = imp["velocity_after"].to_numpy()
    kin = lambda v: v * v / (2 * body.p ** 2)  # noqa: E731
    np.testing.assert_allclose(kin(va) / kin(vb), body.e ** 2, rtol=1e-13)
    # relative to rtol, plus the run's atol (1e-13) once the velocities have decayed
    np.testing.assert_allclose(-vb[1:], va[:-1], rtol=1e-9, atol=1e-12)
    # pivots alternate, theta is 0 at every impact
    assert (imp["theta"] == 0).all()
    assert (np.diff(imp["pivot"].to_numpy()) != 0).all()
    # first impact velocity from energy conservation: theta'^2/(2p^2) = cos(alpha - theta0) - cos(alpha)
    v1 = body.p * math.sqrt(2 * (math.cos(0.2 - 0.15) - math.cos(0.2)))
    assert abs(vb[0]) == pytest.approx(v1, rel=1e-9)


# ---------------------------------------------------------------- mode-2 thresholds (6.4, 6.5)
#
# The exact kernel is bisected for "overturns without any impact" on very flat blocks.  The
# linearisation replaces sin x by x, cos x by 1 (x = alpha - theta) and tan(alpha) by alpha.
# Until the outcome is decided theta stays within a few alpha of 0, say |alpha - theta| <= 2 alpha,
# so the forcing term cos x is off by at most (2 alpha)^2/2 = 2 alpha^2 relative, the restoring
# term by (2 alpha)^2/6 and the uplift level by alpha^2/3: the threshold may move by ~2 alpha^2
# relative, which is the stated tolerance at alpha = 0.01 (plus the table's rounding, 5e-6).
# Then the error is removed: with thr(alpha) = thr0 + c alpha^2 + O(alpha^4), the Richardson
# value (4 thr(0.01) - thr(0.02)) / 3 must reproduce the linearised value itself, to the table's
# rounding plus O(alpha^4) ~ 1e-7 and the bisection width.

ALPHAS = (0.01, 0.02)
P_FLAT = 2.0
BISECT_REL = 1e-9


def _overturns_without_impact(body, pulse):
    # early_exit=False: the run must decide the outcome by itself, no early decision involved
    res = fr.simulate(body, pulse, rtol=1e-10, t_eval=[0.0], max_steps=200_000)
    assert not res.status.startswith("failed"), res.status
    return res.outcome == "mode2"


def _bisect(pred, lo, hi):
    assert not pred(lo) and pred(hi), "bracket"
    while hi - lo > BISECT_REL * hi:
        mid = 0.5 * (lo + hi)
        if pred(mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def one_sine_threshold(alpha, w_ratio):
    body = fr.RigidBlock(alpha=alpha, p=P_FLAT)

    def pred(r):       # r = a_p / (g alpha); a_g = -a_p sin(omega_p t) tips the block to +theta
        return _overturns_without_impact(body, fr.Pulse(r * G * alpha, w_ratio, sign=-1,
                                                        amplitude_unit="m/s2",
                                                        frequency_unit="omega_p/p"))
    return _bisect(pred, 1.0, 40.0)


def rectangular_threshold(alpha, pt1):
    body = fr.RigidBlock(alpha=alpha, p=P_FLAT)

    def pred(r):       # r = A / alpha, a_g = -A g for 0 <= t <= t1
        return _overturns_without_impact(body, fr.Pulse(r * alpha * G, sign=-1, kind="rectangular",
                                                        duration=pt1 / P_FLAT,
                                                        amplitude_unit="m/s2"))
    return _bisect(pred, 1.0, 40.0)


TABLE_ROUNDING = 5e-6      # the table of 6.5 is printed with 5 decimals


@pytest.mark.parametrize("w_ratio,table", [(1, 1.41832), (2, 2.34990), (4, 5.23896), (8, 14.87135)])
def test_one_sine_mode2_threshold_flat_block(w_ratio, table):
    thr = {a: one_sine_threshold(a, w_ratio) for a in ALPHAS}
    a = ALPHAS[0]
    assert abs(thr[a] - table) <= 2 * a * a * table + TABLE_ROUNDING, thr
    # O(alpha^2): halving alpha divides the error by ~4 (the printed table limits this check)
    richardson = (4 * thr[ALPHAS[0]] - thr[ALPHAS[1]]) / 3
    assert abs(richardson - table) <= TABLE_ROUNDING + 2e-6 * table, (richardson, table)


@pytest.mark.parametrize("pt1", [0.4, 1.0, 2.0])
def test_rectangular_mode2_threshold_flat_block(pt1):
    exact = 1.0 / (1.0 - math.exp(-pt1))         # physics.md 6.4: A/alpha >= 1/(1 - e^{-p t1})
    thr = {a: rectangular_threshold(a, pt1) for a in ALPHAS}
    a = ALPHAS[0]
    assert abs(thr[a] - exact) <= 2 * a * a * exact, thr
    richardson = (4 * thr[ALPHAS[0]] - thr[ALPHAS[1]]) / 3
    assert richardson == pytest.approx(exact, rel=2e-6)


def test_rectangular_pulse_check_value():
    assert 1.0 / (1.0 - math.exp(-1.0)) == pytest.approx(1.58198, abs=5e-6)
