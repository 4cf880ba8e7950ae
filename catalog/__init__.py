"""The catalog of Baranov trusses as a library, and its files (this folder holds both):
every Baranov truss with its invariants, as JSON files and a Markdown summary next to
the literature values (:func:`build_catalog`; one entry: :func:`truss_entry`).

Output (all written atomically, byte-identical from run to run):

* ``trusses-<L>.jsonl`` — JSON lines, one object per truss, in catalog order
  (:func:`baranov.enumerate.truss_sort_key`);
* ``crosscheck.json`` — per link count, the result of the independent brute-force
  enumeration (:mod:`baranov.enumerate.crosscheck`), when geng is available;
* ``summary.md`` — tables built from the files above.

An existing ``trusses-<L>.jsonl`` that has every field is reused unless ``force`` (an
``trusses-<L>.json`` of an earlier version, a JSON list, is converted).
"""

from pathlib import Path

from baranov import lazy_exports

#: The folder of the committed catalog files (package data): the names ``baranov show``
#: knows wherever it is run.
CATALOG_FOLDER = Path(__file__).resolve().parent

#: Public name -> its submodule, imported on first use (a name lookup needs neither the
#: solvers nor the enumeration that building a catalog does).
_EXPORTS = {name: f"{__name__}.{module}" for name, module in {
    "build_catalog": "build", "catalog_links": "build", "crosscheck_links": "build",
    "ENTRY_FIELDS": "entries", "dump_entries": "entries", "load_entries": "entries", "nine_link_name": "entries",
    "iter_objects": "files",
    "truss_entry": "entries", "render_summary": "summary", "truss": "lookup", "named_truss": "lookup",
    "TrussNameError": "lookup",
}.items()}

__all__ = ["CATALOG_FOLDER", *sorted(_EXPORTS)]

__getattr__, __dir__ = lazy_exports(globals(), _EXPORTS)
