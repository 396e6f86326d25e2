"""Input validation of the front end: bad input raises ValueError naming the offending field.

Field names are matched as whole words (``\\b...\\b``) so that e.g. "e" cannot be matched by an
unrelated message.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import fastrock as fr
from fastrock.cli import app as cli

NAN = math.nan
DENORMAL = 1e-310
HUGE = 1e300


def field(name):
    return rf"(?<![\w.]){name}\b"



@pytest.fixture(scope="module")
def body():
    return fr.RigidBlock(alpha=0.2, p=2.0)


# ---------------------------------------------------------------- RigidBlock

@pytest.mark.parametrize("alpha", [0.0, -0.1, math.pi / 2, 2.0, NAN, math.inf, -math.inf, DENORMAL,
                                   HUGE, "a", None])
def test_rigidblock_alpha(alpha):
    with pytest.raises(ValueError, match=field("alpha")):
        fr.RigidBlock(alpha=alpha, p=2.0)


@pytest.mark.parametrize("p", [0.0, -1.0, NAN, math.inf, DENORMAL, HUGE, -DENORMAL])
def test_rigidblock_p(p):
    with pytest.raises(ValueError, match=field("p")):
        fr.RigidBlock(alpha=0.2, p=p)


@pytest.mark.parametrize("e", [1.0 + 1e-12, 1.5, -1e-12, -0.5, NAN, DENORMAL, HUGE])
def test_rigidblock_e(e):
    with pytest.raises(ValueError, match=field("e")):
        fr.RigidBlock(alpha=0.2, p=2.0, e=e)


@pytest.mark.parametrize("g", [0.0, -9.8, NAN, DENORMAL, HUGE])
def test_rigidblock_g(g):
    with pytest.raises(ValueError, match=field("g")):
        fr.RigidBlock(alpha=0.2, p=2.0, g=g)


@pytest.mark.parametrize("theta_over", [0.1, 0.2, math.pi, NAN])
def test_rigidblock_theta_over(theta_over):
    with pytest.raises(ValueError, match=field("theta_over")):
        fr.RigidBlock(alpha=0.2, p=2.0, theta_over=theta_over)


def test_rigidblock_limits_accepted():
    assert fr.RigidBlock(alpha=0.2, p=2.0, e=0.0).e == 0.0
    assert fr.RigidBlock(alpha=0.2, p=2.0, e=1.0).e == 1.0
    fr.RigidBlock(alpha=1e-6, p=1e-6)
    fr.RigidBlock(alpha=math.pi / 2 - 1e-9, p=1e6, e=0.5)


def test_squat_block_needs_explicit_restitution():
    """Housner's default e = 1 - 1.5 sin^2(alpha) is negative for alpha > asin(sqrt(2/3)): the
    error names e (the default cannot be used); an explicit e is accepted."""
    a = math.asin(math.sqrt(2 / 3))
    with pytest.raises(ValueError, match=field("e")):
        fr.RigidBlock(alpha=a + 1e-3, p=2.0)
    assert fr.RigidBlock(alpha=a - 1e-3, p=2.0).e > 0
    assert fr.RigidBlock(alpha=1.2, p=2.0, e=0.5).e == 0.5
    with pytest.raises(ValueError, match=field("e")):
        fr.RigidBlock.rectangle(b=2.0, h=1.0)


@pytest.mark.parametrize("name,kw", [
    ("b", dict(b=0.0, h=1.0)), ("b", dict(b=-1.0, h=1.0)), ("h", dict(b=0.2, h=0.0)),
    ("h", dict(b=0.2, h=-2.0)), ("b", dict(b=NAN, h=1.0)), ("h", dict(b=0.2, h=math.inf)),
    ("b", dict(b=DENORMAL, h=1.0)), ("h", dict(b=0.2, h=DENORMAL)),
    ("b", dict(b=HUGE, h=1.0)), ("h", dict(b=0.2, h=HUGE)),
    ("e", dict(b=0.2, h=1.0, e=1.2)), ("g", dict(b=0.2, h=1.0, g=0.0)),
])
def test_rectangle(name, kw):
    with pytest.raises(ValueError, match=field(name)):
        fr.RigidBlock.rectangle(**kw)


@pytest.mark.parametrize("name,kw", [
    ("R", dict(R=0.0, alpha=0.2, I0=2.0, m=1.0)), ("alpha", dict(R=1.0, alpha=2.0, I0=2.0, m=1.0)),
    ("I0", dict(R=1.0, alpha=0.2, I0=-1.0, m=1.0)), ("m", dict(R=1.0, alpha=0.2, I0=2.0, m=0.0)),
    ("I0", dict(R=1.0, alpha=0.2, I0=0.5, m=1.0)),        # I0 < m R^2 (parallel axes)
    ("m", dict(R=1.0, alpha=0.2, I0=2.0, m=HUGE)), ("R", dict(R=DENORMAL, alpha=0.2, I0=2.0, m=1.0)),
])
def test_from_inertia(name, kw):
    with pytest.raises(ValueError, match=field(name)):
        fr.RigidBlock.from_inertia(**kw)


# ---------------------------------------------------------------- Pulse / SampledMotion

@pytest.mark.parametrize("name,kw", [
    ("amplitude", dict(amplitude=-1.0)), ("amplitude", dict(amplitude=NAN)),
    ("amplitude", dict(amplitude=HUGE)), ("amplitude", dict(amplitude=DENORMAL)),
    ("frequency", dict(amplitude=1.0, frequency=0.0)), ("frequency", dict(amplitude=1.0, frequency=-2.0)),
    ("frequency", dict(amplitude=1.0, frequency=NAN)),
    ("sign", dict(amplitude=1.0, sign=0)), ("sign", dict(amplitude=1.0, sign=2)),
    ("kind", dict(amplitude=1.0, kind="triangle")),
    ("amplitude_unit", dict(amplitude=1.0, amplitude_unit="G")),
    ("amplitude_unit", dict(amplitude=1.0, amplitude_unit="gal")),
    ("frequency_unit", dict(amplitude=1.0, frequency_unit="hz")),
    ("frequency_unit", dict(amplitude=1.0, frequency_unit="omega/p")),
    ("t_start", dict(amplitude=1.0, t_start=-0.1)),
    ("duration", dict(amplitude=1.0, kind="rectangular")),
    ("duration", dict(amplitude=1.0, kind="rectangular", duration=-1.0)),
    ("duration", dict(amplitude=1.0, kind="rectangular", duration=0.0)),
])
def test_pulse(name, kw):
    with pytest.raises(ValueError, match=field(name)):
        fr.Pulse(**kw)


@pytest.mark.parametrize("name,kw", [
    ("acc", dict(acc=np.array([0.0, NAN, 1.0]), dt=0.01)),
    ("acc", dict(acc=np.array([0.0, 1.0, math.inf]), dt=0.01)),
    ("acc", dict(acc=np.zeros((3, 2)), dt=0.01)),
    ("acc", dict(acc=np.zeros(1), dt=0.01)),
    ("dt", dict(acc=np.zeros(3), dt=0.0)), ("dt", dict(acc=np.zeros(3), dt=NAN)),
    ("unit", dict(acc=np.zeros(3), dt=0.01, unit="ft/s2")),
    ("scale", dict(acc=np.zeros(3), dt=0.01, scale=NAN)),
])
def test_sampled_motion(name, kw):
    with pytest.raises(ValueError, match=field(name)):
        fr.SampledMotion(**kw)


# ---------------------------------------------------------------- simulate

@pytest.mark.parametrize("name,kw", [
    ("theta0", dict(theta0=math.pi / 2)), ("theta0", dict(theta0=-math.pi / 2)),
    ("theta0", dict(theta0=2.0)), ("theta0", dict(theta0=NAN)), ("theta0", dict(theta0=DENORMAL)),
    ("dtheta0", dict(theta0=0.1, dtheta0=HUGE)), ("dtheta0", dict(theta0=0.1, dtheta0=NAN)),
    ("duration", dict(theta0=0.1, duration=-1.0)), ("duration", dict(theta0=0.1, duration=0.0)),
    ("duration", dict(theta0=0.1, duration=NAN)),
    ("rtol", dict(theta0=0.1, duration=1.0, rtol=0.0)),
    ("rtol", dict(theta0=0.1, duration=1.0, rtol=-1e-6)),
    ("rtol", dict(theta0=0.1, duration=1.0, rtol=NAN)),
    ("atol", dict(theta0=0.1, duration=1.0, atol=0.0)),
    ("dt", dict(theta0=0.1, duration=1.0, dt=-0.01)),
    ("max_steps", dict(theta0=0.1, duration=1.0, max_steps=0)),
    ("t_eval", dict(theta0=0.1, duration=1.0, t_eval=[0.0, NAN])),
])
def test_simulate(body, name, kw):
    kw.setdefault("duration", 1.0)
    with pytest.raises(ValueError, match=field(name)):
        fr.simulate(body, **kw)


def test_simulate_theta0_beyond_custom_theta_over():
    b = fr.RigidBlock(alpha=0.2, p=2.0, theta_over=0.5)
    with pytest.raises(ValueError, match=field("theta0")):
        fr.simulate(b, theta0=0.6, duration=1.0)


def test_simulate_t_after(body):
    with pytest.raises(ValueError, match=field("t_after")):
        fr.simulate(body, fr.Pulse(1.0, 1.0), t_after=-1.0)


def test_simulate_excitation_type(body):
    with pytest.raises(ValueError, match=field("excitation")):
        fr.simulate(body, "one-sine", duration=1.0)


def test_simulate_body_type():
    with pytest.raises(ValueError, match=field("body")):
        fr.simulate("block", theta0=0.1, duration=1.0)


# ---------------------------------------------------------------- overturning_spectrum

@pytest.mark.parametrize("name,amps,freqs,kw", [
    ("amplitude_ratios", [-1.0], [1.0], {}), ("amplitude_ratios", [1.0, NAN], [1.0], {}),
    ("amplitude_ratios", [math.inf], [1.0], {}),
    ("frequency_ratios", [1.0], [-1.0], {}), ("frequency_ratios", [1.0], [NAN], {}),
    ("frequency_ratios", [1.0], [0.0], {}),
    ("sign", [1.0], [1.0], dict(sign=0)), ("sign", [1.0], [1.0], dict(sign=2)),
    ("sign", [1.0], [1.0], dict(sign=[1, 0])), ("sign", [1.0], [1.0], dict(sign="all")),
    ("pulse", [1.0], [1.0], dict(pulse="square")),
    ("rtol", [1.0], [1.0], dict(rtol=0.0)), ("t_after", [1.0], [1.0], dict(t_after=-1.0)),
])
def test_overturning_spectrum(body, name, amps, freqs, kw):
    with pytest.raises(ValueError, match=field(name)):
        fr.overturning_spectrum(body, amps, freqs, progress=False, **kw)


def test_overturning_spectrum_huge_ratio(body):
    try:
        df = fr.overturning_spectrum(body, [HUGE], [1.0], progress=False)
    except ValueError as exc:
        assert "amplitude_ratios" in str(exc)
    else:
        raise AssertionError(f"accepted, status {df['status'].tolist()}")


# ---------------------------------------------------------------- CLI

@pytest.mark.parametrize("command", ["simulate", "spectrum"])
def test_cli_reports_bad_alpha(command, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    argv = [command, "--alpha", "2"] + (["--quiet"] if command == "spectrum" else [])
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastrock: error:")
    assert "alpha" in err
    assert list(tmp_path.iterdir()) == [], "nothing written on a validation error"


def test_cli_reports_bad_restitution(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["simulate", "--e", "1.5"]) == 2
    assert "e must" in capsys.readouterr().err
