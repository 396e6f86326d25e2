"""RigidBody from files and on the command line (issue #17, items 2 and 4): read_outline,
``fastrock spectrum/simulate --outline/--mesh``, and ``vertices = "file"`` in a scene."""
import math

import numpy as np
import pandas as pd
import pytest

import fastrock as fr
from fastrock.cli import app as cli
from test_scene_rigid_body import BOX_OBJ, _scene  # noqa: E402

WEDGE = [(0.0, 0.0), (1.0, 0.0), (0.2, 2.0)]
GRID = ["--n-amp", "5", "--amp-min", "0.6", "--amp-max", "4", "--n-freq", "4", "--freq-min", "0.5",
        "--freq-max", "6", "--sign", "both", "-q"]


@pytest.mark.parametrize("text", [
    "x,y\n0,0\n1,0\n0.2,2\n",
    "# a wedge\n0 0\n1.0 0\n0.2 2.0\n0 0\n",            # closed: the repeated vertex is dropped
    "0;0\n1;0\n0.2;2\n",
    "0\t0\r\n1\t0\r\n0.2\t2\r\n",
])
def test_read_outline_formats(tmp_path, text):
    path = tmp_path / "w.txt"
    path.write_text(text)
    np.testing.assert_array_equal(fr.read_outline(path), np.array(WEDGE))


@pytest.mark.parametrize("text, match", [
    ("0,0\n1,0,5\n0.2,2\n", r"line 2: 3 numbers"),
    ("0,0\n1,zero\n0.2,2\n", r"line 2: '1,zero' is not two numbers"),
    ("0,0\n1,nan\n0.2,2\n", r"line 2: .* not finite"),
    ("0,0\n1,0\n", r"2 vertices"),
    ("", r"0 vertices"),
])
def test_read_outline_refuses_malformed_files(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=match) as exc:
        fr.read_outline(path)
    assert "bad.csv" in str(exc.value)


def _spectrum(tmp_path, name, *options):
    csv = tmp_path / f"{name}.csv"
    assert cli.main(["spectrum", *options, *GRID, "--csv", str(csv), "--png", str(tmp_path / f"{name}.png")]) == 0
    return pd.read_csv(csv)


def test_spectrum_of_a_rectangular_outline_is_the_block(tmp_path):
    (tmp_path / "rect.csv").write_text("0 0\n0.6 0\n0.6 2.0\n0 2.0\n")
    shape = _spectrum(tmp_path, "shape", "--outline", str(tmp_path / "rect.csv"))
    block = _spectrum(tmp_path, "block", "--b", "0.3", "--h", "1.0")
    pd.testing.assert_series_equal(shape["outcome"], block["outcome"])
    np.testing.assert_allclose(shape["max_rotation"], block["max_rotation"], rtol=1e-12, atol=0)


def test_spectrum_of_an_asymmetric_outline(tmp_path, capsys):
    (tmp_path / "wedge.csv").write_text("x,y\n0,0\n1.0,0\n0.2,2.0\n")
    capsys.readouterr()
    csv = tmp_path / "w.csv"
    assert cli.main(["spectrum", "--outline", str(tmp_path / "wedge.csv"), "--density", "2600",
                     "--thickness", "0.5", *GRID[:-1], "--csv", str(csv), "--png", str(tmp_path / "w.png")]) == 0
    printed = capsys.readouterr().out
    body = fr.RigidBody.from_polygon(WEDGE, density=2600, thickness=0.5)
    assert body.describe() in printed                    # the derived body, for the user to check
    got = pd.read_csv(csv)
    ref = fr.overturning_spectrum(body, np.linspace(0.6, 4, 5), np.linspace(0.5, 6, 4), sign=[1, -1],
                                  progress=False)
    assert list(got["outcome"]) == list(ref["outcome"].astype(str))
    assert set(got["side"]) == set(ref["side"]) and {-1, 1} <= set(got["side"])
    assert (tmp_path / "w.png").stat().st_size > 0


def test_spectrum_of_a_mesh_is_its_section(tmp_path):
    (tmp_path / "box.obj").write_text(BOX_OBJ)    # 0.4 x 0.3 x 1.2 m; shaking along x
    shape = _spectrum(tmp_path, "mesh", "--mesh", str(tmp_path / "box.obj"), "--mesh-axis", "0,1,0")
    block = _spectrum(tmp_path, "block", "--b", "0.2", "--h", "0.6")
    pd.testing.assert_series_equal(shape["outcome"], block["outcome"])
    np.testing.assert_allclose(shape["max_rotation"], block["max_rotation"], rtol=1e-9, atol=1e-12)


def test_simulate_an_outline(tmp_path, capsys):
    (tmp_path / "wedge.csv").write_text("0 0\n1 0\n0.2 2\n")
    out = tmp_path / "h.csv"
    assert cli.main(["simulate", "--outline", str(tmp_path / "wedge.csv"), "--amplitude", "0.35",
                     "--amplitude-unit", "g", "--frequency", "1", "--frequency-unit", "Hz",
                     "--csv", str(out), "--png", ""]) == 0
    body = fr.RigidBody.from_polygon(WEDGE, mass=1.0)
    ref = fr.simulate(body, fr.Pulse(0.35, 1.0, amplitude_unit="g", frequency_unit="Hz"))
    assert f"outcome {ref.outcome} ({ref.status})" in capsys.readouterr().out
    assert len(pd.read_csv(out)) == len(ref.history)


@pytest.mark.parametrize("options, match", [
    (["--outline", "W", "--b", "0.3", "--h", "1"], r"--outline defines the body; it takes no --b, --h"),
    (["--outline", "W", "--mesh", "M"], r"--outline or --mesh, not both"),
    (["--outline", "W", "--density", "2000"], r"--density with --outline needs --thickness"),
    (["--mesh", "M", "--thickness", "0.3"], r"--thickness is for --outline"),
    (["--mesh", "M", "--mesh-axis", "0,1"], r"--mesh-axis must be three numbers"),
    (["--outline", "missing.csv"], r"No such file|missing.csv"),
])
def test_bad_shape_options_are_one_line(tmp_path, capsys, options, match):
    (tmp_path / "W").write_text("0 0\n1 0\n0.2 2\n")
    (tmp_path / "M").write_text(BOX_OBJ)
    options = [str(tmp_path / o) if o in ("W", "M", "missing.csv") else o for o in options]
    assert cli.main(["spectrum", *options, *GRID]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastrock: error:") and len(err.strip().splitlines()) == 1
    assert __import__("re").search(match, err)


def test_scene_vertices_from_a_file(tmp_path):
    (tmp_path / "wedge.csv").write_text("x,y\n0,0\n1.0,0\n0.2,2.0\n")
    scene = _scene(tmp_path, '[body]\ntype = "rigid-body"\nvertices = "wedge.csv"\nmass = 3.0\n')
    assert scene.body == fr.RigidBody.from_polygon(WEDGE, mass=3.0)
    with pytest.raises(ValueError, match="line 2"):
        (tmp_path / "bad.csv").write_text("0,0\n1\n0.2,2\n")
        _scene(tmp_path, '[body]\ntype = "rigid-body"\nvertices = "bad.csv"\nmass = 3.0\n')


# ------------------------------------------------------------ the rocking spectrum of a shape
S_GRID, B_GRID = np.linspace(0.1, 0.5, 6), np.array([0.2, 0.6])


def test_shape_family_stretches_the_outline():
    from fastrock.analyses.rocking_spectrum.inputs import shape_family
    body = shape_family([(0, 0), (1, 0), (0.3, 2.5), (0, 2.5)])(0.6, 0.3)
    assert 0.5 * (body.b1 + body.b2) == pytest.approx(0.6, rel=1e-14)
    assert min(math.tan(body.alpha1), math.tan(body.alpha2)) == pytest.approx(0.3, rel=1e-14)
    assert not body.is_symmetric


def test_rocking_spectrum_of_a_rectangular_outline_is_the_rectangles():
    ref, ref_runs = fr.rocking_spectrum(None, S_GRID, B_GRID, walls=[None], progress=False, return_runs=True)
    got, runs = fr.rocking_spectrum(None, S_GRID, B_GRID, walls=[None], progress=False, return_runs=True,
                                    shape=[(0, 0), (1, 0), (1, 3), (0, 3)])
    assert list(runs["outcome"]) == list(ref_runs["outcome"])
    np.testing.assert_allclose(runs["p"], ref_runs["p"], rtol=1e-14)
    np.testing.assert_allclose(runs["max_rotation_ratio"], ref_runs["max_rotation_ratio"], rtol=1e-9)
    for col in ("slenderness_min", "beta", "beta_bound"):
        assert list(got[col]) == list(ref[col])


def test_rocking_spectrum_of_an_asymmetric_outline(tmp_path):
    from fastrock.analyses.rocking_spectrum.inputs import shape_family
    wedge = [(0, 0), (1, 0), (0.3, 2.5), (0, 2.5)]
    table, runs = fr.rocking_spectrum(None, S_GRID, B_GRID, walls=[None], progress=False, return_runs=True,
                                      shape=wedge)
    family = shape_family(wedge)
    record = fr.io.default_records.load_default_record()
    for i in (2, 9):                       # two cells, against the single run of the same body
        row = runs.iloc[i]
        body = family(row["b"], row["slenderness"])
        one = fr.simulate(body, record)
        assert row["outcome"] == one.outcome and row["alpha"] == body.alpha and row["p"] == body.p
    # the threshold's p is the body's at (b/h)_min
    first = table.iloc[0]
    assert first["p"] == family(first["b"], first["slenderness_min"]).p
    (tmp_path / "wedge.csv").write_text("\n".join(f"{x} {y}" for x, y in wedge))
    csv = tmp_path / "rs.csv"
    assert cli.main(["rocking-spectrum", "--outline", str(tmp_path / "wedge.csv"), "--n-slenderness", "6",
                     "--n-sizes", "2", "--b-min", "0.2", "--b-max", "0.6", "--walls", "two-sided",
                     "--csv", str(csv), "--png", str(tmp_path / "rs.png"), "-q"]) == 0
    np.testing.assert_array_equal(pd.read_csv(csv)["beta"], table["beta"])


def test_rocking_spectrum_shape_refuses_a_body():
    with pytest.raises(ValueError, match="shape must be an outline"):
        fr.rocking_spectrum(None, S_GRID, B_GRID, walls=[None], progress=False,
                            shape=fr.RigidBody.from_polygon(WEDGE, mass=1.0))
