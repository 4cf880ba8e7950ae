"""A truss by its name: a thesis name (``9/B28``) or a catalog id (``11/N123``)."""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import THESIS_TRUSSES, thesis_truss
from baranov.topology import KinematicChain, canonical_link_graph6, chain_from_link_graph, is_baranov_truss, natural_sort_key

from .files import iter_objects

#: ``<links>/B<k>`` (a thesis name) or ``<links>/N<k>`` (a catalog id).
TRUSS_NAME = re.compile(r"^(\d+)/([BN])(\d+)$")
#: What a user may type for one: any case, ``-`` for ``/`` (the examples' file names), or a
#: thesis name without its link count where it is unique (``B28``).
_LOOSE_NAME = re.compile(r"^(?:(\d+)[/-])?([BbNn])(\d+)$")


class TrussNameError(ValueError):
    """No truss of the catalog has this name or id."""


def truss(name: str, catalog: Path | None = None) -> KinematicChain:
    """The Baranov truss called ``name``: a thesis name (3/B1, 5/B1, 7/B1–B3, 9/B1–B28,
    identified in the catalog with evidence) or a catalog id ``<links>/N<k>`` (the k-th
    truss of that many links in catalog order, :func:`baranov.enumerate.truss_sort_key`).
    ``catalog``: the folder of ``trusses-<L>.jsonl`` (default: the installed catalog);
    ids of link counts it lacks (up to 13) are enumerated. Raises
    :class:`TrussNameError`, listing the names the catalog knows, for any other name.

    >>> chain = truss("9/B28")
    >>> chain.number_of_links, chain.number_of_joints
    (9, 12)
    >>> truss("7-b1") == truss("7/B1") and truss("B28") == chain
    True
    """
    return named_truss(name, catalog)[1]


def normalised_truss_name(name: str) -> str | None:
    """``name`` as a thesis name or catalog id (``9/B28``, ``11/N123``) where it is one in
    any case or with ``-`` for ``/`` (``7-b1``), or a thesis name without its link count
    that only one link count has (``B28``, not ``B1``); None otherwise.

    >>> [normalised_truss_name(n) for n in ("7-b1", "11/n64", "B28", "B1", "foo")]
    ['7/B1', '11/N64', '9/B28', None, None]
    """
    match = _LOOSE_NAME.match(name.strip())
    if not match:
        return None
    links, kind, number = match.group(1), match.group(2).upper(), match.group(3)
    if links is not None:
        return f"{links}/{kind}{number}"
    candidates = thesis_names_without_links(name) if kind == "B" else []
    return candidates[0] if len(candidates) == 1 else None


def thesis_names_without_links(name: str) -> list[str]:
    """The thesis names that ``name`` (``B1``, ``b28``) is, with their link counts.

    >>> thesis_names_without_links("B1"), thesis_names_without_links("b28")
    (['3/B1', '5/B1', '7/B1', '9/B1'], ['9/B28'])
    """
    from . import CATALOG_FOLDER

    wanted = name.strip().upper()
    names = {t.name for t in THESIS_TRUSSES} | {entry["name"] for links in (3, 5, 7, 9)
                                                for entry in catalog_entries(links, CATALOG_FOLDER)}
    return sorted((n for n in names if n.split("/")[1] == wanted), key=natural_sort_key)


def named_truss(name: str, catalog: Path | None = None) -> tuple[str, KinematicChain]:
    """:func:`truss` with a title: the name, its id or source in the literature."""
    from . import CATALOG_FOLDER

    catalog = CATALOG_FOLDER if catalog is None else catalog
    name = normalised_truss_name(name) or name
    match = TRUSS_NAME.match(name)
    if not match:
        if len(several := thesis_names_without_links(name)) > 1:
            raise TrussNameError(f"{name}: several thesis trusses have this name: {', '.join(several)}")
        raise TrussNameError(f"{name}: not a truss name (expected e.g. 9/B28 or 11/N123)")
    if name in {t.name for t in THESIS_TRUSSES}:
        published = thesis_truss(name)
        return f"{name} — {published.source}", published.chain()
    links = int(match.group(1))
    entries = catalog_entries(links, catalog)
    for entry in entries:
        if name in (entry["id"], entry["name"]):
            title = entry["id"] if entry["name"] == entry["id"] else f"{entry['id']} ({entry['name']})"
            if entry["id"] in LITERATURE_NAMES:
                title += f" — {LITERATURE_NAMES[entry['id']]}"
            return title, chain_from_link_graph(entry["link_graph6"])
    if match.group(2) == "N" and not entries and 3 <= links <= 13 and links % 2:
        trusses = baranov_trusses(links)
        index = int(match.group(3))
        if 1 <= index <= len(trusses):
            return name, trusses[index - 1]
    raise TrussNameError(f"{name}: no such truss in the catalog ({_known_names(entries, links, catalog)})")


#: Trusses the literature names outside the thesis's numbering, by catalog id; each is
#: checked against the chain of its example (tests/test_cli.py).
LITERATURE_NAMES = {"11/N64": "the Watt–Baranov truss of thesis §3.6.2.1",
                    "13/N206": "the Watt–Baranov truss of thesis §3.6.2.2"}


def catalog_truss_of(chain: KinematicChain, catalog: Path | None = None) -> tuple[str, str] | None:
    """The id and name (a thesis name, or the id again) of the catalog truss isomorphic
    to ``chain``, or None: not a Baranov truss, or a link count the catalog lacks (it
    holds 3–13 links). By the canonical link graph (nauty), O(catalog entries) the first
    time for a link count, then one dictionary lookup.

    >>> from baranov.scene import load_scene
    >>> catalog_truss_of(load_scene("examples/9-B28.json").chain)
    ('9/N28', '9/B28')
    """
    from . import CATALOG_FOLDER

    if not is_baranov_truss(chain):
        return None
    return _ids_by_link_graph(chain.number_of_links, CATALOG_FOLDER if catalog is None else catalog).get(
        canonical_link_graph6(chain))


@lru_cache(maxsize=8)
def _ids_by_link_graph(links: int, catalog: Path) -> dict[str, tuple[str, str]]:
    """Canonical link graph6 → (id, name) of every catalog truss with ``links`` links."""
    entries = catalog_entries(links, catalog)
    if not entries and (catalog / f"trusses-{links}.jsonl.gz").is_file():
        entries = list(iter_objects(catalog / f"trusses-{links}.jsonl.gz"))
    return {entry["link_graph6"]: (entry["id"], entry["name"]) for entry in entries}


def catalog_entries(links: int, catalog: Path) -> list[dict]:
    """The entries of ``trusses-<links>.jsonl`` in ``catalog`` ([] if there is none)."""
    try:
        return list(iter_objects(catalog / f"trusses-{links}.jsonl"))
    except (OSError, ValueError):
        return []


def _known_names(entries: list[dict], links: int, catalog: Path) -> str:
    """What the catalog does know at ``links`` links, for an error message."""
    if not entries:
        present = sorted(int(p.stem.split("-")[1]) for p in catalog.glob("trusses-*.jsonl")
                         if p.stem.split("-")[1].isdigit())
        counts = ", ".join(map(str, present)) or "none"
        return f"it has no {links}-link trusses: Baranov trusses have an odd number of links, 3 or more; " \
               f"the catalog holds {counts} links"
    names = sorted((e["name"] for e in entries if e["name"] != e["id"]), key=natural_sort_key)
    named = f"names {', '.join(names[:3])}{' …' if len(names) > 3 else ''}; " if names else ""
    return f"{named}ids {links}/N1..{links}/N{len(entries)}"
