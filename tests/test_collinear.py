"""Joints in line (issue 28): instances drawn with several joints on one line, where a
free-sign triangle of the plan is flat in the generating mode. Both backends must return
the generating configuration and agree mode for mode, and the exact backend must certify
its list complete. The 9-link sweep over every truss is bench/sweep_collinear.py
(docs/stability.md)."""

from __future__ import annotations

import json
import math
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene
from baranov.scene.hard_instances import LINE_DIRECTIONS, collinear_joints_configuration
from baranov.scene.instances import scene_of
from baranov.solvers import solve
from baranov.solvers.verification import distance_bound, same_mode

REGRESSION = Path(__file__).resolve().parent / "regressions" / "9-B28-joints-in-line.json"


def contains(scene, modes, coordinates) -> bool:
    scale = max(1.0, distance_bound(scene))
    return any(all(math.dist(m.joints[j], tuple(map(float, p))) < 1e-6 * scale for j, p in coordinates.items())
               for m in modes)


def same_modes(scene, first, second) -> bool:
    return len(first) == len(second) and all(any(same_mode(m, n, scene) for n in second) for m in first)


@cache
def regression_solutions():
    scene = load_scene(REGRESSION)
    return scene, solve(scene, method="numeric"), solve(scene, method="exact")


@pytest.mark.parametrize("method", ["numeric", "exact"])
def test_the_issue_instance_keeps_its_generating_mode(method):
    """The 9/B28 instance of issue 28: 8 modes, among them s1,11 = 25, s1,9 = 1 with four
    joints on x = 4 (the exact backend used to certify 7)."""
    scene, numeric, exact = regression_solutions()
    solution = numeric if method == "numeric" else exact
    generating = json.loads(REGRESSION.read_text())["generating_configuration"]
    assert len(solution.assembly_modes) == 8
    assert contains(scene, solution.assembly_modes, generating)


def test_the_issue_instance_is_certified_and_both_backends_agree():
    scene, numeric, exact = regression_solutions()
    assert exact.certificate.complete and not exact.certificate.gaps
    assert exact.characteristic_polynomial.degree == 58  # Appendix A: 58 modes over C for 9/B28
    assert same_modes(scene, numeric.assembly_modes, exact.assembly_modes)


def check_instance(truss, coordinates) -> None:
    scene = scene_of(truss, coordinates)
    numeric, exact = solve(scene, method="numeric"), solve(scene, method="exact")
    assert contains(scene, numeric.assembly_modes, coordinates), "numeric backend lost the generating mode"
    assert contains(scene, exact.assembly_modes, coordinates), "exact backend lost the generating mode"
    assert exact.certificate.complete, exact.certificate.gaps
    assert same_modes(scene, numeric.assembly_modes, exact.assembly_modes)


@settings(max_examples=20, deadline=None)
@given(index=st.integers(0, 2), on_line=st.sampled_from([3, 4]), direction=st.sampled_from(sorted(LINE_DIRECTIONS)),
       seed=st.integers(0, 2**32 - 1))
def test_seven_link_trusses_with_joints_in_line(index, on_line, direction, seed):
    truss = baranov_trusses(7)[index]
    check_instance(truss, collinear_joints_configuration(truss, np.random.default_rng(seed), on_line, 3, direction))


@pytest.mark.parametrize("index", [0, 6, 13, 20])
def test_nine_link_trusses_with_joints_in_line(index):
    """A fast sample of the 9-link sweep (coupling degree 1; the sweep has all 28)."""
    truss = baranov_trusses(9)[index]
    for on_line in (3, 4):
        rng = np.random.default_rng([28, index, on_line])
        check_instance(truss, collinear_joints_configuration(truss, rng, on_line, 4, "vertical"))


def test_generator_puts_the_joints_on_one_line():
    truss = baranov_trusses(9)[5]
    for direction, (dx, dy) in LINE_DIRECTIONS.items():
        points = collinear_joints_configuration(truss, np.random.default_rng(3), 4, 4, direction)
        # the value of the line's normal form is shared by at least 4 joints
        values = [dy * x - dx * y for x, y in points.values()]
        assert max(values.count(v) for v in values) >= 4
        assert len(set(points.values())) == len(points)


def test_generator_refuses_bad_arguments():
    truss = baranov_trusses(7)[0]
    with pytest.raises(ValueError, match="direction 'up'"):
        collinear_joints_configuration(truss, np.random.default_rng(0), 3, 4, "up")
    with pytest.raises(ValueError, match="on_line 11"):
        collinear_joints_configuration(truss, np.random.default_rng(0), 11, 4)


SWEEP_FINDS = sorted((Path(__file__).resolve().parent / "regressions").glob("9-joints-in-line-*.json"))


@pytest.mark.parametrize("path", SWEEP_FINDS, ids=lambda p: p.stem)
def test_sweep_finds_agree_mode_for_mode(path):
    """The coupling-1 instances bench/sweep_collinear.py found (each file says what was
    lost and why): both backends keep the generating mode and agree, the exact solve is
    certified complete. (The coupling-2 find, 9-B28-joints-in-line-fold, is checked for
    the numeric backend by test_solvers.test_saved_misses_are_found; its exact solve
    takes about 40 s.)"""
    scene = load_scene(path)
    generating = {}
    for link in json.loads(path.read_text())["links"]:
        generating.update(link["joints"])
    numeric, exact = solve(scene, method="numeric"), solve(scene, method="exact")
    assert contains(scene, numeric.assembly_modes, generating)
    assert contains(scene, exact.assembly_modes, generating)
    assert exact.certificate.complete, exact.certificate.gaps
    assert same_modes(scene, numeric.assembly_modes, exact.assembly_modes)
