"""
A four-bar's coupler curve and configuration space
==================================================

Thesis ch. 6: a one-degree-of-freedom chain traced along its motion. The four-bar with a
coupler point: its configuration space (the pieces of each sign vector) and the path of
the coupler point.
"""

import io

import matplotlib.pyplot as plt
from _paths import EXAMPLES

import baranov
from baranov.motion import one_dof_system, trace
from baranov.motion.drawing import render_trace
from baranov.motion.tracer_paths import traced_with_tracer_points

scene = baranov.load_scene(EXAMPLES / "four-bar-coupler-point.json")
system = one_dof_system(scene)
traced = traced_with_tracer_points(scene, trace(system))  # the coupler point's place on each configuration
print(len(traced.pieces), "pieces")
tracers = [tracer.name for tracer in scene.tracers]
picture = plt.imread(io.BytesIO(render_trace(system, traced, tracers)))
figure, axis = plt.subplots(figsize=(9, 4.5))
axis.imshow(picture)
axis.set_axis_off()
plt.show()
