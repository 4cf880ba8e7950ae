"""Fully-parallel planar robots (thesis ch. 5): legs, the 1653 robots and their ten
families (:mod:`.families`), legs by their home configuration (:mod:`.home`), the locked
robot as a scene with its slider joints (:mod:`.locked`), forward kinematics
(:mod:`.kinematics`), and the analytic 3-RPR conditions of Table 5.1 (:mod:`.analytic`)."""

from .families import RobotFamily, all_robots, robot_families, robot_family
from .kinematics import Pose, forward_kinematics, pose_residuals, robot_solution
from .legs import LEGS, Leg, RobotInputError, parse_robot
from .locked import locked_robot, locked_scene
from .model import HomeJoint, LegGeometry, Robot, load_robot, robot_from_dict

__all__ = ["LEGS", "HomeJoint", "Leg", "LegGeometry", "Pose", "Robot", "RobotFamily", "RobotInputError",
           "all_robots", "forward_kinematics", "load_robot", "locked_robot", "locked_scene", "parse_robot",
           "pose_residuals", "robot_families", "robot_family", "robot_from_dict", "robot_solution"]
