"""Drawings of assembly modes in the style of the thesis figures: one panel per mode,
the ground link hatched, ternary and larger links filled, binary links as bars, joints
labelled, the parameter values in each title."""

from __future__ import annotations

import io
import math

import numpy as np
from matplotlib.figure import Figure  # a bare Figure draws to files without pyplot's global backend
from matplotlib.patches import Polygon

from baranov.scene import Scene
from baranov.topology.diagram import convex_hull

from .modes import Solution
from .verification import slider_axis


def png_bytes(figure: Figure, tight: bool = False) -> bytes:
    """The PNG image (bytes, 110 dpi) of a matplotlib figure, for an atomic write; with
    ``tight``, cropped to what is drawn."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110, **({"bbox_inches": "tight"} if tight else {}))
    return buffer.getvalue()


def render_modes(scene: Scene, solution: Solution, columns: int | None = None) -> bytes:
    """A PNG image (bytes) of :func:`modes_figure`."""
    return png_bytes(modes_figure(scene, solution, columns))


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
    titles = [_title(index, mode) for index, mode in enumerate(modes)]
    extra_lines = max((title.count("\n") for title in titles), default=0)  # coupling degree 3: three-line titles
    figure = Figure(figsize=(3.6 * columns, (3.6 * shape + 0.2 * extra_lines) * rows + 0.8), layout="constrained")
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
        axis.set_title(titles[index], fontsize=9)
    legend = "ground hatched" + ("; (+-…): signs of the plan's free-sign triangles"
                                 if any(mode.signs for mode in modes) else "")
    figure.suptitle(f"{len(modes)} assembly mode{'s' if len(modes) != 1 else ''} ({legend})", fontsize=11)
    figure.get_layout_engine().execute(figure)  # the panels' final size, for the labels' room
    for axis, mode in zip(axes.flat, modes, strict=False):
        draw_mode(axis, scene, mode, extent)
    return figure


def _title(index: int, mode) -> str:
    """"mode k (signs): s = …, t = …"; with three parameters or more (coupling degree 3),
    the values two to a line below the mode's number, so that titles stay within their
    panels."""
    values = [f"{name} = {value:.6g}" for name, value in mode.parameters.items()]
    signs = "".join({1: "+", -1: "-", 0: "0"}[sign] for sign in mode.signs)
    heading = f"mode {index + 1}" + (f" ({signs})" if signs else "")
    if len(values) <= 2:
        return heading + (f": {', '.join(values)}" if values else "")
    return heading + "\n" + "\n".join(", ".join(values[n:n + 2]) for n in range(0, len(values), 2))


def mode_shapes(scene: Scene, joints: dict, extent: float) -> dict:
    """What a drawing of one configuration shows, in world coordinates, for any renderer
    (matplotlib here, the explorer's SVG): ``links`` (each ``{"name", "ground",
    "points"}``: a bar's two ends, or a k-ary link's convex hull), ``axes`` (each slider's
    axis through its two points and ``0.15 · extent`` beyond, as two points) and
    ``joints`` (``{"names", "point", "slider"}``: coincident joints as one, within
    1e-6 · ``extent``)."""
    links = []
    for link in scene.links:
        points = [tuple(joints[scene.point_name(link.name, j)]) for j in link.joints]
        links.append({"name": link.name, "ground": link.name == scene.ground,
                      "points": points if len(points) == 2 else convex_hull(points)})
    sliders = {scene.point_name(axis.link, slider.joint) for slider in scene.sliders for axis in slider.axes}
    return {"links": links, "axes": [_slider_axis_segment(scene, slider, joints, extent) for slider in scene.sliders],
            "joints": [{"names": names, "point": point, "slider": any(name in sliders for name in names)}
                       for names, point in _label_groups(joints, 1e-6 * extent)]}


def draw_mode(axis, scene: Scene, mode, extent: float) -> None:
    """One configuration of ``scene`` (an assembly mode, or any record with ``joints``:
    a traced configuration, a frame of ``baranov trace --animate``) on a matplotlib
    ``axis``, ``extent`` its size: :func:`mode_shapes` drawn as the thesis draws (ground
    hatched, k-ary links filled, bars, slider axes dashed, a slider's two points as
    squares), the joints' labels placed by :func:`_label_directions`."""
    shapes = mode_shapes(scene, mode.joints, extent)
    segments, polygons = [], []
    for link in shapes["links"]:
        points, ground = link["points"], link["ground"]
        if len(points) == 2:
            (x1, y1), (x2, y2) = points
            axis.plot([x1, x2], [y1, y2], color="0.15", linewidth=3 if not ground else 5,
                      solid_capstyle="round", zorder=2)
            segments.append((points[0], points[1]))
        else:
            axis.add_patch(Polygon(points, closed=True, facecolor="0.82" if not ground else "0.95",
                                   edgecolor="0.15", linewidth=1.5, hatch="////" if ground else None, zorder=1))
            segments += [(points[n], points[(n + 1) % len(points)]) for n in range(len(points))]
            polygons.append(points)
    for start, end in shapes["axes"]:
        axis.plot([start[0], end[0]], [start[1], end[1]], color="0.35", linewidth=1, linestyle="--", zorder=2)
        segments.append((start, end))
    groups = [(joint["names"], joint["point"]) for joint in shapes["joints"]]
    limits = (*axis.get_xlim(), *axis.get_ylim())
    axis.apply_aspect()  # data units per typographic point, from the panel's drawn width
    width_points = axis.get_position().width * axis.figure.get_figwidth() * 72
    scale = (limits[1] - limits[0]) / width_points if width_points > 0 else LABEL_SCALE * extent
    directions = _label_directions(groups, segments, polygons, extent, limits, scale)
    for joint, angle in zip(shapes["joints"], directions, strict=True):
        (x, y), marker = joint["point"], "s" if joint["slider"] else "o"
        axis.plot(x, y, marker, markersize=6, markerfacecolor="white", markeredgecolor="0.1", zorder=3)
        dx, dy = math.cos(angle), math.sin(angle)
        axis.annotate("=".join(joint["names"]), (x, y), textcoords="offset points", xytext=(10 * dx, 10 * dy),
                      ha="left" if dx > 0.3 else "right" if dx < -0.3 else "center",
                      va="bottom" if dy > 0.3 else "top" if dy < -0.3 else "center", fontsize=8, zorder=4)


def _slider_axis_segment(scene: Scene, slider, joints: dict, extent: float) -> tuple[tuple, tuple]:
    """A slider's axis through its two points and ``0.15 · extent`` beyond them."""
    at = {name: np.array([complex(*xy)]) for name, xy in joints.items()}
    foot, direction = slider_axis(scene, slider, slider.axes[0].link, at)
    first, unit = complex(foot[0]), complex(direction[0])
    second = joints[scene.point_name(slider.axes[1].link, slider.joint)]
    along = [0.0, ((complex(*second) - first) * unit.conjugate()).real]
    low, high = min(along) - 0.15 * extent, max(along) + 0.15 * extent
    start, end = first + low * unit, first + high * unit
    return (start.real, start.imag), (end.real, end.imag)


#: Directions tried for a joint's label; the label's offset from its joint, a
#: character's width and height (8-point text, measured: "P12" is 15 points wide) and the
#: margin kept between labels, in points; LABEL_SCALE: points to the drawing's extent
#: where no panel size is known (a 3.6-inch panel spanning about 1.24 extents).
LABEL_DIRECTIONS = 16
LABEL_OFFSET = 10.0
CHARACTER = (5.0, 8.0)
LABEL_MARGIN = 2.0
LABEL_SCALE = 1 / 209


def _label_directions(groups: list[tuple[list[str], tuple[float, float]]], segments: list, polygons: list,
                      extent: float, limits: tuple[float, float, float, float] | None = None,
                      scale: float | None = None) -> list[float]:
    """For each joint (group), the direction of its label: of LABEL_DIRECTIONS around
    it, the one whose label box — its corners and centre, the box anchored as
    :func:`draw_mode` anchors the text — keeps farthest from every link edge, bar,
    slider axis, joint and label already placed (a point inside a filled link counts as
    touching it); a box that overlaps a placed label's box (grown by LABEL_MARGIN) loses to
    every box that does not (9-B28: 5 overlapping pairs of 168 labels when only corners
    counted), and one reaching out of the panel's ``limits`` (x0, x1, y0, y1) to every box
    inside (it would be cut off or run into the next panel: 1 label of 9-B28's 168 and 10
    of the 13-link Watt–Baranov example's 1368 before); ties go away from the drawing's
    centre. ``scale``: data units per point (default LABEL_SCALE × ``extent``). Greedy,
    O(J · D · (S + J)) for J joints, D directions, S segments."""
    scale = scale or LABEL_SCALE * extent
    joints = [at for _, at in groups]
    centre = (sum(x for x, _ in joints) / len(joints), sum(y for _, y in joints) / len(joints))
    placed: list[tuple[float, float]] = []
    rectangles: list[tuple[float, float, float, float]] = []
    chosen = []
    for names, (x, y) in groups:
        away = math.atan2(y - centre[1], x - centre[0])
        width = CHARACTER[0] * scale * len("=".join(names))
        best, best_score, best_box = away, -math.inf, []
        for step in range(LABEL_DIRECTIONS):
            angle = away + 2 * math.pi * step / LABEL_DIRECTIONS
            box = _label_box((x, y), angle, width, CHARACTER[1] * scale, LABEL_OFFSET * scale)
            clearance = min([_segment_distance(point, a, b) for point in box for a, b in segments]
                            + [math.dist(point, other) for point in box for other in joints + placed] + [extent])
            if any(_inside(point, polygon) for point in box for polygon in polygons):
                clearance = 0.0
            score = clearance + 1e-3 * extent * math.cos(angle - away)
            if any(_boxes_overlap(_rectangle(box, LABEL_MARGIN * scale), other) for other in rectangles):
                score -= 2 * extent
            if limits is not None and not all(limits[0] <= px <= limits[1] and limits[2] <= py <= limits[3]
                                              for px, py in box):
                score -= extent
            if score > best_score:
                best, best_score, best_box = angle, score, box
        chosen.append(best)
        placed += best_box
        rectangles.append(_rectangle(best_box, LABEL_MARGIN * scale))
    return chosen


def _rectangle(box: list[tuple[float, float]], margin: float) -> tuple[float, float, float, float]:
    """(left, bottom, right, top) of a label box (:func:`_label_box`), grown by ``margin``."""
    (left, bottom), (right, top) = box[1], box[4]
    return left - margin, bottom - margin, right + margin, top + margin


def _boxes_overlap(first: tuple[float, float, float, float], second: tuple[float, float, float, float]) -> bool:
    return first[0] < second[2] and second[0] < first[2] and first[1] < second[3] and second[1] < first[3]


def _label_box(joint, angle: float, width: float, height: float, offset: float) -> list[tuple[float, float]]:
    """Centre, corners and sides' midpoints of a label anchored ``offset`` from ``joint``
    in direction ``angle`` (left/right/centre and bottom/top/centre as :func:`draw_mode` aligns it)."""
    dx, dy = math.cos(angle), math.sin(angle)
    x, y = joint[0] + offset * dx, joint[1] + offset * dy
    left = x if dx > 0.3 else x - width if dx < -0.3 else x - width / 2
    bottom = y if dy > 0.3 else y - height if dy < -0.3 else y - height / 2
    right, top, middle, centre = left + width, bottom + height, left + width / 2, bottom + height / 2
    return [(middle, centre), (left, bottom), (right, bottom), (left, top), (right, top),
            (middle, bottom), (middle, top), (left, centre), (right, centre)]


def _segment_distance(point, start, end) -> float:
    (px, py), (ax, ay), (bx, by) = point, start, end
    dx, dy = bx - ax, by - ay
    length = dx * dx + dy * dy
    t = 0.0 if length == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def _inside(point, polygon) -> bool:
    """Whether ``point`` lies inside the convex, counter-clockwise ``polygon``."""
    (px, py) = point
    return len(polygon) >= 3 and all(
        (bx - ax) * (py - ay) - (by - ay) * (px - ax) > 0
        for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1], strict=True))


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
