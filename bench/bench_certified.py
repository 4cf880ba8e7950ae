"""How often the numeric backend proves its answer complete (issue 56): random generic
integer instances of every truss of coupling degree 1 with the given link counts, solved
by the numeric backend; the share whose certificate is complete (the interval
branch-and-prune decided every box), what the undecided boxes were, and the solve times
(medians, plan cached, kernels compiled before timing), beside msolve's on the same
instances with ``--msolve``.

    python bench/bench_certified.py [--links 7 9 11] [--instances 10] [--every 10] [--seed 1] [--msolve]
        [--sliders N] [--out FILE]

``--every K``: every K-th coupling-1 truss of 11 links or more (409 at 11 links).

``--out`` writes the table (markdown) atomically, e.g. docs/bench/numeric-certified.md.
"""

from __future__ import annotations

import argparse
import collections
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve
from baranov.solvers.msolve import find_msolve
from baranov.solvers.numeric.branch_and_prune import compile_kernels


def _row(links: int, instances: int, every: int, seed: int, with_msolve: bool) -> dict:
    """Certified share, gap reasons and medians over the coupling-1 trusses of ``links``
    (every ``every``-th from 11 links)."""
    rng = np.random.default_rng(seed)
    certified, total, reasons, times, msolve_times = 0, 0, collections.Counter(), [], []
    trusses = [truss for truss in baranov_trusses(links) if coupling_degree(truss) == 1]
    for truss in trusses[::every if links >= 11 else 1]:
        for _ in range(instances):
            scene = scene_of(truss, generic_integer_configuration(truss, rng))
            solve(scene)  # the plan searched and cached
            start = time.perf_counter()
            solution = solve(scene)
            times.append(time.perf_counter() - start)
            total += 1
            certificate = solution.certificate
            if certificate is not None and certificate.complete:
                certified += 1
            else:
                reasons.update(_reason(gap) for gap in (certificate.gaps if certificate else ("no certificate",)))
            if with_msolve:
                start = time.perf_counter()
                solve(scene, method="msolve")
                msolve_times.append(time.perf_counter() - start)
    return {"links": links, "instances": total, "certified": certified, "reasons": reasons,
            "median": statistics.median(times), "msolve": statistics.median(msolve_times) if msolve_times else None}


def _slider_row(links: int, chains: int, seed: int, with_msolve: bool) -> dict:
    """The same over ``chains`` random slider chains of ``links``-link trusses (a random
    admissible slider set, random axes of rational length: scene/slider_instances.py)
    whose plan has coupling degree 1; with msolve, each answer is also compared with
    msolve's mode for mode (a difference is counted among the reasons)."""
    from baranov.scene import scene_from_dict
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
    from baranov.solvers.coincidence import NoPlanError, solvable_plan
    from baranov.solvers.msolve import compare_modes

    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(links)
    certified, total, reasons, times, msolve_times = 0, 0, collections.Counter(), [], []
    while total < chains:
        truss = trusses[int(rng.integers(len(trusses)))]
        scene = scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True))
        try:
            if solvable_plan(scene).number_of_parameters != 1:
                continue
        except NoPlanError:
            continue
        solve(scene)
        start = time.perf_counter()
        solution = solve(scene)
        times.append(time.perf_counter() - start)
        total += 1
        certificate = solution.certificate
        if certificate is not None and certificate.complete:
            certified += 1
        else:
            reasons.update(_reason(gap) for gap in (certificate.gaps if certificate else ("no certificate",)))
        if with_msolve:
            start = time.perf_counter()
            expected = solve(scene, method="msolve")
            msolve_times.append(time.perf_counter() - start)
            missed, spurious, _ = compare_modes([mode.joints for mode in solution.assembly_modes],
                                                [mode.joints for mode in expected.assembly_modes])
            if missed or spurious:
                reasons[f"differs from msolve ({missed} missed, {spurious} spurious)"] += 1
    return {"links": f"{links}, slider chains", "instances": total, "certified": certified, "reasons": reasons,
            "median": statistics.median(times), "msolve": statistics.median(msolve_times) if msolve_times else None}


def _reason(gap: str) -> str:
    """The kind of an undecided box, from its sentence."""
    return gap.split(": ", 1)[1] if ": " in gap else gap


def _table(rows: list[dict], command: str) -> str:
    lines = [f"# Numeric backend: certified complete\n\nGenerated by `{command}`; do not edit by hand. "
             "Random generic integer instances of every truss of coupling degree 1 (and, in the slider-chain rows, "
             "random slider chains with rational axes whose plan has coupling degree 1, each compared with msolve's "
             "modes); times are medians of one solve per instance, plan cached and kernels compiled.\n",
             "| links | instances | certified complete | share | median solve s | msolve s | ratio | undecided boxes |",
             "|---|---|---|---|---|---|---|---|"]
    for row in rows:
        share = row["certified"] / row["instances"] if row["instances"] else float("nan")
        msolve = f"{row['msolve']:.4f}" if row["msolve"] is not None else "—"
        ratio = f"{row['median'] / row['msolve']:.2f}" if row["msolve"] else "—"
        reasons = "; ".join(f"{count}× {reason}" for reason, count in row["reasons"].most_common()) or "none"
        lines.append(f"| {row['links']} | {row['instances']} | {row['certified']} | {share:.1%} | "
                     f"{row['median']:.4f} | {msolve} | {ratio} | {reasons} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, nargs="+", default=[7, 9, 11])
    parser.add_argument("--instances", type=int, default=10, help="random instances per truss")
    parser.add_argument("--every", type=int, default=10, help="every K-th truss from 11 links")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--msolve", action="store_true", help="time msolve on the same instances")
    parser.add_argument("--sliders", type=int, default=0, help="also this many random slider chains per link count")
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    if args.msolve and find_msolve() is None:
        parser.error("--msolve: no msolve binary (make setup installs it)")
    compile_kernels()
    rows = [_row(links, args.instances, args.every, args.seed, args.msolve) for links in args.links]
    rows += [_slider_row(links, args.sliders, args.seed, args.msolve) for links in args.links if args.sliders and links <= 9]
    command = "python bench/bench_certified.py " + " ".join(sys.argv[1:] if argv is None else argv)
    table = _table(rows, command.strip())
    print(table, end="")
    if args.out:
        with tempfile.NamedTemporaryFile("w", dir=args.out.parent, delete=False, suffix=".tmp") as handle:
            handle.write(table)
        os.replace(handle.name, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
