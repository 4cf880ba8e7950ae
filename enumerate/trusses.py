"""Enumeration of all Baranov trusses with a given number of links.

A Baranov truss with L links is a link graph G with J = 3(L-1)/2 edges in which every
proper vertex subset S with |S| ≥ 2 satisfies 2·e(S) ≤ 3|S| - 4 (see
:mod:`baranov.topology.rigidity`). Facts used to prune the search, with proofs:

1. *Heredity.* Every induced subgraph of G on k < L vertices satisfies the subset
   condition for all its own subsets, itself included (they are proper subsets of G).
2. *Minimum degree 2.* With S = V - {v}: 2(J - deg v) ≤ 3(L-1) - 4, i.e. deg v ≥ 2.
3. *Triangle-free for L > 3.* Three mutually adjacent links form S with 2·3 > 3·3 - 4
   (a rigid triad inside the truss).
4. *There is a binary link.* With n_k links of degree k, Σ n_k = L and Σ k·n_k = 2J =
   3L - 3 give Σ (k - 3)·n_k = -3, so n_2 = 3 + Σ_{k≥4} (k-3)·n_k ≥ 3: min degree is 2.
5. *Edge bounds along a min-degree deletion order.* Let G_L = G and G_{j-1} = G_j minus a
   vertex of minimum degree. Then e(G_{j-1}) = e(G_j) - δ(G_j) ≥ e(G_j) - ⌊2e(G_j)/j⌋;
   x ↦ x - ⌊2x/j⌋ is non-decreasing for j ≥ 2, so e(G_j) ≥ lower(j) with lower(L) = J and
   lower(j-1) = lower(j) - ⌊2·lower(j)/j⌋. By 1, e(G_j) ≤ ⌊(3j - 4)/2⌋ for 2 ≤ j < L.
   For L = 13 this pins e(G_12) = 16 and e(G_11) = 14.
6. *Connectivity* follows from the counts: components A, B with |A|, |B| ≥ 2 would give
   2J ≤ 3L - 8 (and a single-vertex component has degree 0, against 2).

**Algorithm.** Vertices are added one at a time; the new vertex must have minimum
degree in the new graph, so by 5 every truss is reached along its min-degree deletion
order. Each level keeps one graph per isomorphism class (nauty certificates through
pynauty), children must satisfy 1, 3 (L > 3) and the edge bounds of 5; at the last
level the subset condition is checked for the proper subsets only and the edge count
must be J. The subset condition for sets containing the new vertex v is checked at once
for all 2^k sets S of old vertices: 2(e(S) + |N(v) ∩ S|) ≤ 3(|S| + 1) - 4.

This is a level-by-level variant of generation by canonical deletion (B. D. McKay,
*Isomorph-free exhaustive generation*, J. Algorithms 26 (1998) 306–324), with
per-level deduplication instead of the canonical-parent test.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from contextlib import nullcontext
from itertools import combinations

import numpy as np

from baranov.topology import (
    KinematicChain,
    canonical_link_graph6,
    chain_from_link_graph,
    degree_sequence,
)
from baranov.topology.automorphisms import link_graph_certificate
from baranov.topology.rigidity import subset_edge_counts

from .parallel import worker_pool

Masks = tuple[int, ...]

def check_link_count(links: int) -> None:
    """Raise ValueError unless ``links`` is an odd number ≥ 3 (J = 3(L-1)/2 must be whole)."""
    if isinstance(links, bool) or not isinstance(links, int) or links < 3 or links % 2 == 0:
        raise ValueError(f"links={links!r}: a Baranov truss has an odd number of links, at least 3")


def edge_bounds(links: int) -> list[tuple[int, int]]:
    """``bounds[j] = (lower, upper)`` on e(G_j) for the j-vertex graphs of the search (fact 5).

    >>> edge_bounds(13)[11:]
    [(14, 14), (16, 16), (18, 18)]
    """
    check_link_count(links)
    joints = 3 * (links - 1) // 2
    lower = [0] * (links + 1)
    lower[links] = joints
    for j in range(links, 1, -1):
        lower[j - 1] = lower[j] - (2 * lower[j]) // j
    bounds = [(0, 0), (0, 0)]
    for j in range(2, links):
        bounds.append((lower[j], (3 * j - 4) // 2))
    bounds.append((joints, joints))
    return bounds


def children(parent: Masks, links: int, bounds: Sequence[tuple[int, int]]) -> list[Masks]:
    """All children of ``parent`` (k vertices) obtained by adding a min-degree vertex."""
    k = len(parent)
    final = k + 1 == links
    degrees = [mask.bit_count() for mask in parent]
    edges = sum(degrees) // 2
    low, high = bounds[k + 1]
    subsets = np.arange(1 << k, dtype=np.int64)
    sizes = np.bitwise_count(subsets).astype(np.int32)
    slack = 3 * (sizes + 1) - 4 - 2 * subset_edge_counts(parent).astype(np.int32)
    slack[0] = 1 << 20
    if final:
        slack[-1] = 1 << 20  # the whole truss is not a proper subset
    triangle_free = links > 3
    result = []
    for degree in range(max(low - edges, 0), min(high - edges, k) + 1):
        forced = [u for u in range(k) if degrees[u] < degree]
        if any(degrees[u] < degree - 1 for u in forced) or len(forced) > degree:
            continue
        forced_mask = sum(1 << u for u in forced)
        optional = [u for u in range(k) if degrees[u] >= degree]
        for extra in combinations(optional, degree - len(forced)):
            neighbours = forced_mask | sum(1 << u for u in extra)
            if triangle_free and any(parent[u] & neighbours for u in range(k) if neighbours >> u & 1):
                continue
            inside = np.bitwise_count(subsets & neighbours).astype(np.int32)
            if np.any(2 * inside > slack):
                continue
            child = tuple(parent[u] | (1 << k) if neighbours >> u & 1 else parent[u] for u in range(k))
            result.append(child + (neighbours,))
    return result


def _expand(job: tuple[list[Masks], int]) -> dict[bytes, Masks]:
    parents, links = job
    bounds = edge_bounds(links)
    found: dict[bytes, Masks] = {}
    for parent in parents:
        for child in children(parent, links, bounds):
            found.setdefault(link_graph_certificate(child), child)
    return found


def baranov_link_graphs(
    links: int,
    workers: int = 1,
    progress: Callable[[int, int], None] | None = None,
) -> list[Masks]:
    """All Baranov trusses with ``links`` links as adjacency bit masks, one per
    isomorphism class, in no particular order (see the module docstring).

    ``workers > 1`` expands each level in that many processes. ``progress(level, count)``
    is called after each level. Measured on 2 cores: see ``bench/bench_enumeration.py``.
    """
    check_link_count(links)
    level: dict[bytes, Masks] = {b"": (0,)}
    chunk = 2000
    with worker_pool(workers) if workers > 1 else nullcontext() as pool:
        for size in range(1, links):
            parents = list(level.values())
            jobs = [(parents[i:i + chunk], links) for i in range(0, len(parents), chunk)]
            results = pool.imap(_expand, jobs) if pool else map(_expand, jobs)
            merged: dict[bytes, Masks] = {}
            for found in results:
                for key, graph in found.items():
                    merged.setdefault(key, graph)
            level = merged
            if progress:
                progress(size + 1, len(level))
    return list(level.values())


def truss_sort_key(chain: KinematicChain) -> tuple:
    """Deterministic catalog order: degree sequence (descending, largest first), then
    the canonical graph6 string of the link graph."""
    return (tuple(-d for d in degree_sequence(chain)), canonical_link_graph6(chain))


def canonical_trusses(graphs: Iterable[Masks]) -> list[tuple[str, KinematicChain]]:
    """(canonical graph6, chain in canonical labelling) from adjacency bit masks, in catalog
    order (:func:`truss_sort_key`); one canonical labelling per graph."""
    found = []
    for masks in graphs:
        edges = [(i, j) for i, mask in enumerate(masks) for j in range(i + 1, len(masks)) if mask >> j & 1]
        graph6 = canonical_link_graph6(chain_from_link_graph(edges))
        chain = chain_from_link_graph(graph6)
        found.append(((tuple(-d for d in degree_sequence(chain)), graph6), graph6, chain))
    found.sort(key=lambda item: item[0])
    return [(graph6, chain) for _, graph6, chain in found]


def chains_from_masks(graphs: Iterable[Masks]) -> list[KinematicChain]:
    """Chains in canonical labelling and catalog order from adjacency bit masks."""
    return [chain for _, chain in canonical_trusses(graphs)]


def baranov_trusses(links: int, workers: int = 1) -> list[KinematicChain]:
    """All non-isomorphic Baranov trusses with ``links`` links, in catalog order.

    Each truss is returned with its canonically labelled link graph (links renumbered
    in nauty's canonical order, joints ``P1..PJ`` in sorted edge order), so the result is
    the same from run to run. Order: :func:`truss_sort_key`.

    >>> [len(baranov_trusses(n)) for n in (3, 5, 7, 9)]
    [1, 1, 3, 28]
    >>> baranov_trusses(4)
    Traceback (most recent call last):
    ...
    ValueError: links=4: a Baranov truss has an odd number of links, at least 3
    """
    return chains_from_masks(baranov_link_graphs(links, workers))
