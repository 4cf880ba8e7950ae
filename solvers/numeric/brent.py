"""Brent's one-dimensional searches as lock-step searches (:mod:`.lockstep`): a root in
a bracket and a bounded minimum, each asking for one point at a time, so that the
brackets and minima of every sign branch advance together, one kernel evaluation per
step for all of them.

They are the algorithms scipy's ``brentq`` and ``minimize_scalar(method="bounded")``
implement (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 4
"zero" and ch. 5 "fmin"), with the same stopping rules; a caller that evaluates one
point at a time gets what scipy gives, to within the tolerance.

>>> import numpy as np
>>> from baranov.solvers.numeric.lockstep import run_alone
>>> cubic = lambda points, signs: points ** 3 - 2 * points - 5  # Newton's example
>>> root = run_alone(brent_root(2.0, 3.0, -1.0, 16.0, lambda reply: float(reply[0]), 1e-15, 1e-15),
...                  cubic, np.zeros(1))
>>> round(root, 12)
2.094551481542
>>> x, value, success = run_alone(brent_minimum(lambda reply: float(abs(reply[0] - 1)), 0.0, 5.0, 1e-12),
...                               cubic, np.zeros(1))
>>> round(x, 6), success  # |x³ − 2x − 6| is 0 at the cubic's real root
(2.179981, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .lockstep import Samples

EPSILON = 2.0 ** -52


class UndefinedInside(ValueError):
    """The function is undefined (NaN) at a point Brent's method asked for: the bracket
    holds a gap of the feasible domain."""


def _at(x: float, signs: np.ndarray | None = None) -> Samples:
    """The request for f at the one point x."""
    return Samples(np.array([x]), signs)


def brent_root(a: float, b: float, fa: float, fb: float, value: Callable[[Any], float], xtol: float,
               rtol: float, maxiter: int = 200):
    """Lock-step search: a root of f in [a, b] given f(a) fa and f(b) fb of opposite
    signs, by Brent's method (inverse quadratic interpolation, secant, bisection;
    Brent 1973 ch. 4), to within (xtol + rtol |x|)/2; ``value`` reads f from the reply
    to one point. Raises :class:`UndefinedInside` where f is NaN. At most ``maxiter``
    evaluations."""
    if fa == 0:
        return a
    if fb == 0:
        return b
    c, fc = a, fa
    d = e = b - a
    for _ in range(maxiter):
        if abs(fc) < abs(fb):  # b the best estimate, c the other end of the bracket
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tolerance = (xtol + rtol * abs(b)) / 2
        middle = (c - b) / 2
        if fb == 0 or abs(middle) < tolerance:
            return b
        if abs(e) >= tolerance and abs(fa) > abs(fb):
            d, e = _interpolated_step(a, b, c, fa, fb, fc, d, e, middle, tolerance)
        else:
            d = e = middle
        a, fa = b, fb
        b += d if abs(d) > tolerance else math.copysign(tolerance, middle)
        fb = value((yield _at(b)))
        if math.isnan(fb):
            raise UndefinedInside(f"the function is undefined at {b!r}")
        if (fb > 0) == (fc > 0):  # the root lies between a and b: a becomes the other end
            c, fc = a, fa
            d = e = b - a
    return b


def _interpolated_step(a, b, c, fa, fb, fc, d, e, middle, tolerance) -> tuple[float, float]:
    """Brent's interpolation step (secant when a = c, else inverse quadratic), or
    bisection where the step is not safe; returns (d, e)."""
    s = fb / fa
    if a == c:
        p, q = 2 * middle * s, 1 - s
    else:
        q, r = fa / fc, fb / fc
        p = s * (2 * middle * q * (q - r) - (b - a) * (r - 1))
        q = (q - 1) * (r - 1) * (s - 1)
    if p > 0:
        q = -q
    else:
        p = -p
    if 2 * p < 3 * middle * q - abs(tolerance * q) and p < abs(e * q / 2):
        return p / q, d
    return middle, middle


GOLDEN = (3 - math.sqrt(5)) / 2


def brent_minimum(objective: Callable[[Any], float], low: float, high: float, xatol: float,
                  maxiter: int = 500, signs: np.ndarray | None = None):
    """Lock-step search: (x, objective(x), success) for a local minimum of the objective
    in [low, high], by Brent's method (golden section and parabolic interpolation; Brent
    1973 ch. 5, the rules of scipy's bounded ``minimize_scalar``); ``objective`` reads
    the value from the reply to one point (on ``signs`` if given). ``success`` is False
    after ``maxiter`` evaluations or where a value is NaN."""
    sqrt_eps = math.sqrt(2.2e-16)
    a, b = low, high
    x = w = v = a + GOLDEN * (b - a)
    fx = objective((yield _at(x, signs)))
    fw = fv = fx
    d = e = 0.0
    fu = math.inf
    evaluations = 1
    while True:
        middle = (a + b) / 2
        tolerance = sqrt_eps * abs(x) + xatol / 3
        if abs(x - middle) <= 2 * tolerance - (b - a) / 2:
            break
        d, e = _minimum_step(a, b, x, w, v, fx, fw, fv, d, e, middle, tolerance)
        u = x + math.copysign(max(abs(d), tolerance), d if d != 0 else 1.0)
        fu = objective((yield _at(u, signs)))
        evaluations += 1
        if fu <= fx:
            a, b = (x, b) if u >= x else (a, x)
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            a, b = (u, b) if u < x else (a, u)
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v == x or v == w:
                v, fv = u, fu
        if evaluations >= maxiter:
            return x, fx, False
    success = not (math.isnan(x) or math.isnan(fx) or math.isnan(fu))
    return x, fx, success


def _minimum_step(a, b, x, w, v, fx, fw, fv, d, e, middle, tolerance) -> tuple[float, float]:
    """Brent's next step from x: parabolic through x, w, v where acceptable (inside the
    interval, smaller than half the step before last), else golden section; (d, e)."""
    if abs(e) > tolerance:
        r = (x - w) * (fx - fv)
        q = (x - v) * (fx - fw)
        p = (x - v) * q - (x - w) * r
        q = 2 * (q - r)
        if q > 0:
            p = -p
        q = abs(q)
        previous, e = e, d
        if abs(p) < abs(q * previous / 2) and q * (a - x) < p < q * (b - x):
            d = p / q
            if (x + d) - a < 2 * tolerance or b - (x + d) < 2 * tolerance:
                d = tolerance if middle >= x else -tolerance
            return d, e
    e = (a - x) if x >= middle else (b - x)
    return GOLDEN * e, e
