"""Exact backend: assembly modes from the certified real roots of the characteristic
polynomial (thesis §3.2–3.6: "the coefficients had to be computed in exact rational
arithmetic").

1. derive the characteristic polynomial of the best plan in exact rational arithmetic
   (:func:`baranov.solvers.characteristic.characteristic_polynomial`);
2. isolate its real roots with certified enclosures (flint/arb);
3. map every real root to the sign branches on which the radical closure condition holds
   there, and build and verify the configurations like the numeric backend;
4. at a real root where the plan itself is undefined — a bilateration's base joints
   coincide, as at T = s1,5 = 0 in thesis §5.1.3.2 — solve again with another plan
   (:mod:`baranov.solvers.coincidence`).

Coupling degree 0 needs no polynomial: every branch is a candidate.
"""

from __future__ import annotations

import numpy as np
from baranov.closure import sign_branches
from baranov.planner import Plan

from .characteristic import (
    CharacteristicPolynomial,
    ExactMethodError,
    characteristic_polynomial,
)
from .coincidence import solvable_plan, with_coincident_modes
from .configuration import assembly_modes, compile_scene, parameter_name
from .modes import Solution
from .scene import Scene

#: A branch is tried for a real root when its closure residual there is below this
#: (relative; the configuration is then verified to 1e-8 on every link dimension).
BRANCH_TOLERANCE = 1e-6


def solve_exact(scene: Scene, plan: Plan | None = None, *, coincidences: bool = True) -> Solution:
    """All assembly modes of ``scene`` (coupling degree 0 or 1) by the exact method; the
    result carries the characteristic polynomial. ``coincidences=False`` skips step 4
    (used by step 4 itself)."""
    plan = plan or solvable_plan(scene)
    compiled = compile_scene(scene, plan)
    branches = sign_branches(len(plan.free_sign_triangles))
    polynomial: CharacteristicPolynomial | None = None
    if plan.number_of_parameters == 0:
        candidates = [(np.zeros(0), branch) for branch in branches]
    elif plan.number_of_parameters == 1:
        polynomial = characteristic_polynomial(scene, plan)
        roots = np.array([float(root.mid()) for root in polynomial.real_roots()])
        roots = np.unique(roots[roots > 0])
        candidates = []
        if roots.size:
            residuals = np.abs(compiled.residuals(roots[:, None], branches)[:, :, 0])
            for b, n in zip(*np.nonzero(residuals < BRANCH_TOLERANCE), strict=True):
                candidates.append((roots[n:n + 1], branches[b]))
    else:
        raise ExactMethodError(
            f"coupling degree {plan.number_of_parameters}: the exact method solves coupling degrees 0 and 1 so far")
    modes = assembly_modes(scene, compiled, candidates)
    if polynomial is not None and coincidences:
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
