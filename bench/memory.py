"""Peak memory of a big overturning spectrum (issue #15, item 5).

Prints the resident memory (RSS) after each stage -- numpy, pandas, fastrock imported, the rigid
kernel loaded (a 1 x 1 spectrum), the N x N spectrum done -- the process's peak RSS and the
table's own size, for one rigid-block spectrum of N x N cells (default 1000: a million runs)::

    python bench/memory.py            # 1000 x 1000
    python bench/memory.py --n 300
    python bench/memory.py --columns outcome max_rotation_ratio    # overturning_spectrum(columns=...)

Run it in a process of its own (the peak is the process's ``ru_maxrss``).  Each stage also shows
its anonymous memory (heap, arrays) apart from the file-backed pages of the shared libraries
(numpy, pandas, numba's LLVM), which count in RSS but are shared between processes.
"""
import argparse
import resource
import sys
import time


def rss_mb():
    """(RSS, its anonymous part, its file-backed part) in MB."""
    found = {}
    with open("/proc/self/status") as f:
        for line in f:
            key = line.split(":")[0]
            if key in ("VmRSS", "RssAnon", "RssFile"):
                found[key] = int(line.split()[1]) / 1024
    return tuple(found.get(k, float("nan")) for k in ("VmRSS", "RssAnon", "RssFile"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="cells per axis (default 1000)")
    ap.add_argument("--columns", nargs="+", default=None,
                    help="result columns to keep (overturning_spectrum(columns=...)); default all")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    import numpy as np
    stages = [("numpy", rss_mb())]
    import pandas  # noqa: F401
    stages.append(("pandas", rss_mb()))
    import fastrock as fr
    stages.append(("import fastrock (numba, scipy through numba)", rss_mb()))
    body = fr.RigidBlock(0.25, 2.0)
    fr.overturning_spectrum(body, [1.0], [1.0], progress=False)
    stages.append(("rigid kernel loaded (1 x 1 spectrum)", rss_mb()))
    t1 = time.perf_counter()
    df = fr.overturning_spectrum(body, np.linspace(0.5, 8, args.n), np.linspace(0.25, 10, args.n),
                                 progress=False, columns=args.columns)
    el = time.perf_counter() - t1
    stages.append((f"{args.n} x {args.n} spectrum done", rss_mb()))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    for name, (mb, anon, file) in stages:
        print(f"{name:<48} RSS {mb:8.1f} MB  (anonymous {anon:6.1f}, shared-library files {file:6.1f})")
    table = df.memory_usage(deep=True).sum() / 2 ** 20
    print(f"{'peak RSS of the process':<48}     {peak:8.1f} MB")
    print(f"{'the table':<48}     {table:8.1f} MB ({table * 2 ** 20 / len(df):.0f} bytes per row, "
          f"{len(df):,} rows, {len(df.columns)} columns)")
    print(f"spectrum {el:.1f} s, whole script {time.perf_counter() - t0:.1f} s; python {sys.version.split()[0]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
