"""Completeness of the numeric backend against the exact one (issue 5): on random generic
instances, the numeric method finds exactly the assembly modes whose parameter values the
exact method certifies as real roots — 200 instances of every 7- and 9-link truss of
coupling degree 1, and 50 of each of the four 9-link trusses of coupling degree 2 (9/B25-
B28). The issue asks for 200 of those too; at 5-21 s per exact solve (the polynomial lifted
from primes, then certified) that would take about 1.5 h on 2 cores, 50 take about 25 min.

Slow (`make test-slow`): two worker processes; a miss prints the instance's coordinates,
to be saved under tests/regressions/.
"""

import json
import multiprocessing
import os
from pathlib import Path

import numpy as np
import pytest
from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.solvers import solve
from baranov.solvers.configuration import same_mode
from baranov.solvers.instances import generic_integer_configuration, scene_of

#: Random instances per truss, by coupling degree, and how many one worker task takes
#: (coupling-2 instances cost 5-30 s each: small tasks keep both workers busy).
INSTANCES = {1: 200, 2: 50}
BATCH = {1: 200, 2: 5}


def _trusses(coupling: int) -> list[tuple[int, int, int, int]]:
    """(links, truss index, first instance, instances) tasks for every truss of 7 and 9
    links with this coupling degree."""
    return [(links, index, first, BATCH[coupling]) for links in (7, 9)
            for index, truss in enumerate(baranov_trusses(links)) if coupling_degree(truss) == coupling
            for first in range(0, INSTANCES[coupling], BATCH[coupling])]


def _disagreements(task: tuple[int, int, int, int]) -> list[tuple[str, frozenset]]:
    """(message, joint coordinates) of every instance of the task where the numeric and
    the exact modes differ."""
    links, index, first, count = task
    truss = baranov_trusses(links)[index]
    rng = np.random.default_rng(1000 * links + index)
    for _ in range(first):  # the instances of earlier tasks
        generic_integer_configuration(truss, rng)
    found = []
    for _ in range(count):
        coordinates = generic_integer_configuration(truss, rng)
        scene = scene_of(truss, coordinates)
        exact, numeric = solve(scene, method="exact"), solve(scene)
        missed = [m for m in exact.assembly_modes if not any(same_mode(m, n, scene) for n in numeric.assembly_modes)]
        spurious = [n for n in numeric.assembly_modes if not any(same_mode(n, m, scene) for m in exact.assembly_modes)]
        if missed or spurious:
            found.append((f"{links}-link truss {index}: {len(missed)} missed, {len(spurious)} spurious; coordinates "
                          + repr({j: (str(x), str(y)) for j, (x, y) in coordinates.items()}),
                          frozenset((j, int(x), int(y)) for j, (x, y) in coordinates.items())))
    return found


def _all_disagreements(trusses: list[tuple[int, int, int, int]]) -> list[tuple[str, frozenset]]:
    workers = min(2, os.cpu_count() or 1)
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        return [line for lines in pool.imap_unordered(_disagreements, trusses) for line in lines]


def _known_failures() -> set[frozenset]:
    """Joint coordinates of the saved instances marked ``known_failure`` (tests/regressions)."""
    known = set()
    for path in (Path(__file__).resolve().parent / "regressions").glob("*.json"):
        data = json.loads(path.read_text())
        if data.get("known_failure"):
            known.add(frozenset((j, int(x), int(y)) for link in data["links"] for j, (x, y) in link["joints"].items()))
    return known


@pytest.mark.slow
def test_numeric_modes_are_the_certified_ones():
    trusses = _trusses(1)
    assert len({task[:2] for task in trusses}) == 27  # 3 seven-link and 24 nine-link trusses
    disagreements = _all_disagreements(trusses)
    assert not disagreements, "\n".join(message for message, _ in disagreements)


@pytest.mark.slow
def test_numeric_modes_are_the_certified_ones_coupling_two():
    """Two of the 200 instances are known failures (a mode in a strip of the feasible
    domain narrower than the sampling grid; saved as tests/regressions/9-B25-narrow-strip
    and 9-B26-narrow-strip, marked ``known_failure``): any other disagreement fails the
    test, and so does a fix until the files are unmarked."""
    trusses = _trusses(2)
    assert len({task[:2] for task in trusses}) == 4  # 9/B25-B28
    disagreements = _all_disagreements(trusses)
    unexpected = [message for message, coordinates in disagreements if coordinates not in _known_failures()]
    assert not unexpected, "\n".join(unexpected)
    assert {coordinates for _, coordinates in disagreements} == _known_failures()
