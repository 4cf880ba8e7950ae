"""Automorphism groups, orbits, canonical forms; thesis §2.7.1 and independent oracles."""

import random

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from networkx.algorithms.isomorphism import GraphMatcher

from baranov.enumerate import baranov_trusses
from baranov.topology import (
    are_isomorphic,
    automorphism_group,
    canonical_link_graph6,
    certificate,
    chain_from_link_graph,
    link_graph,
    list_automorphisms,
)

#: Thesis §2.7.1: the twelve automorphisms of the pentad as joint permutations
#: (position k holds the image of P(k+1)).
THESIS_PENTAD_AUTOMORPHISMS = {
    (1, 2, 3, 4, 5, 6), (1, 3, 2, 4, 6, 5), (2, 1, 3, 5, 4, 6), (2, 3, 1, 5, 6, 4),
    (3, 1, 2, 6, 4, 5), (3, 2, 1, 6, 5, 4), (4, 5, 6, 1, 2, 3), (4, 6, 5, 1, 3, 2),
    (5, 4, 6, 2, 1, 3), (5, 6, 4, 2, 3, 1), (6, 4, 5, 3, 1, 2), (6, 5, 4, 3, 2, 1),
}


def test_pentad_has_the_thesis_twelve_automorphisms(pentad):
    group = automorphism_group(pentad)
    assert group.order == 12
    found = {tuple(int(name[1:]) for name in a.joints) for a in list_automorphisms(pentad)}
    assert found == THESIS_PENTAD_AUTOMORPHISMS


def test_pentad_orbits(pentad):
    group = automorphism_group(pentad)
    assert group.link_orbits == ((0, 1), (2, 3, 4))
    assert group.joint_orbits == (("P1", "P2", "P3", "P4", "P5", "P6"),)


def test_sliders_break_symmetry(pentad):
    assert automorphism_group(pentad.with_joint_kinds(["P1"])).order == 2  # swap the two other bars
    assert automorphism_group(pentad.with_joint_kinds(["P1", "P4"])).order == 4
    assert not are_isomorphic(pentad, pentad.with_joint_kinds(["P1"]))


def vf2_automorphism_count(chain) -> int:
    graph = link_graph(chain)
    return sum(1 for _ in GraphMatcher(graph, graph).isomorphisms_iter())


@pytest.mark.parametrize("links", [3, 5, 7, 9])
def test_group_orders_agree_with_networkx_vf2(links):
    for truss in baranov_trusses(links):
        assert automorphism_group(truss).order == vf2_automorphism_count(truss)


@pytest.mark.parametrize("links", [7, 9])
def test_every_listed_element_is_an_automorphism(links):
    for truss in baranov_trusses(links):
        graph = link_graph(truss)
        elements = list_automorphisms(truss)
        assert len(elements) == automorphism_group(truss).order
        assert len({e.links for e in elements}) == len(elements)
        for element in elements:
            images = {tuple(sorted((element.links[u], element.links[v]))) for u, v in graph.edges}
            assert images == {tuple(sorted(e)) for e in graph.edges}
            for joint, image in zip(truss.joints, element.joints, strict=True):
                mapped = tuple(sorted(element.links[link] for link in joint.links))
                assert truss.joint(image).links == mapped


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(baranov_trusses(9)), st.randoms(use_true_random=False))
def test_invariants_do_not_depend_on_labelling(truss, rng: random.Random):
    relabel = list(range(truss.number_of_links))
    rng.shuffle(relabel)
    shuffled = chain_from_link_graph([(relabel[j.links[0]], relabel[j.links[1]]) for j in truss.joints])
    assert are_isomorphic(truss, shuffled)
    assert certificate(truss) == certificate(shuffled)
    assert canonical_link_graph6(truss) == canonical_link_graph6(shuffled)
    original, permuted = automorphism_group(truss), automorphism_group(shuffled)
    assert original.order == permuted.order
    assert sorted(map(len, original.link_orbits)) == sorted(map(len, permuted.link_orbits))
    assert sorted(sorted(relabel[link] for link in orbit) for orbit in original.link_orbits) == sorted(
        list(orbit) for orbit in permuted.link_orbits
    )


def test_non_isomorphic_trusses_have_distinct_certificates():
    trusses = baranov_trusses(9)
    assert len({certificate(t) for t in trusses}) == 28
    assert not any(nx.is_isomorphic(link_graph(a), link_graph(b)) for i, a in enumerate(trusses) for b in trusses[i + 1:])
