"""Near-copies of one singular assembly mode merged: at a root of multiplicity k the
residual is ~δ^k, so configurations around the mode verify too, and floating point
cannot always tell them apart (issue 25; docs/numeric.md)."""

from __future__ import annotations

import numpy as np

from baranov.closure import CompiledSystem
from baranov.scene import Scene

from .modes import AssemblyMode
from .placement import flattened_mode, mode_of, polished_configurations, read_back
from .polish import polish_at_singular_mode, polish_configurations, polish_on_constraints
from .verification import (
    RESIDUAL_TOLERANCE,
    distance_bound,
    first_of_each_mode,
    joint_residuals,
    placement_residuals,
    sorted_modes,
)

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
    joints = sorted(modes[0].joints)
    # the unclustered modes first: none is within CLUSTER of another, so all stay
    kept += _polished_members(scene, compiled, [modes[i] for i in clustered], joints)
    points = np.array([[complex(*mode.joints[j]) for j in joints] for mode in kept])
    kept = [kept[k] for k in first_of_each_mode(points, scene)]
    groups = _valley_groups(scene, kept)
    modes_out, undecided = [], []
    for group in groups:
        members = [kept[i] for i in group]
        parts = _between_humps(members)
        if len(parts) > 1:  # distinct roots along one valley: each its best member
            modes_out += [_flat_at_rounding(part) or min(part, key=lambda mode: mode.max_residual) for part in parts]
            continue
        if len(members) > 1:
            undecided.append(_valley_sentence(members))
            modes_out.append(_flat_at_rounding(members) or _valley_mode(scene, compiled, members))
        else:
            modes_out.append(members[0])
    return sorted_modes(modes_out), tuple(undecided)


def _polished_members(scene: Scene, compiled: CompiledSystem, modes: list[AssemblyMode],
                      joints: list[str]) -> list[AssemblyMode]:
    """``modes`` in order of their residuals, those above ROUNDING polished by CLUSTER_STEPS
    plain Gauss–Newton steps (all in one batch), each kept as polished only where that
    verifies, then :func:`flattened_mode`. (One at a time, and a duplicate check that
    recomputed the linkage's size per pair, these took 40 s of a 45 s solve on issue 25's
    9/N27 small-box 14, seed 42: 1447 members of one valley.)"""
    modes = sorted(modes, key=lambda mode: mode.max_residual)
    rough = [n for n, mode in enumerate(modes) if mode.max_residual > ROUNDING]  # msolve's stay where they are
    polished = list(modes)
    if rough:
        points = np.array([[complex(*modes[n].joints[j]) for j in joints] for n in rough])
        points, values, branches, residuals = polished_configurations(scene, compiled, joints, points, CLUSTER_STEPS,
                                                                      monotone=False)
        for k, n in enumerate(rough):
            if residuals[k] < RESIDUAL_TOLERANCE:
                polished[n] = mode_of(compiled, joints, values[k], branches[k], points[k], residuals[k])
    return [flattened_mode(scene, compiled, mode) for mode in polished]


#: A valley member placed to this residual is at rounding (a root, simple or not); one at
#: HUMP or more between two such is no root, and separates two distinct roots. HUMP was
#: 1e-11 (9/N18 of seed 30: 3.8e-10 to 5.5e-10 between two roots) until issue 25's 9/N18
#: double-root 27 (seed 42): a simple root 3.9e-3 from a double root, members between them
#: at 2.6e-13 to 4.1e-13, merged into one mode. Between the members at rounding around one
#: singular root none was above 1.0e-14 (11/N561); every valley regression passes at 1e-13.
AT_ROUNDING = 1e-14
HUMP = 1e-13


def _flat_at_rounding(members: list[AssemblyMode]) -> AssemblyMode | None:
    """The member of a valley placed with a free-sign triangle flat (a 0 in its signs)
    to rounding (AT_ROUNDING), the lowest residual first, if any: the singular mode
    itself, as msolve lists it where the plan's joints coincide
    (:func:`~baranov.solvers.coincidence.with_modes_from_msolve`). Among its neighbours
    a float member can verify lower: on issue 25's 9/N27 small-box 14 (seed 42) msolve's
    mode with P1 = P11, (s1,10, s1,11) = (5, 0), had residual 1.8e-15, and a member 1.5e-3
    away, at (4.9986, 8.6e-8), 2.7e-16 — and stood for the mode."""
    flat = [mode for mode in members if 0 in mode.signs and mode.max_residual <= AT_ROUNDING]
    return min(flat, key=lambda mode: mode.max_residual) if flat else None


def _between_humps(members: list[AssemblyMode]) -> list[list[AssemblyMode]]:
    """``members`` of one valley split where two roots lie in it: ordered along the
    parameter the valley spans most, every run of members between two placed to rounding
    (AT_ROUNDING) that holds one at HUMP or more is a cut. Around a singular root the
    members placed to rounding form one stretch in the middle (11/N561: 76 of 404, none
    between them above 1.0e-14); two near-tangent simple roots are at rounding at the ends,
    with 3.8e-10 to 5.5e-10 between them (issue 25's 9/N18 drawn at a double root, seed
    30: six members, two modes merged, then dropped as a near miss). One part when there
    is no cut. Cost O(n log n) for n members."""
    if len(members) < 3:
        return [members]
    names = sorted(members[0].parameters)
    values = np.array([[mode.parameters[name] for name in names] for mode in members])
    spread = int(np.argmax(values.max(axis=0) - values.min(axis=0))) if names else 0
    ordered = [members[i] for i in np.argsort(values[:, spread], kind="stable")] if names else members
    residuals = np.array([mode.max_residual for mode in ordered])
    rounding = np.flatnonzero(residuals <= AT_ROUNDING)
    cuts = [int(first + 1 + np.argmax(residuals[first + 1:second])) for first, second in zip(rounding, rounding[1:], strict=False)
            if second > first + 1 and residuals[first + 1:second].max() >= HUMP]
    if not cuts:
        return [members]
    bounds = [0, *cuts, len(ordered)]
    parts = [[mode for mode in ordered[low:high] if mode.max_residual < HUMP]
             for low, high in zip(bounds, bounds[1:], strict=False)]
    return [part for part in parts if part]


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
            parent[i] = parent[parent[i]]  # path halving: chains of 1400 members took 21 s unhalved
            i = parent[i]
        return i

    for a, b in _close_pairs(scene, modes, CLUSTER):
        if root(a) != root(b) and _same_valley(scene, modes[a], modes[b]):
            parent[root(a)] = root(b)
    groups: dict[int, list[int]] = {}
    for i in range(len(modes)):
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


#: The valley members polished on the rigid-link model, the best by that model first.
VALLEY_SEEDS = 8
VALLEY_STEPS = 80


def _refined_in_valley(scene: Scene, compiled: CompiledSystem, members: list[AssemblyMode]) -> AssemblyMode | None:
    """The mode a valley stands for, refined on the rigid-link model
    (:func:`~baranov.solvers.verification.placement_residuals`): its VALLEY_SEEDS members
    best on that model, polished by Gauss–Newton on it, the best result if it verifies and
    lies within the valley (CLUSTER of the linkage's size). Where the valley comes from a
    link with joints in line, the distances cannot tell its members apart but the rigid
    model can: on 9/N27 drawn at a double root (issue 25), 172 members verify to 1e-13
    across 1.4e-2, the member the parameter box chose was 2.4e-4 from msolve's mode and 8e-9
    on the rigid model, and the polished one agrees with msolve. At a double root the steps
    halve the distance, so VALLEY_STEPS reach rounding from 1e-4. None where nothing verifies
    (the caller falls back on :func:`_valley_representative`)."""
    joints = sorted(members[0].joints)
    points = np.array([[complex(*mode.joints[j]) for j in joints] for mode in members])
    before = np.abs(placement_residuals(scene, {j: points[:, n] for n, j in enumerate(joints)})).max(axis=1)
    seeds = points[np.argsort(before, kind="stable")[:VALLEY_SEEDS]]
    polished, after = polish_on_constraints(scene, joints, seeds, VALLEY_STEPS, model=placement_residuals)
    point = polished[int(np.argmin(after))]
    if after.min() > AT_ROUNDING:  # a singular mode the damped steps stall at (9/N18, 9/N28 of seed 40)
        polished, after = polish_at_singular_mode(scene, joints, seeds, placement_residuals, VALLEY_STEPS)
        point = polished[int(np.argmin(after))]
    if not np.abs(points - point).max(axis=1).min() <= CLUSTER * distance_bound(scene):
        return None
    values, branches = read_back(compiled, {j: point[None, n] for n, j in enumerate(joints)}, scene=scene)
    residual = joint_residuals(scene, joints, point[None])[0]
    if not residual < RESIDUAL_TOLERANCE:
        return None
    return flattened_mode(scene, compiled, mode_of(compiled, joints, values[0], branches[0], point, residual))


def _valley_mode(scene: Scene, compiled: CompiledSystem, members: list[AssemblyMode]) -> AssemblyMode:
    """The mode a valley stands for: :func:`_refined_in_valley` where the rigid-link model
    tells the members apart — the member :func:`_valley_representative` picks is above
    AT_ROUNDING on it — else that member. Where every member is at rounding on both
    models the refinement's pick is arbitrary: on issue 25's 7/N1 double-root 131 (seed
    42), eleven members within 1.6e-3 of s2,7 = 4, all at 2e-16 to 1e-15, the refinement
    stopped 2.5e-4 from msolve's mode and the middle of the valley's box 2.8e-6."""
    representative = _valley_representative(members)
    joints = sorted(representative.joints)
    point = np.array([[complex(*representative.joints[j]) for j in joints]])
    rigid = np.abs(placement_residuals(scene, {j: point[:, n] for n, j in enumerate(joints)})).max()
    if rigid <= AT_ROUNDING:
        return representative
    return _refined_in_valley(scene, compiled, members) or representative


def _valley_representative(modes: list[AssemblyMode]) -> AssemblyMode:
    """The mode reported for a valley: one with a flat free-sign triangle (the singular
    mode itself, placed with its joints in line), else the one nearest the middle of the
    valley's parameter box. Along a valley the residual is ~c δ^k in each parameter's
    offset δ from the singular mode, so the box is symmetric about it; on issue 25's
    11/N561 (648 configurations, s1,10 in [9.961, 10.039], the mode at s1,10 = 10,
    s8,10 = 32) that member is 1.2e-6 from msolve's mode, the member nearest all others
    2.1e-4 and the configurations' mean 8.4e-4."""
    flat = [mode for mode in modes if 0 in mode.signs]
    if flat:
        return min(flat, key=lambda mode: mode.max_residual)
    names = sorted(modes[0].parameters)
    values = np.array([[mode.parameters[name] for name in names] for mode in modes])
    low, high = values.min(axis=0), values.max(axis=0)
    # absolute offsets: the parameters are squared distances of one linkage, and scaled
    # by its extent a parameter the valley barely spans would decide (s8,10 on 11/N561)
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
