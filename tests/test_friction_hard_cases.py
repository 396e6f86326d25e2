"""Hard cases for the rigid block with Coulomb friction (physics.md 4.1-4.3): mu -> 0 (1e-6: pure
sliding, against the closed form d = -double integral of a_g), very large mu (10 and 1e3: the
frictionless kernel's outcomes), bounded stick-slip chatter near mu g, a 90 s record at
dt 0.005, and issue #14's fuzz findings: Painleve at a slip onset (flight, the one consistent
mode), mu = 1e6 against the frictionless block (equal while its pivot force stays in the cone,
parting exactly where it would need tension), a flight's last rotation, the pick's sign rules,
the event rates, and 300 random fuzz-like scenes.  Every run gets a step budget and must end with a definite status and a finite
history.  CI runs this file a second time under ``NUMBA_BOUNDSCHECK=1``.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
import hardcases as H
from fastrock import Friction, Pulse, RigidBlock
from fastrock.constants import G_STANDARD as G0
from fastrock.kernels import layout as L
from fastrock.running.models import rigid_friction_par
from fastrock.running.solver import Solver
from test_friction import HF_BODY, HF_GRID, SLIDER, definite, header, one_sine

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


# ---------------------------------------------------------------------------------------------
# issue #14: Painleve at the slip onset, mu = 1e6 against the frictionless block, flights
# ---------------------------------------------------------------------------------------------
# The contact mode at zero slip velocity is decided by two signs (kernels/friction.py, module
# docstring): A = G - Y theta'^2 (> 0: the free corner is pressed into the ground; flight is
# consistent iff A <= 0) and the slip denominator D(sigma) = i_G + X (X + mu_k sigma Y)
# (N_slip = A i_G / D; D <= 0 is Painleve's case).  The helpers below recompute the stick forces
# and A, D in numpy from the history, independently of the kernel's functions.
def block_par(body):
    from fastrock.kernels import friction as FK
    par = rigid_friction_par(body, Friction(1.0))
    return par[FK.Q_B], par[FK.Q_H], par[FK.Q_IG]


def stick_forces(body, theta, w, s, ag, G=G0):
    """theta'', F, N, A per unit mass of the block rocking without slip on pivot s (arrays),
    from the three equations of kernels/friction.py's docstring with d'' = 0."""
    b, h, iG = block_par(body)
    X = -s * b * np.cos(theta) + h * np.sin(theta)
    Y = s * b * np.sin(theta) + h * np.cos(theta)
    tdd = (G * X - ag * Y) / (iG + X * X + Y * Y)
    F = ag + Y * tdd - X * w * w
    N = G - X * tdd - Y * w * w
    return tdd, F, N, G - Y * w * w, X, Y


def slip_den(body, X, Y, sigma, mu_k):
    _b, _h, iG = block_par(body)
    return iG + X * (X + mu_k * sigma * Y)


def fuzz_pulse(amp, freq, sign, kind):
    return Pulse(amp, freq, sign, kind, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


def pivot_tension_time(body, r0, mu=1e6, rerun=None):
    """First time of a frictionless run at which its bilateral pivot needs more than the cone
    of mu allows (|F| > mu N, in particular N < 0), the last time before it inside the cone (inf,
    inf if never), and the smallest N_s seen.  The history rows are checked, and with ``rerun``
    (t_eval -> history of the same run) also 64 points inside every step next to a row with
    N_s < 0.05 g, where a dip between two rows hides (grazing in an overturning fall)."""
    def scan(h):
        t = h["t"].to_numpy()
        s = h["pivot"].to_numpy()
        rock = s != 0
        _tdd, F, N, _A, _X, _Y = stick_forces(body, h["theta"].to_numpy(), h["theta_dot"].to_numpy(),
                                              np.where(rock, s, 1), h["a_g"].to_numpy())
        return t, rock, F, N

    t, rock, F, N = scan(r0.history)
    if rerun is not None:
        low = np.flatnonzero(rock & (N < 0.05 * G0))
        if low.size:
            te = np.unique(np.concatenate([np.linspace(t[max(i - 1, 0)], t[min(i + 1, t.size - 1)], 129)
                                           for i in low]))
            td, rd, Fd, Nd = scan(rerun(te))
            keep = rd & (td > 0)
            t = np.concatenate([t, td[keep]])
            order = np.argsort(t, kind="stable")
            t = t[order]
            rock = np.concatenate([rock, rd[keep]])[order]
            F = np.concatenate([F, Fd[keep]])[order]
            N = np.concatenate([N, Nd[keep]])[order]
    n_min = float(np.min(np.where(rock, N, np.inf)))
    bad = rock & (np.abs(F) > mu * N)
    if not bad.any():
        return np.inf, np.inf, n_min
    i = int(np.argmax(bad))
    return float(t[i]), float(t[i - 1]), n_min


# fuzz cells that ended failed:transition-loop (bench/README.md "Fuzz baseline (issue #14)"):
# a slip onset while rocking with D(sigma1) < 0 looped between stick and slip at one instant
PAINLEVE_CELLS = [
    ("friction:2026:16", RigidBlock.rectangle(0.9274961789134943, 2.364259092419135), 1.9917015435106786,
     "half-sine", 34.61312773729814, [4.1164419358381785, 1.5356288742822313, 3.654858729425721,
                                       8.834531489155783], Solver(rtol=1.3313470038156705e-09)),
    ("friction:2026:33", RigidBlock(0.318406937718058, 0.669267421913309), 1.8693227740950336,
     "one-cosine", 31.29451911418186, [0.12161102940559598, 6.376230028855794],
     Solver(rtol=1.1001049814176168e-09)),
    ("friction:2026:45", RigidBlock.rectangle(0.4365751414621545, 0.3759312322697188),
     1.8909817552635684, "half-sine", 5.379696156406094, [1.9127868720666663, 1.2397166387489453],
     None),
]


@pytest.mark.parametrize("cell", PAINLEVE_CELLS, ids=[c[0] for c in PAINLEVE_CELLS])
@pytest.mark.parametrize("sign", [1, -1])
def test_painleve_slip_onset_lifts_off(cell, sign):
    """Formerly failed:transition-loop (200 stick/slip transitions at one instant).  At the slip
    onset from stick (N_s > 0, |F_s| = mu_s N_s) the slip toward sigma1 = -sgn F_s has D < 0
    (Painleve); then A < 0 necessarily (kernels/friction.py), so flight is the one consistent
    mode and the run ends "flight" right there (lift_off="stop").  Checked independently: at
    the flight event the stick forces are on or past the cone, N_s > 0, D(sigma1) < 0, A < 0;
    the mirror image gives the same run."""
    name, body, mu, kind, amp, freqs, solver = cell
    for f in freqs:
        if solver is None:     # the fuzz's fixed step for this batch
            solver = Solver(dt=2 * math.pi / (max(freqs) * body.p) / 206.36213098006073)
        pulse = fuzz_pulse(amp, f, sign, kind)
        r = fr.simulate(body, pulse, friction=Friction(mu), solver=solver, t_after=5.0)
        H.definite(r, 200_000, STATE)
        assert r.status == "flight", (name, f, r.status)
        ev = r.events
        assert ev["event"].iloc[-1] == "flight" and r.metrics["stick_slip"] == 0
        t, th, w, s = ev[["t", "theta", "velocity_before", "pivot"]].iloc[-1]
        ag = float(np.interp(t, r.history["t"], r.history["a_g"]))
        _tdd, F, N, A, X, Y = stick_forces(body, th, w, s, ag)
        sig1 = -1.0 if F > 0 else 1.0
        assert N > 0 and abs(F) >= mu * N * (1 - 1e-9), (F, N)
        assert slip_den(body, X, Y, sig1, mu) < 0 and A < 0
        # the flight's rotation counts in the maximum
        assert r.metrics["max_rotation"] >= abs(th)


MU_INF_CELLS = [
    # friction:2026:1 (b/h 0.57, given e): Friction(1e6) looped where the frictionless block
    # overturns (mode 2); the frictionless pivot needs N < 0 from t = 1.3673 s: flight
    ("friction:2026:1", RigidBlock.rectangle(8.687316091593832, 15.293601937155227, e=0.46691214804113146),
     "half-sine", 34.656634552869505, 0.2527555696994872, 1.6556336739813294e-08, "flight"),
    # friction:4:0 (b/h 1.13): "slide" with a larger max rotation; the pivot needs N < 0 from
    # t = 0.0288 s with the free corner pressed (A > 0): the slip with N ~ 1e-6 is the one
    # consistent mode (the friction force stays finite as mu -> inf)
    ("friction:4:0", RigidBlock.rectangle(0.055627905965677064, 0.04943929744764557), "one-cosine",
     3.240755767032052, 7.104554243489959, 6.22404523893308e-05, "slip"),
    ("friction:2026:50", RigidBlock.rectangle(6.846812858973483, 7.716918828647167), "one-sine",
     4.654731080495459, 15.143646652268837, 3.403325878718769e-10, "slip"),
    # fuzz baseline of commit 8c52239 (seed 2026: 392 violated:mu_inf[:given-e] cells, every one
    # parting at the frictionless pivot's first tension, bench/README.md): a flight where the
    # frictionless block overturns in mode 2 (b/h 1.15, N down to -66 g) ...
    ("friction:2026:24", RigidBlock.rectangle(0.056688176216994644, 0.04940034612613083), "one-cosine",
     29.80682500088476, 0.5110578100030113, 1.7198347589235208e-07, "flight"),
    # ... and a slip (outcome "slide") where it is safe, Housner's e (b/h 0.59)
    ("friction:2026:240", RigidBlock.rectangle(0.41971992603380676, 0.7159073328427731), "one-cosine",
     8.016078855841595, 12.485350882557269, 1.4277487697718648e-08, "slip"),
]


@pytest.mark.parametrize("cell", MU_INF_CELLS, ids=[c[0] for c in MU_INF_CELLS])
def test_mu_1e6_follows_rigid_until_the_pivot_needs_tension(cell):
    """The fuzz's violated:mu_inf cells.  Friction(1e6) is the frictionless block (kernels/
    rigid.py) as long as that block's pivot force stays inside the cone |F| <= 1e6 N; in these
    cells the frictionless block needs tension at the pivot (N_s < 0, down to -0.8 g), which no
    unilateral contact gives, so the runs must part there and only there: the friction run's
    first slip or flight falls between the last history row of the frictionless run inside the
    cone and the first outside it, the rotation at that instant is the frictionless one to 1e-6
    relative, and the mode taken is the consistent one (flight where A < 0; slip where A > 0 and
    D(sigma1) > 0).  Formerly: failed:transition-loop, or a slip from a loop-free but unchecked
    pick."""
    name, body, kind, amp, f, rtol, mode = cell
    pulse = fuzz_pulse(amp, f, 1, kind)
    T = pulse.end_time(body) + 2.0
    r0 = fr.simulate(body, pulse, rtol=1e-11, duration=T)
    r1 = fr.simulate(body, pulse, friction=Friction(1e6, slide_tolerance=1e-6), rtol=1e-11, duration=T)
    H.definite(r1, 200_000, STATE)
    t_bad, t_ok, n_min = pivot_tension_time(body, r0)
    assert n_min < -0.1 * G0 and np.isfinite(t_bad)
    ev = r1.events
    part = ev[ev["event"].isin(["slip", "flight"])].iloc[0]
    assert part["event"] == ("flight" if mode == "flight" else "slip")
    assert t_ok - 1e-9 <= part["t"] <= t_bad + 1e-9, (t_ok, part["t"], t_bad)
    # the frictionless rotation at that instant (dense output)
    th0 = fr.simulate(body, pulse, rtol=1e-11, duration=T, t_eval=[part["t"]]).history["theta"].iloc[0]
    assert part["theta"] == pytest.approx(th0, rel=1e-6, abs=1e-9 * body.alpha)
    # independent check of the mode at the parting instant (state from the friction history)
    h1 = r1.history
    row = h1[h1["t"] == part["t"]].iloc[0]
    _tdd, F, N, A, X, Y = stick_forces(body, row["theta"], row["theta_dot"], int(row["pivot"]), row["a_g"])
    sig1 = -1.0 if F > 0 else 1.0
    if mode == "flight":
        assert A < 0
    else:
        assert A > 0 and slip_den(body, X, Y, sig1, 1e6) > 0 and part["pivot"] == sig1
        assert r1.metrics["max_slide"] > 1e-3 * body.h     # a finite slip, as mu -> inf


# slip cells with their measured mu -> inf slip [m] (mu = 1e8, rtol 1e-10): friction:2026:240
# above, and friction:2026:247 (b/h 0.56), a given e, tagged violated:mu_inf:given-e although e
# plays no part (it parts at the first tension, before any impact with a slip velocity)
MU_LIMIT_CELLS = [
    (MU_INF_CELLS[-1], 0.0330591641),
    (("friction:2026:247", RigidBlock.rectangle(1.54423140140743, 2.7481880314506437, e=0.4444965649365037),
      "one-cosine", 5.391010374969534, 45.20700548424042, 2.4257385923665217e-07, "slip"), 6.680314e-4),
]


@pytest.mark.parametrize("cell,limit", MU_LIMIT_CELLS, ids=[c[0][0] for c in MU_LIMIT_CELLS])
def test_mu_to_infinity_is_a_finite_slip_not_the_frictionless_block(cell, limit):
    """Where the frictionless pivot needs tension with the free corner pressed (A > 0), the
    Coulomb block's limit mu -> inf is a slip with N -> 0 and a finite friction force F ->
    -A i_G / (X Y) (kernels/friction.py: N_slip = A i_G / D, D ~ mu sigma X Y), not the
    frictionless block: over mu = 1e4, 1e6, 1e8 the slip converges like 1/mu to a limit well
    above the slide tolerance, at the same number of impacts and stick-slip transitions, and
    the outcome stays "slide" while the frictionless block is "safe".  So the fuzz's
    violated:mu_inf "slide where the frictionless block is safe" is the physical answer, and the
    frictionless block (a bilateral pivot) is the model that fails there."""
    name, body, kind, amp, f, _rtol, _mode = cell
    pulse = fuzz_pulse(amp, f, 1, kind)
    r0 = fr.simulate(body, pulse, rtol=1e-10)
    assert r0.outcome == "safe"
    t_bad, t_ok, n_min = pivot_tension_time(body, r0)
    assert n_min < -0.1 * G0
    slips, counts = [], set()
    for mu in (1e4, 1e6, 1e8):
        r = fr.simulate(body, pulse, friction=Friction(mu, slide_tolerance=1e-6), rtol=1e-10)
        H.definite(r, 200_000, STATE)
        assert r.outcome == "slide" and r.status == "safe:rest", (mu, r.status)
        if mu == 1e6:
            # the first slip comes where the frictionless pivot leaves the cone
            ev = r.events
            t_slip = ev[ev["event"] == "slip"]["t"].iloc[0]
            assert t_ok - 1e-9 <= t_slip <= t_bad + 1e-9 and not (ev["event"] == "flight").any()
        slips.append(r.metrics["max_slide"])
        counts.add((r.metrics["impacts"], r.metrics["stick_slip"]))
    assert len(counts) == 1
    d1, d2 = abs(slips[1] - slips[0]), abs(slips[2] - slips[1])
    assert d2 < 0.05 * d1, slips                    # ~ 1/mu convergence (measured ratio ~ 0.01)
    assert slips[2] == pytest.approx(limit, rel=1e-5)
    assert limit > 100 * 1e-6


def test_flight_rotation_counts_and_scales():
    """friction:2026:11 (violated:scale): a run that ends in flight reported max|theta| without
    the rotation at the flight (the last state), so scaled copies differed (0.2381 vs 0.2334 of
    alpha, still 0.2593 vs 0.2560 at rtol 1e-11).  Now max_rotation includes it, and the length
    scale k = 0.2084 (p / sqrt(k), slide tolerance and chatter thresholds scaled) gives the same
    ratio to 1e-6."""
    b, h, e = 0.06103631863941706, 0.15466571898457424, 0.27090245913269795
    k = 0.20836970439744795
    out = []
    for scale in (1.0, k):
        body = RigidBlock.rectangle(b * scale, h * scale, e=e)
        ts = math.sqrt(scale)
        r = fr.simulate(body, fuzz_pulse(32.6950079258959, 6.498731068858834, 1, "one-sine"),
                        friction=Friction(1.847758575924349, 1.0831471414125566, slide_tolerance=1e-3 * scale),
                        solver=Solver(rtol=1e-11, eps_t=1e-9 * ts, eps_omega=1e-9 / ts), t_after=10 * ts)
        H.definite(r, 200_000, STATE)
        assert r.status == "flight"
        th_end = abs(r.events["theta"].iloc[-1])
        assert r.metrics["max_rotation"] >= th_end
        out.append(r.metrics["max_rotation_ratio"])
    assert out[1] == pytest.approx(out[0], rel=1e-6)


def test_mode_signs_match_slip_accelerations():
    """The rule behind the pick (kernels/friction.py docstring), checked on the kernel's own
    slip_rock at 6000 random states, both pivots and slip directions, mu up to 1e6: N_slip =
    A i_G / D(sigma), and where stick fails (|F_s| > mu_k N_s) the slip toward sigma1 = -sgn F_s
    runs forward (sigma1 d'' > 0) exactly when D(sigma1) > 0."""
    from fastrock.kernels import friction as FK
    rng = np.random.default_rng(14)
    hdr_cache = {}
    checked = painleve = 0
    for _ in range(6000):
        b = 10 ** rng.uniform(-2, 1)
        h = b / math.tan(rng.uniform(0.02, 0.9))
        body = RigidBlock.rectangle(b, h)
        mu = 10 ** rng.uniform(-1, 6)
        par = rigid_friction_par(body, Friction(mu))
        ag = rng.uniform(-5, 5) * G0
        key = round(ag, 12)
        hdr = hdr_cache.setdefault(key, header(ag))
        smp = np.zeros(1)
        s = int(rng.choice([-1, 1]))
        th = s * rng.uniform(0, body.alpha * 1.5)
        w = rng.normal() * body.p * 1.5
        _tdd, F, N, A, X, Y = stick_forces(body, th, w, s, ag)
        for sig in (-1, 1):
            _t2, dd, Ns = FK.slip_rock(1.0, th, w, s, sig, par, hdr, smp)
            D = slip_den(body, X, Y, sig, mu)
            b_, h_, iG = block_par(body)
            assert Ns == pytest.approx(A * iG / D, rel=1e-8, abs=1e-12 * G0 * mu)
        if abs(F) > 1.01 * mu * N:
            sig1 = -1 if F > 0 else 1
            _t2, dd, _Ns = FK.slip_rock(1.0, th, w, s, sig1, par, hdr, smp)
            D1 = slip_den(body, X, Y, sig1, mu)
            if abs(sig1 * dd) > 1e-9 * G0:
                assert (sig1 * dd > 0) == (D1 > 0), (F, N, D1, dd)
                checked += 1
                painleve += D1 < 0
    # measured: 3273 states with stick failing, 534 of them with D(sigma1) < 0
    assert checked > 2000 and painleve > 300, (checked, painleve)


def _logu(rng, lo, hi):
    return float(10 ** rng.uniform(math.log10(lo), math.log10(hi)))


BUDGET_SCENE = 400_000


def draw_scene(rng):
    """One random friction scene as bench/fuzz.py draws them: bodies slender to stout (rectangles
    or alpha/p), Housner's or a given e, the three pulse kinds and both signs, a_p/(g tan alpha)
    0.3-40 with 10 % near 1, omega_p/p 0.1-60, mu_s 0.05-2 (mu_k = mu_s or 0.5-1 of it), rtol
    1e-10-1e-4 or in 10 % a fixed step."""
    u = rng.uniform()
    alpha = _logu(rng, 0.01, 0.1) if u < 0.3 else float(rng.uniform(0.1, 0.45) if u < 0.8
                                                         else rng.uniform(0.45, 0.9))
    e = None if rng.uniform() < 0.7 else float(rng.uniform(0.0, 1.0))
    if rng.uniform() < 0.75:
        R = _logu(rng, 0.05, 20.0)
        body = RigidBlock.rectangle(R * math.sin(alpha), R * math.cos(alpha), e=e)
    else:
        body = RigidBlock(alpha, _logu(rng, 0.5, 20.0), e=e)
    mu_s = _logu(rng, 0.05, 2.0)
    mu_k = mu_s if rng.uniform() < 0.5 else mu_s * float(rng.uniform(0.5, 1.0))
    kind = str(rng.choice(["one-sine", "half-sine", "one-cosine"]))
    u = rng.uniform()
    amp = float(rng.uniform(0.995, 1.005)) if u < 0.1 else (
        float(rng.uniform(0.3, 1.0)) if u < 0.25 else _logu(rng, 1.0, 40.0))
    freq = _logu(rng, 0.1, 60.0)
    sign = int(rng.choice([-1, 1]))
    if rng.uniform() < 0.1:
        w = max(body.p, freq * body.p)
        solver = Solver(dt=2 * math.pi / w / float(rng.uniform(30, 300)), max_steps=BUDGET_SCENE)
    else:
        solver = Solver(rtol=_logu(rng, 1e-10, 1e-4), max_steps=BUDGET_SCENE)
    return body, Friction(mu_s, mu_k), fuzz_pulse(amp, freq, sign, kind), solver


N_SCENES = 300


def test_random_scenes_definite_and_mu_1e6_is_the_rigid_block():
    """300 seeded scenes like the fuzz draws.  Every run with the drawn friction is definite
    (no failed:*, finite history, inside the budget).  Friction(1e6) against the frictionless
    block (both at rtol 1e-10): where the frictionless pivot force stays clearly inside the cone
    (N_s >= 1e-3 g and |F_s| <= 1e6 N_s on every history row, and densely inside the steps
    next to a row with N_s < 0.05 g), the same outcome, no slip at
    all, and max|theta|/alpha to 1e-6 (safe runs; overturning at the same
    rotation); where the frictionless pivot needs |F_s| > 1e6 N_s (tension), the friction run is
    definite and parts from the rigid block (slip or flight) no earlier than the last row inside
    the cone.
    Measured (seed 2026): 300 definite; 157 comparable, all equal (largest max-rotation
    difference 7.7e-8 relative; impact counts of long chatters differ with the step sequence,
    e.g. 4932 against 4635, and are not compared); 142 needing tension, each parting from the
    rigid block at its first tension (two of them only by a dip of N_s below 0 between two
    history rows of an overturning fall, which the kernel finds since its N and cone-margin
    events carry their rates); 1 near the cone edge (skipped).  About 7 s."""
    rng = np.random.default_rng(2026)
    budget = BUDGET_SCENE
    n_cmp = n_tension = n_near = 0
    worst = 0.0
    for i in range(N_SCENES):
        body, friction, pulse, solver = draw_scene(rng)
        where = (i, body, friction, pulse, solver)
        r = fr.simulate(body, pulse, friction=friction, solver=solver, t_after=5.0)
        H.definite(r, budget, STATE)
        assert np.isfinite([r.metrics["max_rotation"], r.metrics["time_end"]]).all(), where
        r0 = fr.simulate(body, pulse, rtol=1e-10, t_after=5.0, max_steps=budget)
        r1 = fr.simulate(body, pulse, friction=Friction(1e6, slide_tolerance=1e-6), rtol=1e-10,
                         t_after=5.0, max_steps=budget)
        H.definite(r1, budget, STATE)
        t_bad, t_ok, n_min = pivot_tension_time(
            body, r0, rerun=lambda te: fr.simulate(body, pulse, rtol=1e-10, t_after=5.0, max_steps=budget,
                                                   t_eval=te).history)
        if np.isfinite(t_bad):
            n_tension += 1
            ev = r1.events
            part = ev[ev["event"].isin(["slip", "flight"])]
            assert len(part) and part["t"].iloc[0] >= t_ok - 1e-9, where
            continue
        if n_min < 1e-3 * G0:
            n_near += 1
            continue
        n_cmp += 1
        assert r1.outcome == r0.outcome, where
        assert r1.metrics["max_slide"] == 0.0 and r1.metrics["stick_slip"] == 0, where
        a, b = r1.metrics["max_rotation_ratio"], r0.metrics["max_rotation_ratio"]
        worst = max(worst, abs(a - b) / max(1.0, abs(b)))
        assert abs(a - b) <= 1e-6 * max(1.0, abs(b)), (where, a, b)
    print(f"comparable {n_cmp}, tension {n_tension}, near {n_near}, worst {worst:.2g}")
    assert n_cmp > 120 and n_tension > 100


def test_grazing_slip_onset_at_mu_1e6_does_not_loop():
    """Found by the random sample (seed 7): a slender block (b/h = 0.011, e = 0.9998) in its
    overturning fall after the pulse, Friction(1e6): N_s grazes 0 (down to 6.9e-6 g), the cone
    is left, the slip toward sigma1 is consistent (A > 0, D > 0) but starts with a computed
    acceleration of -2.9e-10 (rounding: it is 0 at the onset) and re-sticks 0.7 ms later.  The
    stick event fired at once and stick/slip alternated 200 times at one instant
    (failed:transition-loop).  The slip from zero speed now starts with its exact rate sign
    (>= 0), so its stick is found inside the step: 2 transitions, a 7.5e-12 m slip, and the
    frictionless block's outcome (mode 1) and max rotation (to 1e-9)."""
    body = RigidBlock.rectangle(0.00868686220745685, 0.8074714504304525, e=0.9998264148730203)
    pulse = fuzz_pulse(4.343099695433948, 2.0187701141930656, -1, "one-cosine")
    r = fr.simulate(body, pulse, friction=Friction(1e6, slide_tolerance=1e-6), rtol=1.5899521350375924e-10,
                    t_after=5.0)
    r0 = fr.simulate(body, pulse, rtol=1.5899521350375924e-10, t_after=5.0)
    H.definite(r, 200_000, STATE)
    assert r.status == r0.status == "overturn:mode1"
    assert r.metrics["stick_slip"] == 2 and r.metrics["max_slide"] < 1e-9
    ev = r.events.set_index("event")
    assert 1e-4 < ev.loc["stick", "t"] - ev.loc["slip", "t"] < 1e-2
    assert r.metrics["max_rotation_ratio"] == pytest.approx(r0.metrics["max_rotation_ratio"], rel=1e-9)


def test_pick_is_consistent_and_never_jams():
    """kernels/friction.py's pick at zero slip velocity on 20000 random states (rectangles b/h
    0.03-1, mu_s 1-100 and mu_k <= mu_s, |a_g| <= 5 g, any rotation and speed, both pivots):
    the mode returned is consistent by the independent stick forces, A and D (stick: N >= 0 and
    |F| <= mu_s N; slip toward sigma: N_slip = A i_G / D >= 0 and the slip not reversed; flight:
    A <= 0), and never a jam: at zero slip speed some mode is always consistent (the proof in
    the module docstring), so the jam only catches rounding."""
    from fastrock.kernels import friction as FK
    rng = np.random.default_rng(5)
    seen = {FK.PICK_ROCK: 0, FK.PICK_SLIP: 0, FK.PICK_FLIGHT: 0}
    for _ in range(20000):
        body = RigidBlock.rectangle(10 ** rng.uniform(-1.5, 0), 1.0)
        mu_s = 10 ** rng.uniform(0, 2)
        mu_k = mu_s * rng.uniform(0.5, 1.0)
        par = rigid_friction_par(body, Friction(mu_s, mu_k))
        ag = rng.uniform(-5, 5) * G0
        s = int(rng.choice([-1, 1]))
        th = s * rng.uniform(0, 1.2)
        w = rng.normal() * 3
        y = np.array([th, w, 0.0, 0.0])
        code, sig = FK.pick_rocking(1.0, y, s, par, header(ag), np.zeros(1), True)
        _tdd, F, N, A, X, Y = stick_forces(body, th, w, s, ag)
        _b, _h, iG = block_par(body)
        assert code != FK.PICK_JAM, (th, w, ag)
        seen[code] += 1
        if code == FK.PICK_ROCK:
            assert N >= 0 and abs(F) <= mu_s * N
        elif code == FK.PICK_SLIP:
            D = slip_den(body, X, Y, sig, mu_k)
            assert A * iG / D >= 0
            _t2, dd, Ns = FK.slip_rock(1.0, th, w, s, sig, par, header(ag), np.zeros(1))
            assert sig * dd >= -1e-9 * (G0 + abs(ag)) and Ns >= -1e-12 * G0
        else:
            assert A <= 0
    assert min(seen.values()) > 1000, seen


@pytest.mark.parametrize("s", [1, -1])
def test_painleve_slip_stopped_by_tangential_impact(s):
    """A slide-rock that starts in Painleve's inconsistent case: b/h = 0.2, mu = 3, theta = 0.05 s
    on pivot s, slipping toward sigma = s at 0.5 m/s, no excitation.  D(sigma) = i_G + X (X +
    mu sigma Y) < 0 with the corner pressed (A > 0), so the slip would need N < 0 and flight is
    inconsistent: the slip is stopped at once by the tangential impact without collision (the
    plastic stick impulse; angular momentum about the corner conserved, i_0 theta'+ = Y d'-),
    which dissipates, and the block then rocks (stick).  Formerly the run ended "flight" at
    t = 0 (N < 0 read as a lift-off with the corner pressed into the ground)."""
    from test_friction import run_kernel
    body = RigidBlock.rectangle(0.2, 1.0)
    mu, th, v = 3.0, 0.05 * s, 0.5 * s
    _tdd, F, N, A, X, Y = stick_forces(body, th, 0.0, s, 0.0)
    _b, _h, iG = block_par(body)
    assert slip_den(body, X, Y, s, mu) < 0 and A > 0
    code, met, ht, hy, hd, log, _par = run_kernel(body, Friction(mu), (th, 0.0, 0.0, v), 3.0)
    assert code > 0 and np.isfinite(hy).all()
    assert log[0, 1] == 12 and log[0, 0] == 0.0           # EV_STICK at t = 0
    w_post = Y * v / (iG + X * X + Y * Y)
    assert log[0, 2] == 0.0 and log[0, 3] == pytest.approx(w_post, rel=1e-14)
    assert hy[2, 1] == pytest.approx(w_post, rel=1e-14) and hy[2, 3] == 0.0
    ke0 = 0.5 * v * v
    ke1 = 0.5 * ((Y * w_post) ** 2 + (X * w_post) ** 2 + iG * w_post ** 2)
    assert ke1 < ke0
    assert hd[2, 0] == 1                                    # MODE_ROCK after the impulse
    assert met[18] == 1                                     # one stick-slip transition


def test_contact_event_rates_are_the_derivatives():
    """The cone-margin event of ROCK and the N event of SLIDE_ROCK carry their time derivatives
    (so the driver finds a dip of mu_s N - |F| or N between two step ends): against central differences along the flow
    (kernel rhs) at 300 random states of ROCK and SLIDE_ROCK, with a horizontal one-sine and a
    vertical half-sine acting (a_g' and a_v' enter), to 1e-6 relative."""
    from fastrock.model.excitation import to_header
    from fastrock.kernels import friction as FK
    body = RigidBlock.rectangle(0.3, 1.1)
    par = rigid_friction_par(body, Friction(0.7, 0.5))
    hdr, smp = to_header(body, Pulse(0.5, 2.0, 1, "one-sine"), Pulse(0.3, 3.0, 1, "half-sine"))
    rng = np.random.default_rng(3)
    for _ in range(300):
        t = rng.uniform(0.01, 0.15)
        th = rng.uniform(-0.3, 0.3)
        s = 1 if th > 0 else -1
        mode = int(rng.choice([L.MODE_ROCK, L.MODE_SLIDE_ROCK]))
        disc = np.zeros(L.N_DISC, np.int64)
        disc[L.D_MODE], disc[L.D_PIVOT] = mode, s
        disc[L.D_SLIP_DIR] = int(rng.choice([-1, 1])) if mode == L.MODE_SLIDE_ROCK else 0
        y = np.array([th, rng.normal(), 0.0, rng.normal() if mode == L.MODE_SLIDE_ROCK else 0.0])
        f = np.empty(4)
        FK.rhs(t, y, par, disc, hdr, smp, f)
        # (ROCK's N event has none: N <= 0 implies a cone margin <= 0, found first)
        ks = (FK.E_SLIP_STICK,) if mode == L.MODE_ROCK else (FK.E_LIFT_OFF,)
        for k in ks:
            g, dg, _term = FK.event(k, t, y, par, disc, hdr, smp)
            e = 1e-6
            gp = FK.event(k, t + e, y + e * f, par, disc, hdr, smp)[0]
            gm = FK.event(k, t - e, y - e * f, par, disc, hdr, smp)[0]
            assert (gp - gm) / (2 * e) == pytest.approx(dg, rel=1e-6, abs=1e-6 * G0), (mode, k)


@pytest.mark.parametrize("bh", [0.25, 1.0])
def test_tie_mu_s_at_b_over_h_never_loops(bh):
    """mu_s = b/h (1 + eps), eps in {0, +-1e-12, 1e-9}, mu_k = mu_s or 0.9 mu_s, the three pulses,
    a_p/(g tan alpha) 0.95-12, omega_p/p 0.5-50, both signs: 672 runs per body, all definite.
    At the tie the stick-rock margin at theta = 0 is ~(mu_s - b/h) G and falls as |a_g| grows
    past G b/h, so a rocking start from flat slips at once; with mu_k < b/h the slide-rock on
    that corner rotates back (the other corner is still down) and the impact restarted the
    rocking at the same instant: 116 of 1344 runs ended failed:transition-loop.  A slip onset
    before the block has lifted (theta = theta' = 0) now takes the flat rule of physics.md 4.3
    (slide-rock only if mu_k > b/h and it lifts the corner, else a flat slide, which cannot tip
    when mu_k <= b/h)."""
    from fastrock.analyses.spectrum import overturning_spectrum
    body = RigidBlock.rectangle(bh, 1.0, e=None if bh < 0.8 else 0.3)
    for eps in (0.0, 1e-12, -1e-12, 1e-9):
        for k in (1.0, 0.9):
            mu = bh * (1 + eps)
            for kind in ("one-sine", "half-sine", "one-cosine"):
                df = overturning_spectrum(body, [0.95, 1.0, 1.05, 1.1, 2.0, 5.0, 12.0], [0.5, 5.0, 25.0, 50.0],
                                          "both", pulse=kind, friction=Friction(mu, mu * k), progress=False,
                                          rtol=1e-8)
                bad = df[df["status"].str.startswith("failed")]
                assert bad.empty, (eps, k, kind, bad[["amplitude_ratio", "frequency_ratio", "sign", "status"]])
                assert np.isfinite(df["max_rotation"]).all()


def test_slip_at_the_cone_edge_continues_until_stick_is_admissible():
    """fuzz friction:77:138 (violated:mu_inf, check run failed:transition-loop): a slender block
    (b/h = 0.0103, given e = 0.0306) in its overturning fall after a one-cosine pulse
    (a_p/(g tan alpha) = 9.99, omega_p/p = 8.17), Friction(1e6) at rtol 5.8e-5.  At theta = -1.24
    the stick forces graze the cone (N_s = 6.9e-6 g, |F_s| - 1e6 N_s = 5.6e-10 m/s^2, within
    1e6 times the rounding of N_s): the slip toward sigma1 = -sgn F_s is consistent (A > 0, D > 0),
    but its velocity stays below the solver's resolution, the step ended it at once, stick was
    still inadmissible and the same slip was picked again: 200 stick events at one instant.
    Physics.md 4.5: stick only if |F| <= mu_s N, else the slip goes on; toward sigma1 its
    sigma d'' >= 0 exactly, so a sigma d' below 0 is an integration error, and the slip now
    continues until stick is admissible (kernels/friction.py, creep_margin).  The run ends as
    the frictionless block does (overturn:mode1, same max rotation), with one slip ending in an
    admissible stick (checked with independent forces) 0.34 ms later, a slip of 1.3 nm, and the
    mechanical energy of the fall (no excitation) not rising."""
    body = RigidBlock.rectangle(0.0015857358607732517, 0.1543743757733043, e=0.030603781044144518)
    pulse = fuzz_pulse(9.990244836376746, 8.16846645531108, 1, "one-cosine")
    solver = Solver(rtol=5.804829993001642e-05)
    r0 = fr.simulate(body, pulse, solver=solver)
    r = fr.simulate(body, pulse, friction=Friction(1e6, slide_tolerance=1e-6), solver=solver)
    H.definite(r, 200_000, STATE)
    assert r0.status == r.status == "overturn:mode1"
    assert r.metrics["max_rotation_ratio"] == pytest.approx(r0.metrics["max_rotation_ratio"], rel=1e-9)
    ev = r.events
    slips, sticks = ev[ev["event"] == "slip"], ev[ev["event"] == "stick"]
    assert len(slips) == 1 and 1 <= len(sticks) <= 2 and r.metrics["stick_slip"] <= 3
    t_end = sticks["t"].iloc[-1]
    assert 1e-5 < t_end - slips["t"].iloc[0] < 1e-2
    assert r.metrics["max_slide"] < 1e-8      # measured 1.3e-9 m
    h = r.history
    row = h[h["t"] == t_end].iloc[-1]
    _tdd, F, N, _A, _X, _Y = stick_forces(body, row["theta"], row["theta_dot"], int(row["pivot"]), row["a_g"])
    assert N > 0 and abs(F) <= 1e6 * N * (1 + 1e-9)
    # energy per unit mass (bench/fuzz.py's friction formula) from the slip to the overturn
    b, hh, iG = block_par(body)
    part = h[h["t"] >= slips["t"].iloc[0]]
    th, w, dd, s = (part[c].to_numpy() for c in ("theta", "theta_dot", "d_dot", "pivot"))
    XG = -s * b * np.cos(th) + hh * np.sin(th)
    YG = s * b * np.sin(th) + hh * np.cos(th)
    E = 0.5 * (dd + YG * w) ** 2 + 0.5 * (XG * w) ** 2 + 0.5 * iG * w * w + G0 * YG
    assert (part["a_g"] == 0).all()
    rise = E - np.minimum.accumulate(E)
    slip = part["t"].to_numpy() <= t_end
    # integration error only: in the whole fall at most rtol (measured 4.2e-5 of E, at the row
    # located on theta_over; 3.3e-7 at rtol 1e-6, 2.2e-9 at 1e-8), while it slips 3.4e-8
    assert rise.max() <= solver.rtol * abs(E[0])
    assert rise[slip].max() <= 1e-2 * solver.rtol * abs(E[0])
