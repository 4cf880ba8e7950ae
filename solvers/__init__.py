"""Solving backends: every assembly mode of a concrete linkage (a scene)."""

from baranov.scene import Scene
from baranov.scene.sliders import sliding_link

from .backends import available_backends, backend, register_backend
from .batch import BatchError, instance_scenes, solve_many
from .exact import solve_exact
from .exact.characteristic import (
    CharacteristicPolynomial,
    ExactMethodError,
    characteristic_polynomial,
)
from .exact.modular import characteristic_degree_modulo
from .mode_counts import characteristic_degree
from .modes import AssemblyMode, Certificate, ExactSolution, MovableLinkageError, Solution, SolverError
from .numeric import solve_numeric


def solve(scene: Scene, method: str = "numeric", **options) -> Solution:
    """All assembly modes of ``scene`` by a registered backend
    (:func:`~baranov.solvers.backends.available_backends`: ``"numeric"``, ``"exact"`` and
    the baselines), passing it ``options``. A one-DOF scene whose crank input has a value
    is solved held there (:func:`baranov.motion.driving.solve_held`). Raises
    :class:`SolverError` for any other scene with mobility F > 0: its configurations are
    not isolated assembly modes; :class:`MovableLinkageError` for a scene with a link that
    slides on parallel slider axes (:func:`~baranov.scene.sliders.sliding_link`)."""
    if scene.mobility > 0 and any(driver.value is not None for driver in scene.inputs):
        from baranov.motion.driving import solve_held  # its crank held where the scene says

        return solve_held(scene, method, **options)
    if scene.mobility > 0:
        raise SolverError(f"mobility {scene.mobility} (3(L-1) - 2J with L = {len(scene.links)} links): the linkage "
                          "moves by its topology, and the backends find the assembly modes of rigid linkages "
                          "(mobility 0); trace its motion instead: baranov trace SCENE (docs/motion.md), or hold "
                          "its crank by giving its input \"degrees\"")
    sliding = sliding_link(scene)
    if sliding is not None:
        link, sliders = sliding
        raise MovableLinkageError(f"link {link}: its joints {' and '.join(sliders)} are sliders whose axes are "
                                  "parallel on it, so it slides along them without moving any other link: wherever "
                                  "the linkage assembles, it moves (a continuum of configurations, not isolated "
                                  "assembly modes)")
    chosen = backend(method)
    if scene.sliders and not chosen.sliders:
        joints = ", ".join(slider.joint for slider in scene.sliders)
        takers = " or ".join(f"--method {name}" for name in available_backends() if backend(name).sliders)
        raise SolverError(f"slider joints {joints}: the {method} method does not solve slider joints yet "
                          f"(thesis ch. 4); use {takers}")
    return chosen.load()(scene, **options)


__all__ = [
    "AssemblyMode", "BatchError", "Certificate", "CharacteristicPolynomial", "ExactSolution", "ExactMethodError",
    "MovableLinkageError", "Solution", "SolverError", "available_backends", "characteristic_degree",
    "characteristic_degree_modulo", "characteristic_polynomial", "instance_scenes", "register_backend", "solve",
    "solve_exact", "solve_many", "solve_numeric",
]
