"""Sphinx configuration of crankbalance's documentation site.

Build it with ``python -m sphinx -W -b html docs docs/_build/html`` (the ``docs`` extra;
``.ci/run`` builds it with warnings as errors). The Markdown documents of ``docs/`` are read
by myst-parser (through myst-nb), the API reference is generated from the numpydoc docstrings
(autosummary), the scripts of ``examples/`` are run and shown with their output by
sphinx-gallery, and the tutorials (``docs/tutorials/``, MyST text notebooks) and the
validation page are executed by myst-nb in a Jupyter kernel at every build.
"""

from __future__ import annotations

import os
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
    "myst_nb",  # myst-parser for the Markdown documents, and the executed notebooks
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}
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

# myst-nb: the text notebooks (tutorials/*.md, validation_tables.md) are run at every build in
# their own folder (so a tutorial reads ../../examples/), and an error in a cell fails the
# build; NOTEBOOK_GUARD [s] only ends a cell that hangs
NOTEBOOK_GUARD = 600
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_timeout = NOTEBOOK_GUARD
nb_merge_streams = True
# a Markdown output (the validation page's tables) is read as MyST, tables included
nb_render_markdown_format = "myst"
# plotly's figures as HTML drawn by plotly.js, which the first figure of a page embeds (no
# address outside the site); in Jupyter itself the default renderer is left as it is. The
# kernel inherits this environment.
os.environ.setdefault("PLOTLY_RENDERER", "plotly_mimetype+notebook")
# The page shows that HTML; plotly's JSON beside it (for JupyterLab) has no renderer here
# and is left out without a warning. A figure without its HTML would then be missing from
# its page: tests/web/test_docs_site.py checks each tutorial's figures are drawn.
suppress_warnings.append("mystnb.unknown_mime_type")

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
