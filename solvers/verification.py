"""Whether a configuration is an assembly mode, and whether two are one: the relative
residual of joint positions on every link dimension (the same measure for every backend
and baseline, so that their residuals compare), and mode equality relative to the
linkage's size."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from baranov.scene import Scene

from .modes import AssemblyMode

#: A candidate is an assembly mode when every link dimension holds to this (relative).
RESIDUAL_TOLERANCE = 1e-8


#: Two configurations are one mode when every joint agrees to this (relative to the
#: linkage's size): :func:`same_mode`, :func:`first_of_each_mode`.
SAME_MODE = 1e-6


def distance_bound(scene: Scene) -> float:
    """Sum of the link diameters: no two joints are farther apart. The linkage's size, to
    which every tolerance on positions is relative (never to a fixed unit: issue 22, a
    triad scaled by 1e-6 had its two modes merged and a 3-RPR scaled by 1e6 failed to
    verify its modes when tolerances were floored at 1)."""
    return sum(math.sqrt(link.float_size) for link in scene.links)


def joint_residual(scene: Scene, points: dict[str, complex]) -> float:
    """The largest relative error of joint positions (complex) on every link dimension
    and ground joint (:func:`joint_residuals` of one configuration). Shared by every
    method, baselines included, so their residuals compare."""
    joints = sorted(points)
    return float(joint_residuals(scene, joints, np.array([[points[j] for j in joints]]))[0])


def joint_residuals(scene: Scene, joints: list[str], points: np.ndarray, instances: Sequence[Scene] | None = None,
                    owner: np.ndarray | None = None) -> np.ndarray:
    """For configurations ``points`` (complex (K, J), points named ``joints``: joint
    names, and ``P9'``, ``P9''`` for a slider's two points, :meth:`Scene.point_name`): the
    largest relative error on every link dimension, slider and ground joint
    (:func:`constraint_residuals`); 1.0 if a rigid link is mirrored (its widest triangle
    reversed) or a slider's axis reversed on one link; inf where a joint is not finite.
    For coincident joints (target 0) the error is relative to the link's size.

    ``instances``, ``owner``: configuration k is one of ``instances[owner[k]]``, an
    instance of ``scene`` (:func:`~baranov.scene.with_dimensions`: the same links, ground
    and sliders, other dimensions), and is checked on that instance's dimensions and link
    shapes: many instances verified at once, as each alone."""
    at = {j: points[:, n] for n, j in enumerate(joints)}
    residual = np.abs(constraint_residuals(scene, at, instances, owner)).max(axis=1, initial=0.0)
    residual = np.where(_mirrored(scene, at, instances, owner), np.maximum(residual, 1.0), residual)
    for slider in scene.sliders:
        (_, direction), (_, other_direction) = (slider_axis(scene, slider, axis.link, at) for axis in slider.axes)
        reversed_axis = ~((direction.conjugate() * other_direction).real > 0)
        residual = np.where(reversed_axis, np.maximum(residual, 1.0), residual)
    size = _per_configuration([distance_bound(instance) for instance in instances or [scene]], owner)
    for joint, (x, y) in scene.world.items():  # the fixed link is every instance's
        target = complex(float(x), float(y))
        residual = np.maximum(residual, np.abs(at[scene.point_name(scene.ground, joint)] - target)
                              / np.maximum(abs(target), size))
    return np.where(np.isfinite(points).all(axis=1), residual, np.inf)


def _mirrored(scene: Scene, at: dict[str, np.ndarray], instances: Sequence[Scene] | None,
              owner: np.ndarray | None) -> np.ndarray:
    """Whether each configuration has a rigid link mirrored: its widest triangle (each
    instance's own) turned the other way than in the link's shape. All links at once."""
    checks = []  # (link, triangle, whether each instance's widest triangle is it, its sign there)
    for index, link in enumerate(scene.links):
        if len(link.joints) < 3:
            continue
        shapes = [instance.links[index] for instance in instances] if instances is not None else [link]
        triangles = [shape.widest_triangle for shape in shapes]
        for triangle in dict.fromkeys(t for t in triangles if t is not None):
            checks.append((link.name, triangle, [t == triangle for t in triangles],
                           [shape.orientation(triangle) for shape in shapes]))
    shape = np.shape(next(iter(at.values())))
    if not checks:
        return np.zeros(shape, dtype=bool)
    i, j, k = (np.stack([at[scene.point_name(name, triangle[n])] for name, triangle, _, _ in checks], axis=-1)
               for n in range(3))
    cross = ((j - i).conjugate() * (k - i)).imag
    mine, turns = (_per_configuration(np.array([check[part] for check in checks]).T, owner) for part in (2, 3))
    return ((mine != 0) & (np.where(cross > 0, 1, -1) != turns)).any(axis=-1)


def _per_configuration(values: list, owner: np.ndarray | None):
    """One value of each instance, as each configuration's (``owner``: its instance); the
    value itself for one instance (``owner`` None)."""
    return np.asarray(values, dtype=float)[owner] if owner is not None else np.asarray(values[0], dtype=float)


def constraint_residuals(scene: Scene, at: dict[str, np.ndarray], instances: Sequence[Scene] | None = None,
                         owner: np.ndarray | None = None) -> np.ndarray:
    """The signed, smooth errors of configurations (point name → complex array of shape
    (K,)) on every constraint of the linkage, shape (K, m): per link dimension
    (|p_u − p_v|² − s_{u,v}) / s_{u,v} (relative to the link's size where s_{u,v} = 0);
    per slider the sine of the angle between its two links' axes and the distance of its
    second link's point from the first link's axis over the linkage's size. Zero exactly
    at the configurations that satisfy them (senses and mirrors aside:
    :func:`joint_residuals`); what Gauss–Newton polishes a slider chain on
    (:func:`~baranov.solvers.polish.polish_on_constraints`). ``instances``, ``owner``: as
    :func:`joint_residuals` takes them."""
    pairs = [(index, link.name, pair) for index, link in enumerate(scene.links) for pair in link.squared_distances]
    if not pairs:
        return _stacked(_slider_columns(scene, at), at)
    ends = [np.stack([at[scene.point_name(name, sorted(pair)[n])] for _, name, pair in pairs], axis=-1) for n in (0, 1)]
    targets, sizes = [], []
    for shape in instances or [scene]:  # each instance's dimensions, in the order of ``pairs``
        targets.append([shape.links[index].float_distances[pair] for index, _, pair in pairs])
        sizes.append([shape.links[index].float_size for index, _, _ in pairs])
    target, size = (np.array(values)[owner] if owner is not None else np.array(values[0]) for values in (targets, sizes))
    dimensions = (np.abs(ends[0] - ends[1]) ** 2 - target) / np.where(target != 0, target, size)
    sliders = _slider_columns(scene, at)
    return np.concatenate([dimensions, np.stack(sliders, axis=-1)], axis=-1) if sliders else dimensions


def placement_residuals(scene: Scene, at: dict[str, np.ndarray]) -> np.ndarray:
    """The errors of configurations (point name → complex array of shape (K,)) on the
    rigid-link model, shape (K, m): per link with joints P_a, P_b farthest apart,
    (|p_b − p_a|² − s_{a,b}) / s_{a,b}, and for every other joint P_k of it the real and
    imaginary parts of (p_k − p_a − c_k (p_b − p_a)) / √s_{a,b}, where
    c_k = (l_k − l_a) / (l_b − l_a) from the link's own coordinates l; sliders as in
    :func:`constraint_residuals`. Zero exactly at the assembly modes, mirrors excluded.

    Unlike the link dimensions, these equations stay regular where a link has its joints
    in line: there the middle joint may leave the line by δ at a cost of δ² in the
    distances, so every mode sits in a valley, and one at a double root in a valley flat
    to rounding 1e-2 wide (issue 25: 9/N27, tests/regressions/9-N27-double-root-25.json);
    here that mode is a double root of residual ~δ². It is the model msolve is given
    (:mod:`~baranov.solvers.msolve`)."""
    columns = []
    for link in scene.links:
        if len(link.joints) < 2:
            continue
        point = {joint: at[scene.point_name(link.name, joint)] for joint in link.joints}
        a, b = sorted(max(link.squared_distances, key=lambda pair: link.squared_distances[pair]))  # sorted: not hash order
        squared = float(link.squared_distances[frozenset((a, b))])
        columns.append((np.abs(point[b] - point[a]) ** 2 - squared) / squared)
        start, frame = complex(*link.local[a]), complex(*link.local[b]) - complex(*link.local[a])
        for k in link.joints:
            if k not in (a, b):
                offset = (point[k] - point[a] - (complex(*link.local[k]) - start) / frame * (point[b] - point[a]))
                columns += [offset.real / math.sqrt(squared), offset.imag / math.sqrt(squared)]
    return _stacked(columns + _slider_columns(scene, at), at)


def _slider_columns(scene: Scene, at: dict[str, np.ndarray]) -> list[np.ndarray]:
    """Per slider: the sine of the angle between its two links' axes, and the distance of
    its second link's point from the first link's axis over the linkage's size."""
    columns = []
    size = distance_bound(scene)
    for slider in scene.sliders:
        (foot, direction), (other_foot, other_direction) = (slider_axis(scene, slider, axis.link, at)
                                                            for axis in slider.axes)
        with np.errstate(invalid="ignore"):  # a point at ∞ (two parallel axes) gives NaN: not a mode
            columns.append((direction.conjugate() * other_direction).imag)
            columns.append((direction.conjugate() * (other_foot - foot)).imag / size)
    return columns


def _stacked(columns: list[np.ndarray], at: dict[str, np.ndarray]) -> np.ndarray:
    shape = np.shape(next(iter(at.values())))
    return np.stack(columns, axis=-1) if columns else np.zeros((*shape, 0))


def slider_axis(scene: Scene, slider, link: str, at: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(point, unit direction) of a slider's axis as fixed in ``link``, in world
    coordinates (complex arrays): the vector from the slider's point on that link to the
    reference joint, turned back by its angle α (thesis §4.1)."""
    axis = slider.axis_on(link)
    foot = at[scene.point_name(link, slider.joint)]
    turned = (at[scene.point_name(link, axis.reference)] - foot) * complex(float(axis.direction[0]),
                                                                            -float(axis.direction[1]))
    with np.errstate(invalid="ignore", divide="ignore"):
        return foot, turned / np.abs(turned)


def same_mode(first: AssemblyMode, second: AssemblyMode, scene: Scene) -> bool:
    """Whether two modes place every joint within 1e-6 of the linkage's size."""
    scale = distance_bound(scene)
    return all(
        math.dist(first.joints[j], second.joints[j]) < SAME_MODE * scale for j in first.joints
    )


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


def sorted_modes(modes) -> tuple[AssemblyMode, ...]:
    """``modes`` by parameter values, then signs (the order every backend reports)."""
    return tuple(sorted(modes, key=lambda m: (tuple(m.parameters.values()), m.signs)))
