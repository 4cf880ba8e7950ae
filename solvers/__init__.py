"""Solving backends: every assembly mode of a concrete linkage (a scene)."""

from .modes import AssemblyMode, Solution
from .numeric import SolverError, solve_numeric
from .scene import Scene, SceneError, load_scene, scene_from_dict


def solve(scene: Scene, method: str = "numeric", **options) -> Solution:
    """All assembly modes of ``scene``; ``method`` is ``"numeric"`` (exact: a later release)."""
    if method == "numeric":
        return solve_numeric(scene, **options)
    raise SolverError(f"method {method!r}: available methods are 'numeric'")


__all__ = ["AssemblyMode", "Scene", "SceneError", "Solution", "SolverError", "load_scene", "scene_from_dict",
           "solve", "solve_numeric"]
