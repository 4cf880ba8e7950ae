"""Polishing approximate configurations on the link constraints themselves.

Next to the boundary of the feasible domain a closure condition behaves like a square
root of the distance to it (a triangle of the plan turns flat), so Newton's method on the
plan's parameters stalls on roots that lie very close to that boundary — an assembly mode
with a nearly flat free-sign triangle (found on the 9/B28 example of thesis §3.4.1.4,
sin = 5e-4). The link constraints |p_u - p_v|² = s_{u,v} in Cartesian coordinates are
polynomial and have no such singularity, so Gauss–Newton on them converges there; the
polished configuration gives back the parameters and the branch.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from baranov.scene import Scene

#: Gauss–Newton iterations.
POLISH_STEPS = 30


def polish_configurations(scene: Scene, joints: list[str], points: np.ndarray, steps: int = POLISH_STEPS,
                          monotone: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Newton on the relative link residuals (|p_u - p_v|² - s_{u,v}) / s_{u,v},
    ground joints held at their world coordinates, for K configurations at once, at most
    ``steps`` steps. ``monotone``: a step is taken only if it lowers the largest residual,
    and a configuration leaves once it stops doing so; otherwise every step is taken (at
    a singular mode the largest residual stalls at 1e-11 while the steps still approach
    the mode: :func:`~baranov.solvers.mode_clusters.merged_clusters`).

    Parameters
    ----------
    scene
        the linkage.
    joints
        joint names, in the order of the second axis of ``points``.
    points
        shape (K, J, 2), approximate configurations.

    Returns
    -------
        The polished configurations, shape (K, J, 2), and the largest relative link
        residual of each. Cost O(K · E · (2J)²) per step for E link dimensions.
    """
    index = {name: n for n, name in enumerate(joints)}
    fixed = np.zeros(len(joints), bool)
    points = np.array(points, dtype=float)
    for name, (x, y) in scene.world.items():
        fixed[index[name]] = True
        points[:, index[name]] = (float(x), float(y))
    pairs = [(index[u], index[v], float(target)) for pair, target in scene.known.items()
             for u, v in [tuple(pair)] if not (fixed[index[u]] and fixed[index[v]])]
    first = np.array([u for u, _, _ in pairs])
    second = np.array([v for _, v, _ in pairs])
    target = np.array([t for _, _, t in pairs])
    weight = np.where(target > 0, target, target.max())  # relative errors; coincident joints: to scale
    free = np.flatnonzero(~fixed)
    column = -np.ones(len(joints), int)
    column[free] = np.arange(len(free))
    rows = np.arange(len(pairs))

    def residuals(p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        difference = p[:, first] - p[:, second]  # (K, E, 2)
        return difference, (np.sum(difference**2, axis=-1) - target) / weight

    difference, residual = residuals(points)
    size = np.abs(residual).max(axis=1)
    active = np.flatnonzero(np.isfinite(size))
    for _ in range(steps):
        if active.size == 0:
            break
        jacobian = np.zeros((active.size, len(pairs), len(free), 2))
        for end, sign in ((first, 2.0), (second, -2.0)):
            movable = column[end] >= 0
            jacobian[:, rows[movable], column[end][movable], :] = (sign * difference[active][:, movable]
                                                                  / weight[movable, None])
        jacobian = jacobian.reshape(active.size, len(pairs), 2 * len(free))
        transposed = jacobian.transpose(0, 2, 1)  # batched matmul: BLAS, unlike einsum
        normal = transposed @ jacobian
        # Tikhonov term relative to the matrix (an absolute 1e-14 vanished in rounding on a
        # 3-RPR scaled by 1e-6, whose coincident joints make the matrix singular: issue 22)
        diagonal = np.diagonal(normal, axis1=1, axis2=2).max(axis=1)
        normal = normal + 1e-14 * np.maximum(diagonal, np.finfo(float).tiny)[:, None, None] * np.eye(2 * len(free))
        gradient = (transposed @ residual[active][:, :, None])[:, :, 0]
        step = np.linalg.solve(normal, -gradient[:, :, None])[:, :, 0]
        trial = points[active].copy()
        trial[:, free] += step.reshape(active.size, len(free), 2)
        trial_difference, trial_residual = residuals(trial)
        trial_size = np.abs(trial_residual).max(axis=1)
        better = np.isfinite(trial_size) & ((trial_size < size[active]) | (not monotone))
        moved = active[better]
        points[moved], difference[moved], residual[moved], size[moved] = (
            trial[better], trial_difference[better], trial_residual[better], trial_size[better])
        active = moved[size[moved] > 1e-15] if monotone else moved
    return points, size


def polish_on_constraints(scene: Scene, joints: list[str], points: np.ndarray, steps: int = POLISH_STEPS,
                          monotone: bool = True, model: Callable | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Newton on every constraint of the linkage, slider joints included
    (:func:`~baranov.solvers.verification.constraint_residuals`: link dimensions, parallel
    axes, a slider's point on the other link's axis), the ground link's points held at
    their world coordinates, for K configurations at once; as
    :func:`polish_configurations`, which it generalises for slider chains. The constraints
    are quadratic in the coordinates but for the normalised axis directions, so the
    Jacobian is taken by central differences (exact for the quadratic ones up to rounding).
    ``model``: other constraints of the same signature, e.g.
    :func:`~baranov.solvers.verification.placement_residuals`.

    Parameters
    ----------
    scene
        the linkage.
    joints
        point names (``P9'``, ``P9''`` for a slider's), in the order of the second
        axis of ``points``.
    points
        complex, shape (K, J), approximate configurations.

    Returns
    -------
        The polished configurations (complex (K, J)) and the largest constraint residual of
        each. Cost O(K · J · m) per step for m constraints.
    """
    from .verification import constraint_residuals, distance_bound

    points, free, residuals = _grounded(scene, joints, points, model or constraint_residuals)
    delta = 1e-7 * distance_bound(scene)

    residual = residuals(points)
    size = np.abs(residual).max(axis=1, initial=0.0)
    active = np.flatnonzero(np.isfinite(size))
    for _ in range(steps):
        if active.size == 0:
            break
        current = points[active]
        jacobian = _jacobian(residuals, current, free, delta)  # (K, m, 2 · free)
        transposed = jacobian.transpose(0, 2, 1)
        normal = transposed @ jacobian
        diagonal = np.diagonal(normal, axis1=1, axis2=2).max(axis=1)
        normal = normal + 1e-14 * np.maximum(diagonal, np.finfo(float).tiny)[:, None, None] * np.eye(2 * len(free))
        step = np.linalg.solve(normal, -(transposed @ residual[active][:, :, None]))[:, :, 0]
        trial = current.copy()
        trial[:, free] += step[:, 0::2] + 1j * step[:, 1::2]
        trial_residual = residuals(trial)
        trial_size = np.abs(trial_residual).max(axis=1, initial=0.0)
        better = np.isfinite(trial_size) & ((trial_size < size[active]) | (not monotone))
        moved = active[better]
        points[moved], residual[moved], size[moved] = trial[better], trial_residual[better], trial_size[better]
        active = moved[size[moved] > 1e-15] if monotone else moved
    return points, size


def polish_at_singular_mode(scene: Scene, joints: list[str], points: np.ndarray, model: Callable,
                            steps: int = 80) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Newton towards a singular assembly mode (a root of ``model`` where its
    Jacobian loses rank), for K configurations at once: ``steps`` steps, each the
    least-squares solution by the pseudo-inverse; of all iterates, the last whose residual
    2-norm fell below half the best before it (at rounding the norm is noise, and its
    minimum would wander along a valley flat to rounding: 4.7e-4 off on issue 25's
    11/N57, a root of multiplicity 4 or more). Newton's step covers 1/k of the way to a
    root of multiplicity k, so from δ away a double root is reached to rounding (~√ε) in
    log2(δ / √ε) steps; the first steps may raise the residual (they leave a curved
    valley's floor), so none is refused. The regularised normal equations of
    :func:`polish_on_constraints` stall there instead: their damping 1e-14 · σ_max²
    swamps σ² ≈ (c δ)². Measured on issue 25's 9/N18 drawn at a double root: from
    1.1e-3 to 3e-7 of msolve's mode in 12 steps, where the normal equations stayed at
    1.1e-3 (monotone in the largest residual) or crawled to 5.5e-6 (not monotone).

    Returns the configurations (complex (K, J)) and the 2-norm of each one's residuals.
    Cost O(K · J² · m) per step for m constraints.
    """
    from .verification import distance_bound

    current, free, residuals = _grounded(scene, joints, points, model)
    delta = 1e-7 * distance_bound(scene)
    residual = residuals(current)
    best, best_norm = current.copy(), np.linalg.norm(residual, axis=1)
    for _ in range(steps):
        jacobian = _jacobian(residuals, current, free, delta)
        step = -(np.linalg.pinv(jacobian) @ residual[:, :, None])[:, :, 0]
        current = current.copy()
        current[:, free] += step[:, 0::2] + 1j * step[:, 1::2]
        residual = residuals(current)
        norm = np.linalg.norm(residual, axis=1)
        better = np.isfinite(norm) & (norm < best_norm / 2)  # a real gain: at rounding the norm is noise
        best[better], best_norm[better] = current[better], norm[better]
        lost = ~np.isfinite(norm)  # a step to infinity: that configuration stops where it was best
        if lost.any():
            current[lost], residual[lost] = best[lost], residuals(best[lost])
    return best, best_norm


def _grounded(scene: Scene, joints: list[str], points: np.ndarray, model: Callable) -> tuple[np.ndarray, list[int], Callable]:
    """A copy of ``points`` (complex (K, J)) with the ground link's joints at their world
    coordinates, the indices of the other (free) joints, and ``model`` as a function of
    the (K, J) array."""
    points = np.array(points, dtype=complex)
    fixed = {scene.point_name(scene.ground, joint): complex(float(x), float(y)) for joint, (x, y) in scene.world.items()}
    for name, value in fixed.items():
        if name in joints:
            points[:, joints.index(name)] = value

    def residuals(p: np.ndarray) -> np.ndarray:
        return model(scene, {name: p[:, n] for n, name in enumerate(joints)})

    return points, [n for n, name in enumerate(joints) if name not in fixed], residuals


def _jacobian(residuals: Callable, points: np.ndarray, free: list[int], delta: float) -> np.ndarray:
    """The Jacobian (K, m, 2 · free) of ``residuals`` in the real and imaginary parts of
    the free joints, by central differences of step ``delta``."""
    columns = []
    for n in free:
        for unit in (1.0, 1j):
            ahead, behind = points.copy(), points.copy()
            ahead[:, n] += unit * delta
            behind[:, n] -= unit * delta
            columns.append((residuals(ahead) - residuals(behind)) / (2 * delta))
    return np.stack(columns, axis=-1)
