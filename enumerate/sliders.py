"""Assur kinematic chains with slider joints derived from a Baranov truss.

Any set of revolute joints of a truss may be replaced by slider joints (thesis ch. 4,
paper 003 §1: sliders as revolute centres at infinity), except a set that contains
every joint of some cycle of the link graph: a loop closed by sliders only cannot fix
its translation. A set of edges contains a cycle exactly when it is not a forest, so
the admissible slider sets are the forests of the link graph (the all-revolute truss,
the empty forest, included). They are counted up to the automorphisms of the truss
with Burnside's lemma: #orbits = (1/|G|) Σ_{g ∈ G} #{admissible S : g(S) = S}.

The thesis counts 3 chains for the triad and 10 for the pentad.
"""

from __future__ import annotations

from collections.abc import Collection

import networkx as nx
import numpy as np

from baranov.topology import AutomorphismGroup, KinematicChain, automorphism_group, link_graph

#: Above this many joints the 2^J table of joint subsets is not built (13 links: J = 18).
SLIDER_TABLE_LIMIT = 18


def admissible_slider_sets(chain: KinematicChain) -> np.ndarray:
    """Boolean table over all 2^J joint subsets (bit k = k-th joint): True where the
    subset contains no cycle of the link graph. O(2^J · C) for C simple cycles.

    >>> from baranov.topology import chain_from_link_graph
    >>> int(admissible_slider_sets(chain_from_link_graph("Bw")).sum())  # all but the full loop
    7
    """
    joints = chain.number_of_joints
    if joints > SLIDER_TABLE_LIMIT:
        raise ValueError(f"{joints} joints: slider sets are tabulated up to {SLIDER_TABLE_LIMIT} joints")
    graph = link_graph(chain)
    bit = {joint.name: 1 << k for k, joint in enumerate(chain.joints)}
    subsets = np.arange(1 << joints, dtype=np.int64)
    admissible = np.ones(1 << joints, dtype=bool)
    for cycle in nx.simple_cycles(graph):
        loop = 0
        for a, b in zip(cycle, cycle[1:] + cycle[:1], strict=True):
            loop |= bit[graph.edges[a, b]["joint"]]
        admissible &= (subsets & loop) != loop
    return admissible


def count_slider_chains(chain: KinematicChain, group: AutomorphismGroup | None = None) -> int:
    """Number of non-isomorphic chains obtained by turning admissible sets of joints of
    ``chain`` into sliders (the all-revolute chain included), by Burnside's lemma.

    >>> from baranov.topology import chain_from_link_graph
    >>> count_slider_chains(chain_from_link_graph("Bw"))  # the triad (thesis ch. 4)
    3
    >>> count_slider_chains(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    10
    """
    group = group or automorphism_group(chain)
    admissible = admissible_slider_sets(chain)
    subsets = np.arange(admissible.size, dtype=np.int64)
    fixed_total = sum(int(np.count_nonzero(admissible & (image == subsets)))
                      for image in _subset_images(chain, group, subsets))
    count, remainder = divmod(fixed_total, group.order)
    if remainder:
        raise ArithmeticError("Burnside sum not divisible by the group order")  # cannot happen
    return count


def slider_chains(chain: KinematicChain, group: AutomorphismGroup | None = None) -> list[tuple[str, ...]]:
    """One admissible slider set per isomorphism class of the slider chains of ``chain``
    (:func:`count_slider_chains` of them, the all-revolute chain first): of each orbit
    of the automorphism group, the set whose bit mask over the joints is smallest, sorted
    by size and then by mask. O(|G| · 2^J).

    >>> from baranov.topology import chain_from_link_graph
    >>> slider_chains(chain_from_link_graph("Bw"))  # three links in a loop: no, one or two sliders
    [(), ('P1',), ('P1', 'P2')]
    """
    group = group or automorphism_group(chain)
    admissible = admissible_slider_sets(chain)
    subsets = np.arange(admissible.size, dtype=np.int64)
    canonical = subsets.copy()
    for image in _subset_images(chain, group, subsets):
        np.minimum(canonical, image, out=canonical)
    chosen = np.flatnonzero(admissible & (canonical == subsets))
    sizes = [bin(int(mask)).count("1") for mask in chosen]
    return [tuple(joint.name for k, joint in enumerate(chain.joints) if int(mask) >> k & 1)
            for _, mask in sorted(zip(sizes, chosen, strict=True))]


def canonical_slider_set(chain: KinematicChain, sliders: Collection[str],
                         group: AutomorphismGroup | None = None) -> tuple[str, ...]:
    """The representative of the orbit of the slider set ``sliders`` under the
    automorphisms of ``chain``, the one :func:`slider_chains` lists: the image whose bit
    mask over the joints (P1 = bit 0) is smallest, in joint order. O(|G| · J).

    >>> from baranov.topology import chain_from_link_graph
    >>> canonical_slider_set(chain_from_link_graph("Bw"), ["P3"])
    ('P1',)
    """
    group = group or automorphism_group(chain)
    position = {joint.name: k for k, joint in enumerate(chain.joints)}
    mask = np.array([sum(1 << position[name] for name in sliders)], dtype=np.int64)
    smallest = min(int(image[0]) for image in _subset_images(chain, group, mask))
    return tuple(joint.name for k, joint in enumerate(chain.joints) if smallest >> k & 1)


def _subset_images(chain: KinematicChain, group: AutomorphismGroup, subsets: np.ndarray):
    """For each element of ``group``, the bit mask of the image of every joint subset."""
    position = {joint.name: k for k, joint in enumerate(chain.joints)}
    for element in group.elements():
        image = np.zeros_like(subsets)
        for k, target in enumerate(element.joints):
            image |= ((subsets >> k) & 1) << position[target]
        yield image
