"""
Forward kinematics of a 3-RPR robot
===================================

Thesis §5.1.3.1, example I: a fully-parallel planar robot with three RPR legs, its leg
lengths 2, 11 and 13. Locked at these values it is a rigid linkage (a pentad), whose
assembly modes are the platform's poses.
"""

import io

import matplotlib.pyplot as plt
from _paths import EXAMPLES

from baranov.robots import load_robot, locked_scene, robot_family, robot_solution
from baranov.robots.drawing import render_robot

robot, _ = load_robot(EXAMPLES / "robot-I-3RPR.json")
actuators = [2, 11, 13]
solution, poses = robot_solution(robot, actuators, "numeric", None)
print("family", robot_family(robot.legs).name, "-", len(poses), "poses")
for pose in poses:
    print(pose)

picture = plt.imread(io.BytesIO(render_robot(robot, locked_scene(robot, actuators), solution)))
figure, axis = plt.subplots(figsize=(8, 4))
axis.imshow(picture)
axis.set_axis_off()
plt.show()
