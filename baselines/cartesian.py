"""Cartesian baseline: what a Python user would write without the bilateration method.

Unknowns are the coordinates of every joint off the ground link (two per joint); there is
one equation per known link dimension, |P_u − P_v|² − s_{u,v} = 0, scaled by s_{u,v}
(relative, like every residual in this project); ``scipy.optimize.least_squares`` is
started from N random points and the converged solutions are de-duplicated. Nothing in
the formulation tells a rigid link from its mirror image, so mirrored solutions are
reported too: they are the baseline's spurious modes (their residual is 1.0).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

from baranov.scene import Scene
from baranov.solvers import Solution
from baranov.solvers.modes import AssemblyMode
from baranov.solvers.verification import distance_bound, joint_residual, same_mode, sorted_modes

from .coupling import chain_coupling_degree

#: A least-squares run has converged when every equation holds to this (relative).
CONVERGED = 1e-10


def cartesian_size(scene: Scene) -> tuple[int, int]:
    """(unknowns, equations) of the Cartesian formulation: two coordinates per joint off
    the ground link, one equation per known distance not within the ground link."""
    free, pairs = _unknowns_and_equations(scene)
    return 2 * len(free), len(pairs)


def solve_cartesian(scene: Scene, starts: int = 100, seed: int = 0) -> Solution:
    """Every distinct converged solution of the distance equations from ``starts`` random
    starting points, uniform in a square of side 2D around the ground joints (D: sum of
    the link diameters). Modes carry no parameters or signs; mirrored links are not
    filtered out (see the module docstring).

    >>> from baranov.scene import load_scene
    >>> pentad = load_scene("examples/5-B1.json")
    >>> modes = solve_cartesian(pentad, starts=100).assembly_modes
    >>> sum(m.max_residual < 1e-8 for m in modes), sum(m.max_residual == 1.0 for m in modes)  # modes, mirrored
    (6, 4)
    """
    free, pairs = _unknowns_and_equations(scene)
    index = {joint: n for n, joint in enumerate(free)}
    world = {j: complex(float(x), float(y)) for j, (x, y) in scene.world.items()}
    targets = np.array([float(scene.known[frozenset(p)]) for p in pairs])
    scale = np.where(targets > 0, targets, max(targets.max(), 1.0))

    def position(x: np.ndarray, joint: str) -> complex:
        return complex(x[2 * index[joint]], x[2 * index[joint] + 1]) if joint in index else world[joint]

    def equations(x: np.ndarray) -> np.ndarray:
        return np.array([abs(position(x, u) - position(x, v)) ** 2 for u, v in pairs]) / scale - targets / scale

    def jacobian(x: np.ndarray) -> np.ndarray:
        rows = np.zeros((len(pairs), x.size))
        for row, (u, v) in enumerate(pairs):
            difference = position(x, u) - position(x, v)
            for joint, sign in ((u, 2.0), (v, -2.0)):
                if joint in index:
                    rows[row, 2 * index[joint]] = sign * difference.real / scale[row]
                    rows[row, 2 * index[joint] + 1] = sign * difference.imag / scale[row]
        return rows

    rng = np.random.default_rng(seed)
    centre = np.mean(list(world.values()))
    reach = distance_bound(scene)
    modes: list[AssemblyMode] = []
    for _ in range(starts):
        start = np.repeat([[centre.real, centre.imag]], len(free), axis=0).ravel()
        start = start + rng.uniform(-reach, reach, size=start.size)
        result = least_squares(equations, start, jac=jacobian, xtol=1e-15, ftol=1e-15, gtol=1e-15)
        if np.max(np.abs(result.fun)) >= CONVERGED:
            continue
        points = {**world, **{joint: position(result.x, joint) for joint in free}}
        mode = AssemblyMode({}, (), {j: (p.real, p.imag) for j, p in sorted(points.items())},
                            joint_residual(scene, points))
        if not any(same_mode(mode, other, scene) for other in modes):
            modes.append(mode)
    return Solution(f"cartesian-{starts}", chain_coupling_degree(scene), (), (), sorted_modes(modes))


def _unknowns_and_equations(scene: Scene) -> tuple[list[str], list[tuple[str, str]]]:
    """The joints off the ground link, and the joint pairs of known distance that involve
    one of them."""
    free = sorted({j for link in scene.links for j in link.joints} - set(scene.world))
    return free, [tuple(sorted(pair)) for pair in scene.known if pair & set(free)]
