"""Closure conditions: the thesis's formulas, random-configuration oracles, symmetry."""

import numpy as np
import pytest
import sympy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from baranov.closure import (
    closure_system,
    compile_from_coordinates,
    parse_matrix_expression,
    permute_condition,
    sign_branches,
    symmetric_formulation,
    symmetric_variants,
)
from baranov.closure.conditions import DistanceCondition
from baranov.closure.evaluate import (
    condition_residual_at_configuration,
    true_parameters_and_signs,
)
from baranov.closure.notation import canonical_form
from baranov.closure.symmetry import joint_mapping
from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import thesis_truss
from baranov.planner import best_plan, bilateration_plans, coupling_degree
from baranov.topology import automorphism_group, list_automorphisms

TRUSSES = [t for links in (3, 5, 7, 9) for t in baranov_trusses(links)]
ELEVEN = baranov_trusses(11)


def cross(u, v) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def random_configuration(chain, rng):
    """Random joint coordinates, rejected until no three joints are nearly collinear
    (a generic configuration), so every bilateration is well conditioned."""
    names = [j.name for j in chain.joints]
    while True:
        points = rng.uniform(-10, 10, size=(len(names), 2))
        coordinates = dict(zip(names, points, strict=True))
        if all(abs(cross(points[j] - points[i], points[k] - points[i])) > 0.5
               for i in range(len(names)) for j in range(i + 1, len(names)) for k in range(j + 1, len(names))):
            return coordinates


def check_system_at(system, chain, coordinates, tolerance=1e-9):
    compiled = compile_from_coordinates(system, chain, coordinates)
    values, signs = true_parameters_and_signs(system, coordinates)
    residuals = compiled.residuals(values, signs)
    assert residuals.shape == (1, 1, len(system.conditions))
    assert np.all(np.abs(residuals) < tolerance), (system.text(), residuals)
    for condition in system.conditions + system.computed_distances:
        assert abs(condition_residual_at_configuration(condition, coordinates)) < tolerance


# --- the thesis's own formulas -------------------------------------------------------

def test_pentad_condition_is_thesis_equation_2_25():
    plan = bilateration_plans(thesis_truss("5/B1").chain(), reference=("P1", "P6"))[0]
    assert closure_system(plan).conditions[0].text() == "s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6"


def test_thesis_permutation_example_of_section_2_7_1():
    pentad = thesis_truss("5/B1").chain()
    plan = bilateration_plans(pentad, reference=("P1", "P6"))[0]
    permutation = dict(zip(["P1", "P2", "P3", "P4", "P5", "P6"], ["P1", "P3", "P2", "P4", "P6", "P5"], strict=True))
    assert permutation in [joint_mapping(pentad, a) for a in list_automorphisms(pentad)]
    image = permute_condition(closure_system(plan).conditions[0], permutation)
    assert image.text() == "s3,6 = det(I - Z1,2,3 Z1,5,2 - Z5,4,6 Z5,1,4) s1,5"


#: Closure conditions transcribed from the thesis, in its joint numbering:
#: (truss, closure pair, reference, Ω in thesis notation, named sub-expressions).
THESIS_CONDITIONS = [
    ("5/B1", ("P2", "P5"), ("P1", "P6"), "I− Z1,3,2Z1,6,3 − Z6,4,5 Z6,1,4", {}),  # eq. (2.25)
    ("7/B1", ("P6", "P8"), ("P2", "P3"),
     "−Ω3,2,1,6 +Ω3,2,4,5 −Ω5,7,9,8 (Ω3,2,4,5 +Ω2,3,4,7 − I)", {}),  # eq. (3.13)
    ("7/B1", ("P5", "P7"), ("P2", "P3"), "Ω3,2,4,5 +Ω2,3,4,7 − I", {}),  # eq. (3.14)
    ("7/B2", ("P1", "P6"), ("P4", "P8"),
     "−Ω2,9,3,1 (Ω4,8,5,2 +Ω8,4,7,9 − I) +Ω4,8,5,2 −Ω4,8,7,6", {}),  # eq. (3.28)
    ("7/B2", ("P2", "P9"), ("P4", "P8"), "Ω4,8,5,2 +Ω8,4,7,9 − I", {}),  # eq. (3.29)
    ("7/B3", ("P7", "P9"), ("P1", "P4"),
     "−Ω1,4,2,6 +Ω1,4,2,7 − (Ω5,6,8,9 − I) (Ω4,1,3,5 +Ω1,4,2,6 − I)", {}),  # eq. (3.41)
    ("7/B3", ("P5", "P6"), ("P1", "P4"), "Ω4,1,3,5 +Ω1,4,2,6 − I", {}),  # eq. (3.42)
    ("9/B28", ("P8", "P11"), ("P1", "P4"), "−Z1,3,8Z1,4,3 + I− Z4,1,2 + Z2,5,11Z2,4,5Z4,1,2", {}),  # App. A Ω1
    ("9/B28", ("P6", "P10"), ("P1", "P4"),
     "−I+ Z4,3,6Z4,1,3 + Z1,3,8Z1,4,3 + (I − Z11,12,10Z11,8,12)Ω1", {"Ω1": "−Z1,3,8Z1,4,3 + I− Z4,1,2 + Z2,5,11Z2,4,5Z4,1,2"}),
]


def thesis_condition(pair, reference, text, named):
    named = {key: parse_matrix_expression(value) for key, value in named.items()}
    return DistanceCondition(pair, parse_matrix_expression(text, named), reference)


@pytest.mark.parametrize("truss, pair, reference, text, named", THESIS_CONDITIONS,
                         ids=[f"{c[0]}-s{c[1][0][1:]},{c[1][1][1:]}" for c in THESIS_CONDITIONS])
def test_thesis_conditions_and_ours_vanish_on_the_same_configurations(truss, pair, reference, text, named):
    chain = thesis_truss(truss).chain()
    condition = thesis_condition(pair, reference, text, named)
    system = closure_system(best_plan(chain))
    rng = np.random.default_rng(7)
    for _ in range(5):
        coordinates = random_configuration(chain, rng)
        assert abs(condition_residual_at_configuration(condition, coordinates)) < 1e-9
        check_system_at(system, chain, coordinates)


def negated(expression):
    return type(expression)(tuple((m, -c) for m, c in expression.terms))


def test_thesis_reference_gives_exactly_the_thesis_formula_for_7b3():
    """With the thesis's reference pair P1, P4, the planner derives eq. (3.41) and (3.42) of
    thesis §3.3.3 as polynomials in the Z symbols (up to the direction of p7,9, p5,6)."""
    plan = bilateration_plans(thesis_truss("7/B3").chain(), reference=("P1", "P4"))[0]
    system = closure_system(plan)
    condition, computed = system.conditions[0], system.computed_distances[0]
    thesis = thesis_condition(*THESIS_CONDITIONS[5][1:])
    thesis_computed = thesis_condition(*THESIS_CONDITIONS[6][1:])
    assert set(condition.pair) == {"P7", "P9"} and set(computed.pair) == {"P5", "P6"}
    assert canonical_form(condition.omega) in (canonical_form(thesis.omega), canonical_form(negated(thesis.omega)))
    assert canonical_form(computed.omega) in (
        canonical_form(thesis_computed.omega), canonical_form(negated(thesis_computed.omega)))


def test_appendix_a_permutation_gives_the_second_condition_of_9b28():
    chain = thesis_truss("9/B28").chain()
    permutation = dict(zip([f"P{k}" for k in range(1, 13)],
                           [f"P{k}" for k in (2, 1, 5, 4, 3, 7, 6, 11, 10, 9, 8, 12)], strict=True))
    assert permutation in [joint_mapping(chain, a) for a in list_automorphisms(chain)]
    omega1 = THESIS_CONDITIONS[7]
    first = thesis_condition(*THESIS_CONDITIONS[8][1:])
    second = permute_condition(first, permutation)
    assert {second.pair, second.reference} == {("P7", "P9"), ("P2", "P4")}
    computed = permute_condition(thesis_condition(*omega1[1:]), permutation)
    rng = np.random.default_rng(11)
    for _ in range(5):
        coordinates = random_configuration(chain, rng)
        assert abs(condition_residual_at_configuration(second, coordinates)) < 1e-9
        assert abs(condition_residual_at_configuration(computed, coordinates)) < 1e-9


# --- every truss: the conditions vanish at the configuration they come from ------------

@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(TRUSSES), st.integers(0, 2**32 - 1))
def test_conditions_vanish_at_the_generating_configuration(truss, seed):
    system = closure_system(best_plan(truss))
    check_system_at(system, truss, random_configuration(truss, np.random.default_rng(seed)))


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(ELEVEN), st.integers(0, 2**32 - 1))
def test_conditions_vanish_for_eleven_link_trusses(truss, seed):
    system = closure_system(best_plan(truss))
    check_system_at(system, truss, random_configuration(truss, np.random.default_rng(seed)))


def test_every_truss_up_to_nine_links_once():
    rng = np.random.default_rng(2026)
    for truss in TRUSSES:
        for plan in bilateration_plans(truss, count=3):
            check_system_at(closure_system(plan), truss, random_configuration(truss, rng))


# --- symmetry --------------------------------------------------------------------------

@pytest.mark.parametrize("truss", [t for t in baranov_trusses(9) if coupling_degree(t) == 2],
                         ids=lambda t: f"aut{automorphism_group(t).order}")
def test_coupling_two_trusses_have_a_symmetric_formulation(truss):
    """9/B25–B28 (the four trusses of coupling degree 2): some minimal plan has its
    parameter set mapped onto itself by an automorphism that derives a second condition."""
    found = symmetric_formulation(truss)
    assert found is not None
    first, second = found.conditions
    assert frozenset(first.pair) != frozenset(second.pair)
    assert {frozenset(p) for p in found.plan.parameters} == {frozenset(p) for p in found.image.plan.parameters}
    rng = np.random.default_rng(5)
    for _ in range(3):
        coordinates = random_configuration(truss, rng)
        check_system_at(found.system, truss, coordinates)
        check_system_at(found.image, truss, coordinates)


@pytest.mark.parametrize("links", [5, 7, 9])
def test_symmetric_variants_follow_orbit_stabiliser(links):
    for truss in baranov_trusses(links):
        plan = best_plan(truss)
        variants = symmetric_variants(plan, truss)
        order = automorphism_group(truss).order
        assert order % len(variants) == 0
        rng = np.random.default_rng(1)
        coordinates = random_configuration(truss, rng)
        for _, variant in variants:
            check_system_at(closure_system(variant), truss, coordinates)


def test_symmetric_variants_of_the_pentad():
    pentad = thesis_truss("5/B1").chain()
    plan = bilateration_plans(pentad, reference=("P1", "P6"))[0]
    texts = {closure_system(p).conditions[0].text() for _, p in symmetric_variants(plan, pentad)}
    assert len(texts) == 6
    assert "s3,6 = det(I - Z1,2,3 Z1,5,2 - Z5,4,6 Z5,1,4) s1,5" in texts


# --- forms and evaluator details --------------------------------------------------------

def test_sympy_form_holds_numerically_and_latex_renders():
    chain = thesis_truss("5/B1").chain()
    system = closure_system(bilateration_plans(chain, reference=("P1", "P6"))[0])
    coordinates = random_configuration(chain, np.random.default_rng(4))
    equation = system.sympy_conditions[0]
    values = {}
    for symbol in equation.free_symbols:
        parts = [f"P{n}" for n in symbol.name.split("_")[1:]]
        if symbol.name.startswith("s_"):
            u, v = parts
            values[symbol] = float(np.sum((coordinates[u] - coordinates[v]) ** 2))
        else:
            i, j, k = (coordinates[n] for n in parts)
            values[symbol] = cross(j - i, k - i) / 2
    assert abs(float((equation.lhs - equation.rhs).subs(values))) < 1e-6 * values[sympy.Symbol("s_2_5", positive=True)]
    assert system.latex() == r"s_{2,5} = \det\left(I - Z_{1,3,2} Z_{1,6,3} - Z_{6,4,5} Z_{6,1,4}\right) s_{1,6}"


def test_evaluator_shapes_branches_and_nan_outside_the_domain():
    chain = thesis_truss("5/B1").chain()
    system = closure_system(bilateration_plans(chain, reference=("P1", "P6"))[0])
    coordinates = random_configuration(chain, np.random.default_rng(8))
    compiled = compile_from_coordinates(system, chain, coordinates)
    samples = np.linspace(0.01, 1000, 500)
    residuals = compiled.residuals(samples)
    assert residuals.shape == (4, 500, 1)  # 2 free signs → 4 branches
    assert np.isnan(residuals).any() and np.isfinite(residuals).any()
    assert sign_branches(2).shape == (4, 2)


def test_parser_round_trip_and_errors():
    text = "−Ω3,2,1,6 +Ω3,2,4,5 −Ω5,7,9,8 (Ω3,2,4,5 +Ω2,3,4,7 − I)"
    parsed = parse_matrix_expression(text)
    assert canonical_form(parse_matrix_expression(parsed.text())) == parsed
    for bad in ["Z1,2", "(I - Z1,2,3", "I + ", "Ω7", "I ) I"]:
        with pytest.raises(ValueError):
            parse_matrix_expression(bad)


@pytest.mark.slow  # 41 s (2026-11-28)
def test_every_eleven_link_truss_once():
    """The property of test_conditions_vanish_at_the_generating_configuration for each of
    the 562 trusses with 11 links (one random generic configuration each)."""
    rng = np.random.default_rng(562)
    for truss in ELEVEN:
        check_system_at(closure_system(best_plan(truss)), truss, random_configuration(truss, rng))


def test_distinct_branches_fix_the_signs_no_slider_construction_reads():
    """A free-sign step whose slider construction takes no root of its own (a point on two
    axes, a turned axis) keeps +1; every other free sign takes both values. Without
    sliders: all of sign_branches."""
    from pathlib import Path

    from baranov.closure import distinct_branches, sign_branches
    from baranov.closure.sliders import takes_root
    from baranov.scene import load_scene
    from baranov.solvers.coincidence import solvable_plan

    path = Path(__file__).parent / "regressions" / "sliders" / "issue-55-ground-by-squared-length.json"
    scene = load_scene(path)
    plan, sliders = solvable_plan(scene), [slider.joint for slider in scene.sliders]
    reads = [takes_root(step, sliders) for step in plan.steps if step.free_sign]
    assert reads.count(False) == 1 and len(reads) == 3
    branches = distinct_branches(plan, sliders)
    assert len(branches) == 4 and len(set(branches)) == 4
    assert all(signs[reads.index(False)] == 1 for signs in branches)
    assert set(branches) <= {tuple(int(s) for s in row) for row in sign_branches(3)}
    truss_plan = best_plan(thesis_truss("7/B1").chain())
    assert distinct_branches(truss_plan, []) == [tuple(int(s) for s in row)
                                                 for row in sign_branches(len(truss_plan.free_sign_triangles))]


@pytest.mark.parametrize("name", ["issue-55-ground-by-squared-length", "9-N27-eight-sliders-extraneous-factor",
                                  "9-N28-seven-sliders-near-duplicates", "adversarial-7-N2-collinear-moves"])
def test_distinct_branches_vary_exactly_the_signs_the_compiled_program_reads(name):
    """Oracle: the straight-line program of the numeric evaluation, whose instructions
    name the sign registers they read."""
    from pathlib import Path

    from baranov.closure import distinct_branches
    from baranov.scene import load_scene
    from baranov.solvers.coincidence import solvable_plan
    from baranov.solvers.numeric.backend import compile_scene

    scene = load_scene(Path(__file__).parent / "regressions" / "sliders" / f"{name}.json")
    plan = solvable_plan(scene)
    program = compile_scene(scene, plan).straight_line_program()
    read = set(program.instructions[:, 2].tolist()) | set(program.instructions[:, 3].tolist())
    reads = [register in read for register in program.sign_registers.tolist()]
    branches = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    assert len(branches) == 2 ** sum(reads)
    varied = [len({signs[n] for signs in branches}) == 2 for n in range(len(reads))]
    assert varied == reads
