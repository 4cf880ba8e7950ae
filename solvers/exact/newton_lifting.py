"""The candidate polynomial of a coupling-2 plan over Q from one prime by p-adic Newton
iteration, instead of from ~50 primes by the Chinese remainder theorem.

The exact method for coupling degree 2 (:mod:`baranov.solvers.exact.coupling_two`) needs
the candidate polynomial over Q: the characteristic polynomial P (the assembly modes'
values of the first parameter u, about 1 400 bits per coefficient on 9/B28) times the
small part E whose roots the saturations remove (undefined points, points at infinity;
degree 2–9 and tens of bits on the four nine-link trusses). Lifting it by primes
(:func:`~baranov.solvers.exact.modular.lifted_characteristic_polynomial`) takes twice
the coefficients' bits in primes, each a full resultant computation: 36 primes and 3.7 s
of a 4.1 s solve on a random 9/B25 instance.

Here one prime p gives P mod p (:func:`~baranov.solvers.exact.modular.candidate_images`)
and, above each of its roots, the one common point of the genuine curves G_1, G_2 with
v = Q(u) mod P — their gcd in v over F_p[u]/(P) (:func:`~baranov.solvers.exact.fibers.gcd_modulo`).
This *shape-position* parametrization (P, Q) of the modes is lifted p-adically by
Newton's operator for (G_1, G_2) applied to all points at once (global Newton iteration;
Giusti, Lecerf, Salvy, "A Gröbner free alternative for polynomial system solving",
J. Complexity 17, 2001, §4): with (δ_u, δ_v) = J⁻¹·(G_1, G_2) at (u, Q(u)) in
(Z/p^2k)[u]/(P), J the Jacobian,

    P ← P + (δ_u · P' mod P),        Q ← Q + (Q' · δ_u − δ_v mod P),

which doubles the p-adic precision each step; the coefficients of P over Q are recovered
by rational reconstruction once two successive precisions agree. E (small) is recovered
from its images at the first primes by the Chinese remainder theorem; every prime after
the first also checks P: its own image of P must equal the lifted one reduced modulo it.

Where the modes are not simple common points of G_1 and G_2 in shape position modulo p
(a zero divisor in the gcd, a Jacobian not invertible) or a check fails, nothing is
returned and the caller lifts by primes. Cost: one resultant computation per prime used
(two or three on generic nine-link instances) and O(log bits) Newton steps of
O(deg_v) products of polynomials of degree deg P.
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable, Iterator, Sequence
from fractions import Fraction
from itertools import chain

import flint

from baranov.planner import Plan
from baranov.scene import Scene

from ..progress import report_stage
from .characteristic import ExactMethodError, radical_tower
from .fibers import ZeroDivisor, gcd_modulo
from .lifting_by_primes import (
    MOST_BITS,
    chinese_remainder,
    primitive_polynomial,
    rational_reconstruction,
    reconstructed,
    reduced_modulo,
)
from .modular import candidate_images, denominator_parts, random_prime
from .resultant import coefficients_in_v

#: Give up (the caller lifts by primes) beyond this number of primes.
MOST_PRIMES = 12


def _columns(curve: flint.fmpz_mpoly) -> list[flint.fmpz_poly]:
    """``curve``(u, v) as its coefficients in v, integer polynomials in u."""
    return [flint.fmpz_poly([terms.get(k, 0) for k in range(max(terms, default=0) + 1)])
            for terms in coefficients_in_v(curve)]


def shape_position_split(curves: Sequence[flint.fmpz_mpoly], characteristic: flint.nmod_poly) -> tuple[
        flint.nmod_poly, flint.nmod_poly, flint.nmod_poly]:
    """(good, Q, rest): ``characteristic`` = good · rest modulo its prime, where above every
    root of good the two curves have one common point, v = Q(u), and meet there
    transversally (their Jacobian is invertible), so that Newton's iteration lifts good
    and Q (:func:`newton_lifts`); rest holds the other roots (two modes above one value
    of u, a mode where the curves are tangent or singular). The gcd of the curves in v is
    taken modulo the whole polynomial, which is split wherever a leading coefficient
    vanishes at some of its roots only (:class:`~baranov.solvers.exact.fibers.ZeroDivisor`,
    dynamic evaluation). For a lucky prime good and rest are the images of factors over
    Q: the roots they hold are told apart by polynomial conditions over Q.

    >>> from baranov.solvers.exact.coupling_two import PLANE
    >>> u, v = PLANE.gens()
    >>> p = 101
    >>> # v = u² and v² = u⁴ + u² − 2: common points above u² = 2 (one each) and u = ±1 (none)
    >>> good, second, rest = shape_position_split([v - u**2, (v - u**2) * (v + u**2) + u**2 - 2],
    ...                                           flint.nmod_poly([-2, 0, 1], p) * flint.nmod_poly([-1, 0, 1], p))
    >>> good, second, rest
    (x^2 + 99, 2, x^2 + 100)
    >>> shape_position_split([v - u, v + u], flint.nmod_poly([0, 0, 1], p))   # u²: not square-free
    (1, 0, x^2)
    """
    prime = characteristic.modulus()
    if characteristic.gcd(characteristic.derivative()).degree() > 0:  # images are square-free; else no split
        return flint.nmod_poly([1], prime), flint.nmod_poly([0], prime), characteristic
    columns = [[flint.nmod_poly([int(c) for c in column.coeffs()], prime) for column in _columns(curve)]
               for curve in curves]
    pending, parts, rest = [characteristic], [], flint.nmod_poly([1], prime)
    while pending:
        modulus = pending.pop()
        if modulus.degree() < 1:
            continue
        try:
            common = gcd_modulo(*columns, modulus)
        except ZeroDivisor as split:  # the remainder sequences differ between its roots
            pending += [split.factor, modulus // split.factor]
            continue
        if len(common) == 2:
            parts.append((modulus, -common[0]))
        else:
            rest *= modulus
    good, second = flint.nmod_poly([1], prime), flint.nmod_poly([0], prime)
    for modulus, coordinate in parts:  # Q by the Chinese remainder theorem over F_p[u] (coprime parts)
        _, inverse, _ = (good % modulus).xgcd(modulus)
        second += good * ((coordinate - second) * inverse % modulus)
        good *= modulus
    if good.degree() > 0:
        ring = flint.fmpz_mod_poly_ctx(prime)
        (u1, v1, u2, v2), _ = _jacobian([_parts(_columns(curve)) for curve in curves], ring, _integer(good),
                                        _integer(second), flint.fmpz_poly([0]))
        singular = flint.nmod_poly([int(c) for c in ((u1 * v2 - v1 * u2) % ring(_integer(good))).gcd(
            ring(_integer(good))).coeffs()], prime)
        if singular.degree() > 0:  # the curves meet non-transversally there
            good, rest = good // singular, rest * singular
            second = second % good
    return good, second, rest


def _powers(second, modulus, count: int) -> tuple[list, object]:
    """Baby steps Q^0 … Q^(k-1) and the giant step Q^k modulo P, k ≈ √count."""
    steps = math.isqrt(max(count - 1, 0)) + 1
    baby = [modulus**0]
    for _ in range(steps - 1):
        baby.append(baby[-1] * second % modulus)
    return baby, baby[-1] * second % modulus


def _evaluate(coefficients: list, powers: tuple[list, object], modulus):
    """Σ_j coefficients[j]·Q^j modulo P (Paterson–Stockmeyer: each block of k columns
    times the baby steps, the blocks combined by Horner in the giant step), so that a
    curve of degree d in v costs about 2√d products and remainders of size deg P,
    against d for all the powers of Q."""
    baby, giant = powers
    blocks = [sum((c * baby[i] for i, c in enumerate(coefficients[start:start + len(baby)])), start=modulus * 0)
              for start in range(0, len(coefficients), len(baby))]
    value = blocks[-1] % modulus
    for block in reversed(blocks[:-1]):
        value = (value * giant + block) % modulus
    return value


def _parts(columns: list) -> tuple[list, list, list]:
    """The columns of G, ∂G/∂u and ∂G/∂v (coefficients in v, polynomials in u)."""
    return columns, [c.derivative() for c in columns], [j * c for j, c in enumerate(columns)][1:] or [columns[0] * 0]


def _jacobian(parts: list, ring, characteristic, second, inverse) -> tuple:
    """The Jacobian (∂G_i/∂u, ∂G_i/∂v) at (u, Q(u)) modulo P in ``ring``, and the inverse
    of its determinant improved by one Newton step."""
    P, Q = ring(characteristic), ring(second)
    powers = _powers(Q, P, max(len(columns) for columns, _, _ in parts))
    (u1, v1), (u2, v2) = (tuple(_evaluate([ring(c) for c in columns], powers, P) for columns in (along_u, along_v))
                          for _, along_u, along_v in parts)
    determinant = (u1 * v2 - v1 * u2) % P
    inverse = ring(inverse)
    return (u1, v1, u2, v2), (inverse * (2 - determinant * inverse)) % P


def _integer(polynomial) -> flint.fmpz_poly:
    return flint.fmpz_poly([int(c) for c in polynomial.coeffs()])


def _newton_step(parts: list, characteristic, second, inverse, precision: int):
    """One Newton step from ``precision`` m to m²: the new (P, Q) and the inverse of the
    Jacobian determinant modulo (P, m). The Jacobian is needed modulo m only (the
    residuals are ≡ 0 modulo m), so it is evaluated there, at half the size."""
    jacobian, inverse = _jacobian(parts, flint.fmpz_mod_poly_ctx(precision), characteristic, second, inverse)
    ring = flint.fmpz_mod_poly_ctx(precision * precision)
    P, Q = ring(characteristic), ring(second)
    powers = _powers(Q, P, max(len(columns) for columns, _, _ in parts))
    g1, g2 = (_evaluate([ring(c) for c in columns], powers, P) for columns, _, _ in parts)
    (u1, v1, u2, v2), lifted_inverse = (ring(_integer(x)) for x in jacobian), ring(_integer(inverse))
    delta_u = ((v2 * g1 - v1 * g2) % P * lifted_inverse) % P
    delta_v = ((u1 * g2 - u2 * g1) % P * lifted_inverse) % P
    new_second = Q + (Q.derivative() * delta_u - delta_v) % P
    new_characteristic = P + (delta_u * P.derivative()) % P
    return _integer(new_characteristic), _integer(new_second), _integer(inverse)


def newton_lifts(curves: Sequence[flint.fmpz_mpoly], characteristic: flint.nmod_poly,
                 second: flint.nmod_poly | None = None) -> Iterator[list[Fraction]]:
    """Candidates for the monic polynomial over Q whose image modulo the prime is
    ``characteristic``, lifted along the common points of the two ``curves`` (module
    docstring): after each Newton step whose rational reconstruction succeeds, its
    coefficients, lowest first (a too low precision can reconstruct wrongly: callers check
    each candidate at another prime). Nothing where the points are not simple common
    points in shape position modulo the prime. ``second``: Q modulo ``characteristic`` if
    known (:func:`shape_position_split`), else computed by it.

    >>> from baranov.solvers.exact.coupling_two import PLANE
    >>> u, v = PLANE.gens()
    >>> curves = [2 * v - u**2, 3 * v + u - 2]            # common points: 3u² + 2u − 4 = 0
    >>> prime = 1000003
    >>> image = flint.nmod_poly([-4 * pow(3, -1, prime), 2 * pow(3, -1, prime), 1], prime)
    >>> [str(c) for c in next(newton_lifts(curves, image))]
    ['-4/3', '2/3', '1']
    >>> list(newton_lifts([v**2 - 1, u], flint.nmod_poly([0, 1], prime)))   # (0, ±1): one u, two points
    []
    """
    prime = characteristic.modulus()
    if characteristic.degree() < 1:
        yield [Fraction(1)]
        return
    if second is None:
        _, second, rest = shape_position_split(curves, characteristic)
        if rest.degree() > 0:
            return
    parts = [_parts(_columns(curve)) for curve in curves]
    ring = flint.fmpz_mod_poly_ctx(prime)
    lift = [_integer(characteristic), _integer(second), flint.fmpz_poly([0])]
    (u1, v1, u2, v2), _ = _jacobian(parts, ring, *lift)  # the inverse step is unused here: xgcd gives it
    common, inverse, _ = ((u1 * v2 - v1 * u2) % ring(lift[0])).xgcd(ring(lift[0]))
    if common.degree() != 0:
        return  # a mode is not a simple common point modulo p
    lift[2] = _integer(inverse * pow(int(common.coeffs()[0]), -1, prime))
    modulus = prime
    while modulus.bit_length() < MOST_BITS:
        lift = _newton_step(parts, *lift, modulus)
        modulus *= modulus
        report_stage(f"exact: characteristic polynomial of degree {characteristic.degree()} by Newton's iteration, "
                     f"{modulus.bit_length()} bits")
        fractions = reconstructed([int(c) for c in lift[0].coeffs()], modulus)
        if fractions is not None:
            yield fractions


def _rational(coefficients: list[Fraction]) -> flint.fmpq_poly:
    return flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coefficients])


def known_extraneous_factors(scene: Scene, plan: Plan, curves: Sequence[flint.fmpz_mpoly]) -> Iterator[flint.fmpz_poly]:
    """Integer polynomials in u, cheap over Q, whose roots include those that the
    saturations remove: each curve's leading coefficient in v and its value at v = 0
    (points at infinity; the line v = 0, where the second parameter is a factor of a
    denominator), then the parts of the denominators' norms in u alone (the tower over Q,
    computed only if asked for). On seed 3 of 9/B25–B28 they explain every removed root."""
    for curve in curves:
        columns = _columns(curve)
        yield columns[-1]
        yield columns[0]
    for part in denominator_parts(radical_tower(scene, plan)):
        if part.degrees()[-1] == 0:
            terms = dict(zip(part.monoms(), part.coeffs(), strict=True))
            yield flint.fmpq_poly([terms.get(_monomial(part, k), 0) for k in range(part.degrees()[-2] + 1)]).numer()


def _monomial(polynomial, power: int) -> tuple[int, ...]:
    """The exponent vector of u^power in ``polynomial``'s ring (u the second-to-last generator)."""
    exponents = [0] * len(polynomial.degrees())
    exponents[-2] = power
    return tuple(exponents)


def extraneous_from_factors(rest: flint.nmod_poly, known: Iterable[flint.fmpz_poly]) -> list[Fraction] | None:
    """The monic polynomial over Q, product of irreducible factors of the ``known``
    polynomials, whose image modulo the prime is ``rest`` (monic, square-free): its
    coefficients, lowest first; None if the factors met do not make it up exactly. The
    known polynomials are taken in order, and only until they do.

    >>> prime = 1000003
    >>> rest = flint.nmod_poly([0, 1], prime) * flint.nmod_poly([1, 0, 1], prime)   # u (u² + 1)
    >>> [str(c) for c in extraneous_from_factors(rest, [flint.fmpz_poly([0, 3]), flint.fmpz_poly([1, 1]),
    ...                                                 flint.fmpz_poly([5, 0, 5])])]
    ['0', '1', '0', '1']
    >>> extraneous_from_factors(rest, [flint.fmpz_poly([0, 3])]) is None
    True
    """
    prime = rest.modulus()
    if rest.degree() < 1:
        return [Fraction(1)]
    chosen, seen, image = [], set(), flint.nmod_poly([1], prime)
    for polynomial in known:
        if polynomial.degree() < 1:
            continue
        for factor, _ in polynomial.factor()[1]:
            reduced = flint.nmod_poly([int(c) for c in factor.coeffs()], prime)
            if factor.degree() < 1 or str(factor) in seen or reduced.degree() != factor.degree():
                continue
            seen.add(str(factor))
            if rest.gcd(reduced).degree() > 0:
                chosen.append(factor)
                image *= reduced
        if image * pow(int(image.coeffs()[-1]), -1, prime) == rest:
            product = math.prod(chosen, start=flint.fmpz_poly([1]))
            return [Fraction(int(c), int(product.coeffs()[-1])) for c in product.coeffs()]
    return None


def candidate_by_newton(scene: Scene, plan: Plan, curves: Sequence[flint.fmpz_mpoly],
                        seed: int = 0) -> flint.fmpz_poly | None:
    """The candidate polynomial of a coupling-2 ``plan`` over Z (primitive, leading
    coefficient positive), as :func:`~baranov.solvers.exact.modular.lifted_characteristic_polynomial`
    with ``saturated=False`` returns it, from its characteristic part P and the small rest
    E that saturations remove. The part G of P whose roots are simple common points of
    the genuine ``curves`` in shape position (:func:`shape_position_split`: all of P on a
    generic instance) is lifted by Newton's iteration from the first prime and accepted
    when its image divides the second prime's image of P; the rest of the candidate,
    E and P/G, is made of :func:`known_extraneous_factors` matching the first prime's
    image, or else lifted by primes, and accepted when it reduces to a further prime's
    image. Every prime after the first checks G again. None where no root is a simple
    point in shape position or a check fails (the caller then lifts by primes)."""
    rng = random.Random(seed)
    lifts: Iterator[list[Fraction]] | None = None
    characteristic: list[Fraction] | None = None
    extraneous: list[Fraction] | None = None
    residues: list[int] = []
    modulus, degrees = 1, None
    for _ in range(MOST_PRIMES):
        prime = random_prime(rng)
        try:
            candidate, image = candidate_images(scene, plan, prime, seed)
        except ExactMethodError:
            continue
        if lifts is None:
            # the roots that are not simple common points in shape position join the rest E
            good, coordinate, _ = shape_position_split(curves, image)
            degrees, lifts = (candidate.degree(), image.degree()), newton_lifts(curves, good, coordinate)
            first = next(lifts, None) if good.degree() > 0 else None
            if first is None:
                return None  # no simple points in shape position: no need for a second prime
            lifts = chain([first], lifts)
            rest = candidate / good
            extraneous = extraneous_from_factors(rest, known_extraneous_factors(scene, plan, curves))
        elif (candidate.degree(), image.degree()) != degrees:
            return None  # an unlucky prime, or an unlucky first one
        else:
            if characteristic is None:  # the first lift that this prime confirms
                characteristic = next((lift for lift in lifts if (image % reduced_modulo(lift, prime)).is_zero()), None)
            if characteristic is None or not (image % reduced_modulo(characteristic, prime)).is_zero():
                return None
            rest = candidate / reduced_modulo(characteristic, prime)
            if extraneous is None:
                reconstructed = [rational_reconstruction(r, modulus) for r in residues]
                extraneous = None if None in reconstructed else reconstructed
            if extraneous is not None and reduced_modulo(extraneous, prime) == rest:
                return primitive_polynomial([Fraction(int(c.p), int(c.q))
                                                for c in (_rational(characteristic) * _rational(extraneous)).coeffs()])
            extraneous = None  # by primes from here
        residues = chinese_remainder(residues or [0] * (rest.degree() + 1), modulus, [int(c) for c in rest.coeffs()], prime)
        modulus *= prime
    return None
