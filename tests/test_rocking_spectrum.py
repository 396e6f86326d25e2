"""Records in simulations and the rocking spectrum (beta against Tp/Tm)."""
from __future__ import annotations

import importlib
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fastrock import Pulse, RigidBlock, SampledMotion, simulate
from fastrock.constants import G_STANDARD
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.default_records import load_default_record
from fastrock.io.readers import read_record
# the module (``fastrock.rocking_spectrum`` may also name the function once
# the package exports it; import_module always returns the module)
RS = importlib.import_module("fastrock.analyses.rocking_spectrum.inputs")
RS_ENGINE = importlib.import_module("fastrock.analyses.rocking_spectrum.engine")
from fastrock.analyses.rocking_spectrum.engine import (DEFAULT_HALF_WIDTHS, DEFAULT_SLENDERNESS,
    rocking_spectrum_runs)
from fastrock.analyses.rocking_spectrum.definitions import (SPECTRUM_COLUMNS,
    minimum_stable_on_grid, rocking_spectrum, summarize_runs, upper_bound_beta)
from fastrock.analyses.rocking_spectrum.bisection import minimum_stable_slenderness
from fastrock.plotting.rocking_spectrum import plot_rocking_spectrum
from fastrock.analyses.rocking_spectrum.single_runs import simulate_record


from shared_data import records_dir

RECORDS = records_dir()
needs_records = pytest.mark.skipif(
    not RECORDS.is_dir(),
    reason=f"shared record folder {RECORDS} absent (set FASTROCK_RECORDS_DIR)",
)
TABLE_COLUMNS = [line.split()[0] for line in SPECTRUM_COLUMNS.splitlines()
                 if line.strip() and not line.startswith("n_stable")]
TABLE_COLUMNS += ["n_stable", "n_overturned", "n_leaning", "n_failed"]


@pytest.fixture(scope="module")
def el_centro():
    return load_default_record()


# -------------------------------------------------- a record made of one pulse
def _sampled_sine(pulse, body, n):
    """The one-sine pulse sampled with n intervals per period (exact at the
    samples, linearly interpolated between them by the kernel)."""
    ap = pulse.amplitude_si(body)
    w = pulse.omega_si(body)
    dt = 2 * math.pi / w / n
    t = np.arange(n + 1) * dt
    a = pulse.sign * ap * np.sin(w * t)
    a[-1] = 0.0
    return SampledMotion(a, dt), w * dt


# (a_p/(g tan alpha), omega_p/p, sign): three that rock and stay up, overturning
# in mode 1 and in mode 2 -- all away from the boundaries of the spectrum.
PULSE_CASES = [(1.5, 4.0, 1), (3.0, 6.0, -1), (6.0, 8.0, 1), (5.0, 4.0, -1), (1.5, 3.0, 1),
               (2.0, 1.0, 1), (4.0, 1.0, -1), (3.0, 2.0, 1)]


@pytest.mark.parametrize("amp,freq,sign", PULSE_CASES)
def test_sampled_sine_pulse_matches_analytic_pulse(amp, freq, sign):
    """Linear interpolation of sin at n points per period errs by at most
    a_p (omega dt)^2 / 8 (the dt^2 f''/8 bound); the response is smooth in
    the forcing away from the spectrum's boundaries, so the relative error of
    max|theta| (or of the overturning time) is a small multiple of
    (omega dt)^2/8.  A factor 10 leaves room for that multiple (observed
    0.7 to 2.9) while a first-order error (a breakpoint lost) would be 100x
    larger at n = 2000."""
    body = RigidBlock(alpha=0.2, p=2.0)
    pulse = Pulse(amp, freq, sign=sign, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    ref = simulate(body, pulse, rtol=1e-10, early_exit=True)
    sampled, wdt = _sampled_sine(pulse, body, 2000)
    rec = simulate(body, sampled, rtol=1e-10, early_exit=True)
    bound = wdt ** 2 / 8
    assert rec.outcome == ref.outcome
    if ref.outcome == "safe":
        key = "max_rotation_ratio"
    else:
        key = "time_overturn"
        assert rec.metrics["impacts"] == ref.metrics["impacts"]
    rel = abs(rec.metrics[key] / ref.metrics[key] - 1.0)
    assert rel <= 10 * bound, (key, rel, bound)


def test_sampled_pulse_error_is_second_order():
    body = RigidBlock(alpha=0.2, p=2.0)
    pulse = Pulse(1.5, 4.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    r = simulate(body, pulse, rtol=1e-11, early_exit=True)
    assert r.outcome == "safe" and r.metrics["max_rotation_ratio"] > 0.3
    ref = r.metrics["max_rotation_ratio"]
    errs = []
    for n in (200, 2000):
        sm, _ = _sampled_sine(pulse, body, n)
        got = simulate(body, sm, rtol=1e-11, early_exit=True).metrics["max_rotation_ratio"]
        errs.append(abs(got - ref))
    assert 50 < errs[0] / errs[1] < 200        # 10x finer sampling: ~100x smaller error


# ----------------------------------------------------- record breakpoints
def test_record_breakpoints_same_outcome_fewer_rejections_better_accuracy(el_centro):
    """Measured first (rtol 1e-6, 20 s of El Centro): with breakpoints RK45
    never straddles a kink of the interpolated record -- 0 rejected steps
    instead of ~1200, half the evaluations, and max|theta| 1e4x closer to a
    tight reference.  Asserted with wide margins."""
    for b, h in [(0.3, 1.5), (0.25, 1.25), (0.5, 2.5)]:
        body = RigidBlock.rectangle(b, h)
        ref = simulate(body, el_centro, rtol=1e-13, atol=1e-15, duration=20.0)
        on = simulate(body, el_centro, rtol=1e-6, duration=20.0, record_breakpoints=True)
        off = simulate(body, el_centro, rtol=1e-6, duration=20.0, record_breakpoints=False)
        assert on.outcome == off.outcome == ref.outcome == "safe"
        assert on.metrics["rejected_steps"] * 10 < off.metrics["rejected_steps"]
        assert on.metrics["nfev"] < off.metrics["nfev"]
        m_ref = ref.metrics["max_rotation_ratio"]
        err_on = abs(on.metrics["max_rotation_ratio"] - m_ref)
        err_off = abs(off.metrics["max_rotation_ratio"] - m_ref)
        assert err_on * 100 < err_off


def test_record_breakpoints_same_outcomes_over_a_grid(el_centro):
    s = np.linspace(0.1, 0.3, 6)
    b = [0.15, 0.4]
    on = rocking_spectrum_runs(el_centro, s, b, walls=(None,), progress=False)
    off = rocking_spectrum_runs(el_centro, s, b, walls=(None,), progress=False,
                                record_breakpoints=False)
    assert (on["outcome"] == off["outcome"]).all()
    assert on["rejected_steps"].sum() < off["rejected_steps"].sum()


# ----------------------------------------------------- fixed step = record dt
def _same(a, b):
    """Equal metric dicts, NaN equal to NaN."""
    return a.keys() == b.keys() and all(
        a[k] == b[k] or (isinstance(a[k], float) and math.isnan(a[k]) and math.isnan(b[k]))
        for k in a)


def test_simulate_record_fixed_step_follows_record_dt(el_centro):
    body = RigidBlock.rectangle(0.3, 1.5)
    r = simulate_record(body, el_centro, fixed_step=True, duration=20.0)
    same = simulate(body, el_centro, dt=el_centro.dt, duration=20.0)
    assert _same(r.metrics, same.metrics)
    # Between samples the record is linear, so DP5 steps of one sample
    # interval are very accurate: compare with a tight adaptive reference.
    ref = simulate(body, el_centro, rtol=1e-13, atol=1e-15, duration=20.0)
    assert r.outcome == ref.outcome
    assert r.metrics["max_rotation_ratio"] == pytest.approx(ref.metrics["max_rotation_ratio"],
                                                            rel=1e-6)
    half = simulate_record(body, el_centro, fixed_step=True, substeps=2, duration=5.0)
    h = half.history
    rocking = ((h["contact"] == "rock").to_numpy()[:-1] & (h["contact"] == "rock").to_numpy()[1:])
    steps = np.diff(h["t"].to_numpy())[rocking]
    assert steps.size > 50 and steps.max() <= el_centro.dt / 2 * (1 + 1e-9)
    with pytest.raises(ValueError, match="fixed_step"):
        simulate_record(body, el_centro, fixed_step=True, dt=0.001)
    with pytest.raises(ValueError, match="substeps"):
        simulate_record(body, el_centro, fixed_step=True, substeps=0)


def test_simulate_record_adaptive_equals_simulate(el_centro):
    body = RigidBlock.rectangle(0.3, 1.5)
    assert _same(simulate_record(body, el_centro).metrics, simulate(body, el_centro).metrics)


# ----------------------------------------------------- definitions on a grid
@pytest.mark.parametrize("stable,index,bound,non_monotone,first", [
    ([True, True, True, True], 0, "upper", False, 0),
    ([False, False, False], 2, "lower", False, -1),
    ([False, False, True, True], 2, "exact", False, 2),
    ([True, False, True, True], 2, "exact", True, 0),
    ([False, True, False, True], 3, "exact", True, 1),
    ([True, False], 1, "lower", True, 0),
    ([False, True, True, False, True], 4, "exact", True, 1),
    ([True], 0, "upper", False, 0),
    ([False], 0, "lower", False, -1),
])
def test_minimum_stable_on_grid(stable, index, bound, non_monotone, first):
    thr = minimum_stable_on_grid(stable)
    assert (thr.index, thr.bound, thr.non_monotone, thr.first_stable) == \
        (index, bound, non_monotone, first)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.booleans(), min_size=1, max_size=30))
def test_minimum_stable_on_grid_properties(stable):
    thr = minimum_stable_on_grid(stable)
    s = np.array(stable)
    if thr.bound != "lower":
        assert s[thr.index:].all()                 # stable from there up
    if thr.bound == "exact":
        assert not s[thr.index - 1]                # ... and not one point lower
    if thr.bound == "upper":
        assert s.all() and thr.index == 0
    if thr.bound == "lower":
        assert not s[-1] and thr.index == s.size - 1
    # non-monotone: a stable point below an unstable one
    brute = any(s[i] and not s[j] for i in range(s.size) for j in range(i + 1, s.size))
    assert thr.non_monotone == brute
    assert thr.first_stable == (int(np.argmax(s)) if s.any() else -1)


def _synthetic_runs(pattern, s, b=0.5, pga_g=0.4, Tm=0.5):
    out = ["safe" if c == "." else "leaning" if c == "L" else "mode1" for c in pattern]
    return pd.DataFrame({
        "record": "synthetic", "wall": "two-sided", "wall_gap": np.nan, "pga_g": pga_g,
        "mean_period": Tm, "b": b, "slenderness": s, "outcome": out,
        "stable": [o == "safe" for o in out]})


@pytest.mark.parametrize("pattern,bound,non_monotone,k,first", [
    ("XX....", "exact", False, 2, 2),
    ("X.X...", "exact", True, 3, 1),
    ("......", "upper", False, 0, 0),
    ("..XX.X", "lower", True, 5, 0),
    ("XXLL..", "exact", False, 4, 4),        # leaning is not stable by default
])
def test_summarize_synthetic_outcome_grid(pattern, bound, non_monotone, k, first):
    s = np.linspace(0.1, 0.35, len(pattern))
    rng = np.random.default_rng(1)
    runs = _synthetic_runs(pattern, s).iloc[rng.permutation(len(pattern))]  # order-free
    row = summarize_runs(runs).iloc[0]
    assert row["beta_bound"] == bound
    assert row["non_monotone"] == non_monotone
    assert row["slenderness_min"] == pytest.approx(s[k])
    assert row["slenderness_first_stable"] == pytest.approx(s[first])
    assert row["beta"] == pytest.approx(s[k] / 0.4)
    assert row["h_min"] == pytest.approx(0.5 / s[k])
    body = RigidBlock.rectangle(0.5, 0.5 / s[k])
    assert row["Tp"] == pytest.approx(2 * math.pi / body.p)
    assert row["tp_over_tm"] == pytest.approx(row["Tp"] / 0.5)
    assert row["n_overturned"] == pattern.count("X")
    assert row["n_leaning"] == pattern.count("L")
    assert row["n_stable"] == pattern.count(".")


@pytest.mark.parametrize("amp,freq", [(1.55, 1.1), (2.9, 2.3)])
@pytest.mark.parametrize("sign", [1, -1])
def test_early_exit_guard(amp, freq, sign):
    """Blocks past alpha when the excitation ends: the early "safe:bounded"
    decision once misfired here (fixed in the kernel, commit 4e2366c), and
    the study also reruns such rows to the end, so its outcome equals the
    full run's."""
    body = RigidBlock(alpha=0.2, p=2.0)
    R = 3 * body.g / (4 * body.p ** 2)
    b, h = R * math.sin(body.alpha), R * math.cos(body.alpha)
    pulse = Pulse(amp, freq, sign=sign, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    sampled, _ = _sampled_sine(pulse, body, 2000)
    rec = GroundMotion(sampled.acc, sampled.dt, name="pulse")
    fast = rocking_spectrum_runs(rec, [b / h], [b], walls=(None,), progress=False)
    full = rocking_spectrum_runs(rec, [b / h], [b], walls=(None,), progress=False,
                                 early_exit=False)
    assert fast["outcome"][0] == full["outcome"][0] == "mode2"


def test_summarize_incomplete_cells():
    runs = _synthetic_runs("XX....", np.linspace(0.1, 0.35, 6))
    runs.loc[3, "outcome"] = "unfinished"
    runs.loc[3, "stable"] = False
    row = summarize_runs(runs).iloc[0]
    assert row["beta_bound"] == "incomplete"
    assert math.isnan(row["beta"])


def test_interrupted_sweep_marks_cells_incomplete(monkeypatch, el_centro):
    real = RS_ENGINE.run_sweep

    def half(kernel, Y0, *a, **kw):
        status, MET, YF, done = real(kernel, Y0, *a, **kw)
        return status, MET, YF, Y0.shape[0] // 2

    monkeypatch.setattr(RS_ENGINE, "run_sweep", half)
    table = rocking_spectrum(el_centro, [0.1, 0.2, 0.3], [0.2, 0.5], walls=(None,),
                             progress=False)
    assert table.attrs["interrupted"]
    assert (table["beta_bound"] == "incomplete").any()
    assert table.loc[table["beta_bound"] == "incomplete", "beta"].isna().all()


def test_upper_bound_curve():
    assert upper_bound_beta(0.0) == pytest.approx(1.35)
    np.testing.assert_allclose(upper_bound_beta([5.0, 10.0]),
                               1.35 * np.exp(-0.12 * np.array([5.0, 10.0])))


# ----------------------------------------------------- the study on records
@pytest.fixture(scope="module")
def two_records():
    if not RECORDS.is_dir():
        pytest.skip(f"shared record folder {RECORDS} absent (set FASTROCK_RECORDS_DIR)")
    return [read_record(RECORDS / "elCentro.AT2"),
            read_record(RECORDS / "Northridge_Sylmar_County.dat", unit="m/s2")]


@pytest.fixture(scope="module")
def small_study(two_records):
    s = np.linspace(0.1, 0.5, 8)
    b = np.array([0.15, 0.4, 0.9])
    return rocking_spectrum(two_records, s, b, walls=(None,), progress=False, return_runs=True)


@needs_records
def test_rocking_spectrum_table_shape_and_columns(small_study, two_records):
    table, runs = small_study
    assert list(table.columns) == TABLE_COLUMNS
    assert len(table) == 2 * 1 * 3
    assert len(runs) == 2 * 3 * 8
    assert set(table["record"]) == {"elCentro", "Northridge_Sylmar_County"}
    assert (table["wall"] == "two-sided").all() and table["wall_gap"].isna().all()
    assert set(table["beta_bound"]) <= {"exact", "upper", "lower"}
    assert (table["n_slenderness"] == 8).all()
    assert (table[["n_stable", "n_overturned", "n_leaning", "n_failed"]].sum(axis=1) == 8).all()
    pga = {r.name: r.pga_g for r in two_records}
    tm = {r.name: r.mean_period for r in two_records}
    assert table["pga_g"].tolist() == [pga[n] for n in table["record"]]
    assert table["mean_period"].tolist() == [tm[n] for n in table["record"]]
    assert table.attrs["walls"] == ["two-sided"]


@needs_records
def test_beta_identity_and_tp(small_study):
    table, _ = small_study
    np.testing.assert_allclose(table["beta"], table["slenderness_min"] / table["pga_g"],
                               rtol=1e-14)
    np.testing.assert_allclose(table["beta"] * table["pga_g"] * G_STANDARD,
                               table["slenderness_min"] * G_STANDARD, rtol=1e-14)
    for _, row in table.iterrows():
        body = RigidBlock.rectangle(row["b"], row["b"] / row["slenderness_min"])
        assert row["Tp"] == pytest.approx(2 * math.pi / body.p, rel=1e-14)
        assert row["alpha_min"] == pytest.approx(body.alpha, rel=1e-14)
    np.testing.assert_allclose(table["tp_over_tm"], table["Tp"] / table["mean_period"])


@needs_records
def test_flags_consistent_with_runs(small_study):
    table, runs = small_study
    for _, row in table.iterrows():
        cell = runs[(runs["record"] == row["record"]) & (runs["b"] == row["b"])
                    ].sort_values("slenderness")
        s = cell["slenderness"].to_numpy()
        ok = (cell["outcome"] == "safe").to_numpy()
        assert (cell["stable"].to_numpy() == ok).all()
        k = int(np.flatnonzero(s == row["slenderness_min"])[0])
        if row["beta_bound"] == "upper":
            assert ok.all() and k == 0
        elif row["beta_bound"] == "lower":
            assert not ok[-1] and k == s.size - 1
        else:
            assert ok[k:].all() and not ok[k - 1]
        brute = any(ok[i] and not ok[j] for i in range(s.size) for j in range(i + 1, s.size))
        assert row["non_monotone"] == brute
        assert row["n_overturned"] == cell["outcome"].isin(["mode1", "mode2"]).sum()


@needs_records
def test_pseudo_static_rule_holds(small_study):
    """A block with b/h >= PGA/g never uplifts, so beta never exceeds the
    first grid point at or above the pseudo-static slenderness."""
    table, runs = small_study
    stout = runs[runs["slenderness"] > runs["pga_g"]]
    assert (stout["status"] == "safe:no-uplift").all()
    assert len(stout) > 0
    exact = table[table["beta_bound"] != "lower"]
    s = np.linspace(0.1, 0.5, 8)
    for _, row in exact[exact["pga_g"] <= s[-1]].iterrows():
        assert row["slenderness_min"] <= s[np.searchsorted(s, row["pga_g"])]
    # Sylmar (0.843 g) exceeds the grid's largest b/h: only lower bounds there
    # unless the block survives; El Centro (0.319 g) can never be "lower".
    assert not ((table["record"] == "elCentro") & (table["beta_bound"] == "lower")).any()


@needs_records
def test_cells_recomputed_with_simulate(small_study, two_records):
    table, runs = small_study
    recs = {r.name: r for r in two_records}
    rng = np.random.default_rng(3)
    for i in rng.choice(len(runs), size=6, replace=False):
        run = runs.iloc[i]
        body = RigidBlock.rectangle(run["b"], run["h"])
        r = simulate(body, recs[run["record"]], early_exit=True)
        assert r.outcome == run["outcome"]
        assert r.status == run["status"]
        assert r.metrics["max_rotation_ratio"] == pytest.approx(run["max_rotation_ratio"],
                                                                rel=1e-12)


@needs_records
def test_mixed_units_and_unit_only_where_needed():
    files = [RECORDS / "elCentro.AT2", RECORDS / "Northridge_Sylmar_County.dat"]
    recs = RS.load_records(files, unit="m/s2")          # El Centro keeps its g header
    assert [round(r.pga_g, 3) for r in recs] == [0.319, 0.843]
    with pytest.raises(ValueError, match="Northridge_Sylmar_County.dat.*unit"):
        RS.load_records(files)


def test_records_input_validation(el_centro):
    with pytest.raises(ValueError, match="empty"):
        rocking_spectrum([], progress=False)
    with pytest.raises(ValueError, match="all zero"):
        rocking_spectrum(GroundMotion(np.zeros(10), 0.01, name="z"), progress=False)
    with pytest.raises(ValueError, match="slenderness must be > 0"):
        rocking_spectrum(el_centro, [-0.1, 0.2], [0.3], walls=(None,), progress=False)
    with pytest.raises(ValueError, match="walls"):
        rocking_spectrum(el_centro, [0.2], [0.3], walls=(None, None), progress=False)
    with pytest.raises(ValueError, match="wall setting"):
        RS.parse_walls("two-sided,abc")
    with pytest.raises(ValueError, match="records must be"):
        rocking_spectrum([42], progress=False)


def test_duplicate_names_made_unique(el_centro):
    recs = RS.load_records([el_centro, el_centro.scaled(0.5)])
    assert len({r.name for r in recs}) == 2
    same = RS.load_records([el_centro, el_centro])
    assert same[1].name == el_centro.name + " (2)"


def test_default_grid_is_the_papers():
    np.testing.assert_allclose(DEFAULT_SLENDERNESS, np.linspace(0.1, 0.5, 20))
    np.testing.assert_allclose(DEFAULT_HALF_WIDTHS, np.linspace(0.1, 1.0, 20))


# ----------------------------------------------------- bisection
def _pulse_record(ap_g, f, n=400):
    dt = 1.0 / f / n
    t = np.arange(n + 1) * dt
    return GroundMotion(ap_g * G_STANDARD * np.sin(2 * np.pi * f * t), dt, name="sine")


@pytest.mark.parametrize("ap_g,b", [(0.3, 0.5), (0.5, 0.5)])
def test_bisection_agrees_with_fine_scan(ap_g, b):
    rec = _pulse_record(ap_g, 1.0)
    tol = 1e-3
    res = minimum_stable_slenderness(rec, b, lo=0.02, hi=0.6, tol=tol, scan=12)
    assert res.bound == "exact"
    lo, hi = res.bracket
    assert 0 < hi - lo <= tol and res.value == hi
    assert res.beta == pytest.approx(res.value / rec.pga_g)
    step = tol / 2
    s = np.arange(0.02, 0.6 + step / 2, step)
    fine = rocking_spectrum_runs(rec, s, [b], walls=(None,), progress=False)
    thr = minimum_stable_on_grid(fine.sort_values("slenderness")["stable"].to_numpy())
    assert thr.bound == "exact"
    assert abs(s[thr.index] - res.value) <= tol + step
    # the bracket ends are what they claim
    assert res.runs.loc[res.runs["slenderness"] == hi, "stable"].all()
    assert not res.runs.loc[res.runs["slenderness"] == lo, "stable"].any()


def test_bisection_on_a_record_reports_its_runs(el_centro):
    res = minimum_stable_slenderness(el_centro, 0.3, lo=0.05, hi=0.35, tol=2e-3, scan=16,
                                     sections=4)
    assert res.bound == "exact"
    runs = res.runs.sort_values("slenderness")
    # value is the "stable from there up" threshold of everything evaluated
    thr = minimum_stable_on_grid(runs["stable"].to_numpy())
    assert runs["slenderness"].iloc[thr.index] == res.value
    assert thr.non_monotone == res.non_monotone
    assert len(res.scan) == 16 and res.n_runs > 16
    # the coarse scan of El Centro at b = 0.3 m is non-monotone (0.1 survives)
    assert res.non_monotone


def test_bisection_bounds(el_centro):
    up = minimum_stable_slenderness(el_centro, 0.9, lo=0.05, hi=0.5, scan=5)
    assert up.bound == "upper" and up.value == 0.05 and up.n_runs == 5
    strong = el_centro.scaled(3.0)
    low = minimum_stable_slenderness(strong, 0.2, lo=0.05, hi=0.3, scan=4)
    assert low.bound == "lower" and low.value == 0.3
    with pytest.raises(ValueError, match="lo < hi"):
        minimum_stable_slenderness(el_centro, 0.3, lo=0.4, hi=0.2)
    with pytest.raises(ValueError, match="sections"):
        minimum_stable_slenderness(el_centro, 0.3, sections=1)


# ----------------------------------------------------- plot
def test_plot_marks_bounds_hollow(small_study):
    import matplotlib
    matplotlib.use("Agg")
    table, _ = small_study
    fig = plot_rocking_spectrum(table)
    ax = fig.axes[0]
    legend = ax.get_legend()
    labels = [t.get_text() for t in legend.get_texts()]
    assert any("Maiorano" in lab and "1.35" in lab for lab in labels)     # the bound is named
    for h in legend.legend_handles:                    # censored points hollow, the others filled
        if h.get_marker() not in (None, "None", ""):
            hollow = h.get_markerfacecolor() in ("white", "none", (1.0, 1.0, 1.0, 1.0))
            assert hollow == h.get_label().startswith("censored"), h.get_label()
    censored = table["beta_bound"].isin(["upper", "lower"])
    points = [ln for ln in ax.lines if ln.get_linestyle() == "None"]
    assert sum(ln.get_markerfacecolor() == "white" for ln in points) >= (1 if censored.any() else 0)


# ----------------------------------------------------- CLI
def test_cli_record_default(capsys, tmp_path):
    from fastrock.cli.app import main
    png = tmp_path / "rec.png"
    csv = tmp_path / "hist.csv"
    assert main(["record", "--png", str(png), "--csv", str(csv)]) == 0
    out = capsys.readouterr().out
    assert "PGA = 0.319 g" in out
    assert "Tm = " in out and "Arias = " in out and "PGV = " in out and "duration = " in out
    assert "outcome: safe" in out                      # the default block rocks, stays up
    assert "max |theta|/alpha = 0.26" in out
    assert png.stat().st_size > 10_000
    hist = pd.read_csv(csv)
    assert hist["theta_ratio"].abs().max() > 0.2


def test_cli_record_fixed_step_and_block(capsys, tmp_path):
    from fastrock.cli.app import main
    assert main(["record", "--b", "0.15", "--h", "0.75", "--dt", "record",
                 "--png", str(tmp_path / "a.png")]) == 0
    out = capsys.readouterr().out
    assert "outcome: mode1" in out and "record dt = 0.02 s" in out
    assert main(["record", "--b", "0.15", "--png", str(tmp_path / "b.png")]) == 2


@needs_records
def test_cli_record_file_needs_unit(capsys, tmp_path):
    from fastrock.cli.app import main
    f = str(RECORDS / "Northridge_Sylmar_County.dat")
    assert main(["record", f, "--png", str(tmp_path / "s.png")]) == 2
    assert "unit" in capsys.readouterr().err
    assert main(["record", f, "--unit", "m/s2", "--png", str(tmp_path / "s.png")]) == 0
    assert "PGA = 0.843 g" in capsys.readouterr().out


@needs_records
def test_cli_rocking_spectrum_writes_csv_png(capsys, tmp_path):
    from fastrock.cli.app import main
    png, csv = tmp_path / "rs.png", tmp_path / "rs.csv"
    assert main(["rocking-spectrum", str(RECORDS / "RIO270.AT2"), "--n-slenderness", "5",
                 "--n-sizes", "3", "--walls", "two-sided", "--png", str(png), "--csv", str(csv)]) == 0
    out = capsys.readouterr().out
    assert "15 runs" in out and "RIO270: PGA = 0.385 g" in out
    df = pd.read_csv(csv)
    assert len(df) == 3 and list(df.columns) == TABLE_COLUMNS
    assert png.stat().st_size > 10_000


# ----------------------------------------------------- wall settings
def test_default_walls_follow_the_wall_model():
    walls = RS.default_walls()
    try:
        import fastrock.model.wall  # noqa: F401
        import fastrock.kernels.wall  # noqa: F401
    except ImportError:
        assert walls == (None,)
    else:
        assert walls[0] is None and [w.gap for w in walls[1:]] == [0.01, 0.10]


def test_rocking_spectrum_with_walls(el_centro):
    pytest.importorskip("fastrock.model.wall")
    pytest.importorskip("fastrock.kernels.wall")
    from fastrock.model.wall import Wall
    s = np.linspace(0.1, 0.3, 5)
    table, runs = rocking_spectrum(el_centro, s, [0.2, 0.6], walls=(None, 0.01, Wall(0.10)),
                                   progress=False, return_runs=True)
    assert len(table) == 3 * 2 and len(runs) == 3 * 2 * 5
    assert table["wall"].unique().tolist() == ["two-sided", "wall d=0.01 m", "wall d=0.1 m"]
    gaps = table.groupby("wall")["wall_gap"].first()
    assert math.isnan(gaps["two-sided"]) and gaps["wall d=0.01 m"] == 0.01
    np.testing.assert_allclose(table["beta"], table["slenderness_min"] / table["pga_g"])
    # the two-sided rows equal a two-sided-only study (own sweep, same rows)
    alone = rocking_spectrum(el_centro, s, [0.2, 0.6], walls=(None,), progress=False)
    two = table[table["wall"] == "two-sided"].reset_index(drop=True)
    pd.testing.assert_frame_equal(two, alone, check_like=False)
    # a wall cell recomputed with simulate
    wall_runs = runs[runs["wall"] == "wall d=0.01 m"]
    run = wall_runs.iloc[len(wall_runs) // 2]
    r = simulate(RigidBlock.rectangle(run["b"], run["h"]), el_centro, wall=Wall(0.01),
                 early_exit=True)
    assert r.outcome == run["outcome"]
    assert RS.parse_walls("two-sided,0.01")[1] == Wall(0.01)


def test_cli_record_single_column_file_needs_unit_and_dt(capsys, tmp_path):
    from fastrock.cli.app import main
    f = tmp_path / "pulse.txt"
    t = np.arange(201) * 0.005
    np.savetxt(f, 0.4 * np.sin(2 * np.pi * t))           # one 1 Hz sine, 0.4 g
    png = str(tmp_path / "p.png")
    assert main(["record", str(f), "--unit", "g", "--png", png]) == 2
    assert "dt" in capsys.readouterr().err
    assert main(["record", str(f), "--unit", "g", "--record-dt", "0.005", "--png", png]) == 0
    out = capsys.readouterr().out
    assert "PGA = 0.4 g" in out and "201 points, dt = 0.005 s" in out


def test_default_record_when_none(el_centro):
    table = rocking_spectrum(None, [0.2, 0.4], [0.3], walls=(None,), progress=False)
    assert table["record"].tolist() == [el_centro.name]
    assert table["pga_g"].iloc[0] == el_centro.pga_g
