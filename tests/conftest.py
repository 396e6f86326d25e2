"""Shared test configuration.

Tests run in the folder pytest was started in (the repository root, usually): ``import fastrock``
works there, and a fresh Python that a test starts (``python -c ...``) imports the source tree, whose
front end finds its compiled layer in the sibling ``kernels/``.  A test that writes files writes them
under ``tmp_path`` (``monkeypatch.chdir(tmp_path)`` where it relies on a default output path).

Tiers (markers declared in pyproject.toml): ``pytest`` runs the quick tier, ``pytest -m slow`` the
slow oracles, subprocess, Dask, stiff-limit and fuzz tests, ``pytest -m "slow or not slow"`` both;
``NUMBA_DISABLE_JIT=1 pytest -m nojit`` runs a few kernel tests with the kernels as plain Python.
"""
