"""Reproductions of the flexible_friction model's failing cells from the long fuzz run (seed 2027)
(issue #14: no failed runs).  Each scene is the fuzz batch's own, written out.

- ``flexible_friction:2027:74, :108, :240, :261, :451`` (failed:transition-loop, 18 cells): in
  full contact the column vibrates (mostly after the pulse) and the uplift margin of physics.md
  3.3 just touches 0 where u is at its extremum.  The event finds the root on the side where the
  margin reads <= 0 (about -1e-14), so the body uplifts, but at that state the rocking equation's
  s theta'' turns it back within the first step: the impact event fires at once with theta'- = 0
  exactly.  The impact map and its initiation test then saw the same margin <= 0 and uplifted
  again, for ever at one instant.  kernels/flexible.py had the rule for this (``never_left``):
  an impact with theta'- = 0 means the body never left the ground; full contact, the uplift
  undone, and no new test at this instant (the uplift event takes the body up once the margin is
  crossed over a step).  kernels/flexible_friction.py now applies it too (REST, or SLIDE on if
  the base moves).
- ``flexible_friction:2027:331`` (failed:step-underflow, 2 cells): after a held lift-off the
  base slip-rocks back (theta = -0.80 rad, past alpha) and the trajectory runs into the singular
  point of the slip equations where A (the frictionless pivot's N) and D(sigma) = 1 + mu_k sigma
  dN/dF vanish together (Genot & Brogliato; Champneys & Varkonyi's "dynamic jam").  N = A / D
  stays finite (about 0.05 of the weight) while the accelerations grow as 1 / D, and the step
  underflowed at t = 0.158196 s.  The lift-off event now also fires once A and D are both inside
  the lift-off band (A <= N_LIFT W, D <= N_LIFT; elsewhere it is N, unchanged): the pivot is
  unloaded there by the test the kernel already applied at that event (A <= N_LIFT W: lift-off,
  else a tangential impact).  With lift_off "hold" the run goes on through held lift-offs,
  reloads and tangential impacts, and overturns, as at rtol 1e-11, with mu = 1e6 and with the
  stiff column.

Oracles: the definite status; the mechanical energy of the history after the pulse (the fuzz
invariant's formula, not the kernel's) never rises; the mirror run (sign -1) is the exact mirror
image; the outcome is the one of the same run at rtol 1e-11; no zero-length rocking phase is left
in the event log.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from fastrock import FlexibleBody, Friction, Pulse, Solver, simulate
from fastrock.running.models import flexible_friction_par
from fastrock.kernels import layout as L

from test_flexible_friction import lagrangian_model
from test_flexible_friction_chatter import _fuzz

T_AFTER = 10.0
TIGHT_RTOL = 1e-11


def _scene(alpha, p, wr, im, mu_s, mu_k, rtol, pulse, zeta=0.0, hb=0.0):
    return dict(body=FlexibleBody(alpha=alpha, p=p, omega_n_over_p=wr, zeta=zeta, impact="full-contact",
                                  rotary_inertia_ratio=im, base_cm_height=hb),
                friction=Friction(mu_s, mu_k, slide_tolerance=1e-3, lift_off="hold"),
                rtol=rtol, pulse=pulse)


SCENES = {
    74: _scene(0.581680927006009, 5.582369373977782, 142.90558740329305, 0.47429620113918575,
               0.8689997315249369, 0.8689997315249369, 2.7834889657581616e-06, "one-cosine"),
    108: _scene(0.335776127642973, 9.516804772285578, 148.91198336980264, 0.0,
                0.9661208128541541, 0.9604168156515341, 6.073339272193789e-06, "one-sine"),
    240: _scene(0.41209755107384644, 1.5630897457653747, 74.16900883193452, 0.0,
                0.4814811015785837, 0.4814811015785837, 2.85383465173979e-05, "one-sine"),
    261: _scene(0.18390179621270325, 3.4727239301924238, 224.60659629378995, 0.4240996958801097,
                1.1725311163860213, 1.1725311163860213, 5.606017244434036e-06, "one-sine"),
    451: _scene(0.4242912211949814, 0.7434062762740662, 150.73686671746094, 0.028050073472934423,
                0.4765424940320505, 0.38461082351804643, 8.586551226230831e-06, "one-sine"),
    331: _scene(0.38217890215604094, 5.571057277950662, 271.1162987199271, 0.0,
                1.997076324829961, 1.8906091428717744, 3.4383458805382095e-07, "one-sine",
                zeta=0.08535110654221985, hb=0.07347813724623997),
}
JAM_CELL = (331, 27.340342529040864, 17.99140701639385)

# (batch, amplitude a_p / (g tan alpha), frequency omega_p / p): the failing cells (each failed
# with both signs)
LOOP_CELLS = [
    (74, 2.1556045458996254, 6.704777882342238),
    (74, 4.9308937365126635, 3.0418231703897436),
    (108, 12.304089378724697, 11.498124839182163),
    (240, 21.01332205805744, 26.383901309894352),
    (240, 21.01332205805744, 53.62359510436536),
    (240, 15.981450308246892, 26.383901309894352),
    (240, 15.981450308246892, 53.62359510436536),
    (261, 5.632719459649637, 4.439869091631646),
    (451, 9.819346685788192, 0.3768725699810976),
]


def _run(batch, amplitude, frequency, sign, rtol=None, t_eval=None):
    sc = SCENES[batch]
    pulse = Pulse(amplitude, frequency, sign, sc["pulse"], amplitude_unit="g_tan_alpha",
                  frequency_unit="omega_p/p")
    solver = Solver(rtol=rtol or sc["rtol"], eps_t=1e-9, eps_omega=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = simulate(sc["body"], pulse, friction=sc["friction"], solver=solver, t_after=T_AFTER,
                       t_eval=t_eval)
    return run, pulse.end_time(sc["body"])


def test_the_scenes_are_the_fuzz_batches():
    """The written-out scenes are bench/fuzz.py's draws (so the cells are the ones that failed)."""
    fz = _fuzz()
    for batch, sc in SCENES.items():
        P = fz.draw_batch("flexible_friction", 2027, batch)
        kw = fz.build_scene(P)
        assert kw["body"] == sc["body"]
        assert kw["friction"] == sc["friction"]
        assert P["rtol"] == sc["rtol"] and P["pulse"] == sc["pulse"] and P["dt_per"] is None
    for batch, a, f in LOOP_CELLS:
        P = fz.draw_batch("flexible_friction", 2027, batch)
        assert a in P["amps"] and f in P["freqs"]


def _no_instant_rocking(ev):
    """No uplift followed by a landing at the same instant with theta'- = 0 (the loop's signature)."""
    kinds = ev["event"].to_numpy()
    t = ev["t"].to_numpy()
    vb = ev["velocity_before"].to_numpy()
    for i in range(len(ev) - 1):
        if kinds[i] == "uplift" and kinds[i + 1] == "impact" and t[i + 1] == t[i] and vb[i + 1] == 0.0:
            return False
    return True


@pytest.mark.slow
@pytest.mark.parametrize("batch,amplitude,frequency", LOOP_CELLS)
def test_former_transition_loops_end_definite(batch, amplitude, frequency):
    fz = _fuzz()
    sc = SCENES[batch]
    run, t_free = _run(batch, amplitude, frequency, 1)
    assert not run.status.startswith("failed"), run.status
    assert run.status in ("safe:rest", "safe:moving") or run.status.startswith("overturn"), run.status
    assert _no_instant_rocking(run.events)
    h = run.history
    assert np.isfinite(h[["theta", "theta_dot", "u", "u_dot", "d", "d_dot"]].to_numpy()).all()
    # after the pulse no ground work: the mechanical energy never rises (impacts, friction and
    # the tangential impulses only dissipate; zeta = 0, so the column does not)
    E = fz.energy(h, sc["body"], None, "flexible_friction")
    t = h["t"].to_numpy()
    m = t > t_free
    assert m.sum() > 10
    # the fuzz invariant's bound: a rise between two rows of at most (1e-6 + 100 rtol) of the
    # energy scale (the solver bounds each step's error relative to the state, not to E)
    b = sc["body"]
    scale = max(float(np.max(np.abs(E))), b.g ** 2 / b.p ** 2 * (1 - np.cos(b.alpha)))
    rise = float(np.max(np.diff(E[m]))) / scale
    assert rise <= fz.ENERGY_TOL + fz.ENERGY_TOL_RTOL * sc["rtol"], rise
    # the same cell at rtol 1e-11 has the same outcome
    tight, _ = _run(batch, amplitude, frequency, 1, rtol=TIGHT_RTOL)
    assert not tight.status.startswith("failed"), tight.status
    assert tight.outcome == run.outcome


@pytest.mark.slow
@pytest.mark.parametrize("batch,amplitude,frequency", [LOOP_CELLS[0], LOOP_CELLS[2], LOOP_CELLS[3],
                                                       LOOP_CELLS[7]])
def test_former_transition_loops_are_mirror_symmetric(batch, amplitude, frequency):
    """Sign -1 is the mirror image: theta, u, d change sign, the events are the same."""
    run_p, t_free = _run(batch, amplitude, frequency, 1)
    te = np.linspace(0.0, run_p.history["t"].iloc[-1], 401)
    run_p, _ = _run(batch, amplitude, frequency, 1, t_eval=te)
    run_m, _ = _run(batch, amplitude, frequency, -1, t_eval=te)
    assert run_p.status == run_m.status and not run_p.status.startswith("failed")
    assert len(run_p.events) == len(run_m.events)
    assert run_p.metrics["max_rotation"] == pytest.approx(run_m.metrics["max_rotation"], rel=1e-9)
    hp, hm = run_p.history, run_m.history
    for c in ("theta", "u", "d"):
        a, b = hp[c].to_numpy(), hm[c].to_numpy()
        assert np.allclose(a, -b, rtol=1e-9, atol=1e-12 * max(1.0, np.abs(a).max())), c


_LAGRANGIAN = []


def _lagrangian():
    if not _LAGRANGIAN:
        _LAGRANGIAN.append(lagrangian_model())
    return _LAGRANGIAN[0]


def _sympy_margins(body, friction, y, s, ag):
    """(A, D(sigma), N of the slip toward sigma = sgn d') per unit mass at state y on pivot s, from
    the sympy Lagrangian of tests/test_flexible_friction.py (not the kernel's solves)."""
    Mf, rf, Nf, *_ = _lagrangian()
    par = flexible_friction_par(body, friction)
    prm = (s, body.B, body.H, body.base_cm_height, par[L.F_MB], par[L.F_IB], par[L.F_IM], body.omega_n,
           body.zeta, body.g, ag)
    vel = (y[1], y[3], y[5])

    def N_of(F):
        M = np.array(Mf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float)
        r = np.array(rf(*prm, F, y[0], y[2], *vel, 0, 0, 0), float).ravel()
        return float(Nf(*prm, F, y[0], y[2], *vel, *np.linalg.solve(M, r)))

    A = N_of(0.0)
    nF = N_of(1.0) - A
    sigma = 1.0 if y[5] > 0 else -1.0
    D = 1.0 + friction.mu_k * sigma * nF
    return A, D, A / D


@pytest.mark.slow
def test_the_dynamic_jam_of_2027_331_lifts_off_and_the_run_ends_definite():
    batch, a, f = JAM_CELL
    sc = SCENES[batch]
    body, friction = sc["body"], sc["friction"]
    run, t_free = _run(batch, a, f, 1)
    assert run.status == "overturn:mode2", run.status
    ev, h = run.events, run.history
    # the first held lift-off after the slip-rocking phase that ran into the jam (t > 0.151 s)
    lo = ev[(ev["event"] == "lift-off-held") & (ev["t"] > 0.151)].iloc[0]
    i = int(np.flatnonzero(h["t"].to_numpy() == lo["t"])[0])
    W = (1.0 + body.base_mass(sliding=True)) * body.g

    def margins(j):
        row = h.iloc[j]
        assert row["contact"] == "slide-rock" and row["a_g"] == 0.0
        y = row[["u", "u_dot", "theta", "theta_dot", "d", "d_dot"]].to_numpy(float)
        return _sympy_margins(body, friction, y, int(row["pivot"]), 0.0)

    # the jam: at the lift-off A and D are both nearly 0 (at the lift-off band) ...
    A, D, N = margins(i)
    assert abs(A) <= 1.01e-6 * W, A / W
    assert 0.0 < D <= 2e-6, D
    # ... while on the way there N = A / D stayed of the order of 5 % of the weight (an ordinary
    # lift-off has N -> 0 with D of order 1): the last rows with D > 1e-4
    j = i - 1
    while margins(j)[1] <= 1e-4:
        j -= 1
    A, D, N = margins(j)
    assert A > 0.0 and 0.01 * W < N < 0.2 * W, (A / W, D, N / W)
    # energy: no rise after the pulse (held lift-offs are frictionless, tangential impacts dissipate)
    fz = _fuzz()
    E = fz.energy(h, body, None, "flexible_friction")
    m = h["t"].to_numpy() > t_free
    scale = max(float(np.max(np.abs(E))), body.g ** 2 / body.p ** 2 * (1 - np.cos(body.alpha)))
    rise = float(np.max(np.diff(E[m]))) / scale
    assert rise <= fz.ENERGY_TOL + fz.ENERGY_TOL_RTOL * sc["rtol"], rise
    # converged: the same outcome at rtol 1e-11, and the mirror run is the mirror image
    tight, _ = _run(batch, a, f, 1, rtol=TIGHT_RTOL)
    assert tight.status == run.status
    mirror, _ = _run(batch, a, f, -1)
    assert mirror.status == run.status and len(mirror.events) == len(run.events)
    assert mirror.metrics["max_rotation"] == pytest.approx(run.metrics["max_rotation"], rel=1e-9)



@pytest.mark.slow
@pytest.mark.parametrize("amplitude,frequency,events", [(20.791763877045042, 16.55974819618862, 86),
                                                        (13.601597382213386, 17.99140701639385, 68)])
def test_painleve_slip_with_a_and_d_negative_is_not_taken_for_the_jam(amplitude, frequency, events):
    """Two other cells of :331.  A slide lifts a corner into a slip with A = -1.56 m/s^2 and
    D = -0.14, where N = A / D > 0 (Painleve's indeterminate case: the slip is consistent and
    the kernel keeps it).  A first version of the jam rule fired on A <= band and D <= band,
    lifted off there at once, and looped uplift / lift-off at one instant
    (failed:transition-loop, 8 cells of the batch replay).  The rule needs |A| and |D| both in
    the band.  These runs are the ones of the kernel before the jam rule, event for event."""
    run, _ = _run(331, amplitude, frequency, 1)
    assert run.status == "safe:rest", run.status
    assert len(run.events) == events


def test_the_lift_off_event_is_n_outside_the_jam():
    """Random slip states: wherever |A| or |D(sigma)| is outside the lift-off band, the lift-off
    event of a slip is N itself (same value as before the jam rule, so the same roots), in
    particular in Painleve's indeterminate region A < 0, D < 0."""
    from fastrock.kernels import flexible_friction as K
    from test_flexible_friction_painleve import _random_state
    rng = np.random.default_rng(331)
    both_negative = 0
    for _ in range(400):
        b, fr, par, s, ag, hdr, smp, y = _random_state(rng)
        y[5] = rng.normal()
        sig = 1 if y[5] > 0 else -1
        disc = np.zeros(L.N_DISC, np.int64)
        K.set_mode(disc, L.MODE_SLIDE_ROCK, s, sig)
        A, nF = K.normal_margins(1.0, y, s, par, hdr, smp)
        D = 1.0 + fr.mu_k * sig * nF
        _u, _t, _d, N = K.slip_rock(1.0, y, s, sig, par, hdr, smp)
        g, _gd, term = K.event(K.R_LIFT_OFF, 1.0, y, par, disc, hdr, smp)
        assert term and g == N
        both_negative += A < 0 and D < 0
    assert both_negative > 5


# ---------------------------------------------------------------- :594, the stable-step check
def test_the_stable_step_check_stays_within_its_budget():
    """``flexible_friction:2027:594`` (hang): a fixed-step run (dt = 7.5e-5 s from omega_n) ends
    failed:unstable-step in about a second: the body falls over and its held lift-offs and slips
    near D = 0 are far stiffer than the column (|lambda| up to 1e5..1e8 1/s).  simulate() then
    looks for a stable step by running the cell again.  The second try (9.4e-6 s) diverged with a
    local error so large that the h^5 estimate suggested 1.24e-12 s, which ran with a budget of
    1e12 steps (the hang).  Stand-in run with that pattern: no candidate needs more than
    CHECK_BUDGET_FACTOR times the run's budget, and the check ends "none found" (the warning then
    says no fixed step down to that one ended the run: use the adaptive solver)."""
    from fastrock.running.outcomes import CHECK_BUDGET_FACTOR, checked_stable_step
    from hardcases import stand_in_check

    def outcome(o, tried):
        met = np.zeros(L.N_MET)
        met[L.M_DT_STABLE] = 9.45e-6 if len(tried) == 1 else 1.24e-12
        return L.FAIL_UNSTABLE, met

    run, opt, tried = stand_in_check(11.02, 2e6, 7.53e-5, outcome)
    step, how, budget = checked_stable_step(run, opt, 7.53e-5, 1.896e-5)
    floor = 11.02 / (CHECK_BUDGET_FACTOR * 2e6)
    assert step is None and budget is None and how == pytest.approx(floor, rel=1e-2)
    assert [t[0] for t in tried][:2] == [1.89e-5, 9.44e-6]
    assert len(tried) == 3 and tried[-1][0] >= 0.99 * floor
    assert max(t[1] for t in tried) <= 1.06 * CHECK_BUDGET_FACTOR * 2e6 + 1000
