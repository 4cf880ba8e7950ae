"""Benchmarks of the topology layer: median wall time and peak memory (max RSS).

Each measurement runs in a fresh Python process, so the memory figure is its own.
Targets (issue 2, 2-core machine): all 11-link trusses with automorphism groups < 10 s;
all 13-link trusses < 15 min and < 2 GB.

    python bench/bench_enumeration.py            # everything, 3 repeats
    python bench/bench_enumeration.py --repeats 5 --skip-13
    python bench/bench_enumeration.py --skip-catalog   # the enumeration cases only
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

CASES = {
    "11 links: enumerate + automorphism groups (1 process)": (
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.topology import automorphism_group\n"
        "groups = [automorphism_group(t) for t in baranov_trusses(11)]\n"
        "assert len(groups) == 562"
    ),
    "11 links: brute force over geng (2 processes)": (
        "from baranov.enumerate.crosscheck import baranov_link_graphs_by_filter\n"
        "assert len(baranov_link_graphs_by_filter(11, workers=2)[1]) == 562"
    ),
    "catalog 3-11 links, fresh folder (2 workers, with cross-check)": (
        "import tempfile, pathlib\n"
        "from baranov.catalog import build_catalog\n"
        "with tempfile.TemporaryDirectory() as out:\n"
        "    build_catalog([3, 5, 7, 9, 11], pathlib.Path(out), workers=2)"
    ),
    "13 links: enumerate (1 process)": (
        "from baranov.enumerate import baranov_link_graphs\n"
        "assert len(baranov_link_graphs(13)) == 20437"
    ),
    "13 links: enumerate (2 processes)": (
        "from baranov.enumerate import baranov_link_graphs\n"
        "assert len(baranov_link_graphs(13, workers=2)) == 20437"
    ),
    "13 links: canonical augmentation, subtrees at 8 links (1 process)": (
        "from baranov.enumerate.augmentation import augmentation_roots, subtree_link_graphs\n"
        "assert sum(1 for root in augmentation_roots(13, 8) for _ in subtree_link_graphs(root, 13)) == 20437"
    ),
    "13 links: brute force over geng (2 processes)": (
        "from baranov.enumerate.crosscheck import baranov_link_graphs_by_filter\n"
        "assert len(baranov_link_graphs_by_filter(13, workers=2)[1]) == 20437"
    ),
    "13 links: enumerate + automorphism groups (1 process)": (
        "from baranov.enumerate import baranov_trusses\n"
        "from baranov.topology import automorphism_group\n"
        "groups = [automorphism_group(t) for t in baranov_trusses(13)]\n"
        "assert sum(len(g.link_orbits) for g in groups) == 251638"
    ),
}

WRAPPER = """
import json, resource, time
start = time.perf_counter()
exec(compile({code!r}, "case", "exec"))
elapsed = time.perf_counter() - start
peak = max(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
print(json.dumps([elapsed, peak]))
"""


def measure(code: str, inner: bool = False) -> tuple[float, float]:
    """Wall seconds and peak resident memory (MiB) of ``code`` in a fresh interpreter.

    With ``inner``, the time is the one ``code`` prints itself on a line ``INNER <seconds>``
    (to leave out the set-up, such as enumerating the trusses)."""
    output = subprocess.run(
        [sys.executable, "-c", WRAPPER.format(code=code)], check=True, capture_output=True, text=True
    ).stdout
    lines = output.strip().splitlines()
    elapsed, peak_kib = json.loads(lines[-1])
    if inner:
        elapsed = float(next(line.split()[1] for line in lines if line.startswith("INNER ")))
    return elapsed, peak_kib / 1024


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--skip-13", action="store_true", help="leave out the 13-link cases")
    parser.add_argument("--skip-catalog", action="store_true",
                        help="leave out the catalog case (since the 11-link assembly modes: minutes, not seconds)")
    args = parser.parse_args()
    print(f"{'case':<66} {'median s':>9} {'min s':>8} {'peak MiB':>9}")
    for name, code in CASES.items():
        if args.skip_13 and name.startswith("13") or args.skip_catalog and name.startswith("catalog"):
            continue
        runs = [measure(code) for _ in range(args.repeats)]
        times = [t for t, _ in runs]
        print(f"{name:<66} {statistics.median(times):>9.2f} {min(times):>8.2f} {max(m for _, m in runs):>9.0f}", flush=True)


if __name__ == "__main__":
    main()
