"""Following a one-degree-of-freedom linkage's configuration curve in joint space, once
round each of its loops (issue 59; the idea of CUIK's continuation, Porta et al.: cover a
curve once, in the variables where it is smooth).

In the plan's parameters (thesis §6.3) the curve of a sign vector ends wherever a
free-sign triangle turns flat, the joints move as √ of the distance to that edge, and the
curve runs along the edge: a parameter-plane tracer has to stop, jump to the other sign
vector and start again, and can go out and back along an arc. In the joints' coordinates
the same motion is a smooth closed curve: the linkage passes through a flat triangle
without noticing it. So the curve is followed there, and the sign vectors are read off
it: a *crossing* is where a free-sign triangle's oriented area changes sign along the
curve, located to rounding.

**The equations.** Every joint of the ground link is fixed (:attr:`Scene.world`); every
other link with joints a, b, c, … (a, b its two joints farthest apart) contributes
|p_b − p_a|² = d_ab² and, for each further joint c, the complex-linear
p_c − p_a = γ_c (p_b − p_a), γ_c = (c − a) / (b − a) in the link's own frame: the link's
shape, mirror image excluded, in 2k − 3 real equations. Grübler's count, 3(L − 1) − 2J =
1, leaves one more unknown than equations: a curve, smooth wherever the Jacobian has full
rank.

**The tracer.** Pseudo-arclength continuation (Allgower and Georg, *Introduction to
Numerical Continuation Methods*, ch. 2): a step h along the unit tangent (the Jacobian's
null vector, oriented as the previous one), Newton's corrections on the equations and
the hyperplane t·(x − x₀) = h. A step is halved where Newton fails, where the tangent
turns by more than ``MAX_TURN`` or where the arc's estimated distance from its chord
(h·|Δt|/8, the sagitta of a circular arc) exceeds ``chord``; it grows while that is below
chord/4, up to ``jump`` (the linkage's size is 1). The loop closes when a step passes the
starting configuration going its way. A sign change of the augmented Jacobian's
determinant det[J; tᵀ] along the way is a singular configuration passed (a simple
bifurcation: two branches of the curve cross), recorded, not hidden.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy.optimize import brentq

from baranov.scene import Scene
from baranov.solvers.verification import distance_bound

#: Newton corrections per step, and the residual (scaled: the linkage's size is 1) they
#: must reach.
NEWTON_STEPS = 6
NEWTON_TOLERANCE = 1e-13
#: The most a step's tangent may turn (cosine of the angle between them): on a fold of a
#: projection or next to a singular configuration, a longer step could jump to another arc.
MAX_TURN = 0.95
#: The smallest step: below it the loop is left unfinished (its ends reported).
SMALLEST_STEP = 1e-11


@dataclass(frozen=True)
class LinkageCurve:
    """The equations of a one-degree-of-freedom scene's configuration curve in the
    coordinates of its moving joints (module docstring), scaled by the linkage's size.

    ``moving``: the joints that move, in the order of the unknowns (x, y each);
    ``fixed``: the ground link's joints (complex, scaled); ``distances``: per link
    equation (a, b, d²); ``shapes``: per further joint (a, b, c, γ)."""

    moving: tuple[str, ...]
    fixed: dict[str, complex]
    distances: tuple[tuple[str, str, float], ...]
    shapes: tuple[tuple[str, str, str, complex], ...]
    size: float
    triangles: tuple[tuple[str, str, str], ...] = field(default=())

    @property
    def unknowns(self) -> int:
        return 2 * len(self.moving)

    @cached_property
    def columns(self) -> dict[str, int]:
        """Each moving joint's first column among the unknowns (its x; its y follows)."""
        return {joint: 2 * k for k, joint in enumerate(self.moving)}

    def positions(self, x: np.ndarray) -> dict[str, complex]:
        """Every joint's place (scaled) at unknowns ``x``."""
        placed = dict(self.fixed)
        placed.update({joint: complex(x[2 * k], x[2 * k + 1]) for k, joint in enumerate(self.moving)})
        return placed

    def unknowns_of(self, joints: dict[str, tuple[float, float]]) -> np.ndarray:
        """The unknowns of a configuration given in world coordinates."""
        return np.array([value / self.size for joint in self.moving for value in joints[joint]], float)

    def equations(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The equations' values at ``x`` and their Jacobian (rows: equations)."""
        at, index = self.positions(x), self.columns
        values = np.empty(self.unknowns - 1)
        jacobian = np.zeros((self.unknowns - 1, self.unknowns))
        row = 0
        for a, b, squared in self.distances:
            d = at[b] - at[a]
            values[row] = d.real ** 2 + d.imag ** 2 - squared
            _add(jacobian[row:row + 1], index, b, np.array([[2 * d.real, 2 * d.imag]]))
            _add(jacobian[row:row + 1], index, a, np.array([[-2 * d.real, -2 * d.imag]]))
            row += 1
        for a, b, c, gamma in self.shapes:
            residual = at[c] - at[a] - gamma * (at[b] - at[a])
            values[row:row + 2] = residual.real, residual.imag
            block = jacobian[row:row + 2]
            _add(block, index, c, _complex_matrix(1))
            _add(block, index, a, _complex_matrix(gamma - 1))
            _add(block, index, b, _complex_matrix(-gamma))
            row += 2
        return values, jacobian

    def areas(self, x: np.ndarray) -> np.ndarray:
        """Twice the oriented area of each of :attr:`triangles` (scaled)."""
        at = self.positions(x)
        return np.array([((at[j] - at[i]).conjugate() * (at[k] - at[i])).imag for i, j, k in self.triangles])


def _complex_matrix(value: complex) -> np.ndarray:
    """Multiplication by ``value`` as a real 2 × 2 matrix on (x, y)."""
    return np.array([[value.real, -value.imag], [value.imag, value.real]])


def _add(rows: np.ndarray, index: dict[str, int], joint: str, block: np.ndarray) -> None:
    if joint in index:  # a fixed joint has no unknowns
        rows[:, index[joint]:index[joint] + 2] += block


def linkage_curve(scene: Scene, triangles=()) -> LinkageCurve:
    """The configuration curve's equations of a one-degree-of-freedom ``scene`` (no
    slider joints), with the oriented areas of ``triangles`` to watch (a plan's free-sign
    triangles). Cost: linear in the joints."""
    size = distance_bound(scene)
    ground = scene.link_of(scene.ground)
    fixed = {joint: complex(float(x), float(y)) / size for joint, (x, y) in scene.world.items() if joint in ground.joints}
    distances, shapes = [], []
    for link in scene.links:
        if link.name == scene.ground:
            continue
        a, b = max(((a, b) for k, a in enumerate(link.joints) for b in link.joints[k + 1:]),
                   key=lambda pair: link.float_distances[frozenset(pair)])
        distances.append((a, b, link.float_distances[frozenset((a, b))] / size ** 2))
        frame = {joint: complex(*map(float, link.local[joint])) for joint in link.joints}
        shapes += [(a, b, c, (frame[c] - frame[a]) / (frame[b] - frame[a])) for c in link.joints if c not in (a, b)]
    moving = tuple(joint for link in scene.links for joint in link.joints if joint not in fixed)
    return LinkageCurve(tuple(dict.fromkeys(moving)), fixed, tuple(distances), tuple(shapes), size, tuple(triangles))


def tangent(curve: LinkageCurve, x: np.ndarray, previous: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """The unit tangent at ``x`` (oriented along ``previous`` if given) and the sign of the
    augmented Jacobian's determinant det[J; tᵀ], which changes where the loop passes a
    singular configuration."""
    _, jacobian = curve.equations(x)
    direction = np.linalg.svd(jacobian)[2][-1]
    if previous is not None and direction @ previous < 0:
        direction = -direction
    return direction, float(np.sign(np.linalg.det(np.vstack([jacobian, direction]))))


def corrected(curve: LinkageCurve, guess: np.ndarray, normal: np.ndarray, offset: float) -> np.ndarray | None:
    """Newton's iteration from ``guess`` onto the curve within the hyperplane
    normal·x = offset; None if it does not converge in NEWTON_STEPS."""
    x = guess.copy()
    for _ in range(NEWTON_STEPS):
        values, jacobian = curve.equations(x)
        residual = np.append(values, normal @ x - offset)
        if np.abs(residual).max() < NEWTON_TOLERANCE:
            return x
        try:
            x = x - np.linalg.solve(np.vstack([jacobian, normal]), residual)
        except np.linalg.LinAlgError:
            return None
        if not np.isfinite(x).all():
            return None
    values, _ = curve.equations(x)
    return x if np.abs(values).max() < NEWTON_TOLERANCE * 10 else None


@dataclass
class Loop:
    """A followed loop of the curve: its points (unknowns, in order; the start first),
    the crossings among them (point index, the triangles flat there), the singular configurations
    passed (point index after which), whether it closed, and why not."""

    points: list[np.ndarray]
    crossings: list[tuple[int, tuple[int, ...]]]
    singular: list[int]
    closed: bool
    unfinished: str = ""


def followed_loop(curve: LinkageCurve, start: np.ndarray, chord: float, jump: float, max_points: int = 40000,
                  backwards: bool = False) -> Loop:
    """The loop of the curve through ``start`` (unknowns on the curve), followed once
    round (module docstring); crossings inserted at the configurations where a watched
    triangle is flat. Cost: a few small SVDs and solves per point; the points' number
    grows as the loop's length over √(chord · curvature). ``backwards``: the other way
    round."""
    x, (direction, orientation) = start, tangent(curve, start)
    if backwards:
        direction, orientation = -direction, -orientation
    first_direction, step, travelled = direction, jump / 8, 0.0
    loop = Loop([start], [], [], False)
    areas = curve.areas(start)
    while len(loop.points) < max_points:
        if step < SMALLEST_STEP:
            loop.unfinished = f"the step fell below {SMALLEST_STEP:g} of the linkage's size"
            return loop
        y = _ahead(curve, x, direction, step)
        if y is None and step < LEAP_BELOW:
            step, y = _leap(curve, x, direction)
        if y is None:
            step /= 2
            continue
        new_direction, new_orientation = tangent(curve, y, direction)
        turn, sagitta = float(new_direction @ direction), step * float(np.linalg.norm(new_direction - direction)) / 8
        if turn < MAX_TURN or sagitta > chord:
            step /= 2
            continue
        new_areas = curve.areas(y)
        changed = np.flatnonzero(np.sign(new_areas) != np.sign(areas))
        if len(changed) > 1 and step > LEAP_BELOW:  # one crossing per step, each located alone (unless at once)
            step /= 2
            continue
        if _passes_start(start, first_direction, x, y, travelled, step):
            # the last stretch, up to the start, may still cross a triangle
            _add_crossings(loop, curve, x, direction, float(direction @ (start - x)),
                           np.flatnonzero(np.sign(curve.areas(start)) != np.sign(areas)))
            loop.closed = True
            return loop
        _add_crossings(loop, curve, x, direction, step, changed)
        if new_orientation != orientation:
            loop.singular.append(len(loop.points) - 1)
        loop.points.append(y)
        travelled += step
        x, direction, orientation, areas = y, new_direction, new_orientation, new_areas
        if sagitta < chord / 4 and turn > (1 + MAX_TURN) / 2:
            step = min(step * 1.5, jump)
    loop.unfinished = f"more than {max_points} points"
    return loop


def _leap(curve: LinkageCurve, x: np.ndarray, direction: np.ndarray) -> tuple[float, np.ndarray | None]:
    """Across a singular configuration: where Newton's corrections fail for every short
    step, the augmented Jacobian [J; tᵀ] is nearly singular (two branches of the curve
    cross ahead, as in a change-point four-bar); longer steps along the tangent are
    corrected from the far side, the first that lands with the tangent still pointing
    ahead taken (the branch goes on straight through the crossing)."""
    for step in LEAPS:
        y = _ahead(curve, x, direction, step)
        if y is not None and tangent(curve, y, direction)[0] @ direction > MAX_TURN:
            return step, y
    return LEAP_BELOW, None


#: Below this step a failed correction tries the longer steps LEAPS (:func:`_leap`), and
#: two triangles turning flat within one step are taken as flat at once.
LEAP_BELOW = 1e-7
LEAPS = (1e-6, 1e-5, 1e-4, 1e-3)


def _passes_start(start: np.ndarray, first_direction: np.ndarray, x: np.ndarray, y: np.ndarray, travelled: float,
                  step: float) -> bool:
    """Whether the step from ``x`` to ``y`` passes the loop's start going its way: the
    start lies within the step's segment (to a tenth of the step) and the step is headed
    along the start's tangent."""
    if travelled < 2 * step:
        return False
    segment = y - x
    along = float(np.clip((start - x) @ segment / (segment @ segment), 0.0, 1.0))
    return bool(np.linalg.norm(x + along * segment - start) < 0.1 * step and segment @ first_direction > 0
                and along > 0)


def _add_crossings(loop: Loop, curve: LinkageCurve, x: np.ndarray, direction: np.ndarray, step: float,
                   changed: np.ndarray) -> None:
    """The crossings of the triangles ``changed`` between ``x`` and a step on, in order
    along it, appended to the loop; triangles flat at one place (within 1e-9 of the
    linkage's size: all joints in line at a change point) one crossing."""
    located = sorted((_crossing(curve, x, direction, step, int(triangle)), int(triangle)) for triangle in changed)
    previous = None
    for along, triangle in located:
        if previous is not None and abs(along - previous) < 1e-9:
            loop.crossings[-1] = (loop.crossings[-1][0], (*loop.crossings[-1][1], triangle))
            continue
        loop.points.append(_on_step(curve, x, direction, along))
        loop.crossings.append((len(loop.points) - 1, (triangle,)))
        previous = along


def _ahead(curve: LinkageCurve, x: np.ndarray, direction: np.ndarray, along: float) -> np.ndarray | None:
    """The curve's point ``along`` the unit ``direction`` from ``x``, in the hyperplane
    normal to it (the predictor x + along · direction, corrected); None where Newton fails."""
    return corrected(curve, x + along * direction, direction, direction @ x + along)


def _on_step(curve: LinkageCurve, x: np.ndarray, direction: np.ndarray, along: float) -> np.ndarray:
    """:func:`_ahead`, or the predictor itself where Newton fails (Brent needs a value)."""
    found = _ahead(curve, x, direction, along)
    return found if found is not None else x + along * direction


def _crossing(curve: LinkageCurve, x: np.ndarray, direction: np.ndarray, step: float, triangle: int) -> float:
    """How far along a step from ``x`` triangle ``triangle`` is flat: Brent's method on
    its area along the step (each value a corrected point); the step's end where the
    area only touches 0."""
    def area(along: float) -> float:
        return float(curve.areas(_on_step(curve, x, direction, along))[triangle])

    if area(0.0) * area(step) > 0:
        return step
    return brentq(area, 0.0, step, xtol=1e-15, rtol=4 * np.finfo(float).eps)


def singular_point(curve: LinkageCurve, before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """Where the augmented Jacobian's determinant changes sign between two neighbouring
    points of a loop (bisection, 40 steps): a singular configuration of the linkage. Every
    tangent is oriented along the loop (from ``before`` to ``after``), so the signs compare."""
    _, orientation = tangent(curve, before, after - before)
    low, high = before, after
    for _ in range(40):
        middle = (low + high) / 2
        direction = (high - low) / max(np.linalg.norm(high - low), 1e-300)
        middle = corrected(curve, middle, direction, direction @ middle)
        if middle is None:
            break
        _, sign = tangent(curve, middle, direction)
        low, high = (middle, high) if sign == orientation else (low, middle)
    return (low + high) / 2


def on_chord(curve: LinkageCurve, a: np.ndarray, b: np.ndarray, along: float) -> np.ndarray | None:
    """The curve's point between neighbouring points ``a`` and ``b`` of a loop in the
    hyperplane normal to their chord through a + along · (b − a) (0 ≤ along ≤ 1): a
    parametrisation of the arc between them, exact at both ends. None where Newton's
    iteration does not converge."""
    chord = b - a
    normal = chord / np.linalg.norm(chord)
    if along <= 0 or along >= 1:
        return a if along <= 0 else b
    guess = a + along * chord
    return corrected(curve, guess, normal, normal @ guess)


def chord_error(curve: LinkageCurve, a: np.ndarray, b: np.ndarray) -> float:
    """How far the curve between neighbouring points ``a`` and ``b`` lies from their chord,
    at its middle (scaled): an independent check of the step control."""
    found = on_chord(curve, a, b, 0.5)
    return math.inf if found is None else float(np.linalg.norm(found - (a + b) / 2))


def distance_to_polyline(x: np.ndarray, points: np.ndarray, closed: bool = False) -> float:
    """The distance from ``x`` to the polyline through ``points`` (rows; ``closed``: back
    to the first). O(points)."""
    points = np.asarray(points, float)
    starts = points if closed else points[:-1]
    if len(starts) == 0:
        return float(np.linalg.norm(points[0] - x))
    segment = np.roll(points, -1, axis=0) - points if closed else points[1:] - points[:-1]
    along = np.clip(np.einsum("ij,ij->i", x - starts, segment)
                    / np.maximum(np.einsum("ij,ij->i", segment, segment), 1e-300), 0, 1)
    return float(np.min(np.linalg.norm(starts + along[:, None] * segment - x, axis=1)))
