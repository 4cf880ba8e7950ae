"""The locked robot as a scene: with its actuators locked, a fully-parallel planar robot is
a pentad 5/B1 whose base and platform are ternary links and whose legs are binary links
(thesis §5.1–5.2), with a slider joint wherever a leg's passive joint is prismatic
(families II–X, thesis §5.2.1 and Table 5.4).

Joints as in thesis §5.1 (``examples/3-RPR-*.json``): ground ``base`` (P1, P2, P3),
``platform`` (P4, P5, P6, in its own frame) and legs ``leg14``, ``leg25``, ``leg36``; the
passive joint of leg k on the base is P_k, on the platform P_{k+3}. A slider joint's
axis is fixed in each of its links by the angle, from the sliding direction, of the
vector from its point to another joint of that link (docs/scenes.md), given exactly as
a direction (u·v, u×v) where the robot's numbers are exact.

Leg geometry with its actuator locked (:class:`~baranov.robots.model.LegGeometry`), base
points in the world frame, platform points in the platform's frame; a leg given by its
home configuration (any of the 21 legs) is locked by :mod:`.home`:

======  ==========================  ===========================================
leg     geometry                    actuator
======  ==========================  ===========================================
RpR     base A, platform B          the length |AB|
rRR     A, B, lengths (l1, l2)      the angle of A→M (l1 from A) from the x-axis
RrR     A, B, lengths (l1, l2)      the angle at M between M→A and M→B
RRr     A, B, lengths (l1, l2)      the angle of B→M (l2 from B), platform frame
pRR     A (origin of the axis), B,  the offset d along the axis: the base joint
        axis direction, length l    at A + d·axis
RRp     A, B (origin of the axis),  the offset d along the axis (platform frame)
        axis direction, length l
======  ==========================  ===========================================
"""

from __future__ import annotations

import math
from fractions import Fraction

from baranov.scene import Scene, scene_from_dict

from .home import LockedJoint, LockedLeg, locked_leg_from_home
from .legs import Leg, RobotInputError
from .model import LegGeometry, Point, Robot, to_number


def locked_leg(leg: Leg, geometry: LegGeometry, actuator) -> LockedLeg:
    """The rigid link ``leg`` becomes with its actuator at ``actuator``: its passive joint
    on the base (world frame) and on the platform (platform frame), and its squared
    length (RR legs of the module table) or its place in the world (a home
    configuration, :func:`~baranov.robots.home.locked_leg_from_home`). Exact where the
    geometry and a length or offset actuator are."""
    if geometry.home is not None:
        return locked_leg_from_home(leg, geometry.home, actuator)
    a, b = geometry.base, geometry.platform
    kind = str(leg)
    if leg.passive != "RR":
        raise RobotInputError(f"leg {kind}: passive joints {leg.passive}: give the leg by its home configuration "
                              '("home": its three joints, a direction for each prismatic one)')
    if kind == "RpR":
        return _binary(a, b, to_number(actuator, "actuator") ** 2)
    if kind in ("pRR", "RRp"):
        if geometry.axis is None or len(geometry.lengths) != 1:
            raise RobotInputError(f"leg {kind}: give its axis direction and one length")
        (length,), (ux, uy) = geometry.lengths, geometry.axis
        d = to_number(actuator, "actuator")
        moved = (a[0] + d * ux, a[1] + d * uy) if kind == "pRR" else (b[0] + d * ux, b[1] + d * uy)
        return _binary(moved, b, length**2) if kind == "pRR" else _binary(a, moved, length**2)
    if len(geometry.lengths) != 2:
        raise RobotInputError(f"leg {kind}: give its two link lengths (l1 from the base, l2 to the platform)")
    l1, l2 = geometry.lengths
    angle = float(to_number(actuator, "actuator"))
    if kind == "rRR":
        return _binary((a[0] + l1 * math.cos(angle), a[1] + l1 * math.sin(angle)), b, l2**2)
    if kind == "RRr":
        return _binary(a, (b[0] + l2 * math.cos(angle), b[1] + l2 * math.sin(angle)), l1**2)
    return _binary(a, b, l1**2 + l2**2 - 2 * l1 * l2 * math.cos(angle))  # RrR: the cosine theorem


def _binary(base: Point, platform: Point, squared) -> LockedLeg:
    return LockedLeg(LockedJoint(base), LockedJoint(platform), squared_length=squared)


def locked_scene(robot: Robot, actuators) -> Scene:
    """The locked robot as a scene (see the module docstring)."""
    return locked_robot(robot, actuators)[0]


def locked_robot(robot: Robot, actuators) -> tuple[Scene, dict[str, Point]]:
    """The locked robot as a scene, and the platform's joints in the platform frame as
    the scene's modes name them (a slider's point on the platform is ``P4'``: the
    platform comes before the legs)."""
    if len(actuators) != 3:
        raise RobotInputError(f"actuators: three values, one per leg (got {len(actuators)})")
    locked = [locked_leg(leg, geometry, value)
              for leg, geometry, value in zip(robot.legs, robot.geometry, actuators, strict=True)]
    base = {f"P{k + 1}": leg.base.point for k, leg in enumerate(locked)}
    platform = {f"P{k + 4}": leg.platform.point for k, leg in enumerate(locked)}
    links, sliders, pending = [], [], []
    for k, leg in enumerate(locked):
        name, ends = f"leg{k + 1}{k + 4}", (f"P{k + 1}", f"P{k + 4}")
        if leg.squared_length is not None:
            links.append({"name": name, "joints": list(ends), "squared_length": _text(leg.squared_length)})
        else:
            places = _slider_places(leg, ends, base, platform)
            links.append({"name": name, "joints": {joint: [_text(x) for x in place.point]
                                                   for joint, place in places.items()}})
            pending.append((name, ends, leg, places))
    for name, ends, leg, places in pending:  # angles once every slider point has moved
        for joint, owner, points, own in ((ends[0], "base", base, leg.base), (ends[1], "platform", platform, leg.platform)):
            if own.direction is not None:
                other = ends[1] if joint == ends[0] else ends[0]
                reference = next(n for n in sorted(points) if n != joint and points[n] != points[joint])
                sliders.append({"joint": joint, "angles": {
                    name: {other: _angle(places[joint], places[other].point)},
                    owner: {reference: _angle(LockedJoint(points[joint], own.direction), points[reference])}}})
    data = {"ground": "base", "links": [{"name": "base", "joints": _link_joints(base)},
                                        {"name": "platform", "joints": _link_joints(platform)}, *links]}
    if sliders:
        data["sliders"] = sliders
    named = {f"{joint}'" if any(slider["joint"] == joint for slider in sliders) else joint: point
             for joint, point in platform.items()}
    return scene_from_dict(data), named


def _slider_places(leg: LockedLeg, ends: tuple[str, str], base: dict[str, Point],
                   platform: dict[str, Point]) -> dict[str, LockedJoint]:
    """The world places of a locked leg's two passive joints (its link's own frame), a
    slider's point moved along its axis, by whole direction vectors, off any joint of its
    links (its angles need two distinct points); ``base`` and ``platform`` get the moved
    points."""
    places = {ends[0]: leg.base, ends[1]: leg.placed}
    for joint, points, own in ((ends[0], base, leg.base), (ends[1], platform, leg.platform)):
        if own.direction is None:
            continue
        other = places[ends[1] if joint == ends[0] else ends[0]].point
        shift = 0
        while _moved(places[joint], shift) == other or any(
                _moved(own, shift) == p for name, p in points.items() if name != joint):
            shift += 1
        places[joint] = LockedJoint(_moved(places[joint], shift), places[joint].direction)
        points[joint] = _moved(own, shift)
    return places


def _moved(joint: LockedJoint, shift: int) -> Point:
    """The point ``shift`` direction vectors along a slider's axis."""
    return (joint.point[0] + shift * joint.direction[0], joint.point[1] + shift * joint.direction[1])


def _angle(slider: LockedJoint, other: Point) -> list:
    """The angle α of the vector from the slider's point to ``other`` from its sliding
    direction u, as the direction (u·v, u×v) (exact where the numbers are)."""
    (ux, uy), vx, vy = slider.direction, other[0] - slider.point[0], other[1] - slider.point[1]
    return [_text(ux * vx + uy * vy), _text(ux * vy - uy * vx)]


def _link_joints(points: dict[str, Point]) -> dict[str, list]:
    """A link's joints for a scene, its first two at different points (they set the
    link's frame; two coincident attachments, condition C1 of thesis §5.1.2, come later)."""
    names = list(points)
    first = next(((a, b) for a, b in [(names[0], names[1]), (names[0], names[2]), (names[1], names[2])]
                  if points[a] != points[b]), (names[0], names[1]))
    order = [*first, *(name for name in names if name not in first)]
    return {name: [_text(x) for x in points[name]] for name in order}


def _text(value) -> str | float:
    """A scene number: exact as a string ("3/2") where ``value`` is exact (int, Fraction,
    decimal string), else the float."""
    value = to_number(value, "dimension")
    return str(value) if isinstance(value, Fraction) else value
