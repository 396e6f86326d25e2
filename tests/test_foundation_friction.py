"""A rigid block sliding on the two-spring foundation (issue #13, "Composable scenes"; model
two_spring_friction, kernels/foundation_friction.py): Coulomb friction at the base point, which
the two-spring model holds horizontally.

Oracles:
- the accelerations of a sympy Lagrangian in (d, y_c, q) with the horizontal reaction H as a
  generalised force at the base point: stick (d'' = 0 with H = H_s, |H_s| <= mu_s N), slip
  (H = -sigma mu_k N) and flight (H = 0), for a block and an asymmetric body;
- mu_s = mu_k = 1e6 never slips and reproduces the two-spring model (outcomes and maxima on a
  pulse grid; both integrate the same equations, only the error norm differs);
- a stout block (no uplift) slides as the rigid sliding block's closed form (rectangular pulse),
  converging as the springs stiffen; with mu small its centre of mass follows minus the double
  integral of a_g to within the friction impulse's bound mu max(N)/M t^2/2;
- in flight (a vertical pulse beyond g) the centre of mass moves ballistically and theta' is
  constant; on a slope the block at rest sticks, and a pulse slides it further downhill;
- E = T + M g y_G + springs never increases in free motion (hypothesis);
- mirror symmetry; bad input; every entry point (simulate, spectrum, Scene/TOML, run_batch,
  Study, CLI) selects and runs the model.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fastrock as fr
from fastrock import Friction, Pulse, RigidBlock, RigidBody, TwoSpringFoundation
from fastrock.kernels import foundation as K
from fastrock.kernels import foundation_friction as FF
from fastrock.kernels import layout as L
from fastrock.model.foundation import block_inertia
from fastrock.running.foundation import foundation_spec
from test_foundation import corner_forces, random_two_spring_input

BLOCK = RigidBlock.rectangle(b=0.2, h=0.6)
STOUT = RigidBlock.rectangle(b=0.5, h=0.5)
ASYM = RigidBody(mass=1.0, inertia=0.12, b1=0.15, h1=0.8, b2=0.3, h2=0.8)


# ----------------------------------------------------------------- equations of motion
def _sympy_accelerations():
    """(d'', y'', q'') of the Lagrangian in (D, Y, Q) with generalised forces: the corner
    forces (vertical, at the corners x_R, x_L of the body frame), -M a_g at the CM and H at the
    base point (D, Y)."""
    sp = pytest.importorskip("sympy")
    M, IG, xR, xL, h, G, ag, fR, fL, H = sp.symbols("M I_G x_R x_L h G a_g f_R f_L H", real=True)
    y, q, yd, qd, ydd, qdd, ddd = sp.symbols("y q yd qd ydd qdd ddd", real=True)
    t = sp.Symbol("t")
    D, Y, Q = sp.Function("D")(t), sp.Function("Y")(t), sp.Function("Q")(t)
    xG = D + h * sp.sin(Q)
    yG = Y + h * sp.cos(Q)
    T = (M * (sp.diff(xG, t) ** 2 + sp.diff(yG, t) ** 2) + IG * sp.diff(Q, t) ** 2) / 2
    Vg = M * G * yG
    W = fR * (Y - xR * sp.sin(Q)) + fL * (Y - xL * sp.sin(Q)) - M * ag * xG + H * D
    eqs = []
    for qi in (D, Y, Q):
        lhs = sp.diff(sp.diff(T, sp.diff(qi, t)), t) - sp.diff(T, qi) + sp.diff(Vg, qi)
        eqs.append(lhs - sp.diff(W, qi))
    sub2 = {sp.diff(D, t, 2): ddd, sp.diff(Y, t, 2): ydd, sp.diff(Q, t, 2): qdd}
    sub1 = {sp.diff(Y, t): yd, sp.diff(Q, t): qd}
    eqs = [sp.expand(e.subs(sub2).subs(sub1).subs({Y: y, Q: q})) for e in eqs]
    assert all(not e.has(D) and not e.has(sp.diff(D, t)) for e in eqs)    # d and d' do not enter
    sol = sp.solve(eqs, [ddd, ydd, qdd], dict=True)[0]
    args = (y, q, yd, qd, M, IG, xR, xL, h, G, ag, fR, fL, H)
    acc = sp.lambdify(args, (sol[ddd], sol[ydd], sol[qdd]))
    # stick: d'' = 0 fixes H
    H_s = sp.solve(sp.Eq(sol[ddd], 0), H)[0]
    return acc, sp.lambdify(args[:-1], H_s)


@pytest.mark.parametrize("body", [BLOCK, ASYM], ids=["block", "asymmetric"])
def test_accelerations_match_a_sympy_lagrangian_in_every_friction_state(body):
    acc, stick_H = _sympy_accelerations()
    fnd = TwoSpringFoundation(k_v=3.0e4, c_v=40.0)
    fric = Friction(0.4, 0.3)
    spec, blk = foundation_spec(body, fnd, friction=fric)
    assert spec.name == "two_spring_friction"
    xR = body.b2 if isinstance(body, RigidBody) else body.b
    xL = -body.b1 if isinstance(body, RigidBody) else -body.b
    rng = np.random.default_rng(23)
    smp = np.zeros(1)
    states = {"stick": FF.STICK, "slip+": 1, "slip-": -1}
    for _ in range(20):
        state4, a_g, hdr, disc4 = random_two_spring_input(rng, 0.4)
        y = np.concatenate([state4, [rng.normal(0, 0.01), rng.normal(0, 0.3)]])
        disc = np.zeros(FF.N_DISC_FF, np.int64)
        disc[:L.N_DISC] = disc4
        forces = corner_forces(fnd, state4, disc4, xR, xL)
        N = sum(forces)
        common = (y[0], y[2], y[1], y[3], blk.M, blk.I_G, xR, xL, blk.h, body.g, a_g, *forces)
        for name, fs in states.items():
            disc[FF.D_FRIC] = fs
            got = FF.ff_all(0.5, y, spec.par, disc, hdr, smp)
            H = stick_H(*common) if fs == FF.STICK else -fs * fric.mu_k * N
            if fs == FF.STICK and not (disc4[K.D_RIGHT] or disc4[K.D_LEFT]):
                H = 0.0             # no stick without a corner in contact: free
            ddd, ydd, qdd = acc(*common, H)
            np.testing.assert_allclose(got, (ydd, qdd, ddd), rtol=1e-10, atol=1e-9, err_msg=name)
            if fs == FF.STICK and (disc4[K.D_RIGHT] or disc4[K.D_LEFT]):
                assert got[2] == 0.0 and abs(ddd) < 1e-9
                H_k, N_k = FF.stick_force(0.5, y, spec.par, disc, hdr, smp)
                assert H_k == pytest.approx(H, rel=1e-10, abs=1e-9) and N_k == pytest.approx(N, rel=1e-12)
        if N == 0.0:            # no corner in contact: the free state, H = 0
            disc[FF.D_FRIC] = FF.FREE
            ddd, ydd, qdd = acc(*common, 0.0)
            np.testing.assert_allclose(FF.ff_all(0.5, y, spec.par, disc, hdr, smp), (ydd, qdd, ddd),
                                       rtol=1e-10, atol=1e-9)


def test_the_slip_onset_accelerates_the_way_it_slips():
    """At zero slip speed with |H_s| > mu_s N, the slip toward -sgn(H_s) has sigma d'' > 0 (module
    docstring of kernels/foundation_friction.py): d'' = w (H - H_s), w = 1/M + h^2 cos^2 q / I_G."""
    fnd = TwoSpringFoundation(k_v=3.0e4, c_v=40.0)
    spec, blk = foundation_spec(BLOCK, fnd, friction=Friction(0.3, 0.2))
    rng = np.random.default_rng(5)
    n = 0
    for _ in range(400):
        state4, _a_g, hdr, disc4 = random_two_spring_input(rng, 0.4)
        y = np.concatenate([state4, [0.0, 0.0]])
        disc = np.zeros(FF.N_DISC_FF, np.int64)
        disc[:L.N_DISC] = disc4
        H_s, N = FF.stick_force(0.0, y, spec.par, disc, hdr, np.zeros(1))
        if N <= 0.0 or abs(H_s) <= 0.3 * N:
            continue
        sigma = FF.pick_at_zero_speed(0.0, y, spec.par, disc, hdr, np.zeros(1))
        assert sigma == (-1 if H_s > 0 else 1)
        disc[FF.D_FRIC] = sigma
        ddd = FF.ff_all(0.0, y, spec.par, disc, hdr, np.zeros(1))[2]
        w = 1 / blk.M + blk.h ** 2 * math.cos(y[2]) ** 2 / blk.I_G
        assert sigma * ddd > 0.0
        assert ddd == pytest.approx(w * (-sigma * 0.2 * N - H_s), rel=1e-9)
        n += 1
    assert n > 20


# ------------------------------------------------------------------ limit: never slips
def test_huge_friction_reproduces_the_two_spring_model():
    """mu_s = mu_k = 1e6 on a pulse grid of safe, mode1 and mode2 runs in which the two-spring
    block never flies (both corners off: there the held base and the free one differ by
    design).  The base never slips (max_slide exactly 0), so both models integrate the same
    equations of (y, q) and differ only by their step sequences (the error norm has two more
    components, d = d' = 0).  Their maxima then agree to the integration error, which the test
    measures as the plain model's change from rtol = 1e-10 to 1e-11 over the grid."""
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 20.0, 0.1)
    amps, freqs = [0.8, 1.1, 2.0], [1.5, 3.0]
    kw = dict(sign="both", foundation=fnd, progress=False, atol=1e-12, early_exit=False)
    ref = fr.overturning_spectrum(BLOCK, amps, freqs, rtol=1e-10, **kw)
    fine = fr.overturning_spectrum(BLOCK, amps, freqs, rtol=1e-11, **kw)
    got = fr.overturning_spectrum(BLOCK, amps, freqs, friction=Friction(1e6), rtol=1e-10, **kw)
    assert got.attrs["kernel"] == "two_spring_friction" and ref.attrs["kernel"] == "two_spring"
    assert list(got["outcome"]) == list(ref["outcome"])
    assert {"safe", "mode1", "mode2"} == set(ref["outcome"].astype(str))
    assert (got["max_slide"] == 0.0).all() and (got["stick_slip"] == 0).all()
    safe = (ref["outcome"] == "safe").to_numpy()
    lifted = np.isfinite(ref["time_uplift"].to_numpy())
    assert list(np.isfinite(got["time_uplift"])) == list(lifted) and lifted.any() and not lifted.all()
    for col, rows in (("max_rotation", safe), ("time_uplift", lifted)):
        r, f, g = (df[col].to_numpy()[rows] for df in (ref, fine, got))
        integration = np.max(np.abs(f - r) / r)
        assert integration < 1e-8
        assert np.max(np.abs(g - r) / r) <= 10 * integration + 1e-13, col


# ----------------------------------------------------------- limit: the rigid sliding block
def _rectangular_residual(A, t_d, mu, g):
    """Residual slide of a rigid block (mu_s = mu_k = mu) under a rectangular pulse a_g = A > mu g
    for t_d seconds: d'' = -(A - mu g) during the pulse, +mu g after it until d' = 0."""
    return -(A - mu * g) * A * t_d ** 2 / (2 * mu * g)


def test_stout_block_slides_as_the_rigid_sliding_block():
    """b/h = 1 > mu: no uplift; the springs carry M g and the block slides.

    While the base slips one way (sigma = -1), its centre of mass obeys M (x_G'' + a_g) =
    mu N exactly, so from the slip's start t_s, x_G = d + h sin q follows the rigid sliding
    block's law x_G'' = mu g - a_g to within mu max|N/M - g| (t - t_s)^2/2 (N departs from M g
    only by the vertical vibration, second order in the tilt) plus the integration error.
    The residual slide of the base converges to the rigid block's closed form as the springs
    stiffen.  The error falls as 1/omega (omega the rocking vibration), from two effects of the
    block's rotation on its springs: at the pulse's onset the held base needs only
    M a_g I_G / I_C (the block first rocks back; 0.4 M a_g here, below mu_s M g), so the slip
    starts a fraction of the vibration period late; and the friction's moment about the
    centre of mass sets the block vibrating with h q' ~ 1/omega, which shifts the instant the
    base's own velocity d' = x_G' - h cos q q' comes to rest."""
    mu, A, t_d = 0.2, 0.35, 0.4
    g = STOUT.g
    a = A * g
    exc = Pulse(A, 1.0, kind="rectangular", duration=t_d)
    exact = _rectangular_residual(a, t_d, mu, g)
    errs = []
    for omega in (60.0, 120.0, 240.0):
        fnd = TwoSpringFoundation.from_vibration(STOUT, omega, 0.1)
        r = fr.simulate(STOUT, exc, foundation=fnd, friction=Friction(mu), rtol=1e-10, atol=1e-12,
                        t_after=2.0)
        assert r.kernel == "two_spring_friction" and r.outcome == "slide"
        assert math.isnan(r.metrics["time_uplift"]) and r.metrics["stick_slip"] == 2
        ev = r.events.set_index("event")["t"]
        t_s, t_stick = ev["slip"], ev["stick"]
        assert 0.0 < t_s < 0.5 * math.pi / omega + 1e-3 and t_stick > t_d
        h = r.history
        t = h["t"].to_numpy()
        on = (t > t_s) & (t < t_stick)
        assert (h["d_dot"].to_numpy()[on] < 0.0).all()                     # one way only
        q, qd = h["theta"].to_numpy(), h["theta_dot"].to_numpy()
        xG = h["d"].to_numpy() + STOUT.h * np.sin(q)
        vG = h["d_dot"].to_numpy() + STOUT.h * np.cos(q) * qd
        k = np.searchsorted(t, t_s, side="right") - 1                      # the row after the switch
        N = (h["force_right"] + h["force_left"]).to_numpy()[on]
        dev = np.max(np.abs(N / block_inertia(STOUT).M - g)) / g
        assert dev < 1e-3                                                  # the springs carry M g
        tau = t[on] - t_s
        # x_G'' = mu g - a_g, integrated exactly over the pulse's end at t_d
        dur = np.minimum(t[on], t_d) - t_s
        law = xG[k] + vG[k] * tau + mu * g * tau ** 2 / 2 - a * (dur ** 2 / 2 + dur * (tau - dur))
        assert np.all(np.abs(xG[on] - law) <= mu * dev * g * tau ** 2 / 2 + 1e-8)
        errs.append(abs(r.metrics["residual_slide"] - exact))
    assert errs[-1] < 5e-3 * abs(exact)
    assert 1.7 < errs[0] / errs[1] < 2.3 and 1.7 < errs[1] / errs[2] < 2.3


def test_small_friction_slides_by_minus_the_double_integral_of_the_ground():
    """With mu small the horizontal force on the block is at most mu_k N: the centre of mass
    x_G = d + h sin q moves by -double integral of a_g, give or take mu max(N)/M t^2 / 2
    (exactly: M (x_G'' + a_g) = H, |H| <= mu_k N)."""
    A, f = 0.3, 2.0
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 40.0, 0.05)
    w = 2 * math.pi * f
    T = 1.0 / f
    for mu in (1e-2, 1e-3):
        r = fr.simulate(BLOCK, Pulse(A, f), foundation=fnd, friction=Friction(mu), rtol=1e-10,
                        atol=1e-12, duration=T, t_after=0.0)
        hist = r.history
        t = hist["t"].to_numpy()
        ap = A * BLOCK.g
        free = -(ap / w) * (t - np.sin(w * t) / w)
        xG = hist["d"].to_numpy() + block_inertia(BLOCK).h * np.sin(hist["theta"].to_numpy())
        N = (hist["force_right"] + hist["force_left"]).to_numpy()
        bound = mu * N.max() / 1.0 * t ** 2 / 2 + 1e-9
        assert np.all(np.abs(xG - free) <= bound)
        assert abs(xG[-1] - free[-1]) > 0.3 * bound[-1]       # friction acts: the bound is not slack


def test_a_slip_that_starts_as_its_corner_lifts_runs_on():
    """A found case (a random pulse run): rocking on its left corner, the block starts to slip
    when that corner carries 4e-5 N, 7e-7 s before the corner lifts.  The slip starts at d' = 0
    toward sigma with sigma d'' > 0; the step's end beyond the lift-off once made the stop event
    read as 'on the surface' at once, and the run failed with a transition loop.  The springs are
    undamped, so the block rocks on them to the end of the run (about 200 impacts): whether
    the last instant is in full contact ("safe:rest") or on one corner ("safe:moving") is not
    converged (198 to 207 impacts, either end, between rtol 1e-7 and 1e-12), only that it is
    safe."""
    blk = RigidBlock.rectangle(b=0.15227369832291068, h=0.3731360800043914)
    fnd = TwoSpringFoundation.from_vibration(blk, 91.57531288602313, 0.0)
    exc = Pulse(3.4147800850072367, 3.289655568703106, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    r = fr.simulate(blk, exc, foundation=fnd, friction=Friction(0.3057820846897209, 0.19973847518528975))
    assert r.status_code >= 0 and r.status in ("safe:rest", "safe:moving")
    ev = list(r.events["event"])
    assert any(a == "slip" and b == "flight" for a, b in zip(ev, ev[1:]))
    assert ev.count("impact") > 150


def test_in_flight_the_block_is_free_horizontally_too():
    """A vertical pulse beyond g throws the block off its springs.  With no corner in contact
    H = N = 0: the rotation rate stays constant and the centre of mass moves ballistically in
    the ground's frame, x_G'' = -a_g and y_G'' = -(g + a_v) (the two-spring model holds the
    base horizontally instead).  Checked over each flight against the pulses' closed-form
    integrals."""
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 30.0, 0.05)
    A, f, Av, fv = 0.3, 2.0, 1.5, 3.0
    r = fr.simulate(BLOCK, Pulse(A, f), vertical=Pulse(Av, fv, sign=-1), foundation=fnd,
                    friction=Friction(0.5), rtol=1e-10, atol=1e-12)
    g = BLOCK.g
    w, wv = 2 * math.pi * f, 2 * math.pi * fv

    def int_ag(t):          # integral of a_g from 0 to t (one-sine, then 0)
        t = min(t, 1 / f)
        return A * g * (1 - math.cos(w * t)) / w

    def int_G(t):           # integral of g + a_v (a_v = -Av g sin(wv t) for t < 1/fv)
        tv = min(t, 1 / fv)
        return g * t - Av * g * (1 - math.cos(wv * tv)) / wv

    h = r.history
    hh = block_inertia(BLOCK).h
    q, qd = h["theta"].to_numpy(), h["theta_dot"].to_numpy()
    vx = h["d_dot"].to_numpy() + hh * np.cos(q) * qd
    vy = h["y_dot"].to_numpy() - hh * np.sin(q) * qd
    t = h["t"].to_numpy()
    flying = (h["contact"] == "flight").to_numpy()
    starts = np.flatnonzero(flying & ~np.r_[False, flying[:-1]])
    assert len(starts) >= 2
    for i in starts:
        j = i
        while j + 1 < len(t) and flying[j + 1]:
            j += 1
        assert t[j] - t[i] > 1e-3
        np.testing.assert_allclose(qd[i:j + 1], qd[i], rtol=1e-9, atol=1e-12)
        assert vx[j] - vx[i] == pytest.approx(-(int_ag(t[j]) - int_ag(t[i])), rel=1e-7, abs=1e-10)
        assert vy[j] - vy[i] == pytest.approx(-(int_G(t[j]) - int_G(t[i])), rel=1e-7, abs=1e-10)


# -------------------------------------------------------------------------- energy
def _energy(r, fnd, blk):
    h = r.history
    y, yd, q, qd, dd = (h[c].to_numpy() for c in ("y", "y_dot", "theta", "theta_dot", "d_dot"))
    M, hh = blk.M, blk.h
    vx = dd + hh * np.cos(q) * qd
    vy = yd - hh * np.sin(q) * qd
    E = 0.5 * M * (vx ** 2 + vy ** 2) + 0.5 * blk.I_G * qd ** 2 + M * blk.g * (y + hh * np.cos(q))
    for x in (blk.b, -blk.b):
        E = E + 0.5 * fnd.k_v * np.maximum(x * np.sin(q) - y, 0.0) ** 2
    return E


@settings(max_examples=30, deadline=None)
# rounded: a release of 1e-308 rad is refused as denormal, and tells nothing more than 0
@given(theta_ratio=st.floats(-0.9, 0.9).map(lambda x: round(x, 9)),
       dtheta0=st.floats(-1.0, 1.0).map(lambda x: round(x, 9)), mu=st.floats(0.02, 0.8),
       zeta=st.sampled_from([0.0, 0.05]), omega=st.floats(15.0, 60.0))
def test_free_motion_never_gains_energy(theta_ratio, dtheta0, mu, zeta, omega):
    fnd = TwoSpringFoundation.from_vibration(BLOCK, omega, zeta)
    blk = block_inertia(BLOCK)
    r = fr.simulate(BLOCK, None, foundation=fnd, friction=Friction(mu, 0.8 * mu),
                    theta0=theta_ratio * BLOCK.alpha, dtheta0=dtheta0, duration=1.5, rtol=1e-10, atol=1e-12)
    assert r.status_code >= 0
    E = _energy(r, fnd, blk)
    scale = blk.M * blk.g * blk.b
    assert np.max(np.diff(E)) < 1e-8 * scale


def test_a_block_at_rest_on_a_slope_sticks_and_slides_downhill_when_shaken():
    """On a slope with tan(phi) < mu_s the block starts at its static tilt on the springs and
    sticks (the reaction M g sin(phi) is within mu_s N): without shaking nothing moves.  A pulse
    that overcomes friction leaves a residual slide, larger downhill (Newmark's asymmetry)."""
    fnd = TwoSpringFoundation.from_vibration(STOUT, 60.0, 0.1)
    ground = fr.Ground(slope=math.radians(5.0))
    fric = Friction(0.3)
    r = fr.simulate(STOUT, None, foundation=fnd, friction=fric, ground=ground, duration=2.0)
    assert r.kernel == "two_spring_friction" and r.metrics["max_slide"] == 0.0
    assert r.metrics["stick_slip"] == 0 and set(r.history["contact"]) == {"contact"}
    slides = [fr.simulate(STOUT, Pulse(0.35, 1.0, kind="rectangular", duration=0.3, sign=s), foundation=fnd,
                          friction=fric, ground=ground).metrics["residual_slide"] for s in (1, -1)]
    # +x is downhill: the ground pushed uphill (sign -1) leaves the block further downhill
    assert slides[1] > 0.0 and slides[1] > abs(slides[0])


# -------------------------------------------------------------------------- mirror
def test_the_mirrored_pulse_mirrors_rotation_and_slide():
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 30.0, 0.05)
    runs = [fr.simulate(BLOCK, Pulse(0.45, 2.0, sign=s), foundation=fnd, friction=Friction(0.25, 0.2),
                        rtol=1e-10, atol=1e-12) for s in (1, -1)]
    a, b = (r.metrics for r in runs)
    assert a["max_slide"] > 1e-3 and a["stick_slip"] >= 2 and a["max_rotation"] > 1e-3
    assert runs[0].status == runs[1].status
    assert a["max_rotation_pos"] == pytest.approx(b["max_rotation_neg"], rel=1e-8)
    assert a["max_rotation_neg"] == pytest.approx(b["max_rotation_pos"], rel=1e-8, abs=1e-12)
    assert a["residual_slide"] == pytest.approx(-b["residual_slide"], rel=1e-8)
    assert a["max_slide"] == pytest.approx(b["max_slide"], rel=1e-8)
    assert a["stick_slip"] == b["stick_slip"]


# ------------------------------------------------------------------------ bad input
def test_bad_input_is_refused_with_a_clear_error():
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 30.0, 0.05)
    with pytest.raises(ValueError, match="mu_s"):
        fr.simulate(BLOCK, Pulse(0.3, 2.0), foundation=fnd, friction=Friction(-0.1))
    with pytest.raises(ValueError, match=r"mu_k must be <= mu_s"):
        fr.simulate(BLOCK, Pulse(0.3, 2.0), foundation=fnd, friction=Friction(0.2, 0.3))
    with pytest.raises(ValueError, match="TwoSpringFoundation only"):
        fr.simulate(BLOCK, Pulse(0.3, 2.0), foundation=fr.SwitchingFoundation.from_vibration(BLOCK, 30.0),
                    friction=Friction(0.3))
    with pytest.raises(ValueError, match="never slips"):
        fr.simulate(BLOCK, Pulse(0.3, 2.0), foundation=fnd, friction=Friction(math.inf, lift_off="flight"))
    # Friction(inf) is no effect: the plain two-spring model
    assert fr.simulate(BLOCK, Pulse(0.3, 2.0), foundation=fnd, friction=Friction(math.inf)).kernel == "two_spring"


# ---------------------------------------------------------------------- entry points
def test_every_entry_point_runs_the_model(tmp_path):
    from fastrock.cli import app as cli
    from fastrock.io.default_records import load_default_record
    from fastrock.studies.definition import Study
    from fastrock.studies.run import run_study
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 30.0, 0.05)
    fric = Friction(0.25, 0.2)
    exc = Pulse(2.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    ref = fr.simulate(BLOCK, exc, foundation=fnd, friction=fric)
    assert ref.kernel == "two_spring_friction" and "friction" in ref.effects
    assert {"d", "d_dot"} <= set(ref.history.columns) and {"slide", "contact"} <= set(ref.history.contact)
    assert ref.metrics["max_slide"] > 0.0
    # spectrum: the same row
    df = fr.overturning_spectrum(BLOCK, [2.0], [2.0], foundation=fnd, friction=fric, progress=False,
                                 early_exit=False)
    assert df.attrs["kernel"] == "two_spring_friction"
    assert df["outcome"].iloc[0] == ref.outcome
    assert df["max_slide"].iloc[0] == pytest.approx(ref.metrics["max_slide"], rel=1e-9)
    assert df["residual_slide"].iloc[0] == pytest.approx(ref.metrics["residual_slide"], rel=1e-9)
    # a scene from TOML, and run_batch
    toml = tmp_path / "scene.toml"
    toml.write_text('[body]\nb = 0.2\nh = 0.6\n\n[excitation]\ntype = "pulse"\namplitude = 2.0\nfrequency = 2.0\n'
                    'amplitude_unit = "g_tan_alpha"\nfrequency_unit = "omega_p/p"\n\n'
                    '[foundation]\ntype = "two-spring"\nomega = 30.0\nzeta = 0.05\n\n'
                    '[friction]\nmu_s = 0.25\nmu_k = 0.2\n')
    scene = fr.Scene.from_toml(toml)
    assert scene.kernel == "two_spring_friction"
    got = scene.run()
    assert got.status == ref.status and got.metrics["residual_slide"] == ref.metrics["residual_slide"]
    batch = fr.run_batch([scene], early_exit=False, progress=False)
    assert batch["outcome"].iloc[0] == ref.outcome
    assert batch["residual_slide"].iloc[0] == pytest.approx(ref.metrics["residual_slide"], rel=1e-9)
    # a study variant with friction on the foundation
    rec = load_default_record()
    rec = type(rec)(rec.acc[:300], rec.dt, name="El Centro, first 6 s")
    study = Study(records=[rec], bodies=[BLOCK], levels=[0.3], t_after=1.0,
                  variants=[{"name": "soil", "foundation": {"type": "two-spring", "omega": 30.0, "zeta": 0.05},
                             "friction": {"mu_s": 0.25, "mu_k": 0.2}}])
    sdf = run_study(study, tmp_path / "out", progress=False)
    assert list(sdf["kernel"]) == ["two_spring_friction"]
    r = fr.simulate(BLOCK, fr.SampledMotion.from_record(rec, scale=sdf["scale"].iloc[0]), t_after=1.0,
                    foundation=fnd, friction=fric)
    assert r.status == sdf["status"].iloc[0]
    assert r.metrics["max_rotation_ratio"] == pytest.approx(sdf["max_rotation_ratio"].iloc[0], rel=1e-9)
    # the CLI
    csv = tmp_path / "h.csv"
    assert cli.main(["simulate", "--b", "0.2", "--h", "0.6", "--amplitude", "2.0", "--frequency", "2.0",
                     "--amplitude-unit", "g_tan_alpha", "--frequency-unit", "omega_p/p", "--foundation",
                     "two-spring", "--foundation-omega", "30", "--foundation-zeta", "0.05", "--mu-s", "0.25",
                     "--mu-k", "0.2", "--csv", str(csv)]) == 0
    import pandas as pd
    h = pd.read_csv(csv)
    assert h["d"].iloc[-1] == pytest.approx(ref.history["d"].iloc[-1], rel=1e-12)


# ----------------------------------------------------------- early decisions (issue #15)
def _energy_above_rest(y, par):
    return K.ts_energy_above_rest(np.ascontiguousarray(y[:4]), par)[0]


@pytest.mark.parametrize("mu", [0.15, 0.5, 1.2])
def test_sticks_for_good_holds_at_every_state_of_no_more_energy(mu):
    """ff_sticks_for_good's bound, checked directly: where it holds at a state of energy dE above
    the static equilibrium, every state of full contact with no more energy (the set the free
    motion stays in: dE never grows and no corner lifts) has both corner forces > 0 and
    |H_s| < mu_s N (kernel's own stick_force).  The states are drawn toward the equilibrium from
    random directions, so both the decided states and their energy shells are covered."""
    fnd = TwoSpringFoundation(k_v=3.0e4, c_v=40.0)
    spec, blk = foundation_spec(BLOCK, fnd, friction=Friction(mu))
    par = spec.par
    hdr = np.zeros(L.N_EXC)
    disc = np.zeros(FF.N_DISC_FF, np.int64)
    disc[K.D_RIGHT] = disc[K.D_LEFT] = 1
    disc[FF.D_FRIC] = FF.STICK
    y_eq = np.array([-0.5 * blk.M * blk.g / fnd.k_v, 0.0, 0.0, 0.0, 0.0, 0.0])
    scale = np.array([1e-4, 1e-2, 1e-3, 3e-2, 0.0, 0.0])
    rng = np.random.default_rng(11)
    decided = checked = 0
    for _ in range(3000):
        y = y_eq + scale * rng.normal(size=6) * 10 ** rng.uniform(-4, 1)
        if not FF.ff_sticks_for_good(y, par):
            continue
        decided += 1
        dE = _energy_above_rest(y, par)
        for _ in range(20):
            z = y_eq + (y - y_eq) * rng.uniform(-1, 1, size=6)
            if _energy_above_rest(z, par) > dE:
                continue
            fR, fL = FF.normal_forces(z, par, disc)
            H, N = FF.stick_force(0.0, z, par, disc, hdr, np.zeros(1))
            assert fR > 0.0 and fL > 0.0
            assert abs(H) < mu * N
            checked += 1
    assert decided > 100 and checked > 1000
    # and it refuses states whose energy could lift a corner or break the stick
    far = y_eq + np.array([0.0, 0.0, 0.05, 0.0, 0.0, 0.0])
    assert not FF.ff_sticks_for_good(far, par)


@pytest.mark.parametrize("omega, zeta, mu", [(20.0, 0.1, 0.6), (60.0, 0.2, 0.5), (20.0, 0.3, 0.25)])
def test_early_decisions_equal_the_full_runs(omega, zeta, mu):
    """Proved against full runs, as the rigid block's decisions are: on a pulse grid of safe and
    overturning cells (and, at mu = 0.25, sliding ones), early_exit=True ends most safe runs early (stick on both corners for good:
    no further lift-off, or the rest rule) and gives the full run's status, outcome and every
    metric of rotation, slide and contact exactly."""
    fnd = TwoSpringFoundation.from_vibration(BLOCK, omega, zeta)
    kw = dict(sign="both", foundation=fnd, progress=False, friction=Friction(mu), rtol=1e-8)
    amps, freqs = [0.3, 0.6, 0.9, 1.2, 2.0], [1.5, 3.0, 6.0]
    early = fr.overturning_spectrum(BLOCK, amps, freqs, **kw)
    full = fr.overturning_spectrum(BLOCK, amps, freqs, early_exit=False, **kw)
    assert early.attrs["kernel"] == "two_spring_friction"
    shorter = early["time_end"].to_numpy() < full["time_end"].to_numpy() - 1e-9
    assert shorter.sum() >= 20
    assert early["status"].astype(str).str.startswith("safe:").to_numpy()[shorter].all()
    assert list(early["status"].astype(str)) == list(full["status"].astype(str))
    for col in ("max_rotation", "max_slide", "residual_slide", "time_sliding", "time_slide_rocking",
                "stick_slip", "impacts", "time_uplift", "time_overturn"):
        np.testing.assert_array_equal(early[col].to_numpy(float), full[col].to_numpy(float), err_msg=col)
