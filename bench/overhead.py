#!/usr/bin/env python
"""Python overhead of single calls (issue #15, item 6), printed with the load average.

    python bench/overhead.py

* ``simulate`` of a block that never uplifts (a_p = 0.05 g, the kernel takes no step): the whole
  call is front-end work (validation, kernel inputs, the thread that keeps Ctrl-C responsive,
  metrics); the history and events tables are built only when read, so they are timed apart.
* a 1 x 1 ``overturning_spectrum`` and a 10-scene ``run_batch``.
Each figure is the median of 7 repeats of a loop, after a warm-up call (kernels compiled or
loaded from the cache before timing).
"""
import os
import statistics
import time

import fastrock as fr


def per_call(fn, n):
    fn()
    times = []
    for _ in range(7):
        t = time.perf_counter()
        for _ in range(n):
            fn()
        times.append((time.perf_counter() - t) / n)
    return statistics.median(times)


def main():
    blk = fr.RigidBlock(alpha=0.25, p=2.0)
    quiet = fr.Pulse(0.05, 1.0)
    sim = per_call(lambda: fr.simulate(blk, quiet), 300)
    tables = per_call(lambda: (lambda r: (r.history, r.events))(fr.simulate(blk, quiet)), 300)
    spec = per_call(lambda: fr.overturning_spectrum(blk, [0.05], [1.0], progress=False), 100)
    scenes = [fr.Scene(blk, fr.Pulse(0.05 + 0.01 * i, 1.0)) for i in range(10)]
    batch = per_call(lambda: fr.run_batch(scenes, progress=False), 30)
    print(f"load average {os.getloadavg()[0]:.2f}")
    print(f"simulate (never uplifts)            {sim * 1e6:8.0f} us   (issue #15 target: <= 200 us)")
    print(f"  ... and reading history + events  {tables * 1e6:8.0f} us")
    print(f"overturning_spectrum 1 x 1          {spec * 1e6:8.0f} us")
    print(f"run_batch of 10 scenes              {batch * 1e6:8.0f} us  ({batch / 10 * 1e6:.0f} us per scene)")


if __name__ == "__main__":
    main()
