"""The complex roots of an integer polynomial in one variable, isolated once per
polynomial and precision.

The exact backend isolates the roots of each factor of a characteristic polynomial at
several steps, at the same precisions (``TEST_BITS``, ``ROOT_BITS_TWO``,
``ISOLATION_BITS``: 256, 1024, 4096 bits): the factor test at one root
(:mod:`~baranov.solvers.exact.coupling_two`, :mod:`~baranov.solvers.exact.characteristic`),
the common points above one root (:func:`~baranov.solvers.exact.fibers.common_fiber`) and
the modes at its real roots (:func:`~baranov.solvers.exact.backend.modes_at_real_roots`).
flint isolates every complex root each time (Arb's ``acb_poly`` root finder: Aberth
iterations, then certified by interval Newton). On an eleven-link adversarial instance,
a factor of degree 170 with coefficients of about 5 000 bits, each isolation took about
0.7 s at 256 bits, and it was done three times.
"""

from __future__ import annotations

import functools

import flint

#: Distinct (polynomial, precision) pairs kept; a solve meets a few factors at three precisions.
CACHED = 64


def complex_roots(polynomial: flint.fmpz_poly) -> tuple[tuple[flint.acb, int], ...]:
    """flint's ``complex_roots()`` of ``polynomial`` at the working precision
    (``flint.ctx.prec``): certified enclosures of its distinct complex roots with their
    multiplicities, real roots exactly real, computed once for each polynomial and
    precision. Cost: the isolation the first time, then O(deg) to hash the coefficients.

    >>> [(str(root.real.mid()), multiplicity) for root, multiplicity in complex_roots(flint.fmpz_poly([-2, 1]) ** 2)]
    [('2.00000000000000', 2)]
    """
    return _isolated(flint.ctx.prec, tuple(int(c) for c in polynomial.coeffs()))


@functools.lru_cache(maxsize=CACHED)
def _isolated(precision: int, coefficients: tuple[int, ...]) -> tuple[tuple[flint.acb, int], ...]:
    previous = flint.ctx.prec
    flint.ctx.prec = precision
    try:
        return tuple(flint.fmpz_poly(list(coefficients)).complex_roots())
    finally:
        flint.ctx.prec = previous
