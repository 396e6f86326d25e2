"""Early decisions of the rigid block with friction (kernels/friction.py, ``decide``).

After the excitation the mechanical energy can only fall (the ground frame is inertial, Coulomb
friction and the impact maps dissipate).  With ``early_exit`` the kernel decides two states:

* a flat slide (SLIDE) decelerates at mu_k g to a stop and rests for good: the run is completed
  in closed form with the integrated run's status and every metric;
* rocking without slip (ROCK) below the overturning barrier, where stick and contact provably
  hold on every state the energy still allows and no impact can slip (``sticks_for_good``): the
  rest is Housner free rocking: safe:bounded, the next two peaks in closed form counted when
  they come before t_end (``peak_times``, elliptic integrals; the random scenes below have
  t_after down to 0.5 s), the slip metrics final.

Oracle: the same runs integrated to the end (``early_exit=False``), at a tight tolerance.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.kernels import friction as K
from fastrock.kernels import layout as L

RTOL = 1e-10
SLIP = ("max_slide", "residual_slide", "time_sliding", "time_slide_rocking", "stick_slip")
ROTATION = ("max_rotation", "max_rotation_ratio")
WORK = {"nfev", "steps", "rejected_steps", "events", "status_code", "history_rows"}

# (alpha, p, mu_s, mu_k): slides only (mu_s < tan alpha), rocks and slide-rocks, mu_k < mu_s,
# and a stout block that slides (alpha 0.5, tan alpha 0.55) or rocks
GRIDS = [(0.25, 2.0, 0.15, 0.15), (0.25, 2.0, 0.3, 0.3), (0.25, 2.0, 0.6, 0.5),
         (0.5, 3.0, 0.4, 0.35), (0.5, 3.0, 0.9, 0.9)]
N = 24


def spectra(alpha, p, mu_s, mu_k, n=N):
    body = fr.RigidBlock(alpha=alpha, p=p)
    a = np.linspace(0.5, 6.0, n)
    f = np.linspace(0.5, 10.0, n)
    kw = dict(sign="both", friction=fr.Friction(mu_s, mu_k), t_after=8.0, rtol=RTOL,
              progress=False)
    early = fr.overturning_spectrum(body, a, f, early_exit=True, **kw)
    full = fr.overturning_spectrum(body, a, f, early_exit=False, **kw)
    return early, full


@pytest.mark.parametrize("alpha,p,mu_s,mu_k", GRIDS)
def test_early_decisions_equal_full_runs_on_pulse_grids(alpha, p, mu_s, mu_k):
    early, full = spectra(alpha, p, mu_s, mu_k)
    assert len(early) == len(full) == 2 * N * N
    assert (early["outcome"] == full["outcome"]).all()
    bounded = (early["status"] == "safe:bounded").to_numpy()
    assert not (full["status"] == "safe:bounded").any()
    assert full.loc[bounded, "status"].isin(["safe:rest", "safe:moving"]).all()
    # decided while rocking: rotations and slip metrics final
    for c in ROTATION:
        np.testing.assert_allclose(early.loc[bounded, c], full.loc[bounded, c], rtol=1e-9,
                                   atol=1e-12, err_msg=c)
    for c in SLIP:
        np.testing.assert_allclose(early.loc[bounded, c], full.loc[bounded, c], rtol=1e-9,
                                   atol=1e-12, err_msg=c)
    # everything else (slides completed in closed form included): the full run's every column
    rest = ~bounded
    assert (early.loc[rest, "status"] == full.loc[rest, "status"]).all()
    for c in early.columns:
        if c in WORK or c == "status":
            continue
        a, b = early.loc[rest, c], full.loc[rest, c]
        if a.dtype.kind in "fc":
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-11, err_msg=c)
        else:
            assert (a.to_numpy() == b.to_numpy()).all(), c
    # the decisions happen and save work
    slides = (early["nfev"] < full["nfev"]) & ~early["status"].eq("safe:bounded")
    print(f"\nalpha {alpha} mu {mu_s}/{mu_k}: {int(bounded.sum())} decided rocking, "
          f"{int(slides.sum())} slides completed, nfev {early['nfev'].sum()} vs {full['nfev'].sum()}")
    assert early["nfev"].sum() < full["nfev"].sum()


def pulse(ratio, w_ratio, sign=1):
    return fr.Pulse(ratio, w_ratio, sign=sign, amplitude_unit="g_tan_alpha",
                    frequency_unit="omega_p/p")


def test_decided_slide_is_the_integrated_run():
    """A block that only slides (mu 0.2 < b/h 0.25): completed in closed form after the pulse
    with the full run's status, slip metrics, times and events."""
    block = fr.RigidBlock.rectangle(b=0.2, h=0.8)
    for exc, t_after in ((pulse(2.0, 1.5), 5.0), (pulse(3.0, 0.6, -1), 0.05)):
        kw = dict(friction=fr.Friction(0.2, 0.18), t_after=t_after, rtol=RTOL)
        full = fr.simulate(block, exc, early_exit=False, **kw)
        early = fr.simulate(block, exc, early_exit=True, **kw)
        assert early.status == full.status
        assert early.metrics["nfev"] < full.metrics["nfev"]
        for k, v in full.metrics.items():
            if k in WORK:
                continue
            assert early.metrics[k] == pytest.approx(v, rel=1e-10, abs=1e-12, nan_ok=True), k
        ef, ee = full.events, early.events
        assert list(ee["event"]) == list(ef["event"])
        np.testing.assert_allclose(ee["t"], ef["t"], rtol=0, atol=1e-10)
    # the second run ends while still sliding: safe:moving with the slip at t_end
    assert full.status == "safe:moving" and full.metrics["time_sliding"] > 0


def test_decided_rocking_is_bounded_and_exact():
    """Rocking without slip after the pulse (mu 0.6): safe:bounded at the pulse end with the
    full run's peaks."""
    body = fr.RigidBlock(alpha=0.25, p=2.0)
    exc = pulse(1.5, 4.0)
    kw = dict(friction=fr.Friction(0.6), t_after=8.0, rtol=RTOL)
    full = fr.simulate(body, exc, early_exit=False, **kw)
    early = fr.simulate(body, exc, early_exit=True, **kw)
    assert full.status in ("safe:rest", "safe:moving") and early.status == "safe:bounded"
    assert early.outcome == full.outcome
    assert early.metrics["time_end"] >= exc.end_time(body)
    for k in ROTATION + ("max_rotation_pos", "max_rotation_neg"):
        assert early.metrics[k] == pytest.approx(full.metrics[k], rel=1e-9), k
    for k in SLIP:
        assert early.metrics[k] == pytest.approx(full.metrics[k], rel=1e-10, abs=1e-15), k


def test_no_rocking_decision_when_slip_or_flight_is_possible():
    """sticks_for_good refuses where friction cannot hold the free rocking or an impact slips."""
    par = np.zeros(L.N_PAR_FRICTION)
    b, h = 0.25, 1.0
    R2 = b * b + h * h
    par[L.Q_B], par[L.Q_H], par[L.Q_IG] = b, h, R2 / 3.0
    par[L.P_G] = 9.81
    par[L.P_E] = 1.0 - 1.5 * math.sin(math.atan(b / h)) ** 2
    par[L.Q_MU_S] = par[L.Q_MU_K] = 0.6
    assert K.sticks_for_good(0.05, 0.1, 1, par)
    # near the barrier, |F| / N at rest alone needs mu_s above ~0.19
    par[L.Q_MU_S] = par[L.Q_MU_K] = 0.1
    assert not K.sticks_for_good(0.0, 0.0, 1, par)
    # an impact slips for any speed when h (1 - e) > mu_s b (1 + e)
    par[L.Q_MU_S] = par[L.Q_MU_K] = 0.6
    par[L.P_E] = 0.2
    assert not K.sticks_for_good(0.0, 0.0, 1, par)
    # high speed: N would fall below 0 (flight) or friction run out
    par[L.P_E] = 0.9
    assert not K.sticks_for_good(0.0, 10.0, 1, par)


def random_scenes(n, seed):
    """Random rigid blocks with friction (slender to stout, mu_k <= mu_s, Housner's or a given
    e), pulses of every kind and sign, sometimes a vertical pulse, sometimes released tilted or
    sliding with no excitation."""
    rng = np.random.default_rng(seed)
    scenes = []
    for i in range(n):
        alpha = rng.uniform(0.1, 0.7)
        e = None if rng.uniform() < 0.7 else rng.uniform(0.0, 1.0 - 1.5 * math.sin(alpha) ** 2)
        body = fr.RigidBlock(alpha=alpha, p=rng.uniform(1.0, 5.0), e=e)
        mu_s = math.tan(alpha) * rng.uniform(0.3, 4.0)
        fric = fr.Friction(mu_s, mu_s * rng.uniform(0.6, 1.0))
        kind = rng.choice(["one-sine", "half-sine", "one-cosine"])
        exc = fr.Pulse(rng.uniform(0.5, 8.0), rng.uniform(0.3, 10.0), sign=int(rng.choice([-1, 1])),
                       kind=str(kind), amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        kw = dict(t_after=rng.uniform(0.5, 10.0))
        if rng.uniform() < 0.15:
            kw["vertical"] = fr.Pulse(rng.uniform(0.0, 0.5) * body.g, exc.frequency, kind=str(kind),
                                      frequency_unit="omega_p/p", amplitude_unit="m/s2")
        if rng.uniform() < 0.15:
            exc = None
            kw = dict(theta0=rng.uniform(-0.9, 0.9) * alpha, dtheta0=rng.uniform(-1.0, 1.0),
                      duration=rng.uniform(1.0, 8.0))
        scenes.append(fr.Scene(body, excitation=exc, friction=fric, solver=fr.Solver(rtol=RTOL),
                               name=str(i), **kw))
    return scenes


def test_early_decisions_equal_full_runs_on_random_scenes():
    scenes = random_scenes(300, seed=15)
    early = fr.run_batch(scenes, early_exit=True, progress=False)
    full = fr.run_batch(scenes, early_exit=False, progress=False)
    assert (early["outcome"] == full["outcome"]).all()
    bounded = (early["status"] == "safe:bounded").to_numpy()
    rest = ~bounded
    assert (early.loc[rest, "status"] == full.loc[rest, "status"]).all()
    for c in ROTATION:
        np.testing.assert_allclose(early.loc[bounded, c], full.loc[bounded, c], rtol=1e-9,
                                   atol=1e-12, err_msg=c)
    for c in SLIP:
        np.testing.assert_allclose(early[c], full[c], rtol=1e-9, atol=1e-12, err_msg=c)
    for c in ("max_rotation", "time_uplift", "time_overturn", "time_end", "impacts", "theta_end"):
        np.testing.assert_allclose(early.loc[rest, c], full.loc[rest, c], rtol=1e-9, atol=1e-11,
                                   err_msg=c)
    assert bounded.sum() > 30 and (early["nfev"] < full["nfev"]).sum() > 60


def test_peak_times_match_quadrature():
    """peak_times against the integral of dtheta / |theta'| of free rocking, through an impact."""
    from scipy.integrate import quad
    alpha, p, e = 0.3, 2.5, 0.8

    def swing(E, u0, u1):
        """Time from u0 to u1 (0 <= u < alpha, same direction) at energy E (units g R)."""
        f = lambda u: 1.0 / (p * math.sqrt(max(2 * (E + math.cos(alpha) - math.cos(alpha - u)),
                                                 1e-300)))
        # the 1/sqrt singularity at the peak: quad reaches about 1e-9
        return quad(f, min(u0, u1), max(u0, u1), epsabs=0, epsrel=1e-10, limit=400)[0]

    def u_peak(E):
        return alpha - math.acos(math.cos(alpha) + E)

    for theta, w in [(0.05, 0.6), (0.1, -0.4), (0.0, -0.5), (0.2, 0.05), (0.12, 0.0)]:
        E = 0.5 * w * w / p ** 2 + math.cos(alpha - theta) - math.cos(alpha)
        if w > 0:
            t1 = swing(E, theta, u_peak(E))
            e1 = E
        else:
            e1 = e * e * E
            t1 = swing(E, theta, 0.0) + swing(e1, 0.0, u_peak(e1))
        t2 = t1 + swing(e1, u_peak(e1), 0.0) + swing(e * e * e1, 0.0, u_peak(e * e * e1))
        for s in (1, -1):
            r1, r2 = K.peak_times(s * theta, s * w, s, alpha, p, e)
            assert r1 == pytest.approx(t1, rel=1e-7, abs=1e-12), (theta, w)
            assert r2 == pytest.approx(t2, rel=1e-7), (theta, w)
