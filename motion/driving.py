"""The motion driven by an input (issue 19): for each value of an input on a grid — an
angle between two links at their joint (a crank against the ground), or the squared
distance between two joints (a linear actuator): a :class:`~baranov.scene.SceneInput` —
every configuration of the linkage, grouped by the traced
piece it lies on and ordered along it, so that following one branch never jumps to
another (the failure of predictor–corrector tracing in the workspace that thesis ch. 6
removes: the branches are the pieces of the configuration space, split by the signs of
the free-sign triangles).

A configuration at an input value is located between two neighbouring traced points
where the input crosses the value, then refined: d = 1 by Brent's method on the one
parameter (the plan places the configuration exactly at each value), d = 2 by Newton's
method on the closure condition and the input together, started from the linear
interpolation of the two points' parameters. Every configuration is verified on the link
dimensions (1e-8, relative) as the traced ones are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from baranov.scene import Scene, SceneError, SceneInput, link_entry, scene_from_dict
from baranov.solvers.placement import placed_configurations

from .configuration_space import ConfigurationPoint, OneDofSystem, slice_configurations, verified_configurations
from .tracing import Piece, Trace


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
    branches = []
    for index, piece in enumerate(traced.pieces):
        values, points = [], []
        if len(system.parameter_names) == 1:
            piece = _with_extrema(system, driver, piece)
        for before, after in _segments(piece):
            for target in _crossed(driver, before, after, grid):
                _keep(values, points, target, _refined(system, driver, before, after, target))
        if not piece.closed:  # a value just beyond an end, met at the end itself (_beyond)
            for target in _beyond(driver, piece.points[-1], grid):
                _keep(values, points, target, piece.points[-1])
            for target in _beyond(driver, piece.points[0], grid):
                _keep(values, points, target, piece.points[0], first=True)
        if points:
            branches.append(DrivenBranch(index, piece.signs, tuple(values), tuple(points)))
    return branches


def _with_extrema(system: OneDofSystem, driver: SceneInput, piece: Piece) -> Piece:
    """d = 1: ``piece`` with the configuration at each local extremum of the input along
    it added, located to 1e-13 of the parameter's range (a bounded scalar search between
    the samples around it): a dead point of the input (a four-bar rocker's extreme angle)
    lies between two samples, and the values between the higher sample and the extremum
    would be missed (a double-rocker's crank: 109.4633° traced, 109.4712° = arccos(−1/3)
    reached)."""
    name = system.parameter_names[0]
    points = list(piece.points)
    inputs = [input_value(driver, point) for point in points]
    steps = [_turned(driver, after - before) for before, after in zip(inputs, inputs[1:], strict=False)]
    added = []
    for k in range(1, len(points) - 1):
        if steps[k - 1] * steps[k] >= 0:
            continue
        sign = 1.0 if steps[k - 1] > 0 else -1.0  # a maximum: minimise −input
        low, high = sorted((points[k - 1].parameters[name], points[k + 1].parameters[name]))

        def negated(value: float, sign=sign, reference=inputs[k]) -> float:
            found = verified_configurations(system, np.array([[value]]), np.array(piece.signs)[None, :])
            return -sign * _turned(driver, input_value(driver, found[0]) - reference) if found else math.inf

        best = minimize_scalar(negated, bounds=(low, high), method="bounded",
                               options={"xatol": 1e-13 * system.upper[0]})
        found = verified_configurations(system, np.array([[best.x]]), np.array(piece.signs)[None, :])
        if found and abs(best.x - points[k].parameters[name]) > 0:
            added.append((k, found[0]))
    for k, point in reversed(added):  # in order of the parameter, next to the sample it refines
        at = points[k].parameters[name]
        forward = points[-1].parameters[name] >= points[0].parameters[name]
        later = (point.parameters[name] > at) == forward
        points.insert(k + 1 if later else k, point)
    return Piece(piece.signs, tuple(points), piece.closed)


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


def _refined(system: OneDofSystem, driver: SceneInput, before: ConfigurationPoint, after: ConfigurationPoint,
             target: float, splits: int = 0) -> ConfigurationPoint | None:
    """The verified configuration between two neighbouring traced points at which the
    input is ``target`` (module docstring), or None where none is found. d = 2: where
    Newton's method fails from the interpolation, the stretch is split at a point of the
    curve between them (:func:`_middle_on_curve`) and the half the input crosses
    ``target`` on is refined instead, at most MAX_SPLITS times."""
    names = system.parameter_names
    branch = np.array(before.signs)[None, :]
    start = np.array([before.parameters[name] for name in names])
    end = np.array([after.parameters[name] for name in names])

    def placed(values: np.ndarray) -> ConfigurationPoint | None:
        found = verified_configurations(system, values[None, :], branch)
        return found[0] if found else None

    def offset(point: ConfigurationPoint) -> float:
        return _turned(driver, input_value(driver, point) - target)

    for point in (before, after):  # met at a traced point (within VALUE_SLACK)
        if abs(offset(point)) <= VALUE_SLACK * max(1.0, abs(target)):
            return point

    if len(names) == 1:
        try:
            root = brentq(lambda s: offset(placed(np.array([s]))), start[0], end[0], xtol=1e-13 * system.upper[0])
        except (ValueError, TypeError):  # the ends place no configuration or do not bracket
            return None
        return placed(np.array([root]))

    def offset_anywhere(values: np.ndarray) -> float | None:  # off the curve too: Newton's iterates
        joints, points = placed_configurations(system.scene, system.compiled, values[None, :], branch)
        if not np.isfinite(points).all():
            return None
        where = {name: (point.real, point.imag) for name, point in zip(joints, points[0], strict=True)}
        return offset(ConfigurationPoint({}, (), where, math.inf))

    found = _newton(system, branch, start, end, offset_anywhere)
    if found is not None or splits >= MAX_SPLITS:
        return found
    middle = _middle_on_curve(system, before, after)
    if middle is None:
        return None
    for first, second in ((before, middle), (middle, after)):
        if _crossed(driver, first, second, np.array([target])):
            return _refined(system, driver, first, second, target, splits + 1)
    return None


#: Splits of a stretch where Newton's method fails (:func:`_refined`), and the samples of
#: the slice that finds a point of the curve between its ends (:func:`_middle_on_curve`).
MAX_SPLITS = 12
MIDDLE_SAMPLES = 64


def _middle_on_curve(system: OneDofSystem, before: ConfigurationPoint,
                     after: ConfigurationPoint) -> ConfigurationPoint | None:
    """d = 2: a configuration on the curve between two neighbouring traced points of one
    piece: on the slice halfway between them along the parameter that changes more
    (relatively), the root of the closure condition on their branch nearest their joints'
    midpoint (MIDDLE_SAMPLES samples of the other parameter over three times the two
    points' spread, with the roots next to a domain edge). Where the curve bends sharply
    in the parameters the linear interpolation of two traced points can lie outside the
    domain: eight-bar 9 of docs/stability.md, P10 0.87 from P1 (s1,10 between 0.63 and
    0.90) as the crank passes 180°."""
    names = system.parameter_names
    first = np.array([before.parameters[name] for name in names])
    second = np.array([after.parameters[name] for name in names])
    axis = int(np.argmax(np.abs(second - first) / np.maximum(np.abs(first) + np.abs(second), 1e-300)))
    other = 1 - axis
    low, high = sorted((first[other], second[other]))
    spread = max(high - low, 1e-9 * system.upper[other])
    grid = np.linspace(max(low - spread, 1e-12 * system.upper[other]), high + spread, MIDDLE_SAMPLES)
    found = slice_configurations(system, (first[axis] + second[axis]) / 2, grid, np.array(before.signs)[None, :], axis)
    if not found:
        return None
    middle = {name: ((before.joints[name][0] + after.joints[name][0]) / 2,
                     (before.joints[name][1] + after.joints[name][1]) / 2) for name in before.joints}
    return min(found, key=lambda point: max(math.dist(point.joints[name], middle[name]) for name in middle))


def _newton(system: OneDofSystem, branch: np.ndarray, start: np.ndarray, end: np.ndarray,
            offset) -> ConfigurationPoint | None:
    """d = 2: the closure condition and the input's offset both 0, by Newton's method
    with a forward-difference Jacobian from the interpolation of ``start`` and ``end``
    where the input's offset is linear between them."""
    first, last = offset(start), offset(end)
    if first is None or last is None or first == last:
        return None
    values = start + (end - start) * first / (first - last)
    scale = np.array(system.upper)
    residual = _equations(system, branch, values, offset)
    for _ in range(NEWTON_STEPS):
        if residual is None:
            return None
        if np.max(np.abs(residual)) < 1e-12:
            break
        jacobian = np.empty((2, 2))
        for column in range(2):
            # relative to the value: a step of 1e-7 of the range left s1,10 = 0.77 (P10
            # 0.87 from P1 on eight-bar 9 of docs/stability.md) for the undefined region
            step = np.zeros(2)
            step[column] = 1e-7 * max(abs(values[column]), 1e-9 * scale[column])
            moved = _equations(system, branch, values + step, offset)
            if moved is None:
                return None
            jacobian[:, column] = (moved - residual) / step[column]
        try:
            step = np.linalg.solve(jacobian, residual)
        except np.linalg.LinAlgError:
            return None
        values, residual = _damped(system, branch, values, step, residual, offset)
    found = verified_configurations(system, values[None, :], branch)
    return found[0] if found else None


#: Newton steps of :func:`_newton`, and halvings of a step that does not lower the residual.
NEWTON_STEPS = 30
HALVINGS = 12


def _damped(system: OneDofSystem, branch: np.ndarray, values: np.ndarray, step: np.ndarray,
            residual: np.ndarray, offset) -> tuple[np.ndarray, np.ndarray | None]:
    """``values − step``, the step halved (at most HALVINGS times) until the equations are
    defined there and their largest residual lower; the full step if none is (a last
    try, as plain Newton)."""
    size = np.max(np.abs(residual))
    for halving in range(HALVINGS):
        trial = values - step / 2**halving
        moved = _equations(system, branch, trial, offset)
        if moved is not None and np.max(np.abs(moved)) < size:
            return trial, moved
    return values - step, _equations(system, branch, values - step, offset)


def _equations(system: OneDofSystem, branch: np.ndarray, values: np.ndarray, offset) -> np.ndarray | None:
    closure = system.compiled.residuals(values[None, :], branch)[0, 0, 0]
    moved = offset(values)
    if moved is None or not np.isfinite(closure):
        return None
    return np.array([closure, moved])


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
