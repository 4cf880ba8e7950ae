"""
All assembly modes of 7/B1
==========================

Thesis §3.3.1's seven-link Baranov truss 7/B1 with its published dimensions: one unknown
squared distance (coupling degree 1), a closure condition whose real roots on the eight
sign branches are its eight real assembly modes. The numeric backend proves the list
complete (an interval branch-and-prune of the parameter's whole range).
"""

import io

import matplotlib.pyplot as plt
from _paths import EXAMPLES

import baranov
from baranov.solvers.drawing import render_modes

scene = baranov.load_scene(EXAMPLES / "7-B1.json")
solution = baranov.solve(scene)
print(len(solution.assembly_modes), "assembly modes;", solution.certificate.summary())
for mode in solution.assembly_modes:
    print(mode.parameters, mode.signs)

figure, axis = plt.subplots(figsize=(10, 6))
axis.imshow(plt.imread(io.BytesIO(render_modes(scene, solution))))
axis.set_axis_off()
plt.show()

# %%
# The plan behind it: the truss by its thesis name, its best plan and closure condition.
chain = baranov.truss("7/B1")
print("coupling degree", baranov.coupling_degree(chain))
print(baranov.closure_system(baranov.best_plan(chain)).text())
