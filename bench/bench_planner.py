"""Benchmarks of the planner and closure layer: median wall times, fresh process each.

Targets (issue 3, 2-core machine): best plans for all 11-link trusses < 10 s in total;
any 13-link truss < 0.1 s median.

    python bench/bench_planner.py [--repeats 3]
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_enumeration import measure  # noqa: E402

CASES = {
    "coupling degree, all 562 trusses of 11 links (1 process)": (
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.planner import coupling_degree\n"
        "trusses = baranov_trusses(11)\n"
        "import time; start = time.perf_counter()\n"
        "[coupling_degree(t) for t in trusses]\n"
        "print('INNER', time.perf_counter() - start)"
    ),
    "best plan, all 562 trusses of 11 links (1 process)": (
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.planner import best_plan\n"
        "trusses = baranov_trusses(11)\n"
        "import time; start = time.perf_counter()\n"
        "[best_plan(t) for t in trusses]\n"
        "print('INNER', time.perf_counter() - start)"
    ),
    "best plan + closure conditions, all 562 of 11 links (2 processes)": (
        "from concurrent.futures import ProcessPoolExecutor\n"
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.planner import best_plan\n"
        "from baranov.closure import closure_system\n"
        "def work(t): return closure_system(best_plan(t)).text()\n"
        "trusses = baranov_trusses(11)\n"
        "import time; start = time.perf_counter()\n"
        "with ProcessPoolExecutor(2) as pool: list(pool.map(work, trusses, chunksize=8))\n"
        "print('INNER', time.perf_counter() - start)"
    ),
    "best plan, 200 random trusses of 13 links: median per truss (1 process)": (
        "import random, statistics, time\n"
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.planner import best_plan\n"
        "random.seed(13); sample = random.sample(baranov_trusses(13), 200)\n"
        "times = []\n"
        "for t in sample:\n"
        "    start = time.perf_counter(); best_plan(t); times.append(time.perf_counter() - start)\n"
        "print('INNER', statistics.median(times))"
    ),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    print(f"{'case':<74} {'median s':>9} {'min s':>8}")
    for name, code in CASES.items():
        inner = [measure(code, inner=True)[0] for _ in range(args.repeats)]
        print(f"{name:<74} {statistics.median(inner):>9.3f} {min(inner):>8.3f}", flush=True)


if __name__ == "__main__":
    main()
