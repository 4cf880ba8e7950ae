"""Assembly-mode counts beyond the catalog's limit: the generic degree of the
characteristic polynomial (two agreeing random instances,
:func:`baranov.solvers.mode_counts.characteristic_degree`) against pyrigi's realization
count (:func:`baranov.topology.realizations.realization_count`) for every ``--every``-th
coupling-1 truss of ``--links`` links. Prints each truss, every disagreement, and the
median and largest time per truss.

    python bench/sweep_assembly_modes.py --links 11 --every 4 [--workers 1]
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
    index, truss = item
    start = time.perf_counter()
    degree, degrees = characteristic_degree(truss)
    return index, degree, degrees, realization_count(truss), time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=11)
    parser.add_argument("--every", type=int, default=1, help="take every n-th coupling-1 truss (catalog order)")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    trusses = [(n, t) for n, t in enumerate(baranov_trusses(args.links)) if best_plan(t).number_of_parameters == 1]
    sample = trusses[::args.every]
    print(f"{len(sample)} of {len(trusses)} coupling-1 trusses with {args.links} links", flush=True)
    times, disagreements = [], 0
    with multiprocessing.get_context("spawn").Pool(args.workers) as pool:
        for index, degree, degrees, count, seconds in pool.imap(compare, sample):
            times.append(seconds)
            agree = degree == count
            disagreements += not agree
            print(f"truss {index}: degree {degree} (instances {degrees}), realization count {count}"
                  f"{'' if agree else '  DISAGREE'}, {seconds:.1f} s", flush=True)
    print(f"{disagreements} disagreements; median {statistics.median(times):.1f} s, max {max(times):.1f} s per truss")


if __name__ == "__main__":
    main()
