"""Exact backend: assembly modes from the certified real roots of the characteristic
polynomial (thesis §3.2–3.6: "the coefficients had to be computed in exact rational
arithmetic").

1. derive the characteristic polynomial of the best plan in exact rational arithmetic
   (:func:`baranov.solvers.characteristic.characteristic_polynomial`);
2. isolate its real roots with certified enclosures (flint/arb);
3. map every real root to the sign branches on which the radical closure condition holds
   there, in ball arithmetic (flint arb) from the exact dimensions, and build the
   configurations from the same balls; verify them like the numeric backend. (Evaluating
   the condition in floats instead lost both modes of a pentad whose platform is 1e-8 of
   its width from collinear: rounding the dimensions moves the float condition's roots
   by ~4e-6 there, docs/stability.md);
4. at a real root where the plan itself is undefined — a bilateration's base joints
   coincide, as at T = s1,5 = 0 in thesis §5.1.3.2 — solve again with another plan
   (:mod:`baranov.solvers.coincidence`).

Coupling degree 0 needs no polynomial: every branch is a candidate. Coupling degree 2
(thesis §3.4.1.3) eliminates the second parameter by a resultant
(:mod:`baranov.solvers.coupling_two`); the second parameter of a mode is the real common
root of the two genuine curves above the first.
"""

from __future__ import annotations

import math

import flint
import numpy as np
from baranov.closure import sign_branches
from baranov.planner import Plan

from .characteristic import (
    CharacteristicPolynomial,
    ExactMethodError,
    characteristic_polynomial,
    closure_residuals,
    residual_verdict,
)
from .coincidence import solvable_plan, with_coincident_modes
from .coupling_two import characteristic_polynomial_two, common_points
from .configuration import (
    RESIDUAL_TOLERANCE,
    assembly_modes,
    compile_scene,
    joint_residual,
    parameter_name,
    placed_from_ground,
    same_mode,
    sorted_modes,
)
from .modes import AssemblyMode, Solution
from .scene import Scene

#: A branch is a candidate at a real root when its closure residual's ball there contains
#: 0 and is narrower than this (relative; the configuration is then verified to 1e-8 on
#: every link dimension).
BRANCH_TOLERANCE = 1e-6

#: Precisions (bits) at which a real root and its branch residuals are evaluated, in turn,
#: while some branch is undecided; coupling degree 2 starts higher, since the second
#: parameter is isolated from a curve with coefficients of hundreds of bits.
ROOT_BITS = (64, 256, 1024)
ROOT_BITS_TWO = (256, 1024, 4096)


def solve_exact(scene: Scene, plan: Plan | None = None, *, coincidences: bool = True) -> Solution:
    """All assembly modes of ``scene`` (coupling degree 0, 1 or 2) by the exact method;
    the result carries the characteristic polynomial (in the first parameter).
    ``coincidences=False`` skips step 4 (used by step 4 itself)."""
    plan = plan or solvable_plan(scene)
    branches = sign_branches(len(plan.free_sign_triangles))
    polynomial: CharacteristicPolynomial | None = None
    if plan.number_of_parameters == 0:
        modes = assembly_modes(scene, compile_scene(scene, plan), [(np.zeros(0), branch) for branch in branches])
    elif plan.number_of_parameters == 1:
        polynomial = characteristic_polynomial(scene, plan)
        modes = modes_at_real_roots(scene, plan, polynomial, branches)
    elif plan.number_of_parameters == 2:
        polynomial, curves = characteristic_polynomial_two(scene, plan)
        modes = modes_at_real_roots(scene, plan, polynomial, branches, curves)
    else:
        raise ExactMethodError(
            f"coupling degree {plan.number_of_parameters}: the exact method solves coupling degrees 0 to 2")
    if polynomial is not None and coincidences and plan.number_of_parameters == 1:
        pairs, roots = set(), []
        for factor, coincident in polynomial.degenerate:
            real = [float(root.real.mid()) for root, _ in factor.complex_roots() if root.imag == 0 and root.real >= 0]
            if real:
                pairs |= coincident
                roots += real
        if roots:
            modes = with_coincident_modes(scene, plan, pairs, roots, modes,
                                          lambda other: solve_exact(scene, other, coincidences=False))
    return Solution("exact", plan.number_of_parameters, tuple(parameter_name(p) for p in plan.parameters),
                    plan.free_sign_triangles, modes, polynomial)


def modes_at_real_roots(scene: Scene, plan: Plan, polynomial: CharacteristicPolynomial, branches: np.ndarray,
                        curves: tuple | None = None) -> tuple[AssemblyMode, ...]:
    """The verified assembly modes at the positive real roots of ``polynomial``; for
    coupling degree 2, at the real common points (u, v > 0) of the two ``curves`` above
    each root u (:func:`~baranov.solvers.coupling_two.common_points`).

    Each root is enclosed at ROOT_BITS[0] bits (ROOT_BITS_TWO for coupling 2) and every
    branch's closure residuals are evaluated over the enclosure in ball arithmetic from
    the exact dimensions (:func:`~baranov.solvers.characteristic.closure_residuals`): a
    branch where a ball excludes 0 is ruled out (rigorously); where every ball contains 0
    and is narrower than BRANCH_TOLERANCE of its closure distance, the configuration (the
    balls' midpoints of the same placement) is built and verified to RESIDUAL_TOLERANCE on every link dimension. Branches still
    undecided, or whose configuration fails the verification (joints 1e-5 apart place
    too coarsely at 64 bits), are evaluated again with a tighter root at the next
    precision. Modes at distinct roots are distinct (their parameter differs), however
    close; at one root, branches that place every joint alike (a flat free-sign triangle)
    are one mode.

    Cost: O(real roots × 2^m × steps) ball operations (m free-sign triangles), plus a
    root isolation per precision used."""
    names = tuple(parameter_name(pair) for pair in plan.parameters)
    every_branch = [tuple(int(s) for s in b) for b in branches]
    modes: list[AssemblyMode] = []
    previous = flint.ctx.prec
    try:
        for factor, _ in polynomial.factors:
            undecided: dict[int, list[tuple[int, ...]]] | None = None
            found: dict[int, list[AssemblyMode]] = {}
            for bits in ROOT_BITS if curves is None else ROOT_BITS_TWO:
                flint.ctx.prec = bits
                roots = sorted((root.real for root, _ in factor.complex_roots() if root.imag == 0),
                               key=lambda r: float(r.mid()))
                if undecided is None:
                    undecided = {index: every_branch for index in range(len(roots))}
                    found = {index: [] for index in undecided}
                for index, signs_list in list(undecided.items()):
                    still = set()
                    points = _parameter_points(roots[index], curves)
                    if points is None:  # the second parameter could not be isolated: more bits
                        still.update(signs_list)
                        points = []
                    for point in points:
                        for signs in signs_list:
                            residuals, placed, _ = closure_residuals(scene, plan, point, signs)
                            verdict = residual_verdict(residuals, BRANCH_TOLERANCE)
                            if verdict is False:
                                continue
                            mode = _ball_configuration(scene, placed, point, signs, names) if verdict else None
                            if mode is None or mode.max_residual >= RESIDUAL_TOLERANCE:
                                still.add(signs)  # too wide, or placed too coarsely: more bits
                            elif not any(same_mode(mode, other, scene) for other in found[index]):
                                found[index].append(mode)
                    if still:
                        undecided[index] = sorted(still)
                    else:
                        del undecided[index]
                if not undecided:
                    break
            modes += [mode for at_root in found.values() for mode in at_root]
    finally:
        flint.ctx.prec = previous
    return sorted_modes(modes)


def _parameter_points(root: flint.arb, curves: tuple | None) -> list[tuple[flint.acb, ...]]:
    """The parameter values to try at a real root: (root,) for coupling 1; the real common
    points (root, v), v > 0, of the two curves for coupling 2 (None if they cannot be
    isolated at this precision); [] where root ≤ 0."""
    if not root > 0:
        return []
    if curves is None:
        return [(flint.acb(root),)]
    common = common_points(curves, flint.acb(root))
    if common is None:
        return None
    return [(u, flint.acb(v.real)) for u, v in common if v.imag.contains(0) and v.real > 0]


def _ball_configuration(scene: Scene, points: dict, parameters: tuple[flint.acb, ...], signs: tuple[int, ...],
                        names: tuple[str, ...]) -> AssemblyMode:
    """The configuration from the plan's points placed in ball arithmetic
    (:func:`~baranov.solvers.characteristic.placed_points`) at ``parameters``."""
    matrices = {joint: np.array([complex(float(x.real.mid()), float(y.real.mid()))])
                for joint, (x, y) in points.items()}
    placed = {joint: complex(value[0]) for joint, value in placed_from_ground(scene, matrices).items()}
    if not all(math.isfinite(p.real) and math.isfinite(p.imag) for p in placed.values()):
        return AssemblyMode({}, signs, {}, math.inf)
    return AssemblyMode({name: float(value.real.mid()) for name, value in zip(names, parameters, strict=True)},
                        signs, {j: (p.real, p.imag) for j, p in sorted(placed.items())}, joint_residual(scene, placed))
