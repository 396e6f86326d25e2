"""The flexible body's early decision in rocking (issue #15 item 3; kernels/flexible.py
``bounded_free_rocking``): after the excitation, the total energy E (kinetic + column strain +
gravity) never grows, and below the least potential over u at the top of the barrier the body
cannot overturn.  The run then ends ``safe:bounded``, but only once the same energy bound keeps
|theta| within the maxima so far on both sides.

Oracles:

1. the barrier profile m(phi) = min over u of the potential, against a brute-force minimum of
   the potential written from physics.md 3.1 (heights of the mass and the base's centre of mass
   about the pivot, strain w^2 u^2 / 2);
2. full runs (``early_exit=False``) of the same grids: the same outcome on every cell and the same
   ``max_rotation`` and ``max_deformation`` (the decided rows follow the same step sequence up
   to the decision, so the maxima are equal to rounding), and the decision does fire.  It waits
   for the energy's bound on |u| to fall within the largest deflection so far; a soft undamped
   column (omega_n/p = 3, zeta = 0) never gets there within 5 s, and is not decided.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import fastrock as fr
from fastrock import FlexibleBody, Wall
from fastrock.kernels import flexible as K
from fastrock.kernels import layout as L
from fastrock.running.models import flexible_par

BODIES = {
    "I3-wn9-zeta0.05": dict(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05),
    "I1-wn30-e0.9": dict(alpha=0.3, p=2.0, omega_n_over_p=30.0, zeta=0.02, impact="pivot-switch", e=0.9),
    "base-mass": dict(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, base_mass_ratio=0.2,
                      base_cm_height=0.1, rotary_inertia_ratio=0.1),
    "I3-wn100-undamped": dict(alpha=0.15, p=2.5, omega_n_over_p=100.0, zeta=0.0),
    "I3-wn3-soft": dict(alpha=0.25, p=2.0, omega_n_over_p=3.0, zeta=0.0),
}

# measured: 26, 48, 34, 4 and 0 of 100 (the soft undamped column's |u| bound stays above its
# deflections so far)
MIN_DECIDED = {"I3-wn3-soft": 0}


def potential(par, s, u, phi):
    """Gravity + strain per unit mass on pivot s at s theta = phi, zero upright at rest
    (physics.md 3.1: mass at (u - sB, H) in the base frame, base CM at (0, h_b) above the base's
    centre, both turned by theta about the corner s B)."""
    g, B, H, hb, mb, wn = (par[L.F_G], par[L.F_B], par[L.F_H], par[L.F_HB], par[L.F_MB], par[L.F_WN])
    th = s * phi
    y_mass = -(u - s * B) * np.sin(th) + H * np.cos(th)
    y_base = s * B * np.sin(th) + hb * np.cos(th)
    return 0.5 * wn ** 2 * u ** 2 + g * (y_mass + mb * y_base) - g * (H + mb * hb)


@pytest.mark.parametrize("name", BODIES)
def test_barrier_profile_is_the_least_potential_over_u(name):
    par = flexible_par(FlexibleBody(**BODIES[name]))
    g, B, wn = par[L.F_G], par[L.F_B], par[L.F_WN]
    a = B * (1.0 + par[L.F_MB])
    c = par[L.F_H] + par[L.F_MB] * par[L.F_HB]
    k = g / wn ** 2
    for phi in np.linspace(0.0, 0.5, 11):
        m, dm = K.barrier_profile(phi, a, c, k, g)
        for s in (1, -1):
            u = s * k * np.sin(phi) + np.linspace(-3.0, 3.0, 60001) * (k + 1e-3 * B)
            brute = potential(par, s, u, phi).min()
            assert m <= brute + 1e-12 * g * B
            assert m == pytest.approx(brute, rel=1e-8, abs=1e-12 * g * B)
        h = 1e-6
        num = (K.barrier_profile(phi + h, a, c, k, g)[0] - K.barrier_profile(phi - h, a, c, k, g)[0]) / (2 * h)
        assert dm == pytest.approx(num, rel=1e-6, abs=1e-9 * g * B)


def test_energy_above_the_barrier_or_past_its_top_is_not_decided():
    b = FlexibleBody(**BODIES["I3-wn9-zeta0.05"])
    par = flexible_par(b)
    # at rest just inside the top: E = V > m(phi) only slightly, phi below the top: safe
    ok, phi_b, U = K.bounded_free_rocking(np.array([0.0, 0.0, 0.5 * b.alpha, 0.0]), 1, par, np.inf)
    assert ok and 0.5 * b.alpha <= phi_b < b.alpha and U > 0.0
    # the same state with a limit on the future peak: decided only if Phi is within it
    assert K.bounded_free_rocking(np.array([0.0, 0.0, 0.5 * b.alpha, 0.0]), 1, par, phi_b)[0]
    assert not K.bounded_free_rocking(np.array([0.0, 0.0, 0.5 * b.alpha, 0.0]), 1, par, 0.999 * phi_b)[0]
    assert not K.bounded_free_rocking(np.array([0.0, 0.0, 0.5 * b.alpha, 0.0]), 1, par, 0.4 * b.alpha)[0]
    # same rotation, fast outward: above the barrier
    ok, _, _ = K.bounded_free_rocking(np.array([0.0, 0.0, 0.5 * b.alpha, 5.0 * b.p]), 1, par, np.inf)
    assert not ok
    # past the top of the barrier (phi_c <= alpha for a massless base)
    ok, _, _ = K.bounded_free_rocking(np.array([0.0, 0.0, -1.01 * b.alpha, 0.0]), -1, par, np.inf)
    assert not ok


def _grids(body, wall=None):
    A = [1.1, 1.6, 2.4, 3.5, 5.0]
    F = [0.8, 1.5, 2.5, 4.0, 6.5]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for kind in ("one-sine", "half-sine"):
            kw = dict(pulse=kind, wall=wall, progress=False, t_after=5.0)
            e = fr.overturning_spectrum(body, A, F, "both", early_exit=True, **kw)
            f = fr.overturning_spectrum(body, A, F, "both", early_exit=False, **kw)
            yield e, f


def _compare(e, f):
    assert (e.outcome == f.outcome).all(), e.loc[e.outcome != f.outcome, ["amplitude_ratio", "frequency_ratio"]]
    np.testing.assert_allclose(e.max_rotation, f.max_rotation, rtol=1e-12, atol=0.0)
    bounded = e.status == "safe:bounded"
    # the decision waits for the bound on |u| too: max |u| is the full run's
    np.testing.assert_allclose(e.max_deformation, f.max_deformation, rtol=1e-12, atol=0.0)
    assert f.loc[bounded, "status"].str.startswith("safe").all()
    assert (e.nfev <= f.nfev).all()
    return int(bounded.sum())


@pytest.mark.parametrize("name", BODIES)
def test_early_decision_equals_full_runs(name):
    """Same outcome and max_rotation as the full runs, on 100 cells per body
    (one-sine and half-sine, both signs); the decision fires on some of them."""
    decided = 0
    for e, f in _grids(FlexibleBody(**BODIES[name])):
        decided += _compare(e, f)
    print(f"{name}: {decided} of 100 cells decided in rocking")
    assert decided >= MIN_DECIDED.get(name, 1)


@pytest.mark.parametrize("theta_w_over_alpha", [0.6, 1.3])
def test_early_decision_with_a_wall_equals_full_runs(theta_w_over_alpha):
    """With a rear wall, inside the body's instability (0.6 alpha) and beyond it (1.3 alpha, where
    a full run may end leaning: the decision then needs the wall out of the bound's reach)."""
    b = FlexibleBody(**BODIES["I3-wn9-zeta0.05"])
    w = Wall(gap=2.0 * b.H * math.sin(theta_w_over_alpha * b.alpha), restitution=0.5)
    decided = 0
    for e, f in _grids(b, wall=w):
        decided += _compare(e, f)
    print(f"wall at {theta_w_over_alpha} alpha: {decided} of 100 cells decided in rocking")
    assert decided >= 1
