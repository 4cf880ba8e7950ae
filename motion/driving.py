"""The motion driven by an input (issue 19): for each value of an input on a grid — an
angle between two links at their joint (a crank against the ground), or the squared
distance between two joints (a linear actuator): a :class:`~baranov.scene.SceneInput` —
every configuration of the linkage, grouped by the traced
piece it lies on and ordered along it, so that following one branch never jumps to
another (the failure of predictor–corrector tracing in the workspace that thesis ch. 6
removes: the branches are the pieces of the configuration space, split by the signs of
the free-sign triangles).

A configuration at an input value is located between two neighbouring traced points
where the input crosses the value, then refined on the configuration curve itself
(:func:`~.continuation.on_chord`: the curve's point in the hyperplane normal to the two
points' chord, moved along it by Brent's method until the input has the value); the same
for one parameter and two, and exact at a branch point, where a triangle is flat. Every
configuration is verified on the link dimensions (1e-8, relative) as the traced ones are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from baranov.scene import Scene, SceneError, SceneInput, link_entry, scene_from_dict

from .configuration_space import ConfigurationPoint, OneDofSystem
from .continuation import LinkageCurve, linkage_curve, on_chord
from .tracing import Piece, Trace, configurations_on_curve


def input_value(driver: SceneInput, point: ConfigurationPoint) -> float:
    """The value of the input ``driver`` at a configuration, in the scene's units: for an
    angle at P_a from P_f to P_t, degrees counter-clockwise in (−180, 180]; for a distance,
    the squared distance of its two joints."""
    if driver.kind == "angle":
        (ax, ay), (fx, fy), (tx, ty) = (point.joints[name] for name in driver.joints)
        cross = (fx - ax) * (ty - ay) - (fy - ay) * (tx - ax)
        dot = (fx - ax) * (tx - ax) + (fy - ay) * (ty - ay)
        return math.degrees(math.atan2(cross, dot))
    (ux, uy), (vx, vy) = (point.joints[name] for name in driver.joints)
    return (vx - ux) ** 2 + (vy - uy) ** 2


def _turned(driver: SceneInput, value: float) -> float:
    """An angle's difference brought into [−180, 180); a distance's as it is."""
    return (value + 180.0) % 360.0 - 180.0 if driver.kind == "angle" else value


@dataclass(frozen=True)
class DrivenBranch:
    """The configurations of one traced piece at the input values it reaches, in order
    along the piece (:attr:`values` the input's, unwrapped for an angle)."""

    piece: int
    signs: tuple[int, ...]
    values: tuple[float, ...]
    points: tuple[ConfigurationPoint, ...]


def driven_motion(system: OneDofSystem, traced: Trace, driver: SceneInput, grid) -> list[DrivenBranch]:
    """For every traced piece, its configurations at the input values of ``grid`` (the
    input's units; for an angle, every value plus any multiple of 360°), located and
    refined as the module docstring says; pieces that reach no value are left out.

    Cost: per crossing, a Brent search (d = 1, about 40 placements) or a few Newton steps
    (d = 2)."""
    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    branches = []
    for index, piece in enumerate(traced.pieces):
        values, points = [], []
        piece = _with_extrema(system, curve, driver, piece)
        for before, after in _segments(piece):
            for target in _crossed(driver, before, after, grid):
                _keep(values, points, target, _refined(system, curve, driver, before, after, target))
        if not piece.closed:  # a value just beyond an end, met at the end itself (_beyond)
            for target in _beyond(driver, piece.points[-1], grid):
                _keep(values, points, target, piece.points[-1])
            for target in _beyond(driver, piece.points[0], grid):
                _keep(values, points, target, piece.points[0], first=True)
        if points:
            branches.append(DrivenBranch(index, piece.signs, tuple(values), tuple(points)))
    return branches


def _with_extrema(system: OneDofSystem, curve: LinkageCurve, driver: SceneInput, piece: Piece) -> Piece:
    """``piece`` with the configuration at each local extremum of the input along it
    added (:func:`input_extremum`): a dead point of the input (a four-bar rocker's extreme
    angle) lies between two traced points, and the values between the higher one and the
    extremum would be missed (a double-rocker's crank: 109.4633° traced, 109.4712° =
    arccos(−1/3) reached)."""
    points = list(piece.points)
    added = []
    for k, value, maximum in turning_points(driver, points):
        ends = [curve.unknowns_of(points[n].joints) for n in (k - 1, k, k + 1)]
        along, x = input_extremum(curve, driver, ends, value, maximum)
        if abs(along - 1.0) > 1e-12:
            added.append((k, along > 1.0, replace(configurations_on_curve(system, curve, [x])[0], signs=piece.signs)))
    for k, later, point in reversed(added):
        points.insert(k + 1 if later else k, point)
    return Piece(piece.signs, tuple(points), piece.closed)


def turning_points(driver: SceneInput, points: list[ConfigurationPoint], closed: bool = False
                   ) -> list[tuple[int, float, bool]]:
    """Where the input turns back along a polyline of traced points (``closed``: round to
    its start): (index, the input's value there, whether a maximum), the index between
    the two steps of opposite sign. O(points)."""
    count = len(points)
    values = [input_value(driver, point) for point in points]
    ends = range(count) if closed else range(1, count - 1)
    steps = [_turned(driver, values[(k + 1) % count] - values[k]) for k in range(count)]
    return [(k, values[k], steps[k - 1] > 0) for k in ends if steps[k - 1] * steps[k] < 0]


def input_extremum(curve: LinkageCurve, driver: SceneInput, ends: list[np.ndarray], reference: float,
                   maximum: bool) -> tuple[float, np.ndarray]:
    """Where the input (``reference`` at the middle one of three neighbouring points
    ``ends`` of a traced piece, as unknowns of ``curve``) is largest (``maximum``) or
    smallest between them: a bounded scalar search over ``along`` from 0 to 2 (the first
    chord, then the second), each value a point of the curve
    (:func:`~.continuation.on_chord`), to 1e-12 of a chord. Returns ``along`` and the
    curve's point there."""
    def at(along: float) -> np.ndarray | None:
        first = 0 if along < 1 else 1
        return on_chord(curve, ends[first], ends[first + 1], along - first)

    def negated(along: float) -> float:
        x = at(along)
        offset = math.inf if x is None else _turned(driver, _input_of(curve, driver, x) - reference)
        return -offset if maximum else offset

    best = minimize_scalar(negated, bounds=(0.0, 2.0), method="bounded", options={"xatol": 1e-12})
    x = at(best.x)
    return (best.x, x) if x is not None else (1.0, ends[1])


def _same(first: ConfigurationPoint, second: ConfigurationPoint, tolerance: float = 1e-7) -> bool:
    """One configuration found twice on a piece: every joint within 1e-7 of the joints'
    spread (a piece that goes out and back over a stretch, as a trace can where its sign
    vector's curve ends without a flat triangle, meets a value twice at one configuration)."""
    spread = max(max(abs(x) + abs(y) for x, y in first.joints.values()), 1.0)
    return all(math.dist(first.joints[name], second.joints[name]) < tolerance * spread for name in first.joints)


def _segments(piece: Piece) -> list[tuple[ConfigurationPoint, ConfigurationPoint]]:
    points = list(piece.points) + ([piece.points[0]] if piece.closed else [])
    return list(zip(points[:-1], points[1:], strict=True))


def _crossed(driver: SceneInput, before: ConfigurationPoint, after: ConfigurationPoint, grid: np.ndarray) -> list[float]:
    """The grid values the input passes between two neighbouring points (an angle takes
    the short way round, unwrapped from ``before``'s value), in the order passed."""
    start = input_value(driver, before)
    end = start + _turned(driver, input_value(driver, after) - start)
    # a value the input meets at a point is taken within rounding, on both segments (the
    # piece keeps it once, _same): a piece can end exactly there (a crank at 180°, its
    # triangle with the fixed link flat, ends pieces: 8-bar 3 lost 5 of 6 configurations)
    slack = VALUE_SLACK * max(1.0, abs(start), abs(end))
    low, high = min(start, end) - slack, max(start, end) + slack
    found = []
    for value in np.asarray(grid, dtype=float):
        if driver.kind == "angle":
            turns = range(math.ceil((low - value) / 360), math.floor((high - value) / 360) + 1)
            found += [value + 360.0 * n for n in turns]
        elif low <= value <= high:
            found.append(float(value))
    return sorted(found, reverse=end < start)


def _keep(values: list[float], points: list[ConfigurationPoint], target: float, point: ConfigurationPoint | None,
          first: bool = False) -> None:
    """Add ``point`` at ``target`` (at the front with ``first``) unless it is None or
    already there (:func:`_same`)."""
    if point is None or any(value == target and _same(point, other) for value, other in zip(values, points,
                                                                                           strict=True)):
        return
    values.insert(0 if first else len(values), target)
    points.insert(0 if first else len(points), point)


def distinct_configurations(branches: list[DrivenBranch], value: float, period: float | None = None
                            ) -> list[ConfigurationPoint]:
    """The configurations of ``branches`` at input ``value`` (modulo ``period``: 360 for an
    angle), each once: one at a branch point ends every piece that meets there, and each
    lists it, each end located to about 1e-5 of the linkage's size (two configurations
    closer than 1e-4 of it are taken as one, as where two modes merge)."""
    found: list[ConfigurationPoint] = []
    for branch in branches:
        for at, point in zip(branch.values, branch.points, strict=True):
            gap = at - value if period is None else (at - value + period / 2) % period - period / 2
            if abs(gap) <= VALUE_SLACK * max(1.0, abs(value)) and not any(_same(point, other, 1e-4) for other in found):
                found.append(point)
    return found


def _beyond(driver: SceneInput, end: ConfigurationPoint, grid) -> list[float]:
    """The grid values within END_SLACK of the input at a piece's ``end`` (unwrapped to
    it): a piece ends where a triangle is flat, located to about √(1e-13) of the range, so
    a value the linkage meets at that branch point (a crank at 180° in line with the fixed
    link: 8-bar 3 lost 5 of 6 configurations there) can lie just beyond the last point."""
    at = input_value(driver, end)
    scale = 360.0 if driver.kind == "angle" else max(1.0, abs(at))
    return [at + _turned(driver, float(value) - at) for value in np.asarray(grid, dtype=float)
            if abs(_turned(driver, float(value) - at)) <= END_SLACK * scale]


#: A value within this fraction of the input's scale (360° for an angle; a distance's
#: size, at least 1) of its value at a piece's end is met at the end: the ends of 8-bar
#: 15's pieces at a crank angle of 0° lie 1.7e-5° to 2.8e-5° from it.
END_SLACK = 1e-6

#: Input values within this fraction (of the value's size, at least 1) of a point's are met there.
VALUE_SLACK = 1e-12


def _refined(system: OneDofSystem, curve: LinkageCurve, driver: SceneInput, before: ConfigurationPoint,
             after: ConfigurationPoint, target: float) -> ConfigurationPoint | None:
    """The configuration between two neighbouring traced points at which the input is
    ``target`` (module docstring), with their sign vector; None where the input does not
    cross it on the curve between them."""
    for point in (before, after):  # met at a traced point (within VALUE_SLACK)
        if abs(_turned(driver, input_value(driver, point) - target)) <= VALUE_SLACK * max(1.0, abs(target)):
            return point
    first, last = curve.unknowns_of(before.joints), curve.unknowns_of(after.joints)

    def offset(along: float) -> float:
        x = on_chord(curve, first, last, along)
        return math.inf if x is None else _turned(driver, _input_of(curve, driver, x) - target)

    try:
        along = brentq(offset, 0.0, 1.0, xtol=1e-14)
    except ValueError:  # no sign change: the input does not reach the value here
        return None
    x = on_chord(curve, first, last, along)
    return None if x is None else replace(configurations_on_curve(system, curve, [x])[0], signs=before.signs)


def _input_of(curve: LinkageCurve, driver: SceneInput, x: np.ndarray) -> float:
    """The input's value at unknowns ``x`` of the curve."""
    at = curve.positions(x)
    joints = {name: (at[name].real * curve.size, at[name].imag * curve.size) for name in driver.joints}
    return input_value(driver, ConfigurationPoint({}, (), joints, 0.0))


def followed(traced: Trace, driven: list[DrivenBranch], start: int) -> DrivenBranch:
    """The driven configurations met when the linkage moves on from piece ``start``
    through the branch points at its ends, piece after piece, until it is back at a piece
    already met or at an end joined to none: one motion of the linkage, as a crank turning
    round, whose pieces the flat triangles of the branch points split (thesis §6.3). At a
    branch point the motion goes on to the other piece that meets there. The result is
    labelled with ``start``. O(pieces × branch points)."""
    by_piece = {branch.piece: branch for branch in driven}
    values: list[float] = []
    points: list[ConfigurationPoint] = []
    piece, entered, seen = start, 0, set()
    while piece not in seen:
        seen.add(piece)
        branch = by_piece.get(piece)
        if branch is not None:
            order = range(len(branch.points)) if entered == 0 else range(len(branch.points) - 1, -1, -1)
            values += [branch.values[k] for k in order]
            points += [branch.points[k] for k in order]
        leaving = (piece, -1 if entered == 0 else 0)
        onward = [other for point in traced.branch_points for end, other in (point.pieces, point.pieces[::-1])
                  if end == leaving and other[0] not in seen]
        if not onward:
            break
        piece, entered = onward[0]
    signs = traced.pieces[start].signs
    return DrivenBranch(start, signs, tuple(values), tuple(points))


def rigidified(scene: Scene, driver: SceneInput, degrees: float) -> Scene:
    """The rigid linkage ``scene`` becomes with its crank held at ``degrees``: ``driver``
    an angle at P_a from P_f to P_t with P_a and P_f on the fixed link and P_a, P_t the two
    joints of a binary link (the crank); the crank's tip P_t joins the fixed link, at
    P_a + |P_a P_t| (cos, sin)(φ + θ), φ the direction of P_f from P_a, and the crank and its
    pin P_a go. The other links keep their squared distances (and the orientation of
    their first three joints). Its modes are the configurations the driven motion lists at
    that value (tests/test_motion.py), found independently by a backend.

    Raises :class:`~baranov.scene.SceneError` for an input that is not such a crank."""
    at, towards, tip = driver.joints if driver.kind == "angle" else (None, None, None)
    crank = next((link for link in scene.links if link.name != scene.ground and set(link.joints) == {at, tip}), None)
    if crank is None or at not in scene.world or towards not in scene.world:
        raise SceneError(f"input {driver.name}: not a crank (an angle at a joint of the fixed link {scene.ground} "
                         "from another of its joints to the other joint of a binary link)")
    (ax, ay), (fx, fy) = (tuple(map(float, scene.world[name])) for name in (at, towards))
    radius = math.sqrt(float(crank.squared_distances[frozenset((at, tip))]))
    turn = math.atan2(fy - ay, fx - ax) + math.radians(degrees)
    ground = {name: [float(x), float(y)] for name, (x, y) in scene.world.items() if name != at}
    ground[tip] = [ax + radius * math.cos(turn), ay + radius * math.sin(turn)]
    links = [{"name": scene.ground, "joints": ground}]
    for link in scene.links:
        if link.name in (scene.ground, crank.name):
            continue
        links.append(link_entry(link))
    return scene_from_dict({"ground": scene.ground, "links": links})


def solve_held(scene: Scene, method: str = "numeric", **options):
    """Every configuration of a one-DOF ``scene`` whose crank input is held at the value
    the scene gives it (``"degrees"``): the rigid linkage of :func:`rigidified`, solved by
    ``method`` (:func:`baranov.solvers.solve`, with ``options``), each mode with the
    crank's pin added back at its place on the fixed link. The same configurations as the
    driven motion at that value (``baranov trace --input``). Raises
    :class:`~baranov.solvers.SolverError` for another kind of scene: mobility other than
    1, an input without a value, or one that is not a crank.

    >>> from baranov.scene import load_scene
    >>> import json
    >>> data = json.loads(open("examples/four-bar-coupler-point.json").read())
    >>> data["inputs"][0]["degrees"] = 30
    >>> from baranov.scene import scene_from_dict
    >>> len(solve_held(scene_from_dict(data)).assembly_modes)
    2
    """
    from dataclasses import replace

    from baranov.solvers import SolverError, solve

    valued = [driver for driver in scene.inputs if driver.value is not None]
    if scene.mobility != 1 or len(valued) != 1 or valued[0].kind != "angle":
        raise SolverError(f"mobility {scene.mobility} with {len(valued)} input(s) held: solve holds one crank angle "
                          "of a one-DOF linkage (\"degrees\" in its input); baranov trace SCENE --input NAME drives "
                          "any input (docs/motion.md)")
    driver = valued[0]
    try:
        rigid = rigidified(scene, driver, float(driver.value))
    except SceneError as error:
        raise SolverError(f"{error}; baranov trace SCENE --input {driver.name} drives it (docs/motion.md)") from None
    solution = solve(rigid, method=method, **options)
    pin = driver.joints[0]
    at = tuple(float(x) for x in scene.world[pin])
    modes = tuple(replace(mode, joints={**mode.joints, pin: at}) for mode in solution.assembly_modes)
    return replace(solution, assembly_modes=modes)


def crank_of(scene: Scene) -> SceneInput | None:
    """The crank input of ``scene``'s first binary link pinned to the fixed link: the
    angle at its pin P_a from the fixed link's next joint P_f to its tip P_t; None if no
    binary link has exactly one joint on the fixed link."""
    for link in scene.links:
        pinned = [joint for joint in link.joints if joint in scene.world]
        if link.name != scene.ground and len(link.joints) == 2 and len(pinned) == 1:
            at = pinned[0]
            towards = next(joint for joint in scene.world if joint != at)
            return SceneInput(f"crank {link.name}", "angle", (at, towards, next(j for j in link.joints if j != at)))
    return None
