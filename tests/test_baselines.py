"""The baselines of the speed-vs-accuracy study (issue 6): each finds what it should on
small cases, and fails where the study says it does."""

from __future__ import annotations

from pathlib import Path

import pytest

from baranov.baselines import (
    FloatPolynomialError,
    cartesian_size,
    loop_size,
    solve_cartesian,
    solve_float_polynomial,
    solve_loop_equations,
)
from baranov.scene import load_scene
from baranov.solvers import solve
from baranov.solvers.verification import RESIDUAL_TOLERANCE, same_mode

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _matches(found, reference, scene) -> int:
    return sum(any(same_mode(r, m, scene) and m.max_residual < RESIDUAL_TOLERANCE for m in found) for r in reference)


def test_loop_equations_find_the_six_modes_of_5_b1():
    scene = load_scene(EXAMPLES / "5-B1.json")
    reference = solve(scene, method="exact").assembly_modes
    found = solve_loop_equations(scene).assembly_modes
    assert len(reference) == 6 and _matches(found, reference, scene) == 6 and len(found) == 6
    assert loop_size(scene) == (4, 4)


def test_cartesian_solutions_are_modes_or_mirrored_links():
    scene = load_scene(EXAMPLES / "5-B1.json")
    reference = solve(scene, method="exact").assembly_modes
    found = solve_cartesian(scene, starts=100, seed=3).assembly_modes
    verified = [m for m in found if m.max_residual < RESIDUAL_TOLERANCE]
    assert all(any(same_mode(m, r, scene) for r in reference) for m in verified)
    assert all(m.max_residual == 1.0 for m in found if m.max_residual >= RESIDUAL_TOLERANCE)  # mirrored link
    assert cartesian_size(scene) == (6, 6)  # 3 joints off the ground; 3 legs + 3 platform sides


def test_rounded_polynomial_at_100_digits_finds_what_float64_misses():
    scene = load_scene(EXAMPLES / "7-B1.json")
    reference = solve(scene, method="exact").assembly_modes
    assert _matches(solve_float_polynomial(scene, digits=100).assembly_modes, reference, scene) == len(reference)
    assert _matches(solve_float_polynomial(scene).assembly_modes, reference, scene) < len(reference)


def test_rounded_polynomial_needs_coupling_degree_one():
    with pytest.raises(FloatPolynomialError, match="coupling degree 0"):
        solve_float_polynomial(load_scene(EXAMPLES / "3-B1.json"))
