"""The bilateration kernel (closure/bilateration.py) in each arithmetic it runs in: at the
parameter values and signs of a random configuration of a truss, numpy floats, flint
balls, the exact radical tower and a link's own float frame must all place that
configuration (issue 16: one kernel, four arithmetics)."""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from baranov.closure import bilaterated, place_joints, squared_distance, triangle_radicand
from baranov.closure.evaluate import true_parameters_and_signs
from baranov.enumerate import baranov_trusses
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.exact.characteristic import characteristic_polynomial, closure_residuals, radical_tower
from baranov.solvers.placement import compile_scene

TRUSSES = [(links, index) for links in (3, 5, 7, 9) for index in range(len(baranov_trusses(links)))]


def _instance(links: int, index: int, seed: int):
    truss = baranov_trusses(links)[index]
    coordinates = generic_integer_configuration(truss, np.random.default_rng([seed, links, index]))
    scene = scene_of(truss, coordinates)
    plan = solvable_plan(scene)
    system = compile_scene(scene, plan).system
    values, signs = true_parameters_and_signs(system, {n: tuple(map(float, p)) for n, p in coordinates.items()})
    return scene, plan, coordinates, values, signs


def _exact_parameters(plan, coordinates) -> list[Fraction]:
    return [sum((coordinates[u][c] - coordinates[v][c]) ** 2 for c in (0, 1)) for u, v in plan.parameters]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(TRUSSES), st.integers(0, 10**6))
def test_floats_and_balls_place_the_generating_configuration(truss, seed):
    """numpy floats: closure residuals vanish; flint balls (exact rational parameters):
    every closure residual's ball contains 0, and the placed points agree with the
    floats' to 1e-9."""
    scene, plan, coordinates, values, signs = _instance(*truss, seed)
    compiled = compile_scene(scene, plan)
    residuals = compiled.paired_residuals(values, signs)
    assert np.all(np.abs(residuals) < 1e-9)
    exact = [flint.acb(flint.fmpq(v.numerator, v.denominator)) for v in _exact_parameters(plan, coordinates)]
    balls, points, _ = closure_residuals(scene, plan, exact, [int(s) for s in signs[0]], real_only=True)
    assert balls is not None and all(residual.contains(0) for residual, _ in balls)
    floats = compiled.paired_matrices(values, signs)
    for joint, (x, y) in points.items():
        assert abs(complex(x.real.mid()) + 1j * float(y.real.mid()) - floats[joint][0]) < 1e-9 * (1 + abs(floats[joint][0]))


@pytest.mark.parametrize("truss", [t for t in TRUSSES if t[0] <= 7] + [(9, 0), (9, 27)], ids=lambda t: f"{t[0]}-N{t[1] + 1}")
def test_exact_tower_vanishes_at_the_generating_configuration(truss):
    """The radical tower's closure conditions (exact rationals): for coupling degree 1 the
    characteristic polynomial vanishes exactly at the configuration's parameter; for
    coupling degree 2 the tower modulo a prime has as many conditions as closure pairs."""
    scene, plan, coordinates, _, _ = _instance(*truss, 3)
    if plan.number_of_parameters == 1:
        value = _exact_parameters(plan, coordinates)[0]
        polynomial = characteristic_polynomial(scene, plan).polynomial
        assert polynomial(flint.fmpq(value.numerator, value.denominator)) == 0
    else:
        tower = radical_tower(scene, plan, prime=1_000_003)
        assert len(tower.conditions) == len(plan.closure_pairs)


def test_link_frames_keep_every_distance():
    """A link's own frame (scene/model.py, plain floats) reproduces its squared distances."""
    scene, *_ = _instance(9, 27, 5)
    for link in scene.links:
        for (u, p), (v, q) in ((a, b) for a in link.local.items() for b in link.local.items() if a[0] < b[0]):
            assert math.isclose(math.dist(p, q) ** 2, float(scene.known[frozenset((u, v))]), rel_tol=1e-12)


def test_kernel_in_integers_is_exact():
    """In Python integers the homogeneous kernel is exact: the 3-4-5 triangle and the
    distance back from the placed point."""
    sides = (25, 9, 16)
    root = math.isqrt(triangle_radicand(*sides))
    x, y, w = bilaterated((0, 0, 1), (5, 0, 1), sides, root)
    assert (Fraction(x, w), Fraction(y, w)) == (Fraction(9, 5), Fraction(12, 5))
    numerator, denominator = squared_distance((5, 0, 1), (x, y, w), (1, 1))
    assert Fraction(numerator, denominator) == 16


def test_place_joints_stops_when_asked():
    """``after_step`` returning False stops the placement (the ball arithmetic stops at an
    undefined step)."""
    scene, plan, *_ = _instance(7, 0, 1)
    seen = []
    known = {pair: (float(value), 1) for pair, value in scene.known.items()}

    def distance(u, v):
        pair = frozenset((u, v))
        return known.get(pair, (25.0, 1) if pair in {frozenset(p) for p in plan.parameters} else None)

    place_joints(plan, distance, lambda index, step, sides, radicand: math.sqrt(abs(radicand)),
                 after_step=lambda index, step, point: seen.append(index) or index < 1)
    assert seen == [0, 1]
