"""The characteristic polynomial modulo primes: assembly-mode counts at the cost of
word-size arithmetic, and the polynomial over Q lifted from its images.

Over Q (:mod:`baranov.solvers.exact.characteristic`) the norm of a closure condition of an
11-link truss has degree ~2000 and coefficients of ~340 000 bits, and separating its
genuine factor from the extraneous ones means factoring it (24 s per instance at the
median, up to 3 min, on 57 sampled coupling-1 trusses). Only the *degree* of the
genuine part is needed to count assembly modes, and the extraneous factors are known in
advance: they vanish where the computed distance's denominator D does (clearing
denominators brings them in; thesis eqs. 3.6, 3.20, 3.34, 3.92). So, modulo a random
word-size prime p (flint ``nmod_mpoly``/``nmod_poly``):

* the radical tower and the norms are computed as over Q, coefficients mod p;
* the norm N of the condition is *saturated* by the norm M of D — every factor it shares
  with M is divided out, with its multiplicity (repeated gcds) — and so is each content
  removed during the elimination (:func:`~baranov.solvers.exact.characteristic.eliminate_radicals`);
  what remains is the characteristic polynomial mod p, and its degree is counted.

Coupling degree 2 (thesis §3.4.1.3): the saturated norms N_1(u, v), N_2(u, v) of the two
conditions meet at the assembly modes but also where condition 1 holds on one sign branch
and condition 2 on another. Those mismatches are removed without factoring: with c a
random constant, the norm N_c of F_1 + c·F_2 vanishes at a point where F_1 and F_2 vanish on
one branch, and generically not at a mismatch. So gcd(Res_v(N_1, N_2), Res_v(N_1, N_c))
is taken (resultants mod p by evaluation and interpolation,
:mod:`baranov.solvers.exact.resultant`), saturated by Res_v(N_1, D_k) for each square-free part
D_k of the denominators' norms (common points where a distance is 0/0) and by the
leading coefficient of N_1 in v (common points at infinity); its distinct roots are
counted.

For coupling degree 1 a prime can only *lower* the count, never raise it: by dividing a
leading coefficient, by a gcd mod p larger than over Q, or by a genuine factor meeting M
mod p. For coupling degree 2 an accidental common root of the two resultants mod p could
also raise it. Each has probability about (degree / p) ≈ 10^-15. Callers take the
largest count over instances drawn with different primes
(:func:`baranov.solvers.mode_counts.characteristic_degree`).

:func:`lifted_characteristic_polynomial` recovers the polynomial over Q from its monic
images (:mod:`baranov.solvers.exact.lifting_by_primes`); the exact coupling-2 method
uses it and certifies each factor (:mod:`baranov.solvers.exact.coupling_two`).
The counts equal the degrees over Q for every truss up to 9 links and the realization
counts for every truss of 11 links (tests/test_modular.py, the catalog's summary).
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterator

import flint

from baranov.planner import Plan
from baranov.scene import Scene

from .characteristic import ExactMethodError, RadicalTower, eliminate_radicals, radical_tower
from .lifting_by_primes import MOST_BITS, lifted_from_images
from .resultant import coefficients_in_v, resultants_modulo

#: Primes are drawn from [2^61, 2^62): word-size for flint's nmod types.
PRIME_BITS = 62


def random_prime(rng: random.Random, bits: int = PRIME_BITS) -> int:
    """A random prime of ``bits`` bits (default :data:`PRIME_BITS`).

    >>> random_prime(random.Random(0)).bit_length(), random_prime(random.Random(0), bits=30).bit_length()
    (62, 30)
    """
    while True:
        candidate = rng.getrandbits(bits) | (1 << (bits - 1)) | 1
        if flint.fmpz(candidate).is_prime():
            return candidate


def saturate(polynomial, by):
    """``polynomial`` without every irreducible factor it shares with ``by``, whatever
    its multiplicity (flint ``nmod_poly`` or ``nmod_mpoly``; repeated gcd and exact
    division). Cost: one gcd per multiplicity level.

    >>> p = flint.nmod_poly([0, 0, 1, 1], 101)   # t²(t + 1)
    >>> saturate(p, flint.nmod_poly([0, 1], 101))   # by t
    x + 1
    """
    common = polynomial.gcd(by)
    while not common.is_constant():
        polynomial = _divided_out(polynomial, common)
        common = polynomial.gcd(common)
    return polynomial


def _divided_out(polynomial, factor):
    """``polynomial`` / ``factor``^e for the largest e, given that ``factor`` divides it:
    by the powers factor^(2^j), first growing while they divide, then each once more from
    the largest down (the binary digits of what is left), so O(log e) divisions instead of
    e. The norms of 13-link denominators hold factors to powers in the thousands.

    >>> t = flint.nmod_poly([0, 1], 101)
    >>> _divided_out(t**11 * (t + 1), t)
    x + 1
    """
    powers = [factor]
    polynomial = polynomial / factor
    while 2 * _size(powers[-1]) <= _size(polynomial):
        quotient, remainder = divmod(polynomial, powers[-1] * powers[-1])
        if not remainder.is_zero():
            break
        polynomial = quotient
        powers.append(powers[-1] * powers[-1])
    for power in reversed(powers):
        quotient, remainder = divmod(polynomial, power)
        if remainder.is_zero():
            polynomial = quotient
    return polynomial


def _size(polynomial) -> int:
    """The degree of an ``nmod_poly``, the total degree of an ``nmod_mpoly``."""
    return polynomial.degree() if isinstance(polynomial, flint.nmod_poly) else polynomial.total_degree()


def radical(polynomial: flint.nmod_poly) -> flint.nmod_poly:
    """The product of the distinct irreducible factors of ``polynomial``: f / gcd(f, f')
    when its degree is below the prime (one gcd, where flint's square-free factorisation
    took 40 times as long on the 15 728th-degree norm of a 13-link truss's denominator: a
    few factors to powers up to 1 712); otherwise, where a p-th power has derivative 0,
    from that factorisation.

    >>> t = flint.nmod_poly([0, 1], 101)
    >>> radical(t**5 * (t + 1)**2), radical(t**101 * (t + 1))
    (x^2 + x, x^2 + x)
    """
    if polynomial.degree() < polynomial.modulus():
        return polynomial / polynomial.gcd(polynomial.derivative())
    return math.prod((part for part, _ in polynomial.factor_squarefree()[1]), start=polynomial**0)


def norm_factors(polynomial, tower: RadicalTower) -> list[tuple[object, int]]:
    """The norm of ``polynomial`` over the radicals as (factor, multiplicity) pairs: the
    eliminated polynomial and each content divided out on the way (multiplicity = the
    power of 2 it would have had)."""
    norm, contents = eliminate_radicals(polynomial, tower)
    return [(norm, 1), *contents]


def divided_out(polynomial, factor) -> tuple[object, int]:
    """``polynomial`` divided by ``factor`` as often as it divides exactly, and how often
    (flint polynomials of any ring with ``divmod``).

    >>> x = flint.fmpz_poly([0, 1])
    >>> divided_out((x + 1) ** 3 * (x - 2), x + 1)
    (x + (-2), 3)
    """
    multiplicity = 0
    while not polynomial.is_constant():
        quotient, remainder = divmod(polynomial, factor)
        if not remainder.is_zero():
            break
        polynomial, multiplicity = quotient, multiplicity + 1
    return polynomial, multiplicity


def square_free_parts(polynomials) -> list:
    """The distinct non-constant square-free factors of ``polynomials`` (flint
    ``factor_squarefree``): only their zeros matter here, and norms are often high powers
    of small polynomials — the denominators' norms on an 11-link coupling-2 truss have
    degree (353, 329) in all, their parts (8, 12), (6, 4), (1, 0), (0, 1). The parts found
    so far are divided out of each polynomial first, as often as they divide: a later
    norm often holds an earlier one's part to a high power (a nine-link slider chain's
    second denominator norm, (120, 120) = (24, 24)² · (12, 12)⁶ with the (12, 12) of the
    first: 0.61 s → 0.31 s), and exact divisions cost less than the square-free
    factorisation of the whole."""
    parts: list = []
    for polynomial in polynomials:
        for part in parts:
            polynomial, _ = divided_out(polynomial, part)
        if polynomial.is_constant():
            continue
        for part, _ in polynomial.factor_squarefree()[1]:
            if not part.is_constant() and part not in parts:
                parts.append(part)
    return parts


def _leading_coefficient_in_v(polynomial):
    """The coefficient of the highest power of the last generator, as a polynomial."""
    top = polynomial.degrees()[-1]
    return polynomial.context().from_dict({exponents: coefficient for exponents, coefficient in polynomial.to_dict().items()
                                           if exponents[-1] == top})


def _saturated_norm(polynomial, tower: RadicalTower, denominators) -> list[tuple[object, int]]:
    """:func:`norm_factors` of ``polynomial``, each saturated by ``denominators`` (the
    product of the square-free parts of the denominators' norms)."""
    return [(saturate(factor, denominators), multiplicity)
            for factor, multiplicity in norm_factors(polynomial, tower)]


def _univariate(polynomial, prime: int, generator: int = -1) -> flint.nmod_poly:
    """An ``nmod_mpoly`` in one generator only (default: the last), as an ``nmod_poly``."""
    coefficients = [0] * (polynomial.degrees()[generator] + 1)
    for exponents, coefficient in zip(polynomial.monoms(), polynomial.coeffs(), strict=True):
        coefficients[exponents[generator]] = int(coefficient)
    return flint.nmod_poly(coefficients, prime)


def characteristic_polynomial_modulo(scene: Scene, plan: Plan, prime: int, seed: int = 0,
                                    saturated: bool = True) -> flint.nmod_poly:
    """The characteristic polynomial of ``scene`` in the plan's first parameter (coupling
    degree 1 or 2) modulo ``prime``, monic: for coupling degree 1 with the multiplicities
    of the exact method, for 2 square-free (each genuine factor once, as in
    :func:`~baranov.solvers.exact.coupling_two.characteristic_polynomial_two`). ``seed`` draws
    the constant c and the evaluation points of the coupling-2 resultants. Raises
    :class:`ExactMethodError` if ``prime`` divides a denominator of the dimensions, or if
    the result is the zero polynomial (the conditions vanish identically on the instance).

    ``saturated=False`` (coupling degree 2) keeps the roots u that the saturations by
    undefined points and points at infinity would remove: those saturations remove a
    whole u, so they would also remove an assembly mode that shares its u with such a
    point (a coincidence of special instances). The exact method lifts this larger
    polynomial and tests every factor (docs/exact.md, "What the exact backend
    guarantees").
    """
    if plan.number_of_parameters not in (1, 2):
        raise ExactMethodError(f"coupling degree {plan.number_of_parameters}: counts are derived for 1 and 2")
    if plan.number_of_parameters == 2:
        return candidate_images(scene, plan, prime, seed, saturated)[-1]
    # the norms are polynomials in u alone: saturated as nmod_poly, not in the tower's
    # ring, where gcds and square-free parts took 40 % of a 13-link count (multivariate
    # algorithms on univariate input)
    tower = _tower(scene, plan, prime)
    denominators = radical(math.prod((radical(_univariate(factor, prime)) for factor in _denominator_norm_factors(tower)),
                                     start=flint.nmod_poly([1], prime)))
    polynomial = flint.nmod_poly([1], prime)
    for factor, multiplicity in norm_factors(tower.conditions[0], tower):
        polynomial *= saturate(_univariate(factor, prime), denominators) ** multiplicity
    return _monic(polynomial)


def _tower(scene: Scene, plan: Plan, prime: int) -> RadicalTower:
    """The radical tower modulo ``prime``."""
    try:
        return radical_tower(scene, plan, prime)
    except ZeroDivisionError:
        raise ExactMethodError(f"the prime {prime} divides a denominator of the dimensions") from None


def denominator_parts(tower: RadicalTower) -> list:
    """The distinct square-free parts of the norms of ``tower``'s denominators (over Q or
    modulo its prime): where they vanish a condition holds without its distance being the
    known one. A factor that a denominator shares with an earlier one is divided out before
    the norm is taken (its zeros are already among the earlier norm's): the closure
    conditions of a plan often share most of their denominator, and the norms are the cost
    here (:func:`_without_shared_factors`)."""
    return square_free_parts(_denominator_norm_factors(tower))


def _denominator_norm_factors(tower: RadicalTower) -> Iterator:
    """The factors of the norms of ``tower``'s denominators, shared factors divided out
    first (:func:`denominator_parts`)."""
    return (factor for denominator in _without_shared_factors(tower.denominators)
            for factor, _ in norm_factors(denominator, tower))


def _without_shared_factors(polynomials) -> list:
    """``polynomials`` (non-constant ones), each divided by every factor it shares with
    an earlier one (repeated gcds); those left constant are dropped. The product of the
    result has the zeros of the product of ``polynomials``. On 9/B25–B28 the two
    denominators are one polynomial times different monomials."""
    kept: list = []
    for polynomial in polynomials:
        for earlier in kept:
            while not (common := polynomial.gcd(earlier)).is_constant():
                polynomial = polynomial / common
        if not polynomial.is_constant():
            kept.append(polynomial)
    return kept


def candidate_images(scene: Scene, plan: Plan, prime: int, seed: int = 0,
                     saturated: bool = True) -> tuple[flint.nmod_poly, ...]:
    """Coupling degree 2, modulo ``prime``: the candidate polynomial (every u at which
    the curves meet on one branch, the saturations not applied) and, if ``saturated``,
    the characteristic polynomial (the candidate saturated by undefined points and points
    at infinity), each monic with distinct roots, from one set of resultants. Errors as
    :func:`characteristic_polynomial_modulo`."""
    tower = _tower(scene, plan, prime)
    parts = denominator_parts(tower)
    rng = random.Random(seed)
    one = tower.context.constant(1)
    denominators = math.prod(parts, start=one)
    first, second = tower.conditions
    combined = first + rng.randrange(1, prime) * second
    curves = [math.prod(square_free_parts(factor for factor, _ in _saturated_norm(condition, tower, denominators)),
                        start=one) for condition in (first, second, combined)]
    in_plane = [part for part in parts if part.degrees()[-1] > 0] if saturated else []
    every_branch_pair, same_branch, *undefined = _resultants_in_v(curves[0], [curves[1], curves[2], *in_plane],
                                                                  prime, rng)
    common = every_branch_pair.gcd(same_branch)
    candidate = _monic(common / common.gcd(common.derivative()))  # distinct roots
    if not saturated:
        return (candidate,)
    characteristic = candidate
    for part in [*undefined, *(_univariate(part, prime, -2) for part in parts if part.degrees()[-1] == 0)]:
        characteristic = saturate(characteristic, part)
    characteristic = saturate(characteristic, _univariate(_leading_coefficient_in_v(curves[0]), prime, -2))
    return candidate, _monic(characteristic)


def _monic(polynomial: flint.nmod_poly) -> flint.nmod_poly:
    if polynomial.is_zero():  # e.g. a slider chain whose plan's condition holds for every u
        raise ExactMethodError("the closure conditions vanish identically modulo the prime: no characteristic "
                               "polynomial in this plan")
    return polynomial * pow(int(polynomial.coeffs()[-1]), -1, polynomial.modulus())


def characteristic_degree_modulo(scene: Scene, plan: Plan, prime: int, seed: int = 0) -> int:
    """The degree of :func:`characteristic_polynomial_modulo`: the number of assembly
    modes over C, or fewer for an unlucky prime (see the module docstring).

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> from pathlib import Path
    >>> scene = load_scene(Path(__file__).resolve().parents[2] / "examples" / "7-B1.json")
    >>> characteristic_degree_modulo(scene, solvable_plan(scene), random_prime(random.Random(1)))
    14
    """
    return characteristic_polynomial_modulo(scene, plan, prime, seed).degree()


def lifted_characteristic_polynomial(scene: Scene, plan: Plan, seed: int = 0,
                                     saturated: bool = True) -> flint.fmpz_poly:
    """The characteristic polynomial over Q from its images modulo random 62-bit primes
    (:func:`characteristic_polynomial_modulo`), by
    :func:`~baranov.solvers.exact.lifting_by_primes.lifted_from_images` (accepted when two
    further primes agree); primitive over Z, leading coefficient positive.
    ``saturated`` as in :func:`characteristic_polynomial_modulo`.

    Nothing here proves the result; callers certify its factors (the coupling-2 exact
    method tests each at a root in ball arithmetic). On the 9/B28 example: degree 58,
    coefficients of 1418 bits, 48 primes (two of them checks), 17 s beside a test run (the
    resultant route: 174 s).

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> from pathlib import Path
    >>> scene = load_scene(Path(__file__).resolve().parents[2] / "examples" / "7-B1.json")
    >>> lifted_characteristic_polynomial(scene, solvable_plan(scene)).degree()
    14
    """
    rng = random.Random(seed)

    def images() -> Iterator[flint.nmod_poly]:
        while True:
            try:
                yield characteristic_polynomial_modulo(scene, plan, random_prime(rng), seed, saturated)
            except ExactMethodError:  # the prime divides a denominator of the dimensions
                continue

    lifted = lifted_from_images(images(), "the resultants' images")
    if lifted is None:
        raise ExactMethodError(f"the characteristic polynomial needs more than {MOST_BITS} bits of primes")
    return lifted


def _resultants_in_v(first, others: list, prime: int, rng: random.Random) -> list[flint.nmod_poly]:
    """Res_v(first, other) modulo ``prime`` for each of ``others`` (``nmod_mpoly``
    polynomials in the last two generators (u, v), each of positive degree in v), at
    shared evaluation points (:func:`~baranov.solvers.exact.resultant.resultants_modulo`)."""
    first_u, first_v = first.degrees()[-2:]
    degrees = [first_u * other.degrees()[-1] + first_v * other.degrees()[-2] for other in others]
    columns = [coefficients_in_v(other) for other in others]
    while (images := resultants_modulo(coefficients_in_v(first), columns, degrees, prime, rng)) is None:
        pass  # a leading coefficient vanished at an evaluation point: draw other points
    return [flint.nmod_poly(image, prime) for image in images]
