"""Simulate only the effects a scene calls for: what runs is the smallest
kernel, and nothing else is imported or compiled (checked in fresh
subprocesses; a kernel loaded from the on-disk cache counts as compiled)."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

PROBE = textwrap.dedent("""
    import json, sys
    import numba
    import fastrock as fr
    from fastrock.running.scene import Scene

    def compiled():
        out = {}
        for name, mod in list(sys.modules.items()):
            if not name.startswith("fastrock.kernels."):
                continue
            for attr, obj in vars(mod).items():
                if isinstance(obj, numba.core.registry.CPUDispatcher) and obj.signatures \\
                        and attr.endswith(("_simulate", "_sweep")):
                    out[obj.py_func.__name__] = len(obj.signatures)   # an alias counts once
        return out

    report = {"after_import": compiled()}
    case = sys.argv[1]
    pulse = fr.Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    if case == "rigid":
        sc = Scene(fr.RigidBlock(0.2, 2.0), pulse)
    elif case == "friction-inf":
        sc = Scene(fr.RigidBlock(0.2, 2.0), pulse, friction=fr.Friction(float("inf")))
    elif case == "friction":
        sc = Scene(fr.RigidBlock(0.2, 2.0), pulse, friction=fr.Friction(0.3))
    elif case == "flexible":
        sc = Scene(fr.FlexibleBody(0.2, 2.0, 9.0, 0.05), pulse)
    elif case == "flexible-friction":
        sc = Scene(fr.FlexibleBody(0.2, 2.0, 9.0, 0.05), pulse, friction=fr.Friction(0.5, lift_off="hold"))
    elif case == "wall":
        sc = Scene(fr.RigidBlock.rectangle(0.2, 1.0), pulse, wall=fr.Wall(gap=0.02))
    elif case == "flexible-wall":
        sc = Scene(fr.FlexibleBody(0.2, 2.0, 9.0, 0.05), pulse, wall=fr.Wall(gap=0.3))
    elif case == "wall-friction":
        sc = Scene(fr.RigidBlock.rectangle(0.2, 1.0), pulse, wall=fr.Wall(gap=0.02), friction=fr.Friction(0.3))
    elif case == "flight":
        sc = Scene(fr.RigidBlock.rectangle(0.2, 1.0), pulse, friction=fr.Friction(float("inf"), lift_off="flight"))
    elif case == "vertical":
        sc = Scene(fr.RigidBlock(0.2, 2.0), pulse, vertical=fr.Pulse(0.2, 8.0, amplitude_unit="g",
                                                                     frequency_unit="rad/s"))
    elif case == "two-spring":
        block = fr.RigidBlock.rectangle(0.2, 1.0)
        sc = Scene(block, pulse, foundation=fr.TwoSpringFoundation.from_vibration(block, 60.0, 0.05))
    elif case == "flexible-two-spring":
        flex = fr.FlexibleBody(0.2, 2.0, 9.0, 0.05)
        sc = Scene(flex, pulse, foundation=fr.TwoSpringFoundation.from_vibration(flex, 60.0, 0.05))
    r = sc.run(duration=3.0)
    report.update(kernel=r.kernel, scene_kernel=sc.kernel, effects=list(sc.effects),
                  compiled=compiled(),
                  modules=sorted(m for m in sys.modules if m.startswith("fastrock.kernels.")))
    print(json.dumps(report))
""")

EXPECTED = {
    # case: (kernel, effects, the only compiled entry)
    "rigid": ("rigid", [], "rigid_simulate"),
    "friction-inf": ("rigid", [], "rigid_simulate"),
    "friction": ("rigid_friction", ["friction"], "rigid_friction_simulate"),
    "flexible": ("flexible", ["flexible"], "flexible_simulate"),
    "flexible-friction": ("flexible_friction", ["flexible", "friction"], "flexible_friction_simulate"),
    "wall": ("rigid_wall", ["wall"], "rigid_wall_simulate"),
    "flexible-wall": ("flexible_wall", ["flexible", "wall"], "flexible_wall_simulate"),
    "wall-friction": ("contact", ["wall", "friction"], "contact_simulate"),
    "flight": ("contact", ["flight"], "contact_simulate"),
    "vertical": ("rigid", ["vertical"], "rigid_simulate"),
    "two-spring": ("two_spring", ["foundation:two-spring"], "two_spring_simulate"),
    "flexible-two-spring": ("flexible_two_spring", ["flexible", "foundation:two-spring"],
                            "flexible_two_spring_simulate"),
}
MODEL_MODULES = {"fastrock.kernels.rigid", "fastrock.kernels.flexible", "fastrock.kernels.friction",
                 "fastrock.kernels.wall", "fastrock.kernels.foundation", "fastrock.kernels.flexible_friction",
                 "fastrock.kernels.flexible_wall", "fastrock.kernels.contact",
                 "fastrock.kernels.foundation_flexible", "fastrock.kernels.foundation_wall",
                 "fastrock.kernels.foundation_friction"}


def probe(case, tmp_path):
    # not in the repository root: there `python -c` imports the source tree, whose kernels a
    # non-editable install caches apart (a compile per model); elsewhere, the installed fastrock
    out = subprocess.run([sys.executable, "-c", PROBE, case], capture_output=True, text=True,
                         env=dict(os.environ), timeout=900, cwd=tmp_path)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(EXPECTED))
def test_scene_runs_and_compiles_only_its_kernel(case, tmp_path):
    kernel, effects, entry = EXPECTED[case]
    rep = probe(case, tmp_path)
    assert rep["after_import"] == {}, "importing fastrock compiled kernels"
    assert rep["kernel"] == kernel == rep["scene_kernel"]
    assert rep["effects"] == effects
    assert rep["compiled"] == {entry: 1}
    # model modules other than the one needed are not even imported
    # (the flexible and friction kernels reuse helpers of the rigid module)
    needed = {"rigid": {"fastrock.kernels.rigid"},
              "rigid_friction": {"fastrock.kernels.rigid", "fastrock.kernels.friction"},
              "flexible": {"fastrock.kernels.rigid", "fastrock.kernels.flexible"},
              # the shared friction helpers (initial contact, slide tracking) live in kernels/friction.py
              "flexible_friction": {"fastrock.kernels.rigid", "fastrock.kernels.flexible",
                                    "fastrock.kernels.friction", "fastrock.kernels.flexible_friction"},
              "rigid_wall": {"fastrock.kernels.rigid", "fastrock.kernels.wall"},
              "flexible_wall": {"fastrock.kernels.rigid", "fastrock.kernels.flexible",
                                "fastrock.kernels.flexible_wall"},
              # the contact model reuses the friction model's impact maps (Routh, corner impact)
              "contact": {"fastrock.kernels.rigid", "fastrock.kernels.friction", "fastrock.kernels.contact"},
              "two_spring": {"fastrock.kernels.rigid", "fastrock.kernels.foundation"},
              # the two-spring pieces and the flexible body's deflection tracking (track_u)
              "flexible_two_spring": {"fastrock.kernels.rigid", "fastrock.kernels.flexible",
                                      "fastrock.kernels.foundation", "fastrock.kernels.foundation_flexible"}}[kernel]
    assert set(rep["modules"]) & MODEL_MODULES == needed
