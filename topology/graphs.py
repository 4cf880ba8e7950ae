"""Graph views of a kinematic chain: the link graph and the joint (distance) graph.

* The **link graph** has the links as vertices and the joints as edges
  (thesis §3.1; the usual graph of type theory).
* The **joint graph**, or distance graph, has the joints as vertices; every link is a
  rigid body, so the joints on one k-ary link form a clique of k(k-1)/2 known distances
  (thesis §2.2–2.3). A binary link is a single known distance. This is the graph the
  planner searches for bilaterations.
"""

from __future__ import annotations

import networkx as nx

from .chain import KinematicChain


def link_graph(chain: KinematicChain) -> nx.Graph:
    """The link graph: vertices ``0..L-1``; each edge carries its joint's ``name`` and ``kind``.

    Complexity O(L + J).

    >>> from baranov.topology import chain_from_link_graph
    >>> g = link_graph(chain_from_link_graph("Bw"))
    >>> sorted(g.edges(data="joint"))
    [(0, 1, 'P1'), (0, 2, 'P2'), (1, 2, 'P3')]
    """
    graph = nx.Graph()
    graph.add_nodes_from(range(chain.number_of_links))
    for joint in chain.joints:
        graph.add_edge(*joint.links, joint=joint.name, kind=joint.kind.value)
    return graph


def joint_graph(chain: KinematicChain) -> nx.Graph:
    """The joint (distance) graph: vertices are joint names; an edge joins two joints of
    the same link and carries that link's index as ``link``.

    Two joints share at most one link (a chain has no two joints between the same
    pair of links), so every edge belongs to exactly one rigid body. A k-ary link
    contributes a k-clique. Complexity O(J + Σ k²) over the links.

    >>> from baranov.topology import chain_from_link_graph
    >>> pentad = chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)])
    >>> g = joint_graph(pentad)
    >>> g.number_of_nodes(), g.number_of_edges()  # two triangles and three bars
    (6, 9)
    """
    graph = nx.Graph()
    graph.add_nodes_from(joint.name for joint in chain.joints)
    for link, names in enumerate(joints_of_links(chain)):
        for a in range(len(names)):
            for b in range(a + 1, len(names)):
                graph.add_edge(names[a], names[b], link=link)
    return graph


def joints_of_links(chain: KinematicChain) -> list[list[str]]:
    """For every link, the names of its joints in chain order."""
    names: list[list[str]] = [[] for _ in range(chain.number_of_links)]
    for joint in chain.joints:
        for link in joint.links:
            names[link].append(joint.name)
    return names


def degree_sequence(chain: KinematicChain) -> tuple[int, ...]:
    """Link degrees (joints per link) in non-increasing order.

    >>> from baranov.topology import chain_from_link_graph
    >>> degree_sequence(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    (3, 3, 2, 2, 2)
    """
    return tuple(sorted(chain.link_degrees, reverse=True))


def is_planar(chain: KinematicChain) -> bool:
    """Whether the link graph is planar (Boyer–Myrvold test via networkx, O(L + J)).

    >>> from baranov.topology import chain_from_link_graph
    >>> is_planar(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    True
    """
    planar, _ = nx.check_planarity(link_graph(chain))
    return planar
