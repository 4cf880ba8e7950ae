"""A fully-parallel planar robot as data: its three legs and their geometry
(:class:`Robot`), and its JSON form (:func:`robot_from_dict`, :func:`load_robot`).

Robot file::

    {"legs": [{"type": "RpR", "base": [0, 0], "platform": [0, 0]},
              {"type": "rRR", "base": [4, 0], "platform": [6, 0], "lengths": [3, 9]},
              {"type": "pRR", "base": [1, 8], "platform": [3, 4], "axis": [0, 1], "lengths": [13]}],
     "actuators": [1, 0.5, 2]}

Base points in the world frame, platform points in the platform's frame; ``lengths``
and ``axis`` as each leg type needs them (:mod:`.kinematics`); ``actuators`` optional
(lengths, offsets or angles in radians, one per leg). Numbers as in scene files:
integers, decimal strings and fractions stay exact.

Any of the 21 legs, those with a prismatic passive joint included, can instead be given
by its home configuration (:mod:`.home`): its three joints base to platform, each a
point ``at`` (world frame, the platform frame on the world frame) and, for a prismatic
joint, its ``direction``; its actuator value is then the displacement from home::

    {"type": "RpP", "home": [{"at": [0, 0]}, {"at": [0, 0], "direction": [0, 1]},
                             {"at": [0, 1], "direction": [-1, 1]}]}
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

from .legs import Leg, RobotInputError

Point = tuple[float | Fraction, float | Fraction]


@dataclass(frozen=True)
class HomeJoint:
    """A joint of a leg at its home configuration: a revolute joint's centre, or a point of
    a prismatic joint's axis and its direction (world frame)."""

    at: Point
    direction: Point | None = None


@dataclass(frozen=True)
class LegGeometry:
    """Where one leg is attached and its fixed dimensions (see the module table), or its
    home configuration (``home``, three joints base to platform; then ``base`` and
    ``platform`` are its first and last joints' points)."""

    base: Point
    platform: Point
    lengths: tuple[float | Fraction, ...] = ()
    axis: Point | None = None
    home: tuple[HomeJoint, HomeJoint, HomeJoint] | None = None


@dataclass(frozen=True)
class Robot:
    """A fully-parallel planar robot: three legs and their geometry."""

    legs: tuple[Leg, Leg, Leg]
    geometry: tuple[LegGeometry, LegGeometry, LegGeometry]


def robot_from_dict(data) -> tuple[Robot, list | None]:
    """The robot of a robot file's JSON structure, and its actuator values if given."""
    if not isinstance(data, Mapping) or not isinstance(data.get("legs"), list) or len(data["legs"]) != 3:
        raise RobotInputError('robot: expected an object with "legs", a list of three legs')
    unknown = sorted(set(data) - {"legs", "actuators", "comment"})
    if unknown:
        raise RobotInputError(f"robot: unknown key {unknown[0]!r} (legs, actuators, comment)")
    legs, geometry = [], []
    for number, entry in enumerate(data["legs"], 1):
        if isinstance(entry, Mapping) and "type" in entry and "home" in entry:
            legs.append(Leg.parse(str(entry["type"])))
            geometry.append(_home_geometry(entry, number))
            continue
        if not isinstance(entry, Mapping) or "type" not in entry or "base" not in entry or "platform" not in entry:
            raise RobotInputError(f'leg {number}: needs "type" (e.g. RpR), and "base" and "platform" points or "home"')
        legs.append(Leg.parse(str(entry["type"])))
        geometry.append(LegGeometry(_point(entry["base"], number, "base"), _point(entry["platform"], number, "platform"),
                                    tuple(to_number(v, f"leg {number}, lengths") for v in entry.get("lengths", ())),
                                    _point(entry["axis"], number, "axis") if "axis" in entry else None))
    actuators = data.get("actuators")
    if actuators is not None and (not isinstance(actuators, list) or len(actuators) != 3):
        raise RobotInputError('robot: "actuators" should be a list of three values, one per leg')
    return Robot(tuple(legs), tuple(geometry)), actuators


def _home_geometry(entry: Mapping, number: int) -> LegGeometry:
    """A leg entry's home configuration (``"home"``: three joints, each ``{"at": [x, y]}``
    and a ``"direction"`` for a prismatic joint)."""
    unknown = sorted(set(entry) - {"type", "home", "comment"})
    if unknown:
        raise RobotInputError(f"leg {number}: unknown key {unknown[0]!r} beside \"home\" (type, home, comment)")
    home = entry["home"]
    if not isinstance(home, list) or len(home) != 3 or not all(isinstance(j, Mapping) and "at" in j for j in home):
        raise RobotInputError(f'leg {number}, home: three joints base to platform, each {{"at": [x, y]}} '
                              '(and "direction" for a prismatic joint)')
    joints = []
    for k, joint in enumerate(home, 1):
        where = f"leg {number}, joint {k}"
        if set(joint) - {"at", "direction"}:
            raise RobotInputError(f"{where}: unknown key {sorted(set(joint) - {'at', 'direction'})[0]!r} (at, direction)")
        joints.append(HomeJoint(_point(joint["at"], number, f"joint {k} at"),
                                _point(joint["direction"], number, f"joint {k} direction") if "direction" in joint
                                else None))
    return LegGeometry(joints[0].at, joints[2].at, home=tuple(joints))


def load_robot(path: Path) -> tuple[Robot, list | None]:
    """:func:`robot_from_dict` of the JSON file ``path``."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as error:
        raise RobotInputError(f"{path}: cannot read ({error.strerror or error})") from None
    except ValueError as error:
        raise RobotInputError(f"{path}: not JSON ({error})") from None
    return robot_from_dict(data)


def to_number(value, where: str) -> Fraction | float:
    """``value`` as an exact Fraction (int, Fraction, decimal or fraction string) or a
    float; :class:`RobotInputError` naming ``where`` for anything else."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str, Fraction)):
        raise RobotInputError(f"{where}: {value!r} is not a number")
    try:
        return value if isinstance(value, float) else Fraction(value)
    except (ValueError, ZeroDivisionError):
        raise RobotInputError(f"{where}: {value!r} is not a number") from None


def _point(value, leg: int, key: str) -> Point:
    if not isinstance(value, list) or len(value) != 2:
        raise RobotInputError(f"leg {leg}, {key}: expected [x, y]")
    return to_number(value[0], f"leg {leg}, {key}"), to_number(value[1], f"leg {leg}, {key}")
