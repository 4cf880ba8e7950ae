"""Completeness where it is hardest (issue 25): a fast sample of the adversarial run
(bench/adversarial.py) — small boxes, joints in line, joints at one point, modes at a
domain edge, double roots — both backends against msolve, mode for mode; movable
linkages said to be movable."""

from __future__ import annotations

import json
import math
import multiprocessing
import os
from pathlib import Path

import numpy as np
import pytest

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan, coupling_degree
from baranov.scene import load_scene
from baranov.scene.adversarial import (
    ADVERSARIAL_KINDS,
    adversarial_scene,
    double_root_configuration,
    is_infinitesimally_flexible,
)
from baranov.solvers import ExactSolution, MovableLinkageError, coincidence, solve
from baranov.solvers.exact.backend import solve_exact
from baranov.solvers.msolve import compare_modes, find_msolve, msolve_modes

REGRESSIONS = Path(__file__).resolve().parent / "regressions"
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")

#: The sample: every 7-link truss × kind × SEVEN instances, and one instance (kinds in
#: turn) of every coupling-1 9-link truss. Seeds differ from the bench run's.
SEVEN = 8
SEED = 2025


def _tasks() -> list[tuple[int, int, str, int]]:
    tasks = [(7, index, kind, n) for index in range(3) for kind in ADVERSARIAL_KINDS for n in range(SEVEN)]
    nine = [index for index, truss in enumerate(baranov_trusses(9)) if coupling_degree(truss) == 1]
    tasks += [(9, index, ADVERSARIAL_KINDS[n % len(ADVERSARIAL_KINDS)], 0) for n, index in enumerate(nine)]
    return tasks


def _check(task: tuple[int, int, str, int]) -> list[str]:
    """What went wrong on one instance (empty if nothing)."""
    links, index, kind, instance = task
    truss = baranov_trusses(links)[index]
    rng = np.random.default_rng([SEED, links, index, ADVERSARIAL_KINDS.index(kind), instance])
    scene, points = adversarial_scene(truss, kind, rng)
    name = f"{links}/N{index + 1} {kind} #{instance}"
    oracle = msolve_modes(scene, timeout=120)
    if oracle.status == "infinite":  # a movable linkage: the numeric backend must say so
        try:
            solve(scene)
        except MovableLinkageError:
            return []
        return [f"{name}: movable (msolve), but the numeric backend listed modes"]
    problems = [] if oracle.status == "finite" else [f"{name}: msolve {oracle.status} {oracle.message}"]
    generating = {j: (float(x), float(y)) for j, (x, y) in points.items()}
    for method in ("numeric", "exact"):
        solution = solve(scene, method=method)
        found = [mode.joints for mode in solution.assembly_modes]
        missed, spurious, _ = compare_modes(found, list(oracle.configurations))
        if missed or spurious or compare_modes(found, [generating])[0]:
            problems.append(f"{name}, {method}: {missed} missed, {spurious} spurious of "
                            f"{len(oracle.configurations)}; scene {json.dumps(points, default=str)}")
        if isinstance(solution, ExactSolution) and not solution.certificate.complete:
            problems.append(f"{name}, {method}: {solution.certificate.summary()}")
    return problems


@needs_msolve
def test_adversarial_sample_matches_msolve_mode_for_mode():
    """0 missed and 0 spurious modes, both backends, on the sample (about 140 instances;
    the 10⁴-instance run is bench/adversarial.py, docs/stability.md)."""
    tasks = _tasks()
    with multiprocessing.get_context("fork").Pool(min(2, os.cpu_count() or 1)) as pool:
        problems = [p for found in pool.imap_unordered(_check, tasks) for p in found]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("kind", ADVERSARIAL_KINDS)
def test_each_kind_gives_valid_exact_scenes(kind):
    for index, truss in enumerate(baranov_trusses(7)):
        scene, points = adversarial_scene(truss, kind, np.random.default_rng([index, 3]))
        assert scene.exact and set(points) == {j.name for j in truss.joints}


def test_double_root_configurations_are_infinitesimally_flexible():
    truss = baranov_trusses(7)[1]
    for seed in range(3):
        points = double_root_configuration(truss, np.random.default_rng(seed))
        assert is_infinitesimally_flexible(truss, points)


@needs_msolve
@pytest.mark.parametrize("name", ["7-N2-movable", "9-N20-movable", "9-N9-domain-flicker"])
def test_a_movable_linkage_is_reported_as_such(name):
    """7/N2 drawn with P1 = P6 = P8 rotates about that point, 9/N20 moves along s8,10,
    9/N9 drawn at a double root moves with P10 = P4 and its domain flickers with rounding
    along a stretch (issue 25; 17 900 domain edges, searched together since): msolve
    finds a positive-dimensional solution set, the numeric backend
    raises MovableLinkageError, the exact backend lists the isolated modes it found and is
    not certified complete."""
    scene = load_scene(REGRESSIONS / "movable" / f"{name}.json")
    assert msolve_modes(scene).status == "infinite"
    with pytest.raises(MovableLinkageError, match="movable|moves"):
        solve(scene)
    certificate = solve(scene, method="exact").certificate
    assert not certificate.complete and any(word in certificate.summary() for word in ("movable", "moves", "may move"))


@needs_msolve
def test_a_movable_coupling_two_linkage_is_reported_as_such():
    """9/N18 drawn with four joints at one point moves along the line s2,5 = 2, shared by
    both closure conditions (issue 25: the numeric backend ran past 300 s, the exact one
    raised a bare ValueError): both backends raise MovableLinkageError, naming the curve."""
    scene = load_scene(REGRESSIONS / "movable" / "9-N18-shared-curve.json")
    assert msolve_modes(scene).status == "infinite"
    with pytest.raises(MovableLinkageError, match=r"both closure conditions vanish along a curve \(s2,5 from 2 to 2"):
        solve(scene)
    with pytest.raises(MovableLinkageError, match="hold along the curve u - 2 = 0"):
        solve(scene, method="exact")


@needs_msolve
def test_a_movable_linkage_no_plan_can_solve_is_reported_as_such():
    """9/N17 drawn with two joints of one link at one point: no plan avoids that pair, so
    both backends refuse the scene, and say it moves (msolve: positive-dimensional)."""
    scene = load_scene(REGRESSIONS / "movable" / "9-N17-coincident-in-link.json")
    for method in ("numeric", "exact"):
        with pytest.raises(MovableLinkageError, match="P1,P9: coincident .* msolve: the linkage moves"):
            solve(scene, method=method)


def _adversarial_finds() -> list:
    """The saved instances of issue 25's runs; coupling degree 2 (10-25 s each, mostly the
    exact backend's lifting) under the slow marker."""
    finds = []
    for path in sorted(REGRESSIONS.glob("*.json")):
        if "issue 25" in json.loads(path.read_text()).get("comment", "").lower():
            slow = coupling_degree(load_scene(path).chain) == 2
            finds.append(pytest.param(path, id=path.stem, marks=[pytest.mark.slow] if slow else []))
    return finds


ADVERSARIAL_FINDS = _adversarial_finds()


@needs_msolve
@pytest.mark.parametrize("path", ADVERSARIAL_FINDS)
def test_regressions_match_msolve(path):
    """Every instance saved by issue 25's runs, both backends against msolve (every saved
    instance is checked against its generating configuration by test_solvers.py)."""
    scene = load_scene(path)
    oracle = msolve_modes(scene, timeout=120)
    if oracle.status != "finite" or not scene.exact:
        pytest.skip(f"msolve: {oracle.status}" if scene.exact else "float dimensions")
    for method in ("numeric", "exact"):
        try:
            found = [mode.joints for mode in solve(scene, method=method).assembly_modes]
        except ValueError as error:  # e.g. the exact method on irrational link areas
            if method == "exact":
                continue
            raise error
        assert compare_modes(found, list(oracle.configurations))[:2] == (0, 0), method


def test_flat_valley_is_one_undecided_mode():
    """Where the closure condition is flat to rounding around a singular mode, the
    numeric backend reports one mode there and says which stretch it could not resolve
    (9/N15: four noise roots around s8,10 = 32 before)."""
    solution = solve(load_scene(REGRESSIONS / "9-N15-flat-valley.json"))
    values = sorted(mode.parameters["s8,10"] for mode in solution.assembly_modes if mode.signs == (-1, 1, -1, -1))
    assert len(values) == 1 and abs(values[0] - 32) < 1e-3
    # the stretch where |f| is within 100 times its rounding noise (seed 38: not a fixed 1e-12)
    said = [sentence for sentence in solution.undecided if "on branch -+--" in sentence]
    assert len(said) == 1 and "s8,10 in [31.98" in said[0] and "flat to rounding" in said[0]


@needs_msolve
def test_a_singular_valley_reports_the_mode_itself():
    """tests/regressions/9-N27-double-root-25.json (seed 33 at 66d6af0): link L5 has its
    joints in line, so in the link dimensions every mode sits in a valley, and the double
    root at (s1,10, s1,11) = (5, 1) in one flat to rounding 1.4e-2 wide (172 verified
    configurations). The member the parameter box chose, (4.99994, 1.00000001), was
    farther from msolve's mode than the mode tolerance (1 missed, 1 spurious); refined on
    the rigid-link model the valley's mode is msolve's, and the valley is still said."""
    scene = load_scene(REGRESSIONS / "9-N27-double-root-25.json")
    solution = solve(scene)
    found = [mode.joints for mode in solution.assembly_modes]
    assert any("one valley" in sentence for sentence in solution.undecided)
    assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)


@needs_msolve
@pytest.mark.parametrize("name", ["9-N2-touching-inside", "9-N27-edge-double-root", "9-N28-modes-on-edge-line"])
def test_singular_modes_inside_and_on_edge_lines_are_found_to_the_digit(name):
    """Issue 25, seed 35 (coupling 2, the numeric backend; both backends: the slow
    test_regressions_match_msolve): a double root where f_2 touches 0 inside the domain
    (9/N2, missed); modes on an edge line along which f_1 vanishes (9/N27 missed one,
    9/N28 missed one and located two 1e-5 away). All modes, none coarse."""
    scene = load_scene(REGRESSIONS / f"{name}.json")
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations)) == (0, 0, 0)


PARAMETER_JOINTS_COINCIDE = ["7-N2-parameter-joints-coincide", "7-N2-parameter-joints-coincide-double-root"]


@needs_msolve
@pytest.mark.parametrize("name", PARAMETER_JOINTS_COINCIDE)
@pytest.mark.parametrize("with_msolve", [True, False], ids=["msolve", "another-plan"])
def test_exact_backend_settles_the_parameter_joints_coinciding(name, with_msolve, monkeypatch):
    """Issue 25, seed 36 (7/N2, coordinates in [-3, 3]²): four of the eight modes have
    P1 = P8, s1,8 = 0, a value at which the cleared characteristic polynomial does not
    vanish; the exact backend certified the other four. Now it settles s = 0 as the
    numeric backend does, by msolve or, without it, by another plan: all eight, certified."""
    scene = load_scene(REGRESSIONS / f"{name}.json")
    oracle = list(msolve_modes(scene).configurations)
    if not with_msolve:
        monkeypatch.setattr(coincidence, "find_msolve", lambda: None)
    solution = solve(scene, method="exact")
    assert solution.certificate.complete and len(oracle) == 8
    assert compare_modes([mode.joints for mode in solution.assembly_modes], oracle) == (0, 0, 0)
    coincident = [m for m in solution.assembly_modes if math.dist(m.joints["P1"], m.joints["P8"]) < 1e-9]
    assert len(coincident) == 4 and all(m.parameters["s1,8"] == 0 for m in coincident)


@needs_msolve
def test_exact_backend_takes_other_parameters_where_the_norm_vanishes():
    """tests/regressions/9-N21-vanishing-norm-seed39.json (seed 39 at 3eb446264259): P6 on
    P12 and six joints on the line y = x; the norm of the best plan's closure condition in
    s8,10 vanishes identically (a complex curve of solutions through the one real mode),
    so the exact backend listed no mode, uncertified. Other parameters (s7,12) give a
    certified polynomial with msolve's mode; the best plan alone still says why it cannot."""
    scene = load_scene(REGRESSIONS / "9-N21-vanishing-norm-seed39.json")
    solution = solve(scene, method="exact")
    assert solution.certificate.complete and solution.parameters != ("s8,10",)
    assert compare_modes([m.joints for m in solution.assembly_modes], list(msolve_modes(scene).configurations)) == (0, 0, 0)
    alone = solve_exact(scene, best_plan(scene.chain))
    assert not alone.assembly_modes and any("vanishes identically" in gap for gap in alone.certificate.gaps)


def test_exact_certificate_names_a_coincidence_nothing_settles(monkeypatch):
    """Where neither msolve nor another plan can examine the parameter's joints
    coinciding, the exact backend says so instead of certifying."""
    monkeypatch.setattr(coincidence, "find_msolve", lambda: None)
    planned = coincidence.plan_avoiding  # the best plan avoids no pair; none avoids P1 P8
    monkeypatch.setattr(coincidence, "plan_avoiding", lambda chain, pairs: None if pairs else planned(chain, pairs))
    solution = solve(load_scene(REGRESSIONS / f"{PARAMETER_JOINTS_COINCIDE[0]}.json"), method="exact")
    assert not solution.certificate.complete
    assert any("P1=P8" in gap and "not examined" in gap for gap in solution.certificate.gaps)


def test_a_shallow_simple_root_is_placed_to_rounding():
    """tests/regressions/robot-I-shallow-root.json (a family-I robot of issue 18's random
    draws): the simple root s1,5 = 1044 where f' = 6.7e-5. A minimum of |f| below 1e-7,
    7e-6 beside it, had stood for the mode (residual 4.8e-10, the pose 1.4e-6 off)."""
    modes = solve(load_scene(REGRESSIONS / "robot-I-shallow-root.json")).assembly_modes
    values = [mode.parameters["s1,5"] for mode in modes]
    assert len(values) == 2 and abs(values[1] - 1044) < 1e-9 and abs(values[0] - 1041.7013798524135) < 1e-9
    assert all(mode.max_residual < 1e-13 for mode in modes)


@needs_msolve
def test_a_tangential_root_beside_a_crossing_is_found():
    """tests/regressions/7-N2-tangential-beside-crossing.json (seed 37): on branch -++ f
    touches 0 at s1,8 = 5 and crosses it at 5.0012146; the fine re-sampling's minimum at 5
    had been skipped (its parabola's vertex, 1.1e-14, above half the middle sample)."""
    scene = load_scene(REGRESSIONS / "7-N2-tangential-beside-crossing.json")
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations)) == (0, 0, 0)


def test_a_singular_mode_is_one_mode_and_one_sentence():
    """tests/regressions/7-N1-double-root-131-seed42.json (seed 42): at the singular mode
    s2,7 = 4 on branch ++- the closure condition is flat to rounding over [3.9913, 4.0087];
    the mode is reported once, within 1e-6 of s2,7 = 4 (the middle of its valley), and the
    flat stretch in one sentence (there were 88, one per run of noise roots)."""
    solution = solve(load_scene(REGRESSIONS / "7-N1-double-root-131-seed42.json"))
    near = [mode for mode in solution.assembly_modes if mode.signs == (1, 1, -1) and abs(mode.parameters["s2,7"] - 4) < 0.01]
    assert len(near) == 1 and abs(near[0].parameters["s2,7"] - 4) < 1e-5
    assert len([sentence for sentence in solution.undecided if "on branch ++-: the closure condition is flat" in sentence]) == 1
