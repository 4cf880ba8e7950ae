"""The closure conditions of thesis Appendix A (Tables A.1–A.8), and the nine-link thesis
names they identify.

For every nine-link truss 9/B1–9/B28 Appendix A prints its closure conditions as
``s_{u,v} = f(parameters) = det(Ω) s_ref``: a final condition, whose distance s_{u,v} is
a link dimension, and the computed distances it depends on, each defined by an Ω_n. The
figures that showed which joint is which are missing from the text, but the conditions
themselves tell: every bilateration matrix Z_{i,j,k} in them needs the three distances
s_{i,j}, s_{i,k}, s_{j,k}, and each of these is a parameter, a computed distance or a
known one — the distance between two joints of one link. So the conditions determine a
set of pairs that must be on a common link and a set that must not (the parameters and
computed distances: were they on a link, they would be known). A catalog truss is the
thesis truss when some labelling of its joints puts every pair of the first set on a link
and no pair of the second (:func:`appendix_a_labelling`).

For 9/B1–9/B24 (coupling degree 1) the conditions name 21 link pairs, and they fit
exactly one catalog truss each, 24 different ones (tests/test_literature.py). For the four
coupling-2 trusses Appendix A prints one condition (the second follows by symmetry), which
fits several catalog trusses; those are named by invariants instead.

Each expression below is as printed (the vector identity s_{u,v} = det(Ω) s_ref holds
for every point configuration, which checks the transcription: tests/test_literature.py).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from itertools import combinations

import networkx as nx
from networkx.algorithms import isomorphism

from baranov.closure import DistanceCondition, parse_matrix_expression
from baranov.topology import KinematicChain, joint_graph, natural_sort_key


@dataclass(frozen=True)
class AppendixCondition:
    """One line of Appendix A: ``pair = f(arguments) = det(omega) reference``.

    Attributes
    ----------
    pair
        the distance the line computes, e.g. ``"s5,12"``.
    omega
        ``"Ω1"``/``"Ω2"`` where the line defines a computed distance by that Ω;
        None for the final closure condition (``pair`` is then a link dimension).
    arguments
        the distances it is a function of, as printed (``"s1,7, s3,8"``).
    reference
        the reference distance (a parameter), e.g. ``"s1,7"``.
    expression
        the matrix expression Ω, in the thesis's notation.
    """

    pair: str
    omega: str | None
    arguments: str
    reference: str
    expression: str


APPENDIX_A_CONDITIONS: dict[str, tuple[AppendixCondition, ...]] = {
    "9/B1": (
        AppendixCondition("s5,12", None, "s1,7, s3,8, s4,10", "s1,7",
                          "Z4,1,5Z1,3,4Z1,2,3Z1,7,2 + (I − Z10,11,12 Z10,4,11) Ω2"),
        AppendixCondition("s4,10", "Ω2", "s1,7, s3,8", "s1,7",
                          "−Z1,3,4Z1,2,3Z1,7,2 + Z1,2,3Z1,7,2 + (I − Z8,9,10Z8,3,9) Ω1"),
        AppendixCondition("s3,8", "Ω1", "s1,7", "s1,7",
                          "−Z1,2,3Z1,7,2 + I − Z7,6,8Z7,1,6"),
    ),
    "9/B2": (
        AppendixCondition("s10,12", None, "s1,7, s3,8, s4,11", "s1,7",
                          "−Z1,2,3Z1,7,2 − (I − Z8,9,10Z8,3,9)Ω1 + Z1,3,4Z1,2,3Z1,7,2 + Z4,5,12Z4,11,5Ω2"),
        AppendixCondition("s4,11", "Ω2", "s1,7, s3,8", "s1,7",
                          "−Z1,3,4Z1,2,3Z1,7,2 + Z1,2,3Z1,7,2 + (I − Z8,9,11Z8,3,9) Ω1"),
        AppendixCondition("s3,8", "Ω1", "s1,7", "s1,7",
                          "−Z1,2,3Z1,7,2 + I − Z7,6,8Z7,1,6"),
    ),
    "9/B3": (
        AppendixCondition("s8,9", None, "s1,12, s3,10, s2,6", "s1,12",
                          "−Z1,4,3Z1,12,4 − (I − Z10,7,6Z10,3,7)Ω1 + Z6,5,8Z6,2,5Ω2 + I − Z12,11,9Z12,1,11"),
        AppendixCondition("s2,6", "Ω2", "s1,12, s3,10", "s1,12",
                          "−Z1,4,2Z1,12,4 + Z1,4,3Z1,12,4 + (I − Z10,7,6Z10,3,7)Ω1"),
        AppendixCondition("s3,10", "Ω1", "s1,12", "s1,12",
                          "−Z1,4,3Z1,12,4 + I − Z12,11,10Z12,1,11"),
    ),
    "9/B4": (
        AppendixCondition("s6,7", None, "s1,12, s3,10, s2,9", "s1,12",
                          "−Z1,4,2Z1,12,4 − Z2,5,6Z2,9,5Ω2 + Z1,4,3Z1,12,4 + Z3,8,7Z3,10,8Ω1"),
        AppendixCondition("s2,9", "Ω2", "s1,12", "s1,12",
                          "−Z1,4,2Z1,12,4 + I − Z12,11,9Z12,1,11"),
        AppendixCondition("s3,10", "Ω1", "s1,12", "s1,12",
                          "−Z1,4,3Z1,12,4 + I − Z12,11,10Z12,1,11"),
    ),
    "9/B5": (
        AppendixCondition("s6,7", None, "s1,12, s3,10, s2,9", "s1,12",
                          "−Z1,4,2Z1,12,4 − Z2,5,6Z2,9,5Ω2 + Z1,4,3Z1,12,4 + (I − Z10,8,7Z10,3,8)Ω1"),
        AppendixCondition("s2,9", "Ω2", "s1,12", "s1,12",
                          "−Z1,4,2Z1,12,4 + I − Z12,11,9Z12,1,11"),
        AppendixCondition("s3,10", "Ω1", "s1,12", "s1,12",
                          "−Z1,4,3Z1,12,4 + I − Z12,11,10Z12,1,11"),
    ),
    "9/B6": (
        AppendixCondition("s4,12", None, "s7,9, s2,6, s3,10", "s7,9",
                          "(−Z2,3,4 + I)Z2,1,3Z2,6,1Ω1 + (I − Z10,11,12Z10,3,11)Ω2"),
        AppendixCondition("s3,10", "Ω2", "s7,9, s2,6", "s7,9",
                          "Z9,5,2Z9,7,5 − Z2,1,3Z2,6,1Ω1 − Z9,8,10Z9,7,8"),
        AppendixCondition("s2,6", "Ω1", "s7,9", "s7,9",
                          "−I + Z9,5,2Z9,7,5 + Z7,8,6Z7,9,8"),
    ),
    "9/B7": (
        AppendixCondition("s4,12", None, "s1,5, s6,9, s3,10", "s1,5",
                          "−Z1,3,4Z1,2,3Z1,5,2 + Z1,2,3Z1,5,2 + (I − Z10,11,12Z10,3,11)Ω2"),
        AppendixCondition("s3,10", "Ω2", "s1,5, s6,9", "s1,5",
                          "−Z1,2,3Z1,5,2 + Z1,7,6Z1,5,7 + (I − Z9,8,10Z9,6,8)Ω1"),
        AppendixCondition("s6,9", "Ω1", "s1,5", "s1,5",
                          "−Z1,7,6Z1,5,7 + I − Z5,2,9Z5,1,2"),
    ),
    "9/B8": (
        AppendixCondition("s4,12", None, "s1,7, s5,8, s3,10", "s1,7",
                          "−Z1,3,4Z1,2,3Z1,7,2 + Z1,2,3Z1,7,2 + (I − Z10,11,12Z10,3,11)Ω2"),
        AppendixCondition("s3,10", "Ω2", "s1,7, s5,8", "s1,7",
                          "−Z1,2,3Z1,7,2 + I − Z7,2,5Z7,1,2 + (I − Z8,9,10Z8,5,9)Ω1"),
        AppendixCondition("s5,8", "Ω1", "s1,7", "s1,7",
                          "Z7,2,5Z7,1,2 − Z7,6,8Z7,1,6"),
    ),
    "9/B9": (
        AppendixCondition("s4,12", None, "s1,7, s6,8, s3,10", "s1,7",
                          "−Z1,3,4Z1,2,3Z1,7,2 + Z1,2,3Z1,7,2 + (I − Z10,11,12Z10,3,11)Ω2"),
        AppendixCondition("s3,10", "Ω2", "s1,7, s6,8", "s1,7",
                          "−Z1,2,3Z1,7,2 + I − Z7,5,6Z7,1,5 + (I − Z8,9,10Z8,6,9)Ω1"),
        AppendixCondition("s6,8", "Ω1", "s1,7", "s1,7",
                          "−I + Z7,5,6Z7,1,5 + Z1,5,8Z1,7,5"),
    ),
    "9/B10": (
        AppendixCondition("s11,12", None, "s1,3, s5,7, s8,10", "s1,3",
                          "−Z1,7,10Z1,4,7Z1,3,4 + Z10,9,11Z10,8,9Ω2 + Z1,2,12Z1,3,2"),
        AppendixCondition("s8,10", "Ω2", "s1,3, s5,7", "s1,3",
                          "−Z1,4,7Z1,3,4 + Z7,6,8Z7,5,6Ω1 + Z1,7,10Z1,4,7Z1,3,4"),
        AppendixCondition("s5,7", "Ω1", "s1,3", "s1,3",
                          "Z1,4,7Z1,3,4 − I + Z3,4,5Z3,1,4"),
    ),
    "9/B11": (
        AppendixCondition("s11,12", None, "s1,3, s5,7, s8,10", "s1,3",
                          "−Z1,7,10Z1,4,7Z1,3,4 + (I − Z8,9,11Z8,10,9)Ω2 + Z1,2,12Z1,3,2"),
        AppendixCondition("s8,10", "Ω2", "s1,3, s5,7", "s1,3",
                          "−Z1,4,7Z1,3,4 + Z7,6,8Z7,5,6Ω1 + Z1,7,10Z1,4,7Z1,3,4"),
        AppendixCondition("s5,7", "Ω1", "s1,3", "s1,3",
                          "Z1,4,7Z1,3,4 − I + Z3,4,5Z3,1,4"),
    ),
    "9/B12": (
        AppendixCondition("s2,3", None, "s4,6, s8,10, s1,11", "s4,6",
                          "−Z4,7,1Z4,6,7 − Z1,12,2Z1,11,12Ω2 + I − Z6,5,3Z6,4,5"),
        AppendixCondition("s1,11", "Ω2", "s4,6, s8,10", "s4,6",
                          "−Z4,7,1Z4,6,7 + I − Z6,7,8Z6,4,7 + Z8,9,11Z8,10,9Ω1"),
        AppendixCondition("s8,10", "Ω1", "s4,6", "s4,6",
                          "−I + Z6,7,8Z6,4,7 + Z4,7,10Z4,6,7"),
    ),
    "9/B13": (
        AppendixCondition("s8,11", None, "s2,4, s6,7, s10,12", "s2,4",
                          "Z4,3,6Z4,2,3 − Z6,9,8Z6,7,9Ω1 − Z4,1,10Z4,2,1 + (I − Z12,5,11Z12,10,5)Ω2"),
        AppendixCondition("s10,12", "Ω2", "s2,4, s6,7", "s2,4",
                          "−I + Z4,1,10Z4,2,1 + Z2,1,12Z2,4,1"),
        AppendixCondition("s6,7", "Ω1", "s2,4", "s2,4",
                          "Z4,3,6Z4,2,3 − Z4,1,7Z4,2,1"),
    ),
    "9/B14": (
        AppendixCondition("s2,3", None, "s4,6, s10,11, s1,12", "s4,6",
                          "−Z4,7,1Z4,6,7 − (I − Z12,9,2Z12,1,9)Ω2 + I − Z6,5,3Z6,4,5"),
        AppendixCondition("s1,12", "Ω2", "s4,6, s10,11", "s4,6",
                          "−Z4,7,1Z4,6,7 + Z4,7,10Z4,6,7 + (I − Z11,8,12Z11,10,8)Ω1"),
        AppendixCondition("s10,11", "Ω1", "s4,6", "s4,6",
                          "−Z4,7,10Z4,6,7 + I − Z6,7,11Z6,4,7"),
    ),
    "9/B15": (
        AppendixCondition("s3,6", None, "s10,11, s1,12, s2,4", "s10,11",
                          "−Z10,7,1Z10,11,7 − (I − Z12,9,2Z12,1,9)Ω1 − Z2,5,3Z2,4,5Ω2 + I − Z11,7,6Z11,10,7"),
        AppendixCondition("s2,4", "Ω2", "s10,11, s1,12", "s10,11",
                          "−Z10,7,1Z10,11,7 − (I − Z12,9,2Z12,1,9)Ω1 + Z10,7,4Z10,11,7"),
        AppendixCondition("s1,12", "Ω1", "s10,11", "s10,11",
                          "−Z10,7,1Z10,11,7 + I − Z11,8,12Z11,10,8"),
    ),
    "9/B16": (
        AppendixCondition("s2,3", None, "s7,8, s4,6, s1,11", "s7,8",
                          "−Z7,10,1Z7,8,10 − Z1,12,2Z1,11,12Ω2 + Z7,10,4Z7,8,10 + (I − Z6,5,3Z6,4,5)Ω1"),
        AppendixCondition("s1,11", "Ω2", "s7,8, s4,6", "s7,8",
                          "−Z7,10,1Z7,8,10 + I − Z8,10,11Z8,7,10"),
        AppendixCondition("s4,6", "Ω1", "s7,8", "s7,8",
                          "−Z7,10,4Z7,8,10 + I − Z8,9,6Z8,7,9"),
    ),
    "9/B17": (
        AppendixCondition("s3,6", None, "s1,2, s10,12, s7,8", "s1,2",
                          "−I + Z2,4,3Z2,1,4 + Z1,4,7Z1,2,4 + (I − Z8,9,6Z8,7,9)Ω2"),
        AppendixCondition("s7,8", "Ω2", "s1,2, s10,12", "s1,2",
                          "−Z1,4,7Z1,2,4 + Z1,4,10Z1,2,4 + Z10,11,8Z10,12,11Ω1"),
        AppendixCondition("s10,12", "Ω1", "s1,2", "s1,2",
                          "−Z1,4,10Z1,2,4 + I − Z2,5,12Z2,1,5"),
    ),
    "9/B18": (
        AppendixCondition("s11,12", None, "s1,4, s6,7, s5,9", "s1,4",
                          "−Z1,3,5Z1,4,3 − (I − Z9,8,11Z9,5,8)Ω2 + I − Z4,3,6Z4,1,3 + (I − Z7,10,12Z7,6,10)Ω1"),
        AppendixCondition("s5,9", "Ω2", "s1,4, s6,7", "s1,4",
                          "−Z1,3,5Z1,4,3 + I − Z4,3,6Z4,1,3 + Z6,10,9Z6,7,10Ω1"),
        AppendixCondition("s6,7", "Ω1", "s1,4", "s1,4",
                          "Z4,3,6Z4,1,3 − Z4,2,7Z4,1,2"),
    ),
    "9/B19": (
        AppendixCondition("s11,12", None, "s1,4, s6,7, s5,9", "s1,4",
                          "−Z1,3,5Z1,4,3 − Z5,8,11Z5,9,8Ω2 + I − Z4,3,6Z4,1,3 + (I − Z7,10,12Z7,6,10)Ω1"),
        AppendixCondition("s5,9", "Ω2", "s1,4, s6,7", "s1,4",
                          "−Z1,3,5Z1,4,3 + I − Z4,3,6Z4,1,3 + Z6,10,9Z6,7,10Ω1"),
        AppendixCondition("s6,7", "Ω1", "s1,4", "s1,4",
                          "Z4,3,6Z4,1,3 − Z4,2,7Z4,1,2"),
    ),
    "9/B20": (
        AppendixCondition("s5,6", None, "s1,4, s8,11, s9,10", "s1,4",
                          "−I + Z4,3,5Z4,1,3 + Z1,3,8Z1,4,3 + Z8,12,9Z8,11,12Ω1 + (I − Z10,7,6Z10,9,7)Ω2"),
        AppendixCondition("s9,10", "Ω2", "s1,4, s8,11", "s1,4",
                          "(−Z8,12,9Z8,11,12 + I − Z11,12,10Z11,8,12)Ω1"),
        AppendixCondition("s8,11", "Ω1", "s1,4", "s1,4",
                          "−Z1,3,8Z1,4,3 + I − Z4,2,11Z4,1,2"),
    ),
    "9/B21": (
        AppendixCondition("s5,8", None, "s1,4, s6,11, s7,12", "s1,4",
                          "−Z1,3,5Z1,4,3 + I − Z4,3,6Z4,1,3 + Z6,10,7Z6,11,10Ω1 + (I − Z12,9,8Z12,7,9)Ω2"),
        AppendixCondition("s7,12", "Ω2", "s1,4, s6,11", "s1,4",
                          "(−Z6,10,7Z6,11,10 + I − Z11,10,12Z11,6,10)Ω1"),
        AppendixCondition("s6,11", "Ω1", "s1,4", "s1,4",
                          "Z4,3,6Z4,1,3 − Z4,2,11Z4,1,2"),
    ),
    "9/B22": (
        AppendixCondition("s7,10", None, "s1,4, s8,11, s5,9", "s1,4",
                          "−I + Z4,3,5Z4,1,3 − Z5,6,7Z5,9,6Ω2 + Z1,3,8Z1,4,3 + (I − Z11,12,10Z11,8,12)Ω1"),
        AppendixCondition("s5,9", "Ω2", "s1,4, s8,11", "s1,4",
                          "−I + Z4,3,5Z4,1,3 + Z1,3,8Z1,4,3 + Z8,12,9Z8,11,12Ω1"),
        AppendixCondition("s8,11", "Ω1", "s1,4", "s1,4",
                          "−Z1,3,8Z1,4,3 + I − Z4,2,11Z4,1,2"),
    ),
    "9/B23": (
        AppendixCondition("s10,11", None, "s1,4, s6,8, s5,7", "s1,4",
                          "−Z6,12,10Z6,8,12Ω1 − Z1,3,6Z1,4,3 + Z1,2,5Z1,4,2 + Z5,9,11Z5,7,9Ω2"),
        AppendixCondition("s5,7", "Ω2", "s1,4, s6,8", "s1,4",
                          "−Z1,2,5Z1,4,2 + I − Z4,3,7Z4,1,3"),
        AppendixCondition("s6,8", "Ω1", "s1,4", "s1,4",
                          "−Z1,3,6Z1,4,3 + I − Z4,2,8Z4,1,2"),
    ),
    "9/B24": (
        AppendixCondition("s7,11", None, "s1,4, s6,8, s5,10", "s1,4",
                          "−I + Z4,3,7Z4,1,3 + Z1,2,5Z1,4,2 + (I − Z10,9,11Z10,5,9)Ω2"),
        AppendixCondition("s5,10", "Ω2", "s1,4, s6,8", "s1,4",
                          "−Z1,2,5Z1,4,2 + Z1,3,6Z1,4,3 + Z6,12,10Z6,8,12Ω1"),
        AppendixCondition("s6,8", "Ω1", "s1,4", "s1,4",
                          "−Z1,3,6Z1,4,3 + I − Z4,2,8Z4,1,2"),
    ),
    "9/B25": (
        AppendixCondition("s9,10", None, "s1,6, s2,7", "s1,6",
                          "−I + Z6,5,9 Z6,1,5 + Z1,3,2Z1,6,3 + (I − Z7,8,10 Z7,2,8) Z2,4,7 (−Z1,3,2Z1,6,3 "
                          "+ Z1,3,4Z1,6,3)"),
    ),
    "9/B26": (
        AppendixCondition("s5,10", None, "s3,11, s3,12, s1,4", "s3,11",
                          "−Z11,12,10Z11,3,12 + I − Z3,6,1Z3,11,6 + Z1,2,5Z1,4,2Ω1"),
        AppendixCondition("s1,4", "Ω1", "s3,11, s3,12", "s3,11",
                          "Z3,6,1Z3,11,6 − Z3,7,4Z3,12,7Z3,11,12"),
    ),
    "9/B27": (
        AppendixCondition("s9,11", None, "s5,12, s7,12, s3,6", "s7,12",
                          "−Z7,10,6Z7,12,10 + Z6,8,9Z6,3,8Ω1 + I − Z12,10,11Z12,7,10"),
        AppendixCondition("s3,6", "Ω1", "s5,12, s7,12", "s7,12",
                          "−Z5,4,3Z5,12,4 (−Z7,12,5 + I) − Z7,12,5 + Z7,10,6Z7,12,10"),
    ),
    "9/B28": (
        AppendixCondition("s6,10", None, "s1,4, s2,4, s8,11", "s1,4",
                          "−I + Z4,3,6Z4,1,3 + Z1,3,8Z1,4,3 + (I − Z11,12,10Z11,8,12)Ω1"),
        AppendixCondition("s8,11", "Ω1", "s1,4, s2,4", "s1,4",
                          "−Z1,3,8Z1,4,3 + I − Z4,1,2 + Z2,5,11Z2,4,5Z4,1,2"),
    ),
}


def _pair(text: str) -> tuple[str, str]:
    """``"s5,12"`` → ``("P5", "P12")``."""
    u, v = text.strip().lstrip("s").split(",")
    return f"P{u}", f"P{v}"


def appendix_a_conditions(name: str) -> tuple[DistanceCondition, ...]:
    """The Appendix A conditions of ``name`` as :class:`~baranov.closure.DistanceCondition`
    objects with joints ``P1``…``P12``, computed distances first (Ω1, Ω2, then the final
    condition), each Ω_n substituted where it is used.

    >>> [(c.pair, c.reference) for c in appendix_a_conditions("9/B1")]
    [(('P3', 'P8'), ('P1', 'P7')), (('P4', 'P10'), ('P1', 'P7')), (('P5', 'P12'), ('P1', 'P7'))]
    """
    if name not in APPENDIX_A_CONDITIONS:
        raise ValueError(f"truss {name!r}: Appendix A lists 9/B1 to 9/B28")
    lines = sorted(APPENDIX_A_CONDITIONS[name], key=lambda line: (line.omega is None, line.omega or ""))
    named, conditions = {}, []
    for line in lines:
        omega = parse_matrix_expression(line.expression, named)
        if line.omega:
            named[line.omega] = omega
        conditions.append(DistanceCondition(_pair(line.pair), omega, _pair(line.reference)))
    return tuple(conditions)


def link_pairs_required(name: str) -> tuple[frozenset[frozenset[str]], frozenset[frozenset[str]]]:
    """(pairs that must be on a common link, pairs that must not) by the Appendix A
    conditions of ``name``: the three distances of every Z_{i,j,k} and the final
    condition's distance, minus the parameters and computed distances; and those.

    >>> on_link, off_link = link_pairs_required("9/B1")
    >>> len(on_link), sorted(sorted(p) for p in off_link)
    (21, [['P1', 'P7'], ['P10', 'P4'], ['P3', 'P8']])
    """
    on_link, off_link = set(), set()
    for line in APPENDIX_A_CONDITIONS[name]:
        off_link.add(frozenset(_pair(line.reference)))
        off_link |= {frozenset(_pair(argument)) for argument in line.arguments.split(", ")}
        (off_link if line.omega else on_link).add(frozenset(_pair(line.pair)))
        for triple in re.findall(r"Z(\d+),(\d+),(\d+)", line.expression):
            on_link |= {frozenset((f"P{a}", f"P{b}")) for a, b in combinations(triple, 2)}
    return frozenset(on_link - off_link), frozenset(off_link)


def appendix_a_labelling(chain: KinematicChain, name: str) -> dict[str, str] | None:
    """A labelling ``{thesis joint: joint of chain}`` under which every pair that the
    Appendix A conditions of ``name`` treat as known lies on a link of ``chain`` and no
    parameter or computed distance does; None if there is none.

    A subgraph monomorphism search (networkx VF2) of the required pairs into the joint
    graph of ``chain``; 12 joints, milliseconds.

    >>> from baranov.enumerate import baranov_trusses
    >>> [n for n, truss in enumerate(baranov_trusses(9)) if appendix_a_labelling(truss, "9/B10")]
    [18]
    """
    on_link, off_link = link_pairs_required(name)
    # networkx's VF2 iterates over sets of nodes: with integer nodes (whose hashes are
    # their values) the first labelling found does not depend on string hashing.
    thesis_joints = sorted({joint for pair in on_link for joint in pair}, key=natural_sort_key)
    required = nx.Graph()
    required.add_nodes_from(range(len(thesis_joints)))
    required.add_edges_from(sorted(tuple(sorted(thesis_joints.index(j) for j in pair)) for pair in on_link))
    graph = nx.convert_node_labels_to_integers(joint_graph(chain), label_attribute="name")
    for mapping in isomorphism.GraphMatcher(graph, required).subgraph_monomorphisms_iter():
        labelling = {thesis_joints[thesis]: graph.nodes[joint]["name"] for joint, thesis in mapping.items()}
        position = {graph.nodes[n]["name"]: n for n in graph}
        if all(not graph.has_edge(*(position[labelling[j]] for j in pair)) for pair in off_link
               if all(j in labelling for j in pair)):
            return dict(sorted(labelling.items(), key=lambda item: natural_sort_key(item[0])))
    return None


def names_by_closure_conditions(chain: KinematicChain) -> list[str]:
    """The nine-link thesis names whose Appendix A conditions fit ``chain``
    (:func:`appendix_a_labelling`).

    >>> from baranov.enumerate import baranov_trusses
    >>> names_by_closure_conditions(baranov_trusses(9)[0])
    ['9/B1', '9/B25']
    """
    return [name for name in APPENDIX_A_CONDITIONS if appendix_a_labelling(chain, name) is not None]
