"""Irreducible factors over Q of polynomials in the plane of two parameters (u, v).

A coupling-2 plan clears each closure condition of its radicals, which gives a norm
N(u, v) of bidegree up to (72, 72) with coefficients of 1000–1700 bits on the nine-link
trusses. The norm is a product of one or a few *curves* that carry solutions and of high
powers of small extraneous curves. Those extraneous curves are mostly factors of the norms of
the tower's denominators (seed 1 of 9/B25–B28: N = G · S^m with S of bidegree (2, 0)–(12, 12)
and m = 3–12, each S a factor of a denominator's norm). flint's factorisation over Q
proves every factor irreducible, and on these norms that costs 0.1–0.5 s each: 0.86 s of a
3.4 s exact solve of 9/B28.

:func:`plane_factors` asks less of it. Factors known in advance are divided out exactly.
The rest is proven irreducible by one small prime where it can be. Only what is left after
that is factored over Q. The result is the same factorisation over Q (up to the order of
the factors).
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable

import flint

from .modular import divided_out, random_prime

#: The bivariate ring of the two parameters (u = first plan parameter, v = second).
PLANE = flint.fmpz_mpoly_ctx.get(("u", "v"), "lex")

#: The same plane with rational coefficients.
RATIONAL_PLANE = flint.fmpq_mpoly_ctx.get(("u", "v"), "lex")

#: Primes tried by :func:`irreducible_modulo_a_prime`. They have 30 bits because
#: python-flint 0.9's factor sorting converts coefficients to a C int.
CERTIFYING_PRIMES = 3
CERTIFYING_PRIME_BITS = 30


def plane_polynomial(norm: flint.fmpq_mpoly) -> flint.fmpz_mpoly:
    """A norm (in the tower's ring, free of radicals) as a primitive integer polynomial in
    (u, v)."""
    names = norm.context().names()
    rational = norm.project_to_context(RATIONAL_PLANE, mapping={names[-2]: "u", names[-1]: "v"})
    scale = math.lcm(*(int(c.q) for c in rational.coeffs()))
    integer = PLANE.from_dict({k: c.p for k, c in (rational * scale).to_dict().items()})
    if integer.is_zero():
        return integer
    return integer / integer.content()  # in flint throughout: 3.4 times faster than through Fractions


def plane_factors(polynomial: flint.fmpz_mpoly, known: Iterable[flint.fmpz_mpoly] = ()) -> list[
        tuple[flint.fmpz_mpoly, int]]:
    """The irreducible factors over Q of a polynomial in (u, v), primitive with a positive
    leading coefficient (lex, u > v), with their multiplicities; the constant is left out.

    ``known``: irreducible primitive polynomials that may divide ``polynomial``, such as
    the factors of the denominators' norms. Each is divided out exactly, as often as it
    divides. The rest R is then proven irreducible, if it is, by
    :func:`irreducible_modulo_a_prime`. Otherwise R is factored over Q by flint
    (:func:`factors_over_q`).

    Cost: one exact division per known factor and power, and one bivariate factorisation
    over F_p (milliseconds at bidegree (72, 72)) for each of at most
    :data:`CERTIFYING_PRIMES` primes. The factorisation over Q is needed only when R is
    reducible or no prime proves it irreducible.

    >>> u, v = PLANE.gens()
    >>> plane_factors((u * v - 3) * (u + 1) ** 3, known=[u + 1])
    [(u + 1, 3), (u*v - 3, 1)]
    >>> sorted(plane_factors((u * v - 3) * (u - v)), key=str)
    [(u - v, 1), (u*v - 3, 1)]
    """
    rest, factors = polynomial, []
    for candidate in known:
        rest, multiplicity = divided_out(rest, candidate)
        if multiplicity:
            factors.append((candidate, multiplicity))
    if rest.is_constant():
        return factors
    if irreducible_modulo_a_prime(rest):
        return [*factors, (_positive(rest / rest.content()), 1)]
    return factors + factors_over_q(rest)


def _positive(polynomial: flint.fmpz_mpoly) -> flint.fmpz_mpoly:
    return -polynomial if polynomial.leading_coefficient() < 0 else polynomial


def irreducible_modulo_a_prime(polynomial: flint.fmpz_mpoly, seed: int = 0) -> bool:
    """True if ``polynomial`` (non-constant) is irreducible modulo one of
    :data:`CERTIFYING_PRIMES` random primes that keep its leading coefficient (lex). That
    proves it irreducible over Q. If it were A·B with A and B non-constant, its leading
    term would be LT(A)·LT(B), whose coefficient is not 0 modulo p. Then A and B would keep
    their non-constant leading monomials modulo p, so the image would be reducible too.
    False means "not proven". It does not mean reducible: a curve that is irreducible
    over Q but not over its algebraic closure splits modulo about half the primes.

    >>> u, v = PLANE.gens()
    >>> irreducible_modulo_a_prime(u**2 * v + v**3 - 7), irreducible_modulo_a_prime(u**2 - 4 * v**2)
    (True, False)
    >>> irreducible_modulo_a_prime(u**2 - 2 * v**2)  # 2 is not a square modulo one of the primes
    True
    """
    rng = random.Random(seed)
    lead = int(polynomial.leading_coefficient())
    terms = polynomial.to_dict()
    for _ in range(CERTIFYING_PRIMES):
        prime = random_prime(rng, CERTIFYING_PRIME_BITS)
        if lead % prime == 0:
            continue
        context = flint.nmod_mpoly_ctx.get(("u", "v"), modulus=prime, ordering="lex")
        image = context.from_dict({monomial: int(c) % prime for monomial, c in terms.items()})
        try:
            _, factors = image.factor()
        except OverflowError:  # python-flint's factor sorting (factors_over_q); not proven here
            continue
        if len(factors) == 1 and factors[0][1] == 1:
            return True
    return False


def factors_over_q(polynomial: flint.fmpz_mpoly) -> list[tuple[flint.fmpz_mpoly, int]]:
    """flint's factorisation of ``polynomial`` over Q: its irreducible factors, each primitive,
    and their multiplicities (the constant left out).

    python-flint 0.9's ``fmpz_mpoly.factor`` sorts its factors with a key that converts
    coefficients to a C int. It raises OverflowError when two factors of one multiplicity
    agree in their leading terms and differ in a coefficient beyond 2^31 (issue 25: 9/N27
    drawn at a double root, a condition's norm of bidegree (48, 48) with 300-bit
    coefficients). Its ``fmpq_mpoly.factor`` compares rationals and does not, so it is the
    fallback, each factor scaled back to a primitive integer polynomial."""
    try:
        return polynomial.factor()[1]
    except OverflowError:
        rational = RATIONAL_PLANE.from_dict({k: flint.fmpq(c) for k, c in polynomial.to_dict().items()})
        factors = []
        for factor, multiplicity in rational.factor()[1]:
            terms = factor.to_dict()
            scale = math.lcm(*(int(c.q) for c in terms.values()))
            integer = {k: int(c.p) * (scale // int(c.q)) for k, c in terms.items()}
            content = math.gcd(*integer.values())
            factors.append((PLANE.from_dict({k: c // content for k, c in integer.items()}), multiplicity))
        return factors
