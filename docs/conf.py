"""Sphinx configuration: the user guide, the API reference built from the docstrings
(numpydoc), the design notes and a gallery of the paper's figures made by scripts.

Built by ``python3 tasks.py test`` (warnings are errors) and ``python3 tasks.py docs``."""

from __future__ import annotations

import os
import sys

sys.path.insert(0, os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "src")))
os.environ.setdefault("MPLBACKEND", "Agg")

project = "fcgrasp"
author = "fcgrasp developers"
copyright = "2026, fcgrasp developers"
extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
    "matplotlib.sphinxext.plot_directive",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "**/_build"]
myst_heading_anchors = 3
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
autodoc_default_options = {"members": True, "undoc-members": False}
autodoc_member_order = "bysource"
autodoc_typehints = "none"
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 90)]
html_theme = "alabaster"
html_static_path: list[str] = []
suppress_warnings = ["myst.header"]
