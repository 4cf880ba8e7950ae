"""Adversarial instances (issue 25): the integer configurations a user types — small
boxes, joints in line, joints at one point, modes at a domain edge, double roots — made
on purpose, one kind at a time. Each instance is built from a configuration, which is one
of its assembly modes; all dimensions are exact.

Kinds (``ADVERSARIAL_KINDS``):

- ``small-box``: every joint at a random integer point of [−box, box]²; links keep
  their joints apart, anything else may happen (collinear triples, coincident joints of
  different links, collinear ternary links).
- ``collinear``: three or four joints, chosen at random, on one line
  (:func:`~baranov.scene.hard_instances.collinear_joints_configuration`).
- ``coincident``: two joints of different links at one point
  (:func:`~baranov.scene.hard_instances.coincident_joints_configuration`).
- ``domain-edge``: a free-sign triangle of the plan flat, so the generating mode's
  parameters lie on the edge of their domain (thesis §2.3: a parameter's range ends
  where a triangle degenerates).
- ``double-root``: a configuration at which the framework is infinitesimally flexible
  (its rigidity matrix, ground pinned, loses rank), so the characteristic polynomial has
  a multiple root there — two modes merging (thesis §3.3.3, singularities).

Slider chains (:func:`adversarial_slider_scene`): a configuration of one of these kinds,
a random admissible slider set, and axes of rational length through the sliders
(:func:`~baranov.scene.slider_instances.slider_instance_dict`), so that both backends and
msolve take the scene.
"""

from __future__ import annotations

from fractions import Fraction
from itertools import combinations

import numpy as np
from flint import fmpz_mat

from baranov.planner import plan_avoiding
from baranov.topology import KinematicChain
from baranov.topology.graphs import joints_of_links

from .hard_instances import coincident_joints_configuration, collinear_joints_configuration
from .instances import scene_of
from .model import Scene, SceneError, scene_from_dict
from .slider_instances import random_slider_set, slider_instance_dict

ADVERSARIAL_KINDS = ("small-box", "collinear", "coincident", "domain-edge", "double-root")

#: Random configurations drawn before ``double-root`` gives up on a box.
DOUBLE_ROOT_ATTEMPTS = 20_000

Configuration = dict[str, tuple[Fraction, Fraction]]


def small_box_configuration(truss: KinematicChain, rng: np.random.Generator, box: int = 3) -> Configuration:
    """Random integer joint coordinates in [−box, box]², the joints of each link apart.

    >>> from baranov.enumerate import baranov_trusses
    >>> points = small_box_configuration(baranov_trusses(7)[0], np.random.default_rng(0), box=2)
    >>> all(abs(x) <= 2 and abs(y) <= 2 for x, y in points.values())
    True
    """
    names = [joint.name for joint in truss.joints]
    links = joints_of_links(truss)
    while True:
        points = {n: tuple(int(c) for c in rng.integers(-box, box + 1, size=2)) for n in names}
        if all(len({points[j] for j in link}) == len(link) for link in links):
            return {n: (Fraction(x), Fraction(y)) for n, (x, y) in points.items()}


def domain_edge_configuration(truss: KinematicChain, rng: np.random.Generator, box: int = 4) -> Configuration:
    """A small-box configuration with one free-sign triangle (i, j, k) of the plan made
    flat: k moved to a lattice point of the line i j inside the box.

    >>> from baranov.enumerate import baranov_trusses
    >>> points = domain_edge_configuration(baranov_trusses(7)[1], np.random.default_rng(3))
    >>> len(points)
    9
    """
    while True:
        points = small_box_configuration(truss, rng, box)
        scene = _scene_or_none(truss, points)
        if scene is None:
            continue
        plan = plan_avoiding(scene.chain, scene.coincident_pairs)  # the plan the solvers will take
        if plan is None:
            continue
        triangles = plan.free_sign_triangles
        if not triangles:
            return points
        i, j, k = triangles[rng.integers(len(triangles))]
        (xi, yi), (xj, yj) = points[i], points[j]
        step = (xj - xi, yj - yi)
        divisor = np.gcd(int(step[0]), int(step[1])) or 1
        step = (step[0] / divisor, step[1] / divisor)
        on_line = [(xi + t * step[0], yi + t * step[1]) for t in range(-2 * box, 2 * box + 1)]
        on_line = [p for p in on_line if abs(p[0]) <= box and abs(p[1]) <= box and p not in (points[i], points[j])]
        if not on_line:
            continue
        points[k] = on_line[rng.integers(len(on_line))]
        if _scene_or_none(truss, points) is not None:
            return points


def double_root_configuration(truss: KinematicChain, rng: np.random.Generator, box: int = 2,
                              attempts: int = DOUBLE_ROOT_ATTEMPTS) -> Configuration:
    """A small-box configuration at which the framework, its ground link pinned, is
    infinitesimally flexible: its rigidity matrix (one row per pair of joints of a moving
    link, two columns per joint off the ground) has rank below the number of columns,
    decided exactly over the integers. Raises ValueError after ``attempts`` draws.

    >>> from baranov.enumerate import baranov_trusses
    >>> truss = baranov_trusses(7)[0]
    >>> points = double_root_configuration(truss, np.random.default_rng(0))
    >>> is_infinitesimally_flexible(truss, points)
    True
    """
    for _ in range(attempts):
        points = small_box_configuration(truss, rng, box)
        if is_infinitesimally_flexible(truss, points) and _scene_or_none(truss, points) is not None:
            return points
    raise ValueError(f"no infinitesimally flexible configuration in [-{box}, {box}]² after {attempts} draws")


def is_infinitesimally_flexible(truss: KinematicChain, points: Configuration, ground: int = 0) -> bool:
    """Whether the rigidity matrix of ``points`` with link ``ground`` pinned has rank
    below twice the number of joints off the ground (exact, flint's fmpz_mat.rank)."""
    links = joints_of_links(truss)
    pinned = set(links[ground])
    free = [j.name for j in truss.joints if j.name not in pinned]
    column = {name: 2 * n for n, name in enumerate(free)}
    rows = []
    for index, link in enumerate(links):
        if index == ground:
            continue
        for u, v in combinations(link, 2):
            row = [0] * (2 * len(free))
            for a, b in ((u, v), (v, u)):
                if a in column:
                    row[column[a]] = int(points[a][0] - points[b][0])
                    row[column[a] + 1] = int(points[a][1] - points[b][1])
            rows.append(row)
    return fmpz_mat(rows).rank() < 2 * len(free)


def adversarial_configuration(truss: KinematicChain, kind: str, rng: np.random.Generator,
                              box: int | None = None) -> Configuration:
    """A configuration of ``kind`` (one of ADVERSARIAL_KINDS; module docstring) with
    coordinates in [−box, box]² (default per kind: 3, 4, 4, 4, 2)."""
    if kind == "small-box":
        return small_box_configuration(truss, rng, box or 3)
    if kind == "collinear":
        return collinear_joints_configuration(truss, rng, on_line=int(rng.integers(3, 5)), box=box or 4,
                                              direction=("vertical", "horizontal", "diagonal",
                                                         "antidiagonal")[rng.integers(4)])
    if kind == "coincident":
        return coincident_joints_configuration(truss, rng, box or 4)
    if kind == "domain-edge":
        return domain_edge_configuration(truss, rng, box or 4)
    if kind == "double-root":
        return double_root_configuration(truss, rng, box or 2)
    raise ValueError(f"kind {kind!r}: one of {', '.join(ADVERSARIAL_KINDS)}")


def adversarial_scene(truss: KinematicChain, kind: str, rng: np.random.Generator,
                      box: int | None = None) -> tuple[Scene, Configuration]:
    """A scene of ``kind`` (retrying until the scene is valid) and its generating
    configuration.

    >>> from baranov.enumerate import baranov_trusses
    >>> scene, points = adversarial_scene(baranov_trusses(7)[2], "coincident", np.random.default_rng(5))
    >>> scene.exact, len(points)
    (True, 9)
    """
    while True:
        points = adversarial_configuration(truss, kind, rng, box)
        scene = _scene_or_none(truss, points)
        if scene is not None:
            return scene, points


def adversarial_slider_scene(truss: KinematicChain, kind: str, rng: np.random.Generator,
                             box: int | None = None) -> tuple[dict, Scene]:
    """A slider chain of ``truss`` drawn from a configuration of ``kind``
    (:func:`adversarial_configuration`), with a random admissible slider set and random
    axes of rational length (retrying until the scene is valid): its JSON form, whose
    ``"generating_configuration"`` is one of its modes (a slider's two points named
    ``P9'``, ``P9''``), and the scene.

    >>> from baranov.enumerate import baranov_trusses
    >>> data, scene = adversarial_slider_scene(baranov_trusses(7)[0], "collinear", np.random.default_rng(3))
    >>> scene.exact, len(scene.sliders) > 0
    (True, True)
    """
    while True:
        points = adversarial_configuration(truss, kind, rng, box)
        coordinates = {joint: (int(x), int(y)) for joint, (x, y) in points.items()}  # integers by construction
        data = slider_instance_dict(truss, random_slider_set(truss, rng), rng, coordinates=coordinates, rational=True)
        try:
            return data, scene_from_dict(data)
        except SceneError:
            continue


def _scene_or_none(truss: KinematicChain, points: Configuration) -> Scene | None:
    try:
        return scene_of(truss, points)
    except SceneError:
        return None
