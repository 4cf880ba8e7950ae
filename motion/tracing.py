"""Tracing a one-degree-of-freedom chain's configuration space in distance space (thesis
§6.3): ordered pieces, one sign vector each, and the points where an oriented area
vanishes and the linkage can pass from one piece to another.

**Two parameters (d = 2).** On each sign vector the closure condition f(u, v) = 0 is a
curve in the plane of the two parameters (scaled to their ranges). Starting points are
the roots of coarse slices u = const (:func:`~.configuration_space.configurations_at`);
from each not yet on a traced piece the curve is followed both ways by pseudo-arclength
continuation: a step along the tangent (−f_v, f_u), then Newton back onto f = 0 along
the gradient (central differences), the step halved where Newton does not converge in
four iterations, f is undefined (the domain of the sign vector ends: a triangle is
flat) or a joint would move more than ``jump`` of the linkage's size, and doubled up to
``resolution`` of the ranges otherwise. Where the step falls below 1e-6 of the ranges
(next to a domain edge the curve runs along it and predictor steps leave the domain; a
hairpin fold) the curve is followed on slices instead (:func:`_slid`), to the edge, or on
until continuation can resume. A piece ends at a domain edge or closes on itself.

**One parameter (d = 1).** A piece is a range of the parameter on one sign vector: the
runs of RANGE_SAMPLES samples (even in √s) on which the plan places every joint, each
end bisected to 1e-13 of the range against its undefined neighbour, then sampled from
end to end, midpoints inserted where a joint would move more than ``jump``. A range
narrower than a sample step is missed.

**Branch points.** A piece ends where one of the plan's free-sign triangles becomes flat
(a radicand vanishes): there the configuration is the same on the two sign vectors that
differ in that triangle's sign, and the linkage can go on along the other one. Two piece
ends on such sign vectors whose configurations are within ``join`` of the linkage's size
(scaled by the step) are reported as a branch point joining them.

Resolution: the step between slices; a feature of the curve narrower than a step (two
folds between slices) is not resolved. Consecutive points of a piece are checked for
jumps: a joint moving more than ``jump`` of the linkage's size between neighbours is
reported (``Trace.jumps``), never silently joined.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from baranov.solvers.numeric.lockstep import paired_profile, run_alone
from baranov.solvers.numeric.one_parameter import window_samples
from baranov.solvers.placement import placed_configurations
from baranov.solvers.verification import distance_bound

from .configuration_space import (
    ConfigurationPoint,
    OneDofSystem,
    configurations_at,
    oriented_area,
    slice_configurations,
    verified_configurations,
)


@dataclass(frozen=True)
class Piece:
    """One piece of the configuration space: its sign vector (the plan's free-sign
    triangles) and its configurations in order along it; ``closed`` if it is a loop."""

    signs: tuple[int, ...]
    points: tuple[ConfigurationPoint, ...]
    closed: bool = False


@dataclass(frozen=True)
class BranchPoint:
    """Where a free-sign triangle is flat: the ends of two pieces (index, 0 for the first
    point or -1 for the last) that meet there."""

    pieces: tuple[tuple[int, int], tuple[int, int]]
    parameters: dict[str, float]


@dataclass(frozen=True)
class Trace:
    """A traced configuration space: the pieces, the branch points joining them, the
    steps at which neighbouring points of a piece are farther apart than expected, and
    (:attr:`loose_ends`) the piece ends that were not joined."""

    pieces: tuple[Piece, ...]
    branch_points: tuple[BranchPoint, ...]
    jumps: tuple[str, ...] = field(default=())

    @property
    def loose_ends(self) -> tuple[tuple[int, int], ...]:
        """Ends of open pieces (index, 0 or −1) at no branch point: where the tracer found
        no piece to go on along (not resolved: the curve's continuation was not placed)."""
        joined = {end for point in self.branch_points for end in point.pieces}
        return tuple((n, end) for n, piece in enumerate(self.pieces) if not piece.closed for end in (0, -1)
                     if (n, end) not in joined)


def trace(system: OneDofSystem, steps: int = 400, jump: float = 0.02, join: float = 0.02,
          resolution: float = 1 / 200) -> Trace:
    """The configuration space of ``system`` traced (see the module docstring): d = 1 as
    ranges of its parameter, d = 2 by continuation from ``steps // 8`` slices. Cost: d = 1,
    a vectorised placement of RANGE_SAMPLES values per sign vector, 60 per edge; d = 2, a
    few evaluations per point."""
    size = distance_bound(system.scene)
    if len(system.plan.parameters) == 1:
        pieces = [Piece(signs, tuple(points)) for signs, points in _ranges(system, jump * size)]
    else:
        pieces = _continued_pieces(system, max(steps // 8, 8), jump * size, resolution)
    jumps = [f"piece {n}, between points {k} and {k + 1}: a joint moves {moved / size:.3g} of the linkage's size"
             for n, piece in enumerate(pieces) for k, moved in _moves(piece) if moved > 2 * jump * size]
    return Trace(tuple(pieces), tuple(_branch_points(pieces, join * size)), tuple(jumps))


#: Samples of the one parameter (even in its square root) that find its ranges.
RANGE_SAMPLES = 4000


def _ranges(system: OneDofSystem, jump: float) -> list[tuple[tuple[int, ...], list[ConfigurationPoint]]]:
    """The ranges of a one-parameter configuration space, per sign vector (module docstring)."""
    uniform = np.linspace(0.0, math.sqrt(system.upper[0]), RANGE_SAMPLES + 1)[1:] ** 2
    failures, radicands, margins = system.compiled.failure_profile(uniform[:, None], np.array(system.branches))
    found = []
    for b, branch in enumerate(system.branches):
        # a window of the domain narrower than the samples (eight-bar 12 of docs/stability.md:
        # 0.0011 of s2,10 wide, between the crank in line and a domain edge)
        added, _, _ = run_alone(window_samples(uniform, failures[b], radicands[b], margins[b], len(system.plan.steps)),
                                paired_profile(system.compiled), branch)
        grid = np.union1d(uniform, added)
        defined = _placed(system, grid, branch)
        edges = np.flatnonzero(np.diff(defined.astype(int)))
        starts = ([0] if defined[0] else []) + [e + 1 for e in edges if not defined[e]]
        for start in starts:
            stop = next((e for e in edges if e >= start and defined[e]), len(grid) - 1)
            low, flat_low = (grid[0], None) if start == 0 else _edge(system, branch, grid[start - 1], grid[start])
            high, flat_high = ((grid[-1], None) if stop == len(grid) - 1
                               else _edge(system, branch, grid[stop + 1], grid[stop]))
            points = _sampled_range(system, branch, low, high, jump)
            if points:
                found.append((tuple(int(x) for x in branch), _with_flat_ends(system, points, flat_low, flat_high)))
    return found


def _with_flat_ends(system: OneDofSystem, points: list[ConfigurationPoint], flat_low: int | None,
                    flat_high: int | None) -> list[ConfigurationPoint]:
    """A range's end points placed with the free-sign triangle that turns flat at that edge
    flat (index into the plan's free-sign triangles; None at an end of the searched
    range). The bisection leaves the end within 1e-13 of the range of the edge, but the
    joints move like √ of that distance: eight-bar 12 of docs/stability.md ended a range
    with its crank at 179.9987° where the crank's triangle with the fixed link turns flat,
    at 180°, and the configuration at 180° was missed."""
    name = system.parameter_names[0]
    points = list(points)
    for end, flat in ((0, flat_low), (-1, flat_high)):
        if flat is None:
            continue
        branch = np.array(points[end].signs)
        branch[flat] = 0
        placed = verified_configurations(system, np.array([[points[end].parameters[name]]]), branch[None, :])
        if placed:
            points[end] = replace(placed[0], signs=points[end].signs)
    return points


def _placed(system: OneDofSystem, values: np.ndarray, branch: np.ndarray) -> np.ndarray:
    """Whether the plan places every joint at each of ``values`` on ``branch``."""
    _, points = placed_configurations(system.scene, system.compiled, values[:, None],
                                      np.repeat(branch[None, :], len(values), axis=0))
    return np.isfinite(points).all(axis=1)


def _edge(system: OneDofSystem, branch: np.ndarray, outside: float, inside: float) -> tuple[float, int | None]:
    """The domain's edge between an undefined and a defined value, by bisection; and the
    free-sign triangle that cannot be built beyond it (its index among the plan's
    free-sign triangles; None if the failing step has a fixed sign)."""
    for _ in range(60):
        middle = (outside + inside) / 2
        if _placed(system, np.array([middle]), branch)[0]:
            inside = middle
        else:
            outside = middle
        if abs(inside - outside) <= 1e-13 * system.upper[0]:
            break
    steps = system.plan.steps
    failing = int(system.compiled.first_failures(np.array([[outside]]), branch[None, :])[0, 0])
    if failing >= len(steps) or not steps[failing].free_sign:
        return inside, None
    return inside, sum(step.free_sign for step in steps[:failing])


def _sampled_range(system: OneDofSystem, branch: np.ndarray, low: float, high: float,
                   jump: float) -> list[ConfigurationPoint]:
    """Configurations from ``low`` to ``high`` on ``branch``: 64 values clustered at the
    ends (where the joints move as √ of the distance to the edge), then midpoints where a
    joint moves more than ``jump``, up to 12 rounds."""
    values = low + (high - low) * (1 - np.cos(np.linspace(0, math.pi, 64))) / 2
    for _ in range(12):
        points = verified_configurations(system, values[:, None], np.repeat(branch[None, :], len(values), axis=0))
        if len(points) < 2:
            return points
        moves = [move for _, move in _moves(Piece(tuple(branch), tuple(points)))]
        if max(moves) <= jump:
            return points
        where = [k for k, move in enumerate(moves) if move > jump]
        ordered = [p.parameters[system.parameter_names[0]] for p in points]
        values = np.sort(np.concatenate([ordered, [(ordered[k] + ordered[k + 1]) / 2 for k in where]]))
    return points


def _continued_pieces(system: OneDofSystem, slices: int, jump: float, resolution: float) -> list[Piece]:
    """Pieces of a two-parameter configuration space by continuation from the roots of
    ``slices`` slices, and on across every piece end where a free-sign triangle is flat,
    on the sign vector with that sign flipped (module docstring)."""
    low, high = _range(system, slices)
    # inside the range: at its ends a triangle is flat and both its signs give one point
    queue = [point for u in np.linspace(low, high, slices + 2)[1:-1] for point in configurations_at(system, u)]
    pieces: list[Piece] = []
    scale = np.array(system.upper, float)
    while queue:
        start = queue.pop(0)
        here = _scaled(start, scale)
        if any(_on_piece(here, piece, scale, resolution) for piece in pieces if piece.signs == start.signs):
            continue
        piece = _piece_from(system, start, jump, resolution)
        pieces.append(piece)
        if not piece.closed:
            queue += [crossing for end in (0, -1) for crossing in _across(system, piece.points[end])]
    return pieces


def _piece_from(system: OneDofSystem, start: ConfigurationPoint, jump: float, resolution: float) -> Piece:
    forward = _follow(system, start, +1, jump, resolution)
    if forward[-1] is start and len(forward) > 2:  # closed on itself
        return Piece(start.signs, tuple(forward[:-1]), True)
    backward = _follow(system, start, -1, jump, resolution)
    return Piece(start.signs, tuple(backward[:0:-1] + forward), False)


def _across(system: OneDofSystem, end: ConfigurationPoint) -> list[ConfigurationPoint]:
    """The configuration at a piece's ``end`` on the sign vector with its flattest
    free-sign triangle's sign flipped, brought onto that sign vector's curve by Newton
    steps and verified (none where it does not land): the linkage goes on there through
    the flat triangle."""
    areas = [abs(oriented_area(end, triangle)) for triangle in system.plan.free_sign_triangles]
    flat = int(np.argmin(areas))
    signs = tuple(-s if k == flat else s for k, s in enumerate(end.signs))
    scale = np.array(system.upper, float)
    landed = _corrected(_closure_with_gradient(system, signs), _scaled(end, scale))
    if landed is not None:
        found = [p for p in verified_configurations(system, (landed * scale)[None, :], np.array([signs]))
                 if p.max_residual < TRACED_RESIDUAL]
        if found:
            return found
    # Newton left the domain (next to its edge the closure has a square-root edge): the
    # slice through the end, on the flipped sign vector, its root nearest the end; or a
    # slice just beside it, where the end is placed on the edge's other side (eight-bar 9
    # of tests/test_motion.py: −−++ ends at s1,10 = 0.5344, where −−+− is not yet defined)
    names = system.parameter_names
    u, v = end.parameters[names[0]], end.parameters[names[-1]]
    width = CROSSING_GAP * system.upper[-1]
    grid = np.linspace(max(v - width, 0.0), min(v + width, system.upper[-1]), SLIDE_SAMPLES)
    for offset in CROSSING_OFFSETS:
        beside = u + offset * system.upper[0]
        if not 0 < beside <= system.upper[0]:
            continue
        near = [p for p in slice_configurations(system, beside, grid[grid > 0], np.array([signs]))
                if p.max_residual < TRACED_RESIDUAL]
        if near:
            return [min(near, key=lambda p: abs(p.parameters[names[-1]] - v))]
    return []


#: A piece end's crossing found on the slice through it lies within this fraction of the
#: second parameter's range of the end; else on a slice this fraction of the first
#: parameter's range beside it.
CROSSING_GAP = 1e-3
CROSSING_OFFSETS = (0.0, -1e-9, 1e-9, -1e-7, 1e-7, -1e-5, 1e-5)


def _scaled(point: ConfigurationPoint, scale: np.ndarray) -> np.ndarray:
    return np.array(list(point.parameters.values())) / scale


def _on_piece(here: np.ndarray, piece: Piece, scale: np.ndarray, resolution: float) -> bool:
    """Whether ``here`` (scaled) lies within a step of the piece's polyline."""
    points = np.array([_scaled(p, scale) for p in piece.points])
    if len(points) == 1:
        return bool(np.linalg.norm(points[0] - here) < resolution)
    a, b = points[:-1], points[1:]
    t = np.clip(np.einsum("ij,ij->i", here - a, b - a) / np.maximum(np.einsum("ij,ij->i", b - a, b - a), 1e-300), 0, 1)
    return bool(np.min(np.linalg.norm(a + t[:, None] * (b - a) - here, axis=1)) < resolution)


#: Newton corrections per continuation step, and the smallest step (scaled) before a
#: piece is declared ended at a domain edge (where f has a square-root edge, Newton
#: converges only ever closer to it: the piece's end is placed to about this).
NEWTON_STEPS = 4
SMALLEST_STEP = 1e-6
#: At most this many points per piece.
MAX_POINTS = 20000


def _follow(system: OneDofSystem, start: ConfigurationPoint, direction: int, jump: float,
            resolution: float) -> list[ConfigurationPoint]:
    """Points along the curve of ``start``'s sign vector from ``start`` in ``direction``
    (+1 or −1 along the tangent (−f_v, f_u)), until a domain edge, back at the start, or
    MAX_POINTS; where the steps stall, on along slices (:func:`_slid`)."""
    scale = np.array(system.upper, float)
    value_and_gradient = _closure_with_gradient(system, start.signs)
    points, x, step, tangent_sign = [start], _scaled(start, scale), resolution / 4, direction
    origin, previous_tangent, travelled, slides = x.copy(), None, 0.0, 0
    while len(points) < MAX_POINTS:
        _, g = value_and_gradient(x)
        if step < SMALLEST_STEP or not np.isfinite(g).all() or not g.any():
            # next to a domain edge every predictor step leaves the domain
            heading = previous_tangent if previous_tangent is not None else np.array([direction, 0.0])
            more, goes_on = _slid(system, points[-1], heading, jump, resolution)
            ordered = points + more
            if not goes_on and len(ordered) > 1 and not _at_edge(system, ordered[-1]):  # a fold in the slid parameter
                turned = _turned(system, ordered[-2], ordered[-1], heading)
                more_on, goes_on = _slid(system, ordered[-1], turned, jump, resolution)
                more += more_on
            points += more
            if not goes_on or slides >= MAX_SLIDES:
                break
            slides += 1
            moved = _scaled(more[-1], scale) - x
            previous_tangent, x, step = moved / np.linalg.norm(moved), x + moved, resolution / 4
            continue
        tangent = np.array([-g[1], g[0]]) / np.linalg.norm(g) * tangent_sign
        if previous_tangent is not None and tangent @ previous_tangent < 0:  # keep going the same way
            tangent, tangent_sign = -tangent, -tangent_sign
        corrected = _corrected(value_and_gradient, x + step * tangent)
        found = [] if corrected is None else verified_configurations(system, (corrected * scale)[None, :],
                                                                     np.array([start.signs]))
        point = found[0] if found else None
        if point is None or max(math.dist(point.joints[j], points[-1].joints[j]) for j in point.joints) > jump:
            step /= 2
            continue
        points.append(point)
        travelled += float(np.linalg.norm(corrected - x))
        previous_tangent, x = tangent, corrected
        step = min(step * 2, resolution)
        if travelled > 8 * resolution and np.linalg.norm(x - origin) < resolution:
            points.append(start)  # closed: back at the start
            break
    return points


#: Every traced point verifies to this on the link dimensions (issue 19); a slide's or a
#: crossing's point closer to a domain edge, where placement loses digits as √ of the
#: distance to it (8e-9 to 1e-8 on the double butterfly), is not taken.
TRACED_RESIDUAL = 1e-9
#: Samples of the window in which :func:`_slid` follows a root, its bisection steps, and
#: the most slides per piece end.
SLIDE_SAMPLES = 400
SLIDE_STEPS = 24
MAX_SLIDES = 8


def _slid(system: OneDofSystem, last: ConfigurationPoint, heading: np.ndarray, jump: float,
          resolution: float) -> tuple[list[ConfigurationPoint], bool]:
    """Points from ``last`` on along the curve where continuation stalled, and whether the
    curve goes on beyond them. Next to a domain edge the curve runs along it, every
    predictor step leaves the domain and the step falls below SMALLEST_STEP; so the curve
    is followed on slices instead: the parameter along which ``heading`` (scaled) moves
    most is fixed and moved that way, the root of the other nearest the previous one
    within a ``resolution`` window tracked (edge roots included:
    :func:`slice_configurations`). If it exists a full step on, the points up to there
    (the curve goes on: continuation resumes there); else the end is placed by
    SLIDE_STEPS bisections on whether it exists, with points between; either way no joint
    moves more than ``jump`` between neighbours where midpoints can help. On eight-bar 9
    of tests/test_motion.py the piece on −−++ stopped at s1,10 = 0.5535, 1.2e-4 of the
    ranges short of its end at the flat triangle P10 P5 P6 (s1,10 = 0.535), and the short
    piece beyond it was never crossed into. Cost: up to SLIDE_STEPS slices of
    SLIDE_SAMPLES samples, and one per point added."""
    axis = int(np.argmax(np.abs(heading)))
    if heading[axis] == 0:
        return [], False
    names, scale = system.parameter_names, np.array(system.upper, float)
    other, branch = 1 - axis, np.array([last.signs])
    width = resolution * scale[other]

    def near(value: float, previous: float) -> ConfigurationPoint | None:
        grid = np.linspace(max(previous - width, 0.0), min(previous + width, scale[other]), SLIDE_SAMPLES)
        for edges in (False, True):  # the edges' bisection only where no root is bracketed
            found = [p for p in slice_configurations(system, value, grid[grid > 0], branch, axis, edges)
                     if p.max_residual < TRACED_RESIDUAL]
            if found:
                return min(found, key=lambda p: abs(p.parameters[names[other]] - previous))
        return None

    start, previous = last.parameters[names[axis]], last.parameters[names[other]]
    outside = float(np.clip(start + np.sign(heading[axis]) * resolution * scale[axis], scale[axis] * 1e-12,
                            scale[axis]))
    beyond = near(outside, previous) if outside != start else None
    if beyond is not None:
        filled = _without_jumps(_filled(near, names[axis], [last, beyond], jump), jump)
        return filled[1:], filled[-1] is beyond
    inside, point = start, last
    for _ in range(SLIDE_STEPS):
        middle = (inside + outside) / 2
        found = near(middle, point.parameters[names[other]])
        if found is None:
            outside = middle
        else:
            inside, point = middle, found
    if point is last:
        return [], False
    return _without_jumps(_filled(near, names[axis], [last, point], jump), jump)[1:], False


def _without_jumps(points: list[ConfigurationPoint], jump: float) -> list[ConfigurationPoint]:
    """``points`` up to the first neighbour that a joint moves more than ``jump`` to (no
    midpoint verified to TRACED_RESIDUAL there: next to the edge joints move as √ of the
    distance to it): a piece ends short rather than jump."""
    for k, (a, b) in enumerate(zip(points, points[1:], strict=False)):
        if max(math.dist(a.joints[j], b.joints[j]) for j in a.joints) > jump:
            return points[:k + 1]
    return points


def _filled(near, name: str, points: list[ConfigurationPoint], jump: float, rounds: int = 12) -> list[ConfigurationPoint]:
    """``points`` (ordered along parameter ``name``) with midpoints on the slices between
    neighbours (``near(value, previous root)``) wherever a joint moves more than ``jump``,
    up to ``rounds`` rounds."""
    other = next(n for n in points[0].parameters if n != name)
    for _ in range(rounds):
        grown, added = [points[0]], False
        for a, b in zip(points, points[1:], strict=False):
            if max(math.dist(a.joints[j], b.joints[j]) for j in a.joints) > jump:
                middle = near((a.parameters[name] + b.parameters[name]) / 2, a.parameters[other])
                if middle is not None:
                    grown.append(middle)
                    added = True
            grown.append(b)
        points = grown
        if not added:
            break
    return points


#: A free-sign triangle whose doubled area is below this fraction of its longest side
#: squared is flat: a piece's end there is at the domain's edge.
FLAT = 1e-3


def _at_edge(system: OneDofSystem, point: ConfigurationPoint) -> bool:
    """Whether one of the plan's free-sign triangles is flat at ``point`` (FLAT)."""
    for triangle in system.plan.free_sign_triangles:
        corners = [point.joints[name] for name in triangle]
        longest = max(math.dist(a, b) for a in corners for b in corners)
        if abs(oriented_area(point, triangle)) <= FLAT * longest ** 2:
            return True
    return False


def _turned(system: OneDofSystem, before: ConfigurationPoint, fold: ConfigurationPoint,
            heading: np.ndarray) -> np.ndarray:
    """The heading that continues a slide past a fold of the curve in the parameter it
    slid along: along the other parameter, the way the curve was already moving in it
    (eight-bar 9: on ++ +− the curve folds back in s1,10 at 1.3843 and goes on down in
    s3,10; a slide in s1,10 ends there)."""
    axis = 1 - int(np.argmax(np.abs(heading)))
    name = system.parameter_names[axis]
    turned = np.zeros(2)
    turned[axis] = 1.0 if fold.parameters[name] >= before.parameters[name] else -1.0
    return turned


def _closure_with_gradient(system: OneDofSystem, signs: tuple[int, ...]):
    """x (scaled parameters) ↦ (f(x), ∇f(x)) on sign vector ``signs``: one evaluation of 5
    points (central differences, step 1e-7 of the ranges)."""
    scale, branch, h = np.array(system.upper, float), np.array(signs)[None, :], 1e-7

    def value_and_gradient(x: np.ndarray) -> tuple[float, np.ndarray]:
        values = system.compiled.residuals(np.array([x, x + (h, 0), x - (h, 0), x + (0, h), x - (0, h)]) * scale,
                                           branch)[0, :, 0]
        return values[0], np.array([values[1] - values[2], values[3] - values[4]]) / (2 * h)

    return value_and_gradient


def _corrected(value_and_gradient, x: np.ndarray) -> np.ndarray | None:
    """Newton steps along the gradient back onto f = 0, or None if they do not converge."""
    for _ in range(NEWTON_STEPS):
        value, g = value_and_gradient(x)
        if not (np.isfinite(value) and np.isfinite(g).all()) or not g.any():
            return None
        if abs(value) < 1e-12:
            return x
        x = x - value * g / (g @ g)
    value, _ = value_and_gradient(x)
    return x if np.isfinite(value) and abs(value) < 1e-10 else None


def _range(system: OneDofSystem, steps: int) -> tuple[float, float]:
    """The stretch of the first parameter where configurations exist, found on a coarse
    sweep of (0, upper] and widened by one coarse step each side (then clipped)."""
    upper = system.upper[0]
    coarse = np.linspace(0.0, upper, steps + 1)[1:]
    found = [u for u in coarse if configurations_at(system, u, samples=400, edges=False)]
    if not found:
        return float(coarse[0]), float(upper)
    step = upper / steps
    return max(found[0] - step, step * 1e-6), min(found[-1] + step, upper)


def _moves(piece: Piece) -> list[tuple[int, float]]:
    """For each step along the piece, the largest distance a joint moves."""
    return [(k, max(math.dist(a.joints[j], b.joints[j]) for j in a.joints))
            for k, (a, b) in enumerate(zip(piece.points, piece.points[1:], strict=False))]


def _branch_points(pieces: list[Piece], within: float) -> list[BranchPoint]:
    """Piece ends on sign vectors differing in one sign whose configurations coincide to
    ``within`` (a flat free-sign triangle: the linkage can go on along either)."""
    ends = [(n, end, piece.points[end]) for n, piece in enumerate(pieces) if not piece.closed for end in (0, -1)]
    found = []
    for a, (n, end, point) in enumerate(ends):
        for m, other_end, other in ends[a + 1:]:
            if m == n or sum(x != y for x, y in zip(point.signs, other.signs, strict=True)) != 1:
                continue
            if max(math.dist(point.joints[j], other.joints[j]) for j in point.joints) <= within:
                middle = {name: (point.parameters[name] + other.parameters[name]) / 2 for name in point.parameters}
                found.append(BranchPoint(((n, end), (m, other_end)), middle))
    return found
