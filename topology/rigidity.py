"""Mobility, rigid sub-chains and the Baranov-truss predicate.

A planar link has 3 degrees of freedom and a revolute (or slider) joint removes 2,
so a chain of L links and J joints has Grübler mobility F = 3(L-1) - 2J. A set S of
links, with e(S) joints among them, forms a **rigid sub-chain** when
2·e(S) ≥ 3|S| - 3 (its own mobility is ≤ 0).

A **Baranov truss** (thesis ch. 3; Manolescu's "basic truss") is a chain with F = 0,
i.e. J = 3(L-1)/2 revolute joints, in which no proper subset S of links with |S| ≥ 2 is
rigid: 2·e(S) ≤ 3|S| - 4. Removing any link from it leaves an Assur group.

Consequences used by the enumerators (proofs in :mod:`baranov.enumerate.trusses`):
every link has at least two joints, the link graph is 2-connected, and for L > 3 it is
triangle-free.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .chain import KinematicChain
from .errors import TopologyError

#: Largest link count for which all 2^L link subsets are tabulated at once with numpy.
SUBSET_TABLE_LIMIT = 24


def mobility(chain: KinematicChain) -> int:
    """Grübler–Kutzbach mobility F = 3(L - 1) - 2J of a planar chain (thesis §3.1).

    >>> from baranov.topology import chain_from_link_graph
    >>> mobility(chain_from_link_graph("Bw"))  # the triad
    0
    >>> mobility(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (0, 3)]))  # four-bar
    1
    """
    return 3 * (chain.number_of_links - 1) - 2 * chain.number_of_joints


def adjacency_masks(chain: KinematicChain) -> list[int]:
    """Link adjacency as bit masks: bit j of entry i is set when links i and j share a joint."""
    masks = [0] * chain.number_of_links
    for joint in chain.joints:
        a, b = joint.links
        masks[a] |= 1 << b
        masks[b] |= 1 << a
    return masks


def subset_edge_counts(masks: Sequence[int]) -> np.ndarray:
    """e(S) for every link subset S, indexed by the bit mask of S.

    Built by doubling: the subsets containing link i (as highest link) add to e(S \\ {i})
    the number of neighbours of i inside S. Time and memory O(2^L); L ≤ 24.

    >>> subset_edge_counts([0b110, 0b101, 0b011]).tolist()  # triangle
    [0, 0, 0, 1, 0, 1, 1, 3]
    """
    n = len(masks)
    if n > SUBSET_TABLE_LIMIT:
        raise ValueError(f"subset table for {n} links exceeds the limit of {SUBSET_TABLE_LIMIT}")
    counts = np.zeros(1, dtype=np.int16)
    for i in range(n):
        lower = np.arange(1 << i, dtype=np.int64)
        gained = np.bitwise_count(lower & (masks[i] & ((1 << i) - 1))).astype(np.int16)
        counts = np.concatenate([counts, counts + gained])
    return counts


def rigid_subset_masks(masks: Sequence[int], excess: int = 0, proper: bool = True) -> np.ndarray:
    """Bit masks of the link subsets S, |S| ≥ 2 (and S ≠ all links when ``proper``), with
    2·e(S) - 3|S| + 3 ≥ ``excess``: rigid for excess 0, over-constrained for excess 1."""
    n = len(masks)
    counts = subset_edge_counts(masks).astype(np.int32)
    subsets = np.arange(1 << n, dtype=np.int64)
    sizes = np.bitwise_count(subsets).astype(np.int32)
    selected = (2 * counts - 3 * sizes + 3 >= excess) & (sizes >= 2)
    if proper:
        selected &= sizes < n
    return subsets[selected]


def smallest_rigid_subchain(chain: KinematicChain) -> tuple[int, ...] | None:
    """The smallest proper set of ≥ 2 links that forms a rigid sub-chain, or ``None``.

    Among the smallest, the one with the lowest bit mask is returned, so the answer is
    deterministic. Complexity O(2^L) with numpy for L ≤ 24; above that, a search over
    connected link sets by increasing size (a smallest rigid set is connected: if S
    splits into parts S_1..S_k with no joint between them, then ``Σ(2e(S_i) - 3|S_i|) ≥ -3``
    forces some part with ``|S_i| ≥ 2`` to be rigid already).

    >>> from baranov.topology import chain_from_link_graph
    >>> # a triad (links 0,1,2) sharing link 2 with a four-bar loop: 5 links, 6 joints
    >>> chain = chain_from_link_graph([(0, 1), (1, 2), (0, 2), (2, 3), (3, 4), (4, 0)])
    >>> smallest_rigid_subchain(chain)
    (0, 1, 2)
    """
    return _smallest_subset(chain, 0, proper=True)


def _smallest_rigid_connected_set(masks: Sequence[int], excess: int = 0, proper: bool = True) -> tuple[int, ...] | None:
    n = len(masks)
    level = {1 << i for i in range(n)}
    for size in range(2, n if proper else n + 1):
        grown = set()
        for subset in level:
            frontier = 0
            for i in range(n):
                if subset >> i & 1:
                    frontier |= masks[i]
            frontier &= ~subset
            while frontier:
                bit = frontier & -frontier
                frontier ^= bit
                grown.add(subset | bit)
        rigid = [s for s in grown if 2 * _edges_inside(masks, s) - 3 * size + 3 >= excess]
        if rigid:
            best = min(rigid)
            return tuple(i for i in range(n) if best >> i & 1)
        level = grown
    return None


def _smallest_subset(chain: KinematicChain, excess: int, proper: bool) -> tuple[int, ...] | None:
    masks = adjacency_masks(chain)
    n = len(masks)
    if n > SUBSET_TABLE_LIMIT:
        return _smallest_rigid_connected_set(masks, excess, proper)
    found = rigid_subset_masks(masks, excess, proper)
    if found.size == 0:
        return None
    sizes = np.bitwise_count(found)
    best = int(found[sizes == sizes.min()].min())
    return tuple(i for i in range(n) if best >> i & 1)


def smallest_overconstrained_subchain(chain: KinematicChain) -> tuple[int, ...] | None:
    """The smallest set of ≥ 2 links (the whole chain included) with more joints than
    rigidity needs, 2·e(S) > 3|S| - 3, or ``None``. Same method as
    :func:`smallest_rigid_subchain`.

    >>> from baranov.topology import chain_from_link_graph
    >>> smallest_overconstrained_subchain(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)]))
    (0, 1, 2, 3)
    """
    return _smallest_subset(chain, 1, proper=False)


def require_rigid_chain(chain: KinematicChain) -> None:
    """Raise :class:`TopologyError` unless ``chain`` is rigid and not over-constrained:
    mobility 0 and no set of links with 2·e(S) > 3|S| - 3. Rigid proper sub-chains are
    allowed (a chain of triads is rigid: thesis §2.5.2, "ruler and compass").

    >>> from baranov.topology import chain_from_link_graph
    >>> two_triads = [(0, 1), (1, 2), (0, 2), (2, 3), (3, 4), (4, 2)]  # sharing link 2
    >>> require_rigid_chain(chain_from_link_graph(two_triads))
    >>> require_rigid_chain(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)]))
    Traceback (most recent call last):
    ...
    baranov.topology.errors.TopologyError: mobility F = 3(L-1) - 2J = -1 with L = 4 links and J = 5 joints; ...
    """
    _require_zero_mobility(chain, "a rigid chain")
    require_not_over_constrained(chain)


def require_one_dof_chain(chain: KinematicChain) -> None:
    """Raise :class:`TopologyError` unless ``chain`` moves with one degree of freedom for
    generic dimensions: mobility 1 and no over-constrained set of links (thesis §6.1:
    Grübler chains; rigid proper sub-chains are allowed).

    >>> from baranov.topology import chain_from_link_graph
    >>> require_one_dof_chain(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)]))  # four-bar
    """
    f = mobility(chain)
    if f != 1:
        raise TopologyError(
            f"mobility F = 3(L-1) - 2J = {f} with L = {chain.number_of_links} links and "
            f"J = {chain.number_of_joints} joints; a one-degree-of-freedom chain needs F = 1"
            + ("; this chain is rigid: its assembly modes are found by baranov solve SCENE "
               "(baranov.solve in Python)" if f == 0 else "")
        )
    require_not_over_constrained(chain)


def require_not_over_constrained(chain: KinematicChain) -> None:
    """Raise :class:`TopologyError` if some set of links S has 2·e(S) > 3|S| − 3 (more
    joints than rigidity needs: its dimensions could not be chosen freely), the whole
    chain included. A chain with mobility F > 0 that passes moves with F degrees of
    freedom for generic dimensions (thesis §6.1: Grübler chains).

    >>> from baranov.topology import chain_from_link_graph
    >>> require_not_over_constrained(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)]))  # four-bar
    """
    over = smallest_overconstrained_subchain(chain)
    if over is not None:
        listed, joints = _describe_links(chain, over)
        raise TopologyError(
            f"links {listed} are over-constrained ({len(over)} links, {joints} joints, "
            f"mobility {3 * (len(over) - 1) - 2 * joints})"
        )


def _edges_inside(masks: Sequence[int], subset: int) -> int:
    return sum((masks[i] & subset).bit_count() for i in range(len(masks)) if subset >> i & 1) // 2


def is_baranov_link_graph(masks: Sequence[int]) -> bool:
    """Baranov predicate on a link graph given by adjacency bit masks.

    True when L = len(masks) is odd, the graph has 3(L-1)/2 edges, and no proper link
    subset S with ``|S| ≥ 2`` has ``2·e(S) > 3|S| - 4``. (Connectivity and "every link has two
    joints" follow from the counts.) O(2^L) for L ≤ 24.

    >>> is_baranov_link_graph([0b110, 0b101, 0b011])  # the triad
    True
    """
    n = len(masks)
    edges = sum(mask.bit_count() for mask in masks) // 2
    if n < 3 or 2 * edges != 3 * (n - 1):
        return False
    if n <= SUBSET_TABLE_LIMIT:
        return rigid_subset_masks(masks).size == 0
    return _smallest_rigid_connected_set(masks) is None


def is_baranov_truss(chain: KinematicChain) -> bool:
    """Whether the chain's topology is a Baranov truss (see the module docstring).

    Only the link graph is examined: a chain with slider joints and the same link graph
    (an Assur kinematic chain, thesis ch. 4) passes too.

    >>> from baranov.topology import chain_from_link_graph
    >>> is_baranov_truss(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    True
    """
    return mobility(chain) == 0 and smallest_rigid_subchain(chain) is None


def require_baranov_truss(chain: KinematicChain) -> None:
    """Raise :class:`TopologyError` explaining why ``chain`` is not a Baranov truss.

    >>> from baranov.topology import chain_from_link_graph
    >>> require_baranov_truss(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (0, 3)]))
    Traceback (most recent call last):
    ...
    baranov.topology.errors.TopologyError: mobility F = 3(L-1) - 2J = 1 with L = 4 links and J = 4 joints; a truss needs F = 0
    """
    _require_zero_mobility(chain, "a truss")
    rigid = smallest_rigid_subchain(chain)
    if rigid is not None:
        listed, joints = _describe_links(chain, rigid)
        raise TopologyError(
            f"links {listed} form a rigid sub-chain ({len(rigid)} links, {joints} joints): "
            "not a Baranov truss"
        )


def _require_zero_mobility(chain: KinematicChain, what: str) -> None:
    f = mobility(chain)
    if f != 0:
        raise TopologyError(
            f"mobility F = 3(L-1) - 2J = {f} with L = {chain.number_of_links} links and "
            f"J = {chain.number_of_joints} joints; {what} needs F = 0"
        )


def _describe_links(chain: KinematicChain, links: tuple[int, ...]) -> tuple[str, int]:
    """User-facing list of ``links`` and the number of joints among them."""
    joints = _edges_inside(adjacency_masks(chain), sum(1 << i for i in links))
    return ", ".join(chain.link_name(link) for link in links), joints
