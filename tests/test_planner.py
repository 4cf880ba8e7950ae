"""Bilateration plans: coupling degrees against the Yang–Yao table, plan structure,
constraints and bad input."""

import collections

import pytest

from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import thesis_truss
from baranov.planner import StepKind, best_plan, bilateration_plans, coupling_degree
from baranov.topology import TopologyError, chain_from_link_graph

#: Thesis Table 3.1 (after Yang & Yao 1994): trusses per coupling degree.
PUBLISHED_COUPLING = {3: {0: 1}, 5: {1: 1}, 7: {1: 3}, 9: {1: 24, 2: 4}, 11: {1: 197, 2: 42}}
#: Verified here over the 562 trusses of 11 links (docs/planner.md).
VERIFIED_COUPLING_11 = {1: 409, 2: 153}


@pytest.mark.parametrize("links", [3, 5, 7, 9])
def test_coupling_degrees_match_yang_yao(links):
    found = collections.Counter(coupling_degree(t) for t in baranov_trusses(links))
    assert dict(found) == PUBLISHED_COUPLING[links]


def test_coupling_degrees_of_eleven_links():
    found = collections.Counter(coupling_degree(t) for t in baranov_trusses(11))
    assert dict(found) == VERIFIED_COUPLING_11
    # Published 197/42 of 239 trusses; the 239 is not the true count (docs/enumeration.md).
    assert sum(PUBLISHED_COUPLING[11].values()) == 239


def test_thesis_trusses_have_the_thesis_coupling_degree():
    degrees = {t: coupling_degree(thesis_truss(t).chain()) for t in ["3/B1", "5/B1", "7/B1", "7/B2", "7/B3", "9/B28"]}
    assert degrees == {"3/B1": 0, "5/B1": 1, "7/B1": 1, "7/B2": 1, "7/B3": 1, "9/B28": 2}


@pytest.mark.parametrize("links", [3, 5, 7, 9])
def test_best_plans_are_complete_and_square(links):
    for truss in baranov_trusses(links):
        plan = best_plan(truss)
        located = set(plan.reference) | {step.joint for step in plan.steps}
        assert located == {j.name for j in truss.joints}
        assert len(plan.steps) == truss.number_of_joints - 2
        assert len(plan.parameters) == coupling_degree(truss)
        assert len(plan.closure_pairs) == len(plan.parameters)  # a square system
        assert plan.orientation_checks == ()
        # one free sign per loop: J - 2 - Σ(k - 2) over rigid links = (L - 1) / 2
        assert len(plan.free_sign_triangles) == (links - 1) // 2


def test_rigid_links_are_built_from_their_own_joints():
    """Every joint of a ternary or larger link beyond its first two is located from two of
    that link's joints with the fixed sign, so no mirror image of a link can satisfy the
    closure conditions (the issue's spurious-roots warning)."""
    for links in (5, 7, 9):
        for truss in baranov_trusses(links):
            plan = best_plan(truss)
            order = list(plan.reference) + [s.joint for s in plan.steps]
            by_joint = {s.joint: s for s in plan.steps}
            for link in range(truss.number_of_links):
                joints = sorted((j.name for j in truss.joints if link in j.links), key=order.index)
                for later in joints[2:]:
                    step = by_joint[later]
                    assert step.kind is StepKind.LINK and step.link == link
                    assert set(step.base) <= set(joints)


def test_constrained_to_the_thesis_parameter_of_the_pentad():
    plans = bilateration_plans(thesis_truss("5/B1").chain(), count=3, parameters=[("P1", "P6")])
    assert all(p.parameters == (("P1", "P6"),) for p in plans)
    assert plans[0].closure_pairs == (("P2", "P5"),)


def test_k_best_plans_are_ranked_and_distinct():
    plans = bilateration_plans(thesis_truss("7/B3").chain(), count=10)
    keys = [p.ranking_key() for p in plans]
    assert keys == sorted(keys) and len(set(keys)) == len(keys) == 10
    assert all(len(p.parameters) == 1 for p in plans)


def test_fixing_the_thesis_parameters_of_9b28():
    plan = bilateration_plans(thesis_truss("9/B28").chain(), parameters=[("P1", "P4"), ("P2", "P4")])[0]
    assert {frozenset(p) for p in plan.parameters} == {frozenset(("P1", "P4")), frozenset(("P2", "P4"))}
    assert len(plan.closure_pairs) == 2 and plan.orientation_checks == ()


def test_chain_of_triads_is_ruler_and_compass():
    two_triads = chain_from_link_graph([(0, 1), (1, 2), (0, 2), (2, 3), (3, 4), (4, 2)])
    assert coupling_degree(two_triads) == 0
    plan = best_plan(two_triads)
    assert plan.parameters == () and plan.closure_pairs == ()


def test_quaternary_and_pentagonal_links():
    seven_b3 = thesis_truss("7/B3").chain()  # has a quaternary link
    assert max(seven_b3.link_degrees) == 4 and coupling_degree(seven_b3) == 1
    five_ary = [t for t in baranov_trusses(9) if max(t.link_degrees) == 5]
    assert len(five_ary) == 1 and coupling_degree(five_ary[0]) == 1


@pytest.mark.parametrize(
    ("edges", "message"),
    [
        ([(0, 1), (1, 2), (2, 3), (3, 0)], "mobility F = 3\\(L-1\\) - 2J = 1"),
        ([(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)], "mobility F = 3\\(L-1\\) - 2J = -1"),
    ],
)
def test_non_rigid_input_is_a_topology_error(edges, message):
    with pytest.raises(TopologyError, match=message):
        coupling_degree(chain_from_link_graph(edges))


def test_over_constrained_part_is_named():
    # Four mutually jointed links (mobility -3) closed by a five-link chain (+3): F = 0
    # overall (9 links, 12 joints), but links 0..3 are over-constrained.
    edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3), (3, 4), (4, 5), (5, 6), (6, 7), (7, 8), (8, 0)]
    chain = chain_from_link_graph(edges)
    with pytest.raises(TopologyError, match="over-constrained"):
        best_plan(chain)


def test_bad_constraints():
    pentad = thesis_truss("5/B1").chain()
    with pytest.raises(TopologyError, match="joint P9: no such joint"):
        bilateration_plans(pentad, reference=("P1", "P9"))
    with pytest.raises(ValueError, match="must differ"):
        bilateration_plans(pentad, reference=("P1", "P1"))
    with pytest.raises(TopologyError, match="no bilateration plan meets"):
        bilateration_plans(pentad, parameters=[("P1", "P2")])  # a link dimension, never a parameter
    with pytest.raises(ValueError, match="count=0"):
        bilateration_plans(pentad, count=0)


@pytest.mark.slow
def test_coupling_degrees_of_thirteen_links():
    from concurrent.futures import ProcessPoolExecutor

    trusses = baranov_trusses(13, workers=2)
    with ProcessPoolExecutor(2) as pool:
        found = collections.Counter(pool.map(coupling_degree, trusses, chunksize=200))
    assert dict(found) == {1: 10419, 2: 9973, 3: 45}


def test_grubler_chains_with_fixed_inputs():
    from baranov.topology import fuse_links, mobility

    four_bar = chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)])
    assert mobility(four_bar) == 1
    assert coupling_degree(fuse_links(four_bar, [[0, 1]])) == 0  # a triad: ruler and compass
    watt = chain_from_link_graph([(0, 1), (0, 2), (2, 3), (3, 1), (0, 4), (4, 5), (5, 1)])
    assert mobility(watt) == 1
    driven = fuse_links(watt, [[0, 2]])  # the binary crank 2 driven from the ground 0
    plan = best_plan(driven)
    assert mobility(driven) == 0 and len(plan.closure_pairs) == len(plan.parameters)
    # A 1-DOF chain from a 9-link truss: remove a binary link, fix the angle at one joint.
    truss = baranov_trusses(9)[5]
    binary = truss.link_degrees.index(2)
    edges = [j.links for j in truss.joints if binary not in j.links]
    chain = chain_from_link_graph(edges)
    assert mobility(chain) == 1
    u, v = chain.joints[0].links
    fixed = fuse_links(chain, [[u, v]])
    plan = best_plan(fixed)
    assert len(plan.closure_pairs) == len(plan.parameters)
    import numpy as np

    from baranov.closure import closure_system, compile_from_coordinates
    from baranov.closure.evaluate import true_parameters_and_signs

    rng = np.random.default_rng(9)
    coordinates = {j.name: rng.uniform(-10, 10, 2) for j in fixed.joints}
    system = closure_system(plan)
    values, signs = true_parameters_and_signs(system, coordinates)
    residuals = compile_from_coordinates(system, fixed, coordinates).residuals(values, signs)
    assert np.all(np.abs(residuals) < 1e-9)


def test_plans_with_one_more_parameter_have_one_more_closure_condition():
    """``extra_parameters=1``: plans with the fewest parameters plus one, each with as many
    closure conditions as parameters (the chain stays rigid); the search refuses a negative
    count."""
    chain = thesis_truss("7/B1").chain()
    fewest = bilateration_plans(chain, 5)
    more = bilateration_plans(chain, 5, extra_parameters=1)
    assert {plan.number_of_parameters for plan in fewest} == {1}
    assert len(more) == 5 and {plan.number_of_parameters for plan in more} == {2}
    assert all(len(plan.closure_pairs) == 2 for plan in more)
    with pytest.raises(ValueError, match="extra_parameters"):
        bilateration_plans(chain, 1, extra_parameters=-1)
