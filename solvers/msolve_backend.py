"""msolve as a solving method (issue 24): every real assembly mode of a scene — slider
joints included — from the Cartesian system, solved exactly by msolve
(:mod:`~baranov.solvers.msolve`), each configuration verified on every link dimension
and slider, and described in the terms of the truss's best plan.

A plan parameter s_{u,v} is measured on the configuration; where u is a slider joint it
becomes t_{u,v}, the signed distance of P_v to the slider's axis (thesis §4.2.4: a
slider at an end of the variable segment). The free-sign branch is given for
all-revolute scenes only (a triangle with a vertex at infinity has no finite orientation
to measure here).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from baranov.planner import Plan, SliderPlanError, best_plan, parameter_name, slider_plan
from baranov.scene import Scene

from .modes import AssemblyMode, MovableLinkageError, Solution, SolverError
from .msolve import MsolveUnavailable, msolve_modes
from .verification import RESIDUAL_TOLERANCE, distance_bound, joint_residual, slider_axis, sorted_modes


def solve_msolve(scene: Scene, timeout: float = 600.0) -> Solution:
    """All real assembly modes of ``scene`` by msolve (exact dimensions needed). Raises
    :class:`MovableLinkageError` where the solution set has positive dimension and
    :class:`SolverError` where msolve is missing, fails or a mode does not verify.

    >>> from baranov.scene import load_scene
    >>> solution = solve_msolve(load_scene("examples/7-B3-slider-P9.json"))  # doctest: +SKIP
    >>> [round(mode.parameters["s1,6"], 4) for mode in solution.assembly_modes]  # doctest: +SKIP
    [49.5561, 50.1965, 50.627, 85.0]
    """
    plan = description_plan(scene)
    return Solution("msolve", plan.number_of_parameters, tuple(_names(scene, plan)),
                    () if scene.sliders else plan.free_sign_triangles, verified_modes(scene, plan, timeout))


def verified_modes(scene: Scene, plan: Plan, timeout: float = 600.0) -> tuple[AssemblyMode, ...]:
    """msolve's configurations of ``scene``, each verified on every link dimension and
    slider and described in ``plan``'s terms, sorted. Errors as :func:`solve_msolve`."""
    if not scene.exact:
        raise SolverError("the msolve method needs exact dimensions (integers, decimals or fractions such as "
                          "\"9/5\"; a float from Python is binary)")
    try:
        result = msolve_modes(scene, timeout=timeout)
    except MsolveUnavailable as error:
        raise SolverError(str(error)) from None
    if result.status == "infinite":
        raise MovableLinkageError("msolve: a positive-dimensional solution set; the linkage moves with these "
                                  "dimensions (or a complex curve of solutions passes through its real ones)")
    if result.status != "finite":
        raise SolverError(f"msolve: {result.message}")
    return modes_of_configurations(scene, plan, result.configurations, "msolve")


#: The probabilistic step of a list certified through msolve's count.
MSOLVE_MONTE_CARLO = "msolve's multi-modular Gröbner basis over Q is correct with high probability"


def checked_against_generic_count(scene: Scene, timeout: float = 600.0) -> tuple[bool, str]:
    """Whether msolve's list of ``scene``'s modes can be trusted complete: its count of
    complex solutions of the Cartesian system over Q (:func:`~.msolve.msolve_solution_count`)
    equals the chain's generic count — the truss's (:func:`~.mode_counts.cartesian_degree`)
    or the slider chain's (:func:`~.mode_counts.slider_chain_degree`), doubled per
    auxiliary root. Then no solution was lost to the model: a model that does not match
    the scene (issue 55: an irrational ground placed at rounded coordinates, inconsistent
    with a slider on it) has fewer, and so does a degenerate instance, whose list this
    cannot certify. Returns the verdict and a sentence saying what was compared. Costs
    msolve's count on this instance and on a few random ones of the chain."""
    from .msolve import msolve_solution_count

    try:
        count, auxiliary = msolve_solution_count(scene, timeout)
    except (MsolveUnavailable, RuntimeError) as error:
        return False, f"msolve's count of complex solutions failed ({error})"
    generic = _generic_count(scene.chain, tuple(sorted(slider.joint for slider in scene.sliders)))
    if count is None or generic is None:
        return False, "the Cartesian system or the chain has a positive-dimensional solution set"
    expected = generic * 2**auxiliary
    if count != expected:
        return False, (f"msolve's Cartesian system has {count} complex solutions where a generic instance of the chain "
                       f"has {expected}: its list is not certified complete (a degenerate instance, or a model that "
                       "lost solutions)")
    doubled = f" ({generic}, doubled per auxiliary root)" if auxiliary else ""
    return True, f"msolve's Cartesian system has {count} complex solutions, the chain's generic count{doubled}"


@lru_cache(maxsize=256)
def _generic_count(chain, sliders: tuple[str, ...]) -> int | None:
    """The chain's generic number of assembly modes over C with ``sliders`` (its own
    seeded random instances: the same every call, so cached per process)."""
    from .mode_counts import cartesian_degree, slider_chain_degree

    return slider_chain_degree(chain, list(sliders))[0] if sliders else cartesian_degree(chain)[0]


def modes_of_configurations(scene: Scene, plan: Plan, configurations, method: str) -> tuple[AssemblyMode, ...]:
    """Real configurations of ``scene`` found by a Cartesian ``method`` (msolve, the
    homotopy), each verified on every link dimension and slider and described in
    ``plan``'s terms, sorted. Raises :class:`SolverError` for one that does not verify."""
    modes = []
    for configuration in configurations:
        residual = joint_residual(scene, {j: complex(*p) for j, p in configuration.items()})
        if residual >= RESIDUAL_TOLERANCE:
            raise SolverError(f"{method}'s configuration does not verify (residual {residual:.1e})")
        modes.append(described_mode(scene, plan, configuration, residual))
    return sorted_modes(modes)


def description_plan(scene: Scene) -> Plan:
    """The plan whose terms describe the modes: the one the numeric method runs (with
    sliders, :func:`~baranov.planner.slider_plan`), else the truss's best."""
    if scene.sliders:
        try:
            return slider_plan(scene.chain, [slider.joint for slider in scene.sliders])
        except SliderPlanError:
            pass
    return best_plan(scene.chain)


def _names(scene: Scene, plan: Plan) -> list[str]:
    return [parameter_name(pair, [slider.joint for slider in scene.sliders]) for pair in plan.parameters]


def described_mode(scene: Scene, plan: Plan, configuration: dict[str, tuple[float, float]], residual: float,
                   values: list[float] | None = None) -> AssemblyMode:
    """The mode at ``configuration`` in ``plan``'s terms: its parameters (``values``, or
    measured on the configuration) and, for an all-revolute scene, its free-sign branch
    (:func:`branch_signs`)."""
    if values is not None:
        return AssemblyMode(dict(zip(_names(scene, plan), values, strict=True)),
                            branch_signs(configuration, plan, scene), configuration, residual)
    at = {name: np.array([complex(*xy)]) for name, xy in configuration.items()}
    sliders = {slider.joint: slider for slider in scene.sliders}
    values = []
    for u, v in plan.parameters:
        if u in sliders and v in sliders:  # no plan the slider constructions run has such a pair
            values.append(math.nan)
        elif u in sliders or v in sliders:
            slider, other = (sliders[u], v) if u in sliders else (sliders[v], u)
            link = next(axis.link for axis in slider.axes)
            foot, direction = slider_axis(scene, slider, link, at)
            values.append(float((direction.conjugate() * (at[other] - foot)).imag[0]))
        else:
            values.append(abs(at[u][0] - at[v][0]) ** 2)
    signs = () if scene.sliders else branch_signs(configuration, plan, scene)
    return AssemblyMode(dict(zip(_names(scene, plan), values, strict=True)), signs, configuration, residual)


def branch_signs(joints: dict[str, tuple[float, float]], plan: Plan, scene: Scene) -> tuple[int, ...]:
    """The orientation of each free-sign triangle of ``plan`` in the configuration
    ``joints``: 0 where its doubled area is below 1e-6 of the squared size, since at a
    coincidence the numeric method places joints to about √ε of the size only (a
    tangency: thesis §5.1.3.2's quadruple root)."""
    scale = distance_bound(scene) ** 2
    signs = []
    for i, j, k in plan.free_sign_triangles:
        (xi, yi), (xj, yj), (xk, yk) = joints[i], joints[j], joints[k]
        cross = (xj - xi) * (yk - yi) - (yj - yi) * (xk - xi)
        signs.append(0 if abs(cross) <= 1e-6 * scale else int(math.copysign(1, cross)))
    return tuple(signs)
