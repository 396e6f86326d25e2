"""Ctrl-C ends every command the same way (issue #18, item 5): the finished
results are written (table and figure), one line names the count, and the
exit code is 130.

Each sweep command runs in a subprocess that gets SIGINT once its progress
output shows that runs are finishing."""
from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import threading
from importlib import resources

import pandas as pd
import pytest

from fastrock.cli import app as cli

pytestmark = pytest.mark.slow


#: A progress line (tqdm, written as lines to a pipe) with runs finished: "| 3600/720000 [".
RUNS_DONE = re.compile(rb"\|\s*[1-9]\d*/\d+ \[")


def _interrupt_when(cmd, cwd, marker, stream="stderr", timeout=240):
    """Run ``cmd``; send SIGINT when ``marker`` (bytes, or a compiled bytes regex) first shows
    on ``stream``.  Progress lines come every 0.2 s (FASTROCK_PROGRESS_INTERVAL).
    Returns (returncode, stdout, stderr)."""
    env = dict(os.environ, PYTHONUNBUFFERED="1", FASTROCK_PROGRESS_INTERVAL="0.2")
    found = marker.search if hasattr(marker, "search") else (lambda buf: marker in buf)
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    out = {"stdout": bytearray(), "stderr": bytearray()}
    seen = threading.Event()

    def pump(name, pipe):
        while True:
            b = pipe.read1(4096)
            if not b:
                break
            out[name] += b
            if name == stream and found(out[name]):
                seen.set()

    threads = [threading.Thread(target=pump, args=(k, getattr(p, k)), daemon=True) for k in out]
    for t in threads:
        t.start()
    assert seen.wait(timeout), f"{marker!r} never appeared: {bytes(out[stream])[-2000:]!r}"
    p.send_signal(signal.SIGINT)
    rc = p.wait(timeout=60)
    for t in threads:
        t.join(10)
    return rc, out["stdout"].decode(), out["stderr"].decode()


def _fastrock():
    return [sys.executable, "-m", "fastrock.cli"]


def test_spectrum_writes_the_finished_rows_and_figure(tmp_path):
    rc, out, err = _interrupt_when(
        _fastrock() + ["spectrum", "--n-amp", "600", "--n-freq", "600", "--sign", "both",
                       "--png", "s.png", "--csv", "s.csv"], tmp_path, RUNS_DONE)
    assert rc == 130, err[-2000:]
    df = pd.read_csv(tmp_path / "s.csv")
    assert 0 < len(df) < 720_000
    assert not (df["status"] == "failed:interrupted").any()
    assert (tmp_path / "s.png").stat().st_size > 0
    assert f"interrupted: {len(df)} of 720000 runs finished; wrote s.csv and s.png" in err


def test_rocking_spectrum_writes_the_finished_rows_and_figure(tmp_path):
    rc, out, err = _interrupt_when(
        _fastrock() + ["rocking-spectrum", "--n-slenderness", "60", "--n-sizes", "60",
                       "--walls", "two-sided,0.01", "--t-after", "30",
                       "--png", "r.png", "--csv", "r.csv"], tmp_path, RUNS_DONE)
    assert rc == 130, err[-2000:]
    assert (tmp_path / "r.csv").stat().st_size > 0
    assert (tmp_path / "r.png").stat().st_size > 0
    assert "of 7200 runs finished; wrote r.csv and r.png" in err


def test_study_keeps_its_chunks_and_exits_130(tmp_path):
    with resources.as_file(resources.files("fastrock") / "data" / "elcentro_ns.at2") as src:
        shutil.copy(src, tmp_path / "elcentro.at2")
    (tmp_path / "s.toml").write_text(
        'name = "interrupt"\nmeasure = "pga"\nlevels = {start = 0.05, stop = 1.5, num = 400}\n'
        't_after = 10.0\nrecords = ["elcentro.at2"]\n'
        '[[bodies]]\ntype = "rigid"\nb = 0.25\nh = 1.25\n'
        '[[bodies]]\ntype = "rigid"\nb = 0.2\nh = 1.6\n'
        '[run]\nchunk_size = 8\n')
    rc, out, err = _interrupt_when(_fastrock() + ["study", "s.toml", "--output", "res"], tmp_path,
                                   RUNS_DONE)
    assert rc == 130, err[-2000:]
    assert "chunks finished; wrote res with them" in err
    from fastrock.studies.output import load_results
    df = load_results(tmp_path / "res")
    assert 0 < len(df) < 800


def test_accuracy_writes_the_finished_settings(tmp_path):
    rc, out, err = _interrupt_when(
        _fastrock() + ["accuracy", "--models", "rigid", "--excitations", "pulse", "--grid", "4",
                       "--rtols", "1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12",
                       "--dts", "1e-2,1e-3,1e-4,1e-5,5e-6", "--csv", "a.csv", "--png", "a.png"],
        tmp_path, b"rtol=0.001", stream="stdout")
    assert rc == 130, err[-2000:]
    df = pd.read_csv(tmp_path / "a.csv")
    assert 1 <= len(df) < 15
    assert (tmp_path / "a.png").stat().st_size > 0
    assert f"interrupted: {len(df)} of 15 settings finished; wrote a.csv and a.png" in err


def test_a_single_run_command_exits_130_with_one_line(monkeypatch, capsys, tmp_path):
    S = sys.modules["fastrock.running.simulate"]   # the package attribute of that name is the function

    def stopped(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(S, "simulate", stopped)
    rc = cli.main(["simulate", "--csv", str(tmp_path / "h.csv")])
    assert rc == cli.EXIT_INTERRUPTED == 130
    err = capsys.readouterr().err
    assert err.strip() == "fastrock: interrupted: 'simulate' stopped before it finished; nothing written"
    assert not (tmp_path / "h.csv").exists()
