#!/usr/bin/env python
"""Studies: throughput local vs a 2-worker LocalCluster, overhead per chunk,
and the chunk size that keeps that overhead under 5 % (issue 9, Bench).

Usage::

    python bench/bench_study.py            # shared records x 6 blocks x 10 PGA levels
    python bench/bench_study.py --quick    # El Centro only, fewer rows

What it measures
----------------
1. Throughput.  The same study (every record in ``../shared/data/records/``
   -- the packaged El Centro record with ``--quick`` or if the folder is
   absent -- x 12 rectangular blocks x 10 PGA levels 0.1..1.0 g, two-sided,
   RK45 rtol 1e-8, 10 s of free rocking after each record) runs into a fresh
   folder with several chunk sizes on

   * ``local``: the default backend, chunks one after the other, each one
     ``prange`` call on both cores;
   * ``dask 2x1``: ``LocalCluster(n_workers=2, threads_per_worker=1)`` on
     127.0.0.1, one Numba thread per task (``numba_threads=1``): the two
     workers use the two cores;
   * ``dask 2x1 nt2``: the same with Numba's default thread count (two
     workers x two threads on two cores: oversubscribed).

   Simulations per second from the chunk loop's wall time (set-up and the
   final ``load_results`` excluded); every table is checked identical to the
   one-chunk local table.
2. Overhead per chunk.  A study whose rows cost nothing (PGA far below
   uplift: the kernel returns at once) cut into 8-row chunks: wall time per
   chunk = packing, kernel dispatch, the table, the Parquet file and, on
   Dask, the round trip through the scheduler.
3. Chunk size for < 5 % overhead: ``overhead / (0.05 x t_row)`` with
   ``t_row`` the wall time per row of the throughput run at the largest
   chunk size (1 / sims/s).  Besides, a study should have several chunks per
   worker, or the last chunks run with idle workers (seen in 1 at large
   chunk sizes).

First calls (kernel cache load, cluster start) are timed apart.  The machine
may be shared: the load average is printed, and timings vary with it.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RECORDS_DIR = Path(os.environ.get("FASTROCK_RECORDS_DIR",
                                  HERE.parents[1] / "shared" / "data" / "records"))
UNITS = {"Northridge_Sylmar_County.dat": "m/s2"}


def make_study(quick, levels=None):
    from fastrock import RigidBlock
    from fastrock.io.default_records import load_default_record
    from fastrock.io.readers import read_record
    from fastrock.studies.definition import Study
    if quick or not RECORDS_DIR.is_dir():
        records = [load_default_record()]
    else:
        files = sorted(p for p in RECORDS_DIR.iterdir() if p.suffix.lower() in (".at2", ".dat"))
        records = [read_record(f, unit=UNITS.get(f.name)) for f in files]
    bodies = [RigidBlock.rectangle(b, b / s) for b in (0.15, 0.3, 0.6) for s in (0.15, 0.2, 0.25, 0.3)]
    if levels is None:
        levels = np.round(np.linspace(0.1, 1.0, 10), 3)
    return Study(records=records, bodies=bodies, levels=levels, t_after=10.0)


def run(study, chunk_size, **kw):
    from fastrock.studies.run import run_study
    with tempfile.TemporaryDirectory() as tmp:
        df = run_study(study, Path(tmp) / "out", chunk_size=chunk_size, progress=False, **kw)
    a = df.attrs
    return {"rows": len(df), "chunks": a["n_chunks"], "wall": a["wall_seconds"],
            "kernel": a["kernel_seconds"], "df": df}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--sizes", default="16,64,256", help="chunk sizes (default 16,64,256)")
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",")]

    import numba
    import pandas as pd
    from fastrock.studies.definition import Study
    from fastrock.studies.plan import Plan
    from fastrock.studies.worker import run_chunk
    study = make_study(args.quick)
    n = study.n_runs
    # 1 record, 12 blocks, 40 levels below uplift (PGA <= 0.04 g < g tan alpha = 0.15 g)
    empty = make_study(True, levels=np.linspace(0.001, 0.04, 40))
    print(f"study: {len(study.records)} records x {len(study.bodies)} blocks x "
          f"{len(study.levels)} PGA levels = {n} runs; load average "
          f"{', '.join(f'{x:.1f}' for x in os.getloadavg())}; numba {numba.__version__}, "
          f"{numba.get_num_threads()} threads")
    t0 = time.perf_counter()
    run(Study(records=study.records[:1], bodies=study.bodies[:1], levels=[0.2], t_after=1.0), 1)
    print(f"first call (kernel compile or cache load): {time.perf_counter() - t0:.2f} s")

    results = []     # (backend, chunk, result)
    base = None

    def bench(label, **kw):
        nonlocal base
        for cs in sizes + ([n] if label == "local" else []):
            r = run(study, cs, **kw)
            d = r["df"].drop(columns="chunk")
            if base is None:
                base = d
            pd.testing.assert_frame_equal(d, base, check_exact=True)
            results.append((label, cs, r))
        e = run(empty, 8, **kw)
        assert (e["df"]["status"] == "safe:no-uplift").all()
        results.append((label, "empty", e))

    bench("local")
    clusters = []
    if not args.no_dask:
        try:
            import distributed
        except ImportError:
            print("dask.distributed not installed: local only (pip install 'fastrock[distributed]')")
        else:
            t0 = time.perf_counter()
            cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                               host="127.0.0.1", dashboard_address=None,
                                               silence_logs=40)
            client = distributed.Client(cluster)
            plan = Plan(study.prepare(), 2)
            client.run(run_chunk, plan.payload(plan.chunks[0]))   # every worker loads the kernel
            print(f"LocalCluster start + workers' first call: {time.perf_counter() - t0:.2f} s")
            clusters.append((client, cluster))
            bench("dask 2x1", client=client, numba_threads=1)
            bench("dask 2x1 nt2", client=client, numba_threads=0)

    print()
    hdr = f"{'backend':<13} {'chunk':>6} {'chunks':>6} {'wall s':>7} {'sims/s':>8} {'kernel s':>8}"
    print("1. throughput (identical tables: checked)")
    print(hdr)
    print("-" * len(hdr))
    for label, cs, r in results:
        if cs != "empty":
            print(f"{label:<13} {cs:>6} {r['chunks']:>6} {r['wall']:>7.2f} "
                  f"{r['rows'] / r['wall']:>8.1f} {r['kernel']:>8.2f}")
    print()
    print("2./3. overhead per chunk (8-row chunks of rows that cost nothing) and chunk size "
          "for < 5 %")
    hdr = (f"{'backend':<13} {'chunks':>6} {'ms/chunk':>9} {'best sims/s':>11} {'ms/row':>7} "
           f"{'chunk >=':>8} {'ovh % at 64':>11} {'at 128':>7} {'at 256':>7}")
    print(hdr)
    print("-" * len(hdr))
    for label in dict.fromkeys(x[0] for x in results):
        e = next(r for lab, cs, r in results if lab == label and cs == "empty")
        ovh = e["wall"] / e["chunks"]
        best = max(r["rows"] / r["wall"] for lab, cs, r in results if lab == label and cs != "empty")
        t_row = 1.0 / best
        frac = [ovh / (ovh + c * t_row) for c in (64, 128, 256)]
        print(f"{label:<13} {e['chunks']:>6} {1e3 * ovh:>9.1f} {best:>11.1f} {1e3 * t_row:>7.2f} "
              f"{math.ceil(ovh / (0.05 * t_row)):>8d} "
              + " ".join(f"{100 * f:>{w}.1f}" for f, w in zip(frac, (11, 7, 7))))
    for client, cluster in clusters:
        client.close()
        cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
