"""Pictures of a robot's poses: the locked robot's assembly modes (the scene drawing, one
panel per pose) with each actuated prismatic joint drawn as a block on its leg, where the
leg's length is what the actuator sets."""

from __future__ import annotations

import math

from baranov.solvers import Solution
from baranov.solvers.drawing import modes_figure, png_bytes

from .model import Robot


def render_robot(robot: Robot, scene, solution: Solution) -> bytes:
    """A PNG of every pose of ``robot`` (``scene``: its locked scene, ``solution``: the
    backend's solution): the scene drawing of each mode, and on each leg whose actuated
    joint is prismatic, a block centred on the leg and turned along it
    (:func:`actuator_blocks`)."""
    from matplotlib.patches import Polygon

    figure = modes_figure(scene, solution)
    for axis, mode in zip(figure.axes, solution.assembly_modes, strict=False):
        extent = max(abs(b - a) for a, b in (axis.get_xlim(), axis.get_ylim()))
        for corners in actuator_blocks(robot, mode.joints, extent):
            axis.add_patch(Polygon(corners, closed=True, facecolor="white", edgecolor="black", lw=1.2, zorder=5))
    return png_bytes(figure)


def actuator_blocks(robot: Robot, joints: dict, extent: float) -> list[list[tuple[float, float]]]:
    """The four corners of a block on each leg whose actuated joint is prismatic, centred
    on the leg and turned along it, ``0.05 · extent`` long each way (never longer than
    0.3 of the leg), in a configuration ``joints`` of the locked robot."""
    blocks = []
    for k, leg in enumerate(robot.legs):
        ends = [_place(joints, f"P{k + 1}"), _place(joints, f"P{k + 4}")]
        if leg.joints[leg.actuated] != "P" or None in ends:
            continue
        (x0, y0), (x1, y1) = ends
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0:
            continue
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        half_long = min(0.05 * extent, 0.3 * length)  # never longer than the leg itself
        half_wide = 0.4 * half_long
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        blocks.append([(cx + a * ux * half_long - b * uy * half_wide, cy + a * uy * half_long + b * ux * half_wide)
                       for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    return blocks


def _place(joints: dict, name: str):
    """A joint's place, or its point on the leg's side if it is a slider (P4'' …)."""
    for candidate in (name, f"{name}''", f"{name}'"):
        if candidate in joints:
            return joints[candidate]
    return None
