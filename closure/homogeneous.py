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
        return cls._of_parts(re, im, ring)

    @classmethod
    def _of_parts(cls, re, im, ring: dict) -> Homogeneous:
        return cls(re, im, ring.get("constant", lambda v: v)(1), **ring)

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


class FieldComplex(Homogeneous):
    """(x + iy)/w over a field, kept at w = 1: one division per quotient, where
    :class:`Homogeneous` with a ``reduce`` that divides through multiplied weights and
    divided twice after every operation (the complex balls of the exact backend's
    placements: x and y complex balls each, since a complex parameter gives complex
    coordinates).

    >>> a, b = FieldComplex.of(3 + 4j), FieldComplex.of(1 - 2j)
    >>> complex(a * b), complex(a / b), complex(a - b), complex(a.conjugate())
    ((11-2j), (-1+2j), (2+6j), (3-4j))
    """

    __slots__ = ()

    def __init__(self, x, y, w=None, multiply: Callable[[Any, Any], Any] = operator.mul,
                 constant: Callable[[Any], Any] = lambda value: value, reduce: Callable | None = None):
        if w is not None:  # a triple from elsewhere: divided through once
            x, y = x / w, y / w
        self.x, self.y = x, y
        self.multiply, self.constant, self.reduce = multiply, constant, None

    @property
    def w(self):
        """1 in the field (made when read: the constant of every number made cost as much
        as its arithmetic)."""
        return self.constant(1)

    @classmethod
    def _of_parts(cls, re, im, ring: dict) -> FieldComplex:
        return cls(re, im, None, **ring)

    def _new(self, x, y, w=None) -> FieldComplex:
        made = object.__new__(FieldComplex)
        made.x, made.y = x, y
        made.multiply, made.constant, made.reduce = self.multiply, self.constant, None
        return made

    def _lift(self, other) -> FieldComplex:
        if type(other) is FieldComplex:
            return other
        if isinstance(other, Homogeneous):  # a triple from elsewhere
            return FieldComplex(other.x, other.y, other.w, self.multiply, self.constant)
        return FieldComplex.of(other, multiply=self.multiply, constant=self.constant)

    def __add__(self, other) -> FieldComplex:
        other = self._lift(other)
        return self._new(self.x + other.x, self.y + other.y)

    __radd__ = __add__

    def __neg__(self) -> FieldComplex:
        return self._new(-self.x, -self.y)

    def __sub__(self, other) -> FieldComplex:
        other = self._lift(other)
        return self._new(self.x - other.x, self.y - other.y)

    def __mul__(self, other) -> FieldComplex:
        other = self._lift(other)
        return self._new(self.x * other.x - self.y * other.y, self.x * other.y + self.y * other.x)

    __rmul__ = __mul__

    def conjugate(self) -> FieldComplex:
        return self._new(self.x, -self.y)

    @property
    def real(self) -> FieldComplex:
        return self._new(self.x, self.constant(0))

    @property
    def imag(self) -> FieldComplex:
        return self._new(self.y, self.constant(0))

    def __truediv__(self, other) -> FieldComplex:
        other = self._lift(other)
        modulus = other.x * other.x + other.y * other.y
        return self._new((self.x * other.x + self.y * other.y) / modulus, (self.y * other.x - self.x * other.y) / modulus)
