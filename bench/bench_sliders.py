"""Slider chains (issue 17): median wall time per solve of the numeric backend (plan
search included), beside msolve on the same scenes, and whether they agree mode for mode.

Scenes: the three published 7/B3 slider chains of thesis §4.2.2–4.2.4, and random slider
chains of 7- and 9-link trusses (scene/slider_instances.py: a random admissible slider
set with random axes on a random integer configuration), split by the coupling degree of
the plan that runs them.

    python bench/bench_sliders.py [--instances 20] [--repeats 3] [--seed 1]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene, scene_from_dict
from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
from baranov.solvers import solve
from baranov.solvers.msolve import compare_modes, find_msolve, msolve_modes

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ("7-B3-slider-P9", "7-B3-sliders-P8-P9", "7-B3-slider-P1")


def timed(function, repeats: int):
    """(median seconds over ``repeats`` calls, the last result)."""
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def random_slider_scenes(links: int, count: int, seed: int):
    """``count`` random slider chains of random ``links``-link trusses."""
    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(links)
    for _ in range(count):
        truss = trusses[int(rng.integers(len(trusses)))]
        yield scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng))


def measure(scenes, repeats: int) -> dict[int, list[tuple[float, float | None, bool]]]:
    """Per coupling degree: (numeric seconds, msolve seconds or None, same modes)."""
    rows: dict[int, list] = {}
    for scene in scenes:
        seconds, solution = timed(lambda scene=scene: solve(scene), repeats)
        oracle_seconds, agree = None, True
        if find_msolve() is not None:
            oracle_seconds, oracle = timed(lambda scene=scene: msolve_modes(scene), repeats)
            found = [mode.joints for mode in solution.assembly_modes]
            agree = compare_modes(found, list(oracle.configurations))[:2] == (0, 0)
        rows.setdefault(solution.coupling_degree, []).append((seconds, oracle_seconds, agree))
    return rows


def report(label: str, rows: dict[int, list]) -> None:
    for degree, entries in sorted(rows.items()):
        numeric = statistics.median(e[0] for e in entries)
        oracle = [e[1] for e in entries if e[1] is not None]
        msolve_text = f", msolve median {statistics.median(oracle) * 1e3:8.1f} ms" if oracle else ""
        agree = sum(e[2] for e in entries)
        print(f"{label}, coupling {degree}: {len(entries):3d} scenes, numeric median {numeric * 1e3:8.1f} ms, "
              f"max {max(e[0] for e in entries) * 1e3:8.1f} ms{msolve_text}; same modes as msolve: {agree}/{len(entries)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--instances", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()
    report("thesis §4.2.2-4.2.4", measure([load_scene(ROOT / "examples" / f"{name}.json") for name in EXAMPLES],
                                          arguments.repeats))
    for links in (7, 9):
        report(f"{links}-link slider chains", measure(random_slider_scenes(links, arguments.instances, arguments.seed),
                                                      arguments.repeats))


if __name__ == "__main__":
    main()
