"""Sphinx configuration of vofdem's documentation site (`make docs`).

The site is built from the repository's root (`sphinx-build -c docs . build/docs/html`) so that the
guide's pages in docs/, the index pages and results files of benchmarks/ (speed and cost), validation/ and
studies/ (the prediction studies) they link to and the notebooks in notebooks/ are all pages of it, each at its path in the repository; only the files matched by
`include_patterns` are read. The API reference (docs/api.md) is generated from the docstrings of the
installed package `vofdem` and of its pybind11 extension `vofdem._core`. The notebooks are rendered
as committed, without executing them (the test suite executes them).
"""
from __future__ import annotations

import vofdem

project = "vofdem"
author = "the vofdem developers"
copyright = "2026, the vofdem developers"
release = version = vofdem.__version__

extensions = ["myst_nb", "sphinx.ext.autodoc", "sphinx.ext.mathjax"]
root_doc = "docs/index"
include_patterns = ["docs/*.md", "notebooks/*.ipynb", "CHANGELOG.md"] + [
    f"{folder}/{page}" for folder in ("benchmarks", "validation", "studies") for page in ("README.md", "results/*.md")]
exclude_patterns = ["build", "out", ".git", "**/.ipynb_checkpoints"]

# markdown: MyST; headings get anchors so that links to a page's section resolve
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
nb_execution_mode = "off"

autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"

html_theme = "alabaster"
html_title = f"vofdem {release}"
html_extra_path = ["_extra"]  # relative to this folder: the root page that leads to docs/index.html
html_theme_options = {"description": "VOF-DEM model of a rubble mound weir's destruction", "page_width": "1200px",
                      "body_max_width": "none"}
