"""Trusses read from the thesis: consistent, Baranov, and found in the catalog."""

from pathlib import Path

import numpy as np
import pytest

from baranov.catalog import iter_objects
from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import (
    THESIS_TRUSSES,
    thesis_joint_names,
    thesis_name,
    thesis_truss,
)
from baranov.topology import (
    TopologyError,
    chain_from_links,
    is_baranov_truss,
    joint_graph,
)


@pytest.mark.parametrize("published", THESIS_TRUSSES, ids=lambda t: t.name)
def test_thesis_truss_is_a_baranov_truss(published):
    chain = published.chain()
    assert is_baranov_truss(chain)
    assert [j.name for j in chain.joints] == [f"P{k}" for k in range(1, chain.number_of_joints + 1)]


def test_exactly_one_nine_link_truss_is_named_and_it_is_non_planar():
    from baranov.topology import is_planar

    named = [t for t in baranov_trusses(9) if thesis_name(t) is not None]
    assert [thesis_name(t).name for t in named] == ["9/B28"]
    assert not is_planar(named[0])  # thesis §3.4.1: 9/B28 is one of the three non-planar trusses


@pytest.mark.parametrize("links", [3, 5, 7])
def test_every_catalog_truss_gets_a_distinct_thesis_name(links):
    names = [thesis_name(t).name for t in baranov_trusses(links)]
    assert sorted(names) == sorted(t.name for t in THESIS_TRUSSES if t.name.startswith(f"{links}/"))


def test_degree_sequences_match_the_thesis_descriptions():
    # §3.3: 7/B1 and 7/B2 have four ternary and three binary links; 7/B3 one quaternary,
    # two ternary and four binary links.
    assert sorted(thesis_truss("7/B1").chain().link_degrees) == [2, 2, 2, 3, 3, 3, 3]
    assert sorted(thesis_truss("7/B2").chain().link_degrees) == [2, 2, 2, 3, 3, 3, 3]
    assert sorted(thesis_truss("7/B3").chain().link_degrees) == [2, 2, 2, 2, 3, 3, 4]


@pytest.mark.parametrize("links", [3, 5, 7])
def test_thesis_joint_names_are_an_isomorphism(links):
    for truss in baranov_trusses(links):
        published = thesis_name(truss)
        mapping = thesis_joint_names(truss, published)
        ours, theirs = joint_graph(truss), joint_graph(published.chain())
        assert sorted(mapping.values()) == sorted(theirs.nodes)
        assert {frozenset((mapping[u], mapping[v])) for u, v in ours.edges} == {frozenset(e) for e in theirs.edges}


def test_unknown_name_and_non_isomorphic_chain():
    with pytest.raises(ValueError, match="9/B1"):
        thesis_truss("9/B1")
    with pytest.raises(ValueError, match="not isomorphic to 7/B1"):
        thesis_joint_names(baranov_trusses(7)[0], thesis_truss("7/B1"))


@pytest.mark.parametrize(
    ("links", "message"),
    [
        ([("P1", "P2"), ("P2", "P3"), ("P3", "P1", "P2")], "joint P2: lies on 3 links"),
        ([("P1", "P1"), ("P1", "P2")], "link L0: a joint is listed twice"),
    ],
)
def test_chain_from_links_errors(links, message):
    with pytest.raises(TopologyError, match=message):
        chain_from_links(links)


def test_nine_link_names_by_invariants():
    """The catalog's (assembly modes, coupling degree, planarity) of the 28 nine-link
    trusses equal the thesis's as a multiset, and every thesis name given has its
    truss's signature; all 28 names are given, once each."""
    from collections import Counter

    from baranov.literature.trusses import APPENDIX_A_ASSEMBLY_MODES, nine_link_signature

    entries = list(iter_objects(Path(__file__).resolve().parents[1] / "catalog" / "trusses-9.jsonl"))
    ours = Counter((e["realization_count"], e["coupling_degree"], e["planar"]) for e in entries)
    assert ours == Counter(nine_link_signature(name) for name in APPENDIX_A_ASSEMBLY_MODES)
    named = {e["name"]: (e["realization_count"], e["coupling_degree"], e["planar"]) for e in entries}
    assert sorted(named) == sorted(APPENDIX_A_ASSEMBLY_MODES)
    assert all(nine_link_signature(name) == signature for name, signature in named.items())
    assert all(e["assembly_modes"] in (None, APPENDIX_A_ASSEMBLY_MODES[e["name"]]) for e in entries)


def test_appendix_a_transcription_is_a_vector_identity():
    """s_{u,v} = det(Ω) s_ref holds at any point configuration when Ω is transcribed
    right (a wrong index breaks the vector sum it stands for)."""
    from baranov.closure.evaluate import condition_residual_at_configuration
    from baranov.literature.appendix_a import APPENDIX_A_CONDITIONS, appendix_a_conditions

    rng = np.random.default_rng(5)
    assert sorted(APPENDIX_A_CONDITIONS, key=lambda n: int(n[3:])) == [f"9/B{n}" for n in range(1, 29)]
    for name in APPENDIX_A_CONDITIONS:
        points = {f"P{k}": rng.normal(size=2) * 10 for k in range(1, 13)}
        for condition in appendix_a_conditions(name):
            assert abs(condition_residual_at_configuration(condition, points)) < 1e-10, name


def test_appendix_a_conditions_of_9b1_to_9b24_fit_one_truss_each():
    """Each coupling-1 thesis truss's conditions fit exactly one catalog truss, and no two
    fit the same one: the names do not depend on the invariants."""
    from baranov.literature.appendix_a import appendix_a_labelling

    trusses = baranov_trusses(9)
    fits = {f"9/B{n}": [i for i, t in enumerate(trusses) if appendix_a_labelling(t, f"9/B{n}")] for n in range(1, 25)}
    assert all(len(found) == 1 for found in fits.values()), fits
    assert len({found[0] for found in fits.values()}) == 24


def test_appendix_a_labelling_is_consistent_with_the_catalog():
    """The catalog's thesis joint names are a labelling under which the named truss's
    Appendix A conditions fit (known pairs on links, unknown ones not)."""
    from baranov.literature.appendix_a import link_pairs_required

    entries = list(iter_objects(Path(__file__).resolve().parents[1] / "catalog" / "trusses-9.jsonl"))
    trusses = baranov_trusses(9)
    checked = 0
    for entry, truss in zip(entries, trusses, strict=True):
        if not (entry["name_evidence"] or "").startswith("thesis Appendix A"):
            continue
        to_catalog = {thesis: joint for joint, thesis in entry["thesis_joint_names"].items()}
        graph = joint_graph(truss)
        on_link, off_link = link_pairs_required(entry["name"])
        assert all(graph.has_edge(*(to_catalog[j] for j in pair)) for pair in on_link)
        assert not any(graph.has_edge(*(to_catalog[j] for j in pair)) for pair in off_link)
        checked += 1
    assert checked == 27  # all but 9/B28, named by isomorphism


def test_appendix_a_unknown_name():
    from baranov.literature.appendix_a import appendix_a_conditions

    with pytest.raises(ValueError, match="9/B29"):
        appendix_a_conditions("9/B29")
