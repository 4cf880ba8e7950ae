"""Benchmarks of the exact backend: python-flint against sympy for clearing the radicals,
and the time to a characteristic polynomial. Medians of ``--repeats`` runs, one process.

Targets (issue 5, 2-core machine): 7-link ≤ 0.5 s; 9-link coupling-1 ≤ 10 s; 13-link
Watt–Baranov ≤ 60 s; 9/B28 ≤ 15 min.

    python bench/bench_exact.py [--repeats 3] [--sympy-timeout 600] [--coupling-two]
"""

from __future__ import annotations

import argparse
import multiprocessing
import statistics
import time
from pathlib import Path

import numpy as np
import sympy

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan, coupling_degree
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import characteristic_polynomial
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.exact.characteristic import eliminate_radicals, radical_tower
from baranov.solvers.exact.coupling_two import characteristic_polynomial_two

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def median(function, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def sympy_elimination(name: str) -> float:
    """Clearing the radicals of the same (normal-form) closure condition in sympy, by the
    resultant chain Res_r(F, r² − Δ), outermost radical first; seconds."""
    scene = load_scene(EXAMPLES / f"{name}.json")
    tower = radical_tower(scene, best_plan(scene.chain))
    symbols = sympy.symbols(tower.variables)
    table = dict(zip(tower.variables, symbols, strict=True))

    def convert(polynomial):
        return sympy.sympify(str(polynomial).replace("^", "**"), locals=table)

    start = time.perf_counter()
    polynomial = convert(tower.conditions[0])
    for n in range(len(tower.radicands) - 1, -1, -1):
        radical = symbols[len(tower.parameters) + n]
        polynomial = sympy.resultant(polynomial, radical**2 - convert(tower.radicands[n]), radical)
        polynomial = sympy.expand(polynomial)
    return time.perf_counter() - start


def flint_elimination(name: str) -> None:
    scene = load_scene(EXAMPLES / f"{name}.json")
    tower = radical_tower(scene, best_plan(scene.chain))
    eliminate_radicals(tower.conditions[0], tower)


def _run_sympy(name, queue):
    queue.put(sympy_elimination(name))


def sympy_with_timeout(name: str, timeout: float) -> str:
    queue = multiprocessing.Queue()
    process = multiprocessing.Process(target=_run_sympy, args=(name, queue))
    process.start()
    process.join(timeout)
    if process.is_alive():
        process.terminate()
        return f"did not finish in {timeout:.0f} s"
    return f"{queue.get():.3f} s"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--sympy-timeout", type=float, default=600)
    parser.add_argument("--coupling-two", action="store_true", help="also 9/B28 (minutes)")
    args = parser.parse_args()
    for name in ("5-B1", "7-B1"):
        flint_time = median(lambda name=name: flint_elimination(name), args.repeats)
        print(f"clearing radicals, {name}: python-flint {flint_time:.4f} s; "
              f"sympy {sympy_with_timeout(name, args.sympy_timeout)}", flush=True)
    for name in ("5-B1", "7-B1", "7-B2", "7-B3", "11-watt-baranov", "13-watt-baranov"):
        scene = load_scene(EXAMPLES / f"{name}.json")
        print(f"characteristic polynomial, {name}: median "
              f"{median(lambda scene=scene: characteristic_polynomial(scene), args.repeats):.3f} s", flush=True)
    rng = np.random.default_rng(1)
    nine = [t for t in baranov_trusses(9) if coupling_degree(t) == 1]
    scenes = [scene_of(t, generic_integer_configuration(t, rng)) for t in nine]
    times = [median(lambda s=s: characteristic_polynomial(s), 1) for s in scenes]
    print(f"characteristic polynomial, the 24 coupling-1 trusses of 9 links (one random instance each): "
          f"median {statistics.median(times):.2f} s, max {max(times):.2f} s", flush=True)
    if args.coupling_two:
        scene = load_scene(EXAMPLES / "9-B28.json")
        plan = solvable_plan(scene)
        seconds = median(lambda: characteristic_polynomial_two(scene, plan), 1)
        print(f"characteristic polynomial, 9-B28 (coupling degree 2), one run: {seconds:.1f} s", flush=True)


if __name__ == "__main__":
    main()
