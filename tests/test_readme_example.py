"""The README's Python example runs as written (issue #16: every README command runs in CI).

The example is taken from the README itself, so an edit there is what gets tested; it runs in a
temporary folder, where it writes its two figures."""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

README = Path(__file__).resolve().parents[1] / "README.md"


def readme_example():
    text = README.read_text(encoding="utf-8")
    m = re.search(r"^## Python example\n\n```python\n(.*?)^```", text, re.S | re.M)
    assert m, "README.md has no '## Python example' section with a python block"
    return m.group(1)


def test_readme_example_is_short():
    # the brief's README holds a 30-line example
    assert len(readme_example().strip().splitlines()) <= 30


def test_readme_example_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(readme_example(), str(README), "exec"), namespace)
    out = capsys.readouterr().out
    # what the example prints and writes: the run's outcome, the wall and friction runs, the
    # spectrum's outcome counts, and the two figures
    assert namespace["run"].outcome == "mode1"
    assert namespace["wall"].outcome == "safe" and namespace["wall"].metrics["wall_impacts"] > 0
    assert namespace["slide"].outcome == "slide" and namespace["slide"].metrics["max_slide"] > 0
    assert set(namespace["spec"].sign) == {1, -1} and len(namespace["spec"]) == 2 * 60 * 60
    assert "overturn:mode1" in out
    for name in ("spectrum.png", "history.png"):
        assert (tmp_path / name).stat().st_size > 0, name


def test_readme_links_exist():
    """Every relative link of the README points at a file of the repository (the docs pages
    the README sends readers to)."""
    root = README.parent
    targets = [t for t in re.findall(r"\]\(([^)#]+)\)", README.read_text(encoding="utf-8"))
               if "://" not in t]
    assert targets
    missing = [t for t in targets if not (root / t).exists()]
    assert not missing, missing
