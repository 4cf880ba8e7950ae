"""Issue 24's table: the exact backend beside msolve (the general Gröbner solver, on the
Cartesian system: ``method="msolve"``) and the numeric backend, on the same random
instances, in one run; and whether the exact backend's modes are msolve's, mode for mode.

Rows: one random instance of each 7-link truss, of four 9-link trusses of coupling degree
1, of each of the four of coupling degree 2 (9/B25–B28), of three 11-link trusses of each
coupling degree, the 13-link Watt–Baranov example (§3.6.2.2), and random slider chains of
7- and 9-link trusses (a random admissible slider set, axes of rational length:
``bench_numeric.random_slider_scenes``). One solve per method and instance (the plan
searched beforehand), one process, msolve on one thread.

    python bench/bench_exact_vs_msolve.py [--seed 1] [--out docs/bench/exact-vs-msolve.md]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve
from baranov.solvers.verification import same_mode

ROOT = Path(__file__).resolve().parents[1]
METHODS = ("msolve", "exact", "numeric")


def rows(seed: int) -> dict[str, list]:
    """Row name → scenes."""
    rng = np.random.default_rng(seed)

    def drawn(links: int, degree: int, count: int, every: bool = False) -> list:
        pool = [t for t in baranov_trusses(links) if coupling_degree(t) == degree]
        chosen = pool if every else [pool[int(k)] for k in rng.choice(len(pool), count, replace=False)]
        return [scene_of(t, generic_integer_configuration(t, rng)) for t in chosen]

    from bench_numeric import random_slider_scenes  # a sibling script: bench/ is on the path

    return {"7-link trusses": drawn(7, 1, 3, every=True),
            "9-link coupling 1": drawn(9, 1, 4),
            "9-link coupling 2 (9/B25–B28)": drawn(9, 2, 4, every=True),
            "11-link coupling 1": drawn(11, 1, 3),
            "11-link coupling 2": drawn(11, 2, 3),
            "13-link Watt–Baranov example": [load_scene(ROOT / "examples" / "13-watt-baranov.json")],
            "7-link slider chains": random_slider_scenes(7, 1, 6, seed),
            "9-link slider chains, coupling 1": random_slider_scenes(9, 1, 6, seed),
            "9-link slider chains, coupling 2": random_slider_scenes(9, 2, 6, seed)}


def timed(scene, method: str):
    start = time.perf_counter()
    solution = solve(scene, method=method)
    return solution, time.perf_counter() - start


def agree(first, second, scene) -> bool:
    """The two solutions list the same modes (each within the other, :func:`same_mode`)."""
    a, b = first.assembly_modes, second.assembly_modes
    return (all(any(same_mode(m, n, scene) for n in b) for m in a)
            and all(any(same_mode(n, m, scene) for m in a) for n in b))


def span(values: list[float], digits: str = ".3g") -> str:
    low, high = min(values), max(values)
    return f"{low:{digits}}" if len(values) == 1 or low == high else f"{low:{digits}}–{high:{digits}}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", help="write the markdown table to this file")
    parser.add_argument("--rows", help="only the rows whose name contains this text (e.g. 'slider'); with --out, "
                        "the file holds those rows alone")
    args = parser.parse_args()
    lines = ["| instances | modes | msolve s | exact s | exact ÷ msolve (median) | numeric s | numeric ÷ msolve "
             "| mode for mode = msolve's: exact, numeric |", "|---|---|---|---|---|---|---|---|"]
    for name, scenes in rows(args.seed).items():
        if args.rows and args.rows not in name:
            continue
        times = {method: [] for method in METHODS}
        modes, agreeing = [], {"exact": 0, "numeric": 0}
        for scene in scenes:
            solve(scene)  # the plan searched and cached: the times are the solves'
            solutions = {}
            for method in METHODS:
                solutions[method], seconds = timed(scene, method)
                times[method].append(seconds)
            modes.append(len(solutions["msolve"].assembly_modes))
            for method in agreeing:
                agreeing[method] += agree(solutions[method], solutions["msolve"], scene)
            print(name, modes[-1], {m: round(t[-1], 3) for m, t in times.items()}, flush=True)
        ratio = {method: [t / m for t, m in zip(times[method], times["msolve"], strict=True)]
                 for method in ("exact", "numeric")}
        lines.append(f"| {name} ({len(scenes)}) | {span(modes, 'd')} | {span(times['msolve'])} | "
                     f"{span(times['exact'])} | {span(ratio['exact'], '.2g')} ({np.median(ratio['exact']):.2g}) | "
                     f"{span(times['numeric'])} | {span(ratio['numeric'], '.2g')} | "
                     f"{agreeing['exact']} and {agreeing['numeric']} of {len(scenes)} |")
        print(lines[-1], flush=True)
    table = "\n".join(lines) + "\n"
    print(table)
    if args.out:
        from baranov.catalog.files import write_atomically

        header = (f"# Exact backend beside msolve\n\nGenerated by `python bench/bench_exact_vs_msolve.py --seed {args.seed} "
                  f"--out {args.out}`; do not edit by hand. One solve per method and instance (plan cached), one "
                  "process, msolve on one thread (its whole process: the Cartesian system written, solved, read back); "
                  "ranges over the instances of a row. The last column counts the instances where the exact backend, "
                  "and where the numeric backend, lists exactly msolve's modes.\n\n")
        write_atomically(Path(args.out), (header + table).encode())


if __name__ == "__main__":
    main()
