"""Scenes: concrete linkages with link dimensions, read from JSON or Python data.

A scene lists links; each link gives either

* ``"joints": {"P3": [x, y], ...}`` — joint coordinates in a frame of the link's own
  (the ground link's coordinates are world coordinates);
* ``"joints": ["P1", "P2"], "squared_length": s`` — a binary link;
* ``"joints": [...], "squared_distances": {"P3,P1": s, ...}, "orientation": "ccw"|"cw"``
  — a k-ary link by all its pairwise squared distances and the orientation of its first
  three listed joints. A ground link given this way is placed with its first joint at
  the origin and its second on the +x axis.

Numbers may be integers, decimals, or exact strings such as ``"9/5"``. In a JSON file
(:func:`load_scene`) a decimal literal is the exact decimal its author wrote: ``2.5`` is
5/2 and ``0.1`` is 1/10, so every scene file is exact and the exact backend takes it. In
Python data (:func:`scene_from_dict`) integers, :class:`fractions.Fraction`,
:class:`decimal.Decimal` and strings are exact, and a ``float`` is a binary float: it
marks the scene inexact (give ``"5/2"`` or ``Fraction(5, 2)`` for exactness).

Slider joints are listed under ``"sliders"`` (:mod:`~baranov.scene.sliders`; docs/scenes.md).
A linkage with mobility F = 3(L − 1) − 2J > 0 (a four-bar, a six-bar) is a scene too,
with up to F named ``"inputs"`` (a driven angle or distance: :mod:`~baranov.scene.inputs`);
the backends solve rigid scenes (F = 0) and refuse it; ``baranov trace`` traces it. Points
of links that are not joints, whose paths a trace draws, are listed under ``"tracers"``
(:mod:`~baranov.scene.tracers`).

Besides ``"links"`` and ``"ground"``, a scene may carry ``"comment"`` and the
annotations of saved instances (``"verified_modes"``, ``"generating_configuration"``,
``"generating_tolerance"``), which the solvers ignore; a link may carry a
``"comment"``. Any other key is an error (a misspelt ``"grund"`` is not silently
dropped). Every invalid input raises :class:`SceneError` (a ``ValueError``) naming the
link, joint or key.
"""

from __future__ import annotations

import difflib
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from decimal import Decimal
from fractions import Fraction
from functools import cached_property
from itertools import combinations
from pathlib import Path

import networkx as nx

from baranov.closure.bilateration import bilaterated, dehomogenised, triangle_radicand
from baranov.topology import (
    KinematicChain,
    TopologyError,
    chain_from_links,
    mobility,
    require_not_over_constrained,
    require_rigid_chain,
)

from .inputs import INPUT_KEYS, SceneInput
from .numbers import Number, rational_sqrt
from .sliders import SLIDER_KEYS, AngleError, SliderAxis, SliderJoint, angle_direction, axis_frame, axis_turn, slider_loop
from .tracers import TRACER_KEYS, TracerPoint, tracer_from_frame

#: A link triangle whose area is below this fraction of the link's squared size is flat
#: (its orientation is not defined by the link's shape).
FLAT_AREA = 1e-9


class SceneError(ValueError):
    """A scene is malformed; the message names the offending link or joint."""


@dataclass(frozen=True)
class SceneLink:
    """One link of a scene.

    Attributes
    ----------
    name
        the link's name.
    joints
        its joints, in the order given.
    squared_distances
        squared distance of every pair of its joints.
    local
        coordinates of its joints in a frame of the link's own.
    """

    name: str
    joints: tuple[str, ...]
    squared_distances: Mapping[frozenset[str], Number]
    local: Mapping[str, tuple[float, float]]

    @cached_property
    def float_distances(self) -> dict[frozenset[str], float]:
        """Its squared distances as floats, made once per link (every verification reads
        them; instances of a scene share their unchanged links)."""
        return {pair: float(value) for pair, value in self.squared_distances.items()}

    @cached_property
    def float_size(self) -> float:
        """Its largest squared distance as a float: the square of its diameter."""
        return max(self.float_distances.values())

    def orientation(self, triangle: tuple[str, str, str]) -> int:
        """Sign of the oriented area of three of its joints, in its own shape."""
        (xi, yi), (xj, yj), (xk, yk) = (self.local[n] for n in triangle)
        return 1 if (xj - xi) * (yk - yi) - (yj - yi) * (xk - xi) > 0 else -1

    @cached_property
    def widest_triangle(self) -> tuple[str, str, str] | None:
        """The three joints spanning the largest area (None if all collinear): the
        triangle whose orientation tells the link from its mirror image. Areas come from
        the squared distances (16 A², exact for an exact scene), and an area below
        FLAT_AREA of the link's size counts as none: the rounded frame of a straight bar
        scaled by 1e6 had a "widest triangle" of area 1e-4, whose orientation then
        flipped at random (issue 22: a 3-RPR's base, all its modes rejected as mirrored).
        Computed once per link (residuals ask for it at every verification; instances of
        a scene share their unchanged links)."""
        size = max(self.squared_distances.values())
        best, widest = None, FLAT_AREA**2 * size**2
        for triangle in combinations(self.joints, 3):
            i, j, k = triangle
            area16 = triangle_radicand(*(self.squared_distances[frozenset(p)] for p in ((i, j), (i, k), (j, k))))
            if area16 > widest:
                best, widest = triangle, area16
        return best


@dataclass(frozen=True)
class Scene:
    """A linkage: links with dimensions, the name of the ground link, and, for a linkage
    with mobility F > 0, up to F named inputs (:mod:`~baranov.scene.inputs`); tracer
    points, points of links whose paths a trace draws (:mod:`~baranov.scene.tracers`)."""

    links: tuple[SceneLink, ...]
    ground: str
    exact: bool
    world: Mapping[str, tuple[Number, Number]] = field(default_factory=dict)
    inputs: tuple[SceneInput, ...] = ()
    sliders: tuple[SliderJoint, ...] = ()
    tracers: tuple[TracerPoint, ...] = ()

    def point_name(self, link: str, joint: str) -> str:
        """The name of ``joint``'s point on ``link``: the joint's own name for a revolute
        joint; for a slider joint, ``P9'`` on the first of its links in scene order and
        ``P9''`` on the second (thesis §4.1: the slider splits P_i into P_i', P_i'')."""
        for slider in self.sliders:
            if slider.joint == joint:
                return joint + ("'" if slider.axes[0].link == link else "''")
        return joint

    @property
    def mobility(self) -> int:
        """Grübler–Kutzbach mobility F = 3(L − 1) − 2J of the scene's chain: 0 for the
        rigid linkages the backends solve (thesis §3.1)."""
        return mobility(self.chain)

    @cached_property
    def chain(self) -> KinematicChain:
        """The topology (links in scene order, labelled by their names; slider joints of
        kind slider)."""
        chain = chain_from_links([link.joints for link in self.links], [link.name for link in self.links])
        return chain.with_joint_kinds(slider.joint for slider in self.sliders) if self.sliders else chain

    @cached_property
    def axis_frames(self) -> dict[tuple[str, str], dict[str, tuple[Number, Number]]]:
        """Each slider's frame on each of its two links, in world units, keyed by (slider
        joint, link name): :func:`~baranov.scene.sliders.axis_frame`, computed once (it is
        exact arithmetic, most of a 7-link slider chain's solve when made at every use)."""
        return {(slider.joint, axis.link): axis_frame(slider, self.link_of(axis.link))
                for slider in self.sliders for axis in slider.axes}

    @cached_property
    def axis_turns(self) -> dict[tuple[str, str, str], tuple[Number, Number]]:
        """The turn from one slider's axis to another's on a link they share, in world
        units, keyed by (slider joint, other slider joint, link name):
        :func:`~baranov.scene.sliders.axis_turn`, computed once."""
        sliders = {slider.joint: slider for slider in self.sliders}
        return {(slider.joint, other, axis.link): axis_turn(slider, sliders[other], self.link_of(axis.link))
                for slider in self.sliders for axis in slider.axes
                for other in self.link_of(axis.link).joints if other in sliders and other != slider.joint}

    @cached_property
    def known(self) -> dict[frozenset[str], Number]:
        """Squared distance of every pair of joints on a common link."""
        known: dict[frozenset[str], Number] = {}
        for link in self.links:
            known.update(link.squared_distances)
        return known

    @cached_property
    def coincident_pairs(self) -> frozenset[frozenset[str]]:
        """Pairs of joints on a common link at squared distance 0: no bilateration may
        use one as its base (thesis eq. 2.7 divides by it)."""
        return frozenset(pair for pair, value in self.known.items() if value == 0)

    def link_of(self, name: str) -> SceneLink:
        for link in self.links:
            if link.name == name:
                return link
        raise SceneError(f"link {name}: no such link")

    def widest_triangle(self, link: SceneLink) -> tuple[str, str, str] | None:
        """The three joints of ``link`` spanning the largest area (None if all collinear):
        :attr:`SceneLink.widest_triangle`."""
        return link.widest_triangle

    def largest_distance(self, u: str, v: str) -> float:
        """An upper bound on the distance between joints ``u`` and ``v`` in any assembly:
        the shortest path from ``u`` to ``v`` whose steps join two joints of one link,
        each step as long as that link dimension (triangle inequality). A slider joint's
        two points are apart (a path may not slide; for a slider, the distance is to the
        nearer of its points, which bounds the distance to its axis); inf where no path
        joins them. O(E log V).

        >>> scene = scene_from_dict({"ground": "g", "links": [
        ...     {"name": "g", "joints": {"P1": [0, 0], "P2": [3, 0]}},
        ...     {"name": "b13", "joints": ["P1", "P3"], "squared_length": 16},
        ...     {"name": "b23", "joints": ["P2", "P3"], "squared_length": 4}]})
        >>> scene.largest_distance("P1", "P3"), scene.largest_distance("P2", "P3")
        (4.0, 2.0)
        """
        ends = [[self.point_name(link, joint) for link in self._links_of_slider(joint)] or [joint] for joint in (u, v)]
        lengths = [nx.shortest_path_length(self._distance_graph, a, b, weight="length")
                   for a in ends[0] for b in ends[1] if nx.has_path(self._distance_graph, a, b)]
        return float(min(lengths, default=math.inf))

    def _links_of_slider(self, joint: str) -> list[str]:
        return [axis.link for slider in self.sliders if slider.joint == joint for axis in slider.axes]

    @cached_property
    def _distance_graph(self) -> nx.Graph:
        """Joint points (a slider's two points apart: its slide has no bound of its own)
        joined by the link dimensions."""
        graph = nx.Graph()
        for link in self.links:
            for pair, value in link.squared_distances.items():
                graph.add_edge(*(self.point_name(link.name, joint) for joint in pair), length=math.sqrt(float(value)))
        return graph

    def orientation(self, triangle: tuple[str, str, str]) -> int:
        """Sign of the oriented area of three joints of one rigid link, in its own shape."""
        for link in self.links:
            if set(triangle) <= set(link.joints):
                return link.orientation(triangle)
        raise SceneError(f"joints {', '.join(triangle)}: not on one link")


def _number(value, where: str) -> Number:
    if isinstance(value, bool):
        raise SceneError(f"{where}: {value!r} is not a number")
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SceneError(f"{where}: {value!r} is not a finite number")
        return value
    if isinstance(value, str):
        try:
            return Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            raise SceneError(f"{where}: {value!r} is not a number such as 3, 2.5 or \"9/5\"") from None
    if isinstance(value, Fraction):
        return value
    if isinstance(value, Decimal):  # a decimal literal of a JSON file: exact, 2.5 is 5/2
        if not value.is_finite():
            raise SceneError(f"{where}: {value} is not a finite number")
        return Fraction(value)
    raise SceneError(f"{where}: {value!r} is not a number")


def _pair_key(text: str, link: str, joints: tuple[str, ...]) -> frozenset[str]:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2 or parts[0] == parts[1]:
        raise SceneError(f"link {link}: squared distance key {text!r} should name two joints, e.g. \"P1,P2\"")
    for part in parts:
        if part not in joints:
            raise SceneError(f"link {link}: squared distance {text!r} names joint {part}, not on this link")
    return frozenset(parts)


def point_in_frame(name: str, triangle: tuple[str, str, str], squared: Mapping[frozenset[str], float],
                   sign: int) -> tuple[float, float]:
    """Where joint ``triangle[2]`` of link ``name`` lies in the frame of its first two
    (the first at the origin, the second on +x), on the side ``sign`` (+1: to the left),
    from the three float squared distances of ``triangle`` (thesis eq. 2.7, the kernel's
    bilateration). Raises SceneError where they violate the triangle inequality."""
    first, second, joint = triangle
    base, a, b = (squared[frozenset(pair)] for pair in ((first, second), (first, joint), (second, joint)))
    area16 = triangle_radicand(base, a, b)
    if area16 < -1e-9 * max(base, a, b) ** 2:
        lengths = ", ".join(f"{u}{v} = {math.sqrt(w):.6g}" for (u, v), w in
                            (((first, second), base), ((first, joint), a), ((second, joint), b)))
        raise SceneError(f"link {name}: squared distances of {first}, {second}, {joint} violate the triangle "
                         f"inequality (lengths {lengths})")
    x, y, _ = dehomogenised(bilaterated((0, 0, 1), (math.sqrt(base), 0, 1), (base, a, b),
                                        sign * math.sqrt(max(area16, 0.0))))
    return float(x), float(y)


def _embed(name: str, joints: tuple[str, ...], squared: Mapping[frozenset[str], Number], orientation: int):
    """Local coordinates from pairwise squared distances (first joint at the origin, second
    on +x, third on the side ``orientation`` says); checks the distances are planar."""
    s = {key: float(value) for key, value in squared.items()}
    first, second = joints[0], joints[1]
    local = {first: (0.0, 0.0), second: (math.sqrt(s[frozenset((first, second))]), 0.0)}

    def place(joint: str, sign: int) -> tuple[float, float]:
        return point_in_frame(name, (first, second, joint), s, sign)

    if len(joints) >= 3:
        local[joints[2]] = place(joints[2], orientation)
    for joint in joints[3:]:
        candidates = [place(joint, +1), place(joint, -1)]
        third = local[joints[2]]

        def error(point, reference=third, joint=joint):
            return abs((point[0] - reference[0]) ** 2 + (point[1] - reference[1]) ** 2
                       - s[frozenset((joints[2], joint))])

        best = min(candidates, key=error)
        scale = max(s.values())
        for other in joints[2:]:
            if other == joint or other not in local:
                continue
            p, q = best, local[other]
            if abs((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 - s[frozenset((joint, other))]) > 1e-9 * scale:
                raise SceneError(f"link {name}: squared distances are not those of a planar body "
                                 f"(Cayley–Menger check fails at {joint}, {other})")
        local[joint] = best
    return local


def _rational_frame(link: SceneLink) -> dict[str, tuple[Fraction, Fraction]] | None:
    """The link's own frame (:func:`_embed`'s: first joint at the origin, second on +x,
    each other joint on the side ``link.local`` puts it) by the same bilateration, in
    exact rationals, if every triangle area is rational; else None. A ground link given
    by distances is placed in this frame: in floats, 1e-6 is not exact, and msolve, given
    the rounded ground, found the 3-RPR's modes with coincident joints inconsistent at
    that scale (issue 22)."""
    first, second = link.joints[:2]
    d = rational_sqrt(link.squared_distances[frozenset((first, second))])
    if not d:
        return None
    frame = {first: (Fraction(0), Fraction(0)), second: (d, Fraction(0))}
    for joint in link.joints[2:]:
        sides = (d * d, link.squared_distances[frozenset((first, joint))],
                 link.squared_distances[frozenset((second, joint))])
        root = rational_sqrt(triangle_radicand(*sides)) if all(isinstance(x, Fraction) for x in sides) else None
        if root is None:
            return None
        signed = root if link.local[joint][1] >= 0 else -root
        x, y, _ = dehomogenised(bilaterated((0, 0, 1), (d, 0, 1), sides, signed))
        frame[joint] = (x, y)
    return frame


#: The range of squared distances a scene may have: the numeric method squares them
#: (triangle radicands), which must stay finite and normal in double precision. Any
#: linkage fits after a change of units.
SMALLEST_SQUARED = 1e-100
LARGEST_SQUARED = 1e100
LARGEST_COORDINATE = 1e50
RESCALE = "rescale the linkage: a change of units does not change its assembly modes"


def _shown(value: Number) -> str:
    """A number for a message, also where it exceeds the float range."""
    try:
        return f"{float(value):.3g}"
    except OverflowError:
        exponent = len(str(abs(value.numerator))) - len(str(value.denominator))
        return f"{'-' if value < 0 else ''}about 1e{exponent}"


def _require_positive(name: str, joints: tuple[str, ...], squared: Mapping[frozenset[str], Number]) -> None:
    """Squared distances are positive, except that two joints of a link with three or more
    may coincide (0: coalescent attachments, thesis §5.1.3.3) as long as its first two
    joints, which fix the link's own frame, do not."""
    for key, value in squared.items():
        coalescent = value == 0 and len(joints) >= 3 and key != frozenset(joints[:2])
        if value < 0 or (value == 0 and not coalescent):
            raise SceneError(f"link {name}: squared distance {','.join(sorted(key))} = {value} must be positive"
                             + (" (joints of a link with three or more may coincide, but not its first two)"
                                if value == 0 and len(joints) >= 3 else ""))
        if value != 0 and not SMALLEST_SQUARED <= value <= LARGEST_SQUARED:
            raise SceneError(f"link {name}: squared distance {','.join(sorted(key))} = {_shown(value)} is out of "
                             f"range: squared distances lie between {SMALLEST_SQUARED:g} and {LARGEST_SQUARED:g} "
                             f"({RESCALE})")


#: The keys a scene and a link may have (the module docstring says what each means).
SCENE_KEYS = ("links", "ground", "inputs", "sliders", "tracers", "comment", "verified_modes", "generating_configuration",
              "generating_tolerance")
LINK_KEYS = ("name", "joints", "squared_length", "squared_distances", "orientation", "comment")


def _require_known_keys(data: Mapping, known: tuple[str, ...], where: str) -> None:
    """Raise :class:`SceneError` for the first key of ``data`` not in ``known``, with the
    nearest known key as a suggestion."""
    for key in data:
        if key not in known:
            near = difflib.get_close_matches(str(key), known, n=1)
            hint = f"did you mean \"{near[0]}\"?" if near else f"expected one of {', '.join(known)}"
            raise SceneError(f"{where}: unknown key {str(key)!r} ({hint})")


def _parse_link(entry, index: int) -> tuple[SceneLink, dict | None, bool]:
    if not isinstance(entry, Mapping):
        raise SceneError(f"link #{index + 1}: expected an object with \"name\" and \"joints\"")
    name = str(entry.get("name", f"#{index + 1}"))
    _require_known_keys(entry, LINK_KEYS, f"link {name}")
    raw = entry.get("joints")
    exact = True
    if isinstance(raw, Mapping):
        joints = tuple(str(j) for j in raw)
        coordinates = {}
        for joint, point in raw.items():
            if not isinstance(point, (list, tuple)) or len(point) != 2:
                raise SceneError(f"link {name}: joint {joint} needs coordinates [x, y]")
            x, y = (_number(v, f"link {name}, joint {joint}") for v in point)
            for value in (x, y):
                if abs(value) > LARGEST_COORDINATE:
                    raise SceneError(f"link {name}, joint {joint}: coordinate {_shown(value)} is out of range: "
                                     f"coordinates lie within ±{LARGEST_COORDINATE:g} ({RESCALE})")
            exact &= isinstance(x, Fraction) and isinstance(y, Fraction)
            coordinates[str(joint)] = (x, y)
        squared = {frozenset((a, b)): (coordinates[a][0] - coordinates[b][0]) ** 2 + (coordinates[a][1] - coordinates[b][1]) ** 2
                   for a, b in combinations(joints, 2)}
        world = coordinates
        local = {j: (float(x), float(y)) for j, (x, y) in coordinates.items()}
    elif isinstance(raw, list):
        joints = tuple(str(j) for j in raw)
        world = None
        if "squared_length" in entry:
            if len(joints) != 2:
                raise SceneError(f"link {name}: \"squared_length\" is for binary links; give \"squared_distances\"")
            value = _number(entry["squared_length"], f"link {name}, squared_length")
            squared = {frozenset(joints): value}
        elif "squared_distances" in entry:
            given = entry["squared_distances"]
            if not isinstance(given, Mapping):
                raise SceneError(f"link {name}: \"squared_distances\" should map \"P1,P2\" to numbers")
            squared = {_pair_key(k, name, joints): _number(v, f"link {name}, squared distance {k}") for k, v in given.items()}
            missing = [f"{a},{b}" for a, b in combinations(joints, 2) if frozenset((a, b)) not in squared]
            if missing:
                raise SceneError(f"link {name}: squared distance {missing[0]} missing")
        else:
            raise SceneError(f"link {name}: give \"squared_length\", \"squared_distances\" or joint coordinates")
        exact = all(isinstance(v, Fraction) for v in squared.values())
        orientation = 1
        if len(joints) >= 3:
            text = entry.get("orientation")
            if text not in ("ccw", "cw"):
                raise SceneError(f"link {name}: \"orientation\" must be \"ccw\" or \"cw\" (of {', '.join(joints[:3])})")
            orientation = 1 if text == "ccw" else -1
        _require_positive(name, joints, squared)
        local = _embed(name, joints, squared, orientation) if len(joints) >= 2 else {}
    else:
        raise SceneError(f"link {name}: \"joints\" must be a list of names or a map of coordinates")
    if len(joints) < 2 or len(set(joints)) != len(joints):
        raise SceneError(f"link {name}: needs at least two different joints")
    _require_positive(name, joints, squared)  # coordinates: coincident joints
    for a, b, c in combinations(joints, 3):  # collinear joints are fine (a straight bar)
        sides = [float(squared[frozenset(p)]) for p in ((a, b), (a, c), (b, c))]
        if triangle_radicand(*sides) < -1e-9 * max(sides) ** 2:
            raise SceneError(f"link {name}: squared distances of {a}, {b}, {c} violate the triangle inequality")
    return SceneLink(name, joints, squared, local), world, exact


def scene_from_dict(data) -> Scene:
    """Build and validate a scene from its JSON structure (see the module docstring)."""
    if not isinstance(data, Mapping) or not isinstance(data.get("links"), list):
        raise SceneError("scene: expected an object with a \"links\" list and a \"ground\" name")
    _require_known_keys(data, SCENE_KEYS, "scene")
    if not data["links"]:
        raise SceneError("scene: \"links\" is empty")
    parsed = [_parse_link(entry, i) for i, entry in enumerate(data["links"])]
    links = tuple(link for link, _, _ in parsed)
    names = [link.name for link in links]
    if len(set(names)) != len(names):
        repeated = next(n for n in names if names.count(n) > 1)
        raise SceneError(f"link {repeated}: name used twice")
    ground = data.get("ground")
    listed = ", ".join(names[:8]) + (" …" if len(names) > 8 else "")
    if "ground" not in data:
        raise SceneError(f"scene: \"ground\" missing: name the fixed link (one of {listed})")
    if ground not in names:
        raise SceneError(f"ground {ground!r}: no link of that name (links: {listed})")
    counts: dict[str, list[str]] = {}
    for link in links:
        for joint in link.joints:
            counts.setdefault(joint, []).append(link.name)
    alone = [joint for joint, on in counts.items() if len(on) == 1]
    for joint, on in counts.items():
        if len(on) == 1:
            # two joints on one link each are most often one joint misspelt on one of them
            other = next((o for o in alone if o != joint and counts[o][0] != on[0]), None)
            hint = f" (and {other} only on link {counts[other][0]}: one name misspelt?)" if other else ""
            raise SceneError(f"joint {joint}: dangling, only on link {on[0]}{hint}")
        if len(on) > 2:
            raise SceneError(f"joint {joint}: on {len(on)} links ({', '.join(on)}); a joint joins exactly two")
    ground_index = names.index(ground)
    _, world, _ = parsed[ground_index]
    if world is None:  # given by distances: first joint at the origin, second on +x
        world = _rational_frame(links[ground_index]) or dict(links[ground_index].local)
    scene = Scene(links, ground, all(exact for _, _, exact in parsed), world)
    try:
        if scene.mobility > 0:
            require_not_over_constrained(scene.chain)
        else:
            require_rigid_chain(scene.chain)
    except TopologyError as error:
        raise SceneError(f"topology: {error}") from None
    if "sliders" in data:
        sliders = _parse_sliders(data["sliders"], links)
        exact = scene.exact and all(isinstance(c, Fraction) for s in sliders for a in s.axes for c in a.direction)
        scene = Scene(links, ground, exact, world, sliders=sliders)
    if "inputs" in data:
        scene = Scene(links, ground, scene.exact, world, _parse_inputs(data["inputs"], scene), scene.sliders)
    if "tracers" in data:
        frames = [given or _rational_frame(link) or link.local for link, (_, given, _) in zip(links, parsed, strict=True)]
        scene = replace(scene, tracers=_parse_tracers(data["tracers"], scene, dict(zip(names, frames, strict=True))))
    return scene


def _parse_tracers(entries, scene: Scene, frames: Mapping[str, Mapping]) -> tuple[TracerPoint, ...]:
    """The scene's tracer points (:mod:`~baranov.scene.tracers`), validated: each names a
    link of the scene and a point [x, y] in its frame (``frames``: link → its joints'
    coordinates in that frame), under a name no joint or other tracer has."""
    if not isinstance(entries, list):
        raise SceneError("tracers: expected a list of points such as {\"name\": \"C\", \"link\": \"coupler\", "
                         "\"at\": [1, 2]}")
    taken = {joint.name for joint in scene.chain.joints}
    tracers = []
    for index, entry in enumerate(entries):
        if not isinstance(entry, Mapping) or not isinstance(entry.get("name"), str) or not entry["name"]:
            raise SceneError(f"tracer #{index + 1}: expected an object with a \"name\", a \"link\" and \"at\": [x, y]")
        name = entry["name"]
        _require_known_keys(entry, TRACER_KEYS, f"tracer {name}")
        if name in taken:
            raise SceneError(f"tracer {name}: name already used by a joint or another tracer")
        taken.add(name)
        if entry.get("link") not in frames:
            raise SceneError(f"tracer {name}: link {entry.get('link')!r}: no such link "
                             f"(links: {', '.join(link.name for link in scene.links)})")
        at = entry.get("at")
        if not isinstance(at, (list, tuple)) or len(at) != 2:
            raise SceneError(f"tracer {name}: \"at\" needs the point's coordinates [x, y] in link {entry['link']}'s frame")
        point = tuple(_number(value, f"tracer {name}, at") for value in at)
        frame, first, second = frames[entry["link"]], *scene.link_of(entry["link"]).joints[:2]
        tracers.append(tracer_from_frame(name, entry["link"], point, frame[first], frame[second]))
    return tuple(tracers)


def _parse_sliders(entries, links: tuple[SceneLink, ...]) -> tuple[SliderJoint, ...]:
    """The slider joints (:mod:`~baranov.scene.sliders`), validated: each a joint of two
    links with one angle on each, no joint twice, no loop of links closed by sliders."""
    if not isinstance(entries, list):
        raise SceneError("sliders: expected a list such as [{\"joint\": \"P9\", \"angles\": {\"A\": {\"P5\": "
                         "\"pi - atan(5/2)\"}, \"B\": {\"P7\": \"atan(3)\"}}}]")
    sliders = [_parse_slider(entry, index, links) for index, entry in enumerate(entries)]
    names = [slider.joint for slider in sliders]
    if len(set(names)) != len(names):
        raise SceneError(f"slider {next(n for n in names if names.count(n) > 1)}: given twice")
    loop = slider_loop({slider.joint: (slider.axes[0].link, slider.axes[1].link) for slider in sliders})
    if loop is not None:
        joined = {link for slider in sliders if slider.joint in loop for link in (a.link for a in slider.axes)}
        raise SceneError(f"sliders {', '.join(loop)}: they close the loop of links {', '.join(sorted(joined))} "
                         "by sliders only, which cannot fix the links' rotations (not an Assur chain); make one a "
                         "revolute joint")
    return tuple(sliders)


def _parse_slider(entry, index: int, links: tuple[SceneLink, ...]) -> SliderJoint:
    if not isinstance(entry, Mapping) or "joint" not in entry:
        raise SceneError(f"slider #{index + 1}: expected an object with \"joint\" and \"angles\"")
    joint = str(entry["joint"])
    _require_known_keys(entry, SLIDER_KEYS, f"slider {joint}")
    on = [link for link in links if joint in link.joints]
    if not on:
        raise SceneError(f"slider {joint}: no link has this joint")
    angles = entry.get("angles")
    names = sorted(link.name for link in on)
    if not isinstance(angles, Mapping) or sorted(angles) != names:
        raise SceneError(f"slider {joint}: \"angles\" should give one angle on each of its links {' and '.join(names)}, "
                         "e.g. {\"" + names[0] + "\": {\"<joint>\": \"atan(2)\"}, …}")
    axes = []
    for link in on:
        given = angles[link.name]
        if not isinstance(given, Mapping) or len(given) != 1:
            raise SceneError(f"slider {joint}: on link {link.name}, give the angle of exactly one other joint "
                             f"({', '.join(j for j in link.joints if j != joint)})")
        ((reference, value),) = given.items()
        if reference == joint or reference not in link.joints:
            raise SceneError(f"slider {joint}: on link {link.name}, {reference} is not another joint of that link "
                             f"({', '.join(j for j in link.joints if j != joint)})")
        try:
            direction = angle_direction(value)
        except AngleError as error:
            raise SceneError(f"slider {joint}: on link {link.name}, angle of {reference}: {error}") from None
        axes.append(SliderAxis(link.name, reference, direction))
    return SliderJoint(joint, (axes[0], axes[1]))


def _parse_inputs(entries, scene: Scene) -> tuple[SceneInput, ...]:
    """The scene's inputs (module :mod:`~baranov.scene.inputs`), validated: at most F of
    them, distinct names, joints of the scene, each driving a distance no link fixes."""
    if not isinstance(entries, list):
        raise SceneError("inputs: expected a list of inputs such as {\"name\": \"crank\", \"angle\": [\"P1\", "
                         "\"P2\", \"P3\"], \"degrees\": 30}")
    if entries and scene.mobility == 0:
        raise SceneError(f"inputs: a rigid linkage (mobility 3(L-1) - 2J = 0 with L = {len(scene.links)} links) "
                         "has none to drive")
    if len(entries) > scene.mobility:
        raise SceneError(f"inputs: {len(entries)} given, but the linkage has mobility {scene.mobility} "
                         f"(3(L-1) - 2J with L = {len(scene.links)} links): it takes at most {scene.mobility}")
    inputs = tuple(_parse_input(entry, index, scene) for index, entry in enumerate(entries))
    names = [entry.name for entry in inputs]
    if len(set(names)) != len(names):
        raise SceneError(f"input {next(n for n in names if names.count(n) > 1)}: name used twice")
    pairs = [frozenset(entry.driven_pair) for entry in inputs]
    if len(set(pairs)) != len(pairs):
        raise SceneError(f"inputs: two inputs drive the distance of {', '.join(sorted(pairs[0]))}")
    return inputs


def _parse_input(entry, index: int, scene: Scene) -> SceneInput:
    if not isinstance(entry, Mapping):
        raise SceneError(f"input #{index + 1}: expected an object with \"name\" and \"angle\" or \"distance\"")
    name = str(entry.get("name", f"#{index + 1}"))
    _require_known_keys(entry, INPUT_KEYS, f"input {name}")
    if ("angle" in entry) == ("distance" in entry):
        raise SceneError(f"input {name}: give either \"angle\": [at, from, to] or \"distance\": [joint, joint]")
    kind = "angle" if "angle" in entry else "distance"
    size, unit, other = (3, "degrees", "squared_distance") if kind == "angle" else (2, "squared_distance", "degrees")
    joints = entry[kind]
    if not isinstance(joints, list) or len(joints) != size or not all(isinstance(j, str) for j in joints):
        raise SceneError(f"input {name}: \"{kind}\" should list {size} joint names")
    if other in entry:
        raise SceneError(f"input {name}: {'an angle' if kind == 'angle' else 'a distance'} input takes \"{unit}\", "
                         f"not \"{other}\"")
    for joint in joints:
        if not any(joint in link.joints for link in scene.links):
            raise SceneError(f"input {name}: joint {joint} is not in the scene")
    value = _number(entry[unit], f"input {name}") if unit in entry else None
    if kind == "angle":
        _require_angle_joints(name, tuple(joints), scene)
    else:
        _require_free_distance(name, tuple(joints), scene)
        if value is not None and not 0 < value <= LARGEST_SQUARED:
            raise SceneError(f"input {name}: squared distance {_shown(value)} must be positive "
                             f"and at most {LARGEST_SQUARED:g}")
    return SceneInput(name, kind, tuple(joints), value)


def _require_angle_joints(name: str, joints: tuple[str, str, str], scene: Scene) -> None:
    """P_f and P_t on the two different links that meet at P_a."""
    at, start, end = joints
    links = [link for link in scene.links if at in link.joints]
    on_start = [link.name for link in links if start in link.joints and start != at]
    on_end = [link.name for link in links if end in link.joints and end != at]
    if not (on_start and on_end and set(on_start) != set(on_end)):
        meeting = " and ".join(link.name for link in links)
        raise SceneError(f"input {name}: an angle at {at} is measured between the links that meet there "
                         f"({meeting}): {start} on one and {end} on the other")


def _require_free_distance(name: str, joints: tuple[str, str], scene: Scene) -> None:
    """Two distinct joints whose distance no link fixes."""
    u, v = joints
    if u == v:
        raise SceneError(f"input {name}: a distance needs two different joints, not {u} twice")
    if frozenset(joints) in scene.known:
        link = next(link.name for link in scene.links if u in link.joints and v in link.joints)
        raise SceneError(f"input {name}: {u} and {v} are both on link {link}, whose shape fixes their distance")


def load_scene(path: str | Path) -> Scene:
    """Read a scene from a JSON file."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"), parse_float=Decimal)
    except OSError as error:
        raise SceneError(f"{path}: cannot read ({error.strerror})") from None
    except ValueError as error:
        raise SceneError(f"{path}: not valid JSON ({error})") from None
    return scene_from_dict(data)
