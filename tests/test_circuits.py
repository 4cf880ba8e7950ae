"""Circuits of one-degree-of-freedom chains (issue 59): every loop of the configuration
curve traced once, every piece end joined, the polylines within the chord tolerance,
and the number of circuits equal to an independent count.

The independent count (:func:`slice_circuits`) does not follow the curve: it takes the
configurations of many slices of the plan's first parameter (the slice root finder,
:func:`~baranov.motion.configurations_at`), joins configurations of neighbouring slices
that are each other's nearest in joint space, and, where a pair of configurations of one
slice has no partner in the next (the curve turns back in the parameter between them: a
fold), joins the pair. Its connected components are the circuits; an interval where that
pairing is ambiguous is bisected."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from baranov.motion import configurations_at, one_dof_system, trace
from baranov.motion.continuation import chord_error, distance_to_polyline, linkage_curve
from baranov.scene import load_scene

#: Eight-bar 7 of issue 59, a random integer configuration.
ISSUE_INSTANCE = Path(__file__).resolve().parents[1] / "examples" / "eight-bar-7.json"


class _Components:
    def __init__(self) -> None:
        self.parent: dict = {}

    def root(self, node):
        self.parent.setdefault(node, node)
        while self.parent[node] != node:
            self.parent[node] = self.parent[self.parent[node]]
            node = self.parent[node]
        return node

    def join(self, a, b) -> None:
        self.parent[self.root(a)] = self.root(b)

    def count(self) -> int:
        return len({self.root(node) for node in list(self.parent)})


def _layer(system, curve, value: float) -> np.ndarray:
    """The configurations at a slice, as joint-space unknowns (scaled)."""
    return np.array([curve.unknowns_of(p.joints) for p in configurations_at(system, value)]).reshape(-1, curve.unknowns)


def _pairs_within(points: np.ndarray, near: float) -> list[tuple[int, int]] | None:
    """The points of one slice left without a partner, paired by nearness (each pair a
    fold of the curve between the slices); None if they cannot be paired so, or if a
    pair is not clearly closer (twenty times) than either of its points is to any other: next
    to a fold the two configurations that meet there are as close as the square root of
    the distance to it, and two configurations that differ in a nearly flat triangle's
    sign are close everywhere (eight-bar 15)."""
    distance = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    left, pairs = list(range(len(points))), []
    while left:
        first = left.pop(0)
        if not left:
            return None
        other = min(left, key=lambda k: distance[first, k])
        if distance[first, other] > near:
            return None
        rivals = [distance[end, k] for end in (first, other) for k in range(len(points)) if k not in (first, other)]
        if rivals and distance[first, other] > 0.05 * min(rivals):
            return None
        left.remove(other)
        pairs.append((first, other))
    return pairs


def _joined(a: np.ndarray, b: np.ndarray, near: float):
    """Mutual nearest neighbours of two neighbouring slices within ``near``, and the fold
    pairs of the rest of each; None where that is ambiguous."""
    if len(a) == 0 or len(b) == 0:
        matched = []
    else:
        distance = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
        matched = [(i, int(np.argmin(distance[i]))) for i in range(len(a))
                   if np.argmin(distance[:, np.argmin(distance[i])]) == i and distance[i].min() < near]
    rest_a = [i for i in range(len(a)) if i not in {i for i, _ in matched}]
    rest_b = [j for j in range(len(b)) if j not in {j for _, j in matched}]
    if rest_a and rest_b:  # a fold each way between two slices, or a stretch moving too fast: closer slices
        return None
    folds_a, folds_b = _pairs_within(a[rest_a], near), _pairs_within(b[rest_b], near)
    if folds_a is None or folds_b is None:
        return None
    return matched, [(rest_a[i], rest_a[j]) for i, j in folds_a], [(rest_b[i], rest_b[j]) for i, j in folds_b]


def slice_circuits(system, slices: int = 400, near: float = 0.05, depth: int = 24) -> int:
    """The number of connected components of the configuration curve, counted from
    ``slices`` slices of the first parameter (even in its square root) and one beyond its
    bound, as the module docstring says, an ambiguous interval bisected up to ``depth``
    times."""
    curve = linkage_curve(system.scene)
    components = _Components()
    # beyond the parameter's bound a slice is empty: the folds at the bound are paired there
    values = [*list(np.linspace(0.0, np.sqrt(system.upper[0]), slices + 2)[1:-1] ** 2), system.upper[0] * (1 + 1e-9)]
    layers = {value: _layer(system, curve, value) for value in values}
    for k in range(len(layers[values[0]])):
        components.root((values[0], k))
    stack = [(values[n], values[n + 1], 0) for n in range(len(values) - 1)][::-1]
    while stack:
        low, high, level = stack.pop()
        joined = _joined(layers[low], layers[high], near)
        if joined is None:
            # next to a domain edge the slice root finder can miss a root: each slice's
            # configurations carried over to the other by Newton's method, the new ones added
            layers[low], layers[high] = (_completed(system, curve, layers[low], layers[high], low),
                                         _completed(system, curve, layers[high], layers[low], high))
            joined = _joined(layers[low], layers[high], near)
        if joined is None and level < depth:
            middle = (low + high) / 2
            layers[middle] = _layer(system, curve, middle)
            stack += [(middle, high, level + 1), (low, middle, level + 1)]
            continue
        assert joined is not None, f"slices between {low} and {high} cannot be paired"
        matched, folds_low, folds_high = joined
        for k in range(len(layers[high])):
            components.root((high, k))
        for i, j in matched:
            components.join((low, i), (high, j))
        for i, j in folds_low:
            components.join((low, i), (low, j))
        for i, j in folds_high:
            components.join((high, i), (high, j))
    return components.count()


def _completed(system, curve, layer: np.ndarray, others: np.ndarray, value: float) -> np.ndarray:
    """``layer`` (the configurations at ``value``) with those Newton's method reaches at
    ``value`` from ``others`` (a neighbouring slice's) and does not already hold."""
    a, b = system.plan.parameters[0]
    found = list(layer)
    for x in others:
        y = x.copy()
        for _ in range(30):
            values, jacobian = curve.equations(y)
            at = curve.positions(y)
            gap = at[b] - at[a]
            row = np.zeros(curve.unknowns)
            for joint, sign in ((b, 2), (a, -2)):
                if joint in curve.columns:
                    k = curve.columns[joint]
                    row[k:k + 2] += sign * gap.real, sign * gap.imag
            residual = np.append(values, abs(gap) ** 2 - value / curve.size ** 2)
            if np.abs(residual).max() < 1e-14:
                break
            y = y - np.linalg.lstsq(np.vstack([jacobian, row]), residual, rcond=None)[0]
        if np.abs(residual).max() < 1e-12 and all(np.linalg.norm(y - z) > 1e-9 for z in found):
            found.append(y)
    return np.array(found).reshape(-1, curve.unknowns)


def assert_traced_once(system, traced, rng: np.random.Generator, values: int = 12, chord: float = 1e-3) -> None:
    """No loose end, no unfinished loop; every configuration of ``values`` random slices
    on exactly one piece (within 2 · chord in joint space); every segment's arc within
    ``chord`` of it; as many circuits as :func:`slice_circuits` counts."""
    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    assert traced.loose_ends == () and traced.unfinished == ()
    polylines = [np.array([curve.unknowns_of(p.joints) for p in piece.points]) for piece in traced.pieces]
    found = [p for value in rng.uniform(0, system.upper[0], values) for p in configurations_at(system, float(value))]
    assert found
    for point in found:
        x = curve.unknowns_of(point.joints)
        on = [n for n, line in enumerate(polylines)
              if distance_to_polyline(x, line, traced.pieces[n].closed) < 2 * chord]
        if len(on) == 2:  # within the tolerance of a branch point, on the pieces meeting there
            ends = {end: polylines[end[0]][end[1]] for point in traced.branch_points for end in point.pieces}
            shared = [a for a in ends if a[0] == on[0] and any(b[0] == on[1] and np.allclose(ends[a], ends[b])
                                                                 for b in ends)]
            assert any(np.linalg.norm(ends[a] - x) < 4 * chord for a in shared), (point.parameters, on)
            on = [n for n in on if traced.pieces[n].signs == point.signs]
        assert len(on) == 1, (point.parameters, on)
        assert traced.pieces[on[0]].signs == point.signs
    worst = max(chord_error(curve, a, b) for n, line in enumerate(polylines)
                for a, b in zip(line, [*line[1:], *line[:1]] if traced.pieces[n].closed else line[1:], strict=False))
    assert worst <= chord, worst
    assert len(traced.circuits) == slice_circuits(system)


def test_the_issue_instance_is_traced_once():
    """Eight-bar 7 of issue 59 (a random integer configuration): before, 37 pieces, one
    loop of η 12 traced eleven times, 7 ends not joined. Now each loop once: four
    circuits (the slice count's), 27 pieces, every end joined."""
    system = one_dof_system(load_scene(ISSUE_INSTANCE))
    traced = trace(system)
    assert_traced_once(system, traced, np.random.default_rng(59))
    assert (len(traced.circuits), len(traced.pieces), len(traced.branch_points)) == (4, 27, 26)


def _chains() -> list:
    from baranov.enumerate.crosscheck import find_geng

    if find_geng() is None:
        return []
    from baranov.enumerate.grubler import grubler_chains

    return [pytest.param(links, n, seed, id=f"{links}-{n}-seed{seed}") for links in (6, 8)
            for n in range(len(grubler_chains(links))) for seed in (0, 1)]


@pytest.mark.parametrize(("links", "index", "seed"), _chains())
def test_random_six_and_eight_bars_are_traced_once(links, index, seed):
    """Both six-bars and all sixteen eight-bars, two random integer configurations each
    (seeds [59, links, index, seed], not chosen): :func:`assert_traced_once`."""
    from baranov.enumerate.grubler import grubler_chains
    from baranov.scene.instances import generic_integer_configuration, scene_of

    rng = np.random.default_rng([59, links, index, seed])
    chain = grubler_chains(links)[index]
    system = one_dof_system(scene_of(chain, generic_integer_configuration(chain, rng)))
    assert_traced_once(system, trace(system), rng)


def test_the_command_lists_the_circuits(capsys):
    """`baranov trace` prints the circuits and their branches; --json lists them."""
    from baranov.cli.main import main

    path = ISSUE_INSTANCE
    assert main(["trace", str(path)]) == 0
    out = capsys.readouterr().out
    assert "4 circuits, 27 pieces in (s1,10, s3,10), 26 branch points, 0 singular configurations, " \
           "0 piece ends not joined" in out
    assert "circuit 2: 1 branch (pieces 22), 0 branch points" in out
    assert main(["trace", str(path), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert len(result["circuits"]) == 4 and result["loose_ends"] == [] and result["unfinished"] == []
    assert sorted(n for circuit in result["circuits"] for n in circuit["pieces"]) == list(range(27))
    assert main(["trace", str(path), "--chord", "0"]) == 2
    assert "--chord 0: between 1e-9 and 0.1" in capsys.readouterr().err



def _four_bar(frame: int, crank: int, coupler: int, rocker: int):
    """The one-DOF system of a four-bar: frame P1 P4 on the x axis, crank P1 P2, coupler
    P2 P3, rocker P3 P4."""
    from baranov.scene import scene_from_dict

    return one_dof_system(scene_from_dict({"ground": "frame", "links": [
        {"name": "frame", "joints": {"P1": [0, 0], "P4": [frame, 0]}},
        {"name": "crank", "joints": ["P1", "P2"], "squared_length": crank ** 2},
        {"name": "coupler", "joints": ["P2", "P3"], "squared_length": coupler ** 2},
        {"name": "rocker", "joints": ["P3", "P4"], "squared_length": rocker ** 2}]}))


@pytest.mark.parametrize(("kind", "lengths", "circuits", "singular"), [
    ("crank-rocker", (7, 2, 6, 5), 2, 0), ("double-crank", (2, 6, 7, 5), 2, 0), ("double-rocker", (6, 5, 2, 7), 2, 0),
    ("triple-rocker", (5, 3, 4, 7), 1, 0), ("change-point", (5, 2, 4, 3), 1, 1)])
def test_four_bars_have_the_classical_circuits(kind, lengths, circuits, singular):
    """Four-bars (frame, crank, coupler, rocker): a Grashof linkage (s + l < p + q) has two
    circuits, the two assembly configurations it cannot pass between; a non-Grashof one
    (a triple-rocker) one; at the change point (s + l = p + q) the two circuits meet at a
    singular configuration, every joint in line, and are one (Chase and Mirth 1993)."""
    system = _four_bar(*lengths)
    traced = trace(system)
    assert (len(traced.circuits), len(traced.singular_points)) == (circuits, singular)
    assert traced.loose_ends == () and traced.unfinished == ()
    if singular:
        joints = traced.singular_points[0].point.joints
        assert all(abs(y) < 1e-6 for _, y in joints.values())  # every joint on the frame's line
    else:
        assert assert_traced_once(system, traced, np.random.default_rng(1)) is None


def _degrees(cosine: float) -> float:
    import math

    return math.degrees(math.acos(cosine))


@pytest.mark.parametrize(("lengths", "joints", "per_circuit", "extremes"), [
    ((7, 2, 6, 5), ("P1", "P4", "P2"), [0, 0], []),  # crank-rocker, its crank turns round
    ((7, 2, 6, 5), ("P4", "P1", "P3"), [2, 2], [_degrees(10 / 70), _degrees(58 / 70)]),  # its rocker: crank in line
    ((2, 6, 7, 5), ("P1", "P4", "P2"), [0, 0], []),  # double-crank
    ((6, 5, 2, 7), ("P1", "P4", "P2"), [2, 2], [_degrees(-1 / 3), _degrees(0.6)]),  # double-rocker
    ((5, 3, 4, 7), ("P1", "P4", "P2"), [2], [_degrees(25 / 30)])])  # triple-rocker: between ±33.56°
def test_dead_points_cut_circuits_into_branches(lengths, joints, per_circuit, extremes):
    """Chase and Mirth's branches relative to an input: a four-bar's input is stationary
    where the other two moving links are in line (law of cosines for the extreme angles);
    each circuit with k > 0 dead points has k branches, a crank that turns round none."""
    from baranov.motion.dead_points import dead_points
    from baranov.scene import SceneInput

    system = _four_bar(*lengths)
    traced = trace(system)
    found = dead_points(system, traced, SceneInput("input", "angle", joints))
    assert [sum(point.circuit == n for point in found) for n in range(len(traced.circuits))] == per_circuit
    assert sorted({round(abs(point.value), 6) for point in found}) == sorted(round(value, 6) for value in extremes)
    assert all(abs(abs(point.value) - min(extremes, key=lambda e: abs(e - abs(point.value)))) < 1e-7 for point in found)
