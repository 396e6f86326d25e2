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


def add_batch_subcommand(sub):
    p = sub.add_parser("batch", help="run many scene files in one parallel call (one table)",
                       description="Run every scene file given (TOML files, folders of them or glob "
                                   "patterns) through fastrock.run_batch: one parallel sweep per model, "
                                   "one row per scene.")
    p.add_argument("scenes", nargs="+", help="scene files (TOML), folders (every *.toml in them) or "
                                             "glob patterns; see examples/scenes/")
    p.add_argument("--full-runs", action="store_true",
                   help="run every scene to its end time instead of stopping once its outcome is "
                        "decided (default: off, decided early)")
    from fastrock.cli.output import add_output_options
    add_output_options(p, png=None, csv="batch.csv", figure="a bar chart of max |theta|/alpha per scene",
                       table="the table of scenes")
    p.set_defaults(func=_cmd_batch)


def scene_files(items):
    """TOML files from paths, folders and glob patterns, in the order given (a folder's and a
    pattern's files sorted); a name that matches nothing is an error naming it."""
    import glob
    from pathlib import Path
    files = []
    for item in items:
        path = Path(item)
        if path.is_dir():
            found = sorted(str(f) for f in path.glob("*.toml"))
        elif any(c in item for c in "*?["):
            found = sorted(glob.glob(item))
        elif path.exists():
            found = [item]
        else:
            raise ValueError(f"scene file not found: {item}")
        if not found:
            raise ValueError(f"no scene files (*.toml) in {item}")
        files.extend(found)
    return files


def _cmd_batch(args):
    from fastrock.cli.output import write_table, wrote
    from fastrock.running.batch import run_batch
    files = scene_files(args.scenes)
    scenes = []
    for f in files:
        scene = Scene.from_toml(f)
        if not scene.name:
            scene.name = f
        scenes.append(scene)
    df = run_batch(scenes, early_exit=not args.full_runs, progress=not args.quiet)
    width = max(len(str(x)) for x in df["scene"]) if len(df) else 5
    for _, row in df.iterrows():
        print(f"{str(row['scene']):<{width}}  {row['kernel']:<17} {row['status']:<22} "
              f"max |theta|/alpha {row['max_rotation_ratio']:.4g}")
    written = write_table(df, args)
    if args.png and len(df):
        from fastrock.plotting.figures import OUTCOME_COLORS, get_pyplot
        plt = get_pyplot()
        fig, ax = plt.subplots(figsize=(max(4.0, 0.5 * len(df) + 2.0), 3.6), constrained_layout=True)
        colors = [OUTCOME_COLORS.get(o, "#888888") for o in df["outcome"]]
        ax.bar(range(len(df)), df["max_rotation_ratio"], color=colors, edgecolor="0.3")
        ax.set_xticks(range(len(df)), [str(x) for x in df["scene"]], rotation=60, ha="right", fontsize=7)
        ax.set_ylabel("max |theta| / alpha [-]")
        ax.set_title(f"{len(df)} scenes; bar colour: outcome")
        fig.savefig(args.png, dpi=130)
        written.append(args.png)
    wrote(written)
    if df.attrs.get("interrupted"):
        from fastrock.cli.output import interrupted_exit
        return interrupted_exit(len(df), len(scenes), "scenes", written)
    return 0


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
