"""
Assembly modes along a sweep of one link
========================================

The length of 7/B1's link P1P2 swept from 6 to 14 in 120 instances, all solved by one
call (``solve_many``: the instances' interval searches run side by side). Each mode's
parameter against the length, one colour per sign vector: where two curves meet, two
modes merge and the linkage can jam or switch.
"""

from fractions import Fraction

import matplotlib.pyplot as plt
from _paths import EXAMPLES

import baranov

scene = baranov.load_scene(EXAMPLES / "7-B1.json")
lengths = [6 + Fraction(8 * k, 119) for k in range(120)]
solutions = baranov.solve_many(scene, [[length**2] for length in lengths], columns=["P1,P2"])

figure, axis = plt.subplots(figsize=(7, 4.5))
colours = {}
for length, solution in zip(lengths, solutions, strict=True):
    for mode in solution.assembly_modes:
        (name, value), = mode.parameters.items()
        colour = colours.setdefault(mode.signs, f"C{len(colours) % 10}")
        axis.plot(float(length), value, ".", color=colour, markersize=3)
axis.set_xlabel("|P1P2|")
axis.set_ylabel(name)
axis.set_title("7/B1: every assembly mode along the sweep")
print(sum(s.certificate.complete for s in solutions), "of", len(solutions), "instances certified complete")
plt.show()
