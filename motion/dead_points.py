"""Dead points of an input and the branches they cut a circuit into (Chase and Mirth,
"Circuits and branches of single-degree-of-freedom planar linkages", J. Mech. Des. 115,
1993): along a circuit of the configuration curve, the input (a crank angle, a distance)
turns back where it is stationary — a *dead point*, where the linkage cannot be driven on
by that input and may lock or switch branches. A circuit with k > 0 dead points of an
input has k *branches* relative to it, the arcs between them, each driven monotonically;
one without any is driven round in full (a crank of a Grashof crank-rocker).

A dead point is located between the traced points where the input's steps change sign
(:func:`~.driving.input_extremum`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from baranov.scene import SceneInput

from .configuration_space import ConfigurationPoint, OneDofSystem
from .continuation import LinkageCurve, linkage_curve
from .driving import input_extremum, input_value
from .tracing import Trace, configurations_on_curve


@dataclass(frozen=True)
class DeadPoint:
    """Where ``driver`` is stationary along circuit ``circuit``: its value there (a
    maximum if ``maximum``, else a minimum) and the configuration."""

    circuit: int
    value: float
    maximum: bool
    point: ConfigurationPoint


def loop_orders(traced: Trace, circuit: int) -> list[list[int]]:
    """The pieces of a circuit as loops, each in order along it (a piece's end joined to
    the next piece's start by a branch point); an unfinished loop's pieces as a path.
    O(pieces · branch points)."""
    members = traced.circuits[circuit].pieces
    after = {point.pieces[0][0]: point.pieces[1][0] for point in traced.branch_points
             if point.pieces[0][0] in members and point.pieces[0][1] == -1}
    before = {value: key for key, value in after.items()}
    loops, seen = [], set()
    for start in members:
        if start in seen:
            continue
        first = start  # a path's first piece; any piece of a loop
        while first in before and before[first] != start:
            first = before[first]
        order, piece = [], first
        while piece not in seen:
            seen.add(piece)
            order.append(piece)
            piece = after.get(piece, piece)
        loops.append(order)
    return loops


def dead_points(system: OneDofSystem, traced: Trace, driver: SceneInput) -> list[DeadPoint]:
    """Every dead point of ``driver`` on every circuit of ``traced`` (module docstring).
    Cost: per dead point a bounded scalar search of about 30 curve points."""
    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    found = []
    for number in range(len(traced.circuits)):
        for order in loop_orders(traced, number):
            if traced.pieces[order[0]].closed:
                points, closed = list(traced.pieces[order[0]].points), True
            else:  # each piece up to the branch point where the next starts
                points = [point for n in order for point in traced.pieces[n].points[:-1]]
                closed = _joined(traced, order[-1], order[0])
                if not closed:
                    points.append(traced.pieces[order[-1]].points[-1])
            found += [DeadPoint(number, *extremum) for extremum in _extrema(system, curve, driver, points, closed)]
    return found


def _joined(traced: Trace, last: int, first: int) -> bool:
    return any(point.pieces == ((last, -1), (first, 0)) for point in traced.branch_points)


def _turn(driver: SceneInput, difference: float) -> float:
    return (difference + 180.0) % 360.0 - 180.0 if driver.kind == "angle" else difference


def _extrema(system: OneDofSystem, curve: LinkageCurve, driver: SceneInput, points: list[ConfigurationPoint],
             closed: bool) -> list[tuple[float, bool, ConfigurationPoint]]:
    """The input's local extrema along a polyline of the curve (closed: round to its
    start), each refined on the curve."""
    count = len(points)
    if count < 3:
        return []
    values = [input_value(driver, point) for point in points]
    steps = [_turn(driver, values[(k + 1) % count] - values[k]) for k in range(count if closed else count - 1)]
    found = []
    for k in range(count if closed else count - 1):
        if k == 0 and not closed:
            continue
        before, after = steps[k - 1], steps[k]
        if before * after >= 0 and not (before == 0 and after != 0):
            continue
        maximum = before > 0
        ends = [curve.unknowns_of(points[n % count].joints) for n in (k - 1, k, k + 1)]
        found.append(_refined(system, curve, driver, ends, values[k], maximum))
    return found


def _refined(system: OneDofSystem, curve: LinkageCurve, driver: SceneInput, ends: list[np.ndarray], reference: float,
             maximum: bool) -> tuple[float, bool, ConfigurationPoint]:
    """The extremum between the chords ends[0]–ends[1] and ends[1]–ends[2]."""
    _, x = input_extremum(curve, driver, ends, reference, maximum)
    point = configurations_on_curve(system, curve, [x])[0]
    return input_value(driver, point), maximum, point
