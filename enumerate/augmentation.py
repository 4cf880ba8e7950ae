"""Baranov trusses by canonical augmentation: a generation tree whose subtrees are disjoint.

:func:`baranov.enumerate.trusses.baranov_link_graphs` keeps one graph per isomorphism
class at every level, which needs the whole level in one place. Here every graph of the
search has one *canonical parent*, so the search is a tree and its subtrees can be
searched apart (on a Dask cluster, :mod:`baranov.catalog.census`) with no deduplication
between them (B. D. McKay, *Isomorph-free exhaustive generation*, J. Algorithms 26 (1998)
306–324, §3).

**Canonical deletion.** In a graph C of the search (k + 1 vertices), let M be the set of
vertices of minimum degree with the largest invariant (the neighbours' degrees, sorted);
the canonical deletion vertex m(C) is the vertex of M that comes first in nauty's
canonical labelling of C. Both choices are isomorphism-invariant, so the orbit of m(C)
under Aut(C) is too, and C's canonical parent is C − m(C), unique up to isomorphism.

**Acceptance.** A child C = P + v (v the new, last vertex, added with minimum degree by
:func:`~baranov.enumerate.trusses.children`) is kept when v lies in the orbit of m(C).
Then every graph that meets the pruning rules of a level (heredity, triangle-freeness,
the edge bounds of fact 5 in :mod:`~baranov.enumerate.trusses`) is reached from exactly one
parent class: deleting m(C), a vertex of minimum degree, keeps those rules (they hold along
any minimum-degree deletion order), so C − m(C) is in the tree by induction; and two
kept children of *different* parent classes are not isomorphic, since an isomorphism can be
composed with automorphisms so that it maps new vertex to new vertex, hence parent to
parent. Two kept children of one parent P are isomorphic only if an automorphism of P maps
one neighbour set to the other; they are told apart by certificate when Aut(P) is not
trivial (and cannot occur when it is).

Cost per child: a few Python operations; nauty (twice) only when the new vertex ties with
another for m(C).
"""

from __future__ import annotations

from collections.abc import Iterator

import pynauty

from baranov.topology.automorphisms import link_graph_certificate, nauty_link_graph

from .trusses import Masks, check_link_count, children, edge_bounds


def deletion_invariant(masks: Masks, vertex: int, degrees: list[int]) -> tuple[int, ...]:
    """An isomorphism-invariant of a vertex: its neighbours' degrees, largest first."""
    neighbours = masks[vertex]
    return tuple(sorted((degrees[u] for u in range(len(masks)) if neighbours >> u & 1), reverse=True))


def is_canonical_extension(child: Masks) -> bool:
    """Whether the last vertex of ``child`` lies in the Aut(child)-orbit of its canonical
    deletion vertex m(child) (module docstring). The last vertex must have minimum degree.

    >>> star = (0b1110, 0b0001, 0b0001, 0b0001)  # vertex 0 joined to 1, 2, 3
    >>> is_canonical_extension(star)  # vertex 3 is in the orbit of the leaves
    True
    >>> is_canonical_extension((0b10, 0b101, 0b010))  # path 0-1-2: 2 ~ 0 by symmetry
    True
    """
    new = len(child) - 1
    degrees = [mask.bit_count() for mask in child]
    lowest = degrees[new]
    tied = [v for v in range(len(child)) if degrees[v] == lowest]
    if len(tied) > 1:
        invariants = {v: deletion_invariant(child, v, degrees) for v in tied}
        best = max(invariants.values())
        if invariants[new] != best:
            return False
        tied = [v for v in tied if invariants[v] == best]
    if len(tied) == 1:
        return True
    graph = nauty_link_graph(child)
    orbits = pynauty.autgrp(graph)[3]
    if all(orbits[v] == orbits[new] for v in tied):
        return True
    tied_set = set(tied)
    first = next(v for v in pynauty.canon_label(graph) if v in tied_set)
    return orbits[first] == orbits[new]


def canonical_children(parent: Masks, links: int, bounds: list[tuple[int, int]]) -> list[Masks]:
    """The children of ``parent`` kept by canonical augmentation, one per isomorphism class."""
    kept = [child for child in children(parent, links, bounds) if is_canonical_extension(child)]
    if len(kept) < 2 or pynauty.autgrp(nauty_link_graph(parent))[1] == 1.0:
        return kept
    unique: dict[bytes, Masks] = {}
    for child in kept:
        unique.setdefault(link_graph_certificate(child), child)
    return list(unique.values())


def augmentation_roots(links: int, level: int) -> list[Masks]:
    """The graphs of the search with ``level`` vertices (one per isomorphism class, in a
    deterministic order): the roots of disjoint subtrees that together hold every truss
    with ``links`` links.

    >>> [len(augmentation_roots(13, level)) for level in (4, 8, 12)]
    [3, 117, 6856]
    """
    check_link_count(links)
    if not 1 <= level <= links:
        raise ValueError(f"level={level!r}: a level of the search for {links} links is 1..{links}")
    bounds = edge_bounds(links)
    current: list[Masks] = [(0,)]
    for _ in range(1, level):
        current = [child for parent in current for child in canonical_children(parent, links, bounds)]
    return current


def subtree_link_graphs(root: Masks, links: int) -> Iterator[Masks]:
    """The trusses with ``links`` links in the subtree of ``root`` (depth first), each
    isomorphism class once over all roots of one level.

    >>> sum(1 for root in augmentation_roots(11, 6) for _ in subtree_link_graphs(root, 11))
    562
    """
    bounds = edge_bounds(links)
    stack = [root]
    while stack:
        graph = stack.pop()
        if len(graph) == links:
            yield graph
        else:
            stack.extend(canonical_children(graph, links, bounds))
