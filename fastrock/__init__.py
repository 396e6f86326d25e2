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

from fastrock.model.bodies import FlexibleBody, RigidBlock, housner_restitution  # noqa: E402
from fastrock.model.rigid_body import RigidBody
from fastrock.constants import G_STANDARD, VERSION
from fastrock.model.excitation import Pulse, SampledMotion
from fastrock.model.friction import Friction
from fastrock.model.wall import Wall
from fastrock.model.ground import Ground
from fastrock.model.foundation import LinearVibration, SwitchingFoundation, TwoSpringFoundation
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.readers import read_record
from fastrock.io.outline import read_outline
from fastrock.running.solver import Solver
from fastrock.running.result import SimulationResult
from fastrock.running.simulate import simulate
from fastrock.running.batch import run_batch
from fastrock.running.foundation import simulate_foundation
from fastrock.running.scene import Scene
from fastrock.analyses.spectrum import load_spectrum, overturning_spectrum
from fastrock.analyses.freerocking.fitting import FreeRockingFit, fit_free_rocking
from fastrock.analyses.freerocking.half_cycles import half_cycles
# the foundation models register their predictors with fit_free_rocking on import
from fastrock.analyses import foundation_predictors
from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
from fastrock.analyses.fragility import FragilityFit, fit_fragility
from fastrock.studies.definition import Study
from fastrock.studies.run import run_study
# fastrock.plotting registers the figure of SimulationResult.plot() on import
from fastrock.plotting.fragility import plot_fragility
from fastrock.plotting.snapshots import plot_snapshots

del foundation_predictors

__all__ = [
    # bodies, scenes and excitations
    "RigidBlock", "RigidBody", "FlexibleBody", "housner_restitution", "Wall", "Friction", "Ground",
    "TwoSpringFoundation", "SwitchingFoundation", "LinearVibration",
    "Pulse", "SampledMotion", "GroundMotion", "read_record", "read_outline", "Scene", "G_STANDARD",
    # running
    "Solver", "simulate", "run_batch", "SimulationResult", "simulate_foundation",
    # analyses and studies
    "overturning_spectrum", "load_spectrum", "rocking_spectrum", "half_cycles", "fit_free_rocking", "FreeRockingFit",
    "Study", "run_study", "fit_fragility", "FragilityFit", "plot_fragility", "plot_snapshots",
]
__version__ = VERSION
