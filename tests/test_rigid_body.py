"""Asymmetric rigid bodies (issue #17): the two-sided rocking kernel with a
side per pivot, and RigidBody through simulate and overturning_spectrum.

Oracles: the symmetric kernel (equal sides give bit-identical runs), an
independent SciPy event solver written here from the Lagrangian of a body on
either corner, Housner's exact quarter period on each side (scipy quad), the
exact energy map across an impact, and Housner's e = 1 - 1.5 sin^2(alpha) from
the general angular-momentum map for the rectangle.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from fastrock.kernels import layout as L
from fastrock.kernels import rigid as R
from fastrock.kernels.hybrid import C_NHIST, C_NLOG, N_COUNTERS

G = 9.81


# ------------------------------------------------------------ kernel inputs
def header(amp=0.0, omega=1.0, sign=1, kind=L.EXC_ONE_SINE):
    hdr = np.zeros(L.N_EXC)
    if amp == 0.0:
        return hdr                     # EXC_NONE: free rocking
    hdr[L.X_KIND] = kind
    hdr[L.X_AMP] = amp
    hdr[L.X_OMEGA] = omega
    hdr[L.X_SIGN] = sign
    hdr[L.X_DUR] = 2 * math.pi / omega
    return hdr


def options(t_end, early=True, rtol=1e-8):
    opt = np.zeros(L.N_OPT)
    opt[L.O_RTOL] = rtol
    opt[L.O_ATOL] = rtol * 1e-2
    opt[L.O_MAX_STEP] = np.inf
    opt[L.O_MAX_STEPS] = 2e6
    opt[L.O_T_END] = t_end
    opt[L.O_EARLY_EXIT] = 1.0 if early else 0.0
    opt[L.O_RECORD_BREAKS] = 1.0
    opt[L.O_EPS_OMEGA] = 1e-9
    opt[L.O_EPS_T] = 1e-9
    return opt


def run(entry, y0, par, hdr, opt, cap=50_000):
    y = np.array(y0, float)
    met = np.zeros(L.N_MET)
    ht, hy, hd = np.empty(cap), np.empty((cap, 2)), np.empty((cap, 3), np.int64)
    log = np.empty((2000, L.N_LOG))
    cnt = np.zeros(N_COUNTERS, np.int64)
    code = entry(y, par, hdr, np.zeros(1), opt, np.empty(0), met, ht, hy, hd, log, cnt)
    n = int(cnt[C_NHIST])
    return dict(code=int(code), y=y, met=met, t=ht[:n].copy(), hist=hy[:n].copy(), disc=hd[:n].copy(),
                log=log[:int(cnt[C_NLOG])].copy())


def rigid_par(alpha, p, e, theta_over=math.pi / 2):
    par = np.zeros(L.N_PAR_RIGID)
    par[[L.P_ALPHA, L.P_P, L.P_E, L.P_G, L.P_THETA_OVER]] = alpha, p, e, G, theta_over
    return par


def sides_par(alpha2, p2, e21, alpha1, p1, e12, io_ratio, theta_over=math.pi / 2):
    """Side 2 is pivot +1 (theta > 0), side 1 pivot -1; e21 is the impact from pivot +1 onto -1."""
    par = np.zeros(L.N_PAR_RIGID_BODY)
    par[[L.P_ALPHA, L.P_P, L.P_E, L.P_G, L.P_THETA_OVER]] = alpha2, p2, e21, G, theta_over
    par[[L.P_ALPHA_NEG, L.P_P_NEG, L.P_E_NEG, L.P_IO_RATIO]] = alpha1, p1, e12, io_ratio
    return par


class Geometry:
    """A body from its pivots, written out here (not from fastrock): pivot -1 at (-b1, -h1),
    pivot +1 at (b2, -h2) from the centre of mass."""

    def __init__(self, b1, h1, b2, h2, m, IG):
        self.b1, self.h1, self.b2, self.h2, self.m, self.IG = b1, h1, b2, h2, m, IG
        self.r = {-1: np.array([b1, h1]), 1: np.array([-b2, h2])}     # pivot -> CM, body frame
        self.IO = {s: IG + m * self.r[s] @ self.r[s] for s in (-1, 1)}
        self.R = {s: math.hypot(*self.r[s]) for s in (-1, 1)}
        self.alpha = {-1: math.atan2(b1, h1), 1: math.atan2(b2, h2)}
        self.p = {s: math.sqrt(m * G * self.R[s] / self.IO[s]) for s in (-1, 1)}
        # angular momentum about the new pivot j conserved: I_O,j w+ = (I_G + m r_k . r_j) w-
        self.e = {s: (IG + m * self.r[s] @ self.r[-s]) / self.IO[-s] for s in (-1, 1)}

    def par(self):
        return sides_par(self.alpha[1], self.p[1], self.e[1], self.alpha[-1], self.p[-1], self.e[-1],
                         self.IO[-1] / self.IO[1])


def reference(body, ag, t_end, theta0=0.0, n_impacts=8, rtol=1e-12):
    """Independent event solver: on pivot s, I_O,s theta'' = m (g X - a_g Y) with (X, Y) the world
    vector from the pivot to the CM (body vector (a, c) -> (a cos + c sin, -a sin + c cos)); impacts
    by angular momentum about the new pivot; uplift from rest where a_g exceeds g b_k / h_k of the
    side it tips the body to (a_g > 0 tips it onto pivot -1).  Returns the uplift, impact and
    overturning times and the peaks (signed rotations where theta' = 0)."""
    m, r, IO = body.m, body.r, body.IO

    def rhs(t, y, s):
        a, c = r[s]
        X = a * math.cos(y[0]) + c * math.sin(y[0])
        Y = -a * math.sin(y[0]) + c * math.cos(y[0])
        return [y[1], m * (G * X - ag(t) * Y) / IO[s]]

    out = dict(t_uplift=np.nan, impacts=[], peaks=[], t_over=np.nan, side=0)
    t, th, w = 0.0, theta0, 0.0
    if theta0 == 0.0:
        thr = {-1: G * body.b1 / body.h1, 1: G * body.b2 / body.h2}

        def margin(tt):
            a = ag(tt)
            return a - thr[-1] if a > 0 else -a - thr[1]

        ts = np.linspace(0.0, t_end, 100_001)
        vals = np.array([margin(x) for x in ts])
        if not (vals > 0).any():
            return out
        i = int(np.argmax(vals > 0))
        t = brentq(margin, ts[i - 1], ts[i], xtol=1e-15, rtol=1e-15)
        out["t_uplift"] = t
        s = -1 if ag(t) > 0 else 1
    else:
        s = 1 if theta0 > 0 else -1
    while t < t_end and len(out["impacts"]) < n_impacts:
        def impact(tt, y, s):
            return s * y[0]

        def over(tt, y, s):
            return math.pi / 2 - s * y[0]

        def peak(tt, y, s):
            return y[1]

        impact.terminal = over.terminal = True
        impact.direction = over.direction = -1
        sol = solve_ivp(rhs, (t, t_end), [th, w], args=(s,), method="DOP853", rtol=rtol,
                        atol=rtol * 1e-3, events=[impact, over, peak])
        out["peaks"] += [(float(tp), float(v[0])) for tp, v in zip(sol.t_events[2], sol.y_events[2])]
        if sol.t_events[1].size:
            out["t_over"], out["side"] = float(sol.t_events[1][0]), s
            return out
        if not sol.t_events[0].size:
            break
        t = float(sol.t_events[0][0])
        out["impacts"].append(t)
        th, w = 0.0, body.e[s] * sol.y_events[0][0][1]
        s = -s
    return out


def one_sine(amp, omega, sign):
    t1 = 2 * math.pi / omega
    return lambda t: sign * amp * math.sin(omega * t) if t <= t1 else 0.0


# ------------------------------------------------------------ bit identity
def _identical(a, b):
    return (a["code"] == b["code"] and np.array_equal(a["y"], b["y"]) and
            np.array_equal(a["met"], b["met"], equal_nan=True) and np.array_equal(a["t"], b["t"]) and
            np.array_equal(a["hist"], b["hist"]) and np.array_equal(a["disc"], b["disc"]) and
            np.array_equal(a["log"], b["log"]))


def test_equal_sides_bit_identical_to_the_symmetric_kernel():
    """Each asymmetric kernel function performs the symmetric one's floating-point operations when
    the sides agree: whole runs (history, events, metrics, final state) are identical, with and
    without the early decisions, from rest under pulses and released from a rotation."""
    rng = np.random.default_rng(17)
    codes = set()
    for _ in range(120):
        a = rng.uniform(0.05, 0.6)
        p = rng.uniform(1.0, 4.0)
        e = rng.uniform(0.5, 1.0)
        early = bool(rng.integers(2))
        if rng.random() < 0.2:
            hdr, y0, t_end = header(), [rng.uniform(-0.9, 0.9) * a, 0.0], 8.0
        else:
            om = rng.uniform(0.5, 12.0) * p
            hdr = header(rng.uniform(0.5, 6.0) * G * math.tan(a), om, rng.choice([-1, 1]))
            y0, t_end = [0.0, 0.0], 2 * math.pi / om + 10.0
        opt = options(t_end, early)
        sym = run(R.rigid_simulate, y0, rigid_par(a, p, e), hdr, opt)
        gen = run(R.rigid_body_simulate, y0, sides_par(a, p, e, a, p, e, 1.0), hdr, opt)
        assert _identical(sym, gen), (a, p, e, early, sym["code"], gen["code"])
        codes.add(sym["code"])
    # the grid reaches rest, the bounded decision and both overturning modes
    assert {L.SAFE_REST, L.SAFE_BOUNDED, L.OVERTURN_MODE1, L.OVERTURN_MODE2} <= codes, codes


# ------------------------------------------------------------ SciPy reference
BODIES = [Geometry(0.3, 1.0, 0.5, 1.2, 100.0, 40.0),      # pivots at different heights
          Geometry(0.15, 0.7, 0.35, 0.7, 50.0, 9.0)]      # a flat base, CM off centre


# (sign, amplitude ratio on the side the pulse first tips the body to, omega_p / p of that side)
PULSES = [(1, 2.5, 5.0), (-1, 2.5, 5.0), (1, 1.3, 2.0), (-1, 1.3, 2.0), (1, 3.0, 1.5), (-1, 3.0, 1.5)]


@pytest.mark.parametrize("k", range(len(BODIES)))
@pytest.mark.parametrize("case", [("free", 0.8), ("free", -0.8)] + [("pulse",) + c for c in PULSES])
def test_asymmetric_body_against_scipy_events(k, case):
    """Uplift, every impact time, every peak and the overturning time against the independent
    solver, with the early decisions off (the run integrates to the end)."""
    body = BODIES[k]
    if case[0] == "free":
        s = 1 if case[1] > 0 else -1
        theta0 = case[1] * body.alpha[s]
        hdr, ag, t_end = header(), (lambda t: 0.0), 6.0
    else:
        _, sign, ratio, wp = case
        # amplitude ratio on the side the first half-sine tips the body to
        s = -sign
        amp = ratio * G * math.tan(body.alpha[s])
        omega = wp * body.p[s]
        hdr, ag, t_end, theta0 = header(amp, omega, sign), one_sine(amp, omega, sign), \
            2 * math.pi / omega + 4.0, 0.0
    res = run(R.rigid_body_simulate, [theta0, 0.0], body.par(), hdr, options(t_end, False, 1e-11))
    ref = reference(body, ag, t_end, theta0=theta0, n_impacts=10)
    log = res["log"]
    imp = log[log[:, L.LOG_KIND] == L.EV_IMPACT, L.LOG_T]
    n = min(len(imp), len(ref["impacts"]))
    assert n == len(ref["impacts"]) or n == 10
    assert np.allclose(imp[:n], ref["impacts"][:n], rtol=0, atol=1e-8), (imp[:n], ref["impacts"][:n])
    if np.isnan(ref["t_uplift"]):
        assert np.isnan(res["met"][L.M_T_UPLIFT]) or theta0 != 0.0
    else:
        assert res["met"][L.M_T_UPLIFT] == pytest.approx(ref["t_uplift"], abs=1e-12)
    if np.isnan(ref["t_over"]):
        assert res["code"] in (L.SAFE_REST, L.SAFE_MOVING, L.SAFE_NO_UPLIFT), res["code"]
    else:
        assert res["code"] in (L.OVERTURN_MODE1, L.OVERTURN_MODE2)
        assert res["met"][L.M_T_OVER] == pytest.approx(ref["t_over"], abs=1e-8)
        assert np.sign(res["y"][0]) == ref["side"]
    # the largest excursion on each side, up to midway between the 9th and 10th impacts (or the end)
    t_cut = 0.5 * (ref["impacts"][8] + ref["impacts"][9]) if len(ref["impacts"]) == 10 else t_end
    if t_cut < t_end:
        res = run(R.rigid_body_simulate, [theta0, 0.0], body.par(), hdr, options(t_cut, False, 1e-11))
    peaks = np.array([th for tp, th in ref["peaks"] if tp <= t_cut] + [theta0])
    if not np.isnan(ref["t_over"]):
        peaks = np.append(peaks, ref["side"] * math.pi / 2)
    assert res["met"][L.M_MAX_THETA_POS] == pytest.approx(max(peaks.max(), 0.0), abs=1e-9)
    assert res["met"][L.M_MAX_THETA_NEG] == pytest.approx(max(-peaks.min(), 0.0), abs=1e-9)


def test_reference_cases_reach_both_sides_and_both_outcomes():
    """The pulses above are not all alike: some overturn the body onto each side, some leave it
    standing (and an asymmetric body may fall to the side the pulse did not tip it to first)."""
    sides, safe, other = set(), 0, 0
    for body in BODIES:
        for sign, ratio, wp in PULSES:
            s = -sign
            amp, omega = ratio * G * math.tan(body.alpha[s]), wp * body.p[s]
            ref = reference(body, one_sine(amp, omega, sign), 2 * math.pi / omega + 4.0, n_impacts=10)
            sides.add(ref["side"])
            safe += np.isnan(ref["t_over"])
            other += ref["side"] == sign
    assert sides == {1, -1, 0} and safe >= 2 and other >= 1


# ------------------------------------------------------------ closed forms per side
def quarter_period_exact(alpha, p, theta0):
    """T/4 = int_0^theta0 dtheta / (p sqrt(2[cos(alpha - theta0) - cos(alpha - theta)])) of the
    symmetric block (tests/test_rigid_closed_forms.py), here with one side's alpha and p.  The
    1/sqrt singularity is removed with theta = theta0 - w^2."""
    def integrand(w):
        s = 0.5 * w * w
        sinc = math.sin(s) / s if s > 0 else 1.0
        return math.sqrt(2.0 / sinc) / (p * math.sqrt(math.sin(alpha - theta0 + s)))

    val, err = quad(integrand, 0.0, math.sqrt(theta0), epsabs=0.0, epsrel=1e-13)
    assert err < 1e-12 * val
    return val


@pytest.mark.parametrize("k", range(len(BODIES)))
@pytest.mark.parametrize("start", [1, -1])
def test_free_rocking_quarter_periods_per_side(k, start):
    """Released at rest on side s: the first impact comes after side s's quarter period; the body
    then rocks on the other side j with the energy e_s^2 (p_s / p_j)^2 E_s (in units m g R_j), up
    to theta_1 with cos(alpha_j - theta_1) = cos(alpha_j) + that energy, and the second impact
    comes after two of side j's quarter periods at that amplitude."""
    body = BODIES[k]
    s, j = start, -start
    a_s, a_j, p_s, p_j = body.alpha[s], body.alpha[j], body.p[s], body.p[j]
    ratio = body.e[s] ** 2 * (p_s / p_j) ** 2
    # an energy that stays inside both wells
    E_s = min(0.6 * (1 - math.cos(a_s)), 0.5 * (1 - math.cos(a_j)) / ratio)
    theta0 = a_s - math.acos(math.cos(a_s) + E_s)
    E_j = ratio * E_s
    theta1 = a_j - math.acos(math.cos(a_j) + E_j)
    t1 = quarter_period_exact(a_s, p_s, theta0)
    t2 = t1 + 2 * quarter_period_exact(a_j, p_j, theta1)
    res = run(R.rigid_body_simulate, [s * theta0, 0.0], body.par(), header(), options(t2 * 1.01, False, 1e-12))
    log = res["log"]
    imp = log[log[:, L.LOG_KIND] == L.EV_IMPACT, L.LOG_T]
    assert imp[0] == pytest.approx(t1, rel=1e-10)
    assert imp[1] == pytest.approx(t2, rel=1e-10)
    peak_j = res["met"][L.M_MAX_THETA_NEG if j < 0 else L.M_MAX_THETA_POS]
    assert peak_j == pytest.approx(theta1, rel=1e-10)
    # the energy map itself: no impact adds kinetic energy (I_O,j w+^2 <= I_O,s w-^2)
    w_pre, w_post = log[log[:, L.LOG_KIND] == L.EV_IMPACT][0, [L.LOG_PRE, L.LOG_POST]]
    assert body.IO[j] * w_post ** 2 <= body.IO[s] * w_pre ** 2


def test_uplift_threshold_per_side():
    """A constant-sign half of a one-sine pulse just above (below) side k's g tan(alpha_k) lifts
    (does not lift) the body onto that side; a_g > 0 tips it onto pivot -1."""
    body = BODIES[1]          # alpha_-1 = atan(0.15/0.7) < alpha_+1 = atan(0.35/0.7)
    for sign, s in ((1, -1), (-1, 1)):
        thr = G * math.tan(body.alpha[s])
        for f, lifts in ((1.0 + 1e-6, True), (1.0 - 1e-6, False)):
            hdr = header(f * thr, 3.0, sign)
            # stop before the second half of the pulse, which tips the body the other way
            res = run(R.rigid_body_simulate, [0.0, 0.0], body.par(), hdr, options(math.pi / 3.0, False))
            assert (not np.isnan(res["met"][L.M_T_UPLIFT])) == lifts, (sign, f)
            if lifts:
                assert res["log"][0, L.LOG_PIVOT] == s


@pytest.mark.parametrize("k", range(len(BODIES)))
def test_early_decisions_per_side_agree_with_full_runs(k):
    """The per-side early decisions (bounded energy on both sides, the closed-form fall) give the
    outcome, side and largest rotations of the run integrated to its end."""
    body = BODIES[k]
    rng = np.random.default_rng(k)
    decided = set()
    for _ in range(60):
        s = rng.choice([-1, 1])
        amp = rng.uniform(1.0, 5.0) * G * math.tan(body.alpha[s])
        omega = rng.uniform(0.7, 8.0) * body.p[s]
        hdr = header(amp, omega, -s)
        t_end = 2 * math.pi / omega + 15.0
        full = run(R.rigid_body_simulate, [0.0, 0.0], body.par(), hdr, options(t_end, False, 1e-10))
        fast = run(R.rigid_body_simulate, [0.0, 0.0], body.par(), hdr, options(t_end, True, 1e-10))
        over = (L.OVERTURN_MODE1, L.OVERTURN_MODE2)
        assert (full["code"] in over) == (fast["code"] in over)
        decided.add(fast["code"])
        if fast["code"] in over:
            assert fast["code"] == full["code"]
            assert np.sign(fast["y"][0]) == np.sign(full["y"][0])
            assert fast["met"][L.M_T_OVER] == pytest.approx(full["met"][L.M_T_OVER], abs=1e-7)
        for m in (L.M_MAX_THETA_POS, L.M_MAX_THETA_NEG):
            assert fast["met"][m] == pytest.approx(full["met"][m], abs=1e-7)
    assert L.SAFE_BOUNDED in decided and (decided & {L.OVERTURN_MODE1, L.OVERTURN_MODE2})


def test_bounded_decision_checks_the_other_side():
    """Energy below side s's barrier but above the other side's after the impact is not bounded:
    the other side may still tip over (the symmetric rule would call it safe)."""
    alpha_s, alpha_o, p = 0.4, 0.1, 2.0
    E = 0.9 * (1.0 - math.cos(alpha_s))             # inside side s's well, moving inward
    theta = 0.5 * alpha_s
    w = -math.sqrt(2 * p * p * (E - (math.cos(alpha_s - theta) - math.cos(alpha_s))))
    safe, _, _ = R.bounded_after_excitation_sides(theta, w, 1, alpha_s, p, 1.0, alpha_o, p, 1.0)
    assert not safe
    safe, _, _ = R.bounded_after_excitation(theta, w, 1, alpha_s, p, 1.0)
    assert safe          # the symmetric rule with side s's alpha on both sides
    safe, pk1, pk2 = R.bounded_after_excitation_sides(theta, w, 1, alpha_s, p, 0.2, alpha_o, p, 0.2)
    assert safe and pk1 < 0 < pk2 and -pk1 < alpha_o
