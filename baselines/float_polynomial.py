"""Float-polynomial baseline: the characteristic polynomial with its coefficients rounded
to a fixed precision, roots by a standard polynomial root finder.

This is the route the thesis warns against (§3.2: the coefficients "had to be computed in
exact rational arithmetic; otherwise numerical problems make impracticable the correct
computation of its roots"). The polynomial itself is derived exactly
(:func:`baranov.solvers.characteristic_polynomial`), made monic, and only then rounded:
to float64 for ``numpy.roots``, or to ``digits`` significant digits for
``mpmath.polyroots``. A root counts as real when its imaginary part is below 1e-8 of its
modulus; each positive real root becomes a configuration on every sign branch where the
closure condition holds (as in the exact backend), or on its best branch if none does.
The configurations are reported without verification, so inaccurate roots show up as
modes with large residuals (spurious).
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np

from baranov.closure import sign_branches
from baranov.planner import parameter_name
from baranov.scene import Scene
from baranov.solvers import Solution, SolverError, characteristic_polynomial
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.exact.backend import BRANCH_TOLERANCE
from baranov.solvers.placement import compile_scene, configuration
from baranov.solvers.verification import same_mode, sorted_modes

#: A computed root is taken as real when |imaginary part| ≤ REAL_TOLERANCE · |root|.
REAL_TOLERANCE = 1e-8


class FloatPolynomialError(SolverError):
    """The rounded polynomial cannot be solved (a coefficient overflows, or the root
    finder does not converge); the message says which."""


def float_roots(coefficients: list, digits: int | None = None) -> np.ndarray:
    """Roots of the polynomial with exact ``coefficients`` (highest degree first) made
    monic and rounded: to float64 and ``numpy.roots`` when ``digits`` is None, else to
    ``digits`` significant digits and ``mpmath.polyroots``. Complex numpy array.

    >>> np.sort(float_roots([1, -3, 2]).real)
    array([1., 2.])
    """
    leading = coefficients[0]
    monic = [c / leading for c in coefficients]
    if digits is None:
        try:  # float(Fraction) raises rather than returning inf
            return np.roots([float(c) for c in monic])
        except OverflowError:
            raise FloatPolynomialError("a coefficient of the monic polynomial overflows float64") from None
    with mpmath.workdps(digits):
        values = [mpmath.mpf(c.numerator) / c.denominator for c in monic]
        try:
            roots = mpmath.polyroots(values, maxsteps=400, extraprec=digits)
        except mpmath.libmp.NoConvergence:
            raise FloatPolynomialError(f"mpmath.polyroots did not converge at {digits} digits") from None
    return np.array([complex(r) for r in roots])


def solve_float_polynomial(scene: Scene, digits: int | None = None) -> Solution:
    """Assembly modes from the rounded characteristic polynomial (coupling degree 1); see
    the module docstring. ``digits`` None: float64 and numpy; else mpmath at that many
    significant digits."""
    plan = solvable_plan(scene)
    if plan.number_of_parameters != 1:
        raise FloatPolynomialError(f"coupling degree {plan.number_of_parameters}: a univariate characteristic "
                                   "polynomial exists for coupling degree 1 only")
    polynomial = characteristic_polynomial(scene, plan)
    coefficients = [Fraction(int(c)) for c in polynomial.polynomial.coeffs()][::-1]
    roots = float_roots(coefficients, digits)
    real = roots.real[(np.abs(roots.imag) <= REAL_TOLERANCE * np.abs(roots)) & (roots.real > 0)]
    compiled = compile_scene(scene, plan)
    branches = sign_branches(len(plan.free_sign_triangles))
    modes = []
    for root in np.unique(real):
        residuals = np.abs(compiled.residuals(np.array([[root]]), branches)[:, 0, 0])
        chosen = np.nonzero(residuals < BRANCH_TOLERANCE)[0]
        if chosen.size == 0 and np.isfinite(residuals).any():
            chosen = [int(np.nanargmin(residuals))]
        for b in chosen:
            mode = configuration(scene, compiled, np.array([root]), branches[b])
            if mode.joints and not any(same_mode(mode, other, scene) for other in modes):
                modes.append(mode)
    name = "float64-polynomial" if digits is None else f"mpmath{digits}-polynomial"
    return Solution(name, 1, (parameter_name(plan.parameters[0]),), plan.free_sign_triangles, sorted_modes(modes))
