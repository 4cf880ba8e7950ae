"""Configurations from a plan's parameter values and free-sign branch (the world
positions of every joint, placed from the ground link), and back: parameters and signs
read from joint positions. Shared by the numeric and exact backends."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from baranov.closure import CompiledSystem, closure_system
from baranov.closure.sliders import SearchedParameter, SliderGeometry, takes_root
from baranov.planner import Plan
from baranov.scene import Scene
from baranov.scene.sliders import axis_frame, axis_turn, axis_unit

from .modes import AssemblyMode
from .polish import POLISH_STEPS, polish_configurations, polish_on_constraints
from .verification import RESIDUAL_TOLERANCE, distance_bound, joint_residuals, slider_axis

#: Relative doubled area below which :func:`read_back` calls a triangle flat (sign 0).
FLAT_AREA = 1e-10


#: A free-sign triangle of a verified mode whose doubled area is below this (relative to
#: the product of its sides from P_i) is tried flat by :func:`flattened_mode`.
NEARLY_FLAT = 1e-4

#: A snap of :func:`flattened_mode` may move a joint by at most this (relative to the
#: linkage's size): √RESIDUAL_TOLERANCE, how far a configuration that verifies can stand
#: from a singular mode (a residual quadratic in the displacement there).
FLAT_SNAP_MOVE = math.sqrt(RESIDUAL_TOLERANCE)


def compile_scene(scene: Scene, plan: Plan) -> CompiledSystem:
    """The closure system of ``plan`` bound to the dimensions of ``scene`` (floats), with
    the orientation of every link step read from the link's shape, and its sliders."""
    return CompiledSystem(
        closure_system(plan),
        {pair: float(value) for pair, value in scene.known.items()},
        {s.triangle: scene.orientation(s.triangle) for s in plan.steps if not s.free_sign},
        slider_geometry(scene),
        searched_parameters(scene, plan),
    )


def searched_parameters(scene: Scene, plan: Plan) -> dict[tuple[str, str], SearchedParameter]:
    """With sliders, the parameters searched through a map (:class:`SearchedParameter`):
    an oriented distance t (a pair with a slider), bounded by the shortest path of link
    dimensions to the nearer of the slider's points (:meth:`Scene.largest_distance`), and
    a parameter no such path bounds, on the scale of the linkage's size."""
    sliders = {slider.joint for slider in scene.sliders}
    searched = {}
    for pair in plan.parameters if sliders else ():
        bound = scene.largest_distance(*pair)
        if set(pair) & sliders or not math.isfinite(bound):
            bounded = math.isfinite(bound)
            searched[pair] = SearchedParameter(bool(set(pair) & sliders), bounded,
                                               bound if bounded else distance_bound(scene))
    return searched


def slider_geometry(scene: Scene, number: Callable[[tuple], Any] = lambda pair: complex(*map(float, pair)),
                    units: bool = False) -> dict[str, SliderGeometry]:
    """Each slider joint's links, the other (revolute) joints of each in the frame of its
    axis (:func:`~baranov.scene.sliders.axis_frame`) and the turns to the axes of the
    sliders it shares a link with: what the slider constructions need, each place or
    turn (a pair (re, im), exact where the scene is) made a number of the caller's
    arithmetic by ``number`` (complex floats by default). ``units``: each slider's frames
    in the units of √q that make them rational where they are rational times √q
    (:func:`~baranov.scene.sliders.axis_unit`; the exact method), else world units."""
    sliders = {slider.joint: slider for slider in scene.sliders}
    unit = {slider.joint: (axis_unit(slider, [scene.link_of(axis.link) for axis in slider.axes]) or 1) if units else 1
            for slider in scene.sliders}
    geometry = {}
    for slider in scene.sliders:
        links = tuple(axis.link for axis in slider.axes)
        frames = {link: scene.axis_frames[slider.joint, link] if unit[slider.joint] == 1
                  else axis_frame(slider, scene.link_of(link), unit[slider.joint]) for link in links}
        offsets = {link: {joint: number(z) for joint, z in frame.items() if joint not in sliders}
                   for link, frame in frames.items()}
        slider_offsets = {link: {joint: number(z) for joint, z in frame.items() if joint in sliders}
                          for link, frame in frames.items()}
        turns = {other: number(scene.axis_turns[slider.joint, other, link] if unit[slider.joint] == unit[other] == 1
                               else axis_turn(slider, sliders[other], scene.link_of(link),
                                              (unit[slider.joint], unit[other])))
                 for link in links for other in scene.link_of(link).joints if other in sliders and other != slider.joint}
        geometry[slider.joint] = SliderGeometry(links, offsets, turns, slider_offsets, unit[slider.joint])
    return geometry


def placed_from_ground(scene: Scene, matrices: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """World positions (complex) of every joint from the plan's M_k (relative to its
    reference, any array shape): the similarity that takes the ground link's first two
    joints onto their world coordinates. NaN where a radicand was negative or the ground
    joints coincide."""
    ground = scene.link_of(scene.ground)
    g1, g2 = (scene.point_name(ground.name, joint) for joint in ground.joints[:2])  # P1' for a slider
    world = {scene.point_name(ground.name, j): complex(float(x), float(y)) for j, (x, y) in scene.world.items()}
    with np.errstate(invalid="ignore", divide="ignore"):
        denominator = matrices[g2] - matrices[g1]
        reference = np.where(denominator != 0, (world[g2] - world[g1]) / np.where(denominator != 0, denominator, 1),
                             np.nan)
        origin = world[g1] - matrices[g1] * reference
        return {joint: origin + value * reference for joint, value in matrices.items()}


def placed_configurations(scene: Scene, compiled: CompiledSystem, values: np.ndarray,
                          branches: np.ndarray) -> tuple[list[str], np.ndarray]:
    """Joint names (sorted) and the configurations of K candidates, point k at parameter
    values ``values[k]`` on branch ``branches[k]``: complex array (K, J), NaN where a
    radicand was negative."""
    placed = placed_from_ground(scene, compiled.paired_matrices(values, branches))
    joints = sorted(placed)
    return joints, np.stack([np.broadcast_to(placed[j], (len(values),)) for j in joints], axis=1)


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
    return AssemblyMode({name: float(v) for name, v in zip(compiled.parameter_names, compiled.reported(values),
                                                          strict=True)},
                        tuple(int(s) for s in branch),
                        {j: (p.real, p.imag) for j, p in zip(joints, np.asarray(points, complex).tolist(), strict=True)},
                        float(residual))


def orientation(at: dict, i: str, j: str, k: str, flat: float):
    """The orientation of △P_i P_j P_k (joint positions as complex numbers or arrays):
    ±1, or 0 where its doubled area is at most ``flat`` times the product of its two sides
    from P_i."""
    first, second = at[j] - at[i], at[k] - at[i]
    cross = (first.conjugate() * second).imag
    return np.where(np.abs(cross) <= flat * np.abs(first) * np.abs(second), 0, np.where(cross > 0, 1, -1))


def read_back(compiled: CompiledSystem, at: dict[str, np.ndarray],
              flat: float = FLAT_AREA, scene: Scene | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The plan's parameter values and free-sign branch of configurations given as joint
    positions (complex arrays of one shape S): arrays of shape S + (parameters,) and
    S + (free-sign triangles,). A triangle whose doubled area is below FLAT_AREA of the
    product of its two sides from P_i gets sign 0 (flat): placed with ±1 at parameters
    read back to rounding, its radicand can come out a few ulps negative, and the mode
    would be lost (9/N28 of the collinear-joints sweep). ``flat`` replaces FLAT_AREA
    (NEARLY_FLAT for configurations known only to √ε: a double root, numeric.py).
    A slider chain (``scene`` with sliders; ``at`` with the sliders' points P9', P9''):
    :func:`_read_back_sliders`."""
    if scene is not None and scene.sliders:
        return _read_back_sliders(scene, compiled, at, flat)
    shape = np.shape(next(iter(at.values())))

    def stacked(columns: list) -> np.ndarray:
        return np.stack(columns, axis=-1) if columns else np.zeros((*shape, 0))

    parameters = stacked([np.abs(at[u] - at[v]) ** 2 for u, v in compiled.parameters])
    branch = stacked([orientation(at, *triangle, flat) for triangle in compiled.free_triangles])
    return parameters, branch


def _read_back_sliders(scene: Scene, compiled: CompiledSystem, at: dict[str, np.ndarray],
                       flat: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`read_back` for a slider chain (closure/sliders.py): a parameter with a slider
    is t, the other joint's oriented distance to the axis (returned as searched:
    :meth:`~baranov.closure.evaluate.CompiledSystem.searched_values`); a free step that touches a
    slider has the sign σ of its along-axis step, Re(conj(u)(p_b − p_a)) for the axis
    through P_a, P_b (the slider located) or from the base's revolute joint P_a to the
    joint placed P_b (a point off the axis), 0 within ``flat`` of the step's length; a
    step with no sign of its own (a turned axis, two axes meeting) reads +1."""
    sliders = {slider.joint: slider for slider in scene.sliders}
    shape = np.shape(next(iter(at.values())))

    def axis(name: str):
        return slider_axis(scene, sliders[name], sliders[name].axes[0].link, at)

    def stacked(columns: list) -> np.ndarray:
        return np.stack(columns, axis=-1) if columns else np.zeros((*shape, 0))

    parameters = []
    for u, v in compiled.parameters:
        if u in sliders or v in sliders:
            slider, other = (u, v) if u in sliders else (v, u)
            foot, direction = axis(slider)
            parameters.append((direction.conjugate() * (at[other] - foot)).imag)
        else:
            parameters.append(np.abs(at[u] - at[v]) ** 2)
    free_steps = [step for step in compiled.plan.steps if step.free_sign]
    branch = []
    for step, triangle in zip(free_steps, compiled.free_triangles, strict=True):
        touched = [name for name in triangle if name in sliders]
        if not touched:
            branch.append(orientation(at, *triangle, flat))
            continue
        if not takes_root(step, sliders):
            branch.append(np.ones(shape, int))
            continue
        i, j = step.base
        slider = step.joint if step.joint in sliders else next(name for name in step.base if name in sliders)
        start, end = (i, j) if step.joint in sliders else ((j if slider == i else i), step.joint)
        _, direction = axis(slider)
        along = (direction.conjugate() * (at[end] - at[start])).real
        branch.append(np.where(np.abs(along) <= flat * np.abs(at[end] - at[start]), 0, np.where(along > 0, 1, -1)))
    # as searched: mode_of maps them to the reported values (mapping t or s read back as
    # if searched gave NaN or a wrong value: 9/B28 with sliders P1, P2, P7, P8, P11)
    return compiled.searched_values(stacked(parameters)), stacked(branch)


def flattened_mode(scene: Scene, compiled: CompiledSystem, mode: AssemblyMode) -> AssemblyMode:
    """``mode`` rebuilt with its nearly flat free-sign triangles flat (sign 0), if that
    configuration verifies too. Next to a mode with a flat triangle the two branches meet
    like ±√δ, so candidates from either side verify to 1e-8 while their joints differ by
    ~√(1e-10) — at a double root of the characteristic polynomial the same mode was
    reported twice, 5e-5 apart (9/N20 of the collinear-joints sweep). Snapped flat, they
    are one; two genuinely distinct modes this close keep a triangle area whose removal
    breaks the verification (the merging pair of docs/stability.md).

    The snapped configuration must also stay within FLAT_SNAP_MOVE of the mode: a snap
    refines a mode, it does not replace it by another. Issue 25's 9/N13 domain-edge 1
    (seed 43): a simple mode at s2,3 = 9 − 3.4e-8, next to the domain's edge at 9, has a
    triangle of relative area ~1e-5; rebuilt flat at that s it became the mode *at* the
    edge, 0.31 away, with residual 5.7e-9, and the two were reported as one."""
    if scene.sliders:  # a triangle with a vertex at infinity has no area to snap
        return mode
    at = {joint: complex(*point) for joint, point in mode.joints.items()}
    flat = [index for index, triangle in enumerate(compiled.free_triangles)
            if orientation(at, *triangle, NEARLY_FLAT) == 0]
    if not flat or not mode.parameters:
        return mode
    branch = np.array(mode.signs)
    branch[flat] = 0
    snapped = configuration(scene, compiled, np.array(list(mode.parameters.values())), branch)
    if not snapped.max_residual < RESIDUAL_TOLERANCE:
        return mode
    moved = max(math.dist(snapped.joints[joint], point) for joint, point in mode.joints.items())
    return snapped if moved < FLAT_SNAP_MOVE * distance_bound(scene) else mode


def polished_configurations(scene: Scene, compiled: CompiledSystem, joints: list[str], points: np.ndarray,
                            steps: int = POLISH_STEPS, monotone: bool = True):
    """Configurations (complex (K, J)) polished on the link constraints
    (:func:`polish_configurations`; with sliders, on every constraint:
    :func:`polish_on_constraints`), with their parameters and free-sign branches read back
    and their residuals: ``(points, values, branches, residuals)``."""
    if scene.sliders:
        polished, _ = polish_on_constraints(scene, joints, points, steps, monotone)
    else:
        real = np.stack([points.real, points.imag], axis=-1)
        real, _ = polish_configurations(scene, joints, real, steps, monotone)
        polished = real[..., 0] + 1j * real[..., 1]
    values, branches = read_back(compiled, {j: polished[:, n] for n, j in enumerate(joints)}, scene=scene)
    return polished, values, branches, joint_residuals(scene, joints, polished)


def polished_mode(scene: Scene, compiled: CompiledSystem, mode: AssemblyMode, steps: int = POLISH_STEPS,
                  monotone: bool = True) -> AssemblyMode:
    """``mode`` polished on the link constraints (:func:`polish_configurations`, with
    ``steps`` and ``monotone``), its parameters and free-sign branch read back from the
    polished configuration."""
    joints = sorted(mode.joints)
    points, values, branches, residuals = polished_configurations(
        scene, compiled, joints, np.array([[complex(*mode.joints[j]) for j in joints]]), steps, monotone)
    return mode_of(compiled, joints, values[0], branches[0], points[0], residuals[0])
