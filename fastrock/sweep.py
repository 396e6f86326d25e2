"""Chunked parallel sweeps: progress, Ctrl-C keeps finished rows."""
from __future__ import annotations

import sys
import time
import warnings

import numpy as np

from fastrock.kernels import layout as L


class Progress:
    """A minimal progress bar on stderr (no dependency)."""

    def __init__(self, total, enabled=True, label="runs"):
        self.total = total
        self.enabled = enabled and total > 0
        self.label = label
        self.t0 = time.perf_counter()
        self.done = 0

    def update(self, n):
        self.done += n
        if not self.enabled:
            return
        el = time.perf_counter() - self.t0
        rate = self.done / el if el > 0 else float("inf")
        frac = self.done / self.total
        bar = "#" * int(30 * frac)
        eta = (self.total - self.done) / rate if rate > 0 else 0.0
        sys.stderr.write(f"\r[{bar:<30}] {self.done}/{self.total} {self.label} "
                         f"{rate:,.0f}/s eta {eta:5.1f}s")
        sys.stderr.flush()

    def close(self):
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


def run_sweep(sweep_kernel, Y0, PAR, HDR, smp, OPT, chunk_size=None, progress=True, label="runs"):
    """Run a sweep kernel over rows in chunks.

    Returns (status, MET, YF, n_done).  On KeyboardInterrupt the finished
    chunks are returned (n_done < n) with a warning, never lost.
    """
    n = Y0.shape[0]
    status = np.full(n, L.RUNNING, dtype=np.int64)
    MET = np.full((n, L.N_MET), np.nan)
    YF = np.full(Y0.shape, np.nan)
    if chunk_size is None:
        chunk_size = max(256, min(4096, n // 20 + 1))
    bar = Progress(n, progress and n > chunk_size, label)
    done = 0
    try:
        while done < n:
            stop = min(n, done + chunk_size)
            sl = slice(done, stop)
            st = np.empty(stop - done, np.int64)
            met = np.empty((stop - done, L.N_MET))
            yf = np.empty((stop - done, Y0.shape[1]))
            sweep_kernel(np.ascontiguousarray(Y0[sl]), np.ascontiguousarray(PAR[sl]),
                         np.ascontiguousarray(HDR[sl]), smp, np.ascontiguousarray(OPT[sl]), st, met, yf)
            status[sl] = st
            MET[sl] = met
            YF[sl] = yf
            done = stop
            bar.update(stop - sl.start)
    except KeyboardInterrupt:
        warnings.warn(f"interrupted: returning the {done} of {n} runs that finished", stacklevel=3)
    finally:
        bar.close()
    return status, MET, YF, done
