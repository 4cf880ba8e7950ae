"""A sweep of one dimension of the 7/B1 example (thesis §3.3.1.3) with the batch API:
the length of link b12 from 6 to 14 (the example has √101 ≈ 10.05), every assembly mode
of every instance, and the plot docs/images/sweep-7-B1.png of the modes' parameter value
against the swept length, one colour per sign vector of the free-sign triangles.

Run from the repository's root: ``.venv/bin/python examples/sweep_7b1.py [INSTANCES]``.
It prints the instances, the modes per instance and the seconds per instance.
"""

from __future__ import annotations

import sys
import time
from fractions import Fraction
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import baranov  # noqa: E402
from baranov.catalog.files import write_atomically  # noqa: E402
from baranov.solvers.drawing import png_bytes  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def main(count: int = 401) -> None:
    scene = baranov.load_scene(ROOT / "examples" / "7-B1.json")
    lengths = [6 + Fraction(8 * k, count - 1) for k in range(count)]
    start = time.perf_counter()
    solutions = baranov.solve_many(scene, [[length * length] for length in lengths], columns=["P1,P2"])
    seconds = time.perf_counter() - start
    counts = [len(solution.assembly_modes) for solution in solutions]
    print(f"{count} instances of 7/B1, |P1P2| from 6 to 14: {sum(counts)} modes "
          f"({min(counts)} to {max(counts)} per instance), {seconds / count * 1000:.1f} ms per instance")
    name = solutions[0].parameters[0]
    figure, axes = plt.subplots(figsize=(8, 5))
    colours = {}
    for length, solution in zip(lengths, solutions, strict=True):
        for mode in solution.assembly_modes:
            signs = "".join("+" if sign > 0 else "−" for sign in mode.signs)
            colour = colours.setdefault(signs, f"C{len(colours) % 10}")
            axes.plot(float(length), mode.parameters[name], ".", markersize=2.5, color=colour)
    for signs, colour in sorted(colours.items()):
        axes.plot([], [], ".", color=colour, label=signs)
    axes.axvline(101 ** 0.5, color="0.6", linewidth=0.8)
    axes.set_xlabel("|P1 P2| (the example: √101, grey line)")
    axes.set_ylabel(f"{name} of each assembly mode")
    axes.set_title(f"7/B1: assembly modes along a sweep of link b12 ({count} instances, baranov.solve_many)")
    axes.legend(title="signs", fontsize=8, markerscale=3)
    write_atomically(ROOT / "docs" / "images" / "sweep-7-B1.png", png_bytes(figure, tight=True))
    print("wrote docs/images/sweep-7-B1.png")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 401)
