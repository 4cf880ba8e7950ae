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
from collections.abc import Callable, Sequence
from typing import Literal

import numpy as np

from baranov.closure.sliders import takes_root
from baranov.planner import best_plan
from baranov.planner.sliders import SliderPlanError, slider_plan
from baranov.scene import Scene, scene_from_dict
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.scene.slider_instances import slider_instance_dict
from baranov.topology import KinematicChain

from .exact.characteristic import ExactMethodError, characteristic_polynomial
from .exact.coupling_two import characteristic_polynomial_two
from .exact.modular import characteristic_degree_modulo, random_prime
from .exact.plan_system import plan_solution_count_modulo
from .msolve import cartesian_jacobian_rank, msolve_solution_count_modulo

#: Instances that must agree, and the most that are drawn.
AGREEING_INSTANCES = 2
MOST_INSTANCES = 6
#: msolve's sparse FGLM takes primes below 2^30 (:func:`cartesian_degree`).
CARTESIAN_PRIME_BITS = 30


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
    seed = _chain_seed(chain) if seed is None else seed
    rng = np.random.default_rng(seed)
    primes = random.Random(seed)
    plan = best_plan(chain)

    def degree(instance: int) -> int:
        scene = scene_of(chain, generic_integer_configuration(chain, rng))
        if method == "modular":
            return characteristic_degree_modulo(scene, plan, random_prime(primes), seed=instance)
        if plan.number_of_parameters == 2:
            return characteristic_polynomial_two(scene, plan)[0].degree
        return characteristic_polynomial(scene, plan).degree

    return largest_agreeing(degree)


def cartesian_degree(chain: KinematicChain, seed: int | None = None) -> tuple[int, list[int]]:
    """The generic number of assembly modes over C of the truss ``chain``, by elimination
    modulo primes on its Cartesian system, and the counts seen on the instances drawn: on
    random integer instances, each with its own random prime below 2³⁰, the number of
    distinct solutions of the system modulo the prime
    (:func:`~baranov.solvers.msolve.msolve_solution_count_modulo`, msolve's Gröbner basis
    and rational parametrization over F_p), until two agree on the largest
    (:func:`largest_agreeing`). ``seed`` as for :func:`characteristic_degree`.

    It needs no plan, so it counts every coupling degree alike — the 45 thirteen-link
    trusses of coupling degree 3 included, in about 2 s each — and it shares nothing with
    :func:`characteristic_degree` but the random instance: a check of it, and of the
    realization count (:func:`~baranov.topology.realizations.realization_count`). Needs
    the msolve binary (:class:`~baranov.solvers.msolve.MsolveUnavailable` otherwise).

    >>> from baranov.enumerate import baranov_trusses
    >>> [cartesian_degree(t)[0] for t in baranov_trusses(7)]  # doctest: +SKIP
    [18, 14, 16]
    """
    return _elimination_count(chain, seed, lambda scene, prime: msolve_solution_count_modulo(scene, prime)[0])


def plan_system_degree(chain: KinematicChain, seed: int | None = None) -> tuple[int, list[int]]:
    """The generic number of assembly modes over C of the truss ``chain`` by its best
    plan's own bilateration steps and closure conditions, for every coupling degree: on
    random integer instances, each with its own random prime below 2³⁰, the number of
    distinct solutions of the plan as one polynomial system modulo the prime
    (:func:`~baranov.solvers.exact.plan_system.plan_solution_count_modulo`, msolve),
    until two agree on the largest (:func:`largest_agreeing`). ``seed`` as for
    :func:`characteristic_degree`, whose instances it draws. For coupling degrees 1 and 2
    it is a second derivation of :func:`characteristic_degree` (no norms, no resultants,
    no saturation by gcds); for coupling degree 3 it is the plan's only one. Needs the
    msolve binary (:class:`~baranov.solvers.msolve.MsolveUnavailable` otherwise).

    >>> from baranov.enumerate import baranov_trusses
    >>> [plan_system_degree(t)[0] for t in baranov_trusses(7)]  # doctest: +SKIP
    [18, 14, 16]
    """
    plan = best_plan(chain)

    def solutions(scene, prime: int) -> int | None:
        try:
            return plan_solution_count_modulo(scene, plan, prime)
        except ExactMethodError:  # the prime divides a dimension a step needs: this instance counts 0
            return None

    return _elimination_count(chain, seed, solutions)


def _elimination_count(chain: KinematicChain, seed: int | None,
                       solutions: Callable[[Scene, int], int | None]) -> tuple[int, list[int]]:
    """:func:`largest_agreeing` over random integer instances of ``chain``, each counted by
    ``solutions(scene, prime)`` modulo its own random prime below 2³⁰ (None — a solution
    set of positive dimension, or a prime the instance cannot use — counts 0, and another
    instance is drawn)."""
    seed = _chain_seed(chain) if seed is None else seed
    rng = np.random.default_rng(seed)
    primes = random.Random(seed)

    def count(instance: int) -> int:
        found = solutions(scene_of(chain, generic_integer_configuration(chain, rng)),
                          random_prime(primes, bits=CARTESIAN_PRIME_BITS))
        return 0 if found is None else found

    return largest_agreeing(count)


def largest_agreeing(count_instance: Callable[[int], int]) -> tuple[int, list[int]]:
    """Counts ``count_instance(0)``, ``count_instance(1)``, … until AGREEING_INSTANCES of
    them equal the largest (at most MOST_INSTANCES): the largest, and every count. A
    special instance or an unlucky prime can only lower a generic count, so the largest
    seen twice is taken as the generic one."""
    counts: list[int] = []
    while len(counts) < MOST_INSTANCES:
        counts.append(count_instance(len(counts)))
        if len(counts) >= AGREEING_INSTANCES and counts.count(max(counts)) >= AGREEING_INSTANCES:
            break
    return max(counts), counts


def _chain_seed(chain: KinematicChain) -> int:
    """A checksum of the chain's joints: the default seed of the counts."""
    return zlib.crc32(repr([joint.links for joint in chain.joints]).encode())


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
    * ``"msolve"``: where no plan suits the sliders, or the plan's closure conditions
      vanish identically modulo p on an instance (9/N25 with eight sliders P2, P4, P5,
      P6, P8, P9, P10, P12), or its characteristic polynomial has no root left — which
      cannot be, since each instance is drawn around a configuration — because the
      saturations by undefined points removed every mode (9/N27 with sliders P3, P4, P7,
      P9, P10, P11: 4 modes by msolve, the exact and the numeric backend), the complex
      solutions of the
      Cartesian system counted by msolve modulo a random prime below 2³⁰
      (:func:`~baranov.solvers.msolve.msolve_solution_count_modulo`, divided by 2 per
      auxiliary root; over Q until 2026-11-26, the same counts, slower).

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

    def by_plan(instance: int) -> int:
        scene = scene_from_dict(slider_instance_dict(truss, list(sliders), rng, rational=True))
        degree = characteristic_degree_modulo(scene, plan, random_prime(primes), seed=instance) // 2 ** reversible
        if degree == 0:  # the instance was drawn around a configuration: the saturations removed every mode
            raise ExactMethodError("no mode left in the plan's characteristic polynomial")
        return degree

    def by_msolve(instance: int) -> int:
        scene = scene_from_dict(slider_instance_dict(truss, list(sliders), rng, rational=True))
        count, auxiliaries = msolve_solution_count_modulo(scene, random_prime(primes, bits=CARTESIAN_PRIME_BITS))
        return 0 if count is None else count // 2 ** auxiliaries

    if plan is not None:
        try:
            return (*largest_agreeing(by_plan), "modular")
        except ExactMethodError:  # the plan's conditions vanish identically: count without it
            pass
    return (*largest_agreeing(by_msolve), "msolve")


def slider_chain_is_rigid(truss: KinematicChain, sliders: Sequence[str], rng: np.random.Generator) -> bool:
    """Whether the Cartesian system of a random instance of the slider chain has a
    Jacobian of full rank at its generating configuration (then the chain is rigid for
    generic dimensions; a rank-deficient answer may also be an unlucky instance, so
    callers ask twice)."""
    data = slider_instance_dict(truss, list(sliders), rng, rational=True)
    rank, unknowns = cartesian_jacobian_rank(scene_from_dict(data), data["generating_configuration"])
    return rank == unknowns
