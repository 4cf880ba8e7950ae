"""Sphinx configuration of baranov's documentation site (``make docs``).

The pages are the Markdown files of docs/ (myst-parser); the API reference comes from the
docstrings (autodoc, numpydoc), the gallery from docs/gallery/ (sphinx-gallery, run at
build time unless ``-D plot_gallery=0``), and the CLI reference and the catalog pages are
generated before the build from the parser and the catalog files (docs/site/generate.py,
run by the ``builder-inited`` hook below), never written by hand.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "site"))

project = "baranov"
author = "the baranov developers"
copyright = "2026, the baranov developers"
try:
    from baranov import __version__ as release
except ImportError:  # pragma: no cover - the docs are built with the package installed
    release = "unknown"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
# the measurement fragments without a title of their own are pages of docs/stability.md
# (copied there by bench/stability.py), not pages of the site
FRAGMENTS = [f"bench/{page.name}" for page in sorted((HERE / "bench").glob("*.md"))
             if not page.read_text(encoding="utf-8").startswith("# ")]
exclude_patterns = ["_build", "site", "gallery/README.txt", "Thumbs.db", ".DS_Store", *FRAGMENTS]

myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3

html_theme = "furo"
html_title = f"baranov {release}"
html_static_path: list[str] = []

autodoc_member_order = "bysource"
autodoc_typehints = "description"
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()

sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"(__init__|_paths)\.py",
    "download_all_examples": False,
    "remove_config_comments": True,
}


def setup(app):
    from generate import generate_pages

    app.connect("builder-inited", lambda app: generate_pages(HERE))
