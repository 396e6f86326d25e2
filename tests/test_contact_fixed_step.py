"""A fixed step the user set in the contact model (issue #14 item 1: failed:* only for a numerical
limit the user set, with an error that says which).

contact:2026:27 (bench/README.md): RigidBlock.rectangle(0.0955937, 0.1246), one-sine of
a_p/(g tan alpha) = 37.7 at omega_p/p = 8.66, Wall(gap=0.0119962, side=-1, restitution=1),
Friction(1.99631, lift_off="stop"), fixed dt = 2 pi/omega_p/111.3 = 9.52e-4 s.  Its first step
after the uplift read an error above the fixed-step limit and the run ended failed:unstable-step.
That step is stable: the error was relative to what the step itself produced (the motion had no
scale yet), and the driver now judges divergence from the second step on.  At that dt the run
ends with the adaptive solver's outcome (an independent check: rtol 1e-10).  A step 17 times
longer (0.016 s) does diverge: the run ends failed:unstable-step and the warning names the
user's dt and a stable one, at which the cell ends definite with the adaptive outcome.
"""
import math
import re
import warnings

import pytest

from fastrock import Friction, Pulse, RigidBlock, Solver, Wall, simulate

BODY = RigidBlock.rectangle(0.0955937, 0.1246)
WALL = Wall(gap=0.0119962, side=-1, restitution=1)
FRICTION = Friction(1.99631, lift_off="stop")


F = 8.661743183417562


def _pulse(amp, sign):
    return Pulse(amp, F, sign, "one-sine", amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")


@pytest.mark.parametrize("amp", [37.6990920461746, 38.4646768280267])
@pytest.mark.parametrize("sign", [1, -1])
def test_the_fuzz_step_is_stable_and_ends_as_the_adaptive_solver(amp, sign):
    dt = 2 * math.pi / (F * BODY.p) / 111.31602421503298
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r = simulate(BODY, _pulse(amp, sign), wall=WALL, friction=FRICTION, solver=Solver(dt=dt))
    ref = simulate(BODY, _pulse(amp, sign), wall=WALL, friction=FRICTION, solver=Solver(rtol=1e-10))
    assert ref.status.startswith("overturn") and r.status == ref.status, (r.status, ref.status)
    # a fixed step of 1/111 of the pulse period: 4e-6 of the fall time measured
    assert math.isclose(r.metrics["time_overturn"], ref.metrics["time_overturn"], rel_tol=1e-5)


def test_unstable_fixed_step_names_the_users_dt_and_a_stable_one():
    dt = 0.016
    pulse = _pulse(37.6990920461746, -1)
    with pytest.warns(RuntimeWarning, match="unstable-step") as rec:
        r = simulate(BODY, pulse, wall=WALL, friction=FRICTION, solver=Solver(dt=dt))
    assert r.status == "failed:unstable-step"
    msg = " ".join(str(w.message) for w in rec)
    assert f"dt = {dt:g} s" in msg, msg
    named = re.findall(r"dt <= ([0-9.eE+-]+) s would be stable", msg)
    assert named and 0.0 < float(named[0]) < dt, msg
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        r1 = simulate(BODY, pulse, wall=WALL, friction=FRICTION, solver=Solver(dt=float(named[0])))
    ref = simulate(BODY, pulse, wall=WALL, friction=FRICTION, solver=Solver(rtol=1e-10))
    assert not r1.status.startswith("failed") and r1.status == ref.status, (r1.status, ref.status)
