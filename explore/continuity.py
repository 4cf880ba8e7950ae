"""Assembly modes followed from one set of dimensions to the next: which mode continues
which, and where the number of real modes changes.

As a dimension varies, each real assembly mode moves continuously until it meets another
at a branch point (a double root of the characteristic polynomial: the two become a
complex pair, thesis §3.1) or until a triangle of its plan flattens and the mode leaves
through the domain's edge with its mirror image. Between two nearby sets of dimensions the
modes are therefore matched by where they place the joints, not by their order in a list
(which follows the parameter's value and changes as modes cross).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

Joints = Mapping[str, tuple[float, float]]

#: Two configurations farther apart than this fraction of the linkage's size (the largest
#: displacement of a joint) are not one mode that moved.
MATCH_DISTANCE = 0.5


def configuration_distance(first: Joints, second: Joints) -> float:
    """The largest distance by which a joint of one configuration is displaced in the
    other (joints named in both)."""
    return max((math.dist(first[name], second[name]) for name in first.keys() & second.keys()), default=math.inf)


def match_modes(previous: Sequence[Joints], current: Sequence[Joints], size: float,
                limit: float = MATCH_DISTANCE) -> list[int | None]:
    """For each configuration of ``current``, the index of the one of ``previous`` it
    continues, or None (a mode that appeared): the assignment that minimises the sum of
    :func:`configuration_distance` (Hungarian method, O(n³) for n modes), pairs farther
    apart than ``limit · size`` left unmatched.

    >>> before = [{"P1": (0.0, 0.0)}, {"P1": (5.0, 0.0)}]
    >>> match_modes(before, [{"P1": (4.9, 0.1)}, {"P1": (0.2, 0.0)}, {"P1": (9.0, 9.0)}], size=10)
    [1, 0, None]
    """
    if not previous or not current:
        return [None] * len(current)
    cost = np.array([[configuration_distance(old, new) for old in previous] for new in current])
    rows, columns = linear_sum_assignment(np.where(np.isfinite(cost), cost, 1e300))
    matched: list[int | None] = [None] * len(current)
    for row, column in zip(rows, columns, strict=True):
        if cost[row, column] <= limit * size:
            matched[row] = int(column)
    return matched


@dataclass(frozen=True)
class CountChange:
    """Where the number of real modes changes between two sets of dimensions: at
    ``fraction`` of the way (to ``width``), from ``before`` modes to ``after``."""

    fraction: float
    width: float
    before: int
    after: int


def count_changes(count: Callable[[float], int], start: int, end: int, tolerance: float = 1e-4,
                  depth: int = 40) -> list[CountChange]:
    """Where ``count`` (the number of real modes at a fraction λ ∈ [0, 1] of the way from
    one set of dimensions to another) changes, given its values ``start`` and ``end`` at
    the two ends: bisection to ``tolerance`` in λ, both halves searched while their ends
    differ. A change and its reverse inside one interval (two modes that meet and part
    again) cancel and are not seen. Cost: about log₂(1/tolerance) counts per change.

    >>> count_changes(lambda t: 8 if t < 0.3 else 6, 8, 6)[0].before
    8
    """
    changes: list[CountChange] = []

    def search(low: float, high: float, low_count: int, high_count: int, level: int) -> None:
        if low_count == high_count:
            return
        if high - low <= tolerance or level >= depth:
            changes.append(CountChange((low + high) / 2, high - low, low_count, high_count))
            return
        middle = (low + high) / 2
        middle_count = count(middle)
        search(low, middle, low_count, middle_count, level + 1)
        search(middle, high, middle_count, high_count, level + 1)

    search(0.0, 1.0, start, end, 0)
    return changes
