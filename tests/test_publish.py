"""Tests for :mod:`baranov.catalog.publish`: a separate job's compact file and cross-check
moved into the catalog, the summary regenerated from them."""

import json
from pathlib import Path

import pytest

from baranov.catalog.entries import compact_entries, dump_entries, load_entries
from baranov.catalog.files import gzipped
from baranov.catalog.publish import UnfinishedCatalogError, main, publish_link_count

CATALOG = Path(__file__).resolve().parents[1] / "catalog"


def _job_folder(folder: Path) -> Path:
    """A finished 9-link job's folder: its compact file and its cross-check (the
    committed 9-link catalog stands in for a 13-link job)."""
    folder.mkdir()
    entries = load_entries(CATALOG / "trusses-9.jsonl")
    (folder / "trusses-9.jsonl.gz").write_bytes(gzipped(dump_entries(compact_entries(entries))))
    checks = json.loads((CATALOG / "crosscheck.json").read_text(encoding="utf-8"))
    (folder / "crosscheck.json").write_text(json.dumps({"9": checks["9"]}), encoding="utf-8")
    return folder


def test_the_summary_rows_come_from_the_published_files(tmp_path):
    job, catalog = _job_folder(tmp_path / "job"), tmp_path / "catalog"
    catalog.mkdir()
    seven = json.loads((CATALOG / "crosscheck.json").read_text(encoding="utf-8"))["7"]
    (catalog / "crosscheck.json").write_text(json.dumps({"7": seven}), encoding="utf-8")
    account = publish_link_count(job, catalog, 9)
    assert account == f"9 links: 28 trusses (28 with assembly modes) published in {catalog}"
    assert (catalog / "trusses-9.jsonl.gz").read_bytes() == (job / "trusses-9.jsonl.gz").read_bytes()
    checks = json.loads((catalog / "crosscheck.json").read_text(encoding="utf-8"))
    assert checks["7"] == seven and checks["9"]["same_isomorphism_classes"] is True
    summary = (catalog / "summary.md").read_text(encoding="utf-8")
    committed = (CATALOG / "summary.md").read_text(encoding="utf-8").splitlines()
    # Counts (no slider chains in a compact file), invariants, coupling and modes as committed.
    assert "| 9 | 28 | 28 (of 707 candidates; same classes: yes) | 28 | 173 | 173 | — | — |" in summary
    for prefix in ("| 9 | 3 | ", "| 9 | 1: 24, 2: 4 |", "| 9 | 30: 1, "):
        assert [line for line in committed if line.startswith(prefix)][0] in summary.splitlines()


def test_an_unfinished_job_is_refused_and_nothing_is_written(tmp_path, capsys):
    job, catalog = tmp_path / "job", tmp_path / "catalog"
    job.mkdir()
    catalog.mkdir()
    (job / "trusses-13.jsonl.gz").write_bytes(gzipped('{"id": "13/N1"}\n'))  # lacks the compact fields
    with pytest.raises(UnfinishedCatalogError, match="no complete trusses-13.jsonl.gz"):
        publish_link_count(job, catalog, 13)
    assert list(catalog.iterdir()) == []
    assert main([str(job), str(catalog), "13"]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and error.count("\n") == 1
    assert main([str(job), str(catalog), "thirteen"]) == 2


def test_the_committed_summary_is_what_the_committed_files_say():
    """``catalog/summary.md`` is regenerated, never edited: rendering it again from the
    committed files (the 13-link compact file and cross-check included) gives the same text."""
    from baranov.catalog.build import read_crosschecks
    from baranov.catalog.summary import render_summary

    assert render_summary(CATALOG, read_crosschecks(CATALOG)) == (CATALOG / "summary.md").read_text(encoding="utf-8")
