"""The total-degree homotopy on the Cartesian system (solvers/homotopy.py, ``--method
homotopy``): its modes against the exact backend's, its number of finite solutions
against the catalog's assembly-mode counts, the generating configuration of random
instances among its modes, and a truss of coupling degree 3, which no other backend
solves."""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene, scene_from_dict
from baranov.scene.instances import generic_integer_configuration, instance_dict, scene_of
from baranov.solvers import SolverError, solve
from baranov.solvers.homotopy import _polished, _with_conjugates, homotopy_configurations, quadratic_system, solve_system
from baranov.solvers.msolve import cartesian_system, match_configurations
from baranov.solvers.verification import same_mode
from baranov.topology import chain_from_link_graph

ROOT = Path(__file__).resolve().parents[1]
CATALOG = {links: [json.loads(line) for line in (ROOT / "catalog" / f"trusses-{links}.jsonl").read_text().splitlines()]
           for links in (5, 7, 9)}


def _system(scene):
    """The scene's Cartesian system as homogenised quadratics, scaled by 10."""
    variables, polynomials, _, _ = cartesian_system(scene)
    return quadratic_system(variables, polynomials, 10.0)


def _same_modes(first, second, scene) -> bool:
    a, b = first.assembly_modes, second.assembly_modes
    return (len(a) == len(b) and all(any(same_mode(m, n, scene) for n in b) for m in a)
            and all(any(same_mode(n, m, scene) for m in a) for n in b))


@pytest.mark.parametrize("name", ["5-B1", "7-B1", "7-B2", "7-B3", "9-B28"])
def test_the_examples_have_the_exact_backends_modes(name):
    scene = load_scene(ROOT / "examples" / f"{name}.json")
    homotopy = solve(scene, "homotopy")
    assert homotopy.method == "homotopy" and not homotopy.undecided
    assert _same_modes(homotopy, solve(scene, "exact"), scene)


@pytest.mark.parametrize("name, count", [("5-B1", 6), ("7-B1", 14), ("7-B2", 16), ("7-B3", 18), ("9-B28", 58)])
def test_finite_solutions_are_the_complex_assembly_modes(name, count):
    """Every complex solution is reached: as many as the characteristic degree."""
    _, result = homotopy_configurations(load_scene(ROOT / "examples" / f"{name}.json"))
    assert len(result.solutions) == count
    assert len(result.solutions) + result.at_infinity <= result.paths


@settings(max_examples=12, deadline=None)
@given(st.sampled_from([(links, n) for links in (5, 7, 9) for n in range(len(CATALOG[links]))]),
       st.integers(0, 2**32 - 1))
def test_random_instances_count_the_catalogs_modes_and_find_their_own(truss, seed):
    """Property: on a random integer instance of a truss to 9 links the homotopy has the
    catalog's number of complex solutions, and the configuration that generated the
    instance is among its real ones."""
    links, index = truss
    entry = CATALOG[links][index]
    chain = chain_from_link_graph(entry["link_graph6"])
    coordinates = generic_integer_configuration(chain, np.random.default_rng(seed))
    configurations, result = homotopy_configurations(scene_of(chain, coordinates))
    assert not result.undecided
    assert len(result.solutions) == entry["assembly_modes"]
    generating = {j: (float(x), float(y)) for j, (x, y) in coordinates.items()}
    missed, _ = match_configurations(configurations, [generating])
    assert not missed


@pytest.mark.slow
def test_a_coupling_three_truss_is_solved():
    """13/N3 needs three parameters: the numeric and exact backends refuse it, and the
    homotopy (4 096 paths, about a minute) finds its 376 complex solutions (the catalog's
    count, its realization count) and the generating configuration among the real ones
    (examples/13-N3-coupling-3.json is this instance)."""
    chain = chain_from_link_graph("L??????opd@k~?")
    coordinates = generic_integer_configuration(chain, np.random.default_rng(3))
    scene = scene_of(chain, coordinates)
    assert load_scene(ROOT / "examples" / "13-N3-coupling-3.json").links == scene.links
    with pytest.raises(SolverError, match="--method homotopy"):
        solve(scene, "numeric")
    configurations, result = homotopy_configurations(scene)
    assert len(result.solutions) == 376 and not result.undecided
    missed, _ = match_configurations(configurations, [{j: (float(x), float(y)) for j, (x, y) in coordinates.items()}])
    assert not missed


def test_inexact_dimensions_are_refused():
    """A float from Python is binary: the linear equations could not be solved exactly."""
    truss = baranov_trusses(5)[0]
    data = instance_dict(truss, generic_integer_configuration(truss, np.random.default_rng(0)))
    for link in data["links"]:
        link["joints"] = {name: [float(x) + 0.1, float(y)] for name, (x, y) in link["joints"].items()}
    scene = scene_from_dict(data)
    assert not scene.exact
    with pytest.raises(SolverError, match="exact dimensions"):
        solve(scene, "homotopy")


def test_a_system_that_is_not_square_is_refused():
    """Two quadratic equations in three unknowns (after one linear equation in four): a
    linkage that moves."""
    polynomials = [{("a", "a"): Fraction(1), (): Fraction(-1)}, {("b", "b"): Fraction(1), (): Fraction(-4)},
                   {("c",): Fraction(1), ("d",): Fraction(-1)}]
    with pytest.raises(ValueError, match="not rigid"):
        quadratic_system(["a", "b", "c", "d"], polynomials)


def test_inconsistent_linear_equations_are_refused():
    polynomials = [{("a", "a"): Fraction(1), (): Fraction(-1)}, {("b",): Fraction(1)},
                   {("b",): Fraction(1), (): Fraction(-1)}]
    with pytest.raises(ValueError, match="inconsistent"):
        quadratic_system(["a", "b"], polynomials)


def test_a_missing_conjugate_is_restored():
    """The equations are real: the conjugate of a non-real solution is one, and is added
    where the paths missed it (13/N20086 had a solution with |y| ≈ 1.9·10³ reached and its
    conjugate not)."""
    system = _system(load_scene(ROOT / "examples" / "7-B1.json"))
    result = solve_system(system)
    imaginary = result.solutions.imag
    largest = imaginary[np.arange(len(imaginary)), np.abs(imaginary).argmax(axis=1)]
    assert (np.abs(largest) > 1e-6).sum() == 6  # 14 complex assembly modes, 8 real: three conjugate pairs
    kept = result.solutions[largest <= 1e-6]  # one of each pair
    restored = _with_conjugates(system, kept)
    assert len(restored) == len(result.solutions)
    assert all(np.abs(restored - solution).max(axis=1).min() < 1e-9 for solution in result.solutions)


def test_ends_near_infinity_are_not_solutions_and_raise_nothing():
    """An end whose Newton iterates overflow is not a solution (the condition number is
    not asked of a matrix of infinities, where the SVD would not converge)."""
    system = _system(load_scene(ROOT / "examples" / "7-B1.json"))
    ends = np.full((2, system.unknowns), 1e300 + 1e300j)
    with np.errstate(all="ignore"):
        _, converged = _polished(system, ends)
    assert not converged.any()
