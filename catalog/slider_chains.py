"""The catalog's slider chains: every chain derived from a Baranov truss by turning an
admissible set of its joints into slider joints (thesis ch. 4), one per isomorphism
class (:func:`~baranov.enumerate.sliders.slider_chains`), with its generic number of
assembly modes (:func:`~baranov.solvers.mode_counts.slider_chain_degree`) and msolve's
count of the complex solutions of its Cartesian system on another random instance as an
independent check (:func:`~baranov.solvers.msolve.msolve_solution_count_modulo`, modulo a
random prime below 2³⁰: the modes, times 2 per auxiliary root of the system; over Q until
2026-11-26, every 25th nine-link chain, now every chain). The literature has no such table; thesis Tables 5.4–5.6 give the
counts of the pentad's ten (the fully-parallel robot families I–X: 6, 6, 6, 4, 4, 2, 2,
2, 1, 1 assembly modes).

Files: ``slider-chains-<L>.jsonl``, JSON lines with one object per slider chain, one per
line, in the order of the catalog's trusses and then of
:func:`~baranov.enumerate.sliders.slider_chains` (the all-revolute chain first): ``truss``
(its id) and ``truss_name``, ``sliders`` (the truss's joint names), ``assembly_modes``
(None for a chain that moves), ``method`` (``modular``, ``coupling 0``, ``msolve`` where
no plan suits the sliders, or ``moves``), ``degrees`` (seen on the instances) and, where
checked, ``msolve_solutions`` and ``msolve_agrees`` (with ``msolve_special_instances``, the
counts of earlier check instances that came out special, where there were any). Where
every check instance finds the same number of modes, more than the plan's count, that
number is the chain's (``method`` ``msolve``, ``degrees`` the check instances' counts) and
the plan's degrees are kept as ``plan_degrees`` (:func:`_plan_lost_modes`).
"""

from __future__ import annotations

import random
import zlib
from pathlib import Path
from typing import Any

import numpy as np

from baranov.enumerate.sliders import slider_chains
from baranov.scene import scene_from_dict
from baranov.scene.slider_instances import slider_instance_dict
from baranov.solvers.exact.modular import random_prime
from baranov.solvers.mode_counts import CARTESIAN_PRIME_BITS, slider_chain_degree
from baranov.solvers.msolve import MsolveUnavailable, msolve_solution_count_modulo
from baranov.topology import chain_from_link_graph

from .files import load_complete_objects
from .progress import progress_bar
from .tasks import run_in_shards, shard_folder

#: ``baranov catalog`` counts the slider chains' assembly modes up to this many links by
#: default (3 + 10 + 386 chains); 9 links (47 702 chains) is opt-in: ``--slider-modes 9``.
SLIDER_MODES_MAX_LINKS = 7
#: Instances msolve may draw for one check before it disagrees.
MSOLVE_CHECK_INSTANCES = 3
#: msolve checks every this many-th chain (every chain: modulo a prime a check takes
#: milliseconds to a second at 9 links; the plans' counts can lose modes, docs/sliders.md).
MSOLVE_CHECK_EVERY = {3: 1, 5: 1, 7: 1, 9: 1}


def slider_chain_entry(job: tuple[str, tuple[str, ...], bool]) -> dict:
    """The catalog object of one slider chain: ``job`` = (the truss's graph6, the slider
    joints, whether msolve checks the count)."""
    graph6, sliders, check = job
    truss = chain_from_link_graph(graph6)
    try:
        modes, degrees, method = slider_chain_degree(truss, sliders)
    except MsolveUnavailable:
        modes, degrees, method = None, [], "msolve unavailable"
    entry = {"sliders": list(sliders), "assembly_modes": modes, "method": method, "degrees": degrees}
    if check and modes is not None:
        # other instances than the count's: the check is of the generic count. A draw of
        # small integers can be special (fewer solutions: 2 of the 1871 nine-link checks),
        # so up to MSOLVE_CHECK_INSTANCES are drawn until one agrees; the others are kept.
        special = []
        for attempt in range(MSOLVE_CHECK_INSTANCES):
            seed = zlib.crc32(repr((graph6, sliders, "msolve check") + ((attempt,) if attempt else ())).encode())
            scene = scene_from_dict(slider_instance_dict(truss, list(sliders), np.random.default_rng(seed),
                                                         rational=True))
            try:
                solutions, auxiliaries = msolve_solution_count_modulo(
                    scene, random_prime(random.Random(seed), bits=CARTESIAN_PRIME_BITS))
            except MsolveUnavailable:
                return entry
            if solutions == 2 ** auxiliaries * modes:
                break
            special.append(solutions)
        # None: msolve found a positive-dimensional solution set on that draw (a special
        # instance that moves), which says nothing about the generic count
        if (len(special) == MSOLVE_CHECK_INSTANCES and None not in special and len(set(special)) == 1
                and special[0] > 2 ** auxiliaries * modes):
            return _plan_lost_modes(entry, [count // 2 ** auxiliaries for count in special])
        entry["msolve_solutions"] = solutions
        entry["msolve_agrees"] = solutions == 2 ** auxiliaries * modes
        if special:
            entry["msolve_special_instances"] = special
    return entry


def _plan_lost_modes(entry: dict, counts: list[int]) -> dict:
    """The entry of a chain whose plan counted fewer modes than msolve finds on every
    check instance, all alike (docs/sliders.md; 16 chains of 9/B26-B28 with five to seven
    sliders): the degree of a coupling-2 characteristic polynomial counts the values of
    the first parameter, and on these chains two or four modes share each value (the
    second parameter, a slider's oriented distance, takes several values above each
    root). msolve's count is the chain's; the plan's degrees are kept as ``plan_degrees``."""
    return {**entry, "assembly_modes": counts[0], "method": "msolve", "degrees": counts,
            "plan_degrees": entry["degrees"]}


def slider_chain_entries(entries: list[dict], show_progress: bool, client: Any = None,
                         folder: Path | None = None) -> list[dict]:
    """The slider chains of the trusses ``entries`` (one link count): the file's objects,
    computed as Dask tasks on ``client`` (here if None), shards saved in ``folder``
    until done (:func:`~baranov.catalog.tasks.run_in_shards`, :func:`~baranov.catalog.tasks.shard_folder`)."""
    links = entries[0]["links"]
    every = MSOLVE_CHECK_EVERY.get(links, 1)
    jobs, owners = [], []
    for index, entry in enumerate(entries):
        for sliders in slider_chains(chain_from_link_graph(entry["link_graph6"])):
            jobs.append((entry["link_graph6"], sliders, len(jobs) % every == 0))
            owners.append(index)
    bar = progress_bar(len(jobs), f"{links}-link slider chains", "chain", show_progress)
    with shard_folder(folder) as where:
        results = run_in_shards(slider_chain_entry, jobs, where, client, advance=bar.update)
    bar.close()
    return [{"truss": entries[owner]["id"], "truss_name": entries[owner]["name"], **result}
            for owner, result in zip(owners, results, strict=True)]


#: The fields every object of a complete file has.
SLIDER_CHAIN_FIELDS = ("truss", "truss_name", "sliders", "assembly_modes", "method", "degrees")


def load_slider_chains(path: Path) -> list[dict] | None:
    """The objects of a complete ``slider-chains-<L>.jsonl``, or None if missing,
    unreadable or incomplete."""
    return load_complete_objects(path, SLIDER_CHAIN_FIELDS)
