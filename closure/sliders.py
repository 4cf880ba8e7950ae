"""Slider joints in the bilateration kernel: a plan step that touches a slider is the
limit of its bilateration as the slider's centre goes to infinity (thesis §4.1–4.2.4,
paper 003 §3; docs/sliders.md).

A slider P_i is a revolute joint whose centre has gone to infinity, perpendicular to its
axis: every s_{i,j} = (δ + h_j)² with h_j the oriented distance of P_j to the axis (> 0 to
the left of the sliding direction), and the truss's closure condition keeps its leading
coefficient as δ → ∞. In the plan, P_i^∞ is therefore a line, the axis, and each step
that touches it is one of four ruler-and-compass constructions, each the limit of a
bilateration:

==========================================  =============================================
truss step                                  slider version
==========================================  =============================================
P_i from P_a, P_b                           :func:`axis_through` two points of known h
P_k from P_i, P_j                           :func:`point_off_axis`: at h_k from the axis,
                                            √s_{j,k} from P_j (a circle and a line)
P_l from P_i, P_j, both sliders of a link   :func:`turned_axis`: P_i's axis turned by the
                                            angle the link fixes between them
P_k from P_i, P_l, both sliders             :func:`point_on_two_axes` (two lines)
P_k from P_i, P_l, all three sliders of a   :func:`third_axis`: the link is where its two
link (thesis §5.2.1.3)                      placed axes put it, and its third axis with it
closure s_{i,v}                             :func:`height_above`: P_v's h, computed
closure s_{i,l}, both sliders of a link     :func:`turn_mismatch`: the turn between the
                                            placed axes against the link's
==========================================  =============================================

The along-axis step between two joints is ``along`` = σ√(s_{j,k} − Δh²): σ the
orientation of the triangle with a vertex at infinity, fixed by the link's shape when
P_j, P_k lie on one of the slider's links (then ``along`` is a link constant), a free
sign otherwise (thesis: "this possible sign change has to be taken into account").

Arithmetic: anything with the operators of a complex number: numpy arrays and Python
complex numbers (the numeric backend), :class:`~.homogeneous.Homogeneous` triples over the
exact radical tower or over complex balls (the exact backend). Points are in the plan's
frame (the reference pair at 0 and 1, so that one frame unit is √s_ref world units);
squared distances are in world units, a slider's heights and alongs in its axis units
(:attr:`Axis.unit`: world units but where the exact method needs √q; docs/sliders.md).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Axis:
    """A slider's axis placed in the plan's frame.

    Attributes
    ----------
    direction
        ũ, the frame vector of one axis unit along the sliding direction
        (|ũ|² = unit/s_ref).
    anchor
        a point of the frame.
    height
        the anchor's oriented distance to the axis, in axis units.
    unit
        q, the squared world length of the axis unit: 1 (world units) but where
        the exact method measures this slider's heights in units of √q, so that they
        stay rational (:func:`~baranov.scene.sliders.axis_unit`; thesis §4.2.3's
        second axis, 45° from the first: q = 2).
    """

    direction: Any
    anchor: Any
    height: Any
    unit: Any = 1

    def scale(self, reference) -> Any:
        """s_ref / q: what turns Im(conj(ũ) v) of a frame vector v into axis units."""
        return reference if self.unit == 1 else reference / self.unit


def height_above(axis: Axis, point, reference) -> Any:
    """The oriented distance of ``point`` (frame) to ``axis``, in axis units:
    h = h_anchor + (s_ref/q) Im(conj(ũ)(p − anchor)), since a frame vector has s_ref times
    the squared length in world units and ũ is √(q/s_ref) long. O(1).

    >>> float(height_above(Axis(1j, 0j, 2.0), 1 + 0j, 1.0))  # the axis x = 2 upwards, P = (1, 0)
    1.0
    """
    return axis.height + axis.scale(reference) * (axis.direction.conjugate() * (point - axis.anchor)).imag


def axis_through(p_a, h_a, p_b, h_b, along, unit=1) -> Axis:
    """The axis from two points of known oriented distance to it: P_b − P_a =
    (along + i Δh) ũ with Δh = h_b − h_a, so ũ = (p_b − p_a)/(along + iΔh), where
    along² + Δh² = s_{a,b}/q (axis units, ``unit`` = q). The limit of locating P_i from
    P_a, P_b. O(1).

    >>> axis = axis_through(0j, 1.0, 4 + 0j, 1.0, 4.0)  # both 1 above: the x-axis
    >>> complex(axis.direction), float(height_above(axis, 0j, 1.0))
    ((1+0j), 1.0)
    """
    return Axis((p_b - p_a) / (along + 1j * (h_b - h_a)), p_a, h_a, unit)


def point_off_axis(axis: Axis, p_j, h_j, h_k, along) -> Any:
    """P_k at oriented distance ``h_k`` from ``axis`` and √s_{j,k} from P_j (of distance
    ``h_j``): p_k = p_j + (along + i(h_k − h_j)) ũ with along = σ√(s_{j,k} − (h_k − h_j)²)
    (paper 003's circle and line). The limit of locating P_k from P_i^∞, P_j. O(1).

    >>> complex(point_off_axis(Axis(1 + 0j, 0j, 0.0), 0j, 0.0, 3.0, 4.0))  # 5 from P_j, 3 above
    (4+3j)
    """
    return p_j + (along + 1j * (h_k - h_j)) * axis.direction


def turned_axis(axis: Axis, turn, anchor, height, unit=1) -> Axis:
    """The axis of a second slider of the link that holds ``axis``'s slider: the
    direction turned by ``turn`` = e^{iγ} √(q₂/q₁), γ the angle the link fixes between
    the two sliding directions (:func:`~baranov.scene.sliders.axis_turn`), through a
    point ``anchor`` of known oriented distance ``height`` to it, in the new axis's
    units q₂ = ``unit`` (thesis §4.2.3). O(1)."""
    return Axis(axis.direction * turn, anchor, height, unit)


def point_on_two_axes(first: Axis, h_first, second: Axis, h_second, reference) -> Any:
    """The point at oriented distances ``h_first``, ``h_second`` from two axes (two
    lines meet once; NaN or inf where they are parallel): from p = a₁ + ũ₁(λ + i c),
    c = (h_first − h_a₁)/((s_ref/q₁) |ũ₁|²), the second distance fixes λ. The limit of
    locating P_k from two sliders. O(1).

    >>> complex(point_on_two_axes(Axis(1 + 0j, 0j, 0.0), 2.0, Axis(1j, 0j, 0.0), -3.0, 1.0))
    (3+2j)
    """
    u1, u2 = first.direction, second.direction
    across = (h_first - first.height) / (first.scale(reference) * (u1.conjugate() * u1).real)
    start = first.anchor + 1j * across * u1
    offset = (h_second - height_above(second, start, reference)) / second.scale(reference)
    return start + offset / (u2.conjugate() * u1).imag * u1


def third_axis(first: Axis, second: Axis, turn, crossing_height, reference, unit=1) -> Axis:
    """The axis of the third slider of a link whose three joints are all sliders (thesis
    §5.2.1.3), from the link's two other axes, placed: its direction is ``first``'s
    turned by ``turn`` (as :func:`turned_axis`), and it passes at ``crossing_height`` (a
    constant of the link, :meth:`SliderGeometry.crossing_height`) from the point where the
    two placed axes cross, a point of the link. The limit of locating P_k from two sliders
    P_i, P_l of its link. O(1).

    >>> x_axis, y_axis = Axis(1 + 0j, 0j, 0.0), Axis(1j, 0j, 0.0)
    >>> axis = third_axis(x_axis, y_axis, 1j, 2.0, 1.0)  # upwards, the crossing 2 to its left: x = 2
    >>> complex(axis.direction), round(float(height_above(axis, 1 + 5j, 1.0)), 12)
    (1j, 1.0)
    """
    crossing = point_on_two_axes(first, 0 * crossing_height, second, 0 * crossing_height, reference)
    return Axis(first.direction * turn, crossing, crossing_height, unit)


def turn_mismatch(first: Axis, second: Axis, turn) -> Any:
    """r − 1 with r = ũ₂ conj(ũ₁ t) / |ũ₁ t|², t = ``turn`` the link's turn from the first
    axis to the second (:func:`turned_axis`): 0 exactly where the two placed axes hold the
    angle the link fixes between them, sense included. The closure s_{i,l} of two sliders
    of one link as δ_i, δ_l → ∞ (thesis §4.2.3's cosine theorem, §5.2.1.3's
    d4,5² = d5,6² + d4,6² + 2 d5,6 d4,6 cos(α5 − α3)): the link, turned onto the first
    axis, must carry the second axis's direction too.

    |ũ₂| = |ũ₁ t| (both √(q₂/s_ref), also over the radical tower, where the identity is
    algebraic), so r = e^{iθ} with θ the error of the turn: Im r = sin θ, with simple
    zeros, is the closure condition, and Re r − 1 is −2 at θ = π, where the second axis
    is reversed (another linkage: the link with that axis turned by π). Over C,
    (Re r)² + (Im r)² = 1 still holds, so r − 1 = 0, read as the complex number
    Re r − 1 + i Im r, holds only at r = 1: one residual that tells the two apart, for
    complex modes too (the exact method's factor test). O(1).

    >>> x_axis = Axis(1 + 0j, 0j, 0.0)
    >>> [complex(turn_mismatch(x_axis, Axis(d, 0j, 0.0), 1j)) for d in (1j, -1j)]  # turned by 90°, reversed
    [0j, (-2+0j)]
    """
    turned = first.direction * turn
    return second.direction * turned.conjugate() / (turned.conjugate() * turned).real - 1


def turn_residual(mismatch, root: Callable[[Any], Any]) -> Any:
    """The residual of a two-slider closure from its :func:`turn_mismatch` r − 1:
    Im r = sin θ, defined only where Re r ≥ 0 (``root``: √x in the arithmetic, NaN where
    x < 0). sin θ vanishes at θ = π too, where the second axis is reversed — another
    linkage, never a mode of this one (Re r = −1); undefined there, such a root is neither
    searched nor certified. O(1)."""
    return mismatch.imag + 0 * root(1 + mismatch.real)


def slider_point(axis: Axis, p_x, offset) -> Any:
    """The slider's point on a link (P_i' or P_i''), from a placed joint P_x of that link
    whose place in the axis frame of the link is ``offset`` = a_x + i h_x
    (:func:`~baranov.scene.sliders.axis_frame`): p_i = p_x − offset ũ. O(1)."""
    return p_x - offset * axis.direction


def along_radicand(s_jk, rise) -> Any:
    """s_{j,k} − Δh², the squared along-axis step between two joints √s_{j,k} apart whose
    heights differ by Δh (``rise``): negative where no such step exists."""
    return s_jk - rise * rise


@dataclass(frozen=True)
class SearchedParameter:
    """A plan parameter that is not a squared distance with a known bound, as the
    backends search it: a value p in (0, scale²], like a squared distance, mapped to the
    parameter by :meth:`value`. With sliders a parameter can be an oriented distance t
    (thesis §4.2.4: of either sign), and a parameter whose joints no path of link
    dimensions joins without sliding has no bound: a tangent maps (0, scale²] onto the
    whole line (t) or half-line (s), evenly in √p around |value| ≈ scale.

    Attributes
    ----------
    signed
        an oriented distance t rather than a squared distance s.
    bounded
        |t| ≤ scale (t = (2√p/scale − 1) scale); else the tangent map.
    scale
        the bound, or the linkage's size where there is none.
    """

    signed: bool
    bounded: bool
    scale: float

    def value(self, searched):
        """The parameter at the searched value(s) p (numpy)."""
        fraction = np.sqrt(searched) / self.scale  # in (0, 1]
        if self.signed:
            return self.scale * (2 * fraction - 1 if self.bounded else np.tan(np.pi * (fraction - 0.5)))
        return (self.scale * np.tan(np.pi / 2 * fraction)) ** 2

    def searched(self, value):
        """The searched value(s) p of the parameter value(s) ``value`` (numpy): the inverse
        of :meth:`value`, for a parameter read back from a configuration. A bounded t a
        rounding error beyond ±scale is taken at the bound.

        >>> mapping = SearchedParameter(signed=True, bounded=False, scale=3.0)
        >>> round(float(mapping.value(mapping.searched(-23.0))), 12)
        -23.0
        """
        if self.signed:
            ratio = np.asarray(value, float) / self.scale
            fraction = np.clip((ratio + 1) / 2, 0, 1) if self.bounded else np.arctan(ratio) / np.pi + 0.5
        else:
            fraction = 2 / np.pi * np.arctan(np.sqrt(np.asarray(value, float)) / self.scale)
        return (fraction * self.scale) ** 2


@dataclass(frozen=True)
class SliderGeometry:
    """What a plan needs of one slider joint, from the scene.

    Attributes
    ----------
    links
        the names of its two links, in scene order (P_i' on the first).
    offsets
        for each link, each of its other revolute joints in the axis frame of
        the slider's point on it: a + i h (:func:`~baranov.scene.sliders.axis_frame`).
    turns
        for each slider sharing a link with this one, the direction of its axis
        in this one's axis frame (:func:`~baranov.scene.sliders.axis_turn`).
    slider_offsets
        for each link, the points of its other sliders in that frame.
    unit
        q, the squared world length of the unit of its frames (:attr:`Axis.unit`).
    """

    links: tuple[str, str]
    offsets: Mapping[str, Mapping[str, complex]]
    turns: Mapping[str, complex]
    slider_offsets: Mapping[str, Mapping[str, complex]]
    unit: Any = 1

    def offset(self, joint: str) -> complex | None:
        """``joint``'s a + i h, if it lies on one of the slider's links."""
        return next((frame[joint] for frame in self.offsets.values() if joint in frame), None)

    def crossing_height(self, second: str, third: str) -> Any:
        """For a link of this slider whose other joints ``second`` and ``third`` are sliders
        too: the oriented distance, in ``third``'s axis units, of the point where this
        slider's and ``second``'s axes cross (on the link) to ``third``'s axis. In this
        slider's frame on the link (its axis the real line) the crossing is
        x = o₂ − (Im o₂ / Im t₂) t₂, with o the sliders' points on the link and t the
        turns to their axes; its height above the line o₃ + λ t₃ is
        Im(t̄₃ (x − o₃)) / |t₃|² (the turn carries √(q₃/q), :func:`turned_axis`)."""
        frame = next(frame for frame in self.slider_offsets.values() if second in frame and third in frame)
        o2, o3, t2, t3 = frame[second], frame[third], self.turns[second], self.turns[third]
        crossing = o2 - o2.imag / t2.imag * t2
        return (t3.conjugate() * (crossing - o3)).imag / (t3.conjugate() * t3).real


def takes_root(step, sliders: Collection[str]) -> bool:
    """Whether ``step`` takes a square root of its own when the joints ``sliders`` are
    sliders: a free-sign bilateration, or a slider construction with a free along-axis
    sign (:func:`axis_through`, :func:`point_off_axis` off a link); not a turned axis or
    a point on two axes (no sign), nor a link's constant step."""
    touched = [joint for joint in step.triangle if joint in sliders]
    if not touched or not step.free_sign:
        return step.free_sign
    in_base = [joint for joint in step.base if joint in sliders]
    return not in_base if step.joint in sliders else len(in_base) == 1


class _ConvertedPoints(dict):
    """The kernel's points as numbers of the slider constructions, each converted when a
    construction first reads it: a step reads two or three of them, where converting every
    placed point at every slider step made O(steps²) numbers."""

    def __init__(self, points: Mapping[str, Any], to_number: Callable):
        super().__init__()
        self.points, self.to_number = points, to_number

    def __missing__(self, name: str) -> Any:
        value = self[name] = self.to_number(self.points[name])
        return value


class SliderPlacement:
    """The plan steps that touch a slider, for :func:`~.bilateration.place_joints` (its
    ``slider_step``): the axes placed so far, and the constructions above chosen by which
    of a step's joints are sliders. Complex arithmetic (the numeric evaluation).

    Parameters
    ----------
    geometry
        the slider joints.
    parameter
        the value of a parameter pair, None for another pair; for a pair of a
        slider and a joint, the joint's oriented distance t to the axis (thesis
        §4.2.4).
    along_root
        ``along_root(index, step, s, radicand)``: σ√radicand (σ the step's
        sign), for the radicand s − Δh² of a step with a free sign.
    """

    def __init__(self, geometry: Mapping[str, SliderGeometry], parameter: Callable[[str, str], Any],
                 along_root: Callable[[int, Any, Any, Any], Any]):
        self.geometry = geometry
        self.parameter = parameter
        self.along_root = along_root
        self.axes: dict[str, Axis] = {}

    def copy(self) -> SliderPlacement:
        """This placement with the axes placed so far, its own from here on (a sign
        branch keeps its axes while the next branch replaces the steps after their
        common ones)."""
        copied = SliderPlacement(self.geometry, self.parameter, self.along_root)
        copied.axes = dict(self.axes)
        return copied

    def height(self, slider: str, joint: str, points: Mapping[str, Any], reference) -> Any:
        """P_joint's oriented distance to ``slider``'s axis: a link constant, the
        parameter t, or computed from the placed axis."""
        offset = self.geometry[slider].offset(joint)
        if offset is not None:
            return offset.imag
        value = self.parameter(slider, joint)
        if value is not None:
            return value
        return height_above(self.axes[slider], points[joint], reference)

    def frame(self, a: str, b: str) -> tuple[dict[str, Any], Any] | None:
        """For a reference pair (a, b) with one slider: the frame on its axis, in its axis
        units (the axis the real line, sliding towards +1, through 0): the other joint at
        i h, and s_ref = q, 1 in world units (thesis §4.2.4 puts the frame so). None
        without a slider."""
        if a not in self.geometry and b not in self.geometry:
            return None
        slider, other = (a, b) if a in self.geometry else (b, a)
        height, unit = self.height(slider, other, {}, 1), self.geometry[slider].unit
        self.axes[slider] = Axis(1 + 0 * height, 0 * height, 0 * height, unit)  # 1, 0, 0 in the height's arithmetic
        return {other: 1j * height}, unit

    def closure(self, u: str, v: str, points: Mapping[str, Any], reference) -> Any:
        """The closure s_{u,v} of a pair with a slider as δ → ∞: P_v's oriented distance
        to the slider P_u's axis, computed, minus the link's (:func:`height_above`; a
        real number), or, for two sliders of one link, the complex :func:`turn_mismatch`
        of their axes, whose imaginary part is the condition."""
        slider, joint = (u, v) if u in self.geometry else (v, u)
        if joint in self.geometry:
            return turn_mismatch(self.axes[slider], self.axes[joint], self.geometry[slider].turns[joint])
        return height_above(self.axes[slider], points[joint], reference) - self.geometry[slider].offset(joint).imag

    def _along(self, index: int, step, slider: str, first: str, second: str, squared, rise) -> Any:
        """The along-axis step from ``first`` to ``second``: a constant of ``slider``'s
        link where the step is a link step, else σ√(s − Δh²)."""
        geometry = self.geometry[slider]
        if not step.free_sign:
            return (geometry.offset(second) - geometry.offset(first)).real
        return self.along_root(index, step, squared, along_radicand(squared if geometry.unit == 1 else
                                                                    squared / geometry.unit, rise))

    def step(self, index: int, step, points: dict[str, Any], reference, distance: Callable[[str, str], Any]) -> bool:
        """Place ``step`` if it touches a slider (an axis into :attr:`axes`, or a joint
        into ``points``, as complex numbers); False if it does not."""
        i, j = step.base
        k = step.joint
        if not {i, j, k} & self.geometry.keys():
            return False
        sliders = [name for name in (i, j) if name in self.geometry]
        if k in self.geometry:
            if len(sliders) == 2:  # three sliders of one link (planner.sliders allows no other)
                self.axes[k] = third_axis(self.axes[i], self.axes[j], self.geometry[i].turns[k],
                                          self.geometry[i].crossing_height(j, k), reference, self.geometry[k].unit)
                return True
            if sliders:
                other = j if sliders[0] == i else i
                self.axes[k] = turned_axis(self.axes[sliders[0]], self.geometry[sliders[0]].turns[k], points[other],
                                           self.height(k, other, points, reference), self.geometry[k].unit)
                return True
            h_i, h_j = self.height(k, i, points, reference), self.height(k, j, points, reference)
            along = self._along(index, step, k, i, j, distance(i, j), h_j - h_i)
            self.axes[k] = axis_through(points[i], h_i, points[j], h_j, along, self.geometry[k].unit)
            return True
        if len(sliders) == 2:
            points[k] = point_on_two_axes(self.axes[i], self.height(i, k, points, reference),
                                          self.axes[j], self.height(j, k, points, reference), reference)
            return True
        slider = sliders[0]
        other = j if slider == i else i
        h_other, h_k = self.height(slider, other, points, reference), self.height(slider, k, points, reference)
        along = self._along(index, step, slider, other, k, distance(other, k), h_k - h_other)
        points[k] = point_off_axis(self.axes[slider], points[other], h_other, h_k, along)
        return True

    def kernel_hooks(self, reference_pair: tuple[str, str], to_number: Callable, from_number: Callable,
                     reference_of: Callable = lambda reference: reference[0],
                     distance_of: Callable = lambda pair: pair[0]) -> tuple[Callable, Callable]:
        """The ``slider_step`` and ``slider_frame`` hooks of
        :func:`~.bilateration.place_joints`, for an arithmetic whose kernel points
        (x, y, w) become numbers of this class's constructions by ``to_number`` and back
        by ``from_number``; ``reference_of`` and ``distance_of`` turn the kernel's
        (numerator, denominator) pairs into such numbers (floats: the numerator)."""
        def slider_step(index, step, points, reference, distance):
            at = _ConvertedPoints(points, to_number)
            if not self.step(index, step, at, reference_of(reference), lambda u, v: distance_of(distance(u, v))):
                return None
            if step.joint in self.geometry:
                return from_number(self.axes[step.joint].direction)
            points[step.joint] = from_number(at[step.joint])
            return points[step.joint]

        def slider_frame():
            started = self.frame(*reference_pair)
            if started is None:
                return None
            (joint, point), = started[0].items()
            return {joint: from_number(point)}, (started[1], 1)

        return slider_step, slider_frame

    def slider_points(self, points: Mapping[str, Any], reference) -> dict[str, Any]:
        """Each slider's point on each of its links (``P9'`` on the first, ``P9''`` on
        the second): from a placed revolute joint of that link (:func:`slider_point`),
        or, on a link whose other joints are sliders, where its two axes put it: on its
        own axis, and at the height from the other axis that brings the other slider's
        point onto that one (:func:`point_on_two_axes`)."""
        placed = {}
        for name, geometry in self.geometry.items():
            for link, mark in zip(geometry.links, ("'", "''"), strict=True):
                if geometry.offsets[link]:
                    joint, offset = next(iter(geometry.offsets[link].items()))
                    placed[name + mark] = slider_point(self.axes[name], points[joint], offset)
                    continue
                other, offset = next(iter(geometry.slider_offsets[link].items()))
                turn = geometry.turns[other]
                # the height of this point over the other axis, in its units: the turn is
                # e^{iγ} √(q_other/q), so divide by |turn|² = q_other/q
                placed[name + mark] = point_on_two_axes(self.axes[name], 0.0, self.axes[other],
                                                        -(turn.conjugate() * offset).imag / (turn.conjugate() * turn).real,
                                                        reference)
        return placed
