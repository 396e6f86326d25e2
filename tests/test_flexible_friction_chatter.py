"""Flexible body with friction: impact chatter at the uplift threshold (issue #14; physics.md 4.4, 7).

Fuzz batch ``flexible_friction:2026:150`` hung and ended failed:step-budget (299 919 events at
t = 1.014479 s).  After the pulse the base sits at rest with the column vibrating.  The plastic
impact gives the base d'+ = d'- + h_b theta'- (h_b = 2.75 m here), so the base leaves each impact
slipping at about 1e-15 m/s.  The slip solve then applies the saturated friction -mu_k sigma N,
although stick needs far less, and that friction's moment lifts a corner.  The slip stops at once,
stick-rocking (admissible) pulls the corner back, and the next impact starts the same slip again.
Time never advances.  The kernel now applies the rest rule of physics.md 7 to the tangential
velocity too: a chatter impact (|theta'-| < eps_omega, or within eps_t of the previous one) that
leaves the base slower than eps_omega times the body's size stops the base by a plastic horizontal
impulse, and the mode is picked at zero slip speed.

Oracles: the kinetic energy and the mass's horizontal momentum of the impulse (mechanics, not the
kernel's formula); the energy of the history after the pulse, as bench/fuzz.py's invariant computes
it; the same scene with lift_off "stop" and with mu = 1e6, where physics fixes the answer; a grid
around the case.
"""
from __future__ import annotations

import importlib.util
import itertools
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import fastrock as fr
from fastrock.kernels import flexible_friction as K
from fastrock.kernels import layout as L
from fastrock.kernels.hybrid import N_COUNTERS
from fastrock.running.models import flexible_friction_par

from test_flexible_friction import constant_ground

BODY = dict(alpha=0.125793, p=0.749834, omega_n_over_p=6.10411, zeta=0.04051,
            rotary_inertia_ratio=0.2238, base_cm_height=2.753)
MU = 1.8706
RTOL = 9.52e-8
_FUZZ = Path(__file__).resolve().parent.parent / "bench" / "fuzz.py"


def _fuzz():
    if "fastrock_bench_fuzz" not in sys.modules:
        spec = importlib.util.spec_from_file_location("fastrock_bench_fuzz", _FUZZ)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod
        spec.loader.exec_module(mod)
    return sys.modules["fastrock_bench_fuzz"]


def _pulse(amplitude=1.04785, frequency=6.45365, sign=1):
    return fr.Pulse(amplitude, frequency, sign=sign, kind="half-sine", amplitude_unit="g_tan_alpha",
                    frequency_unit="omega_p/p")


def _run(friction, pulse=None, max_steps=200_000):
    body = fr.FlexibleBody(**BODY)
    pulse = _pulse() if pulse is None else pulse
    t0 = time.perf_counter()
    run = fr.simulate(body, pulse, friction=friction, rtol=RTOL, max_steps=max_steps)
    return run, time.perf_counter() - t0


@pytest.fixture(scope="module")
def hold():
    _run(fr.Friction(MU, lift_off="hold"), max_steps=10)        # load the kernel
    return _run(fr.Friction(MU, lift_off="hold"))


def test_the_reproduction_ends_at_rest_within_seconds(hold):
    run, elapsed = hold
    assert run.status == "safe:rest", run.status
    assert elapsed < 5.0, elapsed
    ev = run.events
    assert len(ev) < 100, len(ev)               # was 299 919 events at one instant
    # the chatter ends by the rest rule (the impacts at one instant stop, then full contact)
    assert (ev["event"] == "rest").sum() >= 1
    assert run.history["contact"].iloc[-1] == "rest"
    assert run.history["d_dot"].iloc[-1] == 0.0
    assert run.history["theta"].iloc[-1] == 0.0


def test_energy_never_rises_after_the_pulse(hold):
    """Kinetic + gravity + column strain energy of the history (bench/fuzz.py's ``energy`` for this
    family) never rises between two history rows after the pulse by more than the fuzz tolerance
    (1e-6 of the energy scale + 100 rtol)."""
    fz = _fuzz()
    run, _ = hold
    body = run.body
    h = run.history
    E = fz.energy(h, body, {"friction": fr.Friction(MU, lift_off="hold")}, "flexible_friction")
    R = body.g / body.p ** 2
    scale = max(float(np.nanmax(np.abs(E))), body.g * R * (1 - np.cos(body.alpha)))
    t_free = _pulse().end_time(body)
    assert h["t"].iloc[-1] > t_free + 5.0
    grow, fall = fz.energy_growth(h["t"].to_numpy(), E, t_free, scale, h["theta"].to_numpy(), body.alpha)
    assert fall == 0.0
    assert grow <= fz.ENERGY_TOL + fz.ENERGY_TOL_RTOL * RTOL, grow
    # and it is dissipated overall: the column's damping and the impacts
    m = h["t"].to_numpy() > t_free
    assert E[m][-1] < E[m][0]


def test_lift_off_stop_agrees_when_no_lift_off_happened(hold):
    """lift_off only acts once the pivot's N reaches 0.  A "hold" run that never held a lift-off
    (lift_offs 0, no held lift-off event) is therefore the "stop" run, identically."""
    run, _ = hold
    assert run.metrics["lift_offs"] == 0
    assert not (run.events["event"] == "lift-off-held").any()
    stop, _ = _run(fr.Friction(MU, lift_off="stop"))
    assert stop.status == run.status
    assert stop.metrics["max_rotation"] == run.metrics["max_rotation"]
    assert list(stop.events["event"]) == list(run.events["event"])
    np.testing.assert_array_equal(stop.events["t"].to_numpy(), run.events["t"].to_numpy())


def test_larger_mu_agrees_up_to_the_first_impact_and_on_the_outcome(hold):
    """Up to the first impact the mu_s = 1.87 run stick-rocks without a slip (no slip event, so
    |F| < mu_s N throughout): that motion is the same for every larger mu_s, and it holds the
    largest rotation.  With Friction(1e6) the uplift, first impact and max rotation agree; after
    the pulse both come to rest in full contact (safe)."""
    run, _ = hold
    ev = run.events
    t_imp = float(ev[ev["event"] == "impact"]["t"].iloc[0])
    assert not (ev[ev["t"] < t_imp]["event"].isin(["slip", "stick"])).any()
    big, elapsed = _run(fr.Friction(1e6, lift_off="hold"))
    assert elapsed < 5.0
    assert big.status == run.status == "safe:rest"
    bev = big.events
    assert float(bev[bev["event"] == "impact"]["t"].iloc[0]) == pytest.approx(t_imp, rel=1e-7)
    assert float(bev["t"].iloc[0]) == pytest.approx(float(ev["t"].iloc[0]), rel=1e-7)
    assert big.metrics["max_rotation"] == pytest.approx(run.metrics["max_rotation"], rel=1e-7)
    h = run.history
    assert np.abs(h["theta"][h["t"] > t_imp]).max() < run.metrics["max_rotation"]


def test_grid_around_the_case_has_no_failure():
    """Amplitudes 0.9-1.2 x frequencies 5-8 x both signs (98 runs), each definite within a second."""
    _run(fr.Friction(MU, lift_off="hold"), max_steps=10)
    bad = []
    for a, w, sign in itertools.product(np.linspace(0.9, 1.2, 7), np.linspace(5.0, 8.0, 7), (1, -1)):
        run, elapsed = _run(fr.Friction(MU, lift_off="hold"), _pulse(a, w, sign))
        if run.status.startswith("failed") or elapsed > 1.0 or len(run.events) > 1000:
            bad.append((a, w, sign, run.status, elapsed, len(run.events)))
    assert not bad


def _impact_state(rng):
    b = fr.FlexibleBody(alpha=rng.uniform(0.05, 0.6), p=rng.uniform(0.5, 6), omega_n_over_p=rng.uniform(2, 60),
                        zeta=rng.uniform(0, 0.1), base_mass_ratio=rng.uniform(0.02, 0.5),
                        base_cm_height=rng.uniform(0.0, 1.5), rotary_inertia_ratio=rng.uniform(0, 0.4))
    par = flexible_friction_par(b, fr.Friction(float(rng.uniform(0.1, 3.0))))
    hdr, smp = constant_ground(b, float(rng.uniform(-0.2, 0.2)) * b.g)
    s = int(rng.choice([-1, 1]))
    uy = b.uplift_deformation
    y = np.array([rng.uniform(-0.5, 0.5) * uy, rng.uniform(-1, 1) * uy * b.omega_n, 0.0, 0.0, 0.0, 0.0])
    return b, par, hdr, smp, s, y


def _impact(y, s, par, hdr, smp, opt, t, t_last):
    """The impact event of stick-rocking on s (K.transition, which decides chatter)."""
    disc = np.zeros(L.N_DISC, np.int64)
    K.set_mode(disc, L.MODE_ROCK, s, 0)
    met = np.zeros(L.N_MET)
    met[L.M_T_LAST_IMPACT] = t_last
    log = np.zeros((16, L.N_LOG))
    cnt = np.zeros(N_COUNTERS, np.int64)
    st = K.transition(K.R_IMPACT, t, y, par, disc, hdr, smp, opt, met, log, cnt)
    return st, disc


def _mass_vx(y, s, par):
    """Horizontal velocity of the mass relative to the ground at theta = 0: d' + u' + H theta'."""
    return y[5] + y[1] + par[K.F_H] * y[3]


def test_chatter_impact_rests_the_base_without_adding_energy():
    """Random impacts at theta = 0 from stick-rocking (d'- = 0) with a small theta'-.  By the rest
    rule (chatter: |theta'-| < eps_omega) the base ends with d' = 0; the plastic impacts keep the
    mass's horizontal velocity and never raise the kinetic energy.  Without chatter (|theta'-|
    above eps_omega, impacts far apart) the base keeps d'+ = h_b theta'-."""
    rng = np.random.default_rng(14)
    opt = np.zeros(L.N_OPT)
    opt[L.O_EPS_OMEGA] = 1e-9
    opt[L.O_EPS_T] = 1e-9
    rested = kept = 0
    for i in range(400):
        b, par, hdr, smp, s, y = _impact_state(rng)
        chatter = i % 2 == 0
        y[3] = -s * (10 ** rng.uniform(-16, -9.05) if chatter else 10 ** rng.uniform(-6, -2))
        T0 = K.kinetic(y, s, par)
        vx0 = _mass_vx(y, s, par)
        pre = y[3]
        st, disc = _impact(y, s, par, hdr, smp, opt, 1.0, 0.0)
        assert st == L.RUNNING
        if chatter:
            assert y[5] == 0.0
            rested += 1
        elif b.base_cm_height > 0.0:
            assert y[5] == par[K.F_HB] * pre
            kept += 1
        # at theta = 0 after the impact the rocking kinetic energy is the full-contact one
        assert K.kinetic(y, s, par) <= T0 * (1 + 1e-12) + 1e-300
        assert _mass_vx(y, s, par) == pytest.approx(vx0, rel=1e-12, abs=1e-15 * (1 + abs(vx0)))
    assert rested == 200 and kept > 150


def test_impacts_within_eps_t_rest_a_slow_base_only():
    """Chatter by time (two impacts within eps_t) rests the base only below eps_omega times the
    body's size; a faster slip (a base genuinely sliding) is kept."""
    rng = np.random.default_rng(15)
    opt = np.zeros(L.N_OPT)
    opt[L.O_EPS_OMEGA] = 1e-9
    opt[L.O_EPS_T] = 1e-9
    for _ in range(100):
        b, par, hdr, smp, s, y = _impact_state(rng)
        size = np.sqrt(b.B ** 2 + max(b.H, b.base_cm_height) ** 2)
        y[3] = -s * 1e-6
        y[5] = rng.uniform(0.1, 1.0) * (1 if rng.random() < 0.5 else -1)
        d_post = y[5] + par[K.F_HB] * y[3]
        _impact(y, s, par, hdr, smp, opt, 1.0, 1.0 - 1e-10)
        assert y[5] == d_post
        y[:] = 0.0
        y[0] = 0.1 * b.uplift_deformation
        y[3] = -s * 1e-6
        y[5] = -par[K.F_HB] * y[3] + 0.5e-9 * size
        _impact(y, s, par, hdr, smp, opt, 1.0, 1.0 - 1e-10)
        assert y[5] == 0.0
