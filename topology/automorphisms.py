"""Symmetries of kinematic chains: canonical forms, isomorphism and automorphism groups.

An automorphism of a chain is a permutation of its links that preserves which links
are jointed (and the kind of every joint); it permutes the joints along (thesis §2.7.1).
All computations use nauty through pynauty on the **incidence graph**: one vertex per
link, one per joint, a joint vertex adjacent to its two links, with links, revolute
joints and slider joints in separate colour classes. One nauty call thus gives the
link and the joint permutations of every generator and both orbit partitions. For a
chain (every link has ≥ 2 joints, no repeated joint) the incidence graph has the same
automorphism group as the link graph.

References: B. D. McKay, A. Piperno, *Practical graph isomorphism II*, J. Symbolic
Comput. 60 (2014) 94–112; thesis §2.7.1 (the pentad's twelve automorphisms).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import networkx as nx
import pynauty

if TYPE_CHECKING:  # sympy is imported where the group's elements are listed: it costs 0.25 s
    from sympy.combinatorics import PermutationGroup

from .chain import JointKind, KinematicChain
from .rigidity import adjacency_masks


@dataclass(frozen=True)
class Automorphism:
    """One symmetry of a chain.

    Attributes
    ----------
    links
        ``links[i]`` is the image of link ``i``.
    joints
        ``joints[k]`` is the name of the image of the k-th joint (chain order).
    """

    links: tuple[int, ...]
    joints: tuple[str, ...]


@dataclass(frozen=True)
class AutomorphismGroup:
    """The automorphism group of a chain (see :func:`automorphism_group`).

    Attributes
    ----------
    order
        exact group order (nauty's, where a float holds it exactly; else
        Schreier–Sims in sympy).
    generators
        a generating set as found by nauty (empty for the trivial group).
    link_orbits
        orbits of links, each sorted, ordered by their smallest link.
    joint_orbits
        orbits of joints (names), ordered by first joint in chain order.
    """

    order: int
    generators: tuple[Automorphism, ...]
    link_orbits: tuple[tuple[int, ...], ...]
    joint_orbits: tuple[tuple[str, ...], ...]
    joint_names: tuple[str, ...]
    number_of_links: int

    @cached_property
    def _group(self) -> PermutationGroup:
        return _permutation_group(self.generators, self.number_of_links, self.joint_names)

    def elements(self) -> list[Automorphism]:
        """Every automorphism as link and joint permutations, identity first (``|G|`` items)."""
        n = self.number_of_links
        result = []
        for perm in sorted(self._group.generate(), key=lambda p: p.array_form):
            form = perm.array_form
            joints = tuple(self.joint_names[form[n + k] - n] for k in range(len(self.joint_names)))
            result.append(Automorphism(tuple(form[:n]), joints))
        return result


def _permutation_group(
    generators: Sequence[Automorphism], number_of_links: int, joint_names: Sequence[str]
) -> PermutationGroup:
    """The group as sympy permutations of links 0..L-1 followed by joints L..L+J-1."""
    from sympy.combinatorics import Permutation, PermutationGroup

    n = number_of_links
    index = {name: k for k, name in enumerate(joint_names)}
    perms = [Permutation(list(g.links) + [n + index[name] for name in g.joints]) for g in generators]
    return PermutationGroup(perms or [Permutation(list(range(n + len(joint_names))))])


def _incidence_graph(chain: KinematicChain) -> pynauty.Graph:
    n = chain.number_of_links
    adjacency = {n + k: list(joint.links) for k, joint in enumerate(chain.joints)}
    colouring = [set(range(n))]
    for kind in JointKind:
        colouring.append({n + k for k, joint in enumerate(chain.joints) if joint.kind is kind})
    colouring = [cell for cell in colouring if cell]
    return pynauty.Graph(n + chain.number_of_joints, adjacency_dict=adjacency, vertex_coloring=colouring)


def automorphism_group(chain: KinematicChain) -> AutomorphismGroup:
    """The automorphism group of ``chain``: order, generators, link and joint orbits.

    Complexity: one nauty run on L + J vertices (fast in practice), which also gives the
    order (Schreier–Sims only for orders a float does not hold exactly).

    >>> from baranov.topology import chain_from_link_graph
    >>> pentad = chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)])
    >>> group = automorphism_group(pentad)
    >>> group.order, group.link_orbits, group.joint_orbits
    (12, ((0, 1), (2, 3, 4)), (('P1', 'P2', 'P3', 'P4', 'P5', 'P6'),))
    """
    n = chain.number_of_links
    names = tuple(joint.name for joint in chain.joints)
    generators_raw, mantissa, exponent, orbits, _ = pynauty.autgrp(_incidence_graph(chain))
    generators = tuple(
        Automorphism(tuple(g[:n]), tuple(names[g[n + k] - n] for k in range(len(names))))
        for g in generators_raw
    )
    link_orbits = _orbits_from_representatives(orbits[:n], range(n))
    joint_orbits = tuple(
        tuple(names[k] for k in orbit)
        for orbit in _orbits_from_representatives([r - n for r in orbits[n:]], range(len(names)))
    )
    order = group_order(mantissa, exponent) or (int(_permutation_group(generators, n, names).order())
                                                 if generators else 1)
    return AutomorphismGroup(order, generators, link_orbits, joint_orbits, names, n)


def group_order(mantissa: float, exponent: int) -> int | None:
    """nauty's group order, mantissa · 10^exponent, as an integer where the float holds it
    exactly (an integer below 2^53 and exponent 0: every chain of the catalog); None
    otherwise (then Schreier–Sims in sympy decides)."""
    if exponent == 0 and mantissa < 2**53 and float(mantissa).is_integer():
        return int(mantissa)
    return None


def list_automorphisms(chain: KinematicChain) -> list[Automorphism]:
    """All automorphisms of ``chain`` as link and joint permutations, identity first.

    >>> from baranov.topology import chain_from_link_graph
    >>> len(list_automorphisms(chain_from_link_graph("Bw")))  # the triad: S_3
    6
    """
    return automorphism_group(chain).elements()


def _orbits_from_representatives(representatives: Sequence[int], items) -> tuple[tuple[int, ...], ...]:
    groups: dict[int, list[int]] = {}
    for item, rep in zip(items, representatives, strict=True):
        groups.setdefault(rep, []).append(item)
    return tuple(sorted((tuple(sorted(g)) for g in groups.values()), key=lambda orbit: orbit[0]))


def certificate(chain: KinematicChain) -> bytes:
    """A canonical certificate: equal for two chains exactly when they are isomorphic
    (same link graph up to relabelling, with joint kinds preserved).
    """
    kinds = bytes(sum(joint.kind is kind for joint in chain.joints) for kind in JointKind)
    return kinds + pynauty.certificate(_incidence_graph(chain))


def are_isomorphic(first: KinematicChain, second: KinematicChain) -> bool:
    """Whether two chains are isomorphic (links relabelled, joint kinds preserved).

    >>> from baranov.topology import chain_from_link_graph
    >>> are_isomorphic(chain_from_link_graph([(0, 1), (1, 2), (2, 0)]),
    ...                chain_from_link_graph([("a", "b"), ("b", "c"), ("c", "a")]))
    True
    """
    if (first.number_of_links, first.number_of_joints) != (second.number_of_links, second.number_of_joints):
        return False
    return certificate(first) == certificate(second)


def link_graph_certificate(masks: Sequence[int]) -> bytes:
    """nauty certificate of a link graph given as adjacency bit masks (enumeration hot path)."""
    return pynauty.certificate(nauty_link_graph(masks))


def nauty_link_graph(masks: Sequence[int]) -> pynauty.Graph:
    """The link graph given as adjacency bit masks, as a pynauty graph."""
    n = len(masks)
    return pynauty.Graph(n, adjacency_dict={i: [j for j in range(i + 1, n) if masks[i] >> j & 1] for i in range(n)})


def canonical_labelling(chain: KinematicChain) -> tuple[int, ...]:
    """nauty's canonical order of the links of the link graph (joint kinds ignored):
    position i of the canonical form holds link ``result[i]``.
    """
    return tuple(pynauty.canon_label(nauty_link_graph(adjacency_masks(chain))))


def canonical_link_graph6(chain: KinematicChain) -> str:
    """graph6 string of the canonically labelled link graph (stable identifier).

    >>> from baranov.topology import chain_from_link_graph
    >>> canonical_link_graph6(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    'DFw'
    """
    order = canonical_labelling(chain)
    position = {link: i for i, link in enumerate(order)}
    graph = nx.Graph()
    graph.add_nodes_from(range(chain.number_of_links))
    graph.add_edges_from((position[j.links[0]], position[j.links[1]]) for j in chain.joints)
    return nx.to_graph6_bytes(graph, header=False).decode().strip()
