"""Rigid overturning spectrum against an independent event-driven solver built on solve_ivp.

The reference below shares no code with fastrock: SciPy's DOP853 (8th order, a different method
from the kernel's RK45) at rtol=1e-10, atol=1e-12, with SciPy's own event location:

* rest -> rocking: first time |a_g| > g tan(alpha), located by brentq; pivot s = -sgn(a_g);
* impact: terminal event s*theta -> 0 (direction -1), Housner map theta'+ = e theta'-, pivot
  switch; chatter-to-rest when |theta'+| < eps_omega or two impacts are closer than eps_t
  (eps_omega = eps_t = 1e-9, physics.md 7), then the uplift test;
* overturning: terminal event s*theta = pi/2 (direction +1);
* max |theta|: peaks from a non-terminal event s*theta' -> 0 on the dense output, plus the
  states at every segment boundary;
* integration is split at the pulse end (a_g has a kink there).

It is compared with fastrock.overturning_spectrum on a one-sine grid (alpha = 0.2, p = 2, both
signs, a_p/(g tan alpha) in 1.2..6, omega_p/p in 0.5..8, pulse + 10 s), with early_exit False and
True.  Outcomes must be equal on every cell; max|theta|/alpha within 1e-6 on safe cells and the
overturning time within 1e-6 s on overturning cells.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import fastrock as fr

G = 9.80665
ALPHA, P = 0.2, 2.0
T_AFTER = 10.0
EPS_OMEGA = 1e-9
EPS_T = 1e-9
RTOL, ATOL = 1e-10, 1e-12
THETA_OVER = math.pi / 2

AMPS = np.array([1.2, 1.55, 2.1, 2.9, 4.2, 6.0])
FREQS = np.array([0.5, 1.1, 2.3, 4.4, 8.0])
SIGNS = (1, -1)


class Reference:
    """One run of the one-sine pulse a_g = sign a_p sin(w t), 0 <= t <= 2 pi / w."""

    def __init__(self, alpha, p, e, ratio, w_ratio, sign, t_after=T_AFTER):
        self.alpha, self.p, self.e = alpha, p, e
        self.a_p = ratio * G * math.tan(alpha)
        self.w = w_ratio * p
        self.sign = sign
        self.t_pulse = 2 * math.pi / self.w
        self.t_end = self.t_pulse + t_after
        self.uplift_level = G * math.tan(alpha)

    def a_g(self, t):
        if 0.0 <= t <= self.t_pulse:
            return self.sign * self.a_p * math.sin(self.w * t)
        return 0.0

    def margin(self, t):
        return abs(self.a_g(t)) - self.uplift_level

    def theta_ddot(self, t, theta, s):
        phi = s * self.alpha - theta
        return -self.p ** 2 * (math.sin(phi) + self.a_g(t) / G * math.cos(phi))

    def next_uplift(self, t0):
        """First t >= t0 with |a_g(t)| > g tan(alpha) (None if none): grid scan + brentq."""
        if t0 > self.t_pulse:
            return None
        if self.margin(t0) > 0:
            return t0
        grid = np.linspace(t0, self.t_pulse, 4001)
        m = np.array([self.margin(t) for t in grid])
        k = np.flatnonzero(m > 0)
        if k.size == 0:
            return None
        k = k[0]
        t = brentq(self.margin, grid[k - 1], grid[k], xtol=1e-15, rtol=4 * np.finfo(float).eps)
        while self.margin(t) <= 0:          # strictly past the threshold
            t = np.nextafter(t, np.inf)
        return t

    def run(self):
        t = 0.0
        rocking = False
        s = 0
        y = np.zeros(2)
        impacts = 0
        t_last = -np.inf
        uplifted = False
        max_abs = 0.0
        while True:
            if not rocking:
                t_up = self.next_uplift(t)
                if t_up is None:
                    return dict(outcome="safe", status="safe:rest" if uplifted else "safe:no-uplift",
                                max_rotation=max_abs, impacts=impacts, time_overturn=np.nan)
                t, y, rocking, uplifted = t_up, np.zeros(2), True, True
                s = -1 if self.a_g(t) > 0 else 1
                first_step = None
            t_stop = self.t_pulse if t < self.t_pulse else self.t_end
            fun = lambda tt, yy, s=s: (yy[1], self.theta_ddot(tt, yy[0], s))  # noqa: E731

            def impact(tt, yy, s=s):
                return s * yy[0]
            impact.terminal, impact.direction = True, -1

            def over(tt, yy, s=s):
                return s * yy[0] - THETA_OVER
            over.terminal, over.direction = True, 1

            def peak(tt, yy, s=s):
                return s * yy[1]
            peak.terminal, peak.direction = False, -1

            sol = solve_ivp(fun, (t, t_stop), y, method="DOP853", rtol=RTOL, atol=ATOL,
                            events=(impact, over, peak), first_step=first_step)
            assert sol.status >= 0, sol.message
            for ye in sol.y_events[2]:
                max_abs = max(max_abs, abs(ye[0]))
            if sol.status == 1 and sol.t_events[1].size:                      # overturned
                return dict(outcome="mode1" if impacts else "mode2",
                            status="overturn", max_rotation=THETA_OVER, impacts=impacts,
                            time_overturn=sol.t_events[1][0])
            if sol.status == 1:                                               # impact
                t = sol.t_events[0][0]
                w_minus = sol.y_events[0][0][1]
                w_plus = self.e * w_minus
                impacts += 1
                s = -s
                chatter = abs(w_plus) < EPS_OMEGA or t - t_last < EPS_T
                t_last = t
                y = np.array([0.0, w_plus])
                first_step = None
                if chatter:
                    y = np.zeros(2)
                    if abs(self.a_g(t)) >= self.uplift_level and self.a_g(t) != 0:
                        s = -1 if self.a_g(t) > 0 else 1
                    else:
                        rocking = False
                    continue
                # keep the first step well inside the time the block needs to come back
                # (~2|w+|/|theta''|), so that the return is seen as a sign change
                acc = abs(self.theta_ddot(t, 0.0, s))
                if acc > 0:
                    first_step = min(0.1 * abs(w_plus) / acc, 1e-2, max(t_stop - t, 1e-300))
                continue
            t = sol.t[-1]
            y = sol.y[:, -1].copy()
            max_abs = max(max_abs, abs(y[0]))
            first_step = None
            if t >= self.t_end:
                return dict(outcome="safe", status="safe:moving", max_rotation=max_abs,
                            impacts=impacts, time_overturn=np.nan)


def reference_grid(body):
    rows = []
    for sg in SIGNS:
        for w in FREQS:
            for a in AMPS:
                r = Reference(body.alpha, body.p, body.e, a, w, sg).run()
                r.update(amplitude_ratio=a, frequency_ratio=w, sign=sg)
                rows.append(r)
    return rows


@pytest.fixture(scope="module")
def body():
    return fr.RigidBlock(alpha=ALPHA, p=P)


@pytest.fixture(scope="module")
def reference(body):
    return reference_grid(body)


def _spectrum(body, early_exit):
    df = fr.overturning_spectrum(body, AMPS, FREQS, sign=list(SIGNS), rtol=RTOL, t_after=T_AFTER,
                                 early_exit=early_exit, progress=False)
    return {(int(r.sign), float(r.frequency_ratio), float(r.amplitude_ratio)): r
            for r in df.itertuples()}


def _compare(reference, spec):
    """(mismatched outcomes, max |d max_ratio| on safe cells, max |d t_over|, cells compared)."""
    mismatches, d_ratio, d_tover = [], 0.0, 0.0
    for ref in reference:
        got = spec[(ref["sign"], float(ref["frequency_ratio"]), float(ref["amplitude_ratio"]))]
        assert not got.status.startswith("failed"), got.status
        if got.outcome != ref["outcome"]:
            mismatches.append((ref["sign"], ref["frequency_ratio"], ref["amplitude_ratio"],
                               ref["outcome"], got.outcome, got.status))
            continue
        if ref["outcome"] == "safe":
            d_ratio = max(d_ratio, abs(got.max_rotation_ratio - ref["max_rotation"] / ALPHA))
        else:
            d_tover = max(d_tover, abs(got.time_overturn - ref["time_overturn"]))
    return mismatches, d_ratio, d_tover, len(reference)


def test_reference_grid_is_informative(reference):
    """The grid exercises every outcome class, so the comparisons below mean something."""
    outcomes = {r["outcome"] for r in reference}
    assert outcomes == {"safe", "mode1", "mode2"}
    assert len(reference) >= 50


def test_spectrum_matches_solve_ivp_reference(body, reference):
    spec = _spectrum(body, early_exit=False)
    mismatches, d_ratio, d_tover, n = _compare(reference, spec)
    assert not mismatches, mismatches
    assert d_ratio <= 1e-6, d_ratio
    assert d_tover <= 1e-6, d_tover
    assert n == len(SIGNS) * len(FREQS) * len(AMPS)


def test_early_exit_spectrum_matches_solve_ivp_reference(body, reference):
    spec = _spectrum(body, early_exit=True)
    mismatches, d_ratio, d_tover, _n = _compare(reference, spec)
    assert not mismatches, mismatches
    assert d_ratio <= 1e-6, d_ratio
    assert d_tover <= 1e-6, d_tover


def test_early_exit_equals_full_run(body):
    full = _spectrum(body, early_exit=False)
    early = _spectrum(body, early_exit=True)
    bad = [(k, full[k].outcome, early[k].outcome, early[k].status) for k in full
           if full[k].outcome != early[k].outcome
           or (full[k].outcome == "safe"
               and abs(full[k].max_rotation_ratio - early[k].max_rotation_ratio) > 1e-6)]
    assert not bad, bad
