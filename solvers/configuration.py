"""Assembly modes from candidate roots: configurations placed from the ground link,
verified on every link dimension and orientation, deduplicated. Shared by the numeric and
exact backends."""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
from baranov.closure import CompiledSystem, closure_system
from baranov.planner import Plan
from baranov.topology import thesis_subscript

from .modes import AssemblyMode
from .polish import POLISH_STEPS, polish_configurations
from .scene import Scene

#: A candidate is an assembly mode when every link dimension holds to this (relative).
RESIDUAL_TOLERANCE = 1e-8

#: A candidate whose configuration misses RESIDUAL_TOLERANCE but holds to this is polished
#: on the link constraints first: where a triangle of the plan is very short or very flat,
#: the float radicand loses digits to cancellation (joints 1e-4 apart among sides ~10:
#: residual ~1e-6, docs/stability.md) although the candidate is next to a true mode.
POLISH_LIMIT = 1e-3
#: Relative doubled area below which :func:`read_back` calls a triangle flat (sign 0).
FLAT_AREA = 1e-10


def parameter_name(pair: tuple[str, str]) -> str:
    """``("P1", "P6")`` → ``"s1,6"``."""
    return "s" + ",".join(thesis_subscript(n) for n in pair)


def compile_scene(scene: Scene, plan: Plan) -> CompiledSystem:
    """The closure system of ``plan`` bound to the dimensions of ``scene`` (floats), with
    the orientation of every link step read from the link's shape."""
    return CompiledSystem(
        closure_system(plan),
        {pair: float(value) for pair, value in scene.known.items()},
        {s.triangle: scene.orientation(s.triangle) for s in plan.steps if not s.free_sign},
    )


def distance_bound(scene: Scene) -> float:
    """Sum of the link diameters: no two joints are farther apart."""
    return sum(math.sqrt(max(float(v) for v in link.squared_distances.values())) for link in scene.links)


def distinct_candidates(values: np.ndarray, branches: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Candidates ``(parameter values, branch)`` with repeats removed (same branch, same
    values to 8 decimals of their logarithms): many starts converge to one root, and each
    candidate costs a configuration."""
    unique: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}
    for row, branch in zip(values, branches, strict=True):
        if np.isfinite(row).all() and (row > 0).all():
            unique.setdefault((tuple(int(s) for s in branch), *np.round(np.log(row), 8)), (row.copy(), branch))
    return list(unique.values())


def assembly_modes(scene: Scene, compiled: CompiledSystem, candidates) -> tuple[AssemblyMode, ...]:
    """The verified, distinct assembly modes among ``candidates`` (parameter values,
    branch), sorted by parameters then signs."""
    modes: list[AssemblyMode] = []
    for values, branch in candidates:
        mode = configuration(scene, compiled, np.asarray(values, float), np.asarray(branch))
        if RESIDUAL_TOLERANCE <= mode.max_residual < POLISH_LIMIT:
            mode = polished_mode(scene, compiled, mode)
        if mode.max_residual < RESIDUAL_TOLERANCE:
            mode = flattened_mode(scene, compiled, mode)
            if not any(same_mode(mode, other, scene) for other in modes):
                modes.append(mode)
    return sorted_modes(merged_clusters(scene, compiled, modes))


#: Verified modes closer than this (relative to the linkage's size) are polished again,
#: CLUSTER_STEPS plain Gauss–Newton steps, before they count as distinct.
CLUSTER = 1e-3
CLUSTER_STEPS = 200


def merged_clusters(scene: Scene, compiled: CompiledSystem, modes: list[AssemblyMode]) -> list[AssemblyMode]:
    """``modes`` with the near-copies of a singular mode merged into it. At a root of
    multiplicity k a point δ away has residual ~δ^k, so points 1e-4 from the mode verify
    to 1e-11 (issue 25: 9/N2 drawn at a flexible configuration, five such "modes" around
    s1,10 = s1,12 = 1). Modes with a neighbour within CLUSTER of the linkage's size are
    polished by plain Gauss–Newton steps on the link constraints, which approach the
    singular mode (measured there: from 5e-5 to 7e-7 in 50 steps), and kept only if still
    distinct; two regular roots this close each converge to themselves. Cost: O(n² J)
    distance checks for n modes of J joints, and CLUSTER_STEPS steps per clustered mode."""
    scale = max(1.0, distance_bound(scene))
    clustered = sorted({index for a, b in combinations(range(len(modes)), 2)
                        if all(math.dist(modes[a].joints[j], modes[b].joints[j]) < CLUSTER * scale
                               for j in modes[a].joints) for index in (a, b)})
    if not clustered:
        return modes
    kept = [mode for index, mode in enumerate(modes) if index not in clustered]
    for index in sorted(clustered, key=lambda i: modes[i].max_residual):
        mode = polished_mode(scene, compiled, modes[index], CLUSTER_STEPS, monotone=False)
        mode = flattened_mode(scene, compiled, mode if mode.max_residual < RESIDUAL_TOLERANCE else modes[index])
        if not any(same_mode(mode, other, scene) for other in kept):
            kept.append(mode)
    return kept


#: A free-sign triangle of a verified mode whose doubled area is below this (relative to
#: the product of its sides from P_i) is tried flat by :func:`flattened_mode`.
NEARLY_FLAT = 1e-4


def flattened_mode(scene: Scene, compiled: CompiledSystem, mode: AssemblyMode) -> AssemblyMode:
    """``mode`` rebuilt with its nearly flat free-sign triangles flat (sign 0), if that
    configuration verifies too. Next to a mode with a flat triangle the two branches meet
    like ±√δ, so candidates from either side verify to 1e-8 while their joints differ by
    ~√(1e-10) — at a double root of the characteristic polynomial the same mode was
    reported twice, 5e-5 apart (9/N20 of the collinear-joints sweep). Snapped flat, they
    are one; two genuinely distinct modes this close keep a triangle area whose removal
    breaks the verification (the merging pair of docs/stability.md)."""
    at = {joint: complex(*point) for joint, point in mode.joints.items()}
    flat = [index for index, triangle in enumerate(compiled.free_triangles)
            if orientation(at, *triangle, NEARLY_FLAT) == 0]
    if not flat or not mode.parameters:
        return mode
    branch = np.array(mode.signs)
    branch[flat] = 0
    snapped = configuration(scene, compiled, np.array(list(mode.parameters.values())), branch)
    return snapped if snapped.max_residual < RESIDUAL_TOLERANCE else mode


def sorted_modes(modes) -> tuple[AssemblyMode, ...]:
    """``modes`` by parameter values, then signs (the order every backend reports)."""
    return tuple(sorted(modes, key=lambda m: (tuple(m.parameters.values()), m.signs)))


def placed_from_ground(scene: Scene, matrices: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """World positions (complex) of every joint from the plan's M_k (relative to its
    reference, any array shape): the similarity that takes the ground link's first two
    joints onto their world coordinates. NaN where a radicand was negative or the ground
    joints coincide."""
    ground = scene.link_of(scene.ground)
    g1, g2 = ground.joints[0], ground.joints[1]
    world = {j: complex(float(x), float(y)) for j, (x, y) in scene.world.items()}
    with np.errstate(invalid="ignore", divide="ignore"):
        denominator = matrices[g2] - matrices[g1]
        reference = np.where(denominator != 0, (world[g2] - world[g1]) / np.where(denominator != 0, denominator, 1),
                             np.nan)
        origin = world[g1] - matrices[g1] * reference
        return {joint: origin + value * reference for joint, value in matrices.items()}


def configuration(scene: Scene, compiled: CompiledSystem, values: np.ndarray, branch: np.ndarray) -> AssemblyMode:
    """The configuration of one candidate, with its largest relative error over every link
    dimension (1.0 for a rigid link found mirrored; inf where it cannot be built)."""
    matrices, _ = compiled.matrices(values.reshape(1, -1), branch[None, :])
    points = {j: complex(p[0, 0]) for j, p in placed_from_ground(scene, matrices).items()}
    if not all(math.isfinite(p.real) and math.isfinite(p.imag) for p in points.values()):
        return AssemblyMode({}, tuple(int(s) for s in branch), {}, math.inf)  # a radicand was negative
    residual = joint_residual(scene, points)
    names = [parameter_name(p) for p in compiled.parameters]
    return AssemblyMode(
        {name: float(v) for name, v in zip(names, values, strict=True)},
        tuple(int(s) for s in branch),
        {j: (p.real, p.imag) for j, p in sorted(points.items())},
        residual,
    )


def orientation(at: dict, i: str, j: str, k: str, flat: float):
    """The orientation of △P_i P_j P_k (joint positions as complex numbers or arrays):
    ±1, or 0 where its doubled area is at most ``flat`` times the product of its two sides
    from P_i."""
    first, second = at[j] - at[i], at[k] - at[i]
    cross = (first.conjugate() * second).imag
    return np.where(np.abs(cross) <= flat * np.abs(first) * np.abs(second), 0, np.where(cross > 0, 1, -1))


def read_back(compiled: CompiledSystem, at: dict[str, np.ndarray],
              flat: float = FLAT_AREA) -> tuple[np.ndarray, np.ndarray]:
    """The plan's parameter values and free-sign branch of configurations given as joint
    positions (complex arrays of one shape S): arrays of shape S + (parameters,) and
    S + (free-sign triangles,). A triangle whose doubled area is below FLAT_AREA of the
    product of its two sides from P_i gets sign 0 (flat): placed with ±1 at parameters
    read back to rounding, its radicand can come out a few ulps negative, and the mode
    would be lost (9/N28 of the collinear-joints sweep). ``flat`` replaces FLAT_AREA
    (NEARLY_FLAT for configurations known only to √ε: a double root, numeric.py)."""
    shape = np.shape(next(iter(at.values())))

    def stacked(columns: list) -> np.ndarray:
        return np.stack(columns, axis=-1) if columns else np.zeros((*shape, 0))

    parameters = stacked([np.abs(at[u] - at[v]) ** 2 for u, v in compiled.parameters])
    branch = stacked([orientation(at, *triangle, flat) for triangle in compiled.free_triangles])
    return parameters, branch


def polished_mode(scene: Scene, compiled: CompiledSystem, mode: AssemblyMode, steps: int = POLISH_STEPS,
                  monotone: bool = True) -> AssemblyMode:
    """``mode`` polished on the link constraints (:func:`polish_configurations`, with
    ``steps`` and ``monotone``), its parameters and free-sign branch read back from the
    polished configuration."""
    joints = sorted(mode.joints)
    points, _ = polish_configurations(scene, joints, np.array([[mode.joints[j] for j in joints]]), steps, monotone)
    at = {j: complex(*points[0, n]) for n, j in enumerate(joints)}
    parameters, branch = read_back(compiled, {j: np.asarray(p) for j, p in at.items()})
    return AssemblyMode({parameter_name(pair): float(v) for pair, v in zip(compiled.parameters, parameters,
                                                                           strict=True)},
                        tuple(int(s) for s in branch), {j: (p.real, p.imag) for j, p in at.items()},
                        joint_residual(scene, at))


def joint_residual(scene: Scene, points: dict[str, complex]) -> float:
    """The largest relative error of joint positions (complex) on every link dimension
    and ground joint; 1.0 if a rigid link is mirrored (its widest triangle reversed). For
    coincident joints (target 0) the error is relative to the link's size. Shared by every
    method, baselines included, so their residuals compare."""
    world = {j: complex(float(x), float(y)) for j, (x, y) in scene.world.items()}
    residual = 0.0
    for link in scene.links:
        size = max(float(target) for target in link.squared_distances.values())
        for pair, target in link.squared_distances.items():
            u, v = tuple(pair)
            residual = max(residual, abs(abs(points[u] - points[v]) ** 2 - float(target)) / (float(target) or size))
        triangle = scene.widest_triangle(link) if len(link.joints) >= 3 else None
        if triangle is not None:
            i, j, k = (points[n] for n in triangle)
            cross = ((j - i).conjugate() * (k - i)).imag
            if (1 if cross > 0 else -1) != scene.orientation(triangle):
                residual = max(residual, 1.0)  # mirrored rigid link
    for joint, target in world.items():
        residual = max(residual, abs(points[joint] - target) / max(abs(target), 1.0))
    return residual


def same_mode(first: AssemblyMode, second: AssemblyMode, scene: Scene) -> bool:
    """Whether two modes place every joint within 1e-6 of the linkage's size."""
    scale = max(1.0, distance_bound(scene))
    return all(
        math.dist(first.joints[j], second.joints[j]) < 1e-6 * scale for j in first.joints
    )
