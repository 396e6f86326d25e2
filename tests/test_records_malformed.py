"""read_record never misreads a file silently (issue #18, item 3).

Decimal commas, tables of several numeric columns and implausible units are
refused or warned about; every case writes its file into tmp_path.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from fastrock.constants import G_STANDARD
from fastrock.io.ground_motion import PGA_PLAUSIBLE_G, RecordFormatError, RecordUnitWarning
from fastrock.io.default_records import load_default_record
from fastrock.io.readers import read_record


from shared_data import records_dir

RECORDS = records_dir()

DT = 0.01
N = 40
#: A plausible record in g: PGA 0.3 g, a few sign changes.
ACC_G = 0.3 * np.sin(2 * np.pi * 2.0 * np.arange(N) * DT) * np.exp(-np.arange(N) / 30)
ACC_G[7] = -0.3  # exact PGA


def _write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def _no_warning_read(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return read_record(path, **kw)


def _comma(x: float, fmt: str = ".6f") -> str:
    return format(x, fmt).replace(".", ",")


def _format_error(path, *fragments, lineno=None, **kw) -> str:
    with pytest.raises(RecordFormatError) as ei:
        read_record(path, **kw)
    msg = str(ei.value)
    assert str(path) in msg, msg
    if lineno is not None:
        assert f"line {lineno}" in msg, msg
    for frag in fragments:
        assert frag in msg, msg
    return msg


# -- decimal commas -------------------------------------------------------------

DECIMAL_COMMA_FILES = {
    # name: (text, kwargs for read_record, line of the first decimal comma)
    "single_column": (
        "".join(f"{_comma(v)}\n" for v in ACC_G), {"unit": "g", "dt": DT}, 1
    ),
    "semicolon_pairs": (
        "Time;Accel[g]\n"
        + "".join(f"{_comma(i * DT, '.2f')};{_comma(v, '.4E')}\n" for i, v in enumerate(ACC_G)),
        {},
        2,
    ),
    "at2_body": (
        "ACCELERATION IN UNITS OF G\nNPTS= 40, DT= .01\n"
        + "".join(
            " ".join(_comma(v, "13.6E") for v in ACC_G[i:i + 5]) + "\n"
            for i in range(0, N, 5)
        ),
        {},
        3,
    ),
    "at2_header_dt": (
        "ACCELERATION IN UNITS OF G\nNPTS= 40, DT= 0,01\n"
        + "".join(f"{_comma(v)}\n" for v in ACC_G),
        {},
        2,
    ),
}


@pytest.mark.parametrize("case", sorted(DECIMAL_COMMA_FILES))
def test_decimal_commas_refused_without_decimal(tmp_path, case):
    text, kw, lineno = DECIMAL_COMMA_FILES[case]
    p = _write(tmp_path, f"{case}.txt", text)
    msg = _format_error(p, "decimal comma", "decimal=','", lineno=lineno, **kw)
    assert "1e+06" not in msg


@pytest.mark.parametrize("case", sorted(DECIMAL_COMMA_FILES))
def test_decimal_commas_read_with_decimal_comma(tmp_path, case):
    text, kw, _ = DECIMAL_COMMA_FILES[case]
    p = _write(tmp_path, f"{case}.txt", text)
    gm = _no_warning_read(p, decimal=",", **kw)
    assert gm.npts == N
    assert gm.dt == pytest.approx(DT, rel=1e-12)
    np.testing.assert_allclose(gm.acc / G_STANDARD, ACC_G, rtol=1e-4, atol=1e-6)
    assert gm.pga_g == pytest.approx(0.3, rel=1e-6)


def test_decimal_comma_refuses_dot_marks(tmp_path):
    lines = [_comma(v) for v in ACC_G]
    lines[5] = f"{ACC_G[5]:.6f}"  # one '.' decimal mark on line 6
    p = _write(tmp_path, "mixed.txt", "\n".join(lines) + "\n")
    _format_error(p, f"'{ACC_G[5]:.6f}'", "decimal=','", lineno=6,
                  unit="g", dt=DT, decimal=",")
    q = _write(tmp_path, "dotcsv.txt", "".join(f"{i * DT:.2f},{v:.6f}\n"
                                               for i, v in enumerate(ACC_G)))
    _format_error(q, "'.' decimal mark", lineno=1, unit="g", decimal=",")
    # Commas as decimal marks and as separators at once cannot be read.
    r = _write(tmp_path, "commas.txt", "0,01,0,5\n0,02,0,6\n")
    _format_error(r, "non-numeric", "only whitespace or ';'", lineno=1,
                  unit="g", dt=DT, decimal=",")


@pytest.mark.parametrize("sep", [",", ", ", ";", ",\t"])
def test_comma_separated_dot_decimals_still_read(tmp_path, sep):
    # %g output prints integral values without '.', e.g. "0,0": the other
    # lines show that commas separate '.'-decimal numbers in this file.
    acc = ACC_G.copy()
    acc[0] = 0.0
    rows = [f"{i * DT:g}{sep}{v:g}" for i, v in enumerate(acc)]
    assert rows[0] == f"0{sep}0"
    p = _write(tmp_path, "dots.csv", "time,acc\n" + "\n".join(rows) + "\n")
    gm = _no_warning_read(p, unit="g")
    assert gm.npts == N and gm.dt == pytest.approx(DT, rel=1e-9)
    np.testing.assert_allclose(gm.acc / G_STANDARD, acc, rtol=1e-5, atol=1e-9)


# -- several numeric columns ------------------------------------------------------


def _three_columns(time_first: bool) -> str:
    rows = []
    for i, v in enumerate(ACC_G):
        first = f"{i * DT:.3f}" if time_first else f"{0.5 * v:.6f}"
        rows.append(f"{first} {v:.6f} {2 * v:.6f}")
    return "\n".join(rows) + "\n"


def test_three_columns_refused_without_column(tmp_path):
    for time_first in (False, True):
        p = _write(tmp_path, f"three{time_first}.dat", _three_columns(time_first))
        msg = _format_error(p, "holds 3 numbers", "column=K", "0-based", 'column="all"',
                            lineno=1, unit="g", dt=DT)
        assert "column=-1" in msg


@pytest.mark.parametrize("column,factor", [(1, 1.0), (-1, 2.0), (2, 2.0), (-2, 1.0)])
def test_three_columns_with_column(tmp_path, column, factor):
    p = _write(tmp_path, "three.dat", _three_columns(time_first=False))
    with pytest.raises(ValueError, match="dt"):
        read_record(p, unit="g", column=column)  # no time column: dt needed
    gm = _no_warning_read(p, unit="g", dt=DT, column=column)
    assert gm.npts == N and gm.dt == DT
    np.testing.assert_allclose(gm.acc / G_STANDARD, factor * ACC_G, atol=1e-6)


@pytest.mark.parametrize("column,factor", [(1, 1.0), (-1, 2.0)])
def test_three_columns_dt_from_time_column(tmp_path, column, factor):
    p = _write(tmp_path, "tva.dat", "Time[s] Accel[g] Accel2[g]\n" + _three_columns(True))
    gm = _no_warning_read(p, column=column)
    assert gm.dt == pytest.approx(DT, rel=1e-12) and gm.npts == N
    np.testing.assert_allclose(gm.acc / G_STANDARD, factor * ACC_G, atol=1e-6)
    assert _no_warning_read(p, column=column, dt=DT).dt == pytest.approx(DT)
    with pytest.raises(ValueError, match=r"dt=0\.02.*contradicts"):
        read_record(p, column=column, dt=0.02)


def test_two_time_like_columns_need_dt(tmp_path):
    rows = [f"{i} {i * DT:.3f} {v:.6f}" for i, v in enumerate(ACC_G)]  # index, t, a
    p = _write(tmp_path, "itv.dat", "\n".join(rows) + "\n")
    _format_error(p, "column 0 (step 1 s)", "column 1 (step 0.01 s)", "dt=",
                  unit="g", column=2)
    gm = _no_warning_read(p, unit="g", column=2, dt=DT)
    assert gm.dt == pytest.approx(DT)


def test_uneven_time_column_with_column(tmp_path):
    rows = [f"{i * DT + (0.004 if i == 9 else 0):.3f} {v:.6f} {v:.6f}"
            for i, v in enumerate(ACC_G)]
    p = _write(tmp_path, "jitter3.dat", "\n".join(rows) + "\n")
    _format_error(p, "not uniformly spaced", lineno=10, unit="g", column=1)


@pytest.mark.parametrize("column", [2, -3, 10])
def test_column_out_of_range(tmp_path, column):
    p = _write(tmp_path, "two.dat", "".join(f"{i * DT:.2f} {v:.6f}\n"
                                            for i, v in enumerate(ACC_G)))
    with pytest.raises(ValueError, match=r"column=-?\d+ is out of range.*hold 2") as ei:
        read_record(p, unit="g", column=column)
    assert not isinstance(ei.value, RecordFormatError)


def test_two_columns_without_time_column_refused(tmp_path):
    # Two acceleration components side by side: the first column is no time.
    rows = [f"{v:.6f} {-0.5 * v:.6f}" for v in ACC_G]
    p = _write(tmp_path, "xy.dat", "\n".join(rows) + "\n")
    msg = _format_error(p, "holds 2 numbers", "not an increasing time column",
                        "column=K", lineno=1, unit="g", dt=DT)
    assert 'column="all"' in msg
    gm = _no_warning_read(p, unit="g", dt=DT, column=0)
    np.testing.assert_allclose(gm.acc / G_STANDARD, ACC_G, atol=1e-6)
    gm = _no_warning_read(p, unit="g", dt=DT, column=-1)
    np.testing.assert_allclose(gm.acc / G_STANDARD, -0.5 * ACC_G, atol=1e-6)


def _wrapped(values, per_line: int) -> str:
    return "".join(
        " ".join(f"{v:.6f}" for v in values[i:i + per_line]) + "\n"
        for i in range(0, len(values), per_line)
    )


@pytest.mark.parametrize("per_line", [3, 4, 5, 8])
def test_wrapped_sequence_needs_column_all(tmp_path, per_line):
    p = _write(tmp_path, "wrapped.txt", "Accel[g]\n" + _wrapped(ACC_G, per_line))
    msg = _format_error(p, 'column="all"', unit="g", dt=DT)
    assert "line 2" in msg or f"line {2 + N // per_line}" in msg
    gm = _no_warning_read(p, dt=DT, column="all")
    assert gm.npts == N and gm.dt == DT
    np.testing.assert_allclose(gm.acc / G_STANDARD, ACC_G, atol=1e-6)
    with pytest.raises(ValueError, match="dt"):
        read_record(p, column="all")


def test_npts_header_with_table(tmp_path):
    hdr = f"ACCELERATION IN UNITS OF G\nNPTS= {N}, DT= {DT}\n"
    rows = "".join(f"{i * DT:.3f} {v:.6f}\n" for i, v in enumerate(ACC_G))
    p = _write(tmp_path, "table.AT2", hdr + rows)
    _format_error(p, f"more values than NPTS={N}", "column=K", lineno=3 + N // 2)
    gm = _no_warning_read(p, column=1)
    assert gm.npts == N and gm.dt == DT
    np.testing.assert_allclose(gm.acc / G_STANDARD, ACC_G, atol=1e-6)
    bad = _write(tmp_path, "table_dt.AT2", hdr.replace(f"DT= {DT}", "DT= 0.02") + rows)
    _format_error(bad, "time column gives dt=0.01", "DT=0.02", column=1)
    # "all" on an AT2 file is the AT2 rule itself: the header's count decides.
    _format_error(p, f"more values than NPTS={N}", column="all")


def test_ragged_rows_refused(tmp_path):
    text = _wrapped(ACC_G[:38], 2) + "0.1\n0.2\n"  # 19 rows of 2, then 2 of 1
    p = _write(tmp_path, "ragged.txt", text)
    _format_error(p, "expected 2 columns as on line 1, found 1", 'column="all"',
                  lineno=20, unit="g", dt=DT)
    _format_error(p, "expected 2 columns", lineno=20, unit="g", dt=DT, column=1)
    assert read_record(p, unit="g", dt=DT, column="all").npts == 40


# -- unit plausibility ------------------------------------------------------------


def _two_column(values, header: str = "") -> str:
    return header + "".join(f"{i * DT:.3f} {v:.6f}\n" for i, v in enumerate(values))


@pytest.mark.parametrize("labelled", ["header", "argument"])
def test_cm_s2_labelled_g_warns(tmp_path, labelled):
    acc_cms2 = ACC_G / 0.3 * 378.0  # PGA 378 cm/s2 = 0.385 g
    header = "Time[s] Accel[g]\n" if labelled == "header" else ""
    p = _write(tmp_path, "gal_as_g.dat", _two_column(acc_cms2, header))
    kw = {} if labelled == "header" else {"unit": "g"}
    with pytest.warns(RecordUnitWarning) as rec:
        gm = read_record(p, **kw)
    assert gm.pga_g == pytest.approx(378.0)  # read as stated, only warned
    assert len(rec) == 1
    msg = str(rec[0].message)
    assert str(p) in msg and "'g'" in msg and "PGA = 378 g" in msg
    assert ("file header, line 1" if labelled == "header" else "unit='g'") in msg
    assert "if the samples are in cm/s2 (factor 1/980.665), PGA = 0.385 g" in msg
    assert "m/s2 (factor 1/9.80665)" not in msg  # 38.5 g: still implausible
    assert rec[0].filename == __file__  # points at the caller of read_record


def test_m_s2_labelled_mm_s2_warns(tmp_path):
    acc_ms2 = ACC_G / 0.3 * 0.5  # PGA 0.5 m/s2 = 0.051 g, read as 5.1e-5 g
    p = _write(tmp_path, "ms2_as_mm.dat", _two_column(acc_ms2))
    with pytest.warns(RecordUnitWarning) as rec:
        gm = read_record(p, unit="mm/s2")
    assert gm.pga == pytest.approx(0.5e-3)
    msg = str(rec[0].message)
    assert "'mm/s2'" in msg and f"PGA = {0.5e-3 / G_STANDARD:.3g} g" in msg
    assert "if the samples are in m/s2 (factor 1000), PGA = 0.051 g" in msg
    assert f"{PGA_PLAUSIBLE_G[0]:g} g to {PGA_PLAUSIBLE_G[1]:g} g" in msg


def test_all_zero_record_warns_without_factor(tmp_path):
    p = _write(tmp_path, "zero.dat", _two_column(np.zeros(N)))
    with pytest.warns(RecordUnitWarning, match="every sample is zero") as rec:
        read_record(p, unit="g")
    assert "factor" not in str(rec[0].message)


def test_hopeless_pga_names_no_factor(tmp_path):
    rows = "".join(f"{i * DT:.3f} {v:.6e}\n" for i, v in enumerate(ACC_G * 1e-6))
    p = _write(tmp_path, "tiny.dat", rows)  # 3e-7 g, less still in any other unit
    with pytest.warns(RecordUnitWarning, match="no other unit") as rec:
        read_record(p, unit="g")
    assert "factor" not in str(rec[0].message)


@pytest.mark.parametrize("unit,scale", [("g", 1.0), ("m/s2", G_STANDARD),
                                        ("cm/s2", 100 * G_STANDARD), ("gal", 100 * G_STANDARD),
                                        ("mm/s2", 1000 * G_STANDARD)])
def test_plausible_file_does_not_warn(tmp_path, unit, scale):
    p = _write(tmp_path, "ok.dat", _two_column(ACC_G * scale))
    gm = _no_warning_read(p, unit=unit)
    assert gm.pga_g == pytest.approx(0.3, rel=1e-5)


def test_default_record_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert load_default_record().npts == 1559


SHARED_UNITS = {"Northridge_Sylmar_County.dat": "m/s2"}


@pytest.mark.skipif(not RECORDS.is_dir(), reason=f"shared record folder {RECORDS} absent")
def test_every_shared_record_reads_without_warning():
    files = sorted(f for f in RECORDS.iterdir() if f.is_file() and f.suffix != ".md")
    assert len(files) >= 7
    for f in files:
        gm = _no_warning_read(f, unit=SHARED_UNITS.get(f.name))
        assert PGA_PLAUSIBLE_G[0] < gm.pga_g < PGA_PLAUSIBLE_G[1]


# -- argument checks ----------------------------------------------------------------


@pytest.mark.parametrize(
    "kw,name",
    [
        ({"decimal": ";"}, "decimal"),
        ({"decimal": ""}, "decimal"),
        ({"decimal": None}, "decimal"),
        ({"decimal": ",."}, "decimal"),
        ({"column": "first"}, "column"),
        ({"column": "ALL"}, "column"),
        ({"column": 1.0}, "column"),
        ({"column": True}, "column"),
        ({"column": [1]}, "column"),
        ({"column": 1}, "column"),  # out of range for a single-column file
        ({"column": -2}, "column"),
    ],
)
def test_bad_arguments(tmp_path, kw, name):
    p = _write(tmp_path, "one.txt", "".join(f"{v:.6f}\n" for v in ACC_G))
    with pytest.raises(ValueError, match=rf"^{name}\b|\b{name}=") as ei:
        read_record(p, unit="g", dt=DT, **kw)
    assert not isinstance(ei.value, RecordFormatError)


def test_numpy_integer_column_and_single_column(tmp_path):
    p = _write(tmp_path, "one.txt", "".join(f"{v:.6f}\n" for v in ACC_G))
    for column in (0, -1, np.int64(0), None):
        gm = _no_warning_read(p, unit="g", dt=DT, column=column)
        np.testing.assert_allclose(gm.acc / G_STANDARD, ACC_G, atol=1e-6)


def test_column_and_decimal_reach_every_entry_point(tmp_path, capsys):
    """The CLI (--column, --decimal), a TOML scene and a study's record table
    pass the options on to read_record."""
    from fastrock.cli import app as cli
    from fastrock.running.scene import Scene
    from fastrock.studies.definition import _load
    p = _write(tmp_path, "three.txt", _three_columns(time_first=True))
    q = _write(tmp_path, "comma.txt", "".join(f"{_comma(v)}\n" for v in ACC_G))
    assert cli.main(["record", str(p), "--unit", "g", "--png", str(tmp_path / "r.png")]) == 2
    assert "column=K" in capsys.readouterr().err
    assert cli.main(["record", str(p), "--unit", "g", "--column", "1", "--png", str(tmp_path / "r.png")]) == 0
    assert cli.main(["record", str(q), "--unit", "g", "--record-dt", str(DT), "--decimal", ",",
                     "--png", str(tmp_path / "q.png")]) == 0
    assert cli.main(["record", str(p), "--unit", "g", "--column", "x"]) == 2
    assert "--column must be an integer" in capsys.readouterr().err
    scene = Scene.from_dict({"body": {"b": 0.2, "h": 1.0},
                             "excitation": {"type": "record", "file": "three.txt", "unit": "g", "column": 1}},
                            base=tmp_path)
    assert scene.excitation.acc.size == ACC_G.size
    (rec,) = _load([{"file": str(q), "unit": "g", "dt": DT, "decimal": ","}], None, None)
    np.testing.assert_allclose(rec.acc / G_STANDARD, ACC_G, atol=1e-6)
