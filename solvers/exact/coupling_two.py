"""The exact method for coupling degree 2 (thesis §3.4.1.3–3.4.1.4, the 9/B28 truss).

A plan with two parameters u, v has two closure conditions. Each is cleared of radicals
like a one-parameter condition (:func:`~baranov.solvers.exact.characteristic.eliminate_radicals`),
giving a polynomial N_i(u, v) that vanishes on the solutions of every sign branch; N_i and
the contents divided out on the way are factored over Q (flint) and their *curves* are
kept whose points solve condition i on some branch (tested on one generic line, in ball
arithmetic): G_i, the product of the kept curves.

The u of every assembly mode is a root of the *candidate polynomial*: the gcd of
Res_v(N_1, N_2) and Res_v(N_1, N_c), N_c the norm of F_1 + c·F_2, which keeps every
common point on one branch and drops most mismatched ones (thesis §3.4.1.3: "a resultant
of degree 1826" of which "a factor of degree 58" is characteristic). It is lifted from
its images modulo primes (:mod:`baranov.solvers.exact.modular`), without the saturations that
the mode *count* uses, since they remove whole values of u. Each irreducible factor is
kept when at one of its roots a common point of G_1 and G_2 — computed exactly above that
root (:mod:`baranov.solvers.exact.fibers`) — solves both conditions on one branch. The product
of the kept factors is the characteristic polynomial in u; its degree is the number of
assembly modes over C for generic dimensions. ``route="resultant"`` takes the factors of
Res_v(G_1, G_2) over Q instead (slower; independent of the modular code).
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Sequence

import flint

from baranov.closure.evaluate import distinct_branches
from baranov.planner import Plan, parameter_name
from baranov.scene import Scene

from ..modes import MovableLinkageError
from .characteristic import (
    TEST_BITS,
    CharacteristicPolynomial,
    RadicalTower,
    eliminate_radicals,
    radical_tower,
    real_configuration,
    residual_verdict,
    residuals_on_branches,
)
from .fibers import Fiber, column_over_field, common_fiber
from .modular import denominator_parts, lifted_characteristic_polynomial
from .msolve_images import characteristic_by_msolve
from .newton_lifting import candidate_by_newton
from .plane_factoring import PLANE, factors_over_q, plane_factors, plane_polynomial
from .resultant import coefficients_in_v, resultant_by_primes
from .roots import complex_roots


def branch_solves(scene: Scene, plan: Plan, values: Sequence[flint.acb], conditions: Sequence[int],
                  bits: int, coincident: set | None = None, real_only: bool = False,
                  real_rules_out: bool = False, too_wide: set | None = None) -> bool | None:
    """Whether on some sign branch every closure condition in ``conditions`` holds at the
    parameter values ``values`` (:func:`~baranov.solvers.exact.characteristic.residual_verdict`
    with tolerance 2^(-bits/8)): True if one branch confirms, False if every branch rules
    itself out, None (undecided) otherwise. A branch on which the plan is undefined (a
    base distance's ball contains 0) is undecided, and its joint pair is added to
    ``coincident``. ``real_only``: only real configurations count (a branch whose
    triangle does not exist rules itself out). ``real_rules_out``: a branch rules itself
    out only where its configuration is real (:func:`~baranov.solvers.exact.characteristic.real_configuration`;
    a slider chain's curve test at a real point, :func:`_some_point_solves`). ``too_wide``
    gets True where a branch is undecided for want of precision (a ball too wide, or one
    around 0 where the plan divides)."""
    undecided = False
    branches = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    for _, residuals, points, pair in residuals_on_branches(scene, plan, values, branches, real_only):
        if residuals is None:
            if pair is None:  # real_only: a triangle of this branch does not exist
                continue
            if coincident is not None:
                coincident.add(pair)
            if too_wide is not None:
                too_wide.add(True)
            undecided = True
            continue
        verdict = residual_verdict([residuals[i] for i in conditions], flint.arb(2) ** (-bits // 8))
        if verdict:
            return True
        if verdict is None and too_wide is not None:
            too_wide.add(True)
        undecided |= verdict is None or (real_rules_out and not real_configuration(points))
    return None if undecided else False


def _some_point_solves(points_at: Callable[[], list], scene: Scene, plan: Plan,
                       conditions: Sequence[int]) -> bool | frozenset:
    """Whether one of the parameter points ``points_at()`` (computed afresh at each
    precision of TEST_BITS; None where they cannot be isolated at that precision) solves
    ``conditions`` on some branch: True once one does, False once every point rules
    itself out on every branch; otherwise (no precision decides, or the plan is undefined
    at a point) the set of joint pairs found coincident, possibly empty. Real points are
    tried first.

    A slider construction conjugates (closure/sliders.py): its residuals vanish at real
    configurations only, so on a slider chain a point rules a branch out only where the
    point is real (its coordinates exactly real: a rational line's real roots, as flint
    isolates them) and the branch's configuration too (every triangle built); a complex
    point can only confirm (commit 173e0c5: at the complex points of genuine curves every
    branch looked ruled out)."""
    previous = flint.ctx.prec
    coincident: set = set()
    try:
        for bits in TEST_BITS:
            flint.ctx.prec = bits
            coincident.clear()
            points = points_at()
            if points is None:  # not isolated at this precision
                continue
            verdicts = []
            for point in _real_first(points):
                verdicts.append(_point_solves(scene, plan, point, conditions, bits, coincident, set()))
                if verdicts[-1] is True:
                    return True
            if None not in verdicts:
                return False
        return frozenset(coincident)
    finally:
        flint.ctx.prec = previous


def _curve_point_decides(points_at: Callable[[], list], scene: Scene, plan: Plan, condition: int) -> bool | frozenset:
    """For :func:`_curve_is_genuine`: the points of a curve on one line (``points_at()``,
    isolated at the current precision: :func:`points_on_line`), real ones first, each
    taken to more bits of TEST_BITS until it decides. One generic point of an
    irreducible curve decides the curve: True where some branch solves the condition
    there, False where every branch rules itself out, and the joint pairs found
    coincident where the plan is undefined there at every precision (the plan is
    undefined along the curve). A point left undecided only by complex configurations (a
    slider chain, :func:`_point_solves`) is not taken to more bits: the next point is.
    Returns an empty set where no point decides."""
    previous = flint.ctx.prec
    isolated: dict[int, list] = {}

    def points(bits: int) -> list:
        if bits not in isolated:
            flint.ctx.prec = bits
            isolated[bits] = _real_first(points_at())
        return isolated[bits]

    try:
        for index in range(len(points(TEST_BITS[0]))):
            coincident: set = set()
            for bits in TEST_BITS:
                point = points(bits)[index]
                flint.ctx.prec = bits
                too_wide: set = set()
                verdict = _point_solves(scene, plan, point, (condition,), bits, coincident, too_wide)
                if verdict is not None:
                    return verdict
                if not too_wide:  # undecided at complex configurations: bits do not help
                    break
            else:
                if coincident:
                    return frozenset(coincident)
        return frozenset()
    finally:
        flint.ctx.prec = previous


def _real_first(points: list) -> list:
    """``points`` with the exactly real ones first (a slider chain's branches are ruled
    out at those only), each group in its order."""
    return sorted(points, key=lambda point: not _is_real(point))


def _is_real(point: Sequence[flint.acb]) -> bool:
    """Whether every coordinate of ``point`` is exactly real (an arb compares equal to 0
    only where it is exactly 0): a rational line's real roots, as flint isolates them."""
    return all(value.imag == 0 for value in point)


def _point_solves(scene: Scene, plan: Plan, point: Sequence[flint.acb], conditions: Sequence[int], bits: int,
                  coincident: set, too_wide: set) -> bool | None:
    """:func:`branch_solves` at one point, where on a slider chain only a real point with
    a real configuration can rule a branch out (:func:`_some_point_solves`)."""
    if not scene.sliders:
        return branch_solves(scene, plan, point, conditions, bits, coincident, too_wide=too_wide)
    verdict = branch_solves(scene, plan, point, conditions, bits, coincident, real_rules_out=True, too_wide=too_wide)
    return None if verdict is False and not _is_real(point) else verdict


def _curve_is_genuine(curve: flint.fmpz_mpoly, scene: Scene, plan: Plan, condition: int, seed: int = 0) -> bool:
    """Whether the irreducible ``curve`` of N_condition solves that condition on some
    branch: tested at the points of the curve above a random rational u (or, for a
    vertical line, at a random rational v on it).

    An irreducible curve over Q either lies in the closure of the condition's solutions
    or meets them in finitely many points, so one generic line decides. A line whose
    points cannot be isolated (a multiple root or a vanishing leading coefficient above
    that u: non-generic) is replaced by another, up to ten times; then the curve is kept
    (keeping a curve never loses a mode: its common points are tested again). A curve
    along which the plan is undefined (two joints of a bilateration base coincide, or the
    parameter u or v is 0) holds no mode the plan can express and is dropped; modes with
    coincident joints are the business of :mod:`baranov.solvers.coincidence`.

    Where the curve's points on the line are Galois conjugates (:func:`conjugate_points`)
    and the scene has no slider, one of them is tested: a point solves the condition on
    some branch exactly when its conjugates do, on the conjugate branches (9/B28: the
    (12, 12) extraneous curve's test, 12 points on every branch, took 0.115 s)."""
    rng = random.Random(seed)
    for _ in range(10):
        value = _test_line(rng, scene, plan, curve)
        # a slider construction's residuals vanish at real points only (_some_point_solves)
        some = not scene.sliders and conjugate_points(curve, value)

        def points(value=value, some=some):
            found = points_on_line(curve, value)
            return found[:1] if some and found else found

        verdict = _curve_point_decides(points, scene, plan, condition)
        if verdict is True:
            return True
        if verdict is False or verdict:  # ruled out, or the plan is undefined along the curve
            return False
    return True


def _test_line(rng: random.Random, scene: Scene, plan: Plan, curve: flint.fmpz_mpoly) -> flint.fmpq:
    """A random rational line u = value (v = value for a curve free of v) for
    :func:`_curve_is_genuine`. On a slider chain it crosses the parameter's range of real
    configurations (below its bound :meth:`~baranov.scene.Scene.largest_distance`,
    squared for a squared distance, of either sign for a slider's t), where the curve's
    points are real often enough to rule a curve out (:func:`_some_point_solves`); of eight
    such lines, the first that meets the curve in a real point. Drawn
    anywhere up to 10⁶, the points of the 9-link chain whose curve tests took 18.6 of
    29.6 s were complex on nearly every line, and each line escalated through every
    precision."""
    if not scene.sliders:
        return flint.fmpq(rng.randrange(1, 10**6), rng.randrange(1, 10**3))
    pair = plan.parameters[0 if curve.degrees()[1] > 0 else 1]
    signed = bool(set(pair) & {slider.joint for slider in scene.sliders})
    bound = scene.largest_distance(*pair)
    upper = (bound if signed else bound**2) if math.isfinite(bound) else 10.0**3
    drawn = [flint.fmpq(round(rng.uniform(-upper if signed else 0.0, upper) * 1000) or 1, 1000) for _ in range(8)]
    # the first line that meets the curve in a real point (a root isolation each: milliseconds)
    return next((value for value in drawn if any(map(_is_real, points_on_line(curve, value)))), drawn[0])


def conjugate_points(curve: flint.fmpz_mpoly, value: flint.fmpq) -> bool:
    """Whether the points of the irreducible ``curve`` on the line u = ``value`` (v =
    ``value`` for a curve free of v, :func:`points_on_line`) are conjugate over Q: the
    curve's column at u = ``value`` is irreducible over Q (true for all but a thin set of
    values, Hilbert's irreducibility theorem); a curve free of v is itself that column.

    >>> u, v = PLANE.gens()
    >>> conjugate_points(v**2 - u, flint.fmpq(2)), conjugate_points(v**2 - u, flint.fmpq(4))
    (True, False)
    """
    if curve.degrees()[1] == 0:
        return True
    column = column_over_field(curve, flint.fmpz_poly([-value.p, value.q]))
    _, factors = flint.fmpq_poly([c[0] for c in column]).factor()
    return len(factors) == 1 and factors[0][1] == 1


def points_on_line(curve: flint.fmpz_mpoly, value: flint.fmpq) -> list[tuple[flint.acb, flint.acb]]:
    """The points (u, v) of ``curve`` on the line u = ``value`` (on v = ``value`` for a
    vertical line, a curve free of v), isolated at the current precision (flint's
    isolation of an integer polynomial's roots, its square-free part's: real roots exactly
    real)."""
    if curve.degrees()[1] > 0:  # a column over Q: flint isolates its real roots as exactly real
        column = column_over_field(curve, flint.fmpz_poly([-value.p, value.q]))
        if len(column) <= 1:
            return []
        line = flint.fmpq_poly([coefficient[0] for coefficient in column])
        return [(flint.acb(value), root) for root, _ in line.complex_roots()]
    terms = coefficients_in_v(curve)[0]  # a vertical line: a polynomial in u only
    line = flint.fmpz_poly([terms.get(k, 0) for k in range(max(terms) + 1)])
    return [(root, flint.acb(value)) for root, _ in line.complex_roots()]


def shared_curves(curves: Sequence[flint.fmpz_mpoly], scene: Scene, plan: Plan) -> list[flint.fmpz_mpoly]:
    """The irreducible curves that G_1 and G_2 share (their gcd's factors). Along such a
    curve the two closure conditions hold together, on some branch, at every point: a
    continuum of solutions, which no characteristic polynomial lists (issue 25's 9/N18
    instance drawn with four joints at one point: G_1 and G_2 share the line s2,5 = 2, and
    the fibers above u = 2 had infinitely many common points). Raises
    :class:`~baranov.solvers.modes.MovableLinkageError` where a real point of one of them
    is a real configuration (:func:`moving_point`): the linkage moves."""
    shared = [factor for factor, _ in plane_factors(curves[0].gcd(curves[1]))
              if factor.degrees()[0] + factor.degrees()[1] > 0]
    for curve in shared:
        point = moving_point(curve, scene, plan)
        if point is not None:
            names = [parameter_name(pair) for pair in plan.parameters]
            raise MovableLinkageError(
                f"the linkage moves with these dimensions: both closure conditions hold along the curve {curve} = 0 "
                f"(u = {names[0]}, v = {names[1]}), through the real configuration at "
                f"{names[0]} ≈ {point[0]:.6g}, {names[1]} ≈ {point[1]:.6g}: a continuum rather than isolated "
                "assembly modes")
    return shared


def moving_point(curve: flint.fmpz_mpoly, scene: Scene, plan: Plan, lines: int = 32,
                 bits: int = 256) -> tuple[float, float] | None:
    """A point (u, v) of ``curve`` (each > 0 unless a slider's oriented distance) at which
    some sign branch closes with a real configuration (ball arithmetic at ``bits``),
    searched on ``lines`` lines
    u = (k + 1/2)/lines · upper (v = … for a vertical line) across the parameter's
    range; None if none is found. Cost: lines × 2^m evaluations of the plan."""
    previous = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        axis = 0 if curve.degrees()[1] > 0 else 1
        upper = scene.largest_distance(*plan.parameters[axis]) ** 2
        sliders = {slider.joint for slider in scene.sliders}
        signed = [bool(set(pair) & sliders) for pair in plan.parameters]  # a slider's t: either sign
        for k in range(lines):
            value = flint.fmpq(round((2 * k + 1) * upper * 1000), 2000 * lines)
            for u, v in points_on_line(curve, value) or []:
                if not (u.imag.contains(0) and v.imag.contains(0) and (signed[0] or u.real > 0)
                        and (signed[1] or v.real > 0)):
                    continue
                point = (flint.acb(u.real), flint.acb(v.real))
                if branch_solves(scene, plan, point, (0, 1), bits, real_only=True):
                    return float(u.real.mid()), float(v.real.mid())
        return None
    finally:
        flint.ctx.prec = previous


def _factor_is_genuine(fiber: Fiber, scene: Scene, plan: Plan) -> bool | frozenset:
    """Whether at one root u of the irreducible factor ``fiber.field`` some common point of
    the curves (:mod:`baranov.solvers.exact.fibers`, exact above every root) solves both
    closure conditions on one branch. One root suffices: the modes form a set defined
    over Q, so the Galois conjugates of a mode are modes (on other branches). Where no
    precision decides or the plan is undefined at a common point, the joint pairs found
    coincident are returned instead (as :func:`~baranov.solvers.exact.characteristic._is_genuine`
    does for coupling degree 1)."""
    if fiber.field.degree() < 1:
        return False

    def points() -> list | None:
        roots = [root for root, _ in complex_roots(fiber.field)]
        if scene.sliders:  # a slider plan's residuals decide at real points only (_some_point_solves)
            roots = sorted(roots, key=lambda root: not root.imag.contains(0))
        return common_points(fiber, roots[0])

    return _some_point_solves(points, scene, plan, (0, 1))


def common_points(fiber: Fiber, u: flint.acb) -> list[tuple[flint.acb, flint.acb]] | None:
    """The common points (u, v) of the two curves above the root of ``fiber.field``
    enclosed by ``u``; None if they cannot be isolated at the current precision."""
    roots = fiber.points(u)
    return None if roots is None else [(u, v) for v in roots]


def characteristic_polynomial_two(scene: Scene, plan: Plan, route: str = "lifted") -> tuple[
        CharacteristicPolynomial, tuple[Fiber, ...]]:
    """The characteristic polynomial of a coupling-2 plan in its first parameter, and for
    each of its irreducible factors the :class:`~baranov.solvers.exact.fibers.Fiber` of the
    genuine curves G_1, G_2 above its roots (for the second parameter).

    ``route="lifted"`` (default): the candidate polynomial — every u at which the curves
    meet on one branch, *including* the u that share a point at infinity or an undefined
    point (``saturated=False``) — is lifted from one prime by Newton's iteration
    (:func:`~baranov.solvers.exact.newton_lifting.candidate_by_newton`), or where that does
    not apply from its images modulo many primes
    (:func:`~baranov.solvers.exact.modular.lifted_characteristic_polynomial`); neither forms
    the resultant over Q. Each irreducible factor is kept if it passes
    :func:`_factor_is_genuine`. ``route="resultant"``: Res_v(G_1, G_2) by primes,
    factored, every factor tested (9/B28 example: 174 s, against about 20 s lifted)."""
    curves = genuine_curves(scene, plan)
    shared = shared_curves(curves, scene, plan)
    if shared:  # no real configuration on them: divided out, the curves meet in points again
        common = math.prod(shared, start=PLANE.constant(1))
        curves = (curves[0] / common, curves[1] / common)
    if route == "lifted":
        candidate = characteristic_by_msolve(scene, plan, curves) or candidate_by_newton(scene, plan, curves)
        if candidate is None:  # the modes are not simple points in shape position modulo p: by primes
            candidate = lifted_characteristic_polynomial(scene, plan, saturated=False)
        _, factors = candidate.factor()
    elif route == "resultant":
        (du1, dv1), (du2, dv2) = curves[0].degrees(), curves[1].degrees()
        _, factors = resultant_by_primes(curves[0], curves[1], du1 * dv2 + dv1 * du2).factor()
    else:
        raise ValueError(f"route {route!r}: 'lifted' or 'resultant'")
    kept, dropped, degenerate, fibers = [], [], [], []
    for factor, _ in factors:
        fiber = common_fiber(curves, factor) if factor.degree() > 0 else None
        verdict = _factor_is_genuine(fiber, scene, plan) if fiber is not None else False
        if verdict is True:
            kept.append((factor, 1))
            fibers.append(fiber)
        else:
            dropped.append((factor, 1))
            if verdict is not False:
                degenerate.append((factor, verdict))
    polynomial = math.prod((factor for factor, _ in kept), start=flint.fmpz_poly([1]))
    if polynomial.degree() > 0 and polynomial.coeffs()[-1] < 0:
        polynomial = -polynomial
    return (CharacteristicPolynomial(parameter_name(plan.parameters[0]), polynomial, tuple(kept), tuple(dropped),
                                     tuple(degenerate), shared_curves=tuple(str(curve) for curve in shared)),
            tuple(fibers))


def genuine_curves(scene: Scene, plan: Plan) -> tuple[flint.fmpz_mpoly, flint.fmpz_mpoly]:
    """G_1, G_2: the product of the distinct irreducible curves of each condition's norm,
    and of the contents divided out on the way (:func:`~baranov.solvers.exact.characteristic.eliminate_radicals`),
    that solve the condition on some branch (:func:`_curve_is_genuine`)."""
    tower = radical_tower(scene, plan)
    known = denominator_curves(tower)
    curves = []
    for index, condition in enumerate(tower.conditions):
        norm, contents = eliminate_radicals(condition, tower)
        genuine, seen = PLANE.constant(1), set()
        for part in [norm, *(content for content, _ in contents)]:  # a content's curve can hold modes too
            for factor, _ in plane_factors(plane_polynomial(part), known):
                if factor.degrees()[0] + factor.degrees()[1] > 0 and str(factor) not in seen \
                        and _curve_is_genuine(factor, scene, plan, index):
                    seen.add(str(factor))
                    genuine *= factor
        curves.append(genuine)
    return curves[0], curves[1]


def denominator_curves(tower: RadicalTower) -> list[flint.fmpz_mpoly]:
    """The distinct irreducible curves of the norms of ``tower``'s denominators, over Q.
    High powers of them divide the conditions' norms (9/B25–B28: the whole extraneous part), so
    :func:`~baranov.solvers.exact.plane_factoring.plane_factors` divides them out first."""
    curves: list[flint.fmpz_mpoly] = []
    for part in denominator_parts(tower):
        for factor, _ in factors_over_q(plane_polynomial(part)):
            if not factor.is_constant() and factor not in curves:
                curves.append(factor)
    return curves
