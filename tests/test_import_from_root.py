"""`import fastrock` works in the repository root (issue #16): there the source folder fastrock/
shadows the installed package, and the front end finds its compiled layer in the sibling kernels/
folder."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_import_in_the_repository_root():
    code = ("import fastrock, fastrock.kernels, fastrock.kernels.layout as L\n"
            "from fastrock.kernels import rigid\n"
            "import pathlib\n"
            "print(pathlib.Path(fastrock.__file__).parent.parent, pathlib.Path(rigid.__file__).parent.name)\n"
            "print(fastrock.simulate(fastrock.RigidBlock(0.2, 2.0), fastrock.Pulse(3, 2, "
            "amplitude_unit='g_tan_alpha')).outcome)\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    where, folder = out.stdout.splitlines()[0].split()
    assert Path(where) == ROOT and folder == "kernels"
    assert out.stdout.splitlines()[1] == "safe"
