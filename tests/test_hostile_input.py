"""Hostile input (issue #14, item 3): every public entry point refuses malformed arguments before
any kernel runs, with an error that names the argument.

One table per front door: the Python API, TOML files (scenes and studies), record files and the
command line.  Every row is a malformed input that was tried; each must raise a ValueError (or a
subclass: StudyError, RecordFormatError) or TypeError naming the argument, option, section or
file.  An autouse guard replaces every kernel entry (``call_kernel``, ``run_sweep``) by a function
that fails the test, so an accepted input shows up as "reached a kernel" instead of running, and
an alarm fails any row that takes longer than ``HANG_SECONDS`` (no input may hang).  CLI rows run
``fastrock.cli.main`` in-process and must end with exit status 2 and one error line on stderr
naming the option, without a traceback; a few rows run the real ``fastrock`` process as well.

Kept separate from tests/test_validation.py (the first round of field checks) and
tests/test_records_malformed.py (decimal commas, several columns, implausible units): the rows
here are new inputs.
"""
from __future__ import annotations

import decimal
import importlib
import math
import re
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import fastrock as fr
from fastrock.cli import app as cli
from fastrock.model.foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation
from fastrock.analyses.foundation_predictors import make_predictor
from fastrock.running.foundation import simulate_foundation
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.readers import read_record
from fastrock.running.scene import Scene
from fastrock.running.solver import Solver
from fastrock.running.sweep import run_sweep as unstubbed_run_sweep

NAN = math.nan
INF = math.inf
HANG_SECONDS = 20


class ReachedKernel(AssertionError):
    """The input was accepted: a kernel was about to run."""


def _refuse(*args, **kwargs):
    raise ReachedKernel("the input was accepted and reached a kernel")


class Hang(AssertionError):
    pass


@pytest.fixture(autouse=True)
def no_kernel_no_hang(monkeypatch):
    # the modules, not the functions of the same name that fastrock/__init__.py exports
    mod = {m: importlib.import_module(f"fastrock.{m}")
           for m in ("running.sweep", "running.simulate", "running.foundation", "studies.worker",
                     "analyses.spectrum", "analyses.rocking_spectrum.engine")}
    for m in ("running.sweep", "running.simulate", "running.foundation", "studies.worker"):
        monkeypatch.setattr(mod[m], "call_kernel", _refuse)
    for m in ("running.sweep", "analyses.rocking_spectrum.engine"):
        monkeypatch.setattr(mod[m], "run_sweep", _refuse)
    monkeypatch.setattr(mod["analyses.spectrum"], "run_chunks", _refuse)

    def alarm(signum, frame):
        raise Hang(f"no answer within {HANG_SECONDS} s")
    old = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(HANG_SECONDS)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def names(*fields):
    """Regex: one of ``fields`` as a whole word (not a part of another name)."""
    return "|".join(rf"(?<![\w.]){f}(?![\w])" for f in fields)


# ---------------------------------------------------------------- fixtures of the table
BODY = fr.RigidBlock(alpha=0.2, p=2.0)
RECT = fr.RigidBlock.rectangle(b=0.2, h=1.0)
FLEX = dict(alpha=0.2, p=2.0, omega_n_over_p=5.0)
PULSE = fr.Pulse(1.0, 1.0)
_t = np.arange(400) * 0.01
GM = GroundMotion(0.2 * 9.81 * np.sin(2 * np.pi * 1.5 * _t) * np.exp(-_t / 2), 0.01, name="synthetic")
SPEC = dict(progress=False)


def flex(**kw):
    return fr.FlexibleBody(**{**FLEX, **kw})


def sim(**kw):
    kw.setdefault("duration", 1.0)
    return fr.simulate(BODY, PULSE, **kw)


def spectrum(amps=(1.0,), freqs=(1.0,), **kw):
    return fr.overturning_spectrum(BODY, list(amps) if not isinstance(amps, str) else amps,
                                   list(freqs) if not isinstance(freqs, str) else freqs, progress=False, **kw)


def rocking(**kw):
    from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
    kw.setdefault("slenderness", [0.2])
    kw.setdefault("half_widths", [0.3])
    kw.setdefault("walls", [None])
    return rocking_spectrum(kw.pop("records", GM), progress=False, **kw)


def study(**kw):
    from fastrock.studies.definition import Study
    args = dict(records=[GM], bodies=[RECT], levels=[0.1, 0.2])
    args.update(kw)
    return Study(**args).prepare()


def run_study(tmp, **kw):
    from fastrock.studies.definition import Study
    from fastrock.studies.run import run_study
    return run_study(Study(records=[GM], bodies=[RECT], levels=[0.1]), tmp, progress=False, **kw)


def mss(**kw):
    from fastrock.analyses.rocking_spectrum.bisection import minimum_stable_slenderness
    kw.setdefault("b", 0.3)
    return minimum_stable_slenderness(GM, **kw)


def sim_record(**kw):
    from fastrock.analyses.rocking_spectrum.single_runs import simulate_record
    return simulate_record(RECT, GM, **kw)


def _fragility_frame():
    import pandas as pd
    return pd.DataFrame({"record": ["a", "a", "b", "b"], "outcome": ["safe", "mode1", "safe", "mode2"],
                         "pga_g": [0.1, 0.5, 0.2, 0.4], "max_rotation_ratio": [0.1, 2.0, 0.3, 2.0]})


def fragility(**kw):
    from fastrock.analyses.fragility import fit_fragility
    return fit_fragility(_fragility_frame(), **kw)


def work_precision(**kw):
    from fastrock.analyses.accuracy import work_precision
    args = dict(models=("rigid",), excitations=("pulse",), rtols=(1e-6,), dts=(1e-3,), progress=False)
    args.update(kw)
    return work_precision(**args)


def free(fn, *args, **kw):
    from fastrock.analyses.freerocking import fitting, housner, periods
    home = next(m for m in (fitting, housner, periods) if hasattr(m, fn))
    return getattr(home, fn)(*args, **kw)


def big_grid():
    return spectrum(np.linspace(0.5, 8.0, 4000), np.linspace(0.2, 10.0, 4000))


# ---------------------------------------------------------------- the API table
#: (id, call, expected exception, regex naming the argument)
API = [
    # RigidBlock
    ("rigid-alpha-numeric-string", lambda: fr.RigidBlock(alpha="0.2", p=2.0), ValueError, names("alpha")),
    ("rigid-alpha-list", lambda: fr.RigidBlock(alpha=[0.2], p=2.0), ValueError, names("alpha")),
    ("rigid-alpha-array", lambda: fr.RigidBlock(alpha=np.array([0.2, 0.3]), p=2.0), ValueError, names("alpha")),
    ("rigid-alpha-bool", lambda: fr.RigidBlock(alpha=True, p=2.0), ValueError, names("alpha")),
    ("rigid-alpha-complex", lambda: fr.RigidBlock(alpha=0.2 + 0j, p=2.0), ValueError, names("alpha")),
    ("rigid-alpha-decimal", lambda: fr.RigidBlock(alpha=decimal.Decimal("0.2"), p=2.0), ValueError,
     names("alpha")),
    ("rigid-p-string", lambda: fr.RigidBlock(alpha=0.2, p="2"), ValueError, names("p")),
    ("rigid-p-bool", lambda: fr.RigidBlock(alpha=0.2, p=True), ValueError, names("p")),
    ("rigid-p-none", lambda: fr.RigidBlock(alpha=0.2, p=None), ValueError, names("p")),
    ("rigid-p-minus-inf", lambda: fr.RigidBlock(alpha=0.2, p=-INF), ValueError, names("p")),
    ("rigid-e-string", lambda: fr.RigidBlock(alpha=0.2, p=2.0, e="0.5"), ValueError, names("e")),
    ("rigid-e-inf", lambda: fr.RigidBlock(alpha=0.2, p=2.0, e=INF), ValueError, names("e")),
    ("rigid-e-bool", lambda: fr.RigidBlock(alpha=0.2, p=2.0, e=True), ValueError, names("e")),
    ("rigid-g-inf", lambda: fr.RigidBlock(alpha=0.2, p=2.0, g=INF), ValueError, names("g")),
    ("rigid-g-string", lambda: fr.RigidBlock(alpha=0.2, p=2.0, g="9.81"), ValueError, names("g")),
    ("rigid-g-none", lambda: fr.RigidBlock(alpha=0.2, p=2.0, g=None), ValueError, names("g")),
    ("rigid-theta_over-string", lambda: fr.RigidBlock(alpha=0.2, p=2.0, theta_over="1.5"), ValueError,
     names("theta_over")),
    ("rigid-theta_over-negative", lambda: fr.RigidBlock(alpha=0.2, p=2.0, theta_over=-1.0), ValueError,
     names("theta_over")),
    ("rigid-theta_over-inf", lambda: fr.RigidBlock(alpha=0.2, p=2.0, theta_over=INF), ValueError,
     names("theta_over")),
    ("rigid-b-string", lambda: fr.RigidBlock(alpha=0.2, p=2.0, b="0.2"), ValueError, names("b")),
    ("rigid-h-negative", lambda: fr.RigidBlock(alpha=0.2, p=2.0, h=-1.0), ValueError, names("h")),
    ("rectangle-b-none", lambda: fr.RigidBlock.rectangle(b=None, h=1.0), ValueError, names("b")),
    ("rectangle-h-string", lambda: fr.RigidBlock.rectangle(b=0.2, h="1.0"), ValueError, names("h")),
    ("rectangle-b-bool", lambda: fr.RigidBlock.rectangle(b=True, h=1.0), ValueError, names("b")),
    ("rectangle-e-string", lambda: fr.RigidBlock.rectangle(b=0.2, h=1.0, e="x"), ValueError, names("e")),
    ("rectangle-theta_over-below-alpha", lambda: fr.RigidBlock.rectangle(b=0.2, h=1.0, theta_over=0.1),
     ValueError, names("theta_over")),
    ("from_inertia-I0-nan", lambda: fr.RigidBlock.from_inertia(R=1.0, alpha=0.2, I0=NAN, m=1.0), ValueError,
     names("I0")),
    ("from_inertia-R-string", lambda: fr.RigidBlock.from_inertia(R="1", alpha=0.2, I0=2.0, m=1.0), ValueError,
     names("R")),
    ("from_inertia-m-negative", lambda: fr.RigidBlock.from_inertia(R=1.0, alpha=0.2, I0=2.0, m=-1.0),
     ValueError, names("m")),
    ("from_inertia-g-zero", lambda: fr.RigidBlock.from_inertia(R=1.0, alpha=0.2, I0=2.0, m=1.0, g=0.0),
     ValueError, names("g")),
    ("from_inertia-alpha-zero", lambda: fr.RigidBlock.from_inertia(R=1.0, alpha=0.0, I0=2.0, m=1.0),
     ValueError, names("alpha")),
    # FlexibleBody
    ("flex-omega-zero", lambda: flex(omega_n_over_p=0.0), ValueError, names("omega_n_over_p")),
    ("flex-omega-negative", lambda: flex(omega_n_over_p=-1.0), ValueError, names("omega_n_over_p")),
    ("flex-omega-nan", lambda: flex(omega_n_over_p=NAN), ValueError, names("omega_n_over_p")),
    ("flex-omega-none", lambda: flex(omega_n_over_p=None), ValueError, names("omega_n_over_p")),
    ("flex-omega-string", lambda: flex(omega_n_over_p="5"), ValueError, names("omega_n_over_p")),
    ("flex-zeta-negative", lambda: flex(zeta=-0.1), ValueError, names("zeta")),
    ("flex-zeta-nan", lambda: flex(zeta=NAN), ValueError, names("zeta")),
    ("flex-zeta-string", lambda: flex(zeta="0.05"), ValueError, names("zeta")),
    ("flex-e-above-1", lambda: flex(e=1.5), ValueError, names("e")),
    ("flex-impact-unknown", lambda: flex(impact="rigid"), ValueError, names("impact")),
    ("flex-impact-none", lambda: flex(impact=None), ValueError, names("impact")),
    ("flex-impact-list", lambda: flex(impact=["full-contact"]), ValueError, names("impact")),
    ("flex-rotary-negative", lambda: flex(rotary_inertia_ratio=-1.0), ValueError, names("rotary_inertia_ratio")),
    ("flex-rotary-inf", lambda: flex(rotary_inertia_ratio=INF), ValueError, names("rotary_inertia_ratio")),
    ("flex-mass-zero", lambda: flex(mass=0.0), ValueError, names("mass")),
    ("flex-base-mass-negative", lambda: flex(base_mass_ratio=-0.1), ValueError, names("base_mass_ratio")),
    ("flex-base-mass-nan", lambda: flex(base_mass_ratio=NAN), ValueError, names("base_mass_ratio")),
    ("flex-base-cm-negative", lambda: flex(base_cm_height=-0.1), ValueError, names("base_cm_height")),
    ("flex-theta_over-above-pi", lambda: flex(theta_over=3.5), ValueError, names("theta_over")),
    ("flex-alpha-above-half-pi", lambda: flex(alpha=1.6), ValueError, names("alpha")),
    ("flex-pivot-switch-with-base-mass", lambda: flex(impact="pivot-switch", base_mass_ratio=0.1), ValueError,
     names("impact")),
    ("flex-dims-K-negative", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=-1.0, c=0.0, B=0.2, H=1.0),
     ValueError, names("K")),
    ("flex-dims-c-negative", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=100.0, c=-1.0, B=0.2, H=1.0),
     ValueError, names("c")),
    ("flex-dims-H-nan", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=100.0, c=0.0, B=0.2, H=NAN),
     ValueError, names("H")),
    ("flex-dims-g-negative", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=100.0, c=0.0, B=0.2, H=1.0,
                                                                     g=-9.81), ValueError, names("g")),
    ("flex-dims-g-string", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=100.0, c=0.0, B=0.2, H=1.0,
                                                                   g="9.81"), ValueError, names("g")),
    ("flex-dims-m_b-negative", lambda: fr.FlexibleBody.from_dimensions(m=1.0, K=100.0, c=0.0, B=0.2, H=1.0,
                                                                       m_b=-1.0), ValueError, names("m_b")),
    # Friction
    ("friction-mu_s-negative", lambda: fr.Friction(-0.1), ValueError, names("mu_s")),
    ("friction-mu_s-nan", lambda: fr.Friction(NAN), ValueError, names("mu_s")),
    ("friction-mu_s-string", lambda: fr.Friction("0.5"), ValueError, names("mu_s")),
    ("friction-mu_s-none", lambda: fr.Friction(None), ValueError, names("mu_s")),
    ("friction-mu_s-minus-inf", lambda: fr.Friction(-INF), ValueError, names("mu_s")),
    ("friction-mu_s-bool", lambda: fr.Friction(True), ValueError, names("mu_s")),
    ("friction-mu_k-above-mu_s", lambda: fr.Friction(0.5, 0.6), ValueError, names("mu_k")),
    ("friction-mu_k-negative", lambda: fr.Friction(0.5, -0.1), ValueError, names("mu_k")),
    ("friction-mu_k-inf", lambda: fr.Friction(0.5, INF), ValueError, names("mu_k")),
    ("friction-tolerance-negative", lambda: fr.Friction(0.5, slide_tolerance=-1.0), ValueError,
     names("slide_tolerance")),
    ("friction-tolerance-nan", lambda: fr.Friction(0.5, slide_tolerance=NAN), ValueError,
     names("slide_tolerance")),
    ("friction-lift_off-unknown", lambda: fr.Friction(0.5, lift_off="fly"), ValueError, names("lift_off")),
    ("friction-lift_off-none", lambda: fr.Friction(0.5, lift_off=None), ValueError, names("lift_off")),
    # Wall
    ("wall-gap-negative", lambda: fr.Wall(gap=-0.01), ValueError, names("gap")),
    ("wall-gap-string", lambda: fr.Wall(gap="0.01"), ValueError, names("gap")),
    ("wall-gap-nan", lambda: fr.Wall(gap=NAN), ValueError, names("gap")),
    ("wall-side-zero", lambda: fr.Wall(0.01, side=0), ValueError, names("side")),
    ("wall-side-bool", lambda: fr.Wall(0.01, side=True), ValueError, names("side")),
    ("wall-side-two", lambda: fr.Wall(0.01, side=2), ValueError, names("side")),
    ("wall-height-zero", lambda: fr.Wall(0.01, height=0.0), ValueError, names("height")),
    ("wall-restitution-above-1", lambda: fr.Wall(0.01, restitution=1.5), ValueError, names("restitution")),
    ("wall-friction-negative", lambda: fr.Wall(0.01, friction=-0.1), ValueError, names("friction")),
    ("wall-friction-not-modelled", lambda: fr.simulate(RECT, PULSE, wall=fr.Wall(0.01, friction=0.3)),
     ValueError, names("friction")),
    # foundations
    ("two-spring-k_v-zero", lambda: TwoSpringFoundation(k_v=0.0), ValueError, names("k_v")),
    ("two-spring-k_v-string", lambda: TwoSpringFoundation(k_v="1e6"), ValueError, names("k_v")),
    ("two-spring-c_v-negative", lambda: TwoSpringFoundation(k_v=1e6, c_v=-1.0), ValueError, names("c_v")),
    ("switching-k_t-negative", lambda: SwitchingFoundation(k_t=-1.0), ValueError, names("k_t")),
    ("switching-e_f-above-1", lambda: SwitchingFoundation(k_t=1e4, e_f=1.5), ValueError, names("e_f")),
    ("switching-c_t-nan", lambda: SwitchingFoundation(k_t=1e4, c_t=NAN), ValueError, names("c_t")),
    ("linear-k_t-inf", lambda: LinearVibration(k_t=INF), ValueError, names("k_t")),
    ("from_vibration-omega-zero", lambda: TwoSpringFoundation.from_vibration(RECT, 0.0), ValueError,
     names("omega")),
    ("from_vibration-zeta-negative", lambda: SwitchingFoundation.from_vibration(RECT, 30.0, -0.1), ValueError,
     names("zeta")),
    ("from_vibration-mass-zero", lambda: LinearVibration.from_vibration(RECT, 30.0, mass=0.0), ValueError,
     names("mass")),
    ("from_vibration-body-without-b-h", lambda: TwoSpringFoundation.from_vibration(BODY, 30.0), ValueError,
     names("body")),
    ("simulate_foundation-release-beyond-alpha",
     lambda: simulate_foundation(RECT, TwoSpringFoundation(1e6), theta0=0.25), ValueError, names("theta0")),
    ("simulate_foundation-t_eval-outside",
     lambda: simulate_foundation(RECT, TwoSpringFoundation(1e6), theta0=0.1, duration=1.0, t_eval=[0.5, 2.0]),
     ValueError, names("t_eval")),
    ("simulate_foundation-allow_overturn-string",
     lambda: simulate_foundation(RECT, TwoSpringFoundation(1e6), theta0=0.1, allow_overturn="yes"), ValueError,
     names("allow_overturn")),
    ("make_predictor-max_duration-inf", lambda: make_predictor("two-spring", max_duration=INF), ValueError,
     names("max_duration")),
    ("make_predictor-max_steps-zero", lambda: make_predictor("switching", max_steps=0), ValueError,
     names("max_steps")),
    ("make_predictor-model-unknown", lambda: make_predictor("rubber"), ValueError, names("model")),
    # Pulse
    ("pulse-amplitude-1e12-g", lambda: fr.Pulse(1e12), ValueError, names("amplitude")),
    ("pulse-amplitude-200-g", lambda: fr.Pulse(200.0), ValueError, names("amplitude")),
    ("pulse-amplitude-1e5-m/s2", lambda: fr.Pulse(1e5, amplitude_unit="m/s2"), ValueError, names("amplitude")),
    ("pulse-amplitude-g_tan_alpha-above-bound", lambda: fr.simulate(BODY, fr.Pulse(1000.0,
                                                                    amplitude_unit="g_tan_alpha")),
     ValueError, names("amplitude")),
    ("pulse-amplitude-inf", lambda: fr.Pulse(INF), ValueError, names("amplitude")),
    ("pulse-amplitude-string", lambda: fr.Pulse("1"), ValueError, names("amplitude")),
    ("pulse-amplitude-none", lambda: fr.Pulse(None), ValueError, names("amplitude")),
    ("pulse-frequency-inf", lambda: fr.Pulse(1.0, INF), ValueError, names("frequency")),
    ("pulse-frequency-1e-300-hz", lambda: fr.Pulse(1.0, 1e-300), ValueError, names("frequency")),
    ("pulse-frequency-tiny-omega_p/p", lambda: fr.simulate(BODY, fr.Pulse(1.0, 1e-12, frequency_unit="omega_p/p")),
     ValueError, names("frequency")),
    ("pulse-frequency-string", lambda: fr.Pulse(1.0, "1"), ValueError, names("frequency")),
    ("pulse-sign-bool", lambda: fr.Pulse(1.0, sign=True), ValueError, names("sign")),
    ("pulse-sign-string", lambda: fr.Pulse(1.0, sign="1"), ValueError, names("sign")),
    ("pulse-sign-half", lambda: fr.Pulse(1.0, sign=0.5), ValueError, names("sign")),
    ("pulse-kind-none", lambda: fr.Pulse(1.0, kind=None), ValueError, names("kind")),
    ("pulse-kind-list", lambda: fr.Pulse(1.0, kind=["one-sine"]), ValueError, names("kind")),
    ("pulse-amplitude_unit-none", lambda: fr.Pulse(1.0, amplitude_unit=None), ValueError, names("amplitude_unit")),
    ("pulse-t_start-nan", lambda: fr.Pulse(1.0, t_start=NAN), ValueError, names("t_start")),
    ("pulse-t_start-string", lambda: fr.Pulse(1.0, t_start="0"), ValueError, names("t_start")),
    ("pulse-t_start-1e11", lambda: fr.simulate(BODY, fr.Pulse(1.0, t_start=1e11)), ValueError, names("t_start")),
    ("pulse-rectangular-duration-nan", lambda: fr.Pulse(1.0, kind="rectangular", duration=NAN), ValueError,
     names("duration")),
    ("pulse-rectangular-duration-1e300", lambda: fr.Pulse(1.0, kind="rectangular", duration=1e300), ValueError,
     names("duration")),
    # SampledMotion and records as excitations
    ("sampled-acc-string", lambda: fr.SampledMotion("abc", 0.01), ValueError, names("acc")),
    ("sampled-acc-strings", lambda: fr.SampledMotion(["0", "a"], 0.01), ValueError, names("acc")),
    ("sampled-acc-empty", lambda: fr.SampledMotion([], 0.01), ValueError, names("acc")),
    ("sampled-acc-none", lambda: fr.SampledMotion(None, 0.01), ValueError, names("acc")),
    ("sampled-dt-negative", lambda: fr.SampledMotion(np.zeros(3), -0.01), ValueError, names("dt")),
    ("sampled-dt-string", lambda: fr.SampledMotion(np.zeros(3), "0.01"), ValueError, names("dt")),
    ("sampled-scale-string", lambda: fr.SampledMotion(np.zeros(3), 0.01, scale="2"), ValueError, names("scale")),
    ("sampled-scale-1e12", lambda: fr.simulate(BODY, fr.SampledMotion([0.0, 0.3, -0.2], 0.01, unit="g",
                                                                      scale=1e12)), ValueError, names("scale")),
    ("sampled-acc-1e6-g", lambda: fr.simulate(BODY, fr.SampledMotion([0.0, 1e6, 0.0], 0.01, unit="g")),
     ValueError, names("acc")),
    ("sampled-unit-none", lambda: fr.SampledMotion(np.zeros(3), 0.01, unit=None), ValueError, names("unit")),
    ("sampled-t_start-negative", lambda: fr.SampledMotion(np.zeros(3), 0.01, t_start=-1.0), ValueError,
     names("t_start")),
    ("ground-motion-1e9-m/s2", lambda: fr.simulate(BODY, GroundMotion([0.0, 1e9, 0.0], 0.01)), ValueError,
     names("acc")),
    ("ground-motion-dt-string", lambda: GroundMotion([0.0, 0.1, 0.0], "0.01"), ValueError, names("dt")),
    ("ground-motion-acc-2d", lambda: GroundMotion([[0.0, 0.1], [0.2, 0.0]], 0.01), ValueError, names("acc")),
    ("ground-motion-scaled-string", lambda: GM.scaled("2"), ValueError, names("factor")),
    ("ground-motion-scaled-to-pga-negative", lambda: GM.scaled_to_pga(-0.3), ValueError, names("pga")),
    ("ground-motion-scaled-to-pga-unit", lambda: GM.scaled_to_pga(0.3, unit="furlong/s2"), ValueError,
     names("unit")),
    ("ground-motion-baseline-order-fraction", lambda: GM.baseline_corrected(1.5), ValueError, names("order")),
    ("ground-motion-significant-duration-string", lambda: GM.significant_duration(a="0.05"), ValueError,
     names("a")),
    ("vertical-not-an-excitation", lambda: sim(vertical="x"), ValueError, names("vertical")),
    ("vertical-above-100-g", lambda: sim(vertical=fr.Pulse(1000.0, amplitude_unit="g_tan_alpha")), ValueError,
     names("amplitude")),
    # simulate
    ("simulate-t_eval-before-start", lambda: sim(duration=10.0, t_eval=[-1.0, 5.0]), ValueError, names("t_eval")),
    ("simulate-t_eval-after-end", lambda: sim(t_eval=[0.5, 2.0]), ValueError, names("t_eval")),
    ("simulate-t_eval-after-default-end", lambda: fr.simulate(BODY, PULSE, t_eval=[0.5, 1e3]), ValueError,
     names("t_eval")),
    ("simulate-t_eval-unsorted", lambda: sim(t_eval=[0.5, 0.2]), ValueError, names("t_eval")),
    ("simulate-t_eval-empty", lambda: sim(t_eval=[]), ValueError, names("t_eval")),
    ("simulate-t_eval-strings", lambda: sim(t_eval=["a", "b"]), ValueError, names("t_eval")),
    ("simulate-t_eval-inf", lambda: sim(t_eval=[0.1, INF]), ValueError, names("t_eval")),
    ("simulate-history_capacity-zero", lambda: sim(history_capacity=0), ValueError, names("history_capacity")),
    ("simulate-history_capacity-negative", lambda: sim(history_capacity=-5), ValueError,
     names("history_capacity")),
    ("simulate-history_capacity-float", lambda: sim(history_capacity=1.5), ValueError,
     names("history_capacity")),
    ("simulate-history_capacity-string", lambda: sim(history_capacity="100"), ValueError,
     names("history_capacity")),
    ("simulate-history_capacity-1e12", lambda: sim(history_capacity=10 ** 12), ValueError,
     names("history_capacity")),
    ("simulate-max_steps-fraction", lambda: sim(max_steps=1.7), ValueError, names("max_steps")),
    ("simulate-max_steps-negative", lambda: sim(max_steps=-1), ValueError, names("max_steps")),
    ("simulate-max_steps-inf", lambda: sim(max_steps=INF), ValueError, names("max_steps")),
    ("simulate-max_steps-string", lambda: sim(max_steps="1000"), ValueError, names("max_steps")),
    ("simulate-max_steps-1e13", lambda: sim(max_steps=10 ** 13), ValueError, names("max_steps")),
    ("simulate-max_steps-bool", lambda: sim(max_steps=True), ValueError, names("max_steps")),
    ("simulate-dt-1e-300", lambda: sim(dt=1e-300), ValueError, names("dt")),
    ("simulate-dt-beyond-budget", lambda: sim(dt=1e-9), ValueError, names("dt")),
    ("simulate-dt-nan", lambda: sim(dt=NAN), ValueError, names("dt")),
    ("simulate-dt-string", lambda: sim(dt="0.01"), ValueError, names("dt")),
    ("simulate-dt-zero", lambda: sim(dt=0.0), ValueError, names("dt")),
    ("simulate-rtol-one", lambda: sim(rtol=1.0), ValueError, names("rtol")),
    ("simulate-rtol-1e-20", lambda: sim(rtol=1e-20), ValueError, names("rtol")),
    ("simulate-rtol-string", lambda: sim(rtol="1e-6"), ValueError, names("rtol")),
    ("simulate-atol-negative", lambda: sim(atol=-1e-9), ValueError, names("atol")),
    ("simulate-atol-nan", lambda: sim(atol=NAN), ValueError, names("atol")),
    ("simulate-atol-inf", lambda: sim(atol=INF), ValueError, names("atol")),
    ("simulate-duration-1e12", lambda: sim(duration=1e12), ValueError, names("duration")),
    ("simulate-duration-string", lambda: sim(duration="5"), ValueError, names("duration")),
    ("simulate-duration-bool", lambda: sim(duration=True), ValueError, names("duration")),
    ("simulate-t_after-nan", lambda: fr.simulate(BODY, PULSE, t_after=NAN), ValueError, names("t_after")),
    ("simulate-t_after-1e11", lambda: fr.simulate(BODY, PULSE, t_after=1e11), ValueError, names("t_after")),
    ("simulate-t_after-string", lambda: fr.simulate(BODY, PULSE, t_after="1"), ValueError, names("t_after")),
    ("simulate-theta0-string", lambda: sim(theta0="0.1"), ValueError, names("theta0")),
    ("simulate-theta0-none", lambda: sim(theta0=None), ValueError, names("theta0")),
    ("simulate-dtheta0-inf", lambda: sim(dtheta0=INF), ValueError, names("dtheta0")),
    ("simulate-mass-zero", lambda: sim(mass=0.0), ValueError, names("mass")),
    ("simulate-early_exit-string", lambda: sim(early_exit="yes"), ValueError, names("early_exit")),
    ("simulate-record_breakpoints-string", lambda: sim(record_breakpoints="no"), ValueError,
     names("record_breakpoints")),
    ("simulate-resample_vertical-string", lambda: sim(resample_vertical="no"), ValueError,
     names("resample_vertical")),
    ("simulate-wall-a-number", lambda: sim(wall=0.01), ValueError, names("wall")),
    ("simulate-friction-a-number", lambda: sim(friction=0.5), ValueError, names("friction")),
    ("simulate-foundation-a-string", lambda: sim(foundation="two-spring"), ValueError, names("foundation")),
    ("simulate-solver-a-string", lambda: sim(solver="rk45"), ValueError, names("solver")),
    ("simulate-body-none", lambda: fr.simulate(None, PULSE), ValueError, names("body")),
    ("simulate-theta0-into-wall", lambda: fr.simulate(RECT, PULSE, wall=fr.Wall(0.0), theta0=-0.05), ValueError,
     names("theta0")),
    # Solver
    ("solver-max_step-string", lambda: Solver(max_step="1"), ValueError, names("max_step")),
    ("solver-max_step-zero", lambda: Solver(max_step=0.0), ValueError, names("max_step")),
    ("solver-max_steps-none", lambda: Solver(max_steps=None), ValueError, names("max_steps")),
    ("solver-eps_omega-negative", lambda: Solver(eps_omega=-1.0), ValueError, names("eps_omega")),
    ("solver-eps_t-nan", lambda: Solver(eps_t=NAN), ValueError, names("eps_t")),
    ("solver-record_breakpoints-none", lambda: Solver(record_breakpoints=None), ValueError,
     names("record_breakpoints")),
    # overturning_spectrum
    ("spectrum-amplitude_ratios-empty", lambda: spectrum(amps=[]), ValueError, names("amplitude_ratios")),
    ("spectrum-frequency_ratios-empty", lambda: spectrum(freqs=[]), ValueError, names("frequency_ratios")),
    ("spectrum-amplitude_ratios-2d", lambda: spectrum(amps=[[1.0, 2.0], [3.0, 4.0]]), ValueError,
     names("amplitude_ratios")),
    ("spectrum-amplitude_ratios-string", lambda: spectrum(amps="abc"), ValueError, names("amplitude_ratios")),
    ("spectrum-amplitude_ratios-1e6", lambda: spectrum(amps=[1e6]), ValueError, names("amplitude_ratios")),
    ("spectrum-frequency_ratios-1e-300", lambda: spectrum(freqs=[1e-300]), ValueError, names("frequency_ratios")),
    ("spectrum-frequency_ratios-strings", lambda: spectrum(freqs=["1", "x"]), ValueError,
     names("frequency_ratios")),
    ("spectrum-grid-16e6-runs", big_grid, ValueError, names("amplitude_ratios", "frequency_ratios")),
    ("spectrum-chunk_size-zero", lambda: spectrum(chunk_size=0), ValueError, names("chunk_size")),
    ("spectrum-chunk_size-fraction", lambda: spectrum(chunk_size=1.5), ValueError, names("chunk_size")),
    ("spectrum-chunk_size-negative", lambda: spectrum(chunk_size=-4), ValueError, names("chunk_size")),
    ("spectrum-chunk_size-string", lambda: spectrum(chunk_size="10"), ValueError, names("chunk_size")),
    ("spectrum-chunk_size-bool", lambda: spectrum(chunk_size=True), ValueError, names("chunk_size")),
    ("spectrum-sign-bool", lambda: spectrum(sign=True), ValueError, names("sign")),
    ("spectrum-sign-empty", lambda: spectrum(sign=[]), ValueError, names("sign")),
    ("spectrum-sign-nan", lambda: spectrum(sign=NAN), ValueError, names("sign")),
    ("spectrum-pulse-rectangular", lambda: spectrum(pulse="rectangular"), ValueError, names("pulse")),
    ("spectrum-pulse-none", lambda: spectrum(pulse=None), ValueError, names("pulse")),
    ("spectrum-dt-1e-300", lambda: spectrum(dt=1e-300), ValueError, names("dt")),
    ("spectrum-dt-beyond-budget", lambda: spectrum(dt=1e-8), ValueError, names("dt")),
    ("spectrum-t_after-1e12", lambda: spectrum(t_after=1e12), ValueError, names("t_after")),
    ("spectrum-early_exit-string", lambda: spectrum(early_exit="no"), ValueError, names("early_exit")),
    ("spectrum-boundary_check-string", lambda: spectrum(boundary_check="yes"), ValueError,
     names("boundary_check")),
    ("spectrum-mass-negative", lambda: spectrum(mass=-1.0), ValueError, names("mass")),
    ("run_sweep-chunk_size-zero", lambda: unstubbed_run_sweep(_refuse, np.zeros((3, 2)), np.zeros((3, 4)),
                                                              np.zeros((3, 18)), np.zeros(1), np.zeros((3, 12)),
                                                              chunk_size=0, progress=False),
     ValueError, names("chunk_size")),
    # rocking spectrum and its helpers
    ("rocking-records-missing-file", lambda: rocking(records="/nonexistent/record.at2"), ValueError,
     names("records")),
    ("rocking-records-number", lambda: rocking(records=[5]), ValueError, names("records")),
    ("rocking-slenderness-empty", lambda: rocking(slenderness=[]), ValueError, names("slenderness")),
    ("rocking-slenderness-negative", lambda: rocking(slenderness=[-0.1]), ValueError, names("slenderness")),
    ("rocking-half_widths-zero", lambda: rocking(half_widths=[0.0]), ValueError, names("half_widths")),
    ("rocking-half_widths-strings", lambda: rocking(half_widths=["a"]), ValueError, names("half_widths")),
    ("rocking-walls-text", lambda: rocking(walls=["abc"]), ValueError, names("walls")),
    ("rocking-walls-dict", lambda: rocking(walls=[{"gap": 0.1}]), ValueError, names("walls")),
    ("rocking-walls-negative-gap", lambda: rocking(walls=[-0.1]), ValueError, names("gap")),
    ("rocking-e-string", lambda: rocking(e="0.5"), ValueError, names("e")),
    ("rocking-t_after-1e12", lambda: rocking(t_after=1e12), ValueError, names("t_after")),
    ("rocking-chunk_size-zero", lambda: rocking(chunk_size=0), ValueError, names("chunk_size")),
    ("rocking-chunk_size-fraction", lambda: rocking(chunk_size=1.5), ValueError, names("chunk_size")),
    ("rocking-stable_outcomes-string", lambda: rocking(stable_outcomes="safe"), ValueError,
     names("stable_outcomes")),
    ("rocking-stable_outcomes-unknown", lambda: rocking(stable_outcomes=["stable"]), ValueError,
     names("stable_outcomes")),
    ("rocking-unit-unknown", lambda: rocking(unit="furlong/s2"), ValueError, names("unit")),
    ("rocking-dt-1e-300", lambda: rocking(dt=1e-300), ValueError, names("dt")),
    ("mss-tol-1e-300", lambda: mss(tol=1e-300), ValueError, names("tol")),
    ("mss-scan-fraction", lambda: mss(scan=2.5), ValueError, names("scan")),
    ("mss-scan-1e9", lambda: mss(scan=10 ** 9), ValueError, names("scan")),
    ("mss-sections-fraction", lambda: mss(sections=1.5), ValueError, names("sections")),
    ("mss-lo-above-hi", lambda: mss(lo=0.5, hi=0.2), ValueError, names("lo")),
    ("simulate_record-substeps-zero", lambda: sim_record(fixed_step=True, substeps=0), ValueError,
     names("substeps")),
    ("simulate_record-substeps-fraction", lambda: sim_record(fixed_step=True, substeps=1.5), ValueError,
     names("substeps")),
    ("simulate_record-substeps-1e12", lambda: sim_record(fixed_step=True, substeps=10 ** 12), ValueError,
     names("substeps")),
    # Study, run_study and fragility
    ("study-levels-strings", lambda: study(levels=["a"]), ValueError, names("levels")),
    ("study-levels-empty", lambda: study(levels=[]), ValueError, names("levels")),
    ("study-levels-1e6-g", lambda: study(levels=[1e6]), ValueError, names("levels")),
    ("study-levels-scale-1e9", lambda: study(levels=[1e9], measure="scale"), ValueError, names("levels")),
    ("study-measure-unknown", lambda: study(measure="pgd"), ValueError, names("measure")),
    ("study-bodies-string", lambda: study(bodies=["block"]), ValueError, names("bodies")),
    ("study-variants-bad-wall", lambda: study(variants=[{"wall": "abc"}]), ValueError, names("variants")),
    ("study-solver-unknown-key", lambda: study(solver={"integrator": "rk"}), ValueError, names("solver")),
    ("study-solver-bad-method", lambda: study(solver={"method": "rk"}), ValueError, names("method")),
    ("study-solver-dt-1e-300", lambda: study(solver={"dt": 1e-300}), ValueError, names("dt")),
    ("study-t_after-1e12", lambda: study(t_after=1e12), ValueError, names("t_after")),
    ("study-early_exit-string", lambda: study(early_exit="no"), ValueError, names("early_exit")),
    ("study-records-number", lambda: study(records=[3.5]), ValueError, names("records")),
    ("study-unit-unknown", lambda: study(unit="furlong/s2"), ValueError, names("unit")),
    ("study-dt-negative", lambda: study(dt=-0.01), ValueError, names("dt")),
    ("run_study-chunk_size-string", lambda: run_study("/nonexistent/out", chunk_size="a"), ValueError,
     names("chunk_size")),
    ("run_study-chunk_size-bool", lambda: run_study("/nonexistent/out", chunk_size=True), ValueError,
     names("chunk_size")),
    ("fragility-ci-above-1", lambda: fragility(ci=1.5), ValueError, names("ci")),
    ("fragility-n_boot-negative", lambda: fragility(n_boot=-1), ValueError, names("n_boot")),
    ("fragility-n_boot-fraction", lambda: fragility(n_boot=2.5), ValueError, names("n_boot")),
    ("fragility-im-unknown", lambda: fragility(im="pgd"), ValueError, names("pgd")),
    # free rocking closed forms
    ("freerocking-theta0-beyond-alpha", lambda: free("rocking_period_exact", 0.3, 0.2, 2.0), ValueError,
     names("theta0")),
    ("freerocking-p-zero", lambda: free("rocking_period_exact", 0.1, 0.2, 0.0), ValueError, names("p")),
    ("housner_amplitudes-n-fraction", lambda: free("housner_amplitudes", 0.1, 0.2, 0.8, 1.5), ValueError,
     names("n")),
    ("housner_amplitudes-n-1e12", lambda: free("housner_amplitudes", 0.1, 0.2, 0.8, 10 ** 12), ValueError,
     names("n")),
    ("housner_amplitudes-e-string", lambda: free("housner_amplitudes", 0.1, 0.2, "x", 3), ValueError,
     names("e")),
    ("fit_free_rocking-max_nfev-zero", lambda: free("fit_free_rocking", [0.5, 0.4, 0.3], 0.1, 0.2, max_nfev=0),
     ValueError, names("max_nfev")),
    # accuracy
    ("work_precision-rtols-zero", lambda: work_precision(rtols=(0.0,)), ValueError, names("rtols")),
    ("work_precision-dts-negative", lambda: work_precision(dts=(-1e-3,)), ValueError, names("dts")),
    ("work_precision-grid-zero", lambda: work_precision(grid=0), ValueError, names("grid")),
    ("work_precision-threads-fraction", lambda: work_precision(threads=1.5), ValueError, names("threads")),
    ("work_precision-models-unknown", lambda: work_precision(models=("granite",)), ValueError, names("models")),
    ("work_precision-t_after-negative", lambda: work_precision(t_after=-1.0), ValueError, names("t_after")),
]


@pytest.mark.parametrize("call,exc,pattern", [pytest.param(c, e, p, id=i) for i, c, e, p in API])
def test_api_refuses(call, exc, pattern):
    with pytest.raises(exc, match=pattern):
        call()


# ---------------------------------------------------------------- record files
#: (id, file content, read_record keywords, expected exception, regex; FILE stands for the path)
RECORD_FILES = [
    ("empty", "", dict(unit="g", dt=0.01), "format", "FILE"),
    ("blank-lines-only", "\n \n\t\n", dict(unit="g", dt=0.01), "format", "FILE"),
    ("header-only", "ACCELERATION IN UNITS OF G\nstation 12\n", dict(dt=0.01), "format", "FILE"),
    ("binary-garbage", bytes(np.random.default_rng(0).integers(0, 256, 2000, dtype=np.uint8)),
     dict(unit="g", dt=0.01), "format", "FILE"),
    ("nul-bytes", b"\x00" * 256, dict(unit="g", dt=0.01), "format", "FILE"),
    ("nan-sample", "0.01\n0.02\nnan\n0.01\n", dict(unit="g", dt=0.01), "format", "FILE"),
    ("inf-sample", "0.01\n-inf\n0.02\n", dict(unit="g", dt=0.01), "format", "FILE"),
    ("overflowing-sample", "0.01\n1e400\n0.02\n", dict(unit="g", dt=0.01), "format", "FILE"),
    ("text-inside-data", "0.01\n0.02\nabc\n0.03\n", dict(unit="g", dt=0.01), "format", "FILE"),
    ("time-column-non-uniform", "0.00 0.01\n0.01 0.02\n0.03 0.01\n0.04 0.00\n0.05 0.01\n", dict(unit="g"),
     "format", "FILE"),
    ("time-column-decreasing", "0.00 0.01\n0.02 0.02\n0.01 0.01\n0.03 0.00\n", dict(unit="g"), "format",
     "FILE"),
    ("time-column-repeated", "0.00 0.01\n0.00 0.02\n0.01 0.01\n0.02 0.00\n", dict(unit="g"), "format", "FILE"),
    ("at2-npts-mismatch", "PEER\nACCELERATION IN UNITS OF G\nNPTS= 5, DT= 0.01\n0.1 0.2 0.3\n", {}, "format",
     "FILE"),
    ("at2-dt-zero", "PEER\nACCELERATION IN UNITS OF G\nNPTS= 3, DT= 0.0\n0.1 0.2 0.3\n", {}, ValueError,
     "FILE|DT|dt"),
    ("at2-dt-negative", "PEER\nACCELERATION IN UNITS OF G\nNPTS= 3, DT= -0.01\n0.1 0.2 0.3\n", {}, ValueError,
     "FILE|DT|dt"),
    ("velocity-history", "VELOCITY TIME HISTORY IN CM/S\nNPTS= 3, DT= 0.01\n0.1 0.2 0.3\n", {}, "format", "FILE"),
    ("unit-unknown", "0.01\n0.02\n0.01\n", dict(unit="furlong/s2", dt=0.01), ValueError, names("unit")),
    ("unit-number", "0.01\n0.02\n0.01\n", dict(unit=5, dt=0.01), ValueError, names("unit")),
    ("unit-missing", "0.01\n0.02\n0.01\n", dict(dt=0.01), ValueError, names("unit")),
    ("unit-contradicts-header", "ACCELERATION IN UNITS OF G\nNPTS= 3, DT= 0.01\n0.1 0.2 0.3\n",
     dict(unit="cm/s2"), ValueError, names("unit")),
    ("dt-missing", "0.01\n0.02\n0.01\n", dict(unit="g"), ValueError, names("dt")),
    ("dt-negative", "0.01\n0.02\n0.01\n", dict(unit="g", dt=-0.01), ValueError, names("dt")),
    ("dt-string", "0.01\n0.02\n0.01\n", dict(unit="g", dt="0.01"), ValueError, names("dt")),
    ("dt-nan", "0.01\n0.02\n0.01\n", dict(unit="g", dt=NAN), ValueError, names("dt")),
    ("dt-contradicts-time-column", "0.00 0.01\n0.01 0.02\n0.02 0.01\n", dict(unit="g", dt=0.02), ValueError,
     names("dt")),
    ("column-fraction", "0.01\n0.02\n0.01\n", dict(unit="g", dt=0.01, column=1.5), ValueError, names("column")),
    ("column-word", "0.01\n0.02\n0.01\n", dict(unit="g", dt=0.01, column="x"), ValueError, names("column")),
    ("column-bool", "0.01\n0.02\n0.01\n", dict(unit="g", dt=0.01, column=True), ValueError, names("column")),
    ("column-out-of-range", "0.00 0.01 0.5\n0.01 0.02 0.5\n0.02 0.01 0.5\n", dict(unit="g", column=7),
     ValueError, names("column")),
    ("decimal-semicolon", "0.01\n0.02\n0.01\n", dict(unit="g", dt=0.01, decimal=";"), ValueError,
     names("decimal")),
    ("name-number", "0.01\n0.02\n0.01\n", dict(unit="g", dt=0.01, name=5), ValueError, names("name")),
]


@pytest.mark.parametrize("content,kw,exc,pattern", [pytest.param(c, k, e, p, id=i) for i, c, k, e, p in
                                                    RECORD_FILES])
def test_record_file_refused(tmp_path, content, kw, exc, pattern):
    from fastrock.io.ground_motion import RecordFormatError
    path = tmp_path / "record.txt"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    pattern = pattern.replace("FILE", "record\\.txt")
    with pytest.raises(RecordFormatError if exc == "format" else exc, match=pattern):
        read_record(path, **kw)


@pytest.mark.parametrize("path", [None, 5, ["a.txt"]], ids=["none", "number", "list"])
def test_record_path_must_be_a_path(path):
    with pytest.raises(ValueError, match=names("path")):
        read_record(path, unit="g", dt=0.01)


# ---------------------------------------------------------------- TOML files
GOOD_BODY = "[body]\nalpha = 0.2\np = 2.0\n"
GOOD_PULSE = "[excitation]\namplitude = 1.0\nfrequency = 1.0\n"

#: (id, scene file text, regex naming the section or key); the scene is read and run
SCENES = [
    ("unknown-section", GOOD_BODY + "[bogus]\nx = 1\n", names("bogus")),
    ("unknown-body-key", GOOD_BODY + "colour = 'red'\n", names("colour")),
    ("body-alpha-string", "[body]\nalpha = '0.2'\np = 2.0\n", names("alpha")),
    ("body-alpha-array", "[body]\nalpha = [0.1, 0.2]\np = 2.0\n", names("alpha")),
    ("body-not-a-table", "body = 5\n", names("body")),
    ("body-missing", GOOD_PULSE, names("body")),
    ("body-empty", "[body]\n", names("body")),
    ("body-missing-p", "[body]\nalpha = 0.2\n", names("p")),
    ("body-type-unknown", "[body]\ntype = 'soft'\nalpha = 0.2\np = 2.0\n", names("type")),
    ("body-flexible-no-omega", "[body]\ntype = 'flexible'\nalpha = 0.2\np = 2.0\n", names("omega_n_over_p")),
    ("excitation-type-unknown", GOOD_BODY + "[excitation]\ntype = 'noise'\n", names("type")),
    ("excitation-amplitude-1e12", GOOD_BODY + "[excitation]\namplitude = 1e12\n", names("amplitude")),
    ("excitation-missing-amplitude", GOOD_BODY + "[excitation]\nfrequency = 1.0\n", names("amplitude")),
    ("excitation-sign-zero", GOOD_BODY + GOOD_PULSE + "sign = 0\n", names("sign")),
    ("excitation-record-missing-file", GOOD_BODY + "[excitation]\ntype = 'record'\nfile = 'nope.at2'\n",
     names("file")),
    ("excitation-record-scale-1e9", GOOD_BODY + "[excitation]\ntype = 'record'\nscale = 1e9\n", names("scale")),
    ("vertical-not-a-table", GOOD_BODY + GOOD_PULSE + "vertical = 'strong'\n", names("vertical")),
    ("solver-max_steps-fraction", GOOD_BODY + GOOD_PULSE + "[solver]\nmax_steps = 1.5\n", names("max_steps")),
    ("solver-dt-1e-300", GOOD_BODY + GOOD_PULSE + "[solver]\ndt = 1e-300\n", names("dt")),
    ("solver-unknown-key", GOOD_BODY + GOOD_PULSE + "[solver]\nmethod = 'rk4'\n", names("method")),
    ("run-duration-negative", GOOD_BODY + GOOD_PULSE + "[run]\nduration = -1.0\n", names("duration")),
    ("run-theta0-string", GOOD_BODY + "[run]\ntheta0 = 'tilted'\nduration = 1.0\n", names("theta0")),
    ("run-t_eval-not-allowed", GOOD_BODY + GOOD_PULSE + "[run]\nt_eval = [0.1]\n", names("t_eval")),
    ("wall-gap-negative", "[body]\nb = 0.2\nh = 1.0\n" + GOOD_PULSE + "[wall]\ngap = -0.01\n", names("gap")),
    ("wall-missing-gap", "[body]\nb = 0.2\nh = 1.0\n" + GOOD_PULSE + "[wall]\nside = 1\n", names("gap")),
    ("friction-mu_s-string", GOOD_BODY + GOOD_PULSE + "[friction]\nmu_s = 'high'\n", names("mu_s")),
    ("foundation-type-unknown", "[body]\nb = 0.2\nh = 1.0\n[foundation]\ntype = 'rubber'\n", names("type")),
    ("foundation-k_v-zero", "[body]\nb = 0.2\nh = 1.0\n[foundation]\ntype = 'two-spring'\nk_v = 0.0\n",
     names("k_v")),
    ("foundation-missing-k_v", "[body]\nb = 0.2\nh = 1.0\n[foundation]\ntype = 'two-spring'\nc_v = 1.0\n",
     names("k_v")),
    ("output-csv-number", GOOD_BODY + GOOD_PULSE + "[output]\ncsv = 5\n", names("csv")),
    ("not-toml", "[body\nalpha = \n", "TOML"),
]


@pytest.mark.parametrize("text,pattern", [pytest.param(t, p, id=i) for i, t, p in SCENES])
def test_scene_file_refused(tmp_path, text, pattern):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=pattern):
        Scene.from_toml(path).run()


def test_scene_file_missing(tmp_path):
    with pytest.raises(ValueError, match="scene file"):
        Scene.from_toml(tmp_path / "nope.toml")


GOOD_STUDY = """\
records = ["default"]
levels = [0.1, 0.2]
[[bodies]]
b = 0.2
h = 1.0
"""

#: (id, study file text, regex); the study is read and prepared (nothing runs)
STUDIES = [
    ("unknown-key", GOOD_STUDY + "colour = 'red'\n", names("colour")),
    ("levels-missing", 'records = ["default"]\n[[bodies]]\nb = 0.2\nh = 1.0\n', names("levels")),
    ("levels-table-without-num", GOOD_STUDY.replace("levels = [0.1, 0.2]", "levels = {start = 0.1, stop = 1.0}"),
     names("num")),
    ("levels-table-num-fraction",
     GOOD_STUDY.replace("levels = [0.1, 0.2]", "levels = {start = 0.1, stop = 1.0, num = 2.5}"), names("num")),
    ("levels-negative", GOOD_STUDY.replace("[0.1, 0.2]", "[-0.1]"), names("levels")),
    ("levels-strings", GOOD_STUDY.replace("[0.1, 0.2]", "['low', 'high']"), names("levels")),
    ("levels-1000-g", GOOD_STUDY.replace("[0.1, 0.2]", "[1000.0]"), names("levels")),
    ("records-not-a-list", GOOD_STUDY.replace('records = ["default"]', "records = 5"), names("records")),
    ("records-number-entry", GOOD_STUDY.replace('records = ["default"]', "records = [5]"), names("records")),
    ("records-missing-file", GOOD_STUDY.replace('"default"', '"nope.at2"'), names("nope")),
    ("bodies-alpha-string", GOOD_STUDY.replace("b = 0.2\nh = 1.0", "alpha = 'x'\np = 2.0"), names("alpha")),
    ("bodies-list-explosion", GOOD_STUDY.replace("b = 0.2\nh = 1.0", "alpha = [%s]\np = [%s]" % (
        ", ".join(["0.2"] * 400), ", ".join(["2.0"] * 400))), names("bodies")),
    ("variant-wall-gap-negative", GOOD_STUDY + "[[variants]]\nwall = {gap = -1.0}\n", names("gap")),
    ("variant-unknown-key", GOOD_STUDY + "[[variants]]\ncolour = 'red'\n", names("colour")),
    ("solver-rtol-zero", GOOD_STUDY + "[solver]\nrtol = 0.0\n", names("rtol")),
    ("run-chunk_size-zero", GOOD_STUDY + "[run]\nchunk_size = 0\n", names("chunk_size")),
    ("run-backend-unknown", GOOD_STUDY + "[run]\nbackend = 'mpi'\n", names("backend")),
    ("t_after-negative", "t_after = -1.0\n" + GOOD_STUDY, names("t_after")),
    ("early_exit-string", "early_exit = 'no'\n" + GOOD_STUDY, names("early_exit")),
    ("measure-unknown", "measure = 'pgd'\n" + GOOD_STUDY, names("measure")),
]


@pytest.mark.parametrize("text,pattern", [pytest.param(t, p, id=i) for i, t, p in STUDIES])
def test_study_file_refused(tmp_path, text, pattern):
    from fastrock.studies.definition import Study, StudyError
    path = tmp_path / "study.toml"
    path.write_text(text)
    with pytest.raises(StudyError, match=pattern):
        Study.from_toml(path).prepare()


# ---------------------------------------------------------------- the command line
def opt(name):
    """Regex: the option ``--name`` or the argument ``name`` it sets."""
    return rf"--{name}\b|(?<![\w.-]){name.replace('-', '_')}\b"


#: (id, argv, regex naming the option); {dir} is the test's folder (see cli_files)
CLI = [
    ("spectrum-alpha-negative", "spectrum --alpha -0.1", opt("alpha")),
    ("spectrum-alpha-nan", "spectrum --alpha nan", opt("alpha")),
    ("spectrum-alpha-word", "spectrum --alpha abc", opt("alpha")),
    ("spectrum-p-zero", "spectrum --p 0", opt("p")),
    ("spectrum-n-amp-zero", "spectrum --n-amp 0", opt("n-amp")),
    ("spectrum-n-amp-negative", "spectrum --n-amp -3", opt("n-amp")),
    ("spectrum-n-amp-fraction", "spectrum --n-amp 1.5", opt("n-amp")),
    ("spectrum-n-amp-1e12", "spectrum --n-amp 1000000000000", opt("n-amp")),
    ("spectrum-n-freq-zero", "spectrum --n-freq 0", opt("n-freq")),
    ("spectrum-grid-1e10-runs", "spectrum --n-amp 100000 --n-freq 100000", opt("n-amp")),
    ("spectrum-amp-min-negative", "spectrum --amp-min -1", opt("amp-min")),
    ("spectrum-amp-min-above-max", "spectrum --amp-min 5 --amp-max 1", opt("amp-min")),
    ("spectrum-freq-min-zero", "spectrum --freq-min 0", opt("freq-min")),
    ("spectrum-freq-max-inf", "spectrum --freq-max inf", opt("freq-max")),
    ("spectrum-rtol-zero", "spectrum --rtol 0", opt("rtol")),
    ("spectrum-dt-1e-300", "spectrum --dt 1e-300", opt("dt")),
    ("spectrum-sign-two", "spectrum --sign 2", opt("sign")),
    ("spectrum-pulse-unknown", "spectrum --pulse square", opt("pulse")),
    ("spectrum-mu-s-negative", "spectrum --mu-s -1", opt("mu-s")),
    ("spectrum-mu-k-above-mu-s", "spectrum --mu-s 0.5 --mu-k 0.8", opt("mu-k")),
    ("spectrum-wall-gap-negative", "spectrum --b 0.2 --h 1 --wall-gap -1", "gap"),
    ("spectrum-foundation-without-omega", "spectrum --b 0.2 --h 1 --foundation two-spring",
     opt("foundation-omega")),
    ("spectrum-foundation-mass-zero",
     "spectrum --b 0.2 --h 1 --foundation two-spring --foundation-omega 30 --mass 0", opt("mass")),
    ("spectrum-omega-n-over-p-zero", "spectrum --omega-n-over-p 0", opt("omega-n-over-p")),
    ("simulate-amplitude-1e12", "simulate --amplitude 1e12", opt("amplitude")),
    ("simulate-amplitude-nan", "simulate --amplitude nan", opt("amplitude")),
    ("simulate-frequency-zero", "simulate --frequency 0", opt("frequency")),
    ("simulate-duration-negative", "simulate --duration -1", opt("duration")),
    ("simulate-duration-1e15", "simulate --duration 1e15", opt("duration")),
    ("simulate-theta0-beyond-overturning", "simulate --theta0 2", opt("theta0")),
    ("simulate-dt-zero", "simulate --dt 0", opt("dt")),
    ("simulate-b-without-h", "simulate --b 0.3", opt("h")),
    ("simulate-zeta-negative", "simulate --omega-n-over-p 5 --zeta -1", opt("zeta")),
    ("simulate-amplitude-unit-unknown", "simulate --amplitude-unit furlong", opt("amplitude-unit")),
    ("simulate-wall-side-zero", "simulate --wall-gap 0.01 --wall-side 0", opt("wall-side")),
    ("record-missing-file", "record {dir}/nope.at2", "nope\\.at2"),
    ("record-nan-sample", "record {dir}/nan.txt --unit g --record-dt 0.01", "nan\\.txt"),
    ("record-unit-unknown", "record {dir}/single.txt --unit furlong --record-dt 0.01", opt("unit")),
    ("record-dt-missing", "record {dir}/single.txt --unit g", opt("record-dt")),
    ("record-dt-fixed-word", "record {dir}/good.at2 --dt abc", opt("dt")),
    ("record-dt-fixed-zero", "record {dir}/good.at2 --dt 0", opt("dt")),
    ("record-dt-fixed-1e-300", "record {dir}/good.at2 --dt 1e-300", opt("dt")),
    ("record-t-after-negative", "record {dir}/good.at2 --t-after -1", opt("t-after")),
    ("record-column-word", "record {dir}/good.at2 --column x", opt("column")),
    ("record-wall-gap-negative", "record {dir}/good.at2 --wall-gap -1", "gap"),
    ("record-alpha-without-p", "record {dir}/good.at2 --alpha 0.2", opt("p")),
    ("rocking-n-slenderness-zero", "rocking-spectrum --n-slenderness 0", opt("n-slenderness")),
    ("rocking-n-sizes-negative", "rocking-spectrum --n-sizes -2", opt("n-sizes")),
    ("rocking-walls-word", "rocking-spectrum --walls abc", opt("walls")),
    ("rocking-slenderness-min-negative", "rocking-spectrum --slenderness-min -1", opt("slenderness-min")),
    ("rocking-b-min-zero", "rocking-spectrum --b-min 0", opt("b-min")),
    ("rocking-rtol-two", "rocking-spectrum --rtol 2", opt("rtol")),
    ("rocking-missing-file", "rocking-spectrum {dir}/nope.at2", "nope\\.at2"),
    ("run-missing-scene", "run {dir}/nope.toml", "nope\\.toml"),
    ("run-unknown-key", "run {dir}/bad_scene.toml", "colour"),
    ("run-amplitude-1e12", "run {dir}/strong_scene.toml", opt("amplitude")),
    ("study-missing-file", "study {dir}/nope.toml", "nope\\.toml"),
    ("study-chunk-size-zero", "study {dir}/study.toml --chunk-size 0", opt("chunk-size")),
    ("study-n-boot-negative", "study {dir}/study.toml --n-boot -1", opt("n-boot")),
    ("study-connect-timeout-negative", "study {dir}/study.toml --connect-timeout -5", opt("connect-timeout")),
    ("study-levels-1000-g", "study {dir}/strong_study.toml", opt("levels")),
    ("accuracy-rtols-word", "accuracy --rtols a", opt("rtols")),
    ("accuracy-grid-zero", "accuracy --grid 0", opt("grid")),
    ("accuracy-threads-zero", "accuracy --threads 0", opt("threads")),
    ("accuracy-t-after-negative", "accuracy --t-after -1", opt("t-after")),
    ("accuracy-models-unknown", "accuracy --models granite", opt("models")),
    ("fit-missing-file", "fit {dir}/nope.csv", "nope\\.csv"),
    ("fit-param-malformed", "fit {dir}/nope.csv --param x", opt("param")),
    ("warmup-unknown-model", "warmup granite", "granite"),
    ("unknown-command", "rock", "rock"),
    ("no-command", "", "command"),
]


@pytest.fixture
def cli_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    acc = 0.2 * np.sin(2 * np.pi * 1.5 * _t)
    (tmp_path / "good.at2").write_text("ACCELERATION IN UNITS OF G\nNPTS= 400, DT= 0.01\n"
                                       + "\n".join(f"{v:.6f}" for v in acc) + "\n")
    (tmp_path / "single.txt").write_text("\n".join(f"{v:.6f}" for v in acc) + "\n")
    (tmp_path / "nan.txt").write_text("0.01\n0.02\nnan\n0.01\n")
    (tmp_path / "bad_scene.toml").write_text(GOOD_BODY + "colour = 'red'\n")
    (tmp_path / "strong_scene.toml").write_text(GOOD_BODY + "[excitation]\namplitude = 1e12\n")
    (tmp_path / "study.toml").write_text(GOOD_STUDY)
    (tmp_path / "strong_study.toml").write_text(GOOD_STUDY.replace("[0.1, 0.2]", "[1000.0]"))
    return tmp_path


def run_cli(argv, capsys):
    try:
        code = cli.main(argv)
    except SystemExit as exc:          # argparse's own errors
        code = exc.code
    return code, capsys.readouterr().err


@pytest.mark.parametrize("argv,pattern", [pytest.param(a, p, id=i) for i, a, p in CLI])
def test_cli_refuses(cli_files, capsys, argv, pattern):
    argv = argv.format(dir=cli_files).split()
    before = sorted(p.name for p in cli_files.iterdir())
    code, err = run_cli(argv, capsys)
    assert code == 2, (code, err)
    assert "Traceback" not in err
    errors = [ln for ln in err.splitlines() if "error:" in ln]
    assert len(errors) == 1, err
    assert errors[0].startswith("fastrock"), err
    assert re.search(pattern, errors[0]), errors[0]
    assert sorted(p.name for p in cli_files.iterdir()) == before, "nothing written on an error"


#: A few rows again through a real ``fastrock`` process (its kernels are not stubbed: an accepted
#: input would start compiling and running, caught by the timeout).
PROCESS = ["spectrum-n-amp-zero", "simulate-amplitude-1e12", "record-missing-file", "run-missing-scene",
           "rocking-walls-word", "spectrum-alpha-word"]


@pytest.mark.slow
@pytest.mark.parametrize("case", PROCESS)
def test_cli_process_refuses(cli_files, case):
    _, argv, pattern = next(row for row in CLI if row[0] == case)
    argv = argv.format(dir=cli_files).split()
    proc = subprocess.run([sys.executable, "-m", "fastrock.cli", *argv], capture_output=True, text=True,
                          timeout=60, cwd=cli_files)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    errors = [ln for ln in proc.stderr.splitlines() if "error:" in ln]
    assert len(errors) == 1 and re.search(pattern, errors[0]), proc.stderr


def test_the_table_covers_every_front_door():
    """At least 100 malformed inputs in all, from each of the four front doors."""
    counts = {"api": len(API), "cli": len(CLI), "toml": len(SCENES) + len(STUDIES), "records": len(RECORD_FILES)}
    assert sum(counts.values()) >= 100 and min(counts.values()) >= 20, counts
