"""Sphinx configuration of the fastrock documentation.

Build: ``pip install '.[docs]'`` then ``sphinx-build -W --keep-going -b html docs docs/_build/html``.
"""
import os
import sys

sys.path.insert(0, os.path.abspath("_ext"))

# The fastrock that Python finds (the installed or editable package, as the tests import it, so
# the doctests load the kernels the tests compiled into the cache); without one, the source tree
# this folder belongs to (fastrock imports from the repository root).
try:
    import fastrock
except ImportError:
    sys.path.insert(0, os.path.abspath(".."))
    import fastrock

project = "fastrock"
author = "the fastrock authors"
copyright = "2026, the fastrock authors"
release = fastrock.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.doctest",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "fastrock_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "gallery/*.ipynb", "gallery/*.py",
                    "gallery/*.zip", "gallery/*.json", "gallery/*.md5"]

# MyST: $...$ and $$...$$ maths, ::: fences, and heading anchors for links between pages.
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

# API reference: every name of fastrock.__all__, documented as fastrock.<Name>.  The modules
# behind them move; the top-level names do not.
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()
# Every cross-reference must resolve (nitpicky), except these: classes of pandas and matplotlib
# (no intersphinx: the build runs offline) and names the docstrings cite that live in fastrock's
# modules but are not part of the top-level API documented here.
nitpicky = True
nitpick_ignore = [
    ("py:class", "pandas.DataFrame"),
    ("py:class", "matplotlib.figure.Figure"),
]
nitpick_ignore_regex = [
    # module-level helpers and constants named in docstrings (fastrock.<module>.<name>)
    ("py:(func|class|data|exc)", r"(fastrock\.[\w.]+\.)?(load_results|load_yu2019|"
     r"housner_half_cycle_durations|plot_history|RecordFormatError|PGA_PLAUSIBLE_G|MEASURES|"
     r"DefinitionWarning|DEFAULT_CHUNK_SIZE)"),
]


# Doctests: docstring examples and the ``{doctest}`` blocks of the pages run with
# ``sphinx-build -b doctest``; the kernels they call compile once and stay in Numba's cache.
doctest_global_setup = """
import numpy as np
import fastrock as fr
from fastrock import *
"""
doctest_test_doctest_blocks = "default"

# Gallery: the example scripts are shown with their description and figures, not executed here
# (each compiles several Numba kernels and runs minutes of sweeps; CI keeps the docs step short).
sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"^$",
    "plot_gallery": "False",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "copyfile_regex": "",
}

html_theme = "furo"
html_title = f"fastrock {release}"
html_static_path = []
templates_path = ["_templates"]


def _write_api_index():
    """api/index.rst from ``fastrock.__all__``: every public name, documented as
    ``fastrock.<Name>``, so the reference cannot drift from the package."""
    import inspect
    classes, functions, data = [], [], []
    for name in fastrock.__all__:
        obj = getattr(fastrock, name)
        if inspect.isclass(obj):
            classes.append(name)
        elif callable(obj):
            functions.append(name)
        else:
            data.append(name)

    def block(title, names):
        lines = [title, "-" * len(title), "", ".. autosummary::", "   :toctree: generated",
                 "   :nosignatures:", ""]
        return lines + [f"   {n}" for n in names] + [""]

    lines = ["API reference", "=============", "",
             "Every public name of fastrock is importable from the top level "
             "(``import fastrock as fr``; ``fastrock.__all__``). This page is generated from "
             "``fastrock.__all__`` and the numpydoc docstrings at build time.", "",
             ".. currentmodule:: fastrock", ""]
    lines += block("Classes", classes) + block("Functions", functions)
    lines += ["Constants", "---------", ""]
    for name in data:
        value = getattr(fastrock, name)
        lines += [f".. py:data:: {name}", f"   :value: {value!r}", ""]
        if name == "G_STANDARD":
            lines += ["   Standard gravity [m/s²]: g everywhere in fastrock, and the unit \"g\" "
                      "of amplitudes and records.", ""]
    lines += ["Returned tables", "---------------", "",
              "The columns of every returned table are listed in :doc:`tables`.", "",
              ".. toctree::", "   :hidden:", "", "   tables", ""]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "api", "index.rst")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    text = "\n".join(lines)
    old = open(path).read() if os.path.exists(path) else None
    if old != text:
        with open(path, "w") as f:
            f.write(text)


_write_api_index()
