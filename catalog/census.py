"""The census of a link count too large for catalog entries (15 links, issue 20): how many
Baranov trusses and Assur groups there are, by two independent methods compared as sets of
isomorphism classes, their invariants, and the coupling-degree distribution on a random
sample with its confidence intervals.

Method A is the library's generator by canonical augmentation
(:mod:`baranov.enumerate.augmentation`): the search tree is cut at ``split_level``
vertices and each subtree is a task. Method B is geng's candidates filtered by the Baranov
predicate (:mod:`baranov.enumerate.crosscheck`), one task per class of geng's ``res/mod``
split. Both run as Dask tasks in resumable shards (:mod:`.tasks`). Each truss is
represented by a digest of its nauty certificate (96 bits of BLAKE2b: the chance that two
of a million classes share one is below 10⁻¹⁷), which is also the sampling key: a truss
is in the sample when the top ``sample_bits`` bits of its digest are zero, a uniformly
random subset of the classes of the expected size N / 2^sample_bits that both methods and
every rerun agree on.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import networkx as nx
import pynauty

from baranov.enumerate.augmentation import augmentation_roots, subtree_link_graphs
from baranov.enumerate.crosscheck import filter_part, find_geng
from baranov.enumerate.trusses import Masks, canonical_trusses
from baranov.planner import best_plan
from baranov.topology import chain_from_link_graph
from baranov.topology.automorphisms import group_order, nauty_link_graph

from .progress import progress_bar
from .tasks import run_in_shards, shard_folder

#: Vertices of the roots of method A's subtrees (1 770 roots for 15 links).
SPLIT_LEVEL = 10
#: Classes of geng's res/mod split (method B's tasks).
FILTER_PARTS = 256
#: A truss is in the coupling-degree sample with probability 2^-SAMPLE_BITS.
SAMPLE_BITS = 9
#: Two-sided normal quantile of the 95 % Wilson intervals.
Z_95 = 1.959963984540054


def truss_digest(masks: Masks, graph: pynauty.Graph | None = None) -> str:
    """96-bit hex digest of the nauty certificate of a link graph (isomorphism invariant);
    ``graph``: its pynauty graph, if already built."""
    graph = graph or nauty_link_graph(masks)
    return hashlib.blake2b(pynauty.certificate(graph), digest_size=12).hexdigest()


def in_sample(digest: str, sample_bits: int) -> bool:
    """Whether a truss with this digest belongs to the sample of 2^-sample_bits."""
    return int(digest[:8], 16) >> (32 - sample_bits) == 0


def subtree_census(job: tuple[Masks, int, int]) -> dict:
    """Method A on one subtree: its trusses' count, Assur groups (link orbits), invariants,
    sorted digests, and the graph6 of its sampled trusses. ``job`` = (root, links,
    sample_bits)."""
    root, links, sample_bits = job
    orders: Counter = Counter()
    degrees: Counter = Counter()
    assur_groups = non_planar = 0
    digests, sample = [], []
    for masks in subtree_link_graphs(root, links):
        nauty_graph = nauty_link_graph(masks)  # one for the group and the digest
        _, mantissa, exponent, _, orbit_count = pynauty.autgrp(nauty_graph)
        orders[group_order(mantissa, exponent)] += 1
        degrees[max(mask.bit_count() for mask in masks)] += 1
        assur_groups += orbit_count
        graph = nx.Graph((i, j) for i, mask in enumerate(masks) for j in range(i) if mask >> j & 1)
        non_planar += not nx.check_planarity(graph)[0]
        digest = truss_digest(masks, nauty_graph)
        digests.append(digest)
        if in_sample(digest, sample_bits):
            sample.append(masks)
    return {"trusses": len(digests), "assur_groups": assur_groups, "non_planar": non_planar,
            "automorphism_group_orders": _keyed(orders), "largest_link_degree": _keyed(degrees),
            "digests": sorted(digests), "sample": [graph6 for graph6, _ in canonical_trusses(sample)]}


def subtree_masks(job: tuple[Masks, int]) -> list[list[int]]:
    """Method A on one subtree, the trusses themselves (adjacency masks): the catalog's
    enumeration task up to 13 links. ``job`` = (root, links)."""
    root, links = job
    return [list(masks) for masks in subtree_link_graphs(root, links)]


def enumerate_in_tasks(links: int, folder: Path, client: Any = None, split_level: int = SPLIT_LEVEL) -> list[Masks]:
    """Every truss with ``links`` links (adjacency masks), by subtrees of the canonical
    augmentation run as tasks (on ``client`` if given, shards in ``folder``)."""
    roots = augmentation_roots(links, min(split_level, links))
    found = run_in_shards(subtree_masks, [(root, links) for root in roots], folder, client)
    return [tuple(masks) for result in found for masks in result]


def filter_in_tasks(links: int, folder: Path, client: Any = None, parts: int = FILTER_PARTS) -> tuple[int, set[str]]:
    """Method B as tasks: the number of geng's candidates and the digests of the trusses
    among them."""
    checked = run_in_shards(filter_census, [(links, part, parts) for part in range(parts)], folder, client)
    return sum(result["candidates"] for result in checked), {d for result in checked for d in result["digests"]}


def filter_census(job: tuple[int, int, int]) -> dict:
    """Method B on one res/mod class: candidates, trusses, sorted digests. ``job`` =
    (links, part, parts); geng is looked for where the task runs (a cluster's workers have
    their own)."""
    links, part, parts = job
    geng = find_geng()
    if geng is None:
        raise FileNotFoundError("geng not found on a worker: pip install --no-deps passagemath-nauty there")
    candidates, found = filter_part(links, part, parts, geng)
    return {"candidates": candidates, "trusses": len(found), "digests": sorted(map(truss_digest, found))}


def sample_coupling_degree(graph6: str) -> int:
    """The coupling degree of one sampled truss (:func:`baranov.planner.best_plan`)."""
    return best_plan(chain_from_link_graph(graph6)).number_of_parameters


def wilson_interval(successes: int, trials: int, z: float = Z_95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (E. B. Wilson, J. Amer. Statist.
    Assoc. 22 (1927) 209–212).

    >>> [round(x, 4) for x in wilson_interval(0, 100)]
    [0.0, 0.037]
    """
    if trials == 0:
        return 0.0, 1.0
    p = successes / trials
    centre = (p + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / (1 + z * z / trials)
    # at p = 0 and p = 1 the interval ends at 0 and 1 exactly; floats would miss by an ulp
    return (0.0 if successes == 0 else centre - half), (1.0 if successes == trials else centre + half)


def truss_census(links: int, folder: Path | None, client: Any = None, show_progress: bool = False,
                 split_level: int = SPLIT_LEVEL, parts: int = FILTER_PARTS, sample_bits: int = SAMPLE_BITS,
                 crosscheck: bool = True) -> dict:
    """The census of ``links``-link trusses (module docstring) as a JSON object; the
    shards of the three task lists are kept in ``folder`` until it is done, so that an
    interrupted census resumes."""
    roots = augmentation_roots(links, min(split_level, links))
    crosscheck = crosscheck and find_geng() is not None
    with shard_folder(folder) as where:
        found = _run("method A", subtree_census, [(root, links, sample_bits) for root in roots],
                     where / "method-a", client, show_progress)
        checked = (_run("method B", filter_census, [(links, part, parts) for part in range(parts)],
                        where / "method-b", client, show_progress) if crosscheck else None)
        sample = sorted(graph6 for result in found for graph6 in result["sample"])
        degrees = _run("coupling degree", sample_coupling_degree, sample, where / "sample", client, show_progress)
    return _census_object(links, found, checked, sample, degrees, split_level, len(roots), parts, sample_bits)


def _run(what: str, function, jobs: list, folder: Path, client: Any, show_progress: bool) -> list:
    bar = progress_bar(len(jobs), what, "task", show_progress)
    try:
        return run_in_shards(function, jobs, folder, client, advance=bar.update)
    finally:
        bar.close()


def _census_object(links: int, found: list[dict], checked: list[dict] | None, sample: list[str],
                   degrees: Sequence[int], split_level: int, roots: int, parts: int, sample_bits: int) -> dict:
    ours = [digest for result in found for digest in result["digests"]]
    census: dict = {
        "links": links,
        "trusses": len(ours),
        "distinct_classes": len(set(ours)) == len(ours),
        "assur_groups": sum(result["assur_groups"] for result in found),
        "non_planar": sum(result["non_planar"] for result in found),
        "automorphism_group_orders": _summed(found, "automorphism_group_orders"),
        "largest_link_degree": _summed(found, "largest_link_degree"),
        "method_a": f"canonical augmentation, {roots} subtrees rooted at {split_level} links",
        "method_b": None,
    }
    if checked is not None:
        theirs = [digest for result in checked for digest in result["digests"]]
        census["method_b"] = {
            "method": f"geng -c -d2 L J:J in {parts} res/mod classes, filtered by the Baranov predicate",
            "candidates": sum(result["candidates"] for result in checked),
            "trusses": len(theirs),
            "same_isomorphism_classes": set(theirs) == set(ours),
        }
    counts = Counter(degrees)
    observed = range(min(counts, default=1), max(counts, default=0) + 2)  # and the next degree, unseen
    census["coupling_degree_sample"] = {
        "rule": f"digest's top {sample_bits} bits zero (expected fraction 1/{2 ** sample_bits})",
        "size": len(sample),
        "counts": _keyed(counts),
        "wilson_95": {str(d): [round(x, 4) for x in wilson_interval(n, len(sample))] for d in observed
                      for n in [counts[d]]},
        "sample": dict(zip(sample, degrees, strict=True)),
    }
    return census


def _keyed(counter: Counter) -> dict[str, int]:
    return {str(key): counter[key] for key in sorted(counter)}


def _summed(results: list[dict], field: str) -> dict[str, int]:
    total: Counter = Counter()
    for result in results:
        total.update({int(key): value for key, value in result[field].items()})
    return _keyed(total)


def census_path(out: Path, links: int) -> Path:
    """Where the census of ``links`` links is kept in a catalog folder."""
    return out / f"census-{links}.json"


def load_census(path: Path) -> dict | None:
    """The census saved at ``path``, or None if there is none (or it is unreadable)."""
    try:
        census = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return census if isinstance(census, dict) and "trusses" in census else None


def dump_census(census: dict) -> str:
    """The census as the JSON text of its file."""
    return json.dumps(census, indent=1) + "\n"
