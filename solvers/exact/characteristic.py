"""Characteristic polynomials in exact rational arithmetic (python-flint).

A plan locates every joint by bilaterations (thesis §2.3). With the reference at
M_a = 0, M_b = 1 (complex numbers, thesis §2.4), step k sets

    M_k = M_i + Z_{i,j,k} (M_j - M_i),
    Z_{i,j,k} = (s_{i,j} + s_{i,k} - s_{j,k} + i σ √Δ_k) / (2 s_{i,j}),
    Δ_k = (s_{i,j} + s_{i,k} + s_{j,k})² - 2 (s_{i,j}² + s_{i,k}² + s_{j,k}²) = 16 A²_{i,j,k}

(thesis eq. 2.7), where a distance is known, a parameter, or computed as
|M_v - M_u|² s_{a,b}. Every quantity is therefore a rational function of the parameters and
of one radical r_k = √(numerator of Δ_k) per free-sign step: a tower of quadratic
extensions, nested because Δ_k may involve earlier radicals. A link step's triangle has
three known sides, so its √Δ is a constant; for scenes built from rational coordinates it is
rational, and the exact method requires that.

Each closure condition s_{u,v}(computed) = s_{u,v}(known) becomes, after clearing
denominators, a polynomial F in the parameters and the radicals. Its *norm* — the product of
F over all 2^m sign choices of the radicals, the outermost first — is free of radicals and
vanishes on the solutions of every branch at once; it is what the thesis obtains by
"isolating one radical at a time and squaring" (§3.2.1, §3.3.2.2, §3.6.2). Here each norm
step is a resultant: Res_{r}(F, r² - Δ) = F(√Δ) F(-√Δ).

The norm carries extraneous factors: clearing denominators multiplies by powers of the
parameter and of computed distances (thesis eqs. 3.6, 3.20, 3.34, 3.92). Every irreducible
factor is tested at one of its (complex) roots, in high precision: it is kept when some sign
branch satisfies the original radical equation there with every denominator non-zero. (The
test needs one root only: the solution set is defined over Q, so an irreducible factor is
either all solutions or none.) The product of the kept factors, with multiplicity, is the
characteristic polynomial; its degree is the number of assembly modes over C for generic
dimensions.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from itertools import combinations

import flint

from baranov.closure.bilateration import dehomogenised, place_joints, squared_distance, triangle_radicand
from baranov.closure.evaluate import distinct_branches
from baranov.closure.homogeneous import FieldComplex, Homogeneous
from baranov.closure.sliders import SliderPlacement, takes_root
from baranov.planner import Plan, SliderPlanError, parameter_name, slider_plan
from baranov.scene import Scene, rational_sqrt
from baranov.scene.sliders import axis_unit, axis_units

from ..coincidence import slider_plan_undefined, solvable_plan
from ..modes import SolverError
from ..placement import slider_geometry
from .roots import complex_roots

#: Precisions (bits) of the genuineness test of a factor, tried in turn.
TEST_BITS = (256, 1024, 4096)


class ExactMethodError(SolverError):
    """The exact method cannot treat this scene (the message says why)."""


@dataclass(frozen=True)
class RadicalTower:
    """A plan's closure conditions as polynomials over a tower of quadratic extensions.

    Every polynomial is kept in *normal form*: of degree at most 1 in each radical, since
    r_n² is replaced by its radicand Δ_n (which involves r_1, …, r_{n-1} only). The
    relations r_n² - Δ_n have pairwise coprime leading monomials r_n² in the lex order
    r_m > … > r_1 > t_1 > … > t_c, so they are a Gröbner basis and the normal form is
    unique. Without it, products of points raise the radicals' degrees and the norm grows
    by orders of magnitude (11-link Watt–Baranov: 169 129 terms at the largest norm step,
    17 s; in normal form 256 terms, 0.12 s). Products are formed in normal form directly
    (:func:`_multiply`); reducing unreduced products instead took 37 s of a random
    11-link instance's 38 s, against 1.1 s.

    Attributes
    ----------
    context
        the flint polynomial ring Q[r_m, …, r_1, t_1, …, t_c] (lex order).
    parameters
        the plan's parameter pairs, one per t_n.
    radicands
        Δ-numerator of r_n, a polynomial in the t's and r_1, …, r_{n-1}.
    conditions
        numerator of s_{u,v}(computed) · den(known) - known · den, one per
        closure pair.
    denominators
        den, the denominator of s_{u,v}(computed), one per closure pair:
        where it vanishes the condition holds without the distance being the known
        one (the extraneous roots; thesis eqs. 3.6, 3.20, 3.34, 3.92).
    """

    context: flint.fmpq_mpoly_ctx
    parameters: tuple[tuple[str, str], ...]
    radicands: tuple[flint.fmpq_mpoly, ...]
    conditions: tuple[flint.fmpq_mpoly, ...]
    denominators: tuple[flint.fmpq_mpoly, ...] = ()

    @property
    def variables(self) -> tuple[str, ...]:
        return self.context.names()

    def radical(self, n: int) -> flint.fmpq_mpoly:
        """The generator r_{n+1} (``n`` counts from 0, innermost first)."""
        return self.context.gen(len(self.radicands) - 1 - n)

    def multiply(self, first: flint.fmpq_mpoly, second: flint.fmpq_mpoly, below: int | None = None) -> flint.fmpq_mpoly:
        """The product of two normal forms free of r_n for n > ``below`` (default: all
        radicals), in normal form."""
        count = len(self.radicands) if below is None else below
        return _multiply(first, second, [self.radical(n) for n in range(count)], self.radicands, count)

    def normal_form(self, polynomial: flint.fmpq_mpoly) -> flint.fmpq_mpoly:
        """``polynomial`` reduced modulo r_n² - Δ_n, outermost radical first: Δ_n only
        involves inner radicals, so reducing an inner one never raises an outer one's
        degree again. Multivariate division by a relation whose leading monomial is r_n²
        leaves a remainder of degree at most 1 in r_n."""
        for n in range(len(self.radicands) - 1, -1, -1):
            _, polynomial = divmod(polynomial, self.radical(n) ** 2 - self.radicands[n])
        return polynomial


def _multiply(first: flint.fmpq_mpoly, second: flint.fmpq_mpoly, radicals, radicands,
              level: int | None = None) -> flint.fmpq_mpoly:
    """The product of two normal forms, in normal form, without forming the unreduced
    product (whose 3^m radical monomials made reduction the bottleneck): split on the
    outermost radical r = r_level, (a + b r)(c + d r) = (ac + Δ bd) + ((a + b)(c + d) - ac - bd) r,
    each product recursively over the inner radicals (Karatsuba: 3 products per level,
    plus one by Δ)."""
    if level is None:
        level = len(radicands)
    if level == 0 or first.is_constant() or second.is_constant():
        return first * second
    radical = radicals[level - 1]
    odd_first, even_first = divmod(first, radical)
    odd_second, even_second = divmod(second, radical)
    if odd_first.is_zero() and odd_second.is_zero():
        return _multiply(first, second, radicals, radicands, level - 1)
    if odd_first.is_zero() or odd_second.is_zero():
        scalar, (odd, even) = (first, (odd_second, even_second)) if odd_first.is_zero() else (second, (odd_first, even_first))
        return (_multiply(scalar, even, radicals, radicands, level - 1)
                + _multiply(scalar, odd, radicals, radicands, level - 1) * radical)
    low = _multiply(even_first, even_second, radicals, radicands, level - 1)
    high = _multiply(odd_first, odd_second, radicals, radicands, level - 1)
    cross = _multiply(even_first + odd_first, even_second + odd_second, radicals, radicands, level - 1) - low - high
    return low + _multiply(radicands[level - 1], high, radicals, radicands, level - 1) + cross * radical


@dataclass(frozen=True)
class CharacteristicPolynomial:
    """The characteristic polynomial of a scene in one parameter.

    Attributes
    ----------
    variable
        the parameter, e.g. ``"s1,6"``.
    polynomial
        primitive integer polynomial, positive leading coefficient.
    factors
        its irreducible factors with multiplicities.
    extraneous
        the irreducible factors of the norm that were dropped.
    degenerate
        those dropped factors at whose roots the plan is undefined (a base
        distance vanishes: joints coincide), with the joint pairs found coincident;
        the plan cannot tell whether they are assembly modes (thesis §5.1.3.2).
    vanishing
        the norm of the closure condition is identically 0: on some branch
        the condition holds for every value of the parameter, the linkage moves
        (``polynomial`` is then only the product of the contents divided out).
    shared_curves
        coupling degree 2: the curves in (u, v) along which both closure
        conditions hold, on which no real configuration was found
        (:func:`~baranov.solvers.exact.coupling_two.shared_curves`); divided out
        before the common points are computed.
    """

    variable: str
    polynomial: flint.fmpz_poly
    factors: tuple[tuple[flint.fmpz_poly, int], ...]
    extraneous: tuple[tuple[flint.fmpz_poly, int], ...]
    degenerate: tuple[tuple[flint.fmpz_poly, frozenset[frozenset[str]]], ...] = ()
    vanishing: bool = False
    shared_curves: tuple[str, ...] = ()

    @property
    def degree(self) -> int:
        return self.polynomial.degree()

    def real_roots(self) -> list[flint.arb]:
        """Certified enclosures of the real roots, increasing, each repeated by its
        multiplicity (flint's complex root isolation returns real roots as real balls)."""
        return [root for root, multiplicity in self.distinct_real_roots() for _ in range(multiplicity)]

    def distinct_real_roots(self) -> list[tuple[flint.arb, int]]:
        """The distinct real roots, increasing, each as (certified enclosure,
        multiplicity): a root of multiplicity m > 1 is where m modes merge (a singular
        configuration, thesis §3.3.3) or a double root of two branches' conditions. The
        factors are distinct and irreducible, so no two share a root."""
        roots = [(root.real, multiplicity) for factor, multiplicity in self.factors
                 for root, _ in complex_roots(factor) if root.imag == 0]
        return sorted(roots, key=lambda item: float(item[0].mid()))

    def to_dict(self) -> dict:
        """JSON form: integer coefficients (highest degree first, as exact strings) and
        the real-root enclosures as midpoint and radius strings."""
        return {
            "variable": self.variable,
            "degree": self.degree,
            "coefficients": [str(int(c)) for c in self.polynomial.coeffs()][::-1],
            "real_root_enclosures": [{"midpoint": root.mid().str(20, radius=False),
                                      "radius": root.rad().str(3, radius=False)} for root in self.real_roots()],
        }

    def monic_coefficients(self) -> list[Fraction]:
        """Coefficients of the monic form, highest degree first."""
        coefficients = [int(c) for c in self.polynomial.coeffs()][::-1]
        return [Fraction(c, coefficients[0]) for c in coefficients]


def radical_tower(scene: Scene, plan: Plan, prime: int | None = None) -> RadicalTower:
    """The closure conditions of ``plan`` for the dimensions of ``scene``, exactly, or
    their images modulo ``prime`` (a word-size prime; polynomials then in flint
    ``nmod_mpoly``, see :mod:`baranov.solvers.exact.modular`).

    Every point is kept as (X + iY) / d with X, Y, d polynomials in normal form (see
    :class:`RadicalTower`), common factors cancelled (flint gcd) after each step. Raises
    :class:`ExactMethodError` if a dimension is inexact or a link triangle has an
    irrational area, and ``ZeroDivisionError`` if ``prime`` divides a denominator of the
    dimensions.
    """
    if not scene.exact:
        raise ExactMethodError("scene: the exact method needs integer or rational dimensions (a float was given)")
    slider_names = [slider.joint for slider in scene.sliders]
    free = [step for step in plan.steps if takes_root(step, slider_names)]
    names = tuple(f"r{n}" for n in range(len(free), 0, -1)) + tuple(f"t{n + 1}" for n in range(plan.number_of_parameters))
    if prime is None:
        context = flint.fmpq_mpoly_ctx.get(names, "lex")
    else:
        context = flint.nmod_mpoly_ctx.get(names, modulus=prime, ordering="lex")
    generators = context.gens()
    radicals = generators[:len(free)][::-1]  # r_1, r_2, …
    radicands = []
    parameter_of = {frozenset(pair): generators[len(free) + n] for n, pair in enumerate(plan.parameters)}
    constant, known = dimension_inputs(scene, context, prime, parameter_of)

    def signed_root(index, step, sides, radicand):
        if not step.free_sign:  # a link's three joints: known sides, a rational area
            return constant(link_area_root(scene, step.triangle))
        radicands.append(radicand)
        return radicals[len(radicands) - 1]

    def polynomial(value):
        return constant(value) if isinstance(value, int) else value

    def reduced_point(point):
        x, y, d = (polynomial(value) for value in point)
        common = x.gcd(y).gcd(d)
        return x / common, y / common, d / common

    def reduced_distance(pair):
        numerator, denominator = (polynomial(value) for value in pair)
        common = numerator.gcd(denominator)
        return numerator / common, denominator / common

    def multiply(first, second):  # the kernel's small ints (±1 from the reference points) become constants
        return _multiply(polynomial(first), polynomial(second), radicals, radicands)

    sliders, hooks = None, {}
    if slider_names:
        ring = {"multiply": multiply, "constant": lambda value: polynomial(value) if isinstance(value, int) else
                constant(value), "reduce": lambda number: Homogeneous(*reduced_point((number.x, number.y, number.w)),
                                                                      multiply, number.constant, number.reduce)}

        def along_root(index, step, squared, radicand):  # σ√(n/d) = r/d with r² = n d
            radicands.append(multiply(radicand.x, radicand.w))
            return Homogeneous(radicals[len(radicands) - 1], constant(0), radicand.w, **ring)

        sliders = _slider_placement(scene, plan, ring, parameter_of, along_root)
        hooks = dict(zip(("slider_step", "slider_frame"), sliders.kernel_hooks(
            plan.reference, lambda point: Homogeneous(*(polynomial(c) for c in point), **ring),
            lambda number: (number.x, number.y, number.w),
            reference_of=lambda pair: Homogeneous(polynomial(pair[0]), constant(0), polynomial(pair[1]), **ring),
            distance_of=lambda pair: Homogeneous(polynomial(pair[0]), constant(0), polynomial(pair[1]), **ring)),
            strict=True))
    points, reference, distance = place_joints(plan, known, signed_root, multiply=multiply, reduced_point=reduced_point,
                                               reduced_distance=reduced_distance, **hooks)
    conditions, denominators = [], []
    for u, v in plan.closure_pairs:
        if sliders is not None and {u, v} & set(slider_names):
            value = _slider_closure(sliders, u, v, points, reference, ring)
            numerator, denominator = (value.y if {u, v} <= set(slider_names) else value.x), value.w
        else:
            numerator, denominator = distance(u, v, computed=True)
            target = Fraction(scene.known[frozenset((u, v))])
            numerator, denominator = numerator * target.denominator - denominator * target.numerator, denominator
        conditions.append(numerator)
        denominators.append(denominator)
    return RadicalTower(context, plan.parameters, tuple(radicands), tuple(conditions), tuple(denominators))


def dimension_inputs(scene: Scene, context, prime: int | None, parameter_of: dict) -> tuple[Callable, Callable]:
    """``constant(value)``: a dimension as a constant of the polynomial ring ``context``
    (over Q, or modulo ``prime``: ZeroDivisionError where the prime divides its
    denominator); ``known(u, v)``: what :func:`~baranov.closure.bilateration.place_joints`
    asks, (s_{u,v}, 1) for a link's pair, (its generator, 1) for a parameter of
    ``parameter_of`` (pair → generator), None for a pair the plan computes."""

    def constant(value):
        value = Fraction(value)
        if prime is not None:
            if value.denominator % prime == 0:
                raise ZeroDivisionError(f"the prime {prime} divides the denominator of the dimension {value}")
            return context.constant(value.numerator * pow(value.denominator, -1, prime) % prime)
        return context.constant(flint.fmpq(value.numerator, value.denominator))

    def known(u: str, v: str):
        pair = frozenset((u, v))
        if pair in scene.known:
            return constant(scene.known[pair]), 1
        if pair in parameter_of:
            return parameter_of[pair], 1
        return None

    return constant, known


def _ring_number(ring: dict) -> type[Homogeneous]:
    """The number class of ``ring``: :class:`FieldComplex` for balls, else :class:`Homogeneous`."""
    return ring.get("number", Homogeneous)


def _arithmetic(ring: dict) -> dict:
    """``ring``'s keyword arguments of its number class."""
    return {key: value for key, value in ring.items() if key != "number"}


def _slider_placement(scene: Scene, plan: Plan, ring: dict, parameters: dict, along_root,
                      geometry: dict | None = None) -> SliderPlacement:
    """The slider constructions (:mod:`baranov.closure.sliders`) over ``ring`` (a
    :class:`Homogeneous` arithmetic), with the scene's axis frames exact (``geometry``, or
    :func:`_exact_slider_geometry`)."""
    number, arithmetic = _ring_number(ring), _arithmetic(ring)

    def parameter(u: str, v: str):
        value = parameters.get(frozenset((u, v)))
        return None if value is None else number.of(value, **arithmetic)

    if geometry is None:
        geometry = _exact_slider_geometry(scene, plan, ring)
    return SliderPlacement(geometry, parameter, along_root)


def _exact_slider_geometry(scene: Scene, plan: Plan, ring: dict) -> dict:
    """:func:`~baranov.solvers.placement.slider_geometry` over ``ring``, exact; raises
    :class:`ExactMethodError` where a place or turn is irrational."""
    kind, arithmetic = _ring_number(ring), _arithmetic(ring)

    def number(pair):
        if not all(isinstance(c, Fraction) for c in pair):
            raise ExactMethodError("slider axes: a joint's place in an axis frame, or the turn between two axes, is "
                                   "irrational; the exact method needs them rational (docs/sliders.md)")
        return kind.of(pair, **arithmetic)

    for slider in scene.sliders:
        units = axis_units(slider, [scene.link_of(axis.link) for axis in slider.axes])
        if len(set(units.values())) > 1 and None not in units.values():
            shown = ", ".join(f"{'rational' if q == 1 else f'√{q} times rational'} on link {link}"
                              for link, q in units.items())
            raise ExactMethodError(f"slider {slider.joint}: its axis frames are {shown}; the exact method needs "
                                   "them rational in one unit √q (docs/sliders.md); the numeric method takes the scene")

    geometry = slider_geometry(scene, number, units=True)
    for pair in plan.parameters:
        for slider in set(pair) & geometry.keys():
            if geometry[slider].unit != 1:  # t would be √q times a rational variable
                raise ExactMethodError(f"slider {slider}: the parameter t is its axis's oriented distance, and its "
                                       f"axis frames are rational only in units of √{geometry[slider].unit}; the "
                                       "exact method needs a plan whose parameters avoid it (docs/sliders.md)")
    return geometry


def _slider_closure(sliders: SliderPlacement, u: str, v: str, points: dict, reference, ring: dict) -> Homogeneous:
    """The closure s_{i,v} of a slider P_i as δ → ∞
    (:meth:`~baranov.closure.sliders.SliderPlacement.closure`) over the tower: a real
    :class:`Homogeneous` (a height), or for two sliders of one link the complex turn
    mismatch r − 1, whose imaginary part is the condition and which is 0 as a whole only
    where the axis keeps its sense."""
    slider, joint = (u, v) if u in sliders.geometry else (v, u)
    number, arithmetic = _ring_number(ring), _arithmetic(ring)
    at = {joint: number(*points[joint], **arithmetic)} if joint in points else {}
    scale = number(reference[0], ring["constant"](0), reference[1], **arithmetic)
    return sliders.closure(slider, joint, at, scale)


def link_area_root(scene: Scene, triangle: tuple[str, str, str]) -> Fraction:
    """√Δ = 4·(oriented area) of three joints of one link, from its known squared
    distances (thesis eq. 2.7), exactly; raises :class:`ExactMethodError` unless it is
    rational.

    >>> from baranov.scene import load_scene
    >>> from pathlib import Path
    >>> scene = load_scene(Path(__file__).resolve().parents[2] / "examples" / "7-B1.json")
    >>> link = next(link for link in scene.links if len(link.joints) == 3)
    >>> abs(link_area_root(scene, tuple(link.joints))) > 0
    True
    """
    a, b, c = (Fraction(scene.known[frozenset(pair)]) for pair in combinations(triangle, 2))
    radicand = triangle_radicand(a, b, c)
    root = rational_sqrt(radicand)
    if root is None:
        raise ExactMethodError(
            f"link with joints {', '.join(triangle)}: 16·area² = {radicand} is not the square of a "
            "rational; the exact method needs rational link areas (e.g. rational joint coordinates)")
    return root * scene.orientation(triangle)


def eliminate_radicals(polynomial: flint.fmpq_mpoly,
                       tower: RadicalTower) -> tuple[flint.fmpq_mpoly, list[tuple[flint.fmpq_mpoly, int]]]:
    """The norm of ``polynomial`` over all sign choices of the radicals, outermost first
    (thesis §3.2.1, "twice squaring"): a polynomial in the parameters only.

    In normal form F = A + B r_n with A, B free of r_n, and the norm step is
    Res_{r_n}(F, r_n² - Δ_n) = F(√Δ_n) F(-√Δ_n) = A² - Δ_n B², reduced again modulo the
    inner radicals; n = m, …, 1. Before each step the *content* — the gcd, a polynomial in
    the parameters, of the coefficients of the radical monomials — is divided out: it
    comes from clearing denominators (thesis eqs. 3.6, 3.20, 3.34, 3.92) and would be
    squared by every later step (on a random 11-link instance, a sextic to the power 492
    and t^584 beside a characteristic factor of degree 126). Returns the norm without
    them and the removed contents with the multiplicity (a power of 2) they would have
    had in the full norm, so that the caller can test their roots too.
    Cost: m steps, each a few products of polynomials of at most 2^(n-1) radical
    monomials times the parameter degrees (thesis §3.6.2: the degree doubles per step).
    """
    polynomial = tower.normal_form(polynomial)
    removed = []
    for n in range(len(tower.radicands) - 1, -1, -1):
        content = _radical_content(polynomial, len(tower.radicands))
        if not content.is_constant():
            polynomial = polynomial / content
            removed.append((content, 2 ** (n + 1)))
        polynomial = _norm_step(tower, polynomial, n)
    return polynomial, removed


def _norm_step(tower: RadicalTower, polynomial: flint.fmpq_mpoly, n: int) -> flint.fmpq_mpoly:
    """Res_{r_n}(F, r_n² - Δ_n) = A² - Δ_n B² for F = A + B r_n in normal form, free of the
    radicals beyond r_n: F(√Δ_n) F(-√Δ_n), in normal form."""
    odd, even = divmod(polynomial, tower.radical(n))
    return tower.multiply(even, even, n) - tower.multiply(tower.radicands[n], tower.multiply(odd, odd, n), n)


def radicand_norm(tower: RadicalTower, n: int) -> flint.fmpz_poly:
    """The norm of the radicand Δ_{n+1} (``n`` counts from 0, innermost first) over the
    radicals it involves, r_n, …, r_1: a primitive integer polynomial in the one parameter
    (coupling degree 1) whose real roots hold every value at which triangle n + 1 of the
    plan turns flat on some sign branch (a domain edge, thesis §3.3.1). Cost: n norm
    steps (:func:`eliminate_radicals`)."""
    polynomial = tower.radicands[n]
    for inner in range(n - 1, -1, -1):
        polynomial = _norm_step(tower, polynomial, inner)
    return _univariate(polynomial)


def _radical_content(polynomial: flint.fmpq_mpoly, radicals: int) -> flint.fmpq_mpoly:
    """The gcd of the coefficients of ``polynomial`` (in normal form: of degree at most 1
    in each radical) as a polynomial in the first ``radicals`` generators (a polynomial in
    the remaining ones, monic). The coefficients are split off one radical at a time by
    flint's division by the generator (grouping the terms in Python took 19 ms a call on
    a nine-link instance, a tenth of its genuine curves)."""
    coefficients = [polynomial]
    for generator in polynomial.context().gens()[:radicals]:
        coefficients = [part for coefficient in coefficients for part in divmod(coefficient, generator)
                        if not part.is_zero()]
    content = None
    for coefficient in sorted(coefficients, key=len):
        content = coefficient if content is None else content.gcd(coefficient)
        if content.is_constant():
            break
    return content if content is not None else polynomial.context().constant(1)


def _univariate(polynomial: flint.fmpq_mpoly) -> flint.fmpz_poly:
    """A polynomial in the last generator only, as a primitive integer polynomial."""
    coefficients = [flint.fmpq(0)] * (polynomial.degrees()[-1] + 1)
    for exponents, coefficient in zip(polynomial.monoms(), polynomial.coeffs(), strict=True):
        coefficients[exponents[-1]] = coefficient
    return flint.fmpq_poly(coefficients).numer()


def exact_plan(scene: Scene) -> Plan:
    """The plan the exact method runs: :func:`~baranov.solvers.coincidence.solvable_plan`,
    or, where one of its parameters is the oriented distance t to a slider's axis whose
    frames are rational only in units of √q (t would be √q times a rational variable,
    which the radical tower cannot hold: docs/sliders.md), the best slider plan whose
    parameters avoid such sliders, if it is defined for the scene (a family-VIII robot of
    thesis §5.2.2, every platform joint a slider: its best plan's t1,5 is in units of √13,
    the plan in t1,6 is rational)."""
    plan = solvable_plan(scene)
    sliders = [slider.joint for slider in scene.sliders]
    irrational = {slider.joint for slider in scene.sliders
                  if axis_unit(slider, [scene.link_of(axis.link) for axis in slider.axes]) not in (None, 1)}
    if not irrational & {joint for pair in plan.parameters for joint in pair}:
        return plan
    joints = sorted(joint.name for joint in scene.chain.joints)
    allowed = [pair for pair in combinations(joints, 2) if not irrational & set(pair)]
    try:
        other = slider_plan(scene.chain, sliders, parameters=allowed)
    except SliderPlanError:
        return plan  # refused with the slider named (characteristic.py)
    return other if slider_plan_undefined(scene, other) is None else plan


def characteristic_polynomial(scene: Scene, plan: Plan | None = None) -> CharacteristicPolynomial:
    """The characteristic polynomial of ``scene`` in the parameter of ``plan`` (default:
    :func:`exact_plan`), coupling degree 1.

    >>> from baranov.scene import load_scene
    >>> from pathlib import Path
    >>> scene = load_scene(Path(__file__).resolve().parents[2] / "examples" / "7-B1.json")
    >>> characteristic_polynomial(scene).degree   # thesis §3.3.1: 14 assembly modes
    14
    """
    plan = plan or exact_plan(scene)
    if plan.number_of_parameters != 1:
        raise ExactMethodError(
            f"coupling degree {plan.number_of_parameters}: the exact method derives one-parameter polynomials so far")
    tower = radical_tower(scene, plan)
    norm, contents = eliminate_radicals(tower.conditions[0], tower)
    kept, dropped = [], []
    _, factors = _univariate(norm).factor()
    for content, power in contents:
        factors += [(factor, multiplicity * power) for factor, multiplicity in _univariate(content).factor()[1]]
    merged: dict[tuple[int, ...], int] = {}
    for factor, multiplicity in factors:
        key = tuple(int(c) for c in factor.coeffs())
        merged[key] = merged.get(key, 0) + multiplicity
    factors = [(flint.fmpz_poly(list(key)), multiplicity) for key, multiplicity in merged.items()]
    degenerate = []
    for factor, multiplicity in factors:
        verdict = _is_genuine(factor, scene, plan)
        (kept if verdict is True else dropped).append((factor, multiplicity))
        if verdict not in (True, False):
            degenerate.append((factor, verdict))
    polynomial = flint.fmpz_poly([1])
    for factor, multiplicity in kept:
        polynomial *= factor**multiplicity
    if polynomial.degree() > 0 and polynomial.coeffs()[-1] < 0:
        polynomial = -polynomial
    return CharacteristicPolynomial(parameter_name(plan.parameters[0], [slider.joint for slider in scene.sliders]),
                                    polynomial, tuple(kept), tuple(dropped),
                                    tuple(degenerate), vanishing=norm == 0)


def _is_genuine(factor: flint.fmpz_poly, scene: Scene, plan: Plan) -> bool | frozenset[frozenset[str]]:
    """Whether one root of the irreducible ``factor`` solves the closure condition on
    some sign branch with every bilateration defined (base distances and the reference
    distance non-zero). Where no branch confirms it but some could not be evaluated
    because a base distance vanishes there, the plan cannot decide: the joint pairs
    found coincident are returned instead (see :func:`baranov.solvers.exact.backend.solve_exact`).
    The plan is evaluated in complex ball arithmetic (flint acb), x and y coordinates
    separately, since a complex parameter gives complex coordinates.

    A branch confirms the factor when the closure residual's ball contains 0 and is
    narrower than 2^(-bits/8) of the closure distance; it rules itself out when the ball
    excludes 0. Balls widen where a radicand nearly vanishes (a square root of a ball
    around 0) or a division nearly divides by 0, so an undecided branch is evaluated
    again with four times the bits, up to TEST_BITS[-1]."""
    if factor.degree() < 1:
        return False
    previous = flint.ctx.prec
    undecided = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    try:
        for bits in TEST_BITS:
            flint.ctx.prec = bits
            root = complex_roots(factor)[0][0]
            still, coincident = [], set()
            for signs, residuals, _, pair in residuals_on_branches(scene, plan, (root,), undecided):
                if residuals is None:  # a base distance's ball contains 0: try more bits
                    coincident.add(pair)
                    still.append(signs)
                    continue
                verdict = residual_verdict(residuals, flint.arb(2) ** (-bits // 8))
                if verdict:
                    return True
                if verdict is None:
                    still.append(signs)
            if not still:
                return False
            undecided = still
        return frozenset(coincident)  # empty: undecided at every precision (reported, never silently dropped)
    finally:
        flint.ctx.prec = previous


def placed_points(scene: Scene, plan: Plan, parameters: Sequence[flint.acb], signs,
                  real_only: bool = False) -> tuple[
        dict[str, tuple[flint.acb, flint.acb]] | None, flint.acb, frozenset[str] | None]:
    """The plan's points at complex parameter values (one per plan parameter) on one sign
    branch, in complex ball arithmetic at the current precision: (x, y) per joint in the
    reference frame M_a = 0, M_b = 1 (thesis eq. 2.6–2.7, coordinates as complex numbers,
    since a complex parameter gives complex coordinates), and the reference distance
    s_{a,b}. Where a bilateration is
    undefined (its base distance's ball contains 0), None and the base's joint pair.
    ``real_only=True`` (real parameter values, real modes wanted): where a radicand is
    certainly negative the triangle does not exist, and (None, reference, None) is
    returned; without it, a radicand on the negative real axis is a square root taken
    across flint's branch cut, a ball as wide as the root itself at every precision
    (9/N24 of the collinear-joints sweep: undecided at 1024 bits). With sliders, the
    slider placement (its axes) and s_{a,b} under a key of their own, for the closures
    and :func:`with_slider_points`.

    Cost: O(steps) ball operations."""
    (_, *placed), = placed_on_branches(scene, plan, parameters, [tuple(signs)], real_only)
    return tuple(placed)


def placed_on_branches(scene: Scene, plan: Plan, parameters: Sequence[flint.acb],
                       branches: Sequence[tuple[int, ...]], real_only: bool = False) -> Iterator[tuple]:
    """:func:`placed_points` on each sign branch of ``branches`` (a tuple of ±1 per
    free-sign step), as (signs, points, reference, pair), in that order: the steps
    before a branch's first differing sign are placed once for all branches that share
    them, a depth-first walk of the sign tree. On a nine-link slider chain's ten-step
    plan with free signs at steps 2, 4, 6 and 8, the 16 branches take 62 step placements
    instead of 160. A branch's points are its own (later branches do not change them);
    a step undefined on a shared prefix is undefined on every branch below it.

    Cost: O(steps · branches) ball operations at most, O(steps + branches) when the
    free signs come last."""
    values = {frozenset(pair): value for pair, value in zip(plan.parameters, parameters, strict=True)}

    def distance(u: str, v: str):
        pair = frozenset((u, v))
        if pair in scene.known:
            return exact_ball(scene.known[pair]), 1
        return (values[pair], 1) if pair in values else None

    a, b = plan.reference
    signs = list(branches[0]) if branches else []  # the branch being placed: what the roots read
    sliders, hooks = None, {}
    if scene.sliders:  # the slider constructions in balls; the frame may sit on an axis
        sliders, hooks = _ball_sliders(scene, plan, values, signs, real_only)
    on_axis = [joint for joint in plan.reference if sliders is not None and joint in sliders.geometry]
    # a frame on a slider's axis is in its axis units: s_ref = q (closure/sliders.py)
    reference = flint.acb(sliders.geometry[on_axis[0]].unit) if on_axis else distance(a, b)[0]
    if reference.contains(0):
        yield from ((branch, None, reference, frozenset((a, b))) for branch in branches)
        return
    free_steps = [i for i, step in enumerate(plan.steps) if step.free_sign]
    free_index = {index: n for n, index in enumerate(free_steps)}

    def signed_root(index, step, sides, radicand):
        s_ij = sides[0]
        if s_ij.contains(0):
            raise _Undefined(frozenset(step.base))
        if real_only and radicand.real < 0:
            raise _Undefined(None)
        sign = signs[free_index[index]] if step.free_sign else scene.orientation(step.triangle)
        return sign * _square_root(radicand)

    bounds = [0, *free_steps, len(plan.steps)]

    def placed(level: int, state, group: list[tuple[int, ...]]):
        """The branches of ``group`` (sharing their first ``level`` signs) from ``state``
        (None at the start): the points, reference and slider axes after the steps
        before free step ``level``."""
        for sign in dict.fromkeys(branch[level - 1] for branch in group) if level else (None,):
            below = [branch for branch in group if not level or branch[level - 1] == sign]
            signs[:] = below[0]
            if sliders is not None:
                sliders.axes = dict(state[2]) if state else {}
            try:
                points, kernel_reference, _ = place_joints(
                    plan, distance, signed_root, reduced_point=dehomogenised, steps=(bounds[level], bounds[level + 1]),
                    start=(dict(state[0]), state[1]) if state else None, **hooks)
            except _Undefined as undefined:
                yield from ((branch, None, reference, undefined.pair) for branch in below)
                continue
            if level < len(free_steps):
                # the state is copied where a branch goes on from it, not here
                yield from placed(level + 1, (points, kernel_reference, sliders.axes if sliders else {}), below)
            else:
                yield from ((branch, _ball_points(points, sliders, reference), reference, None) for branch in below)

    yield from placed(0, None, list(branches))


def _ball_points(placed: dict, sliders: SliderPlacement | None, reference: flint.acb) -> dict:
    """The kernel's placed points as (x, y) balls, with a copy of the slider placement."""
    points = {joint: (flint.acb(x), flint.acb(y)) for joint, (x, y, _) in placed.items()}
    if sliders is not None:
        points[_SLIDERS] = (sliders.copy(), reference)
    return points


def with_slider_points(points: dict) -> dict[str, tuple[flint.acb, flint.acb]]:
    """The joints' points of :func:`placed_points` with each slider's point on each of its
    links added (``P9'``, ``P9''``: what a configuration shows). Made only for the
    configurations built: the closures need the axes alone, and making these points at
    every placement took 0.50 of 1.10 s of five exact solves of one nine-link slider chain
    (cProfile)."""
    placed = {joint: point for joint, point in points.items() if joint != _SLIDERS}
    if _SLIDERS not in points:
        return placed
    sliders, reference = points[_SLIDERS]
    at = {joint: FieldComplex(x, y, constant=exact_ball) for joint, (x, y) in placed.items()}
    placed.update({name: (point.x / point.w, point.y / point.w)
                   for name, point in sliders.slider_points(at, reference).items()})
    return placed


def real_configuration(points: dict) -> bool:
    """Whether the placement of :func:`placed_points` is real: every coordinate of every
    joint, and every slider axis, an exactly real ball (the square root of a negative
    radicand, or of a ball around 0, leaves an imaginary part). Only there do the slider
    constructions, which conjugate, compute what the closure conditions are over the
    radical tower (:func:`~baranov.solvers.exact.coupling_two.branch_solves`)."""
    def real(value) -> bool:
        if isinstance(value, Homogeneous):
            return real(value.x) and real(value.y) and real(value.w)
        return not isinstance(value, flint.acb) or (value.imag.is_exact() and value.imag == 0)

    for joint, point in points.items():
        if joint == _SLIDERS:
            axes = point[0].axes.values()
            if not all(real(part) for axis in axes for part in (axis.direction, axis.anchor, axis.height)):
                return False
        elif not (real(point[0]) and real(point[1])):
            return False
    return True


def exact_ball(value) -> flint.acb:
    """A rational (an int or a Fraction) as a complex ball at the current precision, exact
    where it is dyadic. Cached per precision: the ball placements of one solve read the
    same dimensions thousands of times, and building them anew (two Fractions and an fmpq
    per dimension and placement) took 7.5 of the 16 s of the modes of the 11-link
    Watt–Baranov example (issue 24, cProfile).

    >>> exact_ball(Fraction(9, 4))
    2.25000000000000
    """
    if type(value) is int and -256 <= value <= 256:  # the constants 0, 1, 2 of the constructions: no Fraction
        key = (value, flint.ctx.prec)
        ball = _INTEGER_BALLS.get(key)
        if ball is None:
            ball = _INTEGER_BALLS[key] = _rational_ball(Fraction(value), flint.ctx.prec)
        return ball
    value = value if isinstance(value, Fraction) else Fraction(value)
    return _rational_ball(value, flint.ctx.prec)


#: exact_ball of small integers, by (value, precision): bounded by 513 values per precision.
_INTEGER_BALLS: dict[tuple[int, int], flint.acb] = {}


@lru_cache(maxsize=8192)
def _rational_ball(value: Fraction, bits: int) -> flint.acb:
    return flint.acb(flint.fmpq(value.numerator, value.denominator))  # rounded at the current precision (= bits)


#: Ball arithmetic for the slider constructions: :class:`FieldComplex` over flint's complex
#: balls (``number``: the class the shared helpers make numbers of, :func:`_ring_number`).
_BALLS = {"constant": exact_ball, "number": FieldComplex}
#: The key under which :func:`placed_points` leaves its slider placement for the closures.
_SLIDERS = "<sliders>"


#: The last few ball slider geometries, by (scene, plan, precision): the ball placements
#: of one solve (the curve and factor tests) make the same geometry thousands of times
#: (a nine-link chain: 8930 times, 28 of 119 s, cProfile). Each entry keeps its scene and
#: plan, so their ids are not reused while it is here.
_BALL_GEOMETRIES: dict = {}


def _ball_slider_geometry(scene: Scene, plan: Plan) -> dict:
    """:func:`_exact_slider_geometry` in balls at the current precision, cached."""
    key = (id(scene), id(plan), flint.ctx.prec)
    if key not in _BALL_GEOMETRIES:
        if len(_BALL_GEOMETRIES) >= 16:
            del _BALL_GEOMETRIES[next(iter(_BALL_GEOMETRIES))]
        _BALL_GEOMETRIES[key] = (scene, plan, _exact_slider_geometry(scene, plan, _BALLS))
    return _BALL_GEOMETRIES[key][2]


def _ball_sliders(scene: Scene, plan: Plan, values: dict, signs, real_only: bool):
    """The slider placement of :func:`placed_points` and its kernel hooks, in balls."""
    free_index = {index: n for n, index in enumerate(i for i, step in enumerate(plan.steps) if step.free_sign)}

    def along_root(index, step, squared, radicand):
        value = radicand.x / radicand.w
        if real_only and value.real < 0:
            raise _Undefined(None)
        return FieldComplex(signs[free_index[index]] * _square_root(value), flint.acb(0), constant=exact_ball)

    sliders = _slider_placement(scene, plan, _BALLS, values, along_root, _ball_slider_geometry(scene, plan))
    slider_step, slider_frame = sliders.kernel_hooks(
        plan.reference, lambda point: FieldComplex(*(flint.acb(c) for c in point), constant=exact_ball),
        lambda number: (number.x / number.w, number.y / number.w, 1),
        reference_of=lambda pair: FieldComplex(flint.acb(pair[0]), flint.acb(0), flint.acb(pair[1]), constant=exact_ball),
        distance_of=lambda pair: FieldComplex(flint.acb(pair[0]), flint.acb(0), flint.acb(pair[1]), constant=exact_ball))

    def defined_step(index, step, points, reference, distance):
        # an axis through two joints divides by their distance, two axes crossed by the
        # sine of their angle: undefined where the joints meet or the axes are parallel, as
        # a bilateration is where its base's joints meet (the pair is then examined:
        # coincidence.py, parallel_axis_pairs)
        on_axes = set(step.base) & sliders.geometry.keys()
        if step.joint in sliders.geometry and not on_axes:
            numerator, denominator = distance(*step.base)
            if (flint.acb(numerator) / flint.acb(denominator)).contains(0):
                raise _Undefined(frozenset(step.base))
        if len(on_axes) == 2:
            first, second = (sliders.axes[joint].direction for joint in step.base)
            sine = (second.conjugate() * first).imag
            if (sine.x / sine.w).contains(0):
                raise _Undefined(frozenset(step.base))
        return slider_step(index, step, points, reference, distance)

    return sliders, {"slider_step": defined_step, "slider_frame": slider_frame}


class _Undefined(Exception):
    """A bilateration of :func:`placed_points` cannot be formed (its base's ball contains 0:
    ``pair``), or its triangle certainly does not exist (``pair`` None)."""

    def __init__(self, pair: frozenset[str] | None):
        super().__init__(pair)
        self.pair = pair


def _square_root(radicand: flint.acb) -> flint.acb:
    """√radicand with its branch cut away from the radicand: i√(−radicand) where the real
    part is certainly negative. Either determination serves (both signs of each free
    triangle are branches), but flint's principal root is cut along the negative real
    axis, and a ball there came out as wide as the root itself at every precision: issue
    25's 9/N13 (a real root s2,3 = 22.5687 of a dropped factor, the radicand negative on
    four branches) was left undecided at 4096 bits and the solve uncertified."""
    if radicand.real < 0:
        return flint.acb(0, 1) * (-radicand).sqrt()
    return radicand.sqrt()


def computed_distance(points: dict[str, tuple[flint.acb, flint.acb]], u: str, v: str,
                      reference: flint.acb) -> flint.acb:
    """s_{u,v} = |M_v - M_u|² s_{a,b} from the points of :func:`placed_points` (x and y
    squared separately: complex coordinates)."""
    (xu, yu), (xv, yv) = points[u], points[v]
    return squared_distance((xu, yu, 1), (xv, yv, 1), (reference, 1))[0]


def closure_residuals(scene: Scene, plan: Plan, parameters: Sequence[flint.acb], signs,
                      real_only: bool = False) -> tuple[
        list[tuple[flint.acb, flint.arb]] | None, dict[str, tuple[flint.acb, flint.acb]] | None, frozenset[str] | None]:
    """(s_{u,v}(computed) - s_{u,v}(known), s_{u,v}(known)) for every closure pair of the
    plan on one branch at complex parameter values, and the placed points they come from
    (:func:`placed_points`, done once for all pairs); where a bilateration is undefined,
    (None, None, the base's joint pair), and with ``real_only`` where a triangle does not
    exist, (None, None, None)."""
    (_, *residuals), = residuals_on_branches(scene, plan, parameters, [tuple(signs)], real_only)
    return tuple(residuals)


def residuals_on_branches(scene: Scene, plan: Plan, parameters: Sequence[flint.acb],
                          branches: Sequence[tuple[int, ...]], real_only: bool = False) -> Iterator[tuple]:
    """:func:`closure_residuals` on each branch of ``branches``, as (signs, residuals,
    points, pair), the branches' common steps placed once (:func:`placed_on_branches`)."""
    for signs, points, reference, pair in placed_on_branches(scene, plan, parameters, branches, real_only):
        if points is None:
            yield signs, None, None, pair
            continue
        sliders = points[_SLIDERS][0] if _SLIDERS in points else None
        residuals = []
        for u, v in plan.closure_pairs:
            if sliders is not None and {u, v} & sliders.geometry.keys():
                at = {joint: (x, y, flint.acb(1)) for joint, (x, y) in points.items() if joint != _SLIDERS}
                value = _slider_closure(sliders, u, v, at, (reference, flint.acb(1)), _BALLS)
                # a height over the link's, relative to 1; or r − 1 of two axes, 0 only with the sense kept
                residuals.append(((value.x + flint.acb(0, 1) * value.y) / value.w, flint.arb(1)))
                continue
            target = exact_ball(scene.known[frozenset((u, v))]).real
            residuals.append((computed_distance(points, u, v, reference) - target, target))
        yield signs, residuals, points, None


def residual_verdict(residuals: list[tuple[flint.acb, flint.arb]] | None, tolerance) -> bool | None:
    """False if the plan is undefined (None) or some residual ball excludes 0; True if
    every ball contains 0 and is narrower than ``tolerance`` times its target; None
    (undecided: more precision needed) otherwise."""
    if residuals is None or not all(residual.contains(0) for residual, _ in residuals):
        return False
    narrow = all(max(residual.real.rad(), residual.imag.rad()) < tolerance * target for residual, target in residuals)
    return True if narrow else None
