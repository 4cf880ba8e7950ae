"""The exact backend against the thesis's characteristic polynomials and the numeric
backend."""

import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shared import PUBLISHED_EXAMPLES, SOLVABLE, same_modes

from baranov.catalog import iter_objects
from baranov.enumerate import baranov_trusses
from baranov.literature.trusses import APPENDIX_A_ASSEMBLY_MODES
from baranov.planner import bilateration_plans, coupling_degree
from baranov.scene import load_scene, scene_from_dict
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import ExactMethodError, characteristic_polynomial, solve
from baranov.solvers.mode_counts import characteristic_degree
from baranov.topology.realizations import realization_count

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def thesis_polynomial(name: str, parameter: tuple[str, str]):
    scene = load_scene(EXAMPLES / f"{name}.json")
    plan = bilateration_plans(scene.chain, parameters=[parameter])[0]
    assert {frozenset(p) for p in plan.parameters} == {frozenset(parameter)}
    return characteristic_polynomial(scene, plan)


def test_pentad_sextic_is_the_published_one():
    """Thesis §3.2.3, parameter s1,6: 266085 s⁶ − 44959860 s⁵ + … + 366616640000, exactly
    up to a constant factor."""
    published = [266085, -44959860, 2314950740, -35686383040, 210282384000, -482011052800, 366616640000]
    polynomial = thesis_polynomial("5-B1", ("P1", "P6"))
    assert polynomial.monic_coefficients() == [Fraction(c, published[0]) for c in published]


#: Thesis §3.3.x.3: characteristic polynomials as printed (4 significant digits), highest
#: degree first, in the parameter the thesis uses.
SEVEN_LINK_POLYNOMIALS = {
    "7-B1": (("P2", "P3"), [119.5503e12, -132.8081e15, 67.7507e18, -20.9729e21, 4.3875e24, -654.0472e24,
                            71.4151e27, -5.7830e30, 347.7941e30, -15.4050e33, 492.8930e33, -11.0051e36,
                            161.4709e36, -1.3884e39, 5.2641e39]),
    "7-B2": (("P4", "P8"), [18.8825e24, -5.9735e27, 818.5722e27, -64.1837e30, 3.2137e33, -108.7285e33,
                            2.5531e36, -41.5239e36, 452.6824e36, -3.1196e39, 12.6154e39, -28.2936e39,
                            38.9353e39, -36.1341e39, 25.5007e39, -15.1151e39, 5.2854e39]),
    "7-B3": (("P1", "P4"), [-702.0669e12, 440.9551e15, -126.5260e18, 21.9306e21, -2.5592e24, 212.2835e24,
                            -12.8945e27, 583.5044e27, -19.9010e30, 517.8331e30, -10.4725e33, 168.7340e33,
                            -2.1961e36, 22.5420e36, -171.4717e36, 898.7415e36, -3.0279e39, 5.9942e39,
                            -5.5218e39]),
}


@pytest.mark.parametrize("name", sorted(SEVEN_LINK_POLYNOMIALS))
def test_seven_link_polynomials_are_the_published_ones(name):
    """Degrees 14, 16, 18; every coefficient, scaled to the published leading one, agrees
    with the printed value to 4 significant digits (the printed values have 5 to 7, and
    the leading one, used for scaling, is itself rounded)."""
    parameter, published = SEVEN_LINK_POLYNOMIALS[name]
    polynomial = thesis_polynomial(name, parameter)
    assert polynomial.degree == len(published) - 1
    monic = polynomial.monic_coefficients()
    assert [float(c * Fraction(published[0])) for c in monic] == pytest.approx(published, rel=1e-4)


@pytest.mark.parametrize("name", ["7-B1", "7-B2", "7-B3", "7-B3-section-4.2.1"])
def test_certified_real_roots_are_the_published_ones(name):
    (u, v), roots = PUBLISHED_EXAMPLES[name]
    polynomial = thesis_polynomial(name, (u, v))
    assert [round(float(r.mid()), 4) for r in polynomial.real_roots()] == roots
    assert all(float(r.rad()) < 1e-10 for r in polynomial.real_roots())


@pytest.mark.parametrize(("name", "degree"), [("11-watt-baranov", 62), ("13-watt-baranov", 126)])
def test_watt_baranov_polynomials_have_the_published_degrees_and_roots(name, degree):
    """Thesis §3.6.2: degree 2^(k+1) − 2 (62 for 11 links, 126 for 13), 16 and 76 real
    roots in s1,3, the published values (4 decimals)."""
    (u, v), published = PUBLISHED_EXAMPLES[name]
    polynomial = thesis_polynomial(name, (u, v))
    assert polynomial.degree == degree
    assert [round(float(r.mid()), 4) for r in polynomial.real_roots()] == published


def test_eleven_link_watt_baranov_modes_by_the_exact_method():
    solution = solve(load_scene(EXAMPLES / "11-watt-baranov.json"), method="exact")
    assert solution.characteristic_polynomial.degree == 62
    assert len(solution.assembly_modes) == 16


@pytest.mark.parametrize("name", ["3-B1", "5-B1", "7-B1", "7-B2", "7-B3", "7-B3-section-4.2.1"])
def test_exact_and_numeric_modes_agree_on_the_examples(name):
    scene = load_scene(EXAMPLES / f"{name}.json")
    exact, numeric = solve(scene, method="exact"), solve(scene)
    assert len(exact.assembly_modes) == len(numeric.assembly_modes)
    for a, b in zip(exact.assembly_modes, numeric.assembly_modes, strict=True):
        assert a.signs == b.signs
        assert all(math.dist(a.joints[j], b.joints[j]) < 1e-7 for j in a.joints)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(SOLVABLE), st.integers(0, 2**32 - 1))
def test_numeric_finds_exactly_the_certified_modes(truss, seed):
    """On random generic instances: the numeric backend's modes are exactly the modes built
    from the certified real roots (and the generating configuration is among them)."""
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed)))
    exact, numeric = solve(scene, method="exact"), solve(scene)
    assert [v for m in exact.assembly_modes for v in m.parameters.values()] == pytest.approx(
        [v for m in numeric.assembly_modes for v in m.parameters.values()], rel=1e-7)
    if exact.characteristic_polynomial is not None:  # generic: every real root is a mode
        assert len(exact.characteristic_polynomial.real_roots()) == len(exact.assembly_modes)


def test_float_dimensions_are_refused():
    data = json.loads((EXAMPLES / "7-B1.json").read_text())
    binary = next(link for link in data["links"] if "squared_length" in link)
    binary["squared_length"] = 97.5
    with pytest.raises(ExactMethodError, match="integer or rational dimensions"):
        solve(scene_from_dict(data), method="exact")


def test_irrational_link_area_is_refused():
    data = json.loads((EXAMPLES / "5-B1.json").read_text())
    ternary = next(link for link in data["links"] if "squared_distances" in link)
    first = next(iter(ternary["squared_distances"]))
    ternary["squared_distances"][first] += 1
    with pytest.raises(ExactMethodError, match="not the square of a rational"):
        solve(scene_from_dict(data), method="exact")


def test_realization_counts_of_nine_links_are_appendix_a():
    """pyrigi's realization count (fan identity) gives exactly the multiset of the 28
    assembly-mode counts of thesis Appendix A."""
    counts = sorted(realization_count(t) for t in baranov_trusses(9))
    assert counts == sorted(APPENDIX_A_ASSEMBLY_MODES.values())


def test_catalog_assembly_modes_agree_with_realization_counts():
    """In the committed catalog (which a CLI test regenerates byte for byte): wherever the
    characteristic polynomial was derived, its degree equals the realization count; every
    9-link degree (coupling 2 included) is the Appendix A value of its thesis name."""
    catalog = Path(__file__).resolve().parents[1] / "catalog"
    for links in (3, 5, 7, 9, 11):
        for entry in list(iter_objects(catalog / f"trusses-{links}.jsonl")):
            if entry["assembly_modes"] is not None:
                assert entry["assembly_modes"] == entry["realization_count"], entry["id"]
    nine = {e["name"]: e["assembly_modes"] for e in list(iter_objects(catalog / "trusses-9.jsonl"))}
    assert nine == APPENDIX_A_ASSEMBLY_MODES


@pytest.mark.slow
def test_characteristic_degrees_equal_realization_counts_up_to_nine_links():
    """For every coupling-1 truss up to 9 links, the degree of the characteristic
    polynomial over Q (the catalog counts modulo primes) equals the realization count;
    for 9 links they are the 24 Appendix A values of 9/B1-9/B24 (the coupling-1 ones)."""
    nine = []
    for links in (5, 7, 9):
        for truss in baranov_trusses(links):
            if coupling_degree(truss) == 1:
                degree, _ = characteristic_degree(truss, method="exact")
                assert degree == realization_count(truss)
                if links == 9:
                    nine.append(degree)
    assert sorted(nine) == sorted(APPENDIX_A_ASSEMBLY_MODES[f"9/B{n}"] for n in range(1, 25))


def test_coupling_two_characteristic_polynomial_on_a_random_instance():
    """9/B25 (coupling degree 2, thesis §3.4.2) on a random integer instance: the
    characteristic polynomial in the first parameter (resultant of the two genuine curves,
    genuine factors kept) has degree 52, the Appendix A count and the realization count;
    its real roots give exactly the numeric backend's modes."""
    truss = [t for t in baranov_trusses(9) if coupling_degree(t) == 2][0]
    assert realization_count(truss) == APPENDIX_A_ASSEMBLY_MODES["9/B25"]
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(3)))
    exact, numeric = solve(scene, method="exact"), solve(scene)
    assert exact.characteristic_polynomial.degree == 52
    assert len(exact.characteristic_polynomial.real_roots()) == len(exact.assembly_modes) == 4
    assert same_modes(scene, exact.assembly_modes, numeric.assembly_modes)


def test_nine_link_b28_example_by_the_exact_method():
    """Thesis §3.4.1.4: 9/B28 has a characteristic polynomial of degree 58 (the factor of
    a resultant of degree 1826 in the thesis; 1728 by the fallback route here, with this
    plan's curves; lifted from primes without the resultant by default) and the example
    14 real roots; the exact modes are the numeric backend's (about 20 s)."""
    scene = load_scene(EXAMPLES / "9-B28.json")
    exact, numeric = solve(scene, method="exact"), solve(scene)
    assert exact.characteristic_polynomial.degree == 58
    assert len(exact.characteristic_polynomial.real_roots()) == len(exact.assembly_modes) == 14
    assert same_modes(scene, exact.assembly_modes, numeric.assembly_modes)


def test_plane_factors_survive_python_flint_sort_overflow():
    """python-flint 0.9 raises OverflowError sorting two factors of one multiplicity whose
    leading coefficients agree beyond 2^31 (issue 25: 9/N27 drawn at a double root);
    plane_factors falls back to rational factoring and returns the same primitive factors."""
    from baranov.solvers.exact.coupling_two import PLANE, plane_factors

    u, v = PLANE.gens()
    first, second = 2**40 * u * v + 3 * u + 5, 2**40 * u * v + 7 * u - 1
    factors = plane_factors(first * second * (u - v) ** 2)
    assert sorted((str(f), m) for f, m in factors) == sorted([(str(first), 1), (str(second), 1), (str(u - v), 2)])


@pytest.mark.parametrize("path", ["examples/7-B1.json", "examples/7-B3-sliders-P8-P9.json",
                                  "tests/scenes/9-slider-chain-coupling-2.json"])
def test_branches_placed_together_are_placed_as_alone(path):
    """placed_on_branches places the steps that sign branches share once; each branch's
    points, and whether its placement is real, are those of placing it alone."""
    import flint

    from baranov.closure import distinct_branches
    from baranov.solvers.exact.characteristic import (
        exact_plan,
        placed_on_branches,
        placed_points,
        real_configuration,
    )

    scene = load_scene(EXAMPLES.parent / path)
    plan = exact_plan(scene)
    branches = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    rng = np.random.default_rng(3)
    values = [flint.acb(flint.fmpq(int(rng.integers(1, 4000)), 100)) for _ in plan.parameters]
    together = list(placed_on_branches(scene, plan, values, branches))
    assert [signs for signs, *_ in together] == branches
    for signs, points, reference, pair in together:
        alone, alone_reference, alone_pair = placed_points(scene, plan, values, signs)
        assert (pair, str(reference)) == (alone_pair, str(alone_reference))
        assert (points is None) == (alone is None)
        if points is not None:
            assert {joint: str(point) for joint, point in points.items() if not joint.startswith("<")} == \
                {joint: str(point) for joint, point in alone.items() if not joint.startswith("<")}
            assert real_configuration(points) == real_configuration(alone)


def test_a_real_configuration_is_told_from_a_complex_one():
    """real_configuration: every coordinate exactly real; a branch whose triangle does not
    exist (a square root of a negative radicand) is not."""
    import flint

    from baranov.solvers.exact.characteristic import exact_plan, placed_points, real_configuration

    scene = load_scene(EXAMPLES / "7-B1.json")
    plan = exact_plan(scene)
    mode = solve(scene, method="exact").assembly_modes[0]
    at_mode = placed_points(scene, plan, [flint.acb(next(iter(mode.parameters.values())))], mode.signs)[0]
    assert real_configuration(at_mode)
    unbuilt = []
    for value in (1, 10, 100, 1000, 10000):
        points, _, _ = placed_points(scene, plan, [flint.acb(value)], mode.signs)
        real_points, _, _ = placed_points(scene, plan, [flint.acb(value)], mode.signs, real_only=True)
        assert real_configuration(points) == (real_points is not None)
        unbuilt.append(real_points is None)
    assert any(unbuilt)
