"""Benchmarks of the numeric backend: median wall time per solve, the first solve of a
topology (the plan searched: the planner's cache cleared before each solve) and with the
plan cached (what every further solve of the topology costs).

Targets (issue 21, 2-core machine, one process, plan cached): 7-link instance ≤ 5 ms;
9-link coupling-1 instance ≤ 30 ms; coupling-2 instance ≤ 300 ms; 13-link Watt–Baranov
example ≤ 200 ms (issue 4's were 5 ms, 50 ms, 1 s and 2 s).

    python bench/bench_numeric.py [--repeats 3] [--instances 20]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import clear_plan_cache, coupling_degree
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve

ROOT = Path(__file__).resolve().parents[1]


def median_time(scenes, repeats: int, cached: bool) -> float:
    """Median over scenes of the median over repeats of one solve; ``cached=False``
    clears the plan cache before each solve (a topology's first solve)."""
    per_scene = []
    for scene in scenes:
        times = []
        for _ in range(repeats):
            if not cached:
                clear_plan_cache()
            start = time.perf_counter()
            solve(scene)
            times.append(time.perf_counter() - start)
        per_scene.append(statistics.median(times))
    return statistics.median(per_scene)


def random_scenes(links: int, degree: int, count: int, seed: int = 1):
    rng = np.random.default_rng(seed)
    pool = [t for t in baranov_trusses(links) if coupling_degree(t) == degree]
    return [scene_of(t, generic_integer_configuration(t, rng)) for t in (pool[int(rng.integers(len(pool)))]
                                                                          for _ in range(count))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--instances", type=int, default=20)
    args = parser.parse_args()
    examples = ROOT / "examples"
    cases = {
        "7-link thesis examples (7/B1, 7/B2, 7/B3, 7/B3 §4.2.1)": [
            load_scene(examples / f"{n}.json") for n in ("7-B1", "7-B2", "7-B3", "7-B3-section-4.2.1")],
        f"7-link random instances ({args.instances})": random_scenes(7, 1, args.instances),
        f"9-link coupling-1 random instances ({args.instances})": random_scenes(9, 1, args.instances),
        f"9-link coupling-2 random instances ({args.instances // 2})": random_scenes(9, 2, args.instances // 2),
        "9/B28 example (§3.4.1.4, coupling 2)": [load_scene(examples / "9-B28.json")],
        "11-link Watt-Baranov example (§3.6.2.1)": [load_scene(examples / "11-watt-baranov.json")],
        "13-link Watt-Baranov example (§3.6.2.2)": [load_scene(examples / "13-watt-baranov.json")],
    }
    for name, scenes in cases.items():
        first, cached = (median_time(scenes, args.repeats, cached) for cached in (False, True))
        print(f"{name}: median {first:.3f} s per first solve (plan searched), {cached:.3f} s with the plan cached",
              flush=True)


if __name__ == "__main__":
    main()
