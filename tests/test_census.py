"""The census of a link count (catalog/census.py, issue 20): counts by two methods, the
invariants and the coupling-degree sample agree with the catalog's entries where both
exist; a Dask run equals a serial one; an interrupted census resumes from its shards."""

import json
from collections import Counter
from pathlib import Path

import pytest

from baranov.catalog import census as census_module
from baranov.catalog.census import in_sample, truss_census, wilson_interval
from baranov.catalog.entries import load_entries
from baranov.catalog.summary import render_summary
from baranov.catalog.tasks import dask_client
from baranov.enumerate.crosscheck import find_geng

CATALOG = Path(__file__).resolve().parents[1] / "catalog"
needs_geng = pytest.mark.skipif(find_geng() is None, reason="geng not installed (make test installs it)")


class Interrupted(Exception):
    pass


def _without_sample_list(census: dict) -> dict:
    census = json.loads(json.dumps(census))
    census["coupling_degree_sample"].pop("sample")
    return census


@needs_geng
@pytest.mark.parametrize(("links", "sample_bits"), [(7, 0), (9, 0), (11, 3)])
def test_the_census_agrees_with_the_catalog_entries(links, sample_bits):
    entries = load_entries(CATALOG / f"trusses-{links}.jsonl")
    census = truss_census(links, None, sample_bits=sample_bits, split_level=links // 2, parts=4)
    assert census["trusses"] == len(entries) and census["distinct_classes"]
    assert census["assur_groups"] == sum(e["assur_groups"] for e in entries)
    assert census["non_planar"] == sum(not e["planar"] for e in entries)
    assert census["automorphism_group_orders"] == {
        str(k): v for k, v in sorted(Counter(e["automorphism_group_order"] for e in entries).items())}
    assert census["largest_link_degree"] == {
        str(k): v for k, v in sorted(Counter(max(e["link_degrees"]) for e in entries).items())}
    assert census["method_b"]["trusses"] == len(entries) and census["method_b"]["same_isomorphism_classes"]
    sample = census["coupling_degree_sample"]
    degrees = {e["link_graph6"]: e["coupling_degree"] for e in entries}
    assert sample["sample"] == {graph6: degrees[graph6] for graph6 in sample["sample"]}
    if sample_bits == 0:
        assert len(sample["sample"]) == len(entries)
    else:
        assert 0 < len(sample["sample"]) < len(entries)


def test_sampling_takes_the_share_it_says():
    digests = [f"{n << 20:08x}" + "f" * 16 for n in range(4096)]  # every value of the top 12 bits once
    assert sum(in_sample(d, 4) for d in digests) == 256
    assert all(in_sample(d, 0) for d in digests)


def test_wilson_intervals_hold_the_share_and_stay_in_0_1():
    for successes, trials in [(0, 10), (10, 10), (3, 7), (500, 1000)]:
        low, high = wilson_interval(successes, trials)
        assert 0 <= low <= successes / trials <= high <= 1
    assert wilson_interval(0, 0) == (0.0, 1.0)


@needs_geng
def test_a_dask_census_equals_a_serial_one():
    serial = truss_census(9, None, sample_bits=1, split_level=5, parts=4)
    with dask_client(2) as client:
        distributed = truss_census(9, None, client, sample_bits=1, split_level=5, parts=4)
    assert json.dumps(distributed) == json.dumps(serial)


@needs_geng
def test_an_interrupted_census_resumes_from_its_shards(tmp_path, monkeypatch):
    reference = truss_census(9, None, sample_bits=1, split_level=6)

    def interrupted(graph6):
        raise Interrupted

    monkeypatch.setattr(census_module, "sample_coupling_degree", interrupted)
    with pytest.raises(Interrupted):
        truss_census(9, tmp_path / "shards", sample_bits=1, split_level=6)
    assert (tmp_path / "shards" / "method-a").is_dir() and (tmp_path / "shards" / "method-b").is_dir()
    monkeypatch.undo()
    monkeypatch.setattr(census_module, "subtree_census", interrupted)  # method A must be read back
    assert truss_census(9, tmp_path / "shards", sample_bits=1, split_level=6) == reference
    assert not (tmp_path / "shards").exists()


def test_the_summary_has_a_row_for_a_census(tmp_path):
    census = truss_census(7, None, sample_bits=0, split_level=3, crosscheck=False)
    (tmp_path / "census-7.json").write_text(census_module.dump_census(census))
    summary = render_summary(tmp_path, {})
    assert "| 7 | 3 | — | 3 | 10 | 10 | — | — |" in summary
    assert "| 7 | random sample of 3 trusses" in summary
    assert "1: 3 (" in summary


def test_the_summary_reads_a_compact_file_without_its_full_one(tmp_path):
    """13 links commit only ``trusses-13.jsonl.gz``: its coupling degrees and assembly
    modes reach the summary (here the 9-link entries, cut to the compact fields)."""
    from baranov.catalog.entries import compact_entries, dump_entries
    from baranov.catalog.files import gzipped

    entries = load_entries(CATALOG / "trusses-9.jsonl")
    compact = compact_entries(entries)
    (tmp_path / "trusses-9.jsonl.gz").write_bytes(gzipped(dump_entries(compact)))
    summary = render_summary(tmp_path, {})
    assert "| 9 | 1: 24, 2: 4 | 1: 24, 2: 4 |" in summary  # coupling degrees, beside Yang & Yao's
    modes = Counter(e["assembly_modes"] for e in entries)
    row = "| 9 | " + ", ".join(f"{k}: {v}" for k, v in sorted(modes.items())) + " | "
    assert row in summary and summary.split(row)[1].split("\n")[0].endswith("| 28 | 28 |")
