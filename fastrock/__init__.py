"""fastrock: fast event-driven simulation of rocking, sliding and overturning
of free-standing bodies under earthquake ground motion.

Importing fastrock compiles nothing; kernels compile (or load from the
on-disk cache) at their first call.  ``fastrock warmup`` compiles ahead.
"""
from .bodies import FlexibleBody, RigidBlock, housner_restitution
from .excitation import Pulse, SampledMotion
from .solver import Solver
from .simulate import SimulationResult, simulate
from .spectrum import overturning_spectrum
from .friction import Friction
from .records import GroundMotion, read_record
from .foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation, simulate_foundation
from .wall import Wall

__all__ = [
    "RigidBlock", "FlexibleBody", "housner_restitution", "Pulse", "SampledMotion", "Solver",
    "SimulationResult", "simulate", "overturning_spectrum", "Friction", "GroundMotion", "read_record",
    "Wall",
]
__version__ = "0.1.0"
