"""Per-task costs of the catalog job by coupling degree (issue 20): on a random sample of
the trusses of one link count, the seconds of each part of a catalog entry — the best
plan, the assembly-mode count (:func:`~baranov.solvers.mode_counts.characteristic_degree`,
modulo primes), the realization count (pyrigi) and, with ``--cartesian``, the count by
elimination modulo primes on the Cartesian system
(:func:`~baranov.solvers.mode_counts.cartesian_degree`, msolve) and, with ``--plan-system``,
on the best plan's steps and closure conditions as one system
(:func:`~baranov.solvers.mode_counts.plan_system_degree`, msolve) — one truss at a time in
this process; medians, quartiles, maxima and a histogram per coupling degree, so that the full run's
time on N workers can be computed (docs/catalog-13.md).

    python bench/bench_catalog_costs.py --links 13 --sample 40 --seed 1
    python bench/bench_catalog_costs.py --links 11 --sample 20 --out bench/results/costs-11.jsonl
    python bench/bench_catalog_costs.py --links 13 --coupling 3 --sample 45 \
        --out bench/results/catalog-costs-13-coupling-3.jsonl   # all 45: realization counts only
    python bench/bench_catalog_costs.py --links 13 --coupling 3 --sample 45 --no-modes --cartesian \
        --out bench/results/catalog-costs-13-coupling-3.jsonl   # and the Cartesian counts
    python bench/bench_catalog_costs.py --links 13 --coupling 3 --sample 45 --no-modes --plan-system \
        --out bench/results/catalog-costs-13-coupling-3.jsonl   # and the plan's own counts

Rows (one JSON object per truss) are appended to ``--out`` and a rerun measures only the
parts a truss's row lacks (appending the completed row; the last row of an id wins, and
the file is rewritten with one row per id at the end), so a long sample can be stopped and
resumed. Timings beside another job
are inflated: say so where they are quoted.
"""

from __future__ import annotations

import argparse
import faulthandler
import json
import math
import random
import signal
import statistics
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from baranov.catalog.files import write_atomically
from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan, coupling_degree
from baranov.solvers.mode_counts import cartesian_degree, characteristic_degree, plan_system_degree
from baranov.topology.realizations import realization_count

#: Histogram bin edges, seconds.
EDGES = (0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000, 3000)


#: The counts by elimination modulo primes that ``--cartesian`` and ``--plan-system`` add: the
#: row's key prefix (``<prefix>_modes``, ``_counts``, ``_seconds``) and the function.
ELIMINATION_COUNTS = {"cartesian": cartesian_degree, "plan_system": plan_system_degree}


def measure(links: int, index: int, truss, modes: bool, eliminations: tuple[str, ...],
            row: dict | None = None) -> dict:
    """The costs of one truss's entry (seconds), with the counts; only the parts that
    ``row`` (an earlier measurement) lacks are measured."""
    row = dict(row or {})
    if "coupling_degree" not in row:
        start = time.perf_counter()
        plan = best_plan(truss)
        row.update({"links": links, "id": f"{links}/N{index + 1}", "coupling_degree": plan.number_of_parameters,
                    "plan_seconds": time.perf_counter() - start})
    if "realization_count" not in row:
        start = time.perf_counter()
        row["realization_count"] = realization_count(truss)
        row["realization_seconds"] = time.perf_counter() - start
    if modes and row["coupling_degree"] in (1, 2) and "assembly_modes" not in row:
        start = time.perf_counter()
        row["assembly_modes"], row["degrees"] = characteristic_degree(truss)
        row["assembly_modes_seconds"] = time.perf_counter() - start
    for name in eliminations:
        if f"{name}_modes" not in row:
            start = time.perf_counter()
            row[f"{name}_modes"], row[f"{name}_counts"] = ELIMINATION_COUNTS[name](truss)
            row[f"{name}_seconds"] = time.perf_counter() - start
    return row


def missing(row: dict, modes: bool, eliminations: tuple[str, ...]) -> bool:
    """Whether ``row`` lacks a part that this run measures."""
    return ("realization_count" not in row or (modes and row["coupling_degree"] in (1, 2) and "assembly_modes" not in row)
            or any(f"{name}_modes" not in row for name in eliminations))


def histogram(values: list[float]) -> str:
    """Counts per bin of EDGES, as ``≤0.1 s: 3, ≤0.3 s: 5, …`` (empty bins left out)."""
    bins = [0] * (len(EDGES) + 1)
    for value in values:
        bins[next((n for n, edge in enumerate(EDGES) if value <= edge), len(EDGES))] += 1
    labels = [f"≤{edge:g} s" for edge in EDGES] + [f">{EDGES[-1]:g} s"]
    return ", ".join(f"{label}: {count}" for label, count in zip(labels, bins, strict=True) if count)


def report(rows: list[dict]) -> None:
    """Print, per coupling degree and cost, the sample size, median, quartiles, max and histogram."""
    for degree in sorted({row["coupling_degree"] for row in rows}):
        mine = [row for row in rows if row["coupling_degree"] == degree]
        for cost in ("plan_seconds", "realization_seconds", "assembly_modes_seconds",
                     *(f"{name}_seconds" for name in ELIMINATION_COUNTS)):
            values = sorted(row[cost] for row in mine if cost in row)
            if not values:
                continue
            quartiles = statistics.quantiles(values, n=4) if len(values) > 1 else values * 3
            print(f"coupling {degree}, {cost}: n={len(values)} median {statistics.median(values):.3g} "
                  f"quartiles {quartiles[0]:.3g}-{quartiles[2]:.3g} max {values[-1]:.3g} sum {math.fsum(values):.4g}")
            print(f"    {histogram(values)}")
        agree = [row for row in mine if "assembly_modes" in row]
        if agree:
            same = sum(row["assembly_modes"] == row["realization_count"] for row in agree)
            print(f"coupling {degree}: assembly modes = realization count on {same} of {len(agree)}")
        for name in ELIMINATION_COUNTS:
            crossed = [row for row in mine if f"{name}_modes" in row]
            if crossed:
                same = sum(row[f"{name}_modes"] == row["realization_count"]
                           == row.get("assembly_modes", row["realization_count"]) for row in crossed)
                print(f"coupling {degree}: {name} count = realization count (= assembly modes where counted) on "
                      f"{same} of {len(crossed)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=13)
    parser.add_argument("--sample", type=int, default=40, help="trusses drawn at random (all if larger)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--coupling", type=int, help="only trusses of this coupling degree")
    parser.add_argument("--no-modes", action="store_true", help="skip the assembly-mode counts")
    parser.add_argument("--cartesian", action="store_true",
                        help="also count by elimination modulo primes on the Cartesian system (msolve)")
    parser.add_argument("--plan-system", action="store_true",
                        help="also count by elimination modulo primes on the best plan as one system (msolve)")
    parser.add_argument("--out", type=Path, default=Path("bench/results/catalog-costs.jsonl"))
    parser.add_argument("--workers", type=int, default=1,
                        help="trusses measured side by side (their times then share the cores)")
    args = parser.parse_args()
    eliminations = tuple(name for name in ELIMINATION_COUNTS if getattr(args, name))
    faulthandler.register(signal.SIGUSR1)  # kill -USR1 <pid> (of a worker, too): where a long task is
    start = time.perf_counter()
    trusses = baranov_trusses(args.links)
    print(f"{len(trusses)} trusses of {args.links} links enumerated in {time.perf_counter() - start:.1f} s",
          flush=True)
    order = list(range(len(trusses)))
    random.Random(args.seed).shuffle(order)
    done = {}
    if args.out.exists():
        done = {row["id"]: row for line in args.out.read_text().splitlines() for row in [json.loads(line)]}
    # trusses measured before come first: a rerun that adds a part need not scan for them
    order.sort(key=lambda index: f"{args.links}/N{index + 1}" not in done)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    selected = []  # (id, index) of the sample, in order
    for index in order:
        if len(selected) >= args.sample:
            break
        identifier = f"{args.links}/N{index + 1}"
        if identifier not in done and args.coupling is not None and coupling_degree(trusses[index]) != args.coupling:
            continue
        if args.coupling is None or done.get(identifier, {}).get("coupling_degree", args.coupling) == args.coupling:
            selected.append((identifier, index))
    wanted = [(identifier, index) for identifier, index in selected
              if identifier not in done or missing(done[identifier], not args.no_modes, eliminations)]
    with args.out.open("a", encoding="utf-8") as out, ProcessPoolExecutor(args.workers, initializer=faulthandler.register,
                                                                  initargs=(signal.SIGUSR1,)) as pool:
        futures = [pool.submit(measure, args.links, index, trusses[index], not args.no_modes, eliminations,
                               done.get(identifier)) for identifier, index in wanted]
        for future in as_completed(futures):  # each row saved as it comes: a stopped run resumes
            row = future.result()
            done[row["id"]] = row
            out.write(json.dumps(row) + "\n")
            out.flush()
            print(json.dumps(row), flush=True)
    rows = [done[identifier] for identifier, _ in selected]
    write_atomically(args.out, "".join(json.dumps(row) + "\n" for row in done.values()))
    report(rows)


if __name__ == "__main__":
    main()
