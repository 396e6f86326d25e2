"""The README's list of combinations that are not available yet (issue #13 item 3: "where a
combination is refused, say why in the error, and list it in the README"): every registry
refusal is in the list, and every scene in the list is refused with a message, not a crash."""
from pathlib import Path

import pytest

import fastrock as fr
from fastrock.running import registry

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()
BLOCK = fr.RigidBlock.rectangle(0.2, 0.8)
FLEX = fr.FlexibleBody(alpha=0.25, p=2.0, omega_n_over_p=9.0)
ASYM = fr.RigidBody.from_polygon([(0, 0), (1, 0), (0.2, 2)], mass=1.0)
UNEVEN = fr.RigidBody(mass=1.0, inertia=0.1, b1=0.2, h1=0.8, b2=0.3, h2=0.9)
FND = fr.LinearVibration(1e4)
PULSE = fr.Pulse(1.0, 1.0)

SCENES = [
    (FLEX, {"wall": fr.Wall(0.05), "friction": fr.Friction(0.5)}, "FlexibleBody"),
    (BLOCK, {"foundation": FND, "wall": fr.Wall(0.05)}, "TwoSpringFoundation"),
    (BLOCK, {"foundation": FND, "friction": fr.Friction(0.5)}, "foundation"),
    (BLOCK, {"foundation": FND, "wall": fr.Wall(0.05), "friction": fr.Friction(0.5)}, "foundation"),
    (FLEX, {"foundation": FND}, "foundation"),
    (ASYM, {"foundation": FND}, "foundation"),
    (UNEVEN, {"friction": fr.Friction(0.5)}, "h1 = "),
    (BLOCK, {"foundation": fr.TwoSpringFoundation(1e4), "wall": fr.Wall(0.05), "friction": fr.Friction(0.5)},
     "foundation"),
    (FLEX, {"foundation": fr.TwoSpringFoundation(1e4), "wall": fr.Wall(0.05)}, "FlexibleBody"),
    (FLEX, {"foundation": fr.TwoSpringFoundation(1e4), "friction": fr.Friction(0.5)}, "FlexibleBody"),
    (BLOCK, {"foundation": fr.TwoSpringFoundation(1e4), "friction": fr.Friction(float("inf"), lift_off="flight")},
     "never slips"),
]


def test_readme_lists_the_refused_combinations():
    text = " ".join(README.split())
    assert "**Not available yet**" in text
    for phrase in ("a `FlexibleBody` with `wall=` and `friction=` together",
                   "`foundation=` together with both `wall=` and `friction=`",
                   "a `FlexibleBody` on a foundation with `wall=` or `friction=`, on a slope, or on the "
                   "switching or linear foundation, and an asymmetric `RigidBody` on the switching or linear "
                   "foundation (both run on `TwoSpringFoundation`)",
                   "`friction=` on the switching or linear foundation, and `Friction(inf, lift_off=\"flight\")` "
                   "on any foundation",
                   "`LinearVibration` with `wall=`"):
        assert phrase in text, phrase
    # pivots at different heights are ruled out on one ground plane, with the turn that fixes it
    ruled_out = text.split("**Ruled out by the physics**")[1]
    assert "an asymmetric body whose two pivots are not level" in ruled_out
    assert "`body.on_level_ground()`" in ruled_out
    # every refusal of the registry is one of the listed kinds
    for (body, effects) in registry.NOT_AVAILABLE:
        assert body == "flexible" and effects == {"wall", "friction"} or "foundation" in effects


@pytest.mark.parametrize("body, kw, says", SCENES)
def test_each_listed_scene_is_refused_with_a_reason(body, kw, says):
    with pytest.raises(ValueError, match=None) as exc:
        fr.simulate(body, PULSE, **kw)
    assert says in str(exc.value)


def test_sliding_on_the_two_spring_foundation_runs_and_the_others_say_where_it_does():
    """Friction on a flexible foundation runs on TwoSpringFoundation (two_spring_friction); on the
    SDOF foundation models the refusal names the one that takes it."""
    two = fr.TwoSpringFoundation(1e4)
    assert registry.select(BLOCK, friction=fr.Friction(0.5), foundation=two).name == "two_spring_friction"
    assert registry.select(ASYM, friction=fr.Friction(0.5), foundation=two).name == "two_spring_friction"
    for fnd in (FND, fr.SwitchingFoundation(1e4)):
        for fric in (fr.Friction(0.5), fr.Friction(0.5, lift_off="flight")):
            with pytest.raises(ValueError, match="TwoSpringFoundation only"):
                registry.select(BLOCK, friction=fric, foundation=fnd)


def test_a_wall_beside_the_two_spring_foundation_runs():
    """Issue #13: foundation=TwoSpringFoundation or SwitchingFoundation with wall= is no longer
    refused (models two_spring_wall, switching_wall, tests/test_foundation_wall.py); the linear
    SDOF with a wall still is."""
    fnd = fr.TwoSpringFoundation.from_vibration(BLOCK, 60.0, 0.05)
    assert registry.select(BLOCK, wall=fr.Wall(0.05), foundation=fnd).name == "two_spring_wall"
    fnd = fr.SwitchingFoundation.from_vibration(BLOCK, 60.0, 0.05)
    assert registry.select(BLOCK, wall=fr.Wall(0.05), foundation=fnd).name == "switching_wall"
