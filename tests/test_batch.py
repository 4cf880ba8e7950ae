"""Batches of one linkage (solvers/batch.py, scene/dimensions.py, `baranov solve --batch`)
and the plan cache they rely on (issue 21)."""

import json
import subprocess
import sys
from fractions import Fraction
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan, clear_plan_cache
from baranov.planner.search import _cached_plans
from baranov.scene import SceneError, dimension_names, load_scene, scene_from_dict, with_dimensions
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import BatchError, MovableLinkageError, instance_scenes, solve, solve_many
from baranov.solvers.verification import same_mode

REPO = Path(__file__).resolve().parents[1]
EXAMPLE = REPO / "examples" / "7-B1.json"


def orientation(coordinates, triangle) -> int:
    (x1, y1), (x2, y2), (x3, y3) = (coordinates[name] for name in triangle)
    return int(np.sign((x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1)))


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kind=st.integers(0, 2), seed=st.integers(0, 2**32 - 1), moves=st.lists(
    st.tuples(st.integers(0, 5), st.integers(-2, 2), st.integers(-2, 2)), min_size=1, max_size=3))
def test_a_batch_finds_each_generating_configuration_and_the_single_solves_modes(kind, seed, moves):
    """Each instance moves joints of a random 7-link configuration (the fixed link's joints
    stay, every link keeps its orientation); the batch, given only the moved dimensions,
    finds that configuration among its modes, and its modes are those of a single solve of
    the same scene with the plan searched anew (the cache cleared)."""
    truss = baranov_trusses(7)[kind]
    start = generic_integer_configuration(truss, np.random.default_rng(seed))
    scene = scene_of(truss, start)
    ground = set(scene.world)
    movable = sorted(set(start) - ground)
    configurations, rows = [], []
    for joint, dx, dy in moves:
        moved = dict(start)
        name = movable[joint % len(movable)]
        moved[name] = (moved[name][0] + dx, moved[name][1] + dy)
        triangles = [link.joints[:3] for link in scene.links if len(link.joints) >= 3]
        assume(all(orientation(moved, t) == orientation(start, t) != 0 for t in triangles))
        assume(len(set(moved.values())) == len(moved))
        configurations.append(moved)
        rows.append({key: (moved[a][0] - moved[b][0]) ** 2 + (moved[a][1] - moved[b][1]) ** 2
                     for key in dimension_names(scene) for a, b in [key.split(",")]})
    solutions = solve_many(scene, rows)
    for configuration, row, solution in zip(configurations, rows, solutions, strict=True):
        generating = SimpleNamespace(joints={k: tuple(map(float, v)) for k, v in configuration.items()})
        assert any(same_mode(generating, mode, scene) for mode in solution.assembly_modes)
        clear_plan_cache()
        single = solve(with_dimensions(scene, row))
        assert [(m.parameters, m.signs, m.joints) for m in single.assembly_modes] == \
               [(m.parameters, m.signs, m.joints) for m in solution.assembly_modes]


def test_with_dimensions_is_the_scene_file_with_those_numbers():
    """with_dimensions against the scene built from its file with the numbers replaced:
    the same dimensions, orientations and exactness."""
    scene = load_scene(EXAMPLE)
    data = json.loads(EXAMPLE.read_text())
    side = scene.orientation(("P2", "P4", "P7"))  # kept by with_dimensions
    for link in data["links"]:
        if link["name"] == "t247":
            link["joints"] = {"P2": [0, 0], "P4": [5, 0], "P7": [5, 3 * side]}  # s2,4 = 25, s2,7 = 34, s4,7 = 9
    expected = scene_from_dict(data)
    changed = with_dimensions(scene, {"P2,P7": 34, ("P4", "P7"): "9"})
    assert changed.known == expected.known and changed.exact
    assert all(changed.orientation(link.joints[:3]) == expected.orientation(link.joints[:3])
               for link in changed.links if len(link.joints) >= 3)
    assert not with_dimensions(scene, {"P1,P2": 101.5}).exact
    assert str(with_dimensions(scene, {"P1,P2": "203/2"}).known[frozenset(("P1", "P2"))]) == "203/2"


@pytest.mark.parametrize(("dimensions", "message"), [
    ({"P3,P4": 30}, "dimension P3,P4: on the fixed link t345"),
    ({"P1,P9": 30}, "dimension P1,P9: joints on no common link"),
    ({"P1": 30}, "dimension 'P1': should name two joints"),
    ({"P2,P7": 1000}, "link t247: squared distances of P2, P4, P7 violate the triangle inequality"),
    ({"P1,P2": "x"}, "link b12, squared distance P1,P2: 'x' is not a number"),
    ({"P1,P2": 0}, "link b12"),
])
def test_with_dimensions_names_the_bad_dimension(dimensions, message):
    with pytest.raises(SceneError, match=None) as raised:
        with_dimensions(load_scene(EXAMPLE), dimensions)
    assert message in str(raised.value)


def test_instances_from_rows_and_columns_numpy_and_errors():
    scene = load_scene(EXAMPLE)
    exact = instance_scenes(scene, np.array([[100], [102]]), ["P1,P2"])
    assert [s.exact for s in exact] == [True, True]
    assert [str(s.known[frozenset(("P1", "P2"))]) for s in exact] == ["100", "102"]
    assert not instance_scenes(scene, np.array([[100.5]]), ["P1,P2"])[0].exact
    with pytest.raises(BatchError, match=r"instance 2: 2 values for 1 columns"):
        instance_scenes(scene, [[100], [1, 2]], ["P1,P2"])
    with pytest.raises(BatchError, match=r"instance 1: expected a mapping"):
        instance_scenes(scene, [[100]])
    with pytest.raises(BatchError, match=r"instance 3: link t247"):
        instance_scenes(scene, [{"P2,P7": 36}, {"P2,P7": 37}, {"P2,P7": 1000}])


def test_an_exact_batch_is_certified():
    """Integers keep the instances exact for the exact backend."""
    scene = load_scene(EXAMPLE)
    seen = []
    solutions = solve_many(scene, [[101], [100]], ["P1,P2"], method="exact", on_solution=lambda k, r: seen.append(k))
    assert seen == [1, 2]
    assert [len(s.assembly_modes) for s in solutions] == [8, len(solve(instance_scenes(scene, [[100]], ["P1,P2"])[0],
                                                                      "exact").assembly_modes)]
    assert all(s.certificate.complete for s in solutions)


def test_movable_instance_raises_or_stands_in_the_list():
    """A parallelogram instance of a 5/B1-shaped scene moves (MovableLinkageError)."""
    data = {"ground": "g", "links": [
        {"name": "g", "joints": {"P1": [0, 0], "P2": [4, 0], "P3": [8, 0]}},
        {"name": "a", "joints": ["P1", "P4"], "squared_length": 9},
        {"name": "b", "joints": ["P2", "P5"], "squared_length": 9},
        {"name": "c", "joints": ["P3", "P6"], "squared_length": 9},
        {"name": "t", "joints": {"P4": [0, 3], "P5": [4, 3], "P6": [8, 3]}}]}
    scene = scene_from_dict(data)
    results = solve_many(scene, [{"P1,P4": 10}, {"P1,P4": 9}], return_errors=True)
    assert not isinstance(results[0], Exception)
    assert isinstance(results[1], MovableLinkageError)
    with pytest.raises(MovableLinkageError):
        solve_many(scene, [{"P1,P4": 9}])


def test_the_plan_is_searched_once_per_topology():
    truss = baranov_trusses(9)[3]
    clear_plan_cache()
    first = best_plan(truss)
    misses = _cached_plans.cache_info().misses
    assert best_plan(truss) is first and _cached_plans.cache_info().misses == misses
    relabelled = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(1))).chain
    assert best_plan(relabelled).number_of_parameters == first.number_of_parameters


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "baranov.cli", *args], capture_output=True, text=True)


def test_cli_batch_writes_one_json_line_per_instance(tmp_path):
    csv = tmp_path / "sweep.csv"
    csv.write_text('"P1,P2","P2,P7"\n101,36\n100.5,36\n')
    printed = run("solve", str(EXAMPLE), "--batch", str(csv))
    assert printed.returncode == 0, printed.stderr
    lines = [json.loads(line) for line in printed.stdout.splitlines()]
    assert [line["instance"] for line in lines] == [1, 2]
    assert lines[0]["dimensions"] == {"P1,P2": "101", "P2,P7": "36"} and len(lines[0]["assembly_modes"]) == 8
    single = solve(with_dimensions(load_scene(EXAMPLE), {"P1,P2": Fraction(201, 2)}))
    assert len(lines[1]["assembly_modes"]) == len(single.assembly_modes)
    jsonl = tmp_path / "sweep.jsonl"
    jsonl.write_text('{"P1,P2": 101}\n\n{"P1,P2": 100.5}\n')
    out = tmp_path / "modes.jsonl"
    written = run("solve", str(EXAMPLE), "--batch", str(jsonl), "--out", str(out), "--method", "exact")
    assert written.returncode == 0 and written.stdout == ""
    assert [json.loads(line)["certificate"]["complete"] for line in out.read_text().splitlines()] == [True, True]


@pytest.mark.parametrize(("content", "extra", "message"), [
    ('"P1,P2"\n101\n1e9999x\n', (), "instance 2: link b12, squared distance P1,P2: '1e9999x' is not a number"),
    ('"P3,P4"\n30\n', (), "dimension P3,P4: on the fixed link t345"),
    ('"P1,P2","P2,P7"\n101\n', (), "row 2: 1 values for 2 columns"),
    ('"P1,P2"\n101\n', ("--plot", "x.png"), "--batch: prints JSON lines"),
])
def test_cli_batch_bad_input_is_one_line_exit_2_nothing_written(tmp_path, content, extra, message):
    csv = tmp_path / "bad.csv"
    csv.write_text(content)
    out = tmp_path / "modes.jsonl"
    result = run("solve", str(EXAMPLE), "--batch", str(csv), "--out", str(out), *extra)
    assert result.returncode == 2 and result.stdout == "" and result.stderr.count("\n") == 1
    assert message in result.stderr, result.stderr
    assert not out.exists() and not list(tmp_path.glob(".*.tmp"))


def test_cli_out_and_workers_without_batch_are_refused(tmp_path):
    result = run("solve", str(EXAMPLE), "--out", str(tmp_path / "x.jsonl"))
    assert result.returncode == 2 and "--out: for --batch only" in result.stderr
    assert "--workers: for --batch only" in run("solve", str(EXAMPLE), "--workers", "2").stderr


def test_workers_give_the_same_solutions_in_order(tmp_path):
    """Two processes: the same modes in the same order as one, callbacks in order, an
    instance's error in its place; and on the command line the same lines."""
    scene = load_scene(EXAMPLE)
    rows = [[100], [101], [102], [103], [104]]
    seen = []
    together = solve_many(scene, rows, ["P1,P2"], workers=2, on_solution=lambda k, r: seen.append(k))
    alone = solve_many(scene, rows, ["P1,P2"])
    assert seen == [1, 2, 3, 4, 5]
    assert [[m.joints for m in s.assembly_modes] for s in together] == [[m.joints for m in s.assembly_modes]
                                                                          for s in alone]
    with pytest.raises(ValueError, match="workers=0"):
        solve_many(scene, rows, ["P1,P2"], workers=0)
    csv = tmp_path / "sweep.csv"
    csv.write_text('"P1,P2"\n100\n101\n102\n')
    lines = [run("solve", str(EXAMPLE), "--batch", str(csv), *extra).stdout for extra in ((), ("--workers", "2"))]
    assert lines[0] == lines[1] and lines[0].count("\n") == 3
