"""baranov: the position analysis of planar linkages by bilateration (N. Rojas and
F. Thomas): Baranov trusses, their plans and closure conditions, and every assembly
mode of a linkage, numerically or exactly.

The first things a researcher reaches for, importable from here (each is loaded on first
use, so ``import baranov`` stays cheap):

* :func:`truss` — a Baranov truss by its thesis name or catalog id; :func:`baranov_trusses`
  — all of them for a link count, in catalog order;
* :func:`best_plan`, :func:`coupling_degree` — a bilateration plan of a truss (thesis §2.6,
  ch. 3); :func:`closure_system` — its closure conditions (thesis §2.7);
* :func:`characteristic_degree` — the number of assembly modes over C for generic
  dimensions (the degree of the characteristic polynomial);
* :func:`load_scene`, :func:`scene_from_dict` — a linkage with its dimensions (a scene);
  :func:`solve` — its assembly modes (``method="numeric"`` or ``"exact"``);
  :func:`solve_many` — those of many instances of it (a sweep of its dimensions).

>>> import baranov
>>> chain = baranov.truss("7/B1")
>>> baranov.coupling_degree(chain)
1
>>> print(baranov.closure_system(baranov.best_plan(chain)).text())  # doctest: +ELLIPSIS
s... = det(...) s...
>>> scene = baranov.scene_from_dict({
...     "links": [{"name": "ground", "joints": {"P1": [1, 3], "P2": [6, 8]}},
...               {"name": "b13", "joints": ["P1", "P3"], "squared_length": 20},
...               {"name": "b23", "joints": ["P2", "P3"], "squared_length": 18}],
...     "ground": "ground"})
>>> modes = baranov.solve(scene, method="exact").assembly_modes
>>> sorted((round(x, 9), round(y, 9)) for x, y in (mode.joints["P3"] for mode in modes))
[(1.8, 7.4), (5.4, 3.8)]
"""

from __future__ import annotations

import importlib
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("baranov")
except PackageNotFoundError:  # run from a checkout that was never installed
    __version__ = "unknown"

#: Public name -> the module that defines it.
_EXPORTS = {
    "truss": "baranov.catalog.lookup",
    "TrussNameError": "baranov.catalog.lookup",
    "baranov_trusses": "baranov.enumerate",
    "best_plan": "baranov.planner",
    "bilateration_plans": "baranov.planner",
    "coupling_degree": "baranov.planner",
    "closure_system": "baranov.closure",
    "characteristic_degree": "baranov.solvers",
    "load_scene": "baranov.scene",
    "scene_from_dict": "baranov.scene",
    "Scene": "baranov.scene",
    "SceneError": "baranov.scene",
    "solve": "baranov.solvers",
    "solve_many": "baranov.solvers",
    "with_dimensions": "baranov.scene",
    "Solution": "baranov.solvers",
    "ExactSolution": "baranov.solvers",
    "AssemblyMode": "baranov.solvers",
    "SolverError": "baranov.solvers",
    "MovableLinkageError": "baranov.solvers",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


def lazy_exports(namespace: dict, exports: dict[str, str]):
    """``__getattr__`` and ``__dir__`` for a package whose names in ``exports`` (name ->
    module) are imported on first use and then kept in ``namespace`` (its globals()), so
    that importing the package stays cheap (PEP 562). Used here and by
    :mod:`baranov.catalog`."""
    package = namespace["__name__"]

    def __getattr__(name: str):
        if name in exports:
            value = getattr(importlib.import_module(exports[name]), name)
            namespace[name] = value  # once loaded, a plain attribute
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__


__getattr__, __dir__ = lazy_exports(globals(), _EXPORTS)
