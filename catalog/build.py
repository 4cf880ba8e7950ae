"""The catalog regeneration job: enumerate, compute every entry (in worker processes,
costliest first), cross-check the enumeration by brute force, and write the files
atomically; a complete existing file is reused unless ``force``."""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Iterable
from pathlib import Path

from tqdm import tqdm

from baranov.enumerate import baranov_link_graphs
from baranov.enumerate.crosscheck import baranov_link_graphs_by_filter, find_geng
from baranov.enumerate.parallel import worker_pool
from baranov.enumerate.trusses import canonical_trusses
from baranov.planner import best_plan
from baranov.topology import adjacency_masks, chain_from_link_graph
from baranov.topology.automorphisms import link_graph_certificate

from .entries import ASSEMBLY_MODES_MAX_LINKS, dump_entries, load_entries, truss_entry
from .files import write_atomically
from .slider_chains import SLIDER_MODES_MAX_LINKS, load_slider_chains, slider_chain_entries
from .summary import render_summary

Progress = Callable[[str], None]


def catalog_links(links: int, workers: int, show_progress: bool) -> list[dict]:
    """Enumerate the trusses with ``links`` links and compute every catalog entry."""
    trusses = canonical_trusses(baranov_link_graphs(links, workers))
    items = [(f"{links}/N{i + 1}", graph6) for i, (graph6, _) in enumerate(trusses)]
    bar = tqdm(total=len(items), desc=f"{links} links", unit="truss", disable=not show_progress, file=sys.stderr)
    entries = []
    # Worker processes are spawned, not forked: a forked worker deadlocked once flint and
    # lnumber had run in the parent.
    if workers > 1 and len(items) > 16:
        order = list(range(len(items)))
        if links <= ASSEMBLY_MODES_MAX_LINKS:
            # Coupling-2 counts cost ~10x coupling-1 ones: the costliest first, so that
            # no worker is left with a long tail.
            coupling = [best_plan(chain_from_link_graph(graph6)).number_of_parameters for _, graph6 in items]
            order.sort(key=lambda i: -coupling[i])
        done: dict[int, dict] = {}
        with worker_pool(workers, spawn=True) as pool:
            for index, entry in pool.imap_unordered(_numbered_entry, [(i, items[i]) for i in order]):
                done[index] = entry
                bar.update()
        entries = [done[i] for i in range(len(items))]
    else:
        for item in items:
            entries.append(truss_entry(item))
            bar.update()
    bar.close()
    return entries


def _numbered_entry(job: tuple[int, tuple[str, str]]) -> tuple[int, dict]:
    index, item = job
    return index, truss_entry(item)


def crosscheck_links(links: int, entries: list[dict], workers: int) -> dict:
    """Run the brute-force enumeration and compare its classes with the catalog's."""
    candidates, graphs = baranov_link_graphs_by_filter(links, workers)
    ours = {link_graph_certificate(adjacency_masks(chain_from_link_graph(e["link_graph6"]))) for e in entries}
    theirs = {link_graph_certificate(masks) for masks in graphs}
    return {
        "method": "geng -c -d2 L J:J, filtered by the Baranov predicate, deduplicated with pynauty",
        "candidates": candidates,
        "trusses": len(graphs),
        "same_isomorphism_classes": ours == theirs,
    }


def build_catalog(
    link_counts: Iterable[int],
    out: Path,
    workers: int = 1,
    force: bool = False,
    crosscheck: bool = True,
    slider_modes: int = SLIDER_MODES_MAX_LINKS,
    show_progress: bool = False,
    log: Progress = lambda message: None,
) -> str:
    """Regenerate (or reuse) the catalog files for ``link_counts`` in ``out``, with the
    slider chains' assembly modes up to ``slider_modes`` links; return the summary."""
    crosscheck_path = out / "crosscheck.json"
    try:
        checks = {int(k): v for k, v in json.loads(crosscheck_path.read_text(encoding="utf-8")).items()}
    except (OSError, ValueError):
        checks = {}
    geng = find_geng() if crosscheck else None
    for links in sorted(set(link_counts)):
        path = out / f"trusses-{links}.json"
        entries = None if force else load_entries(path)
        if entries is None:
            log(f"{links} links: enumerating")
            entries = catalog_links(links, workers, show_progress)
            write_atomically(path, dump_entries(entries))
        else:
            log(f"{links} links: reusing {path}")
        if geng and (force or links not in checks or checks[links].get("trusses") != len(entries)):
            log(f"{links} links: brute-force cross-check")
            checks[links] = crosscheck_links(links, entries, workers)
            write_atomically(crosscheck_path, json.dumps({str(k): checks[k] for k in sorted(checks)}, indent=2) + "\n")
        if links <= slider_modes:
            path = out / f"slider-chains-{links}.json"
            if force or load_slider_chains(path) is None:
                log(f"{links} links: slider chains")
                write_atomically(path, dump_entries(slider_chain_entries(entries, workers, show_progress)))
            else:
                log(f"{links} links: reusing {path}")
    summary = render_summary(out, checks)
    write_atomically(out / "summary.md", summary)
    return summary
