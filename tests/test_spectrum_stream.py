"""overturning_spectrum(out=...): the table streamed to Parquet chunk by chunk, and resumed
(issue #15, item 5)."""
import importlib

import numpy as np
import pandas as pd
import pytest

import fastrock as fr

pytest.importorskip("pyarrow")
SPECTRUM = importlib.import_module("fastrock.analyses.spectrum")
BLOCK = fr.RigidBlock(alpha=0.25, p=2.0)
GRID = dict(amplitude_ratios=np.linspace(0.8, 6.0, 9), frequency_ratios=np.linspace(0.5, 6.0, 7),
            sign=[1, -1], progress=False, chunk_size=20)


def test_streamed_table_equals_the_in_memory_one(tmp_path):
    mem = fr.overturning_spectrum(BLOCK, **GRID)
    folder = fr.overturning_spectrum(BLOCK, out=tmp_path / "s", **GRID)
    assert len(list(folder.glob("part-*.parquet"))) == -(-len(mem) // 20)
    back = SPECTRUM.load_spectrum(folder)
    assert not back.attrs["interrupted"] and back.attrs["kernel"] == "rigid"
    pd.testing.assert_frame_equal(back, mem, check_dtype=False)


def test_resume_runs_only_the_missing_rows(tmp_path, monkeypatch):
    folder = fr.overturning_spectrum(BLOCK, out=tmp_path / "s", **GRID)
    full = SPECTRUM.load_spectrum(folder)
    parts = sorted(folder.glob("part-*.parquet"))
    lost = pd.read_parquet(parts[2], columns=["row"])["row"].to_numpy()
    parts[2].unlink()
    partial = SPECTRUM.load_spectrum(folder)
    assert partial.attrs["interrupted"] and len(partial) == len(full) - lost.size
    calls = []
    real = SPECTRUM.run_chunks

    def counting(kernel, n, *args, **kw):
        calls.append(n)
        return real(kernel, n, *args, **kw)
    monkeypatch.setattr(SPECTRUM, "run_chunks", counting)
    fr.overturning_spectrum(BLOCK, out=folder, **GRID)
    assert calls == [lost.size]
    pd.testing.assert_frame_equal(SPECTRUM.load_spectrum(folder), full)
    fr.overturning_spectrum(BLOCK, out=folder, **GRID)       # nothing left to run
    assert calls == [lost.size]


def test_another_call_into_the_same_folder_is_refused(tmp_path):
    fr.overturning_spectrum(BLOCK, out=tmp_path / "s", **GRID)
    with pytest.raises(ValueError, match="out: .*another spectrum"):
        fr.overturning_spectrum(BLOCK, out=tmp_path / "s", **dict(GRID, sign=1))
    with pytest.raises(ValueError, match="out: boundary_check"):
        fr.overturning_spectrum(BLOCK, out=tmp_path / "t", boundary_check=True, **GRID)
    (tmp_path / "file").write_text("x")
    with pytest.raises(ValueError, match="out: .*not a folder"):
        fr.overturning_spectrum(BLOCK, out=tmp_path / "file", **GRID)
    with pytest.raises(ValueError, match="no streamed spectrum"):
        SPECTRUM.load_spectrum(tmp_path)
