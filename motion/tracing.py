"""Tracing a one-degree-of-freedom chain's configuration space (thesis §6.3): every loop
of its configuration curve followed once, cut into pieces of one sign vector each at the
branch points where an oriented area vanishes, and the loops gathered into circuits.

**Loops.** The curve is followed in the joints' coordinates, where it is smooth through a
flat triangle (:mod:`.continuation`), from configurations found on slices of the plan's
first parameter (:func:`~.configuration_space.configurations_at`): a starting
configuration already within ``2 · chord`` of a followed loop is on it and skipped, so
each loop is followed once, and it closes when it passes its start again. A loop's
points lie within ``chord`` (of the linkage's size) of the curve between neighbours, and
no joint moves more than ``jump`` between them.

**Pieces and branch points.** Where one of the plan's free-sign triangles turns flat
along a loop (a crossing, located to rounding), the linkage passes from one sign vector to
the one with that triangle's sign flipped (thesis §6.3): the loop is cut there, and the
branch point joins the piece ending there to the piece starting there. A loop without a
crossing is one closed piece. Every piece end is thus joined; an end stays loose only
where a loop could not be finished (:attr:`Trace.unfinished` says why).

**Circuits** (:class:`Circuit`; Chase and Mirth, "Circuits and branches of
single-degree-of-freedom planar linkages", J. Mech. Des. 115, 1993): the connected
components of the real configuration curve, between which the linkage cannot pass without
being taken apart. A loop is one circuit unless it passes a singular configuration (the
Jacobian of the link equations loses rank: two branches of the curve cross, as in a
change-point four-bar) that another loop passes too; then they are one circuit. A
circuit's *branches* are its pieces: the arcs between its branch points, along which the
plan's sign vector is fixed.

Completeness: a loop is found if one of the slices meets it — ``steps`` slices for one
parameter (the whole range, a slice is one placement per sign vector), ``steps // 8`` for
two (4000 samples each); a circuit that lies between two neighbouring slices is missed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from baranov.solvers.verification import joint_residuals

from .configuration_space import ConfigurationPoint, OneDofSystem, configurations_at
from .continuation import LinkageCurve, Loop, distance_to_polyline, followed_loop, linkage_curve, singular_point


@dataclass(frozen=True)
class Piece:
    """One piece of the configuration space: its sign vector (the plan's free-sign
    triangles) and its configurations in order along it; ``closed`` if it is a loop."""

    signs: tuple[int, ...]
    points: tuple[ConfigurationPoint, ...]
    closed: bool = False

    @property
    def middle(self) -> ConfigurationPoint:
        """Its middle point: its ends are branch points, where a triangle is flat and its
        sign is not the piece's."""
        return self.points[len(self.points) // 2]


@dataclass(frozen=True)
class BranchPoint:
    """Where free-sign triangles (``flat``: one, or several where they turn flat at one
    configuration) are flat: the ends of two pieces (index, 0 for the first point or -1
    for the last) that meet there, and the plan's parameters there."""

    pieces: tuple[tuple[int, int], tuple[int, int]]
    parameters: dict[str, float]
    flat: tuple[tuple[str, str, str], ...] = ()


@dataclass(frozen=True)
class SingularPoint:
    """A singular configuration of the linkage passed by a loop (the Jacobian of its link
    equations loses rank; generically two branches of the curve cross there): its joints
    and parameters, and the pieces whose polylines pass it."""

    point: ConfigurationPoint
    pieces: tuple[int, ...]


@dataclass(frozen=True)
class Circuit:
    """A connected component of the real configuration curve (module docstring): its
    loops, each the pieces (its branches) in order along it, the branch points joining
    them, and the singular configurations on it (indices into :attr:`Trace.pieces`,
    :attr:`Trace.branch_points`, :attr:`Trace.singular_points`). One loop, unless loops
    meet at a singular configuration."""

    loops: tuple[tuple[int, ...], ...]
    branch_points: tuple[int, ...]
    singular_points: tuple[int, ...] = ()

    @property
    def pieces(self) -> tuple[int, ...]:
        """Its pieces, loop after loop."""
        return tuple(n for loop in self.loops for n in loop)


@dataclass(frozen=True)
class Trace:
    """A traced configuration space: the pieces, the branch points joining them, the
    circuits, the singular configurations passed, the steps at which neighbouring points
    of a piece are farther apart than expected, and why a loop was left unfinished."""

    pieces: tuple[Piece, ...]
    branch_points: tuple[BranchPoint, ...]
    jumps: tuple[str, ...] = field(default=())
    circuits: tuple[Circuit, ...] = field(default=())
    singular_points: tuple[SingularPoint, ...] = field(default=())
    unfinished: tuple[str, ...] = field(default=())

    @property
    def loose_ends(self) -> tuple[tuple[int, int], ...]:
        """Ends of open pieces (index, 0 or −1) at no branch point: the ends of a loop the
        tracer could not finish (:attr:`unfinished`)."""
        joined = {end for point in self.branch_points for end in point.pieces}
        return tuple((n, end) for n, piece in enumerate(self.pieces) if not piece.closed for end in (0, -1)
                     if (n, end) not in joined)


def trace(system: OneDofSystem, steps: int = 400, jump: float = 0.02, chord: float = 1e-3) -> Trace:
    """The configuration space of ``system`` traced (module docstring): each loop of its
    curve followed once from the configurations of ``steps`` slices (``steps // 8`` for
    two parameters), its points within ``chord`` of the curve and no joint moving more
    than ``jump`` between neighbours (both fractions of the linkage's size). Cost: per
    loop point a few 2n × 2n solves (n joints); per slice one vectorised placement (two
    parameters: 4000 samples of the closure condition per sign vector)."""
    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    loops: list[Loop] = []
    for start in _starting_configurations(system, steps):
        x = curve.unknowns_of(start.joints)
        # a loop is not started at a flat triangle: its crossing there would be met only once
        if np.abs(curve.areas(x)).min(initial=1.0) < FLAT_START or any(
                distance_to_polyline(x, loop.points, loop.closed) < 2 * chord for loop in loops):
            continue
        loops.append(_whole_loop(curve, x, chord, jump))
    pieces, branch_points, owners = [], [], []
    for number, loop in enumerate(loops):
        found, joined = _loop_pieces(system, curve, loop, len(pieces))
        pieces += found
        branch_points += joined
        owners += [number] * len(found)
    singular = _singular_points(system, curve, loops, owners)
    circuits = _circuits(loops, owners, branch_points, singular)
    size = curve.size
    jumps = [f"piece {n}, between points {k} and {k + 1}: a joint moves {moved / size:.3g} of the linkage's size"
             for n, piece in enumerate(pieces) for k, moved in _moves(piece) if moved > 2 * jump * size]
    unfinished = tuple(f"loop {n}: {loop.unfinished}" for n, loop in enumerate(loops) if not loop.closed)
    return Trace(tuple(pieces), tuple(branch_points), tuple(jumps), circuits, singular, unfinished)


#: A starting configuration with a free-sign triangle's area (scaled) below this is not
#: used: a slice through a branch point (the crank in line at the parameter's bound).
FLAT_START = 1e-8


def _starting_configurations(system: OneDofSystem, steps: int) -> list[ConfigurationPoint]:
    """The configurations of ``steps`` slices of the first parameter, even in its square
    root (one parameter), or of ``steps // 8`` slices across the stretch where it has
    configurations (two)."""
    if len(system.plan.parameters) == 1:
        values = np.linspace(0.0, math.sqrt(system.upper[0]), steps + 2)[1:-1] ** 2
    else:
        slices = max(steps // 8, 8)
        low, high = _range(system, slices)
        values = np.linspace(low, high, slices + 2)[1:-1]
    return [point for value in values for point in configurations_at(system, float(value))]


def _whole_loop(curve: LinkageCurve, x: np.ndarray, chord: float, jump: float) -> Loop:
    """The loop through ``x``; if it cannot be closed, followed the other way from ``x``
    too, so that only the stretch the tracer could not pass is missing."""
    loop = followed_loop(curve, x, chord, jump)
    if loop.closed:
        return loop
    back = followed_loop(curve, x, chord, jump, backwards=True)
    count = len(back.points)
    points = back.points[:0:-1] + loop.points
    crossings = [(count - 1 - k, t) for k, t in reversed(back.crossings)] + [(k + count - 1, t) for k, t in loop.crossings]
    singular = [count - 2 - k for k in reversed(back.singular)] + [k + count - 1 for k in loop.singular]
    reasons = "; ".join(dict.fromkeys(r for r in (back.unfinished, loop.unfinished) if r))
    return Loop(points, crossings, singular, False, reasons)


def _loop_pieces(system: OneDofSystem, curve: LinkageCurve, loop: Loop,
                 first: int) -> tuple[list[Piece], list[BranchPoint]]:
    """A loop cut into pieces at its crossings (numbered from ``first``), and the branch
    points joining consecutive ones (module docstring)."""
    points = configurations_on_curve(system, curve, loop.points)
    cuts = [k for k, _ in loop.crossings]
    triangles = [tuple(system.plan.free_sign_triangles[t] for t in flat) for _, flat in loop.crossings]
    if not cuts:
        return [Piece(_piece_signs(points), tuple(points), loop.closed)], []
    if loop.closed:  # from the first crossing round to it again
        spans = [(a, b) for a, b in zip(cuts, cuts[1:], strict=False)] + [(cuts[-1], cuts[0] + len(points))]
        joints = list(zip(range(len(cuts)), [*range(1, len(cuts)), 0], triangles[1:] + triangles[:1], strict=True))
    else:
        spans = [(0, cuts[0]), *zip(cuts, cuts[1:], strict=False), (cuts[-1], len(points) - 1)]
        joints = [(k, k + 1, triangles[k]) for k in range(len(cuts))]
    pieces = []
    for a, b in spans:
        stretch = [points[k % len(points)] for k in range(a, b + 1)]
        signs = _piece_signs(stretch)
        pieces.append(Piece(signs, tuple(replace(point, signs=signs) for point in stretch)))
    branch_points = [BranchPoint(((first + a, -1), (first + b, 0)), pieces[b].points[0].parameters, triangle)
                     for a, b, triangle in joints]
    return pieces, branch_points


def configurations_on_curve(system: OneDofSystem, curve: LinkageCurve, points: list[np.ndarray]) -> list[ConfigurationPoint]:
    """The loop's points as configurations: world joints, the plan's parameters, the
    signs of its free-sign triangles' areas (0 where flat to rounding) and the residual
    on the link dimensions."""
    names = sorted({joint for link in system.scene.links for joint in link.joints})
    placed = [curve.positions(x) for x in points]
    world = np.array([[place[name] * curve.size for name in names] for place in placed])
    residuals = joint_residuals(system.scene, names, world)
    found = []
    for row, x, residual in zip(world, points, residuals, strict=True):
        joints = {name: (value.real, value.imag) for name, value in zip(names, row, strict=True)}
        parameters = {name: (joints[u][0] - joints[v][0]) ** 2 + (joints[u][1] - joints[v][1]) ** 2
                      for name, (u, v) in zip(system.parameter_names, system.plan.parameters, strict=True)}
        areas = curve.areas(x)
        signs = tuple(int(s) for s in np.sign(np.where(np.abs(areas) < 1e-14, 0.0, areas)))
        found.append(ConfigurationPoint(parameters, signs, joints, float(residual)))
    return found


def _piece_signs(stretch: list[ConfigurationPoint]) -> tuple[int, ...]:
    """The sign vector of a piece: at each triangle, its sign at the point nearest the
    piece's middle where it is not flat (the ends are branch points, flat)."""
    middle = len(stretch) // 2
    outward = sorted(range(len(stretch)), key=lambda k: abs(k - middle))
    return tuple(next((stretch[k].signs[t] for k in outward if stretch[k].signs[t] != 0), 1)
                 for t in range(len(stretch[0].signs)))


def _singular_points(system: OneDofSystem, curve: LinkageCurve, loops: list[Loop],
                     owners: list[int]) -> tuple[SingularPoint, ...]:
    """The singular configurations the loops passed, located by bisection, one record per
    place (two loops through one crossing of branches share it), with the pieces of the
    loops that pass it."""
    found: list[tuple[np.ndarray, set[int]]] = []
    for number, loop in enumerate(loops):
        pieces = {n for n, owner in enumerate(owners) if owner == number}
        for k in loop.singular:
            x = singular_point(curve, loop.points[k], loop.points[(k + 1) % len(loop.points)])
            same = next((entry for entry in found if np.linalg.norm(entry[0] - x) < 1e-6), None)
            if same is None:
                found.append((x, set(pieces)))
            else:
                same[1].update(pieces)
    return tuple(SingularPoint(configurations_on_curve(system, curve, [x])[0], tuple(sorted(pieces))) for x, pieces in found)


def _circuits(loops: list[Loop], owners: list[int], branch_points: list[BranchPoint],
              singular: tuple[SingularPoint, ...]) -> tuple[Circuit, ...]:
    """Loops joined by a singular configuration they share, as circuits (module
    docstring)."""
    group = list(range(len(loops)))

    def root(n: int) -> int:
        while group[n] != n:
            n = group[n]
        return n

    for point in singular:
        loops_there = sorted({owners[n] for n in point.pieces})
        for other in loops_there[1:]:
            group[root(other)] = root(loops_there[0])
    circuits = []
    for head in dict.fromkeys(root(n) for n in range(len(loops))):
        members = tuple(tuple(n for n, owner in enumerate(owners) if owner == loop)
                        for loop in range(len(loops)) if root(loop) == head)
        pieces = {n for loop in members for n in loop}
        joined = tuple(k for k, point in enumerate(branch_points) if point.pieces[0][0] in pieces)
        places = tuple(k for k, point in enumerate(singular) if set(point.pieces) & pieces)
        circuits.append(Circuit(members, joined, places))
    return tuple(circuits)


def circuit_of(traced: Trace, joints: dict[str, tuple[float, float]]) -> tuple[int, float]:
    """The circuit of ``traced`` a configuration (joint name → place, the scene's joints)
    lies on: the index of the circuit whose pieces pass nearest it, and that distance (the
    largest over the joints, from the nearest traced point: at most about the chord
    tolerance plus half a step for a configuration of the linkage). Two configurations
    the linkage can move between without being taken apart have the same circuit. Cost:
    linear in the traced points.

    >>> from pathlib import Path
    >>> from baranov.motion import one_dof_system, trace
    >>> from baranov.scene import load_scene
    >>> examples = Path(__file__).resolve().parents[1] / "examples"
    >>> four_bar = load_scene(examples / "four-bar-coupler-point.json")  # frame 7, crank 2, coupler 6, rocker 5
    >>> traced = trace(one_dof_system(four_bar))
    >>> up = {"P1": (0, 0), "P2": (2, 0), "P3": (5.6, 4.8), "P4": (7, 0)}
    >>> down = {"P1": (0, 0), "P2": (2, 0), "P3": (5.6, -4.8), "P4": (7, 0)}
    >>> len(traced.circuits), circuit_of(traced, up)[0] != circuit_of(traced, down)[0]
    (2, True)
    """
    names = sorted(joints)
    target = np.array([joints[name] for name in names], float)
    best = (-1, math.inf)
    for number, circuit in enumerate(traced.circuits):
        for n in circuit.pieces:
            points = np.array([[point.joints[name] for name in names] for point in traced.pieces[n].points], float)
            distance = float(np.linalg.norm(points - target, axis=2).max(axis=1).min())
            if distance < best[1]:
                best = (number, distance)
    return best


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
