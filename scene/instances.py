"""Random generic instances of a truss: integer joint coordinates and the scene of their
dimensions. Built from a configuration, an instance has at least one real assembly mode
(the configuration itself), and its link areas are rational, as the exact method needs."""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import numpy as np

from baranov.topology import KinematicChain
from baranov.topology.graphs import joints_of_links

from .model import Scene, scene_from_dict


def scene_of(truss: KinematicChain, coordinates, ground: int = 0) -> Scene:
    """A scene whose links carry the given joint coordinates (exact when they are), links
    named ``L0``, ``L1``, … in the truss's link order, link ``ground`` fixed."""
    return scene_from_dict(instance_dict(truss, coordinates, ground))


def instance_dict(truss: KinematicChain, coordinates, ground: int = 0) -> dict:
    """The JSON form (``baranov solve``'s input) of :func:`scene_of`: every link given by
    its joints' coordinates, as strings so that rationals stay exact."""
    links = []
    for index, names in enumerate(joints_of_links(truss)):
        links.append({"name": f"L{index}", "joints": {n: [str(coordinates[n][0]), str(coordinates[n][1])] for n in names}})
    return {"links": links, "ground": f"L{ground}"}


def generic_integer_configuration(truss: KinematicChain, rng: np.random.Generator) -> dict[str, tuple[Fraction, Fraction]]:
    """Random integer joint coordinates, no two equal and no three within area 10 of
    collinear (a generic configuration); the box is [-30, 30]² up to 12 joints, [-60, 60]²
    beyond.

    >>> from baranov.enumerate import baranov_trusses
    >>> triad = baranov_trusses(3)[0]
    >>> sorted(generic_integer_configuration(triad, np.random.default_rng(0)))
    ['P1', 'P2', 'P3']
    """
    names = [j.name for j in truss.joints]
    size = 30 if len(names) <= 12 else 60
    i, j, k = (np.array(t) for t in zip(*combinations(range(len(names)), 3), strict=True))
    while True:
        points = rng.integers(-size, size + 1, size=(len(names), 2))
        a, b, c = points[i], points[j], points[k]
        cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
        if len({tuple(p) for p in points}) == len(names) and np.all(np.abs(cross) >= 20):
            return {n: (Fraction(int(x)), Fraction(int(y))) for n, (x, y) in zip(names, points, strict=True)}
