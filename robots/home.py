"""Any of the 21 legs described by its home configuration, and the locked leg it becomes
(thesis §5.2: with its actuator locked, a leg is one rigid link whose two passive joints,
revolute or prismatic, join it to the base and to the platform).

A leg's *home configuration* places its three joints in the world frame with the
platform frame on the world frame: a revolute joint by its centre, a prismatic joint by
a point of its axis and the axis direction. The actuator value is the actuated joint's
displacement from home: an angle in radians (counter-clockwise) for a revolute joint, an
offset in length units along its direction for a prismatic one. Any line along a
prismatic joint's direction is an axis of it (a translation along the direction keeps
every such line), so its point only places the slider's points in the locked scene.

With the actuator at ``value``, the joints after the actuated one move with it by the
rigid motion M of that joint; the platform frame is then M (the passive joints stay at
home, so the leg is one assembly of itself). The passive joint on the base side is read
in the world frame, the one on the platform side in the platform frame (M⁻¹ of its world
place), and the leg link between them keeps their relative place. Exact (Fractions)
where the home data are and the motion is: a prismatic offset along a direction of
rational length; a rotation is in floats.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from baranov.scene.numbers import rational_sqrt

from .legs import Leg, RobotInputError
from .model import HomeJoint, Point, to_number


@dataclass(frozen=True)
class LockedJoint:
    """A passive joint of a locked leg: its centre (revolute) or a point of its axis and
    the axis direction (prismatic), in the world frame (base side) or the platform frame
    (platform side)."""

    point: Point
    direction: Point | None = None


@dataclass(frozen=True)
class LockedLeg:
    """A locked leg: its passive joint on the base (world frame), its passive joint on the
    platform (platform frame), and the leg link's geometry: the latter joint as placed in
    the world at the leg's configuration (the link holds it and ``base``), or for a leg of
    two revolute joints only their squared distance."""

    base: LockedJoint
    platform: LockedJoint
    placed: LockedJoint | None = None
    squared_length: object = None


@dataclass(frozen=True)
class Motion:
    """A planar rigid motion p ↦ R p + t, R the rotation (cos, sin)."""

    cos: float | Fraction
    sin: float | Fraction
    shift: Point

    def point(self, p: Point) -> Point:
        return (self.cos * p[0] - self.sin * p[1] + self.shift[0], self.sin * p[0] + self.cos * p[1] + self.shift[1])

    def vector(self, v: Point) -> Point:
        return (self.cos * v[0] - self.sin * v[1], self.sin * v[0] + self.cos * v[1])

    def inverse(self) -> Motion:
        x, y = self.shift
        return Motion(self.cos, -self.sin, (-(self.cos * x + self.sin * y), self.sin * x - self.cos * y))


IDENTITY = Motion(1, 0, (0, 0))


def joint_motion(joint: HomeJoint, kind: str, value) -> Motion:
    """The motion of a revolute joint turned by ``value`` radians about its centre, or of
    a prismatic one moved ``value`` length units along its direction."""
    value = to_number(value, "actuator")
    if value == 0:  # home itself, exact
        return IDENTITY
    if kind == "R":
        angle = float(value)
        c, s = math.cos(angle), math.sin(angle)
        x, y = joint.at
        return Motion(c, s, (x - (c * x - s * y), y - (s * x + c * y)))
    dx, dy = joint.direction
    squared = dx * dx + dy * dy
    squared = Fraction(squared) if isinstance(squared, int) else squared
    length = rational_sqrt(squared) or math.sqrt(squared)  # exact where the length is rational
    return Motion(1, 0, (value * dx / length, value * dy / length))


def locked_leg_from_home(leg: Leg, home: tuple[HomeJoint, HomeJoint, HomeJoint], value) -> LockedLeg:
    """The locked leg of ``leg`` (see the module docstring) with its actuator at
    ``value`` (radians or length units from home).

    An RPR leg from (1, 8) to the platform's (4, 4), its prismatic joint along (3, −4)
    pushed 8 beyond home: the platform moves by (24/5, −32/5), the leg is 5 + 8 long.

    >>> from baranov.robots.legs import Leg
    >>> home = (HomeJoint((1, 8)), HomeJoint((1, 8), (3, -4)), HomeJoint((4, 4)))
    >>> locked = locked_leg_from_home(Leg.parse("RpR"), home, 8)
    >>> locked.base.point, locked.platform.point, locked.placed.point
    ((1, 8), (Fraction(4, 1), Fraction(4, 1)), (Fraction(44, 5), Fraction(-12, 5)))
    """
    _check_home(leg, home)
    motion = joint_motion(home[leg.actuated], leg.joints[leg.actuated], value)
    passive = [k for k in range(3) if k != leg.actuated]
    placed = []
    for k in passive:  # the joints after the actuated one move with it
        moved = motion if k > leg.actuated else IDENTITY
        direction = moved.vector(home[k].direction) if leg.joints[k] == "P" else None
        placed.append(LockedJoint(moved.point(home[k].at), direction))
    back = motion.inverse()  # world to platform frame
    on_platform = LockedJoint(back.point(placed[1].point),
                              back.vector(placed[1].direction) if placed[1].direction is not None else None)
    return LockedLeg(placed[0], on_platform, placed[1])


def _check_home(leg: Leg, home: tuple[HomeJoint, HomeJoint, HomeJoint]) -> None:
    for k, (letter, joint) in enumerate(zip(leg.joints, home, strict=True)):
        if letter == "P" and (joint.direction is None or joint.direction == (0, 0)):
            raise RobotInputError(f"leg {leg}, joint {k + 1}: a prismatic joint needs a non-zero direction")
        if letter == "R" and joint.direction is not None:
            raise RobotInputError(f"leg {leg}, joint {k + 1}: a revolute joint has no direction")
