"""Fully-parallel planar robots (issue 18, first part): legs, the 1653 robots and their
ten families, every count computed and compared with thesis §5.2 (Tables 5.2-5.3)."""

from collections import Counter

import pytest

from baranov.cli.main import main
from baranov.literature.robots import THESIS_ROBOT_FAMILIES, THESIS_ROBOTS
from baranov.robots import LEGS, Leg, RobotInputError, all_robots, parse_robot, robot_families, robot_family
from baranov.robots.families import locked_sliders


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
