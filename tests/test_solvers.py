"""The numeric backend: thesis examples, random-configuration oracles and saved misses
(scene validation: test_scene.py)."""

import json
import math
from itertools import product
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shared import PUBLISHED_EXAMPLES, SEVEN_LINK_EXAMPLES, SOLVABLE

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene import load_scene, scene_from_dict
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_triad_of_section_3_1_1():
    solution = solve(load_scene(EXAMPLES / "3-B1.json"))
    found = sorted((round(m.joints["P3"][0], 12), round(m.joints["P3"][1], 12)) for m in solution.assembly_modes)
    assert found == [(1.8, 7.4), (5.4, 3.8)]  # (9/5, 37/5) and (27/5, 19/5)


PENTAD_ROOTS = [1.6525, 2.3684, 5.9939, 10.6876, 73.7712, 74.4945]  # thesis §3.2.3, s1,6


def squared(mode, u, v):
    (x1, y1), (x2, y2) = mode.joints[u], mode.joints[v]
    return (x1 - x2) ** 2 + (y1 - y2) ** 2


def test_pentad_of_section_3_2_3_has_the_six_published_roots():
    solution = solve(load_scene(EXAMPLES / "5-B1.json"))
    roots = sorted(squared(m, "P1", "P6") for m in solution.assembly_modes)
    assert [round(r, 4) for r in roots] == PENTAD_ROOTS
    assert all(m.max_residual < 1e-12 for m in solution.assembly_modes)


def test_only_the_thesis_orientation_reproduces_the_pentad():
    """The text has no figures. With the ground link t123 as given, of the two mirror
    images of the other ternary link only the one read from the printed Z6,4,5 gives the
    published roots; flipping both links mirrors the whole linkage, with the same roots."""
    data = json.loads((EXAMPLES / "5-B1.json").read_text())

    def roots(first: str, second: str) -> list[float]:
        data["links"][0]["orientation"], data["links"][1]["orientation"] = first, second
        return sorted(round(squared(m, "P1", "P6"), 4) for m in solve(scene_from_dict(data)).assembly_modes)

    assert roots("ccw", "cw") == PENTAD_ROOTS
    assert roots("ccw", "ccw") != PENTAD_ROOTS
    assert roots("cw", "ccw") == PENTAD_ROOTS  # the mirror image of the whole linkage




@pytest.mark.parametrize("name", sorted(PUBLISHED_EXAMPLES))
def test_examples_reproduce_the_published_roots(name):
    """Every published real root, to the 4 decimals printed (the 13-link list has roots
    0.006 apart)."""
    (u, v), published = PUBLISHED_EXAMPLES[name]
    solution = solve(load_scene(EXAMPLES / f"{name}.json"))
    assert solution.coupling_degree == 1
    assert sorted(round(squared(m, u, v), 4) for m in solution.assembly_modes) == published
    assert all(m.max_residual < 1e-9 for m in solution.assembly_modes)


@pytest.mark.parametrize("name", [*sorted(SEVEN_LINK_EXAMPLES),
                                  pytest.param("11-watt-baranov", marks=pytest.mark.slow)])
def test_examples_other_orientations_do_not(name):
    """The figures are missing: of all mirror-image choices of the non-ground rigid links,
    exactly the one in the example file reproduces the published roots."""
    (u, v), published = PUBLISHED_EXAMPLES[name]
    data = json.loads((EXAMPLES / f"{name}.json").read_text())
    rigid = [link for link in data["links"] if "orientation" in link]
    matches = []
    for combination in product(("ccw", "cw"), repeat=len(rigid)):
        for link, orientation in zip(rigid, combination, strict=True):
            link["orientation"] = orientation
        modes = solve(scene_from_dict(data)).assembly_modes
        if sorted(round(squared(m, u, v), 4) for m in modes) == published:
            matches.append(combination)
    orientations = tuple(link["orientation"] for link in json.loads((EXAMPLES / f"{name}.json").read_text())["links"]
                         if "orientation" in link)
    assert matches == [orientations]


def test_nine_link_b28_example_has_fourteen_real_modes():
    """Thesis §3.4.1.4: 14 real roots, coupling degree 2 (one of the 8 choices of mirror
    images that give 14; the figure that would single one out is missing)."""
    solution = solve(load_scene(EXAMPLES / "9-B28.json"))
    assert solution.coupling_degree == 2
    assert len(solution.assembly_modes) == 14
    assert max(m.max_residual for m in solution.assembly_modes) < 1e-9




ELEVEN_SOLVABLE = [t for t in baranov_trusses(11) if coupling_degree(t) == 1]


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(ELEVEN_SOLVABLE), st.integers(0, 2**32 - 1))
def test_the_generating_configuration_is_found_for_eleven_links(truss, seed):
    test_the_generating_configuration_is_found.hypothesis.inner_test(truss, seed)


COUPLING_TWO = [t for t in baranov_trusses(9) if coupling_degree(t) == 2]


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(COUPLING_TWO), st.integers(0, 2**32 - 1))
def test_the_generating_configuration_is_found_for_coupling_two(truss, seed):
    test_the_generating_configuration_is_found.hypothesis.inner_test(truss, seed)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(SOLVABLE), st.integers(0, 2**32 - 1))
def test_the_generating_configuration_is_found(truss, seed):
    rng = np.random.default_rng(seed)
    coordinates = generic_integer_configuration(truss, rng)
    scene = scene_of(truss, coordinates)
    assert scene.exact
    solution = solve(scene)
    scale = max(abs(float(c)) for point in coordinates.values() for c in point)
    assert any(
        all(math.dist(mode.joints[n], (float(x), float(y))) < 1e-6 * scale for n, (x, y) in coordinates.items())
        for mode in solution.assembly_modes
    ), f"generating configuration missed: {coordinates}"
    assert all(mode.max_residual < 1e-8 for mode in solution.assembly_modes)


def test_unassemblable_linkage_has_zero_modes():
    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    data["links"][1]["squared_length"] = 1  # P3 cannot reach both P1 and P2
    assert solve(scene_from_dict(data)).assembly_modes == ()


REGRESSIONS = sorted((Path(__file__).resolve().parent / "regressions").glob("*.json"))


@pytest.mark.parametrize("path", REGRESSIONS, ids=lambda p: p.stem)
def test_saved_misses_are_found(path):
    """Every instance the numeric backend once missed: the configuration it was built from
    (the coordinates in the file) must be among the modes, to 6e-5 of the joints' spread
    or to the file's ``generating_tolerance`` (a singular mode, which floats locate only
    to ~ε^(1/k): docs/numeric.md)."""
    scene = load_scene(path)
    tolerance = json.loads(path.read_text()).get("generating_tolerance", 1e-6 * 60)
    generating = {n: tuple(map(float, p)) for n, p in json.loads(path.read_text()).get("generating_configuration", {}).items()}
    for link in json.loads(path.read_text())["links"]:
        if isinstance(link["joints"], dict):
            generating.update({n: tuple(map(float, p)) for n, p in link["joints"].items()})
    modes = solve(scene).assembly_modes
    verified = json.loads(path.read_text()).get("verified_modes")
    assert len(generating) == len(scene.chain.joints) or verified, f"{path.name} checks nothing"
    if len(generating) == len(scene.chain.joints):  # the scene was built from a configuration
        assert any(all(math.dist(m.joints[n], p) < tolerance for n, p in generating.items()) for m in modes)
    if verified:  # no mode ever verified on this instance may be lost again
        found = [m.parameters[verified["parameter"]] for m in modes]
        for value in verified["values"]:
            assert any(abs(v - value) < 1e-5 * value for v in found), value


def test_time_limit_names_what_was_not_searched():
    """A numeric solve past its time limit still verifies what it found and lists the
    branches (coupling 1) or cells (coupling 2) it did not search."""
    one = solve(load_scene(EXAMPLES / "7-B1.json"), time_limit=0)
    assert one.assembly_modes == () or all(m.max_residual < 1e-8 for m in one.assembly_modes)
    assert any("branches +++, ++-" in s and "time limit" in s for s in one.undecided)
    complete = solve(load_scene(EXAMPLES / "7-B1.json"), time_limit=60)
    assert len(complete.assembly_modes) == 8 and complete.undecided == ()
    two = solve(load_scene(EXAMPLES / "9-B28.json"), time_limit=0)
    assert all(m.max_residual < 1e-8 for m in two.assembly_modes)
    assert two.undecided and all("cells not searched: the time limit was reached" in s for s in two.undecided)


@pytest.mark.parametrize("bad", [-1.0, float("nan")])
def test_time_limit_must_be_seconds(bad):
    with pytest.raises(ValueError, match=f"time_limit {bad}: must be a number of seconds"):
        solve(load_scene(EXAMPLES / "5-B1.json"), time_limit=bad)
