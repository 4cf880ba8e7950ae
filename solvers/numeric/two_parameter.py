"""Roots of two closure conditions in two parameters (coupling degree 2).

A plan with two parameters u = s_{a,b}, v = s_{c,d} (e.g. 9/B25–B28, thesis §3.4.1)
closes with two scalar radical equations f_1(u, v) = f_2(u, v) = 0 on every free-sign
branch. The thesis clears their radicals and eliminates one parameter by a resultant
(§3.4.1.3); numerically, this module branches and prunes over the parameter box, in the
plane of the distances (√u, √v):

1. sample both conditions on a grid, all branches at once (numpy);
2. find, by bisection, where each grid edge leaves the feasible domain (a triangle of the
   plan turns flat): the conditions behave like square roots there, so their values at
   the boundary join each cell's corner values (a root next to the boundary is otherwise
   invisible from the corners);
3. a cell where both zero sets may pass — each f_k changes sign on the cell's values, or
   its smallest value is within the spread of f_k over the neighbouring cells (a
   Lipschitz estimate) — is split into SPLIT × SPLIT sub-cells, level by level, all cells
   of a level in one vectorised evaluation;
4. damped Newton (finite-difference Jacobian, steps that leave the domain are halved)
   from every cell where both conditions change sign, and from every cell still suspect
   at the last level (tangential intersections): from its centre and from its best sample.

The caller verifies every candidate as a configuration, so a spurious candidate costs
time, never a wrong mode. Sampling cannot prove completeness; the exact backend can.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import maximum_filter, minimum_filter
from scipy.optimize import brentq, minimize_scalar

from baranov.closure import CompiledSystem

from ..candidates import distinct_candidates
from ..progress import report_stage
from .one_parameter import TOUCH_SEARCH, TOUCH_TOLERANCE

#: Samples per axis of the first grid (uniform in the distances √u, √v).
GRID = 160
#: Each suspect cell is split into SPLIT × SPLIT sub-cells, DEPTH levels deep.
SPLIT = 4
#: The most suspect cells a level refines; beyond, they are left unsearched and said so
#: (a level of C cells evaluates C (SPLIT + 1)² points, about 1 kB of memory each).
MOST_CELLS = 40_000
DEPTH = 4
#: Suspect cells on the domain boundary are split this many levels, then polished.
BOUNDARY_DEPTH = 2
#: Bisection steps locating the domain boundary on a grid edge.
BOUNDARY_STEPS = 30
#: Samples between the domain boundary and the defined end of a grid edge, spaced
#: uniformly in the square root of the distance from the boundary (:func:`_boundary`).
EDGE_SAMPLES = 4
#: Newton iterations, and the largest residual a candidate may keep.
NEWTON_STEPS = 50
CANDIDATE_TOLERANCE = 1e-9
#: Newton ends that stall above CANDIDATE_TOLERANCE but below this are returned for
#: polishing on the link constraints (a root next to the domain boundary).
STALLED_TOLERANCE = 0.2
#: A branch with more distinct roots than this is tested for a curve shared by the two
#: conditions (:func:`shared_curve`), at CURVE_SAMPLES of its roots; a path of
#: CURVE_STEPS steps of CURVE_STEP (relative) is continued where the Jacobian's singular
#: values differ by more than 1 / RANK_TOLERANCE.
CROWDED_ROOTS = 64
CURVE_SAMPLES = 8
CURVE_STEPS = 4
CURVE_STEP = 1e-2
RANK_TOLERANCE = 1e-5


@dataclass
class Cells:
    """A batch of rectangular cells of the (√u, √v) plane, each on one branch."""

    branch: np.ndarray  # (C,) index into the branch table
    low: np.ndarray  # (C, 2) lower corner
    high: np.ndarray  # (C, 2) upper corner

    def __len__(self) -> int:
        return len(self.branch)

    @staticmethod
    def concatenate(batches: list[Cells]) -> Cells:
        if not batches:
            return Cells(np.zeros(0, int), np.zeros((0, 2)), np.zeros((0, 2)))
        return Cells(*(np.concatenate([getattr(b, name) for b in batches]) for name in ("branch", "low", "high")))


def two_parameter_roots(compiled: CompiledSystem, branches: np.ndarray, upper: tuple[float, float],
                        deadline: float = math.inf):
    """Candidate roots ``(array([u, v]), branch)`` of the two closure conditions of
    ``compiled`` on every branch, for (u, v) in (0, upper[0]] × (0, upper[1]]; and the
    points to polish on the link constraints (:mod:`baranov.solvers.polish`) as
    ``(points (K, 2), branch indices (K,))``: where Newton stalled close to a root, and
    the best sample of every suspect cell on the domain boundary after BOUNDARY_DEPTH
    levels (a condition behaves like a square root there, so splitting further only
    multiplies the cells along the boundary); and ``(cells, reason)``: the cells left
    unsearched when the ``deadline`` (``time.monotonic()``) passed between two levels, or
    when a level had more than MOST_CELLS suspect cells (9/B27 with sliders P1, P2, P3, P7,
    P8, P11: about a million at the third level, 23 GB, before this bound).

    Cost: GRID² · B evaluations of the plan for B branches, BOUNDARY_STEPS evaluations per
    grid edge crossing the domain boundary, and SPLIT² per suspect cell and level.
    """
    low = np.array([math.sqrt(bound) * 1e-6 for bound in upper])
    high = np.array([math.sqrt(bound) for bound in upper])
    whole = Cells(np.arange(len(branches)), np.tile(low, (len(branches), 1)), np.tile(high, (len(branches), 1)))
    interior, boundary, windows, starts = _examine(compiled, branches, whole, GRID - 1, last=None, one_grid=True)
    all_starts, to_polish, unsearched, reason = [starts], [], Cells.concatenate([]), ""
    for depth in range(DEPTH):
        if depth >= BOUNDARY_DEPTH:
            to_polish.append(boundary)
            interior = Cells.concatenate([interior, windows])
        else:
            interior = Cells.concatenate([interior, windows, boundary[1]])
        if len(interior) == 0:
            break
        if time.monotonic() > deadline:
            unsearched, reason = interior, "the time limit was reached"
            break
        if len(interior) > MOST_CELLS:  # each level multiplies suspect cells by up to SPLIT²
            unsearched, reason = interior, f"more than {MOST_CELLS} suspect cells at one level"
            break
        report_stage(f"numeric: two-parameter search, level {depth + 2} of {DEPTH + 1} ({len(interior)} cells)")
        interior, boundary, windows, starts = _examine(compiled, branches, interior, SPLIT,
                                                       last=low if depth == DEPTH - 1 else None)
        all_starts.append(starts)
    to_polish.append(boundary)
    report_stage("numeric: Newton's method from the suspect cells")
    roots, stalled = _newton(compiled, branches, *(np.concatenate(parts) for parts in zip(*all_starts, strict=True)))
    polish_points = np.concatenate([stalled[0]] + [points for points, _ in to_polish])
    polish_branches = np.concatenate([stalled[1]] + [cells.branch for _, cells in to_polish])
    return roots, (polish_points, polish_branches), (unsearched, reason)


def _examine(compiled: CompiledSystem, branches: np.ndarray, cells: Cells, split: int, last: np.ndarray | None,
             one_grid: bool = False):
    """Split every cell into split × split sub-cells and sample them. Returns the suspect
    sub-cells inside the domain; the suspect sub-cells on its boundary as ``(best sample
    (u, v), cells)``; the sub-cells with no defined corner that a strip of the domain
    crosses, shrunk to it (:func:`_strip_cells`); and the Newton starts ``(points, branch
    indices)``: the centre and the best sample of each interior sub-cell where both
    conditions change sign; at the last level (``last``: the origin of the cells' lattice)
    also the best sample of every interior suspect that is a local minimum of its
    distance from a common zero (:func:`_classify`) among its neighbours
    (:func:`_local_minima`). ``one_grid``: cell c is the whole box on branch c (the first
    level), so every branch is evaluated at one grid's points."""
    count, side = len(cells), split + 1
    fractions = np.linspace(0.0, 1.0, side)
    axis = [cells.low[:, a, None] + (cells.high - cells.low)[:, a, None] * fractions for a in range(2)]
    t1 = np.broadcast_to(axis[0][:, :, None], (count, side, side))
    t2 = np.broadcast_to(axis[1][:, None, :], (count, side, side))
    grid = np.stack([t1, t2], axis=-1)  # (C, side, side, 2) in the √ plane
    signs = branches[cells.branch]
    if one_grid:  # cell c is branch c over one box: every branch at every grid point, their common steps once
        profile = compiled.profile(grid[0].reshape(-1, 2) ** 2, signs)
        values, failures = profile.residuals, profile.failures
    else:
        values, failures = compiled.paired_residuals_and_failures(grid.reshape(-1, 2) ** 2,
                                                                 np.repeat(signs, side * side, axis=0))
    values, failures = values.reshape(count, side, side, 2), failures.reshape(count, side, side)
    along_first, along_second = _boundary(compiled, signs, [
        (grid[:, :-1, :, :], grid[:, 1:, :, :], failures[:, :-1], failures[:, 1:]),
        (grid[:, :, :-1, :], grid[:, :, 1:, :], failures[:, :, :-1], failures[:, :, 1:])])
    # the points and values seen by cell (i, j): four corners and the boundary points on
    # its four edges, as eight views (C, n, n, 2), gathered only for the cells kept
    points = _corners(grid) + _sides(along_first[0], along_second[0])
    seen = _corners(values) + _sides(along_first[1], along_second[1])
    near_boundary = _EdgeSamples.of_cells(along_first[3], along_second[3])
    changes, suspect, distance = _classify(values, near_boundary)
    inside = _over_corners(np.logical_and, _both(np.isfinite(values)))

    def cells_of(mask: np.ndarray) -> tuple[Cells, np.ndarray]:
        at = np.nonzero(mask)
        c, i, j = at
        best = _best_samples(points, seen, near_boundary, at)
        return Cells(cells.branch[c], grid[c, i, j], grid[c, i + 1, j + 1]), best

    undefined = failures < len(compiled.plan.steps)
    first, second, third, fourth = _sides(_both(np.isfinite(along_first[1])), _both(np.isfinite(along_second[1])))
    window = _over_corners(np.logical_and, undefined) & (first | second | third | fourth)
    strip = points[4:] + _sides(along_first[2], along_second[2])
    interior, _ = cells_of(suspect & inside)
    edge_cells, edge_best = cells_of(suspect & ~inside & ~window)
    started, started_best = cells_of(changes & inside)
    centre = (started.low + started.high) / 2
    starts = (np.concatenate([centre, started_best]) ** 2, np.concatenate([started.branch] * 2))
    if last is not None:
        lowest = distance
        low_corner = grid[:, :-1, :-1].reshape(-1, 2)
        minima = _local_minima(np.repeat(cells.branch, split * split), low_corner,
                               grid[:, 1:, 1:].reshape(-1, 2) - low_corner, lowest.reshape(-1), last)
        touching, touching_best = cells_of(suspect & ~changes & inside & minima.reshape(lowest.shape))
        starts = (np.concatenate([starts[0], touching_best**2]), np.concatenate([starts[1], touching.branch]))
    return interior, (edge_best**2, edge_cells), _strip_cells(cells, grid, window, strip), starts


@dataclass
class _EdgeSamples:
    """What the EDGE_SAMPLES samples between the domain boundary and a grid edge's defined
    end saw (:func:`_boundary`), per grid edge: the smallest and largest value of each
    condition there and at the boundary point itself (±inf where none), and the sample of
    the smallest max(|f_1|, |f_2|) with that size (NaN, inf where none). Kept per edge and
    merged into its two cells, rather than stacked as more samples of every cell, because
    few edges cross the boundary."""

    low: np.ndarray  # (..., 2)
    high: np.ndarray  # (..., 2)
    best: np.ndarray  # (..., 2) a point of the √ plane
    size: np.ndarray  # (...)

    @staticmethod
    def empty(shape: tuple[int, ...]) -> _EdgeSamples:
        return _EdgeSamples(np.full((*shape, 2), np.inf), np.full((*shape, 2), -np.inf),
                            np.full((*shape, 2), np.nan), np.full(shape, np.inf))

    def record(self, at: tuple[np.ndarray, ...], points: np.ndarray, values: np.ndarray) -> None:
        """Samples ``points`` (E, k, 2) with ``values`` (E, k, 2) of the edges ``at``."""
        defined = np.isfinite(values)
        self.low[at] = np.where(defined, values, np.inf).min(axis=1)
        self.high[at] = np.where(defined, values, -np.inf).max(axis=1)
        size = np.where(defined.all(axis=-1), np.abs(values).max(axis=-1), np.inf)
        pick = np.argmin(size, axis=1)
        self.best[at] = points[np.arange(len(points)), pick]
        self.size[at] = size[np.arange(len(points)), pick]

    @staticmethod
    def of_cells(along_first: _EdgeSamples, along_second: _EdgeSamples) -> _CellEdgeSamples:
        """Per cell (i, j), the samples of its four sides merged, from the edges along the
        first axis (C, n, n + 1) and along the second (C, n + 1, n)."""
        def sides(name: str) -> list[np.ndarray]:
            return _sides(getattr(along_first, name), getattr(along_second, name))
        return _CellEdgeSamples(np.minimum.reduce(sides("low")), np.maximum.reduce(sides("high")), sides("best"),
                                sides("size"))


@dataclass
class _CellEdgeSamples:
    """:class:`_EdgeSamples` merged per cell (C, n, n): the smallest and largest value of
    each condition over its four sides; the sides' best samples and their sizes kept as
    four views, merged only for the cells asked (:meth:`best_at`)."""

    low: np.ndarray  # (C, n, n, 2)
    high: np.ndarray  # (C, n, n, 2)
    sides_best: list[np.ndarray]  # 4 × (C, n, n, 2)
    sides_size: list[np.ndarray]  # 4 × (C, n, n)

    def best_at(self, at: tuple[np.ndarray, ...]) -> tuple[np.ndarray, np.ndarray]:
        """The best sample of the sides of the cells ``at`` (an index tuple), and its size."""
        return _smallest([side[at] for side in self.sides_best], [side[at] for side in self.sides_size])


def _over_corners(combine: np.ufunc, array: np.ndarray) -> np.ndarray:
    """``combine`` (a commutative, associative ufunc) over each cell's four corners:
    (C, n + 1, n + 1, ...) → (C, n, n, ...), along one axis, then the other."""
    along = combine(array[:, :-1], array[:, 1:])
    return combine(along[:, :, :-1], along[:, :, 1:])


def _corners(array: np.ndarray) -> list[np.ndarray]:
    """Per cell (C, n, n, ...), the values at its four corners, as views of ``array``
    (C, n + 1, n + 1, ...)."""
    return [array[:, :-1, :-1], array[:, 1:, :-1], array[:, :-1, 1:], array[:, 1:, 1:]]


def _sides(along_first: np.ndarray, along_second: np.ndarray) -> list[np.ndarray]:
    """Per cell (C, n, n, ...), the values of its four sides, as views of those of the
    edges along the first axis (C, n, n + 1, ...) and along the second (C, n + 1, n, ...)."""
    return [along_first[:, :, :-1], along_first[:, :, 1:], along_second[:, :-1, :], along_second[:, 1:, :]]


def _best_samples(points: list[np.ndarray], seen: list[np.ndarray], near_boundary: _CellEdgeSamples,
                  at: tuple[np.ndarray, ...]) -> np.ndarray:
    """For the cells ``at`` (an index tuple into (C, n, n)), the sample of the smallest
    max(|f_1|, |f_2|) among those each saw (``points``, ``seen``: eight views; both
    conditions defined) and its sides' samples near the domain boundary. Only the cells a
    level keeps ask: computed for every cell of a first level (16 branches × 160²), this
    was a fifth of a coupling-2 solve."""
    sizes = []
    for part in seen:
        values = part[at]
        sizes.append(np.where(_both(np.isfinite(values)), _larger(values), np.inf))
    best, smallest = _smallest([part[at] for part in points], sizes)
    edge_best, edge_size = near_boundary.best_at(at)
    return np.where((edge_size < smallest)[..., None], edge_best, best)


def _local_minima(branch: np.ndarray, low: np.ndarray, width: np.ndarray, value: np.ndarray,
                  origin: np.ndarray) -> np.ndarray:
    """Which cells (lower corners ``low``, sides ``width``, on branches ``branch``) have a
    ``value`` no larger than any cell of the same branch that shares a side or a corner
    with them, on the lattice of the level's cell size from ``origin``; cells of another
    size or off that lattice (a strip's shrunk window) always count as minima.
    O(C log C) for C cells.

    Where the two conditions' zero curves run within a cell of each other over a long
    arc, every cell along it stays suspect at every level, and a Newton start from each
    of them cost most of the solve (issue 25: 9/N28 drawn in a small box, 125 749
    suspect cells at the last level, 57 of 89 s in Newton). A common zero of f_1 and f_2
    is a minimum of the cells' distance from one (:func:`_classify`), so the cell holding
    it or a neighbour of it is a local minimum, and Newton starts there."""
    common = np.median(width, axis=0)  # the level's cell size; other sizes came from strips
    position = (low - origin) / common
    index = np.round(position).astype(np.int64)
    regular = (np.abs(position - index) < 1e-6).all(axis=1) & (np.abs(width / common - 1) < 1e-6).all(axis=1)
    base = np.int64(1) << 21  # cell indices stay below GRID · SPLIT^DEPTH < 2^21
    key = (branch.astype(np.int64) * base + index[:, 0]) * base + index[:, 1]
    key[~regular] = -1 - np.arange(np.count_nonzero(~regular))  # no neighbours
    order = np.argsort(key)
    sorted_keys, sorted_values = key[order], value[order]
    minimum = np.ones(len(key), bool)
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            if dx == dy == 0:
                continue
            at = np.searchsorted(sorted_keys, key + dx * base + dy)
            found = at < len(key)
            found[found] = sorted_keys[at[found]] == (key + dx * base + dy)[found]
            minimum[found] &= value[found] <= sorted_values[at[found]]
    return minimum | ~regular


def _strip_cells(cells: Cells, grid: np.ndarray, window: np.ndarray, strip: list[np.ndarray]) -> Cells:
    """The windows shrunk to the strip crossing them: the bounding box of the points found
    on the window's edges (``strip``, eight arrays (C, n, n, 2), NaN where none: the strip's
    two ends, and where the failing step changes on an edge no strip crosses, which can
    only widen the box), the window's whole extent along an axis where those points do
    not spread. Shrinking, rather than splitting the window like other cells, keeps one
    cell per window and level: split SPLIT × SPLIT, a strip narrower than a sub-cell
    crosses SPLIT of them (measured on tests/regressions/9-B25-narrow-strip.json: 1024
    windows, then 4088, 16352, and 39152 suspect cells inside the strip; Newton from them
    took 6.5 s)."""
    c, i, j = np.nonzero(window)
    low, high = grid[c, i, j], grid[c, i + 1, j + 1]
    ends = np.stack([part[c, i, j] for part in strip], axis=1)
    with np.errstate(invalid="ignore"):
        end_low, end_high = np.nanmin(ends, axis=1), np.nanmax(ends, axis=1)
    spread = end_high > end_low
    return Cells(cells.branch[c], np.where(spread, end_low, low), np.where(spread, end_high, high))


def _paired(compiled: CompiledSystem, roots_of_parameters: np.ndarray, signs: np.ndarray) -> np.ndarray:
    """Residuals at points of the √ plane (each on its own branch)."""
    return compiled.paired_residuals(roots_of_parameters**2, signs)


def _boundary(compiled, signs, sides: list[tuple]) -> list[tuple]:
    """Where the first failing step changes along each grid edge (first → second), found
    by bisection (BOUNDARY_STEPS steps) and kept on the side that fails later, with the
    values there: where the feasible domain begins on an edge with one end defined, and
    on an edge whose two ends fail at different steps, a point of a strip of the domain
    between them if there is one (values NaN if not). For such a strip, also where it ends
    (a second bisection towards the later-failing end). NaN for edges whose ends fail at
    the same step, or are both defined, and for ends of strips not found. Last, on an edge
    with one end defined, EDGE_SAMPLES points between the boundary and that end with the
    values there, at distances from the boundary growing like k² (uniform in the square
    root of the distance, in which the conditions are smooth).

    The conditions change like the square root of the distance from the boundary, so
    between the boundary and the nearest grid point they can dip to 0 and back unseen
    (issue 25, seed 41: 9/N27 drawn at a domain edge, a mode 0.0125 inside the edge line
    of s1,11 in a cell 0.058 tall; f_2 is 3.5 on the boundary, 3.4 at the corners and
    negative on an interval 0.004 wide beside the mode).

    ``sides``: (first, second, first_failures, second_failures) of each set of grid edges
    (the edges along each axis of a level), searched together — one bisection for all
    (sequential rounds halved against a search per axis, the same values) — and returned
    apart: (points, values, far, inner samples) per set."""
    selected = []
    for first, second, first_failures, second_failures in sides:
        index = np.nonzero(first_failures != second_failures)
        first_later = (first_failures[index] > second_failures[index])[:, None]
        selected.append((index, np.where(first_later, first[index], second[index]),
                         np.where(first_later, second[index], first[index]),
                         np.maximum(first_failures[index], second_failures[index]), signs[index[0]]))
    beyond, earlier, later_failure, edge_signs = (np.concatenate([part[k] for part in selected])
                                                  for k in range(1, 5))
    if len(later_failure):  # else nothing to search (and 30 rounds of empty evaluations to spare)
        later, values, far, inner = _boundary_points(compiled, edge_signs, beyond, earlier, later_failure)
    found, start = [], 0
    for (first, _, _, _), (index, *_) in zip(sides, selected, strict=True):
        mine = slice(start, start + len(index[0]))
        start = mine.stop
        points, far_points = np.full(first.shape, np.nan), np.full(first.shape, np.nan)
        at_points = np.full((*first.shape[:-1], 2), np.nan)
        if len(later_failure):
            points[index], at_points[index], far_points[index] = later[mine], values[mine], far[mine]
        samples = _EdgeSamples.empty(first.shape[:-1])
        edges = np.flatnonzero(inner[0][mine]) if len(later_failure) else []
        if len(edges):
            samples.record(tuple(axis[edges] for axis in index), inner[1][mine][edges], inner[2][mine][edges])
        if len(later_failure):  # the boundary point's values join the samples' range
            samples.low[index] = np.fmin(samples.low[index], values[mine])
            samples.high[index] = np.fmax(samples.high[index], values[mine])
        found.append((points, at_points, far_points, samples))
    return found


def _boundary_points(compiled, edge_signs, beyond, earlier, later_failure):
    """For grid edges from ``beyond`` (failing later, at ``later_failure``) to ``earlier``
    (:func:`_boundary`): where the failing step changes, f there, where a strip found
    there ends (NaN where none), and (which edges have a defined end, their EDGE_SAMPLES
    points, f there)."""
    later = _bisection(compiled, edge_signs, beyond, earlier, lambda failure: failure >= later_failure)
    values = _paired(compiled, later, edge_signs)
    feasible = len(compiled.plan.steps)
    far = np.full(later.shape, np.nan)
    in_strip = np.flatnonzero((later_failure < feasible) & np.isfinite(values).all(axis=-1))
    if len(in_strip):
        far[in_strip] = _bisection(compiled, edge_signs[in_strip], later[in_strip], beyond[in_strip],
                                   lambda failure: failure == feasible)
    edge = later_failure == feasible
    fractions = (np.arange(1, EDGE_SAMPLES + 1) / (EDGE_SAMPLES + 1)) ** 2
    samples = later[edge, None] + (beyond[edge] - later[edge])[:, None] * fractions[:, None]
    sampled = np.full((len(later), EDGE_SAMPLES, 2), np.nan)
    if edge.any():
        sampled[edge] = _paired(compiled, samples.reshape(-1, 2),
                                np.repeat(edge_signs[edge], EDGE_SAMPLES, axis=0)).reshape(samples.shape)
    points = np.full((len(later), EDGE_SAMPLES, 2), np.nan)
    points[edge] = samples
    return later, values, far, (edge, points, sampled)


def _bisection(compiled, signs, good, bad, is_good):
    """BOUNDARY_STEPS bisection steps on segments from ``good`` to ``bad`` (points of the
    √ plane, shape (K, 2)), ``is_good`` deciding on first failing steps; the good ends."""
    for _ in range(BOUNDARY_STEPS):
        middle = (good + bad) / 2
        ok = is_good(compiled.paired_residuals_and_failures(middle**2, signs)[1])[:, None]
        good = np.where(ok, middle, good)
        bad = np.where(ok, bad, middle)
    return good


def _smallest(points: list[np.ndarray], sizes: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Elementwise over parallel arrays of candidates: the point (..., 2) of the smallest
    size (...), the first of equals as ``argmin`` takes it, and that size — without
    stacking them (a reduction over a stacked small axis is slow in numpy)."""
    best, smallest = points[0], sizes[0]
    for at, size in zip(points[1:], sizes[1:], strict=True):
        better = size < smallest
        best, smallest = np.where(better[..., None], at, best), np.where(better, size, smallest)
    return best, smallest


def _both(pairs: np.ndarray) -> np.ndarray:
    """Both conditions' flags, shape (..., 2) → (...) (on a last axis of two, an
    elementwise and is ten times faster than ``all(axis=-1)``)."""
    return pairs[..., 0] & pairs[..., 1]


def _larger(values: np.ndarray) -> np.ndarray:
    """max(|f_1|, |f_2|), shape (..., 2) → (...), NaN where either is."""
    return np.maximum(np.abs(values[..., 0]), np.abs(values[..., 1]))


def _classify(values: np.ndarray, near_boundary: _CellEdgeSamples) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the values at the cells' corners, (C, n + 1, n + 1, 2) with NaN where
    undefined, and those its sides' points on and near the domain boundary saw
    (``near_boundary``):
    cells where both conditions change sign; cells where both zero sets may pass (a sign
    change, or the smallest |f_k| within the spread of f_k over the 3 × 3 neighbouring
    cells); and each cell's distance from a common zero, measured by the conditions that
    keep their sign on it: the largest, over those, of the smallest |f_k| seen (0 where
    both change sign).

    Only the conditions that keep their sign measure it: along the zero curve of f_1, the
    |f_1| seen at a cell's corners depends only on how near the corners fall to the curve,
    and where f_2 touches 0 without changing sign (a double root inside the domain) that
    noise hid the cell of the root: max(|f_1|, |f_2|) was not a local minimum there
    (issue 25, seed 35: 9/N2 (s1,10, s1,12) = (25, 10), f_2 ≥ 0 with an isolated zero,
    no Newton start on its branch)."""
    # over each cell's four corners, NaN (undefined) ignored
    low = np.fmin(_over_corners(np.fmin, values), near_boundary.low)
    high = np.fmax(_over_corners(np.fmax, values), near_boundary.high)
    smallest = _over_corners(np.fmin, np.abs(values))
    # where the boundary samples keep one sign, their smallest |f| is their low or -high
    # (where they change sign, so does the cell, and its smallest |f| is not used)
    boundary_smallest = np.where(near_boundary.low > 0, near_boundary.low, np.maximum(-near_boundary.high, 0.0))
    smallest = np.fmin(smallest, boundary_smallest)
    changes = (low <= 0) & (high >= 0)
    size = (1, 3, 3, 1)
    spread = maximum_filter(high, size=size, mode="nearest") - minimum_filter(low, size=size, mode="nearest")
    spread = np.where(np.isfinite(spread), spread, 0.0)
    near = changes | (smallest <= spread)
    distance = np.where(changes, 0.0, smallest)
    return _both(changes), _both(near), np.maximum(distance[..., 0], distance[..., 1])


def _newton(compiled: CompiledSystem, branches: np.ndarray, start: np.ndarray, branch: np.ndarray):
    """Damped Newton in (u, v) from every start, all at once; the distinct converged points,
    and the stalled ones."""
    if len(branch) == 0:
        return [], (np.zeros((0, 2)), np.zeros(0, int))
    signs = branches[branch]
    x = start.copy()
    f = compiled.paired_residuals(x, signs)
    # a point whose step fails (no usable Jacobian, or no halving lowers |f|) would repeat
    # the same failed step at every iteration: it leaves (9/N18: 105 411 of 144 848 starts
    # stalled so, and retrying them took 26 of the solve's 36 s)
    stuck = np.zeros(len(x), bool)
    for _ in range(NEWTON_STEPS):
        norm = np.max(np.abs(f), axis=1)
        active = np.isfinite(norm) & (norm > 1e-14) & ~stuck
        if not active.any():
            break
        xa, fa, sa = x[active], f[active], signs[active]
        delta, usable = _newton_step(compiled, xa, fa, sa)
        scale = np.ones(len(xa))
        pending = usable.copy()
        old = np.max(np.abs(fa), axis=1)
        for _ in range(12):
            if not pending.any():
                break
            index = np.flatnonzero(pending)
            trial = xa[index] + scale[index, None] * delta[index]
            trial_values = compiled.paired_residuals(trial, sa[index])
            new = np.max(np.abs(trial_values), axis=1)
            better = np.isfinite(new) & (new < old[index]) & (trial > 0).all(axis=1)
            xa[index[better]], fa[index[better]] = trial[better], trial_values[better]
            pending[index[better]] = False
            scale[pending] /= 2
        x[active], f[active] = xa, fa
        stuck[np.flatnonzero(active)[pending | ~usable]] = True
    norm = np.max(np.abs(f), axis=1)
    good = np.isfinite(norm) & (norm < CANDIDATE_TOLERANCE)
    roots = distinct_candidates(x[good], branches[branch[good]])
    stalled = np.flatnonzero(np.isfinite(norm) & (norm >= CANDIDATE_TOLERANCE) & (norm < STALLED_TOLERANCE))
    return roots, (x[stalled], branch[stalled])


def _newton_step(compiled: CompiledSystem, x: np.ndarray, f: np.ndarray, signs: np.ndarray):
    """Newton steps -J⁻¹f with a finite-difference Jacobian (:func:`_jacobian`), and which
    points have a usable Jacobian."""
    jacobian = _jacobian(compiled, x, f, signs)
    usable = np.isfinite(jacobian).all(axis=(1, 2))
    usable[usable] = np.abs(np.linalg.det(jacobian[usable])) > 0
    delta = np.zeros_like(x)
    if usable.any():
        delta[usable] = np.linalg.solve(jacobian[usable], -f[usable][:, :, None])[:, :, 0]
    return delta, usable


def _jacobian(compiled: CompiledSystem, x: np.ndarray, f: np.ndarray, signs: np.ndarray) -> np.ndarray:
    """The Jacobians ∂(f_1, f_2)/∂(u, v) at the points ``x`` (K, 2) with values ``f``, by
    central differences (one-sided next to the domain boundary): shape (K, 2, 2)."""
    step = 1e-7 * np.maximum(np.abs(x), 1.0)
    jacobian = np.empty((len(x), 2, 2))
    for axis in range(2):
        shifted = x.copy()
        shifted[:, axis] += step[:, axis]
        forward = compiled.paired_residuals(shifted, signs)
        shifted[:, axis] -= 2 * step[:, axis]
        backward = compiled.paired_residuals(shifted, signs)
        h = step[:, axis, None]
        central = (forward - backward) / (2 * h)
        one_sided = np.where(np.isfinite(forward), (forward - f) / h, (f - backward) / h)
        jacobian[:, :, axis] = np.where(np.isfinite(central), central, one_sided)
    return jacobian


def shared_curve(compiled: CompiledSystem, branches: np.ndarray, roots) -> tuple[np.ndarray, np.ndarray] | None:
    """A path of common zeros of the two closure conditions, if they share a curve: the
    root and CURVE_STEPS points continued from it ``(points (n, 2), branch)``, else None.

    Two conditions that share a curve have a continuum of common zeros, and Newton from
    every suspect cell along it converges to a different one (issue 25's 9/N18 instance
    drawn with four joints at one point: 450 066 distinct roots on the line s2,5 = 2,
    whose configurations took minutes to sort into "modes"). Isolated roots are few, so
    only a branch with more than CROWDED_ROOTS distinct roots is examined, at
    CURVE_SAMPLES of them: at a root of a shared curve the Jacobian has rank 1 and its
    kernel is the curve's tangent; the path steps along it and returns to f = 0 by
    minimum-norm Gauss–Newton steps, each point ending within CANDIDATE_TOLERANCE. An
    isolated root where the curves touch also has rank 1, but there the continued points
    keep a residual of order step², and the test fails. The caller verifies the path's
    configurations (distinct real configurations along a path: the linkage moves)."""
    if not roots:
        return None
    values = np.array([value for value, _ in roots])
    table = np.array([branch for _, branch in roots])
    kinds, which, counts = np.unique(table, axis=0, return_inverse=True, return_counts=True)
    for kind in np.flatnonzero(counts > CROWDED_ROOTS):
        mine = values[which.reshape(-1) == kind]
        for x0 in mine[np.linspace(0, len(mine) - 1, CURVE_SAMPLES).astype(int)]:
            path = _continued(compiled, kinds[kind], x0)
            if path is not None:
                return path, kinds[kind]
    return None


def _continued(compiled: CompiledSystem, signs: np.ndarray, x0: np.ndarray) -> np.ndarray | None:
    """``x0`` and CURVE_STEPS points continued from it along the kernel of the Jacobian
    (steps of CURVE_STEP · |x0|), or None where the Jacobian has full rank or a point
    does not return to the zeros (:func:`shared_curve`)."""
    signs = signs[None, :]
    f0 = compiled.paired_residuals(x0[None, :], signs)
    jacobian = _jacobian(compiled, x0[None, :], f0, signs)[0]
    if not np.isfinite(jacobian).all():
        return None
    _, sigma, right = np.linalg.svd(jacobian)
    if sigma[1] > RANK_TOLERANCE * max(sigma[0], 1e-300):
        return None
    step = CURVE_STEP * np.linalg.norm(x0)
    x = x0 + step * np.arange(1, CURVE_STEPS + 1)[:, None] * right[1]
    many = np.repeat(signs, len(x), axis=0)
    for _ in range(NEWTON_STEPS):
        f = compiled.paired_residuals(x, many)
        if not np.isfinite(f).all() or np.abs(f).max() < CANDIDATE_TOLERANCE:
            break
        # rank 1 on the curve: the tiny singular value is noise, so cut it off
        inverse = np.linalg.pinv(_jacobian(compiled, x, f, many), rtol=RANK_TOLERANCE)
        x = x - (inverse @ f[:, :, None])[:, :, 0]
    f = compiled.paired_residuals(x, many)
    moved = np.linalg.norm(x - x0, axis=1)
    if not np.isfinite(f).all() or np.abs(f).max() >= CANDIDATE_TOLERANCE or (moved < step / 2).any():
        return None
    return np.concatenate([x0[None, :], x])


#: Samples along one parameter when looking for lines of the domain's boundary.
RIDGE_SAMPLES = 2000
#: On an edge line, a root of one condition is a candidate where the other is within
#: this (relative to the larger of the two conditions' sizes along the line) of 0.
EDGE_COMMON = 1e-6


def ridge_roots(compiled: CompiledSystem, branches: np.ndarray, upper: tuple[float, float]) -> list:
    """Candidates on the lines p = p* where a free-sign triangle whose radicand depends on
    one parameter p only is flat: ridges, where the radicand touches 0 from below, so
    that the branch is defined only on that line; and edges, where the radicand crosses
    0, so that the line bounds the feasible domain.

    Ridges: issue 25's seventh run, 9/N2 drawn at a double root (seed 28), its one mode at
    (s1,10, s1,12) = (13, 1) where P10 P3 P4 is flat; no cell of the plane has a defined
    corner there, and the mode was missed. Edges: a mode on such a line is found by the
    plane search only as a boundary sample polished on the links, which at a singular
    mode stops 1e-5 away (issue 25, seed 35: 9/N28 drawn at a double root, where
    P9 P1 P2 is flat on s1,9 = 5 and one condition vanishes along the whole line: three
    modes there 1e-5 from msolve's); on the line itself they are roots of one variable.

    For each parameter, the free-sign radicands that the other parameter does not change
    (two vectorised evaluations along the parameter, at two values of the other) are
    searched for a touch (bounded Brent on the radicand's local maxima within
    TOUCH_SEARCH of 0, as for one parameter) and for crossings (Brent); on each line
    found, with that triangle flat, both conditions are sampled along the other
    parameter (:func:`_roots_on_line`). Every candidate is verified by the caller.
    Cost: 4 · RIDGE_SAMPLES evaluations per branch, plus RIDGE_SAMPLES per line found."""
    lines: dict[tuple, tuple[float, bool]] = {}  # (along, flat branch, rounded value): (value, edge)
    zeros: dict[tuple, list[tuple[float, bool]]] = {}
    for along in (0, 1):
        other = 1 - along
        line = np.linspace(math.sqrt(upper[along]) * 1e-6, math.sqrt(upper[along]), RIDGE_SAMPLES) ** 2
        profiles = []
        for fraction in (0.3, 0.7):
            points = np.empty((RIDGE_SAMPLES, 2))
            points[:, along], points[:, other] = line, fraction * upper[other]
            profiles.append(compiled.failure_profile(points, branches)[2])  # (B, N, free)
        first, second = profiles
        difference = np.where(np.isfinite(first - second), np.abs(first - second), 0.0).max(axis=1)
        size = np.where(np.isfinite(first), np.abs(first), 0.0).max(axis=1)
        unchanged = (difference <= 1e-9 * size) & (size > 0)  # (B, free); a step never defined has size 0
        for b, k in zip(*np.nonzero(unchanged), strict=True):
            margin_at = _radicand_along(compiled, branches[b], k, along, 0.3 * upper[other])
            flat = branches[b].copy()
            flat[k] = 0
            profile = first[b, :, k]
            key = (along, k, profile.tobytes())  # branches differing in later signs share it
            if key not in zeros:
                zeros[key] = _flat_values(profile, line, margin_at)
            for value, edge in zeros[key]:
                lines.setdefault((along, tuple(flat), round(value, 12)), (value, edge))
    return _roots_on_lines(compiled, lines, upper)


def _radicand_along(compiled: CompiledSystem, branch: np.ndarray, k: int, along: int, at_other: float):
    """Free-sign radicand ``k`` on ``branch`` as a function of parameter ``along``, the
    other parameter held at ``at_other``."""
    def margin(value: float) -> float:
        point = np.empty((1, 2))
        point[0, along], point[0, 1 - along] = value, at_other
        return float(compiled.failure_profile(point, branch[None, :])[2][0, 0, k])
    return margin


def _flat_values(margin: np.ndarray, line: np.ndarray, margin_at) -> list[tuple[float, bool]]:
    """Where a radicand sampled as ``margin`` along ``line`` (and evaluated by
    ``margin_at``) is 0: ``(value, False)`` where its local maximum touches 0 from below
    (within TOUCH_TOLERANCE, searched where within TOUCH_SEARCH), ``(value, True)`` where
    it crosses 0 between two samples (Brent)."""
    values = []
    inner = margin[1:-1]
    peaks = np.flatnonzero((inner >= margin[:-2]) & (inner >= margin[2:]) & (inner < 0)
                           & (inner > -TOUCH_SEARCH)) + 1
    for i in peaks[:4]:
        best = minimize_scalar(lambda value: -margin_at(value) if math.isfinite(margin_at(value)) else 10.0,
                               bounds=(line[i - 1], line[i + 1]), method="bounded",
                               options={"xatol": 1e-14 * line[i + 1]})
        if best.success and best.fun <= TOUCH_TOLERANCE:
            values.append((float(best.x), False))
    finite = np.isfinite(margin[:-1]) & np.isfinite(margin[1:])
    for i in np.flatnonzero(finite & (margin[:-1] * margin[1:] < 0))[:4]:
        try:
            values.append((brentq(margin_at, line[i], line[i + 1], xtol=1e-15 * line[i + 1], rtol=1e-15), True))
        except ValueError:  # not finite inside the bracket
            continue
    return values


def _roots_on_lines(compiled: CompiledSystem, lines: dict[tuple, tuple[float, bool]],
                    upper: tuple[float, float]) -> list:
    """Candidates on each line ``(along, branch, _): (value, edge)`` (parameter ``along``
    = ``value``, branch ``branch``, the flat triangle's sign 0): the sign changes of
    either condition along the other parameter (RIDGE_SAMPLES samples, every line in one
    evaluation), refined by Brent. On an edge line only sign changes beside one of the
    other condition, or anywhere if the other vanishes all along the line (within
    EDGE_COMMON of the larger size), kept where the other is within that of 0 at the
    root too; a condition that vanishes all along the line (sign changes of rounding
    noise) has no roots of its own searched."""
    if not lines:
        return []
    keys = list(lines)
    points = np.empty((len(keys), RIDGE_SAMPLES, 2))
    for n, (along, _, _) in enumerate(keys):
        points[n, :, along] = lines[keys[n]][0]
        points[n, :, 1 - along] = np.linspace(math.sqrt(upper[1 - along]) * 1e-6, math.sqrt(upper[1 - along]),
                                              RIDGE_SAMPLES) ** 2
    signs = np.repeat(np.array([branch for _, branch, _ in keys]), RIDGE_SAMPLES, axis=0)
    tables = compiled.paired_residuals(points.reshape(-1, 2), signs).reshape(len(keys), RIDGE_SAMPLES, -1)
    found = []
    for n, (along, branch, _) in enumerate(keys):
        found += _roots_on_line(compiled, np.array(branch), along, points[n], tables[n], common=lines[keys[n]][1])
    return found


def _roots_on_line(compiled: CompiledSystem, branch: np.ndarray, along: int, points: np.ndarray,
                   table: np.ndarray, common: bool) -> list:
    """:func:`_roots_on_lines` on one line, sampled at ``points`` with values ``table``."""
    other = 1 - along
    grid = points[:, other]

    def conditions(q: float) -> np.ndarray:
        point = points[:1].copy()
        point[0, other] = q
        return compiled.paired_residuals(point, branch[None, :])[0]

    sizes = np.where(np.isfinite(table), np.abs(table), 0.0).max(axis=0)
    scale = EDGE_COMMON * sizes.max()
    found = []
    for c in range(table.shape[1]):
        if common and sizes[c] <= scale:
            continue
        changes = _sign_changes(table[:, c])
        if common and sizes[1 - c] > scale:  # the other condition must change sign beside
            beside = _sign_changes(table[:, 1 - c])
            near = np.zeros(len(grid) + 1, bool)
            for shift in (0, 1, 2):
                near[beside + shift] = True
            changes = changes[near[changes + 1]]
        for i in changes[:CROWDED_ROOTS]:
            try:
                root = brentq(lambda q, c=c: float(conditions(q)[c]), grid[i], grid[i + 1],
                              xtol=1e-14 * grid[i + 1], rtol=1e-15)
            except ValueError:
                continue
            if common and not abs(conditions(root)[1 - c]) <= scale:
                continue
            point = points[0].copy()
            point[other] = root
            found.append((point, branch))
    return found


def _sign_changes(column: np.ndarray) -> np.ndarray:
    """Indices i where the sampled ``column`` changes sign (or is 0) from i to i + 1."""
    return np.flatnonzero(np.isfinite(column[:-1]) & np.isfinite(column[1:]) & (column[:-1] * column[1:] <= 0))
