"""Numbers of a scene: exact rationals (integers, decimals, fractions as users write them)
or binary floats, and the exact square root where one exists."""

from __future__ import annotations

import math
from fractions import Fraction

#: A dimension or coordinate: exact where the input is.
Number = Fraction | float


def rational_sqrt(value: Number) -> Fraction | None:
    """√value if it is rational (a nonnegative Fraction whose numerator and denominator
    are squares), else None.

    >>> rational_sqrt(Fraction(9, 4)), rational_sqrt(Fraction(2)), rational_sqrt(2.25)
    (Fraction(3, 2), None, None)
    """
    if not isinstance(value, Fraction) or value < 0:
        return None
    numerator, denominator = math.isqrt(value.numerator), math.isqrt(value.denominator)
    if numerator**2 != value.numerator or denominator**2 != value.denominator:
        return None
    return Fraction(numerator, denominator)
