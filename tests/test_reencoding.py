"""The answer does not depend on how a scene is written (issue 55): random slider chains
drawn around integer configurations (every link by coordinates, every slider angle as a
direction [x, y]) are re-encoded in the scene format's other forms — a link by its squared
distances and orientation, a binary link by its squared length, the ground by its
distances (placed anew: first joint at the origin, second on the +x axis), an angle as an
``atan2`` expression, as π plus the opposite direction's, or from another joint of its
link — and every method gives the modes of the original, compared in the frame of the
ground's first two joints. The fuzz target runs 10⁴ cases (``make fuzz``; FUZZ cases)."""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.scene import scene_from_dict
from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
from baranov.solvers import MovableLinkageError, solve
from baranov.solvers.msolve import compare_modes, find_msolve

needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve not installed (make setup installs it)")
TRUSSES = [truss for links in (5, 7) for truss in baranov_trusses(links)]
METHODS = ("numeric", "exact", "msolve")
#: Cases of the default run; the fuzz target sets BARANOV_FUZZ_EXAMPLES (``make fuzz``).
EXAMPLES = int(os.environ.get("BARANOV_FUZZ_EXAMPLES", "6"))

LINK_FORMS = ("coordinates", "distances")
ANGLE_FORMS = ("direction", "atan2", "pi plus", "another joint")


def _squared(p, q) -> int:
    return (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2


def _cross(p, q, r) -> int:
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def _by_distances(link: dict) -> dict:
    """A link given by coordinates, written by its squared distances (and the orientation
    of its first three joints, ordered so that they are not in line)."""
    points = link["joints"]
    names = list(points)
    if len(names) == 2:
        return {"name": link["name"], "joints": names, "squared_length": _squared(*points.values())}
    order = next([a, b, c] for a in names for b in names for c in names
                 if len({a, b, c}) == 3 and _cross(points[a], points[b], points[c]) != 0)
    order += [n for n in names if n not in order]
    distances = {f"{u},{v}": _squared(points[u], points[v]) for i, u in enumerate(order) for v in order[i + 1:]}
    orientation = "ccw" if _cross(*(points[n] for n in order[:3])) > 0 else "cw"
    return {"name": link["name"], "joints": order, "squared_distances": distances, "orientation": orientation}


def _angle(form: str, direction: list[int], joint_point, reference_point, other: tuple[str, list[int]] | None):
    """The angle of ``direction`` (seen from the slider's point ``joint_point`` towards
    ``reference_point``, from the axis) in another form; (reference joint, value)."""
    x, y = direction
    if form == "atan2":
        return None, f"atan2({y}, {x})"
    if form == "pi plus":
        return None, f"pi + atan2({-y}, {-x})"
    if form == "another joint" and other is not None:
        # the axis d has conj(d) ∝ a / (P_ref − P_i); from P_k the angle is (P_k − P_i) conj(d)
        name, point = other
        a = complex(x, y)
        k = complex(point[0] - joint_point[0], point[1] - joint_point[1])
        r = complex(reference_point[0] - joint_point[0], reference_point[1] - joint_point[1])
        new = k * a * r.conjugate()
        return name, [int(new.real), int(new.imag)]
    return None, [x, y]


def reencoded(data: dict, draw) -> dict:
    """``data`` (links by coordinates, angles as directions) with each link, the ground
    and each slider angle written in a form ``draw`` picks (a hypothesis draw)."""
    links = {link["name"]: link for link in data["links"]}
    forms = {name: draw(st.sampled_from(LINK_FORMS)) for name in links}
    sliders = []
    for slider in data["sliders"]:
        angles = {}
        for link_name, ((reference, direction),) in ((n, tuple(a.items())) for n, a in slider["angles"].items()):
            points = links[link_name]["joints"]
            others = [(n, p) for n, p in points.items() if n not in (slider["joint"], reference)
                      and p != points[slider["joint"]]]
            form = draw(st.sampled_from(ANGLE_FORMS))
            new_reference, value = _angle(form, direction, points[slider["joint"]], points[reference],
                                          others[0] if others else None)
            angles[link_name] = {new_reference or reference: value}
        sliders.append({"joint": slider["joint"], "angles": angles})
    return {"ground": data["ground"], "sliders": sliders,
            "links": [_by_distances(link) if forms[name] == "distances" else link for name, link in links.items()]}


def _in_ground_frame(configurations: list[dict], first: str, second: str) -> list[dict]:
    """Configurations moved so that joint ``first`` is at the origin and ``second`` on the +x axis."""
    moved = []
    for joints in configurations:
        origin, towards = complex(*joints[first]), complex(*joints[second])
        turn = ((towards - origin) / abs(towards - origin)).conjugate()
        points = {name: (complex(*xy) - origin) * turn for name, xy in joints.items()}
        moved.append({name: (z.real, z.imag) for name, z in points.items()})
    return moved


@st.composite
def _instances(draw):
    truss = TRUSSES[draw(st.integers(0, len(TRUSSES) - 1))]
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    data = slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=True)
    data.pop("generating_configuration")
    return data, reencoded(data, draw)


@needs_msolve
@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(_instances())
def test_every_encoding_gives_the_same_modes(instance):
    original, other = instance
    ground = next(link for link in original["links"] if link["name"] == original["ground"])
    reference = scene_from_dict(original)
    first, second = (reference.point_name(reference.ground, joint) for joint in list(ground["joints"])[:2])
    try:
        exact = solve(reference, "exact")
    except MovableLinkageError:
        exact = None
    # a slider set can make the chain move (docs/sliders.md); such draws say nothing here
    assume(exact is not None and exact.certificate.complete)
    expected = _in_ground_frame([mode.joints for mode in exact.assembly_modes], first, second)
    scene = scene_from_dict(other)
    for method in METHODS:
        found = _in_ground_frame([mode.joints for mode in solve(scene, method).assembly_modes], first, second)
        assert compare_modes(found, expected)[:2] == (0, 0), (method, other)
