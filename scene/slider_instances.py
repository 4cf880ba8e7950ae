"""Random slider chains with a known assembly mode: a random configuration of a truss, a
random admissible set of its joints turned into sliders (thesis ch. 4), each with a random
axis through the joint and its second link's point moved along it. The configuration is
an assembly mode of the scene it defines, and every number stays an integer, so that the
scene is exact (msolve's oracle needs that)."""

from __future__ import annotations

import numpy as np

from baranov.enumerate.sliders import admissible_slider_sets
from baranov.topology import KinematicChain
from baranov.topology.graphs import joints_of_links

from .instances import generic_integer_configuration


def random_slider_set(truss: KinematicChain, rng: np.random.Generator, count: int | None = None) -> list[str]:
    """An admissible set of ``count`` joints (no loop of links closed by sliders only;
    :func:`~baranov.enumerate.sliders.admissible_slider_sets`), uniform among those of
    that size; ``count`` itself uniform in 1 … the largest size when None. O(2^J)."""
    table = admissible_slider_sets(truss)
    sizes = np.array([bin(subset).count("1") for subset in range(len(table))])
    if count is None:
        count = int(rng.integers(1, sizes[table].max() + 1))
    choices = np.flatnonzero(table & (sizes == count))
    if len(choices) == 0:
        raise ValueError(f"{count} sliders: no admissible set of that size")
    subset = int(rng.choice(choices))
    return [joint.name for k, joint in enumerate(truss.joints) if subset >> k & 1]


#: Directions of rational length (Pythagorean triples): with them every axis frame of an
#: integer configuration is rational, as the exact method needs (scene/sliders.py).
RATIONAL_DIRECTIONS = ((1, 0), (3, 4), (4, 3), (5, 12), (12, 5), (8, 15), (15, 8), (7, 24), (24, 7))


def _direction(rng: np.random.Generator, box: int, rational: bool) -> tuple[int, int]:
    if not rational:
        return tuple(int(c) for c in rng.integers(-box, box + 1, size=2))
    x, y = RATIONAL_DIRECTIONS[int(rng.integers(len(RATIONAL_DIRECTIONS)))]
    quarter = int(rng.integers(4))  # turned by a multiple of 90°
    for _ in range(quarter):
        x, y = -y, x
    return x, y


def slider_instance_dict(truss: KinematicChain, sliders: list[str], rng: np.random.Generator,
                         coordinates: dict | None = None, ground: int = 0, box: int = 5,
                         rational: bool = False) -> dict:
    """The JSON form of a scene of ``truss`` with the joints ``sliders`` turned into
    sliders, and its generating configuration (joint names, ``P9'``/``P9''`` for a
    slider's two points) under ``"generating_configuration"``: each slider's axis has a
    random integer direction in [−box, box]², no two parallel, its second link's point is moved along it
    by a random multiple in [−2, 2] (0: the points coincide), and each link's angle is
    given as the exact direction [x, y] of the vector to one of its other joints.
    ``coordinates``: the truss's configuration (a generic integer one by default);
    ``rational``: directions of rational length only (:data:`RATIONAL_DIRECTIONS`), so
    that the exact method takes the scene."""
    coordinates = coordinates or generic_integer_configuration(truss, rng)
    links = joints_of_links(truss)
    moved: dict[str, tuple[int, int]] = {}
    directions: dict[str, tuple[int, int]] = {}
    for joint in sliders:
        # no two axes parallel: two sliders of one link with parallel axes let it slide
        # (a generic instance has none; docs/sliders.md says what happens where one does)
        while True:
            direction = _direction(rng, box, rational)
            if direction != (0, 0) and all(direction[0] * d[1] != direction[1] * d[0] for d in directions.values()):
                break
        directions[joint] = direction
        taken = {tuple(int(c) for c in point) for point in coordinates.values()} | set(moved.values())
        while True:  # never onto another joint (a link's first two joints may not coincide)
            shift = int(rng.integers(-2, 3))
            moved[joint] = (int(coordinates[joint][0]) + shift * direction[0],
                            int(coordinates[joint][1]) + shift * direction[1])
            if shift == 0 or moved[joint] not in taken:
                break
    holders = {joint: [index for index, names in enumerate(links) if joint in names] for joint in sliders}

    def point(joint: str, index: int) -> tuple[int, int]:
        if joint in moved and holders[joint][1] == index:
            return moved[joint]
        return int(coordinates[joint][0]), int(coordinates[joint][1])

    entries = [{"name": f"L{index}", "joints": {n: list(point(n, index)) for n in names}}
               for index, names in enumerate(links)]
    slider_entries = []
    for joint in sliders:
        angles = {}
        for index in holders[joint]:
            reference = next(n for n in links[index] if n != joint)
            (x, y), (fx, fy) = point(reference, index), point(joint, index)
            dx, dy = directions[joint]
            # (P_ref − P_i) · conj(d): the angle of P_ref seen from the slider's point, from the axis
            angles[f"L{index}"] = {reference: [(x - fx) * dx + (y - fy) * dy, (y - fy) * dx - (x - fx) * dy]}
        slider_entries.append({"joint": joint, "angles": angles})
    configuration = {n: point(n, 0) for n in coordinates if n not in moved}
    for joint in sliders:
        first, second = holders[joint]
        configuration[joint + "'"], configuration[joint + "''"] = point(joint, first), point(joint, second)
    return {"links": entries, "ground": f"L{ground}", "sliders": slider_entries,
            "generating_configuration": {n: list(p) for n, p in configuration.items()}}
