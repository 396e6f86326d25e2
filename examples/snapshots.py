#!/usr/bin/env python
"""Snapshots of a run: the same block and pulse on level and on sloping ground.
=============================================================================

Block b = 0.2 m, h = 0.8 m (half-dimensions: alpha = 0.245 rad), Housner's restitution, one
one-sine pulse of 0.3 g at 1.5 Hz whose ground first accelerates toward -x (uphill on the slope).
On level ground the block rocks and comes back to rest; on a 5 degree slope, where the downhill
uplift threshold drops from g tan(alpha) = 0.25 g to g tan(alpha - phi) = 0.16 g, the same pulse
overturns it downhill (docs: guide, 'Sloping ground').  ``fastrock.plot_snapshots`` draws each
run as a strip of the block's outline at six instants, the one of largest rotation among them,
with the time, rotation and slip under each.

Usage::

    python examples/snapshots.py [OUT_DIR]

writes ``snapshots.png`` to OUT_DIR (default ``out/``).  The committed figure:

.. image:: /snapshots.png
   :alt: the block at six instants on level ground (top) and on a 5 degree slope (bottom)
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import fastrock as fr
from fastrock.plotting.figures import get_pyplot


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default="out", help="output folder (default out/)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    block = fr.RigidBlock.rectangle(b=0.2, h=0.8)
    pulse = fr.Pulse(0.3, 1.5, sign=-1)
    runs = {"level ground": fr.simulate(block, pulse),
            "5 degree slope": fr.simulate(block, pulse, ground=fr.Ground(math.radians(5.0)))}
    plt = get_pyplot()
    fig, axes = plt.subplots(2, 1, figsize=(9.0, 4.6), constrained_layout=True)
    for ax, (label, run) in zip(axes, runs.items()):
        print(f"{label}: {run.status}, max |theta| = {run.metrics['max_rotation']:.3f} rad")
        fr.plot_snapshots(run, n=6, ax=ax)
        ax.set_title(f"{label}: {run.status}", fontsize=9)
    fig.savefig(out / "snapshots.png", dpi=90)
    print(f"wrote {out / 'snapshots.png'}")


if __name__ == "__main__":
    main()
