"""fastrock batch: scene files in one parallel call; every row equals the scene's own run."""
from pathlib import Path

import pandas as pd

from fastrock.cli.app import main
from fastrock.running.scene import Scene

SCENES = Path(__file__).resolve().parent.parent / "examples" / "scenes"


def test_batch_of_the_example_scenes(tmp_path, capsys):
    csv, png = tmp_path / "batch.csv", tmp_path / "batch.png"
    assert main(["batch", str(SCENES), "--csv", str(csv), "--png", str(png)]) == 0
    df = pd.read_csv(csv)
    files = sorted(SCENES.glob("*.toml"))
    assert len(df) == len(files) and png.stat().st_size > 1000
    for (_, row), f in zip(df.iterrows(), files):
        scene = Scene.from_toml(f)
        r = scene.run(early_exit=True)        # the batch decides early, foundations included
        assert (row["scene"], row["kernel"], row["status"]) == (scene.name, r.kernel, r.status)
        assert row["max_rotation"] == r.metrics["max_rotation"]
    assert "wrote" in capsys.readouterr().out


def test_batch_files_and_patterns(tmp_path, capsys):
    one = str(SCENES / "housner_pulse.toml")
    assert main(["batch", one, str(SCENES / "sliding*.toml"), "-q", "--csv", str(tmp_path / "b.csv")]) == 0
    assert len(pd.read_csv(tmp_path / "b.csv")) == 2
    assert main(["batch", str(tmp_path / "missing.toml"), "-q"]) == 2
    assert "scene file not found" in capsys.readouterr().err
    assert main(["batch", str(tmp_path), "-q"]) == 2
    assert "no scene files" in capsys.readouterr().err
