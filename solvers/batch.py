"""Many instances of one linkage: a sweep of a dimension, a workspace map, forward
kinematics in a loop (issue 21).

An instance is the scene with some of its moving links' squared distances replaced
(:func:`~baranov.scene.with_dimensions`). Every instance is checked before any is solved,
so a malformed row stops the batch at once, naming itself; each is then solved by
:func:`~baranov.solvers.solve` with the plan searched once (the planner caches it per
topology). The modes of an instance are exactly those of a single solve of the same
scene (tests/test_batch.py).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence

from baranov.scene import Scene, SceneError, with_dimensions

from .coincidence import solvable_plan
from .modes import Solution, SolverError


class BatchError(SceneError):
    """An instance of a batch is malformed; the message names the instance (counted from
    1) and the offending dimension or link."""


def instance_scenes(scene: Scene, instances: Iterable, columns: Sequence[str] | None = None) -> list[Scene]:
    """The scene of every instance: ``instances`` a sequence of mappings ``{"P1,P2": s, ...}``,
    or, with ``columns`` (dimension names such as ``"P1,P2"``), rows of values in that
    order (a list of lists or an N × m numpy array). Numpy scalars become Python numbers
    (an integer array keeps the instances exact, a float array makes them inexact).

    Raises :class:`BatchError` naming the instance and the dimension or link.

    >>> from baranov.scene import load_scene
    >>> scene = load_scene("examples/7-B1.json")
    >>> [str(s.known[frozenset(("P2", "P4"))]) for s in instance_scenes(scene, [[40], [41]], ["P2,P4"])]
    ['40', '41']
    """
    scenes = []
    for number, row in enumerate(instances, start=1):
        if columns is not None:
            values = list(row)
            if len(values) != len(columns):
                raise BatchError(f"instance {number}: {len(values)} values for {len(columns)} columns "
                                 f"({', '.join(columns)})")
            row = dict(zip(columns, values, strict=True))
        elif not isinstance(row, Mapping):
            raise BatchError(f"instance {number}: expected a mapping such as {{\"P1,P2\": 17}}, or give columns")
        try:
            scenes.append(with_dimensions(scene, {key: _python_number(value) for key, value in row.items()}))
        except SceneError as error:
            raise BatchError(f"instance {number}: {error}") from None
    return scenes


def solve_many(scene: Scene, instances: Iterable, columns: Sequence[str] | None = None, method: str = "numeric", *,
               return_errors: bool = False, on_solution: Callable[[int, Solution | SolverError], None] | None = None,
               workers: int = 1, **options) -> list[Solution | SolverError]:
    """Every assembly mode of every instance of ``scene`` (:func:`instance_scenes` reads
    ``instances`` and ``columns``), by the backend ``method`` with ``options`` as
    :func:`~baranov.solvers.solve` takes them; one :class:`Solution` per instance, in order.

    An instance the backend refuses (the linkage moves with its dimensions, no plan is
    defined) raises its :class:`SolverError`, or with ``return_errors=True`` stands in the
    list in its place, like ``asyncio.gather(return_exceptions=True)``, so that a sweep
    keeps its other instances. ``on_solution(number, result)`` is called after each
    instance (counted from 1, in order), e.g. for a progress bar. ``workers`` > 1 solves
    the instances in that many processes (the plan is searched before they start, and
    each inherits it where processes fork).

    Cost: the plan search once; with the numeric method in one process, one
    branch-and-prune over the boxes of every instance side by side and one verification
    of all their roots (7/B1: about 1 ms an instance, docs/bench/numeric-speed.md), an
    instance not certified so solved alone; else a single solve's per instance.

    >>> from baranov.scene import load_scene
    >>> scene = load_scene("examples/7-B1.json")
    >>> [len(s.assembly_modes) for s in solve_many(scene, [{"P2,P4": 40}, {"P2,P4": 40}])]
    [8, 8]
    """
    if not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers={workers!r}: a number of processes, 1 or more")
    scenes = instance_scenes(scene, instances, columns)
    jobs = [(instance, method, return_errors, options) for instance in scenes]
    if workers == 1 or len(scenes) < 2:
        certified = _certified_together(scenes) if method == "numeric" and not options else [None] * len(scenes)
        return _collected((solution or _solved(job) for solution, job in zip(certified, jobs, strict=True)),
                          on_solution)
    from baranov.enumerate.parallel import worker_pool

    try:  # the plan searched and cached before the workers fork
        solvable_plan(scenes[0])
    except (SolverError, ValueError):
        pass  # the instance's own solve says why
    with worker_pool(min(workers, len(scenes))) as pool:
        return _collected(pool.imap(_solved, jobs, chunksize=max(1, len(jobs) // (8 * workers))), on_solution)


def _certified_together(scenes: list[Scene]) -> list[Solution | None]:
    """The numeric solutions of the instances that one branch-and-prune over all of them
    certifies (:func:`~baranov.solvers.numeric.many.solve_certified_many`: rigid instances
    of a coupling-1 plan without sliders; instances with the same joints coincident share
    a plan), None for the others and where that does not apply."""
    solutions: list[Solution | None] = [None] * len(scenes)
    if not scenes or scenes[0].sliders or scenes[0].mobility != 0:
        return solutions
    from .numeric.many import solve_certified_many

    groups: dict[frozenset, list[int]] = {}
    for number, instance in enumerate(scenes):
        groups.setdefault(instance.coincident_pairs, []).append(number)
    for members in groups.values():
        try:
            plan = solvable_plan(scenes[members[0]])
        except (SolverError, ValueError):
            continue  # each instance's own solve says why
        if plan.number_of_parameters == 1:
            for number, solution in zip(members, solve_certified_many([scenes[n] for n in members], plan),
                                        strict=True):
                solutions[number] = solution
    return solutions


def _solved(job) -> Solution | SolverError:
    """One instance solved (in this process or a worker): its solution, or its error
    where errors are returned."""
    from . import solve  # the registry: solve() picks the backend and checks it takes the scene

    instance, method, return_errors, options = job
    try:
        return solve(instance, method, **options)
    except SolverError as error:
        if not return_errors:
            raise
        return error


def _collected(solved: Iterable, on_solution) -> list[Solution | SolverError]:
    results = []
    for number, result in enumerate(solved, start=1):
        results.append(result)
        if on_solution is not None:
            on_solution(number, result)
    return results


def _python_number(value):
    """A numpy scalar as the Python number it holds (``np.int64`` → ``int``); any other
    value as it is, for the scene's own number check."""
    item = getattr(value, "item", None)
    return item() if callable(item) and getattr(value, "shape", None) == () else value
