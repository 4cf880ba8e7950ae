"""Fully-parallel planar robots (thesis ch. 5): legs, the 1653 robots and their ten
families (:mod:`.families`); forward kinematics is to come (issue 18)."""

from .families import RobotFamily, all_robots, robot_families, robot_family
from .legs import LEGS, Leg, RobotInputError, parse_robot

__all__ = ["LEGS", "Leg", "RobotFamily", "RobotInputError", "all_robots", "parse_robot", "robot_families",
           "robot_family"]
