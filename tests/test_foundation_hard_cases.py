"""Hard cases of the foundation family found by bench/fuzz.py (issue #14), each with a definite
status, finite results and an independent check of its physics."""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.model.foundation import TwoSpringFoundation


def _definite(run):
    assert not run.status.startswith("failed"), run.status
    m = run.metrics
    for k in ("max_rotation", "time_end"):
        assert np.isfinite(m[k]), (k, m[k])
    return m


# foundation:2027:109: a slender block (b/h = 0.0127) on two-spring corners (omega/p = 29.3,
# zeta = 0.103: the vertical mode is overdamped, zeta_v ~ 9, its fast eigenvalue -2 c_v/M ~ -5e5
# 1/s bounds the explicit step to ~6e-6 s) under a half-sine just below the rigid uplift
# threshold.  The free vibration after the pulse used to exhaust the 2e6-step budget in 10 s of
# t_after; the early decision ts_stays_in_contact ends it once the energy above the static
# equilibrium can no longer lift a corner or raise the rotation maxima.
HARD_109 = dict(b=0.0007735112837389468, h=0.060891575164387146, omega_over_p=29.286520218216538,
                zeta=0.1030087850670467, mass=57.131286380556205, rtol=1.5869936196274667e-07)


def _scene(case, model=TwoSpringFoundation):
    """The block and foundation of a fuzz case (``from_vibration`` as bench/fuzz.py builds it)."""
    body = fr.RigidBlock.rectangle(case["b"], case["h"])
    return body, model.from_vibration(body, case["omega_over_p"] * body.p, case["zeta"], case["mass"])


def test_two_spring_below_uplift_decided_early():
    """The spectrum cells of foundation:2027:109 that ran out of steps end definite and safe;
    simulate (which runs foundations to the end) over a t_after the step budget allows, past
    each cell's decision, gives the same status, maxima and impacts: the decision bounds every
    later rotation by the maxima so far."""
    body, fnd = _scene(HARD_109)
    amp, freqs = 0.9998623243667234, [0.1213432946985018, 0.144828332337818]
    solver = fr.Solver(rtol=HARD_109["rtol"])
    df = fr.overturning_spectrum(body, [amp], freqs, "both", pulse="half-sine", foundation=fnd,
                                 mass=HARD_109["mass"], solver=solver, progress=False)
    assert len(df) == 4
    for _, r in df.iterrows():
        assert r["status"].startswith("safe"), r["status"]
        assert np.isfinite(r["max_rotation"]) and r["max_rotation"] < body.alpha
        pulse = fr.Pulse(amp, r["frequency_ratio"], int(r["sign"]), "half-sine",
                         amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        t_end = pulse.end_time(body)
        assert t_end < r["time_end"] < t_end + 10.0
        full = fr.simulate(body, pulse, foundation=fnd, mass=HARD_109["mass"], solver=solver,
                           t_after=r["time_end"] - t_end + 0.5)
        m = _definite(full)
        assert full.status == r["status"]
        assert m["impacts"] == r["impacts"]
        assert m["max_rotation"] == r["max_rotation"]


# foundation:2027:37: the linear vibration model (omega/p = 144.5, zeta = 0.19) at a fixed step
# under a strong half-sine.  After the pulse the free vibration decays as exp(-124 t): at
# t = 6.13 s theta underflowed to 0 with theta' = 2.6e-320, and both sides' zero-crossing events
# fired at once, forever (failed:transition-loop).  A crossing slower than eps_omega now ends the
# vibration's sides (the run is upright at rest, as one that starts so).
HARD_37 = dict(b=0.044561272278008955, h=0.36341008928518054, omega_over_p=144.49927078230064,
               zeta=0.19084912249259167, mass=16.961097410988437, dt=9.331737715228895e-05)


@pytest.mark.parametrize("sign", [1, -1])
def test_linear_vibration_decays_to_rest_at_a_fixed_step(sign):
    from fastrock.model.foundation import LinearVibration
    body, fnd = _scene(HARD_37, LinearVibration)
    pulse = fr.Pulse(37.11520024785257, 3.1806642834352497, sign, "half-sine",
                     amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    run = fr.simulate(body, pulse, foundation=fnd, mass=HARD_37["mass"],
                      solver=fr.Solver(dt=HARD_37["dt"]))
    m = _definite(run)
    assert run.status == "safe:no-uplift"
    assert m["time_end"] == pytest.approx(pulse.end_time(body) + 10.0, rel=1e-12)
    H = run.history
    assert np.isfinite(H[["theta", "theta_dot"]].to_numpy()).all()
    assert abs(H["theta"].iloc[-1]) < 1e-300
    # independent check: the same scene with the adaptive solver at a tight rtol, the peak
    # reached during the pulse
    ref = fr.simulate(body, pulse, foundation=fnd, mass=HARD_37["mass"],
                      solver=fr.Solver(rtol=1e-11), t_after=1.0)
    assert ref.status == "safe:no-uplift"
    assert m["max_rotation"] == pytest.approx(ref.metrics["max_rotation"], rel=1e-6)


# foundation:2027:411: a slender block (b/h = 0.0108) on stiff two-spring corners (omega/p = 226,
# zeta = 0.086: the overdamped vertical mode bounds the explicit step to ~1e-6 s) at rtol 2e-10.
# Short pulses set it rocking on a corner for the whole t_after (2.6 s of it took the 2e6-step
# budget; the batch took longer than the fuzz's 120 s limit).  After the excitation its energy
# E = T + M g y_G + springs never grows, and below M g R - (M g)^2/(2 k_v) it can never pass
# alpha: ts_cannot_overturn ends the spectrum run safe:bounded once that bound also keeps the
# rotation below its maxima so far.
HARD_411 = dict(b=0.0008533285899270345, h=0.07922794078647816, omega_over_p=226.31865375829202,
                zeta=0.08595060057194347, mass=1.5922170975359664, rtol=2.0044066687805604e-10)


@pytest.mark.parametrize("amp,freq", [(2.1231692436643503, 5.173998603224901),
                                      (12.6327569768902, 42.5487670090091)])
def test_two_spring_rocking_bounded_after_the_pulse(amp, freq):
    body, fnd = _scene(HARD_411)
    solver = fr.Solver(rtol=HARD_411["rtol"])
    df = fr.overturning_spectrum(body, [amp], [freq], "both", pulse="half-sine", foundation=fnd,
                                 mass=HARD_411["mass"], solver=solver, progress=False)
    assert list(df["status"]) == ["safe:bounded", "safe:bounded"]
    assert df["max_rotation"].iloc[0] == df["max_rotation"].iloc[1]      # mirror
    r = df.iloc[0]
    pulse = fr.Pulse(amp, freq, int(r["sign"]), "half-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    t_exc = pulse.end_time(body)
    assert t_exc < r["time_end"] < t_exc + 1.0
    # the full run well past the decision (as far as the step budget allows): it keeps rocking
    # without passing its earlier maxima, and its energy never grows after the pulse
    full = fr.simulate(body, pulse, foundation=fnd, mass=HARD_411["mass"], solver=solver,
                       t_after=r["time_end"] - t_exc + 0.15)
    m = _definite(full)
    assert full.outcome == "safe"
    assert m["max_rotation"] == r["max_rotation"]
    H = full.history
    after = H[H["t"] >= t_exc]
    y, yd, q, qd = (after[c].to_numpy() for c in ("y", "y_dot", "theta", "theta_dot"))
    M, g, b, h, k = HARD_411["mass"], body.g, body.b, body.h, fnd.k_v
    IG = M * (b * b + h * h) / 3.0
    spring = 0.5 * k * (np.maximum(b * np.sin(q) - y, 0) ** 2 + np.maximum(-b * np.sin(q) - y, 0) ** 2)
    E = (0.5 * M * ((yd - h * np.sin(q) * qd) ** 2 + (h * np.cos(q) * qd) ** 2) + 0.5 * IG * qd ** 2
         + M * g * (y + h * np.cos(q)) + spring)
    assert np.max(np.diff(E)) <= 1e-7 * M * g * h
    assert E.max() < M * g * math.hypot(b, h)


# The same scene's cells below uplift (safe:no-uplift) with early_exit=False (the fuzz's mirror and
# simulate checks): the free vibration after the pulse decays as exp(-187 t), but the explicit step
# stays at the corner dashpots' stability limit (~6.5e5 steps per simulated second) while y_c'
# jitters at about atol, so the 10 s of t_after took more than the 2e6-step budget.  The rest
# rule in full contact (ts_at_rest: the energy above the static equilibrium below I_G
# eps_omega^2 / 2, which bounds |theta'| by eps_omega for good) sets the static equilibrium and
# the run goes to its end in a static phase.
@pytest.mark.parametrize("freq", [5.173998603224901, 42.5487670090091])
def test_two_spring_full_contact_comes_to_rest(freq):
    body, fnd = _scene(HARD_411)
    amp = 0.9485190754479218
    pulse = fr.Pulse(amp, freq, 1, "half-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    M = HARD_411["mass"]
    solver = fr.Solver(rtol=HARD_411["rtol"])
    run = fr.simulate(body, pulse, foundation=fnd, mass=M, solver=solver, early_exit=False)
    m = _definite(run)
    t_exc = pulse.end_time(body)
    assert run.status == "safe:no-uplift"
    assert m["time_end"] == pytest.approx(t_exc + 10.0, rel=1e-12)
    assert m["steps"] < 2e5
    end = run.history.iloc[-1]
    assert (end["theta"], end["theta_dot"], end["y_dot"]) == (0.0, 0.0, 0.0)
    assert end["y"] == -0.5 * M * body.g / fnd.k_v
    cell = fr.overturning_spectrum(body, [amp], [freq], 1, pulse="half-sine", foundation=fnd,
                                   mass=M, solver=solver, progress=False).iloc[0]
    assert cell["status"] == run.status and cell["max_rotation"] == m["max_rotation"]
    # independent check: without the rule (eps_omega = 0) the integrated decay, 0.25 s past the
    # pulse, has the same maximum and is within the rule's bounds of the rest state
    free = fr.simulate(body, pulse, foundation=fnd, mass=M, early_exit=False, t_after=0.25,
                       solver=fr.Solver(rtol=HARD_411["rtol"], eps_omega=0.0))
    assert free.status == "safe:no-uplift"
    assert free.metrics["max_rotation"] == m["max_rotation"]
    last = free.history.iloc[-1]
    assert abs(last["theta"]) < 1e-12 and abs(last["theta_dot"]) < 1e-9
    # the stiff method integrates the decay in few steps; DP5 alone sits at the dashpots' limit
    assert len(free.history) < 5e3
    dp5 = fr.simulate(body, pulse, foundation=fnd, mass=M, early_exit=False, t_after=0.25, history_capacity=10,
                      solver=fr.Solver(rtol=HARD_411["rtol"], eps_omega=0.0, method="RK45"))
    assert abs(dp5.metrics["max_rotation"] - m["max_rotation"]) < 1e-2 * HARD_411["rtol"]     # atol
    assert dp5.metrics["steps"] > 1e5


# foundation_friction:14:15: a slender block (b/h = 0.023, 1.6 kg) on stiff, damped corners
# (omega/p = 208, zeta = 0.175: static deflection 1.35e-9 m, 2 c_v/M = 1.5e6 1/s) under a half-sine
# below uplift, rtol 9.23e-6 (atol 9.23e-8).  After the pulse the full run (early_exit=False)
# used to end failed:step-budget at t = 3.78 s, with and without friction: the explicit step sits
# at the dashpots' stability limit while y_c' jitters at about atol, so the energy above the
# static equilibrium never fell to I_G eps_omega^2 / 2 (it cannot: atol on y_c is 70 times the
# static deflection).  The rest rule now also holds where the state is the equilibrium to within
# the solver's tolerance, no corner can lift and the energy bounds |theta| below the maxima so far
# (ts_at_rest); with friction the stick must also hold for good (ff_sticks_for_good).
HARD_FF15 = dict(b=0.00256978, h=0.112725, omega_over_p=208.22, zeta=0.1747, mass=1.586, rtol=9.23e-6)


@pytest.mark.parametrize("friction", [None, fr.Friction(1.01457, 0.795623)], ids=["plain", "friction"])
def test_two_spring_at_rest_within_the_solver_tolerance(friction):
    body, fnd = _scene(HARD_FF15)
    pulse = fr.Pulse(0.576817, 28.6296, 1, "half-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    kw = dict(foundation=fnd, mass=HARD_FF15["mass"], friction=friction)
    t_exc = pulse.end_time(body)
    full = fr.simulate(body, pulse, early_exit=False, solver=fr.Solver(rtol=HARD_FF15["rtol"]), **kw)
    m = _definite(full)
    assert full.status == "safe:no-uplift"
    assert m["time_end"] == pytest.approx(t_exc + 10.0, rel=1e-12)
    assert m["steps"] < 2e4
    end = full.history.iloc[-1]
    assert (end["theta"], end["theta_dot"], end["y_dot"]) == (0.0, 0.0, 0.0)
    early = fr.simulate(body, pulse, early_exit=True, solver=fr.Solver(rtol=HARD_FF15["rtol"]), **kw)
    assert early.status == full.status and early.metrics["time_end"] < t_exc + 0.01
    assert early.metrics["max_rotation"] == m["max_rotation"]
    # with the rule off (eps_omega = 0), 0.3 s past the pulse reach the same maximum; what they
    # integrate after the rule's instant stays within the tolerance box of the equilibrium in
    # (theta, y), the components that carry the maxima (the stiff method's steps, few and long;
    # DP5 alone took more than 1e5 steps there, the rule's run under 2e4 for all 10 s)
    off = fr.simulate(body, pulse, early_exit=False, t_after=0.3,
                      solver=fr.Solver(rtol=HARD_FF15["rtol"], eps_omega=0.0), **kw)
    assert off.status == full.status and off.metrics["max_rotation"] == m["max_rotation"]
    H = full.history
    t_rest = H["t"][(H["t"] > t_exc) & (H["theta"] == 0.0) & (H["theta_dot"] == 0.0)].min()
    after = off.history[off.history["t"] > t_rest]
    atol = 1e-2 * HARD_FF15["rtol"]
    assert len(after) >= 5
    assert after["theta"].abs().max() < atol
    assert (after["y"] - end["y"]).abs().max() < atol


# foundation:2027:215: two-spring corners (omega/p = 223, zeta = 0.147, b/h = 0.05) at the fuzz's
# fixed step dt = 1.08e-5 s, drawn from the vertical and rocking frequencies.  The corner
# dashpots' overdamped mode (eigenvalue ~ -c_v/m_eff, m_eff the corner's effective mass, up to
# 4.6e5 1/s while rocking) is beyond the fixed-step DP5's stability limit: with method="RK45"
# failed:unstable-step is the user's numerical limit, honest when the error names a stable step
# that works.  The default method takes such a step with Rodas4 and ends definite.
HARD_215 = dict(b=0.008439480686083658, h=0.1674114268924415, omega_over_p=222.82766431489057,
                zeta=0.1473626236141928, mass=248.179146026459, dt=1.077479060229978e-05)


def test_two_spring_unstable_fixed_step_names_a_stable_one():
    import re
    import warnings
    body, fnd = _scene(HARD_215)
    amp, freq = 11.452189214144326, 2.5487015577598444
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        df = fr.overturning_spectrum(body, [amp], [freq], 1, pulse="one-sine", foundation=fnd,
                                     mass=HARD_215["mass"], solver=fr.Solver(dt=HARD_215["dt"], method="RK45"),
                                     progress=False)
    assert df["status"].iloc[0] == "failed:unstable-step"
    named = [float(m) for w in caught
             for m in re.findall(r"dt <= ([0-9.eE+-]+) s would be stable", str(w.message))]
    assert named and 0.0 < named[0] < HARD_215["dt"]
    pulse = fr.Pulse(amp, freq, 1, "one-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    run = fr.simulate(body, pulse, foundation=fnd, mass=HARD_215["mass"],
                      solver=fr.Solver(dt=named[0], method="RK45"))
    m = _definite(run)
    ref = fr.simulate(body, pulse, foundation=fnd, mass=HARD_215["mass"],
                      solver=fr.Solver(rtol=1e-10))
    assert run.status == ref.status == "overturn:mode2"
    assert m["time_overturn"] == pytest.approx(ref.metrics["time_overturn"], rel=1e-9)
    auto = fr.overturning_spectrum(body, [amp], [freq], 1, pulse="one-sine", foundation=fnd,
                                   mass=HARD_215["mass"], solver=fr.Solver(dt=HARD_215["dt"]), progress=False)
    assert auto["status"].iloc[0] == "overturn:mode2"
    assert auto["time_overturn"].iloc[0] == pytest.approx(ref.metrics["time_overturn"], rel=1e-6)


def test_simulate_takes_early_exit_on_a_foundation():
    """simulate(..., foundation=..., early_exit=True) applies the two-spring model's early decisions
    (it used to drop the argument): the spectrum cell's status and time, and the maxima of the full
    run over the same t_after."""
    body, fnd = _scene(HARD_109)
    amp, freq = 0.9998623243667234, 0.1213432946985018
    solver = fr.Solver(rtol=HARD_109["rtol"])
    pulse = fr.Pulse(amp, freq, 1, "half-sine", amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    cell = fr.overturning_spectrum(body, [amp], [freq], 1, pulse="half-sine", foundation=fnd,
                                   mass=HARD_109["mass"], solver=solver, progress=False).iloc[0]
    early = fr.simulate(body, pulse, foundation=fnd, mass=HARD_109["mass"], solver=solver, early_exit=True)
    assert early.status == cell["status"]
    assert early.metrics["time_end"] == pytest.approx(cell["time_end"], rel=1e-12)
    t_end = pulse.end_time(body)
    full = fr.simulate(body, pulse, foundation=fnd, mass=HARD_109["mass"], solver=solver,
                       t_after=early.metrics["time_end"] - t_end + 0.5)
    assert early.metrics["max_rotation"] == full.metrics["max_rotation"]


# foundation:2027:463: a slender block (b/h = 0.012) on stiff, overdamped two-spring corners
# (omega/p = 75.5, zeta = 0.145, c_v/M ~ 3.7e5 1/s) under a one-cosine of 12.6 g tan(alpha), at the
# fuzz's loose rtol 8.9e-5 (atol 8.9e-7 does not resolve y_c ~ 1.4e-8 m: the end of a 6e-6 s step
# put the right corner's force at -15.7 N where it is truly rising).  At t = 7.27e-4 s the corner
# lifted and re-touched 109 times at one instant at zero force (failed:transition-loop): the
# re-contact was right (f' > 0 at f = 0), the lift fired at once from the surface.  The zero-force
# rule (ts_corner_transition) decides such a second switch by the sign of f' and holds the corner
# 2 eps_f past the surface for the next step.
HARD_463 = dict(b=0.006422146906547041, h=0.5272291771100616, omega_over_p=75.50645686217604,
                zeta=0.1445616014621935, mass=23.729341477856025, rtol=8.901284409005013e-05)


def test_two_spring_zero_force_retouch_does_not_loop():
    body, fnd = _scene(HARD_463)
    amp, freq = 12.550585121720099, 1.2254402344039947
    kw = dict(pulse="one-cosine", foundation=fnd, mass=HARD_463["mass"], progress=False)
    # the re-touch happened on DP5's tiny steps at the dashpots' stability limit
    df = fr.overturning_spectrum(body, [amp], [freq], "both",
                                 solver=fr.Solver(rtol=HARD_463["rtol"], method="RK45"), **kw)
    assert list(df["status"]) == ["overturn:mode2", "overturn:mode2"]
    assert df["time_overturn"].iloc[0] == df["time_overturn"].iloc[1]      # mirror
    assert np.isfinite(df[["max_rotation", "time_end", "theta_end", "theta_dot_end"]].to_numpy()).all()
    # independent check: the tight solver has a single uplift (no re-touch) and the same fall
    ref = fr.overturning_spectrum(body, [amp], [freq], 1, solver=fr.Solver(rtol=1e-10), **kw)
    assert ref["status"].iloc[0] == "overturn:mode2"
    assert df["time_overturn"].iloc[0] == pytest.approx(ref["time_overturn"].iloc[0], rel=1e-6)
    # the default method turns to Rodas4, whose steps follow the tolerance: the same fall, mirrored
    # exactly, within a global error of a few rtol
    auto = fr.overturning_spectrum(body, [amp], [freq], "both", solver=fr.Solver(rtol=HARD_463["rtol"]), **kw)
    assert list(auto["status"]) == ["overturn:mode2", "overturn:mode2"]
    assert auto["time_overturn"].iloc[0] == auto["time_overturn"].iloc[1]
    assert auto["time_overturn"].iloc[0] == pytest.approx(ref["time_overturn"].iloc[0], rel=10 * HARD_463["rtol"])
