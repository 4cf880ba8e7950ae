"""Legs of fully-parallel planar robots (thesis §5.2, Table 5.2).

A leg is a serial chain of three one-degree-of-freedom joints from the base to the
platform, revolute (R) or prismatic (P), one of them actuated. Notation: the chain base
to platform in capitals with the actuated joint in lower case, e.g. ``RpR`` for the
RPR leg with its prismatic joint actuated (the literature underlines it); a robot is its
three legs joined by hyphens, ``RpR-RpR-RpR`` for the 3-RPR. PPP is no leg (three
translations in the plane are not independent), so there are 7 chains × 3 actuated
joints = 21 legs. Locked, a leg is one rigid binary link whose two passive joints are
its ends: its *architecture* RR, RP, PR or PP (6, 6, 6 and 3 legs).
"""

from __future__ import annotations

from dataclasses import dataclass

#: The seven leg chains, base to platform (Table 5.2's order).
CHAINS = ("RRR", "RPR", "RRP", "PRR", "RPP", "PRP", "PPR")


class RobotInputError(ValueError):
    """A leg or robot string that names no fully-parallel planar robot."""


@dataclass(frozen=True, order=True)
class Leg:
    """One leg: ``joints`` base to platform (``"RPR"``), ``actuated`` its index (0–2)."""

    joints: str
    actuated: int

    def __post_init__(self) -> None:
        if self.joints not in CHAINS:
            raise RobotInputError(f"leg {self.joints}: not one of {', '.join(CHAINS)} (PPP cannot move the "
                                  "platform in three independent directions)")
        if self.actuated not in (0, 1, 2):
            raise RobotInputError(f"leg {self.joints}: actuated joint {self.actuated} is not 0, 1 or 2")

    @classmethod
    def parse(cls, text: str) -> Leg:
        """The leg written ``text``: R/P letters, the actuated one in lower case.

        >>> Leg.parse("RpR"), Leg.parse("rRR").passive
        (Leg(joints='RPR', actuated=1), 'RR')
        """
        lower = [k for k, letter in enumerate(text) if letter.islower()]
        if len(text) != 3 or set(text.upper()) - {"R", "P"} or len(lower) != 1:
            raise RobotInputError(f"leg {text!r}: three joints R or P, base to platform, the actuated one in lower "
                                  "case (e.g. RpR)")
        return cls(text.upper(), lower[0])

    @property
    def passive(self) -> str:
        """Its architecture: the passive joints, base to platform (RR, RP, PR or PP)."""
        return self.joints[:self.actuated] + self.joints[self.actuated + 1:]

    def __str__(self) -> str:
        return "".join(letter.lower() if k == self.actuated else letter for k, letter in enumerate(self.joints))


#: The 21 legs.
LEGS = tuple(Leg(chain, actuated) for chain in CHAINS for actuated in range(3))


def parse_robot(text: str) -> tuple[Leg, Leg, Leg]:
    """The three legs of a robot written ``RpR-RRp-pRR`` (in the order given); at most
    one PP leg (two would leave the platform a translation, the locked structure a
    loop closed by sliders only).

    >>> [str(leg) for leg in parse_robot("RpR-RpR-RpR")]
    ['RpR', 'RpR', 'RpR']
    """
    parts = text.split("-")
    if len(parts) != 3:
        raise RobotInputError(f"robot {text!r}: three legs joined by hyphens (e.g. RpR-RpR-RpR), got {len(parts)}")
    legs = tuple(Leg.parse(part) for part in parts)
    if sum(leg.passive == "PP" for leg in legs) > 1:
        raise RobotInputError(f"robot {text!r}: at most one leg with two passive prismatic joints (PP); with two "
                              "a loop of the locked robot has four passive prismatic joints and it moves (thesis §5.2)")
    return legs
