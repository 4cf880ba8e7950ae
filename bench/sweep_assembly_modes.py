"""Assembly-mode counts for every truss of a link count: the generic degree of the
characteristic polynomial (two agreeing random instances,
:func:`baranov.solvers.mode_counts.characteristic_degree`, modulo primes by default or
over Q with ``--method exact``) against pyrigi's realization count
(:func:`baranov.topology.realizations.realization_count`), for every ``--every``-th truss
of ``--links`` links (catalog order) with coupling degree 1 or 2. Prints every
disagreement, the wall time, and the median and largest time per truss for each coupling
degree.

    python bench/sweep_assembly_modes.py --links 11 --workers 2
    python bench/sweep_assembly_modes.py --links 13 --every 100 --workers 2
"""

from __future__ import annotations

import argparse
import multiprocessing
import statistics
import time

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan
from baranov.solvers.mode_counts import characteristic_degree
from baranov.topology.realizations import realization_count


def compare(item):
    index, truss, coupling, method = item
    start = time.perf_counter()
    degree, degrees = characteristic_degree(truss, method=method)
    seconds = time.perf_counter() - start
    return index, coupling, degree, degrees, realization_count(truss), seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=11)
    parser.add_argument("--every", type=int, default=1, help="take every n-th truss (catalog order)")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--method", choices=("modular", "exact"), default="modular")
    parser.add_argument("--verbose", action="store_true", help="print every truss")
    args = parser.parse_args()
    trusses = baranov_trusses(args.links)
    sample = [(n, t, best_plan(t).number_of_parameters, args.method) for n, t in enumerate(trusses)][::args.every]
    sample = [item for item in sample if item[2] in (1, 2)]
    sample.sort(key=lambda item: -item[2])  # coupling 2 first: the costliest
    print(f"{len(sample)} of {len(trusses)} trusses with {args.links} links, method {args.method}, "
          f"{args.workers} worker(s)", flush=True)
    times: dict[int, list[float]] = {1: [], 2: []}
    disagreements = 0
    start = time.perf_counter()
    with multiprocessing.get_context("spawn").Pool(args.workers) as pool:
        for index, coupling, degree, degrees, count, seconds in pool.imap_unordered(compare, sample):
            times[coupling].append(seconds)
            agree = degree == count
            disagreements += not agree
            if args.verbose or not agree:
                print(f"truss {index} (coupling {coupling}): degree {degree} (instances {degrees}), realization "
                      f"count {count}{'' if agree else '  DISAGREE'}, {seconds:.1f} s", flush=True)
    wall = time.perf_counter() - start
    print(f"{disagreements} disagreements in {len(sample)} trusses; wall time {wall:.1f} s")
    for coupling, values in times.items():
        if values:
            print(f"coupling {coupling}: {len(values)} trusses, median {statistics.median(values):.2f} s, "
                  f"max {max(values):.2f} s, sum {sum(values):.1f} s per truss (two instances)")


if __name__ == "__main__":
    main()
