"""Assembly modes from candidate roots: the candidates of a backend (parameter values,
branch) placed from the ground link, verified on every link dimension and orientation
(polished first where cancellation cost digits), deduplicated. Shared by the numeric and
exact backends."""

from __future__ import annotations

import numpy as np

from baranov.closure import CompiledSystem
from baranov.scene import Scene

from .modes import AssemblyMode
from .placement import flattened_mode, mode_of, placed_configurations, polished_configurations
from .verification import RESIDUAL_TOLERANCE, first_of_each_mode, joint_residuals, sorted_modes

#: A candidate whose configuration misses RESIDUAL_TOLERANCE but holds to this is polished
#: on the link constraints first: where a triangle of the plan is very short or very flat,
#: the float radicand loses digits to cancellation (joints 1e-4 apart among sides ~10:
#: residual ~1e-6, docs/stability.md) although the candidate is next to a true mode.
POLISH_LIMIT = 1e-3


def distinct_candidates(values: np.ndarray, branches: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Candidates ``(parameter values, branch)`` with repeats removed (same branch, same
    values to 8 decimals of their logarithms): many starts converge to one root, and each
    candidate costs a configuration."""
    unique: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}
    for row, branch in zip(values, branches, strict=True):
        if np.isfinite(row).all() and (row > 0).all():
            unique.setdefault((tuple(int(s) for s in branch), *np.round(np.log(row), 8)), (row.copy(), branch))
    return list(unique.values())


def assembly_modes(scene: Scene, compiled: CompiledSystem, candidates,
                   configurations: tuple[list[str], np.ndarray, np.ndarray, np.ndarray] | None = None,
                   distinct: bool = False) -> tuple[AssemblyMode, ...]:
    """The verified, distinct assembly modes among ``candidates`` (parameter values,
    branch), sorted by parameters then signs. All candidates are placed, verified and
    polished together (a coupling-2 solve can bring 10⁴ candidates: one at a time, they
    took 41 of 62 s on an issue-25 instance of 9/N18); the candidate of each mode with the
    smallest residual is kept. Cost O(K · J) array work for K candidates of J joints, and O(K · n · J) for
    the duplicate check against the n modes.

    ``configurations`` ``(joints, points (K', J) complex, values, branches)``: candidates
    that are configurations already (polished on the link constraints), verified as they
    are rather than placed again from their parameters. Next to the edge of the feasible
    domain a parameter read back from a configuration is right to ~√ε only, and the
    closure condition is as steep as √ of the distance to the edge there: placed again,
    a mode 1e-6 from the edge came out with residual 3e-3 and was lost
    (tests/regressions/9-N2-mode-next-to-edge.json).

    ``distinct``: the candidates are known to be distinct modes with every triangle of
    their branch proper (certified roots: :mod:`~baranov.solvers.numeric.branch_and_prune`,
    each alone in a box where every radicand is positive), so the duplicate checks and the
    snap of nearly flat triangles (:func:`flattened_mode`) are skipped: two certified roots
    are two modes however close, and a proper triangle is not flat."""
    candidates = list(candidates)
    if not candidates and configurations is None:
        return ()
    if candidates:
        values = np.array([np.asarray(v, float) for v, _ in candidates]).reshape(len(candidates), -1)
        branches = np.array([np.asarray(b) for _, b in candidates], int).reshape(len(candidates), -1)
        joints, points = placed_configurations(scene, compiled, values, branches)
        residual = joint_residuals(scene, joints, points)
        polish = np.flatnonzero((RESIDUAL_TOLERANCE <= residual) & (residual < POLISH_LIMIT))
        if len(polish):
            points[polish], values[polish], branches[polish], residual[polish] = polished_configurations(
                scene, compiled, joints, points[polish])
    if configurations is not None:
        given_joints, given_points, given_values, given_branches = configurations
        given = (given_points, given_values, np.asarray(given_branches, int),
                 joint_residuals(scene, given_joints, given_points))
        if candidates:
            order = [given_joints.index(j) for j in joints]
            given = (given[0][:, order], *given[1:])
            points, values, branches, residual = (np.concatenate(pair) for pair in
                                                  zip((points, values, branches, residual), given, strict=True))
        else:
            joints, (points, values, branches, residual) = given_joints, given
    kept = np.flatnonzero(residual < RESIDUAL_TOLERANCE)
    if len(kept) == 0:
        return ()
    if distinct:
        return sorted_modes(mode_of(compiled, joints, values[k], branches[k], points[k], residual[k]) for k in kept)
    # the best placed candidate of each mode first: a shallow root's minimum of |f| lay
    # 7e-6 beside Brent's root and, listed first, had stood for the mode (issue 18)
    kept = kept[np.argsort(residual[kept], kind="stable")]
    kept = kept[first_of_each_mode(points[kept], scene)]
    modes = [flattened_mode(scene, compiled, mode_of(compiled, joints, values[k], branches[k], points[k], residual[k]))
             for k in kept]
    stacked = np.array([[complex(*mode.joints[j]) for j in joints] for mode in modes])
    return sorted_modes([modes[k] for k in first_of_each_mode(stacked, scene)])
