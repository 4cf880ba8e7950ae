"""Assembly modes from candidate roots: configurations placed from the ground link,
verified on every link dimension and orientation, deduplicated. Shared by the numeric and
exact backends."""

from __future__ import annotations

import math

import numpy as np

from baranov.closure import CompiledSystem, closure_system
from baranov.planner import Plan
from baranov.scene import Scene
from baranov.topology import distance_name

from .modes import AssemblyMode
from .polish import POLISH_STEPS, polish_configurations

#: A candidate is an assembly mode when every link dimension holds to this (relative).
RESIDUAL_TOLERANCE = 1e-8

#: A candidate whose configuration misses RESIDUAL_TOLERANCE but holds to this is polished
#: on the link constraints first: where a triangle of the plan is very short or very flat,
#: the float radicand loses digits to cancellation (joints 1e-4 apart among sides ~10:
#: residual ~1e-6, docs/stability.md) although the candidate is next to a true mode.
POLISH_LIMIT = 1e-3
#: Two configurations are one mode when every joint agrees to this (relative to the
#: linkage's size): :func:`same_mode`, :func:`first_of_each_mode`.
SAME_MODE = 1e-6
#: Relative doubled area below which :func:`read_back` calls a triangle flat (sign 0).
FLAT_AREA = 1e-10


def parameter_name(pair: tuple[str, str]) -> str:
    """``("P1", "P6")`` → ``"s1,6"``."""
    return distance_name(*pair)


def compile_scene(scene: Scene, plan: Plan) -> CompiledSystem:
    """The closure system of ``plan`` bound to the dimensions of ``scene`` (floats), with
    the orientation of every link step read from the link's shape."""
    return CompiledSystem(
        closure_system(plan),
        {pair: float(value) for pair, value in scene.known.items()},
        {s.triangle: scene.orientation(s.triangle) for s in plan.steps if not s.free_sign},
    )


def distance_bound(scene: Scene) -> float:
    """Sum of the link diameters: no two joints are farther apart. The linkage's size, to
    which every tolerance on positions is relative (never to a fixed unit: issue 22, a
    triad scaled by 1e-6 had its two modes merged and a 3-RPR scaled by 1e6 failed to
    verify its modes when tolerances were floored at 1)."""
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
    branch), sorted by parameters then signs. All candidates are placed, verified and
    polished together (a coupling-2 solve can bring 10⁴ candidates: one at a time, they
    took 41 of 62 s on an issue-25 instance of 9/N18); the first candidate of each mode
    is kept. Cost O(K · J) array work for K candidates of J joints, and O(K · n · J) for
    the duplicate check against the n modes."""
    candidates = list(candidates)
    if not candidates:
        return ()
    values = np.array([np.asarray(v, float) for v, _ in candidates]).reshape(len(candidates), -1)
    branches = np.array([np.asarray(b) for _, b in candidates], int).reshape(len(candidates), -1)
    joints, points = placed_configurations(scene, compiled, values, branches)
    residual = joint_residuals(scene, joints, points)
    polish = np.flatnonzero((RESIDUAL_TOLERANCE <= residual) & (residual < POLISH_LIMIT))
    if len(polish):
        points[polish], values[polish], branches[polish], residual[polish] = polished_configurations(
            scene, compiled, joints, points[polish])
    kept = np.flatnonzero(residual < RESIDUAL_TOLERANCE)
    kept = kept[first_of_each_mode(points[kept], scene)]
    modes = [flattened_mode(scene, compiled, mode_of(compiled, joints, values[k], branches[k], points[k], residual[k]))
             for k in kept]
    stacked = np.array([[complex(*mode.joints[j]) for j in joints] for mode in modes])
    return sorted_modes([modes[k] for k in first_of_each_mode(stacked, scene)])


def placed_configurations(scene: Scene, compiled: CompiledSystem, values: np.ndarray,
                          branches: np.ndarray) -> tuple[list[str], np.ndarray]:
    """Joint names (sorted) and the configurations of K candidates, point k at parameter
    values ``values[k]`` on branch ``branches[k]``: complex array (K, J), NaN where a
    radicand was negative."""
    placed = placed_from_ground(scene, compiled.paired_matrices(values, branches))
    joints = sorted(placed)
    return joints, np.stack([np.broadcast_to(placed[j], (len(values),)) for j in joints], axis=1)


def polished_configurations(scene: Scene, compiled: CompiledSystem, joints: list[str], points: np.ndarray,
                            steps: int = POLISH_STEPS, monotone: bool = True):
    """Configurations (complex (K, J)) polished on the link constraints
    (:func:`polish_configurations`), with their parameters and free-sign branches read back
    and their residuals: ``(points, values, branches, residuals)``."""
    real = np.stack([points.real, points.imag], axis=-1)
    real, _ = polish_configurations(scene, joints, real, steps, monotone)
    polished = real[..., 0] + 1j * real[..., 1]
    values, branches = read_back(compiled, {j: polished[:, n] for n, j in enumerate(joints)})
    return polished, values, branches, joint_residuals(scene, joints, polished)


def first_of_each_mode(points: np.ndarray, scene: Scene) -> np.ndarray:
    """Indices of the configurations (complex (K, J)) that do not repeat an earlier one:
    the first of each group placing every joint within 1e-6 of the linkage's size
    (:func:`same_mode`). Cost O(K · n · J) for n distinct configurations."""
    tolerance = SAME_MODE * distance_bound(scene)
    first: list[int] = []
    for k in range(len(points)):
        if not first or (np.abs(points[first] - points[k]).max(axis=1) >= tolerance).all():
            first.append(k)
    return np.array(first, int)


#: Verified modes closer than this (relative to the linkage's size) are polished again,
#: CLUSTER_STEPS plain Gauss–Newton steps, before they count as distinct.
CLUSTER = 1e-3
CLUSTER_STEPS = 200
#: A mode whose residual is at this level is placed to rounding: polishing it without the
#: monotone test could only move it (issue 22: msolve's exact mode with P1 = P5 on a
#: 3-RPR-II scaled by 1/1000 and mirrored was moved 5e-5 away, then stood for its valley).
ROUNDING = 1e-15


def merged_clusters(scene: Scene, compiled: CompiledSystem,
                    modes: tuple[AssemblyMode, ...]) -> tuple[tuple[AssemblyMode, ...], tuple[str, ...]]:
    """``modes`` with the near-copies of a singular mode merged into it, sorted; and one
    sentence per group of modes that floating point could not tell apart.

    At a root of multiplicity k a point δ away has residual ~δ^k, so points 1e-4 from the
    mode verify to 1e-11 (issue 25: 9/N2 drawn at a flexible configuration, five such
    "modes" around s1,10 = s1,12 = 1). Modes with a neighbour within CLUSTER of the
    linkage's size are polished by plain Gauss–Newton steps on the link constraints, which
    approach the singular mode (measured there: from 5e-5 to 7e-7 in 50 steps), and kept
    only if still distinct; two regular roots this close each converge to themselves.
    Where the residual is flat to rounding along a valley, the steps do not move them
    (9/N15, 9/N22: four and eleven points within 3e-5 of the mode, residuals 1e-16 to
    1e-13); those still close are merged by :func:`_same_valley`. Cost: O(n² J) distance
    checks for n modes of J joints, CLUSTER_STEPS steps per clustered mode."""
    clustered = sorted({index for a, b in _close_pairs(scene, modes, CLUSTER) for index in (a, b)})
    if not clustered:
        return sorted_modes(modes), ()
    kept = [mode for index, mode in enumerate(modes) if index not in clustered]
    for index in sorted(clustered, key=lambda i: modes[i].max_residual):
        mode = modes[index]
        if mode.max_residual > ROUNDING:  # one placed to rounding (msolve's) stays where it is
            mode = polished_mode(scene, compiled, mode, CLUSTER_STEPS, monotone=False)
        mode = flattened_mode(scene, compiled, mode if mode.max_residual < RESIDUAL_TOLERANCE else modes[index])
        if not any(same_mode(mode, other, scene) for other in kept):
            kept.append(mode)
    groups = _valley_groups(scene, kept)
    undecided = tuple(_valley_sentence([kept[i] for i in group]) for group in groups if len(group) > 1)
    return sorted_modes([_valley_representative([kept[i] for i in group]) for group in groups]), undecided


def _close_pairs(scene: Scene, modes, within: float) -> list[tuple[int, int]]:
    """Pairs of modes placing every joint within ``within`` of the linkage's size."""
    if len(modes) < 2:
        return []
    distance = _joint_distances(modes)
    first, second = np.nonzero(np.triu(distance < within * distance_bound(scene), k=1))
    return list(zip(first.tolist(), second.tolist(), strict=True))


def _same_valley(scene: Scene, first: AssemblyMode, second: AssemblyMode) -> bool:
    """Whether two verified modes lie in one valley of the residual, flat to rounding:
    their midpoint, polished on the link constraints, verifies as well as they do and
    stays put (moves less than a tenth of their distance). Between two distinct regular
    roots the midpoint's residual is ~L d²/8 and polishing carries it towards one of
    them; measured on 9/N15 and 9/N22, the polished midpoints moved 0–8 % of d."""
    joints = sorted(first.joints)
    ends = np.array([[complex(*mode.joints[j]) for j in joints] for mode in (first, second)])
    middle = ends.mean(axis=0)
    real, _ = polish_configurations(scene, joints, np.stack([middle.real, middle.imag], axis=-1)[None])
    polished = real[0, :, 0] + 1j * real[0, :, 1]
    residual = joint_residuals(scene, joints, polished[None])[0]
    distance = np.abs(ends[0] - ends[1]).max()
    return bool(residual <= max(10 * max(first.max_residual, second.max_residual), 1e-14)
                and np.abs(polished - middle).max() <= 0.1 * distance)


def _valley_groups(scene: Scene, modes: list[AssemblyMode]) -> list[list[int]]:
    """Indices of ``modes`` grouped by :func:`_same_valley` among close pairs (union–find)."""
    parent = list(range(len(modes)))

    def root(i: int) -> int:
        while parent[i] != i:
            i = parent[i]
        return i

    for a, b in _close_pairs(scene, modes, CLUSTER):
        if root(a) != root(b) and _same_valley(scene, modes[a], modes[b]):
            parent[root(a)] = root(b)
    groups: dict[int, list[int]] = {}
    for i in range(len(modes)):
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def _valley_representative(modes: list[AssemblyMode]) -> AssemblyMode:
    """The mode reported for a valley: one with a flat free-sign triangle (the singular
    mode itself, placed with its joints in line), else the one nearest the middle of the
    valley's parameter box. Along a valley the residual is ~c δ^k in each parameter's
    offset δ from the singular mode, so the box is symmetric about it; on issue 25's
    11/N561 (648 configurations, s10,1 in [9.961, 10.039], the mode at s10,1 = 10,
    s10,8 = 32) that member is 1.2e-6 from msolve's mode, the member nearest all others
    2.1e-4 and the configurations' mean 8.4e-4."""
    flat = [mode for mode in modes if 0 in mode.signs]
    if flat:
        return min(flat, key=lambda mode: mode.max_residual)
    names = sorted(modes[0].parameters)
    values = np.array([[mode.parameters[name] for name in names] for mode in modes])
    low, high = values.min(axis=0), values.max(axis=0)
    # absolute offsets: the parameters are squared distances of one linkage, and scaled
    # by its extent a parameter the valley barely spans would decide (s10,8 on 11/N561)
    return modes[int(np.argmin(np.abs(values - (low + high) / 2).max(axis=1)))]


def _valley_sentence(modes: list[AssemblyMode]) -> str:
    names = sorted(modes[0].parameters)
    ranges = ", ".join(f"{name} in [{min(m.parameters[name] for m in modes):.8g}, "
                       f"{max(m.parameters[name] for m in modes):.8g}]" for name in names)
    return (f"{len(modes)} verified configurations within {_joint_distances(modes).max():.1e} of each other "
            f"({ranges}) lie in one valley of the residual, flat to rounding: reported as one mode (a singular "
            "mode, or modes closer than floating point separates)")


def _joint_distances(modes) -> np.ndarray:
    """For n modes, the (n, n) largest distance of a joint between two of them."""
    joints = sorted(modes[0].joints)
    points = np.array([[complex(*mode.joints[j]) for j in joints] for mode in modes])
    return np.abs(points[:, None, :] - points[None, :, :]).max(axis=-1)


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
    joints, points = placed_configurations(scene, compiled, values.reshape(1, -1), branch.reshape(1, -1))
    if not np.isfinite(points).all():
        return AssemblyMode({}, tuple(int(s) for s in branch), {}, math.inf)  # a radicand was negative
    return mode_of(compiled, joints, values, branch, points[0], joint_residuals(scene, joints, points)[0])


def mode_of(compiled: CompiledSystem, joints: list[str], values: np.ndarray, branch: np.ndarray,
            points: np.ndarray, residual: float) -> AssemblyMode:
    """The :class:`AssemblyMode` at parameter ``values`` on ``branch``, joints ``joints``
    at ``points`` (complex)."""
    return AssemblyMode({parameter_name(pair): float(v) for pair, v in zip(compiled.parameters, values, strict=True)},
                        tuple(int(s) for s in branch),
                        {j: (float(p.real), float(p.imag)) for j, p in zip(joints, points, strict=True)},
                        float(residual))


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
    points, values, branches, residuals = polished_configurations(
        scene, compiled, joints, np.array([[complex(*mode.joints[j]) for j in joints]]), steps, monotone)
    return mode_of(compiled, joints, values[0], branches[0], points[0], residuals[0])


def joint_residual(scene: Scene, points: dict[str, complex]) -> float:
    """The largest relative error of joint positions (complex) on every link dimension
    and ground joint (:func:`joint_residuals` of one configuration). Shared by every
    method, baselines included, so their residuals compare."""
    joints = sorted(points)
    return float(joint_residuals(scene, joints, np.array([[points[j] for j in joints]]))[0])


def joint_residuals(scene: Scene, joints: list[str], points: np.ndarray) -> np.ndarray:
    """For configurations ``points`` (complex (K, J), joints named ``joints``): the largest
    relative error on every link dimension and ground joint; 1.0 if a rigid link is
    mirrored (its widest triangle reversed); inf where a joint is not finite. For
    coincident joints (target 0) the error is relative to the link's size."""
    at = {j: points[:, n] for n, j in enumerate(joints)}
    residual = np.zeros(len(points))
    for link in scene.links:
        size = max(float(target) for target in link.squared_distances.values())
        for pair, target in link.squared_distances.items():
            u, v = tuple(pair)
            residual = np.maximum(residual, np.abs(np.abs(at[u] - at[v]) ** 2 - float(target)) / (float(target) or size))
        triangle = scene.widest_triangle(link) if len(link.joints) >= 3 else None
        if triangle is not None:
            i, j, k = (at[n] for n in triangle)
            cross = ((j - i).conjugate() * (k - i)).imag
            mirrored = np.where(cross > 0, 1, -1) != scene.orientation(triangle)
            residual = np.where(mirrored, np.maximum(residual, 1.0), residual)
    size = distance_bound(scene)
    for joint, (x, y) in scene.world.items():
        target = complex(float(x), float(y))
        residual = np.maximum(residual, np.abs(at[joint] - target) / max(abs(target), size))
    return np.where(np.isfinite(points).all(axis=1), residual, np.inf)


def same_mode(first: AssemblyMode, second: AssemblyMode, scene: Scene) -> bool:
    """Whether two modes place every joint within 1e-6 of the linkage's size."""
    scale = distance_bound(scene)
    return all(
        math.dist(first.joints[j], second.joints[j]) < SAME_MODE * scale for j in first.joints
    )
