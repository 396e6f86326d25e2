"""Studies (fastrock.study): chunking and resume, Parquet, local vs Dask bit
for bit, a worker killed mid-study, bad input, IM columns, fragility MLE.

The Dask tests share one LocalCluster (2 worker processes, 1 thread each, on
127.0.0.1).  Records are the packaged El Centro record and two variants of it
(sign flipped, time reversed), so nothing here needs the shared data folder.
"""
from __future__ import annotations

import json
import math
import os
import signal
import time

import numpy as np
import pandas as pd
import pytest

from fastrock import RigidBlock, Solver
from fastrock.constants import G_STANDARD
from fastrock.io.ground_motion import GroundMotion
from fastrock.io.default_records import load_default_record
from fastrock.studies.output import DEFAULT_CHUNK_SIZE, write_chunk, load_results
from fastrock.studies.plan import RESULT_COLUMNS, Plan
from fastrock.analyses.fragility import FragilityFit, fit_fragility
from fastrock.studies.definition import Study, StudyError
from fastrock.plotting.fragility import plot_fragility
from fastrock.studies.run import run_study

try:
    from fastrock.model.wall import Wall
except ImportError:   # the wall model may not have landed
    Wall = None

pytest.importorskip("pyarrow")


# ----------------------------------------------------------------- helpers
@pytest.fixture(scope="module")
def records():
    rec = load_default_record()
    return [rec, GroundMotion(-rec.acc, rec.dt, name="El Centro flipped"),
            GroundMotion(rec.acc[::-1], rec.dt, name="El Centro reversed")]


BODIES = [RigidBlock.rectangle(0.2, 1.0), RigidBlock.rectangle(0.3, 1.5)]
LEVELS = [0.1, 0.25, 0.4, 0.6]


def _study(records, **kw):
    args = dict(records=records, bodies=BODIES, levels=LEVELS, t_after=5.0)
    args.update(kw)
    return Study(**args)


def _assert_identical(a, b):
    """Same columns, dtypes and values, bit for bit (NaN == NaN)."""
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    for c in a.columns:
        if a[c].dtype.kind == "f":
            np.testing.assert_array_equal(a[c].to_numpy().view(np.int64),
                                          b[c].to_numpy().view(np.int64), err_msg=c)


# ----------------------------------------------------- chunking and resume
def test_chunks_are_deterministic(records):
    p1 = _study(records).prepare()
    p2 = _study(list(records)).prepare()
    assert p1.hash == p2.hash
    a, b = Plan(p1, 5), Plan(p2, 5)
    assert [c.id for c in a.chunks] == [c.id for c in b.chunks]
    for c1, c2 in zip(a.chunks, b.chunks):
        np.testing.assert_array_equal(c1.rows, c2.rows)
    # every row exactly once, record-major order
    rows = np.concatenate([c.rows for c in a.chunks])
    np.testing.assert_array_equal(np.sort(rows), np.arange(3 * 2 * 4))
    assert a.n == 24 and len(a.chunks) == 5
    # anything that changes the runs changes the hash
    assert _study(records, levels=LEVELS[:3]).prepare().hash != p1.hash
    assert _study(records, t_after=4.0).prepare().hash != p1.hash
    assert _study(records, solver=Solver(rtol=1e-7)).prepare().hash != p1.hash
    assert _study(records, measure="scale").prepare().hash != p1.hash
    assert _study(records, name="other").prepare().hash == p1.hash   # a label only


def test_resume_reruns_only_missing_chunk(records, tmp_path):
    out = tmp_path / "study"
    df1 = run_study(_study(records), out, chunk_size=5, progress=False)
    assert len(df1) == 24 and df1.attrs["complete"] and df1.attrs["chunks_run"] == 5
    assert df1["row"].tolist() == list(range(24))
    (out / "results" / "chunk-00002.parquet").unlink()
    assert load_results(out).attrs["missing_chunks"] == ["00002"]
    ran = []
    df2 = run_study(_study(records), out, progress=False, callback=lambda cid, k, n: ran.append(cid))
    assert ran == ["00002"]
    assert df2.attrs["chunks_skipped"] == 4 and df2.attrs["chunk_size"] == 5
    _assert_identical(df1, df2)
    # a third run does nothing
    df3 = run_study(_study(records), out, progress=False)
    assert df3.attrs["chunks_run"] == 0
    _assert_identical(df1, df3)


def test_parquet_round_trip_and_manifest(records, tmp_path):
    out = tmp_path / "study"
    df = run_study(_study(records, levels=[0.3, 0.5]), out, chunk_size=4, progress=False)
    man = json.loads((out / "manifest.json").read_text())
    assert man["study_hash"] == df.attrs["study_hash"]
    assert [c["id"] for c in man["chunks"]] == ["00000", "00001", "00002"]
    assert sorted(p.name for p in (out / "results").iterdir()) == [
        f"chunk-{c['id']}.parquet" for c in man["chunks"]]
    documented = " ".join(RESULT_COLUMNS.split())
    for c in df.columns:
        assert c in documented, c
    assert df["row"].dtype == np.int64 and df["overturned"].dtype == bool
    assert df["status_code"].dtype == np.int64
    # write / read one frame: identical, dtypes included
    sub = df.iloc[:4].reset_index(drop=True)
    (tmp_path / "rt" / "results").mkdir(parents=True)
    write_chunk(tmp_path / "rt", "x", sub, "h")
    back = pd.read_parquet(tmp_path / "rt" / "results" / "chunk-x.parquet")
    _assert_identical(sub, back)
    assert not list((out / "results").glob(".*.tmp"))


# ------------------------------------------------------------- IM columns
def test_im_columns(records):
    rec = records[0]
    for measure, col in (("pga", "pga_g"), ("pgv", "pgv"),
                         ("pga_over_g_tan_alpha", "pga_over_g_tan_alpha"), ("scale", "scale")):
        plan = Plan(_study(records, measure=measure).prepare(), 8)
        np.testing.assert_array_equal(plan.im.get(col, plan.scale), plan.level)   # exactly
        for i in (0, 5, 23):
            r, b = records[plan.rec[i]], BODIES[plan.body[i]]
            acc = plan.scale[i] * r.acc                       # what the kernel sees
            assert np.max(np.abs(acc)) / G_STANDARD == pytest.approx(plan.im["pga_g"][i], rel=1e-15)
            v = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * r.dt)])
            assert plan.im["pgv"][i] == pytest.approx(np.max(np.abs(v)), rel=1e-12)
            assert plan.im["pga_over_g_tan_alpha"][i] == pytest.approx(
                np.max(np.abs(acc)) / (b.g * math.tan(b.alpha)), rel=1e-14)
            assert plan.im["omega_p_over_p"][i] == pytest.approx(2 * math.pi / r.mean_period / b.p)
    plan = Plan(_study(records, measure="pga").prepare(), 8)
    assert plan.scale[0] == pytest.approx(0.1 * G_STANDARD / rec.pga)


def test_scaled_rows_match_rocking_spectrum_runs(records, tmp_path):
    """The header's scale factor gives the run of the pre-scaled record."""
    from fastrock.analyses.rocking_spectrum.engine import rocking_spectrum_runs
    df = run_study(_study(records[:1], bodies=BODIES[:1]), tmp_path / "s", progress=False)
    for _, row in df.iterrows():
        ref = rocking_spectrum_runs([records[0].scaled(row["scale"])], slenderness=[0.2],
                                    half_widths=[0.2], walls=(None,), t_after=5.0, progress=False)
        assert ref["outcome"][0] == row["outcome"]
        assert ref["max_rotation_ratio"][0] == pytest.approx(row["max_rotation_ratio"], rel=1e-6)
    np.testing.assert_array_equal(df["pga_g"], LEVELS)
    assert df["outcome"].tolist()[0] == "safe" and df["overturned"].any()


# ------------------------------------------------------------- bad input
def test_missing_record_file(tmp_path):
    with pytest.raises(StudyError, match="record file not found: .*nope.AT2"):
        run_study(Study([tmp_path / "nope.AT2"], BODIES, LEVELS), tmp_path / "o", progress=False)
    assert not (tmp_path / "o").exists()


def test_zero_pga_record(records, tmp_path):
    zero = GroundMotion(np.zeros(100), 0.01, name="flat")
    with pytest.raises(StudyError, match="'flat'.*PGA = 0"):
        run_study(Study([records[0], zero], BODIES, LEVELS), tmp_path / "o", progress=False)
    assert not (tmp_path / "o").exists()


def test_other_study_in_folder(records, tmp_path):
    out = tmp_path / "o"
    run_study(_study(records[:1], levels=[0.2]), out, progress=False)
    with pytest.raises(StudyError, match="holds a different study"):
        run_study(_study(records[:1], levels=[0.3]), out, progress=False)
    with pytest.raises(StudyError, match="chunk_size=128"):
        run_study(_study(records[:1], levels=[0.2]), out, chunk_size=7, progress=False)
    assert DEFAULT_CHUNK_SIZE == 128


@pytest.mark.parametrize("kw, msg", [
    (dict(measure="pgd"), "measure must be one of"),
    (dict(levels=[0.1, -0.2]), "levels must be > 0"),
    (dict(levels=[]), "levels is empty"),
    (dict(variants=[{"gap": 0.1}]), "unknown key"),
    (dict(bodies=["block"]), "must be a RigidBlock"),
])
def test_bad_definitions(records, tmp_path, kw, msg):
    with pytest.raises(StudyError, match=msg):
        run_study(_study(records[:1], **kw), tmp_path / "o", progress=False)
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_unreachable_scheduler(records, tmp_path):
    pytest.importorskip("distributed")
    import socket
    with socket.socket() as s:             # a free loopback port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t0 = time.perf_counter()
    with pytest.raises(StudyError, match="cannot reach the Dask scheduler"):
        run_study(_study(records[:1]), tmp_path / "o", scheduler=f"tcp://127.0.0.1:{port}",
                  connect_timeout=1.0, progress=False)
    assert time.perf_counter() - t0 < 30
    assert not (tmp_path / "o").exists()


# ------------------------------------------------------------------ Dask
@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.mark.slow
def test_local_and_dask_bit_identical(records, client, tmp_path):
    variants = [{"wall": None}] + ([{"wall": Wall(0.01)}] if Wall is not None else [])
    st = _study(records, variants=variants)
    local = run_study(st, tmp_path / "local", chunk_size=6, progress=False)
    dask = run_study(st, tmp_path / "dask", client=client, chunk_size=6, progress=False)
    assert dask.attrs["backend"] == "dask" and dask.attrs["chunks_run"] == len(local) // 6
    _assert_identical(local, dask)
    assert local["outcome"].nunique() >= 2


@pytest.mark.slow
def test_scheduler_address(records, client, tmp_path):
    """A scheduler given by address: run_study opens (and closes) its own client."""
    st = _study(records[:2])
    local = run_study(st, tmp_path / "local", chunk_size=4, progress=False)
    dask = run_study(st, tmp_path / "dask", scheduler=client.scheduler.address, chunk_size=4,
                     progress=False)
    _assert_identical(local, dask)


@pytest.mark.slow
def test_worker_killed_mid_study(records, client, tmp_path):
    bodies = [RigidBlock.rectangle(b, 5 * b) for b in (0.15, 0.2, 0.3, 0.45)]
    st = _study(records, bodies=bodies, levels=np.linspace(0.1, 0.9, 8), t_after=10.0)
    ref = run_study(st, tmp_path / "local", chunk_size=4, progress=False)
    pids = client.run(os.getpid)
    killed = {}

    def kill_once(cid, k, n):
        if killed:
            return
        busy = {w: ts for w, ts in client.processing().items() if ts and w in pids}
        if not busy:
            return                             # try again after the next chunk
        victim = next(iter(busy))              # a worker holding a chunk
        killed.update(addr=victim, keys=list(busy[victim]), at=k)
        os.kill(pids[victim], signal.SIGKILL)

    df = run_study(st, tmp_path / "dask", client=client, chunk_size=4, progress=False,
                   callback=kill_once)
    assert killed and killed["keys"] and killed["at"] < df.attrs["n_chunks"]
    assert df.attrs["complete"] and df.attrs["chunks_run"] == df.attrs["n_chunks"] == 24
    _assert_identical(ref, df)
    # the chunks the dead worker held were sent to a worker again
    for key in killed["keys"]:
        story = client.story(key)
        starts = [s for s in story if len(s) > 3 and s[0] == "scheduler" and s[3] == "processing"]
        assert len(starts) >= 2, (key, story)


# -------------------------------------------------------------- fragility
def _synthetic(theta, beta, levels, n_records, seed):
    """IDA-like table: every record at every level, Bernoulli outcomes."""
    from math import erf
    rng = np.random.default_rng(seed)
    x = np.tile(levels, n_records)
    p = np.array([0.5 * (1 + erf(math.log(v / theta) / beta / math.sqrt(2))) for v in x])
    y = rng.random(x.size) < p
    return pd.DataFrame({"record": np.repeat([f"r{i}" for i in range(n_records)], len(levels)),
                         "pga_g": x, "outcome": np.where(y, "mode1", "safe"),
                         "max_rotation_ratio": np.where(y, 10.0, 0.5 * x / theta)})


def test_fragility_mle_recovers_known_parameters():
    theta, beta = 0.4, 0.35
    df = _synthetic(theta, beta, np.linspace(0.1, 1.0, 10), 300, seed=1)
    f = fit_fragility(df, n_boot=200, seed=3)
    assert isinstance(f, FragilityFit) and f.n_rows == 3000 and f.n_records == 300
    assert abs(math.log(f.theta / theta)) < 3 * f.se_ln_theta
    assert abs(f.beta - beta) < 3 * f.se_beta
    iv = f.interval(ci=0.99)
    assert iv["theta"][0] < theta < iv["theta"][1]
    assert iv["beta"][0] < beta < iv["beta"][1]
    lo, hi = f.band([theta], ci=0.99)
    assert lo[0] < 0.5 < hi[0]
    assert f.probability(f.theta) == pytest.approx(0.5)


def test_fragility_mle_agrees_with_scipy():
    scipy_opt = pytest.importorskip("scipy.optimize")
    from scipy.stats import norm
    df = _synthetic(0.5, 0.5, np.array([0.2, 0.3, 0.45, 0.6, 0.9, 1.3]), 25, seed=7)
    df.loc[df.index[::7], "outcome"] = "failed"          # left out
    f = fit_fragility(df, n_boot=0)
    d = df[df["outcome"] != "failed"]
    x, y = d["pga_g"].to_numpy(), (d["outcome"] == "mode1").to_numpy()

    def nll(q):
        z = (np.log(x) - q[0]) / q[1]
        return -np.sum(np.where(y, norm.logcdf(z), norm.logcdf(-z)))
    r = scipy_opt.minimize(nll, [0.0, 1.0], method="Nelder-Mead",
                           options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    assert f.n_excluded == (df["outcome"] == "failed").sum()
    assert math.log(f.theta) == pytest.approx(r.x[0], abs=1e-6)
    assert f.beta == pytest.approx(r.x[1], abs=1e-6)
    assert f.loglik == pytest.approx(-r.fun, abs=1e-8)


def test_fragility_threshold_and_errors(tmp_path):
    df = _synthetic(0.4, 0.3, np.linspace(0.1, 1.0, 10), 40, seed=2)
    over = fit_fragility(df, n_boot=20)
    exceed = fit_fragility(df, threshold=0.5, n_boot=20)   # exceeded earlier than overturning
    assert exceed.event == "max_rotation_ratio > 0.5"
    assert exceed.theta < over.theta
    sep = pd.DataFrame({"record": ["a", "a", "b", "b"], "pga_g": [0.1, 0.5, 0.1, 0.5],
                        "outcome": ["safe", "mode2", "safe", "mode1"]})
    with pytest.raises(ValueError, match="separated"):
        fit_fragility(sep)
    with pytest.raises(ValueError, match="no event"):
        fit_fragility(sep.assign(outcome="safe"))
    fig = plot_fragility([over, exceed])
    fig.savefig(tmp_path / "f.png")
    assert (tmp_path / "f.png").stat().st_size > 1000


# ------------------------------------------------------------- TOML / CLI
def test_toml_and_cli(tmp_path, capsys):
    from fastrock.cli.app import main
    (tmp_path / "s.toml").write_text(
        'name = "tiny"\nmeasure = "pga_over_g_tan_alpha"\nlevels = {start = 1.0, stop = 4.0, num = 4}\n'
        't_after = 2.0\nrecords = ["default"]\n'
        '[[bodies]]\ntype = "rigid"\nb = [0.2, 0.3]\nh = 1.0\n'
        '[[variants]]\nname = "free"\n'
        '[run]\noutput = "res"\nchunk_size = 3\n')
    st = Study.from_toml(tmp_path / "s.toml")
    assert st.n_runs == 8 and st.run["output"] == str(tmp_path / "res")
    assert main([ "study", str(tmp_path / "s.toml"), "--n-boot", "10"]) == 0
    out = capsys.readouterr().out
    assert "8 runs in 3 chunks of 3" in out
    df = load_results(tmp_path / "res")
    np.testing.assert_array_equal(df["pga_over_g_tan_alpha"], df["level"])
    assert set(df["variant"]) == {"free"}
    (tmp_path / "bad.toml").write_text('records = ["missing/*.AT2"]\nlevels = [0.1]\n'
                                       '[[bodies]]\nalpha = 0.2\np = 2.0\n')
    assert main(["study", str(tmp_path / "bad.toml")]) == 2
    assert "no record file matches" in capsys.readouterr().err
