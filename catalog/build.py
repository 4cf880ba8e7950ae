"""The catalog regeneration job: enumerate, compute every entry (in worker processes,
costliest first), cross-check the enumeration by brute force, and write the files
atomically; a complete existing file is reused unless ``force``."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from baranov.enumerate.crosscheck import find_geng
from baranov.enumerate.trusses import canonical_trusses
from baranov.planner import best_plan
from baranov.topology import adjacency_masks, chain_from_link_graph

from .census import (
    FILTER_PARTS,
    census_path,
    dump_census,
    enumerate_in_tasks,
    filter_in_tasks,
    load_census,
    truss_census,
    truss_digest,
)
from .entries import (
    ASSEMBLY_MODES_MAX_LINKS,
    CHARACTERISTIC_COUPLING_TWO_MAX_LINKS,
    COMPACT_FROM_LINKS,
    compact_entries,
    dump_entries,
    load_entries,
    truss_entry,
)
from .files import gzipped, legacy_path, write_atomically
from .progress import progress_bar
from .slider_chains import SLIDER_MODES_MAX_LINKS, load_slider_chains, slider_chain_entries
from .summary import GRUBLER_FILE, read_grubler_counts, render_summary
from .tasks import ClusterLost, dask_client, run_in_shards, shard_folder

Progress = Callable[[str], None]
#: From this link count on, the catalog holds a census (counts, invariants, a sample)
#: instead of one entry per truss: 15 links have about a million trusses.
CENSUS_FROM_LINKS = 15
#: An embedded cluster lost mid-job is restarted this many times (the job resumes from its
#: shards); a cluster named by address is the user's to restart.
EMBEDDED_RESTARTS = 3


def catalog_links(links: int, show_progress: bool, client: Any = None,
                  folder: Path | None = None, assembly_modes: int = ASSEMBLY_MODES_MAX_LINKS) -> list[dict]:
    """Enumerate the trusses with ``links`` links and compute every catalog entry, with
    assembly-mode counts if ``links`` ≤ ``assembly_modes``: on ``client`` (Dask,
    :mod:`.tasks`) if given, else here; finished shards saved in ``folder`` (a temporary
    one if None) and reused by a rerun."""
    with shard_folder(None) as where:  # seconds up to 13 links: nothing to resume
        trusses = canonical_trusses(enumerate_in_tasks(links, where, client))
    count_modes = links <= assembly_modes
    items = [(f"{links}/N{i + 1}", graph6, count_modes) for i, (graph6, _) in enumerate(trusses)]
    costs = None
    if count_modes and client is not None and links <= CHARACTERISTIC_COUPLING_TWO_MAX_LINKS:
        # coupling-2 counts by the characteristic degree cost ~10x coupling-1 ones: the
        # costliest shards first, so that no worker is left with a long tail (beyond, they
        # cost alike, and finding the plans here would take the client 50 min at 13 links)
        costs = [10.0 ** best_plan(chain_from_link_graph(graph6)).number_of_parameters for _, graph6, _ in items]
    bar = progress_bar(len(items), f"{links} links", "truss", show_progress)
    with shard_folder(folder) as where:
        entries = run_in_shards(truss_entry, items, where, client, costs, bar.update)
    bar.close()
    return entries


def crosscheck_links(links: int, entries: list[dict], client: Any) -> dict:
    """Run the brute-force enumeration (as tasks, :mod:`.census`) and compare its classes
    with the catalog's."""
    parts = FILTER_PARTS if links >= 13 else 1
    with shard_folder(None) as where:  # 2 s for 13 links
        candidates, theirs = filter_in_tasks(links, where, client, parts)
    ours = {truss_digest(adjacency_masks(chain_from_link_graph(e["link_graph6"]))) for e in entries}
    return {
        "method": "geng -c -d2 L J:J, filtered by the Baranov predicate, deduplicated with pynauty",
        "candidates": candidates,
        "trusses": len(theirs),
        "same_isomorphism_classes": ours == theirs,
    }


def _reused(path: Path, load: Callable[[Path], list[dict] | None]) -> list[dict] | None:
    """The complete objects of ``path`` (``load``), or None; read from its legacy JSON
    list (:func:`~baranov.catalog.files.legacy_path`), they are written as JSON lines and
    the legacy file removed, so that an old catalog folder is converted, not recomputed."""
    objects = load(path)
    if objects is not None and not path.exists():
        write_atomically(path, dump_entries(objects))
        legacy_path(path).unlink()
    return objects


def read_crosschecks(out: Path) -> dict[int, dict]:
    """The brute-force cross-checks in ``out/crosscheck.json`` by link count ({} if the file
    is absent or unreadable: the job then recomputes them)."""
    try:
        return {int(k): v for k, v in json.loads((out / "crosscheck.json").read_text(encoding="utf-8")).items()}
    except (OSError, ValueError):
        return {}


def write_crosschecks(out: Path, checks: dict[int, dict]) -> None:
    """Write ``checks`` to ``out/crosscheck.json`` atomically, by ascending link count."""
    write_atomically(out / "crosscheck.json", json.dumps({str(k): checks[k] for k in sorted(checks)}, indent=2) + "\n")


def _census(links: int, out: Path, client: Any, force: bool, crosscheck: bool, show_progress: bool,
            log: Progress) -> None:
    """Write (or reuse) ``census-<L>.json``: counts without entries (:mod:`.census`)."""
    path = census_path(out, links)
    if not force and load_census(path) is not None:
        log(f"{links} links: reusing {path}")
        return
    log(f"{links} links: census (counts only, no entries)")
    census = truss_census(links, out / ".shards" / path.stem, client, show_progress, crosscheck=crosscheck)
    write_atomically(path, dump_census(census))


def _catalog_files(links: int, out: Path, client: Any, force: bool, crosscheck: bool, checks: dict,
                   geng: str | None, slider_modes: int, assembly_modes: int, show_progress: bool,
                   log: Progress) -> None:
    """Write (or reuse) the files of one link count (:func:`build_catalog`); ``checks``
    (the cross-check results by link count) is updated and written."""
    if links >= CENSUS_FROM_LINKS:
        _census(links, out, client, force, crosscheck, show_progress, log)
        return
    path = out / f"trusses-{links}.jsonl"
    entries = None if force else _reused(path, load_entries)
    if entries and links <= assembly_modes and any(
            e["assembly_modes"] is None and e["assembly_modes_evidence"].startswith(f"not derived: {links} links")
            for e in entries):
        entries = None  # written without the counts now asked for
    if entries is None:
        log(f"{links} links: enumerating")
        entries = catalog_links(links, show_progress, client, out / ".shards" / path.stem,
                                assembly_modes)
        write_atomically(path, dump_entries(entries))
    else:
        log(f"{links} links: reusing {path}")
    if links >= COMPACT_FROM_LINKS:  # seconds, and always what the full file says
        write_atomically(path.with_name(path.name + ".gz"), gzipped(dump_entries(compact_entries(entries))))
    if geng and (force or links not in checks or checks[links].get("trusses") != len(entries)):
        log(f"{links} links: brute-force cross-check")
        checks[links] = crosscheck_links(links, entries, client)
        write_crosschecks(out, checks)
    if links <= slider_modes:
        path = out / f"slider-chains-{links}.jsonl"
        if force or _reused(path, load_slider_chains) is None:
            log(f"{links} links: slider chains")
            chains = slider_chain_entries(entries, show_progress, client, out / ".shards" / path.stem)
            write_atomically(path, dump_entries(chains))
        else:
            log(f"{links} links: reusing {path}")


def build_catalog(
    link_counts: Iterable[int],
    out: Path,
    workers: int = 1,
    force: bool = False,
    crosscheck: bool = True,
    slider_modes: int = SLIDER_MODES_MAX_LINKS,
    assembly_modes: int = ASSEMBLY_MODES_MAX_LINKS,
    show_progress: bool = False,
    log: Progress = lambda message: None,
    scheduler: str | None = None,
) -> str:
    """Regenerate (or reuse) the catalog files for ``link_counts`` in ``out`` (from
    CENSUS_FROM_LINKS links on, a census of counts instead of entries), with the
    slider chains' assembly modes up to ``slider_modes`` links and the trusses' up to
    ``assembly_modes``; return the summary. The
    entries are computed as Dask tasks (:mod:`.tasks`): on an embedded cluster of
    ``workers`` processes, or on the cluster of ``scheduler``; finished shards wait in
    ``out/.shards/`` until their file is written, so an interrupted job resumes; an
    embedded cluster lost mid-job (:class:`~baranov.catalog.tasks.ClusterLost`) is
    restarted up to :data:`EMBEDDED_RESTARTS` times and the job resumes from its shards
    (a cluster named by ``scheduler`` is the user's to restart: the error is raised). Files:
    ``trusses-<L>.jsonl`` (from COMPACT_FROM_LINKS links on also ``trusses-<L>.jsonl.gz``,
    :data:`~baranov.catalog.entries.COMPACT_FIELDS` only) and ``slider-chains-<L>.jsonl``,
    JSON lines (one object per
    line, :func:`~baranov.catalog.files.iter_objects` streams them)."""
    checks = read_crosschecks(out)
    geng = find_geng() if crosscheck else None
    attempts = 1 if scheduler else EMBEDDED_RESTARTS + 1
    for attempt in range(1, attempts + 1):
        try:
            with dask_client(workers, scheduler) as client:
                for links in sorted(set(link_counts)):
                    _catalog_files(links, out, client, force, crosscheck, checks, geng, slider_modes,
                                   assembly_modes, show_progress, log)
            break
        except ClusterLost as error:
            if attempt == attempts:
                raise
            log(f"{error}; restarting the embedded cluster ({attempt} of {EMBEDDED_RESTARTS})")
            force = False  # what this run wrote is fresh; the rest resumes from its shards
    _grubler_census(out, max(link_counts) + 1, geng or find_geng(), log)
    summary = render_summary(out, checks)
    write_atomically(out / "summary.md", summary)
    return summary


def _grubler_census(out: Path, max_links: int, geng: str | None, log: Callable[[str], None]) -> None:
    """The Grübler chains (one degree of freedom) counted up to ``max_links`` links (even
    counts, at most :data:`~baranov.enumerate.grubler.CENSUS_LINKS`) into ``out``/grubler-chains.json,
    where geng is installed and the file does not already count as far."""
    from baranov.enumerate.grubler import CENSUS_LINKS, grubler_counts

    wanted = min(max_links, CENSUS_LINKS)
    if geng is None or wanted < 4 or max(read_grubler_counts(out), default=0) >= wanted:
        return
    counts = grubler_counts(wanted, geng)
    write_atomically(out / GRUBLER_FILE, json.dumps({"counts": {str(k): v for k, v in counts.items()}}, indent=1) + "\n")
    log(f"Grübler chains counted to {wanted} links")

