"""What the explorer varies: a scene's or a robot's dimensions as named controls, and the
linkage they make.

A *document* is a scene file or a robot file, kept as its JSON structure so that what is
not varied stays exactly as written. Its *controls* are independent dimensions, each a
number a slider of the page sets:

* a link's **squared distances**, named ``"Pu,Pv"`` as in a scene file: for a link of k
  joints the 2k − 3 of a trilateration (every side of a binary or ternary link; for
  k ≥ 4 the triangle of its first three joints and each further joint's distances to the
  first two), so that any values satisfying the triangle inequality make a planar body.
  The other distances of a changed link follow from its shape, each joint kept on its
  side of the line through the first two. The fixed link is varied too: its first joint
  stays where it is and the direction to its second joint is kept;
* a slider's **angle** on each of its two links (thesis §4.1: the angle α_j from the
  sliding direction to the link's reference joint P_j), in degrees, named
  ``"P9 on t569"``;
* a robot's **actuators** (thesis ch. 5), named ``"actuator 1"`` … ``"actuator 3"``;
* a moving linkage's **inputs** (a scene's ``"inputs"``: a crank angle in degrees, a
  squared distance), named ``"input crank"``: held at a value, a one-degree-of-freedom
  linkage is rigid, and its assembly modes are its configurations there. An input the
  file leaves without a value starts where the traced motion first passes (the middle
  of its first piece, :func:`baranov.motion.trace`); a moving scene without inputs is
  driven by its one-degree-of-freedom plan's first parameter (a squared distance).

A control left at its initial value leaves its link as the file gives it, exact numbers
included: the first frame is the scene ``baranov solve`` reads.
"""

from __future__ import annotations

import copy
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from baranov.scene import Scene, SceneError, load_scene, scene_from_dict
from baranov.scene.model import point_in_frame
from baranov.scene.sliders import angle_direction

#: The range a squared-distance control spans, as factors of its initial length.
LENGTH_RANGE = (0.05, 2.0)


class ControlError(SceneError):
    """A control the document does not have, or a value it cannot take (the message names
    the control)."""


@dataclass(frozen=True)
class Control:
    """One dimension the page varies.

    Attributes
    ----------
    name
        ``"P2,P4"`` (a squared distance), ``"P9 on t569"`` (a slider's angle on a
        link) or ``"actuator 2"``.
    kind
        ``"squared distance"``, ``"angle"`` (degrees), ``"actuator"`` or
        ``"input"`` (degrees for an angle input, else a squared distance).
    link
        the link the dimension belongs to (None for an actuator).
    value
        its value in the document, as a float.
    low, high
        the slider's range.
    """

    name: str
    kind: str
    link: str | None
    value: float
    low: float
    high: float

    def to_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "link": self.link, "value": self.value,
                "low": self.low, "high": self.high}


@dataclass(frozen=True)
class Document:
    """A scene or robot file for the explorer: its JSON structure and its controls."""

    title: str
    kind: str  # "scene" or "robot"
    data: Mapping
    controls: tuple[Control, ...]
    #: the linkage at the document's own values (a robot: its locked scene)
    scene: Scene

    def control(self, name: str) -> Control:
        for control in self.controls:
            if control.name == name:
                return control
        raise ControlError(f"dimension {name!r}: not a dimension of {self.title}")


def load_document(path: str | Path) -> Document:
    """The document of a scene file or a robot file (a file with ``"legs"``), checked by
    the same loaders as ``baranov solve`` and ``baranov robot``.

    >>> document = load_document("examples/7-B1.json")
    >>> [control.name for control in document.controls][:4]
    ['P3,P4', 'P3,P5', 'P4,P5', 'P2,P4']
    """
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except OSError as error:
        raise SceneError(f"{path}: cannot read ({error.strerror})") from None
    except ValueError as error:
        raise SceneError(f"{path}: not valid JSON ({error})") from None
    if isinstance(data, Mapping) and "legs" in data:
        from baranov.robots.model import robot_from_dict

        robot, actuators = robot_from_dict(data)
        if actuators is None:
            raise ControlError(f"{path}: give the robot's \"actuators\" (three values) to explore it")
        from baranov.robots.locked import locked_scene

        return Document(path.name, "robot", data, tuple(_actuator_controls(data, actuators)),
                        locked_scene(robot, actuators))
    scene = load_scene(path)
    if scene.mobility > 0 and not scene.inputs:
        data = {**data, "inputs": [_distance_input(scene)]}
        scene = scene_from_dict(data)
    controls = _scene_controls(data, scene)
    if scene.mobility > 0:
        inputs = _input_controls(scene)
        controls += inputs
        scene = scene_from_dict(_with_inputs(data, {control.name: control.value for control in inputs}))
    return Document(path.name, "scene", data, tuple(controls), scene)


def document_scene(document: Document, values: Mapping[str, float] | None = None) -> Scene:
    """The linkage the document makes with the controls ``values`` (name → value; a
    control not named, or at its initial value, as the file gives it).

    Raises :class:`~baranov.scene.SceneError` (:class:`ControlError` for an unknown
    control) naming what makes no linkage, e.g. a triangle inequality.

    >>> document = load_document("examples/7-B1.json")
    >>> scene = document_scene(document, {"P2,P4": 20.0})
    >>> float(scene.known[frozenset(("P2", "P4"))]), scene.exact
    (20.0, False)
    """
    if document.kind == "robot":
        return document_robot(document, values)[0]
    return scene_from_dict(document_data(document, values))


def document_data(document: Document, values: Mapping[str, float] | None = None) -> dict:
    """The document's JSON structure with the controls ``values``: what the page exports
    as the current scene (or robot) file."""
    changed = _changed(document, values or {})
    data = copy.deepcopy(dict(document.data))
    if document.kind == "robot":
        data["actuators"] = _actuators(data["actuators"], changed)
        return data
    by_link: dict[str, dict[str, float]] = {}
    for name, value in changed.items():
        control = document.control(name)
        if control.kind == "squared distance":
            by_link.setdefault(control.link, {})[name] = value
    for index, entry in enumerate(data["links"]):
        values_here = by_link.get(entry["name"])
        if values_here:
            data["links"][index] = _rebuilt_link(document.scene, entry, values_here, ground=entry["name"] == data["ground"])
    for slider in data.get("sliders", []):
        for link, angles in slider["angles"].items():
            name = f"{slider['joint']} on {link}"
            if name in changed:
                (reference,) = angles
                angles[reference] = changed[name]  # a float: degrees (scene/sliders.py)
    inputs = {control.name: changed.get(control.name, control.value) for control in document.controls
              if control.kind == "input"}
    return _with_inputs(data, inputs) if inputs else data


def document_robot(document: Document, values: Mapping[str, float] | None = None):
    """A robot document's robot, its actuator values with ``values``, its locked scene and
    its platform's joints (:func:`baranov.robots.locked.locked_robot`)."""
    return _robot_scene(document, _changed(document, values or {}))


def _changed(document: Document, values: Mapping[str, float]) -> dict[str, float]:
    """The controls whose values differ from the document's, as floats."""
    changed = {}
    for name, value in values.items():
        control = document.control(name)
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ControlError(f"dimension {name}: {value!r} is not a number") from None
        if not math.isfinite(number):
            raise ControlError(f"dimension {name}: {value!r} is not a finite number")
        if control.kind == "squared distance" and number <= 0:
            raise ControlError(f"dimension {name}: squared distance {number:g} is not positive")
        if number != control.value:
            changed[name] = number
    return changed


def _robot_scene(document: Document, changed: Mapping[str, float]):
    from baranov.robots.locked import locked_robot
    from baranov.robots.model import robot_from_dict

    robot, actuators = robot_from_dict(document.data)
    actuators = _actuators(actuators, changed)
    scene, platform = locked_robot(robot, actuators)
    return scene, robot, actuators, platform


def _actuators(given, changed: Mapping[str, float]) -> list:
    """The actuator values ``given`` with the controls ``"actuator k"`` of ``changed``."""
    values = list(given)
    for name, value in changed.items():
        values[int(name.removeprefix("actuator ")) - 1] = value
    return values


def _actuator_controls(data: Mapping, actuators) -> list[Control]:
    from baranov.robots.legs import Leg
    from baranov.robots.model import to_number

    controls = []
    for number, (entry, value) in enumerate(zip(data["legs"], actuators, strict=True), 1):
        leg, value = Leg.parse(str(entry["type"])), float(to_number(value, "actuator"))
        if str(leg)[leg.actuated] == "r":  # an angle in radians (robots/locked.py)
            low, high = value - math.pi, value + math.pi
        else:
            span = max(abs(value), 1.0)
            low, high = value - span, value + span
            if str(leg) == "RpR":  # a leg's length
                low = max(low, 0.02 * span)
        controls.append(Control(f"actuator {number}", "actuator", None, value, low, high))
    return controls


def independent_pairs(joints: tuple[str, ...]) -> list[tuple[str, str]]:
    """The 2k − 3 pairs of a k-joint link whose squared distances fix its shape up to
    reflection of each further joint: the first three joints' triangle, then each further
    joint's distances to the first two (a trilateration).

    >>> independent_pairs(("P1", "P2", "P3", "P4"))
    [('P1', 'P2'), ('P1', 'P3'), ('P2', 'P3'), ('P1', 'P4'), ('P2', 'P4')]
    """
    pairs = [(joints[0], joints[1])]
    if len(joints) >= 3:
        pairs += [(joints[0], joints[2]), (joints[1], joints[2])]
    pairs += [pair for joint in joints[3:] for pair in ((joints[0], joint), (joints[1], joint))]
    return pairs


def _scene_controls(data: Mapping, scene: Scene) -> list[Control]:
    controls = []
    for link in scene.links:
        for a, b in independent_pairs(link.joints):
            value = float(link.squared_distances[frozenset((a, b))])
            low, high = (factor**2 * value for factor in LENGTH_RANGE)
            controls.append(Control(f"{a},{b}", "squared distance", link.name, value, low, high))
    for slider in data.get("sliders", []):
        for link, angles in slider["angles"].items():
            (given,) = angles.values()
            x, y = (float(c) for c in angle_direction(given))
            value = math.degrees(math.atan2(y, x))
            controls.append(Control(f"{slider['joint']} on {link}", "angle", link, value, value - 180, value + 180))
    return controls


def _input_controls(scene: Scene) -> list[Control]:
    """A control per input of a moving scene (``scene.mobility`` 1); an input without a
    value gets the one the traced motion first passes."""
    start = None
    controls = []
    for driver in scene.inputs:
        value = driver.value
        if value is None:
            start = start or _traced_start(scene)
            from baranov.motion.driving import input_value

            value = input_value(driver, start)
        value = float(value)
        if driver.kind == "angle":
            controls.append(Control(f"input {driver.name}", "input", None, value, -180.0, 180.0))
        else:
            low, high = (factor**2 * value for factor in LENGTH_RANGE)
            controls.append(Control(f"input {driver.name}", "input", None, value, low, high))
    return controls


def _distance_input(scene: Scene) -> dict:
    """An input for a moving scene that names none: the squared distance its one-degree-
    of-freedom plan takes as first parameter (thesis §6.1)."""
    from baranov.motion import one_dof_system

    u, v = one_dof_system(scene).plan.parameters[0]
    return {"name": f"s{u.removeprefix('P')},{v.removeprefix('P')}", "distance": [u, v]}


def _traced_start(scene: Scene):
    """A configuration of a moving scene: the middle of the first traced piece."""
    from baranov.motion import one_dof_system, trace

    pieces = trace(one_dof_system(scene), steps=100).pieces
    if not pieces:
        raise ControlError("the linkage has no configuration to start from (its traced motion is empty): give its "
                           "inputs values")
    return pieces[0].points[len(pieces[0].points) // 2]


def _with_inputs(data: Mapping, values: Mapping[str, float]) -> dict:
    """``data`` with each input ``"input NAME"`` of ``values`` held at its value."""
    data = dict(data)
    entries = []
    for entry in data["inputs"]:
        entry = dict(entry)
        name = f"input {entry['name']}"
        if name in values:
            entry.pop("degrees", None)
            entry.pop("squared_distance", None)
            entry["degrees" if "angle" in entry else "squared_distance"] = values[name]
        entries.append(entry)
    data["inputs"] = entries
    return data


def _rebuilt_link(scene: Scene, entry: Mapping, values: Mapping[str, float], ground: bool) -> dict:
    """A link's scene-file entry with some of its independent squared distances replaced:
    by squared distances (a moving link) or coordinates (the fixed link, its first joint
    and the direction to its second kept)."""
    link = scene.link_of(entry["name"])
    joints = link.joints
    squared = {frozenset(pair): float(link.squared_distances[frozenset(pair)]) for pair in independent_pairs(joints)}
    for name, value in values.items():
        squared[frozenset(name.split(","))] = value
    local = _trilaterated(link.name, joints, squared, link.local)
    if ground:
        world = {joint: tuple(float(c) for c in scene.world[joint]) for joint in joints[:2]}
        placed = _moved_to(local, joints, world)
        return {"name": link.name, "joints": {joint: list(placed[joint]) for joint in joints},
                **({"comment": entry["comment"]} if "comment" in entry else {})}
    if len(joints) == 2:
        return {"name": link.name, "joints": list(joints), "squared_length": squared[frozenset(joints)]}
    distances = {f"{a},{b}": (local[a][0] - local[b][0]) ** 2 + (local[a][1] - local[b][1]) ** 2
                 for k, a in enumerate(joints) for b in joints[k + 1:]}
    for pair in independent_pairs(joints):  # as given, not as rounded through the frame
        distances[",".join(pair)] = squared[frozenset(pair)]
    (x1, y1), (x2, y2), (x3, y3) = (local[joint] for joint in joints[:3])
    orientation = "ccw" if (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1) > 0 else "cw"
    return {"name": link.name, "joints": list(joints), "squared_distances": distances, "orientation": orientation}


def _trilaterated(name: str, joints, squared: Mapping[frozenset, float], sides: Mapping) -> dict:
    """Local coordinates from the independent squared distances (first joint at the
    origin, second on +x), each further joint on the side of the first two that ``sides``
    (the link's current frame) puts it (:func:`~baranov.scene.model.point_in_frame`)."""
    first, second = joints[0], joints[1]
    local = {first: (0.0, 0.0), second: (math.sqrt(squared[frozenset((first, second))]), 0.0)}
    (ax, ay), (bx, by) = sides[first], sides[second]
    for joint in joints[2:]:
        px, py = sides[joint]
        side = 1 if (bx - ax) * (py - ay) - (by - ay) * (px - ax) >= 0 else -1
        local[joint] = point_in_frame(name, (first, second, joint), squared, side)
    return local


def _moved_to(local: Mapping, joints, world: Mapping) -> dict[str, tuple[float, float]]:
    """``local`` turned and moved so that its first joint is at ``world``'s and its second
    lies in the direction ``world`` gives it."""
    (x0, y0), (x1, y1) = world[joints[0]], world[joints[1]]
    angle = math.atan2(y1 - y0, x1 - x0)
    c, s = math.cos(angle), math.sin(angle)
    return {joint: (x0 + c * x - s * y, y0 + s * x + c * y) for joint, (x, y) in local.items()}
