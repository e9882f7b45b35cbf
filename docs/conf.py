"""Sphinx configuration of the isoslide documentation.

Build with ``python -m sphinx -W -b html docs docs/_build/html`` (warnings are errors).
The API pages are generated on every build from the package's docstrings
(``sphinx.ext.autosummary`` with ``:recursive:`` over :mod:`isoslide`), so a module added
or moved is documented without editing these files.
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))  # a source checkout documents itself, installed or not

import isoslide  # noqa: E402

project = "isoslide"
author = "the isoslide authors"
copyright = "the isoslide authors, MIT licence"
release = isoslide.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "isoslide_docs",
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
root_doc = "index"

# API: one page per module, generated from the docstrings at build time into api/ (git-ignored).
autosummary_generate = True
autosummary_imported_members = False
autosummary_ignore_module_all = True
autodoc_default_options = {"members": True, "undoc-members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # numpydoc sections already give the types

# numpydoc renders the docstrings' sections; members are listed by autodoc on the module page.
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

html_theme = "alabaster"
html_title = f"isoslide {release}"
html_static_path = []
html_theme_options = {"description": "exact stick-slip sliding of contents on isolated floors"}
nitpicky = False
