"""pytest configuration of the benchmark suite (``pytest bench/ --benchmark-only``).

Benchmark modules are named ``bench_*.py`` so that the correctness suite never collects them
(the project's ``testpaths`` is ``tests``); this hook collects them when ``bench/`` is given.
"""
import fnmatch
import os
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parent
if str(BENCH) not in sys.path:          # ``import ratios`` (shared set-up and SciPy baseline)
    sys.path.insert(0, str(BENCH))


def pytest_collect_file(file_path, parent):
    if file_path.suffix != ".py" or not file_path.name.startswith("bench_"):
        return None
    # pytest itself collects a file named on the command line, or one matching python_files
    if parent.session.isinitpath(file_path) or any(
            fnmatch.fnmatch(file_path.name, pat) for pat in parent.config.getini("python_files")):
        return None
    return pytest.Module.from_parent(parent, path=file_path)


def pytest_benchmark_update_machine_info(config, machine_info):
    """Record what makes timings on a shared 2-core machine comparable (or not)."""
    import numba
    try:
        machine_info["loadavg"] = list(os.getloadavg())
    except OSError:
        pass
    machine_info["numba"] = numba.__version__
    machine_info["numba_threads"] = numba.get_num_threads()
    machine_info["numba_cache_dir"] = os.environ.get("NUMBA_CACHE_DIR", "")
