#!/usr/bin/env python
"""C anchor (issue #15, item 1): fastrock's kernels against our own plain C solver.

Usage::

    python bench/c_anchor.py            # full grids, 7 interleaved repeats (about 1.5 min)
    python bench/c_anchor.py --quick    # smaller grids, 3 repeats (under a minute)
    python bench/c_anchor.py --fma      # let gcc fuse multiply-adds (default: off, as Numba)

``bench/c_anchor/rocking.c`` is an event-driven Dormand-Prince 5(4) solver written from scratch
in C for the rigid Housner block and for the block beside a rear wall, with the same tableau,
error control, initial step, dense output, event location, rules and early decisions as
fastrock's ``rigid`` and ``wall`` kernels (see its header).  This script compiles it with
``gcc -O3 -march=native -shared -fPIC`` into ``bench/c_anchor/build/`` (git ignores it; the
library is rebuilt when the source or the flags change), once as is and once with
``-DNO_PASS_ALPHA`` ("lean": without the pass-alpha observer, which no outcome needs), loads them
with ctypes and runs, on the same grids:

* rigid: RigidBlock(alpha=0.25, p=2), one-sine sign +1, a_p/(g tan alpha) in [0.5, 8] x
  omega_p/p in [0.25, 10] (``np.linspace``, 100 x 100; quick 30 x 30), as ``bench/ratios.py``;
* wall 1 cm and wall 10 cm: the Mennitti block RigidBlock.rectangle(b=0.5, h=2.5), Wall(gap=d)
  (side -1, e_w = 1), both signs, [1.3, 25] x [0.2, 9.2] (48 x 48 x 2; quick 16 x 16 x 2), as
  ``bench/bench_wall.py``;

rtol 1e-6, atol 1e-8 and t_after 10 s on both sides, with early decisions on and off.

For each grid it checks, then times:

1. fastrock's answer is ``fastrock.overturning_spectrum``; the timed fastrock work is one direct
   call of the model's compiled sweep kernel (``spec.sweep``) with ``numba.set_num_threads(1)``
   on the arrays ``overturning_spectrum`` builds (its statuses and nfev are checked equal to the
   spectrum's, so the timed run is the grid).
2. Outcomes (safe / mode1 / mode2 / leaning) must be equal on every cell, for C and for C lean.
   A differing cell is printed; it is tolerated only as a *boundary cell* (safe against
   overturned with the safe side's max |theta| within 1e-3 rad of theta_over, or mode 1 against
   mode 2 with max |theta| agreeing to 1e-3 rad) -- every one is listed, none is hidden.  The
   fractions of cells with equal refined status, nfev, max |theta| and time of the first passage
   of alpha are printed too (not asserted: they are 100 % when the arithmetic is the same).
3. Time: the minimum over interleaved repeats (C, C lean, fastrock, then the reverse order) of
   the CPU time of this process (``time.process_time``), one thread on both sides.  Printed per
   grid: time per run on each side and the ratio fastrock / C (and / C lean), mean nfev per run
   on each side and the per-evaluation ratio (time / nfev on each side), with the load average;
   at the end a markdown table (the one in bench/README.md).
"""
from __future__ import annotations

import argparse
import ctypes
import hashlib
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent / "c_anchor"
SRC = HERE / "rocking.c"
BUILD = HERE / "build"
BASE_FLAGS = ["-O3", "-march=native", "-shared", "-fPIC", "-std=c99"]
# Numba (fastmath off) never fuses a*b + c into an FMA; gcc does in GNU mode (ISO C mode,
# -std=c99, does not).  Off, the two sides do the same arithmetic (bit-identical trajectories);
# --fma lets gcc fuse.
NO_FMA = ["-ffp-contract=off"]
FMA = ["-ffp-contract=fast"]

RTOL = 1e-6
ATOL = 1e-8
T_AFTER = 10.0
BOUNDARY_RAD = 1e-3

OUTCOME = {1: "safe", 2: "safe", 3: "safe", 4: "safe", 5: "mode1", 6: "mode2", 7: "leaning", 8: "flight"}


def outcome_of(code):
    return OUTCOME.get(int(code), "failed")


# ---- compile and load -------------------------------------------------------------------
def c_flags(fma=False, lean=False):
    return BASE_FLAGS + (FMA if fma else NO_FMA) + (["-DNO_PASS_ALPHA"] if lean else [])


def compile_c(build_dir=BUILD, fma=False, lean=False, cc=None):
    """Compile rocking.c into a shared library in ``build_dir`` (reused while the source and
    the flags are unchanged).  ``lean``: without the pass-alpha observer.  Returns its path."""
    cc = cc or os.environ.get("CC", "gcc")
    flags = c_flags(fma, lean)
    src = SRC.read_bytes()
    tag = hashlib.sha1(src + " ".join([cc] + flags).encode()).hexdigest()[:12]
    build_dir = Path(build_dir)
    build_dir.mkdir(parents=True, exist_ok=True)
    lib = build_dir / f"librocking-{tag}.so"
    if not lib.exists():
        tmp = lib.with_suffix(f".{os.getpid()}.tmp")
        subprocess.run([cc, *flags, "-o", str(tmp), str(SRC), "-lm"], check=True)
        os.replace(tmp, lib)
    return lib


class CAnchor:
    """ctypes wrapper of ``rock_grid``."""

    def __init__(self, lib_path):
        self.lib = ctypes.CDLL(str(lib_path))
        f = self.lib.rock_grid
        d = np.ctypeslib.ndpointer(np.float64, flags="C_CONTIGUOUS")
        i32 = np.ctypeslib.ndpointer(np.int32, flags="C_CONTIGUOUS")
        i64 = np.ctypeslib.ndpointer(np.int64, flags="C_CONTIGUOUS")
        f.argtypes = [ctypes.c_long, d, ctypes.c_int, d, d, d, d, d, i32, d, i64, i64, d, d, d]
        f.restype = ctypes.c_int
        self.fn = f

    def prepare(self, grid, early):
        """Arguments of one grid call, from the kernel inputs fastrock builds (same doubles)."""
        from fastrock.kernels import layout as L
        Y0, PAR, HDR, smp, OPT = grid.inputs
        n = Y0.shape[0]
        par = np.ascontiguousarray(PAR[0, :9], dtype=np.float64)
        amp = np.ascontiguousarray(HDR[:, L.X_AMP])
        omega = np.ascontiguousarray(HDR[:, L.X_OMEGA])
        sign = np.ascontiguousarray(HDR[:, L.X_SIGN])
        t_end = np.ascontiguousarray(OPT[:, L.O_T_END])
        o = OPT[0]
        opt = np.array([o[L.O_RTOL], o[L.O_ATOL], o[L.O_EPS_OMEGA], o[L.O_EPS_T],
                        1.0 if early else 0.0, o[L.O_MAX_STEPS]])
        out = dict(status=np.empty(n, np.int32), max_theta=np.empty(n), nfev=np.empty(n, np.int64),
                   nsteps=np.empty(n, np.int64), impacts=np.empty(n), wall_impacts=np.empty(n),
                   t_pass_alpha=np.empty(n))
        args = (n, par, 1 if grid.wall is not None else 0, amp, omega, sign, t_end, opt,
                out["status"], out["max_theta"], out["nfev"], out["nsteps"], out["impacts"],
                out["wall_impacts"], out["t_pass_alpha"])
        return args, out

    def run(self, grid, early):
        args, out = self.prepare(grid, early)
        self.fn(*args)
        return out


# ---- grids ------------------------------------------------------------------------------
class Grid:
    """One spectrum grid: fastrock's answer (overturning_spectrum) and the kernel inputs it
    builds, early exit on or off."""

    def __init__(self, name, body, amps, freqs, signs, wall, early):
        self.name, self.body, self.amps, self.freqs, self.signs = name, body, amps, freqs, signs
        self.wall, self.early = wall, early
        self.spec, self.inputs = self._kernel_inputs()
        self.n = self.inputs[0].shape[0]

    def _kernel_inputs(self):
        """The arrays ``overturning_spectrum`` hands to the sweep kernel (same expressions,
        same order: sign slowest, amplitude fastest)."""
        from fastrock.running import registry
        from fastrock.kernels import layout as L
        from fastrock.running.solver import Solver
        b = self.body
        spec = registry.select(b, self.wall)
        S, F, A = np.meshgrid(np.array(self.signs, float), self.freqs, self.amps, indexing="ij")
        S, F, A = S.ravel(), F.ravel(), A.ravel()
        n = A.size
        omega = F * b.p
        amp = A * b.g * np.tan(b.alpha)
        dur = 2 * np.pi / omega
        HDR = np.zeros((n, L.N_EXC))
        HDR[:, L.X_KIND] = L.EXC_ONE_SINE
        HDR[:, L.X_AMP] = amp
        HDR[:, L.X_OMEGA] = omega
        HDR[:, L.X_SIGN] = S
        HDR[:, L.X_DUR] = dur
        OPT = np.tile(Solver(rtol=RTOL, atol=ATOL).options(0.0, self.early), (n, 1))
        OPT[:, L.O_T_END] = dur + T_AFTER
        PAR = np.tile(spec.par, (n, 1))
        return spec, (np.zeros((n, spec.n_state)), PAR, HDR, np.zeros(1), OPT)

    def spectrum(self):
        import fastrock as fr
        return fr.overturning_spectrum(self.body, self.amps, self.freqs, sign=list(self.signs),
                                       wall=self.wall, rtol=RTOL, atol=ATOL, t_after=T_AFTER,
                                       early_exit=self.early, progress=False)

    def kernel_args(self):
        from fastrock.kernels import layout as L
        Y0, PAR, HDR, smp, OPT = self.inputs
        n = self.n
        return (Y0, PAR, HDR, smp, OPT, np.empty(n, np.int64), np.empty((n, L.N_MET)),
                np.empty_like(Y0))

    def run_kernel(self):
        """One direct sweep-kernel call; returns (status, MET)."""
        args = self.kernel_args()
        self.spec.sweep(*args)
        return args[5], args[6]


def grids(quick=False, early=True, which=("rigid", "wall 1 cm", "wall 10 cm")):
    import fastrock as fr
    n_r = 30 if quick else 100
    n_w = 16 if quick else 48
    out = []
    for name in which:
        if name == "rigid":
            out.append(Grid(name, fr.RigidBlock(alpha=0.25, p=2.0), np.linspace(0.5, 8.0, n_r),
                            np.linspace(0.25, 10.0, n_r), (1,), None, early))
        else:
            gap = {"wall 1 cm": 0.01, "wall 10 cm": 0.10}[name]
            out.append(Grid(name, fr.RigidBlock.rectangle(b=0.5, h=2.5), np.linspace(1.3, 25.0, n_w),
                            np.linspace(0.2, 9.2, n_w), (1, -1), fr.Wall(gap=gap), early))
    return out


# ---- comparison -------------------------------------------------------------------------
def _codes(df):
    from fastrock.running.outcomes import STATUS
    inv = {v: k for k, v in STATUS.items()}
    return np.array([inv.get(x, -99) for x in df["status"]])


def compare(grid, df, c, met=None):
    """Cells where C (``c``, from ``CAnchor.run``) and fastrock (``df``, from
    ``overturning_spectrum``; ``met``: the sweep kernel's metrics, for t_pass_alpha) differ.

    Returns (diffs, agree): ``diffs`` lists every cell whose outcome differs (a dict each, with
    ``boundary`` True for a cell on the overturning boundary: the safe side's max |theta| within
    BOUNDARY_RAD of theta_over, or two overturning modes whose max |theta| agree to BOUNDARY_RAD);
    ``agree`` gives the fraction of cells on which the refined status, nfev, max |theta| and
    t_pass_alpha are equal (bit for bit)."""
    from fastrock.kernels import layout as L
    fo = df["outcome"].to_numpy()
    co = np.array([outcome_of(x) for x in c["status"]])
    th_over = grid.body.theta_over
    diffs = []
    for i in np.flatnonzero(fo != co):
        mf = float(df["max_rotation"].iat[i])
        mc = float(c["max_theta"][i])
        if fo[i] == "safe" or co[i] == "safe":
            safe_side = mf if fo[i] == "safe" else mc
            boundary = abs(safe_side - th_over) < BOUNDARY_RAD
        else:
            boundary = {fo[i], co[i]} <= {"mode1", "mode2"} and abs(mf - mc) < BOUNDARY_RAD
        diffs.append(dict(i=int(i), amplitude_ratio=float(df["amplitude_ratio"].iat[i]),
                          frequency_ratio=float(df["frequency_ratio"].iat[i]), sign=int(df["sign"].iat[i]),
                          fastrock=str(df["status"].iat[i]), c=int(c["status"][i]), c_outcome=str(co[i]),
                          max_theta_fastrock=mf, max_theta_c=mc, nfev_fastrock=int(df["nfev"].iat[i]),
                          nfev_c=int(c["nfev"][i]), boundary=bool(boundary)))
    agree = dict(status=float(np.mean(_codes(df) == c["status"])),
                 nfev=float(np.mean(df["nfev"].to_numpy() == c["nfev"])),
                 max_theta=float(np.mean(df["max_rotation"].to_numpy() == c["max_theta"])))
    if met is not None:
        tf = met[:, L.M_T_PASS_ALPHA]
        tc = c["t_pass_alpha"]
        agree["t_pass_alpha"] = float(np.mean((tf == tc) | (np.isnan(tf) & np.isnan(tc))))
    return diffs, agree


# ---- timing -----------------------------------------------------------------------------
def interleaved(fns, repeats, clock=time.process_time):
    """Minimum and median over interleaved repeats of each callable (one warm-up call each);
    the order is reversed every other repeat, so no side always runs first."""
    for f in fns:
        f()
    samples = [[] for _ in fns]
    for r in range(repeats):
        order = range(len(fns)) if r % 2 == 0 else reversed(range(len(fns)))
        for i in order:
            t0 = clock()
            fns[i]()
            samples[i].append(clock() - t0)
    return [min(x) for x in samples], [float(np.median(x)) for x in samples]


def load_avg():
    try:
        return "%.2f %.2f %.2f" % os.getloadavg()
    except OSError:
        return "n/a"


def measure(grid, anchor, lean, repeats):
    """Check, then time one grid (early exit as ``grid.early``): C with fastrock's events
    (``anchor``), C without the pass-alpha observer (``lean``) and fastrock's sweep kernel on
    one thread, interleaved.  Returns a result dict."""
    import numba
    from fastrock.kernels import layout as L
    df = grid.spectrum()
    st_k, met_k = grid.run_kernel()
    assert (st_k == _codes(df)).all(), f"{grid.name}: sweep kernel != overturning_spectrum (status)"
    assert (met_k[:, L.M_NFEV].astype(np.int64) == df["nfev"].to_numpy()).all(), \
        f"{grid.name}: sweep kernel != overturning_spectrum (nfev)"
    c = anchor.run(grid, grid.early)
    diffs, agree = compare(grid, df, c, met_k)
    c_lean = lean.run(grid, grid.early)
    lean_diffs, _ = compare(grid, df, c_lean)
    assert (c_lean["nfev"] == c["nfev"]).all() and (c_lean["status"] == c["status"]).all()

    c_args, _ = anchor.prepare(grid, grid.early)
    l_args, _ = lean.prepare(grid, grid.early)
    k_args = grid.kernel_args()
    n_threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        (t_c, t_l, t_f), (m_c, m_l, m_f) = interleaved(
            [lambda: anchor.fn(*c_args), lambda: lean.fn(*l_args), lambda: grid.spec.sweep(*k_args)], repeats)
        load = load_avg()
    finally:
        numba.set_num_threads(n_threads)
    n = grid.n
    ev_c = float(c["nfev"].sum())
    ev_f = float(met_k[:, L.M_NFEV].sum())
    return dict(grid=grid.name, early=grid.early, n=n, t_c=t_c, t_l=t_l, t_f=t_f, med_c=m_c, med_l=m_l,
                med_f=m_f, ratio=t_f / t_c, ratio_lean=t_f / t_l, nfev_c=ev_c / n, nfev_f=ev_f / n,
                ns_c=1e9 * t_c / ev_c, ns_l=1e9 * t_l / ev_c, ns_f=1e9 * t_f / ev_f,
                per_eval=(t_f / ev_f) / (t_c / ev_c), per_eval_lean=(t_f / ev_f) / (t_l / ev_c),
                steps_c=float(c["nsteps"].mean()), steps_f=float(met_k[:, L.M_NSTEPS].mean()),
                diffs=diffs, lean_diffs=lean_diffs, agree=agree,
                counts=df["outcome"].value_counts().to_dict(), load=load)


def report(results, flags):
    import fastrock as fr
    import numba
    print()
    print(f"fastrock {fr.__version__}, numba {numba.__version__}, {os.cpu_count()} CPUs; C: gcc "
          f"{' '.join(flags)} (lean: -DNO_PASS_ALPHA); rtol {RTOL:g}, atol {ATOL:g}, t_after {T_AFTER:g} s")
    print("CPU time (time.process_time), one thread on both sides, minimum over interleaved repeats.")
    print("C = same events as fastrock; C lean = without the pass-alpha observer (no outcome needs it).")
    print()
    hdr = ("| grid | early exit | runs | nfev/run (C = fastrock) | C µs/run | C lean µs/run | fastrock µs/run "
           "| **fastrock/C per run** | fastrock/C lean | C ns/eval | fastrock ns/eval "
           "| **fastrock/C per eval** | outcome diffs | load avg |")
    print(hdr)
    print("|" + "---|" * (hdr.count("|") - 1))
    for r in results:
        nfev = (f"{r['nfev_c']:.1f}" if r["nfev_c"] == r["nfev_f"] else
                f"{r['nfev_c']:.1f} / {r['nfev_f']:.1f}")
        print(f"| {r['grid']} | {'on' if r['early'] else 'off'} | {r['n']} | {nfev} | "
              f"{1e6 * r['t_c'] / r['n']:.1f} | {1e6 * r['t_l'] / r['n']:.1f} | {1e6 * r['t_f'] / r['n']:.1f} | "
              f"**{r['ratio']:.2f}** | {r['ratio_lean']:.2f} | {r['ns_c']:.0f} | {r['ns_f']:.0f} | "
              f"**{r['per_eval']:.2f}** | {len(r['diffs'])} | {r['load']} |")
    print()
    for r in results:
        a = r["agree"]
        print(f"{r['grid']:<10} early {'on ' if r['early'] else 'off'}: {r['counts']}; equal per cell: status "
              f"{100 * a['status']:.2f}%, nfev {100 * a['nfev']:.2f}%, max|theta| {100 * a['max_theta']:.2f}%, "
              f"t_pass_alpha {100 * a['t_pass_alpha']:.2f}%; steps/run C {r['steps_c']:.1f} fastrock "
              f"{r['steps_f']:.1f}; medians C {1e3 * r['med_c']:.1f} ms, C lean {1e3 * r['med_l']:.1f} ms, "
              f"fastrock {1e3 * r['med_f']:.1f} ms")
        for tag, diffs in (("", r["diffs"]), (" (C lean)", r["lean_diffs"])):
            for d in diffs:
                kind = "BOUNDARY" if d["boundary"] else "DIFFERS"
                print(f"  {kind}{tag}: cell {d['i']} a_p/(g tan alpha)={d['amplitude_ratio']:.4f} "
                      f"w_p/p={d['frequency_ratio']:.4f} sign {d['sign']:+d}: fastrock {d['fastrock']} "
                      f"max|theta| {d['max_theta_fastrock']:.6f}, C {d['c_outcome']} (code {d['c']}) max|theta| "
                      f"{d['max_theta_c']:.6f}; nfev {d['nfev_fastrock']} / {d['nfev_c']}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="smaller grids and 3 repeats (under a minute)")
    ap.add_argument("--repeats", type=int, default=None, help="interleaved repeats (default 7, quick 3)")
    ap.add_argument("--fma", action="store_true", help="let gcc contract a*b+c into FMA (default off)")
    ap.add_argument("--grid", action="append", choices=["rigid", "wall 1 cm", "wall 10 cm"],
                    help="run only this grid (repeatable)")
    a = ap.parse_args(argv)
    if shutil.which(os.environ.get("CC", "gcc")) is None:
        sys.exit("gcc not found (set CC)")
    repeats = a.repeats or (3 if a.quick else 7)
    t0 = time.perf_counter()
    anchor = CAnchor(compile_c(fma=a.fma))
    lean = CAnchor(compile_c(fma=a.fma, lean=True))
    print(f"C libraries in {BUILD.relative_to(HERE.parent.parent)} ({time.perf_counter() - t0:.1f} s); "
          f"load average {load_avg()}")
    which = tuple(a.grid) if a.grid else ("rigid", "wall 1 cm", "wall 10 cm")
    results = []
    for early in (True, False):
        for g in grids(a.quick, early, which):
            r = measure(g, anchor, lean, repeats)
            results.append(r)
            print(f"  {r['grid']:<10} early {'on ' if early else 'off'}: {r['n']} runs, fastrock/C per run "
                  f"{r['ratio']:.2f}, per eval {r['per_eval']:.2f}, {len(r['diffs'])} outcome diffs "
                  f"({time.perf_counter() - t0:.0f} s)", flush=True)
    report(results, c_flags(a.fma))
    every = [(r["grid"], r["early"], d) for r in results for d in r["diffs"] + r["lean_diffs"]]
    bad = [x for x in every if not x[2]["boundary"]]
    print(f"\n{len(every)} outcome differences ({len(every) - len(bad)} boundary cells, {len(bad)} others); "
          f"total {time.perf_counter() - t0:.0f} s")
    assert not bad, f"C and fastrock outcomes differ on {len(bad)} non-boundary cells: {bad[:5]}"
    return results


if __name__ == "__main__":
    main()
