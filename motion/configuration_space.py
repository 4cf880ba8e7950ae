"""The configuration space of a one-degree-of-freedom chain in distance space (thesis
§6.2–6.3): its plan's d parameters (1 or 2 for every Grübler chain to eight links) locate
every joint, d − 1 closure conditions remain, and the signs of the plan's free-sign
triangles split the space into pieces, one per sign vector.

For d = 1 (the four-bar, the six-bars, twelve of the sixteen eight-bar chains) each
feasible value s of the parameter is one configuration per sign vector on which every
radicand is non-negative: the configuration space is a union of ranges of s. For d = 2
(the double butterfly) it is a curve in the plane of the two parameters: at each value of
the first, the roots of the closure condition in the second, per sign vector
(:func:`configurations_at`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from baranov.closure import CompiledSystem, sign_branches
from baranov.closure.evaluate import orientation_sign
from baranov.planner import Plan, one_dof_plans
from baranov.scene import Scene
from baranov.solvers.modes import AssemblyMode
from baranov.solvers.placement import compile_scene, placed_configurations
from baranov.solvers.verification import joint_residual

#: One configuration of a one-degree-of-freedom chain: the same record as a rigid chain's
#: assembly mode (the plan's parameter values, named as ``baranov solve`` names them, the
#: signs of its free-sign triangles, every joint's place, the largest relative error).
ConfigurationPoint = AssemblyMode


@dataclass(frozen=True)
class OneDofSystem:
    """A one-degree-of-freedom scene with its plan, the plan's compiled closure system,
    its sign vectors and an upper bound on each parameter (a squared distance)."""

    scene: Scene
    plan: Plan
    compiled: CompiledSystem
    branches: np.ndarray
    upper: tuple[float, ...]

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return self.compiled.parameter_names


def one_dof_system(scene: Scene, parameters: list[tuple[str, str]] | None = None) -> OneDofSystem:
    """The best plan of ``scene``'s one-degree-of-freedom chain (with parameters among
    ``parameters`` if given, e.g. ``[("P2", "P4"), ("P1", "P6")]`` as thesis §6.2 does for
    the double butterfly), compiled. Cost: the planner's search, milliseconds to ten links."""
    plan = one_dof_plans(scene.chain, parameters=parameters)[0]
    upper = tuple(scene.largest_distance(u, v) ** 2 for u, v in plan.parameters)
    return OneDofSystem(scene, plan, compile_scene(scene, plan), sign_branches(len(plan.free_sign_triangles)), upper)


#: Samples of the second parameter (even in its square root) per slice of a d = 2 space.
SLICE_SAMPLES = 4000


def configurations_at(system: OneDofSystem, value: float, samples: int = SLICE_SAMPLES) -> list[ConfigurationPoint]:
    """Every configuration whose first parameter is ``value``: for d = 1 one per sign
    vector on which the plan places every joint; for d = 2 one per root of the closure
    condition in the second parameter, per sign vector (sign changes over ``samples``
    samples even in √s, then Brent to 1e-13). Verified on the link dimensions; a root
    where the condition only touches 0 (a fold of the curve) can be missed between
    samples. Cost: one vectorised evaluation of ``samples`` × 2^m points."""
    if len(system.plan.parameters) == 1:
        values = np.full((len(system.branches), 1), float(value))
        return verified_configurations(system, values, system.branches)
    grid = np.linspace(0.0, math.sqrt(system.upper[1]), samples + 1)[1:] ** 2
    points = np.stack([np.full_like(grid, float(value)), grid], axis=-1)
    table = system.compiled.residuals(points, system.branches)[:, :, 0]
    values, branches = [], []
    for b, branch in enumerate(system.branches):
        row = table[b]
        def closure(s: float, branch=branch) -> float:
            return float(system.compiled.residuals(np.array([[value, s]]), branch[None, :])[0, 0, 0])

        roots = [float(grid[i]) for i in np.flatnonzero(row == 0)]
        roots += [brentq(closure, grid[i], grid[i + 1], xtol=1e-13 * grid[i + 1])
                  for i in np.flatnonzero(np.isfinite(row[:-1]) & np.isfinite(row[1:]) & (row[:-1] * row[1:] < 0))]
        values += [(value, root) for root in sorted(roots)]
        branches += [branch] * len(roots)
    if not values:
        return []
    return verified_configurations(system, np.array(values), np.array(branches))


def verified_configurations(system: OneDofSystem, values: np.ndarray, branches: np.ndarray) -> list[ConfigurationPoint]:
    """The configurations placed at parameter ``values`` (K, d) on ``branches`` (K, m) that
    verify to 1e-8 on every link dimension. Cost: one vectorised placement."""
    joints, points = placed_configurations(system.scene, system.compiled, values, branches)
    found = []
    for row, branch, placed in zip(values, branches, points, strict=True):
        if not np.isfinite(placed).all():
            continue
        configuration = {joint: complex(point) for joint, point in zip(joints, placed, strict=True)}
        residual = joint_residual(system.scene, configuration)
        if residual < 1e-8:
            found.append(ConfigurationPoint(dict(zip(system.parameter_names, map(float, row), strict=True)),
                                            tuple(int(s) for s in branch),
                                            {j: (p.real, p.imag) for j, p in configuration.items()}, residual))
    return found


def oriented_area(point: ConfigurationPoint, triangle: tuple[str, str, str]) -> float:
    """Twice the oriented area of the triangle of joints (positive counter-clockwise)."""
    (x1, y1), (x2, y2), (x3, y3) = (point.joints[name] for name in triangle)
    return (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1)


def sign_index(point: ConfigurationPoint, triangles: list[tuple[str, str, str]]) -> int:
    """The thesis's η: the signs of the oriented areas of ``triangles`` as the bits of an
    integer, the first the most significant, 1 for a positive area (§6.3: η = 10 = (1010)₂
    for A2,4,10 > 0, A1,3,6 < 0, A1,6,5 > 0, A4,9,7 < 0)."""
    return int("".join("1" if orientation_sign(point.joints, triangle) > 0 else "0" for triangle in triangles), 2)
