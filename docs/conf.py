"""Sphinx configuration of asperity's documentation site.

Build (from the repository root, after ``pip install -e '.[docs]'``)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Warnings are errors: a broken cross-reference, an example that fails, a public name without
an API page, a command without its reference, a docstring missing a numpydoc section.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path[:0] = [str(ROOT), str(HERE / "_ext")]

import asperity
from asperity_docs import NUMPYDOC_CHECKS  # the same checks as tests/test_api_docs.py

project = "asperity"
author = "the asperity developers"
copyright = "2026, the asperity developers"
release = version = asperity.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",            # MathJax served from the site (no CDN, works offline)
    "matplotlib.sphinxext.plot_directive",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "asperity_docs",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "_run", "examples/*.md", "examples/*.rst", "Thumbs.db",
                    ".DS_Store"]
templates_path = ["_templates"]

# --- MyST (the prose pages are Markdown)
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist", "attrs_inline"]
myst_heading_anchors = 3

# --- cross-references: every reference inside the site must resolve (nitpicky), those to
# outside libraries are plain text (the build reaches no network, so no intersphinx)
nitpicky = True
nitpick_ignore_regex = [(r"py:.*", r"^(?!asperity\.).*")]

# --- API reference
autosummary_generate = True
autodoc_typehints = "none"           # the numpydoc Parameters section gives the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

# ASPERITY_DOCS_QUICK=1: no numpydoc validation and no gallery run (a draft build of the
# prose pages; CI builds without it)
QUICK = os.environ.get("ASPERITY_DOCS_QUICK") == "1"
numpydoc_validation_checks = set() if QUICK else set(NUMPYDOC_CHECKS)
# public names only (asperity.X); their methods and the private modules are not checked
numpydoc_validation_exclude = {r"^asperity\.\w+\.\w+"}

# --- gallery: every example runs at build time and draws its figures
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r".*\.py$",      # execute them all
    "within_subsection_order": "FileNameSortKey",   # plot_01 ... plot_09: the pipeline's order
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "plot_gallery": not QUICK,
}

# --- figures drawn at build time (``{plot}``)
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 110)]

# --- HTML
html_theme = "furo"
html_title = f"asperity {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
