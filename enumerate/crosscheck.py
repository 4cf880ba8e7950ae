"""Independent second enumeration of Baranov trusses, for cross-checking.

Brute force: nauty's ``geng`` lists every connected graph with L vertices, J = 3(L-1)/2
edges and minimum degree 2 (up to isomorphism); each is kept when it satisfies the
Baranov predicate (:func:`baranov_rows`: the full 2^L subset test of
:func:`baranov.topology.is_baranov_link_graph`, on blocks of candidates at once), and the
survivors are deduplicated with pynauty certificates. It shares no pruning or
generation code with :mod:`baranov.enumerate.trusses`.

``geng`` is not part of the library's dependencies: it comes from the PyPI wheel
``passagemath-nauty`` (installed with ``--no-deps`` by ``make test``), from ``PATH``, or
from the ``BARANOV_GENG`` environment variable. Candidate counts measured with geng
2.8 (``geng -c -d2 -u``): 31 (L = 7), 707 (9), 27 678 (11), 1 567 236 (13), 115 275 652 (15).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import networkx as nx
import numpy as np

from baranov.enumerate.parallel import worker_pool
from baranov.topology.automorphisms import link_graph_certificate

from .trusses import check_link_count


def find_geng() -> str | None:
    """Path of a usable ``geng`` executable, or ``None``."""
    candidates = [os.environ.get("BARANOV_GENG"), shutil.which("geng")]
    for root in {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"], *sys.path}:
        candidates.append(str(Path(root) / "sage_wheels" / "bin" / "geng"))
    for candidate in candidates:
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None


def graph6_masks(line: bytes) -> tuple[int, ...]:
    """A graph6 line (geng's output) as adjacency bit masks."""
    graph = nx.from_graph6_bytes(line)
    masks = [0] * graph.number_of_nodes()
    for u, v in graph.edges:
        masks[u] |= 1 << v
        masks[v] |= 1 << u
    return tuple(masks)


def filter_part(links: int, part: int, parts: int, geng: str) -> tuple[int, list[tuple[int, ...]]]:
    """Class ``part`` of ``parts`` of geng's candidates (its ``res/mod`` split): the number
    of candidates and those that are Baranov trusses, as adjacency bit masks."""
    joints = 3 * (links - 1) // 2
    command = [geng, "-c", "-d2", "-q", str(links), f"{joints}:{joints}", f"{part}/{parts}"]
    output = subprocess.run(command, check=True, capture_output=True).stdout
    masks = graph6_block_masks(output, links)
    kept = masks[baranov_rows(masks)]
    return len(masks), [tuple(int(mask) for mask in row) for row in kept]


def _filter_job(job: tuple[str, int, int, int]) -> tuple[int, list[tuple[int, ...]]]:
    geng, links, part, parts = job
    return filter_part(links, part, parts, geng)


def baranov_link_graphs_by_filter(links: int, workers: int = 1, geng: str | None = None) -> tuple[int, list[tuple[int, ...]]]:
    """Baranov trusses by brute force over geng's output.

    Returns ``(candidates, graphs)``: the number of connected min-degree-2 graphs
    examined and the trusses as adjacency bit masks. Raises ``FileNotFoundError`` when no
    geng is found. Work is split over ``workers`` processes with geng's ``res/mod``.
    """
    check_link_count(links)
    geng = geng or find_geng()
    if geng is None:
        raise FileNotFoundError("geng not found: pip install --no-deps passagemath-nauty, or set BARANOV_GENG")
    parts = max(1, workers) * 4 if links >= 11 else 1
    jobs = [(geng, links, part, parts) for part in range(parts)]
    if workers > 1:
        with worker_pool(workers) as pool:
            results = pool.map(_filter_job, jobs)
    else:
        results = [_filter_job(job) for job in jobs]
    candidates = sum(count for count, _ in results)
    merged: dict[bytes, tuple[int, ...]] = {}
    for _, found in results:
        for masks in found:
            merged.setdefault(link_graph_certificate(masks), masks)
    return candidates, list(merged.values())


def graph6_block_masks(block: bytes, vertices: int) -> np.ndarray:
    """Adjacency bit masks, shape (N, vertices), of a block of N newline-ended graph6
    lines of one vertex count (2 ≤ vertices ≤ 62), decoded in one array operation.

    graph6 lists the upper triangle column by column (x(0,1), x(0,2), x(1,2), x(0,3), …),
    six bits to a byte, each byte offset by 63 (B. D. McKay, *graph6 and sparse6 formats*).

    >>> graph6_block_masks(b"DFw\\nD]o\\n", 5).tolist()  # the pentad, twice labelled
    [[24, 24, 24, 7, 7], [28, 28, 3, 3, 3]]
    """
    pairs = [(i, j) for j in range(1, vertices) for i in range(j)]
    width = 1 + -(-len(pairs) // 6)
    rows = np.frombuffer(block, dtype=np.uint8)
    if rows.size % (width + 1) == 0:
        rows = rows.reshape(-1, width + 1)
    if rows.ndim == 1 or rows.size and (np.any(rows[:, 0] != vertices + 63) or np.any(rows[:, -1] != 10)):
        raise ValueError(f"not a block of graph6 lines with {vertices} vertices")
    # byte b holds pairs 6b..6b+5, most significant bit first: one table of the masks'
    # contributions per byte position, indexed by the byte's 64 values
    values = np.arange(64)
    masks = np.zeros((len(rows), vertices), dtype=np.int64)
    for byte in range(width - 1):
        table = np.zeros((64, vertices), dtype=np.int64)
        for bit, (i, j) in enumerate(pairs[6 * byte:6 * byte + 6]):
            present = (values >> (5 - bit) & 1).astype(bool)
            table[present, i] |= 1 << j
            table[present, j] |= 1 << i
        masks |= table[rows[:, 1 + byte] - 63]
    return masks


def baranov_rows(masks: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """The Baranov predicate (:func:`~baranov.topology.is_baranov_link_graph`) on each row
    of an (N, L) array of adjacency masks, as a boolean array.

    Three instances of the subset condition are tested first on all rows at once, because
    they reject most candidates for a few array operations each: a triangle (3 links, 3
    joints; for L > 3), two links with three common neighbours (5 links, 6 joints; for
    L > 5) and two adjacent binary links (the other L − 2 links hold all joints but 3:
    2(J − 3) > 3(L − 2) − 4; for L > 3).
    The rows left get every proper subset counted (2^L per row, ``chunk`` rows at a time).
    """
    rows, links = masks.shape
    keep = np.full(rows, 2 * np.bitwise_count(masks).sum(axis=1) == 6 * (links - 1))
    degrees = np.bitwise_count(masks)
    for j in range(links):
        for i in range(j):
            adjacent = (masks[:, i] >> j & 1).astype(bool)
            common = np.bitwise_count(masks[:, i] & masks[:, j])
            if links > 3:  # each set below is then a proper subset
                keep &= ~(adjacent & ((common > 0) | ((degrees[:, i] == 2) & (degrees[:, j] == 2))))
            if links > 5:
                keep &= common < 3
    survivors = np.flatnonzero(keep)
    subsets = np.arange(1 << links, dtype=np.int64)
    sizes = np.bitwise_count(subsets).astype(np.int16)
    limit = np.where((sizes >= 2) & (sizes < links), (3 * sizes - 4) // 2, 127).astype(np.int8)
    for start in range(0, len(survivors), chunk):
        block = masks[survivors[start:start + chunk]]
        counts = np.zeros((len(block), 1), dtype=np.int8)
        for i in range(links):
            lower = np.arange(1 << i, dtype=np.int64)
            gained = np.bitwise_count(lower[None, :] & (block[:, i:i + 1] & ((1 << i) - 1))).astype(np.int8)
            counts = np.concatenate([counts, counts + gained], axis=1)
        keep[survivors[start:start + chunk]] = ~np.any(counts > limit, axis=1)
    return keep
