"""A study's plan: its rows, cut into chunks.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastrock.running.outcomes import outcome_of, status_of
from fastrock.constants import G_STANDARD
from fastrock.analyses.rocking_spectrum.inputs import gap_of_wall
from fastrock.kernels import layout as L
from fastrock.analyses.fragility import COLLAPSE_OUTCOMES
from fastrock.studies.definition import StudyError
from fastrock.studies.output import arrow_table


RESULT_COLUMNS = """\
row                   global row id (record-major order: record, body, variant, level)
chunk                 chunk id (file results/chunk-<id>.parquet)
record_index, record  record position in the study and its (unique) name
polarity              sign the record ran with, +1 or -1 (Study.polarities)
body_index, body      body position and label
variant_index, variant  scene variant position and label ("two-sided", "wall d=0.01 m", ...)
wall_gap              clear gap to the rear wall [m] (NaN: no wall)
level_index, level    intensity level and its measure (column "measure")
kernel                compiled kernel that ran the row
alpha [rad], p [rad/s], e [-], b [m], h [m]   body (b, h NaN if unknown)
record_pga_g [g], record_pgv [m/s], mean_period Tm [s], duration [s]   unscaled record
scale                 factor applied to the record [-]
pga_g                 PGA of the scaled record / g [-]  (the study's own measure equals
                      the level exactly; the samples' max differs by an ulp or two)
pgv                   PGV of the scaled record [m/s]
pga_over_g_tan_alpha  PGA / (g tan alpha), g of the body [-]
omega_p_over_p        (2 pi / Tm) / p, Tm as pulse-period proxy [-]
outcome, status, status_code   coarse class, refined status and kernel code
overturned            outcome in (mode1, mode2)
side                  +1 / -1: the side it overturned to (theta > 0 / < 0), 0 if it did not
max_rotation_ratio    max |theta| / alpha [-]
impacts, wall_impacts, time_uplift [s], time_overturn [s], time_end [s],
nfev, steps, rejected_steps
"""


# ==================================================================== plan
@dataclass
class _Chunk:
    id: str
    kernel: str
    rows: np.ndarray


class Plan:
    """Every row of a prepared study, its scale and its chunk."""

    def __init__(self, prep, chunk_size):
        self.prep = prep
        self.chunk_size = int(chunk_size)
        # a record slot is one record with one polarity (record-major: record, then sign)
        npol = len(prep.polarities)
        self.slot_record = np.repeat(np.arange(len(prep.records)), npol)
        self.slot_sign = np.tile(np.array(prep.polarities, float), len(prep.records))
        nr, nb, nv, nl = self.slot_record.size, len(prep.bodies), len(prep.walls), prep.levels.size
        R, B, W, Lv = (a.ravel() for a in np.meshgrid(np.arange(nr), np.arange(nb), np.arange(nv),
                                                      np.arange(nl), indexing="ij"))
        self.rec, self.body, self.var, self.lvl = R, B, W, Lv
        self.n = R.size
        # per-slot record measures, computed once per record (mean_period is an FFT per call)
        sr = self.slot_record
        pga = np.array([r.pga for r in prep.records])[sr]
        pgv = np.array([r.pgv for r in prep.records])[sr]
        tm = np.array([r.mean_period for r in prep.records])[sr]
        self.rec_cols = {"record_pga_g": pga / G_STANDARD, "record_pgv": pgv, "mean_period": tm,
                         "duration": np.array([r.duration for r in prep.records])[sr]}
        self.rec_names = np.array([r.name for r in prep.records], dtype=object)[sr]
        self.body_labels = np.array(prep.body_labels, dtype=object)
        self.variant_names = np.array(prep.variant_names, dtype=object)
        alpha = np.array([b.alpha for b in prep.bodies])
        p = np.array([b.p for b in prep.bodies])
        g_body = np.array([b.g for b in prep.bodies])
        uplift = g_body * np.tan(alpha)
        self.body_cols = {"alpha": alpha, "p": p,
                          "e": np.array([b.e for b in prep.bodies], float),
                          "b": np.array([_nan(getattr(b, "b", None)) for b in prep.bodies]),
                          "h": np.array([_nan(getattr(b, "h", None)) for b in prep.bodies])}
        self.wall_gaps = np.array([gap_of_wall(w) for w in prep.walls], float)
        level = prep.levels[Lv]
        if prep.measure == "pga":
            scale = level * G_STANDARD / pga[R]
        elif prep.measure == "pgv":
            if (pgv == 0).any():
                bad = sorted({n for n, v in zip(self.rec_names, pgv) if v == 0})
                raise StudyError(f"record(s) {bad} have PGV = 0: cannot scale to a PGV level")
            scale = level / pgv[R]
        elif prep.measure == "pga_over_g_tan_alpha":
            scale = level * uplift[B] / pga[R]
        else:
            scale = level.copy()
        self.scale = scale
        self.level = level
        for (b, v), spec in prep.specs.items():       # the rocking model on a slope stays on the ground
            gnd = prep.effects[v].get("ground")
            rows = (B == b) & (W == v)
            if gnd is not None and rows.any():
                try:
                    gnd.check_lift_off(prep.bodies[b], float(np.max(np.abs(scale[rows]) * pga[R[rows]])), spec.name)
                except ValueError as exc:
                    raise StudyError(f"body {b} with variant {prep.variant_names[v]!r}: {exc}") from None
        self.im = {"pga_g": scale * pga[R] / G_STANDARD, "pgv": scale * pgv[R],
                   "pga_over_g_tan_alpha": scale * pga[R] / uplift[B],
                   "omega_p_over_p": (2.0 * math.pi / tm[R]) / p[B]}
        # the study's own measure is the level itself (the scaled samples'
        # value differs by an ulp or two), so that rows of one level share
        # one IM value: df[df.pga_g == 0.3] selects the level
        own = {"pga": "pga_g", "pgv": "pgv", "pga_over_g_tan_alpha": "pga_over_g_tan_alpha"}
        if prep.measure in own:
            self.im[own[prep.measure]] = level.copy()
        kname = np.array([prep.specs[b, v].name for b, v in zip(B, W)], dtype=object)
        self.kernel = kname
        self.chunks = []
        for k in dict.fromkeys(kname.tolist()):
            rows = np.flatnonzero(kname == k)
            for s in range(0, rows.size, self.chunk_size):
                cid = f"{len(self.chunks):05d}"
                self.chunks.append(_Chunk(cid, k, rows[s:s + self.chunk_size]))

    def payload(self, chunk):
        """Plain data for :func:`run_chunk` (arrays, strings, ints)."""
        prep = self.prep
        rows = chunk.rows
        # shuffle the rows inside the chunk (fixed seed) so that the static
        # prange schedule gives every thread a mix of low and high levels;
        # rows are independent, so the numbers do not depend on the order
        order = np.random.default_rng(int(chunk.id)).permutation(rows.size)
        rows = rows[order]
        recs = list(dict.fromkeys(self.slot_record[self.rec[rows]].tolist()))
        local = {k: i for i, k in enumerate(recs)}
        lens = [prep.records[k].npts for k in recs]
        offsets = np.concatenate([[0], np.cumsum(lens)[:-1]]).astype(float)
        smp = np.concatenate([np.asarray(prep.records[k].acc, float) for k in recs])
        m = rows.size
        spec0 = prep.specs[self.body[rows[0]], self.var[rows[0]]]
        PAR = np.array([prep.specs[self.body[i], self.var[i]].par for i in rows])
        HDR = np.zeros((m, L.N_EXC))
        HDR[:, L.X_KIND] = L.EXC_SAMPLED
        HDR[:, L.X_AMP] = self.scale[rows]           # SAMPLED: X_AMP is the scale factor
        HDR[:, L.X_SIGN] = self.slot_sign[self.rec[rows]]
        ri = self.slot_record[self.rec[rows]]
        HDR[:, L.X_DT] = [prep.records[k].dt for k in ri]
        HDR[:, L.X_N] = [prep.records[k].npts for k in ri]
        HDR[:, L.X_DUR] = [prep.records[k].duration for k in ri]
        HDR[:, L.X_OFFSET] = offsets[[local[k] for k in ri]]
        OPT = np.tile(prep.solver.options(0.0, prep.early_exit), (m, 1))
        OPT[:, L.O_T_END] = HDR[:, L.X_DUR] + prep.t_after
        for j, i in enumerate(rows):
            gnd = prep.effects[self.var[i]].get("ground")
            if gnd is not None:
                gnd.fill_header(HDR[j], prep.bodies[self.body[i]].g)
                OPT[j, L.O_EARLY_EXIT] = 0.0     # the early decisions assume level ground
        return {"chunk": chunk.id, "module": spec0.module, "kernel": spec0.name,
                "rows": rows.astype(np.int64), "theta_index": int(spec0.theta_index),
                "Y0": np.array([prep.y0s[self.body[i], self.var[i]] for i in rows], float).reshape(m, -1),
                "PAR": PAR, "HDR": HDR, "smp": smp, "OPT": OPT, "numba_threads": 0}

    def columns(self, chunk, result):
        """The chunk's table (column name -> array, in :data:`RESULT_COLUMNS`
        order) from the kernel output of :func:`run_chunk`."""
        prep = self.prep
        order = np.argsort(result["rows"], kind="stable")
        rows = result["rows"][order]
        if not np.array_equal(rows, chunk.rows):
            raise StudyError(f"chunk {chunk.id}: the worker returned other rows than asked")
        status = result["status"][order]
        MET = result["met"][order]
        theta_end = result["theta_end"][order] if "theta_end" in result else np.full(order.size, np.nan)
        m = rows.size
        R, B, W = self.rec[rows], self.body[rows], self.var[rows]
        alpha = self.body_cols["alpha"][B]
        outcome = np.array([outcome_of(c) for c in status], dtype=object)
        return {
            "row": rows.astype(np.int64),
            "chunk": np.full(m, chunk.id, dtype=object),
            "record_index": self.slot_record[R].astype(np.int64),
            "record": self.rec_names[R],
            "polarity": self.slot_sign[R].astype(np.int64),
            "body_index": B.astype(np.int64),
            "body": self.body_labels[B],
            "variant_index": W.astype(np.int64),
            "variant": self.variant_names[W],
            "wall_gap": self.wall_gaps[W],
            "level_index": self.lvl[rows].astype(np.int64),
            "measure": np.full(m, prep.measure, dtype=object),
            "level": self.level[rows],
            "kernel": np.full(m, chunk.kernel, dtype=object),
            **{k: v[B] for k, v in self.body_cols.items()},
            **{k: v[R] for k, v in self.rec_cols.items()},
            "scale": self.scale[rows],
            **{k: v[rows] for k, v in self.im.items()},
            "outcome": outcome,
            "status": np.array([status_of(c) for c in status], dtype=object),
            "status_code": status.astype(np.int64),
            "overturned": np.isin(outcome, COLLAPSE_OUTCOMES),
            "side": np.where((status == L.OVERTURN_MODE1) | (status == L.OVERTURN_MODE2),
                             np.sign(np.nan_to_num(theta_end)), 0).astype(np.int64),
            "max_rotation_ratio": MET[:, L.M_MAX_ABS_THETA] / alpha,
            "impacts": MET[:, L.M_IMPACTS], "wall_impacts": MET[:, L.M_WALL_IMPACTS],
            "time_uplift": MET[:, L.M_T_UPLIFT], "time_overturn": MET[:, L.M_T_OVER],
            "time_end": MET[:, L.M_T_FINAL], "nfev": MET[:, L.M_NFEV],
            "steps": MET[:, L.M_NSTEPS], "rejected_steps": MET[:, L.M_NREJECT],
        }

    def frame(self, chunk, result):
        """:meth:`columns` as a DataFrame (as :func:`load_results` reads it)."""
        return arrow_table(self.columns(chunk, result), "").to_pandas()


def _nan(x):
    return math.nan if x is None else float(x)


