"""The number of assembly modes of a truss: the degree of its characteristic polynomial on
random generic instances (thesis Appendix A counts them up to 9 links).

For generic dimensions the degree of the characteristic polynomial is the number of
assembly modes over C; a special instance can only lower it, and so can an unlucky prime
of the modular count. So the degree is taken on two random instances built from random
integer coordinates (each with its own random prime), and more are drawn while they
disagree (the larger degree is the generic one).
"""

from __future__ import annotations

import random
import zlib
from typing import Literal

import numpy as np

from baranov.planner import best_plan
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.topology import KinematicChain

from .exact.characteristic import characteristic_polynomial
from .exact.coupling_two import characteristic_polynomial_two
from .exact.modular import characteristic_degree_modulo, random_prime

#: Instances that must agree, and the most that are drawn.
AGREEING_INSTANCES = 2
MOST_INSTANCES = 6


def characteristic_degree(chain: KinematicChain, seed: int | None = None,
                          method: Literal["modular", "exact"] = "modular") -> tuple[int, list[int]]:
    """The generic degree of the characteristic polynomial of ``chain`` (coupling degree
    1 or 2; for 2, in the first parameter after eliminating the second), and the degrees
    seen on the instances drawn. ``seed`` defaults to a checksum of the chain's joints, so
    the result is reproducible.

    ``method="modular"`` (default) counts modulo a random 62-bit prime per instance
    (:func:`~baranov.solvers.exact.modular.characteristic_degree_modulo`: seconds for 11
    links); ``"exact"`` derives the polynomial over Q and keeps its genuine factors
    (:func:`~baranov.solvers.exact.characteristic.characteristic_polynomial`,
    :func:`~baranov.solvers.exact.coupling_two.characteristic_polynomial_two`: minutes for a
    coupling-2 truss of 9 links).

    >>> from baranov.enumerate import baranov_trusses
    >>> [characteristic_degree(t)[0] for t in baranov_trusses(7)]
    [18, 14, 16]
    >>> [characteristic_degree(t, method="exact")[0] for t in baranov_trusses(7)]
    [18, 14, 16]
    """
    if method not in ("modular", "exact"):
        raise ValueError(f"method {method!r}: expected 'modular' or 'exact'")
    if seed is None:
        seed = zlib.crc32(repr([joint.links for joint in chain.joints]).encode())
    rng = np.random.default_rng(seed)
    primes = random.Random(seed)
    plan = best_plan(chain)
    degrees: list[int] = []
    while len(degrees) < MOST_INSTANCES:
        scene = scene_of(chain, generic_integer_configuration(chain, rng))
        if method == "modular":
            degrees.append(characteristic_degree_modulo(scene, plan, random_prime(primes), seed=len(degrees)))
        elif plan.number_of_parameters == 2:
            degrees.append(characteristic_polynomial_two(scene, plan)[0].degree)
        else:
            degrees.append(characteristic_polynomial(scene, plan).degree)
        if len(degrees) >= AGREEING_INSTANCES and degrees.count(max(degrees)) >= AGREEING_INSTANCES:
            break
    return max(degrees), degrees
