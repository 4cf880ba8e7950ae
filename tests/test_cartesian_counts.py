"""Assembly-mode counts by elimination modulo primes on the Cartesian system
(solvers/msolve.py: msolve_solution_count_modulo; solvers/mode_counts.py: cartesian_degree),
against the characteristic degrees, the catalog, thesis Appendix A and pyrigi's realization
counts; and the coupling-degree-3 counts of the catalog (issue 20)."""

from __future__ import annotations

import json
import random
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.catalog.entries import assembly_mode_count, realization_sampled
from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import msolve as msolve_module
from baranov.solvers.exact.modular import characteristic_degree_modulo, random_prime
from baranov.solvers.mode_counts import CARTESIAN_PRIME_BITS, cartesian_degree, plan_system_degree
from baranov.solvers.msolve import find_msolve, msolve_solution_count_modulo, msolve_text
from baranov.topology import chain_from_link_graph
from baranov.topology.realizations import realization_count

ROOT = Path(__file__).resolve().parents[1]
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")
#: The first coupling-3 truss of 13 links in catalog order, and its realization count
#: (pyrigi's lnumber, bench/results/catalog-costs-13-coupling-3.jsonl).
THIRTEEN_N3 = ("L??????opd@k~?", 376)
THIRTEEN_N6601 = "L???Z?O?KooiWg"  # coupling degree 2, 390 modes


def test_coefficients_are_written_reduced_modulo_the_prime():
    """msolve 0.10.1 misreads integers of more than 64 bits in a prime field; the text
    it gets has them reduced (least absolute residues), and a prime dividing a
    denominator is refused."""
    big = {("x",): 1, (): -(10**21)}
    assert msolve_text(big) == "x-1000000000000000000000"
    assert msolve_text(big, prime=65521) == "x+14627"  # 10^21 = 50894 = -14627 mod 65521
    with pytest.raises(ArithmeticError, match="65521"):
        msolve_text({("x",): 1, (): Fraction(1, 65521)}, prime=65521)


@needs_msolve
@pytest.mark.parametrize("name, count, auxiliary", [("5-B1", 6, 1), ("7-B1", 14, 0), ("7-B2", 16, 0), ("7-B3", 18, 0),
                                                    ("9-B28", 58, 1), ("11-watt-baranov", 62, 0),
                                                    ("13-watt-baranov", 126, 0)])
def test_counts_of_the_examples_are_their_characteristic_degrees(name, count, auxiliary):
    """The examples' counts modulo a 30-bit prime are the degrees of their characteristic
    polynomials (tests/test_modular.py), times 2 for each auxiliary root. The pentad's and
    9/B28's grounds are given by distances with an irrational length: the Cartesian system
    places them by those distances, the length an auxiliary root that also solves the
    ground turned by π (they were placed in rounded coordinates, whose cleared denominators
    overflowed msolve's reading until the coefficients were reduced: 16 counted)."""
    found = msolve_solution_count_modulo(load_scene(ROOT / "examples" / f"{name}.json"), 1073741789)
    assert found == (count * 2**auxiliary, auxiliary)


@needs_msolve
def test_primes_msolve_refuses_are_refused_first():
    scene = load_scene(ROOT / "examples" / "7-B1.json")
    for prime in (2**31 - 1, 1073741790, 2):
        with pytest.raises(ValueError, match=str(prime)):
            msolve_solution_count_modulo(scene, prime)


@needs_msolve
@settings(max_examples=20, deadline=None)
@given(st.integers(0, 2**32), st.integers(0, 27))
def test_count_equals_the_characteristic_degree_on_the_same_instance(seed, index):
    """Property: on a random integer instance of a nine-link truss (coupling 1 or 2),
    elimination on the Cartesian system and the characteristic polynomial — two methods
    that share only the instance — count the same number of complex modes, each modulo
    its own random prime."""
    truss = baranov_trusses(9)[index]
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed)))
    primes = random.Random(seed)
    cartesian, _ = msolve_solution_count_modulo(scene, random_prime(primes, bits=CARTESIAN_PRIME_BITS))
    assert cartesian == characteristic_degree_modulo(scene, best_plan(truss), random_prime(primes))


@needs_msolve
@pytest.mark.parametrize("elimination", [cartesian_degree, plan_system_degree])
@pytest.mark.parametrize("links", [5, 7, 9, pytest.param(11, marks=pytest.mark.slow)])
def test_generic_counts_are_the_catalogs(links, elimination):
    """Every truss of 5, 7 and 9 links (and, slow, the 562 of 11 links: about 2 min on the
    Cartesian system, 30 min on the plan's): the generic count, on the Cartesian system
    and on the best plan's system (tests/test_plan_system.py), is the catalog's
    assembly-mode count (characteristic degrees; for 9 links the multiset of thesis
    Appendix A) and its realization count."""
    entries = [json.loads(line) for line in (ROOT / "catalog" / f"trusses-{links}.jsonl").read_text().splitlines()]
    for entry in entries:
        count, counts = elimination(chain_from_link_graph(entry["link_graph6"]))
        assert count == entry["assembly_modes"] == entry["realization_count"], entry["id"]
        assert counts == [count, count]


@needs_msolve
def test_a_coupling_three_truss_has_its_realization_count():
    """13/N3, coupling degree 3: the catalog counts it on the Cartesian system, and the
    count is its realization count (all 45 agree: docs/catalog-13.md)."""
    graph6, realizations = THIRTEEN_N3
    chain = chain_from_link_graph(graph6)
    plan = best_plan(chain)
    assert plan.number_of_parameters == 3
    modes, evidence = assembly_mode_count(chain, plan, True)
    assert modes == realizations
    assert "Cartesian system" in evidence and f"{realizations}, {realizations}" in evidence


@needs_msolve
def test_thirteen_link_coupling_two_is_counted_on_the_cartesian_system():
    """From 13 links on, coupling degree 2 is counted on the Cartesian system (2.4 s
    median against 112 s for the characteristic degree); 13/N6601 has 390 modes by the
    characteristic degree and by the realization count
    (bench/results/catalog-costs-13.jsonl)."""
    chain = chain_from_link_graph(THIRTEEN_N6601)
    plan = best_plan(chain)
    assert plan.number_of_parameters == 2
    modes, evidence = assembly_mode_count(chain, plan, True)
    assert modes == 390 and evidence.startswith("coupling degree 2: distinct solutions of the Cartesian system")


def test_realization_counts_are_sampled_from_thirteen_links():
    """Every truss up to 11 links and every coupling-3 truss has one; of the 20 437
    thirteen-link trusses, those whose graph6 digest falls in 1 class of 32."""
    nine = baranov_trusses(9)[0]
    assert realization_sampled(nine, "any", best_plan(nine))
    three = chain_from_link_graph(THIRTEEN_N3[0])
    assert realization_sampled(three, THIRTEEN_N3[0], best_plan(three))
    two = chain_from_link_graph(THIRTEEN_N6601)
    plan = best_plan(two)
    drawn = [realization_sampled(two, f"{THIRTEEN_N6601}{n}", plan) for n in range(3200)]
    assert 60 <= sum(drawn) <= 140  # 100 expected


def test_without_msolve_coupling_three_says_why_it_has_no_count(monkeypatch):
    monkeypatch.setattr(msolve_module, "find_msolve", lambda: None)
    chain = chain_from_link_graph(THIRTEEN_N3[0])
    modes, evidence = assembly_mode_count(chain, best_plan(chain), True)
    assert modes is None and "msolve" in evidence and "not installed" in evidence


@pytest.mark.slow
@needs_msolve
def test_a_coupling_three_count_against_a_live_realization_count():
    """The same, with pyrigi's count computed here (13 s)."""
    chain = chain_from_link_graph(THIRTEEN_N3[0])
    assert cartesian_degree(chain)[0] == realization_count(chain) == THIRTEEN_N3[1]
