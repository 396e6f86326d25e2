"""No impact creates energy (issue #18, item 2), in every family.

Release mode: the event log of random runs is checked here (impact maps of
the rigid, wall and switching models scale theta'; the friction and flexible
maps are checked with their own kinetic energies in test_friction.py and
test_flexible*.py).  Debug mode (``FASTROCK_DEBUG=1``, the CI pass that also
sets ``NUMBA_BOUNDSCHECK=1``): every kernel compares the kinetic energy
before and after each impact and counts gains in ``energy_gains``."""
import warnings

import numpy as np
import pytest

from fastrock import FlexibleBody, Pulse, RigidBlock, simulate
from fastrock.model.friction import Friction
from fastrock.kernels import config
from fastrock.model.wall import Wall

FAMILIES = ["rigid", "wall", "friction", "flexible", "flexible_friction"]


def _random_runs(family, n, seed):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        e = float(rng.uniform(0.0, 1.0))
        if family.startswith("flexible"):
            body = FlexibleBody(rng.uniform(0.1, 0.4), rng.uniform(1, 4), rng.uniform(3, 30), zeta=0.02)
        else:
            body = RigidBlock.rectangle(rng.uniform(0.1, 0.4), rng.uniform(0.5, 1.5), e=e)
        kw = {}
        if family == "wall":
            kw["wall"] = Wall(gap=float(rng.uniform(0.001, 0.05)), side=-1, restitution=float(rng.uniform(0, 1)))
        if family.endswith("friction"):
            kw["friction"] = Friction(float(rng.uniform(0.1, 1.5)),
                                      lift_off="hold" if family.startswith("flexible") else "stop")
        pulse = Pulse(rng.uniform(1, 4), rng.uniform(0.5, 3), sign=int(rng.choice([-1, 1])),
                      amplitude_unit="g_tan_alpha")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            yield simulate(body, pulse, duration=4.0, **kw)


@pytest.mark.parametrize("family", ["rigid", "wall"])
def test_rotation_maps_never_speed_up(family):
    n = 0
    for r in _random_runs(family, 10, 1):
        ev = r.events[r.events["event"].isin(["impact", "wall-impact"])]
        assert (ev["velocity_after"].abs() <= ev["velocity_before"].abs()).all()
        n += len(ev)
    assert n > 50


@pytest.mark.skipif(not config.DEBUG, reason="the debug pass of .ci/run sets FASTROCK_DEBUG=1")
@pytest.mark.parametrize("family", FAMILIES)
def test_debug_kernels_find_no_energy_gain(family):
    impacts = gains = 0
    for r in _random_runs(family, 12, 2):
        impacts += r.metrics["impacts"]
        gains += r.metrics["energy_gains"]
    assert impacts > 20
    assert gains == 0


@pytest.mark.skipif(not config.DEBUG, reason="the debug pass of .ci/run sets FASTROCK_DEBUG=1")
def test_debug_check_catches_a_map_that_gains():
    """Positive control: a rigid kernel fed e = 1.5 (refused by the front end)."""
    from fastrock.running import registry
    from fastrock.kernels import layout as L
    from fastrock.kernels import rigid as K
    from fastrock.kernels.hybrid import N_COUNTERS
    from fastrock.running.solver import Solver
    body = RigidBlock(0.2, 2.0)
    spec = registry.select(body, None, None)
    par = spec.par.copy()
    par[K.P_E] = 1.5
    y = np.array([0.5 * body.alpha, 0.0])
    met = np.zeros(L.N_MET)
    spec.simulate(y, par, np.zeros(L.N_EXC), np.zeros(1), Solver().options(5.0, False), np.empty(0), met,
                  np.empty(0), np.empty((0, 2)), np.empty((0, 3), np.int64), np.empty((10, L.N_LOG)),
                  np.zeros(N_COUNTERS, np.int64))
    assert met[L.M_IMPACTS] >= 1
    assert met[L.M_ENERGY_GAINS] == met[L.M_IMPACTS]
