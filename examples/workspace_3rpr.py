"""A map of the forward kinematics of thesis example I's 3-RPR robot (§5.1.3.1) over a
grid of two actuator values, with the batch API: the legs' lengths ρ1 and ρ2 from 0 to
16 (ρ3 = 13 fixed), the number of real platform poses at every grid point, and the plot
docs/images/workspace-3-RPR-I.png. The curves where the count changes are the robot's
singularities (a double root of the forward kinematics: two poses merge); thesis example
I, (ρ1, ρ2, ρ3) = (1, 11, 13), lies on one (one double pose).

Each grid point is the locked robot (a pentad, 5/B1: base, platform and three binary
legs; ``baranov.robots.locked_scene``) with the legs' squared lengths replaced
(``baranov.solve_many`` with columns ``P1,P4`` and ``P2,P5``), solved by the numeric
backend in two processes. A grid point where the robot moves (or no plan is defined) is
kept as an error and drawn grey.

Run from the repository's root: ``.venv/bin/python examples/workspace_3rpr.py [SIDE]``
(SIDE × SIDE grid points, default 160). It prints the counts and the seconds per point.
"""

from __future__ import annotations

import sys
import time
from collections import Counter
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402

import baranov  # noqa: E402
from baranov.catalog.files import write_atomically  # noqa: E402
from baranov.robots import load_robot, locked_scene  # noqa: E402
from baranov.solvers.drawing import png_bytes  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
#: Leg lengths swept (ρ1, ρ2 from 0 to LONGEST, the first sample excluded) and the third.
LONGEST, THIRD = 16.0, 13


def main(side: int = 160) -> None:
    robot, _ = load_robot(ROOT / "examples" / "robot-I-3RPR.json")
    scene = locked_scene(robot, [1, 11, THIRD])
    lengths = np.linspace(0, LONGEST, side + 1)[1:]
    instances = [[first**2, second**2] for second in lengths for first in lengths]
    start = time.perf_counter()
    solutions = baranov.solve_many(scene, instances, columns=["P1,P4", "P2,P5"], return_errors=True, workers=2)
    seconds = time.perf_counter() - start
    counts = np.array([len(s.assembly_modes) if isinstance(s, baranov.Solution) else -1 for s in solutions])
    print(f"{side}×{side} grid points, ρ3 = {THIRD}: poses per point {dict(sorted(Counter(counts.tolist()).items()))} "
          f"(-1: refused), {seconds / len(instances) * 1000:.2f} ms per point with two workers")
    figure, axes = plt.subplots(figsize=(6.5, 5.5))
    levels = [-1, 0, 2, 4, 6]
    colours = ListedColormap(["0.75", "white", "#9ecae1", "#3182bd", "#08519c"])
    image = axes.imshow(counts.reshape(side, side), origin="lower", extent=(0, LONGEST, 0, LONGEST),
                        cmap=colours, norm=BoundaryNorm([-1.5, -0.5, 1, 3, 5, 7], colours.N), interpolation="nearest")
    bar = figure.colorbar(image, ticks=levels)
    bar.ax.set_yticklabels(["moves / refused", "0", "2", "4", "6"])
    bar.set_label("real platform poses")
    axes.plot([1], [11], "r+", markersize=10, label="thesis example I (1, 11, 13): one double pose")
    axes.set_xlabel("ρ1 (leg P1 P4)")
    axes.set_ylabel("ρ2 (leg P2 P5)")
    axes.set_title(f"3-RPR of thesis §5.1.3.1, ρ3 = {THIRD}: poses over {side}×{side} leg lengths\n"
                   "(baranov.solve_many on the locked robot)", fontsize=10)
    axes.legend(loc="upper left", fontsize=8)
    write_atomically(ROOT / "docs" / "images" / "workspace-3-RPR-I.png", png_bytes(figure, tight=True))
    print("wrote docs/images/workspace-3-RPR-I.png")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 160)
