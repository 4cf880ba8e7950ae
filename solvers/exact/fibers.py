"""The common points of two plane curves above the roots of an irreducible polynomial,
exactly: polynomial arithmetic over the number field K = Q[u]/(f).

A coupling-2 plan (thesis §3.4.1.3) eliminates its second parameter v from two curves
G_1(u, v) = G_2(u, v) = 0, leaving a characteristic polynomial in u. Going back — the
assembly modes above a root u* of an irreducible factor f — needs the common roots v of
G_1(u*, ·) and G_2(u*, ·). Isolating the roots of G_1(u*, ·) numerically fails exactly
where it matters most: at a configuration with a flat free-sign triangle both curves have
a multiple root in v (the 9/B28 instance of docs/exact.md: G_1(25, v) and G_2(25, v) both
have the factor (v - 1)², and the numerical isolation never succeeds, so the mode was
dropped), and where a leading coefficient vanishes at u* a root goes to infinity and the
column's leading ball never excludes 0.

Here the columns are reduced modulo f (a coefficient ≡ 0 mod f is exactly 0 at every
root of f), their gcd h is taken over K by Euclid's algorithm, and h is made square-free
(h / gcd(h, h')). Since K ≅ Q(u*), the roots of h at u* are exactly the common points
above u*, each simple, so flint's certified root isolation succeeds once the precision is
high enough. A K element is an ``fmpq_poly`` of degree < deg f.

Cost: O(deg_v²) operations in K, each a product and a remainder of polynomials of degree
< deg f, plus one inversion per Euclid step (extended gcd with f); free for deg f = 1
(plain gcd in Q[v]).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import flint

from .resultant import coefficients_in_v
from .roots import complex_roots

#: A polynomial in v over K: its coefficients (``fmpq_poly`` in u reduced modulo f),
#: lowest degree first, without top zeros; [] is the zero polynomial.
FieldPolynomial = list


def column_over_field(curve: flint.fmpz_mpoly, field: flint.fmpz_poly) -> FieldPolynomial:
    """``curve``(u, v) as a polynomial in v over K = Q[u]/(``field``).

    >>> from baranov.solvers.exact.coupling_two import PLANE
    >>> u, v = PLANE.gens()
    >>> column_over_field((u - 2) * v**2 + u * v + 1, flint.fmpz_poly([-2, 1]))  # at u = 2
    [1, 2]
    """
    modulus = flint.fmpq_poly(field)
    column = []
    for terms in coefficients_in_v(curve):
        top = max(terms, default=0)
        coefficient = flint.fmpq_poly([terms.get(k, 0) for k in range(top + 1)])
        column.append(_reduce(coefficient, modulus))
    return _trimmed(column)


def _reduce(element, modulus):
    return element % modulus if element.degree() >= modulus.degree() else element


def _trimmed(polynomial: FieldPolynomial) -> FieldPolynomial:
    while polynomial and polynomial[-1].is_zero():
        polynomial = polynomial[:-1]
    return polynomial


def _over_q(polynomial: FieldPolynomial) -> flint.fmpq_poly:
    """A polynomial over K = Q (constant coefficients) as an ``fmpq_poly`` in v."""
    return flint.fmpq_poly([c[0] for c in polynomial])


class ZeroDivisor(ZeroDivisionError):
    """An element of R[u]/(modulus) with no inverse: it shares ``factor`` (monic, a proper
    factor of the modulus) with the modulus, so it vanishes at the roots of ``factor``
    only. A caller can split the modulus there and go on with each part (dynamic
    evaluation: Della Dora, Dicrescenzo, Duval, EUROCAL 1985)."""

    def __init__(self, factor):
        super().__init__("a leading coefficient is a zero divisor modulo a reducible polynomial")
        self.factor = factor


def _inverse(element, modulus):
    """1/element in R[u]/(modulus) (``fmpq_poly`` or ``nmod_poly``). For an irreducible
    modulus (a field) every non-zero element has one; otherwise :class:`ZeroDivisor` where
    ``element`` shares a factor with the modulus (it vanishes at some of its roots only)."""
    if modulus.degree() == 1 and isinstance(modulus, flint.fmpq_poly):
        return flint.fmpq_poly([1 / element[0]])
    gcd, inverse, _ = element.xgcd(modulus)
    if gcd.degree() != 0:
        raise ZeroDivisor(gcd)
    return inverse / gcd[0] if isinstance(modulus, flint.fmpq_poly) else inverse * pow(int(gcd[0]), -1, modulus.modulus())


def _monic(polynomial: FieldPolynomial, modulus) -> FieldPolynomial:
    inverse = _inverse(polynomial[-1], modulus)
    return [_reduce(c * inverse, modulus) for c in polynomial[:-1]] + [modulus**0]


def _remainder(dividend: FieldPolynomial, divisor: FieldPolynomial, modulus,
               quotient: list | None = None) -> FieldPolynomial:
    """``dividend`` mod the monic ``divisor`` over R[u]/(modulus); the quotient's
    coefficients are put in ``quotient`` (highest first, zeros included) if given."""
    remainder = list(dividend)
    shift = len(divisor) - 1
    for top in range(len(remainder) - 1, shift - 1, -1):
        lead = remainder[top]
        if quotient is not None:
            quotient.append(lead)
        if not lead.is_zero():
            for k in range(shift):
                remainder[top - shift + k] = _reduce(remainder[top - shift + k] - lead * divisor[k], modulus)
        remainder[top] = modulus * 0
    return _trimmed(remainder[:shift])


def gcd_over_field(first: FieldPolynomial, second: FieldPolynomial, field: flint.fmpz_poly) -> FieldPolynomial:
    """The monic gcd of two polynomials in v over K = Q[u]/(``field``) (Euclid); [] if
    both are zero.

    >>> one = flint.fmpq_poly([1])
    >>> x = [flint.fmpq_poly([0]), one]                       # v
    >>> square = [one, flint.fmpq_poly([-2]), one]            # (v - 1)²
    >>> root = flint.fmpq_poly([0, 1])                         # u, with u² = 3
    >>> gcd_over_field([flint.fmpq_poly([-3]), flint.fmpq_poly([0]), one], [-root, one], flint.fmpz_poly([-3, 0, 1]))
    [(-1)*x, 1]
    >>> gcd_over_field(square, x, flint.fmpz_poly([-3, 0, 1]))
    [1]
    """
    if field.degree() == 1:  # K = Q: flint's gcd in Q[v]
        common = _over_q(_trimmed(list(first))).gcd(_over_q(_trimmed(list(second))))
        return [flint.fmpq_poly([c]) for c in common.coeffs()]
    return gcd_modulo(first, second, flint.fmpq_poly(field))


def gcd_modulo(first: FieldPolynomial, second: FieldPolynomial, modulus) -> FieldPolynomial:
    """The monic gcd of two polynomials in v over R[u]/(``modulus``), R = Q (``fmpq_poly``)
    or F_p (``nmod_poly``), by Euclid's algorithm; [] if both are zero. Over a reducible
    modulus this is the gcd at every root of it at once, and :class:`ZeroDivisor` is raised
    where the remainder sequence differs between roots (a leading coefficient vanishing at
    some roots only).

    >>> p = 101
    >>> modulus = flint.nmod_poly([-2, 0, 1], p) * flint.nmod_poly([-3, 1], p)   # u² = 2 or u = 3
    >>> u = flint.nmod_poly([0, 1], p)
    >>> # v - u and v² - 2 have a common point above u² = 2 only
    >>> gcd_modulo([-u, u**0], [-2 * u**0, u * 0, u**0], modulus)   # doctest: +IGNORE_EXCEPTION_DETAIL
    Traceback (most recent call last):
    ...
    ZeroDivisor: a leading coefficient is a zero divisor modulo a reducible polynomial
    >>> gcd_modulo([-u, u**0], [-u * u, u * 0, u**0], modulus)   # v - u and v² - u²
    [100*x, 1]
    """
    first, second = _trimmed([_reduce(c, modulus) for c in first]), _trimmed([_reduce(c, modulus) for c in second])
    if len(first) < len(second):
        first, second = second, first
    while second:
        second = _monic(second, modulus)
        first, second = second, _remainder(first, second, modulus)
    return _monic(first, modulus) if first else []


def square_free_over_field(polynomial: FieldPolynomial, field: flint.fmpz_poly) -> FieldPolynomial:
    """``polynomial`` / gcd(polynomial, its derivative in v), monic: the same roots, each
    simple (characteristic 0)."""
    modulus = flint.fmpq_poly(field)
    if field.degree() == 1:
        polynomial = _over_q(polynomial)
        part = polynomial / polynomial.gcd(polynomial.derivative())
        return _monic([flint.fmpq_poly([c]) for c in part.coeffs()], modulus)
    derivative = _trimmed([c * k for k, c in enumerate(polynomial)][1:])
    common = gcd_over_field(polynomial, derivative, field)
    if len(common) <= 1:
        return _monic(polynomial, modulus)
    quotient: list = []
    _remainder(_monic(polynomial, modulus), common, modulus, quotient)
    return quotient[::-1]


#: Precisions (bits) at which the numerical path tries to isolate a column's roots.
ISOLATION_BITS = (256, 1024, 4096)


@dataclass(frozen=True)
class Fiber:
    """The common points of two curves above the roots of an irreducible ``field`` f.

    Either ``common`` is set — h, monic and square-free over K = Q[u]/(f), whose roots at
    each root u* of f are exactly the common points (``[]``: the curves share the vertical
    line u = u*; a constant: no finite common point) — or ``columns`` is: the two columns
    over K, the first of them certified square-free (its roots were isolated at one root
    of f, so it is square-free over K ≅ Q(u*) and at every conjugate root), and the common
    points are its roots at which the second column's ball contains 0 (complete; a
    root of the first column near but not on the second curve can pass, and is then
    ruled out or confirmed by the branch test)."""

    field: flint.fmpz_poly
    common: FieldPolynomial | None = None
    columns: tuple[FieldPolynomial, FieldPolynomial] | None = None

    @property
    def exact(self) -> bool:
        return self.common is not None

    def points(self, u: flint.acb) -> list[flint.acb] | None:
        """The common roots v above the root u* of f enclosed by ``u`` (a ball), isolated
        at the current precision; None if that precision does not separate them (raise
        it). Raises ValueError where the curves share the line u = u*."""
        if self.common is None:
            first, second = self.columns
            roots = isolated_roots(first, u)
            if roots is None:
                return None
            at_second = _at(second, u)
            return [v for v in roots if at_second(v).contains(0)]
        if not self.common:
            raise ValueError("the two curves share the line above this root: infinitely many common points")
        return isolated_roots(self.common, u)


def _at(polynomial: FieldPolynomial, u: flint.acb) -> flint.acb_poly:
    """The polynomial in v with its coefficients (elements of K) evaluated at ``u``."""
    return flint.acb_poly([flint.acb_poly(element)(u) for element in polynomial])


def isolated_roots(polynomial: FieldPolynomial, u: flint.acb) -> list[flint.acb] | None:
    """The roots in v of ``polynomial`` (coefficients in K) at the root of f enclosed by
    ``u``, refined to about half the working precision; None where flint cannot isolate
    them at this precision (a ball too wide, or a multiple root)."""
    if len(polynomial) <= 1:
        return []
    bits = flint.ctx.prec
    try:
        return _at(polynomial, u).roots(tol=flint.arb(2) ** (-bits // 2), maxprec=4 * bits)
    except ValueError:
        return None


def common_fiber(curves: Sequence[flint.fmpz_mpoly], field: flint.fmpz_poly) -> Fiber:
    """The :class:`Fiber` of ``curves`` = (G_1, G_2) above the roots of the irreducible
    polynomial ``field`` in u. A rational root (deg f = 1) is treated exactly in Q[v]. For
    deg f > 1 the columns are first isolated numerically at one root of f (a column
    whose roots separate is square-free over K, which certifies the numerical path);
    only if neither column separates at ISOLATION_BITS is the gcd taken over K (exact,
    but its coefficients grow: minutes for a 57th-degree field).

    >>> from baranov.solvers.exact.coupling_two import PLANE
    >>> u, v = PLANE.gens()
    >>> fiber = common_fiber([(v - 1)**2 + (u - 2)**2, v**2 - 1 + u - 2], flint.fmpz_poly([-2, 1]))
    >>> fiber.exact, [str(root.real.mid()) for root in fiber.points(flint.acb(2))]
    (True, ['1.00000000000000'])
    """
    columns = [column_over_field(curve, field) for curve in curves]
    if field.degree() > 1 and all(columns):
        root = None
        previous = flint.ctx.prec
        try:
            for bits in ISOLATION_BITS:
                flint.ctx.prec = bits
                root = complex_roots(field)[0][0]
                for first, second in (columns, columns[::-1]):
                    if isolated_roots(first, root) is not None:
                        return Fiber(field, columns=(first, second))
        finally:
            flint.ctx.prec = previous
    common = gcd_over_field(columns[0], columns[1], field)
    return Fiber(field, common=square_free_over_field(common, field) if len(common) > 2 else common)
