"""Independent second enumeration of Baranov trusses, for cross-checking.

Brute force: nauty's ``geng`` lists every connected graph with L vertices, J = 3(L-1)/2
edges and minimum degree 2 (up to isomorphism); each is kept when it satisfies the
Baranov predicate :func:`baranov.topology.is_baranov_link_graph` (full 2^L subset test),
and the survivors are deduplicated with pynauty certificates. It shares no pruning or
generation code with :mod:`baranov.enumerate.trusses`.

``geng`` is not part of the library's dependencies: it comes from the PyPI wheel
``passagemath-nauty`` (installed with ``--no-deps`` by ``make test``), from ``PATH``, or
from the ``BARANOV_GENG`` environment variable. Candidate counts measured with geng
2.8 (``geng -c -d2 -u``): 31 (L = 7), 707 (9), 27 678 (11), 1 567 236 (13).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import networkx as nx

from baranov.enumerate.parallel import worker_pool
from baranov.topology import is_baranov_link_graph
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


def _filter_part(job: tuple[str, int, int, int]) -> tuple[int, dict[bytes, tuple[int, ...]]]:
    geng, links, part, parts = job
    joints = 3 * (links - 1) // 2
    command = [geng, "-c", "-d2", "-q", str(links), f"{joints}:{joints}", f"{part}/{parts}"]
    output = subprocess.run(command, check=True, capture_output=True).stdout
    candidates = 0
    found: dict[bytes, tuple[int, ...]] = {}
    for line in output.split():
        candidates += 1
        masks = graph6_masks(line)
        if is_baranov_link_graph(masks):
            found.setdefault(link_graph_certificate(masks), masks)
    return candidates, found


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
            results = pool.map(_filter_part, jobs)
    else:
        results = [_filter_part(job) for job in jobs]
    candidates = sum(count for count, _ in results)
    merged: dict[bytes, tuple[int, ...]] = {}
    for _, found in results:
        for key, masks in found.items():
            merged.setdefault(key, masks)
    return candidates, list(merged.values())
