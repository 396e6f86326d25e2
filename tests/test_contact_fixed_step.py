"""A fixed step the user set that is unstable in the contact model (issue #14 item 1: failed:* only
for a numerical limit the user set, with an error that says which).

contact:2026:27 (bench/README.md): RigidBlock.rectangle(0.0955937, 0.1246), one-sine of
a_p/(g tan alpha) = 37.7 at omega_p/p = 8.66, Wall(gap=0.0119962, side=-1, restitution=1),
Friction(1.99631, lift_off="stop"), fixed dt = 2 pi/omega_p/111.3 = 9.52e-4 s: the first step after
the uplift exceeds the fixed-step error limit.  The run ends failed:unstable-step and the warning
names the user's dt and a dt that would be stable; at that dt the cell ends definite, with the
adaptive solver's outcome (an independent check: rtol 1e-10).
"""
import math
import re
import warnings

import pytest

from fastrock import Friction, Pulse, RigidBlock, Solver, Wall, simulate

BODY = RigidBlock.rectangle(0.0955937, 0.1246)
WALL = Wall(gap=0.0119962, side=-1, restitution=1)
FRICTION = Friction(1.99631, lift_off="stop")


@pytest.mark.parametrize("amp", [37.6990920461746, 38.4646768280267])
@pytest.mark.parametrize("sign", [1, -1])
def test_unstable_fixed_step_names_the_users_dt_and_a_stable_one(amp, sign):
    f = 8.661743183417562
    pulse = Pulse(amp, f, sign, "one-sine", amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    dt = 2 * math.pi / (f * BODY.p) / 111.31602421503298
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
