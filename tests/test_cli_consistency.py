"""One CLI (issue #16, item 6): the same options mean the same thing on every command, every
option says its default and unit, and a missing file or a bad value is one line, not a traceback."""
import argparse
import math
import re
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import fastrock
from fastrock.cli import app as cli
from fastrock.io.default_records import load_default_record

WRITERS = ["spectrum", "simulate", "record", "rocking-spectrum", "accuracy", "run", "study", "fit"]
ROOT = Path(__file__).resolve().parents[1]


def _subparsers():
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return parser, sub.choices


def _options(cmd):
    return [a for a in cmd._actions if a.option_strings and a.help != argparse.SUPPRESS
            and not isinstance(a, (argparse._HelpAction, argparse._VersionAction))]


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"fastrock {fastrock.__version__}"


def test_every_command_has_quiet_and_every_writer_the_same_output_options():
    _, cmds = _subparsers()
    for name, cmd in cmds.items():
        assert "--quiet" in cmd._option_string_actions, name
    for name in WRITERS:
        opts = cmds[name]._option_string_actions
        for o in ("--png", "--csv", "--parquet"):
            assert o in opts, (name, o)
            assert opts[o].metavar == "FILE", (name, o)


def test_every_option_states_its_default_and_every_number_its_unit():
    _, cmds = _subparsers()
    missing_default, missing_unit = [], []
    for name, cmd in cmds.items():
        for a in _options(cmd):
            label = f"{name} {a.option_strings[0]}"
            if "default" not in (a.help or ""):
                missing_default.append(label)
            if a.type is float and not re.search(r"\[[^\]]+\]", a.help or ""):
                missing_unit.append(label)
    assert missing_default == []
    assert missing_unit == []


def test_dt_is_the_fixed_integration_step_everywhere():
    _, cmds = _subparsers()
    having = [n for n, c in cmds.items() if "--dt" in c._option_string_actions]
    assert {"spectrum", "simulate", "record", "rocking-spectrum"} <= set(having)
    for n in having:
        assert "fixed integration step [s]" in cmds[n]._option_string_actions["--dt"].help, n
    # the sample step of a single-column record file has its own name
    for n in ("record", "rocking-spectrum"):
        assert "--record-dt" in cmds[n]._option_string_actions


def test_bare_angle_options_are_radians_and_degree_options_say_so():
    _, cmds = _subparsers()
    for name, cmd in cmds.items():
        for a in _options(cmd):
            o = a.option_strings[0]
            if o in ("--alpha", "--theta0"):
                assert "[rad]" in a.help, (name, o)
            if o.endswith("-deg"):
                assert "[deg]" in a.help, (name, o)


@pytest.mark.parametrize("argv", [
    ["record", "{missing}"],
    ["rocking-spectrum", "{missing}"],
    ["run", "{missing}"],
    ["study", "{missing}"],
    ["fit", "{missing}"],
])
def test_a_missing_file_is_one_line_naming_it(argv, tmp_path, capsys):
    missing = tmp_path / "no_such_file.AT2"
    rc = cli.main([a.format(missing=missing) for a in argv])
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert len(err.splitlines()) == 1 and "no_such_file" in err and "Traceback" not in err


@pytest.mark.parametrize("argv, option", [
    (["spectrum", "--n-amp", "0"], "--n-amp"),
    (["simulate", "--theta0", "nan"], "theta0"),
    (["record", "--dt", "-1"], "--dt"),
    (["rocking-spectrum", "--b-min", "-1"], "--b-min"),
    (["accuracy", "--rtols", "x"], "--rtols"),
    (["fit", str(ROOT / "fastrock" / "data" / "yu2019_halfcycles.csv"), "--alpha", "2"], "alpha"),
    (["study", str(ROOT / "examples" / "study.toml"), "--n-boot", "-3"], "--n-boot"),
])
def test_a_bad_value_is_one_line_naming_the_option(argv, option, capsys):
    rc = cli.main(argv)
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert len(err.splitlines()) == 1 and option in err, err


def test_quiet_prints_nothing_and_parquet_equals_csv(tmp_path, capsys):
    csv, pq = tmp_path / "h.csv", tmp_path / "h.parquet"
    assert cli.main(["simulate", "--amplitude", "3", "--csv", str(csv), "--parquet", str(pq), "--quiet"]) == 0
    out = capsys.readouterr()
    assert out.out == "" and out.err == ""
    a, b = pd.read_csv(csv), pd.read_parquet(pq)
    assert list(a.columns) == list(b.columns) and len(a) == len(b) > 10
    np.testing.assert_allclose(a.select_dtypes("number").to_numpy(), b.select_dtypes("number").to_numpy(),
                               rtol=1e-14)
    assert cli.main(["simulate", "--amplitude", "3"]) == 0
    assert "outcome" in capsys.readouterr().out


def test_fit_takes_angles_in_radians_or_degrees(tmp_path, capsys):
    data = str(ROOT / "fastrock" / "data" / "yu2019_halfcycles.csv")
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert cli.main(["fit", data, "--alpha", str(math.radians(14.8)), "--csv", str(a)]) == 0
    assert cli.main(["fit", data, "--alpha-deg", "14.8", "--csv", str(b), "--png", str(tmp_path / "f.png")]) == 0
    pd.testing.assert_frame_equal(pd.read_csv(a), pd.read_csv(b))
    assert (tmp_path / "f.png").stat().st_size > 0
    capsys.readouterr()
    with pytest.raises(SystemExit):        # one angle, one unit
        cli.main(["fit", data, "--alpha", "0.25", "--alpha-deg", "14.8"])


def _record_folder(tmp_path):
    """The packaged El Centro record as .AT2, .at2 (a scaled copy) and a two-column .dat, plus a
    file that is no record."""
    src = Path(fastrock.__file__).resolve().parent / "data"
    at2 = next(f for f in src.iterdir() if f.suffix.lower() == ".at2")
    folder = tmp_path / "recs"
    folder.mkdir()
    shutil.copy(at2, folder / "UPPER.AT2")
    shutil.copy(at2, folder / "lower.at2")
    rec = load_default_record()
    t = np.arange(rec.npts) * rec.dt
    lines = ["Time[s] Accel[g]"] + [f"{ti:.4f} {a / 9.80665:.8f}" for ti, a in zip(t, rec.acc)]
    (folder / "two_column.dat").write_text("\n".join(lines))
    (folder / "notes.txt").write_text("not a record")
    return folder


def test_rocking_spectrum_takes_a_folder_or_a_glob_in_any_letter_case(tmp_path, capsys):
    from fastrock.analyses.rocking_spectrum.inputs import load_records
    folder = _record_folder(tmp_path)
    names = [r.name for r in load_records(folder)]
    assert len(names) == 3 and not any("notes" in n for n in names)
    assert len(load_records(str(folder / "*.at2"))) == 2       # UPPER.AT2 and lower.at2
    assert len(load_records(str(folder / "*.DAT"))) == 1
    with pytest.raises(ValueError, match=r"no file matches"):
        load_records(str(folder / "*.xyz"))
    csv = tmp_path / "rs.csv"
    rc = cli.main(["rocking-spectrum", str(folder), "--n-slenderness", "3", "--n-sizes", "2", "--walls",
                   "two-sided", "--csv", str(csv), "--png", str(tmp_path / "rs.png"), "-q"])
    assert rc == 0
    assert pd.read_csv(csv)["record"].nunique() == 3


def test_wall_friction_on_the_command_line(tmp_path, capsys):
    csv = tmp_path / "h.csv"
    assert cli.main(["simulate", "--b", "0.2", "--h", "1.0", "--wall-gap", "0.05", "--wall-friction", "0.5",
                     "--mu-s", "0.6", "--amplitude", "4", "--csv", str(csv)]) == 0
    assert "kernel contact" in capsys.readouterr().out
    ref = fastrock.simulate(fastrock.RigidBlock.rectangle(0.2, 1.0),
                            fastrock.Pulse(4, 2, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                            wall=fastrock.Wall(0.05, friction=0.5), friction=fastrock.Friction(0.6))
    np.testing.assert_array_equal(pd.read_csv(csv)["theta"].to_numpy(), ref.history["theta"].to_numpy())
    assert cli.main(["simulate", "--b", "0.2", "--h", "1.0", "--wall-gap", "0.05", "--wall-friction", "0.5"]) == 2
    assert "friction" in capsys.readouterr().err
