"""The structural diagram of a kinematic chain: its links drawn as the thesis draws them
(a k-ary link, k ≥ 3, as a filled polygon through its joints, a binary link as a bar),
at positions chosen for legibility rather than for any dimensions.

The positions come from a force-directed layout of the joint graph in which the joints of
one link are joined pairwise, so that a link's joints sit together (Kamada and Kawai, "An
algorithm for drawing general undirected graphs", Inf. Process. Lett. 31, 1989;
``networkx.kamada_kawai_layout``), started from several initial placements (a planar
embedding where the graph has one, a circle, seeded random ones) and kept where the
links' outlines cross least. Deterministic for a given chain.
"""

from __future__ import annotations

import html
import itertools
import math

import networkx as nx
import numpy as np

from .chain import KinematicChain
from .graphs import joints_of_links

#: Random starting placements tried besides the planar and circular ones (on 60 of the
#: 11-link trusses: 3.4 outline crossings a drawing with one, 3.2 with four at 2.7 times
#: the time, 64 ms a drawing; measured).
RANDOM_STARTS = 1


def diagram_layout(chain: KinematicChain) -> dict[str, tuple[float, float]]:
    """Positions of the joints of ``chain`` for :func:`diagram_svg`, in [−1, 1]²: the
    Kamada–Kawai layout of the joint graph with each link's joints joined pairwise, from
    the start whose drawing has the fewest crossings between the outlines of different
    links (ties: the first). O(starts × J³) for J joints (Kamada–Kawai's cost).

    >>> from baranov.enumerate import baranov_trusses
    >>> layout = diagram_layout(baranov_trusses(5)[0])
    >>> sorted(layout), all(abs(x) <= 1 and abs(y) <= 1 for x, y in layout.values())
    (['P1', 'P2', 'P3', 'P4', 'P5', 'P6'], True)
    """
    links = joints_of_links(chain)
    graph = nx.Graph()
    graph.add_nodes_from(joint.name for joint in chain.joints)
    for names in links:
        graph.add_edges_from(itertools.combinations(names, 2))
    starts = [nx.circular_layout(graph)]
    planar, _ = nx.check_planarity(graph)
    if planar:
        starts.insert(0, nx.planar_layout(graph))
    rng = np.random.default_rng(0)
    starts += [{node: rng.uniform(-1, 1, 2) for node in graph} for _ in range(RANDOM_STARTS)]
    best, fewest = None, math.inf
    for start in starts:
        layout = nx.kamada_kawai_layout(graph, pos=start)
        outlines = [convex_hull([layout[name] for name in names]) for names in links]
        crossings = _crossings(outlines)
        if crossings < fewest:
            best, fewest = layout, crossings
    return _normalised(best)


def convex_hull(points) -> list[tuple[float, float]]:
    """The convex hull of planar ``points`` ((x, y) pairs), counter-clockwise from the
    lowest-leftmost (Andrew's monotone chain, O(n log n)); the points themselves, sorted,
    where there are at most two: a link's outline, or its bar.

    >>> convex_hull([(0, 0), (2, 0), (1.5, 1.5), (1, 0.2), (0, 2)])  # (1, 0.2) inside
    [(0.0, 0.0), (2.0, 0.0), (1.5, 1.5), (0.0, 2.0)]
    """
    points = sorted({(float(x), float(y)) for x, y in points})
    if len(points) <= 2:
        return points

    def turn(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    upper: list = []
    for point in points:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], point) <= 0:
            lower.pop()
        lower.append(point)
    for point in reversed(points):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], point) <= 0:
            upper.pop()
        upper.append(point)
    return lower[:-1] + upper[:-1]


def _edges(outline: list) -> list:
    if len(outline) == 2:
        return [tuple(outline)]
    return [(outline[n], outline[(n + 1) % len(outline)]) for n in range(len(outline))]


def _crossings(outlines: list[list]) -> int:
    """Pairs of edges of different links' outlines that cross (meeting at a shared joint
    does not count)."""
    edges = [(link, edge) for link, outline in enumerate(outlines) for edge in _edges(outline)]
    count = 0
    for (first, (a, b)), (second, (c, d)) in itertools.combinations(edges, 2):
        if first != second and len({a, b, c, d}) == 4 and _proper_crossing(a, b, c, d):
            count += 1
    return count


def _proper_crossing(a, b, c, d) -> bool:
    def side(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    return side(a, b, c) * side(a, b, d) < 0 and side(c, d, a) * side(c, d, b) < 0


def _normalised(layout: dict) -> dict[str, tuple[float, float]]:
    points = np.array(list(layout.values()), dtype=float)
    centre = (points.max(axis=0) + points.min(axis=0)) / 2
    half = max(float((points.max(axis=0) - points.min(axis=0)).max()) / 2, 1e-12)
    return {name: tuple(float(v) for v in (np.asarray(at) - centre) / half) for name, at in layout.items()}


def diagram_svg(chain: KinematicChain, layout: dict[str, tuple[float, float]] | None = None,
                size: int = 240) -> str:
    """The chain's structural diagram as an SVG document ``size`` pixels square: each
    k-ary link a grey polygon through its joints, each binary link a bar, each joint a
    white circle with its name; ``layout`` from :func:`diagram_layout` by default. O(J).

    >>> from baranov.enumerate import baranov_trusses
    >>> svg = diagram_svg(baranov_trusses(5)[0])
    >>> svg.startswith("<svg") and svg.count("<polygon") == 2 and svg.count("<line") == 3
    True
    """
    layout = layout or diagram_layout(chain)
    margin = 36  # room for a label on the outside of a joint at the edge
    scale = (size - 2 * margin) / 2

    def at(name: str) -> tuple[float, float]:
        x, y = layout[name]
        return margin + (x + 1) * scale, margin + (1 - y) * scale  # SVG's y points down

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {size} {size}" width="{size}" height="{size}" '
             'font-family="sans-serif" font-size="11">']
    links = joints_of_links(chain)
    for names in sorted(links, key=len, reverse=True):  # polygons under bars
        if len(names) >= 3:
            outline = convex_hull([at(name) for name in names])
            points = " ".join(f"{x:.1f},{y:.1f}" for x, y in outline)
            parts.append(f'<polygon points="{points}" fill="#d0d0d0" stroke="#262626" stroke-width="1.5"/>')
        else:
            (x1, y1), (x2, y2) = at(names[0]), at(names[1])
            parts.append(f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" stroke="#262626" '
                         'stroke-width="3.5" stroke-linecap="round"/>')
    centre = np.mean([at(joint.name) for joint in chain.joints], axis=0)
    for joint in chain.joints:
        x, y = at(joint.name)
        dx, dy = x - centre[0], y - centre[1]
        length = math.hypot(dx, dy) or 1.0
        lx, ly = x + 13 * dx / length, y + 13 * dy / length + 4
        anchor = "start" if dx / length > 0.3 else "end" if dx / length < -0.3 else "middle"
        parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="white" stroke="#1a1a1a" stroke-width="1.2"/>')
        parts.append(f'<text x="{lx:.1f}" y="{ly:.1f}" text-anchor="{anchor}">{html.escape(joint.name)}</text>')
    parts.append("</svg>")
    return "\n".join(parts) + "\n"
