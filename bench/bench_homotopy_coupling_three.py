"""The homotopy method (solvers/homotopy.py) on the 45 thirteen-link trusses of coupling
degree 3 (issue 20's stretch goal: a numeric method for them, checked against their
counts): one random integer instance of each, its number of finite solutions against the
catalog's count of the truss (elimination modulo primes, equal to pyrigi's realization
count on all 45: bench/results/catalog-costs-13-coupling-3.jsonl), and whether the
configuration that made the instance is among the real modes. Resumable: rows are
appended to the output, and trusses already there are skipped.

    python bench/bench_homotopy_coupling_three.py [--seed 1] \\
        [--out bench/results/homotopy-13-coupling-3.jsonl]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.homotopy import homotopy_configurations
from baranov.solvers.msolve import match_configurations

ROOT = Path(__file__).resolve().parents[1]
COUNTS = ROOT / "bench" / "results" / "catalog-costs-13-coupling-3.jsonl"


def measure(identifier: str, truss, count: int, seed: int) -> dict:
    coordinates = generic_integer_configuration(truss, np.random.default_rng(seed))
    start = time.perf_counter()
    configurations, result = homotopy_configurations(scene_of(truss, coordinates))
    seconds = time.perf_counter() - start
    missed, _ = match_configurations(configurations, [{j: (float(x), float(y)) for j, (x, y) in coordinates.items()}])
    return {"id": identifier, "seed": seed, "catalog_count": count, "finite_solutions": len(result.solutions),
            "real_modes": len(configurations), "generating_found": not missed, "paths": result.paths,
            "undecided": result.undecided, "seconds": seconds}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "homotopy-13-coupling-3.jsonl")
    args = parser.parse_args()
    counts = {row["id"]: row["cartesian_modes"] for row in map(json.loads, COUNTS.read_text().splitlines())}
    done = {json.loads(line)["id"] for line in args.out.read_text().splitlines()} if args.out.exists() else set()
    trusses = baranov_trusses(13)
    for identifier in sorted(set(counts) - done, key=lambda name: int(name.split("N")[1])):
        row = measure(identifier, trusses[int(identifier.split("N")[1]) - 1], counts[identifier], args.seed)
        with args.out.open("a") as out:
            out.write(json.dumps(row) + "\n")
        print(json.dumps(row), flush=True)
    rows = [json.loads(line) for line in args.out.read_text().splitlines()]
    equal = sum(row["finite_solutions"] == row["catalog_count"] for row in rows)
    found = sum(row["generating_found"] for row in rows)
    undecided = sum(bool(row["undecided"]) for row in rows)
    print(f"{len(rows)} trusses: finite solutions = catalog count on {equal}, generating configuration found on "
          f"{found}, undecided on {undecided}; {statistics.median(r['seconds'] for r in rows):.1f} s median, "
          f"{max(r['seconds'] for r in rows):.1f} s at most")


if __name__ == "__main__":
    main()
