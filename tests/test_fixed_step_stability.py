"""Fixed-step runs that diverge end as failed:unstable-step, never as physics
(issue #18, item 1).  The check is the embedded Dormand-Prince error of each
fixed step relative to the motion's scale (kernels/dopri.fixed_step_error)."""
import warnings

import numpy as np
import pytest

from fastrock import FlexibleBody, RigidBlock, overturning_spectrum, simulate
from fastrock.kernels.dopri import A, B, E
from fastrock.kernels.hybrid import ERR_FIXED_MAX


def _stability_and_error(z):
    """|R(z)| of the DP5 step and |embedded error| for y' = lambda y, z = h lambda."""
    K = []
    for s in range(6):
        K.append(z * (1 + sum(A[s][j] * K[j] for j in range(s))))
    y5 = 1 + sum(B[j] * K[j] for j in range(6))
    K.append(z * y5)
    return abs(y5), abs(sum(E[j] * K[j] for j in range(7)))


def test_threshold_sits_where_undamped_modes_start_to_grow():
    # below the threshold an undamped mode grows by at most 0.6 % a step: any mode
    # the threshold lets through on the imaginary axis is (nearly) neutral
    ys = np.linspace(0.01, 4.0, 400)
    for y in ys:
        amp, err = _stability_and_error(1j * y)
        if err <= ERR_FIXED_MAX:
            assert amp < 1.006
    # and the real-axis limit (|R(-3.3)| ~ 1) is far beyond it
    amp, err = _stability_and_error(-3.3)
    assert err > 50 * ERR_FIXED_MAX


def test_issue_case_flexible_one_cosine_is_failed_not_overturn():
    body = FlexibleBody(0.04664, 0.84498, 9.0618)
    with pytest.warns(RuntimeWarning, match=r"unstable-step.*dt <= ([0-9.e-]+) s would be stable"):
        df = overturning_spectrum(body, [3.98138], [7.89409], sign=1, pulse="one-cosine", dt=0.02612,
                                  progress=False)
    assert df["status"].tolist() == ["failed:unstable-step"]
    adaptive = overturning_spectrum(body, [3.98138], [7.89409], sign=1, pulse="one-cosine", progress=False)
    assert adaptive["status"].tolist() == ["safe:moving"]
    # the suggested step gives the adaptive answer
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        overturning_spectrum(body, [3.98138], [7.89409], sign=1, pulse="one-cosine", dt=0.02612,
                             progress=False)
    dt_ok = float(str(rec[0].message).split("dt <= ")[1].split(" s")[0])
    small = overturning_spectrum(body, [3.98138], [7.89409], sign=1, pulse="one-cosine", dt=dt_ok,
                                 progress=False)
    assert small["status"].tolist() == ["safe:moving"]
    assert small["max_rotation_ratio"][0] == pytest.approx(adaptive["max_rotation_ratio"][0], rel=1e-3)


def test_pivot_switch_divergence_is_failed():
    body = FlexibleBody(alpha=0.0789, p=3.76, omega_n_over_p=23.1, zeta=0, impact="pivot-switch", e=0.564)
    with pytest.warns(RuntimeWarning, match="unstable-step"):
        df = overturning_spectrum(body, [4.46], [0.766], sign="both", pulse="one-sine", dt=0.0023,
                                  progress=False)
    assert set(df["status"]) == {"failed:unstable-step"}
    assert np.isfinite(df[["max_rotation", "theta_end", "theta_dot_end"]].to_numpy()).all()


def test_simulate_reports_unstable_step_with_a_stable_dt():
    body = FlexibleBody(0.04664, 0.84498, 9.0618)
    from fastrock import Pulse
    pulse = Pulse(3.98138 * 9.80665 * np.tan(0.04664), 7.89409 * 0.84498 / (2 * np.pi), kind="one-cosine",
                  amplitude_unit="m/s2")
    with pytest.warns(RuntimeWarning, match="would be stable"):
        r = simulate(body, pulse, dt=0.02612)
    assert r.status == "failed:unstable-step"
    assert np.isfinite(r.history[["theta", "theta_dot", "u"]].to_numpy()).all()


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_random_fixed_step_rows_give_the_adaptive_outcome_or_fail(seed):
    """Random flexible bodies, pulses and fixed steps: a fixed-step row either
    fails as unstable or gives the adaptive solver's outcome, and an overturn
    is always reached by a finite motion."""
    rng = np.random.default_rng(seed)
    n_checked = n_failed = 0
    for _ in range(6):
        body = FlexibleBody(rng.uniform(0.03, 0.4), rng.uniform(0.7, 5), rng.uniform(2, 30),
                            zeta=float(rng.choice([0.0, 0.02])))
        amps = rng.uniform(0.5, 6, 3)
        freqs = rng.uniform(0.5, 10, 3)
        dt = 10 ** rng.uniform(-3, -1.3)
        pulse = str(rng.choice(["one-sine", "one-cosine"]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            fixed = overturning_spectrum(body, amps, freqs, sign="both", pulse=pulse, dt=dt, progress=False)
        adaptive = overturning_spectrum(body, amps, freqs, sign="both", pulse=pulse, progress=False)
        failed = fixed["status"] == "failed:unstable-step"
        n_failed += int(failed.sum())
        n_checked += int((~failed).sum())
        same = fixed["outcome"][~failed].to_numpy() == adaptive["outcome"][~failed].to_numpy()
        assert same.all(), fixed[~failed][~same]
        over = fixed["outcome"].isin(["mode1", "mode2"])
        assert np.isfinite(fixed.loc[over, ["max_rotation", "theta_dot_end"]].to_numpy()).all()
        assert (fixed.loc[over, "theta_end"].abs() < np.pi).all()
    assert n_checked > 0 and n_failed > 0   # the sample holds both kinds


def test_rigid_fixed_step_is_not_flagged():
    # the rigid block's only time scale is 1/p: ordinary fixed steps pass
    df = overturning_spectrum(RigidBlock(0.25, 2.0), np.linspace(1, 6, 6), np.linspace(0.5, 8, 6),
                              sign="both", dt=0.01, progress=False)
    assert not (df["outcome"] == "failed").any()


def test_simulate_names_a_step_it_checked():
    """friction:2027:280 (bench/fuzz.py): a fixed step of 2 pi/omega_max/96 diverges in a 23.5 g tan(alpha)
    half-sine, and the local-error estimate's step (2.25e-3 s) diverges as well. simulate() runs the case
    again from that estimate, halving, and names the step at which it ends definite; at that step it
    does."""
    import re
    import warnings
    from fastrock import Friction, Pulse, RigidBlock
    body = RigidBlock.rectangle(b=6.569492515789904, h=18.01853645912481, e=0.7473255108407602)
    pulse = Pulse(23.531351370140506, 9.708941270170655, 1, "half-sine", amplitude_unit="g_tan_alpha",
                  frequency_unit="omega_p/p")
    friction = Friction(1.620827675325542)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        r = simulate(body, pulse, friction=friction, dt=0.0108624)
    assert r.status == "failed:unstable-step"
    msg = " ".join(str(w.message) for w in rec)
    named = re.findall(r"dt <= ([0-9.eE+-]+) s would be stable \(checked: at that step this run ends ([a-z:0-9-]+)\)",
                       msg)
    assert len(named) == 1
    dt_ok, status = float(named[0][0]), named[0][1]
    assert dt_ok < 0.0108624 / 2
    again = simulate(body, pulse, friction=friction, dt=dt_ok)
    assert again.status == status and not status.startswith("failed")


def test_foundation_runs_name_a_checked_step_too():
    """simulate(..., foundation=...) warns like the other families (it had no warning), with DP5
    pinned: the default method takes a step at which DP5 is unstable with Rodas4
    (tests/test_foundation_stiff.py)."""
    import re
    import warnings
    from fastrock import Pulse, RigidBlock, Solver, TwoSpringFoundation
    block = RigidBlock.rectangle(0.2, 1.0)
    foundation = TwoSpringFoundation.from_vibration(block, 60.0)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        r = simulate(block, Pulse(1.5, 2.0), foundation=foundation,
                     solver=Solver(dt=0.02, method="RK45"))
    assert r.status == "failed:unstable-step"
    named = re.findall(r"dt <= ([0-9.eE+-]+) s would be stable \(checked: at that step this run ends ([a-z:0-9-]+)\)",
                       " ".join(str(w.message) for w in rec))
    assert len(named) == 1
    again = simulate(block, Pulse(1.5, 2.0), foundation=foundation,
                     solver=Solver(dt=float(named[0][0]), method="RK45"))
    assert again.status == named[0][1] and not again.status.startswith("failed")


def test_checked_step_gives_a_small_step_the_budget_it_needs():
    """checked_stable_step with a stand-in run: it starts from the kernels' estimate, halves while
    the run diverges, and a step that needs more fixed steps than the budget runs with the budget a
    user would give it (named in the warning)."""
    from fastrock.kernels import layout as L
    from fastrock.running.outcomes import checked_stable_step
    from hardcases import stand_in_check

    def outcome(o, tried):
        met = np.zeros(L.N_MET)
        met[L.M_DT_STABLE] = np.nan
        code = L.SAFE_REST if o[L.O_DT_FIXED] < 4e-6 and 10.0 / o[L.O_DT_FIXED] <= o[L.O_MAX_STEPS] \
            else L.FAIL_UNSTABLE
        return code, met

    run, opt, tried = stand_in_check(10.0, 2e6, 1e-4, outcome)
    step, status, budget = checked_stable_step(run, opt, 1e-4, 2e-5)
    assert [t[0] for t in tried] == [2e-5, 1e-5, 5e-6, 2.5e-6]
    assert step == 2.5e-6 and status == "safe:rest"
    assert budget == int(1.05 * 10.0 / 2.5e-6) + 1000 and tried[-1][1] == budget
    assert tried[0][1] == 2e6                                  # 5e5 steps fit the budget as it was
    assert checked_stable_step(lambda o: (L.FAIL_UNSTABLE, np.full(L.N_MET, np.nan)), opt, 1e-4, 2e-5)[0] is None
