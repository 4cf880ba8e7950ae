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


def configurations_at(system: OneDofSystem, value: float, samples: int = SLICE_SAMPLES,
                      edges: bool = True) -> list[ConfigurationPoint]:
    """Every configuration whose first parameter is ``value``: for d = 1 one per sign
    vector on which the plan places every joint; for d = 2 one per root of the closure
    condition in the second parameter, per sign vector: sign changes over ``samples``
    samples even in √s, then Brent to 1e-13, and the roots between a sample and the edge
    of the domain next to it (:func:`_edge_roots`; not if ``edges`` is false). Verified
    on the link dimensions; a root where the condition only touches 0 (a fold of the
    curve) can be missed between samples. Cost: one vectorised evaluation of ``samples`` × 2^m points, and EDGE_STEPS
    of all the domain's edges between samples at once."""
    if len(system.plan.parameters) == 1:
        values = np.full((len(system.branches), 1), float(value))
        return verified_configurations(system, values, system.branches)
    grid = np.linspace(0.0, math.sqrt(system.upper[1]), samples + 1)[1:] ** 2
    return slice_configurations(system, value, grid, system.branches, edges=edges)


def slice_configurations(system: OneDofSystem, value: float, grid: np.ndarray, branches: np.ndarray,
                         axis: int = 0, edges: bool = True) -> list[ConfigurationPoint]:
    """The configurations of a d = 2 space with parameter ``axis`` (0 or 1) at ``value``
    and the other at a root of the closure condition among the sorted samples ``grid``,
    on each of ``branches`` (:func:`configurations_at` samples the whole range with the
    first fixed): exact zeros, sign changes (Brent to 1e-13) and, if ``edges``, the roots
    next to a domain edge (:func:`_edge_roots`, most of a slice's cost)."""
    table = system.compiled.residuals(_slice_points(value, grid, axis), branches)[:, :, 0]
    values, found_on = [], []
    for b, branch in enumerate(branches):
        row, closure = table[b], _slice_closure(system, value, branch, axis)
        roots = [float(grid[i]) for i in np.flatnonzero(row == 0)]
        roots += [brentq(closure, grid[i], grid[i + 1], xtol=1e-13 * grid[i + 1])
                  for i in np.flatnonzero(np.isfinite(row[:-1]) & np.isfinite(row[1:]) & (row[:-1] * row[1:] < 0))]
        values += [root for root in sorted(roots)]
        found_on += [branch] * len(roots)
    for b, root in _edge_roots(system, value, grid, table, branches, axis) if edges else ():
        values.append(root)
        found_on.append(branches[b])
    if not values:
        return []
    return verified_configurations(system, _slice_points(value, np.array(values), axis), np.array(found_on))


def _slice_points(value: float, at: np.ndarray, axis: int) -> np.ndarray:
    """Points (K, 2) with parameter ``axis`` at ``value`` and the other at ``at``."""
    fixed = np.full_like(at, float(value))
    return np.stack([fixed, at] if axis == 0 else [at, fixed], axis=-1)


def _slice_closure(system: OneDofSystem, value: float, branch: np.ndarray, axis: int):
    """The closure condition on ``branch`` along the slice, as a function of the free
    parameter (for Brent)."""
    def closure(s: float) -> float:
        return float(system.compiled.residuals(_slice_points(value, np.array([s]), axis), branch[None, :])[0, 0, 0])

    return closure


#: At most this many bisection steps place the domain's edge between two samples of a
#: slice (fewer where 1e-13 of the slice's range is reached sooner).
EDGE_STEPS = 48


def _edge_roots(system: OneDofSystem, value: float, grid: np.ndarray, table: np.ndarray,
                branches: np.ndarray, axis: int = 0) -> list[tuple[int, float]]:
    """(branch index, root) for every root of the closure condition between a sample of
    the slice at ``value`` and the edge of the domain next to it, where the condition is
    undefined (``table``: its values, ``branches`` × ``grid``): every such edge is bisected
    (all at once, EDGE_STEPS paired evaluations) and the condition's sign compared at the
    sample and at the edge's defined side, then Brent between them. Where a curve meets
    the edge at a flat triangle its root lies there: on eight-bar 9 of tests/test_motion.py
    the root at s1,10 = 0.535 lies 3e-4 below the edge, samples 2.2 apart, and no sample
    pair bracketed it. Cost: EDGE_STEPS vectorised evaluations, and Brent per root."""
    finite = np.isfinite(table)
    rows, columns = np.nonzero(finite[:, :-1] != finite[:, 1:])
    if rows.size == 0:
        return []
    defined = finite[rows, columns]
    inside = np.where(defined, grid[columns], grid[columns + 1])
    outside = np.where(defined, grid[columns + 1], grid[columns])
    signs, samples = branches[rows], inside.copy()

    def paired(at: np.ndarray) -> np.ndarray:
        return system.compiled.paired_residuals(_slice_points(value, at, axis), signs)[:, 0]

    gap = float(np.abs(outside - inside).max())
    for _ in range(min(EDGE_STEPS, max(1, math.ceil(math.log2(gap / (1e-13 * grid[-1])))))):  # to 1e-13
        middle = (inside + outside) / 2
        ok = np.isfinite(paired(middle))
        inside, outside = np.where(ok, middle, inside), np.where(ok, outside, middle)
    at_sample = np.where(defined, table[rows, columns], table[rows, columns + 1])
    at_edge = paired(inside)
    found = []
    for k in np.flatnonzero(np.isfinite(at_edge) & (at_edge * at_sample <= 0)):
        if at_edge[k] == 0:
            found.append((int(rows[k]), float(inside[k])))
            continue
        low, high = sorted((float(samples[k]), float(inside[k])))
        closure = _slice_closure(system, value, branches[rows[k]], axis)
        try:  # to 1e-15: next to the edge f is steep (a square root)
            found.append((int(rows[k]), brentq(closure, low, high, xtol=1e-15 * grid[-1])))
        except ValueError:  # undefined inside the bracket: a second gap there, no single root
            continue
    return found


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
