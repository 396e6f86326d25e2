"""Sphinx directives that render what the code itself says, at build time.

``fastrock-columns KEY``
    the columns (and units) of a returned table, from the constant the code uses to describe it:
    ``spectrum`` (``SPECTRUM_COLUMNS`` beside ``overturning_spectrum``), ``rocking-spectrum`` and
    ``rocking-spectrum-runs`` (``SPECTRUM_COLUMNS`` / ``RUN_COLUMNS`` beside
    ``rocking_spectrum``), ``study`` (``RESULT_COLUMNS`` beside ``run_study``), ``metrics``
    (``METRIC_COLUMNS`` beside ``simulate``, described as in ``SPECTRUM_COLUMNS`` or by the
    ``METRIC_DESCRIPTIONS`` beside it), ``batch`` (``BATCH_COLUMNS`` beside ``run_batch``) and
    ``models`` (the registry's entries and the columns each model adds).
``fastrock-cli``
    the help of ``fastrock`` and of every subcommand, from the argparse parser the CLI runs.

Modules are found through the public objects (``fastrock.overturning_spectrum.__module__`` and
its package), never by a hard-coded module path, so moving a module does not break the build.
"""
from __future__ import annotations

import importlib
import os
import pkgutil
import re

from docutils import nodes
from docutils.parsers.rst import Directive, directives

import fastrock


# ---------------------------------------------------------------- finding things in the package
def _modules_near(obj):
    """The module that defines ``obj``, then its parent packages' modules (nearest first)."""
    name = obj.__module__
    yield importlib.import_module(name)
    parts = name.split(".")
    seen = {name}
    for k in range(len(parts) - 1, 0, -1):
        pkg = importlib.import_module(".".join(parts[:k]))
        for mod in _walk(pkg):
            if mod.__name__ not in seen:
                seen.add(mod.__name__)
                yield mod


def _walk(pkg):
    """``pkg`` and every module below it (kernels excluded: they compile nothing here, but the
    columns are a front-end matter)."""
    yield pkg
    for info in pkgutil.walk_packages(getattr(pkg, "__path__", []), pkg.__name__ + "."):
        if info.name.startswith("fastrock.kernels") or info.name.endswith("__main__"):
            continue
        try:
            yield importlib.import_module(info.name)
        except ImportError:   # an optional dependency (e.g. dask) missing
            continue


def find(attr, near, check):
    """The value of ``attr`` in the module nearest to ``near`` for which ``check(value)`` holds."""
    for mod in _modules_near(near):
        value = getattr(mod, attr, None)
        if value is not None and check(value):
            return value, mod.__name__
    raise LookupError(f"no {attr} found near {near!r}")


def find_registry():
    """The registry module: the one holding ``MODELS`` (name -> model) and ``select``."""
    for mod in _walk(fastrock):
        models = getattr(mod, "MODELS", None)
        if isinstance(models, dict) and callable(getattr(mod, "select", None)):
            return mod
    raise LookupError("no model registry found in fastrock")


def find_parser():
    """The CLI's ``build_parser`` (in the module the ``fastrock`` console script runs)."""
    import fastrock.cli as cli
    for mod in _walk(cli):
        fn = getattr(mod, "build_parser", None)
        if callable(fn):
            return fn
    raise LookupError("no build_parser found in fastrock.cli")


# ---------------------------------------------------------------- parsing the column texts
_UNIT = re.compile(r"\s*(\[[^\]]*\])\s*$")


def parse_columns(text):
    """Rows (names, meaning, unit) of a column description.

    The texts hold one entry per line: the column name(s), two or more spaces, the meaning, and
    the unit in brackets at the end of the line; indented lines continue the meaning; a name list
    ending in a comma continues on the next line.
    """
    rows = []
    for line in text.splitlines():
        if not line.strip():
            continue
        if line[0].isspace() and rows:
            rows[-1][1] = (rows[-1][1] + " " + line.strip()).strip()
            continue
        parts = re.split(r"\s{2,}", line.strip(), maxsplit=1)
        names, meaning = parts[0], (parts[1] if len(parts) > 1 else "")
        # a long name followed by a single space: "slenderness_first_stable smallest ..."
        m = re.match(r"([A-Za-z_]\w*) (?![\[,])(.*)", names)
        if m and not re.match(r"[A-Za-z_]\w*,", names):
            names, meaning = m.group(1), (m.group(2) + "  " + meaning).strip()
        if rows and rows[-1][0].endswith(",") and not rows[-1][1]:
            rows[-1][0] = rows[-1][0] + " " + names
            rows[-1][1] = meaning
            continue
        rows.append([names, meaning])
    out = []
    for names, meaning in rows:
        unit = ""
        m = _UNIT.search(meaning)
        if m:
            unit, meaning = m.group(1), meaning[:m.start()]
        out.append((names.strip(), meaning.strip(), unit.strip("[] ")))
    return out


def parse_column_list(text):
    """Rows (name, meaning, unit) of a comma-separated list such as ``RUN_COLUMNS``:
    ``wall_gap [m], slenderness b/h [-], outcome, ...``."""
    items, depth, cur = [], 0, ""
    for ch in " ".join(text.split()):
        if ch == "[":
            depth += 1
        elif ch == "]":
            depth -= 1
        if ch == "," and depth == 0:
            items.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        items.append(cur.strip())
    out = []
    for item in items:
        unit = ""
        m = _UNIT.search(item)
        if m:
            unit, item = m.group(1).strip("[] "), item[:m.start()]
        name, _, meaning = item.partition(" ")
        out.append((name, meaning.strip(), unit))
    return out


# ---------------------------------------------------------------- docutils helpers
def _cell(content):
    entry = nodes.entry()
    para = nodes.paragraph()
    if isinstance(content, nodes.Node):
        para += content
    elif isinstance(content, list):
        for c in content:
            para += c
    else:
        para += nodes.Text(str(content))
    entry += para
    return entry


def _names_cell(names):
    """Column names as code; what follows a name in the text (its unit written after it,
    "time_end [s]", or a symbol, "mean_period Tm [s]") stays beside it as plain text."""
    parts = [n.strip() for n in names.split(",") if n.strip()]
    out = []
    for i, n in enumerate(parts):
        if i:
            out.append(nodes.Text(", "))
        name, _, rest = n.partition(" ")
        out.append(nodes.literal(text=name))
        if rest:
            out.append(nodes.Text(" " + rest))
    return out


def _table(header, rows, widths):
    table = nodes.table(classes=["fastrock-columns"])
    group = nodes.tgroup(cols=len(header))
    table += group
    for w in widths:
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    hrow = nodes.row()
    for h in header:
        hrow += _cell(h)
    head += hrow
    group += head
    body = nodes.tbody()
    for r in rows:
        row = nodes.row()
        for c in r:
            row += _cell(c)
        body += row
    group += body
    return table


def _source_note(attr, module):
    para = nodes.paragraph()
    para += nodes.emphasis(text="Generated at build time from ")
    para += nodes.literal(text=attr)
    para += nodes.emphasis(text=" in ")
    para += nodes.literal(text=module)
    para += nodes.emphasis(text=".")
    return para


# ---------------------------------------------------------------- directives
class ColumnsDirective(Directive):
    required_arguments = 1
    has_content = False

    def run(self):
        key = self.arguments[0]
        if key == "spectrum":
            text, mod = find("SPECTRUM_COLUMNS", fastrock.overturning_spectrum,
                             lambda v: isinstance(v, str) and "amplitude_ratio" in v)
            return self._described(text, "SPECTRUM_COLUMNS", mod)
        if key == "rocking-spectrum":
            text, mod = find("SPECTRUM_COLUMNS", fastrock.rocking_spectrum,
                             lambda v: isinstance(v, str) and "beta" in v)
            return self._described(text, "SPECTRUM_COLUMNS", mod)
        if key == "rocking-spectrum-runs":
            text, mod = find("RUN_COLUMNS", fastrock.rocking_spectrum,
                             lambda v: isinstance(v, str) and "outcome" in v)
            rows = parse_column_list(text)
            return [_source_note("RUN_COLUMNS", mod),
                    _table(["column", "meaning", "unit"],
                           [(_names_cell(n), m, u) for n, m, u in rows], [30, 50, 20])]
        if key == "study":
            text, mod = find("RESULT_COLUMNS", fastrock.run_study,
                             lambda v: isinstance(v, str) and "record" in v)
            return self._described(text, "RESULT_COLUMNS", mod)
        if key == "metrics":
            cols, mod = find("METRIC_COLUMNS", fastrock.simulate, lambda v: isinstance(v, dict))
            spec, _ = find("SPECTRUM_COLUMNS", fastrock.overturning_spectrum,
                           lambda v: isinstance(v, str) and "amplitude_ratio" in v)
            described = _by_name(parse_columns(spec))
            # the metrics that are not spectrum columns are described beside METRIC_COLUMNS
            # (the module defining both; others only import METRIC_COLUMNS)
            own, mod = find("METRIC_DESCRIPTIONS", fastrock.simulate, lambda v: isinstance(v, str))
            cols = getattr(importlib.import_module(mod), "METRIC_COLUMNS", cols)
            described.update(_by_name(parse_columns(own)))
            missing = [n for n in cols if n not in described]
            if missing:
                raise self.error(f"metrics without a description (METRIC_DESCRIPTIONS in {mod}): "
                                 + ", ".join(missing))
            rows = [(_names_cell(n),) + described[n] for n in cols]
            return [_source_note("METRIC_COLUMNS", mod),
                    _table(["key", "meaning", "unit"], rows, [30, 50, 20])]
        if key == "batch":
            text, mod = find("BATCH_COLUMNS", fastrock.run_batch,
                             lambda v: isinstance(v, str) and "scene" in v)
            return self._described(text, "BATCH_COLUMNS", mod)
        if key == "models":
            return self._models()
        if key == "statuses":
            return self._statuses()
        raise self.error(f"unknown column table {key!r}")

    def _described(self, text, attr, mod):
        rows = parse_columns(text)
        return [_source_note(attr, mod),
                _table(["column", "meaning", "unit"],
                       [(_names_cell(n), m, u) for n, m, u in rows], [30, 55, 15])]

    def _statuses(self):
        status, mod = find("STATUS", fastrock.simulate,
                           lambda v: isinstance(v, dict) and "safe:rest" in v.values())
        module = importlib.import_module(mod)
        described = getattr(module, "STATUS_DESCRIPTION", {})
        outcome_of = module.outcome_of
        rows = [(nodes.literal(text=outcome_of(code)), nodes.literal(text=name),
                 described.get(name, ""))
                for code, name in status.items()]
        return [_source_note("STATUS", mod),
                _table(["outcome", "status", "meaning"], rows, [15, 30, 55])]

    def _models(self):
        reg = find_registry()
        spec, _ = find("SPECTRUM_COLUMNS", fastrock.overturning_spectrum,
                       lambda v: isinstance(v, str) and "amplitude_ratio" in v)
        described = _by_name(parse_columns(spec))
        rows = []
        for name, model in reg.MODELS.items():
            effects = ", ".join(sorted(model.effects)) or "none"
            cols = []
            for c in model.columns:
                unit = described.get(c, ("", ""))[1]
                if cols:
                    cols.append(nodes.Text(", "))
                cols.append(nodes.literal(text=c))
                if unit:
                    cols.append(nodes.Text(f" [{unit}]"))
            rows.append((nodes.literal(text=name), model.body, effects,
                         _names_cell(", ".join(model.state_names)),
                         cols or "none", ", ".join(model.outcomes)))
        return [_source_note("MODELS", reg.__name__),
                _table(["model", "body", "effects", "state", "added columns [unit]", "outcomes"],
                       rows, [14, 8, 14, 18, 30, 16])]


def _by_name(rows):
    out = {}
    for names, meaning, unit in rows:
        parts = [n.strip() for n in names.split(",") if n.strip()]
        units = [u.strip() for u in unit.split(",")] if unit else []
        for i, n in enumerate(parts):
            u = units[i] if len(units) == len(parts) else unit
            out[n] = (meaning, u)
    return out


class CliDirective(Directive):
    """The help of ``fastrock`` and of each subcommand, one section each."""
    has_content = False
    option_spec = {"heading-level": directives.unchanged}

    def run(self):
        import argparse
        os.environ["COLUMNS"] = "100"
        parser = find_parser()()
        out = [nodes.literal_block(text=parser.format_help().rstrip())]
        sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        for name, cmd in sub.choices.items():
            section = nodes.section(ids=[f"cli-{name}"], names=[f"fastrock {name}"])
            section += nodes.title(text=f"fastrock {name}")
            section += nodes.literal_block(text=cmd.format_help().rstrip())
            self.state.document.note_implicit_target(section)
            out.append(section)
        return out


def setup(app):
    app.add_directive("fastrock-columns", ColumnsDirective)
    app.add_directive("fastrock-cli", CliDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
