"""Scenes of mobile linkages and their inputs (scene/inputs.py): the input model that
one-DOF tracing (issue 19) will read; the law of cosines against coordinates."""

from __future__ import annotations

import cmath
import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.scene import SceneError, angle_as_distance, scene_from_dict
from baranov.solvers import SolverError, solve

FOUR_BAR = {"ground": "L0", "links": [
    {"name": "L0", "joints": {"P1": [0, 0], "P4": [4, 0]}},
    {"name": "L1", "joints": ["P1", "P2"], "squared_length": 1},
    {"name": "L2", "joints": ["P2", "P3"], "squared_length": 16},
    {"name": "L3", "joints": ["P3", "P4"], "squared_length": 9}]}


def test_a_four_bar_with_a_crank_angle_is_a_scene():
    scene = scene_from_dict({**FOUR_BAR, "inputs": [{"name": "crank", "angle": ["P1", "P4", "P2"], "degrees": 30}]})
    assert scene.mobility == 1
    (crank,) = scene.inputs
    assert (crank.name, crank.kind, crank.joints, crank.value) == ("crank", "angle", ("P1", "P4", "P2"), 30)
    assert crank.driven_pair == ("P4", "P2")


def test_an_input_may_be_left_without_a_value():
    scene = scene_from_dict({**FOUR_BAR, "inputs": [{"name": "coupler", "distance": ["P1", "P3"]}]})
    assert scene.inputs[0].value is None and scene.inputs[0].driven_pair == ("P1", "P3")


def test_a_mobile_scene_is_refused_by_the_solvers_with_its_mobility():
    scene = scene_from_dict(FOUR_BAR)
    with pytest.raises(SolverError, match=r"mobility 1 \(3\(L-1\) - 2J with L = 4 links\)"):
        solve(scene)


def test_an_over_constrained_part_of_a_mobile_chain_is_refused():
    """Links A, B, C, D joined by five joints (2·5 > 3·4 − 3: over-constrained) and a
    chain of four binary links from B to D: F = 3·7 − 2·10 = 1, yet not a mobile chain."""
    def ternary(name, points):
        return {"name": name, "joints": {joint: list(xy) for joint, xy in points.items()}}

    def binary(name, u, v):
        return {"name": name, "joints": [u, v], "squared_length": 25}
    links = [ternary("A", {"P1": (0, 0), "P4": (5, 0), "P5": (0, 5)}),
             ternary("B", {"P1": (0, 0), "P2": (5, 0), "P6": (0, 5)}),
             ternary("C", {"P2": (0, 0), "P3": (5, 0), "P5": (0, 5)}),
             ternary("D", {"P3": (0, 0), "P4": (5, 0), "P10": (0, 5)}),
             binary("E1", "P6", "P7"), binary("E2", "P7", "P8"), binary("E3", "P8", "P9"), binary("E4", "P9", "P10")]
    with pytest.raises(SceneError, match="links A, B, C, D are over-constrained"):
        scene_from_dict({"ground": "A", "links": links})


@pytest.mark.parametrize("inputs, message", [
    ([{"name": "a", "angle": ["P1", "P4", "P2"]}, {"name": "a", "distance": ["P1", "P3"]}], "more|mobility 1"),
    ([{"name": "a", "angle": ["P2", "P1", "P4"]}], "between the links that meet there"),
    ([{"name": "a", "distance": ["P1", "P1"]}], "two different joints"),
    ([{"name": "a", "distance": ["P1", "P9"]}], "joint P9 is not in the scene"),
    ([{"name": "a", "distance": ["P1", "P3"], "squared_distance": 0}], "must be positive"),
    ([{"name": "a", "angle": ["P1", "P4"]}], "should list 3 joint names"),
    ([{"name": "a", "angle": ["P1", "P4", "P2"], "distance": ["P1", "P3"]}], "either"),
    ([{"name": "a", "angle": ["P1", "P4", "P2"], "degree": 3}], 'did you mean "degrees"'),
    ({"name": "a"}, "expected a list of inputs"),
])
def test_bad_inputs_name_the_input_and_the_fault(inputs, message):
    with pytest.raises(SceneError, match=message):
        scene_from_dict({**FOUR_BAR, "inputs": inputs})


@settings(max_examples=200, deadline=None)
@given(st.integers(-40, 40), st.integers(-40, 40), st.integers(-40, 40), st.integers(-40, 40),
       st.floats(-720, 720, allow_nan=False))
def test_angle_as_distance_is_the_law_of_cosines(fx, fy, tx, ty, degrees):
    """Against coordinates: P_a at the origin, P_f anywhere, P_t the point at the angle θ
    from P_f (counter-clockwise) and at the given distance."""
    start = complex(fx, fy)
    end_length = abs(complex(tx, ty))
    if start == 0 or end_length == 0:
        return
    end = end_length * cmath.exp(1j * (cmath.phase(start) + math.radians(degrees)))
    squared, orientation = angle_as_distance(Fraction(fx * fx + fy * fy), Fraction(tx * tx + ty * ty), degrees)
    assert math.isclose(squared, abs(end - start) ** 2, rel_tol=1e-9, abs_tol=1e-9 * (abs(start) + end_length) ** 2)
    cross = (start.conjugate() * end).imag
    if abs(cross) > 1e-9 * abs(start) * end_length:
        assert orientation == (1 if cross > 0 else -1)


@pytest.mark.parametrize("degrees, expected", [(0, (Fraction(1), 0)), (90, (Fraction(25), 1)),
                                               (180, (Fraction(49), 0)), (270, (Fraction(25), -1)),
                                               (-90, (Fraction(25), -1)), (450, (Fraction(25), 1))])
def test_right_angles_stay_exact(degrees, expected):
    assert angle_as_distance(Fraction(9), Fraction(16), Fraction(degrees)) == expected
