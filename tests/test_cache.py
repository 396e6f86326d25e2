"""On-disk kernel cache and lazy compilation, checked in fresh processes.

Both subprocesses point NUMBA_CACHE_DIR to a private temporary directory, so the test neither
depends on nor disturbs the developer's cache.  The first process compiles and writes the cache;
the second must load ``rigid_simulate`` from it without compiling anything.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.slow          # two fresh processes, one compiling

RUN = textwrap.dedent("""
    import json, sys
    import fastrock
    from fastrock.kernels import rigid
    out = {
        "signatures_after_import": len(rigid.rigid_simulate.signatures),
        "sweep_signatures_after_import": len(rigid.rigid_sweep.signatures),
    }
    body = fastrock.RigidBlock(alpha=0.2, p=2.0)
    res = fastrock.simulate(body, fastrock.Pulse(3.0, 2.0, amplitude_unit="g_tan_alpha",
                                                 frequency_unit="omega_p/p"))
    st = rigid.rigid_simulate.stats
    out.update(
        status=res.status,
        signatures=len(rigid.rigid_simulate.signatures),
        cache_path=st.cache_path,
        cache_hits=sum(st.cache_hits.values()),
        cache_misses=sum(st.cache_misses.values()),
        wall_imported="fastrock.kernels.wall" in sys.modules,
        kernel_modules=sorted(m for m in sys.modules if m.startswith("fastrock.kernels")),
    )
    print("RESULT " + json.dumps(out))
""")


def _run(env):
    proc = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    line = [ln for ln in proc.stdout.splitlines() if ln.startswith("RESULT ")][-1]
    return json.loads(line[len("RESULT "):])


@pytest.fixture(scope="module")
def two_runs(tmp_path_factory):
    cache = tmp_path_factory.mktemp("numba_cache")
    env = dict(os.environ)
    env["NUMBA_CACHE_DIR"] = str(cache)
    env.pop("FASTROCK_CACHE", None)          # default: cache on
    env.pop("NUMBA_DISABLE_JIT", None)
    first = _run(env)
    files = sorted(p.name for p in cache.rglob("*") if p.is_file())
    second = _run(env)
    return first, second, cache, files


def test_first_process_compiles_and_writes_the_cache(two_runs):
    first, _second, cache, files = two_runs
    assert not first["status"].startswith("failed"), first["status"]
    assert first["cache_misses"] >= 1 and first["cache_hits"] == 0
    assert first["cache_path"].startswith(str(cache))
    assert any(f.startswith("rigid.rigid_simulate") and f.endswith(".nbi") for f in files), files
    assert any(f.startswith("rigid.rigid_simulate") and f.endswith(".nbc") for f in files), files


def test_second_process_loads_from_cache(two_runs):
    first, second, _cache, _files = two_runs
    assert second["status"] == first["status"]
    assert second["cache_hits"] >= 1, second
    assert second["cache_misses"] == 0, second
    assert second["signatures"] == 1


def test_import_compiles_nothing(two_runs):
    for run in two_runs[:2]:
        assert run["signatures_after_import"] == 0
        assert run["sweep_signatures_after_import"] == 0


RIGID_KERNEL_MODULES = {"fastrock.kernels", "fastrock.kernels.config", "fastrock.kernels.dopri",
                        "fastrock.kernels.excitation", "fastrock.kernels.hybrid",
                        "fastrock.kernels.layout", "fastrock.kernels.rigid"}


def test_rigid_simulate_does_not_import_wall_kernel(two_runs):
    """A scene imports only the kernel modules it needs (fastrock/models.py)."""
    for run in two_runs[:2]:
        assert not run["wall_imported"], run["kernel_modules"]
        assert "fastrock.kernels.rigid" in run["kernel_modules"]
        assert set(run["kernel_modules"]) <= RIGID_KERNEL_MODULES, run["kernel_modules"]


def test_cache_folder_follows_every_kernel_source(tmp_path, monkeypatch):
    """Numba stamps a cached kernel with its own file only; the entry kernels inline the driver
    and helpers of other files, so the cache folder is keyed by all kernel sources: editing any
    one of them (here the driver) moves it."""
    import shutil
    from fastrock.kernels import config
    src = tmp_path / "kernels"
    shutil.copytree(os.path.dirname(config.__file__), src, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    before = config._kernel_cache_dir(src)
    assert before.startswith(str(tmp_path / "cache")) and before == config._kernel_cache_dir(src)
    with open(src / "hybrid.py", "a") as f:
        f.write("\n# an edit\n")
    assert config._kernel_cache_dir(src) != before
