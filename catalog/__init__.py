"""The catalog of Baranov trusses as a library, and its files (this folder holds both):
every Baranov truss with its invariants, as JSON files and a Markdown summary next to
the literature values (:func:`build_catalog`; one entry: :func:`truss_entry`).

Output (all written atomically, byte-identical from run to run):

* ``trusses-<L>.json`` — a JSON list, one object per truss, in catalog order
  (:func:`baranov.enumerate.truss_sort_key`);
* ``crosscheck.json`` — per link count, the result of the independent brute-force
  enumeration (:mod:`baranov.enumerate.crosscheck`), when geng is available;
* ``summary.md`` — tables built from the files above.

An existing ``trusses-<L>.json`` that has every field is reused unless ``force``.
"""

from pathlib import Path

from .build import build_catalog, catalog_links, crosscheck_links
from .entries import ENTRY_FIELDS, dump_entries, load_entries, nine_link_name, truss_entry
from .summary import render_summary

#: The folder of the committed catalog files (package data): the names ``baranov show``
#: knows wherever it is run.
CATALOG_FOLDER = Path(__file__).resolve().parent

__all__ = [
    "CATALOG_FOLDER",
    "ENTRY_FIELDS",
    "build_catalog",
    "catalog_links",
    "crosscheck_links",
    "dump_entries",
    "load_entries",
    "nine_link_name",
    "render_summary",
    "truss_entry",
]
