"""Progress through tqdm (issue #16, item 4): a compile stage before the first chunk, and whole
lines, no carriage returns, when stderr is a log file."""
import numpy as np
import pytest

from fastrock.running import sweep
from fastrock.kernels import layout as L


def fake_sweep(Y0, PAR, HDR, smp, opt, st, met, yf):
    st[:] = L.SAFE_NO_UPLIFT
    met[:] = 0.0
    yf[:] = Y0


fake_sweep.signatures = ()          # as a Numba dispatcher that has not compiled yet


def test_a_sweep_shows_the_compile_stage_and_writes_lines_to_a_log(capsys):
    n = 2000
    Y0 = np.zeros((n, 2))
    PAR = np.zeros((n, 3))
    HDR = np.zeros((n, 4))
    OPT = np.zeros((n, L.N_OPT))
    status, MET, YF, done = sweep.run_sweep(fake_sweep, Y0, PAR, HDR, np.zeros(1), OPT, chunk_size=100,
                                            progress=True, model="rigid")
    err = capsys.readouterr().err
    assert done == n
    assert "\r" not in err
    lines = err.splitlines()
    assert lines[0].startswith("fastrock: first use of the rigid kernel")
    assert any(ln.startswith("compiling rigid (first use)") for ln in lines)
    assert lines[-1].startswith("100%") and f"{n}/{n}" in lines[-1]


def test_no_progress_writes_nothing(capsys):
    bar = sweep.Progress(100, enabled=False)
    bar.stage("compiling")
    bar.update(100)
    bar.close()
    assert capsys.readouterr().err == ""


def test_the_log_interval_is_set_by_the_environment(monkeypatch):
    monkeypatch.setenv("FASTROCK_PROGRESS_INTERVAL", "0.5")
    assert sweep.Progress.log_interval() == 0.5
    monkeypatch.delenv("FASTROCK_PROGRESS_INTERVAL")
    assert sweep.Progress.log_interval() == sweep.Progress.LOG_INTERVAL == 30.0
    for bad in ("soon", "-1", "nan"):
        monkeypatch.setenv("FASTROCK_PROGRESS_INTERVAL", bad)
        with pytest.raises(ValueError, match="FASTROCK_PROGRESS_INTERVAL"):
            sweep.Progress.log_interval()
