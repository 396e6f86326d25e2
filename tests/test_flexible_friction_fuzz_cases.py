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

Oracles: the definite status; the mechanical energy of the history after the pulse (the fuzz
invariant's formula, not the kernel's) never rises; the mirror run (sign -1) is the exact mirror
image; the outcome is the one of the same run at rtol 1e-11; no zero-length rocking phase is left
in the event log.
"""
from __future__ import annotations

import importlib.util
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from fastrock import FlexibleBody, Friction, Pulse, Solver, simulate

_FUZZ = Path(__file__).resolve().parent.parent / "bench" / "fuzz.py"
T_AFTER = 10.0
TIGHT_RTOL = 1e-11


def _fuzz():
    if "fastrock_bench_fuzz" not in sys.modules:
        spec = importlib.util.spec_from_file_location("fastrock_bench_fuzz", _FUZZ)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod
        spec.loader.exec_module(mod)
    return sys.modules["fastrock_bench_fuzz"]


def _scene(alpha, p, wr, im, mu_s, mu_k, rtol, pulse):
    return dict(body=FlexibleBody(alpha=alpha, p=p, omega_n_over_p=wr, zeta=0.0, impact="full-contact",
                                  rotary_inertia_ratio=im, base_cm_height=0.0),
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
}

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
