"""A plan's bilateration steps and closure conditions as one polynomial system, solved
modulo a prime: the plan's own count of assembly modes for every coupling degree, three
included.

The plan (thesis §2.5) places joint P_k of step k from its base P_i, P_j by the
bilateration P_k = (X_k + i Y_k) / d_k, whose numerators involve ±√Δ_k (Δ_k = 16 A², the
Cayley–Menger form of the step's triangle). Here every step gets unknowns of its own,
the point's coordinates x_k, y_k and, for a free-sign step, the signed root r_k:

    r_k² − Δ_k = 0,   X_k − x_k d_k = 0,   Y_k − y_k d_k = 0      (each step k),
    N_c = 0                                                        (each closure pair c),
    z_e · e − 1 = 0                              (each non-constant denominator e: d_k, D_c),

with X_k, Y_k, d_k, Δ_k formed by the kernel itself
(:func:`~baranov.closure.bilateration.place_joints`) from the earlier steps' unknowns, the
parameters t_1, …, t_c and the link dimensions, and N_c / D_c the closure pair's computed
distance minus its known one. A solution is a configuration reached by the plan on one
sign branch (r_k carries the sign), with every step defined (d_k ≠ 0) and every computed
distance defined (D_c ≠ 0): the last equations (Rabinowitsch's trick) do the saturation
that :mod:`~baranov.solvers.exact.modular` does by gcds. One saturation variable per
denominator, not one for their product: on the 13-link Watt–Baranov example msolve took
290 s with z · Π e − 1 (865 terms) and 1.0 s with one per denominator. So the number of distinct
solutions over an algebraic closure of F_p is the instance's number of assembly modes
over C at which the plan is defined, for every coupling degree, unless the prime is one
of the finitely many bad ones. msolve counts them (F4 and sparse FGLM,
:func:`~baranov.solvers.msolve.solution_count_modulo`): 0.15 s on 9/B28, 1.0 s on the
13-link Watt–Baranov example, 1.4 s on 13/N3 (coupling degree 3, 376 modes), 38 s on
13/N4962 (458) and 97 s on 13/N20129 (600), one thread.

Each polynomial stays of low degree because every step starts from unknowns, not from
the expanded expressions of the earlier steps: the radical tower of
:mod:`~baranov.solvers.exact.characteristic`, which substitutes them, has conditions of
up to 26 640 terms and denominators of up to 529 793 terms on the coupling-3 trusses of 13
links, which msolve had not counted after 6 min 40 s of CPU (13/N20129). Substituting the expressions
of the steps whose denominator is a constant (fewer unknowns, larger equations) made no
difference that mattered (31.6 against 30.5 s on 13/N4962).
"""

from __future__ import annotations

from fractions import Fraction

import flint

from baranov.closure.bilateration import place_joints
from baranov.planner import Plan
from baranov.scene import Scene

from ..msolve import solution_count_modulo
from .characteristic import ExactMethodError, dimension_inputs, link_area_root

#: The prefix of the saturation variables of :func:`plan_system`: z0, z1, …
SATURATION = "z"


def _terms(polynomial, names: tuple[str, ...]) -> dict:
    """``polynomial`` (flint ``nmod_mpoly``) as {monomial (variable names, repeated):
    coefficient}, :func:`~baranov.solvers.msolve.msolve_text`'s form."""
    return {tuple(name for name, exponent in zip(names, exponents, strict=True) for _ in range(exponent)):
            Fraction(int(coefficient)) for exponents, coefficient in zip(polynomial.monoms(), polynomial.coeffs(),
                                                                         strict=True)}


def plan_system(scene: Scene, plan: Plan, prime: int) -> tuple[list[str], list[dict]]:
    """(variables, polynomials) of the system of the module docstring modulo ``prime``:
    the saturation variables z0, z1, … first, then x_k, y_k of every step's joint and
    r_k of every free-sign step in step order, then the parameters t_1, …, t_c. Raises
    :class:`~baranov.solvers.exact.characteristic.ExactMethodError` for a scene with
    sliders, inexact dimensions, an irrational link area or a prime dividing a
    denominator of the dimensions. O(steps) polynomials of bounded degree.

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.exact.characteristic import exact_plan
    >>> scene = load_scene("examples/7-B1.json")
    >>> variables, polynomials = plan_system(scene, exact_plan(scene), 1073741789)
    >>> " ".join(variables)   # seven steps, three of free sign, one parameter; two denominators
    'z0 z1 x0 y0 x1 y1 r1 x2 y2 x3 y3 r3 x4 y4 x5 y5 r5 x6 y6 t1'
    >>> len(polynomials)      # two per step, one per free-sign step, one condition, two saturations
    20
    """
    if scene.sliders:
        raise ExactMethodError("sliders: the plan's system is written for revolute joints only")
    if not scene.exact:
        raise ExactMethodError("scene: the plan's system needs integer or rational dimensions (a float was given)")
    names = []
    for index, step in enumerate(plan.steps):
        names += [f"x{index}", f"y{index}"] + ([f"r{index}"] if step.free_sign else [])
    names += [f"t{n + 1}" for n in range(plan.number_of_parameters)]
    context = flint.nmod_mpoly_ctx.get(names, modulus=prime, ordering="degrevlex")
    variable = dict(zip(names, context.gens(), strict=True))
    try:
        constant, known = dimension_inputs(scene, context, prime, {
            frozenset(pair): variable[f"t{n + 1}"] for n, pair in enumerate(plan.parameters)})
        equations, undefined = _step_equations(scene, plan, variable, constant, known)
    except ZeroDivisionError:
        raise ExactMethodError(f"the prime {prime} divides a denominator of the dimensions, or a "
                               "dimension that a step divides by") from None
    saturations = [f"{SATURATION}{k}" for k in range(len(undefined))]
    ring_names = tuple(names)
    polynomials = [_terms(polynomial, ring_names) for polynomial in equations]
    for saturation, denominator in zip(saturations, undefined, strict=True):
        terms = {(saturation, *monomial): c for monomial, c in _terms(denominator, ring_names).items()}
        terms[()] = terms.get((), Fraction(0)) - 1
        polynomials.append(terms)
    return saturations + names, polynomials


def _step_equations(scene: Scene, plan: Plan, variable: dict, constant, known) -> tuple[list, list]:
    """The equations of every step and closure pair (module docstring) and the
    non-constant denominators d_k, D_c whose zeros are saturated away."""
    equations, undefined = [], []
    step_indices = iter(range(len(plan.steps)))  # the kernel places one point per step, in order

    def signed_root(index, step, sides, radicand):
        if not step.free_sign:  # a link's three joints: known sides, a rational area
            return constant(link_area_root(scene, step.triangle))
        root = variable[f"r{index}"]
        equations.append(root * root - radicand)
        return root

    def placed(point):
        x_numerator, y_numerator, denominator = point
        index = next(step_indices)
        x, y = variable[f"x{index}"], variable[f"y{index}"]
        equations.extend([x_numerator - x * denominator, y_numerator - y * denominator])
        _undefined_where(denominator, undefined)
        return x, y, 1

    _, _, distance = place_joints(plan, known, signed_root, reduced_point=placed)
    for u, v in plan.closure_pairs:
        numerator, denominator = distance(u, v, computed=True)
        target = Fraction(scene.known[frozenset((u, v))])
        equations.append(numerator * target.denominator - denominator * constant(target.numerator))
        _undefined_where(denominator, undefined)
    return equations, undefined


def _undefined_where(denominator, undefined: list) -> None:
    """Add ``denominator`` to the ones saturated away, unless it is a constant; a constant
    0 (a dimension ≡ 0 modulo the prime) raises ZeroDivisionError: the prime is bad for
    this instance."""
    if isinstance(denominator, int) or denominator.is_constant():
        if denominator == 0:
            raise ZeroDivisionError("a step's constant denominator vanishes modulo the prime")
        return
    undefined.append(denominator)


def plan_solution_count_modulo(scene: Scene, plan: Plan, prime: int, timeout: float = 600.0) -> int | None:
    """The number of distinct solutions of :func:`plan_system` for ``scene`` and ``plan``
    modulo ``prime`` (an odd prime below 2³⁰): the number of assembly modes of the
    instance over C at which the plan is defined, for a good prime; None where the
    solution set has positive dimension. Errors as :func:`plan_system`, and
    :class:`~baranov.solvers.msolve.MsolveUnavailable` without msolve.

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.exact.characteristic import exact_plan
    >>> scene = load_scene("examples/7-B1.json")
    >>> plan_solution_count_modulo(scene, exact_plan(scene), 1073741789)  # doctest: +SKIP
    14
    """
    return solution_count_modulo(*plan_system(scene, plan, prime), prime, timeout)
