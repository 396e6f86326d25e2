"""Early overturning decision of the rigid kernel (kernels/rigid.py).

After the excitation, a block rocking outward (s theta' > 0) that is past alpha, or inside the
well with energy above the barrier 1 - cos(alpha), must overturn without any impact.  With
``early_exit`` the kernel decides it there (``overturns_after_excitation``) and completes the run
in closed form (``fall_to_overturn``): theta'^2 = 4 p^2 (c + sin^2(u/2)) with u = s theta - alpha,
so the fall time is an incomplete elliptic integral of the first kind, evaluated with Carlson's
R_F.  Oracles: ``scipy.special.elliprf``, ``scipy.integrate.quad`` of the fall time, and the same
run integrated to the end (``early_exit=False``) at a tight tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import elliprf

import fastrock as fr
from fastrock.kernels import rigid as K

RTOL = 1e-11


def test_carlson_rf_matches_scipy():
    rng = np.random.default_rng(7)
    for _ in range(500):
        x, y, z = rng.uniform(0.0, 1.0, 3) * 10.0 ** rng.uniform(-14.0, 4.0, 3)
        if rng.uniform() < 0.2:
            x = 0.0                          # complete integrals: one argument zero
        ref = elliprf(x, y, z)
        assert K.carlson_rf(x, y, z) == pytest.approx(ref, rel=4e-15, abs=0.0), (x, y, z)


def fall_time_quad(theta0, w0, alpha, p, theta_end):
    """Time from (theta0, w0 > 0) to theta_end under free rocking about the right corner:
    int dtheta / theta', theta'^2 = w0^2 + 2 p^2 [cos(alpha - theta0) - cos(alpha - theta)]."""
    def integrand(th):
        return 1.0 / math.sqrt(w0 * w0 + 2 * p * p * (math.cos(alpha - theta0)
                                                       - math.cos(alpha - th)))
    pts = [alpha] if theta0 < alpha < theta_end else None
    val, err = quad(integrand, theta0, theta_end, epsabs=0.0, epsrel=1e-13, limit=200,
                    points=pts)
    assert err < 1e-11 * val
    return val


# (theta0, theta0'): inside the well above the barrier (c > 0), at alpha, and past alpha with
# energy below the barrier (c < 0) or above it, down to a speed of 1e-3 rad/s
FALLS = [(0.0, 1.2), (0.1, 0.8), (0.2, 0.55), (0.25, 0.05), (0.3, 1e-3), (0.3, 0.2),
         (0.6, 0.01), (1.2, 2.0)]


@pytest.mark.parametrize("theta0,w0", FALLS)
def test_fall_times_match_quadrature(theta0, w0):
    alpha, p, theta_over = 0.25, 2.0, math.pi / 2
    for s in (1, -1):
        falls, _c, dt_alpha, dt_over = K.overturns_after_excitation(s * theta0, s * w0, s, alpha,
                                                                    p, theta_over)
        assert falls
        ref = fall_time_quad(theta0, w0, alpha, p, theta_over)
        assert dt_over == pytest.approx(ref, rel=1e-12)
        if theta0 < alpha:
            assert dt_alpha == pytest.approx(fall_time_quad(theta0, w0, alpha, p, alpha),
                                             rel=1e-12)
        else:
            assert np.isnan(dt_alpha)


@pytest.mark.parametrize("theta0,w0", [(0.1, 0.2), (0.2, -0.9), (0.3, -0.5), (0.3, 0.0)])
def test_no_decision_when_it_may_come_back(theta0, w0):
    """Inside the well below the barrier, or moving inward, or at rest: not decided."""
    for s in (1, -1):
        assert not K.overturns_after_excitation(s * theta0, s * w0, s, 0.25, 2.0, math.pi / 2)[0]


def pulse(ratio, w_ratio, sign):
    return fr.Pulse(ratio, w_ratio, sign=sign, amplitude_unit="g_tan_alpha",
                    frequency_unit="omega_p/p")


# runs decided after the excitation: pulses that overturn after one impact, and free rocking
# from an initial state (the excitation "ends" at t = 0)
CASES = [
    (0.25, 2.0, dict(excitation=pulse(3.0, 4.0, +1))),
    (0.2, 3.0, dict(excitation=pulse(6.0, 5.0, -1))),
    (0.25, 2.0, dict(theta0=0.1, dtheta0=0.8, duration=5.0)),
    (0.25, 2.0, dict(theta0=-0.3, dtheta0=-0.01, duration=5.0)),
    (0.3, 1.5, dict(theta0=0.05, dtheta0=-0.7, duration=5.0)),   # impact first: mode 1
]


@pytest.mark.parametrize("alpha,p,kw", CASES)
def test_early_overturn_equals_the_integrated_run(alpha, p, kw):
    body = fr.RigidBlock(alpha=alpha, p=p)
    full = fr.simulate(body, rtol=RTOL, early_exit=False, **kw)
    early = fr.simulate(body, rtol=RTOL, early_exit=True, **kw)
    assert full.outcome in ("mode1", "mode2")
    assert early.status == full.status
    mf, me = full.metrics, early.metrics
    assert me["nfev"] < mf["nfev"], "the decision was made before the fall was integrated"
    # the history stops at the decision, which comes after the excitation
    t_decided = early.history["t"].iloc[-1]
    assert t_decided < me["time_overturn"]
    if "excitation" in kw:
        assert t_decided >= kw["excitation"].end_time(body)
    for key in ("time_overturn", "time_end", "time_pass_alpha"):
        assert me[key] == pytest.approx(mf[key], rel=0, abs=1e-8, nan_ok=True), key
    assert me["time_end"] == me["time_overturn"]
    for key in ("max_rotation", "max_rotation_pos", "max_rotation_neg", "impacts"):
        assert me[key] == pytest.approx(mf[key], rel=1e-12, abs=1e-15), key
    assert me["max_rotation"] == pytest.approx(body.theta_over, rel=1e-14)
    # the same events, the fall's pass-alpha and overturn included
    ef, ee = full.events, early.events
    assert list(ee["event"]) == list(ef["event"])
    assert ee["event"].iloc[-1] == "overturn"
    np.testing.assert_allclose(ee["t"], ef["t"], rtol=0, atol=1e-8)
    np.testing.assert_allclose(ee["theta"], ef["theta"], rtol=0, atol=1e-10)
    np.testing.assert_allclose(ee["velocity_before"], ef["velocity_before"], rtol=1e-8, atol=1e-10)
    assert (ee["pivot"].to_numpy() == ef["pivot"].to_numpy()).all()


def test_fall_ending_after_the_run_is_integrated_on():
    """A fall decided after the pulse that would reach theta_over only after the end of the run
    (t_over 15.0 s > t_end 11.8 s): the run integrates on and ends safe:moving, as without
    early_exit (found by test_property_spectrum_early_exit_equals_full)."""
    body = fr.RigidBlock(alpha=0.14874007576403125, p=0.5)
    exc = pulse(6.913507976034974, 6.913507976034974, +1)
    full = fr.simulate(body, exc, early_exit=False)
    early = fr.simulate(body, exc, early_exit=True)
    assert full.status == early.status == "safe:moving"
    np.testing.assert_equal(early.metrics, full.metrics)
    longer = fr.simulate(body, exc, t_after=14.0, early_exit=True)
    assert longer.status == "overturn:mode1"
    assert 15.0 < longer.metrics["time_overturn"] < 15.01
