"""Chains: construction from the three input forms, derived graphs, structural errors."""

import networkx as nx
import pytest

from baranov.topology import (
    JointKind,
    TopologyError,
    chain_from_link_graph,
    degree_sequence,
    is_planar,
    joint_graph,
    link_graph,
)


def test_three_input_forms_give_the_same_chain(pentad):
    from_graph = chain_from_link_graph(nx.complete_bipartite_graph(2, 3))
    from_graph6 = chain_from_link_graph(nx.to_graph6_bytes(nx.complete_bipartite_graph(2, 3)).decode())
    assert from_graph == pentad == from_graph6


def test_labels_of_a_networkx_graph_are_kept_for_messages():
    graph = nx.Graph([("frame", "crank"), ("crank", "coupler"), ("coupler", "frame")])
    chain = chain_from_link_graph(graph)
    assert chain.link_labels == ("coupler", "crank", "frame")
    assert chain.link_name(0) == "coupler"


def test_joint_graph_of_pentad_is_two_triangles_and_three_bars(pentad):
    graph = joint_graph(pentad)
    assert sorted(graph.nodes) == ["P1", "P2", "P3", "P4", "P5", "P6"]
    triangles = [c for c in nx.enumerate_all_cliques(graph) if len(c) == 3]
    assert sorted(sorted(t) for t in triangles) == [["P1", "P2", "P3"], ["P4", "P5", "P6"]]
    bars = sorted(tuple(sorted(e)) for e in graph.edges if graph.edges[e]["link"] >= 2)
    assert bars == [("P1", "P4"), ("P2", "P5"), ("P3", "P6")]


def test_quaternary_link_is_a_four_clique():
    # link 0 carries four joints
    chain = chain_from_link_graph([(0, 1), (0, 2), (0, 3), (0, 4), (1, 2), (3, 4)])
    graph = joint_graph(chain)
    on_link_0 = [j.name for j in chain.joints if 0 in j.links]
    assert all(graph.has_edge(a, b) for a in on_link_0 for b in on_link_0 if a != b)
    assert graph.subgraph(on_link_0).number_of_edges() == 6


def test_link_graph_round_trip_and_invariants(pentad):
    graph = link_graph(pentad)
    assert nx.is_isomorphic(graph, nx.complete_bipartite_graph(2, 3))
    assert degree_sequence(pentad) == (3, 3, 2, 2, 2)
    assert is_planar(pentad)
    assert not is_planar(chain_from_link_graph(nx.complete_bipartite_graph(3, 3)))


def test_slider_joints_are_stored(pentad):
    chain = pentad.with_joint_kinds(["P2", "P5"])
    assert [j.kind for j in chain.joints].count(JointKind.SLIDER) == 2
    assert link_graph(chain).edges[0, 3]["kind"] == "slider"
    with pytest.raises(TopologyError, match="joint P9"):
        pentad.with_joint_kinds(["P9"])


@pytest.mark.parametrize(
    ("edges", "message"),
    [
        ([(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3)], r"disconnected: links L3, L4, L5"),
        ([(0, 1), (1, 2), (2, 0), (2, 3)], r"link L3: fewer than two joints"),
        ([(0, 1), (1, 2), (2, 0), (0, 1)], r"links L0, L1: two joints between the same pair"),
        ([(0, 0), (0, 1), (1, 2), (2, 0)], r"joins link L0 to itself"),
        ([(0, 1, 2)], r"a joint joins exactly two links"),
    ],
)
def test_structural_errors_name_the_links(edges, message):
    with pytest.raises(TopologyError, match=message):
        chain_from_link_graph(edges)


def test_topology_error_is_a_value_error():
    assert issubclass(TopologyError, ValueError)


def test_multigraph_input_with_repeated_joint_is_rejected():
    graph = nx.MultiGraph([(0, 1), (0, 1), (1, 2), (2, 0)])
    with pytest.raises(TopologyError, match="two joints between the same pair"):
        chain_from_link_graph(graph)


def test_bad_graph6_is_a_topology_error():
    with pytest.raises(TopologyError, match="graph6"):
        chain_from_link_graph("~~~not graph6")


def test_joint_names_must_match_the_joint_count():
    with pytest.raises(TopologyError, match="2 joint names given for 3 joints"):
        chain_from_link_graph([(0, 1), (1, 2), (2, 0)], joint_names=["P1", "P2"])


def test_fuse_links_and_its_errors(pentad):
    from baranov.topology import fuse_links

    fused = fuse_links(pentad, [[0, 2]])  # a ternary link and a bar jointed at P1
    assert fused.number_of_links == 4 and [j.name for j in fused.joints] == ["P2", "P3", "P4", "P5", "P6"]
    assert fused.link_labels[0] == "L0+L2"
    with pytest.raises(TopologyError, match="not jointed together"):
        fuse_links(pentad, [[0, 1]])
    with pytest.raises(TopologyError, match="in more than one group"):
        fuse_links(pentad, [[0, 2], [2, 1]])
    with pytest.raises(TopologyError, match="no such link"):
        fuse_links(pentad, [[0, 9]])
    with pytest.raises(TopologyError, match="fuse those links too"):
        fuse_links(pentad, [[0, 2, 1]])  # links 3 and 4 would each get two joints to it
