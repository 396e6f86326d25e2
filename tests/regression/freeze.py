"""Frozen regression grids: the single source of the case definitions.

Every model family that exists today (rigid two-sided, rear wall, rigid friction, flexible body
with both impact maps, flexible body with friction ("stop" and "hold"), the three foundation
models, records, vertical excitation) is run on small grids and the results are frozen in
``tests/data/regression/<case id>.csv.gz``.  ``tests/test_regression_frozen.py`` recomputes
every case from the definitions below and compares (contract: same outcomes and statuses,
same integer counts, every float within ``|a - b| <= 1e-12 * max(1, |b|)``, NaN == NaN).

Command line (from the repository root)::

    python tests/regression/freeze.py --list              # the cases and their files
    python tests/regression/freeze.py --check             # recompute and compare (as the test)
    python tests/regression/freeze.py --missing           # freeze only cases without a file
    python tests/regression/freeze.py --overwrite [ID..]  # re-freeze (defeats the purpose!)

Without ``--overwrite`` the script refuses to touch an existing frozen file: regenerating the
files after a change would freeze the change.  Re-freeze only on purpose (a deliberate change
of results, stated in the commit message), never to make the regression test pass.

Case definitions call the public API with keyword arguments only, so a model that gains new
optional parameters is still called the same way.  Objects are described by :class:`O`
(constructor name + keyword arguments), which builds them and gives the stable text stored in
the frozen files (a dataclass ``repr`` would change when a class gains a field).

File format: gzip'd CSV (gzip mtime 0, so the bytes are reproducible); line 1 the column
names, line 2 their types (``f`` float64 written with ``repr``, which round-trips exactly,
``i`` int, ``b`` bool, ``s`` text); then one line per row.  ``MANIFEST.json`` records the rows,
a SHA-256 of each CSV text, and the commit ("+dirty": fastrock/ or kernels/ modified) and
environment that froze each file.
"""
from __future__ import annotations

import argparse
import csv
import gzip
import hashlib
import io
import json
import math
import platform
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
DATA_DIR = HERE.parent / "data" / "regression"
MANIFEST = DATA_DIR / "MANIFEST.json"

#: Relative/absolute tolerance of the float comparison: |a - b| <= TOL * max(1, |b|).
TOL = 1e-12
#: Integration cost counters: a speed refactor may change them legitimately.  They are
#: compared by a separate test (test_regression_frozen.py::test_step_counts_unchanged).
COST_COLUMNS = ("nfev", "steps", "rejected_steps", "history_rows")
#: Columns that describe the inputs of a row (reported apart in failure messages).
INPUT_PREFIX = "in_"


# ----------------------------------------------------------------------------- objects
class O:
    """A constructor call with keyword arguments: ``O("RigidBlock", alpha=0.2, p=2.0)``.

    ``build()`` makes the object (nested ``O`` values are built first); ``str()`` is the
    text stored in the frozen files.
    """

    def __init__(self, ctor, **kw):
        self.ctor = ctor
        self.kw = kw

    def build(self):
        import fastrock as fr
        from fastrock.model import foundation as F
        from fastrock.io import default_records as R
        ctors = {
            "RigidBlock": fr.RigidBlock,
            "RigidBlock.rectangle": fr.RigidBlock.rectangle,
            "FlexibleBody": fr.FlexibleBody,
            "Wall": fr.Wall,
            "Friction": fr.Friction,
            "Pulse": fr.Pulse,
            "SampledMotion.from_record": fr.SampledMotion.from_record,
            "load_default_record": R.load_default_record,
            "TwoSpringFoundation": F.TwoSpringFoundation,
            "TwoSpringFoundation.from_vibration": F.TwoSpringFoundation.from_vibration,
            "SwitchingFoundation": F.SwitchingFoundation,
            "SwitchingFoundation.from_vibration": F.SwitchingFoundation.from_vibration,
            "LinearVibration": F.LinearVibration,
            "LinearVibration.from_vibration": F.LinearVibration.from_vibration,
        }
        return ctors[self.ctor](**{k: build(v) for k, v in self.kw.items()})

    def __str__(self):
        return f"{self.ctor}({', '.join(f'{k}={describe(v)}' for k, v in self.kw.items())})"

    __repr__ = __str__


def build(v):
    if isinstance(v, O):
        return v.build()
    if isinstance(v, (list, tuple)):
        return type(v)(build(x) for x in v)
    return v


def describe(v):
    if isinstance(v, O):
        return str(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(describe(x) for x in v) + "]"
    return repr(v)


# ------------------------------------------------------------------------------- cases
@dataclass(frozen=True)
class Case:
    family: str
    name: str
    run: Callable[[], pd.DataFrame]
    setup: str          # the call, as text (stored in the file, column in_setup)

    @property
    def id(self):
        return f"{self.family}-{self.name}"

    @property
    def path(self):
        return DATA_DIR / f"{self.id}.csv.gz"


CASES: list[Case] = []


def _add(case):
    if any(c.id == case.id for c in CASES):
        raise ValueError(f"duplicate case id {case.id}")
    CASES.append(case)


def _quiet(fn):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn()


def spectrum(family, name, body, amplitude_ratios, frequency_ratios, **kw):
    """A case: ``overturning_spectrum(body, amplitude_ratios, frequency_ratios, **kw)``
    (sign "both" unless given; progress off)."""
    kw.setdefault("sign", "both")
    setup = (f"overturning_spectrum(body={describe(body)}, amplitude_ratios="
             f"{describe(tuple(amplitude_ratios))}, frequency_ratios={describe(tuple(frequency_ratios))}, "
             + ", ".join(f"{k}={describe(v)}" for k, v in kw.items()) + ")")

    def run():
        import fastrock as fr
        df = _quiet(lambda: fr.overturning_spectrum(build(body), list(amplitude_ratios),
                                                    list(frequency_ratios), progress=False,
                                                    **{k: build(v) for k, v in kw.items()}))
        df = df.rename(columns={c: INPUT_PREFIX + c for c in ("amplitude_ratio", "frequency_ratio",
                                                               "sign")})
        df.insert(0, INPUT_PREFIX + "setup", setup)
        return df

    _add(Case(family, name, run, setup))


STATE_COLUMNS = ("theta", "theta_dot", "u", "u_dot", "d", "d_dot", "y", "y_dot")


def _single_row(call, kw):
    import fastrock as fr
    from fastrock.running import foundation as F
    import importlib
    RS = importlib.import_module("fastrock.analyses.rocking_spectrum.single_runs")
    fn = {"simulate": fr.simulate, "simulate_foundation": F.simulate_foundation,
          "simulate_record": RS.simulate_record}[call]
    built = {k: build(v) for k, v in kw.items()}
    res = _quiet(lambda: fn(**built))
    row = {INPUT_PREFIX + "call": call}
    for k, v in kw.items():
        row[INPUT_PREFIX + k] = describe(v)
    row.update(kernel=res.kernel, outcome=res.outcome, status=res.status,
               status_code=int(res.status_code), effects=" ".join(res.effects))
    for k, v in sorted(res.metrics.items()):
        row[k] = v
    h = res.history
    row["history_rows"] = len(h)
    row["t_last"] = float(h["t"].iloc[-1]) if len(h) else math.nan
    row["end_contact"] = str(h["contact"].iloc[-1]) if len(h) else ""
    for c in STATE_COLUMNS:
        if c in h:
            row["end_" + c] = float(h[c].iloc[-1])
    ev = res.events
    counts = ev["event"].value_counts()
    row["events"] = len(ev)
    row["event_counts"] = ";".join(f"{k}={int(counts[k])}" for k in sorted(counts.index))
    row["events_dropped"] = int(ev.attrs.get("dropped", 0))
    return row


def singles(family, name, rows, call="simulate"):
    """A case: one ``call(**kw)`` (simulate, simulate_foundation, simulate_record) per row;
    ``rows`` is a list of keyword dicts (a row may give its own ``call``)."""
    rows = [dict(r) for r in rows]
    setup = f"{call} x {len(rows)} rows"

    def run():
        out = []
        for r in rows:
            r = dict(r)
            c = r.pop("call", call)
            out.append(_single_row(c, r))
        df = pd.DataFrame(out)
        # input columns first, the same text "" where a row does not give that input
        ins = [c for c in df.columns if c.startswith(INPUT_PREFIX)]
        df[ins] = df[ins].fillna("")
        return df[ins + [c for c in df.columns if c not in ins]]

    _add(Case(family, name, run, setup))


def table(family, name, setup, fn):
    """A case: any function returning a DataFrame (rocking spectrum)."""
    def run():
        df = _quiet(fn).reset_index(drop=True)
        df.insert(0, INPUT_PREFIX + "setup", setup)
        return df
    _add(Case(family, name, run, setup))


# ----------------------------------------------------------------------- definitions
# Grids avoid round values that sit exactly on a threshold (amplitude ratio 1 is the
# static uplift limit).
A8 = (0.7, 1.3, 2.1, 3.0, 4.2, 5.6, 7.3, 9.5)
F8 = (0.6, 1.1, 1.7, 2.5, 3.6, 5.1, 7.0, 9.6)
A6 = (0.8, 1.6, 2.7, 4.1, 6.2, 9.1)
F6 = (0.7, 1.4, 2.3, 3.8, 5.7, 8.9)
A4 = (1.3, 3.0, 5.6, 9.5)
F4 = (0.9, 2.2, 4.4, 8.3)
PULSES = ("one-sine", "half-sine", "one-cosine")


def pulse(amplitude_ratio, frequency_ratio, **kw):
    return O("Pulse", amplitude=amplitude_ratio, frequency=frequency_ratio,
             amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p", **kw)


# 1. rigid block, two-sided --------------------------------------------------------------
RIGID = O("RigidBlock", alpha=0.2, p=2.0)
for _p in PULSES:
    for _early in (True, False):
        spectrum("rigid", f"{_p}-{'early' if _early else 'full'}", RIGID, A8, F8, pulse=_p,
                 early_exit=_early)
spectrum("rigid", "one-sine-dt0.005-early", RIGID, A4, F4, pulse="one-sine", dt=0.005,
         early_exit=True)
spectrum("rigid", "one-cosine-dt0.002-full", RIGID, A4, F4, pulse="one-cosine", dt=0.002,
         early_exit=False)
spectrum("rigid", "half-sine-dt0.02-full", RIGID, A4, F4, pulse="half-sine", dt=0.02,
         early_exit=False)
spectrum("rigid", "rectangle-e0.85-rtol1e-10", O("RigidBlock.rectangle", b=0.25, h=1.0, e=0.85),
         A6, F6, pulse="one-sine", rtol=1e-10, atol=1e-12)
spectrum("rigid", "theta_over1.0-t_after3", O("RigidBlock", alpha=0.2, p=2.0, theta_over=1.0),
         A4, F4, pulse="half-sine", t_after=3.0, early_exit=False)
singles("rigid", "simulate", [
    *[dict(body=RIGID, excitation=pulse(a, f, sign=s, kind=k))
      for a in (2.1, 5.6) for f in (1.7, 5.1) for s in (1, -1) for k in ("one-sine", "one-cosine")],
    *[dict(body=RIGID, theta0=th, dtheta0=om, duration=6.0)
      for th, om in ((0.05, 0.0), (0.15, 0.0), (-0.1, 0.3), (0.19, 0.05))],
    dict(body=RIGID, excitation=O("Pulse", kind="rectangular", amplitude=0.35, duration=0.6,
                                  t_start=0.2)),
    dict(body=RIGID, excitation=pulse(3.0, 2.5), early_exit=True),
    dict(body=RIGID, excitation=pulse(3.0, 2.5), dt=0.004),
])

# 2. rigid block with a rear wall ---------------------------------------------------------
WB = O("RigidBlock.rectangle", b=0.2, h=1.0)
spectrum("wall", "gap0.01-one-sine-early", WB, A8, F8, pulse="one-sine",
         wall=O("Wall", gap=0.01), early_exit=True)
spectrum("wall", "gap0.01-one-sine-full", WB, A8, F8, pulse="one-sine",
         wall=O("Wall", gap=0.01), early_exit=False)
spectrum("wall", "hogan-side+1-r0.8", WB, A6, F6, pulse="one-sine",
         wall=O("Wall", gap=0.0, side=1, restitution=0.8))
spectrum("wall", "gap0.05-short-r0.7-half-sine", WB, A6, F6, pulse="half-sine",
         wall=O("Wall", gap=0.05, height=1.2, restitution=0.7))
spectrum("wall", "gap0.1-one-cosine-dt0.005", WB, A4, F4, pulse="one-cosine",
         wall=O("Wall", gap=0.1), dt=0.005)
spectrum("wall", "gap3-unreachable", WB, A4, F4, pulse="one-sine", wall=O("Wall", gap=3.0))
singles("wall", "simulate", [
    *[dict(body=WB, wall=O("Wall", gap=0.01), excitation=pulse(a, f, sign=s))
      for a in (2.1, 5.6) for f in (1.7, 5.1) for s in (1, -1)],
    dict(body=WB, wall=O("Wall", gap=0.0, restitution=0.8), excitation=pulse(3.0, 2.5, sign=-1)),
    dict(body=WB, wall=O("Wall", gap=0.03, side=1), theta0=-0.15, duration=6.0),
    dict(body=WB, wall=O("Wall", gap=0.03), theta0=0.15, duration=6.0),
])

# 3. rigid block with friction --------------------------------------------------------------
spectrum("friction", "mu0.3-one-sine-early", RIGID, A8, F8, pulse="one-sine",
         friction=O("Friction", mu_s=0.3))
spectrum("friction", "mu0.6-0.5-one-sine-full", RIGID, A8, F8, pulse="one-sine",
         friction=O("Friction", mu_s=0.6, mu_k=0.5), early_exit=False)
spectrum("friction", "mu0.15-half-sine", RIGID, A6, F6, pulse="half-sine",
         friction=O("Friction", mu_s=0.15))
spectrum("friction", "mu0.35-0.3-one-cosine-rectangle", O("RigidBlock.rectangle", b=0.2, h=0.8),
         A4, F4, pulse="one-cosine", friction=O("Friction", mu_s=0.35, mu_k=0.3,
                                                 slide_tolerance=1e-4))
singles("friction", "simulate", [
    *[dict(body=RIGID, friction=O("Friction", mu_s=mu), excitation=pulse(a, f, sign=s))
      for mu in (0.15, 0.4) for a in (1.3, 4.2) for f in (1.7, 5.1) for s in (1, -1)],
    dict(body=RIGID, friction=O("Friction", mu_s=0.3), theta0=0.12, dtheta0=0.2, duration=5.0),
    dict(body=RIGID, friction=O("Friction", mu_s=0.1, mu_k=0.08),
         excitation=O("Pulse", kind="rectangular", amplitude=0.3, duration=0.5)),
])

# 3b. the contact model (rigid block + wall + friction, free flight) ---------------------------
# frozen after the other families (kernels of 4728fc9), before the contact fuzz fixes
CB = O("RigidBlock.rectangle", b=0.1, h=0.5)
CB_SLENDER = O("RigidBlock.rectangle", b=0.02, h=0.8)
spectrum("contact", "wall0.01-mu0.3-one-sine", CB, A8, F8, pulse="one-sine",
         wall=O("Wall", gap=0.01), friction=O("Friction", mu_s=0.3))
spectrum("contact", "wall0-mu0.25-0.2-half-sine", CB, A6, F6, pulse="half-sine",
         wall=O("Wall", gap=0.0, side=1, restitution=0.6), friction=O("Friction", mu_s=0.25, mu_k=0.2))
spectrum("contact", "slender-wall0.002-mu0.08-one-cosine", CB_SLENDER, A6, F6, pulse="one-cosine",
         wall=O("Wall", gap=0.002, restitution=0.1), friction=O("Friction", mu_s=0.08, mu_k=0.07))
spectrum("contact", "flight-wall0.02-one-sine", CB, A6, F6, pulse="one-sine",
         wall=O("Wall", gap=0.02, side=1), friction=O("Friction", mu_s=0.5, lift_off="flight"))
singles("contact", "simulate", [
    *[dict(body=CB, wall=O("Wall", gap=0.01), friction=O("Friction", mu_s=mu), excitation=pulse(a, f, sign=s))
      for mu in (0.12, 0.5) for a in (1.3, 4.2) for f in (1.7, 5.1) for s in (1, -1)],
    *[dict(body=CB_SLENDER, wall=O("Wall", gap=g, side=-1, restitution=0.1),
           friction=O("Friction", mu_s=0.06, mu_k=0.05), excitation=pulse(a, 0.6, kind="one-cosine"))
      for g in (0.0, 0.001) for a in (2.4, 6.0)],
    dict(body=CB, wall=O("Wall", gap=0.02), friction=O("Friction", mu_s=0.3), theta0=0.15, duration=5.0),
    dict(body=CB, friction=O("Friction", mu_s=0.5, lift_off="flight"), excitation=pulse(2.0, 2.5),
         vertical=O("Pulse", kind="rectangular", amplitude=1.2, sign=-1, amplitude_unit="g",
                    duration=0.2, t_start=0.1)),
])

# 4. flexible body (both impact maps) -------------------------------------------------------
FB9 = O("FlexibleBody", alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05)
FB30 = O("FlexibleBody", alpha=0.3, p=2.0, omega_n_over_p=30.0, zeta=0.02)
FB9_I1 = O("FlexibleBody", alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, impact="pivot-switch")
FB30_I1 = O("FlexibleBody", alpha=0.3, p=2.0, omega_n_over_p=30.0, zeta=0.02,
            impact="pivot-switch", e=0.9)
FB_BASE = O("FlexibleBody", alpha=0.3, p=2.0, omega_n_over_p=9.0, zeta=0.05, base_mass_ratio=0.2,
            base_cm_height=0.1, rotary_inertia_ratio=0.1)
spectrum("flexible", "wn9-full-contact-one-sine-early", FB9, A8, F8, pulse="one-sine")
spectrum("flexible", "wn30-full-contact-one-sine-full", FB30, A8, F8, pulse="one-sine",
         early_exit=False)
spectrum("flexible", "wn9-pivot-switch-one-sine-early", FB9_I1, A8, F8, pulse="one-sine")
spectrum("flexible", "wn30-pivot-switch-e0.9-half-sine", FB30_I1, A6, F6, pulse="half-sine")
spectrum("flexible", "wn9-base-mass-one-cosine", FB_BASE, A6, F6, pulse="one-cosine")
spectrum("flexible", "wn9-dt0.002", FB9, A4, F4, pulse="one-sine", dt=0.002)
# a fixed step outside the stability region: failed:unstable-step (tests/test_fixed_step_stability.py)
spectrum("flexible", "dt-unstable", O("FlexibleBody", alpha=0.04664, p=0.84498, omega_n_over_p=9.0618),
         (3.98138,), (7.89409,), sign=1, pulse="one-cosine", dt=0.02612)
singles("flexible", "simulate", [
    *[dict(body=b, excitation=pulse(a, f, sign=s))
      for b in (FB9, FB9_I1, FB_BASE) for a in (2.1, 5.6) for f in (1.7, 5.1) for s in (1, -1)],
    *[dict(body=b, theta0=0.15, duration=5.0) for b in (FB9, FB30, FB9_I1, FB30_I1)],
])

# 5. flexible body with friction -------------------------------------------------------------
spectrum("flexible_friction", "stop-mu0.6-0.5-one-sine", FB9, A8, F8, pulse="one-sine",
         friction=O("Friction", mu_s=0.6, mu_k=0.5))
spectrum("flexible_friction", "hold-mu1.0-one-sine", FB9, A8, F8, pulse="one-sine",
         friction=O("Friction", mu_s=1.0, lift_off="hold"))
spectrum("flexible_friction", "stop-mu0.25-half-sine", FB9, A6, F6, pulse="half-sine",
         friction=O("Friction", mu_s=0.25))
spectrum("flexible_friction", "hold-mu0.8-0.7-wn30-full", FB30, A6, F6, pulse="one-sine",
         friction=O("Friction", mu_s=0.8, mu_k=0.7, lift_off="hold"), early_exit=False)
singles("flexible_friction", "simulate", [
    *[dict(body=FB9, friction=O("Friction", mu_s=mu, lift_off=lo), excitation=pulse(a, f, sign=s))
      for mu, lo in ((0.25, "stop"), (0.8, "hold")) for a in (1.3, 4.2) for f in (1.7, 5.1)
      for s in (1, -1)],
    dict(body=FB_BASE, friction=O("Friction", mu_s=0.5), excitation=pulse(3.0, 2.5)),
    dict(body=FB9, friction=O("Friction", mu_s=1.0, lift_off="hold"), theta0=0.2, duration=4.0),
])

# 6. foundation models (simulate_foundation) -------------------------------------------------
FBODY = O("RigidBlock.rectangle", b=0.1, h=0.5)
FOUNDATIONS = {
    "two_spring": [O("TwoSpringFoundation.from_vibration", body=FBODY, omega=40.0, zeta=0.1),
                   O("TwoSpringFoundation", k_v=2.0e4, c_v=30.0)],
    "switching": [O("SwitchingFoundation.from_vibration", body=FBODY, omega=40.0, zeta=0.1, e_f=0.9),
                  O("SwitchingFoundation", k_t=300.0, c_t=2.0)],
    "linear": [O("LinearVibration.from_vibration", body=FBODY, omega=20.0, zeta=0.05),
               O("LinearVibration", k_t=10.0, c_t=0.1)],
}
RELEASES = ((0.01, 0.0), (0.05, 0.0), (0.1, 0.0), (0.15, 0.0), (0.19, 0.0), (0.08, -0.5),
            (-0.12, 0.3))
for _model, _fnds in FOUNDATIONS.items():
    singles("foundation", f"{_model}-free", [
        *[dict(body=FBODY, foundation=fnd, theta0=th, dtheta0=om, duration=3.0)
          for fnd in _fnds for th, om in RELEASES],
        *([dict(body=FBODY, foundation=_fnds[0], theta0=0.21, duration=3.0, allow_overturn=True)]
          if _model != "linear" else []),
    ], call="simulate_foundation")
    singles("foundation", f"{_model}-pulses", [
        dict(body=FBODY, foundation=_fnds[0], excitation=pulse(a, f, sign=s), mass=2.5)
        for a in (1.3, 4.2) for f in (1.7, 5.1) for s in (1, -1)
    ], call="simulate_foundation")

# a flexible body on the two-spring foundation (frozen when the model was added)
FFLEX = O("FlexibleBody", alpha=0.2, p=2.0, omega_n_over_p=6.0, zeta=0.05, base_mass_ratio=0.3, mass=2.0)
FFLEX_FND = [O("TwoSpringFoundation.from_vibration", body=FFLEX, omega=40.0, zeta=0.1),
             O("TwoSpringFoundation", k_v=3.0e4, c_v=30.0)]
singles("foundation", "flexible_two_spring-free", [
    dict(body=FFLEX, foundation=fnd, theta0=th, dtheta0=om, duration=3.0)
    for fnd in FFLEX_FND for th, om in RELEASES
], call="simulate_foundation")
singles("foundation", "flexible_two_spring-pulses", [
    dict(body=FFLEX, foundation=FFLEX_FND[0], excitation=pulse(a, f, sign=s))
    for a in (1.3, 4.2) for f in (1.7, 5.1) for s in (1, -1)
], call="simulate_foundation")

# 7. records (packaged El Centro) -------------------------------------------------------------
REC = O("load_default_record")
REC15 = O("SampledMotion.from_record", record=REC, scale=1.5)
REC20 = O("SampledMotion.from_record", record=REC, scale=2.0)
RB = O("RigidBlock.rectangle", b=0.3, h=1.5)       # the CLI's default record block
RB_SLENDER = O("RigidBlock.rectangle", b=0.15, h=1.2)
FBR = O("FlexibleBody", alpha=0.2, p=2.2, omega_n_over_p=9.0, zeta=0.05)
FBR_I1 = O("FlexibleBody", alpha=0.2, p=2.2, omega_n_over_p=30.0, zeta=0.02, impact="pivot-switch")
singles("records", "rigid", [
    dict(body=RB, excitation=REC),
    dict(body=RB, excitation=REC, early_exit=True),
    dict(body=RB_SLENDER, excitation=REC),
    dict(body=RB_SLENDER, excitation=REC20),
    dict(body=O("RigidBlock", alpha=0.15, p=1.5), excitation=REC),
    dict(body=RB, excitation=REC15),
    dict(body=RB, excitation=REC15, early_exit=True),
    dict(body=RB, excitation=REC, dt=0.01),
    dict(body=RB, excitation=REC, record_breakpoints=False),
    dict(body=RB, record=REC, fixed_step=True, substeps=2, call="simulate_record"),
])
singles("records", "wall", [
    dict(body=RB, excitation=REC, wall=O("Wall", gap=0.01)),
    dict(body=RB, excitation=REC, wall=O("Wall", gap=0.1)),
    dict(body=RB, excitation=REC, wall=O("Wall", gap=0.01, side=1, restitution=0.8)),
    dict(body=RB, excitation=REC15, wall=O("Wall", gap=0.01)),
    dict(body=RB_SLENDER, excitation=REC, wall=O("Wall", gap=0.0, restitution=0.7)),
])
singles("records", "friction", [
    dict(body=RB, excitation=REC, friction=O("Friction", mu_s=0.3)),
    dict(body=RB, excitation=REC, friction=O("Friction", mu_s=0.15, mu_k=0.12)),
    dict(body=RB, excitation=REC15, friction=O("Friction", mu_s=0.2)),
])
singles("records", "flexible", [
    dict(body=FBR, excitation=REC),
    dict(body=FBR_I1, excitation=REC),
    dict(body=FBR, excitation=REC15),
    dict(body=FBR, excitation=REC20),
])
singles("records", "flexible_friction", [
    dict(body=FBR, excitation=REC, friction=O("Friction", mu_s=0.3)),
    dict(body=FBR, excitation=REC, friction=O("Friction", mu_s=0.5, lift_off="hold")),
    dict(body=FBR, excitation=REC15, friction=O("Friction", mu_s=0.2, lift_off="hold")),
])
singles("records", "foundation", [
    dict(body=RB, foundation=O("TwoSpringFoundation.from_vibration", body=RB, omega=40.0, zeta=0.05),
         excitation=REC),
    dict(body=RB, foundation=O("SwitchingFoundation.from_vibration", body=RB, omega=40.0, zeta=0.05,
                               e_f=0.9), excitation=REC),
    dict(body=RB, foundation=O("LinearVibration.from_vibration", body=RB, omega=15.0, zeta=0.05),
         excitation=REC),
], call="simulate_foundation")
_RS = dict(slenderness=(0.1, 0.14, 0.18, 0.22, 0.26, 0.3), half_widths=(0.05, 0.1, 0.3),
           walls=(None, 0.01))
_RS_TEXT = ", ".join(f"{k}={describe(v)}" for k, v in _RS.items())


def _rocking_runs():
    from fastrock.analyses.rocking_spectrum.engine import rocking_spectrum_runs
    return rocking_spectrum_runs(None, progress=False, **{k: list(v) for k, v in _RS.items()})


def _rocking_table():
    from fastrock.analyses.rocking_spectrum.definitions import rocking_spectrum
    return rocking_spectrum(None, progress=False, **{k: list(v) for k, v in _RS.items()})


table("records", "rocking_spectrum_runs", f"rocking_spectrum_runs(None, {_RS_TEXT})", _rocking_runs)
table("records", "rocking_spectrum_table", f"rocking_spectrum(None, {_RS_TEXT})", _rocking_table)

# 8. vertical excitation (simulate and simulate_foundation accept it for every model) --------
V_DOWN = O("Pulse", amplitude=0.4, frequency=2.0, sign=-1, amplitude_unit="g",
           frequency_unit="omega_p/p")
V_UP = O("Pulse", amplitude=0.6, frequency=1.0, sign=1, kind="half-sine", amplitude_unit="g",
         frequency_unit="omega_p/p")
V_FLIGHT = O("Pulse", kind="rectangular", amplitude=1.2, sign=-1, amplitude_unit="g",
             duration=0.2, t_start=0.1)


def _vertical_rows(**effects):
    return [
        *[dict(excitation=pulse(a, 2.5), vertical=v, **effects)
          for a in (1.5, 3.0, 5.0) for v in (V_DOWN, V_UP)],
        dict(excitation=pulse(1.5, 2.5), vertical=V_FLIGHT, **effects),
        dict(vertical=V_DOWN, theta0=0.1, duration=4.0, **effects),
    ]


singles("vertical", "rigid", _vertical_rows(body=RIGID))
singles("vertical", "wall", _vertical_rows(body=WB, wall=O("Wall", gap=0.01)))
singles("vertical", "friction", _vertical_rows(body=RIGID, friction=O("Friction", mu_s=0.3)))
singles("vertical", "flexible", _vertical_rows(body=FB9) + _vertical_rows(body=FB9_I1))
singles("vertical", "flexible_friction",
        _vertical_rows(body=FB9, friction=O("Friction", mu_s=0.6)) +
        _vertical_rows(body=FB9, friction=O("Friction", mu_s=0.6, lift_off="hold")))
singles("vertical", "foundation", [
    dict(body=FBODY, foundation=f, excitation=pulse(a, 2.5), vertical=v)
    for f in (FOUNDATIONS["two_spring"][0], FOUNDATIONS["switching"][0], FOUNDATIONS["linear"][0])
    for a in (1.5, 4.0) for v in (V_DOWN, V_UP)
], call="simulate_foundation")

FAMILIES = tuple(dict.fromkeys(c.family for c in CASES))


# -------------------------------------------------------------------------------- files
def _type_code(s: pd.Series):
    k = s.dtype.kind
    if k == "f":
        return "f"
    if k in "iu":
        return "i"
    if k == "b":
        return "b"
    if k == "O" and all(isinstance(v, str) for v in s):
        return "s"
    if k == "O" and all(isinstance(v, (bool, np.bool_)) for v in s):
        return "b"
    raise TypeError(f"column {s.name!r}: cannot freeze dtype {s.dtype} ({s.head(3).tolist()})")


def _cell(v, code):
    if code == "f":
        return repr(float(v))
    if code == "i":
        return str(int(v))
    if code == "b":
        return "True" if bool(v) else "False"
    return str(v)


def to_csv_text(df: pd.DataFrame) -> str:
    codes = [_type_code(df[c]) for c in df.columns]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(df.columns)
    w.writerow(codes)
    cols = [df[c].tolist() for c in df.columns]
    for row in zip(*cols):
        w.writerow([_cell(v, code) for v, code in zip(row, codes)])
    return buf.getvalue()


def from_csv_text(text: str) -> pd.DataFrame:
    rows = list(csv.reader(io.StringIO(text)))
    names, codes, body = rows[0], rows[1], rows[2:]
    conv = {"f": float, "i": int, "b": lambda s: s == "True", "s": str}
    data = {}
    for j, (name, code) in enumerate(zip(names, codes)):
        vals = [conv[code](r[j]) for r in body]
        dtype = {"f": np.float64, "i": np.int64, "b": bool, "s": object}[code]
        data[name] = np.array(vals, dtype=dtype)
    return pd.DataFrame(data, columns=names)


def write_frozen(path: Path, df: pd.DataFrame) -> str:
    text = to_csv_text(df)
    back = from_csv_text(text)            # the file must read back bit for bit
    diff = compare(back, df, cost=True)
    if diff:
        raise AssertionError(f"{path.name} does not read back exactly:\n{diff}")
    raw = io.BytesIO()
    with gzip.GzipFile(filename="", mode="wb", fileobj=raw, mtime=0, compresslevel=9) as gz:
        gz.write(text.encode())
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(raw.getvalue())
    return hashlib.sha256(text.encode()).hexdigest()


def read_frozen(path: Path) -> pd.DataFrame:
    with gzip.open(path, "rt", newline="") as f:
        return from_csv_text(f.read())


# ----------------------------------------------------------------------------- compare
def _is_num(s):
    return s.dtype.kind in "fiub"


def _same_float(a, b):
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    both_nan = np.isnan(a) & np.isnan(b)
    same_inf = np.isinf(a) & np.isinf(b) & (a == b)
    with np.errstate(invalid="ignore"):
        close = np.abs(a - b) <= TOL * np.maximum(1.0, np.abs(b))
    return both_nan | same_inf | close


def _fmt(v):
    """A value as plain Python repr (full precision, no numpy type names)."""
    return repr(v.item() if isinstance(v, np.generic) else v)


def compare(fresh: pd.DataFrame, frozen: pd.DataFrame, *, cost=False, max_report=25) -> str:
    """'' if ``fresh`` matches ``frozen``, else a report naming the rows and columns that changed.

    Main contract (``cost=False``): the same rows, every frozen column present; text and bool
    columns identical; integer columns identical; float columns within
    ``|a - b| <= TOL * max(1, |b|)`` (b frozen; NaN equals NaN, inf equals the same inf).
    Columns in ``COST_COLUMNS`` are skipped unless ``cost=True``, which compares only them.
    Columns the fresh frame has in addition (a new output) are ignored.
    """
    if len(fresh) != len(frozen):
        return f"row count changed: frozen {len(frozen)}, now {len(fresh)}"
    cols = [c for c in frozen.columns if (c in COST_COLUMNS) == cost]
    missing = [c for c in cols if c not in fresh.columns]
    lines = []
    if missing:
        lines.append(f"columns missing from the new results: {missing}")
    bad = {}
    for c in cols:
        if c in missing:
            continue
        a, b = fresh[c], frozen[c]
        if _is_num(b) and _is_num(a) and b.dtype.kind in "fc":
            ok = _same_float(a.to_numpy(float), b.to_numpy(float))
        elif _is_num(b) and _is_num(a):
            ok = a.to_numpy() == b.to_numpy()
        else:
            ok = np.array([x == y or (isinstance(x, float) and isinstance(y, float) and x != x and y != y)
                           for x, y in zip(a.tolist(), b.tolist())], bool)
        if not ok.all():
            bad[c] = np.flatnonzero(~ok)
    if not bad:
        return "\n".join(lines)
    rows = sorted(set().union(*[set(v.tolist()) for v in bad.values()]))
    inputs = [c for c in frozen.columns if c.startswith(INPUT_PREFIX) and c != INPUT_PREFIX + "setup"]
    lines.append(f"{len(rows)} of {len(frozen)} rows changed; columns (number of rows): "
                 + ", ".join(f"{c} ({v.size})" for c, v in bad.items()))
    for i in rows[:max_report]:
        key = ", ".join(f"{c[len(INPUT_PREFIX):]}={frozen[c].iloc[i]}" for c in inputs)
        changes = "; ".join(f"{c}: {_fmt(frozen[c].iloc[i])} -> {_fmt(fresh[c].iloc[i])}"
                            for c in bad if i in set(bad[c].tolist()))
        lines.append(f"  row {i} ({key}): {changes}")
    if len(rows) > max_report:
        lines.append(f"  ... and {len(rows) - max_report} more rows")
    return "\n".join(lines)


# ----------------------------------------------------------------------------- command
def environment():
    """The platform and versions that froze a file (ulp-level differences of libm or of
    NumPy between platforms could move results; see the test's docstring)."""
    import numba
    return (f"python {platform.python_version()}, numpy {np.__version__}, pandas {pd.__version__}, "
            f"numba {numba.__version__}, {platform.platform()}")


def _git_head():
    """HEAD, with "+dirty" if fastrock/ or kernels/ differ from it ("" outside git)."""
    import subprocess
    root = HERE.parent.parent
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--", "fastrock",
                                "kernels"], capture_output=True, text=True, check=True).stdout.strip()
        return head + ("+dirty" if dirty else "")
    except Exception:   # noqa: BLE001 - informational only
        return ""


def select_cases(ids):
    if not ids:
        return list(CASES)
    out = []
    for pat in ids:
        hit = [c for c in CASES if c.id == pat or c.family == pat]
        if not hit:
            raise SystemExit(f"no case or family {pat!r}; see --list")
        out += [c for c in hit if c not in out]
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*", help="case ids or family names (default: all)")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--check", action="store_true", help="recompute and compare with the frozen files")
    ap.add_argument("--missing", action="store_true", help="freeze only the cases that have no file")
    ap.add_argument("--overwrite", action="store_true",
                    help="replace existing frozen files (only for a deliberate change of results)")
    args = ap.parse_args(argv)
    cases = select_cases(args.cases)
    if args.list:
        for c in cases:
            print(f"{c.id:55s} {'frozen' if c.path.exists() else 'MISSING'}  {c.setup}")
        return 0
    if args.check:
        failed = 0
        for c in cases:
            t0 = time.perf_counter()
            fresh = c.run()
            frozen = read_frozen(c.path)
            d, dc = compare(fresh, frozen), compare(fresh, frozen, cost=True)
            print(f"{c.id}: {len(fresh)} rows, {time.perf_counter() - t0:.2f} s, "
                  f"{'OK' if not d else 'CHANGED'}{'' if not dc else ' (cost counters changed)'}")
            if d:
                failed += 1
                print(d)
        return 1 if failed else 0
    if args.missing:
        cases = [c for c in cases if not c.path.exists()]
    exist = [c for c in cases if c.path.exists()]
    if exist and not args.overwrite:
        print("refusing to overwrite frozen files (regenerating them defeats their purpose); pass "
              "--overwrite to replace them deliberately, or --missing to freeze only new cases:\n  "
              + "\n  ".join(str(c.path) for c in exist), file=sys.stderr)
        return 2
    manifest = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {"cases": {}}
    head, env, today = _git_head(), environment(), time.strftime("%Y-%m-%d")
    for c in cases:
        t0 = time.perf_counter()
        df = c.run()
        digest = write_frozen(c.path, df)
        manifest["cases"][c.id] = {"file": c.path.name, "rows": len(df), "columns": len(df.columns),
                                   "csv_sha256": digest, "setup": c.setup, "frozen_at_commit": head,
                                   "frozen_on": today, "environment": env}
        print(f"froze {c.id}: {len(df)} rows x {len(df.columns)} columns, "
              f"{c.path.stat().st_size} bytes, {time.perf_counter() - t0:.2f} s", flush=True)
    if cases:
        manifest["cases"] = {k: manifest["cases"][k] for k in [c.id for c in CASES]
                             if k in manifest["cases"]}
        MANIFEST.write_text(json.dumps(manifest, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
