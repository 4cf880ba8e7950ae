"""Assembly-mode counts modulo a prime (baranov.solvers.exact.modular) against the degrees
over Q, thesis Appendix A and pyrigi's realization counts."""

import random
from pathlib import Path

import flint
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import APPENDIX_A_ASSEMBLY_MODES
from baranov.planner import best_plan
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import ExactMethodError, characteristic_polynomial
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.exact.coupling_two import characteristic_polynomial_two
from baranov.solvers.exact.modular import (
    characteristic_degree_modulo,
    lifted_characteristic_polynomial,
    random_prime,
    saturate,
)
from baranov.solvers.mode_counts import characteristic_degree
from baranov.topology.realizations import realization_count

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SEVEN = baranov_trusses(7)


def test_saturate_removes_every_shared_factor_with_its_multiplicity():
    p = 1_000_003
    t = flint.nmod_poly([0, 1], p)
    genuine = t**2 + 3
    assert saturate(genuine * t**5 * (t + 1) ** 3, t * (t + 1)) == genuine
    assert saturate(genuine, t) == genuine


def test_modular_counts_equal_the_degrees_over_q_up_to_nine_links():
    """Every coupling-1 truss of 5, 7 and 9 links, one random instance each: the count
    modulo a random prime is the degree of the characteristic polynomial over Q (whose
    extraneous factors were found by testing each irreducible factor at a root)."""
    rng, primes = np.random.default_rng(11), random.Random(11)
    for links in (5, 7, 9):
        for truss in baranov_trusses(links):
            plan = best_plan(truss)
            if plan.number_of_parameters != 1:
                continue
            scene = scene_of(truss, generic_integer_configuration(truss, rng))
            assert characteristic_degree_modulo(scene, plan, random_prime(primes)) == \
                characteristic_polynomial(scene, plan).degree


def test_published_examples_modulo_a_prime():
    """The thesis examples: 7/B1-B3 14, 16, 18; Watt-Baranov 11 and 13 links 62 and 126
    (2^(k+1) - 2); 9/B28 58 (coupling degree 2, thesis §3.4.1.4)."""
    expected = {"7-B1": 14, "7-B2": 16, "7-B3": 18, "11-watt-baranov": 62, "13-watt-baranov": 126, "9-B28": 58}
    for name, degree in expected.items():
        scene = load_scene(EXAMPLES / f"{name}.json")
        assert characteristic_degree_modulo(scene, solvable_plan(scene), random_prime(random.Random(name))) == degree


def test_coupling_two_nine_link_counts_are_appendix_a():
    """9/B25-B28 by their realization counts (52, 56, 50, 58 are pairwise different), two
    random instances each: the modular count is the Appendix A value."""
    values = {APPENDIX_A_ASSEMBLY_MODES[f"9/B{n}"] for n in range(25, 29)}
    seen = set()
    for truss in baranov_trusses(9):
        if best_plan(truss).number_of_parameters == 2:
            degree, degrees = characteristic_degree(truss)
            assert degrees == [degree, degree]
            assert degree == realization_count(truss)
            seen.add(degree)
    assert seen == values


@pytest.mark.slow
def test_coupling_two_modular_counts_equal_the_degrees_over_q():
    """The four coupling-2 trusses of 9 links, one random instance each (about 10 min):
    the modular count = the degree of the genuine part of the resultant over Q (the
    route that factors Res_v(G_1, G_2) and tests every factor, independent of the
    modular method), and the lifted polynomial is that genuine part."""
    rng = np.random.default_rng(5)
    for truss in baranov_trusses(9):
        plan = best_plan(truss)
        if plan.number_of_parameters == 2:
            scene = scene_of(truss, generic_integer_configuration(truss, rng))
            product = characteristic_polynomial_two(scene, plan, route="resultant")[0].polynomial
            assert characteristic_degree_modulo(scene, plan, random_prime(random.Random(5))) == product.degree()
            lifted = lifted_characteristic_polynomial(scene, plan)
            assert lifted == product or lifted == -product


@pytest.mark.parametrize("index", [0, 60, 135, 440])
def test_eleven_link_counts_equal_realization_counts(index):
    """A sample of 11-link trusses (both coupling degrees; the catalog has all 562)."""
    truss = baranov_trusses(11)[index]
    assert characteristic_degree(truss)[0] == realization_count(truss)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32), st.sampled_from(range(len(SEVEN))))
def test_any_large_prime_gives_the_degree_over_q(seed, index):
    """Property: on a random instance of a 7-link truss, a random 62-bit prime gives the
    degree over Q."""
    truss = SEVEN[index]
    plan = best_plan(truss)
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed)))
    prime = random_prime(random.Random(seed))
    assert characteristic_degree_modulo(scene, plan, prime) == characteristic_polynomial(scene, plan).degree


def test_small_primes_can_only_lower_a_coupling_one_count():
    """An unlucky prime divides a leading coefficient or merges a genuine factor with an
    extraneous one: the count drops, it never rises (coupling degree 1)."""
    truss = baranov_trusses(9)[0]
    plan = best_plan(truss)
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(0)))
    degree = characteristic_polynomial(scene, plan).degree
    counts = []
    for prime in (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47):
        try:
            counts.append(characteristic_degree_modulo(scene, plan, prime))
        except (ExactMethodError, ZeroDivisionError):
            continue  # the prime divides a denominator of the dimensions or of a step
    assert counts and max(counts) <= degree
    assert min(counts) < degree
