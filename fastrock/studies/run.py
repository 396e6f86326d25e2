"""run_study: local or Dask execution of a study's chunks, resumable.
"""
from __future__ import annotations

import json
import os
import time
import warnings
from pathlib import Path

from fastrock import _validate as V
from fastrock.running.sweep import Progress
from fastrock.studies.definition import Study, StudyError
from fastrock.studies.output import (MANIFEST, RESULTS_DIR, atomic_write_bytes, check_folder,
    chunk_done, manifest_of, need_pyarrow, write_chunk, load_results)
from fastrock.studies.plan import Plan
from fastrock.studies.worker import worker_info, run_chunk


#: Seconds to wait for a scheduler given by address.
CONNECT_TIMEOUT = 10.0

#: Dask retries of a chunk whose task raised.
RETRIES = 2


# =================================================================== run
def run_study(study, output, backend=None, client=None, scheduler=None, chunk_size=None,
              progress=True, *, retries=RETRIES, connect_timeout=CONNECT_TIMEOUT,
              numba_threads=None, n_workers=None, callback=None):
    """Run (or resume) a study into the folder ``output``.

    Parameters
    ----------
    study : Study
    output : path
        Folder of the partitioned Parquet dataset and ``manifest.json``;
        created if needed.  Rerunning into it skips the finished chunks.
    backend : {"local", "dask"}, optional
        Default: "dask" if ``client`` or ``scheduler`` is given, else "local".
    client : dask.distributed.Client, optional
    scheduler : str, optional
        Scheduler address, e.g. ``"tcp://10.0.0.5:8786"``.  With backend
        "dask" and neither ``client`` nor ``scheduler``, a LocalCluster on
        127.0.0.1 is started for the call (``n_workers`` processes, default
        the CPU count, one thread and one Numba thread each).
    chunk_size : int, optional
        Rows per chunk (default :data:`DEFAULT_CHUNK_SIZE`, or the folder's).
    progress : bool
        Progress bar on stderr (rows done, rate, ETA).
    retries : int
        Dask retries of a chunk whose task raised.
    connect_timeout : float
        Seconds to reach a scheduler given by address.
    numba_threads : int, optional
        Numba threads per chunk on Dask workers (default: Numba's default).
    callback : callable, optional
        ``callback(chunk_id, n_chunks_done, n_chunks)`` after each chunk is
        written.

    Returns
    -------
    pandas.DataFrame
        :func:`load_results` of the folder; ``attrs`` add ``chunks_run``,
        ``chunks_skipped``, ``kernel_seconds``, ``wall_seconds``, ``backend``.

    Raises
    ------
    StudyError
        Before any work: bad input, unreachable scheduler, output folder of
        another study.  After the work: chunks that failed (the others are
        saved; rerun to retry those).
    """
    if not isinstance(study, Study):
        raise StudyError(f"study must be a fastrock.Study, got {type(study).__name__}")
    if backend is None:
        backend = "dask" if (client is not None or scheduler is not None) else "local"
    if backend not in ("local", "dask"):
        raise StudyError(f"backend must be 'local' or 'dask', got {backend!r}")
    if backend == "local" and (client is not None or scheduler is not None):
        raise StudyError("client/scheduler given with backend='local'")
    if client is not None and scheduler is not None:
        raise StudyError("give either client= or scheduler=, not both")
    if chunk_size is not None:
        try:
            chunk_size = V.integer("chunk_size", chunk_size, 1)
        except ValueError:
            raise StudyError(f"chunk_size must be a positive integer, got {chunk_size!r}") from None
    need_pyarrow()
    prep = study.prepare()
    folder = Path(output)
    cs = check_folder(folder, prep, chunk_size)
    plan = Plan(prep, cs)
    todo = [c for c in plan.chunks if not chunk_done(folder, c, prep.hash)]
    own = None
    if backend == "dask":
        client, own = _connect(client, scheduler, connect_timeout, n_workers)
        if own is not None and numba_threads is None:
            numba_threads = 1
    try:
        (folder / RESULTS_DIR).mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(folder / MANIFEST, json.dumps(manifest_of(plan, study), indent=1).encode())
        for tmp in (folder / RESULTS_DIR).glob(".*.tmp"):
            tmp.unlink(missing_ok=True)   # left by a crash mid-write
        stats = {"kernel_seconds": 0.0, "chunks_run": 0}
        t0 = time.perf_counter()
        bar = Progress(sum(c.rows.size for c in todo), progress, "runs")
        n_total = len(plan.chunks)
        done_before = n_total - len(todo)

        def finish(chunk, result):
            write_chunk(folder, chunk.id, plan.columns(chunk, result), prep.hash)
            stats["kernel_seconds"] += float(result["seconds"])
            stats["chunks_run"] += 1
            bar.update(chunk.rows.size)
            if callback is not None:
                callback(chunk.id, done_before + stats["chunks_run"], n_total)

        interrupted = False
        try:
            if backend == "local":
                for chunk in todo:
                    finish(chunk, run_chunk(plan.payload(chunk)))
            else:
                failed = _run_dask(client, plan, todo, finish, retries, numba_threads)
                if failed:
                    bar.close()
                    msg = "; ".join(f"chunk {cid}: {type(e).__name__}: {e}" for cid, e in failed[:5])
                    raise StudyError(f"{len(failed)} of {len(todo)} chunks failed ({msg}); the "
                                     f"{stats['chunks_run']} others are saved in {folder}; rerun "
                                     f"run_study to retry the failed ones")
        except KeyboardInterrupt:
            interrupted = True
            warnings.warn(f"interrupted: {done_before + stats['chunks_run']} of {n_total} chunks "
                          f"are saved in {folder}; rerun to resume", stacklevel=2)
        finally:
            bar.close()
        wall = time.perf_counter() - t0
    finally:
        if own is not None:
            own()
    df = load_results(folder)
    df.attrs.update(chunks_run=stats["chunks_run"], chunks_skipped=done_before,
                    kernel_seconds=stats["kernel_seconds"], wall_seconds=wall, backend=backend,
                    interrupted=interrupted, chunk_size=cs, n_chunks=n_total)
    return df


def _connect(client, scheduler, timeout, n_workers):
    """(client, closer or None).  Errors before any work."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise StudyError("the Dask backend needs dask.distributed: "
                         "pip install 'fastrock[distributed]'") from None
    closer = None
    if client is None:
        if scheduler is not None:
            if not isinstance(scheduler, str) or not scheduler.strip():
                raise StudyError(f"scheduler must be an address such as 'tcp://host:8786', "
                                 f"got {scheduler!r}")
            try:
                client = Client(scheduler, timeout=timeout, set_as_default=False)
            except (OSError, TimeoutError, ValueError) as exc:
                raise StudyError(f"cannot reach the Dask scheduler at {scheduler} within "
                                 f"{timeout:g} s ({type(exc).__name__}: {exc})") from None
            closer = client.close
        else:
            cluster = LocalCluster(n_workers=n_workers or os.cpu_count() or 1, threads_per_worker=1,
                                   processes=True, host="127.0.0.1", dashboard_address=None)
            client = Client(cluster, set_as_default=False)

            def closer():
                client.close()
                cluster.close()
    elif not hasattr(client, "submit"):
        raise StudyError(f"client must be a dask.distributed.Client, got {type(client).__name__}")
    try:
        info = client.run(worker_info)
    except Exception as exc:  # noqa: BLE001 - typically fastrock missing on the workers
        if closer is not None:
            closer()
        raise StudyError(f"the Dask workers cannot run fastrock ({type(exc).__name__}: {exc}); "
                         f"install fastrock on every worker") from None
    from fastrock.constants import VERSION
    versions = {v["fastrock"] for v in info.values()}
    if versions - {VERSION}:
        warnings.warn(f"workers run fastrock {sorted(versions)}, this client "
                      f"{VERSION}", stacklevel=3)
    if not info:
        warnings.warn("the Dask scheduler has no workers yet; chunks wait for them", stacklevel=3)
    return client, closer


def _run_dask(client, plan, todo, finish, retries, numba_threads):
    """Submit one task per chunk; write each as it completes.  Returns the
    [(chunk id, exception)] of chunks that failed after their retries."""
    from distributed import as_completed
    by_key = {}
    futures = []
    for chunk in todo:
        payload = plan.payload(chunk)
        payload["numba_threads"] = int(numba_threads or 0)
        key = f"fastrock-study-{plan.prep.hash[:16]}-{chunk.id}"
        fut = client.submit(run_chunk, payload, key=key, pure=True, retries=int(retries))
        by_key[fut.key] = chunk
        futures.append(fut)
    failed = []
    ac = as_completed(futures, loop=client.loop)     # this client, even if not the default
    try:
        for fut in ac:
            chunk = by_key[fut.key]
            if fut.status == "error":
                failed.append((chunk.id, fut.exception()))
            else:
                finish(chunk, fut.result())
            fut.release()
    except BaseException:
        client.cancel([f for f in futures if not f.done()])
        raise
    return failed


