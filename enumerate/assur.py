"""Assur groups derived from a Baranov truss.

Removing any one link from a Baranov truss leaves an Assur group (thesis ch. 3): the
removed link becomes the frame the group is attached to, and the joints it carried
become the group's external joints. Two removals give isomorphic groups exactly when
the removed links lie in the same orbit of the truss's automorphism group, so a truss
yields as many distinct Assur groups as it has link orbits (thesis Table 3.1 counts
1, 2, 10, 173 for 3, 5, 7, 9 links).
"""

from __future__ import annotations

from dataclasses import dataclass

from baranov.topology import AutomorphismGroup, KinematicChain, automorphism_group


@dataclass(frozen=True)
class AssurGroup:
    """An Assur group: ``truss`` with link ``removed_link`` taken away (it is the frame).

    Attributes
    ----------
    truss
        the Baranov truss the group comes from.
    removed_link
        index of the removed link.
    """

    truss: KinematicChain
    removed_link: int

    @property
    def links(self) -> tuple[int, ...]:
        """The links of the group (all links of the truss but the removed one)."""
        return tuple(link for link in range(self.truss.number_of_links) if link != self.removed_link)

    @property
    def external_joints(self) -> tuple[str, ...]:
        """Joints that attached the group to the removed link."""
        return tuple(j.name for j in self.truss.joints if self.removed_link in j.links)


def assur_groups(truss: KinematicChain, group: AutomorphismGroup | None = None) -> list[AssurGroup]:
    """One Assur group per link orbit of ``truss`` (the smallest link of each orbit removed).

    >>> from baranov.topology import chain_from_link_graph
    >>> pentad = chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)])
    >>> [(g.removed_link, g.external_joints) for g in assur_groups(pentad)]
    [(0, ('P1', 'P2', 'P3')), (2, ('P1', 'P4'))]
    """
    group = group or automorphism_group(truss)
    return [AssurGroup(truss, orbit[0]) for orbit in group.link_orbits]
