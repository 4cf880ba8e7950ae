"""Fusing links: fixing the relative position of jointed links makes them one rigid body.

A single-DOF (Grübler) chain with its input angle fixed, or a robot with locked
actuators, is analysed as the chain in which each input link and the link it is driven
from form one link (thesis ch. 5: a 3-RPR robot with locked legs is a pentad). Joints
inside a fused group disappear; the fused link carries every joint that leaves the group.
"""

from __future__ import annotations

from collections.abc import Iterable

import networkx as nx

from .chain import Joint, KinematicChain
from .errors import TopologyError
from .graphs import link_graph


def fuse_links(chain: KinematicChain, groups: Iterable[Iterable[int]]) -> KinematicChain:
    """The chain with every group of links welded into one link.

    Each group must be connected through joints among its own links. The fused link takes
    the place of the group's smallest link; links are renumbered in their old order and
    keep their labels (a fused link is labelled with its members joined by ``+``).
    Raises :class:`TopologyError` for unknown or repeated links, a group that is not
    jointed together, or a fusion that would put two joints between one pair of links
    (that pair would be welded too: fuse it explicitly).

    >>> from baranov.topology import chain_from_link_graph, mobility
    >>> four_bar = chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)])  # 0 = ground, 1 = crank
    >>> triad = fuse_links(four_bar, [[0, 1]])  # input angle fixed
    >>> triad.number_of_links, mobility(triad), triad.link_labels
    (3, 0, ('L0+L1', 2, 3))
    """
    groups = [sorted(set(group)) for group in groups]
    n = chain.number_of_links
    owner = list(range(n))
    seen: set[int] = set()
    graph = link_graph(chain)
    for group in groups:
        for link in group:
            if not (isinstance(link, int) and 0 <= link < n):
                raise TopologyError(f"link {link!r}: no such link (0..{n - 1})")
            if link in seen:
                raise TopologyError(f"link {chain.link_name(link)}: in more than one group to fuse")
            seen.add(link)
        if len(group) < 2:
            continue
        if not nx.is_connected(graph.subgraph(group)):
            listed = ", ".join(chain.link_name(link) for link in group)
            raise TopologyError(f"links {listed}: not jointed together, cannot be fused")
        for link in group:
            owner[link] = group[0]
    survivors = sorted(set(owner))
    index = {link: i for i, link in enumerate(survivors)}
    labels = []
    for link in survivors:
        members = [m for m in range(n) if owner[m] == link]
        labels.append("+".join(chain.link_name(m) for m in members) if len(members) > 1 else chain.link_labels[link])
    joints = []
    pairs: dict[tuple[int, int], str] = {}
    for joint in chain.joints:
        a, b = (index[owner[link]] for link in joint.links)
        if a == b:
            continue  # inside a fused body
        pair = (min(a, b), max(a, b))
        if pair in pairs:
            raise TopologyError(
                f"joints {pairs[pair]} and {joint.name} would both join L{labels[pair[0]]} and "
                f"L{labels[pair[1]]}: fuse those links too"
            )
        pairs[pair] = joint.name
        joints.append(Joint(joint.name, pair, joint.kind))
    return KinematicChain(len(survivors), tuple(joints), tuple(labels))
