"""Fully-parallel planar robots (thesis ch. 5): legs, the 1653 robots and their ten
families (:mod:`.families`), forward kinematics of the robots whose legs lock to RR
links, family I (:mod:`.kinematics`), and the analytic 3-RPR conditions of Table 5.1
(:mod:`.analytic`); the slider families are to come (issue 18)."""

from .families import RobotFamily, all_robots, robot_families, robot_family
from .kinematics import Pose, forward_kinematics, locked_scene, robot_solution
from .legs import LEGS, Leg, RobotInputError, parse_robot
from .model import LegGeometry, Robot, load_robot, robot_from_dict

__all__ = ["LEGS", "Leg", "LegGeometry", "Pose", "Robot", "RobotFamily", "RobotInputError", "all_robots",
           "forward_kinematics", "load_robot", "locked_scene", "parse_robot", "robot_families", "robot_family",
           "robot_from_dict", "robot_solution"]
