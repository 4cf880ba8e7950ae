"""Speed-up of the catalog job on Dask (issue 20): the entries of one link count computed
with 1 worker (in process) and with N (an embedded LocalCluster), each in a fresh
process and a fresh folder: median wall times and their ratio from one run. (The
per-task cost histograms by coupling degree are bench/bench_catalog_costs.py's.)

    python bench/bench_catalog_workers.py                    # 9 links, 1 and 2 workers, 3 repeats
    python bench/bench_catalog_workers.py --links 7 --workers 1,2 --repeats 5

Run it on an otherwise idle machine: the ratio is only as good as the cores are free.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

JOB = (
    "import pathlib, sys, tempfile\n"
    "from baranov.catalog.build import catalog_links\n"
    "from baranov.catalog.tasks import dask_client\n"
    "links, workers = int(sys.argv[1]), int(sys.argv[2])\n"
    "with tempfile.TemporaryDirectory() as out, dask_client(workers) as client:\n"
    "    catalog_links(links, False, client, pathlib.Path(out) / 'shards')\n"
)


def wall_time(links: int, workers: int) -> float:
    """Seconds of one fresh process computing the entries of ``links`` links."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", JOB, str(links), str(workers)], check=True)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=9)
    parser.add_argument("--workers", default="1,2", help="worker counts, e.g. 1,2")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    counts = [int(w) for w in args.workers.split(",")]
    medians = {}
    for workers in counts:
        times = [wall_time(args.links, workers) for _ in range(args.repeats)]
        medians[workers] = statistics.median(times)
        print(f"{args.links} links, {workers} worker(s): median {medians[workers]:.1f} s "
              f"(runs: {', '.join(f'{t:.1f}' for t in times)})", flush=True)
    base = medians[counts[0]]
    for workers in counts[1:]:
        print(f"speed-up {counts[0]} -> {workers} workers: {base / medians[workers]:.2f}x")


if __name__ == "__main__":
    main()
