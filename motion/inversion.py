"""Kinematic inversion (thesis §6.3.1): the same configuration space seen with another link
fixed. A configuration does not depend on which link is fixed, only the frame it is drawn
in does: each configuration is moved by the rigid motion that brings the new fixed link's
first joint to the origin and its second onto the positive x axis, so the coupler curves
of every inversion come from one trace."""

from __future__ import annotations

import math
from dataclasses import replace

from baranov.scene import Scene

from .configuration_space import ConfigurationPoint
from .tracing import Trace


class InversionError(ValueError):
    """The link named to be fixed cannot be (the message says why)."""


def fixed_frame_joints(scene: Scene, link: str) -> tuple[str, str]:
    """The two joints of ``link`` that define its frame: its first two.

    Raises :class:`InversionError` naming the link if there is no such link."""
    for candidate in scene.links:
        if candidate.name == link:
            return candidate.joints[0], candidate.joints[1]
    names = ", ".join(candidate.name for candidate in scene.links)
    raise InversionError(f"link {link}: no such link to fix (links: {names})")


def in_frame(point: ConfigurationPoint, frame: tuple[str, str]) -> ConfigurationPoint:
    """``point`` moved rigidly so that ``frame``'s first joint is at the origin and its
    second on the positive x axis. O(joints)."""
    (ax, ay), (bx, by) = point.joints[frame[0]], point.joints[frame[1]]
    angle = math.atan2(by - ay, bx - ax)
    c, s = math.cos(angle), math.sin(angle)
    joints = {name: (c * (x - ax) + s * (y - ay), -s * (x - ax) + c * (y - ay)) for name, (x, y) in point.joints.items()}
    return replace(point, joints=joints)


def inverted(traced: Trace, scene: Scene, link: str) -> Trace:
    """``traced`` with ``link`` fixed instead of the scene's ground: every configuration of
    every piece in ``link``'s frame (:func:`in_frame`); the pieces, their sign vectors and
    the branch points are the same. O(points × joints)."""
    frame = fixed_frame_joints(scene, link)
    pieces = tuple(replace(piece, points=tuple(in_frame(point, frame) for point in piece.points))
                   for piece in traced.pieces)
    return replace(traced, pieces=pieces)
