"""Completeness of the numeric backend against the exact one (issue 5): on random generic
instances, the numeric method finds exactly the assembly modes whose parameter values the
exact method certifies as real roots — 200 instances of every 7- and 9-link truss of
coupling degree 1, and 50 of each of the four 9-link trusses of coupling degree 2 (9/B25-
B28). The issue asks for 200 of those too; at 5-21 s per exact solve (the polynomial lifted
from primes, then certified) that would take about 1.5 h on 2 cores, 50 take about 25 min.

Slow (`make test-slow`): two worker processes; a miss prints the instance's coordinates,
to be saved under tests/regressions/.
"""

import multiprocessing
import os

import numpy as np
import pytest
from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.solvers import solve
from baranov.solvers.configuration import same_mode
from baranov.solvers.instances import generic_integer_configuration, scene_of

#: Random instances per truss, by coupling degree.
INSTANCES = {1: 200, 2: 50}


def _trusses(coupling: int) -> list[tuple[int, int, int]]:
    return [(links, index, coupling) for links in (7, 9) for index, truss in enumerate(baranov_trusses(links))
            if coupling_degree(truss) == coupling]


def _disagreements(item: tuple[int, int, int]) -> list[str]:
    links, index, coupling = item
    truss = baranov_trusses(links)[index]
    rng = np.random.default_rng(1000 * links + index)
    found = []
    for _ in range(INSTANCES[coupling]):
        coordinates = generic_integer_configuration(truss, rng)
        scene = scene_of(truss, coordinates)
        exact, numeric = solve(scene, method="exact"), solve(scene)
        missed = [m for m in exact.assembly_modes if not any(same_mode(m, n, scene) for n in numeric.assembly_modes)]
        spurious = [n for n in numeric.assembly_modes if not any(same_mode(n, m, scene) for m in exact.assembly_modes)]
        if missed or spurious:
            found.append(f"{links}-link truss {index}: {len(missed)} missed, {len(spurious)} spurious; coordinates "
                         + repr({j: (str(x), str(y)) for j, (x, y) in coordinates.items()}))
    return found


def _all_disagreements(trusses: list[tuple[int, int, int]]) -> list[str]:
    workers = min(2, os.cpu_count() or 1)
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        return [line for lines in pool.imap_unordered(_disagreements, trusses) for line in lines]


@pytest.mark.slow
def test_numeric_modes_are_the_certified_ones():
    trusses = _trusses(1)
    assert len(trusses) == 27  # 3 seven-link and 24 nine-link trusses
    disagreements = _all_disagreements(trusses)
    assert not disagreements, "\n".join(disagreements)


@pytest.mark.slow
def test_numeric_modes_are_the_certified_ones_coupling_two():
    trusses = _trusses(2)
    assert len(trusses) == 4  # 9/B25-B28
    disagreements = _all_disagreements(trusses)
    assert not disagreements, "\n".join(disagreements)
