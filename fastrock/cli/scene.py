"""``fastrock run SCENE.toml``: run a scene file.
"""
from __future__ import annotations
from fastrock.running.scene import Scene


def add_subcommand(sub):
    p = sub.add_parser("run", help="run a scene from a TOML file")
    p.add_argument("scene", help="scene file (TOML); see examples/scenes/")
    from fastrock.cli.output import add_output_options
    add_output_options(p, figure="the time-history figure (overrides [output] png)",
                       table="the time history (overrides [output] csv / parquet)")
    p.set_defaults(func=_cmd_run)


def _cmd_run(args):
    sc = Scene.from_toml(args.scene)
    r = sc.run()
    m = r.metrics
    print(f"scene {sc.name}: effects {list(sc.effects) or ['none']}; kernel {r.kernel}")
    print(f"outcome {r.outcome} ({r.status}); max |theta|/alpha = {m['max_rotation_ratio']:.6g}; "
          f"impacts {m['impacts']}; nfev {m['nfev']}")
    out = dict(sc.outputs)
    for k in ("csv", "png", "parquet"):
        if getattr(args, k, None):
            out[k] = getattr(args, k)
    from fastrock.cli.output import write_table, wrote
    wrote(write_table(r.history, args, csv=out.get("csv") or "", parquet=out.get("parquet") or ""))
    if out.get("events"):
        r.events.to_csv(out["events"], index=False)
        wrote([out["events"]])
    if out.get("png"):
        r.plot().savefig(out["png"], dpi=130)
        wrote([out["png"]])
    return 0
