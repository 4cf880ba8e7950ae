"""Forward kinematics of fully-parallel planar robots: every platform pose for given
actuator values, as the assembly modes of the locked robot (thesis §5.1–5.2).

With its actuators locked the robot is the pentad 5/B1, with a slider joint wherever a
leg's passive joint is prismatic (:mod:`.locked`), solved by the project's backends like
any scene. A pose is the platform's frame in the world: the position of its origin and
its orientation angle, fitted to the placed platform joints (three points, an exact
rigid motion up to rounding).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from baranov.planner import SliderPlanError, slider_plan
from baranov.solvers import Solution, solve

from .families import robot_family
from .home import LockedLeg, Motion
from .legs import RobotInputError
from .locked import locked_leg, locked_robot
from .model import Robot


@dataclass(frozen=True)
class Pose:
    """One platform pose: the world position of the platform frame's origin, its
    orientation angle (radians, from the world x-axis), the world coordinates of every
    joint of the locked robot, and the assembly mode it comes from (its parameters)."""

    position: tuple[float, float]
    angle: float
    joints: dict[str, tuple[float, float]]
    parameters: dict[str, float]


def forward_kinematics(robot: Robot, actuators, method: Literal["numeric", "exact"] = "numeric") -> list[Pose]:
    """Every platform pose of ``robot`` with these actuator values (one per leg), by the
    ``method`` backend on the locked robot (:func:`locked_scene`).

    Thesis §5.1.3.1, example I: base (0, 0), (4, 0), (1, 8), platform (0, 0), (6, 0),
    (3, 4), leg lengths 1, 11, 13: one pose (a double root), the platform at (−1, 0)
    turned by π.

    >>> from baranov.robots import Leg, LegGeometry, Robot
    >>> legs = tuple(Leg.parse("RpR") for _ in range(3))
    >>> geometry = tuple(LegGeometry(a, b) for a, b in [((0, 0), (0, 0)), ((4, 0), (6, 0)), ((1, 8), (3, 4))])
    >>> [(round(p.position[0], 6) + 0, round(p.position[1], 6) + 0, round(abs(p.angle), 6))
    ...  for p in forward_kinematics(Robot(legs, geometry), [1, 11, 13])]
    [(-1.0, 0.0, 3.141593)]
    """
    return robot_solution(robot, actuators, method)[1]


def robot_solution(robot: Robot, actuators, method: str = "numeric",
                   parameter: tuple[str, str] | None = None) -> tuple[Solution, list[Pose]]:
    """The backend's solution of the locked robot (plan, parameters, for the exact method
    the characteristic polynomial) and the pose of each of its assembly modes.
    ``parameter``: solve (numeric, exact) in a plan with this parameter, e.g. ``("P1",
    "P6")`` as thesis §5.2.2 does (s1,6, or t1,6 where P6 is a slider), instead of the
    best plan; msolve describes its modes in the best plan."""
    robot_family(robot.legs)  # raises for a leg string no robot has
    scene, platform = locked_robot(robot, actuators)
    if parameter is None or method == "msolve":
        solution = solve(scene, method=method)
    else:
        try:
            plan = slider_plan(scene.chain, [slider.joint for slider in scene.sliders], parameters=[parameter])
        except SliderPlanError as error:
            raise RobotInputError(f"parameter {','.join(parameter)}: {error}") from None
        solution = solve(scene, method=method, plan=plan)
    frame = {name: (float(x), float(y)) for name, (x, y) in platform.items()}
    return solution, [_pose(mode.joints, frame, mode.parameters) for mode in solution.assembly_modes]


def pose_residuals(robot: Robot, actuators, pose: Pose) -> tuple[float, float, float]:
    """How far ``pose`` is from satisfying each leg at its actuator value, by forward
    substitution into the leg alone (not the locked scene): a locked leg is one rigid link
    and constrains the platform by one equation, by its passive joints:

    * RR: the distance between its base point and the platform point, placed by the pose;
    * RP, PR: the signed distance from its revolute joint to its prismatic joint's axis;
    * PP: the angle between its two axes.

    Each residual is the difference from the locked leg's own value, in length units
    (radians for PP).

    Cost: O(1) per leg."""
    motion = Motion(math.cos(pose.angle), math.sin(pose.angle), pose.position)
    return tuple(_leg_residual(locked_leg(leg, geometry, value), motion)
                 for leg, geometry, value in zip(robot.legs, robot.geometry, actuators, strict=True))


def _leg_residual(leg: LockedLeg, motion: Motion) -> float:
    base, platform = leg.base, leg.platform
    point = motion.point(platform.point)
    if leg.squared_length is not None:
        return math.dist(base.point, point) - math.sqrt(float(leg.squared_length))
    if base.direction is None and platform.direction is None:
        return math.dist(base.point, point) - math.dist(base.point, leg.placed.point)
    if base.direction is not None and platform.direction is not None:
        return math.remainder(_turn(base.direction, motion.vector(platform.direction))
                              - _turn(base.direction, leg.placed.direction), 2 * math.pi)
    if platform.direction is not None:  # RP: the base joint to the platform's axis
        return (_height(motion.vector(platform.direction), point, base.point)
                - _height(leg.placed.direction, leg.placed.point, base.point))
    return _height(base.direction, base.point, point) - _height(base.direction, base.point, leg.placed.point)


def _height(direction, on_axis, point) -> float:
    """The signed distance of ``point`` to the line through ``on_axis`` along ``direction``."""
    (ux, uy), vx, vy = direction, point[0] - on_axis[0], point[1] - on_axis[1]
    return float(ux * vy - uy * vx) / math.hypot(ux, uy)


def _turn(first, second) -> float:
    return math.atan2(float(first[0] * second[1] - first[1] * second[0]), float(first[0] * second[0] + first[1] * second[1]))


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

