"""Complex numbers as homogeneous triples over a ring with no division.

The exact radical tower (``solvers/exact/characteristic.py``) has sums and products only;
the kernel's points are already triples (x, y, w) standing for (x + iy)/w
(:mod:`.bilateration`). :class:`Homogeneous` gives such triples the operators of a complex
number — ``+ − × /``, ``conjugate()``, ``.real``, ``.imag`` — so that a construction written
once for Python or numpy complex numbers (the slider constructions of :mod:`.sliders`)
runs unchanged in the tower, as python-flint runs one formula over several number types.
A quotient multiplies by the divisor's conjugate and keeps the squared modulus as the
new weight; the caller reduces common factors (``reduce``) where its ring has a gcd.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from fractions import Fraction
from typing import Any


class Homogeneous:
    """(x + iy)/w with x, y, w in a ring whose product is ``multiply`` (the tower's keeps
    normal form) and whose constants are made by ``constant``.

    >>> a, b = Homogeneous.of(3 + 4j), Homogeneous.of(1 - 2j)
    >>> complex(a * b), complex(a / b), complex(a.conjugate()), complex(a.imag)
    ((11-2j), (-1+2j), (3-4j), (4+0j))
    """

    __slots__ = ("x", "y", "w", "multiply", "constant", "reduce")

    def __init__(self, x, y, w, multiply: Callable[[Any, Any], Any] = operator.mul,
                 constant: Callable[[Any], Any] = lambda value: value, reduce: Callable | None = None):
        self.x, self.y, self.w = x, y, w
        self.multiply, self.constant, self.reduce = multiply, constant, reduce

    @classmethod
    def of(cls, value, **ring) -> Homogeneous:
        """A constant: a Python number (complex, float, int, Fraction), a pair (re, im) of
        them, or an element of the ring itself (real)."""
        constant = ring.get("constant", lambda v: v)
        if isinstance(value, tuple):
            re, im = (constant(part) for part in value)
        elif isinstance(value, (int, float, complex, Fraction)):
            re, im = constant(value.real), constant(value.imag)
        else:
            re, im = value, constant(0)
        return cls(re, im, constant(1), **ring)

    def _new(self, x, y, w) -> Homogeneous:
        made = Homogeneous(x, y, w, self.multiply, self.constant, self.reduce)
        return made if self.reduce is None else self.reduce(made)

    def _lift(self, other) -> Homogeneous:
        if isinstance(other, Homogeneous):
            return other
        return Homogeneous.of(other, multiply=self.multiply, constant=self.constant, reduce=self.reduce)

    def __add__(self, other) -> Homogeneous:
        other, m = self._lift(other), self.multiply
        return self._new(m(self.x, other.w) + m(other.x, self.w), m(self.y, other.w) + m(other.y, self.w),
                         m(self.w, other.w))

    __radd__ = __add__

    def __neg__(self) -> Homogeneous:
        return self._new(-self.x, -self.y, self.w)

    def __sub__(self, other) -> Homogeneous:
        return self + (-self._lift(other))

    def __rsub__(self, other) -> Homogeneous:
        return self._lift(other) - self

    def __mul__(self, other) -> Homogeneous:
        other, m = self._lift(other), self.multiply
        return self._new(m(self.x, other.x) - m(self.y, other.y), m(self.x, other.y) + m(self.y, other.x),
                         m(self.w, other.w))

    __rmul__ = __mul__

    def __truediv__(self, other) -> Homogeneous:
        other, m = self._lift(other), self.multiply
        numerator = self * other.conjugate()  # (a/w)(c̄/z) over |c|²/z²: times z²/|c|²
        modulus = m(other.x, other.x) + m(other.y, other.y)
        return self._new(m(numerator.x, m(other.w, other.w)), m(numerator.y, m(other.w, other.w)),
                         m(numerator.w, modulus))

    def __rtruediv__(self, other) -> Homogeneous:
        return self._lift(other) / self

    def conjugate(self) -> Homogeneous:
        return self._new(self.x, -self.y, self.w)

    @property
    def real(self) -> Homogeneous:
        return self._new(self.x, self.constant(0), self.w)

    @property
    def imag(self) -> Homogeneous:
        return self._new(self.y, self.constant(0), self.w)

    def value(self) -> complex:
        """As a Python complex number (floats, Fractions, flint numbers that convert)."""
        return complex(complex(self.x) / complex(self.w) + 1j * complex(self.y) / complex(self.w))

    def __complex__(self) -> complex:
        return self.value()
