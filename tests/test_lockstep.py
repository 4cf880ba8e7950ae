"""Lock-step searches (solvers/numeric/lockstep.py) and Brent's searches in that form
(solvers/numeric/brent.py): running searches side by side changes when their points are
evaluated, never what they compute; Brent's methods give scipy's answers."""

import math
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq, minimize_scalar

from baranov.scene import load_scene
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.numeric.brent import UndefinedInside, brent_minimum, brent_root
from baranov.solvers.numeric.lockstep import Samples, Together, paired_profile, run_alone, run_lockstep
from baranov.solvers.placement import compile_scene

coefficients = st.lists(st.floats(-10, 10, allow_nan=False, allow_infinity=False), min_size=2, max_size=7)


def polynomial(points, signs):
    """f(x) = Σ c_k x^k with the coefficients carried as the "branch" of each point."""
    return np.array([np.polyval(c[::-1], x) for x, c in zip(points, signs, strict=True)])


def tree_search(depth: int, width: int, seed: int):
    """A search that asks for a few points, then runs sub-searches side by side, and
    returns everything it saw: a tree of dependent requests of uneven depth."""
    seen = [(yield Samples(np.linspace(seed, seed + 1, 1 + seed % 3))).tolist()]
    if depth > 0:
        seen.append((yield Together([tree_search(depth - 1, width, seed * width + k) for k in range(width)])))
    seen.append((yield Samples(np.array([seed / 7]))).tolist())
    return seen


@given(st.lists(st.tuples(st.integers(0, 3), st.integers(0, 3), st.integers(0, 50)), min_size=1, max_size=5),
       st.lists(coefficients, min_size=1, max_size=5))
@settings(max_examples=50, deadline=None)
def test_side_by_side_equals_one_at_a_time(shapes, branches):
    """Each search's result run with others equals its result run alone, and the rounds
    are the longest chain of requests, not their sum."""
    width = max(len(c) for c in branches)
    signs = [np.array(c + [0.0] * (width - len(c))) for c in branches]
    tasks = [(tree_search(*shape), signs[n % len(signs)]) for n, shape in enumerate(shapes)]
    together, rounds = run_lockstep(polynomial, tasks)
    alone = [run_alone(tree_search(*shape), polynomial, signs[n % len(signs)]) for n, shape in enumerate(shapes)]
    assert together == alone
    assert rounds == max(2 * (depth + 1) if width else 2 for depth, width, _ in shapes)


def test_requests_on_another_branch_and_empty_requests():
    def search():
        other = yield Samples(np.array([2.0]), np.array([1.0, 1.0]))  # f = 1 + x on another branch
        nothing = yield Samples(np.zeros(0))
        mine = yield Samples(np.array([2.0]))
        empty = yield Together([])
        return float(other[0]), len(nothing), float(mine[0]), empty

    assert run_alone(search(), polynomial, np.array([0.0, 0.0, 1.0])) == (3.0, 0, 4.0, [])


def test_a_search_error_propagates_and_the_deadline_leaves_searches_unfinished():
    def failing():
        yield Samples(np.array([1.0]))
        raise ZeroDivisionError("inside a search")

    with pytest.raises(ZeroDivisionError, match="inside a search"):
        run_lockstep(polynomial, [(failing(), np.ones(1))])
    results, rounds = run_lockstep(polynomial, [(tree_search(2, 2, 1), np.ones(1))], deadline=time.monotonic() - 1)
    assert results == [None] and rounds == 0


@given(coefficients, st.floats(-3, 3), st.floats(0.1, 3))
@settings(max_examples=200, deadline=None)
def test_brent_root_is_scipys(c, low, width):
    f = np.polynomial.Polynomial(c)
    high = low + width
    if not f(low) * f(high) < 0:
        return
    root = run_alone(brent_root(low, high, f(low), f(high), lambda reply: float(reply[0]), 1e-14, 1e-15),
                     polynomial, np.array(c))
    try:
        expected = brentq(f, low, high, xtol=1e-14, rtol=1e-15, maxiter=200)
    except RuntimeError:  # scipy did not converge either (x³ at 0: f below rounding for long)
        return
    assert math.isclose(root, expected, rel_tol=1e-12, abs_tol=1e-13)


@given(coefficients, st.floats(-3, 3), st.floats(0.1, 3))
@settings(max_examples=200, deadline=None)
def test_brent_minimum_is_scipys(c, low, width):
    """The same iterates as scipy's bounded minimize_scalar: the same point, bit for bit."""
    f = np.polynomial.Polynomial(c)
    x, value, success = run_alone(brent_minimum(lambda reply: abs(float(reply[0])), low, low + width, 1e-12),
                                  polynomial, np.array(c))
    expected = minimize_scalar(lambda s: abs(f(s)), bounds=(low, low + width), method="bounded",
                               options={"xatol": 1e-12})
    assert (x, success) == (expected.x, expected.success)


def test_brent_root_meets_an_undefined_point():
    def evaluate(points, signs):
        return np.where(np.abs(points - 0.5) < 0.2, np.nan, points - 0.45)

    with pytest.raises(UndefinedInside):
        run_alone(brent_root(0.0, 1.0, -0.45, 0.55, lambda reply: float(reply[0]), 1e-14, 1e-15), evaluate,
                  np.zeros(1))


def test_profiles_of_a_plan_side_by_side_are_those_of_single_evaluations():
    """paired_profile serves requests of several branches in one evaluation; each reply is
    what evaluating its points alone on its branch gives, bit for bit."""
    scene = load_scene("examples/7-B1.json")
    compiled = compile_scene(scene, solvable_plan(scene))
    branches = [np.array(signs) for signs in ((1, 1, 1), (-1, 1, -1), (1, -1, -1))]

    def search(points):
        return (yield Samples(points))

    points = [np.linspace(1, 200, n) for n in (1, 17, 64)]
    together, rounds = run_lockstep(paired_profile(compiled), list(zip(map(search, points), branches, strict=True)))
    assert rounds == 1
    for reply, at, branch in zip(together, points, branches, strict=True):
        alone = compiled.profile(at[:, None], branch[None, :])
        for part, expected in zip(reply, alone, strict=True):
            np.testing.assert_array_equal(part, expected[0])
