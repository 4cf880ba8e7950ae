"""Forward kinematics of fully-parallel planar robots: every platform pose for given
actuator values, as the assembly modes of the locked robot (thesis §5.1–5.2).

With its actuators locked, each leg of RR architecture is one binary link between a
point of the base and a point of the platform (:func:`locked_leg`): the robot is the
pentad 5/B1 (family I), solved by the project's backends like any scene. A pose is the
platform's frame in the world: the position of its origin and its orientation angle,
fitted to the placed platform joints (three points, an exact rigid motion up to
rounding). Legs with a passive prismatic joint (families II–X) need the slider
constructions and are refused for now (issue 18).

Leg geometry (:class:`~baranov.robots.model.LegGeometry`), base points in the world frame,
platform points in the platform's frame:

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
from dataclasses import dataclass
from fractions import Fraction
from typing import Literal

from baranov.scene import Scene, scene_from_dict
from baranov.solvers import Solution, solve

from .families import robot_family
from .legs import Leg, RobotInputError
from .model import LegGeometry, Point, Robot, to_number


@dataclass(frozen=True)
class Pose:
    """One platform pose: the world position of the platform frame's origin, its
    orientation angle (radians, from the world x-axis), the world coordinates of every
    joint of the locked robot, and the assembly mode it comes from (its parameters)."""

    position: tuple[float, float]
    angle: float
    joints: dict[str, tuple[float, float]]
    parameters: dict[str, float]


def locked_leg(leg: Leg, geometry: LegGeometry, actuator) -> tuple[Point, Point, object]:
    """The binary link a leg of RR architecture becomes with its actuator at ``actuator``:
    its base point (world), platform point (platform frame) and squared length, exact
    where the geometry and a length or offset actuator are."""
    a, b = geometry.base, geometry.platform
    kind = str(leg)
    if leg.passive != "RR":
        raise RobotInputError(f"leg {kind}: passive joints {leg.passive}: forward kinematics of legs with a passive "
                              "prismatic joint needs the slider constructions (not yet; family I only)")
    if kind == "RpR":
        return a, b, to_number(actuator, 'actuator') ** 2
    if kind in ("pRR", "RRp"):
        if geometry.axis is None or len(geometry.lengths) != 1:
            raise RobotInputError(f"leg {kind}: give its axis direction and one length")
        (length,), (ux, uy) = geometry.lengths, geometry.axis
        d = to_number(actuator, 'actuator')
        moved = (a[0] + d * ux, a[1] + d * uy) if kind == "pRR" else (b[0] + d * ux, b[1] + d * uy)
        return (moved, b, length**2) if kind == "pRR" else (a, moved, length**2)
    if len(geometry.lengths) != 2:
        raise RobotInputError(f"leg {kind}: give its two link lengths (l1 from the base, l2 to the platform)")
    l1, l2 = geometry.lengths
    angle = float(to_number(actuator, 'actuator'))
    if kind == "rRR":
        return (a[0] + l1 * math.cos(angle), a[1] + l1 * math.sin(angle)), b, l2**2
    if kind == "RRr":
        return a, (b[0] + l2 * math.cos(angle), b[1] + l2 * math.sin(angle)), l1**2
    return a, b, l1**2 + l2**2 - 2 * l1 * l2 * math.cos(angle)  # RrR: the cosine theorem


def locked_scene(robot: Robot, actuators) -> Scene:
    """The locked robot as a scene, joints as in thesis §5.1 (``examples/3-RPR-*.json``):
    ground ``base`` (P1, P2, P3), ``platform`` (P4, P5, P6, in its own frame) and legs
    ``leg14``, ``leg25``, ``leg36``."""
    if len(actuators) != 3:
        raise RobotInputError(f"actuators: three values, one per leg (got {len(actuators)})")
    locked = [locked_leg(leg, geometry, value)
              for leg, geometry, value in zip(robot.legs, robot.geometry, actuators, strict=True)]
    base = _link_joints({f"P{k + 1}": point for k, (point, _, _) in enumerate(locked)})
    platform = _link_joints({f"P{k + 4}": point for k, (_, point, _) in enumerate(locked)})
    legs = [{"name": f"leg{k + 1}{k + 4}", "joints": [f"P{k + 1}", f"P{k + 4}"], "squared_length": _text(squared)}
            for k, (_, _, squared) in enumerate(locked)]
    return scene_from_dict({"ground": "base", "links": [{"name": "base", "joints": base},
                                                        {"name": "platform", "joints": platform}, *legs]})


def _link_joints(points: dict[str, Point]) -> dict[str, list]:
    """A link's joints for a scene, its first two at different points (they set the
    link's frame; two coincident attachments, condition C1 of thesis §5.1.2, come later)."""
    names = list(points)
    first = next(((a, b) for a, b in [(names[0], names[1]), (names[0], names[2]), (names[1], names[2])]
                  if points[a] != points[b]), (names[0], names[1]))
    order = [*first, *(name for name in names if name not in first)]
    return {name: [_text(x) for x in points[name]] for name in order}


def forward_kinematics(robot: Robot, actuators, method: Literal["numeric", "exact"] = "numeric") -> list[Pose]:
    """Every platform pose of ``robot`` with these actuator values (one per leg), by the
    ``method`` backend on the locked robot (:func:`locked_scene`).

    Thesis §5.1.3.1, example I: base (0, 0), (4, 0), (1, 8), platform (0, 0), (6, 0),
    (3, 4), leg lengths 1, 11, 13: one pose (a double root), the platform at (−1, 0)
    turned by π.

    >>> legs = tuple(Leg.parse("RpR") for _ in range(3))
    >>> geometry = tuple(LegGeometry(a, b) for a, b in [((0, 0), (0, 0)), ((4, 0), (6, 0)), ((1, 8), (3, 4))])
    >>> [(round(p.position[0], 6) + 0, round(p.position[1], 6) + 0, round(abs(p.angle), 6))
    ...  for p in forward_kinematics(Robot(legs, geometry), [1, 11, 13])]
    [(-1.0, 0.0, 3.141593)]
    """
    return robot_solution(robot, actuators, method)[1]


def robot_solution(robot: Robot, actuators, method: str = "numeric") -> tuple[Solution, list[Pose]]:
    """The backend's solution of the locked robot (plan, parameters, for the exact method
    the characteristic polynomial) and the pose of each of its assembly modes."""
    robot_family(robot.legs)  # raises for a leg string no robot has
    solution = solve(locked_scene(robot, actuators), method=method)
    frame = {f"P{k + 4}": tuple(map(float, locked_leg(leg, geometry, actuators[k])[1]))
             for k, (leg, geometry) in enumerate(zip(robot.legs, robot.geometry, strict=True))}
    return solution, [_pose(mode.joints, frame, mode.parameters) for mode in solution.assembly_modes]


def _pose(joints: dict, frame: dict, parameters: dict) -> Pose:
    """The rigid motion taking the platform points ``frame`` to their placed ``joints``
    (least squares over the three points: the angle of the cross-covariance)."""
    names = sorted(frame)
    cx = sum(frame[n][0] for n in names) / 3
    cy = sum(frame[n][1] for n in names) / 3
    wx = sum(joints[n][0] for n in names) / 3
    wy = sum(joints[n][1] for n in names) / 3
    dot = cross = 0.0
    for n in names:
        px, py = frame[n][0] - cx, frame[n][1] - cy
        qx, qy = joints[n][0] - wx, joints[n][1] - wy
        dot += px * qx + py * qy
        cross += px * qy - py * qx
    angle = math.atan2(cross, dot)
    c, s = math.cos(angle), math.sin(angle)
    position = (wx - (c * cx - s * cy), wy - (s * cx + c * cy))
    return Pose(position, angle, dict(joints), dict(parameters))


def _text(value) -> str | float:
    """A scene number: exact as a string ("3/2") where ``value`` is exact (int, Fraction,
    decimal string), else the float."""
    value = to_number(value, "dimension")
    return str(value) if isinstance(value, Fraction) else value
