"""Slider steps traced into a plan's straight-line program (issue 56, item 7).

The slider constructions of :mod:`.sliders` run on "anything with the operators of a
complex number"; the numeric backend runs them on numpy complex arrays. Here they run on
:class:`~.straight_line.TracedComplex` values — a pair of traced reals (:class:`~.straight_line.Traced`)
whose sums, products, quotients and conjugates record the real instructions numpy's
complex arithmetic performs — so that a plan with slider joints becomes a
:class:`~.straight_line.StraightLineProgram` like any other and runs compiled.

A slider's geometry (its links' joints in its axis frame, the turns to the other sliders'
axes, the scale of its closure residual) depends on the instance, so each of its numbers
is an *input* of the program (:func:`traced_geometry`): one program serves every instance
of the plan with the same slider joints, and :func:`slider_constant_values` lists an
instance's numbers in the program's order. Mixed operations promote a real to a complex
number with imaginary part 0, as numpy does, so a product is the same four products and
two sums numpy forms; a quotient by a complex number is formed as a product by the
conjugate over the squared modulus (numpy's division scales differently: the values
agree to rounding, not bit for bit).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

from .sliders import SliderGeometry, SliderPlacement, turn_residual
from .straight_line import GUARDED_ROOT, Recorder, Traced, TracedComplex

#: An input of a slider's geometry: (slider, field, key, part), field "offsets" (key:
#: (link, joint)), "turns" (key: other slider), "slider_offsets" (key: (link, slider)),
#: "unit" or "scale" (key None); part 0 the real part, 1 the imaginary one.
ConstantPath = tuple[str, str, Any, int]


def traced_geometry(recorder: Recorder, sliders: Mapping[str, SliderGeometry]
                    ) -> tuple[dict[str, SliderGeometry], dict[str, Traced], list[tuple[ConstantPath, Traced]]]:
    """The slider geometries with every number an input register of ``recorder``
    (a unit of 1 stays the number 1: the constructions branch on it), each slider's
    closure scale (:func:`closure_scale`) as an input too, and the inputs in order with
    their paths (for :func:`slider_constant_values`)."""
    inputs: list[tuple[ConstantPath, Traced]] = []

    def number(path: tuple[str, str, Any], value, is_complex: bool = True):
        real = recorder.input()
        inputs.append(((*path, 0), real))
        if not is_complex:
            return real
        imaginary = recorder.input()
        inputs.append(((*path, 1), imaginary))
        return TracedComplex(real, imaginary)

    traced, scales = {}, {}
    for name in sorted(sliders):
        geometry = sliders[name]
        offsets = {link: {joint: number((name, "offsets", (link, joint)), z) for joint, z in sorted(frame.items())}
                   for link, frame in geometry.offsets.items()}
        turns = {other: number((name, "turns", other), z) for other, z in sorted(geometry.turns.items())}
        slider_offsets = {link: {other: number((name, "slider_offsets", (link, other)), z)
                                 for other, z in sorted(frame.items())}
                          for link, frame in geometry.slider_offsets.items()}
        unit = 1 if _is_one(geometry.unit) else number((name, "unit", None), geometry.unit, is_complex=False)
        traced[name] = SliderGeometry(geometry.links, offsets, turns, slider_offsets, unit)
        scales[name] = number((name, "scale", None), None, is_complex=False)
    return traced, scales, inputs


def _is_one(unit) -> bool:
    return type(unit) is int and unit == 1


def closure_scale(geometry: SliderGeometry) -> float:
    """What a closure residual with this slider (P_v's computed height against the
    link's) is divided by: the largest |a + i h| of its links' joints, the link's size."""
    return max((abs(complex(z)) for frame in geometry.offsets.values() for z in frame.values()), default=1.0)


def _geometry_number(geometry: SliderGeometry, field: str, key) -> Any:
    """The number of a slider input's path in ``geometry`` (a closure scale: none)."""
    if field == "unit":
        return geometry.unit
    if field == "turns":
        return geometry.turns[key]
    return getattr(geometry, field)[key[0]][key[1]]


def slider_constant_values(paths: tuple[ConstantPath, ...], sliders: Mapping[str, SliderGeometry]) -> list[float]:
    """An instance's numbers for a program's slider inputs (``paths``, in order)."""
    values = []
    for name, field, key, part in paths:
        value = complex(closure_scale(sliders[name]) if field == "scale" else _geometry_number(sliders[name], field, key))
        values.append(value.imag if part else value.real)
    return values


class TracedSliderHooks(NamedTuple):
    """What :func:`~.straight_line.trace_plan` needs of a plan's sliders: the kernel's
    ``slider_step`` and ``slider_frame`` hooks, the closure residual of a pair with a
    slider, and the program's slider inputs (path, register)."""

    slider_step: Callable
    slider_frame: Callable
    closure: Callable
    inputs: list


def traced_slider_placement(recorder: Recorder, plan, sliders: Mapping[str, SliderGeometry],
                            parameter: Callable[[str, str], Any], root: Callable) -> TracedSliderHooks:
    """The slider constructions of ``plan`` on traced numbers, as the numeric kernel runs
    them in numpy (``closure/evaluate.py``): ``parameter(u, v)`` the traced parameter of a
    pair (a slider's t), ``root`` the trace's signed root of a step."""
    geometry, scales, inputs = traced_geometry(recorder, sliders)

    def along_root(index, step, squared, radicand):
        # as the numpy kernel: scaled to a triangle radicand's form, then divided back
        length = recorder.emit(GUARDED_ROOT, recorder.operand(squared), recorder.operand(-math.inf))
        return root(index, step, (squared, 0.0, 0.0), radicand * squared) / length

    placement = SliderPlacement(geometry, parameter, along_root)
    slider_step, slider_frame = placement.kernel_hooks(plan.reference, lambda point: TracedComplex(point[0], point[1]),
                                                       lambda number: (number.real, number.imag, 1))

    def closure(u: str, v: str, points: Mapping, reference) -> Traced:
        """The residual of the closure pair (u, v) with a slider, as
        ``CompiledSystem._slider_closure`` computes it."""
        slider, joint = (u, v) if u in sliders else (v, u)
        point = points.get(joint)
        at = {joint: TracedComplex(point[0], point[1])} if point is not None else {}
        value = placement.closure(slider, joint, at, reference)
        if joint in sliders:
            return turn_residual(value, lambda x: recorder.emit(GUARDED_ROOT, recorder.operand(x), recorder.operand(0.0)))
        return value.real / scales[slider]

    return TracedSliderHooks(slider_step, slider_frame, closure, inputs)


def exact_slider_constants(paths: tuple[ConstantPath, ...], exact: Mapping[str, SliderGeometry],
                           sliders: Mapping[str, SliderGeometry]) -> list | None:
    """The exact numbers of a program's slider inputs (``paths``), for interval
    evaluation: from ``exact``, the geometry with each number a pair (re, im) of exact
    numbers where the scene makes it rational (Fractions; a float where it is not); None
    where one is not. A closure scale is any positive number (it does not move a
    residual's zeros): the float one of ``sliders``."""
    values: list = []
    for name, field, key, part in paths:
        if field == "scale":
            values.append(closure_scale(sliders[name]))
            continue
        number = _geometry_number(exact[name], field, key)
        component = (number, 0)[part] if field == "unit" else number[part]
        if isinstance(component, float):
            return None
        values.append(component)
    return values
