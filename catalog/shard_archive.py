"""Finished shards of a long catalog job kept between machines (issue 20: the 13-link
assembly modes take about 18 core-hours, more than one session of this project's machine).

A catalog job saves each finished shard as ``<out>/.shards/trusses-<L>/shard-<k>.json``
(:func:`baranov.catalog.tasks.run_in_shards`) and resumes from them; that folder is a
working folder, deleted when the job's file is written. :func:`archive_shards` copies the
finished shards, gzip-compressed and byte-identical from run to run, into a folder that
can be committed (``catalog/shards-13/``); :func:`restore_shards` puts them back for a
job to resume from, on this machine or on a cluster's client. A restored shard is reused
only if it holds exactly the jobs the job would give it (``run_in_shards`` checks the
jobs' reprs), so an archive from another revision of the enumeration is recomputed, not
trusted. :func:`archive_report` summarises what an archive holds.

Command line (``make catalog-13-modes`` restores, then runs the job)::

    python -m baranov.catalog.shard_archive save catalog-13/.shards/trusses-13 catalog/shards-13
    python -m baranov.catalog.shard_archive restore catalog/shards-13 catalog-13/.shards/trusses-13
    python -m baranov.catalog.shard_archive report catalog/shards-13
"""

from __future__ import annotations

import gzip
import json
import sys
from collections import Counter
from pathlib import Path

from .files import gzipped, write_atomically


def archive_shards(folder: Path, archive: Path) -> int:
    """Copy every shard ``folder/shard-<k>.json`` into ``archive/shard-<k>.json.gz``
    (written atomically; an archived shard with the same content is left alone) and
    return how many were new or changed. Cost: linear in the shards' size."""
    archive.mkdir(parents=True, exist_ok=True)
    written = 0
    for shard in sorted(folder.glob("shard-*.json")):
        content = gzipped(shard.read_text(encoding="utf-8"))
        target = archive / f"{shard.name}.gz"
        if target.exists() and target.read_bytes() == content:
            continue
        write_atomically(target, content)
        written += 1
    return written


def restore_shards(archive: Path, folder: Path) -> int:
    """Write every archived ``archive/shard-<k>.json.gz`` that ``folder`` lacks as
    ``folder/shard-<k>.json`` (atomically); return how many. A shard already in ``folder``
    is kept: it is at least as new as the archive's."""
    folder.mkdir(parents=True, exist_ok=True)
    restored = 0
    for packed in sorted(archive.glob("shard-*.json.gz")):
        target = folder / packed.name.removesuffix(".gz")
        if target.exists():
            continue
        write_atomically(target, gzip.decompress(packed.read_bytes()).decode("utf-8"))
        restored += 1
    return restored


def archived_entries(archive: Path) -> list[dict]:
    """The catalog entries of every archived shard, in shard order."""
    def number(path: Path) -> int:
        return int(path.name.split("-")[1].split(".")[0])

    return [entry for packed in sorted(archive.glob("shard-*.json.gz"), key=number)
            for entry in json.loads(gzip.decompress(packed.read_bytes()))["results"]]


def archive_report(archive: Path) -> str:
    """What an archive holds: shards, trusses by coupling degree, the assembly-mode counts'
    range, and how many were compared with a realization count (and how many differ).

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print(archive_report(Path(folder)))
    0 shards, 0 trusses
    """
    entries = archived_entries(archive)
    lines = [f"{len(list(archive.glob('shard-*.json.gz')))} shards, {len(entries)} trusses"]
    by_coupling = Counter(entry["coupling_degree"] for entry in entries)
    for coupling in sorted(by_coupling):
        modes = [e["assembly_modes"] for e in entries if e["coupling_degree"] == coupling]
        known = [m for m in modes if m is not None]
        span = f"{min(known)}-{max(known)}" if known else "none"
        lines.append(f"coupling degree {coupling}: {by_coupling[coupling]} trusses, assembly modes {span}")
    compared = [e for e in entries if e.get("realization_count") is not None]
    differing = [e["id"] for e in compared if e["realization_count"] != e["assembly_modes"]]
    if compared:
        lines.append(f"realization count taken on {len(compared)}: {len(differing)} differ"
                     + (f" ({', '.join(differing)})" if differing else ""))
    return "\n".join(lines)


def main(arguments: list[str]) -> int:
    """``save FOLDER ARCHIVE``, ``restore ARCHIVE FOLDER`` or ``report ARCHIVE``."""
    match arguments:
        case ["save", folder, archive]:
            print(f"{archive_shards(Path(folder), Path(archive))} shards archived")
        case ["restore", archive, folder]:
            print(f"{restore_shards(Path(archive), Path(folder))} shards restored")
        case ["report", archive]:
            print(archive_report(Path(archive)))
        case _:
            print("usage: python -m baranov.catalog.shard_archive save FOLDER ARCHIVE | restore ARCHIVE FOLDER"
                  " | report ARCHIVE", file=sys.stderr)
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
