"""`fastrock warmup` compiles every model of the registry by default, and a sweep says before a
kernel's first call in a process that it may compile (issue #15 item 4, issue #16)."""
import os
import subprocess
import sys
import tempfile

import pytest

from fastrock.running import registry
from fastrock.running.warmup import TYPICAL_COMPILE_SECONDS, resolve


def test_every_model_has_a_warm_up_scene_and_a_typical_time():
    assert resolve(None) == list(registry.MODELS)
    assert set(TYPICAL_COMPILE_SECONDS) >= set(registry.MODELS)
    assert resolve(["foundation", "wall"]) == ["two_spring", "switching", "linear_sdof", "flexible_two_spring",
                                               "rigid_wall"]
    with pytest.raises(ValueError, match="unknown model 'walls'"):
        resolve(["walls"])


@pytest.mark.slow
def test_warmup_compiles_every_model():
    code = ("import json, sys, numba\n"
            "from fastrock.running.warmup import warmup\n"
            "from fastrock.running import registry\n"
            "done = [n for n, _s in warmup()]\n"
            "ready = {n: bool(registry.MODELS[n].load().__dict__[registry.MODELS[n].sweep_entry].signatures)"
            " for n in done}\n"
            "print(json.dumps([done, ready]))\n")
    # not in the repository root: there `python -c` imports the source tree, whose kernels a
    # non-editable install caches apart (a compile per model); elsewhere, the installed fastrock
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=1800,
                         env=dict(os.environ), cwd=tempfile.gettempdir())
    assert out.returncode == 0, out.stderr[-2000:]
    import json
    done, ready = json.loads(out.stdout.strip().splitlines()[-1])
    assert done == list(registry.MODELS)
    assert all(ready.values())


@pytest.mark.slow
def test_a_sweep_announces_a_first_kernel_call():
    code = ("import fastrock as fr\n"
            "fr.overturning_spectrum(fr.RigidBlock(0.2, 2.0), [1, 2, 3], [1, 2], progress=True, chunk_size=2)\n"
            "fr.overturning_spectrum(fr.RigidBlock(0.2, 2.0), [1, 2, 3], [1, 2], progress=True, chunk_size=2)\n")
    # not in the repository root: there `python -c` imports the source tree, whose kernels a
    # non-editable install caches apart (a compile per model); elsewhere, the installed fastrock
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=900,
                         env=dict(os.environ), cwd=tempfile.gettempdir())
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stderr.count("first use of the rigid kernel in this process") == 1
    assert "about 34 s" in out.stderr
