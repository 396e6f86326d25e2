"""Minimum stable slenderness by bisection (a refinement of the grid answer).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from fastrock import _validate as V
from fastrock.model.bodies import RigidBlock
from fastrock.analyses.rocking_spectrum.definitions import minimum_stable_on_grid
from fastrock.analyses.rocking_spectrum.engine import STABLE_OUTCOMES, T_AFTER, rows_sweep, spectrum_solver
from fastrock.analyses.rocking_spectrum.inputs import (check_record_options, check_run_length,
    check_stable_outcomes, load_records)


# ------------------------------------------------------------- bisection
@dataclass
class MinimumStableSlenderness:
    """Result of :func:`minimum_stable_slenderness`.

    Attributes
    ----------
    value : float
        (b/h)_min [-]: the upper (stable) end of the final bracket
        ("exact"), ``lo`` ("upper": every scanned block is stable) or ``hi``
        ("lower": the stoutest block is not stable).
    bracket : (float, float)
        Unstable and stable slenderness enclosing the threshold, width <=
        ``tol`` for "exact"; (0, lo) for "upper", (hi, inf) for "lower".
    bound : str
        "exact" (to ``tol``), "upper" or "lower".
    non_monotone : bool
        Among all evaluated blocks, a stable one lies below an unstable one.
    beta : float
        value * g / PGA [-].
    Tp : float
        2 pi / p of the block (b, value) [s].
    runs : DataFrame
        Every evaluated block: ``round`` (0 = coarse scan), slenderness,
        outcome, status, stable, max_rotation_ratio.
    """

    value: float
    bracket: tuple
    bound: str
    non_monotone: bool
    beta: float
    Tp: float
    tol: float
    runs: pd.DataFrame = field(repr=False)

    @property
    def n_runs(self):
        return len(self.runs)

    @property
    def scan(self):
        """The coarse scan (round 0)."""
        return self.runs[self.runs["round"] == 0].reset_index(drop=True)


#: minimum_stable_slenderness: smallest tol relative to hi, most points of a scan or round, and
#: most refinement rounds (bisection from a bracket of width hi down to MIN_TOL hi takes 40).
MIN_TOL = 1e-12
MAX_SCAN = 100_000
MAX_ROUNDS = 200


def minimum_stable_slenderness(record, b, lo=0.05, hi=0.6, tol=1e-3, *, wall=None, scan=20,
                               sections=2, e=None, unit=None, solver=None, rtol=None, atol=None,
                               dt=None, t_after=T_AFTER, stable_outcomes=STABLE_OUTCOMES):
    """Minimum stable slenderness of blocks of half-width ``b`` by bisection.

    1. A coarse scan of ``scan`` slenderness values in [lo, hi] (one
       parallel sweep) applies the grid definition of the module docstring
       ("stable from there up") and gives a bracket (last unstable, next
       stable) -- or a bound if every / no scanned block is stable.
    2. The bracket is cut in ``sections`` parts per round (2: bisection;
       more: k-section, the ``sections - 1`` interior blocks run in one
       parallel sweep) until it is narrower than ``tol``.  Each round applies
       the same "stable from there up" rule to its points, so with
       ``sections > 2`` non-monotone stability inside the bracket is seen
       and followed upwards.

    ``non_monotone`` reports a stable block below an unstable one among all
    evaluated blocks.  On recorded motions stability is often non-monotone on
    fine scales: bisection then finds *a* threshold of the bracket that the
    coarse scan isolated, and an unstable slenderness may still hide between
    coarse points above it; a denser ``scan`` (and ``sections``) narrows
    that gap.  ``value`` is always the "stable from there up" threshold of
    all evaluated blocks.

    Parameters
    ----------
    record : GroundMotion or path
    b : float
        Half-width [m].
    lo, hi : float
        Slenderness range b/h [-], 0 < lo < hi.
    tol : float
        Width of the final bracket in b/h [-].
    wall : Wall, optional
    scan : int
        Points of the coarse scan (>= 2).
    sections : int
        Parts per refinement round (>= 2; 2 is bisection).

    Returns
    -------
    MinimumStableSlenderness
    """
    check_record_options(unit, None)
    (rec,) = load_records(record, unit)
    b = V.positive("b", b)
    lo = V.positive("lo", lo)
    hi = V.positive("hi", hi)
    if not lo < hi:
        raise ValueError(f"need lo < hi, got lo={lo}, hi={hi}")
    tol = V.positive("tol", tol)
    if tol < MIN_TOL * hi:
        raise ValueError(f"tol = {tol!r} is below {MIN_TOL:g} hi = {MIN_TOL * hi:.3g}: float64 slenderness "
                         f"values cannot be bisected that finely")
    scan = V.integer("scan", scan, 2, MAX_SCAN)
    sections = V.integer("sections", sections, 2, MAX_SCAN)
    solver = spectrum_solver(solver, rtol, atol, dt)
    t_after = V.run_time("t_after", V.non_negative("t_after", t_after))
    if e is not None:
        e = V.in_closed("e", e, 0.0, 1.0)
    stable_outcomes = check_stable_outcomes(stable_outcomes)
    check_run_length([rec], solver, t_after)
    walls = (wall,)
    cols = ["round", "slenderness", "outcome", "status", "stable", "max_rotation_ratio"]
    done = []

    def run(svals, rnd):
        svals = np.asarray(svals, float)
        k = svals.size
        df = rows_sweep([rec], np.zeros(k, int), np.full(k, b), svals, np.zeros(k, int), walls,
                         e=e, solver=solver, t_after=t_after, early_exit=True, progress=False,
                         chunk_size=None)
        df["stable"] = df["outcome"].isin(stable_outcomes)
        df["round"] = rnd
        done.append(df[cols])
        return df["stable"].to_numpy()

    grid = np.linspace(lo, hi, int(scan))
    thr = minimum_stable_on_grid(run(grid, 0))
    if thr.bound == "upper":
        value, bracket = lo, (0.0, lo)
    elif thr.bound == "lower":
        value, bracket = hi, (hi, math.inf)
    else:
        a, c = float(grid[thr.index - 1]), float(grid[thr.index])
        rnd = 0
        while c - a > tol and rnd < MAX_ROUNDS:     # each round narrows the bracket by `sections`
            rnd += 1
            pts = np.linspace(a, c, int(sections) + 1)
            st = np.concatenate([[False], run(pts[1:-1], rnd), [True]])
            k = minimum_stable_on_grid(st).index
            a, c = float(pts[k - 1]), float(pts[k])
        value, bracket = c, (a, c)
    runs = pd.concat(done, ignore_index=True)
    allpts = runs.sort_values("slenderness", kind="stable")
    non_monotone = minimum_stable_on_grid(allpts["stable"].to_numpy()).non_monotone
    body = RigidBlock.rectangle(b, b / value, e=e)
    return MinimumStableSlenderness(
        value=value, bracket=bracket, bound=thr.bound, non_monotone=bool(non_monotone),
        beta=value / rec.pga_g, Tp=2 * math.pi / body.p, tol=tol, runs=runs)


