"""Common points of two plane curves above the roots of an irreducible polynomial
(solvers/exact/fibers.py), the step that lost issue 28's mode."""

from __future__ import annotations

import flint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.solvers.exact.coupling_two import PLANE
from baranov.solvers.exact.fibers import common_fiber, gcd_over_field, square_free_over_field

U, V = PLANE.gens()


def real_points(fiber, root) -> list[float]:
    flint.ctx.prec = 256
    try:
        return sorted(float(v.real.mid()) for v in fiber.points(root))
    finally:
        flint.ctx.prec = 53


def test_a_double_root_in_both_columns_is_found_exactly():
    """Both curves have the factor (v - 1)² above u = 25, as in issue 28: certified root
    isolation of either column fails there, the gcd does not."""
    first = (V - 1) ** 2 * (V + 3) + (U - 25) * (V**3 + 7)
    second = (V - 1) ** 2 * (V - 5) + (U - 25) ** 2 * V
    fiber = common_fiber([first, second], flint.fmpz_poly([-25, 1]))
    assert fiber.exact
    assert real_points(fiber, flint.acb(25)) == [1.0]


def test_a_root_at_infinity_is_dropped_exactly():
    """The leading coefficient of the first curve in v vanishes at u = 2: the column has
    degree 1 there, exactly, and the common point v = -1/2 is found."""
    first = (U - 2) * V**2 + 2 * V + 1
    second = 2 * V + 1 + (U - 2) * V**3
    fiber = common_fiber([first, second], flint.fmpz_poly([-2, 1]))
    assert real_points(fiber, flint.acb(2)) == [-0.5]


def test_algebraic_roots_use_the_certified_numerical_path_or_the_field():
    """Above each root α = ±√2 of u² − 2, the curves v² − 2 and v − u share the one
    point v = α."""
    fiber = common_fiber([V**2 - 2, V - U], flint.fmpz_poly([-2, 0, 1]))
    flint.ctx.prec = 256
    try:
        for root, _ in flint.fmpz_poly([-2, 0, 1]).complex_roots():
            points = fiber.points(root)
            assert len(points) == 1 and abs(complex(points[0]) - complex(root)) < 1e-30
    finally:
        flint.ctx.prec = 53


def test_shared_vertical_line_is_refused():
    fiber = common_fiber([(U - 3) * (V + 1), (U - 3) * (V - 7)], flint.fmpz_poly([-3, 1]))
    with pytest.raises(ValueError, match="infinitely many"):
        fiber.points(flint.acb(3))


@settings(max_examples=40, deadline=None)
@given(roots=st.lists(st.integers(-9, 9), min_size=1, max_size=5), extra=st.integers(-9, 9),
       field=st.sampled_from([[-2, 0, 1], [-3, 0, 1], [1, 1, 1], [-2, 0, 0, 1]]))
def test_gcd_over_a_number_field_is_the_common_part(roots, extra, field):
    """gcd((v − α)·Π(v − r)², (v − α)(v − extra)) over Q(α) = v − α (times v − extra when
    it is a root too): the common part whatever the multiplicities; square-free parts
    drop the repeats."""
    modulus = flint.fmpz_poly(field)
    alpha = [-flint.fmpq_poly([0, 1]), flint.fmpq_poly([1])]  # v − α, coefficients in K

    def times(first, second):
        product = [flint.fmpq_poly([0])] * (len(first) + len(second) - 1)
        for i, a in enumerate(first):
            for j, b in enumerate(second):
                product[i + j] = (product[i + j] + a * b) % flint.fmpq_poly(modulus)
        return product

    first = alpha
    for r in roots:
        first = times(first, times([flint.fmpq_poly([-r]), flint.fmpq_poly([1])],
                                   [flint.fmpq_poly([-r]), flint.fmpq_poly([1])]))
    second = times(alpha, [flint.fmpq_poly([-extra]), flint.fmpq_poly([1])])
    common = gcd_over_field(first, second, modulus)
    expected_degree = 1 + (extra in roots)
    assert len(common) - 1 == expected_degree
    assert len(square_free_over_field(first, modulus)) - 1 == 1 + len(set(roots))
