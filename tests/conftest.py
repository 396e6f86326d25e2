"""Run every test from a scratch directory.

Tests that start a fresh Python (``python -c ...``) must import the
installed fastrock: from the repository root, the source folder
``fastrock/`` would shadow it, and it lacks ``fastrock.kernels`` (installed
from ``kernels/`` via setuptools' package-dir).  Files a test writes by
default land in the scratch directory too.
"""
import os

import pytest


@pytest.fixture(scope="session", autouse=True)
def _scratch_cwd(tmp_path_factory):
    old = os.getcwd()
    os.chdir(tmp_path_factory.mktemp("cwd"))
    yield
    os.chdir(old)
