"""Enumeration of the Grübler chains: one-degree-of-freedom planar linkages of revolute
joints without a rigid sub-chain (thesis §6.1; the four-bar, the Watt and Stephenson
six-bars, the 16 eight-bar chains, 230 ten-bar chains).

A Grübler chain with L links (L even) is a link graph with J = (3L − 4)/2 edges, mobility
3(L − 1) − 2J = 1, in which every proper link subset S with |S| ≥ 2 has 2·e(S) ≤ 3|S| − 4
(it moves on its own: a subset with 2·e(S) ≥ 3|S| − 3 would be a rigid or
over-constrained sub-chain, a degenerate chain). The whole graph is then connected and
every link has at least two joints, as for the Baranov trusses (enumerate/trusses.py:
the same counting arguments with 3L − 4 for 3L − 3).

**Algorithm.** geng (nauty) lists the connected graphs with L vertices, J edges and
minimum degree 2, one per isomorphism class; the subset condition keeps the chains
(:func:`~baranov.topology.rigidity.rigid_subset_masks`). Cost: geng's output (1, 5, 71,
1878 graphs for 4, 6, 8, 10 links) times O(2^L) each. Reference: the counts 1, 2, 16, 230
are the classical ones (e.g. T. S. Mruthyunjaya, *Kinematic structure of mechanisms
revisited*, Mech. Mach. Theory 38 (2003) 279–320).
"""

from __future__ import annotations

import subprocess

from baranov.topology import KinematicChain
from baranov.topology.rigidity import rigid_subset_masks

from .crosscheck import find_geng, graph6_masks
from .trusses import chains_from_masks


def check_grubler_link_count(links: int) -> None:
    """Raise ValueError unless ``links`` is an even number ≥ 4 (J = (3L − 4)/2 whole)."""
    if isinstance(links, bool) or not isinstance(links, int) or links < 4 or links % 2:
        raise ValueError(f"links={links!r}: a Grübler chain has an even number of links, at least 4")


def grubler_link_graphs(links: int, geng: str | None = None) -> list[tuple[int, ...]]:
    """The Grübler chains with ``links`` links as link graphs (adjacency bit masks), one
    per isomorphism class, in geng's order. Raises ``FileNotFoundError`` without geng.

    >>> [len(grubler_link_graphs(links)) for links in (4, 6, 8)]  # doctest: +SKIP
    [1, 2, 16]
    """
    check_grubler_link_count(links)
    geng = geng or find_geng()
    if geng is None:
        raise FileNotFoundError("geng not found: pip install --no-deps passagemath-nauty, or set BARANOV_GENG")
    joints = (3 * links - 4) // 2
    output = subprocess.run([geng, "-c", "-d2", "-q", str(links), f"{joints}:{joints}"], check=True,
                            capture_output=True).stdout
    graphs = (graph6_masks(line) for line in output.split())
    return [masks for masks in graphs if rigid_subset_masks(masks).size == 0]


def grubler_chains(links: int) -> list[KinematicChain]:
    """:func:`grubler_link_graphs` as kinematic chains (joints named as for the trusses)."""
    return chains_from_masks(grubler_link_graphs(links))


#: The published counts of Grübler chains (one degree of freedom, revolute joints, no
#: rigid sub-chain): 4–10 links the classical ones (Mruthyunjaya 2003), 12 and 14 links
#: Sunkari and Schmidt, Mech. Mach. Theory 41 (2006) 1021–1030 (OEIS A233288).
PUBLISHED_COUNTS = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856, 14: 318_162}
#: The catalog job counts the Grübler chains up to this many links (12: 15 s; 14 takes
#: about 36 min, a slow test).
CENSUS_LINKS = 12


def grubler_counts(max_links: int, geng: str | None = None) -> dict[int, int]:
    """The number of Grübler chains of each even link count from 4 to ``max_links`` (at
    most CENSUS_LINKS), one per isomorphism class. Cost: that of :func:`grubler_link_graphs`
    for the largest count (15 s at 12 links)."""
    return {links: len(grubler_link_graphs(links, geng)) for links in range(4, min(max_links, CENSUS_LINKS) + 1, 2)}
