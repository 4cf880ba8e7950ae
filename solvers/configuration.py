"""Assembly modes from candidate roots: configurations placed from the ground link,
verified on every link dimension and orientation, deduplicated. Shared by the numeric and
exact backends."""

from __future__ import annotations

import math

import numpy as np
from baranov.closure import CompiledSystem, closure_system
from baranov.planner import Plan
from baranov.topology import thesis_subscript

from .modes import AssemblyMode
from .scene import Scene

#: A candidate is an assembly mode when every link dimension holds to this (relative).
RESIDUAL_TOLERANCE = 1e-8


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


def assembly_modes(scene: Scene, compiled: CompiledSystem, candidates) -> tuple[AssemblyMode, ...]:
    """The verified, distinct assembly modes among ``candidates`` (parameter values,
    branch), sorted by parameters then signs."""
    modes: list[AssemblyMode] = []
    for values, branch in candidates:
        mode = configuration(scene, compiled, np.asarray(values, float), np.asarray(branch))
        if mode.max_residual < RESIDUAL_TOLERANCE and not any(same_mode(mode, other, scene) for other in modes):
            modes.append(mode)
    modes.sort(key=lambda m: (tuple(m.parameters.values()), m.signs))
    return tuple(modes)


def configuration(scene: Scene, compiled: CompiledSystem, values: np.ndarray, branch: np.ndarray) -> AssemblyMode:
    matrices, s_ref = compiled.matrices(values.reshape(1, -1), branch[None, :])
    m = {joint: complex(value[0, 0]) for joint, value in matrices.items()}
    ground = scene.link_of(scene.ground)
    g1, g2 = ground.joints[0], ground.joints[1]
    world = {j: complex(float(x), float(y)) for j, (x, y) in scene.world.items()}
    denominator = m[g2] - m[g1]
    if not all(map(math.isfinite, (denominator.real, denominator.imag))) or abs(denominator) == 0:
        return AssemblyMode({}, tuple(int(s) for s in branch), {}, math.inf)
    reference = (world[g2] - world[g1]) / denominator
    origin = world[g1] - m[g1] * reference
    points = {j: origin + value * reference for j, value in m.items()}
    if not all(math.isfinite(p.real) and math.isfinite(p.imag) for p in points.values()):
        return AssemblyMode({}, tuple(int(s) for s in branch), {}, math.inf)  # a radicand was negative
    residual = 0.0
    for link in scene.links:
        for pair, target in link.squared_distances.items():
            u, v = tuple(pair)
            residual = max(residual, abs(abs(points[u] - points[v]) ** 2 - float(target)) / float(target))
        triangle = scene.widest_triangle(link) if len(link.joints) >= 3 else None
        if triangle is not None:
            i, j, k = (points[n] for n in triangle)
            cross = ((j - i).conjugate() * (k - i)).imag
            if (1 if cross > 0 else -1) != scene.orientation(triangle):
                residual = max(residual, 1.0)  # mirrored rigid link
    for joint, target in world.items():
        residual = max(residual, abs(points[joint] - target) / max(abs(target), 1.0))
    names = [parameter_name(p) for p in compiled.parameters]
    return AssemblyMode(
        {name: float(v) for name, v in zip(names, values, strict=True)},
        tuple(int(s) for s in branch),
        {j: (p.real, p.imag) for j, p in sorted(points.items())},
        residual,
    )


def same_mode(first: AssemblyMode, second: AssemblyMode, scene: Scene) -> bool:
    scale = max(1.0, distance_bound(scene))
    return all(
        math.dist(first.joints[j], second.joints[j]) < 1e-6 * scale for j in first.joints
    )
