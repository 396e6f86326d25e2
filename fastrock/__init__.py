"""fastrock: fast event-driven simulation of rocking, sliding and overturning
of free-standing bodies under earthquake ground motion.

Importing fastrock compiles nothing; kernels compile (or load from the
on-disk cache) at their first call.  ``fastrock warmup`` compiles ahead.
"""


def _source_checkout_kernels():
    """The compiled layer is the folder kernels/ beside this one, installed as fastrock.kernels
    through setuptools' package-dir.  In a source checkout (a REPL or notebook started in the
    repository root, where this folder shadows the installed package) load it from there."""
    import importlib.util
    import os
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    sibling = os.path.join(os.path.dirname(here), "kernels", "__init__.py")
    if ("fastrock.kernels" in sys.modules or os.path.isdir(os.path.join(here, "kernels"))
            or not os.path.isfile(sibling)):
        return
    spec = importlib.util.spec_from_file_location("fastrock.kernels", sibling,
                                                  submodule_search_locations=[os.path.dirname(sibling)])
    module = importlib.util.module_from_spec(spec)
    sys.modules["fastrock.kernels"] = module
    spec.loader.exec_module(module)
    globals()["kernels"] = module


_source_checkout_kernels()

from .bodies import FlexibleBody, RigidBlock, housner_restitution  # noqa: E402
from .constants import G_STANDARD
from .excitation import Pulse, SampledMotion
from .solver import Solver
from .simulate import SimulationResult, simulate
from .spectrum import overturning_spectrum
from .friction import Friction
from .records import GroundMotion, read_record
from .foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation, simulate_foundation
from .wall import Wall
from .freerocking import FreeRockingFit, fit_free_rocking, half_cycles
from .rocking_spectrum import rocking_spectrum
from .scene import Scene
from .study import FragilityFit, Study, fit_fragility, plot_fragility, run_study

__all__ = [
    # bodies, scenes and excitations
    "RigidBlock", "FlexibleBody", "housner_restitution", "Wall", "Friction",
    "TwoSpringFoundation", "SwitchingFoundation", "LinearVibration",
    "Pulse", "SampledMotion", "GroundMotion", "read_record", "Scene", "G_STANDARD",
    # running
    "Solver", "simulate", "SimulationResult", "simulate_foundation",
    # analyses and studies
    "overturning_spectrum", "rocking_spectrum", "half_cycles", "fit_free_rocking", "FreeRockingFit",
    "Study", "run_study", "fit_fragility", "FragilityFit", "plot_fragility",
]
__version__ = "0.1.0"
