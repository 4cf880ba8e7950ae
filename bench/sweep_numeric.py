"""Completeness and speed sweep of the numeric backend on random instances.

Each instance: a random truss (``--links``, coupling degree in ``--coupling``), random integer joint
coordinates with no three joints nearly collinear, the scene of those dimensions; the
generating configuration must be among the modes. Prints every miss (with its
coordinates, to be saved under tests/regressions/) and the median time per solve.

    python bench/sweep_numeric.py --seed 1 --instances 300 [--links 7,9] [--coupling 0,1]
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--instances", type=int, default=300)
    parser.add_argument("--links", default="7,9", help="link counts of the trusses to draw from")
    parser.add_argument("--coupling", default="0,1", help="coupling degrees of the trusses to draw from")
    args = parser.parse_args()
    degrees = set(map(int, args.coupling.split(",")))
    rng = np.random.default_rng(args.seed)
    pool = [t for links in map(int, args.links.split(",")) for t in baranov_trusses(links) if coupling_degree(t) in degrees]
    misses, times = 0, []
    for number in range(args.instances):
        truss = pool[int(rng.integers(len(pool)))]
        coordinates = generic_integer_configuration(truss, rng)
        start = time.perf_counter()
        solution = solve(scene_of(truss, coordinates))
        times.append(time.perf_counter() - start)
        if not any(all(math.dist(m.joints[j], (float(x), float(y))) < 3e-5 for j, (x, y) in coordinates.items())
                   for m in solution.assembly_modes):
            misses += 1
            points = {k: (int(x), int(y)) for k, (x, y) in coordinates.items()}
            print(f"MISS #{number}: link graph {[j.links for j in truss.joints]} coordinates {points}", flush=True)
    print(f"instances {len(times)}, misses {misses}, median {statistics.median(times):.3f} s per solve")


if __name__ == "__main__":
    main()
