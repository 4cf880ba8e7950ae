"""Topology of planar kinematic chains: links, joints, link and joint graphs, rigidity,
and symmetry (automorphisms via nauty).

>>> from baranov.topology import chain_from_link_graph, automorphism_group, is_baranov_truss
>>> pentad = chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)])
>>> is_baranov_truss(pentad), automorphism_group(pentad).order
(True, 12)
"""

from .automorphisms import (
    Automorphism,
    AutomorphismGroup,
    are_isomorphic,
    automorphism_group,
    canonical_labelling,
    canonical_link_graph6,
    certificate,
    list_automorphisms,
)
from .chain import (
    Joint,
    JointKind,
    KinematicChain,
    chain_from_link_graph,
    chain_from_links,
    distance_name,
    natural_sort_key,
    thesis_subscript,
)
from .diagram import diagram_layout, diagram_svg
from .errors import TopologyError
from .fusion import fuse_links
from .graphs import degree_sequence, is_planar, joint_graph, joints_of_links, link_graph
from .rigidity import (
    adjacency_masks,
    is_baranov_link_graph,
    is_baranov_truss,
    mobility,
    require_baranov_truss,
    require_not_over_constrained,
    require_one_dof_chain,
    require_rigid_chain,
    smallest_overconstrained_subchain,
    smallest_rigid_subchain,
)

__all__ = [
    "Automorphism",
    "AutomorphismGroup",
    "Joint",
    "JointKind",
    "KinematicChain",
    "TopologyError",
    "adjacency_masks",
    "are_isomorphic",
    "automorphism_group",
    "list_automorphisms",
    "canonical_labelling",
    "canonical_link_graph6",
    "certificate",
    "chain_from_link_graph",
    "chain_from_links",
    "degree_sequence",
    "diagram_layout",
    "diagram_svg",
    "fuse_links",
    "is_baranov_link_graph",
    "is_baranov_truss",
    "is_planar",
    "joint_graph",
    "joints_of_links",
    "link_graph",
    "mobility",
    "natural_sort_key",
    "require_baranov_truss",
    "require_not_over_constrained",
    "require_one_dof_chain",
    "require_rigid_chain",
    "smallest_overconstrained_subchain",
    "smallest_rigid_subchain",
    "distance_name",
    "thesis_subscript",
]
