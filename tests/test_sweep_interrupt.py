"""A Ctrl-C between two chunks of a sweep (while a finished chunk is consumed and shown) keeps that
chunk: the count returned is what was kept and shown, never less (issue #14: "never lose finished
results").  The CLI's Ctrl-C test found it: the bar showed 4096 of 720000 runs, and the command
wrote 0 rows, because the KeyboardInterrupt landed before the loop counted the chunk."""
from __future__ import annotations

import os
import signal
import warnings

import numpy as np
import pytest

from fastrock.kernels import layout as L
from fastrock.running.sweep import run_chunks


def _fake_kernel(y0, par, hdr, smp, opt, st, met, yf):
    # every run of the chunk finishes (status 0) unless the abort flag is already set
    if (opt[..., L.O_ABORT] == 0).all():
        st[:] = 0
        met[:] = 1.0
        yf[:] = y0


def _inputs(start, stop):
    m = stop - start
    return (np.zeros((m, 2)), np.zeros((m, 3)), np.zeros((m, 4)), np.zeros((m, L.N_OPT)))


@pytest.mark.parametrize("where", ["consume", "inputs"])
def test_ctrl_c_between_chunks_keeps_the_finished_chunks(where):
    kept = []
    calls = {"inputs": 0}

    def consume(start, st, met, yf):
        kept.append((start, st.size))
        if where == "consume" and len(kept) == 2:
            os.kill(os.getpid(), signal.SIGINT)       # lands while the second chunk is consumed

    def inputs(start, stop):
        calls["inputs"] += 1
        if where == "inputs" and calls["inputs"] == 3:
            os.kill(os.getpid(), signal.SIGINT)       # lands while the third chunk's inputs are built
        return _inputs(start, stop)

    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        done = run_chunks(_fake_kernel, 100, inputs, np.zeros(1), consume, chunk_size=10, progress=False)
    assert done == sum(size for _start, size in kept) == 20
    assert kept == [(0, 10), (10, 10)]
    assert any("returning the 20 of 100 runs" in str(x.message) for x in w)
    # the default handler is back
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
