"""Tracer points: points attached to a link that are not joints (a coupler point), whose
paths a trace draws (thesis ch. 6: the coupler curve of a point of the coupler link).

In a scene (JSON) a tracer is ``{"name": "C", "link": "coupler", "at": [x, y]}``: the
point at (x, y) in the link's own frame — the frame its joints' coordinates are given in,
or, for a link given by squared distances (binary links too), the frame with its first
listed joint at the origin and its second on the +x axis (:mod:`~baranov.scene.model`).
It is stored frame-free, as the complex ratio λ + iμ = (z − z_a) / (z_b − z_a) of its
offset from the link's first two joints P_a, P_b, so that in any configuration

    C = P_a + λ (P_b − P_a) + μ J (P_b − P_a),

J the rotation by +90° (the point :func:`~baranov.motion.coupler_curve_degree` takes).
λ and μ are exact rationals where the link's frame is (integer or rational coordinates,
or distances whose triangle areas are rational).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction

from .numbers import Number

#: The keys of a tracer in a scene.
TRACER_KEYS = ("name", "link", "at", "comment")


@dataclass(frozen=True)
class TracerPoint:
    """A point of a link that is not a joint (see the module docstring).

    Attributes
    ----------
    name
        its name, unique among the scene's joints and tracers.
    link
        the link it is attached to.
    along
        λ, its offset along P_a → P_b in units of ``|P_a P_b|`` (P_a, P_b the link's
        first two joints).
    across
        μ, its offset to the left of P_a → P_b in the same unit.
    """

    name: str
    link: str
    along: Number
    across: Number

    def position(self, first: tuple[float, float], second: tuple[float, float]) -> tuple[float, float]:
        """The point's coordinates when the link's first two joints are at ``first`` and
        ``second``. O(1).

        >>> TracerPoint("C", "coupler", Fraction(1, 2), Fraction(1, 2)).position((0.0, 0.0), (2.0, 0.0))
        (1.0, 1.0)
        """
        dx, dy = second[0] - first[0], second[1] - first[1]
        along, across = float(self.along), float(self.across)
        return first[0] + along * dx - across * dy, first[1] + along * dy + across * dx


def tracer_from_frame(name: str, link: str, at: tuple[Number, Number], first: tuple[Number, Number],
                      second: tuple[Number, Number]) -> TracerPoint:
    """The tracer at ``at`` in a frame where the link's first two joints are at ``first``
    and ``second``: λ + iμ = (z − z_a) / (z_b − z_a), exact if all are rationals. O(1).

    >>> tracer_from_frame("C", "coupler", (Fraction(3), Fraction(2)), (Fraction(0), Fraction(0)), (Fraction(6), Fraction(0)))
    TracerPoint(name='C', link='coupler', along=Fraction(1, 2), across=Fraction(1, 3))
    """
    x, y = at[0] - first[0], at[1] - first[1]
    dx, dy = second[0] - first[0], second[1] - first[1]
    norm = dx * dx + dy * dy
    return TracerPoint(name, link, (x * dx + y * dy) / norm, (y * dx - x * dy) / norm)


def tracer_positions(tracers: tuple[TracerPoint, ...], link_joints: Mapping[str, tuple[str, ...]],
                     joints: Mapping[str, tuple[float, float]]) -> dict[str, tuple[float, float]]:
    """Every tracer's coordinates in a configuration ``joints`` (joint name → (x, y)),
    ``link_joints`` naming each link's joints in order. O(tracers)."""
    return {tracer.name: tracer.position(joints[link_joints[tracer.link][0]], joints[link_joints[tracer.link][1]])
            for tracer in tracers}


def exact_ratio(tracer: TracerPoint) -> tuple[Fraction, Fraction] | None:
    """(λ, μ) as rationals, or None where the link's frame is not rational."""
    if isinstance(tracer.along, Fraction) and isinstance(tracer.across, Fraction):
        return tracer.along, tracer.across
    return None
