"""A polynomial over Q from its images modulo primes: the Chinese remainder theorem,
rational reconstruction, and the Monte Carlo rule that accepts a result.

Every exact route to a characteristic polynomial computes it modulo primes first, where
the arithmetic is word-size: the resultants of the closure conditions
(:func:`~baranov.solvers.exact.modular.characteristic_polynomial_modulo`, 62-bit primes)
or msolve's rational parametrization (:mod:`baranov.solvers.exact.msolve_images`, 30-bit
primes). :func:`lifted_from_images` recovers the polynomial over Q from such images;
Newton's iteration (:mod:`baranov.solvers.exact.newton_lifting`) recovers it from one
image and checks it here (:func:`reduced_modulo`). A result is accepted only when it
reduces to the image of a prime that was not used to make it.

Reference: P. S. Wang, "A p-adic algorithm for univariate partial fractions", SYMSAC
1981 (rational reconstruction); J. von zur Gathen, J. Gerhard, *Modern Computer
Algebra*, §5.4 and §5.10.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from fractions import Fraction

import flint

from ..progress import report_stage

#: Give up beyond this modulus (p-adic precision or product of primes), in bits.
MOST_BITS = 1 << 18

#: Bits of margin asked of a reconstruction: a residue drawn at random reconstructs
#: within them with probability about 2^-MARGIN_BITS.
MARGIN_BITS = 64

#: Primes not used to make a polynomial that must each reduce it to their image.
CHECK_PRIMES = 2


def chinese_remainder(residues: list[int], modulus: int, image: list[int], prime: int) -> list[int]:
    """x ≡ residues[k] (mod modulus) and x ≡ image[k] (mod prime), in [0, modulus·prime).

    >>> chinese_remainder([2], 3, [3], 5)
    [8]
    """
    inverse = pow(modulus, -1, prime)
    return [r + modulus * (((value - r) * inverse) % prime) for r, value in zip(residues, image, strict=True)]


def rational_reconstruction(residue: int, modulus: int) -> Fraction | None:
    """The fraction n/d ≡ ``residue`` (mod ``modulus``) with |n|, d ≤ √(modulus/2), if
    there is one (extended Euclid stopped half way; Wang 1981). python-flint has none.

    >>> rational_reconstruction(3 * pow(7, -1, 10007) % 10007, 10007)
    Fraction(3, 7)
    """
    bound = math.isqrt(modulus // 2)
    r0, r1, s0, s1 = modulus, residue % modulus, 0, 1
    while r1 > bound:
        quotient = r0 // r1
        r0, r1, s0, s1 = r1, r0 - quotient * r1, s1, s0 - quotient * s1
    if s1 == 0 or abs(s1) > bound or math.gcd(r1, s1) != 1:
        return None
    return Fraction(r1, s1)


def reconstructed(residues: list[int], modulus: int) -> list[Fraction] | None:
    """The rationals with a common denominator D whose residues modulo ``modulus`` are
    ``residues``: D is the lcm of the denominators of the coefficients that rational
    reconstruction recovers with :data:`MARGIN_BITS` to spare (|n|·d < modulus / 2^64),
    and every coefficient times D must then be an integer of that size. This needs fewer
    bits than rational reconstruction coefficient by coefficient once the coefficients
    that come out give all of D: one Newton step fewer on seed 3 of 9/B25, none on B26–B28
    or the 11-link instance of issue 24's table (there, at 7 930 bits, 33 coefficients of
    137 come out, and their denominators' lcm is not yet the 3 422-bit D). None where
    they do not suffice.

    >>> modulus = 2**521 - 1
    >>> reconstructed([x * pow(3, -1, modulus) % modulus for x in (5, 2**70 + 1, 3)], modulus)
    [Fraction(5, 3), Fraction(1180591620717411303425, 3), Fraction(1, 1)]
    """
    limit = modulus >> MARGIN_BITS
    fractions = [rational_reconstruction(r, modulus) for r in residues]
    denominators = [f.denominator for f in fractions if f is not None and abs(f.numerator) * f.denominator < limit]
    if not denominators:
        return None
    denominator = math.lcm(*denominators)
    numerators = [(r * denominator + modulus // 2) % modulus - modulus // 2 for r in residues]
    if any(abs(n) >= limit for n in numerators):
        return None
    return [Fraction(n, denominator) for n in numerators]


def reduced_modulo(coefficients: list[Fraction], prime: int) -> flint.nmod_poly | None:
    """The polynomial with these rational coefficients modulo ``prime`` (None if the
    prime divides a denominator); monic if they are.

    >>> reduced_modulo([Fraction(1, 2), Fraction(1)], 7)
    x + 4
    """
    if any(c.denominator % prime == 0 for c in coefficients):
        return None
    return flint.nmod_poly([c.numerator * pow(c.denominator, -1, prime) for c in coefficients], prime)


def primitive_polynomial(coefficients: list[Fraction]) -> flint.fmpz_poly:
    """The primitive integer polynomial with leading coefficient > 0 proportional to the
    one with these rational ``coefficients`` (lowest first).

    >>> primitive_polynomial([Fraction(1, 2), Fraction(-1, 3)])
    2*x + (-3)
    """
    denominator = math.lcm(*(f.denominator for f in coefficients))
    integers = [int(f * denominator) for f in coefficients]
    sign = -1 if integers[-1] < 0 else 1
    content = math.gcd(*integers)
    return flint.fmpz_poly([sign * c // content for c in integers])


def lifted_from_images(images: Iterator[flint.nmod_poly | None], source: str = "images") -> flint.fmpz_poly | None:
    """The polynomial over Z (primitive, leading coefficient positive) whose monic images
    modulo distinct primes are ``images``: combined by the Chinese remainder theorem,
    reconstructed (:func:`reconstructed`) whenever the modulus has grown by a quarter
    since the last attempt, and accepted once :data:`CHECK_PRIMES` further images agree
    with it. An image of lower degree than another comes from an unlucky prime and is
    skipped; a higher one restarts the combination. None if an image is None or the
    images run out first or the modulus exceeds :data:`MOST_BITS`. ``source`` names the
    images in the progress messages.

    Cost: about twice the coefficients' bits in primes, plus :data:`CHECK_PRIMES`, and a
    reconstruction (O(n · b²) for n coefficients of b bits) at each quarter of growth.

    >>> primes = [1000003, 1000033, 1000037, 1000039, 1000081, 1000099]
    >>> images = [flint.nmod_poly([-4 * pow(3, -1, p), 2 * pow(3, -1, p), 1], p) for p in primes]   # (3u² + 2u − 4)/3
    >>> lifted_from_images(iter(images))
    3*x^2 + 2*x + (-4)
    """
    residues: list[int] = []
    modulus, attempt_bits, candidate, checks = 1, 64, None, 0
    for image in images:
        if image is None:
            return None
        if candidate is not None:
            checks = checks + 1 if reduced_modulo(candidate, image.modulus()) == image else 0
            if checks == CHECK_PRIMES:
                return primitive_polynomial(candidate)
            if checks:
                continue  # a check prime is not combined: it must stay independent of the candidate
            candidate = None
        coefficients = [int(c) for c in image.coeffs()]
        if len(coefficients) < len(residues):
            continue
        if len(coefficients) > len(residues):  # every earlier prime was unlucky
            residues, modulus, attempt_bits = [0] * len(coefficients), 1, 64
        residues = chinese_remainder(residues, modulus, coefficients, image.modulus())
        modulus *= image.modulus()
        if modulus.bit_length() > MOST_BITS:
            return None
        if modulus.bit_length() >= attempt_bits:
            report_stage(f"exact: characteristic polynomial of degree {len(residues) - 1} from {source}, "
                         f"{modulus.bit_length()} bits")
            candidate = reconstructed(residues, modulus)
            attempt_bits = modulus.bit_length() * 5 // 4
    return None
