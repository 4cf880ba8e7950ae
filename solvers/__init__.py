"""Solving backends: every assembly mode of a concrete linkage (a scene)."""

from .characteristic import (
    CharacteristicPolynomial,
    ExactMethodError,
    characteristic_polynomial,
)
from .exact import solve_exact
from .mode_counts import characteristic_degree
from .modular import characteristic_degree_modulo
from .modes import AssemblyMode, MovableLinkageError, Solution, SolverError
from .numeric import solve_numeric
from .scene import Scene, SceneError, load_scene, scene_from_dict


def solve(scene: Scene, method: str = "numeric", **options) -> Solution:
    """All assembly modes of ``scene``; ``method`` is ``"numeric"`` or ``"exact"``."""
    if method == "numeric":
        return solve_numeric(scene, **options)
    if method == "exact":
        return solve_exact(scene, **options)
    raise SolverError(f"method {method!r}: available methods are 'numeric' and 'exact'")


__all__ = [
    "AssemblyMode", "CharacteristicPolynomial", "ExactMethodError", "MovableLinkageError", "Scene", "SceneError", "Solution", "SolverError",
    "characteristic_degree", "characteristic_degree_modulo", "characteristic_polynomial", "load_scene", "scene_from_dict", "solve", "solve_exact", "solve_numeric",
]
