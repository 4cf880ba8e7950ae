"""Lock-step evaluation: searches written as generators that yield the points they need,
run side by side so that one vectorised evaluation of the plan serves them all.

The numeric backend's searches on one sign branch (windows, domain edges, Brent
brackets, bounded minimisations, re-samplings) each ask for a few points at a time, one
request after another. Evaluated one request at a time, a 7-link solve made ~330 calls
of the bilateration kernel, each ~0.2 ms of numpy overhead on arrays of a few elements
(issue 21's profile). Here each search is a generator that yields :class:`Samples` and
receives a :class:`~baranov.closure.evaluate.Profile` of those points; it yields
:class:`Together` to run sub-searches side by side and receives their results in order.
:func:`run_lockstep` runs the searches of every branch at once: in each round it
gathers every pending request of every search, evaluates them all in one paired
evaluation (point n on its own branch, :meth:`~baranov.closure.CompiledSystem.profile`)
and hands each search its rows. The searches are unchanged in what they compute (a
point's values do not depend on the points evaluated beside it); only their order of
evaluation is, so the number of kernel calls is the longest chain of dependent requests
instead of their total.

>>> import numpy as np
>>> def square_root(c):  # bisection for √c on f(s) = s² − c, one point per round
...     low, high = 0.0, max(c, 1.0)
...     for _ in range(60):
...         middle = (low + high) / 2
...         value = yield Samples(np.array([middle]))
...         low, high = (middle, high) if value[0] < 0 else (low, middle)
...     return round(low, 12)
>>> def evaluate(points, signs):
...     return points ** 2 - signs[:, 0]  # c carried in the "branch"
>>> run_lockstep(evaluate, [(square_root(2.0), np.array([2.0])), (square_root(9.0), np.array([9.0]))])
([1.414213562373, 3.0], 60)
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np


class Samples(NamedTuple):
    """A search's request: the values at ``points`` (1-D), on the search's branch or on
    ``signs`` (one branch, shape (m,), or one per point, (N, m))."""

    points: np.ndarray
    signs: np.ndarray | None = None


class Together(NamedTuple):
    """A search's request to run ``tasks`` (generators) side by side on its branch; the
    reply is the list of their results, in order."""

    tasks: Sequence[Generator]


#: A search: yields Samples or Together, returns its result.
Search = Generator[Any, Any, Any]


@dataclass
class _Join:
    """A search waiting for the sub-searches it started with :class:`Together`."""

    thread: _Thread
    results: list
    pending: int


@dataclass
class _Thread:
    generator: Search
    branch: np.ndarray
    join: _Join | None
    slot: int
    reply: Any = field(default=None)


def run_lockstep(evaluate: Callable[[np.ndarray, np.ndarray], Any],
                 tasks: Sequence[tuple[Search, np.ndarray]], deadline: float = math.inf,
                 progress: Callable[[int, int], None] | None = None) -> tuple[list, int]:
    """Run ``tasks`` (search, branch) side by side; return their results (None for a
    search not finished at the ``deadline``, ``time.monotonic()``) and the number of
    rounds, i.e. of calls ``evaluate(points (N,), signs (N, m))``, whose reply is split
    row by row among the requests (indexing its first axis, or each field of a
    NamedTuple). ``progress(finished, total)`` is called after each round. An exception
    raised by a search propagates. Cost: one evaluation per round; the rounds are the
    longest chain of dependent requests."""
    results: list = [None] * len(tasks)
    ready = [_Thread(search, np.asarray(branch), None, n) for n, (search, branch) in enumerate(tasks)]
    waiting: list[tuple[_Thread, Samples]] = []
    rounds = finished = 0
    while ready:
        while ready:
            thread = ready.pop()
            try:
                request = thread.generator.send(thread.reply)
            except StopIteration as stop:
                finished += _finish(thread, stop.value, results, ready)
                continue
            if isinstance(request, Together):
                join = _Join(thread, [None] * len(request.tasks), len(request.tasks))
                if not request.tasks:
                    thread.reply = []
                    ready.append(thread)
                ready += [_Thread(task, thread.branch, join, k) for k, task in enumerate(request.tasks)]
            else:
                waiting.append((thread, request))
        if not waiting or time.monotonic() > deadline:
            break
        for (thread, _), reply in zip(waiting, _evaluated(evaluate, waiting), strict=True):
            thread.reply = reply
            ready.append(thread)
        waiting, rounds = [], rounds + 1
        if progress is not None:
            progress(finished, len(tasks))
    for thread, _ in waiting:
        thread.generator.close()
    return results, rounds


def _finish(thread: _Thread, value: Any, results: list, ready: list[_Thread]) -> int:
    """Record a finished search's result; resume its parent when its last sibling is
    done. Returns 1 for a finished task of :func:`run_lockstep`'s list, else 0."""
    if thread.join is None:
        results[thread.slot] = value
        return 1
    join = thread.join
    join.results[thread.slot] = value
    join.pending -= 1
    if join.pending == 0:
        join.thread.reply = join.results
        ready.append(join.thread)
    return 0


def _evaluated(evaluate, waiting: list[tuple[_Thread, Samples]]) -> list:
    """One evaluation of every waiting request's points, split back per request."""
    points = [np.asarray(request.points, dtype=float).reshape(-1) for _, request in waiting]
    branches = [thread.branch if request.signs is None else np.asarray(request.signs) for thread, request in waiting]
    sizes = [len(at) for at in points]
    if all(branch.ndim == 1 for branch in branches):  # the usual case: one branch a request, repeated
        signs = np.repeat(np.array(branches).reshape(len(branches), -1), sizes, axis=0)
    else:
        signs = np.concatenate([np.broadcast_to(branch, (size, branch.shape[-1]))
                                for branch, size in zip(branches, sizes, strict=True)])
    reply = evaluate(np.concatenate(points), signs)
    bounds = np.cumsum([0] + sizes)
    if isinstance(reply, tuple):  # a NamedTuple of arrays, each split alike
        return [type(reply)(*(part[a:b] for part in reply)) for a, b in zip(bounds[:-1], bounds[1:], strict=True)]
    return [reply[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True)]


def paired_profile(compiled) -> Callable[[np.ndarray, np.ndarray], Any]:
    """The evaluation :func:`run_lockstep` takes for a compiled closure system: the
    :meth:`~baranov.closure.CompiledSystem.profile` of point n on branch ``signs[n]``."""
    def evaluate(points: np.ndarray, signs: np.ndarray):
        return compiled.profile(points[:, None], signs, paired=True)
    return evaluate


def run_alone(search: Search, evaluate: Callable[[np.ndarray, np.ndarray], Any], branch: np.ndarray) -> Any:
    """The result of one search on ``branch`` (:func:`run_lockstep` with one task)."""
    results, _ = run_lockstep(evaluate, [(search, branch)])
    return results[0]
