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

from baranov.scene import SceneInput

from .configuration_space import ConfigurationPoint, OneDofSystem
from .continuation import linkage_curve
from .driving import input_extremum, input_value, turning_points
from .tracing import Trace, configurations_on_curve


@dataclass(frozen=True)
class DeadPoint:
    """Where ``driver`` is stationary along circuit ``circuit``: its value there (a
    maximum if ``maximum``, else a minimum) and the configuration."""

    circuit: int
    value: float
    maximum: bool
    point: ConfigurationPoint


def dead_points(system: OneDofSystem, traced: Trace, driver: SceneInput) -> list[DeadPoint]:
    """Every dead point of ``driver`` on every circuit of ``traced`` (module docstring).
    Cost: per dead point a bounded scalar search of about 30 curve points."""
    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    found = []
    for number, circuit in enumerate(traced.circuits):
        for order in circuit.loops:
            if traced.pieces[order[0]].closed:
                points, closed = list(traced.pieces[order[0]].points), True
            else:  # each piece up to the branch point where the next starts
                points = [point for n in order for point in traced.pieces[n].points[:-1]]
                closed = (order[0], 0) not in traced.loose_ends  # else an unfinished loop's path
                if not closed:
                    points.append(traced.pieces[order[-1]].points[-1])
            for k, value, maximum in turning_points(driver, points, closed):
                ends = [curve.unknowns_of(points[n % len(points)].joints) for n in (k - 1, k, k + 1)]
                _, x = input_extremum(curve, driver, ends, value, maximum)
                point = configurations_on_curve(system, curve, [x])[0]
                found.append(DeadPoint(number, input_value(driver, point), maximum, point))
    return found
