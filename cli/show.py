"""``baranov show``: topology, symmetry, plan and closure conditions of one chain."""

from __future__ import annotations

import json
from pathlib import Path

from baranov.catalog.lookup import TRUSS_NAME, named_truss
from baranov.closure import closure_system
from baranov.planner import bilateration_plans
from baranov.topology import (
    JointKind,
    KinematicChain,
    automorphism_group,
    chain_from_link_graph,
    chain_from_links,
    is_baranov_truss,
    is_planar,
)


class ShowError(ValueError):
    """The chain to show could not be found or read."""


def resolve_chain(argument: str, catalog: Path | None = None) -> tuple[str, KinematicChain]:
    """A title and the chain for a thesis name (9/B28) or a catalog id (11/N123)
    (:func:`baranov.catalog.named_truss`), a file (graph6, an edge list "u v" per line,
    or JSON: a list of link pairs, {"links": [[joint names], ...]}, or a scene file), or a
    graph6 string."""
    path = Path(argument)
    if TRUSS_NAME.match(argument.upper()) and not path.is_file():
        return named_truss(argument, catalog)
    if path.is_file():
        return str(path), _chain_from_text(path.read_text(encoding="utf-8"), str(path))
    return argument, _chain_from_text(argument, "argument")


def _chain_from_text(text: str, source: str) -> KinematicChain:
    text = text.strip()
    if text.startswith(("[", "{")):
        try:
            data = json.loads(text)
        except ValueError as error:
            raise ShowError(f"{source}: not valid JSON ({error.msg}, line {error.lineno})") from None
        if isinstance(data, dict) and isinstance(data.get("links"), list) and data["links"] \
                and all(isinstance(link, dict) for link in data["links"]):
            from baranov.scene import scene_from_dict  # a scene file: its linkage's chain

            return scene_from_dict(data).chain
        if isinstance(data, dict) and "links" in data:
            return chain_from_links(data["links"])
        return chain_from_link_graph([tuple(edge) for edge in data])
    lines = [line.split("#")[0].strip() for line in text.splitlines()]
    lines = [line for line in lines if line]
    if len(lines) == 1 and len(lines[0].split()) == 1:
        return chain_from_link_graph(lines[0])
    edges = []
    for number, line in enumerate(lines, 1):
        parts = line.replace(",", " ").split()
        if len(parts) != 2:
            raise ShowError(f"{source}: line {number}: expected two link labels, got {line!r}")
        edges.append(tuple(int(p) if p.isdigit() else p for p in parts))
    return chain_from_link_graph(edges)


def _pair(text: str, option: str) -> tuple[str, str]:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2 or not all(parts):
        raise ShowError(f"{option} {text}: expected two joint names such as P1,P6")
    return parts[0], parts[1]


def show(argument: str, catalog: Path | None = None, latex: bool = False, reference: str | None = None,
         parameters: list[str] | None = None, plans: int = 1) -> str:
    """The text that ``baranov show`` prints."""
    title, chain = resolve_chain(argument, catalog)
    group = automorphism_group(chain)
    ranked = bilateration_plans(
        chain,
        count=plans,
        reference=_pair(reference, "--reference") if reference else None,
        parameters=[_pair(p, "--parameter") for p in parameters] if parameters else None,
    )
    degrees = ",".join(str(d) for d in chain.link_degrees)
    lines = [
        title,
        f"links {chain.number_of_links}, joints {chain.number_of_joints}, link degrees {degrees}, "
        f"planar: {'yes' if is_planar(chain) else 'no'}, Baranov truss: {'yes' if is_baranov_truss(chain) else 'no'}",
        "links: " + "  ".join(
            f"L{link}:" + ",".join(j.name for j in chain.joints if link in j.links)
            for link in range(chain.number_of_links)
        ),
        f"automorphism group order {group.order}; link orbits "
        + " ".join("{" + ",".join(f"L{x}" for x in orbit) + "}" for orbit in group.link_orbits),
        f"coupling degree {ranked[0].number_of_parameters}"
        + (" (with the given constraints)" if reference or parameters else ""),
    ]
    sliders = [joint.name for joint in chain.joints if joint.kind is JointKind.SLIDER]
    if sliders:  # a slider chain: its truss's plans and conditions, the sliders at infinity (thesis ch. 4)
        lines.insert(2, f"slider joints: {', '.join(sliders)} (an Assur kinematic chain derived from this truss, "
                        "thesis ch. 4: the plans below are the truss's; solve it with --method msolve)")
    for number, plan in enumerate(ranked, 1):
        system = closure_system(plan)
        lines.append("")
        lines.append(f"plan {number}" + (f" of {len(ranked)}" if len(ranked) > 1 else "")
                     + f": {len(plan.free_sign_triangles)} free signs, radical depth {plan.radical_depth}")
        lines += ["  " + line for line in plan.describe().splitlines()]
        lines.append("closure conditions:")
        body = system.latex().split("\\\\\n") if latex else system.text().splitlines()
        lines += ["  " + line for line in body]
    return "\n".join(lines) + "\n"
