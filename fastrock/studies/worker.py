"""The worker: runs one chunk of a study.
"""
from __future__ import annotations

import os
import threading
import time

import numpy as np

from fastrock.running.sweep import call_kernel
from fastrock.kernels import layout as L


# ================================================================= worker
_KERNEL_LOCK = threading.Lock()


def run_chunk(payload):
    """Run one chunk with its model's parallel sweep kernel.

    The Dask task function: top level, plain data in and out, pure (the
    same payload always gives the same arrays), no side effect, so Dask may
    rerun it anywhere.  Kernel calls of one process are serialised by a lock
    (each call already uses every Numba thread; some threading layers do not
    allow concurrent launches from several threads).

    Parameters
    ----------
    payload : dict
        ``module``, ``kernel`` (names in :mod:`fastrock.kernels`), ``rows``
        (int64[m]), kernel inputs ``Y0`` (m, n_state), ``PAR``, ``HDR``
        (m, N_EXC), ``smp`` (samples [m/s^2]), ``OPT`` (m, N_OPT), and
        ``numba_threads`` (> 0: Numba threads for this call).

    Returns
    -------
    dict
        ``rows``, ``status`` (int64[m]), ``met`` (float64[m, N_MET]),
        ``seconds`` (kernel wall time), ``pid``.
    """
    import importlib
    mod = importlib.import_module(f"fastrock.kernels.{payload['module']}")
    sweep = getattr(mod, f"{payload['kernel']}_sweep")
    Y0 = np.ascontiguousarray(payload["Y0"], float)
    m = Y0.shape[0]
    status = np.empty(m, np.int64)
    met = np.empty((m, L.N_MET))
    yf = np.empty_like(Y0)
    with _KERNEL_LOCK:
        nt = int(payload.get("numba_threads") or 0)
        if nt > 0:
            import numba
            numba.set_num_threads(min(nt, numba.config.NUMBA_NUM_THREADS))
        t0 = time.perf_counter()
        opt = np.array(payload["OPT"], float, order="C")
        call_kernel(sweep, Y0, np.ascontiguousarray(payload["PAR"], float),
                    np.ascontiguousarray(payload["HDR"], float), np.ascontiguousarray(payload["smp"], float),
                    opt, status, met, yf, opt=opt)
        seconds = time.perf_counter() - t0
    out = {"rows": np.asarray(payload["rows"], np.int64), "status": status, "met": met,
           "seconds": seconds, "pid": os.getpid()}
    if "theta_index" in payload:
        out["theta_end"] = yf[:, int(payload["theta_index"])].copy()
    return out


def worker_info():
    """Versions and process id of a worker (fastrock, numba, pid)."""
    import numba
    from fastrock.constants import VERSION
    return {"fastrock": VERSION, "numba": numba.__version__, "pid": os.getpid()}


