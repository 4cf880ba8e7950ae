"""One-degree-of-freedom chains (thesis ch. 6, issue 19): the Grübler chains enumerated,
and the distances that parametrise their configuration spaces (thesis §6.4, Table 6.2)."""

from collections import Counter

import pytest

from baranov.enumerate.crosscheck import find_geng
from baranov.enumerate.grubler import check_grubler_link_count, grubler_chains, grubler_link_graphs
from baranov.planner import one_dof_plans, parametrising_distances
from baranov.topology import TopologyError, adjacency_masks, chain_from_link_graph, chain_from_links
from baranov.topology.automorphisms import link_graph_certificate
from baranov.topology.rigidity import rigid_subset_masks

needs_geng = pytest.mark.skipif(find_geng() is None, reason="geng not installed (make installs it)")

#: Thesis §6.2, Fig. 6.5(a): binary links P1P5, P3P6, P4P7, P2P8, ternary △P1P10P2,
#: △P10P3P4, △P6P5P9, △P7P9P8.
DOUBLE_BUTTERFLY = [("P1", "P5"), ("P3", "P6"), ("P4", "P7"), ("P2", "P8"), ("P1", "P10", "P2"),
                    ("P10", "P3", "P4"), ("P6", "P5", "P9"), ("P7", "P9", "P8")]


@needs_geng
def test_grubler_chain_counts():
    """1 four-bar, 2 six-bars (Watt, Stephenson), 16 eight-bar and 230 ten-bar chains
    (the classical counts), each a one-degree-of-freedom chain without a rigid sub-chain."""
    counts = {links: grubler_link_graphs(links) for links in (4, 6, 8, 10)}
    assert {links: len(graphs) for links, graphs in counts.items()} == {4: 1, 6: 2, 8: 16, 10: 230}
    for graphs in counts.values():
        assert len({link_graph_certificate(masks) for masks in graphs}) == len(graphs)
        assert all(rigid_subset_masks(masks).size == 0 for masks in graphs)


#: The published counts of one-degree-of-freedom planar simple-jointed chains without a
#: rigid sub-chain with 12 and 14 links (Sunkari and Schmidt, "Structural synthesis of
#: planar kinematic chains by adapting a McKay-type algorithm", Mech. Mach. Theory 41
#: (2006) 1021-1030; OEIS A233288).
PUBLISHED = {12: 6856, 14: 318_162}


@needs_geng
def test_twelve_link_chains():
    """6856 twelve-link chains, as published; distinct classes (15 s alone, 2026-11-28)."""
    graphs = grubler_link_graphs(12)
    assert len(graphs) == PUBLISHED[12]
    assert len({link_graph_certificate(masks) for masks in graphs}) == len(graphs)


@pytest.mark.slow
@needs_geng
def test_fourteen_link_chains():
    """318 162 fourteen-link chains, as published (36 min in one process beside other work, 2026-11-28)."""
    assert len(grubler_link_graphs(14)) == PUBLISHED[14]


@needs_geng
def test_table_6_2_distances_and_oriented_areas():
    """Thesis §6.4: the four-bar's configuration space is ranges of one distance per sign
    combination of two oriented areas, the six-bars' of three; twelve of the sixteen
    eight-bar chains need one distance and four need two (Table 6.2), all with four
    oriented areas, so the latter split into 2^4 = 16 components. Beyond the thesis:
    of the 230 ten-bar chains 140 need one distance, 90 two, all five oriented areas."""
    profile = {links: Counter((len(plan.parameters), len(plan.free_sign_triangles))
                              for plan in (one_dof_plans(chain)[0] for chain in grubler_chains(links)))
               for links in (4, 6, 8, 10)}
    assert profile == {4: {(1, 2): 1}, 6: {(1, 3): 2}, 8: {(1, 4): 12, (2, 4): 4}, 10: {(1, 5): 140, (2, 5): 90}}
    for links in (4, 6, 8):  # d parameters, d - 1 closure conditions
        assert all(len(plan.closure_pairs) == len(plan.parameters) - 1
                   for plan in (one_dof_plans(chain)[0] for chain in grubler_chains(links)))


@needs_geng
def test_the_double_butterfly_is_one_of_the_four():
    """The double butterfly (thesis §6.2) is one of Table 6.2's four eight-bar chains: two
    distances, four oriented areas, 16 components."""
    chain = chain_from_links(DOUBLE_BUTTERFLY)
    plan = one_dof_plans(chain)[0]
    assert parametrising_distances(chain) == 2 and len(plan.free_sign_triangles) == 4
    two = {link_graph_certificate(adjacency_masks(other)) for other in grubler_chains(8)
           if parametrising_distances(other) == 2}
    assert link_graph_certificate(adjacency_masks(chain)) in two


def test_one_dof_planner_refuses_other_mobilities():
    triad = chain_from_link_graph([(0, 1), (1, 2), (0, 2)])
    with pytest.raises(TopologyError, match="mobility F = 3\\(L-1\\) - 2J = 0 .* needs F = 1"):
        parametrising_distances(triad)
    with pytest.raises(ValueError, match="links=5: a Grübler chain has an even number of links"):
        check_grubler_link_count(5)
