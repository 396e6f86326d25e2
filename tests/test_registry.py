"""The model registry (issue #13, item 1): one entry per model, every entry
point goes through it, the foundation family runs under pulses and in
spectra, and vertical excitation reaches the spectrum."""
from __future__ import annotations

import math

import numpy as np
import pytest

from fastrock import FlexibleBody, Friction, Pulse, RigidBlock, SampledMotion, Wall, overturning_spectrum
from fastrock import simulate
from fastrock.running import registry
from fastrock.model.foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation, block_inertia

BLOCK = RigidBlock.rectangle(0.15, 0.6)
FLEX = FlexibleBody(0.2, 2.0, 10.0)


@pytest.mark.parametrize("body,kw,name", [
    (BLOCK, {}, "rigid"),
    (BLOCK, {"friction": Friction(math.inf)}, "rigid"),
    (BLOCK, {"wall": Wall(gap=0.01)}, "rigid_wall"),
    (BLOCK, {"friction": Friction(0.4)}, "rigid_friction"),
    (FLEX, {}, "flexible"),
    (FLEX, {"friction": Friction(math.inf)}, "flexible"),
    (FLEX, {"friction": Friction(0.4)}, "flexible_friction"),
    (BLOCK, {"foundation": TwoSpringFoundation(1e6, 1e3)}, "two_spring"),
    (BLOCK, {"foundation": SwitchingFoundation(1e5)}, "switching"),
    (BLOCK, {"foundation": LinearVibration(1e5)}, "linear_sdof"),
    (FLEX, {"foundation": TwoSpringFoundation(1e6, 1e3)}, "flexible_two_spring"),
    (BLOCK, {"wall": Wall(gap=0.01), "friction": Friction(0.4)}, "contact"),
    (BLOCK, {"friction": Friction(math.inf, lift_off="flight")}, "contact"),
    (BLOCK, {"foundation": TwoSpringFoundation(1e5), "friction": Friction(0.3)}, "two_spring_friction"),
    (BLOCK, {"foundation": TwoSpringFoundation(1e5), "friction": Friction(0.3, lift_off="flight")},
     "two_spring_friction"),
    (BLOCK, {"foundation": TwoSpringFoundation(1e5), "friction": Friction(math.inf)}, "two_spring"),
])
def test_a_scene_selects_exactly_its_model(body, kw, name):
    spec = registry.select(body, **kw)
    assert spec.name == name
    model = registry.MODELS[name]
    assert spec.model is model
    assert spec.n_state == len(model.state_names) and model.state_names[spec.theta_index] == "theta"
    assert spec.friction == (name in ("rigid_friction", "flexible_friction", "contact", "two_spring_friction"))
    assert spec.flexible == isinstance(body, FlexibleBody)


def test_every_entry_names_its_kernels_and_columns():
    from fastrock.analyses.spectrum import SPECTRUM_COLUMNS
    assert set(registry.MODELS) == {"rigid", "rigid_body", "rigid_wall", "rigid_friction", "contact", "contact_body",
                                    "flexible",
                                    "flexible_friction", "flexible_wall", "flexible_flight", "two_spring", "switching", "wall_body",
                                    "linear_sdof", "two_spring_friction", "flexible_two_spring",
                                    "two_spring_wall", "switching_wall"}
    for m in registry.MODELS.values():
        mod = m.load()
        assert callable(getattr(mod, m.simulate_entry)) and callable(getattr(mod, m.sweep_entry))
        for col in m.columns:
            assert col in SPECTRUM_COLUMNS, (m.name, col)
        assert set(m.outcomes) <= {"safe", "slide", "mode1", "mode2", "leaning", "flight", "failed"}


def test_cli_and_toml_know_every_option_an_entry_names():
    from fastrock.cli import app as cli
    from fastrock.running.scene import Scene
    spectrum = next(a for a in cli.build_parser()._subparsers._group_actions[0].choices.items()
                    if a[0] == "spectrum")[1]
    options = {s for a in spectrum._actions for s in a.option_strings}
    sections = {"body", "excitation", "vertical", "wall", "friction", "foundation", "solver", "run", "output",
                "name"}
    for m in registry.MODELS.values():
        assert set(m.cli_options) <= options, (m.name, set(m.cli_options) - options)
        assert set(m.toml_keys) <= sections, m.name
    with pytest.raises(ValueError, match="unknown scene section"):
        Scene.from_dict({"body": {"b": 0.2, "h": 1.0}, "walls": {}})


@pytest.mark.parametrize("body,kw,match", [
    (FLEX, {"wall": Wall(gap=0.01), "friction": Friction(0.4)}, "RigidBlock only"),
    (FLEX, {"wall": Wall(gap=0.0)}, "Hogan's one-sided rocking"),
    (FLEX, {"foundation": LinearVibration(1e5)}, "stands on foundation=TwoSpringFoundation"),
    (BLOCK, {"foundation": LinearVibration(1e5), "friction": Friction(0.3)}, "on TwoSpringFoundation only"),
    (BLOCK, {"foundation": TwoSpringFoundation(1e5), "friction": Friction(math.inf, lift_off="flight")},
     "never slips"),
    (BLOCK, {"foundation": "stiff"}, "foundation must be"),
    (BLOCK, {"wall": 0.01}, "wall must be a fastrock.Wall"),
    ("block", {}, "body must be a fastrock body"),
])
def test_combinations_not_available_say_why(body, kw, match):
    with pytest.raises(ValueError, match=match):
        registry.select(body, **kw)


def test_a_model_cannot_be_registered_twice():
    m = registry.MODELS["rigid"]
    with pytest.raises(ValueError, match="registered already"):
        registry.register(m)


# ------------------------------------------------------------- the foundation family
def test_simulate_with_a_foundation_is_simulate_foundation():
    from fastrock.running.foundation import simulate_foundation
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 60.0, 0.05)
    pulse = Pulse(2.0, 1.5, amplitude_unit="g_tan_alpha")
    a = simulate(BLOCK, pulse, foundation=fnd, mass=2.0)
    b = simulate_foundation(BLOCK, fnd, pulse, mass=2.0, allow_overturn=True)
    assert a.kernel == "two_spring" and a.status == b.status
    np.testing.assert_array_equal(a.history["theta"].to_numpy(), b.history["theta"].to_numpy())
    assert a.metrics == b.metrics


def test_linear_vibration_under_a_pulse_follows_the_closed_form():
    """I_C theta'' + k_t theta = -M h a_p sin(w t): Duhamel's closed form."""
    fnd = LinearVibration(k_t=2.0e3)
    blk = block_inertia(BLOCK, 1.0)
    wn = math.sqrt(fnd.k_t / blk.I_C)
    a_p, w = 0.3, 0.37 * wn
    pulse = Pulse(a_p, w, amplitude_unit="m/s2", frequency_unit="rad/s")
    t = np.linspace(0.0, 2 * math.pi / w, 57)[1:]
    r = simulate(BLOCK, pulse, foundation=fnd, t_eval=t, rtol=1e-11, atol=1e-14)
    q = blk.M * blk.h * a_p / blk.I_C
    exact = -q / (wn ** 2 - w ** 2) * (np.sin(w * t) - (w / wn) * np.sin(wn * t))
    h = r.history.drop_duplicates("t", keep="last")
    np.testing.assert_allclose(h["theta"].to_numpy(), exact, atol=1e-9 * np.abs(exact).max())


def _adjacent_to_change(grid):
    """True where a cell of an outcome grid has a neighbour of another outcome."""
    g = np.asarray(grid)
    out = np.zeros(g.shape, bool)
    out[1:, :] |= g[1:, :] != g[:-1, :]
    out[:-1, :] |= g[:-1, :] != g[1:, :]
    out[:, 1:] |= g[:, 1:] != g[:, :-1]
    out[:, :-1] |= g[:, :-1] != g[:, 1:]
    return out


@pytest.mark.slow
def test_a_stiff_two_spring_foundation_gives_the_rigid_spectrum():
    amps, freqs = np.linspace(0.8, 6.0, 12), np.linspace(0.5, 8.0, 12)
    rigid = overturning_spectrum(BLOCK, amps, freqs, progress=False)
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 1000.0, 0.05)
    stiff = overturning_spectrum(BLOCK, amps, freqs, foundation=fnd, progress=False)
    assert stiff.attrs["kernel"] == "two_spring"
    assert {"time_rocking", "time_contact"} <= set(stiff.columns)
    # overturned or not: the stiff model's soft re-contacts near uplift can count as an
    # impact (mode 1 against mode 2), and its impacts dissipate through c_v, not Housner's e
    a = rigid["outcome"].isin(["mode1", "mode2"]).to_numpy().reshape(freqs.size, amps.size)
    b = stiff["outcome"].isin(["mode1", "mode2"]).to_numpy().reshape(freqs.size, amps.size)
    differ = a != b
    assert differ.mean() <= 0.03
    assert _adjacent_to_change(a)[differ].all()      # only cells on the rigid overturning boundary move
    # the motion before any impact is the rigid one: the no-uplift cells are the same
    np.testing.assert_array_equal(rigid["status"] == "safe:no-uplift", stiff["status"] == "safe:no-uplift")


# ------------------------------------------------------------- vertical excitation
def test_a_constant_vertical_acceleration_is_a_change_of_g():
    c = -2.5                                   # m/s^2, lighter effective gravity
    g2 = BLOCK.g + c
    pulse = Pulse(1.5 * g2 * math.tan(BLOCK.alpha), 12.0, amplitude_unit="m/s2", frequency_unit="rad/s")
    vert = SampledMotion(np.full(2001, c), 0.01, unit="m/s2")
    a = simulate(BLOCK, pulse, vertical=vert, duration=12.0, record_breakpoints=False, rtol=1e-10)
    # the same block under gravity g + c: p^2/g is the geometry, kept
    other = RigidBlock(BLOCK.alpha, BLOCK.p * math.sqrt(g2 / BLOCK.g), e=BLOCK.e, g=g2)
    b = simulate(other, pulse, duration=12.0, rtol=1e-10)
    assert a.outcome == b.outcome
    assert a.metrics["max_rotation"] == pytest.approx(b.metrics["max_rotation"], rel=1e-7)
    assert a.metrics["impacts"] == b.metrics["impacts"] > 0
    assert a.metrics["time_uplift"] == pytest.approx(b.metrics["time_uplift"], abs=1e-9)


def test_spectrum_takes_a_vertical_pulse():
    amps, freqs = np.linspace(1.0, 4.0, 5), np.linspace(1.0, 4.0, 5)
    up = Pulse(0.5, 6.0, amplitude_unit="g", frequency_unit="rad/s", sign=1)
    base = overturning_spectrum(BLOCK, amps, freqs, progress=False)
    with_v = overturning_spectrum(BLOCK, amps, freqs, vertical=up, progress=False)
    assert len(with_v) == len(base)
    assert (with_v["max_rotation"] != base["max_rotation"]).any()
    # each row is simulate() with both excitations
    row = with_v.iloc[7]
    r = simulate(BLOCK, Pulse(row["amplitude"], 2 * math.pi * row["frequency_hz"], sign=int(row["sign"]),
                              amplitude_unit="m/s2", frequency_unit="rad/s"),
                 vertical=up, duration=row["time_end"], early_exit=True)
    assert r.outcome == row["outcome"]


def test_a_toml_scene_runs_a_foundation(tmp_path):
    from pathlib import Path
    from fastrock.running.scene import Scene
    ex = Path(__file__).resolve().parents[1] / "examples" / "scenes" / "foundation_pulse.toml"
    sc = Scene.from_toml(ex)
    assert sc.kernel == "two_spring" and sc.mass == 100.0
    assert "foundation:two-spring" in sc.effects
    r = sc.run()
    fnd = TwoSpringFoundation.from_vibration(sc.body, 40.0, 0.05, mass=100.0)
    ref = simulate(sc.body, sc.excitation, foundation=fnd, mass=100.0)
    assert r.status == ref.status and r.metrics == ref.metrics
    for bad, match in [({"type": "winkler"}, "type must be one of"),
                       ({"type": "linear", "k_t": 1e4, "omega": 30.0}, "not both"),
                       ({"type": "two-spring", "k_v": 1e6, "zeta": 0.1}, "zeta goes with omega"),
                       ({"type": "switching", "k_v": 1e6}, "unknown key")]:
        with pytest.raises(ValueError, match=match):
            Scene.from_dict({"body": {"b": 0.15, "h": 0.6}, "foundation": bad})


def test_the_cli_runs_a_foundation_spectrum(tmp_path, capsys):
    from fastrock.cli import app as cli
    import pandas as pd
    out = [f"--png={tmp_path / 'f.png'}", f"--csv={tmp_path / 'f.csv'}", "--quiet"]
    rc = cli.main(["spectrum", "--b", "0.15", "--h", "0.6", "--foundation", "two-spring", "--foundation-omega",
                   "60", "--foundation-zeta", "0.05", "--mass", "100", "--n-amp", "4", "--n-freq", "3"] + out)
    assert rc == 0
    df = pd.read_csv(tmp_path / "f.csv")
    fnd = TwoSpringFoundation.from_vibration(BLOCK, 60.0, 0.05, mass=100.0)
    ref = overturning_spectrum(BLOCK, np.linspace(0.5, 8.0, 4), np.linspace(0.25, 10.0, 3), foundation=fnd,
                               mass=100.0, progress=False)
    assert list(df["outcome"]) == list(ref["outcome"])
    assert cli.main(["spectrum", "--foundation", "linear"] + out) == 2
    assert "--foundation needs --foundation-omega" in capsys.readouterr().err


def test_a_vertical_record_must_match_the_horizontal_one():
    from fastrock.io.default_records import load_default_record
    rec = load_default_record()
    h = SampledMotion.from_record(rec)
    v_same = SampledMotion(0.3 * rec.acc, rec.dt)
    assert simulate(BLOCK, h, vertical=v_same, duration=3.0).status
    v_other = SampledMotion(0.3 * rec.acc[::2], 2 * rec.dt)
    with pytest.raises(ValueError, match=r"vertical: its record \(dt = 0.04 s, 780 samples.*resample_vertical=True"):
        simulate(BLOCK, h, vertical=v_other)
    # resampled: the same as giving the interpolated samples by hand
    r = simulate(BLOCK, h, vertical=v_other, resample_vertical=True, duration=3.0)
    t = rec.dt * np.arange(rec.acc.size)
    by_hand = SampledMotion(np.interp(t, 2 * rec.dt * np.arange(780), 0.3 * rec.acc[::2], right=0.0), rec.dt)
    ref = simulate(BLOCK, h, vertical=by_hand, duration=3.0)
    np.testing.assert_equal(r.metrics, ref.metrics)   # NaN equals NaN


def test_wall_friction_is_a_named_option_of_the_contact_model():
    """Wall friction runs in the contact model (tests/test_contact_wall_friction.py); the wall model,
    whose wall is frictionless, refuses it and names the way to the contact model."""
    assert Wall(gap=0.01).friction == 0.0
    with pytest.raises(ValueError, match="friction must be >= 0"):
        Wall(gap=0.01, friction=-0.1)
    with pytest.raises(ValueError, match="wall: friction > 0 .*friction=Friction"):
        simulate(BLOCK, Pulse(2.0, 1.0, amplitude_unit="g_tan_alpha"), wall=Wall(gap=0.01, friction=0.3))
    assert registry.select(BLOCK, wall=Wall(gap=0.01, friction=0.3), friction=Friction(0.5)).name == "contact"
