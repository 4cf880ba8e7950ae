"""The registry of solving backends: every method that turns a scene into a
:class:`~baranov.solvers.Solution` registers here under a name, and :func:`solve` and the
command line's ``--method`` choices come from it. A backend is named by its module and
function, imported on first use, so listing the backends imports none of them.

>>> "numeric" in available_backends() and "exact" in available_backends()
True
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module

from .modes import Solution, SolverError


@dataclass(frozen=True)
class Backend:
    """A solving method: its name, where its solve function lives (``"module:function"``,
    called as ``function(scene, **options)``) and one line on what it does."""

    name: str
    location: str
    summary: str
    sliders: bool = False  # whether it solves scenes with slider joints

    def load(self) -> Callable[..., Solution]:
        module, function = self.location.split(":")
        return getattr(import_module(module), function)


BACKENDS: dict[str, Backend] = {}


def register_backend(name: str, location: str, summary: str, sliders: bool = False) -> None:
    """Register a backend (a later registration under the same name replaces it);
    ``sliders``: it solves scenes with slider joints."""
    BACKENDS[name] = Backend(name, location, summary, sliders)


def available_backends() -> tuple[str, ...]:
    """The registered backends' names, in registration order."""
    return tuple(BACKENDS)


def backend(name: str) -> Backend:
    """The backend registered as ``name``; :class:`SolverError` naming the available ones
    otherwise."""
    if name not in BACKENDS:
        names = ", ".join(repr(n) for n in BACKENDS)
        raise SolverError(f"method {name!r}: available methods are {names}")
    return BACKENDS[name]


register_backend("numeric", "baranov.solvers.numeric:solve_numeric",
                 "floating point: interval branch-and-prune, certified, for coupling degrees 0-1, sampling searches "
                 "otherwise (docs/numeric.md); slider joints too",
                 sliders=True)
register_backend("exact", "baranov.solvers.exact:solve_exact",
                 "characteristic polynomial over Q, certified real roots and modes (docs/exact.md); slider joints "
                 "with rational axis frames, coupling degree 1", sliders=True)
register_backend("msolve", "baranov.solvers.msolve_backend:solve_msolve",
                 "msolve (exact Groebner-basis solver) on the Cartesian system; slider joints too", sliders=True)
register_backend("homotopy", "baranov.solvers.homotopy:solve_homotopy",
                 "total-degree homotopy on the Cartesian system: every complex solution followed, any coupling degree "
                 "(three included); exact dimensions, revolute joints (docs/homotopy.md)")
register_backend("cartesian", "baranov.baselines.cartesian:solve_cartesian",
                 "baseline: Gauss-Newton on the Cartesian system from random starts (no completeness)")
register_backend("loop-equations", "baranov.baselines.loop_equations:solve_loop_equations",
                 "baseline: loop equations eliminated by resultants in sympy")
register_backend("float-polynomial", "baranov.baselines.float_polynomial:solve_float_polynomial",
                 "baseline: the characteristic polynomial rounded to floats, numpy roots")
