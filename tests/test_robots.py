"""Fully-parallel planar robots (issue 18, first part): legs, the 1653 robots and their
ten families, every count computed and compared with thesis §5.2 (Tables 5.2-5.3)."""

import re
from collections import Counter
from fractions import Fraction

import flint
import pytest

from baranov.cli.main import main
from baranov.literature.robots import THESIS_ROBOT_FAMILIES, THESIS_ROBOTS
from baranov.robots import LEGS, Leg, RobotInputError, all_robots, parse_robot, robot_families, robot_family
from baranov.robots.families import locked_sliders

REPO = __import__("pathlib").Path(__file__).resolve().parents[1]


def test_the_21_legs_by_architecture():
    """Table 5.2: 6 legs of each of the RR, RP and PR architectures, 3 PP."""
    assert len(LEGS) == len(set(LEGS)) == 21
    assert Counter(leg.passive for leg in LEGS) == {"RR": 6, "RP": 6, "PR": 6, "PP": 3}
    assert all(Leg.parse(str(leg)) == leg for leg in LEGS)


def test_the_1653_robots():
    robots = all_robots()
    without = sum(all(leg.passive != "PP" for leg in legs) for legs in robots)
    assert (without, len(robots) - without, len(robots)) == THESIS_ROBOTS
    assert len(set(robots)) == len(robots)


def test_the_ten_families_match_table_5_3():
    """Robots per family (from the enumeration) and generic assembly modes (the locked
    slider chain's characteristic degree), family names by their leg architectures."""
    families = robot_families()
    assert [f.name for f in families] == list(THESIS_ROBOT_FAMILIES)
    for family in families:
        printed, robots, modes = THESIS_ROBOT_FAMILIES[family.name]
        assert (family.robots, family.assembly_modes) == (robots, modes), family
        assert set(family.architectures) == {"-".join(sorted(a.split("-"))) for a in printed}
    assert sum(f.robots for f in families) == 1653


def test_family_does_not_depend_on_leg_order_or_on_swapping_base_and_platform():
    assert robot_family(parse_robot("RpR-rRP-RpR")).name == robot_family(parse_robot("RpR-RpR-rRP")).name == "II"
    # rRP locks to RP (prismatic at the platform), PrR to PR (at the base): one family
    assert robot_family(parse_robot("rRP-RpR-RpR")) == robot_family(parse_robot("PrR-RpR-RpR"))
    assert locked_sliders(parse_robot("rPP-RpR-RpR")) == ("P1", "P2")  # both ends of the PP leg


@pytest.mark.parametrize(("text", "message"), [
    ("RpR-RpR", "three legs joined by hyphens"),
    ("RpR-RpR-RPR", "the actuated one in lower case"),
    ("RpR-RpR-RxR", "three joints R or P"),
    ("pPP-RpR-RpR", "not one of RRR"),
    ("rPP-rPP-RpR", "at most one leg with two passive prismatic joints"),
])
def test_bad_robot_strings(text, message):
    with pytest.raises(RobotInputError, match=message):
        parse_robot(text)


def test_robots_command(capsys):
    assert main(["robots"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("1653 fully-parallel planar robots (1140 without a PP leg)")
    assert "| VIII | P1, P3, P5 | PR-PR-PR, RP-RP-RP | 112 | 2 | 112 robots, 2 modes |" in out


# --- forward kinematics (family I: every leg locks to an RR link) ---------------------

import math  # noqa: E402

import numpy as np  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from baranov.robots import LegGeometry, Robot, forward_kinematics, locked_scene  # noqa: E402
from baranov.scene import load_scene  # noqa: E402
from baranov.solvers import solve  # noqa: E402
from baranov.solvers.msolve import compare_modes, find_msolve  # noqa: E402

RR_LEGS = [leg for leg in LEGS if leg.passive == "RR"]


def _rotated(point, angle):
    c, s = math.cos(angle), math.sin(angle)
    return c * point[0] - s * point[1], s * point[0] + c * point[1]


def _leg_at_pose(leg, rng, position, angle):
    """A random geometry of ``leg`` and the actuator value that puts the platform at the
    pose (position, angle): drawn from a configuration, so the pose is one of its modes."""
    base, platform = tuple(rng.uniform(-5, 5, 2)), tuple(rng.uniform(-2, 2, 2))
    world = np.add(position, _rotated(platform, angle))
    middle = rng.uniform(-5, 5, 2)  # the leg's middle joint, where it has one
    l1, l2 = float(np.linalg.norm(middle - base)), float(np.linalg.norm(world - middle))
    kind = str(leg)
    if kind == "RpR":
        return LegGeometry(base, platform), float(np.linalg.norm(world - base))
    if kind == "rRR":
        return LegGeometry(base, platform, (l1, l2)), math.atan2(*(middle - base)[::-1])
    if kind == "RrR":
        a, b = base - middle, world - middle
        return LegGeometry(base, platform, (l1, l2)), math.atan2(abs(a[0] * b[1] - a[1] * b[0]), a @ b)
    if kind == "RRr":
        local = _rotated(middle - world, -angle)
        return LegGeometry(base, platform, (l1, l2)), math.atan2(local[1], local[0])
    axis = rng.normal(size=2)
    axis = tuple(axis / np.linalg.norm(axis))
    offset = float(rng.uniform(-3, 3))
    if kind == "pRR":
        joint = np.add(base, np.multiply(offset, axis))
        return LegGeometry(base, platform, (float(np.linalg.norm(world - joint)),), axis), offset
    origin = tuple(np.subtract(platform, np.multiply(offset, axis)))  # RRp: the platform joint at origin + d·axis
    return LegGeometry(base, origin, (float(np.linalg.norm(world - base)),), axis), offset


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.lists(st.sampled_from(RR_LEGS), min_size=3, max_size=3))
def test_a_pose_is_found_again_from_its_actuator_values(seed, legs):
    """Random geometry drawn around a random pose, its actuator values, forward
    kinematics: the pose is among the results (both backends where the dimensions are
    exact would need rational angles; the numeric backend here)."""
    rng = np.random.default_rng(seed)
    position, angle = tuple(rng.uniform(-3, 3, 2)), float(rng.uniform(-math.pi, math.pi))
    drawn = [_leg_at_pose(leg, rng, position, angle) for leg in legs]
    robot = Robot(tuple(legs), tuple(geometry for geometry, _ in drawn))
    poses = forward_kinematics(robot, [value for _, value in drawn])
    assert any(math.dist(p.position, position) < 1e-6 and abs(math.remainder(p.angle - angle, 2 * math.pi)) < 1e-6
               for p in poses), (position, angle, [(p.position, p.angle) for p in poses])


def test_the_3rpr_examples_through_the_robot_api():
    """Thesis §5.1.3, example I: the robot API builds the scene examples/3-RPR-I.json
    holds (base placed at (0, 0), (4, 0), (1, 8)) and finds the same mode."""
    legs = tuple(Leg.parse("RpR") for _ in range(3))
    geometry = tuple(LegGeometry(a, b) for a, b in [((0, 0), (0, 0)), ((4, 0), (6, 0)), ((1, 8), (3, 4))])
    scene = locked_scene(Robot(legs, geometry), [1, 11, 13])
    example = load_scene(REPO / "examples" / "3-RPR-I.json")
    assert scene.known == example.known
    for method in ("numeric", "exact"):
        found = [mode.joints for mode in solve(scene, method=method).assembly_modes]
        assert compare_modes(found, [{"P1": (0, 0), "P2": (4, 0), "P3": (1, 8), "P4": (-1, 0), "P5": (-7, 0),
                                      "P6": (-4, -4)}]) == (0, 0, 0), method


SQRT3, SQRT10 = math.sqrt(3), math.sqrt(10)
#: Thesis §5.1.3's six 3-RPR examples as robots: base and platform points (placed to give
#: examples/3-RPR-*.json's squared distances and orientations) and the leg lengths.
THESIS_3RPR = {
    "I": ([(0, 0), (4, 0), (1, 8)], [(0, 0), (6, 0), (3, 4)], [1, 11, 13]),
    "II": ([(0, 0), (4, 0), (0, 3)], [(0, 0), (4, 0), (2, 3)], [4, 4, 2]),
    "III": ([(0, 0), (5, 0), (0, 0)], [(0, 0), (1, 3), (3, 1)], [SQRT10, 5, 6]),
    "IV": ([(0, 0), (1, 0), (2, 0)], [(0, 0), (3, 0), (2, 0)], [1, 2, 2]),
    "V": ([(0, 0), (40, 0), (10 * SQRT3, 10)], [(0, 0), (20, 0), (5 * SQRT3, 5)], [2, 44, 21]),
    "VI": ([(0, 0), (1, 0), (0, 1)], [(0, 0), (1, 0), (0, -1)], [2, "1/2", 1]),
}


@pytest.mark.parametrize("name", THESIS_3RPR)
def test_the_six_3rpr_examples_through_the_robot_api(name):
    """Thesis §5.1.3's examples I-VI built as robots lock to the scenes of
    examples/3-RPR-*.json (the same squared distances, exactly where the example's are
    exact) and give the same modes (parameter values and signs) by both backends (the
    numeric one only where a leg length is irrational: III, V)."""
    base, platform, lengths = THESIS_3RPR[name]
    legs = tuple(Leg.parse("RpR") for _ in range(3))
    robot = Robot(legs, tuple(LegGeometry(b, p) for b, p in zip(base, platform, strict=True)))
    scene, example = locked_scene(robot, lengths), load_scene(REPO / "examples" / f"3-RPR-{name}.json")
    assert scene.known.keys() == example.known.keys()
    assert all(abs(float(scene.known[pair]) - float(value)) < 1e-9 * (1 + float(value))
               for pair, value in example.known.items())
    assert scene.known == example.known or not scene.exact
    for method in ("numeric", "exact") if scene.exact and example.exact else ("numeric",):
        ours, theirs = (sorted((tuple(round(v, 6) for v in m.parameters.values()), m.signs)
                               for m in solve(s, method=method).assembly_modes) for s in (scene, example))
        assert ours == theirs and ours, method


def test_forward_kinematics_bad_input():
    geometry = tuple(LegGeometry((0, 0), (0, 0)) for _ in range(3))
    with pytest.raises(RobotInputError, match="three values, one per leg"):
        forward_kinematics(Robot(tuple(Leg.parse("RpR") for _ in range(3)), geometry), [1, 2])
    with pytest.raises(RobotInputError, match="actuator: 'long' is not a number"):
        forward_kinematics(Robot(tuple(Leg.parse("RpR") for _ in range(3)), geometry), [1, 2, "long"])


def test_robot_command(capsys, tmp_path):
    """`baranov robot FILE`: the file's actuators or --actuators, both backends agree;
    bad input is one line and exit code 2."""
    example = str(REPO / "examples" / "robot-I-3RPR.json")
    assert main(["robot", example]) == 0
    assert "robot RpR-RpR-RpR, family I, 1 pose (numeric)\npose   x  y  angle (degrees)  s1,5\n   1  -1  0 " in \
        capsys.readouterr().out  # aligned, and -4.4e-16 printed as 0 (issue 57)
    lines = {}
    for method in ("numeric", "exact"):
        assert main(["robot", example, "--actuators", "2,11,13", "--method", method]) == 0
        out = capsys.readouterr().out.splitlines()
        lines[method] = [line.split()[1:] for line in out[out.index(next(x for x in out if x.startswith("pose"))) + 1:]]
    assert len(lines["exact"]) == 2
    assert [[round(float(v), 6) for v in row] for row in lines["numeric"]] == \
           [[round(float(v), 6) for v in row] for row in lines["exact"]]
    assert main(["robot", example, "--actuators", "2,11,13", "--plot", str(tmp_path / "poses.png")]) == 0
    assert (tmp_path / "poses.png").read_bytes().startswith(b"\x89PNG")
    capsys.readouterr()
    assert main(["robot", str(REPO / "examples" / "robot-II-RPP-RPR-RPR.json"), "--method", "msolve"]) == 0
    assert "robot RpP-RpR-RpR, family II, 4 poses (msolve)" in capsys.readouterr().out
    assert main(["robot", str(REPO / "examples" / "robot-IV-RPP-RPP-RPR.json"), "--parameter", "P1,P6"]) == 0
    assert re.search(r"pose +x +y +angle \(degrees\) +t1,6\n", capsys.readouterr().out)
    for bad, message in [("P1", "--parameter P1: two joints, e.g. P2,P3"), ("P1,P9", "joint P9: no such joint")]:
        assert main(["robot", example, "--parameter", bad]) == 2
        assert message in capsys.readouterr().err
    assert main(["robot", example, "--actuators", "1,1,1"]) == 0
    assert capsys.readouterr().out.endswith("0 poses (numeric)\nno pose: the legs cannot all reach the platform with "
                                            "these actuator values (the locked robot has no real assembly mode)\n")
    assert main(["robot", example, "--actuators", "1,x,2"]) == 2
    assert capsys.readouterr().err == "baranov: error: actuator: 'x' is not a number\n"


@pytest.mark.parametrize("method", ["numeric", "exact", "msolve"])
@pytest.mark.parametrize("name", sorted(path.name for path in (REPO / "examples").glob("robot-*.json")))
def test_robot_command_on_every_example(name, method, capsys):
    """Every example robot through `baranov robot` by every method: the same poses, each
    row's parameter under the header's name (3-RPP, where msolve lists the modes: the
    header said s1,5 above modes in t1,5, and the command failed with a KeyError)."""
    if method == "msolve" and find_msolve() is None:
        pytest.skip("msolve binary not installed")
    assert main(["robot", str(REPO / "examples" / name), "--method", method]) == 0
    out = capsys.readouterr().out.splitlines()
    family = name.split("-")[1]
    assert f"family {family}," in out[0]
    if method == "exact":  # the characteristic polynomial, degree and monic form (issue 57)
        assert out[1].startswith("characteristic polynomial in ") and out[2].startswith("  monic: ")
        out = out[:1] + out[3:]
    parameter = out[1].split()[-1]
    # t1,6: the exact method's plan for 3-RPP, whose t1,5 is in units of √13 (exact_plan)
    assert parameter in {"s1,5", "t1,5", "t1,6"} and len(out) - 2 == int(out[0].split(", ")[2].split()[0])


def test_example_vi_is_analytic_its_sextic_solvable():
    """Thesis §5.1.2-5.1.3.6: mirrored base and platform (C4) give an irreducible sextic
    whose Galois group is solvable: S4 × C2, order 48 (sympy)."""
    from baranov.robots.analytic import analytic_conditions, galois_group

    scene = load_scene(REPO / "examples" / "3-RPR-VI.json")
    polynomial = solve(scene, method="exact").characteristic_polynomial
    assert analytic_conditions(scene) == ("C4",) and polynomial.degree == 6 and len(polynomial.factors) == 1
    name, order, solvable = galois_group(polynomial.monic_coefficients())
    assert (name, order, solvable) == ("S6TransitiveSubgroups.S4xC2", 48, True)
    # a 3-RPR with none of the conditions: an irreducible sextic with the full group S6
    legs = tuple(Leg.parse("RpR") for _ in range(3))
    geometry = (LegGeometry((0, 0), (0, 0)), LegGeometry((7, 1), (5, 0)), LegGeometry((2, 9), (1, 4)))
    general = locked_scene(Robot(legs, geometry), [5, 8, 9])
    polynomial = solve(general, method="exact").characteristic_polynomial
    assert analytic_conditions(general) == () and polynomial.degree == 6 and len(polynomial.factors) == 1
    assert galois_group(polynomial.monic_coefficients()) == ("S6TransitiveSubgroups.S6", 720, False)


TABLE_5_1 = [  # (row of thesis Table 5.1, base, platform, conditions, degree of Γ(T) without repeated factors)
    ("coincidence", [(0, 0), (5, 1), (0, 0)], [(0, 0), (3, 1), (1, 4)], ("C1",), 2),
    ("double coincidence", [(0, 0), (5, 1), (0, 0)], [(0, 0), (3, 1), (3, 1)], ("C1", "C2"), 1),
    ("collinearity", [(0, 0), (4, 0), (9, 0)], [(0, 0), (2, 0), (7, 0)], ("C2",), 3),
    ("collinearity + similarity", [(0, 0), (4, 0), (10, 0)], [(0, 0), (2, 0), (5, 0)], ("C2", "C3"), 2),
    ("similarity", [(0, 0), (6, 0), (2, 4)], [(0, 0), (3, 0), (1, 2)], ("C3",), 4),
    ("mirror reflection", [(0, 0), (6, 0), (2, 4)], [(0, 0), (6, 0), (2, -4)], ("C4",), 6),
]


def test_a_scaled_mirror_image_is_not_analytic():
    """C4 is a congruent mirror image (example VI): at half the size, the sextic is
    irreducible and its Galois group is not solvable (issue 18: the finding behind the
    definition in robots/analytic.py)."""
    from baranov.robots.analytic import analytic_conditions, galois_group

    legs = tuple(Leg.parse("RpR") for _ in range(3))
    geometry = tuple(LegGeometry(b, p) for b, p in zip([(0, 0), (6, 0), (2, 4)], [(0, 0), (3, 0), (1, -2)], strict=True))
    scene = locked_scene(Robot(legs, geometry), [3, 7, 5])
    polynomial = solve(scene, method="exact").characteristic_polynomial
    assert analytic_conditions(scene) == () and len(polynomial.factors) == 1 and polynomial.degree == 6
    assert not galois_group(polynomial.monic_coefficients())[2]


@pytest.mark.parametrize(("row", "base", "platform", "conditions", "degree"), TABLE_5_1, ids=[r[0] for r in TABLE_5_1])
def test_table_5_1_rows(row, base, platform, conditions, degree):
    """Thesis Table 5.1 on robots meeting each row's conditions, three random leg-length
    triples each: the characteristic polynomial in T = s1,5 (the thesis's variable, which
    the planner picks here), its repeated factors counted once, has the table's degree;
    the mirror row's sextic is irreducible and solvable by radicals."""
    from baranov.robots.analytic import analytic_conditions, galois_group

    legs = tuple(Leg.parse("RpR") for _ in range(3))
    geometry = tuple(LegGeometry(b, p) for b, p in zip(base, platform, strict=True))
    rng = np.random.default_rng(len(row))
    for _ in range(3):
        scene = locked_scene(Robot(legs, geometry), [int(v) for v in rng.integers(2, 10, 3)])
        polynomial = solve(scene, method="exact").characteristic_polynomial
        assert analytic_conditions(scene) == conditions
        assert polynomial.variable == "s1,5"
        assert sum(factor.degree() for factor, _ in polynomial.factors) == degree
        if row == "mirror reflection":
            assert len(polynomial.factors) == 1 and galois_group(polynomial.monic_coefficients())[2]


# --- every family: legs by their home configuration (families II-X: slider joints) -----

from baranov.robots import HomeJoint, load_robot, pose_residuals, robot_solution  # noqa: E402
from baranov.robots.home import locked_leg_from_home  # noqa: E402

#: Pairwise non-parallel directions of rational length (Pythagorean), so that the exact
#: backend takes them; two parallel axes on one link make the construction "a point on
#: two axes" singular (tests/regressions/sliders/open/robot-*-exact-zero-division.json).
DIRECTIONS = [(1, 0), (0, 1), (3, 4), (-3, 4), (4, 3), (4, -3), (5, 12), (-5, 12), (12, 5), (12, -5), (8, 15),
              (-8, 15), (15, 8), (15, -8)]


def _random_home_robot(rng, legs):
    """Random home configurations of ``legs`` (coordinates in [-30, 30]², pairwise
    non-parallel directions of rational length, either sense): with every actuator at 0
    the platform frame on the world frame is a pose."""
    directions = iter(rng.permutation(len(DIRECTIONS)))
    geometry = []
    for leg in legs:
        joints = []
        for letter in leg.joints:
            at = tuple(int(v) for v in rng.integers(-30, 31, 2))
            if letter == "P":
                sense = int(rng.choice((-1, 1)))
                joints.append(HomeJoint(at, tuple(sense * c for c in DIRECTIONS[next(directions)])))
            else:
                joints.append(HomeJoint(at))
        geometry.append(LegGeometry(joints[0].at, joints[2].at, home=tuple(joints)))
    return Robot(tuple(legs), tuple(geometry))


def _pose_values(poses):
    return sorted((round(p.position[0], 6), round(p.position[1], 6), round(p.angle, 6)) for p in poses)


def test_thesis_example_ii_rpp_rpr_rpr():
    """Thesis §5.2.2: example I's 3-RPR with the platform's joint P4 a prismatic joint
    (RPP-RPR-RPR, family II, alpha1 = 3π/4, alpha3 = 5π/4): the published roots
    s1,6 = 32.0000, 112.2332, 141.1726, 342.8691, by every backend; six modes generic
    (the exact characteristic polynomial's degree)."""
    robot, actuators = load_robot(REPO / "examples" / "robot-II-RPP-RPR-RPR.json")
    assert robot_family(robot.legs).name == "II"
    poses = {}
    for method in ("numeric", "exact", "msolve"):
        solution, found = robot_solution(robot, actuators, method)
        assert all(max(map(abs, pose_residuals(robot, actuators, pose))) < 1e-9 for pose in found)
        s16 = sorted(math.dist(m.joints["P1"], m.joints["P6"]) ** 2 for m in solution.assembly_modes)
        assert [round(v, 4) for v in s16] == [32.0, 112.2332, 141.1726, 342.8691], method
        poses[method] = _pose_values(found)
        if method == "exact":  # certified: P1 = P5 (s1,5 = 0, the factor s1,5) cannot happen here
            assert solution.characteristic_polynomial.degree == 6 and solution.certificate.complete
    assert poses["numeric"] == poses["exact"] == poses["msolve"]


def _to_printed_digits(value, printed: str) -> bool:
    """Whether ``value`` rounds to ``printed`` ("-293.1486", "-3.5587e6") at its last digit."""
    mantissa, _, exponent = printed.partition("e")
    decimals = len(mantissa.partition(".")[2])
    return abs(value - float(printed)) <= 0.5 * 10.0 ** (int(exponent or 0) - decimals) * (1 + 1e-9)


#: Thesis §5.2.2's characteristic polynomials in s1,6 (t1,6 for family IV), monic, as printed.
GAMMA_S16 = {
    "robot-I-3RPR": ["1", "-293.1486", "54084.9111", "-3.5587e6", "1.0004e8", "-1.2240e9", "5.3843e9"],
    "robot-II-RPP-RPR-RPR": ["1", "-672.0638", "1.4983e5", "-1.4372e7", "6.1729e8", "-1.2023e10", "8.7934e10"],
    "robot-IV-RPP-RPP-RPR": ["1", "-35.1765", "410.7778", "-1849.7255", "2821.7516"],
}


@pytest.mark.parametrize("name", GAMMA_S16)
def test_thesis_characteristic_polynomials_in_s16(name):
    """Thesis §5.2.2 derives every family's polynomial from the 3-RPR's Γ(s1,6): solved in
    a plan with parameter P1,P6 (``parameter=("P1", "P6")``, `baranov robot --parameter
    P1,P6`) the exact backend gives the printed coefficients to their last digit; for
    family IV in t1,6 = −t (our sign of t, docs/sliders.md, Robots), odd coefficients
    negated. The 3-RPR's has the double root 32 (T = 49 in §5.1.3.1)."""
    robot, actuators = load_robot(REPO / "examples" / f"{name}.json")
    solution, _ = robot_solution(robot, actuators, "exact", parameter=("P1", "P6"))
    polynomial = solution.characteristic_polynomial
    coefficients = [float(c) for c in polynomial.monic_coefficients()]
    if polynomial.variable == "t1,6":
        coefficients = [c * (-1) ** k for k, c in enumerate(coefficients)]
    printed = GAMMA_S16[name]
    assert len(coefficients) == len(printed)
    assert all(_to_printed_digits(c, p) for c, p in zip(coefficients, printed, strict=True)), coefficients
    assert solution.certificate.complete
    if name == "robot-I-3RPR":
        assert (flint.fmpz_poly([-32, 1]), 2) in polynomial.factors


FAMILY_NAMES = ["I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX", "X"]


def _distances_to_p6_axis(poses, axis=(1, 0), point=(3, 4), digits=4):
    """For each pose, P1's oriented distance (cross(u, P1 − q), u the axis direction, q
    its point, world frame; P1 at the origin) to P6's axis, fixed in the platform frame."""
    values = []
    for pose in poses:
        c, s = math.cos(pose.angle), math.sin(pose.angle)
        u = (c * axis[0] - s * axis[1], s * axis[0] + c * axis[1])
        q = (pose.position[0] + c * point[0] - s * point[1], pose.position[1] + s * point[0] + c * point[1])
        values.append(u[0] * -q[1] - u[1] * -q[0])
    return sorted(round(v, digits) for v in values)


@pytest.mark.parametrize(("name", "family", "published"), [
    ("robot-IV-RPP-RPP-RPR", "IV", [3.9529, 4.0, 11.0, 16.2235]),
    ("robot-VIII-3RPP", "VIII", [4.0, 4.1681]),
])
def test_thesis_examples_iv_and_viii(name, family, published):
    """Thesis §5.2.2: P6, then P5 too, made prismatic (RPP-RPP-RPR, family IV; 3-RPP,
    family VIII, every platform joint a slider): the published roots t, P1's oriented
    distance to P6's axis, by every backend. Ours are their negatives: with the axis
    sense the published angles α4, α5 fix, P1 lies on the negative side of it
    (docs/sliders.md, "Robots")."""
    robot, actuators = load_robot(REPO / "examples" / f"{name}.json")
    assert robot_family(robot.legs).name == family
    solutions = {}
    for method in ("numeric", "exact", "msolve"):
        solution, poses = robot_solution(robot, actuators, method)
        solutions[method] = solution
        assert _distances_to_p6_axis(poses) == [-t for t in published[::-1]]
        assert method != "exact" or solution.certificate.complete
        assert all(max(map(abs, pose_residuals(robot, actuators, pose))) < 1e-9 for pose in poses)
    if family == "VIII":
        # every platform joint a slider: the plan of thesis §5.2.1.3 (the third axis from
        # the other two) in t1,6, which the exact method picks since t1,5 is in units of
        # √13; Γ(t) = 2713 t² + 22160 t + 45232, the published t² − 8.1681 t + 16.6723 in
        # our t = −(the thesis's t): the family's generic degree 2 (Table 5.3)
        polynomial = solutions["exact"].characteristic_polynomial
        assert polynomial.variable == "t1,6" and polynomial.degree == 2
        assert [round(float(c), 4) for c in polynomial.monic_coefficients()] == [1.0, 8.1681, 16.6723]


@pytest.mark.parametrize("family", FAMILY_NAMES)
def test_every_family_finds_the_home_pose(family):
    """Five random robots of each family, random home configurations: with the actuators
    at 0 the home pose is found; at most the family's generic number of poses; numeric =
    msolve mode for mode (a numeric mode may be *coarse*, within 1e-4 not 1e-6, as on a
    family-I robot of an earlier draw: tests/regressions/open/robot-I-RrR-RRr-pRR-coarse-root.json);
    the exact backend = msolve where it takes the scene (a slider's frames rational in one
    unit, docs/sliders.md)."""
    rng = np.random.default_rng([18, FAMILY_NAMES.index(family)])
    members = [legs for legs in all_robots() if robot_family(legs).name == family]
    generic = next(f.assembly_modes for f in robot_families() if f.name == family)
    for _ in range(5):
        robot = _random_home_robot(rng, members[rng.integers(len(members))])
        found = {}
        for method in ("numeric", "msolve", "exact"):
            try:
                found[method] = robot_solution(robot, [0, 0, 0], method)
            except ValueError as error:  # the exact method's refusal, by name
                assert method == "exact" and "rational" in str(error), error
        oracle = [m.joints for m in found["msolve"][0].assembly_modes]
        assert len(oracle) <= generic
        assert all(max(map(abs, pose_residuals(robot, [0, 0, 0], pose))) < 1e-9 for pose in found["msolve"][1])
        assert any(max(abs(v) for v in (*pose.position, pose.angle)) < 1e-12 for pose in found["msolve"][1])
        assert any(max(abs(v) for v in (*pose.position, pose.angle)) < 1e-5 for pose in found["numeric"][1])
        assert compare_modes([m.joints for m in found["numeric"][0].assembly_modes], oracle)[:2] == (0, 0)
        if "exact" in found:
            assert compare_modes([m.joints for m in found["exact"][0].assembly_modes], oracle) == (0, 0, 0)


def test_random_actuators_numeric_equals_msolve():
    """Random home configurations moved by random actuator values (every family): the
    numeric poses are msolve's (the independent oracle: the Cartesian system, which needs
    exact dimensions, so a revolute actuator stays at home)."""
    rng = np.random.default_rng(1805)
    robots = all_robots()
    for _ in range(20):
        robot = _random_home_robot(rng, robots[rng.integers(len(robots))])
        actuators = [int(v) if leg.joints[leg.actuated] == "P" else 0
                     for v, leg in zip(rng.integers(-4, 5, 3), robot.legs, strict=True)]
        numeric = robot_solution(robot, actuators, "numeric")[0]
        oracle = robot_solution(robot, actuators, "msolve")[0]
        assert compare_modes([m.joints for m in numeric.assembly_modes],
                             [m.joints for m in oracle.assembly_modes])[:2] == (0, 0)


def test_a_home_leg_locks_like_the_leg_conventions():
    """An RpR leg given by its home configuration locks to the link the RpR convention
    gives (|AB| the actuator), exactly."""
    home = (HomeJoint((1, 8)), HomeJoint((1, 8), (3, -4)), HomeJoint((4, 4)))  # |AB| = 5 at home
    legs = (Leg.parse("RpR"),) * 3
    by_home = Robot(legs, (LegGeometry((0, 0), (0, 0)), LegGeometry((4, 0), (6, 0)),
                           LegGeometry((1, 8), (4, 4), home=home)))
    by_convention = Robot(legs, (LegGeometry((0, 0), (0, 0)), LegGeometry((4, 0), (6, 0)),
                                 LegGeometry((1, 8), (4, 4))))
    moved = locked_leg_from_home(legs[2], home, 8)  # 8 along (3, -4)/5 from home: the platform moves by (24/5, -32/5)
    assert moved.platform.point == (4, 4) and moved.placed.point == (Fraction(44, 5), Fraction(-12, 5))
    assert locked_scene(by_home, [1, 11, 8]).known == locked_scene(by_convention, [1, 11, 13]).known


@pytest.mark.parametrize(("leg", "message"), [
    ({"type": "RpP", "home": [{"at": [0, 0]}, {"at": [0, 0], "direction": [0, 1]}, {"at": [0, 0]}]},
     "leg RpP, joint 3: a prismatic joint needs a non-zero direction"),
    ({"type": "RpR", "home": [{"at": [0, 0]}, {"at": [0, 0], "direction": [0, 1]}]},
     "leg 1, home: three joints base to platform"),
    ({"type": "RpR", "home": [{"at": [0, 0]}, {"at": [0, 0], "dir": [0, 1]}, {"at": [0, 1]}]},
     "leg 1, joint 2: unknown key 'dir'"),
    ({"type": "RrP", "base": [0, 0], "platform": [0, 0]}, "leg RrP: passive joints RP: give the leg by its home"),
])
def test_home_legs_bad_input(leg, message):
    from baranov.robots import robot_from_dict

    rest = [{"type": "RpR", "base": [4, 0], "platform": [6, 0]}, {"type": "RpR", "base": [1, 8], "platform": [3, 4]}]
    with pytest.raises(RobotInputError, match=message):
        robot, _ = robot_from_dict({"legs": [leg, *rest]})
        forward_kinematics(robot, [1, 11, 13])


def test_pose_residuals_see_a_wrong_pose():
    """Forward substitution tells a pose from a nearby one: each leg's residual moves."""
    robot, actuators = load_robot(REPO / "examples" / "robot-VIII-3RPP.json")
    pose = robot_solution(robot, actuators, "msolve")[1][0]
    assert max(map(abs, pose_residuals(robot, actuators, pose))) < 1e-12
    turned = type(pose)(pose.position, pose.angle + 1e-6, pose.joints, pose.parameters)
    assert all(abs(r) > 1e-8 for r in pose_residuals(robot, actuators, turned))  # three RP legs: every axis turns
