"""Mobility, rigid sub-chains and the Baranov predicate, against brute-force oracles."""

from itertools import combinations

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.topology import (
    TopologyError,
    adjacency_masks,
    chain_from_link_graph,
    is_baranov_link_graph,
    is_baranov_truss,
    mobility,
    require_baranov_truss,
    smallest_rigid_subchain,
)
from baranov.topology.rigidity import _smallest_rigid_connected_set


def naive_smallest_rigid(graph: nx.Graph) -> tuple[int, ...] | None:
    """Oracle: try every proper subset by size, in lexicographic order of bit masks."""
    n = graph.number_of_nodes()
    for size in range(2, n):
        rigid = [
            subset for subset in combinations(range(n), size)
            if 2 * graph.subgraph(subset).number_of_edges() >= 3 * size - 3
        ]
        if rigid:
            return min(rigid, key=lambda s: sum(1 << i for i in s))
    return None


@st.composite
def chains(draw, max_links=9):
    """Random connected chains: a random tree plus random extra joints, all degrees ≥ 2."""
    n = draw(st.integers(3, max_links))
    graph = nx.Graph()
    graph.add_nodes_from(range(n))
    for v in range(1, n):
        graph.add_edge(v, draw(st.integers(0, v - 1)))
    pairs = [(u, v) for u in range(n) for v in range(u + 1, n) if not graph.has_edge(u, v)]
    extra = draw(st.lists(st.sampled_from(pairs), max_size=2 * n, unique=True)) if pairs else []
    graph.add_edges_from(extra)
    for v in range(n):
        while graph.degree(v) < 2:
            graph.add_edge(v, draw(st.sampled_from([u for u in range(n) if u != v and not graph.has_edge(u, v)])))
    return graph


@settings(max_examples=300, deadline=None)
@given(chains())
def test_smallest_rigid_subchain_matches_brute_force(graph):
    chain = chain_from_link_graph(graph)
    expected = naive_smallest_rigid(graph)
    assert smallest_rigid_subchain(chain) == expected
    assert _smallest_rigid_connected_set(adjacency_masks(chain)) == expected
    counts_ok = 2 * graph.number_of_edges() == 3 * (graph.number_of_nodes() - 1)
    assert is_baranov_truss(chain) == (counts_ok and expected is None)
    assert is_baranov_link_graph(adjacency_masks(chain)) == is_baranov_truss(chain)


def test_mobility_of_known_chains(pentad):
    assert mobility(pentad) == 0
    four_bar = chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)])
    assert mobility(four_bar) == 1
    watt_six_bar = chain_from_link_graph([(0, 1), (0, 2), (2, 3), (3, 1), (0, 4), (4, 5), (5, 1)])
    assert mobility(watt_six_bar) == 1


def test_rigid_subchain_is_named_smallest_first():
    # Two triads glued into a 5-link, 6-joint chain: links 0,1,2 are rigid.
    chain = chain_from_link_graph([(0, 1), (1, 2), (0, 2), (2, 3), (3, 4), (4, 0)])
    with pytest.raises(TopologyError, match=r"links L0, L1, L2 form a rigid sub-chain \(3 links, 3 joints\)"):
        require_baranov_truss(chain)


def test_mobility_error_message():
    chain = chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)])
    with pytest.raises(TopologyError, match="mobility F = 3\\(L-1\\) - 2J = 1 with L = 4 links"):
        require_baranov_truss(chain)


def test_large_chain_uses_connected_set_search():
    # 25 links: a ring of 24 four-bar-like links closed by a triad at the end.
    edges = [(i, i + 1) for i in range(24)] + [(24, 0), (0, 2)]
    chain = chain_from_link_graph(edges)
    assert smallest_rigid_subchain(chain) == (0, 1, 2)


@pytest.mark.parametrize("links", [3, 5, 7, 9])
def test_trusses_are_minimally_rigid_for_pyrigi(links):
    """Independent check with PyRigi: each k-ary link replaced by a fan of k-2 triangles
    (2k-3 bars on its k joints) makes the joint graph minimally rigid (Laman)."""
    from pyrigi import Graph

    for truss in baranov_trusses(links):
        bars = []
        for link in range(truss.number_of_links):
            joints = [j.name for j in truss.joints if link in j.links]
            hub, rest = joints[0], joints[1:]
            bars += [(hub, other) for other in rest]
            bars += list(zip(rest, rest[1:], strict=False))
        assert Graph(bars).is_min_rigid()
