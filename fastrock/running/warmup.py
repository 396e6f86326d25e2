"""Compile (or load from the on-disk cache) kernels ahead of time.

Every model of :mod:`fastrock.running.registry` has a small example scene here; warming a model calls its
two entry kernels (single run and parallel sweep) once on that scene, which is what a first
``simulate`` or ``overturning_spectrum`` would compile.
"""
from __future__ import annotations

import time

import numpy as np

#: Names accepted besides the registry's model names, for the families as the README lists them.
FAMILIES = {
    "wall": ("rigid_wall",),
    "friction": ("rigid_friction",),
    "foundation": ("two_spring", "switching", "linear_sdof", "flexible_two_spring"),
}


def _example(name):
    """(body, effects) of a small scene that runs model ``name``."""
    from fastrock.model.bodies import FlexibleBody, RigidBlock
    from fastrock.model.foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation
    from fastrock.model.friction import Friction
    from fastrock.model.rigid_body import RigidBody
    from fastrock.model.wall import Wall
    block = RigidBlock.rectangle(b=0.2, h=1.0)
    flex = FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=9.0, zeta=0.05)
    return {
        "rigid": (block, {}),
        "rigid_body": (RigidBody(mass=1.0, inertia=0.1, b1=0.15, h1=1.0, b2=0.25, h2=1.0), {}),
        "rigid_wall": (block, {"wall": Wall(gap=0.01)}),
        "wall_body": (RigidBody.from_polygon([(0.0, 0.0), (0.5, 0.0), (0.1, 2.0)], mass=1.0),
                      {"wall": Wall(gap=0.01)}),
        "rigid_friction": (block, {"friction": Friction(0.3)}),
        "contact": (block, {"wall": Wall(gap=0.01), "friction": Friction(0.3)}),
        "contact_body": (RigidBody(mass=1.0, inertia=0.1, b1=0.15, h1=1.0, b2=0.25, h2=1.0),
                         {"friction": Friction(0.3)}),
        "flexible": (flex, {}),
        "flexible_friction": (flex, {"friction": Friction(0.5)}),
        "flexible_wall": (flex, {"wall": Wall(gap=0.05)}),
        "flexible_flight": (flex, {"friction": Friction(0.5, lift_off="flight")}),
        "two_spring": (block, {"foundation": TwoSpringFoundation.from_vibration(block, 30.0, 0.05)}),
        "switching": (block, {"foundation": SwitchingFoundation.from_vibration(block, 30.0, 0.05)}),
        "linear_sdof": (block, {"foundation": LinearVibration(10.0, 0.1)}),
        "two_spring_friction": (block, {"foundation": TwoSpringFoundation.from_vibration(block, 30.0, 0.05),
                                        "friction": Friction(0.3)}),
        "flexible_two_spring": (flex, {"foundation": TwoSpringFoundation.from_vibration(flex, 30.0, 0.05)}),
        "two_spring_wall": (block, {"foundation": TwoSpringFoundation.from_vibration(block, 30.0, 0.05),
                                    "wall": Wall(gap=0.01)}),
        "switching_wall": (block, {"foundation": SwitchingFoundation.from_vibration(block, 30.0, 0.05),
                                   "wall": Wall(gap=0.05)}),
    }[name]


def warm_model(name):
    """Call model ``name``'s single-run and sweep entry kernels once (compiling or loading them)."""
    from fastrock.model import excitation as X
    from fastrock.model.excitation import Pulse
    from fastrock.running.registry import select
    from fastrock.running.solver import Solver
    from fastrock.kernels import layout as L
    from fastrock.kernels.hybrid import N_COUNTERS
    body, effects = _example(name)
    spec = select(body, **effects)
    if spec.name != name:
        raise RuntimeError(f"the warm-up scene of {name!r} selects {spec.name!r}")
    y0 = np.zeros(spec.n_state)
    if "foundation" in effects:
        from fastrock.model.foundation import block_inertia
        from fastrock.running.foundation import with_slide
        y0 = with_slide(spec, effects["foundation"].initial_state(block_inertia(body, 1.0), 0.0, 0.0))
    hdr, smp = X.to_header(body, Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha"))
    opt = Solver().options(0.5, False)
    y = y0.copy()
    met = np.zeros(L.N_MET)
    spec.simulate(y, spec.par, hdr, smp, opt, np.empty(0), met, np.empty(8), np.empty((8, spec.n_state)),
                  np.empty((8, 3), np.int64), np.empty((8, L.N_LOG)), np.zeros(N_COUNTERS, np.int64))
    status, MET, YF = np.empty(1, np.int64), np.empty((1, L.N_MET)), np.empty((1, spec.n_state))
    spec.sweep(y0[None, :].copy(), spec.par[None, :].copy(), hdr[None, :].copy(), smp, opt[None, :].copy(),
               status, MET, YF)


def resolve(models=None):
    """Registry model names for ``models`` (model or family names; None: every model)."""
    from fastrock.running.registry import MODELS
    if not models:
        return list(MODELS)
    out = []
    for m in models:
        if m in MODELS:
            out.append(m)
        elif m in FAMILIES:
            out.extend(FAMILIES[m])
        else:
            raise ValueError(f"unknown model {m!r}; choose from {sorted(MODELS)} or {sorted(FAMILIES)}")
    return list(dict.fromkeys(out))


def warmup(models=None):
    """Compile (or load) the named models' kernels (default: every model); yields (name, seconds)."""
    for name in resolve(models):
        t0 = time.perf_counter()
        warm_model(name)
        yield name, time.perf_counter() - t0


def is_ready(kernel):
    """True if a kernel dispatcher already holds a compiled version in this process."""
    return bool(getattr(kernel, "signatures", ()))


#: First-use cost [s] of a model's two entry kernels with an empty cache, measured with
#: ``fastrock warmup`` on this project's 2-core machine under a load of about 3 (docs:
#: guide/install, "Compilation and the kernel cache"); a quiet machine takes about two thirds of it.
TYPICAL_COMPILE_SECONDS = {"rigid": 34, "rigid_body": 27, "rigid_wall": 31, "wall_body": 31, "rigid_friction": 33, "contact": 140, "contact_body": 140,
                           "flexible": 31, "flexible_friction": 43, "flexible_wall": 40, "flexible_flight": 52, "two_spring": 30, "switching": 30,
                           "linear_sdof": 29, "two_spring_friction": 37, "flexible_two_spring": 31,
                           "two_spring_wall": 35, "switching_wall": 35}


def compile_notice(name, kernel=None):
    """The line shown before the first call of model ``name``'s kernel in this process."""
    typical = TYPICAL_COMPILE_SECONDS.get(name)
    around = f"about {typical} s" if typical else "up to a minute"
    return (f"fastrock: first use of the {name} kernel in this process: loading it from the on-disk "
            f"cache, or compiling it ({around}) if it is not there yet (`fastrock warmup` does it ahead)")


__all__ = ["warmup", "warm_model", "resolve", "compile_notice", "FAMILIES"]
