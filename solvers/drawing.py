"""Drawings of assembly modes in the style of the thesis figures: one panel per mode,
the ground link hatched, ternary and larger links filled, binary links as bars, joints
labelled, the parameter values in each title."""

from __future__ import annotations

import io
import math

from matplotlib.figure import Figure  # a bare Figure draws to files without pyplot's global backend
from matplotlib.patches import Polygon

from baranov.scene import Scene

from .modes import Solution


def _hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Convex hull (monotone chain), counter-clockwise."""
    points = sorted(set(points))
    if len(points) <= 2:
        return points

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in points:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(points):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def render_modes(scene: Scene, solution: Solution, columns: int | None = None) -> bytes:
    """A PNG image (bytes) of :func:`modes_figure`."""
    buffer = io.BytesIO()
    modes_figure(scene, solution, columns).savefig(buffer, format="png", dpi=110)
    return buffer.getvalue()


def modes_figure(scene: Scene, solution: Solution, columns: int | None = None) -> Figure:
    """One drawing per assembly mode, ``columns`` per row (by default 4, or about √n for
    n > 16 modes so that the grid stays roughly square), laid out by matplotlib's
    constrained layout so that no title runs into a neighbouring panel; joint labels sit
    away from the mode's centre, and joints at one point share one label ("P1=P5")."""
    modes = solution.assembly_modes
    count = max(len(modes), 1)
    if columns is None:
        columns = max(4, math.ceil(math.sqrt(count)))
    columns = min(columns, count)
    rows = math.ceil(count / columns)
    everything = [p for m in modes for p in m.joints.values()] or [(0.0, 0.0)]
    xs, ys = [p[0] for p in everything], [p[1] for p in everything]
    extent = max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
    margin = 0.12 * extent
    # panels as tall as the drawings need (a flat 3-RPR left wide empty bands before)
    shape = min(max((max(ys) - min(ys) + 2 * margin) / (max(xs) - min(xs) + 2 * margin), 0.45), 1.6)
    figure = Figure(figsize=(3.6 * columns, 3.6 * shape * rows + 0.8), layout="constrained")
    axes = figure.subplots(rows, columns, squeeze=False)
    for index, axis in enumerate(axes.flat):
        axis.set_aspect("equal")
        axis.set_xticks([])
        axis.set_yticks([])
        axis.set_xlim(min(xs) - margin, max(xs) + margin)
        axis.set_ylim(min(ys) - margin, max(ys) + margin)
        if index >= len(modes):
            axis.axis("off")
            if not modes:
                axis.text(0.5, 0.5, "no assembly mode", ha="center", va="center", transform=axis.transAxes)
            continue
        _draw_mode(axis, scene, modes[index], extent)
        values = ", ".join(f"{name} = {value:.6g}" for name, value in modes[index].parameters.items())
        axis.set_title(f"mode {index + 1}" + (f": {values}" if values else ""), fontsize=9)
    figure.suptitle(f"{len(modes)} assembly mode{'s' if len(modes) != 1 else ''} (ground hatched)", fontsize=11)
    return figure


def _draw_mode(axis, scene: Scene, mode, extent: float) -> None:
    """The links (ground hatched, k-ary links filled, bars), joints and their labels."""
    for link in scene.links:
        points = [mode.joints[j] for j in link.joints]
        ground = link.name == scene.ground
        if len(points) == 2:
            (x1, y1), (x2, y2) = points
            axis.plot([x1, x2], [y1, y2], color="0.15", linewidth=3 if not ground else 5,
                      solid_capstyle="round", zorder=2)
        else:
            axis.add_patch(Polygon(_hull(points), closed=True, facecolor="0.82" if not ground else "0.95",
                                   edgecolor="0.15", linewidth=1.5, hatch="////" if ground else None, zorder=1))
    centre = (sum(x for x, _ in mode.joints.values()) / len(mode.joints),
              sum(y for _, y in mode.joints.values()) / len(mode.joints))
    for names, (x, y) in _label_groups(mode.joints, 1e-6 * extent):
        axis.plot(x, y, "o", markersize=6, markerfacecolor="white", markeredgecolor="0.1", zorder=3)
        dx, dy = x - centre[0], y - centre[1]
        length = math.hypot(dx, dy) or 1.0
        axis.annotate("=".join(names), (x, y), textcoords="offset points", xytext=(9 * dx / length, 9 * dy / length),
                      ha="left" if dx >= 0 else "right", va="bottom" if dy >= 0 else "top", fontsize=8, zorder=4)


def _label_groups(joints: dict, tolerance: float) -> list[tuple[list[str], tuple[float, float]]]:
    """Joints grouped where they lie within ``tolerance`` of each other (coincident
    joints: one label), each group with its first joint's position."""
    groups: list[tuple[list[str], tuple[float, float]]] = []
    for name, point in joints.items():
        for names, at in groups:
            if math.dist(point, at) <= tolerance:
                names.append(name)
                break
        else:
            groups.append(([name], point))
    return groups
