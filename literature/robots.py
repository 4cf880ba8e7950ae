"""The fully-parallel planar robot families of thesis §5.2, Table 5.3: each family's
locked structure (one of the ten 5-link Assur kinematic chains), its leg architectures
(the passive joints of each leg, base to platform) as printed, the number of robots the
thesis counts in it, and its generic number of assembly modes (the degree of its
characteristic polynomial, "AM" in Tables 5.4–5.6: 6, 6, 6, 4, 4, 2, 2, 2, 1, 1)."""

from __future__ import annotations

#: Family → (leg architectures as printed in Table 5.3, robots, assembly modes).
THESIS_ROBOT_FAMILIES: dict[str, tuple[tuple[str, ...], int, int]] = {
    "I": (("RR-RR-RR",), 56, 6),
    "II": (("RP-RR-RR", "PR-RR-RR"), 252, 6),
    "III": (("RP-PR-RR",), 216, 6),
    "IV": (("RP-RP-RR", "PR-PR-RR"), 252, 4),
    "V": (("RP-RP-PR", "PR-PR-RP"), 252, 4),
    "VI": (("PP-RR-RR",), 63, 2),
    "VII": (("PP-RR-RP", "PP-RR-PR"), 216, 2),
    "VIII": (("RP-RP-RP", "PR-PR-PR"), 112, 2),
    "IX": (("PP-PR-RP",), 108, 1),
    "X": (("PP-RP-RP", "PP-PR-PR"), 126, 1),
}

#: Robots in all: (18 legs of types RR, RP, PR, three at a time with repetition) +
#: 3 PP legs × (two of the 18 with repetition) = 1140 + 513 (§5.2).
THESIS_ROBOTS = (1140, 513, 1653)
