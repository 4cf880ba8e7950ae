"""The fully-parallel planar robots and their ten families (thesis §5.2, Table 5.3).

With its actuators locked, a robot is a 5-link Assur chain: the base and the platform
(ternary links) and three binary links, its legs, each ending in its two passive joints;
a passive prismatic joint is a slider joint of that chain (thesis ch. 4). The robot's
*family* is the isomorphism class of that slider chain: the orbit of its slider set under
the automorphisms of the pentad (order 12: the legs permuted, base and platform
swapped). Robots are multisets of three legs with at most one PP leg; every count here
is computed from that enumeration, the literature only names the families and is
compared in the tests.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from itertools import combinations_with_replacement

from baranov.enumerate import baranov_trusses
from baranov.enumerate.sliders import canonical_slider_set
from baranov.literature.robots import THESIS_ROBOT_FAMILIES
from baranov.topology import KinematicChain

from .legs import LEGS, Leg


@dataclass(frozen=True)
class RobotFamily:
    """One family: its ``name`` (thesis Table 5.3, I–X), the pentad joints that are
    sliders in its locked structure (``sliders``, the orbit's smallest set), its leg
    architectures (``"PR-RP-RR"``: passive joints per leg, sorted), how many ``robots``
    it has and its generic number of ``assembly_modes``."""

    name: str
    sliders: tuple[str, ...]
    architectures: tuple[str, ...]
    robots: int
    assembly_modes: int | None


@cache
def pentad() -> tuple[KinematicChain, tuple[tuple[str, str], ...], int, int]:
    """The 5-link truss (5/N1 of the catalog), the joints ``(base end, platform end)`` of
    each binary link (a leg), and the base and platform links (its two ternary links)."""
    chain = baranov_trusses(5)[0]
    base, platform = (link for link, degree in enumerate(chain.link_degrees) if degree == 3)
    legs = []
    for link, degree in enumerate(chain.link_degrees):
        if degree == 2:
            ends = {next(other for other in joint.links if other != link): joint.name
                    for joint in chain.joints if link in joint.links}
            legs.append((ends[base], ends[platform]))
    return chain, tuple(legs), base, platform


def locked_sliders(legs: Sequence[Leg]) -> tuple[str, ...]:
    """The pentad joints that are sliders once the actuators of ``legs`` are locked: the
    base end of leg k if its first passive joint is prismatic, its platform end if its
    second is."""
    _, ends, _, _ = pentad()
    return tuple(sorted((joint for leg, pair in zip(legs, ends, strict=True)
                         for letter, joint in zip(leg.passive, pair, strict=True) if letter == "P"),
                        key=lambda name: int(name[1:])))


def canonical_sliders(sliders: Sequence[str]) -> tuple[str, ...]:
    """The representative of the orbit of ``sliders`` under the pentad's automorphisms,
    as :func:`baranov.enumerate.sliders.slider_chains` lists it. O(|G|) = 12 images."""
    return canonical_slider_set(pentad()[0], sliders)


def all_robots() -> list[tuple[Leg, Leg, Leg]]:
    """Every fully-parallel planar robot, as its legs sorted: three of the 21 legs with
    repetition, at most one PP leg (1653, thesis §5.2)."""
    return [legs for legs in combinations_with_replacement(LEGS, 3)
            if sum(leg.passive == "PP" for leg in legs) <= 1]


def architectures(legs: Sequence[Leg]) -> str:
    """The robot's leg architectures, sorted, e.g. ``"PR-RP-RR"``."""
    return "-".join(sorted(leg.passive for leg in legs))


@cache
def robot_families(assembly_modes: bool = True) -> tuple[RobotFamily, ...]:
    """The families of :func:`all_robots`, in the thesis's order (I–X), each with its
    robot count, and, if ``assembly_modes``, its generic number of assembly modes (the
    slider chain's characteristic degree, :func:`~baranov.solvers.mode_counts.slider_chain_degree`).
    Seconds (the ten characteristic degrees); the enumeration alone is instant.

    >>> [family.robots for family in robot_families(assembly_modes=False)]
    [56, 252, 216, 252, 252, 63, 216, 112, 108, 126]
    """
    groups: dict[tuple[str, ...], list[tuple[Leg, Leg, Leg]]] = defaultdict(list)
    for legs in all_robots():
        groups[canonical_sliders(locked_sliders(legs))].append(legs)
    names = {tuple(sorted("-".join(sorted(a.split("-"))) for a in printed)): name
             for name, (printed, _, _) in THESIS_ROBOT_FAMILIES.items()}
    order = list(THESIS_ROBOT_FAMILIES)
    if assembly_modes:
        from baranov.solvers.mode_counts import slider_chain_degree  # the exact machinery: only when counting
    families = []
    for sliders, robots in groups.items():
        kinds = tuple(sorted({architectures(legs) for legs in robots}))
        modes = slider_chain_degree(pentad()[0], sliders)[0] if assembly_modes else None
        families.append(RobotFamily(names.get(kinds, "?"), sliders, kinds, len(robots), modes))
    return tuple(sorted(families, key=lambda f: order.index(f.name) if f.name in order else len(order)))


def robot_family(legs: Sequence[Leg]) -> RobotFamily:
    """The family of the robot with these legs (in any order).

    >>> from baranov.robots.legs import parse_robot
    >>> robot_family(parse_robot("RpR-RpR-RpR")).name, robot_family(parse_robot("RpP-RpR-RpP")).name
    ('I', 'IV')
    """
    sliders = canonical_sliders(locked_sliders(legs))
    return next(family for family in robot_families(assembly_modes=False) if family.sliders == sliders)
