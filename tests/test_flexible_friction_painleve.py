"""Flexible body with friction: Painleve-type contact (issue #14; physics.md 4.4-4.6).

Where neither stick nor a slip toward either side is consistent, the kernel used to end
``failed:inconsistent-contact`` (or loop: ``failed:transition-loop``).  It now picks the contact
mode at zero slip speed by the signs of A (the frictionless pivot's N: the free pivot is pressed
iff A > 0) and D(sigma) = 1 + mu_k sigma dN/dF, as kernels/friction.py does for the rigid block,
and stops a slip that has no consistent continuation with the pivot pressed by a tangential
impact (the plastic horizontal impulse at the pivot).

Oracles, none of them the function under test:

1. the sympy Lagrangian of tests/test_flexible_friction.py: A is its N with F = 0, dN/dF its
   slope in F;
2. the direct solves: whatever mode the pick returns is consistent by the kernel's own
   ``slip_rock`` / ``stick_rock`` (N >= 0, the slip not reversed, flight only where A <= 0), on
   random states, and a jam never comes out off the boundaries;
3. mechanics of an impulse at the pivot: it changes only the generalised momentum of d (the
   pivot's height is fixed in these coordinates, so the normal impulse does no virtual work), so
   p_u and p_theta are kept, d'+ = 0 and the kinetic energy does not rise;
4. the fuzz cells that failed: they end definite, with the outcome of the same run at rtol 1e-11.
"""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from fastrock import FlexibleBody, Friction
from fastrock.kernels import flexible as KF
from fastrock.kernels import flexible_friction as K
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import N_COUNTERS
from fastrock.running.models import flexible_friction_par

from test_flexible_friction import constant_ground, lagrangian_model


def _random_state(rng, mu=None):
    b = FlexibleBody(alpha=rng.uniform(0.05, 0.6), p=rng.uniform(0.5, 6), omega_n_over_p=rng.uniform(2, 60),
                     zeta=rng.uniform(0, 0.1), base_mass_ratio=rng.uniform(0.02, 0.5),
                     base_cm_height=rng.uniform(0.0, 0.3) * 0.5, rotary_inertia_ratio=rng.uniform(0, 0.4))
    mu_s = float(np.exp(rng.uniform(np.log(0.05), np.log(20.0)))) if mu is None else mu
    fr = Friction(mu_s, mu_s * rng.uniform(0.5, 1.0))
    par = flexible_friction_par(b, fr)
    s = int(rng.choice([-1, 1]))
    ag = float(rng.uniform(-3, 3)) * b.g
    hdr, smp = constant_ground(b, ag)
    uy = b.uplift_deformation
    y = np.array([rng.uniform(-3, 3) * uy, rng.uniform(-1, 1) * uy * b.omega_n, s * rng.uniform(1e-3, 1.4),
                  rng.uniform(-3, 3) * b.p, 0.0, 0.0])
    return b, fr, par, s, ag, hdr, smp, y


def test_normal_margins_against_the_sympy_lagrangian():
    """A = N of the frictionless pivot and nF = dN/dF, from the Lagrangian of (u, theta, d) with
    the d row carrying F; and N of a slip toward sigma is A / (1 + mu_k sigma nF)."""
    Mf, rf, Nf, *_ = lagrangian_model()
    rng = np.random.default_rng(11)
    for _ in range(40):
        b, fr, par, s, ag, hdr, smp, y = _random_state(rng)
        prm = (s, b.B, b.H, b.base_cm_height, par[KF.F_MB], par[KF.F_IB], par[KF.F_IM], b.omega_n, b.zeta,
               b.g, ag)
        vel = (y[1], y[3], y[5])

        def N_of(F):
            M = np.array(Mf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float)
            r = np.array(rf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float).ravel()
            return float(Nf(*prm, F, y[0], y[2], *vel, *np.linalg.solve(M, r)))

        A, nF = K.normal_margins(1.0, y, s, par, hdr, smp)
        N0, N1 = N_of(0.0), N_of(1.0)
        scale = abs(N0) + b.g
        assert A == pytest.approx(N0, abs=1e-9 * scale)
        assert nF == pytest.approx(N1 - N0, abs=1e-9 * (1 + abs(nF)))
        for sigma in (-1, 1):
            _u, _t, _d, N = K.slip_rock(1.0, y, s, sigma, par, hdr, smp)
            D = 1.0 + fr.mu_k * sigma * nF
            assert N * D == pytest.approx(A, abs=1e-9 * (scale + abs(N * D)))


def test_the_pick_is_always_consistent():
    """2 000 random rocking states at zero slip speed (mu_s 0.05-20, 1e4 in a quarter): the
    mode picked is consistent by the direct solves, and a jam (no consistent mode) never comes
    out.  Painleve states (stick and both slips inconsistent) occur and are resolved by flight
    (A <= 0)."""
    rng = np.random.default_rng(5)
    counts = {K.PICK_ROCK: 0, K.PICK_SLIP: 0, K.PICK_FLIGHT: 0}
    painleve = 0
    for i in range(2000):
        b, fr, par, s, ag, hdr, smp, y = _random_state(rng, 1e4 if i % 4 == 0 else None)
        code, sig = K.pick_rocking(1.0, y, s, par, hdr, smp, True)
        assert code in counts, (i, code)
        counts[code] += 1
        A, _nF = K.normal_margins(1.0, y, s, par, hdr, smp)
        _u, _t, F, Ns = K.stick_rock(1.0, y, s, par, hdr, smp)
        ok = []
        for sigma in (-1, 1):
            _u, _t, dd, N = K.slip_rock(1.0, y, s, sigma, par, hdr, smp)
            ok.append(N >= 0.0 and sigma * dd >= -1e-9 * b.g * (1 + fr.mu_k))
        stick_ok = Ns >= 0.0 and abs(F) <= fr.mu_s * Ns
        if code == K.PICK_ROCK:
            assert stick_ok
        elif code == K.PICK_SLIP:
            _u, _t, dd, N = K.slip_rock(1.0, y, s, sig, par, hdr, smp)
            assert N >= -1e-12 * b.g and sig * dd >= -1e-9 * b.g * (1 + fr.mu_k), (i, sig, N, dd)
        else:
            assert A <= 0.0 and not stick_ok
            painleve += not any(ok)
    assert min(counts.values()) > 100, counts
    assert painleve > 10


def _momenta(y, s, par, h=1e-3):
    """p_i = dT/dq'_i of the kinetic energy (quadratic: central differences are exact)."""
    p = []
    for i in (1, 3, 5):
        a, b = y.copy(), y.copy()
        a[i] += h
        b[i] -= h
        p.append((K.kinetic(a, s, par) - K.kinetic(b, s, par)) / (2 * h))
    return np.array(p)


def test_tangential_impact_keeps_p_u_and_p_theta_and_dissipates():
    rng = np.random.default_rng(8)
    for _ in range(500):
        b, fr, par, s, ag, hdr, smp, y = _random_state(rng)
        y[5] = rng.normal() * b.p * b.H
        p0 = _momenta(y, s, par)
        T0 = K.kinetic(y, s, par)
        K.stop_slip(1.0, y, s, par, np.zeros(L.N_MET))
        p1 = _momenta(y, s, par)
        assert y[5] == 0.0
        np.testing.assert_allclose(p1[:2], p0[:2], rtol=1e-9, atol=1e-9 * (1 + np.abs(p0).max()))
        assert K.kinetic(y, s, par) <= T0 * (1 + 1e-12)


def test_a_held_slip_that_cannot_continue_is_stopped_not_looped():
    """reload() of a held lift-off with the base moving, where the slip toward sgn d' has N < 0
    (D < 0 with A > 0): a tangential impact (logged as a stick), then a consistent mode (a slip
    with N >= 0, stick, or a flight where A <= 0 after the impulse); it used to re-enter that
    slip, lift off at once and loop (failed:transition-loop)."""
    rng = np.random.default_rng(3)
    found = 0
    for _ in range(20000):
        b, fr, par, s, ag, hdr, smp, y = _random_state(rng, 1e3)
        y[5] = rng.normal()
        sig = 1 if y[5] > 0 else -1
        A, nF = K.normal_margins(1.0, y, s, par, hdr, smp)
        if not (A > 0 and 1 + fr.mu_k * sig * nF < 0):
            continue
        found += 1
        disc = np.zeros(L.N_DISC, np.int64)
        K.set_mode(disc, L.MODE_SLIDE_ROCK, s, 0)
        met = np.zeros(L.N_MET)
        log = np.zeros((8, L.N_LOG))
        cnt = np.zeros(N_COUNTERS, np.int64)
        T0 = K.kinetic(y, s, par)
        st = K.reload(1.0, y, par, disc, hdr, smp, met, log, cnt)
        assert y[5] == 0.0 and K.kinetic(y, s, par) <= T0 * (1 + 1e-12)
        assert log[1, L.LOG_KIND] == L.EV_STICK
        assert st in (L.RUNNING, L.FLIGHT)
        if st == L.FLIGHT:          # lift_off "stop": consistent only with A <= 0 after the impulse
            assert K.normal_margins(1.0, y, s, par, hdr, smp)[0] <= 0.0
            continue
        mode, sigma = disc[L.D_MODE], disc[L.D_SLIP_DIR]
        if mode == L.MODE_SLIDE_ROCK and sigma != 0:
            _u, _t, _d, N = K.slip_rock(1.0, y, s, sigma, par, hdr, smp)
            assert N >= 0.0
        if found >= 50:
            break
    assert found >= 50


# ---------------------------------------------------------------- 4. the fuzz cells
_FUZZ = Path(__file__).resolve().parent.parent / "bench" / "fuzz.py"


def _fuzz():
    if "fastrock_bench_fuzz" not in sys.modules:
        spec = importlib.util.spec_from_file_location("fastrock_bench_fuzz", _FUZZ)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod
        spec.loader.exec_module(mod)
    return sys.modules["fastrock_bench_fuzz"]


@pytest.mark.parametrize("batch,key,variant,was", [
    # hold, mu_s 0.72, b/h-like slender body with a raised heavy base: slip and stick at one
    # instant, twice (failed:inconsistent-contact)
    (17, (17.284316, 0.706193, 1), None, "failed:inconsistent-contact"),
    # hold, mu_s 1.82: a held lift-off that reloads while slipping with D < 0 (failed:transition-loop)
    (31, (13.001996, 2.399074, 1), None, "failed:transition-loop"),
    # Friction(1e6), hold: Painleve slip onset (the mu_inf check run, failed:inconsistent-contact)
    (36, (34.685429, 0.255194, 1), "mu_inf", "failed:inconsistent-contact"),
    (6, (27.837103, 0.472021, 1), "mu_inf", "failed:inconsistent-contact"),
    # hold, mu_s 1.75, h_b = 2.08: a slip onset with D(sigma1) < 0 and A < 0 (N = A / D > 0 and
    # d'' = 0 passed the old test), slip/stick at one instant (failed:transition-loop, early exit)
    (110, (5.829471625780531, 0.19309077676424508, 1), None, "failed:transition-loop"),
])
def test_former_painleve_failures_end_definite_and_converged(batch, key, variant, was):
    fz = _fuzz()
    P = fz.draw_batch("flexible_friction", 2026, batch)
    run, *_ = fz._simulate_cell(P, key, variant, early_exit=True)
    assert not run.status.startswith("failed"), (was, run.status)
    run, *_ = fz._simulate_cell(P, key, variant)
    assert not run.status.startswith("failed"), (was, run.status)
    tight, *_ = fz._simulate_cell(P, key, "tight" if variant is None else variant)
    assert run.outcome == tight.outcome


def test_max_rotation_counts_the_state_at_the_lift_off():
    """lift_off "stop" ends the run at the located lift-off; its rotation counts in max_rotation
    (it used to stop at the last step before the event: 0.5143 rad here against |theta| = 0.5153
    at the lift-off, frozen grid flexible_friction-stop-mu0.6-0.5-one-sine, row 7)."""
    from fastrock import Pulse, simulate
    b = FlexibleBody(alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05)
    run = simulate(b, Pulse(9.5, 0.6, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                   friction=Friction(0.6, 0.5))
    assert run.status == "flight"
    ev = run.events
    th = abs(float(ev[ev["event"] == "flight"]["theta"].iloc[-1]))
    assert run.metrics["max_rotation"] == pytest.approx(max(th, float(np.abs(run.history["theta"]).max())),
                                                        rel=1e-12)
    assert run.metrics["max_rotation"] >= th
