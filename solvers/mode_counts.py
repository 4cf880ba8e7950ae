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
from collections.abc import Sequence
from typing import Literal

import numpy as np

from baranov.closure.sliders import takes_root
from baranov.planner import best_plan
from baranov.planner.sliders import SliderPlanError, slider_plan
from baranov.scene import scene_from_dict
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.scene.slider_instances import slider_instance_dict
from baranov.topology import KinematicChain

from .exact.characteristic import characteristic_polynomial
from .exact.coupling_two import characteristic_polynomial_two
from .exact.modular import characteristic_degree_modulo, random_prime
from .msolve import cartesian_jacobian_rank, msolve_solution_count

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


def slider_chain_degree(truss: KinematicChain, sliders: Sequence[str], seed: int | None = None
                        ) -> tuple[int | None, list[int], str]:
    """The generic number of assembly modes of the slider chain that turns the joints
    ``sliders`` of ``truss`` into slider joints (thesis ch. 4), the degrees seen on the
    instances drawn, and how it was counted:

    * ``"modular"``: as :func:`characteristic_degree` counts a truss's, the degree of the
      characteristic polynomial modulo a random prime, in the plan the slider
      constructions run (:func:`~baranov.planner.sliders.slider_plan`), on random
      instances with axes of rational length
      (:func:`~baranov.scene.slider_instances.slider_instance_dict`) until two agree;
    * ``"coupling 0"``: no parameter, one configuration per sign of the steps that take a
      square root (:func:`~baranov.closure.sliders.takes_root`; two lines meet once);
      Where the plan closes on two sliders of one link (:func:`~baranov.closure.sliders.turn_mismatch`),
      its condition sin θ = 0 also holds with that axis reversed, θ = π: the solutions
      of the linkage whose link turns that axis by π more, another generic instance of
      the same chain with as many modes. The degree modulo p counts both (the exact
      method's factor test tells them apart; modulo p there is no root to test), so it
      is divided by 2 per such closure pair; msolve's count on another instance checks
      it (the catalog's ``msolve_agrees``: every chain of 3–7 links);
    * ``"msolve"``: where no plan suits the sliders, the complex solutions of the
      Cartesian system counted by msolve over Q
      (:func:`~baranov.solvers.msolve.msolve_solution_count`, divided by 2 per auxiliary
      root).

    ``seed`` defaults to a checksum of the chain and the sliders. An admissible slider set
    (no loop closed by sliders only) can still give a chain that moves: one whose sliders
    lock the turn of a sub-chain that its revolute joints must then take up twice (7/N2
    with sliders P1, P2, P3, P4, P7). That is tested first, by the rank of the Cartesian
    system's Jacobian at the generating configuration of two random instances
    (:func:`~baranov.solvers.msolve.cartesian_jacobian_rank`), and such a chain gives
    (None, [], ``"moves"``): it is no Assur chain.

    The chains of thesis §4.2.2–4.2.4, in the joint numbering of their scenes: the
    published degrees 16, 12 and 18 are the generic counts.

    >>> from baranov.scene import load_scene
    >>> truss = load_scene("examples/7-B3-slider-P9.json").chain
    >>> [slider_chain_degree(truss, s)[0] for s in ([], ["P9"], ["P8", "P9"], ["P1"])]
    [18, 16, 12, 18]
    """
    if seed is None:
        seed = zlib.crc32(repr(([joint.links for joint in truss.joints], sorted(sliders))).encode())
    rng = np.random.default_rng(seed)
    if sliders and not any(slider_chain_is_rigid(truss, sliders, rng) for _ in range(AGREEING_INSTANCES)):
        return None, [], "moves"
    try:
        plan = slider_plan(truss, sliders)
    except SliderPlanError:
        plan = None
    if plan is not None and plan.number_of_parameters == 0:
        steps = sum(takes_root(step, sliders) for step in plan.steps)
        return 2 ** steps, [], "coupling 0"
    if not sliders:
        return (*characteristic_degree(truss, seed), "modular")
    primes = random.Random(seed)
    reversible = 0 if plan is None else sum(set(pair) <= set(sliders) for pair in plan.closure_pairs)
    degrees: list[int] = []
    while len(degrees) < MOST_INSTANCES:
        scene = scene_from_dict(slider_instance_dict(truss, list(sliders), rng, rational=True))
        if plan is not None:
            degrees.append(characteristic_degree_modulo(scene, plan, random_prime(primes), seed=len(degrees))
                           // 2 ** reversible)
        else:
            count, auxiliaries = msolve_solution_count(scene)
            degrees.append(0 if count is None else count // 2 ** auxiliaries)
        if len(degrees) >= AGREEING_INSTANCES and degrees.count(max(degrees)) >= AGREEING_INSTANCES:
            break
    return max(degrees), degrees, "modular" if plan is not None else "msolve"


def slider_chain_is_rigid(truss: KinematicChain, sliders: Sequence[str], rng: np.random.Generator) -> bool:
    """Whether the Cartesian system of a random instance of the slider chain has a
    Jacobian of full rank at its generating configuration (then the chain is rigid for
    generic dimensions; a rank-deficient answer may also be an unlucky instance, so
    callers ask twice)."""
    data = slider_instance_dict(truss, list(sliders), rng, rational=True)
    rank, unknowns = cartesian_jacobian_rank(scene_from_dict(data), data["generating_configuration"])
    return rank == unknowns
