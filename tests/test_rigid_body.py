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


# ============================================================ the front end: RigidBody
import fastrock as fr  # noqa: E402
from fastrock.model.rigid_body import RigidBody  # noqa: E402

WEDGE = [(0.0, 0.0), (1.0, 0.0), (0.3, 2.0)]            # centre of mass left of the middle


def body_geometry(body):
    """The test's own Geometry of a RigidBody (from its pivots, mass and I_G only; g = G)."""
    assert body.g == G
    return Geometry(body.b1, body.h1, body.b2, body.h2, body.mass, body.inertia)


def test_rigid_body_is_exported():
    assert fr.RigidBody is RigidBody and "RigidBody" in fr.__all__


@pytest.mark.parametrize("b,h", [(0.25, 1.0), (0.5, 0.6), (0.05, 2.0)])
def test_general_impact_map_is_housners_e_for_the_rectangle(b, h):
    """(I_G + m r_1 . r_2) / I_O with I_G = m (b^2 + h^2) / 3, r_1 . r_2 = h^2 - b^2: Housner's
    e = 1 - 1.5 sin^2(alpha), both ways."""
    m = 3.0
    body = RigidBody(mass=m, inertia=m * (b * b + h * h) / 3, b1=b, h1=h, b2=b, h2=h)
    alpha = math.atan2(b, h)
    assert body.e12 == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-14)
    assert body.e21 == body.e12
    assert body.e12 == pytest.approx(fr.housner_restitution(alpha), rel=1e-14)
    assert body.p1 == pytest.approx(math.sqrt(3 * body.g / (4 * math.hypot(b, h))), rel=1e-14)
    # and the polygon constructor derives the same body
    poly = RigidBody.from_polygon([(0, 0), (2 * b, 0), (2 * b, 2 * h), (0, 2 * h)], mass=m)
    assert (poly.b1, poly.h1, poly.b2, poly.h2) == pytest.approx((b, h, b, h), rel=1e-13)
    assert poly.inertia == pytest.approx(body.inertia, rel=1e-13)
    assert poly.e12 == pytest.approx(body.e12, rel=1e-12) and poly.is_symmetric


def test_general_impact_map_of_a_symmetric_body_is_from_inertia():
    """Any symmetric body: RigidBlock.from_inertia's e = 1 - (m R^2 / I_0)(1 - cos 2 alpha)."""
    m, IG, b, h = 2.0, 0.7, 0.3, 0.9
    body = RigidBody(mass=m, inertia=IG, b1=b, h1=h, b2=b, h2=h)
    R = math.hypot(b, h)
    block = fr.RigidBlock.from_inertia(R, math.atan2(b, h), IG + m * R * R, m)
    assert body.e12 == pytest.approx(block.e, rel=1e-14)
    assert body.p1 == pytest.approx(block.p, rel=1e-14)


def test_derived_quantities_per_side():
    body = RigidBody.from_polygon(WEDGE, density=2500.0, thickness=0.4, g=G)
    A = 1.0
    cx, cy = 1.3 / 3, 2.0 / 3
    assert body.mass == pytest.approx(2500 * 0.4 * A)
    assert (body.b1, body.h1, body.b2, body.h2) == pytest.approx((cx, cy, 1 - cx, cy), rel=1e-14)
    assert body.alpha1 == pytest.approx(math.atan2(cx, cy)) and body.alpha2 == pytest.approx(math.atan2(1 - cx, cy))
    geo = body_geometry(body)
    assert body.p1 == pytest.approx(geo.p[-1], rel=1e-14) and body.p2 == pytest.approx(geo.p[1], rel=1e-14)
    assert body.e12 == pytest.approx(geo.e[-1], rel=1e-14) and body.e21 == pytest.approx(geo.e[1], rel=1e-14)
    assert body.uplift_acceleration1 == pytest.approx(body.g * cx / cy)
    assert body.uplift_acceleration2 == pytest.approx(body.g * (1 - cx) / cy)
    assert body.alpha == body.alpha1 and body.p == body.p1 and body.smaller_side == 1
    assert not body.is_symmetric
    text = body.describe()
    assert f"{body.alpha1:.6g}" in text and f"{body.alpha2:.6g}" in text and "asymmetric" in text
    assert str(body) == text


def test_plot_draws_outline_cm_and_pivots():
    import matplotlib
    matplotlib.use("Agg")
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    ax = body.plot()
    xs = np.concatenate([ln.get_xdata() for ln in ax.lines])
    ys = np.concatenate([ln.get_ydata() for ln in ax.lines])
    for x, y in body.pivots:
        assert np.any(np.isclose(xs, x) & np.isclose(ys, y))
    assert np.any((xs == 0.0) & (ys == 0.0))          # the centre of mass
    import matplotlib.pyplot as plt
    plt.close(ax.figure)


def test_mesh_body_equals_its_polygon(tmp_path):
    """A box read as a mesh gives the rectangle of its section: mass, I_G about the axis, pivots."""
    a, b, c = 0.6, 0.4, 1.8           # x, y (out of the shaking plane), z (up)
    V = np.array([[x, y, z] for x in (0, a) for y in (0, b) for z in (0, c)]) + [3.0, 1.0, 0.0]
    F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6),
         (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    path = tmp_path / "box.obj"
    with open(path, "w") as f:
        f.writelines("v %.17g %.17g %.17g\n" % tuple(v) for v in V)
        f.writelines("f %d %d %d\n" % tuple(i + 1 for i in t) for t in F)
    body = RigidBody.from_mesh(path, axis=(0, 1, 0), density=2000.0)
    m = 2000.0 * a * b * c
    assert body.mass == pytest.approx(m, rel=1e-13)
    assert body.inertia == pytest.approx(m * (a * a + c * c) / 12, rel=1e-12)
    assert (body.b1, body.h1, body.b2, body.h2) == pytest.approx((a / 2, c / 2, a / 2, c / 2), rel=1e-12)
    assert body.is_symmetric
    poly = RigidBody.from_polygon([(0, 0), (a, 0), (a, c), (0, c)], mass=m)
    assert body.p1 == pytest.approx(poly.p1, rel=1e-12) and body.e12 == pytest.approx(poly.e12, rel=1e-12)


# ------------------------------------------------------------ symmetric == RigidBlock, bit for bit
SYMMETRIC = [RigidBody.from_block(fr.RigidBlock.rectangle(0.2, 1.0)),
             RigidBody.from_block(fr.RigidBlock(alpha=0.3, p=2.2, e=0.8)),
             RigidBody(mass=2.0, inertia=0.7, b1=0.3, h1=0.9, b2=0.3, h2=0.9)]


def _block_of(body):
    if body.source_block is not None:
        return body.source_block
    return fr.RigidBlock(alpha=body.alpha1, p=body.p1, e=body.e12, g=body.g, b=body.b1, h=body.h1)


@pytest.mark.parametrize("k", range(len(SYMMETRIC)))
def test_symmetric_body_simulate_is_the_block_bit_for_bit(k):
    body = SYMMETRIC[k]
    block = _block_of(body)
    assert body.to_block() == block
    pulse = fr.Pulse(amplitude=2.5, frequency=2.0)
    for kw in ({}, {"early_exit": True}, {"theta0": 0.5 * block.alpha, "duration": 4.0}):
        exc = None if "theta0" in kw else pulse
        a = fr.simulate(body, exc, **kw)
        b = fr.simulate(block, exc, **kw)
        assert a.kernel == b.kernel == "rigid"
        assert a.history.equals(b.history) and a.events.equals(b.events)
        assert list(a.metrics) == list(b.metrics) and a.status == b.status
        assert np.array_equal(np.array(list(a.metrics.values()), float),
                              np.array(list(b.metrics.values()), float), equal_nan=True)


@pytest.mark.parametrize("k", range(len(SYMMETRIC)))
def test_symmetric_body_spectrum_is_the_block_bit_for_bit(k):
    body = SYMMETRIC[k]
    block = _block_of(body)
    grid = (np.linspace(0.6, 4.0, 6), np.linspace(0.5, 8.0, 6))
    a = fr.overturning_spectrum(body, *grid, sign="both", progress=False)
    b = fr.overturning_spectrum(block, *grid, sign="both", progress=False)
    assert a.equals(b) and a.attrs == b.attrs
    assert set(a["outcome"]) >= {"safe", "mode1", "mode2"} or k == 2


def test_symmetric_body_runs_with_every_effect():
    body = SYMMETRIC[0]
    pulse = fr.Pulse(amplitude=2.0, frequency=2.0)
    for kw in ({"wall": fr.Wall(gap=0.02)}, {"friction": fr.Friction(0.3)},
               {"foundation": fr.LinearVibration(1e5)}):
        a = fr.simulate(body, pulse, **kw)
        # a block has no mass: on a foundation it takes the body's own (which the body carries)
        b = fr.simulate(body.to_block(), pulse, **kw, **({"mass": body.mass} if "foundation" in kw else {}))
        assert a.kernel == b.kernel and a.history.equals(b.history)


# ------------------------------------------------------------ asymmetric through the front end
def test_asymmetric_simulate_against_scipy_events():
    """simulate() builds the per-side parameters right: a wedge's run against the independent
    solver written from its pivots (which side is which, which restitution for which impact)."""
    body = RigidBody.from_polygon(WEDGE, mass=10.0, g=G)
    geo = body_geometry(body)
    for sign, ratio, wp in ((1, 1.5, 3.0), (-1, 1.5, 3.0), (-1, 3.0, 1.2)):
        s = -sign
        amp = ratio * G * math.tan(geo.alpha[s])
        omega = wp * geo.p[s]
        res = fr.simulate(body, fr.Pulse(amplitude=amp, frequency=omega, sign=sign, amplitude_unit="m/s2",
                                          frequency_unit="rad/s"), rtol=1e-11, t_after=4.0)
        ref = reference(geo, one_sine(amp, omega, sign), 2 * math.pi / omega + 4.0, n_impacts=10)
        imp = res.events[res.events["event"] == "impact"]["t"].to_numpy()
        n = min(len(imp), len(ref["impacts"]))
        assert n == len(ref["impacts"]) or n == 10
        assert np.allclose(imp[:n], ref["impacts"][:n], rtol=0, atol=1e-8)
        if np.isnan(ref["t_over"]):
            assert res.outcome == "safe"
        else:
            assert res.outcome in ("mode1", "mode2")
            assert res.metrics["time_overturn"] == pytest.approx(ref["t_over"], abs=1e-8)
            assert np.sign(res.history["theta"].iloc[-1]) == ref["side"]


def test_asymmetric_spectrum_side_column_and_mirror():
    """Mirroring the body (x -> -x) and the pulse sign mirrors every run: the same outcomes, the
    side column negated; overturned rows have side = sign(theta_end), the others 0."""
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    mirror = RigidBody.from_polygon([(-x, y) for x, y in WEDGE], mass=1.0)
    assert mirror.alpha2 == pytest.approx(body.alpha1, rel=1e-14)
    grid = (np.linspace(0.6, 4.0, 7), np.linspace(0.5, 8.0, 7))
    a = fr.overturning_spectrum(body, *grid, sign=[1, -1], progress=False)
    # the same physical pulses: both bodies' ratios refer to their smaller side, the same alpha and p
    b = fr.overturning_spectrum(mirror, *grid, sign=[-1, 1], progress=False)
    assert a.attrs["kernel"] == "rigid_body" and a.attrs["ratio_side"] == 1 and b.attrs["ratio_side"] == 2
    assert a.attrs["alpha1"] == body.alpha1 and a.attrs["alpha2"] == body.alpha2
    assert a.attrs["p1"] == body.p1 and a.attrs["p2"] == body.p2
    assert np.allclose(a["amplitude"], b["amplitude"], rtol=1e-12)
    assert list(a["outcome"]) == list(b["outcome"])
    assert (a["side"] == -b["side"]).all()
    over = a["outcome"].isin(["mode1", "mode2"])
    assert over.any() and (~over).any()
    assert (a.loc[over, "side"] == np.sign(a.loc[over, "theta_end"])).all()
    assert (a.loc[~over, "side"] == 0).all()
    assert set(a.loc[over, "side"]) == {1, -1}       # this wedge falls both ways over the grid
    assert np.allclose(a["max_rotation"], b["max_rotation"], rtol=1e-9)


def test_side_column_on_a_block_spectrum():
    block = fr.RigidBlock.rectangle(0.2, 1.0)
    df = fr.overturning_spectrum(block, [3.0], [1.0, 2.0], sign="both", progress=False)
    over = df["outcome"].isin(["mode1", "mode2"])
    assert (df["side"] == np.where(over, np.sign(df["theta_end"]), 0)).all()
    assert set(df["side"]) <= {-1, 0, 1}


def test_asymmetric_early_exit_matches_full_spectrum():
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    grid = (np.linspace(0.6, 4.0, 6), np.linspace(0.5, 8.0, 6))
    fast = fr.overturning_spectrum(body, *grid, sign="both", progress=False, rtol=1e-10)
    full = fr.overturning_spectrum(body, *grid, sign="both", progress=False, rtol=1e-10, early_exit=False)
    assert list(fast["outcome"]) == list(full["outcome"]) and (fast["side"] == full["side"]).all()
    assert "safe:bounded" in set(fast["status"])
    assert np.allclose(fast["max_rotation"], full["max_rotation"], rtol=0, atol=1e-7)


# ------------------------------------------------------------ bad input
@pytest.mark.parametrize("kw,match", [
    ({"foundation": fr.LinearVibration(1e5)},
     "^an asymmetric RigidBody .* foundation= is not available for it yet"),
])
def test_asymmetric_body_refuses_other_models(kw, match):
    """Friction and flight run it (the contact model: tests/test_contact_rigid_body.py); walls and
    foundations do not yet, and say so."""
    body = RigidBody.from_polygon(WEDGE, mass=1.0)
    with pytest.raises(ValueError, match=match):
        fr.simulate(body, fr.Pulse(amplitude=2.0, frequency=2.0), **kw)
    with pytest.raises(ValueError, match=match):
        fr.overturning_spectrum(body, [1.0], [1.0], progress=False, **kw)


def test_flexible_body_unaffected_by_the_routing():
    flex = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=10.0)
    assert fr.simulate(flex, fr.Pulse(amplitude=2.0, frequency=2.0)).kernel == "flexible"


@pytest.mark.parametrize("make,match", [
    (lambda: RigidBody(mass=1.0, inertia=1.0, b1=-0.1, h1=1.0, b2=0.5, h2=1.0), "^b1 must be > 0.*cannot stand"),
    (lambda: RigidBody(mass=1.0, inertia=1.0, b1=0.3, h1=1.0, b2=0.0, h2=1.0), "^b2 must be > 0"),
    (lambda: RigidBody(mass=0.0, inertia=1.0, b1=0.3, h1=1.0, b2=0.3, h2=1.0), "^mass"),
    (lambda: RigidBody(mass=1.0, inertia=1.0, b1=0.3, h1=1.0, b2=0.3, h2=1.0, theta_over=0.2), "^theta_over"),
    (lambda: RigidBody(mass=1.0, inertia=0.01, b1=2.0, h1=0.3, b2=2.0, h2=0.3), "negative restitution"),
    (lambda: RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=1.0, b2=0.6, h2=1.0, e=0.99), "^e = 0.99 would add energy"),
    (lambda: RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=1.0, b2=0.3, h2=1.0, top="pointed"), "^top"),
    (lambda: RigidBody.from_polygon([(0, 0), (1, 1), (1, 0), (0, 1)], mass=1.0), "^vertices: the polygon crosses"),
    (lambda: RigidBody.from_polygon([(0, 0), (0.2, 0), (0.2, 1), (3, 1), (3, 1.5), (0, 1.5)], mass=1.0),
     "^pose: the body cannot stand"),
    (lambda: RigidBody.from_polygon(WEDGE), "^give either mass"),
    (lambda: RigidBody.from_polygon(WEDGE, density=2000.0), "^thickness"),
    (lambda: RigidBody.from_polygon(WEDGE, mass=1.0, density=2000.0), "^give either mass"),
])
def test_bad_rigid_body_input_named(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_bad_mesh_input_named(tmp_path):
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    path = tmp_path / "open.obj"
    with open(path, "w") as f:
        f.writelines("v %g %g %g\n" % tuple(v) for v in V)
        f.writelines("f %d %d %d\n" % t for t in [(1, 3, 2), (1, 2, 4), (2, 3, 4)])
    with pytest.raises(ValueError, match="^path: .*not closed"):
        RigidBody.from_mesh(path, density=1.0)
    with pytest.raises(ValueError, match="^axis must be a unit vector"):
        RigidBody.from_mesh(path, axis=(0, 0.5, 0), density=1.0)


def test_docstring_examples_run():
    import doctest
    import fastrock.model.rigid_body as mod
    res = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert res.attempted >= 4 and res.failed == 0
