"""Chunked parallel sweeps: progress (tqdm), Ctrl-C keeps finished rows."""
from __future__ import annotations

import os
import signal
import sys
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from fastrock.kernels import layout as L


class _LogLines:
    """A stream for tqdm that writes whole lines: no carriage returns in a log file."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, text):
        text = text.replace("\r", "").strip()
        if text:
            self.stream.write(text + "\n")

    def flush(self):
        self.stream.flush()


class Progress:
    """Progress of a sweep on stderr through tqdm (terminals, notebooks; a log file gets a line
    every ``LOG_INTERVAL`` s instead of a stream of carriage returns)."""

    #: Seconds between progress lines when stderr is no terminal (environment variable
    #: FASTROCK_PROGRESS_INTERVAL overrides it).
    LOG_INTERVAL = 30.0

    @classmethod
    def log_interval(cls):
        text = os.environ.get("FASTROCK_PROGRESS_INTERVAL")
        if text is None:
            return cls.LOG_INTERVAL
        try:
            value = float(text)
        except ValueError:
            value = -1.0
        if not (0.0 <= value < 1e6):
            raise ValueError(f"FASTROCK_PROGRESS_INTERVAL must be a number of seconds >= 0, got {text!r}")
        return value

    def __init__(self, total, enabled=True, label="runs"):
        self.total = total
        self.enabled = enabled and total > 0
        self.label = label
        self.done = 0
        self._bar = None
        if self.enabled:
            from tqdm.auto import tqdm
            tty = getattr(sys.stderr, "isatty", lambda: False)()
            self._bar = tqdm(total=total, unit=" " + label, file=sys.stderr if tty else _LogLines(sys.stderr),
                             dynamic_ncols=True, mininterval=0.1 if tty else self.log_interval(),
                             smoothing=0.1)

    def stage(self, text):
        """Show ``text`` ahead of the bar (e.g. "compiling ... (first use)"); "" clears it."""
        if self._bar is not None:
            self._bar.set_description_str(text, refresh=True)

    def update(self, n):
        self.done += n
        if self._bar is not None:
            self._bar.update(n)

    def close(self):
        if self._bar is not None:
            self._bar.close()


_EXECUTOR = None


def call_kernel(kernel, *args, opt):
    """Call a kernel so that Ctrl-C stops it within one integration step.

    Kernels release the GIL (``nogil``), so the call runs on a worker thread
    while the main thread waits.  For the length of the call, SIGINT only
    sets the abort flag of every run (``opt[..., O_ABORT]``, the array the
    kernel reads); the kernel returns (its unfinished runs report
    ``failed:interrupted``) and KeyboardInterrupt is raised after it.  The
    interrupt is deferred, not raised while waiting, because a
    KeyboardInterrupt that lands inside ``Condition.wait`` can leave the
    future's lock released and surface as "RuntimeError: cannot release
    un-acquired lock" (seen in CI).  Off the main thread (Dask workers), or
    when SIGINT has a handler installed outside Python, the kernel is
    called directly.
    """
    global _EXECUTOR
    if threading.current_thread() is not threading.main_thread():
        return kernel(*args)
    previous = signal.getsignal(signal.SIGINT)
    if previous is None or previous is signal.SIG_IGN:
        return kernel(*args)
    interrupted = []

    def abort(signum, frame):
        interrupted.append(signum)
        opt[..., L.O_ABORT] = 1.0

    if _EXECUTOR is None:
        _EXECUTOR = ThreadPoolExecutor(1, thread_name_prefix="fastrock-kernel")
    signal.signal(signal.SIGINT, abort)
    try:
        result = _EXECUTOR.submit(kernel, *args).result()
    finally:
        signal.signal(signal.SIGINT, previous)
    if interrupted:
        if callable(previous) and previous is not signal.default_int_handler:
            previous(signal.SIGINT, None)
        else:
            raise KeyboardInterrupt
    return result


def run_sweep(sweep_kernel, Y0, PAR, HDR, smp, OPT, chunk_size=None, progress=True, label="runs",
              model=None, reraise_when_complete=False):
    """Run a sweep kernel over rows in chunks.

    Returns (status, MET, YF, n_done).  On KeyboardInterrupt the finished
    chunks are returned (n_done < n) with a warning, never lost.  A Ctrl-C
    that lands after every run has finished returns the complete result,
    or, with ``reraise_when_complete`` (callers that run many sweeps and
    must stop at the next one), raises KeyboardInterrupt again.  With
    ``progress``, the first call of a model's kernel in this process
    (``model``: its registry name) is announced before it may compile.
    """
    n = Y0.shape[0]
    status = np.full(n, L.RUNNING, dtype=np.int64)
    MET = np.full((n, L.N_MET), np.nan)
    YF = np.full(Y0.shape, np.nan)

    def inputs(start, stop):
        sl = slice(start, stop)
        return (np.ascontiguousarray(Y0[sl]), np.ascontiguousarray(PAR[sl]), np.ascontiguousarray(HDR[sl]),
                np.array(OPT[sl], order="C"))

    def consume(start, st, met, yf):
        stop = start + st.size
        status[start:stop] = st
        MET[start:stop] = met
        YF[start:stop] = yf

    done = run_chunks(sweep_kernel, n, inputs, smp, consume, chunk_size, progress, label, model,
                      reraise_when_complete)
    return status, MET, YF, done


def run_chunks(sweep_kernel, n, inputs, smp, consume, chunk_size=None, progress=True, label="runs",
               model=None, reraise_when_complete=False):
    """Run a sweep kernel over n rows, one chunk at a time, without holding
    the inputs or the kernel's outputs of the whole sweep: ``inputs(start,
    stop)`` builds the chunk's (Y0, PAR, HDR, OPT) (C-contiguous; OPT a copy,
    whose abort flag Ctrl-C sets) and ``consume(start, status, MET, YF)``
    keeps what the caller needs of the finished rows.  Returns the number
    of rows finished (all of them, or the rows before a Ctrl-C: see
    :func:`run_sweep`)."""
    if chunk_size is None:
        chunk_size = max(256, min(4096, n // 20 + 1))
    else:
        from fastrock._validate import integer
        chunk_size = integer("chunk_size", chunk_size, 1)     # 0 would never advance
    first_use = progress and model is not None and not getattr(sweep_kernel, "signatures", ())
    if first_use:
        from fastrock.running.warmup import compile_notice
        sys.stderr.write(compile_notice(model, sweep_kernel) + "\n")
        sys.stderr.flush()
    bar = Progress(n, progress and n > chunk_size, label)
    if first_use:
        bar.stage(f"compiling {model} (first use)")
    done = 0
    # Between kernel calls (building inputs, consuming rows, the progress bar) a Ctrl-C is deferred
    # to the end of the chunk's bookkeeping: raised in the middle of it, it reported fewer rows than
    # had been kept and shown (0 of 720000 with 4096 on the bar: the finished chunk was lost).
    pending = []
    chunk_opt = [None]

    def defer(signum, frame):
        pending.append(signum)
        if chunk_opt[0] is not None:          # a chunk about to start stops at once
            chunk_opt[0][..., L.O_ABORT] = 1.0

    previous = None
    if (threading.current_thread() is threading.main_thread()
            and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
        previous = signal.signal(signal.SIGINT, defer)
    try:
        while done < n:
            if pending:
                raise KeyboardInterrupt
            stop = min(n, done + chunk_size)
            y0, par, hdr, opt = inputs(done, stop)
            chunk_opt[0] = opt
            if pending:                       # a Ctrl-C while the inputs were built
                opt[..., L.O_ABORT] = 1.0
            # a row the kernel never wrote (Ctrl-C before it started) reads as interrupted
            st = np.full(stop - done, L.FAIL_INTERRUPTED, np.int64)
            met = np.empty((stop - done, L.N_MET))
            yf = np.empty(y0.shape)
            try:
                call_kernel(sweep_kernel, y0, par, hdr, smp, opt, st, met, yf, opt=opt)
                if pending:           # call_kernel passed the Ctrl-C on to the deferring handler
                    raise KeyboardInterrupt
            except KeyboardInterrupt:
                # keep the chunk's runs that finished before the first one stopped
                k = int(np.argmax(st == L.FAIL_INTERRUPTED)) if (st == L.FAIL_INTERRUPTED).any() else st.size
                if k:
                    consume(done, st[:k], met[:k], yf[:k])
                done += k
                raise
            consume(done, st, met, yf)
            if first_use and done == 0:
                bar.stage("")
            bar.update(stop - done)
            done = stop
        if pending:
            raise KeyboardInterrupt
    except KeyboardInterrupt:
        if done == n and reraise_when_complete:
            raise
        warnings.warn(f"interrupted: returning the {done} of {n} runs that finished", stacklevel=4)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
        bar.close()
    return done
