"""Sphinx configuration of crankbalance's documentation site.

Build it with ``python -m sphinx -W -b html docs docs/_build/html`` (the ``docs`` extra;
``.ci/run`` builds it with warnings as errors). The Markdown documents of ``docs/`` are read
by myst-parser, the API reference is generated from the numpydoc docstrings (autosummary),
and the scripts of ``examples/`` are run and shown with their output by sphinx-gallery.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))  # the clone's code, installed or not

import crankbalance  # noqa: E402

project = "crankbalance"
author = "the crankbalance developers"
copyright = "crankbalance developers, MIT licence"
version = release = crankbalance.__version__

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = [
    "_build",
    "sg_execution_times.rst",
    "gallery/*.ipynb",
    "gallery/*.py.md5",
    "gallery/*.codeobj.json",
]
root_doc = "index"
# theory.md goes from ## to ####; numpydoc numbers the References of a docstring whether or
# not the text cites them
suppress_warnings = ["myst.header", "ref.citation"]

# myst-parser: `$...$` maths as in the Markdown documents, headings linkable
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3

# autosummary writes one page per public object of the modules listed in api.rst
autosummary_generate = True
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"  # the numpydoc docstrings give the types and their units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "gallery",
    "filename_pattern": r".*\.py$",  # every example is run, not only plot_*.py
    # the examples print their results and write their figures to files (docs/_gallery.py)
    "image_scrapers": ("_gallery.png_scraper",),
    "download_all_examples": False,
    "reset_modules": (),
    "abort_on_example_error": True,
    "min_reported_time": 5,
}

html_theme = "alabaster"
html_title = f"crankbalance {release}"
html_static_path: list[str] = []
# wide enough for the tables the examples print and the README's commands
html_theme_options = {"page_width": "1300px", "sidebar_width": "270px"}

sys.path.insert(0, str(Path(__file__).resolve().parent))  # _gallery.py, named below by string
sphinx_gallery_conf["reset_argv"] = "_gallery.reset_argv"


def _skip_type_helpers(app: object, what: str, name: str, obj: object, skip: bool, options: object):
    """Leave type variables and type aliases (``Scalar``, ``Batch``) out of the reference:
    they are annotations' helpers, not API, and have no numpydoc docstring."""
    import types
    import typing

    if isinstance(obj, typing.TypeVar | types.GenericAlias) or type(obj).__module__ == "typing":
        return True
    return None


def setup(app: object) -> None:
    app.connect("autodoc-skip-member", _skip_type_helpers)  # type: ignore[attr-defined]
