"""Compile (or load from the on-disk cache) kernels ahead of time."""
from __future__ import annotations

import time

import numpy as np


def _rigid(wall=None):
    from .bodies import RigidBlock
    from .excitation import Pulse
    from .simulate import simulate
    from .spectrum import overturning_spectrum
    b = RigidBlock.rectangle(b=0.2, h=1.0)
    simulate(b, Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"), wall=wall,
             duration=1.0)
    overturning_spectrum(b, [3.0], [2.0], wall=wall, progress=False)


def _wall():
    from .wall import Wall
    _rigid(Wall(gap=0.01))


def _foundation():
    from .bodies import RigidBlock
    from .foundation import (LinearVibration, SwitchingFoundation, TwoSpringFoundation,
                             simulate_foundation)
    b = RigidBlock.rectangle(b=0.1, h=0.5)
    for f in (TwoSpringFoundation.from_vibration(b, 30.0, 0.05),
              SwitchingFoundation.from_vibration(b, 30.0, 0.05), LinearVibration(10.0, 0.1)):
        simulate_foundation(b, f, theta0=0.05, duration=0.5)


def _friction():
    from .bodies import RigidBlock
    from .excitation import Pulse
    from .friction import Friction
    from .simulate import simulate
    from .spectrum import overturning_spectrum
    b = RigidBlock(alpha=0.2, p=2.0)
    simulate(b, Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
             friction=Friction(0.3), duration=1.0)
    overturning_spectrum(b, [3.0], [2.0], friction=Friction(0.3), progress=False)


MODELS = {"rigid": _rigid, "friction": _friction, "wall": _wall, "foundation": _foundation}


def warmup(models=None):
    """Compile the named kernels (default all); yields (name, seconds)."""
    names = models or list(MODELS)
    for name in names:
        if name not in MODELS:
            raise ValueError(f"unknown model {name!r}; choose from {sorted(MODELS)}")
        t0 = time.perf_counter()
        MODELS[name]()
        yield name, time.perf_counter() - t0
