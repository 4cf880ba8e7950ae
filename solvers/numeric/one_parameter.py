"""The numeric backend's one-parameter root finder (coupling degree 1): every root of the
closure condition f(s) on every free-sign branch, with the rules that make it complete
on degenerate-prone instances (domain edges, windows narrower than the grid, tangential
roots, flat valleys, rounding noise, touching radicands, folds, critical values).

1. sample f on a grid uniform in the distance √s over (0, D²], D the sum of all link
   diameters (no two joints can be farther apart), all branches at once (numpy);
2. where neighbouring samples both fail, at different steps, a feasible window narrower
   than the grid may lie between them: re-sample there, level by level;
3. find the ends of the feasible domain (a triangle of zero area, where f stops being
   real) and add them to the samples; an end where f vanishes is a root;
4. roots with a sign change: Brent's method on each bracketing pair of samples (a bracket
   that hides an undefined gap is re-sampled finely instead);
5. roots without a sign change (tangential, or two roots in one cell): every local minimum
   of |f| is refined by bounded minimisation, and its cell re-sampled finely.

docs/numeric.md explains each rule with the miss that required it.
"""

from __future__ import annotations

import math
from itertools import combinations
from typing import NamedTuple

import numpy as np

from baranov.closure import CompiledSystem, sign_branches
from baranov.closure.evaluate import Profile
from baranov.planner import Plan, parameter_name
from baranov.scene import Scene

from ..modes import MovableLinkageError, signs_text
from ..progress import report_stage
from .brent import UndefinedInside, brent_minimum, brent_root
from .lockstep import Samples, Search, Together, paired_profile, run_lockstep

#: A local minimum of |f| below this but not below 1e-7 (a root where f is not smooth:
#: f ≈ c√|s − s0| at a singular mode, issue 25's 7/N3 instance at s1,9 = 13 with P6 = P9
#: and P8 P3 P4 in line) is polished on the link constraints and verified.
NEAR_ROOT = 1e-4

#: A local minimum of |f| between samples is re-sampled this finely: two close simple
#: roots inside one cell show no sign change on the coarse grid (a saved regression:
#: tests/regressions/9-close-roots.json, roots 3636 and 3637.34 in a cell 26 wide).
REFINEMENT = 400


#: Feasible windows narrower than the grid are searched where neighbouring samples fail
#: at different steps, WINDOW_SAMPLES at a time, WINDOW_DEPTH levels deep (a saved
#: regression: tests/regressions/9-missed-2.json, a window 0.6 wide in a cell 7 wide).
WINDOW_SAMPLES = 64
WINDOW_DEPTH = 6
#: More window cells than this at one level means the failing step flickers with rounding
#: noise (a radicand at 0 along a stretch): refining further multiplied the cells by up to
#: 64 per level (issue 25's 9/N9 drawn at a double root: 215 million samples at the fourth
#: level, 24 GB, the worker killed), so the refinement stops there.
WINDOW_CROWD = 4096


def critical_values(scene: Scene, plan: Plan) -> list[float]:
    """Parameter values where a triangle of the plan with the parameter as one side and
    two known sides d_a, d_b is flat: (d_a ± d_b)². There a radicand vanishes, the
    feasible domain may end or shrink to a point, and a root may sit on it — the double
    root T = 49 of thesis §5.1.3.1, where both free-sign triangles are flat and the
    feasible domain is that single value, which sampling cannot find."""
    parameter = frozenset(plan.parameters[0])
    values = []
    for step in plan.steps:
        sides = [frozenset(pair) for pair in combinations(step.triangle, 2)]
        if parameter in sides:
            known = [scene.known.get(side) for side in sides if side != parameter]
            if all(value is not None for value in known):
                a, b = (math.sqrt(float(value)) for value in known)
                values += [(a - b) ** 2, (a + b) ** 2]
    return sorted(set(v for v in values if v > 0))


def roots_at_critical_values(compiled: CompiledSystem, branches: np.ndarray, values: list[float]):
    """The (value, branch) pairs among the critical values where the closure residual
    vanishes (relative 1e-9), on every branch and on every branch with its nearly flat
    free-sign triangles (relative radicand below FLAT_MARGIN) taken flat: the critical
    value, (a ± b)² in floats, can miss the exact one by an ulp, and a radicand that
    vanishes there then comes out negative (issue 25's 7/N1 instance: a mode at s4,5 = 2,
    where one radicand turns positive as another turns negative — the feasible domain is
    that single point)."""
    if not values:
        return []
    points = np.array(values)[:, None]
    _, _, margins = compiled.failure_profile(points, branches)  # (B, N, free)
    flat = np.abs(np.nan_to_num(margins, nan=1.0)) < FLAT_MARGIN
    variants = np.where(flat, 0, branches[:, None, :])  # (B, N, free)
    tried = [np.unique(np.concatenate([branches, variants[:, n]]), axis=0) for n in range(len(values))]
    rows = np.repeat(np.array(values), [len(signs) for signs in tried])
    residuals = np.abs(compiled.paired_residuals(rows[:, None], np.concatenate(tried))[:, 0])  # all in one evaluation
    closing = np.split(residuals < 1e-9, np.cumsum([len(signs) for signs in tried])[:-1])
    return [(np.array([value]), signs[b]) for value, signs, closes in zip(values, tried, closing, strict=True)
            for b in np.flatnonzero(closes)]


#: A free-sign triangle whose relative radicand is within FLAT_NOISE of 0 at FLAT_SAMPLES
#: grid samples or more is flat along its branch (:func:`_flat_along_branches`).
FLAT_NOISE = 1e-12
FLAT_SAMPLES = 16


def _flat_along_branches(branches: np.ndarray, margins: np.ndarray) -> np.ndarray:
    """``branches`` with sign 0 for each free-sign triangle that stays flat along the
    parameter (its radicand is 0 at FLAT_SAMPLES samples and at all but a twentieth of
    the samples where it is defined: a polynomial in the parameter that vanishes that
    often vanishes identically on the branch). Rounding then makes the radicand flip
    between ±1e-16, and the feasible domain between defined and undefined, at every
    sample: issue 25's 7/N3 instance drawn with P8, P3, P4 in line, whose alternative
    plan keeps s3,8 constant on a branch, ran for over 300 s in edge searches and Brent
    brackets across that noise. Flat, the branch is one smooth curve. A triangle flat on
    a stretch only (an earlier step clamped at a fold: issue 25's 9/N12 small box, seed
    29, P11 P4 P3 flat for s1,10 in [4.8, 19.4] and not below, where six modes lie) keeps
    its ±1 branches beside the flat one."""
    with np.errstate(invalid="ignore"):
        flat_samples = (np.abs(margins) < FLAT_NOISE).sum(axis=1)  # NaN (undefined) compares False
    flat = flat_samples >= FLAT_SAMPLES
    if not flat.any():
        return branches
    defined = np.isfinite(margins).sum(axis=1)
    everywhere = flat & (flat_samples >= 0.95 * defined)
    return np.unique(np.concatenate([np.where(everywhere, 0, branches), np.where(flat, 0, branches)]), axis=0)


def _require_isolated_roots(compiled: CompiledSystem, branches: np.ndarray, grid: np.ndarray,
                            table: np.ndarray) -> None:
    """Raise :class:`MovableLinkageError` where a branch's closure residual is within
    FLAT_NOISE of 0 at FLAT_SAMPLES samples or more (a polynomial condition that vanishes
    that often vanishes identically: a continuum of configurations). Issue 25's 7/N2
    instance rotates about P1 = P6 = P8; the bracketing of its rounding noise ran for over
    300 s."""
    with np.errstate(invalid="ignore"):
        vanishing = np.abs(table) < FLAT_NOISE  # NaN (undefined) compares False
    if (vanishing.sum(axis=1) >= FLAT_SAMPLES).any():
        b = int(np.argmax(vanishing.sum(axis=1)))
        where = grid[vanishing[b]]
        name = parameter_name(compiled.plan.parameters[0])
        raise MovableLinkageError(
            f"the linkage moves with these dimensions: the closure condition vanishes for {name} from "
            f"{where.min():.6g} to {where.max():.6g} (signs {signs_text(branches[b])}), "
            "a continuum of configurations rather than isolated assembly modes")


def one_parameter_roots(compiled: CompiledSystem, branches: np.ndarray, upper: float, samples: int,
                         undecided: list[str], deadline: float = math.inf):
    """Candidate roots ``(array([s]), branch)`` of the closure condition on every branch,
    and the approximate roots to polish on the link constraints; a sentence for each
    stretch where f is flat to rounding, and for the branches left at the ``deadline``
    (``time.monotonic()``), is appended to ``undecided``. The branches are searched side
    by side (:func:`~.lockstep.run_lockstep`: one evaluation of the plan per round for
    all their pending searches)."""
    grid = (np.linspace(0, math.sqrt(upper), samples + 1)[1:]) ** 2
    # below the first sample, samples even in √s down to joints 1e-7 of the largest
    # distance apart (closer, they coincide to same_mode's resolution: coincidence.py):
    # a root at s5,11 = 5.8e-7 (issue 25's 9/N7, P11 and P5 7.6e-4 apart) lay below the
    # first sample, 1e-4
    below = grid[0] * 4.0 ** -np.arange(EDGE_LEVELS, 0, -1)
    grid = np.concatenate([below[below >= 1e-14 * upper], grid])
    coarse = compiled.profile(grid[:, None], branches)
    flattened = _flat_along_branches(branches, coarse.margins)
    if flattened.shape != branches.shape or (flattened != branches).any():
        branches = flattened
        coarse = compiled.profile(grid[:, None], branches)
    _require_isolated_roots(compiled, branches, grid, coarse.residuals[:, :, 0])
    tasks = [(_branch_roots(compiled, grid, Profile(*(part[b] for part in coarse)), branch, RESOLUTION * upper), branch)
             for b, branch in enumerate(branches)]

    def progress(finished: int, total: int) -> None:
        report_stage(f"numeric: {finished} of {total} sign branches searched")

    results, _ = run_lockstep(paired_profile(compiled), tasks, deadline, progress)
    candidates, near_roots, left = [], [], []
    for branch, result in zip(branches, results, strict=True):
        if result is None:
            left.append(signs_text(branch))
            continue
        found, near, sentences = result
        candidates += found
        near_roots += near
        undecided += sentences
    if left:
        undecided.append(f"branches {', '.join(left)}: not searched, the time limit was reached")
    return candidates, near_roots


def _branch_roots(compiled: CompiledSystem, grid: np.ndarray, coarse: Profile, branch: np.ndarray,
                  resolution: float):
    """Lock-step search: the candidates of one branch from its ``coarse`` samples on
    ``grid``, the approximate roots to polish and the sentences for ``undecided``
    (:func:`one_parameter_roots`; ``resolution``: the parameter's, RESOLUTION × its upper
    bound). The roots of f and the one-point domains (folds, touching and crossing
    radicands) are searched side by side."""
    points, values, narrow = yield from _with_windows(grid, coarse, len(compiled.plan.steps))
    points, values, edges = yield from _with_edges(points, values)
    (roots, near, sentences), *one_point = yield Together([
        _roots_of_condition(compiled, points, values, edges, branch, resolution),
        _roots_at_folds(branch, edges),
        _roots_at_touching_radicands(compiled, branch, grid, coarse.failures, coarse.radicands),
        _roots_at_crossing_radicands(branch, narrow)])
    candidates = [(np.array([root]), branch) for root in roots] + [found for part in one_point for found in part]
    return candidates, [(np.array([x]), branch) for x in near], sentences


def _roots_of_condition(compiled: CompiledSystem, points: np.ndarray, values: np.ndarray,
                        edges: list[tuple[float, float]], branch: np.ndarray, resolution: float):
    """Lock-step search: the roots of f on one branch from its samples (windows and edges
    included), the approximate roots to polish, and the sentences on flat valleys and
    noise stretches: roots at edges, :func:`_scan`, the cells next to roots and around
    minima re-sampled (side by side), flat valleys and noise stretches merged."""
    roots = [edge for edge, value in edges if abs(value) < 1e-7]
    scans = [(yield from _scan(points, values, resolution))]
    cells = _next_to_roots(points, roots + scans[0].roots) + _suspicious_minima(points, values)[:MAX_MINIMA]
    scans += yield Together([_refined_scan(low, high, resolution) for low, high in cells])
    roots += [root for scan in scans for root in scan.roots]
    near = [x for scan in scans for x in scan.near]
    noise = [stretch for scan in scans for stretch in scan.noise]
    roots, valleys = yield from _merged_flat_valleys(roots, resolution)
    # one sentence per stretch: around one singular mode the runs of noise roots give
    # overlapping valleys (issue 25's 7/N1 double-root 131, seed 42: 88 sentences)
    valleys = [(low, high) for low, high, _ in _merged_stretches([(low, high, 0) for low, high in valleys])]
    stretches = _merged_stretches(noise)
    roots = _one_per_noise_stretch(roots, stretches)
    name = parameter_name(compiled.parameters[0])
    sentences = [f"{name} in [{low:.10g}, {high:.10g}] on branch {signs_text(branch)}: the closure condition "
                 "is flat to rounding there; reported as one mode (a singular mode, or modes closer than "
                 "floating point separates)" for low, high in valleys]
    sentences += [f"{name} in [{low:.10g}, {high:.10g}] on branch {signs_text(branch)}: the closure condition's "
                  f"sign is rounding noise there ({changes} sign changes); reported as one mode"
                  for low, high, changes in stretches
                  if not any(a <= low and high <= b for a, b in valleys)]  # said already
    return roots, near, sentences


def _refined_scan(low: float, high: float, resolution: float):
    """Lock-step search: :func:`_scan` of REFINEMENT samples over [low, high]."""
    fine = np.linspace(low, high, REFINEMENT)
    return (yield from _scan(fine, (yield from _values(fine)), resolution, refined=True))


def _values(points) -> Search:
    """Lock-step search: f at ``points`` (NaN where undefined), an array."""
    return (yield Samples(np.asarray(points, dtype=float))).residuals[:, 0]


def _value(reply: Profile) -> float:
    """f at the one point of a reply."""
    return float(reply.residuals[0, 0])


def _merged_stretches(stretches: list[tuple[float, float, int]]) -> list[tuple[float, float, int]]:
    """(low, high, sign changes) stretches merged where they overlap or the gap between
    them is narrower than the wider of the two (the coarse scan and the re-samplings
    meet the same noise in pieces)."""
    merged: list[list] = []
    for low, high, changes in sorted(stretches):
        if merged and low - merged[-1][1] <= max(high - low, merged[-1][1] - merged[-1][0]):
            merged[-1][1] = max(merged[-1][1], high)
            merged[-1][2] += changes
        else:
            merged.append([low, high, changes])
    return [(low, high, changes) for low, high, changes in merged]


def _one_per_noise_stretch(roots: list[float], stretches: list[tuple[float, float, int]]) -> list[float]:
    """``roots`` with those inside one stretch where f's sign is rounding noise replaced
    by the one nearest the stretch's middle: f cannot tell them apart, and the stretch is
    symmetric about a singular root to first order (as in :func:`_merged_flat_valleys`).
    Issue 25's 11/N57 drawn at a double root: five roots in s1,12 in [19.99968, 20.00023]
    (53 sign changes) around msolve's mode at 20, polished to five configurations of
    residual 4e-16 to 8e-9 in one valley of the rigid-link model too (flat to rounding
    5.6e-4 from the mode: multiplicity 4 or more), which the mode clusters then split at
    a "hump" into two modes. O(r · n) for r roots and n stretches."""
    kept = [root for root in roots if not any(low <= root <= high for low, high, _ in stretches)]
    for low, high, _ in stretches:
        inside = [root for root in roots if low <= root <= high]
        if inside:
            kept.append(min(inside, key=lambda root: abs(root - (low + high) / 2)))
    return sorted(kept)


#: Samples of f between two neighbouring roots, and of a flat stretch's extent.
VALLEY_SAMPLES = 64


def _merged_flat_valleys(roots: list[float], resolution: float = 0.0):
    """Lock-step search: ``roots`` with each run of neighbours between which |f| stays below FLAT_NOISE
    replaced by the middle of that flat stretch, and the stretches. Next to a singular
    mode of high multiplicity f ≈ c (s − s0)^m is flat to rounding over a whole stretch,
    its sign flips with the noise and every flip brackets a "root": issue 25's 9/N15
    (tests/regressions/9-N15-flat-valley.json) gave four modes between s8,10 = 31.9974
    and 32.0043 around the true one at 32, |f| < 1e-14 on [31.99, 32.01]. |f| is
    symmetric about s0 to first order, so the middle of the stretch where it stays below
    FLAT_NOISE is the estimate (31.99994 there). Where the noise is larger than FLAT_NOISE
    (next to a fold: 1e-8 on 9/N22) the modes are merged later, by
    :func:`~baranov.solvers.mode_clusters.merged_clusters`."""
    ordered = sorted(roots)
    roots = [r for n, r in enumerate(ordered) if n == 0 or r - ordered[n - 1] > 1e-12 * abs(r)]
    flat = yield Together([_flat(roots[n - 1], roots[n], resolution) for n in range(1, len(roots))])
    kept, valleys, start = [], [], 0
    for n in range(1, len(roots) + 1):
        if n < len(roots) and flat[n - 1]:
            continue
        if n - start > 1:
            level = _flat_level((yield from _values(
                _jittered(roots[start], roots[n - 1], resolution))))
            (low, high), (low_cut, high_cut) = yield from _flat_stretch(roots[start], roots[n - 1], level)
            # cut off by the domain on one side: the mode is at that edge, not in the middle
            # (issue 25's 9/N19 drawn at a double root: flat on [8.9899, 9], the domain ends
            # at 9, where the mode is; the middle, 8.99495, was a spurious mode on 2 branches)
            kept.append(low if low_cut and not high_cut else high if high_cut and not low_cut else (low + high) / 2)
            valleys.append((low, high))
        else:
            kept.append(roots[start])
        start = n
    return kept, valleys


def _jittered(low: float, high: float, resolution: float) -> np.ndarray:
    """The points at offsets JITTER × ``resolution`` (at most an eighth of the middle)
    from the middle of [low, high] (none where ``resolution`` is 0)."""
    if resolution <= 0:
        return np.zeros(0)
    middle = (low + high) / 2
    return middle + JITTER * min(resolution, abs(middle) / 8)


def _flat_level(jittered: np.ndarray) -> float:
    """The |f| below which f counts as flat around two roots: FLAT_NOISE, or, given f at
    the :func:`_jittered` points of their middle (the parameter's resolution), VALLEY_NOISE times f's own
    rounding noise there (its spread at offsets JITTER × resolution from the middle) if
    that is lower: a hump of 8e-13 between a double root at s2,7 = 5 and a simple one at
    5.0016916 is no noise where that spread is 1e-15 (issue 25, seed 38: 7/N1 collinear
    324, the two modes reported as one valley's middle)."""
    if len(jittered) == 0:
        return FLAT_NOISE
    return min(FLAT_NOISE, VALLEY_NOISE * float(np.ptp(jittered)))


def _flat(low: float, high: float, resolution: float = 0.0):
    """Lock-step search: whether |f| stays below the flat level (:func:`_flat_level`)
    between two roots. One evaluation."""
    jittered = _jittered(low, high, resolution)
    values = yield from _values(np.concatenate([np.linspace(low, high, VALLEY_SAMPLES), jittered]))
    values, jittered_values = values[:VALLEY_SAMPLES], values[VALLEY_SAMPLES:]
    return bool(np.isfinite(values).all() and (np.abs(values) <= _flat_level(jittered_values)).all())


#: Between two roots, |f| up to this many times its rounding noise is a flat valley.
VALLEY_NOISE = 100


def _flat_stretch(low: float, high: float, level: float = FLAT_NOISE):
    """Lock-step search: the stretch around [low, high] (flat) where |f| stays below
    ``level``, sampled outwards over windows of growing width, then across the last
    sample step twice more (to VALLEY_SAMPLES⁻³ of the last window: the middle of the
    stretch is the mode's estimate, and a coarse end moved it by 2e-4 on 9/N15); and for
    each end, whether the domain ends there (f undefined just beyond) rather than |f|
    rising. Returns ((low end, high end), (low cut, high cut)); both ends side by side."""
    (low_end, low_cut), (high_end, high_cut) = yield Together([_flat_end(-1, low, high - low, level),
                                                              _flat_end(1, high, high - low, level)])
    return (low_end, high_end), (low_cut, high_cut)


def _flat_end(direction: int, end: float, width: float, level: float):
    """Lock-step search: one end of :func:`_flat_stretch`, and whether it is cut."""
    for _ in range(8):
        end, width, inside, undefined = yield from _last_flat(end, direction, width, level)
        if not inside:
            break
    for _ in range(2):
        end, width, inside, finer = yield from _last_flat(end, direction, width / (VALLEY_SAMPLES - 1), level)
        undefined = finer if not inside else undefined
    return end, bool(undefined)


def _last_flat(start: float, direction: int, width: float, level: float = FLAT_NOISE):
    """Lock-step search: the last of VALLEY_SAMPLES samples from ``start`` over ``width``
    in ``direction`` before |f| first exceeds ``level``, whether none did (then the next
    window is 4 times wider), and whether the first sample that did is undefined (the
    domain's end)."""
    points = start + direction * np.linspace(0, width, VALLEY_SAMPLES)
    values = yield from _values(points)
    flat = np.abs(np.nan_to_num(values, nan=np.inf)) <= level
    if flat.all():
        return float(points[-1]), width * 4, True, False
    first = int(np.argmin(flat))
    return float(points[max(first - 1, 0)]), width, False, bool(np.isnan(values[first]))


#: A failing radicand whose coarse-grid local maximum is below −this (relative to the
#: squared largest side) is not searched for a touching point.
TOUCH_SEARCH = 1e-2
#: A radicand maximum above −this (relative) counts as touching 0: its triangle is flat.
TOUCH_TOLERANCE = 1e-12


def _roots_at_touching_radicands(compiled: CompiledSystem, branch: np.ndarray, grid: np.ndarray,
                                 failures: np.ndarray, radicands: np.ndarray):
    """Lock-step search: candidates where a free-sign radicand touches 0 from below: the
    branch's feasible domain there is a single point, which no sample can hit (joints in
    line: on 9/N6 the triangle P11 P1 P2 is flat only at s3,10 = 26 and its radicand ≈
    −c(s − 26)² around, docs/stability.md; thesis §5.1.3.1's T = 49 is the case with
    known sides, handled by :func:`critical_values`). At every local maximum of a failing
    free-sign radicand among the coarse samples (above −TOUCH_SEARCH, both neighbours
    failing at the same step, or at an earlier one up to where they fail at it:
    :func:`_failing_at`; a parabola through the three reaching near 0:
    :func:`_may_touch_zero`), the radicand is maximised (bounded Brent); where the
    maximum reaches −TOUCH_TOLERANCE the point is a candidate with that triangle flat
    (sign 0), verified like every other. The bumps are searched side by side."""
    free_index = {}
    for index, step in enumerate(compiled.plan.steps):
        if step.free_sign:
            free_index[index] = len(free_index)
    bumps = [i for i in _radicand_bumps(failures, radicands, len(compiled.plan.steps))
             if int(failures[i]) in free_index and radicands[i] >= -TOUCH_SEARCH]
    found = yield Together([_root_at_touching_radicand(branch, grid, failures, radicands, i, free_index[int(failures[i])])
                            for i in bumps])
    return [candidate for candidate in found if candidate is not None]


def _root_at_touching_radicand(branch: np.ndarray, grid: np.ndarray, failures: np.ndarray, radicands: np.ndarray,
                               i: int, k: int):
    """Lock-step search: the candidate of :func:`_roots_at_touching_radicands` at the
    bump at sample ``i`` of free-sign step ``k``, or None."""
    step = int(failures[i])
    sides = yield Together([_failing_at(step, float(grid[i]), float(grid[n]), int(failures[n]), float(radicands[n]))
                            for n in (i - 1, i + 1)])
    if None in sides:
        return None  # a bump next to a defined sample is a domain edge, the edge search's business
    (low, left), (high, right) = sides
    if not _may_touch_zero(np.array([low, grid[i], high]), np.array([left, radicands[i], right]), 1):
        return None

    def negative_margin(reply: Profile) -> float:
        margin = reply.margins[0, k]
        return -float(margin) if np.isfinite(margin) else 10.0  # |relative radicand| ≤ 3: 10 is "undefined"

    x, value, success = yield from brent_minimum(negative_margin, low, high, 1e-14 * high)
    if not (success and value <= TOUCH_TOLERANCE):
        return None
    flat = branch.copy()
    flat[k] = 0
    # another free-sign triangle may turn flat at the same point (a domain edge: issue
    # 25's 9/N21, where P11 P3 P4 touches flat at s8,10 = 10 exactly as P9 P5 P6 folds);
    # by a rounding error it fails there, so it is taken flat too
    margins = (yield Samples(np.array([x]), flat)).margins[0]
    flat[np.abs(np.nan_to_num(margins, nan=1.0)) < FLAT_MARGIN] = 0
    return np.array([float(x)]), flat


#: At most this many of the narrowest windows are searched for a one-point domain.
MAX_NARROW = 16


def _roots_at_crossing_radicands(branch: np.ndarray, cells: list[tuple[float, float]]):
    """Lock-step search: candidates where the branch's feasible domain is a single point
    at which one free-sign radicand turns negative as another turns positive: left of it
    one step fails, right of it another, and window refinement narrows the cell forever
    without a sample landing on the point (issue 25's 9/N17 drawn at a double root, seed
    28: P11 P4 P3 and P12 P5 P6 both flat at s1,10 = 1 exactly, the generating mode,
    missed). Of the first MAX_NARROW cells left by :func:`_with_windows`, those across
    which one free-sign radicand turns negative and another positive (one vectorised
    evaluation of their ends: a window edge between two failing steps, two per branch on
    7-B1, has no such pair) have the largest negated relative radicand of the free-sign
    steps minimised (bounded Brent, the cells side by side); where the minimum is at most
    TOUCH_TOLERANCE the point is a candidate with every nearly flat triangle
    (FLAT_MARGIN) flat, verified like every other."""
    cells = cells[:MAX_NARROW]
    if not cells:
        return []
    ends = np.array(cells, dtype=float).ravel()
    at_ends = (yield Samples(ends)).margins.reshape(len(cells), 2, -1)
    left, right = np.nan_to_num(at_ends[:, 0], nan=-1.0), np.nan_to_num(at_ends[:, 1], nan=-1.0)
    # a one-point domain needs one radicand turning negative and another turning positive
    crossing = ((left >= 0) & (right < 0)).any(axis=1) & ((left < 0) & (right >= 0)).any(axis=1)
    found = yield Together([_root_at_crossing_radicands(branch, low, high)
                            for (low, high), keep in zip(cells, crossing, strict=True) if keep])
    return [candidate for candidate in found if candidate is not None]


def _root_at_crossing_radicands(branch: np.ndarray, low: float, high: float):
    """Lock-step search: the candidate of :func:`_roots_at_crossing_radicands` in the
    cell [low, high], or None."""

    def infeasibility(reply: Profile) -> float:
        margins = reply.margins[0]
        return float(np.max(-np.nan_to_num(margins, nan=-10.0))) if margins.size else 10.0

    x, value, success = yield from brent_minimum(infeasibility, low, high, 1e-15 * max(abs(high), 1e-300))
    if not (success and value <= TOUCH_TOLERANCE):
        return None
    margins = (yield Samples(np.array([x]))).margins[0]
    flat = branch.copy()
    flat[np.abs(np.nan_to_num(margins, nan=1.0)) < FLAT_MARGIN] = 0
    return np.array([float(x)]), flat


def _failing_at(step: int, inside: float, outside: float, failure: int, radicand: float):
    """Lock-step search: the neighbour of a radicand bump at ``inside`` on the side of
    ``outside`` (which fails at step ``failure`` with relative radicand ``radicand``):
    itself if it fails at ``step`` too; if an earlier step fails there, the farthest of
    WINDOW_SAMPLES samples towards it that still fails at ``step`` (issue 25's 9/N4 drawn
    at a domain edge: P12 P8 P7 touches flat at s1,4 = 58, the sample before it, 57.84,
    fails at an earlier step, and the bump at 58.06 was skipped); None if it is defined
    or fails later (an edge, the edge search's business)."""
    if failure == step:
        return outside, radicand
    if failure > step:
        return None
    points = np.linspace(inside, outside, WINDOW_SAMPLES)
    reply = yield Samples(points)
    same = np.flatnonzero(reply.failures == step)
    same = same[same == np.arange(len(same))]  # the run from ``inside``
    if len(same) < 2:
        return None
    return float(points[same[-1]]), float(reply.radicands[same[-1]])


#: A free-sign triangle counts as flat at a domain edge when its radicand, relative to its
#: squared largest side, is below this: the triangle that ends the domain (~1e-15 there)
#: and any whose radicand vanishes with it like √δ (two joints in line with a third).
FLAT_MARGIN = 1e-4


def _roots_at_folds(branch: np.ndarray, edges: list[tuple[float, float]]):
    """Lock-step search: candidates at domain edges where free-sign triangles are flat
    and the residual has opposite signs on branches that differ only in those
    triangles' signs. Across the fold those branches are one curve, f(e ± δ) ≈ V ± W√δ,
    so opposite signs at the edge found (δ ≈ 1e-14 of the cell) mean V ≈ 0: a mode with
    those triangles flat, where no branch changes sign and none reaches |f| < 1e-7 at δ
    (joints in line: docs/stability.md; on 9/N1 two triangles were flat at once). A
    candidate is placed with each non-empty subset of the nearly flat triangles' signs 0
    (their joints on the line) and verified and polished like every other. Two
    vectorised evaluations for all edges."""
    if not edges:
        return []
    points = np.array([edge for edge, _ in edges])
    margins = (yield Samples(points)).margins  # all edges at once, (edges, free)
    folds, rows, variant_signs = [], [], []
    for i, (edge, value) in enumerate(edges):
        flat = np.flatnonzero(np.abs(margins[i]) < FLAT_MARGIN) if margins.size else []
        if not len(flat) or not np.isfinite(value):
            continue
        variants = np.repeat(branch[None, :], 2 ** len(flat), axis=0)
        variants[:, flat] = sign_branches(len(flat))
        folds.append((edge, flat, len(rows), len(rows) + len(variants)))
        rows += [edge] * len(variants)
        variant_signs.append(variants)
    if not folds:
        return []
    others = (yield Samples(np.array(rows), np.concatenate(variant_signs))).residuals[:, 0]
    found = []
    for edge, flat, start, stop in folds:
        near = others[start:stop][np.isfinite(others[start:stop])]
        if (near > 0).any() and (near < 0).any():
            # every non-empty subset taken flat: a triangle with a small margin need not be
            # flat (issue 25's 7/N1 drawn at a double root: margins 3e-8 and 3e-6 at the
            # edge; only the first is flat, and the candidate with both flat failed to verify)
            for size in range(1, len(flat) + 1):
                for subset in combinations(flat, size):
                    folded = branch.copy()
                    folded[list(subset)] = 0
                    found.append((np.array([edge]), folded))
    return found


def _may_touch_zero(grid: np.ndarray, radicands: np.ndarray, i: int) -> bool:
    """Whether the parabola through the failing radicand's samples i − 1, i, i + 1 (a
    local maximum) reaches within half their spread of 0: a radicand that touches 0
    between samples does (up to the cubic term), a maximum well below 0 does not. Keeps
    the bounded maximisation to the few bumps that matter (on a random 9-link instance,
    80 bumps cost 2000 plan evaluations, 3.3 s of a 4.7 s solve)."""
    x, y = grid[i - 1:i + 2], radicands[i - 1:i + 2]
    bottom = _parabola_minimum(x, -y)  # the radicand's maximum
    top = -bottom if bottom is not None else y.max()
    return bool(top > -0.5 * (y.max() - y.min()))


def _parabola_minimum(x: np.ndarray, y: np.ndarray) -> float | None:
    """The minimum value of the parabola through three points (x sorted), or None if it
    opens downwards (Newton's divided differences: no ill-conditioned fit)."""
    if not (x[0] < x[1] < x[2]) or not np.isfinite(y).all():
        return None  # merged samples may repeat a point
    first, second = (y[1] - y[0]) / (x[1] - x[0]), (y[2] - y[1]) / (x[2] - x[1])
    curvature = (second - first) / (x[2] - x[0])
    if not curvature > 0:
        return None
    slope = first + curvature * (x[1] - x[0])  # the derivative at x[1]
    return float(y[1] - slope * slope / (4 * curvature))


def _window_cells(codes: np.ndarray, feasible: int) -> np.ndarray:
    """Where samples i and i+1 (along the last axis) both fail, at different steps: a
    feasible window may hide between them (a defined/undefined boundary is left to the
    edge search); a mask of shape (..., n − 1)."""
    return (codes[..., :-1] != codes[..., 1:]) & (codes[..., :-1] < feasible) & (codes[..., 1:] < feasible)


def _radicand_bumps(codes: np.ndarray, radicands: np.ndarray, feasible: int) -> np.ndarray:
    """Indices i of failing samples whose radicand (of the step they fail at) is a local
    maximum among the neighbours failing at that same step: the radicand may turn
    positive between samples, a window whose two sides fail at one step
    (tests/regressions/11-missed-property.json)."""
    inner = codes[1:-1]
    left_ok = (codes[:-2] != inner) | (radicands[1:-1] >= radicands[:-2])
    right_ok = (codes[2:] != inner) | (radicands[1:-1] >= radicands[2:])
    return np.flatnonzero((inner < feasible) & left_ok & right_ok) + 1


def _radicand_dips(codes: np.ndarray, margins: np.ndarray, feasible: int) -> np.ndarray:
    """Indices i of defined samples with a defined neighbour where some free-sign step's
    radicand (``margins``, one column per step) is a local minimum among the defined
    neighbours: it may turn negative between samples, an undefined gap with a domain edge
    (and a root next to it) on each side (tests/regressions/9-gap-between-samples.json,
    found by the completeness test). An undefined neighbour does not count against the
    minimum: on issue 25's 9/N7 drawn with a mode at a domain edge (seed 41) the domain
    starts at s5,11 = 4, its first sample 4.0118 holds the radicand's minimum, and the gap
    (4.012, 4.037) and the mode at its far edge, 4.038146, lay before the next sample."""
    inner = margins[1:-1]
    defined = codes == feasible
    around = defined[1:-1] & (defined[:-2] | defined[2:])
    left = np.where(defined[:-2, None], margins[:-2], np.inf)
    right = np.where(defined[2:, None], margins[2:], np.inf)
    minimum = ((inner <= left) & (inner <= right)).any(axis=-1)
    return np.flatnonzero(around & minimum) + 1


def _with_windows(grid: np.ndarray, coarse: Profile, feasible: int):
    """Lock-step search: the grid plus :func:`window_samples`, with f there; and the
    cells still failing at different steps on both sides after WINDOW_DEPTH levels."""
    added, residuals, cells = yield from window_samples(grid, coarse.failures, coarse.radicands, coarse.margins,
                                                        feasible)
    values = coarse.residuals[:, 0]
    if len(added) == 0:
        return grid, values, cells
    return (*_merge(grid, values, added, residuals[:, 0]), cells)


def window_samples(grid: np.ndarray, failures: np.ndarray, radicands: np.ndarray, margins: np.ndarray,
                   feasible: int):
    """Lock-step search (:func:`~.lockstep.run_alone` runs it alone): dense samples
    (sorted, without repeats) of one parameter wherever a feasible window may hide
    between the samples ``grid`` of one branch: neighbours failing at different steps, a
    local maximum of a failing radicand, or a local minimum of a free-sign one
    (``failures``, ``radicands``, ``margins``:
    :meth:`~baranov.closure.CompiledSystem.failure_profile`); refined level by level,
    all cells of a level in one vectorised evaluation. Returns the samples, the closure
    residuals there (shape (N, c)), and the cells still failing at different steps on
    both sides after WINDOW_DEPTH levels: windows narrower than 64^-6 of a cell,
    possibly a single point (:func:`_roots_at_crossing_radicands`). Cost: WINDOW_SAMPLES
    placements per suspect cell and level."""
    extra, residuals = [], []
    cells = [(grid[i], grid[i + 1]) for i in np.flatnonzero(_window_cells(failures, feasible))]
    cells += [(grid[i - 1], grid[i + 1]) for i in _radicand_bumps(failures, radicands, feasible)]
    cells += [(grid[i - 1], grid[i + 1]) for i in _radicand_dips(failures, margins, feasible)]
    for _ in range(WINDOW_DEPTH):
        if not cells:
            break
        ends = np.array(cells, dtype=float)
        points = np.linspace(ends[:, 0], ends[:, 1], WINDOW_SAMPLES, axis=1)  # (cells, WINDOW_SAMPLES)
        reply = yield Samples(points.ravel())
        extra.append(points.ravel())
        residuals.append(reply.residuals)
        codes = reply.failures.reshape(points.shape)
        cell, i = np.nonzero(_window_cells(codes, feasible))  # within each cell's samples, all cells at once
        if len(cell) > WINDOW_CROWD:  # the failing step flickers at rounding noise: no window converges
            cells = []
            break
        cells = list(zip(points[cell, i].tolist(), points[cell, i + 1].tolist(), strict=True))
    if not extra:
        return np.zeros(0), np.zeros((0, 0)), cells
    points, first = np.unique(np.concatenate(extra), return_index=True)
    return points, np.concatenate(residuals)[first], cells


def _merge(points: np.ndarray, values: np.ndarray, more_points: np.ndarray, more_values: np.ndarray):
    """Samples and further samples as one sorted set, without repeated points."""
    merged = np.concatenate([points, more_points])
    order = np.argsort(merged, kind="stable")
    merged, merged_values = merged[order], np.concatenate([values, more_values])[order]
    keep = np.concatenate([[True], np.diff(merged) > 0])
    return merged[keep], merged_values[keep]


#: A local minimum of |f| must lie below both neighbours by this (relative to |f| there,
#: and to 1e-3 at least): where f is flat to rounding, every other sample is a "minimum"
#: (issue 25's 7/N1 instance: 36 cells of 397 noise minima each, one bounded
#: minimisation per minimum, over 60 s).
MINIMUM_DEPTH = 1e-10
#: The |f| below which MINIMUM_DEPTH no longer shrinks: the dip a minimum needs is at least
#: 1e-10 × this. It was 1e-3 (a dip of 1e-13): issue 25's seed 38 (7/N1 collinear 324)
#: has a double root at s2,7 = 5 where f ≈ 1.4e-5 (s − 5)², its fine samples 2e-14 beside
#: it, and that minimum was skipped (a mode missed); noise minima are left to the jitter
#: test (:func:`_above_noise`) and MAX_MINIMA.
MINIMUM_FLOOR = 1e-6


#: At most this many local minima of |f| are minimised per scan, and re-sampled per
#: branch, the deepest first (uncapped re-sampling took 50 of 81 s on issue 25's 9/N10 at a
#: flexible configuration, then 32 s: tests/regressions/9-N10-noise-brackets.json): next
#: to a singular mode f is flat to rounding over a stretch and a fine re-sampling showed
#: 100–150 "minima" per cell (issue 25's 9/N8 instance drawn at a flexible configuration:
#: 12 000 evaluations, 36 s where its siblings take 0.6 s).
MAX_MINIMA = 8


def _next_to_roots(grid: np.ndarray, roots: list[float]) -> list[tuple[float, float]]:
    """The cells on either side of each root's cell, and the next ones out, to re-sample
    finely: a tangential
    root next to a simple one hides in the slope towards it (issue 25's 9/N6: f ≈ −c(s −
    25)² touches 0 at 25 and crosses it at 25.0472; the samples 24.971, 25.047, 25.123
    read −3e-7, −5e-9, +4e-6, a single crossing)."""
    merged: list[list[float]] = []
    for root in sorted(roots):
        i = int(np.clip(np.searchsorted(grid, root), 1, len(grid) - 1))
        low, high = float(grid[max(i - 2, 0)]), float(grid[min(i + 1, len(grid) - 1)])
        if merged and low <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], high)  # neighbouring roots share their cells
        else:
            merged.append([low, high])
    # where f is noise, every sample flips its sign and brackets a "root": beside those the
    # re-sampling only finds more noise (issue 25's 9/N10 drawn at a flexible configuration,
    # seed 26: 16 470 brackets, 198 s); past MAX_MINIMA stretches only lone roots are kept
    if len(merged) > MAX_MINIMA:
        merged = [cell for cell in merged if sum(cell[0] <= r <= cell[1] for r in roots) == 1]
    merged = merged[:MAX_MINIMA]
    # and the next cell out on each side, on its own (the windows above keep their
    # sampling): seed 40's 9/N19 (collinear 15) crosses 0 at s1,10 = 9.8902, at the end of
    # its cell, and touches it at 10, in the second cell beyond (samples 9.892, 9.975,
    # 10.058 read −4.0e-8, −7.6e-8, −7.0e-7: no minimum of |f|)
    outer = []
    for low, high in merged:
        i, j = int(np.searchsorted(grid, low)), int(np.searchsorted(grid, high))
        outer += [(float(grid[a]), float(grid[a + 1])) for a in (i - 1, j) if 0 <= a < len(grid) - 1
                  and not any(m_low <= grid[a] and grid[a + 1] <= m_high for m_low, m_high in merged)]
    return [(low, high) for low, high in merged] + sorted(set(outer))


def _suspicious_minima(grid: np.ndarray, values: np.ndarray) -> list[tuple[float, float]]:
    """Cells around interior local minima of |f| with no sign change, the smallest |f|
    first."""
    finite = np.isfinite(values)
    magnitude = np.abs(values)
    dip = MINIMUM_DEPTH * np.maximum(magnitude[1:-1], MINIMUM_FLOOR)  # below rounding noise: not a minimum
    minima = (finite[:-2] & finite[1:-1] & finite[2:] & (magnitude[1:-1] <= magnitude[:-2] - dip)
              & (magnitude[1:-1] <= magnitude[2:] - dip) & (values[:-2] * values[2:] > 0))
    index = np.flatnonzero(minima) + 1
    return [(float(grid[i - 1]), float(grid[i + 1])) for i in index[np.argsort(magnitude[index], kind="stable")]]


#: Next to each domain edge, samples at distances 4^-k (k = 1 … EDGE_LEVELS) of the gap to
#: the nearest sample, down to EDGE_FLOOR of the edge: f is smooth in √δ at distance δ
#: from an edge, so these are evenly spread in the variable that matters (issue 25's
#: 9/N24: a root 8.7e-8 from the edge at s9,11 = 18, f ≈ −6e-7 between them, the nearest
#: sample 7e-6 away).
EDGE_LEVELS = 24
EDGE_FLOOR = 1e-10


def _with_edges(points: np.ndarray, values: np.ndarray):
    """Lock-step search: add the ends of the feasible domain (one per defined/undefined neighbour pair), and
    the defined samples the edge search made on the way, to the samples: f often turns
    quickly near an edge, and two roots between the last coarse sample and the edge show
    no sign change there (tests/regressions/11-missed-21.json); a root 3e-7 from an edge at
    s = 2811.6 changed sign only between the edge and the last sample before it
    (tests/regressions/7-root-at-edge.json, found by the completeness test). Also return
    the edges with their values (a root may sit on an edge). Next to each edge, samples
    spread evenly in √δ (EDGE_LEVELS). All edges are searched together, a few vectorised
    evaluations in all (:func:`_domain_edges`)."""
    finite = np.isfinite(values)
    cells = np.flatnonzero(finite[:-1] != finite[1:])
    if cells.size == 0:
        return points, values, []
    inside = np.where(finite[cells], points[cells], points[cells + 1])
    found, edge_values, seen_points, seen_values = yield from _domain_edges(
        points[cells], points[cells + 1], finite[cells], np.where(finite[cells], values[cells], values[cells + 1]))
    steps = found[:, None] + (inside - found)[:, None] * 4.0 ** -np.arange(1, EDGE_LEVELS + 1)
    steps = steps[np.abs(steps - found[:, None]) >= EDGE_FLOOR * np.abs(found[:, None])]
    step_values = yield from _values(steps)
    edges = list(zip(found.tolist(), edge_values.tolist(), strict=True))
    # the edges are samples too: a root within 1e-10 (relative) of an edge changes sign only there
    more_points = np.concatenate([seen_points, steps, found])
    more_values = np.concatenate([seen_values, step_values, edge_values])
    return (*_merge(points, values, more_points, more_values), edges)


class Scan(NamedTuple):
    """What :func:`_scan` finds: roots, approximate roots (minima of |f| below NEAR_ROOT,
    to polish) and stretches (low, high, sign changes) where f's sign is noise."""

    roots: list[float]
    near: list[float]
    noise: list[tuple[float, float, int]]


def _scan(grid: np.ndarray, values: np.ndarray, resolution: float = 0.0, resample: bool = True,
          refined: bool = False):
    """Lock-step search: the :class:`Scan` of f on sampled ``grid``: exact zeros, sign
    changes (Brent), and tangential roots at local minima of |f| (bounded minimisation),
    the brackets and minima side by side. A sign change across an undefined gap narrower
    than the cell (Brent meets NaN) is re-sampled finely, with its domain edges, once
    (``resample``). A run of sign changes across samples whose sign is rounding noise at
    the parameter's ``resolution`` (:func:`_noise_runs`) gives one root, the run's
    middle, and its stretch."""
    finite = np.isfinite(values)
    both = finite[:-1] & finite[1:]
    roots: list[float] = [float(grid[i]) for i in np.flatnonzero(finite & (values == 0))]
    cells = np.flatnonzero(both & (values[:-1] * values[1:] < 0))
    minima = _suspicious_minima(grid, values)
    if refined:  # a fine re-sampling is quadratic between samples: only minima that may reach 0
        minima = [cell for cell in minima if _may_reach_zero(grid, values, cell)]
    (single, runs), minima = yield Together([_noise_runs(grid, values, cells, resolution),
                                             _above_noise(grid, values, minima, resolution)])
    noise = []
    for first, last in runs:
        low, high = float(grid[first]), float(grid[last + 1])
        roots.append((low + high) / 2)
        noise.append((low, high, last - first + 1))
    found = yield Together([_bracketed(grid, values, i, resolution, resample) for i in single]
                           + [_tangential(low, high) for low, high in minima])
    return Scan(roots + [root for scan in found for root in scan.roots], [x for scan in found for x in scan.near],
                noise + [stretch for scan in found for stretch in scan.noise])


def _bracketed(grid: np.ndarray, values: np.ndarray, i: int, resolution: float, resample: bool):
    """Lock-step search: the :class:`Scan` of the sign-change cell i: Brent's root, or,
    where f is undefined inside, the cell re-sampled finely with its domain edges
    (``resample``)."""
    low, high = float(grid[i]), float(grid[i + 1])
    try:
        return Scan([(yield from brent_root(low, high, float(values[i]), float(values[i + 1]), _value,
                                            1e-14 * high, 1e-15))], [], [])
    except UndefinedInside:
        if not resample:
            return Scan([], [], [])
    fine = np.linspace(low, high, REFINEMENT)
    points, fine_values, edges = yield from _with_edges(fine, (yield from _values(fine)))
    inner = yield from _scan(points, fine_values, resolution, resample=False)
    return Scan([edge for edge, value in edges if abs(value) < 1e-7] + inner.roots, inner.near, inner.noise)


def _tangential(low: float, high: float):
    """Lock-step search: the :class:`Scan` of a local minimum of |f| in (low, high): a
    root where bounded minimisation brings |f| below 1e-7 (:func:`_crossing_beside`), an
    approximate root below NEAR_ROOT, or nothing."""
    x, value, success = yield from brent_minimum(lambda reply: abs(_value(reply)), low, high, 1e-14 * high)
    if success and value < 1e-7:
        return Scan([(yield from _crossing_beside(low, x, high))], [], [])
    if success and value < NEAR_ROOT:
        return Scan([], [x], [])
    return Scan([], [], [])


def _crossing_beside(low: float, at: float, high: float):
    """Lock-step search: ``at``, a minimum of |f| below 1e-7 in (low, high), or the
    simple root next to it where f changes sign between it and an end of the cell
    (Brent): where f is shallow |f| < 1e-7 holds far from the root (a family-I robot of
    issue 18: slope 6.7e-5 at s1,5 = 1044, the minimum accepted at 1043.9999929, which
    the clustering then kept over Brent's 1044.00000000002)."""
    f_low, value, f_high = (yield from _values(np.array([low, at, high]))).tolist()
    for a, b, fa, fb in ((low, at, f_low, value), (at, high, value, f_high)):
        if np.isfinite(fa) and np.isfinite(fb) and fa * fb < 0:
            try:
                return (yield from brent_root(a, b, fa, fb, _value, 1e-14 * b, 1e-15))
            except UndefinedInside:  # a gap of the domain between: the minimum stands
                return at
    return at


#: Offsets, in units of the parameter's resolution, at which a sample is re-evaluated
#: to tell its sign from rounding noise.
JITTER = np.array([-4.0, -3.0, -2.0, -1.0, 1.0, 2.0, 3.0, 4.0])
#: The parameter's resolution relative to its upper bound: s enters sums with squared
#: distances up to that bound, so f cannot resolve s more finely than a few ulps of it.
RESOLUTION = 2.0 ** -48


def _may_reach_zero(grid: np.ndarray, values: np.ndarray, cell: tuple[float, float]) -> bool:
    """Whether the parabola through |f| at a local minimum's three samples of a fine
    re-sampling has its vertex at most half the sampled minimum, or the minimum is a
    sharp dip, at most SHARP_DIP of its lower neighbour: |f| ≈ c (s − s0)² at a tangential
    root (vertex ≈ 0), |f| ≈ m + c (s − s1)² at a minimum well above 0 (vertex ≈ m, its
    neighbours barely higher: skipped, issue 25's 9/N17 drawn with a double root spent 7.2
    of 8.4 s in 632 bounded minimisations of such minima). The second test: with the
    middle sample close to a tangential root the vertex is not 0 but the error of fitting a
    skewed |f| (issue 25's seed 37, 7/N2: samples 4.4e-12, 2.0e-14, 3.7e-12 around the
    double root s1,8 = 5, vertex 1.1e-14; seed 38, 7/N1: 3.0e-13, 1.1e-14, 3.5e-13 around
    s2,7 = 5; each skipped, a mode missed)."""
    i = int(np.searchsorted(grid, cell[0])) + 1
    x, y = grid[i - 1:i + 2], np.abs(values[i - 1:i + 2])
    vertex = _parabola_minimum(x, y)
    vertex = y.min() if vertex is None else vertex
    return bool(vertex <= 0.5 * y[1] or y[1] <= SHARP_DIP * min(y[0], y[2]))


#: A fine re-sampling's local minimum at most this fraction of its lower neighbour is
#: searched whatever its parabola says (:func:`_may_reach_zero`).
SHARP_DIP = 0.1


def _above_noise(grid: np.ndarray, values: np.ndarray, minima: list[tuple[float, float]], resolution: float):
    """Lock-step search: the first MAX_MINIMA of ``minima`` (cells around a local minimum of |f| at their
    middle sample) whose dip below both neighbours exceeds the spread of f re-evaluated at
    offsets JITTER × ``resolution`` from the minimum: where f is rounding noise every
    other sample is a "minimum" (issue 25's 9/N10: 972 bounded minimisations near s5,10 =
    1e-10, 8 of its 9.5 s). One vectorised evaluation of 8 points per minimum looked at."""
    if resolution <= 0 or not minima:
        return minima[:MAX_MINIMA]
    minima = minima[:4 * MAX_MINIMA]
    index = np.searchsorted(grid, [low for low, _ in minima]) + 1  # a cell is (grid[i − 1], grid[i + 1])
    centres = grid[index][:, None]
    jittered = yield from _values((centres + JITTER * np.minimum(resolution, np.abs(centres) / 8)).ravel())
    spread = np.ptp(jittered.reshape(len(index), len(JITTER)), axis=1)
    magnitude = np.abs(values)
    dip = np.minimum(magnitude[index - 1], magnitude[index + 1]) - magnitude[index]
    kept = [cell for cell, keep in zip(minima, dip > spread, strict=True) if keep]
    return kept[:MAX_MINIMA]


#: A scan with more sign changes than this is noise wherever they crowd (NOISE_GAP), even
#: where re-evaluation near a sample does not flip its sign: rounding steps coarser than
#: the jitter (issue 25's 9/N8 drawn with a double root: 556 Brent brackets in a valley
#: 5e-3 wide around s1,11 = 8, 21 verified configurations of one singular mode). The
#: characteristic polynomials of 9-link trusses have degree ≤ 58 on all branches together.
NOISE_CROWD = 24

#: Noisy sign-change cells at most this many cells apart belong to one noise stretch.
NOISE_GAP = 8


def _noise_runs(grid: np.ndarray, values: np.ndarray, cells: np.ndarray, resolution: float):
    """Lock-step search: split the sign-change cells ``cells`` (f(grid[i]) f(grid[i+1]) < 0) into lone cells,
    to bracket, and stretches of cells whose sign rounding decides: f re-evaluated at
    offsets JITTER × ``resolution`` (at most an eighth of the sample) from an end of the
    cell takes both signs. Noisy cells at most NOISE_GAP cells apart form one stretch;
    a noisy cell alone (a root on a sample) is bracketed as usual. Where f is below its
    own rounding noise every few samples flip its sign, and each flip bracketed a
    "root" (issue 25's 9/N10 drawn at a flexible configuration: f ≈ c s^0.2 near s5,10 =
    0, where P10 and P5 coincide; re-sampled every 5e-14 near s = 3e-11, it flipped
    between ±2e-4: 4 222 Brent brackets, 39 of its 51 s). Returns (lone cells,
    [(first cell, last cell)] of the stretches). Cost: one vectorised evaluation of 8
    points per end of a sign-change cell."""
    if len(cells) < 2 or resolution <= 0:
        return cells, []
    ends = np.unique(np.concatenate([cells, cells + 1]))
    centres = grid[ends][:, None]
    points = (centres + JITTER * np.minimum(resolution, np.abs(centres) / 8)).ravel()
    jittered = (yield from _values(points)).reshape(len(ends), len(JITTER))
    noisy_ends = ends[~(np.sign(jittered) == np.sign(values[ends])[:, None]).all(axis=1)]
    noisy = np.isin(cells, noisy_ends) | np.isin(cells + 1, noisy_ends)
    if len(cells) > NOISE_CROWD:  # more sign changes than a closure condition has roots here: noise
        noisy[:] = True
    single, runs = [int(i) for i in cells[~noisy]], []
    group: list[int] = []
    for i in cells[noisy].tolist() + [None]:
        if group and (i is None or i - group[-1] > NOISE_GAP):
            if len(group) > 1:
                runs.append((group[0], group[-1]))
            else:
                single.append(group[0])
            group = []
        if i is not None:
            group.append(i)
    return sorted(single), runs


def _domain_edges(lows: np.ndarray, highs: np.ndarray, inside_low: np.ndarray, inside_values: np.ndarray):
    """Lock-step search: the boundaries of the feasible domain in the cells (``lows``,
    ``highs``), each on its defined side (``inside_low``: the low end is defined, f there
    ``inside_values``): 7 rounds of 64 samples per cell (resolution 64^-7 of the cell),
    each round one vectorised evaluation for all cells. Returns the edges and f there
    (each edge is a defined sample), and the defined samples of the first two rounds
    (spread over the cells and over their last 64th; the later rounds crowd at the
    edges, where rounding noise would only add spurious minima: keeping all seven made
    the 5/B1 example 300 times slower). Cost: 7 × 64 evaluations per cell, in 7 requests
    (one evaluation per cell per round made issue 25's 9/N9, whose domain flickers with
    rounding along a stretch, spend 56 s in 17 900 searches)."""
    inside = np.where(inside_low, lows, highs).astype(float)
    inside_values = np.array(inside_values, dtype=float)
    outside = np.where(inside_low, highs, lows).astype(float)
    active = np.ones(len(inside), dtype=bool)
    kept_points, kept_values = [], []
    fractions = np.linspace(0.0, 1.0, 64)
    for round_number in range(7):
        rows = np.flatnonzero(active)
        if rows.size == 0:
            break
        points = inside[rows, None] + (outside[rows] - inside[rows])[:, None] * fractions
        values = (yield from _values(points.ravel())).reshape(points.shape)
        defined = np.isfinite(values)
        if round_number < 2:
            kept_points.append(points[defined])
            kept_values.append(values[defined])
        has_undefined = (~defined).any(axis=1)
        first = np.argmax(~defined, axis=1)
        moving = has_undefined & (first > 0)
        active[rows[~moving]] = False
        rows, first = rows[moving], first[moving]
        inside[rows] = points[moving, first - 1]
        inside_values[rows] = values[moving, first - 1]
        outside[rows] = points[moving, first]
    return inside, inside_values, np.concatenate(kept_points), np.concatenate(kept_values)
