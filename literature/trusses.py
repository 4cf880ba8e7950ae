"""Baranov trusses as the thesis describes them, with the thesis's joint numbering.

The thesis gives no drawings in its text form, but it names the joints of every rigid
link ("the triangles △P2P4P7, ...") and, through its bilateration matrices Z_{i,j,k}
(which need the known distances s_{i,k} and s_{j,k}) and its closure conditions, the
binary links. Each entry below records where its links were read. Every joint lies on
exactly two links, which checks the reading. Catalog entries are named after the entry
they are isomorphic to (:func:`thesis_name`).
"""

from __future__ import annotations

from dataclasses import dataclass

from baranov.topology import (
    KinematicChain,
    are_isomorphic,
    canonical_labelling,
    chain_from_links,
)


@dataclass(frozen=True)
class PublishedTruss:
    """A truss from the literature.

    Attributes
    ----------
    name
        Manolescu's name as used in the thesis, e.g. ``"7/B1"``.
    links
        joint names of every link (rigid links first, as the thesis lists them).
    source
        where in the thesis each link was read.
    """

    name: str
    links: tuple[tuple[str, ...], ...]
    source: str

    def chain(self) -> KinematicChain:
        """The truss as a chain with the thesis's joint names."""
        return chain_from_links(self.links)


THESIS_TRUSSES: tuple[PublishedTruss, ...] = (
    PublishedTruss(
        "3/B1",
        (("P1", "P2"), ("P2", "P3"), ("P3", "P1")),
        "thesis §3.1.1: the triad, three binary links",
    ),
    PublishedTruss(
        "5/B1",
        (("P1", "P2", "P3"), ("P4", "P5", "P6"), ("P1", "P4"), ("P3", "P6"), ("P2", "P5")),
        "thesis §2.7, eq. (2.24)-(2.25): ternary links △P1P3P2, △P4P5P6; binary links P1P4 "
        "(Z6,1,4), P3P6 (Z1,6,3), P2P5 (closure s2,5)",
    ),
    PublishedTruss(
        "7/B1",
        (("P2", "P4", "P7"), ("P3", "P5", "P4"), ("P3", "P1", "P6"), ("P5", "P8", "P9"),
         ("P1", "P2"), ("P7", "P9"), ("P6", "P8")),
        "thesis §3.3.1: ternary links △P2P4P7, △P3P5P4, △P3P1P6, △P5P8P9; binary links "
        "P1P2 (Z3,2,1, eq. 3.9), P7P9 (Z5,7,9, eq. 3.10), P6P8 (closure s6,8)",
    ),
    PublishedTruss(
        "7/B2",
        (("P2", "P4", "P5"), ("P1", "P2", "P3"), ("P4", "P6", "P7"), ("P8", "P7", "P9"),
         ("P5", "P8"), ("P3", "P9"), ("P1", "P6")),
        "thesis §3.3.2: ternary links △P2P4P5, △P1P2P3, △P4P6P7, △P8P7P9; binary links "
        "P5P8 (Z4,8,5, eq. 3.22), P3P9 (Z2,9,3, eq. 3.25), P1P6 (closure s1,6)",
    ),
    PublishedTruss(
        "7/B3",
        (("P1", "P2", "P6", "P7"), ("P3", "P5", "P4"), ("P8", "P5", "P9"),
         ("P2", "P4"), ("P1", "P3"), ("P6", "P8"), ("P7", "P9")),
        "thesis §3.3.3: quaternary link △P1P6P7 ∪ △P1P2P6, ternary links △P3P5P4, △P8P5P9; "
        "binary links P2P4 (Z1,4,2, eq. 3.35), P1P3 (Z4,1,3, eq. 3.37), P6P8 (Z5,6,8, "
        "eq. 3.38), P7P9 (closure s7,9)",
    ),
    PublishedTruss(
        "9/B28",
        (("P1", "P8", "P3"), ("P3", "P6", "P4"), ("P4", "P7", "P5"), ("P2", "P5", "P11"),
         ("P8", "P12", "P9"), ("P10", "P12", "P11"), ("P1", "P2"), ("P6", "P10"), ("P7", "P9")),
        "thesis §3.4.1: ternary links △P1P8P3, △P3P6P4, △P4P7P5, △P2P5P11, △P8P12P9, "
        "△P10P12P11; binary links P1P2 (Z4,1,2 with parameters s1,4, s2,4, Appendix A), "
        "P6P10 and P7P9 (closures s6,10, s7,9)",
    ),
)


#: Assembly modes of the nine-link trusses, thesis Appendix A (Tables A.3-A.8).
APPENDIX_A_ASSEMBLY_MODES = {
    "9/B1": 54, "9/B2": 54, "9/B3": 48, "9/B4": 42, "9/B5": 48, "9/B6": 48, "9/B7": 48, "9/B8": 48,
    "9/B9": 42, "9/B10": 30, "9/B11": 36, "9/B12": 40, "9/B13": 40, "9/B14": 42, "9/B15": 52, "9/B16": 44,
    "9/B17": 44, "9/B18": 38, "9/B19": 46, "9/B20": 46, "9/B21": 40, "9/B22": 50, "9/B23": 46, "9/B24": 50,
    "9/B25": 52, "9/B26": 56, "9/B27": 50, "9/B28": 58,
}


#: Nine-link trusses with coupling degree 2 (thesis §3.4.2) and without a planar link
#: graph (thesis §3.4.1: "9/B28 ... the other two are 9/B23 and 9/B24").
NINE_LINK_COUPLING_TWO = ("9/B25", "9/B26", "9/B27", "9/B28")
NINE_LINK_NON_PLANAR = ("9/B23", "9/B24", "9/B28")


def nine_link_signature(name: str) -> tuple[int, int, bool]:
    """(assembly modes, coupling degree, planar) of the thesis truss ``name`` (9/B1–9/B28).

    >>> nine_link_signature("9/B28")
    (58, 2, False)
    """
    return (APPENDIX_A_ASSEMBLY_MODES[name], 2 if name in NINE_LINK_COUPLING_TWO else 1,
            name not in NINE_LINK_NON_PLANAR)


def name_by_invariants(assembly_modes: int, coupling: int, planar: bool) -> str | None:
    """The nine-link thesis name whose (assembly modes, coupling degree, planarity) is
    ``(assembly_modes, coupling, planar)``, when exactly one of the 28 has it; else None
    (11 of the 28 signatures are unique; the catalog's 28 signatures equal the thesis's as
    a multiset, which a test checks, so a unique one names exactly one catalog truss).

    >>> name_by_invariants(30, 1, True), name_by_invariants(54, 1, True)
    ('9/B10', None)
    """
    matches = [name for name in APPENDIX_A_ASSEMBLY_MODES
               if nine_link_signature(name) == (assembly_modes, coupling, planar)]
    return matches[0] if len(matches) == 1 else None


def thesis_truss(name: str) -> PublishedTruss:
    """The published truss called ``name`` (e.g. ``"7/B2"``); ValueError if unknown.

    >>> thesis_truss("7/B3").chain().link_degrees
    (4, 3, 3, 2, 2, 2, 2)
    """
    for truss in THESIS_TRUSSES:
        if truss.name == name:
            return truss
    known = ", ".join(t.name for t in THESIS_TRUSSES)
    raise ValueError(f"truss {name!r}: not among the recorded thesis trusses ({known})")


def thesis_name(chain: KinematicChain) -> PublishedTruss | None:
    """The recorded thesis truss isomorphic to ``chain``, if any.

    >>> from baranov.enumerate import baranov_trusses
    >>> [thesis_name(t).name for t in baranov_trusses(7)]
    ['7/B3', '7/B1', '7/B2']
    """
    for truss in THESIS_TRUSSES:
        if are_isomorphic(chain, truss.chain()):
            return truss
    return None


def thesis_joint_names(chain: KinematicChain, published: PublishedTruss) -> dict[str, str]:
    """One isomorphism from ``chain`` onto ``published``, as joint names:
    ``{joint of chain: thesis joint}``. Where the truss has symmetries, any of the
    |Aut| equivalent matchings could be returned; this one pairs the two canonical forms.

    >>> from baranov.enumerate import baranov_trusses
    >>> truss = baranov_trusses(5)[0]
    >>> names = thesis_joint_names(truss, thesis_truss("5/B1"))
    >>> sorted(names.values())
    ['P1', 'P2', 'P3', 'P4', 'P5', 'P6']
    """
    target = published.chain()
    if not are_isomorphic(chain, target):
        raise ValueError(f"the chain is not isomorphic to {published.name}")
    link_map = dict(zip(canonical_labelling(chain), canonical_labelling(target), strict=True))
    by_links = {joint.links: joint.name for joint in target.joints}
    return {
        joint.name: by_links[tuple(sorted(link_map[link] for link in joint.links))]
        for joint in chain.joints
    }
