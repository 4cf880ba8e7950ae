"""The plan's steps and closure conditions as one polynomial system modulo a prime
(solvers/exact/plan_system.py; solvers/mode_counts.py: plan_system_degree): its solutions
counted by msolve are the assembly modes, for coupling degrees 1 and 2 the characteristic
degree, for coupling degree 3 the realization count (issue 20)."""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.exact.characteristic import ExactMethodError, exact_plan
from baranov.solvers.exact.modular import characteristic_degree_modulo, random_prime
from baranov.solvers.exact.plan_system import SATURATION, plan_solution_count_modulo, plan_system
from baranov.solvers.mode_counts import CARTESIAN_PRIME_BITS, plan_system_degree
from baranov.solvers.msolve import find_msolve, solution_count_modulo
from baranov.topology import chain_from_link_graph

ROOT = Path(__file__).resolve().parents[1]
PRIME = 1073741789
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")
#: 13/N3, coupling degree 3, and its realization count (pyrigi's lnumber,
#: bench/results/catalog-costs-13-coupling-3.jsonl).
THIRTEEN_N3 = ("L??????opd@k~?", 376)


def _saturations(variables: list[str]) -> int:
    return sum(name.startswith(SATURATION) for name in variables)


def test_the_system_has_equations_per_step_the_conditions_and_the_saturations():
    scene = load_scene(ROOT / "examples" / "9-B28.json")
    plan = exact_plan(scene)
    variables, polynomials = plan_system(scene, plan, PRIME)
    free = sum(step.free_sign for step in plan.steps)
    saturations = _saturations(variables)
    assert variables[saturations:] == [name for index, step in enumerate(plan.steps)
                                       for name in (f"x{index}", f"y{index}", *([f"r{index}"] * step.free_sign))] + \
        ["t1", "t2"]
    assert len(polynomials) == 2 * len(plan.steps) + free + len(plan.closure_pairs) + saturations
    for n, saturation in enumerate(polynomials[-saturations:]):  # z_n · e − 1
        assert saturation[()] == -1
        assert all(monomial[0] == f"{SATURATION}{n}" for monomial in saturation if monomial)
    assert max(len(polynomial) for polynomial in polynomials) <= 11  # bounded: no expanded tower


@needs_msolve
@pytest.mark.parametrize("name, count", [("7-B1", 14), ("7-B2", 16), ("7-B3", 18), ("9-B28", 58),
                                         ("11-watt-baranov", 62), ("13-watt-baranov", 126)])
def test_counts_of_the_examples_are_their_characteristic_degrees(name, count):
    scene = load_scene(ROOT / "examples" / f"{name}.json")
    assert plan_solution_count_modulo(scene, exact_plan(scene), PRIME) == count


@needs_msolve
def test_without_the_saturations_undefined_points_are_counted_too():
    """Where a step or a computed distance is 0/0 the equations hold without a
    configuration: on 7/B1 a whole curve of such points (the solution set has positive
    dimension; so has 9/B28's). The saturations remove them."""
    scene = load_scene(ROOT / "examples" / "7-B1.json")
    variables, polynomials = plan_system(scene, exact_plan(scene), PRIME)
    saturations = _saturations(variables)
    assert saturations == 2
    assert solution_count_modulo(variables[saturations:], polynomials[:-saturations], PRIME) is None
    assert solution_count_modulo(variables, polynomials, PRIME) == 14


def test_a_prime_dividing_a_dimension_is_refused():
    truss = baranov_trusses(7)[0]
    sevenths = {joint: (x / 7, y / 7) for joint, (x, y) in
                generic_integer_configuration(truss, np.random.default_rng(1)).items()}
    scene = scene_of(truss, sevenths)
    with pytest.raises(ExactMethodError, match="prime 7 divides"):
        plan_solution_count_modulo(scene, best_plan(truss), 7)


def test_a_prime_dividing_a_step_denominator_is_refused():
    """The first step divides by the reference pair's squared distance, 981 = 3² · 109 on
    this instance: modulo 109 that step would read 0 = 0, so the prime is refused, not
    used."""
    truss = baranov_trusses(7)[0]
    plan = best_plan(truss)
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(0)))
    assert scene.known[frozenset(plan.reference)] == 981
    with pytest.raises(ExactMethodError, match="prime 109 divides"):
        plan_system(scene, plan, 109)


@needs_msolve
@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**32), st.integers(0, 27))
def test_count_equals_the_characteristic_degree_on_the_same_instance(seed, index):
    """Property: on a random integer instance of a nine-link truss (coupling 1 or 2), the
    plan's system modulo one prime (Gröbner bases) and the characteristic polynomial
    (norms, resultants, saturation by gcds) modulo another count the same modes."""
    truss = baranov_trusses(9)[index]
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed)))
    primes = random.Random(seed)
    plan = best_plan(truss)
    system = plan_solution_count_modulo(scene, plan, random_prime(primes, bits=CARTESIAN_PRIME_BITS))
    assert system == characteristic_degree_modulo(scene, plan, random_prime(primes))


@needs_msolve
def test_a_coupling_three_truss_by_its_plan():
    """13/N3 has coupling degree 3: its best plan's system counts its realization count
    (all 45 coupling-3 trusses: docs/catalog-13.md)."""
    graph6, realizations = THIRTEEN_N3
    chain = chain_from_link_graph(graph6)
    assert best_plan(chain).number_of_parameters == 3
    assert plan_system_degree(chain) == (realizations, [realizations, realizations])


def test_sliders_are_refused():
    sliders = load_scene(ROOT / "examples" / "7-B3-sliders-P8-P9.json")
    with pytest.raises(ExactMethodError, match="sliders"):
        plan_system(sliders, exact_plan(sliders), PRIME)
