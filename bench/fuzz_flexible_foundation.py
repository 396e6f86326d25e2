"""Random pulses on a FlexibleBody on TwoSpringFoundation (model flexible_two_spring), run with
``run_batch(early_exit=False)``: counts of outcomes and statuses, and every failed scene, which
``--replay`` reruns through ``simulate`` with its parameters and the base's own stiffness (the
upper frequency of ``flexible_frequencies`` and the dashpots' rate 2 c_v B^2 / J_b on the
base's rotation, docs: theory/foundation_flexible, "Stiff scenes").

    python bench/fuzz_flexible_foundation.py SEED N [--wide] [--replay]

bench/fuzz.py's family flexible_foundation draws this model too, with its status, mirror, scale,
early-exit and energy checks; this script keeps its own draw (lighter bases, ``--wide``) and no
checks beyond the status (the limits are tests/test_foundation_flexible.py's).  Measured (2 cores, load ~3): seed 7, 1500 scenes,
125-167 s, 11 failed:step-budget (base frequencies 6.0e3 ... 9.5e4 rad/s); seed 11 --wide, 600
scenes, 258 s, 30 failed:step-budget; none failed otherwise.
"""
import argparse
import time
import warnings

import numpy as np

import fastrock as fr
from fastrock import FlexibleBody, Pulse, TwoSpringFoundation
from fastrock.model.foundation import flexible_inertia


def draw(seed, n, wide):
    """(scenes, skipped): n random scenes, named by their index in the draw."""
    omax, wmin, wmax = (5000.0, 1.05, 300.0) if wide else (800.0, 1.5, 60.0)
    mbs = [0.005, 0.02, 0.1, 0.5, 3.0, 30.0] if wide else [0.02, 0.1, 0.5, 3.0]
    rng = np.random.default_rng(seed)
    scenes, skipped = [], 0
    for i in range(n):
        body = FlexibleBody(alpha=rng.uniform(0.08, 0.5), p=rng.uniform(0.8, 5.0),
                            omega_n_over_p=float(np.exp(rng.uniform(np.log(wmin), np.log(wmax)))),
                            zeta=float(rng.choice([0.0, 0.02, 0.1, 0.5])), base_mass_ratio=float(rng.choice(mbs)),
                            base_cm_height=float(rng.choice([0.0, 0.05])),
                            rotary_inertia_ratio=float(rng.choice([0.0, 0.1])), mass=float(np.exp(rng.uniform(0, 6))))
        om = float(np.exp(rng.uniform(np.log(8), np.log(omax))))
        try:
            fnd = TwoSpringFoundation.from_vibration(body, om, float(rng.choice([0.0, 0.02, 0.2, 1.0])))
        except ValueError:
            skipped += 1
            continue
        pulse = Pulse(float(rng.uniform(0.3, 8.0)), float(rng.uniform(0.5, 8.0)), sign=int(rng.choice([-1, 1])),
                      amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
        scenes.append(fr.Scene(body, pulse, foundation=fnd, name=str(i)))
    return scenes, skipped


def base_stiffness(scene):
    """(upper coupled frequency [rad/s], dashpot rate on the base's own rotation [1/s])."""
    blk = flexible_inertia(scene.body)
    J_b = blk.I_b + blk.m_b * blk.h_b ** 2 + blk.I_m
    return scene.foundation.flexible_frequencies(scene.body)[2], 2 * scene.foundation.c_v * blk.b ** 2 / J_b


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("seed", type=int)
    ap.add_argument("n", type=int)
    ap.add_argument("--wide", action="store_true", help="lighter bases, stiffer springs and columns")
    ap.add_argument("--replay", action="store_true", help="rerun each failed scene with simulate")
    args = ap.parse_args(argv)
    scenes, skipped = draw(args.seed, args.n, args.wide)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        df = fr.run_batch(scenes, early_exit=False, progress=False)
    print(f"{len(df)} scenes ({skipped} draws without a rest on the springs), {time.perf_counter() - t0:.0f} s")
    print(df["status"].value_counts().to_dict())
    failed = df[df["outcome"] == "failed"]
    by_name = {s.name: s for s in scenes}
    for _, row in failed.iterrows():
        sc = by_name[str(row["scene"])]
        w, rate = base_stiffness(sc)
        line = (f"{row['scene']}: {row['status']}; base_mass_ratio {sc.body.base_mass_ratio:g}, base frequency "
                f"{w:.3g} rad/s, dashpot rate {rate:.3g} 1/s")
        if args.replay:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = fr.simulate(sc.body, sc.excitation, foundation=sc.foundation)
            line += f"; simulate: {r.status} after {r.metrics['steps']} steps"
        print(line)
    return 1 if len(failed) else 0


if __name__ == "__main__":
    raise SystemExit(main())
