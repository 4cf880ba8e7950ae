"""
A chain with a slider joint
===========================

Thesis ch. 4: the 7/B3 Assur chain with a slider at P1 (its two links meet on a line
instead of a point). Solved exactly: the characteristic polynomial and its certified real
roots.
"""

import io

import matplotlib.pyplot as plt
from _paths import EXAMPLES

import baranov
from baranov.solvers.drawing import render_modes

scene = baranov.load_scene(EXAMPLES / "7-B3-slider-P1.json")
solution = baranov.solve(scene, method="exact")
print(len(solution.assembly_modes), "assembly modes;", solution.certificate.summary())
figure, axis = plt.subplots(figsize=(10, 6))
axis.imshow(plt.imread(io.BytesIO(render_modes(scene, solution))))
axis.set_axis_off()
plt.show()
