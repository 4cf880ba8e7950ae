"""Slider (prismatic) joints of a scene (thesis ch. 4, paper 003 §3).

A slider joint P_i between links A and B lets B translate along an axis fixed in both
links, without rotating relative to A. Following the thesis, the joint keeps its name and
its place on each link: on A it is the point P_i' of the axis whose squared distances to
A's other joints are A's dimensions, on B the point P_i'' likewise (the two coincide
only when the translation is 0). The axis is fixed in each link by one angle: α_j, the
polar angle of the vector P_i'→P_j (P_j another joint of that link) measured from the
sliding direction, so that √s_{i',j} sin α_j is P_j's oriented distance to the axis
(thesis §4.1; the same sense of the axis on both links). The angles of the link's other
joints follow from its shape.

In a scene (JSON)::

    "sliders": [{"joint": "P9", "angles": {"t569": {"P5": "pi - atan(5/2)"},
                                           "t789": {"P7": "2 pi - atan(5/3)"}}}]

An angle is exact when written as a sum of multiples of π/2 and arctangents of rationals
(``"atan(5/2)"``, ``"atan2(-5, 3)"``, ``"pi + atan(1/2)"``: the thesis's angles are all of
this form), or as a direction ``[x, y]`` (the angle of that vector); a plain number is in
degrees (exact at multiples of 45°). Internally an angle is its direction (cos α, sin α)
up to a positive factor: rational wherever the input is exact.

A set of sliders that closes a loop of links is refused: a loop closed by sliders only
cannot fix its links' rotations, and the chain is no Assur kinematic chain (thesis ch. 4
introduction; :func:`~baranov.enumerate.sliders.admissible_slider_sets`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

import networkx as nx

from baranov.closure.bilateration import triangle_radicand

from .numbers import Number, rational_sqrt

#: The keys of a slider entry in a scene.
SLIDER_KEYS = ("joint", "angles", "comment")


@dataclass(frozen=True)
class SliderAxis:
    """The axis of a slider joint as fixed in one of its links.

    Attributes
    ----------
    link
        the link's name.
    reference
        the joint P_j of that link whose angle is given.
    direction
        (cos α_j, sin α_j) up to a positive factor, α_j the angle of the
        vector from the slider's point on this link to P_j, from the sliding
        direction.
    """

    link: str
    reference: str
    direction: tuple[Number, Number]


@dataclass(frozen=True)
class SliderJoint:
    """A slider joint: its name and its axis in each of its two links."""

    joint: str
    axes: tuple[SliderAxis, SliderAxis]

    def axis_on(self, link: str) -> SliderAxis:
        """The axis as fixed in ``link`` (one of the joint's two links)."""
        return next(axis for axis in self.axes if axis.link == link)


class AngleError(ValueError):
    """An angle could not be read; the message says what is expected."""


_RATIONAL = r"[+-]?\s*\d+(?:\.\d+)?(?:\s*/\s*\d+(?:\.\d+)?)?"
_TERM = re.compile(
    r"\s*(?P<sign>[+-])?\s*(?:"
    rf"(?P<atan2>atan2\(\s*(?P<y>{_RATIONAL})\s*,\s*(?P<x>{_RATIONAL})\s*\))"
    rf"|(?P<atan>atan\(\s*(?P<ratio>{_RATIONAL})\s*\))"
    rf"|(?P<pi>(?P<times>\d+(?:/\d+)?)?\s*\*?\s*pi(?:\s*/\s*(?P<over>\d+))?)"
    r")\s*")


def _rational(text: str) -> Fraction:
    return Fraction(re.sub(r"\s+", "", text))


def _times(first: tuple, second: tuple) -> tuple:
    """Directions of α and β → direction of α + β (complex multiplication)."""
    (a, b), (c, d) = first, second
    return a * c - b * d, a * d + b * c


def _pi_direction(multiple: Fraction) -> tuple[Number, Number]:
    """Direction of multiple·π, up to a positive factor: exact at multiples of π/4."""
    if (4 * multiple).denominator == 1:
        return ((1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1))[int(4 * multiple) % 8]
    angle = math.pi * float(multiple)
    return math.cos(angle), math.sin(angle)


def angle_direction(value) -> tuple[Number, Number]:
    """The direction (cos α, sin α), up to a positive factor, of an angle written as in
    the module docstring; exact (Fractions) where the angle is.

    >>> angle_direction("pi - atan(5/2)")
    (Fraction(-1, 1), Fraction(5, 2))
    >>> angle_direction("2 pi - atan(1/2)"), angle_direction("atan2(-5, 3)")
    ((Fraction(1, 1), Fraction(-1, 2)), (Fraction(3, 1), Fraction(-5, 1)))
    >>> angle_direction(90), angle_direction([3, 4])
    ((Fraction(0, 1), Fraction(1, 1)), (Fraction(3, 1), Fraction(4, 1)))
    """
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise AngleError(f"{value!r}: a direction is two numbers [x, y]")
        direction = tuple(Fraction(str(c)) if not isinstance(c, float) else c for c in value)
    elif isinstance(value, bool):
        raise AngleError(f"{value!r}: not an angle")
    elif isinstance(value, (int, Fraction, Decimal)):
        turns = Fraction(str(value)) / 180
        direction = _pi_direction(turns)
    elif isinstance(value, float):
        direction = math.cos(math.radians(value)), math.sin(math.radians(value))
    elif isinstance(value, str):
        direction = _parsed_angle(value)
    else:
        raise AngleError(f"{value!r}: expected an angle such as \"pi - atan(5/2)\", [x, y] or degrees")
    if direction[0] == 0 and direction[1] == 0:
        raise AngleError(f"{value!r}: the direction [0, 0] has no angle")
    return tuple(Fraction(c) if isinstance(c, int) else c for c in direction)


def _parsed_angle(text: str) -> tuple[Number, Number]:
    if re.fullmatch(rf"\s*{_RATIONAL}\s*", text):  # degrees, as a number would be
        return _pi_direction(_rational(text) / 180) if "." not in text else angle_direction(float(text))
    direction: tuple = (Fraction(1), Fraction(0))
    position, terms = 0, 0
    while position < len(text.rstrip()):
        match = _TERM.match(text, position)
        if match is None or match.end() == position or (terms and not match["sign"]):
            raise AngleError(f"{text!r}: expected an angle such as \"pi - atan(5/2)\", \"atan2(5, -2)\", "
                             "[x, y] or degrees")
        if match["atan2"]:
            term = (_rational(match["x"]), _rational(match["y"]))
        elif match["atan"]:
            term = (Fraction(1), _rational(match["ratio"]))
        else:
            multiple = Fraction(match["times"] or 1) / int(match["over"] or 1)
            term = _pi_direction(multiple)
        if match["sign"] == "-":
            term = (term[0], -term[1])
        direction = _times(direction, term)
        position, terms = match.end(), terms + 1
    if not terms:
        raise AngleError(f"{text!r}: an empty angle")
    return direction


def slider_loop(links_of_sliders: dict[str, tuple[str, str]]) -> list[str] | None:
    """The slider joints of a loop of links closed by sliders only (each slider given by
    the two links it joins), or None if there is none. O(number of sliders).

    >>> slider_loop({"P1": ("A", "B"), "P2": ("B", "C")}) is None
    True
    >>> sorted(slider_loop({"P1": ("A", "B"), "P2": ("B", "C"), "P3": ("C", "A")}))
    ['P1', 'P2', 'P3']
    """
    graph = nx.MultiGraph()
    for joint, (a, b) in links_of_sliders.items():
        graph.add_edge(a, b, key=joint)
    try:
        return [key for _, _, key in nx.find_cycle(graph)]
    except nx.NetworkXNoCycle:
        return None


def axis_frame(slider: SliderJoint, link, unit: Number = 1) -> dict[str, tuple[Number, Number]]:
    """The joints of ``link`` (one of the slider's two links) in the frame of the
    slider's axis as fixed in that link: the slider's point on the link at 0, the sliding
    direction along +1, so that each other joint P_j sits at (a_j, h_j), h_j = √s_{i',j}
    sin α_j its oriented distance to the axis (thesis §4.1) and a_j = √s_{i',j} cos α_j
    its place along it. The reference joint sits at √s_{i',ref} (cos α, sin α), every
    other joint at that times the bilateration Z_{i',ref,j} (thesis eq. 2.7): exact
    (Fractions) where the link's areas and √(s_{i',ref} / (|direction|² unit)) are
    rational, floats otherwise. Lengths are in units of √``unit`` (:func:`axis_unit`: a
    frame √2 times rational is rational in units of √2). O(joints of the link).

    >>> from baranov.scene import load_scene
    >>> scene = load_scene("examples/7-B3-slider-P9.json")
    >>> frame = axis_frame(scene.sliders[0], scene.link_of("t569"))
    >>> frame["P5"], frame["P6"]
    ((Fraction(-2, 1), Fraction(5, 1)), (Fraction(-3, 1), Fraction(2, 1)))
    """
    exact = _axis_frame(slider, link, unit, exact=True)
    return exact if exact is not None else _axis_frame(slider, link, unit, exact=False)


def axis_unit(slider: SliderJoint, links) -> int | None:
    """The square-free integer q such that the slider's frames on its two ``links`` are
    rational in units of √q (thesis §4.2.3's second slider: q = 2), or None where the
    scene is inexact or the two links need different q (:func:`axis_units`)."""
    classes = set(axis_units(slider, links).values())
    return classes.pop() if len(classes) == 1 and None not in classes else None


def axis_units(slider: SliderJoint, links) -> dict[str, int | None]:
    """For each of the slider's ``links``, the square-free q such that its frame there is
    rational times √q, None where the link or the axis is inexact. A frame's scale is
    √(s_{i',ref} / |direction|²), rational times the square root of the square-free part
    of that fraction's numerator × denominator."""
    units: dict[str, int | None] = {}
    for link in links:
        axis = slider.axis_on(link.name)
        base = link.squared_distances[frozenset((slider.joint, axis.reference))]
        if not isinstance(base, Fraction) or not all(isinstance(c, Fraction) for c in axis.direction):
            units[link.name] = None
            continue
        ratio = base / (axis.direction[0] ** 2 + axis.direction[1] ** 2)
        units[link.name] = _square_free(ratio.numerator * ratio.denominator)
    return units


def _square_free(value: int) -> int:
    """The square-free part of a positive integer (trial division: scene numbers are small)."""
    part, factor = 1, 2
    while factor * factor <= value:
        while value % (factor * factor) == 0:
            value //= factor * factor
        if value % factor == 0:
            part, value = part * factor, value // factor
        factor += 1
    return part * value


def _axis_frame(slider: SliderJoint, link, unit: Number, exact: bool) -> dict[str, tuple[Number, Number]] | None:
    """:func:`axis_frame` in Fractions (None where a root is irrational) or in floats."""
    def number(value):
        return Fraction(value) if exact else float(value)

    def root(value):
        return rational_sqrt(value) if exact else math.sqrt(max(value, 0.0))

    axis = slider.axis_on(link.name)
    joint, reference = slider.joint, axis.reference
    squared = {pair: number(value) for pair, value in link.squared_distances.items()}
    x, y = (number(c) for c in axis.direction)
    base = squared[frozenset((joint, reference))]
    scale = root(base / (x * x + y * y) / number(unit)) if exact and all(
        isinstance(c, Fraction) for c in axis.direction) else (None if exact else root(base / (x * x + y * y) / unit))
    if scale is None:
        return None
    start = complex(*link.local[joint])
    toward = complex(*link.local[reference]) - start
    frame = {reference: (scale * x, scale * y)}
    for other in link.joints:
        if other in (joint, reference):
            continue
        second, third = squared[frozenset((joint, other))], squared[frozenset((reference, other))]
        area = root(triangle_radicand(base, second, third))  # 4 A, unsigned
        if area is None:
            return None
        if ((toward.conjugate() * (complex(*link.local[other]) - start)).imag) < 0:
            area = -area
        real, imaginary = (base + second - third) / (2 * base), area / (2 * base)  # Z_{i',ref,j}
        frame[other] = (scale * (x * real - y * imaginary), scale * (x * imaginary + y * real))
    return frame


def axis_turn(first: SliderJoint, second: SliderJoint, link, units: tuple[Number, Number] = (1, 1)
              ) -> tuple[Number, Number]:
    """The direction of ``second``'s axis in the frame of ``first``'s (:func:`axis_frame`),
    two sliders of one ``link``: the unit vector (cos γ, sin γ), γ the angle the link
    fixes between the two sliding directions (thesis §4.2.3: the cosine theorem with that
    angle); exact where both frames are: the vector between the two sliders' points of the
    link, in the first frame over the same vector in the second. With the frames in
    units of √q₁, √q₂ (``units``, :func:`axis_unit`) it is that turn times √(q₂/q₁).

    >>> from baranov.scene import load_scene
    >>> scene = load_scene("examples/7-B3-sliders-P8-P9.json")
    >>> p8, p9 = sorted(scene.sliders, key=lambda slider: slider.joint)
    >>> [round(c, 12) for c in axis_turn(p9, p8, scene.link_of("t789"))]  # 45°: the angle of §4.2.3
    [0.707106781187, 0.707106781187]
    """
    (dx, dy), (u, v) = axis_frame(first, link, units[0])[second.joint], axis_frame(second, link, units[1])[first.joint]
    norm = u * u + v * v  # the vector from the first's point to the second's: (dx + i dy) / (−u − i v)
    return -(dx * u + dy * v) / norm, -(dy * u - dx * v) / norm


def sliding_link(scene) -> tuple[str, tuple[str, ...]] | None:
    """A link of ``scene`` whose joints are all sliders with parallel axes on it (two
    prismatic joints of one direction in a leg, as in a robot leg written pPR): it slides
    along that direction without moving any other link, so wherever the linkage
    assembles, its configurations form a continuum (thesis ch. 4 assumes the axes of a
    link's sliders cross: its point on two axes). The link's name and its sliders; None
    where no link is so. Parallel: the turn between the axes (:func:`axis_turn`) has sine
    0, within 1e-12 where an angle is irrational (floats). O(sliders²).

    >>> from baranov.scene import load_scene
    >>> sliding_link(load_scene("examples/7-B3-sliders-P8-P9.json")) is None  # 45° apart
    True
    """
    on_link: dict[str, list[SliderJoint]] = {}
    for slider in scene.sliders:
        for axis in slider.axes:
            on_link.setdefault(axis.link, []).append(slider)
    for link in scene.links:
        sliders = on_link.get(link.name, [])
        if len(sliders) < 2 or len(sliders) < len(link.joints):
            continue
        sines = [axis_turn(sliders[0], other, link)[1] for other in sliders[1:]]
        if all(sine == 0 if isinstance(sine, (int, Fraction)) else abs(float(sine)) <= 1e-12 for sine in sines):
            return link.name, tuple(slider.joint for slider in sliders)
    return None
