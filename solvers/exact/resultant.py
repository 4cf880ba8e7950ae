"""Resultants of bivariate integer polynomials by evaluation, interpolation and the
Chinese remainder theorem.

Eliminating the second parameter of a coupling-2 chain takes Res_v(F, G) of two bivariate
polynomials with coefficients of hundreds of bits and degrees ~30–70 in each variable
(thesis §3.4.1.3: for 9/B28 "a resultant of degree 1826"). Over Z, flint's
``fmpz_mpoly.resultant`` did not finish on 9/B28 in 15 minutes; modulo a word-size prime
the resultant is cheap, so it is computed modulo enough primes and lifted:

* modulo p, F(a, v) and G(a, v) are univariate in v for each of deg_u R + 1 random points
  a (every coefficient in v evaluated at all points by one matrix product), their
  resultants R(a) are taken (flint ``nmod_poly.resultant``) and R is interpolated
  (subproduct tree); the first image's degree sets the number of points for the others;
* the images are combined by the Chinese remainder theorem into symmetric residues, until
  two more primes leave every coefficient unchanged;
* the result is checked against the resultant over Z at random integer points (a wrong
  R would agree at a random point with negligible probability).

Cost: O(deg_u(R) · (deg_v F + deg_v G)²) word operations per prime, and about
(coefficient bits of R) / 62 primes.
"""

from __future__ import annotations

import random
from itertools import accumulate

import flint

from .lifting_by_primes import chinese_remainder

#: The primes used are the ones just below 2^62, in decreasing order.
_PRIME_START = (1 << 62) - 1


def _primes():
    candidate = _PRIME_START
    while True:
        candidate -= 2
        if flint.fmpz(candidate).is_prime():
            yield candidate


def coefficients_in_v(polynomial) -> list[dict[int, int]]:
    """``polynomial`` (flint ``fmpz_mpoly`` or ``nmod_mpoly`` in its last two generators
    u, v) as its coefficients in v: {power of u: integer or residue}."""
    columns: dict[int, dict[int, int]] = {}
    for exponents, coefficient in zip(polynomial.monoms(), polynomial.coeffs(), strict=True):
        columns.setdefault(exponents[-1], {})[exponents[-2]] = int(coefficient)
    return [columns.get(k, {}) for k in range(max(columns) + 1)]


def _subproduct_tree(points: list, context: flint.fmpz_mod_poly_ctx) -> list[list]:
    """Levels of the products Π (x − a) over halves, quarters, …, leaves first."""
    x = context.gen()
    level = [x - a for a in points]
    tree = [level]
    while len(level) > 1:
        level = [level[i] * level[i + 1] if i + 1 < len(level) else level[i] for i in range(0, len(level), 2)]
        tree.append(level)
    return tree


def _lagrange_nodes(points: list, context: flint.fmpz_mod_poly_ctx) -> tuple[list[list], list]:
    """What interpolation at ``points`` needs whatever the values: the subproduct tree and
    the derivative of Π (x − a) at each point (shared by the resultants interpolated at
    the same points: building them once per prime saved 8 % of a coupling-2 exact solve)."""
    tree = _subproduct_tree(points, context)
    return tree, tree[-1][0].derivative().multipoint_evaluate(points)


def _interpolate(values: list, nodes: tuple[list[list], list], context: flint.fmpz_mod_poly_ctx):
    """The polynomial of degree < len(values) through the points of ``nodes``
    (:func:`_lagrange_nodes`) and ``values`` modulo the context's prime (fast Lagrange
    interpolation on the subproduct tree)."""
    tree, derivatives = nodes
    weights = [value / d for value, d in zip(values, derivatives, strict=True)]
    level = [context([w]) for w in weights]
    for depth in range(len(tree) - 1):
        products = tree[depth]
        level = [level[i] * products[i + 1] + level[i + 1] * products[i] if i + 1 < len(level) else level[i]
                 for i in range(0, len(level), 2)]
    return level[0]


def resultants_modulo(columns_f, columns_others: list, degrees: list[int], prime: int,
                      rng: random.Random) -> list[list[int]] | None:
    """Coefficients of Res_v(F, G_k) modulo ``prime`` for several G_k (columns: the
    coefficients in v as {power of u: integer}), Res_v(F, G_k) of degree ≤ ``degrees[k]``
    in u, from their values at max(degrees) + 1 random points (each interpolated from
    the first degrees[k] + 1); None if a leading coefficient in v vanishes at one of them.

    Every coefficient in v of every polynomial is evaluated at all points by one matrix
    product (Vandermonde · coefficients, flint ``nmod_mat``): 12 times faster on 9/B28
    than a multipoint evaluation per coefficient; the points, the Vandermonde matrix and
    F's values are shared by all the resultants."""
    context = flint.fmpz_mod_poly_ctx(prime)
    points = rng.sample(range(1, prime), max(degrees) + 1)
    groups = [columns_f, *columns_others]
    columns = [column for group in groups for column in group]
    powers = 1 + max(max(column, default=0) for column in columns)
    vandermonde = []
    for a in points:
        row, value = [], 1
        for _ in range(powers):
            row.append(value)
            value = value * a % prime
        vandermonde += row
    coefficients = [column.get(k, 0) % prime for k in range(powers) for column in columns]
    values_at = (flint.nmod_mat(len(points), powers, vandermonde, prime)
                 * flint.nmod_mat(powers, len(columns), coefficients, prime)).entries()
    width = len(columns)
    bounds = [0, *accumulate(len(group) for group in groups)]
    values: list[list[int]] = [[] for _ in columns_others]
    for index in range(len(points)):
        row = values_at[index * width:(index + 1) * width]
        # from the nmod entries as they are: converting each to int first cost 12 times more
        polynomials = [flint.nmod_poly(row[start:stop], prime) for start, stop in zip(bounds, bounds[1:], strict=False)]
        if any(p.degree() != len(group) - 1 for p, group in zip(polynomials, groups, strict=True)):
            return None  # a leading coefficient vanishes at this point: take other points
        for k, other in enumerate(polynomials[1:]):
            if index <= degrees[k]:
                values[k].append(int(polynomials[0].resultant(other)))
    images, nodes = [], {}
    for degree, image_values in zip(degrees, values, strict=True):
        if degree not in nodes:
            nodes[degree] = _lagrange_nodes(points[:degree + 1], context)
        coefficients = [int(c) for c in _interpolate(image_values, nodes[degree], context).coeffs()]
        images.append(coefficients + [0] * (degree + 1 - len(coefficients)))
    return images


def resultant_by_primes(f: flint.fmpz_mpoly, g: flint.fmpz_mpoly, degree: int,
                        checks: int = 2, seed: int = 0) -> flint.fmpz_poly:
    """Res_v(f, g) for bivariate integer polynomials in (u, v) (lex context with exactly
    these two generators), a polynomial in u of degree at most ``degree`` (e.g. the
    Bézout bound deg_u f · deg_v g + deg_v f · deg_u g).

    >>> ctx = flint.fmpz_mpoly_ctx.get(("u", "v"), "lex")
    >>> u, v = ctx.gens()
    >>> resultant_by_primes(v**2 - u, v - 3 * u + 1, 2)  # (3u - 1)² - u
    9*x^2 + (-7)*x + 1
    """
    columns_f, columns_g = coefficients_in_v(f), coefficients_in_v(g)
    rng = random.Random(seed)
    residues = [0] * (degree + 1)
    modulus, stable, previous = 1, 0, None
    for prime in _primes():
        images = resultants_modulo(columns_f, [columns_g], [degree], prime, rng)
        if images is None:
            continue
        image = images[0]
        if modulus == 1:  # the first image's degree (R's, unless p divides its leading
            # coefficient, which the check over Z below would catch) saves points
            degree = max((k for k, c in enumerate(image) if c), default=0)
            residues, image = residues[:degree + 1], image[:degree + 1]
        residues = chinese_remainder(residues, modulus, image, prime)
        modulus *= prime
        half = modulus // 2
        symmetric = [r - modulus if r > half else r for r in residues]
        stable = stable + 1 if symmetric == previous else 0
        previous = symmetric
        if stable == 2:
            break
    result = flint.fmpz_poly(previous)
    for _ in range(checks):
        a = rng.randrange(-10**6, 10**6)
        left = _at(f, a).resultant(_at(g, a))
        if left != result(a):
            raise ArithmeticError(f"modular resultant disagrees with the resultant over Z at u = {a}")
    return result


def _at(polynomial: flint.fmpz_mpoly, a: int) -> flint.fmpz_poly:
    """``polynomial`` with u = a, as a polynomial in v."""
    return flint.fmpz_poly([sum(c * a**k for k, c in column.items()) for column in coefficients_in_v(polynomial)])
