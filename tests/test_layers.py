"""The front end's import rules (issue #16): no module imports another module's private names,
no module imports the package root, every subpackage ships, and the import-linter contracts
of .importlinter (layers, kernels alone, free rocking without the foundation models) hold."""
import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
FRONT_END = ROOT / "fastrock"


def module_name(path, top=FRONT_END):
    parts = list(path.relative_to(top.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def is_module(dotted, top=FRONT_END):
    """Whether fastrock.x.y names a module or package of the front end (a file or a folder)."""
    rel = Path(*dotted.split(".")[1:]) if "." in dotted else Path()
    base = top / rel
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def imported_from(node, module, is_package):
    """Absolute module a `from ... import` statement reads from."""
    if node.level == 0:
        return node.module
    package = module if is_package else module.rpartition(".")[0]
    for _ in range(node.level - 1):
        package = package.rpartition(".")[0]
    return f"{package}.{node.module}" if node.module else package


def private_imports(source, module, is_package=False, top=FRONT_END):
    """(line, source module, name) of every private name that `module` imports from another
    front-end module, at any depth (lazy imports inside functions count).  A private module
    imported as a whole (``from fastrock import _validate as V``) is not a private name."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.ImportFrom):
            continue
        src = imported_from(node, module, is_package)
        if not src or src.split(".")[0] != "fastrock" or src.startswith("fastrock.kernels"):
            continue
        for alias in node.names:
            name = alias.name
            if (name.startswith("_") and not name.startswith("__") and src != module
                    and not is_module(f"{src}.{name}", top)):
                out.append((node.lineno, src, name))
    return out


def front_end_files():
    return sorted(FRONT_END.rglob("*.py"))


def test_the_checker_finds_private_names(tmp_path):
    top = tmp_path / "fastrock"
    (top / "a").mkdir(parents=True)
    for f in ("__init__.py", "_helpers.py", "a/__init__.py", "a/b.py", "a/c.py"):
        (top / f).write_text("")
    src = ("from fastrock.a.c import _hidden, shown\n"
           "from .c import _also\n"
           "from fastrock import _helpers as H\n"
           "def f():\n"
           "    from ..a.c import _lazy\n")
    found = private_imports(src, "fastrock.a.b", top=top)
    assert [(src, name) for _, src, name in found] == [
        ("fastrock.a.c", "_hidden"), ("fastrock.a.c", "_also"), ("fastrock.a.c", "_lazy")]


def test_no_module_imports_another_modules_private_names():
    found = []
    for path in front_end_files():
        module = module_name(path)
        for line, src, name in private_imports(path.read_text(), module, path.name == "__init__.py"):
            found.append(f"{path.relative_to(ROOT)}:{line}: {name} from {src}")
    assert found == []


def test_no_front_end_module_imports_the_package_root():
    # .importlinter ignores `fastrock.** -> fastrock` because the front end's imports of
    # fastrock.kernels resolve to the root there; that holds only while nothing imports the root
    found = []
    for path in front_end_files():
        module = module_name(path)
        if module == "fastrock":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names if a.name == "fastrock"]
            elif isinstance(node, ast.ImportFrom):
                src = imported_from(node, module, path.name == "__init__.py")
                names = [a.name for a in node.names if src == "fastrock" and not is_module(f"fastrock.{a.name}")]
            else:
                continue
            found += [f"{path.relative_to(ROOT)}:{node.lineno}: {n}" for n in names]
    assert found == []


def test_every_subpackage_ships():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    packages = {module_name(p.parent / "__init__.py") for p in FRONT_END.rglob("__init__.py")}
    assert packages - listed == set()
    assert "fastrock.kernels" in listed and "fastrock.data" in listed


def test_import_contracts():
    if shutil.which("lint-imports") is None:
        pytest.skip("import-linter is not installed (pip install '.[test]')")
    run = subprocess.run(["lint-imports", "--no-cache"], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    assert "0 broken" in run.stdout
