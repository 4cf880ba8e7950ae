"""The cost of the catalog's slider-chain counts per chain (issue 17): what
``baranov catalog --slider-modes 9`` would spend on the 47 702 nine-link chains.

A random sample of the chains of ``--links`` links (``enumerate.sliders.slider_chains``,
uniform over all chains of all trusses, seeded), each counted as the catalog counts it
(``catalog.slider_chains.slider_chain_entry``, with the msolve check where asked), timed in
CPU seconds of this process and of its msolve children (so that other work on the machine
does not inflate it). Prints the median and mean per counting method and the extrapolated
CPU hours for every chain.

    python bench/bench_slider_modes.py --links 9 --sample 60 [--seed 1] [--check-every 25]
"""

from __future__ import annotations

import argparse
import resource
import statistics
import time

import numpy as np

from baranov.catalog.slider_chains import slider_chain_entry
from baranov.enumerate import baranov_trusses
from baranov.enumerate.sliders import slider_chains
from baranov.topology import canonical_link_graph6, chain_from_link_graph


def cpu_seconds() -> float:
    """CPU time of this process and its finished children (msolve)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=9)
    parser.add_argument("--sample", type=int, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--check-every", type=int, default=25, help="the msolve check on every K-th chain")
    arguments = parser.parse_args()
    graphs = [canonical_link_graph6(truss) for truss in baranov_trusses(arguments.links)]
    # joint names as the catalog's entries have them: from the canonical graph6
    everything = [(graph6, sliders) for graph6 in graphs for sliders in slider_chains(chain_from_link_graph(graph6))]
    rng = np.random.default_rng(arguments.seed)
    chosen = sorted(rng.choice(len(everything), size=min(arguments.sample, len(everything)), replace=False))
    by_method: dict[str, list[float]] = {}
    checks: list[float] = []
    walls: list[float] = []
    sizes: list[int] = []
    wall = time.perf_counter()
    for n, index in enumerate(chosen):
        graph6, sliders = everything[index]
        check = n % arguments.check_every == 0
        start, started = cpu_seconds(), time.perf_counter()
        entry = slider_chain_entry((graph6, sliders, check))
        spent = cpu_seconds() - start
        walls.append(time.perf_counter() - started)
        (checks if check else by_method.setdefault(entry["method"], [])).append(spent)
        sizes.append(len(sliders))
    wall = time.perf_counter() - wall
    counted = [t for times in by_method.values() for t in times]
    print(f"{arguments.links} links: {len(everything)} chains; sample of {len(chosen)} (seed {arguments.seed}), "
          f"{wall:.0f} s wall")
    for method, times in sorted(by_method.items()):
        print(f"  {method:12s} {len(times):4d} chains: median {statistics.median(times):7.2f} s, "
              f"mean {statistics.mean(times):7.2f} s, max {max(times):7.2f} s CPU")
    if checks:
        print(f"  with the msolve check: {len(checks)} chains, median {statistics.median(checks):.2f} s CPU")
    print(f"  wall per chain: median {statistics.median(walls):.2f} s, mean {statistics.mean(walls):.2f} s; "
          f"sliders per sampled chain: median {statistics.median(sizes)}")
    mean = statistics.mean(counted + checks)
    print(f"  every chain: about {mean * len(everything) / 3600:.1f} CPU hours "
          f"(mean {mean:.2f} s x {len(everything)} chains; with the check on every "
          f"{arguments.check_every}-th)")


if __name__ == "__main__":
    main()
