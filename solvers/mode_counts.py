"""The number of assembly modes of a truss: the degree of its characteristic polynomial on
random generic instances (thesis Appendix A counts them up to 9 links).

For generic dimensions the degree of the characteristic polynomial is the number of
assembly modes over C; a special instance can only lower it. So the degree is taken on
two random instances built from random integer coordinates, and more are drawn while they
disagree (the larger degree is the generic one).
"""

from __future__ import annotations

import zlib

import numpy as np
from baranov.planner import best_plan
from baranov.topology import KinematicChain

from .characteristic import characteristic_polynomial
from .coupling_two import characteristic_polynomial_two
from .instances import generic_integer_configuration, scene_of

#: Instances that must agree, and the most that are drawn.
AGREEING_INSTANCES = 2
MOST_INSTANCES = 6


def characteristic_degree(chain: KinematicChain, seed: int | None = None) -> tuple[int, list[int]]:
    """The generic degree of the characteristic polynomial of ``chain`` (coupling degree
    1 or 2; for 2, in the first parameter after eliminating the second:
    :func:`~baranov.solvers.coupling_two.characteristic_polynomial_two`), and the degrees
    seen on the instances drawn. ``seed`` defaults to a checksum of the
    chain's joints, so the result is reproducible.

    >>> from baranov.enumerate import baranov_trusses
    >>> [characteristic_degree(t)[0] for t in baranov_trusses(7)]
    [18, 14, 16]
    """
    if seed is None:
        seed = zlib.crc32(repr([joint.links for joint in chain.joints]).encode())
    rng = np.random.default_rng(seed)
    plan = best_plan(chain)
    degrees: list[int] = []
    while len(degrees) < MOST_INSTANCES:
        scene = scene_of(chain, generic_integer_configuration(chain, rng))
        if plan.number_of_parameters == 2:
            degrees.append(characteristic_polynomial_two(scene, plan)[0].degree)
        else:
            degrees.append(characteristic_polynomial(scene, plan).degree)
        if len(degrees) >= AGREEING_INSTANCES and degrees.count(max(degrees)) >= AGREEING_INSTANCES:
            break
    return max(degrees), degrees
