"""The exact method for coupling degree 2 (thesis §3.4.1.3–3.4.1.4, the 9/B28 truss).

A plan with two parameters u, v has two closure conditions. Each is cleared of radicals
like a one-parameter condition (:func:`~baranov.solvers.characteristic.eliminate_radicals`),
giving a polynomial N_i(u, v) that vanishes on the solutions of every sign branch; N_i is
factored over Q (flint) and its *curves* are kept whose points solve condition i on some
branch (tested at one point of each irreducible curve, in ball arithmetic). With G_i the
product of the kept curves, the resultant Res_v(G_1, G_2) (by primes:
:mod:`baranov.solvers.resultant`) vanishes at the u of every common point — the assembly
modes, but also points where G_1 and G_2 meet on *different* branches (thesis §3.4.1.3:
"a resultant of degree 1826" of which "a factor of degree 58" is characteristic). Its
irreducible factors are tested at one root each: kept when some common root v of
G_1(u, ·) and G_2(u, ·) solves both conditions on one branch. The product of the kept
factors is the characteristic polynomial in u; its degree is the number of assembly
modes over C for generic dimensions.

That resultant route is the fallback. First, the characteristic polynomial is lifted from
its images modulo primes (:mod:`baranov.solvers.modular`, where mismatched branches are
removed by a gcd instead of by factoring), and each of its irreducible factors is tested
the same way; it is used when every factor passes.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Sequence
from fractions import Fraction
from itertools import product

import flint
from baranov.planner import Plan

from .characteristic import (
    TEST_BITS,
    CharacteristicPolynomial,
    closure_residuals,
    eliminate_radicals,
    radical_tower,
    residual_verdict,
)
from .configuration import parameter_name
from .modular import lifted_characteristic_polynomial
from .resultant import coefficients_in_v, resultant_by_primes
from .scene import Scene

#: The bivariate ring of the two parameters (u = first plan parameter, v = second).
PLANE = flint.fmpz_mpoly_ctx.get(("u", "v"), "lex")


def plane_polynomial(norm: flint.fmpq_mpoly) -> flint.fmpz_mpoly:
    """A norm (in the tower's ring, free of radicals) as a primitive integer polynomial in
    (u, v)."""
    terms = {(exponents[-2], exponents[-1]): Fraction(int(c.p), int(c.q))
             for exponents, c in zip(norm.monoms(), norm.coeffs(), strict=True)}
    denominator = math.lcm(*(value.denominator for value in terms.values()))
    numerators = {k: int(value * denominator) for k, value in terms.items()}
    content = math.gcd(*numerators.values())
    return PLANE.from_dict({k: value // content for k, value in numerators.items()})


def roots_in_v(polynomial: flint.fmpz_mpoly, u: flint.acb) -> list[flint.acb]:
    """The roots v of ``polynomial``(u, v), refined to about half the working precision;
    None where flint cannot isolate them at this precision (a ball too wide, or a
    multiple root), which leaves the caller undecided."""
    bits = flint.ctx.prec
    try:
        return column(polynomial, u).roots(tol=flint.arb(2) ** (-bits // 2), maxprec=4 * bits)
    except ValueError:
        return None


def column(polynomial: flint.fmpz_mpoly, u: flint.acb) -> flint.acb_poly:
    """``polynomial`` at u, as a polynomial in v with ball coefficients."""
    return flint.acb_poly([sum((flint.acb(c) * u**k for k, c in terms.items()), flint.acb(0))
                           for terms in coefficients_in_v(polynomial)])


def branch_solves(scene: Scene, plan: Plan, values: Sequence[flint.acb], conditions: Sequence[int],
                  bits: int) -> bool | None:
    """Whether on some sign branch every closure condition in ``conditions`` holds at the
    parameter values ``values`` (:func:`~baranov.solvers.characteristic.residual_verdict`
    with tolerance 2^(-bits/8)): True if one branch confirms, False if every branch rules
    itself out, None (undecided) otherwise."""
    undecided = False
    for signs in product((1, -1), repeat=len(plan.free_sign_triangles)):
        residuals, _, _ = closure_residuals(scene, plan, values, signs)
        verdict = residual_verdict(residuals and [residuals[i] for i in conditions], flint.arb(2) ** (-bits // 8))
        if verdict:
            return True
        undecided |= verdict is None
    return None if undecided else False


def _some_point_solves(points_at: Callable[[], list], scene: Scene, plan: Plan, conditions: Sequence[int]) -> bool:
    """Whether one of the parameter points ``points_at()`` (computed afresh at each
    precision of TEST_BITS) solves ``conditions`` on some branch; False once every point
    rules itself out, or when no precision decides."""
    previous = flint.ctx.prec
    try:
        for bits in TEST_BITS:
            flint.ctx.prec = bits
            verdicts = [branch_solves(scene, plan, point, conditions, bits) for point in points_at()]
            if True in verdicts:
                return True
            if verdicts and None not in verdicts:
                return False
        return False
    finally:
        flint.ctx.prec = previous


def _curve_is_genuine(curve: flint.fmpz_mpoly, scene: Scene, plan: Plan, condition: int, seed: int = 0) -> bool:
    """Whether the irreducible ``curve`` of N_condition solves that condition on some
    branch: tested at the points of the curve above a random rational u (or, for a
    vertical line, at a random rational v on it)."""
    rng = random.Random(seed)
    value = flint.fmpq(rng.randrange(1, 10**6), rng.randrange(1, 10**3))

    def points() -> list:
        if curve.degrees()[1] > 0:
            return [(flint.acb(value), v) for v in roots_in_v(curve, flint.acb(value)) or []]
        terms = coefficients_in_v(curve)[0]  # a vertical line: a polynomial in u only
        line = flint.fmpz_poly([terms.get(k, 0) for k in range(max(terms) + 1)])
        return [(root, flint.acb(value)) for root, _ in line.complex_roots()]

    return _some_point_solves(points, scene, plan, (condition,))


def common_points(curves: Sequence[flint.fmpz_mpoly], u: flint.acb) -> list[tuple[flint.acb, flint.acb]] | None:
    """The points (u, v) with v a root of the first curve's column at u at which the
    second curve's value ball contains 0; None if the roots cannot be isolated at the
    current precision."""
    roots = roots_in_v(curves[0], u)
    if roots is None:
        return None
    second = column(curves[1], u)
    return [(u, v) for v in roots if second(v).contains(0)]


def _factor_is_genuine(factor: flint.fmpz_poly, curves: Sequence[flint.fmpz_mpoly], scene: Scene,
                       plan: Plan) -> bool:
    """Whether at one root u of the irreducible ``factor`` some common point of the curves
    solves both closure conditions on one branch."""
    if factor.degree() < 1:
        return False
    return _some_point_solves(lambda: common_points(curves, factor.complex_roots()[0][0]) or [], scene, plan, (0, 1))


def characteristic_polynomial_two(scene: Scene, plan: Plan) -> tuple[CharacteristicPolynomial,
                                                                     tuple[flint.fmpz_mpoly, flint.fmpz_mpoly]]:
    """The characteristic polynomial of a coupling-2 plan in its first parameter, and the
    two genuine curves G_1, G_2 (for the second parameter's back-substitution).

    The polynomial is first lifted from its images modulo primes
    (:func:`~baranov.solvers.modular.lifted_characteristic_polynomial`, which never forms
    the resultant over Q) and each of its irreducible factors is certified at a root like
    a factor of the resultant; if one fails, the resultant route is taken: Res_v(G_1, G_2)
    by primes, factored, every factor tested (9/B28 example: 174 s, against 19 s lifted)."""
    curves = genuine_curves(scene, plan)
    _, factors = lifted_characteristic_polynomial(scene, plan).factor()
    if all(_factor_is_genuine(factor, curves, scene, plan) for factor, _ in factors):
        kept, dropped = list(factors), []
    else:
        kept, dropped = genuine_factors_of_the_resultant(curves, scene, plan)
    polynomial = flint.fmpz_poly([1])
    for factor, _ in kept:
        polynomial *= factor
    if polynomial.degree() > 0 and polynomial.coeffs()[-1] < 0:
        polynomial = -polynomial
    return (CharacteristicPolynomial(parameter_name(plan.parameters[0]), polynomial,
                                     tuple((f, 1) for f, _ in kept), tuple(dropped)), tuple(curves))


def genuine_curves(scene: Scene, plan: Plan) -> tuple[flint.fmpz_mpoly, flint.fmpz_mpoly]:
    """G_1, G_2: the product of the irreducible curves of each condition's norm that
    solve it on some branch (:func:`_curve_is_genuine`)."""
    tower = radical_tower(scene, plan)
    curves = []
    for index, condition in enumerate(tower.conditions):
        norm, _ = eliminate_radicals(condition, tower)
        _, factors = plane_polynomial(norm).factor()
        genuine = PLANE.constant(1)
        for factor, _ in factors:
            if _curve_is_genuine(factor, scene, plan, index):
                genuine *= factor
        curves.append(genuine)
    return curves[0], curves[1]


def genuine_factors_of_the_resultant(curves: Sequence[flint.fmpz_mpoly], scene: Scene,
                                      plan: Plan) -> tuple[list, list]:
    """The irreducible factors of Res_v(G_1, G_2) that pass :func:`_factor_is_genuine`,
    and the others (thesis §3.4.1.3: 1826 and 58 for 9/B28)."""
    (du1, dv1), (du2, dv2) = curves[0].degrees(), curves[1].degrees()
    resultant = resultant_by_primes(curves[0], curves[1], du1 * dv2 + dv1 * du2)
    _, factors = resultant.factor()
    kept, dropped = [], []
    for factor, multiplicity in factors:
        (kept if _factor_is_genuine(factor, curves, scene, plan) else dropped).append((factor, multiplicity))
    return kept, dropped
