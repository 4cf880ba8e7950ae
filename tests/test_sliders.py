"""Slider joints (scene/sliders.py, thesis ch. 4, paper 003): the scene format, its
validation, exact angles, and the three published 7/B3 slider chains of thesis
§4.2.2–4.2.4 reproduced by the independent msolve oracle on the Cartesian system."""

from __future__ import annotations

import copy
import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.planner import best_plan
from baranov.scene import SceneError, load_scene, scene_from_dict
from baranov.scene.sliders import angle_direction
from baranov.solvers import SolverError, solve
from baranov.solvers.msolve import compare_modes, find_msolve, msolve_modes
from baranov.solvers.msolve_backend import described_mode
from baranov.topology.chain import JointKind

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")


def _s16(configuration: dict, first: str = "P1") -> float:
    (x1, y1), (x6, y6) = configuration[first], configuration["P6"]
    return (x1 - x6) ** 2 + (y1 - y6) ** 2


@needs_msolve
@pytest.mark.parametrize("example, published", [
    ("7-B3-slider-P9", [49.5561, 50.1965, 50.6270, 85.0000]),   # thesis §4.2.2
    ("7-B3-sliders-P8-P9", [48.1037, 85.0000, 88.2000, 88.5483]),  # §4.2.3, erratum alpha7 = pi - atan(4/5)
])
def test_the_published_slider_chains_have_the_published_roots(example, published):
    result = msolve_modes(load_scene(EXAMPLES / f"{example}.json"))
    assert result.status == "finite"
    assert sorted(round(_s16(c), 4) for c in result.configurations) == published


@needs_msolve
def test_a_slider_at_an_end_of_the_variable_segment_gives_the_published_t():
    """§4.2.4: the variable is t, P6's oriented distance to the slider's axis (the line
    P1 P2 of the ground, sliding towards P2: +x); published real roots 7.4867, 8.7825."""
    scene = load_scene(EXAMPLES / "7-B3-slider-P1.json")
    result = msolve_modes(scene)
    assert result.status == "finite"
    assert sorted(round(c["P6"][1] - c["P1'"][1], 4) for c in result.configurations) == [7.4867, 8.7825]
    for configuration in result.configurations:  # P1'' slides on the ground's axis, y = 0
        assert abs(configuration["P1''"][1]) < 1e-12


@needs_msolve
def test_a_reversed_axis_is_another_mechanism():
    """The Cartesian system asks the two links' axes to be parallel; turning one by π
    (the same line, opposite sense) gives a different chain, whose modes are not these."""
    data = json.loads((EXAMPLES / "7-B3-slider-P9.json").read_text())
    data["sliders"][0]["angles"]["t789"]["P7"] = "pi - atan(5/3)"  # 2 pi - atan(5/3) turned by pi
    reversed_modes = msolve_modes(scene_from_dict(data)).configurations
    assert sorted(round(_s16(c), 4) for c in reversed_modes) != [49.5561, 50.1965, 50.6270, 85.0]


def test_a_slider_scene_names_the_two_points_of_the_joint():
    scene = load_scene(EXAMPLES / "7-B3-sliders-P8-P9.json")
    kinds = {joint.name: joint.kind for joint in scene.chain.joints}
    assert kinds["P9"] == kinds["P8"] == JointKind.SLIDER and kinds["P5"] == JointKind.REVOLUTE
    assert (scene.point_name("t569", "P9"), scene.point_name("t789", "P9")) == ("P9'", "P9''")
    assert (scene.point_name("t789", "P8"), scene.point_name("b28", "P8")) == ("P8'", "P8''")
    assert scene.point_name("t789", "P7") == "P7"
    axis = scene.sliders[1].axis_on("b28")
    assert (axis.reference, axis.direction) == ("P2", (Fraction(-1), Fraction(4, 5)))
    assert scene.exact


def test_the_baselines_refuse_sliders_with_a_clear_message():
    with pytest.raises(SolverError, match="slider joints P9: the cartesian method does not solve slider joints yet.*"
                                          "use --method numeric or --method exact or --method msolve"):
        solve(load_scene(EXAMPLES / "7-B3-slider-P9.json"), method="cartesian")


@pytest.mark.parametrize("example, name, published", [
    ("7-B3-slider-P9", "s1,6", [49.5561, 50.1965, 50.6270, 85.0000]),
    ("7-B3-sliders-P8-P9", "s1,6", [48.1037, 85.0000, 88.2000, 88.5483]),
    ("7-B3-slider-P1", "t1,6", [7.4867, 8.7825]),
])
def test_the_numeric_method_reproduces_the_published_roots(example, name, published):
    """The slider constructions of closure/sliders.py in the numeric backend: every mode,
    described in the thesis's variable (the truss's best plan; t1,6 for a slider at an
    end of the variable segment, §4.2.4), verified to rounding."""
    scene = load_scene(EXAMPLES / f"{example}.json")
    thesis = best_plan(scene.chain)
    modes = solve(scene).assembly_modes
    values = sorted(described_mode(scene, thesis, mode.joints, mode.max_residual).parameters[name] for mode in modes)
    assert [round(value, 4) for value in values] == published
    assert all(mode.max_residual < 1e-12 for mode in modes)


@needs_msolve
@pytest.mark.parametrize("example, name, published", [
    ("7-B3-slider-P9", "s1,6", [49.5561, 50.1965, 50.6270, 85.0000]),
    ("7-B3-sliders-P8-P9", "s1,6", [48.1037, 85.0000, 88.2000, 88.5483]),
    ("7-B3-slider-P1", "t1,6", [7.4867, 8.7825]),
])
def test_the_msolve_method_solves_slider_chains_in_the_thesis_variable(example, name, published):
    solution = solve(load_scene(EXAMPLES / f"{example}.json"), method="msolve")
    assert solution.parameters == (name,)
    assert [round(mode.parameters[name], 4) for mode in solution.assembly_modes] == published
    assert all(mode.max_residual < 1e-12 for mode in solution.assembly_modes)


@needs_msolve
def test_a_slider_residual_sees_a_turned_or_shifted_axis():
    """The verification every method shares (solvers/verification.py): a configuration
    of the P9 chain verifies to rounding; turning link t789 about P9'' by 1e-3 rad, or
    moving it off the axis, is an error of that size; reversing it is 1."""
    from baranov.solvers.verification import joint_residual

    scene = load_scene(EXAMPLES / "7-B3-slider-P9.json")
    mode = {name: complex(*xy) for name, xy in msolve_modes(scene).configurations[0].items()}
    assert joint_residual(scene, mode) < 1e-12
    moved = ("P7", "P8", "P9''")

    def changed(transform):
        return {name: transform(point) if name in moved else point for name, point in mode.items()}

    pivot = mode["P9''"]
    turned = changed(lambda p: pivot + (p - pivot) * complex(math.cos(1e-3), math.sin(1e-3)))
    assert 5e-4 < joint_residual(scene, turned) < 2e-3
    shifted = changed(lambda p: p + 1e-3j * (mode["P9'"] - mode["P9''"]) / abs(mode["P9'"] - mode["P9''"]))
    assert joint_residual(scene, shifted) > 1e-6
    reversed_link = changed(lambda p: pivot - (p - pivot))
    assert joint_residual(scene, reversed_link) >= 1.0


def _with_sliders(sliders) -> dict:
    data = json.loads((EXAMPLES / "7-B3-section-4.2.1.json").read_text())
    data["sliders"] = copy.deepcopy(sliders)
    return data


P9 = {"joint": "P9", "angles": {"t569": {"P5": "pi - atan(5/2)"}, "t789": {"P7": "2 pi - atan(5/3)"}}}


@pytest.mark.parametrize("sliders, message", [
    ([P9, {"joint": "P5", "angles": {"b15": {"P1": 0}, "t569": {"P6": 0}}},
      {"joint": "P1", "angles": {"q1234": {"P2": 0}, "b15": {"P5": 0}}},
      {"joint": "P3", "angles": {"q1234": {"P2": 0}, "b36": {"P6": 0}}},
      {"joint": "P6", "angles": {"b36": {"P3": 0}, "t569": {"P5": 0}}}], "close the loop of links"),
    ([P9, P9], "slider P9: given twice"),
    ([{"joint": "P10", "angles": {}}], "slider P10: no link has this joint"),
    ([{"joint": "P9", "angles": {"t569": {"P5": 0}}}], 'should give one angle on each of its links t569 and t789'),
    ([{"joint": "P9", "angles": {"t569": {"P5": 0, "P6": 1}, "t789": {"P7": 0}}}], "exactly one other joint"),
    ([{"joint": "P9", "angles": {"t569": {"P9": 0}, "t789": {"P7": 0}}}], "P9 is not another joint of that link"),
    ([{"joint": "P9", "angles": {"t569": {"P7": 0}, "t789": {"P7": 0}}}], "P7 is not another joint of that link"),
    ([{"joint": "P9", "angles": {"t569": {"P5": "pi minus 2"}, "t789": {"P7": 0}}}], "angle of P5: 'pi minus 2'"),
    ([{"joint": "P9", "angles": {"t569": {"P5": [0, 0]}, "t789": {"P7": 0}}}], "has no angle"),
    ([{"joint": "P9", "angle": {}}], 'unknown key .angle. \\(did you mean "angles"'),
    ({"joint": "P9"}, "sliders: expected a list"),
])
def test_bad_sliders_name_the_joint_and_the_fault(sliders, message):
    with pytest.raises(SceneError, match=message):
        scene_from_dict(_with_sliders(sliders))


def test_a_loop_of_sliders_is_refused_by_name():
    loop = [{"joint": joint, "angles": {link: {other: 0} for link, other in links}} for joint, links in (
        ("P5", (("b15", "P1"), ("t569", "P6"))), ("P1", (("q1234", "P2"), ("b15", "P5"))),
        ("P3", (("q1234", "P2"), ("b36", "P6"))), ("P6", (("b36", "P3"), ("t569", "P5"))))]
    with pytest.raises(SceneError, match=r"sliders P\d, P\d, P\d, P\d: they close the loop of links b15, b36, q1234, "
                                         "t569 by sliders only"):
        scene_from_dict(_with_sliders(loop))


def test_angles_in_degrees_are_exact_at_multiples_of_45():
    assert angle_direction(135) == (Fraction(-1), Fraction(1))
    assert isinstance(angle_direction(30)[0], float)


rationals = st.fractions(min_value=-50, max_value=50, max_denominator=12)


@settings(max_examples=200, deadline=None)
@given(rationals, rationals, rationals, st.integers(-4, 4))
def test_written_angles_have_the_direction_of_their_value(x, y, ratio, quarters):
    """'k pi/2 + atan2(y, x) - atan(r)' against the float angle it denotes."""
    if x == 0 and y == 0:
        return
    text = f"{quarters}*pi/2 + atan2({y}, {x}) - atan({ratio})"
    angle = quarters * math.pi / 2 + math.atan2(y, x) - math.atan(ratio)
    direction = angle_direction(text)
    assert all(isinstance(c, Fraction) for c in direction)
    length = math.hypot(*direction)
    assert math.isclose(direction[0] / length, math.cos(angle), abs_tol=1e-12)
    assert math.isclose(direction[1] / length, math.sin(angle), abs_tol=1e-12)


def _random_slider_scene(links: int, seed: int) -> tuple[dict, object]:
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict

    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(links)
    truss = trusses[int(rng.integers(len(trusses)))]
    data = slider_instance_dict(truss, random_slider_set(truss, rng), rng)
    return data, scene_from_dict(data)


@settings(max_examples=40, deadline=None)
@given(links=st.sampled_from([3, 5, 7]), seed=st.integers(0, 2**32 - 1))
def test_a_random_slider_chain_is_solved_with_its_generating_configuration(links, seed):
    """Issue 17's property: a random configuration of a random truss, a random admissible
    slider set with random axes (scene/slider_instances.py) → the numeric backend lists
    the generating configuration among its modes, and, where msolve is installed, exactly
    msolve's modes (the oracle on the Cartesian system, modelled independently)."""
    data, scene = _random_slider_scene(links, seed)
    _check_numeric_modes(data, scene)


@settings(max_examples=6, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_a_random_nine_link_slider_chain_is_solved_with_its_generating_configuration(seed):
    """The same property on the 28 nine-link trusses (coupling degrees 1 and 2)."""
    data, scene = _random_slider_scene(9, seed)
    _check_numeric_modes(data, scene)


def _check_numeric_modes(data: dict, scene) -> None:
    """The numeric modes hold the generating configuration and are msolve's; or the chain
    moves (an admissible slider set can lock a turn twice: 5 of the 386 seven-link chains)
    and its Cartesian Jacobian is rank-deficient at the generating configuration."""
    from baranov.solvers import MovableLinkageError
    from baranov.solvers.msolve import cartesian_jacobian_rank

    try:
        found = [mode.joints for mode in solve(scene).assembly_modes]
    except MovableLinkageError:
        rank, unknowns = cartesian_jacobian_rank(scene, data["generating_configuration"])
        assert rank < unknowns
        return
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    assert compare_modes(found, [generating])[0] == 0
    if find_msolve() is not None:
        assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)


def test_slider_parameters_are_named_t_and_reported_as_oriented_distances():
    """A plan parameter with a slider is t, the other joint's oriented distance to the
    axis (§4.2.4), of either sign; the backends search it through a map of (0, B²]."""
    scene = load_scene(EXAMPLES / "7-B3-slider-P1.json")
    solution = solve(scene)
    assert solution.parameters == ("t1,6",)
    for mode in solution.assembly_modes:  # the axis is the ground's x-axis through P1
        assert abs(mode.parameters["t1,6"] - (mode.joints["P6"][1] - mode.joints["P1'"][1])) < 1e-12


@pytest.mark.parametrize("example, variable, leading, roots", [
    # thesis §4.2.2: s^16 − 1088.1889 s^15 + 5.5629·10^5 s^14 …, real roots 49.5561, 50.1965, 50.6270, 85.0000
    ("7-B3-slider-P9", "s1,6", [1, -1088.1889, 5.5629e5, -1.7759e8], [49.5561, 50.1965, 50.6270, 85.0000]),
    # §4.2.3 (erratum alpha7 = pi - atan(4/5)): all 13 printed coefficients, real roots 48.1037, 85, 88.2, 88.5483
    ("7-B3-sliders-P8-P9", "s1,6", [1, -801.1113, 2.8716e5, -6.0970e7, 8.5621e9, -8.4211e11, 6.0004e13, -3.1645e15,
                                    1.2496e17, -3.6854e18, 7.8680e19, -1.1067e21, 7.7765e21],
     [48.1037, 85.0000, 88.2000, 88.5483]),
    # §4.2.4: t^18 − 99.9226 t^17 + 4616.5154 t^16 − 1.3111·10^5 t^15 …, real roots 7.4867, 8.7825
    ("7-B3-slider-P1", "t1,6", [1, -99.9226, 4616.5154, -1.3111e5], [7.4867, 8.7825]),
])
def test_the_exact_backend_derives_the_published_characteristic_polynomials(example, variable, leading, roots):
    """The slider constructions run over the exact radical tower (closure/homogeneous.py):
    the published degree, leading coefficients to the printed digits, certified roots, and
    every mode certified."""
    scene = load_scene(EXAMPLES / f"{example}.json")
    solution = solve(scene, method="exact")
    polynomial = solution.characteristic_polynomial
    assert polynomial.variable == variable and polynomial.degree == len(polynomial.monic_coefficients()) - 1
    assert polynomial.degree == {"7-B3-slider-P9": 16, "7-B3-sliders-P8-P9": 12, "7-B3-slider-P1": 18}[example]
    published = [float(f"{value:.5g}") for value in leading]
    derived = [float(coefficient) for coefficient in polynomial.monic_coefficients()[:len(leading)]]
    assert all(math.isclose(d, p, rel_tol=5e-5) for d, p in zip(derived, published, strict=True))
    assert [round(mode.parameters[variable], 4) for mode in solution.assembly_modes] == roots
    assert solution.certificate.complete


def test_axis_frames_rational_in_units_of_a_root_are_exact():
    """§4.2.3's second slider sits at 45° to the first: its frames are √2 times rational,
    so the exact method measures its heights in units of √2 (scene/sliders.py:
    axis_unit), and the turn between the two axes, e^{iπ/4}√2 = 1 + i, is rational."""
    from baranov.scene.sliders import axis_turn, axis_unit

    scene = load_scene(EXAMPLES / "7-B3-sliders-P8-P9.json")
    p9, p8 = (next(s for s in scene.sliders if s.joint == name) for name in ("P9", "P8"))
    assert axis_unit(p9, [scene.link_of(a.link) for a in p9.axes]) == 1
    assert axis_unit(p8, [scene.link_of(a.link) for a in p8.axes]) == 2
    assert axis_turn(p9, p8, scene.link_of("t789"), (1, 2)) == (1, 1)


def test_the_exact_backend_refuses_irrational_axis_frames_by_name():
    """A slider whose two links put its frames in different units (√2 on one, √5 on the
    other: no common unit makes both rational) is refused by name, not approximated."""
    data = json.loads((EXAMPLES / "7-B3-slider-P9.json").read_text())
    slider = data["sliders"][0]
    link = next(iter(slider["angles"]))
    joint = next(iter(slider["angles"][link]))
    slider["angles"][link][joint] = "pi/4"
    with pytest.raises(SolverError, match=r"slider P9: its axis frames are √58 times rational on link t569, "
                                          r"rational on link t789; the exact method needs them rational in one unit"):
        solve(scene_from_dict(data), method="exact")


@needs_msolve
@pytest.mark.parametrize("link, joint, angle", [("t569", "P5", "0"), ("t569", "P5", "pi"), ("t569", "P5", "pi/2"),
                                                ("t789", "P7", "0"), ("t789", "P7", "pi")])
def test_a_joint_on_the_axis_gives_msolves_modes(link, joint, angle):
    """A joint of a slider's link on its axis (oriented distance 0: angle 0 or π) or at a
    right angle to it: the numeric method finds exactly msolve's modes (4, 6, 2, 4, 6 of
    them); the exact method refuses by name, since √29 (the frame on t569 along P5) and
    the frame on t789 need different units."""
    data = json.loads((EXAMPLES / "7-B3-slider-P9.json").read_text())
    data["sliders"][0]["angles"][link] = {joint: angle}
    scene = scene_from_dict(data)
    expected = list(msolve_modes(scene).configurations)
    assert len(expected) >= 2
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert compare_modes(found, expected)[:2] == (0, 0)


@settings(max_examples=15, deadline=None)
@given(links=st.sampled_from([3, 5, 7]), seed=st.integers(0, 2**32 - 1))
def test_exact_and_numeric_modes_agree_on_random_slider_chains(links, seed):
    """Axes of rational length (Pythagorean directions) give rational axis frames: the
    exact backend lists the generating configuration and the numeric backend's modes."""
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
    from baranov.solvers import MovableLinkageError
    from baranov.solvers.coincidence import NoPlanError, solvable_plan
    from baranov.solvers.msolve import cartesian_jacobian_rank

    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(links)
    truss = trusses[int(rng.integers(len(trusses)))]
    data = slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True)
    scene = scene_from_dict(data)
    try:
        if solvable_plan(scene).number_of_parameters > 1:
            return  # coupling degree 2 takes ~15 s exactly: one case below
    except NoPlanError:
        return  # no plan the slider constructions run: msolve's modes, tested above
    try:
        exact = solve(scene, method="exact")
    except MovableLinkageError:  # a chain that moves (tests/test_slider_chains.py)
        rank, unknowns = cartesian_jacobian_rank(scene, data["generating_configuration"])
        assert rank < unknowns
        return
    found = [mode.joints for mode in exact.assembly_modes]
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    assert compare_modes(found, [generating])[0] == 0
    assert compare_modes(found, [mode.joints for mode in solve(scene).assembly_modes])[:2] == (0, 0)


@needs_msolve
def test_the_exact_backend_solves_a_coupling_two_slider_chain():
    """9/B28 (coupling degree 2) with a slider at P5: the exact method lifts the
    characteristic polynomial from its images modulo primes, as for the trusses (degree 58,
    the truss's generic count), and certifies exactly msolve's modes."""
    from baranov.literature.trusses import thesis_truss
    from baranov.scene.slider_instances import slider_instance_dict

    data = slider_instance_dict(thesis_truss("9/B28").chain(), ["P5"], np.random.default_rng(2), rational=True)
    scene = scene_from_dict(data)
    solution = solve(scene, method="exact")
    assert solution.coupling_degree == 2 and solution.characteristic_polynomial.degree == 58
    assert solution.certificate.complete
    found = [mode.joints for mode in solution.assembly_modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    assert compare_modes(found, [generating])[0] == 0


@needs_msolve
@pytest.mark.parametrize("turn", [0.0, 1e-9, 1e-6, 1e-3])
def test_nearly_parallel_axes_on_one_link_give_msolves_modes(turn):
    """§4.2.3's chain with P8's axis turned on t789 until it is parallel to P9's there (to
    the 15 decimals the scene gives), and 1e-9, 1e-6, 1e-3 rad from it: the link keeps
    its revolute joint P7, so the chain stays rigid (msolve: 2 modes), and the numeric
    method finds exactly those modes."""
    from baranov.scene.sliders import axis_turn

    data = json.loads((EXAMPLES / "7-B3-sliders-P8-P9.json").read_text())
    angle = math.pi + math.atan(0.5) + math.pi / 4 + turn  # +π/4 undoes the 45° between the axes
    data["sliders"][1]["angles"]["t789"] = {"P7": [repr(round(math.cos(angle), 15)), repr(round(math.sin(angle), 15))]}
    scene = scene_from_dict(data)
    p9, p8 = (next(s for s in scene.sliders if s.joint == name) for name in ("P9", "P8"))
    assert abs(float(axis_turn(p9, p8, scene.link_of("t789"))[1]) + math.sin(turn)) < 1e-12
    expected = list(msolve_modes(scene).configurations)
    assert len(expected) == 2
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert compare_modes(found, expected)[:2] == (0, 0)


@needs_msolve
def test_a_slider_mode_at_the_edge_of_an_along_axis_step_is_found():
    """tests/regressions/sliders/9-N28-mode-at-axis-edge.json (found by
    bench/bench_sliders.py): 9/N28 with sliders P3, P7, P8, coupling degree 2; msolve and
    the exact backend find 10 modes. The numeric backend found 9: the generating
    configuration sits where P11's along-axis step from P1 vanishes, the closure
    condition rises like a square root from that edge, and the polish on the link
    constraints that rescues such modes of the trusses knew no slider constraint. Now
    every constraint is polished (solvers/polish.py: polish_on_constraints) and the
    branch read back with the sign of each along-axis step: the mode comes out on branch
    (+1, +1, −1, −1), as the exact backend has it."""
    data = json.loads((Path(__file__).parent / "regressions" / "sliders" / "9-N28-mode-at-axis-edge.json").read_text())
    scene = scene_from_dict(data)
    modes = solve(scene).assembly_modes
    found = [mode.joints for mode in modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    assert compare_modes(found, [generating])[0] == 0
    edge = min(modes, key=lambda mode: mode.parameters["s1,11"])
    assert edge.signs == (1, 1, -1, -1) and abs(edge.parameters["s1,11"] - 1970.2864033818687) < 1e-8


@needs_msolve
def test_a_slider_chain_with_two_unbounded_parameters_is_solved():
    """tests/regressions/sliders/9-N2-slow-unbounded-parameters.json: both parameters have
    no bound of link dimensions; the branch-and-prune searches them out to UNBOUNDED_REACH
    and the sampling searches, through tangent maps, the branches it leaves undecided; the
    numeric method finds msolve's 6 modes (in about 4 s; it took a minute by the searches
    alone)."""
    data = json.loads((Path(__file__).parent / "regressions" / "sliders" /
                       "9-N2-slow-unbounded-parameters.json").read_text())
    scene = scene_from_dict(data)
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)


ROBOT_REGRESSIONS = sorted((Path(__file__).parent / "regressions" / "sliders").glob("robot-*.json"))


@pytest.mark.parametrize("path", ROBOT_REGRESSIONS, ids=lambda p: p.stem)
def test_degenerate_slider_plans_fall_back_to_msolve(path):
    """Issue 18's random robots with small integer coordinates, locked: two joints of a
    slider's link at one point, or two parallel axes fixed in one link, make the slider
    plan divide by 0 (the exact backend raised ZeroDivisionError, the numeric one lost
    modes in rounding noise); the plan's probe now says so and both backends list
    msolve's modes, mode for mode."""
    if find_msolve() is None:
        pytest.skip("msolve binary not installed (make installs it)")
    scene = load_scene(path)
    oracle = list(msolve_modes(scene).configurations)
    assert oracle
    for method in ("numeric", "exact"):
        found = [mode.joints for mode in solve(scene, method=method).assembly_modes]
        assert compare_modes(found, oracle) == (0, 0, 0), method


ISSUE_55 = Path(__file__).parent / "regressions" / "sliders" / "issue-55-ground-by-squared-length.json"


def test_a_slider_plan_whose_range_falls_between_probes_is_defined():
    """Issue 55: the real range of t1,9 is [-44.3, -41.7], between two of the probe's
    samples 5.1 apart; no triangle of the plan can be built at any sample, which says
    nothing of a division by 0: the plan is defined (it was declared undefined, and the
    modes left to msolve)."""
    from baranov.planner import slider_plan
    from baranov.solvers.coincidence import slider_plan_undefined

    scene = load_scene(ISSUE_55)
    plan = slider_plan(scene.chain, [slider.joint for slider in scene.sliders])
    assert slider_plan_undefined(scene, plan) is None


@needs_msolve
@pytest.mark.parametrize("method", ["numeric", "exact", "msolve"])
def test_a_slider_on_a_ground_given_by_squared_length_keeps_its_modes(method):
    """Issue 55: sliders P1, P7 of a 7/N3 chain, the ground P1P2 by its squared length
    1097 (irrational length), drawn around a configuration at t1,9 = -43.2: both real
    modes in every method, by the plan in the numeric and exact backends (no msolve
    note), the exact one certified; each the mode msolve finds with the ground placed by
    its distances (an auxiliary root for its length: rounded coordinates made the
    slider's equations inconsistent and msolve found none)."""
    scene = load_scene(ISSUE_55)
    solution = solve(scene, method=method)
    assert [round(mode.parameters["t1,9"], 6) for mode in solution.assembly_modes] == [-43.2, -41.978762]
    assert not solution.undecided
    oracle = list(msolve_modes(scene).configurations)
    assert compare_modes([mode.joints for mode in solution.assembly_modes], oracle) == (0, 0, 0)
    if method == "exact":
        assert solution.certificate.complete and solution.certificate.probabilistic is None


def _no_plan_slider_chain(by_length: bool = False):
    """9/N1 with sliders P1, P2, P11, P12, which no slider plan suits (the catalog: 4
    modes, by msolve), drawn around a configuration; ``by_length``: its ground written by
    its squared length (irrational length)."""
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import slider_instance_dict

    data = slider_instance_dict(baranov_trusses(9)[0], ["P1", "P2", "P11", "P12"], np.random.default_rng(6),
                                rational=True)
    data.pop("generating_configuration")
    if by_length:
        ground = next(link for link in data["links"] if link["name"] == data["ground"])
        (u, p), (v, q) = ground["joints"].items()
        ground.pop("joints")
        ground.update(joints=[u, v], squared_length=(p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2)
    return scene_from_dict(data)


def _without_plans_of_two_parameters(monkeypatch) -> None:
    """The exact backend as where no plan of two parameters certifies either: msolve's
    route (this chain has a plan of two, by which it is solved otherwise)."""
    from baranov.solvers.exact import backend

    monkeypatch.setattr(backend, "by_one_more_parameter", lambda scene: None)


@needs_msolve
def test_msolves_list_without_a_plan_is_certified_by_its_count(monkeypatch):
    """Issue 55: where no plan is defined the modes are msolve's; the exact backend
    certifies them only when msolve's count of complex solutions is the chain's generic
    count (the model lost none), as on this generic instance."""
    _without_plans_of_two_parameters(monkeypatch)
    solution = solve(_no_plan_slider_chain(), method="exact")
    assert len(solution.assembly_modes) == 4 and solution.certificate.complete
    assert "has 4 complex solutions, the chain's generic count" in solution.certificate.probabilistic


@needs_msolve
def test_a_model_that_loses_solutions_gives_no_certificate(monkeypatch):
    """Issue 55's fault brought back on purpose — the ground, given by an irrational
    length, placed at rounded coordinates in msolve's model — loses solutions, and the
    count says so: no certificate (it had printed "certified complete" over no mode)."""
    import baranov.solvers.msolve as msolve

    _without_plans_of_two_parameters(monkeypatch)
    scene = _no_plan_slider_chain(by_length=True)
    assert not msolve.exact_ground(scene)
    faithful = msolve.cartesian_system
    monkeypatch.setattr(msolve, "cartesian_system",
                        lambda scene, *args, **kwargs: faithful(scene, *args, rounded_ground=True))
    solution = solve(scene, method="exact")
    assert not solution.certificate.complete
    assert "where a generic instance of the chain has" in solution.certificate.gaps[0]


def test_a_degenerate_instance_without_a_plan_is_not_certified():
    """9/N12 drawn with P1 and P9 at one point: no plan is defined; msolve's 4 modes are
    verified, but its system has 12 complex solutions where the chain generically has 44:
    not certified complete."""
    if find_msolve() is None:
        pytest.skip("msolve binary not installed (make installs it)")
    solution = solve(load_scene(Path(__file__).parent / "regressions" / "9-N12-no-plan-coincident-input.json"),
                     method="exact")
    assert len(solution.assembly_modes) == 4 and not solution.certificate.complete
    assert "12 complex solutions where a generic instance of the chain has 44" in solution.certificate.gaps[0]


@needs_msolve
def test_msolve_places_an_irrational_ground_exactly():
    """The 5/B1 example's ground P1P2P3 is given by distances whose frame is irrational:
    msolve's model places it by those distances (an auxiliary root, kept positive) rather
    than in rounded coordinates, and finds the numeric backend's 6 modes, mode for mode."""
    from baranov.solvers.msolve import cartesian_system, exact_ground

    scene = load_scene(EXAMPLES / "5-B1.json")
    assert not exact_ground(scene)
    assert cartesian_system(scene)[3]  # the ground's length is an auxiliary root
    oracle = msolve_modes(scene)
    found = [mode.joints for mode in solve(scene).assembly_modes]
    assert len(found) == 6 and compare_modes(found, list(oracle.configurations)) == (0, 0, 0)


@needs_msolve
@pytest.mark.parametrize(("truss", "sliders", "seed"), [
    ("5/N1", ["P1", "P3", "P5"], 0),              # the pentad with a ternary link all sliders (a robot's platform)
    ("5/N1", ["P1", "P2", "P3", "P5"], 1),
    ("7/N1", ["P3", "P5", "P9"], 2),
    ("7/N3", ["P1", "P4", "P7", "P8"], 3),
])
def test_a_link_whose_joints_are_all_sliders_is_placed_by_its_two_axes(truss, sliders, seed):
    """Thesis §5.2.1.3: where every joint of a ternary link is a slider, the plan locates
    its third axis from the other two (closure/sliders.py: third_axis), so these chains,
    solved by msolve before, run the bilateration method: both backends give msolve's
    modes and the generating configuration, with no fallback note, and the exact one
    certifies them."""
    from baranov.planner.plan import StepKind

    chain, plan = _slider_chain_plan(truss, sliders)
    assert any(set(step.triangle) <= set(sliders) and step.kind is StepKind.LINK for step in plan.steps)
    _check_plan_against_msolve(chain, sliders, seed)


@needs_msolve
@pytest.mark.parametrize(("truss", "sliders", "seed", "modes"), [
    ("7/N3", ["P5", "P6"], 4, 6),
    ("7/N2", ["P1", "P2", "P5", "P6", "P7"], 5, 2),
    ("7/N3", ["P5", "P6", "P8"], 6, 4),
])
def test_a_closure_between_two_sliders_compares_the_turn_of_their_axes(truss, sliders, seed, modes):
    """A closure pair of two sliders of one link: the turn between their placed axes
    against the link's (closure/sliders.py: turn_mismatch). sin θ = 0 holds with the
    second axis reversed too; the numeric verification drops those modes, and the exact
    factor test, on r − 1, drops the reversed linkage's factors: the characteristic
    polynomial has the chain's generic degree (the catalog's count), where the norm of
    sin θ has twice as many roots (solvers/mode_counts.py: slider_chain_degree)."""
    chain, plan = _slider_chain_plan(truss, sliders)
    assert any(set(pair) <= set(sliders) for pair in plan.closure_pairs)
    solution = _check_plan_against_msolve(chain, sliders, seed)
    assert solution.characteristic_polynomial.degree == modes


def _slider_chain_plan(truss: str, sliders: list[str]):
    from baranov.catalog.lookup import truss as catalog_truss
    from baranov.planner import slider_plan

    chain = catalog_truss(truss)
    return chain, slider_plan(chain, sliders)


def _check_plan_against_msolve(chain, sliders: list[str], seed: int):
    """Both backends on a random rational instance: msolve's modes and the generating
    configuration, no msolve fallback, the exact list certified; the exact solution."""
    from baranov.scene.slider_instances import slider_instance_dict

    data = slider_instance_dict(chain, sliders, np.random.default_rng(seed), rational=True)
    scene = scene_from_dict(data)
    oracle = list(msolve_modes(scene).configurations)
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    for method in ("numeric", "exact"):
        solution = solve(scene, method=method)
        assert not any("msolve" in sentence for sentence in solution.undecided), method
        assert "msolve" not in str(solution.certificate), method  # no fallback to msolve's list
        found = [mode.joints for mode in solution.assembly_modes]
        assert compare_modes(found, oracle)[:2] == (0, 0), method
        assert compare_modes(found, [generating])[0] == 0, method
    assert solution.certificate.complete
    return solution


ADVERSARIAL_SLIDER_CHAINS = sorted((Path(__file__).parent / "regressions" / "sliders").glob("adversarial-*.json"))


@needs_msolve
@pytest.mark.parametrize("path", ADVERSARIAL_SLIDER_CHAINS, ids=lambda p: p.stem)
def test_adversarial_slider_chains_give_msolves_modes(path):
    """Slider chains drawn as issue 25's adversarial instances (small boxes, joints in
    line or at one point, modes at a domain edge) that a backend once got wrong: both
    give msolve's modes, mode for mode, and the generating configuration, the exact list
    certified; a chain that moves is said to (numeric) or left uncertified (exact)."""
    from baranov.solvers import MovableLinkageError

    data = json.loads(path.read_text())
    scene = scene_from_dict({key: value for key, value in data.items() if key != "comment"})
    result = msolve_modes(scene)
    if result.status == "infinite":  # the chain moves: said, or left uncertified
        with pytest.raises(MovableLinkageError):
            solve(scene)
        assert not solve(scene, method="exact").certificate.complete
        return
    oracle = list(result.configurations)
    generating = {name: tuple(map(float, point)) for name, point in data["generating_configuration"].items()}
    for method in ("numeric", "exact"):
        solution = solve(scene, method=method)
        found = [mode.joints for mode in solution.assembly_modes]
        assert compare_modes(found, oracle)[:2] == (0, 0), method
        assert compare_modes(found, [generating])[0] == 0, method
    assert solution.certificate.complete, solution.certificate.gaps


@needs_msolve
@pytest.mark.parametrize("truss_index, sliders", [(27, ("P1", "P2", "P7", "P8", "P11")),
                                                  (17, ("P1", "P2", "P4", "P5", "P6", "P10", "P11"))])
def test_a_negative_second_slider_parameter_keeps_its_modes(truss_index, sliders):
    """9/B28 (9/N28) with sliders P1, P2, P7, P8, P11: the plan's second parameter t10,1
    is an oriented distance, negative in all four modes; the exact backend kept only
    positive second parameters and certified 0 modes (2026-11-26). Now its modes are
    msolve's, mode for mode, as the numeric backend's configurations are; and 9/B26
    (9/N18) with seven sliders, whose modes have it of both signs."""
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import slider_instance_dict

    truss = baranov_trusses(9)[truss_index]
    scene = scene_from_dict(slider_instance_dict(truss, list(sliders), np.random.default_rng(1), rational=True))
    expected = list(msolve_modes(scene).configurations)
    assert expected
    parameters = {}
    for method in ("exact", "numeric"):
        solution = solve(scene, method=method)
        assert compare_modes([mode.joints for mode in solution.assembly_modes], expected)[:2] == (0, 0), method
        parameters[method] = sorted(tuple(mode.parameters.values()) for mode in solution.assembly_modes)
    # the numeric backend read t back from polished configurations and mapped it as if
    # searched: NaN or a wrong value (t10,8 = -43.7 for 20)
    assert np.allclose(parameters["numeric"], parameters["exact"], rtol=1e-7, atol=1e-9)


def test_a_search_whose_suspect_cells_explode_stops_and_says_so(monkeypatch):
    """9/B27 (9/N27) with sliders P1, P2, P3, P7, P8, P11 (plan parameters t10,1 and
    t1,5, which no path of link dimensions bounds): every cell of the sampling search's
    second level stays suspect, and the third level asked for about 24 million points
    (23 GB: the process was killed). A level is now refined only up to MOST_CELLS cells;
    the rest is reported undecided, and the four modes are found (msolve's, on this
    instance). The interval branch-and-prune, out to UNBOUNDED_REACH, now decides every box
    and finds them without the searches; it is switched off to test the searches."""
    import baranov.solvers.numeric.backend as backend
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import slider_instance_dict
    from baranov.solvers.modes import Certificate

    truss = baranov_trusses(9)[26]
    scene = scene_from_dict(slider_instance_dict(truss, ["P1", "P2", "P3", "P7", "P8", "P11"],
                                                 np.random.default_rng(0), rational=True))
    pruned = solve(scene, method="numeric")
    assert len(pruned.assembly_modes) == 4 and not pruned.undecided
    assert pruned.certificate.gaps == (pruned.certificate.gaps[-1],)
    assert pruned.certificate.gaps[-1].startswith("no path of link dimensions bounds t10,1, t1,5")
    monkeypatch.setattr(backend, "_certified", lambda scene, plan, compiled, branches, deadline: (
        (), Certificate(False, None, ("switched off",)), branches))
    solution = solve(scene, method="numeric")
    assert [mode.joints for mode in solution.assembly_modes] and compare_modes(
        [mode.joints for mode in solution.assembly_modes], [mode.joints for mode in pruned.assembly_modes]) == (0, 0, 0)
    assert solution.undecided and all("suspect cells at one level" in sentence for sentence in solution.undecided)


SLIDER_REGRESSIONS = Path(__file__).resolve().parent / "regressions" / "sliders"


@needs_msolve
@pytest.mark.parametrize("name, method", [
    pytest.param("9-N27-eight-sliders-extraneous-factor", "exact", marks=pytest.mark.xfail(
        strict=True, reason="open (2026-11-26): the exact backend drops the factor 25 t - 636 as extraneous and "
        "reports a gap (not a certificate); its one mode has t11,8 = -0.4 (docs/sliders.md)")),
    pytest.param("9-N28-seven-sliders-near-duplicates", "numeric", marks=[pytest.mark.slow, pytest.mark.xfail(
        strict=True, reason="open (2026-11-26): six near-duplicates of one ill-conditioned mode "
        "(s10,11 = 2041605) are listed as modes (docs/sliders.md)")]),
])
def test_saved_slider_instances_have_msolves_modes(name, method):
    scene = load_scene(SLIDER_REGRESSIONS / f"{name}.json")
    solution = solve(scene, method=method)
    expected = list(msolve_modes(scene).configurations)
    assert compare_modes([mode.joints for mode in solution.assembly_modes], expected)[:2] == (0, 0)


@needs_msolve
@pytest.mark.slow  # 110 s (2026-11-28)
@pytest.mark.parametrize("truss_index, sliders, seed", [(27, ("P5", "P6", "P7"), 260),
                                                        (26, ("P1", "P2", "P5", "P6", "P7"), 150)])
def test_slider_curves_are_judged_at_real_points(truss_index, sliders, seed):
    """A slider construction conjugates, so its residuals vanish at real points only: at
    the complex points of a genuine curve every branch looked ruled out, the curves of
    one condition were all dropped and the exact backend answered with a gap and no mode
    (9/B28 with sliders P5, P6, P7; 9/B27 with P1, P2, P5, P6, P7; 17 of the 18 such
    instances of the 261-chain sample). Now complex points rule nothing out there, a
    factor is tested at a real root, and both are certified with msolve's modes."""
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import slider_instance_dict

    truss = baranov_trusses(9)[truss_index]
    scene = scene_from_dict(slider_instance_dict(truss, list(sliders), np.random.default_rng(seed), rational=True))
    solution = solve(scene, method="exact")
    assert solution.certificate.complete
    expected = list(msolve_modes(scene).configurations)
    assert expected and compare_modes([mode.joints for mode in solution.assembly_modes], expected)[:2] == (0, 0)


@needs_msolve
@settings(max_examples=16, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_a_certified_slider_chain_has_exactly_msolves_modes(seed):
    """Slider chains through the interval branch-and-prune (issue 56 item 7): a random
    slider chain of a 7- or 9-link truss with rational axes, coupling 1 — where the
    numeric backend certifies its list complete, the list is msolve's, mode for mode."""
    from baranov.enumerate import baranov_trusses
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict

    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(7 if seed % 2 else 9)
    truss = trusses[int(rng.integers(len(trusses)))]
    scene = scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True))
    try:
        solution = solve(scene)
    except SolverError:
        return
    if solution.certificate is None or not solution.certificate.complete:
        return
    found = [mode.joints for mode in solution.assembly_modes]
    assert compare_modes(found, list(msolve_modes(scene).configurations))[:2] == (0, 0)


@pytest.mark.parametrize("example, parameter", [("7-B3-slider-P9", "s1,6"), ("7-B3-slider-P1", "t1,6")])
def test_published_slider_chains_are_certified(example, parameter):
    """Thesis §4.2.2 and §4.2.4: a slider chain whose parameter is a squared distance, and
    one whose parameter is a slider's oriented distance t (searched in |t| ≤ the shortest
    path of link dimensions to the slider's nearer point), certified complete by the
    interval branch-and-prune, with the published modes."""
    solution = solve(load_scene(EXAMPLES / f"{example}.json"))
    assert solution.certificate.complete and f"branch-and-prune of {parameter}" in solution.certificate.proof


def test_two_parallel_slider_axes_give_no_numpy_warning():
    """tests/regressions/sliders/open/robot-RrR-rPP-pPR.json, a locked robot that moves
    (msolve: a positive-dimensional solution set): where two slider axes the plan crosses
    are parallel, the point where they meet is ∞ or NaN and no mode, and numpy's
    divide-by-zero and invalid-value warnings reached the command line's stderr. The
    solve says nothing is proven and warns of nothing."""
    import warnings

    from baranov.solvers.numeric import solve_numeric

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        solution = solve_numeric(load_scene(SLIDER_REGRESSIONS / "open" / "robot-RrR-rPP-pPR.json"))
    assert not solution.certificate.complete


@pytest.mark.parametrize("method", ["numeric", "exact"])
def test_a_link_sliding_on_parallel_axes_is_reported_as_a_motion(method):
    """The same robot: its leg25 carries two sliders P2 and P5 whose axes are parallel on
    it (both at the angle (−24, 12) from the other joint), so the leg slides along them
    and the robot moves wherever it assembles (msolve: a positive-dimensional solution
    set). Both backends used to answer "no mode found, not proven" (the exact one: two
    real roots undecided at 1024 bits, where the leg's point on the two axes is
    undefined); solve now says the linkage moves and which link slides. A turned leg
    (P5's axis at another angle) is solved as before."""
    from baranov.scene.sliders import sliding_link
    from baranov.solvers import MovableLinkageError

    path = SLIDER_REGRESSIONS / "open" / "robot-RrR-rPP-pPR.json"
    assert sliding_link(load_scene(path)) == ("leg25", ("P2", "P5"))
    with pytest.raises(MovableLinkageError, match="link leg25: its joints P2 and P5 .* parallel"):
        solve(load_scene(path), method=method)
    data = json.loads(path.read_text())
    data["sliders"][1]["angles"]["leg25"]["P2"] = ["-12", "24"]
    assert sliding_link(scene_from_dict(data)) is None


@needs_msolve
def test_a_chain_no_one_parameter_plan_suits_is_solved_by_a_plan_of_two():
    """9/N24 with seven sliders: none of the 300 best one-parameter plans suits them (both
    backends used to hand such chains, 3095 of the nine-link catalog's, to msolve); the
    exact backend solves it by the best plan of two parameters, certified, with msolve's
    modes."""
    from baranov.planner import SliderPlanError, slider_plan
    from baranov.solvers.coincidence import NoPlanError, solvable_plan
    from baranov.solvers.exact.backend import solve_exact

    scene = load_scene(Path(__file__).parent / "scenes" / "9-slider-chain-no-one-parameter-plan.json")
    sliders = [slider.joint for slider in scene.sliders]
    with pytest.raises(SliderPlanError):
        slider_plan(scene.chain, sliders)
    assert slider_plan(scene.chain, sliders, extra_parameters=1).number_of_parameters == 2
    with pytest.raises(NoPlanError):
        solvable_plan(scene)
    exact = solve_exact(scene)
    assert exact.coupling_degree == 2 and exact.certificate.complete
    reference = msolve_modes(scene)
    assert reference.status == "finite" and len(reference.configurations) == len(exact.assembly_modes) == 2
    assert compare_modes([mode.joints for mode in exact.assembly_modes], list(reference.configurations))[:2] == (0, 0)
