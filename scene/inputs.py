"""Inputs of a linkage with mobility F > 0: the quantities a user drives (a crank angle,
an actuator's stroke), named so that a sweep or a trace can set them.

In the distance-based formulation every input is a squared distance between two joints
(thesis §6.1: a one-DOF chain is traced in a space of squared distances, and rigidified
at an input it becomes a rigid chain of the kind the backends solve):

- a **distance** input drives the squared distance s_{u,v} of two joints on no common
  link;
- an **angle** input drives the angle θ at a joint P_a between the two links that meet
  there, measured counter-clockwise from P_a→P_f to P_a→P_t (P_f on one link, P_t on the
  other). By the law of cosines it is the squared distance
  s_{f,t} = s_{a,f} + s_{a,t} − 2 √(s_{a,f} s_{a,t}) cos θ together with the orientation
  of △P_a P_f P_t, the sign of sin θ (thesis §2.2: a distance fixes a triangle up to its
  orientation).

In a scene (JSON) an input is ``{"name": "crank", "angle": ["P1", "P2", "P3"],
"degrees": 30}`` (θ at P1 from P2 to P3) or ``{"name": "stroke", "distance": ["P2",
"P5"], "squared_distance": 20}``; the value may be left out (an input a sweep will set).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from .numbers import Number, rational_sqrt

#: The keys of an input in a scene.
INPUT_KEYS = ("name", "angle", "distance", "degrees", "squared_distance", "comment")


@dataclass(frozen=True)
class SceneInput:
    """One driven quantity of a mobile linkage (see the module docstring).

    Attributes
    ----------
    name
        the input's name, unique in its scene.
    kind
        ``"angle"`` or ``"distance"``.
    joints
        ``(a, f, t)`` for an angle at P_a from P_f to P_t; ``(u, v)`` for a
        distance.
    value
        degrees for an angle, a squared distance for a distance; ``None`` if not
        given.
    """

    name: str
    kind: str
    joints: tuple[str, ...]
    value: Number | None = None

    @property
    def driven_pair(self) -> tuple[str, str]:
        """The two joints whose squared distance the input sets: (f, t) or (u, v)."""
        return (self.joints[1], self.joints[2]) if self.kind == "angle" else (self.joints[0], self.joints[1])


def angle_as_distance(at_from: Number, at_to: Number, degrees: Number) -> tuple[Number, int]:
    """The squared distance s_{f,t} and the orientation (+1 counter-clockwise, −1
    clockwise, 0 flat) of △P_a P_f P_t for the angle θ (degrees) at P_a from P_f to P_t,
    given s_{a,f} = ``at_from`` and s_{a,t} = ``at_to``: the law of cosines,
    s_{f,t} = s_{a,f} + s_{a,t} − 2 √(s_{a,f} s_{a,t}) cos θ. Exact (a Fraction) where θ
    is a multiple of 90° and, for 0° and 180°, √(s_{a,f} s_{a,t}) is rational.

    >>> angle_as_distance(Fraction(9), Fraction(16), Fraction(90))
    (Fraction(25, 1), 1)
    >>> angle_as_distance(Fraction(9), Fraction(16), Fraction(180))
    (Fraction(49, 1), 0)
    >>> round(angle_as_distance(1.0, 1.0, -60.0)[0], 12), angle_as_distance(1.0, 1.0, -60.0)[1]
    (1.0, -1)
    """
    turns = Fraction(degrees) / 90 if isinstance(degrees, Fraction) else None
    if turns is not None and turns.denominator == 1:
        quarter = int(turns) % 4  # θ = 0°, 90°, 180°, 270°: cos θ = 1, 0, −1, 0
        cosine, sine = ((1, 0), (0, 1), (-1, 0), (0, -1))[quarter]
        product = Fraction(at_from) * Fraction(at_to) if isinstance(at_from, Fraction) and isinstance(at_to, Fraction) else None
        root = rational_sqrt(product) if product is not None and cosine else Fraction(0)
        if root is not None:
            return at_from + at_to - 2 * cosine * root, sine
    radians = math.radians(float(degrees))
    squared = float(at_from) + float(at_to) - 2 * math.sqrt(float(at_from) * float(at_to)) * math.cos(radians)
    sine = math.sin(radians)
    return max(squared, 0.0), (sine > 0) - (sine < 0)
