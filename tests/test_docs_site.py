"""The documentation site (docs/conf.py; `make docs`): it builds with Sphinx, warnings
treated as errors, the gallery's scripts not run (`make docs-quick`), and its generated
pages are there: the command-line reference from the parser, a page per truss to 11 links
and the 13-link table, from the catalog files. Skipped where the `docs` extra is not
installed."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("sphinx_gallery")

REPO = Path(__file__).resolve().parents[1]


def test_the_site_builds_without_warnings(tmp_path):
    html = tmp_path / "html"
    result = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                             "-D", "plot_gallery=0", "docs", str(html)], cwd=REPO, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr[-4000:]
    for page in ("index", "solving", "reference/api", "generated/cli", "generated/catalog",
                 "generated/catalog-13", "auto_examples/index"):
        assert (html / f"{page}.html").exists(), page
    assert "baranov solve" in (html / "generated" / "cli.html").read_text(encoding="utf-8")
    assert "13/N206" in (html / "generated" / "catalog-13.html").read_text(encoding="utf-8")
