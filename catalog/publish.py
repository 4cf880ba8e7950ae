"""One link count's results moved from a separate catalog job into the committed catalog
(issue 20: the 13-link assembly modes are computed by ``baranov catalog --links 13 --out
catalog-13 --assembly-modes 13``, whose full file is about 122 MB and is not committed).

:func:`publish_link_count` copies the compact file ``trusses-<L>.jsonl.gz``
(:data:`~baranov.catalog.entries.COMPACT_FIELDS`) and the link count's brute-force
cross-check (``crosscheck.json``) into the catalog folder and regenerates its
``summary.md``, so that the summary's rows for L come from the job's own files, never from
an edit by hand.

Command line (the last step of ``make catalog-13-modes``)::

    python -m baranov.catalog.publish catalog-13 catalog 13
"""

from __future__ import annotations

import sys
from pathlib import Path

from .build import read_crosschecks, write_crosschecks
from .entries import COMPACT_FIELDS
from .files import load_complete_objects, write_atomically
from .summary import render_summary


class UnfinishedCatalogError(ValueError):
    """The job's folder lacks a complete compact file for the link count asked for."""


def publish_link_count(source: Path, catalog: Path, links: int) -> str:
    """Copy ``source/trusses-<links>.jsonl.gz`` and the ``links`` entry of
    ``source/crosscheck.json`` (if there is one) into ``catalog`` (each written atomically),
    regenerate ``catalog/summary.md`` and return a one-line account. Raises
    :class:`UnfinishedCatalogError` if the compact file is missing, unreadable or lacks one of
    the compact fields. Cost: linear in the compact file's size, plus the summary.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     publish_link_count(Path(folder), Path(folder), 13)
    Traceback (most recent call last):
    ...
    baranov.catalog.publish.UnfinishedCatalogError: ... has no complete trusses-13.jsonl.gz ...
    """
    compact = source / f"trusses-{links}.jsonl.gz"
    entries = load_complete_objects(compact, COMPACT_FIELDS)
    if not entries:
        raise UnfinishedCatalogError(
            f"{source} has no complete trusses-{links}.jsonl.gz (run the catalog job for {links} links to its end)")
    write_atomically(catalog / compact.name, compact.read_bytes())
    checks = read_crosschecks(catalog)
    if links in (found := read_crosschecks(source)):
        checks[links] = found[links]
        write_crosschecks(catalog, checks)
    write_atomically(catalog / "summary.md", render_summary(catalog, checks))
    counted = sum(entry["assembly_modes"] is not None for entry in entries)
    return (f"{links} links: {len(entries)} trusses ({counted} with assembly modes) published in {catalog}"
            + ("" if links in checks else " (no brute-force cross-check found)"))


def main(arguments: list[str]) -> int:
    """``SOURCE CATALOG LINKS``: one line on stdout, or one on stderr and status 2."""
    match arguments:
        case [source, catalog, links] if links.isdigit():
            try:
                print(publish_link_count(Path(source), Path(catalog), int(links)))
            except (OSError, ValueError) as error:  # UnfinishedCatalogError among them
                print(f"error: {error}", file=sys.stderr)
                return 2
            return 0
    print("usage: python -m baranov.catalog.publish SOURCE CATALOG LINKS", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
