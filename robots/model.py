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
class LegGeometry:
    """Where one leg is attached and its fixed dimensions (see the module table)."""

    base: Point
    platform: Point
    lengths: tuple[float | Fraction, ...] = ()
    axis: Point | None = None


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
        if not isinstance(entry, Mapping) or "type" not in entry or "base" not in entry or "platform" not in entry:
            raise RobotInputError(f'leg {number}: needs "type" (e.g. RpR), "base" and "platform" points')
        legs.append(Leg.parse(str(entry["type"])))
        geometry.append(LegGeometry(_point(entry["base"], number, "base"), _point(entry["platform"], number, "platform"),
                                    tuple(to_number(v, f"leg {number}, lengths") for v in entry.get("lengths", ())),
                                    _point(entry["axis"], number, "axis") if "axis" in entry else None))
    actuators = data.get("actuators")
    if actuators is not None and (not isinstance(actuators, list) or len(actuators) != 3):
        raise RobotInputError('robot: "actuators" should be a list of three values, one per leg')
    return Robot(tuple(legs), tuple(geometry)), actuators


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
