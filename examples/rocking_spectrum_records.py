#!/usr/bin/env python
"""Rocking spectrum of the shared recorded earthquakes: beta against Tp/Tm.
========================================================================

Runs every record in ``../shared/data/records/`` (override with
FASTROCK_RECORDS_DIR; the Sylmar file has no unit in its header and is in
m/s^2) against Mennitti et al.'s 400 blocks (20 b/h in [0.1, 0.5] x 20
half-widths in [0.1, 1] m) and the wall settings available (two-sided, plus
d = 1 cm and 10 cm with the wall model), then saves

* ``out/rocking_spectrum_records.png``: beta = (b/h)_min g / PGA against
  Tp/Tm, one panel per wall setting, with Maiorano et al.'s upper-bound curve
  1.35 exp(-0.12 Tp/Tm); hollow triangles are bounds (down: every block of
  the grid was stable, so beta is at most that; up: none was);
* ``out/rocking_spectrum_records.csv``: the table, one row per
  record x size x wall setting.

Usage: ``python examples/rocking_spectrum_records.py`` (about half a minute).
If the shared folder is absent it falls back to the packaged El Centro record.
"""
from __future__ import annotations

import os
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from fastrock.io.default_records import load_default_record  # noqa: E402
from fastrock.io.readers import read_record  # noqa: E402
from fastrock.plotting.rocking_spectrum import plot_rocking_spectrum  # noqa: E402
from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
RECORDS = Path(os.environ.get("FASTROCK_RECORDS_DIR", ROOT.parent / "shared" / "data" / "records"))
OUT = ROOT / "out"
UNITS = {"Northridge_Sylmar_County.dat": "m/s2"}


def load_records():
    if not RECORDS.is_dir():
        print(f"{RECORDS} absent: using the packaged El Centro record only")
        return [load_default_record()]
    files = sorted(p for p in RECORDS.iterdir() if p.suffix.lower() in (".at2", ".dat"))
    return [read_record(f, unit=UNITS.get(f.name)) for f in files]


def main():
    records = load_records()
    t0 = time.perf_counter()
    table = rocking_spectrum(records)            # default grid and wall settings
    el = time.perf_counter() - t0
    walls = table.attrs["walls"]
    n_runs = len(records) * 400 * len(walls)
    print(f"{n_runs} runs in {el:.1f} s ({n_runs / el:,.0f} runs/s)")
    summary = table.groupby("wall", sort=False).agg(
        median_beta=("beta", "median"), exact=("beta_bound", lambda b: int((b == "exact").sum())),
        upper=("beta_bound", lambda b: int((b == "upper").sum())),
        lower=("beta_bound", lambda b: int((b == "lower").sum())),
        non_monotone=("non_monotone", "sum"))
    print(summary.round(3).to_string())
    above = table[(table["wall"] == "two-sided") & (table["beta_bound"] == "exact")]
    from fastrock.analyses.rocking_spectrum.definitions import upper_bound_beta
    n_above = int((above["beta"] > upper_bound_beta(above["tp_over_tm"])).sum())
    print(f"two-sided, exact points above the upper-bound curve: {n_above} of {len(above)}")

    OUT.mkdir(exist_ok=True)
    fig, axes = plt.subplots(1, len(walls), figsize=(5.2 * len(walls), 4.6), sharey=True,
                             squeeze=False, constrained_layout=True)
    for ax, wall in zip(axes[0], walls):
        plot_rocking_spectrum(table[table["wall"] == wall], ax=ax, title=wall)
    fig.suptitle(f"{len(records)} records x 400 blocks: minimum stable slenderness")
    png = OUT / "rocking_spectrum_records.png"
    csv = OUT / "rocking_spectrum_records.csv"
    fig.savefig(png, dpi=130)
    table.to_csv(csv, index=False)
    print(f"wrote {png} and {csv}")


if __name__ == "__main__":
    main()
