"""Stiff, damped springs under the foundation models: ``Solver(method="auto")``
turns to Rodas4 (kernels/rodas.py) and gives DP5's answers at a fraction
of the steps.  Oracle: DP5 (``method="RK45"``) at tight tolerance, and the
converged values of both methods."""
import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.model.foundation import SwitchingFoundation, TwoSpringFoundation

MASS = 10.0


def _slender():
    # foundation:2027 fuzz scenes: b/h ~ 0.011, springs 82 times the block's p, zeta 0.17
    body = fr.RigidBlock.rectangle(b=0.0078, h=0.70)
    return body, TwoSpringFoundation.from_vibration(body, omega=82 * body.p, zeta=0.17, mass=MASS)


def _pulse(body, ratio, freq=3.0):
    return fr.Pulse(amplitude=ratio, amplitude_unit="g_tan_alpha", frequency=freq * body.p / (2 * math.pi))


def _run(body, fnd, pulse, t_after=0.5, **solver):
    return fr.simulate(body, pulse, foundation=fnd, mass=MASS, solver=fr.Solver(**solver), t_after=t_after,
                       history_capacity=10)


@pytest.mark.parametrize("ratio", [0.5, 1.05, 1.3, 3.0])
def test_two_spring_stiff_runs_agree_with_dp5(ratio):
    """Same status and impacts; max rotation and uplift time within what
    DP5 itself moves between rtol 1e-8 and 1e-11; at least 50 times fewer
    steps."""
    body, fnd = _slender()
    p = _pulse(body, ratio)
    dp = _run(body, fnd, p, rtol=1e-11, method="RK45")
    dp8 = _run(body, fnd, p, rtol=1e-8, method="RK45")
    au = _run(body, fnd, p, rtol=1e-8)
    assert au.status == dp.status == dp8.status
    assert au.metrics["impacts"] == dp.metrics["impacts"]
    spread = abs(dp8.metrics["max_rotation"] - dp.metrics["max_rotation"])
    assert abs(au.metrics["max_rotation"] - dp.metrics["max_rotation"]) <= max(spread, 1e-6 * dp.metrics["max_rotation"])
    if not math.isnan(dp.metrics["time_uplift"]):
        t_spread = abs(dp8.metrics["time_uplift"] - dp.metrics["time_uplift"])
        assert abs(au.metrics["time_uplift"] - dp.metrics["time_uplift"]) <= max(t_spread, 1e-6)
    assert au.metrics["steps"] * 50 < dp8.metrics["steps"]


def test_rodas4_converges_to_the_dp5_answer():
    """Both methods converge to one uplift time and max rotation: at rtol
    1e-12 they agree to 1e-8 and 1e-9 relative.  (Rodas4 locates events on
    a dense output of order 3, whose error goes as rtol^(4/5), 4e-10 here.)"""
    body, fnd = _slender()
    p = _pulse(body, 1.05)
    dp = _run(body, fnd, p, rtol=1e-12, method="RK45")
    ro = _run(body, fnd, p, rtol=1e-12, method="Rodas4")
    assert ro.status == dp.status
    assert ro.metrics["time_uplift"] == pytest.approx(dp.metrics["time_uplift"], rel=1e-8)
    assert ro.metrics["max_rotation"] == pytest.approx(dp.metrics["max_rotation"], rel=1e-9)
    errs = [abs(_run(body, fnd, p, rtol=r, method="Rodas4").metrics["time_uplift"] - dp.metrics["time_uplift"])
            for r in (1e-6, 1e-8, 1e-10)]
    assert errs[0] > errs[1] > errs[2]


def test_a_run_past_the_dp5_step_budget_ends_definite():
    """The budget of a 10-s full run, which DP5 exhausts in rocking on the
    dashpots' stability limit, is plenty for the switch."""
    body, fnd = _slender()
    p = _pulse(body, 1.3)
    with pytest.warns(RuntimeWarning):
        dp = _run(body, fnd, p, t_after=10.0, method="RK45", max_steps=200_000)
    assert dp.status == "failed:step-budget"
    au = _run(body, fnd, p, t_after=10.0, max_steps=200_000)
    assert not au.status.startswith("failed")
    assert au.metrics["steps"] < 20_000


def test_a_fixed_step_unstable_for_dp5_is_taken_by_rodas4():
    """dt = 2 ms is 100 times the dashpots' DP5 limit: "RK45" fails as
    unstable, "auto" finishes and agrees with the adaptive run."""
    body, fnd = _slender()
    p = _pulse(body, 1.3)
    with pytest.warns(RuntimeWarning):
        dp = _run(body, fnd, p, dt=2e-3, method="RK45")
    assert dp.status == "failed:unstable-step"
    au = _run(body, fnd, p, dt=2e-4)
    ref = _run(body, fnd, p, rtol=1e-10)
    assert au.status == ref.status
    assert au.metrics["max_rotation"] == pytest.approx(ref.metrics["max_rotation"], rel=1e-3)


@pytest.mark.parametrize("foundation", ["switching", "wall", "friction"])
def test_other_foundation_models_switch_and_agree(foundation):
    """The switching model, a wall beside the two-spring model and sliding
    on it: same status as DP5 at rtol 1e-10 and max rotation within 1e-5
    relative, in fewer steps."""
    body, fnd = _slender()
    kw = {}
    if foundation == "switching":
        fnd = SwitchingFoundation.from_vibration(body, omega=82 * body.p, zeta=0.17, mass=MASS)
    elif foundation == "wall":
        kw["wall"] = fr.Wall(gap=0.02)
    else:
        kw["friction"] = fr.Friction(0.8)
    p = _pulse(body, 1.3)

    def run(**solver):
        return fr.simulate(body, p, foundation=fnd, mass=MASS, solver=fr.Solver(**solver), t_after=0.5,
                           history_capacity=10, **kw)
    dp = run(rtol=1e-10, method="RK45")
    au = run(rtol=1e-8)
    assert au.status == dp.status
    assert au.metrics["max_rotation"] == pytest.approx(dp.metrics["max_rotation"], rel=1e-5)
    assert au.metrics["steps"] < dp.metrics["steps"]


def test_method_rodas4_is_refused_where_no_model_has_it():
    body = fr.RigidBlock.rectangle(b=0.2, h=1.0)
    with pytest.raises(ValueError, match="method='Rodas4'.*foundation"):
        fr.simulate(body, _pulse(body, 2.0), solver=fr.Solver(method="Rodas4"))
    with pytest.raises(ValueError, match="method must be one of"):
        fr.Solver(method="rodas")


def test_method_in_a_scene_file(tmp_path):
    from fastrock.running.scene import Scene
    f = tmp_path / "s.toml"
    f.write_text('[body]\ntype = "rigid"\nalpha = 0.25\np = 2.0\n[excitation]\ntype = "pulse"\namplitude = 0.5\n'
                 '[solver]\nmethod = "RK45"\n')
    assert Scene.from_toml(f).solver.method == "RK45"


def test_the_spectrum_of_a_stiff_foundation_keeps_its_outcomes():
    """A 4 x 3 overturning spectrum: "auto" against "RK45" at rtol 1e-10,
    cell by cell."""
    body, fnd = _slender()
    kw = dict(amplitude_ratios=np.array([0.9, 1.2, 2.0, 4.0]), frequency_ratios=np.array([2.0, 4.0, 8.0]),
              foundation=fnd, mass=MASS, progress=False)
    a = fr.overturning_spectrum(body, **kw)
    b = fr.overturning_spectrum(body, solver=fr.Solver(rtol=1e-10, method="RK45"), **kw)
    assert list(a["outcome"]) == list(b["outcome"])


def _grazing_lift_off():
    # foundation:2027:109: a slender block (b/h = 0.0127) on springs with a 2e-8 m static deflection
    body = fr.RigidBlock.rectangle(b=0.0007735112837389468, h=0.060891575164387146)
    fnd = TwoSpringFoundation(k_v=24480071658.761642, c_v=15651222.071522184)
    pulse = fr.Pulse(32.06156336303051, 0.144828332337818, 1, "half-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    return body, fnd, pulse, 57.131286380556205


def test_the_springs_tolerances_resolve_the_corner_forces():
    """y_c and y_c' have absolute tolerances, with no relative part, that
    resolve k_v y_c and c_v y_c' to rtol M g; the rotation keeps atol and
    rtol."""
    from fastrock.kernels import foundation as F
    from fastrock.kernels import layout as L
    body, fnd, _p, mass = _grazing_lift_off()
    par = np.zeros(L.N_PAR_FOUNDATION)
    par[F.P_MASS], par[F.P_G], par[F.P_KV], par[F.P_CV] = mass, 9.80665, fnd.k_v, fnd.c_v
    opt = fr.Solver(rtol=1e-7).options(1.0, False)
    atol, rtol = F.spring_tol(opt, par, 4)
    Mg = mass * 9.80665
    assert fnd.k_v * atol[0] == pytest.approx(1e-7 * Mg)
    assert fnd.c_v * atol[1] == pytest.approx(1e-7 * Mg)        # c_v > sqrt(k_v M) here
    assert list(atol[2:]) == [1e-9, 1e-9]
    assert list(rtol) == [0.0, 0.0, 1e-7, 1e-7]
    par[F.P_KV], par[F.P_CV] = 1e3, 0.0                         # soft springs: atol itself
    assert list(F.spring_tol(opt, par, 4)[0]) == [1e-9] * 4


def test_a_grazing_lift_off_does_not_chatter():
    """At rtol 1.6e-7 the pivot corner's force of foundation:2027:109 grazes
    0 while the block falls (theta = 70 alpha).  With atol in m the corner
    touched and left again at every step, 1e-11 s apart, until the step
    budget ran out; now every method lifts off once and overturns at one
    time.  (foundation_wall:2027:356 was the same with rtol |y_c| in place
    of atol: a tall block whose y_c carries 0.24 m of rocking.)"""
    body, fnd, pulse, mass = _grazing_lift_off()
    runs = {m: fr.simulate(body, pulse, foundation=fnd, mass=mass, t_after=10.0, history_capacity=10,
                           solver=fr.Solver(rtol=1.5869936196274667e-07, method=m, max_steps=100_000))
            for m in ("auto", "RK45", "Rodas4")}
    for m, r in runs.items():
        assert r.status == "overturn:mode2", m
        assert (r.events.event == "flight").sum() == 1, m
        assert r.metrics["time_overturn"] == pytest.approx(runs["RK45"].metrics["time_overturn"], abs=1e-6), m
    assert runs["auto"].metrics["steps"] < runs["RK45"].metrics["steps"]


def test_a_free_corner_recontacts_above_the_force_resolution():
    """foundation:2027:139: a slender block (b = 0.95 mm, h = 66 mm) on soft springs (omega/p =
    7.4) falls after a half-sine and its pivot corner's force grazes 0.  Under Rodas4 the corner
    touched and left again on forces of 1e-10 N, far below what rtol resolves (rtol M g = 0.02
    N), until the step budget ran out.  A free corner now re-contacts once its force law exceeds
    rtol M g: auto and Rodas4 end as RK45 does (overturn after an impact) at one time, to within
    what rtol = 5e-5 resolves."""
    body = fr.RigidBlock.rectangle(b=0.0009524630670977434, h=0.06639314409713372)
    mass = 39.281005756320994
    fnd = TwoSpringFoundation.from_vibration(body, omega=7.437711715558029 * body.p, zeta=0.14510287272202993,
                                             mass=mass)
    pulse = fr.Pulse(3.066030509802924, 0.1062380066164248, 1, "half-sine", amplitude_unit="g_tan_alpha",
                     frequency_unit="omega_p/p")
    runs = {m: fr.simulate(body, pulse, foundation=fnd, mass=mass, t_after=10.0, history_capacity=10,
                           solver=fr.Solver(rtol=5.00790021535665e-05, method=m, max_steps=200_000))
            for m in ("auto", "RK45", "Rodas4")}
    for m, r in runs.items():
        assert r.status == "overturn:mode1", m
        assert (r.events.event == "flight").sum() <= 2, m
        assert r.metrics["time_overturn"] == pytest.approx(runs["RK45"].metrics["time_overturn"], abs=1e-5), m
