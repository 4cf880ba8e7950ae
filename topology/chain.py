"""Planar kinematic chains: links joined by joints.

A chain is stored as data only (frozen dataclasses); the algorithms that act on it
live in the sibling modules (:mod:`~baranov.topology.graphs`,
:mod:`~baranov.topology.rigidity`, :mod:`~baranov.topology.automorphisms`).

Conventions (thesis §2.2, §3.1):

* links are numbered ``0 .. L-1`` (the vertices of the *link graph*); the user's own
  labels, when the chain came from a labelled graph, are kept in
  :attr:`KinematicChain.link_labels` and are what error messages show;
* every joint connects exactly two distinct links (a revolute pair, or a slider
  joint, thesis ch. 4) and is named ``P1, P2, ...`` unless names are given;
* a chain is connected, every link carries at least two joints, and no two joints
  join the same pair of links (two such joints would weld the links together).
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Hashable, Iterable, Sequence
from dataclasses import dataclass, field
from enum import Enum

import networkx as nx

from .errors import TopologyError


class JointKind(str, Enum):
    """Kind of a joint. Slider joints are stored only (thesis ch. 4 uses them)."""

    REVOLUTE = "revolute"
    SLIDER = "slider"


@dataclass(frozen=True)
class Joint:
    """A joint (kinematic pair) between two links.

    Attributes
    ----------
    name
        user-facing name, e.g. ``"P3"``.
    links
        the two link indices it connects, in increasing order.
    kind
        revolute (default) or slider.
    """

    name: str
    links: tuple[int, int]
    kind: JointKind = JointKind.REVOLUTE


@dataclass(frozen=True)
class KinematicChain:
    """A planar kinematic chain: ``number_of_links`` links and the joints between them.

    Build one with :func:`chain_from_link_graph`; the constructor validates the
    structure (see the module docstring) and raises :class:`TopologyError`.

    >>> pentad = chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)])
    >>> pentad.number_of_links, len(pentad.joints)
    (5, 6)
    >>> pentad.joints[0]
    Joint(name='P1', links=(0, 2), kind=<JointKind.REVOLUTE: 'revolute'>)
    >>> pentad.link_degrees
    (3, 3, 2, 2, 2)
    """

    number_of_links: int
    joints: tuple[Joint, ...]
    link_labels: tuple[Hashable, ...] = field(default=())

    def __post_init__(self) -> None:
        if not self.link_labels:
            object.__setattr__(self, "link_labels", tuple(range(self.number_of_links)))
        _validate_structure(self)

    @property
    def number_of_joints(self) -> int:
        return len(self.joints)

    @property
    def link_degrees(self) -> tuple[int, ...]:
        """Number of joints on each link (2 = binary link, 3 = ternary, ...)."""
        degree = [0] * self.number_of_links
        for joint in self.joints:
            for link in joint.links:
                degree[link] += 1
        return tuple(degree)

    def link_name(self, link: int) -> str:
        """User-facing name of a link: its label if that is a name (a scene's link
        names), ``L<label>`` for a numeric label (``L0``, ``L1``, …)."""
        return _shown_label(self.link_labels[link])

    def joint(self, name: str) -> Joint:
        """The joint called ``name``; :class:`TopologyError` if there is none."""
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise TopologyError(f"joint {name}: no such joint in this chain")

    def with_joint_kinds(self, sliders: Iterable[str]) -> KinematicChain:
        """The same chain with the named joints turned into slider joints."""
        sliders = set(sliders)
        unknown = sliders - {joint.name for joint in self.joints}
        if unknown:
            raise TopologyError(f"joint {sorted(unknown)[0]}: no such joint in this chain")
        joints = tuple(
            Joint(j.name, j.links, JointKind.SLIDER if j.name in sliders else j.kind)
            for j in self.joints
        )
        return KinematicChain(self.number_of_links, joints, self.link_labels)


def _validate_structure(chain: KinematicChain) -> None:
    """Check the structural rules of the module docstring; raise TopologyError."""
    n = chain.number_of_links
    if n < 2:
        raise TopologyError(f"a kinematic chain needs at least two links, got {n}")
    names = Counter(joint.name for joint in chain.joints)
    repeated = sorted(name for name, count in names.items() if count > 1)
    if repeated:
        raise TopologyError(f"joint {repeated[0]}: name used more than once")
    pairs: dict[tuple[int, int], str] = {}
    for joint in chain.joints:
        a, b = joint.links
        for link in (a, b):
            if not (isinstance(link, int) and 0 <= link < n):
                raise TopologyError(f"joint {joint.name}: link index {link!r} out of range 0..{n - 1}")
        if a == b:
            raise TopologyError(f"joint {joint.name}: joins link {chain.link_name(a)} to itself")
        if a > b:
            raise TopologyError(f"joint {joint.name}: links must be given in increasing order")
        if (a, b) in pairs:
            raise TopologyError(
                f"links {chain.link_name(a)}, {chain.link_name(b)}: two joints between the same "
                f"pair of links ({pairs[(a, b)]} and {joint.name})"
            )
        pairs[(a, b)] = joint.name
    degrees = chain.link_degrees
    weak = [link for link in range(n) if degrees[link] < 2]
    if weak:
        listed = ", ".join(chain.link_name(link) for link in weak)
        raise TopologyError(f"link {listed}: fewer than two joints")
    graph = nx.Graph()
    graph.add_nodes_from(range(n))
    graph.add_edges_from(pairs)
    if not nx.is_connected(graph):
        parts = sorted(sorted(c) for c in nx.connected_components(graph))
        listed = ", ".join(chain.link_name(link) for link in parts[1])
        raise TopologyError(f"chain is disconnected: links {listed} are not joined to link {chain.link_name(0)}")


LinkGraphInput = nx.Graph | Sequence[tuple[Hashable, Hashable]] | str | bytes


def chain_from_link_graph(
    link_graph: LinkGraphInput,
    joint_names: Sequence[str] | None = None,
) -> KinematicChain:
    """Build a chain of revolute joints from its link graph.

    Parameters
    ----------
    link_graph
        a :class:`networkx.Graph` (links = vertices, joints = edges), an
        edge list of link pairs, or a graph6 string (with or without the
        ``>>graph6<<`` header).
    joint_names
        names of the joints in the order of the edges sorted by their
        (link, link) indices; default ``P1, P2, ...``.

    Links are renumbered ``0..L-1`` in the sorted order of the given labels (graph6:
    as encoded). Raises :class:`TopologyError` for repeated joints between two links,
    self-joints, links with fewer than two joints, a disconnected chain, or an
    unreadable graph6 string.

    >>> chain_from_link_graph("Bw").link_degrees  # graph6 of the triangle: the triad
    (2, 2, 2)
    >>> chain_from_link_graph([(0, 1), (1, 2)])
    Traceback (most recent call last):
    ...
    baranov.topology.errors.TopologyError: link L0, L2: fewer than two joints
    """
    if isinstance(link_graph, (str, bytes)):
        labels, pairs = _parse_graph6(link_graph)
    elif isinstance(link_graph, nx.Graph):
        if link_graph.is_directed() or link_graph.is_multigraph():
            multi = [(u, v) for u, v, k in link_graph.edges(keys=True) if k] if link_graph.is_multigraph() else []
            if multi:
                u, v = multi[0]
                raise TopologyError(f"links L{u}, L{v}: two joints between the same pair of links")
            link_graph = nx.Graph(link_graph)
        labels = _sorted_labels(link_graph.nodes)
        pairs = list(link_graph.edges)
    else:
        pairs = [tuple(edge) for edge in link_graph]
        for edge in pairs:
            if len(edge) != 2:
                raise TopologyError(f"edge {edge!r}: a joint joins exactly two links")
        labels = _sorted_labels({x for edge in pairs for x in edge})
    index = {label: i for i, label in enumerate(labels)}
    edges = sorted(tuple(sorted((index[u], index[v]))) for u, v in pairs)
    if joint_names is None:
        joint_names = [f"P{k + 1}" for k in range(len(edges))]
    elif len(joint_names) != len(edges):
        raise TopologyError(f"{len(joint_names)} joint names given for {len(edges)} joints")
    joints = tuple(Joint(name, edge) for name, edge in zip(joint_names, edges, strict=True))
    return KinematicChain(len(labels), joints, tuple(labels))


def chain_from_links(links: Sequence[Iterable[str]], link_labels: Sequence[Hashable] | None = None) -> KinematicChain:
    """Build a chain from its links, each given as the names of the joints it carries.

    This is how the thesis describes trusses (e.g. the 7/B1 truss by its triangles
    △P2P4P7, △P3P5P4, ... and binary links): every joint must lie on exactly two of the
    given links. Joints are ordered by name, numbers compared as numbers (P2 < P10).

    >>> pentad = chain_from_links([("P1", "P2", "P3"), ("P4", "P5", "P6"),
    ...                            ("P1", "P4"), ("P2", "P5"), ("P3", "P6")])
    >>> pentad.joint("P5").links
    (1, 3)
    >>> chain_from_links([("P1", "P2"), ("P2", "P3")])
    Traceback (most recent call last):
    ...
    baranov.topology.errors.TopologyError: joint P1: lies on 1 link (L0); a joint joins exactly two links
    """
    links = [tuple(link) for link in links]
    labels = tuple(link_labels) if link_labels is not None else tuple(range(len(links)))
    if len(labels) != len(links):
        raise TopologyError(f"{len(labels)} link labels given for {len(links)} links")
    carriers: dict[str, list[int]] = {}
    for index, link in enumerate(links):
        if len(set(link)) != len(link):
            raise TopologyError(f"link {_shown_label(labels[index])}: a joint is listed twice")
        for name in link:
            carriers.setdefault(name, []).append(index)
    for name, on in carriers.items():
        if len(on) != 2:
            listed = ", ".join(_shown_label(labels[i]) for i in on)
            raise TopologyError(f"joint {name}: lies on {len(on)} link{'s' if len(on) != 1 else ''} ({listed}); "
                                "a joint joins exactly two links")
    names = sorted(carriers, key=natural_sort_key)
    joints = tuple(Joint(name, (carriers[name][0], carriers[name][1])) for name in names)
    return KinematicChain(len(links), joints, labels)


def _shown_label(label: Hashable) -> str:
    """A link label as :meth:`KinematicChain.link_name` shows it."""
    return label if isinstance(label, str) else f"L{label}"


def thesis_subscript(name: str) -> str:
    """A joint's subscript in the thesis's notation: ``P12`` → ``12`` (so ``s1,12``,
    ``Z1,3,12``); other names are kept whole.

    >>> thesis_subscript("P12"), thesis_subscript("hub")
    ('12', 'hub')
    """
    return name[1:] if name[:1] == "P" and name[1:].isdigit() else name


def distance_name(u: str, v: str) -> str:
    """The squared distance between two joints in the thesis's notation, the smaller
    index first (s_{i,j} = s_{j,i}; one name for one distance in every output, issue 26).

    >>> distance_name("P1", "P6"), distance_name("P10", "P6")
    ('s1,6', 's6,10')
    """
    first, second = sorted((u, v), key=natural_sort_key)
    return f"s{thesis_subscript(first)},{thesis_subscript(second)}"


def natural_sort_key(name: str) -> tuple:
    """Sort key comparing digit runs as numbers: P2 < P10.

    >>> sorted(["P10", "P2", "P1"], key=natural_sort_key)
    ['P1', 'P2', 'P10']
    """
    return tuple(int(part) if part.isdigit() else part for part in re.split(r"(\d+)", name))


def _sorted_labels(labels: Iterable[Hashable]) -> list[Hashable]:
    labels = list(labels)
    try:
        return sorted(labels)
    except TypeError:
        return sorted(labels, key=repr)


def _parse_graph6(text: str | bytes) -> tuple[list[int], list[tuple[int, int]]]:
    raw = text.encode() if isinstance(text, str) else text
    raw = raw.strip()
    if raw.startswith(b">>graph6<<"):
        raw = raw[len(b">>graph6<<"):]
    try:
        graph = nx.from_graph6_bytes(raw)
    except (nx.NetworkXError, ValueError, IndexError) as error:
        shown = raw.decode(errors="replace")
        raise TopologyError(f"graph6 {shown!r}: not a valid graph6 string ({error})") from None
    return list(range(graph.number_of_nodes())), list(graph.edges)
