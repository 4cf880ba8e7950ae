"""Both backends on random trusses drawn with joints in line (issue 28): every truss of
the chosen link counts, ``--on-line`` joints on one line (vertical, horizontal, diagonal,
antidiagonal in turn), small integer coordinates; with ``--kind coincident``, two joints
of different links at one point instead (issue 25). For each instance: does each backend
return the generating configuration, do the two agree mode for mode, is the exact solve
certified complete. Prints one line per disagreement and a summary; the numbers in
docs/stability.md come from

    python bench/sweep_collinear.py --links 9 --on-line 3,4 --instances 5 --box 4 --workers 2 \
        --out docs/bench/collinear-joints.md

which writes the report that ``bench/stability.py`` includes in docs/stability.md.
"""

from __future__ import annotations

import argparse
import math
import shlex
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.scene.hard_instances import (
    LINE_DIRECTIONS,
    coincident_joints_configuration,
    collinear_joints_configuration,
)
from baranov.scene.instances import scene_of
from baranov.solvers import solve
from baranov.solvers.verification import distance_bound, same_mode


def contains_configuration(scene, modes, coordinates) -> bool:
    """Whether some mode places every joint within 1e-6 of the linkage's size of
    ``coordinates``."""
    scale = max(1.0, distance_bound(scene))
    return any(all(math.dist(mode.joints[j], (float(x), float(y))) < 1e-6 * scale
                   for j, (x, y) in coordinates.items()) for mode in modes)


def unmatched(scene, first, second) -> int:
    """How many modes of ``first`` have no equal in ``second``."""
    return sum(1 for m in first if not any(same_mode(m, n, scene) for n in second))


def run(links: int, index: int, on_line: int, instance: int, box: int, seed: int, kind: str = "collinear") -> dict:
    truss = baranov_trusses(links)[index]
    directions = list(LINE_DIRECTIONS)
    direction = directions[instance % len(directions)] if kind == "collinear" else "coincident"
    rng = np.random.default_rng([seed, links, index, on_line, instance])
    if kind == "collinear":
        coordinates = collinear_joints_configuration(truss, rng, on_line, box, direction)
    else:
        coordinates = coincident_joints_configuration(truss, rng, box)
    scene = scene_of(truss, coordinates)
    row = {"links": links, "truss": f"{links}/N{index + 1}", "on_line": on_line, "instance": instance,
           "direction": direction}
    solutions = {}
    for method in ("numeric", "exact"):
        start = time.perf_counter()
        solutions[method] = solve(scene, method=method)
        row[f"{method}_seconds"] = time.perf_counter() - start
        row[f"{method}_modes"] = len(solutions[method].assembly_modes)
        row[f"{method}_has_generating"] = contains_configuration(scene, solutions[method].assembly_modes, coordinates)
    numeric, exact = solutions["numeric"].assembly_modes, solutions["exact"].assembly_modes
    row["only_numeric"] = unmatched(scene, numeric, exact)
    row["only_exact"] = unmatched(scene, exact, numeric)
    row["certified"] = solutions["exact"].certificate.complete
    row["gaps"] = list(solutions["exact"].certificate.gaps)
    row["coupling_degree"] = solutions["exact"].coupling_degree
    return row


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--links", default="9", help="link counts, comma-separated (default 9)")
    parser.add_argument("--on-line", default="3,4", help="joints on the line, comma-separated (default 3,4)")
    parser.add_argument("--instances", type=int, default=5, help="instances per truss and count (default 5)")
    parser.add_argument("--box", type=int, default=4, help="coordinates in [-box, box] (default 4)")
    parser.add_argument("--seed", type=int, default=28)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", type=Path, help="write the report (Markdown) here")
    parser.add_argument("--kind", choices=["collinear", "coincident"], default="collinear")
    args = parser.parse_args(argv)
    counts = [int(n) for n in args.on_line.split(",")] if args.kind == "collinear" else [0]
    tasks = [(links, index, on_line, instance, args.box, args.seed, args.kind)
             for links in map(int, args.links.split(",")) for index in range(len(baranov_trusses(links)))
             for on_line in counts for instance in range(args.instances)]
    start = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(args.workers) as pool:
        futures = [pool.submit(run, *task) for task in tasks]
        for future in as_completed(futures):
            row = future.result()
            rows.append(row)
            bad = (not row["numeric_has_generating"] or not row["exact_has_generating"] or row["only_numeric"]
                   or row["only_exact"] or not row["certified"])
            if bad:
                print("DISAGREE", row, flush=True)
    wall = time.perf_counter() - start
    report = summary(rows, wall, args.workers)
    print("\n".join(report))
    if args.out is not None:
        command = "python bench/sweep_collinear.py " + shlex.join(argv if argv is not None else sys.argv[1:])
        text = "\n".join([f"Command: `{command}` ({len(rows)} instances).", "", *report, "", *table(rows)]) + "\n"
        args.out.with_suffix(".tmp").write_text(text, encoding="utf-8")
        args.out.with_suffix(".tmp").replace(args.out)
    return 0


def summary(rows: list[dict], wall: float, workers: int) -> list[str]:
    lines = []
    for method in ("numeric", "exact"):
        missed = sum(1 for r in rows if not r[f"{method}_has_generating"])
        times = sorted(r[f"{method}_seconds"] for r in rows)
        lines.append(f"- {method}: {missed} missed generating configurations in {len(rows)} instances; "
                     f"solve time median {np.median(times):.2f} s, max {times[-1]:.1f} s")
    disagreements = sum(1 for r in rows if r["only_numeric"] or r["only_exact"])
    lines.append(f"- {disagreements} instances where the backends disagree "
                 f"({sum(r['only_exact'] for r in rows)} modes found only by the exact backend, "
                 f"{sum(r['only_numeric'] for r in rows)} only by the numeric one)")
    lines.append(f"- {sum(1 for r in rows if not r['certified'])} exact solves not certified complete")
    lines.append(f"- wall time {wall:.0f} s on {workers} workers")
    return lines


def table(rows: list[dict]) -> list[str]:
    """Per truss: instances, coupling degree, real modes (exact), median times, misses."""
    lines = ["| truss | coupling degree | instances | real modes (min–max) | numeric median s | exact median s "
             "| missed (numeric / exact) | disagreements |", "|---|---:|---:|---|---:|---:|---|---:|"]
    for truss in sorted({r["truss"] for r in rows}, key=lambda t: int(t.split("N")[1])):
        mine = [r for r in rows if r["truss"] == truss]
        modes = [r["exact_modes"] for r in mine]
        lines.append(f"| {truss} | {mine[0]['coupling_degree']} | {len(mine)} | {min(modes)}–{max(modes)} | "
                     f"{np.median([r['numeric_seconds'] for r in mine]):.2f} | "
                     f"{np.median([r['exact_seconds'] for r in mine]):.2f} | "
                     f"{sum(not r['numeric_has_generating'] for r in mine)} / "
                     f"{sum(not r['exact_has_generating'] for r in mine)} | "
                     f"{sum(bool(r['only_numeric'] or r['only_exact']) for r in mine)} |")
    return lines


if __name__ == "__main__":
    sys.exit(main())
