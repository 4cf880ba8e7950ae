"""``baranov show``: topology, symmetry, plan and closure conditions of one chain."""

from __future__ import annotations

import json
from pathlib import Path

import networkx as nx

from baranov.catalog.entries import assembly_mode_count
from baranov.catalog.lookup import (
    LITERATURE_NAMES,
    catalog_truss_of,
    named_truss,
    normalised_truss_name,
    thesis_names_without_links,
)
from baranov.closure import closure_system
from baranov.closure.slider_notation import slider_closure_text
from baranov.planner import best_plan, bilateration_plans
from baranov.planner.search import ALTERNATIVE_PLANS
from baranov.planner.sliders import slider_plan_obstacle
from baranov.solvers.mode_counts import plan_system_degree, slider_chain_degree
from baranov.solvers.msolve import MsolveUnavailable
from baranov.topology import (
    JointKind,
    KinematicChain,
    automorphism_group,
    chain_from_link_graph,
    chain_from_links,
    is_baranov_truss,
    is_planar,
)

from .arguments import parameter_pair


class ShowError(ValueError):
    """The chain to show could not be found or read."""


def resolve_chain(argument: str, catalog: Path | None = None) -> tuple[str, KinematicChain]:
    """A title and the chain for a thesis name (9/B28) or a catalog id (11/N123)
    (:func:`baranov.catalog.named_truss`), a file (graph6, an edge list "u v" per line,
    or JSON: a list of link pairs, {"links": [[joint names], ...]}, or a scene file), or a
    graph6 string."""
    path = Path(argument)
    if (normalised_truss_name(argument) or thesis_names_without_links(argument)) and not path.is_file():
        return named_truss(argument, catalog)
    if path.is_file():
        chain = _chain_from_text(path.read_text(encoding="utf-8"), str(path))
        return _with_catalog_name(str(path), chain, catalog), chain
    try:
        chain = _chain_from_text(argument, "argument")
    except ValueError as error:  # e.g. a misspelt name read as graph6 (issue 57)
        raise ShowError(f"{argument}: not a truss name (e.g. 9/B28, 7-b1, 11/N123), an existing file, or a valid "
                        f"graph6 string ({error})") from None
    return _with_catalog_name(argument, chain, catalog), chain


def _with_catalog_name(title: str, chain: KinematicChain, catalog: Path | None) -> str:
    """``title`` followed by the catalog truss the chain is isomorphic to, if any."""
    found = catalog_truss_of(chain, catalog)
    if found is None:
        return title
    identifier, name = found
    title += f" — the catalog's {identifier}" + (f" ({name})" if name != identifier else "")
    return title + (f", {LITERATURE_NAMES[identifier]}" if identifier in LITERATURE_NAMES else "")


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


def _sliders(chain: KinematicChain, text: str | None) -> list[str]:
    """The slider joints: ``--sliders`` (checked: joints of the chain, no loop of links
    closed by sliders only), else the chain's own (a scene file's)."""
    if text is None:
        return [joint.name for joint in chain.joints if joint.kind is JointKind.SLIDER]
    names = [name.strip() for name in text.split(",") if name.strip()]
    known = {joint.name: joint for joint in chain.joints}
    for name in names:
        if name not in known:
            raise ShowError(f"--sliders {text}: {name} is no joint of this chain (joints "
                            f"{', '.join(joint.name for joint in chain.joints)})")
    graph = nx.MultiGraph([known[name].links for name in names])
    try:
        loop = nx.find_cycle(graph)
    except nx.NetworkXNoCycle:
        return names
    links = ", ".join(chain.link_name(edge[0]) for edge in loop)
    raise ShowError(f"--sliders {text}: they close the loop of links {links}; an Assur chain needs a revolute "
                    "joint in every loop")


def _plans(chain: KinematicChain, sliders: list[str], plans: int, reference: str | None,
           parameters: list[str] | None) -> tuple[list, str | None]:
    """The ``plans`` best plans (with the given constraints) that the slider
    constructions run, and why none does where none does."""
    constraints = {"reference": parameter_pair(reference, "--reference") if reference else None,
                   "parameters": [parameter_pair(p) for p in parameters] if parameters else None}
    if not sliders:
        return bilateration_plans(chain, count=plans, **constraints), None
    candidates = bilateration_plans(chain, count=max(plans, ALTERNATIVE_PLANS), **constraints)
    suited = [plan for plan in candidates if slider_plan_obstacle(plan, sliders) is None][:plans]
    if suited:
        return suited, None
    return candidates[:plans], (f"none of the {len(candidates)} best plans suits these sliders (the best: "
                                f"{slider_plan_obstacle(candidates[0], sliders)}); `baranov solve` solves such "
                                "a chain with msolve; the plans below are the truss's")


def _counts(chain: KinematicChain, slider_names: list[str]) -> list[str]:
    """``--count``: the number of assembly modes over C of the truss (or of its slider
    chain), counted on random integer instances as the catalog counts it
    (:func:`~baranov.catalog.entries.assembly_mode_count`,
    :func:`~baranov.solvers.mode_counts.slider_chain_degree`), and for a truss the check
    by its best plan as one polynomial system
    (:func:`~baranov.solvers.mode_counts.plan_system_degree`, msolve). Seconds up to 11
    links, minutes for some 13-link trusses."""
    if not is_baranov_truss(chain):
        raise ShowError("--count: assembly modes are counted for Baranov trusses and their slider chains; "
                        "this chain is not a Baranov truss")
    if slider_names:
        modes, degrees, how = slider_chain_degree(chain, slider_names)
        return [f"assembly modes over C: {modes} (slider chain, {how}; on random instances: "
                f"{', '.join(map(str, degrees))})"]
    modes, evidence = assembly_mode_count(chain, best_plan(chain), True)
    lines = [f"assembly modes over C: {modes if modes is not None else 'not counted'} ({evidence})"]
    try:
        check, counts = plan_system_degree(chain)
    except MsolveUnavailable as error:
        return [*lines, f"not checked on the best plan's system: {error}"]
    verdict = "the same" if check == modes else "DIFFERENT"
    return [*lines, f"best plan as one polynomial system modulo random primes: {check} ({verdict}; on random "
                    f"instances: {', '.join(map(str, counts))})"]


def show(argument: str, catalog: Path | None = None, latex: bool = False, reference: str | None = None,
         parameters: list[str] | None = None, plans: int = 1, sliders: str | None = None,
         count: bool = False) -> str:
    """The text that ``baranov show`` prints (with ``count``, :func:`_counts` too)."""
    title, chain = resolve_chain(argument, catalog)
    group = automorphism_group(chain)
    slider_names = _sliders(chain, sliders)
    ranked, unsuited = _plans(chain, slider_names, plans, reference, parameters)
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
    if count:
        lines += _counts(chain, slider_names)
    if slider_names:  # the truss's plans and conditions, then the sliders at infinity (thesis ch. 4)
        lines.insert(2, f"slider joints: {', '.join(slider_names)} (an Assur kinematic chain derived from this "
                        "truss, thesis ch. 4: the truss's closure conditions with the sliders at infinity)")
        if unsuited:
            lines.insert(3, unsuited)
    for number, plan in enumerate(ranked, 1):
        system = closure_system(plan)
        lines.append("")
        lines.append(f"plan {number}" + (f" of {len(ranked)}" if len(ranked) > 1 else "")
                     + f": {len(plan.free_sign_triangles)} free signs, radical depth {plan.radical_depth}")
        lines += ["  " + line for line in plan.describe(slider_names).splitlines()]
        lines.append("closure conditions" + (" of the truss:" if slider_names else ":"))
        body = system.latex().split("\\\\\n") if latex else system.text().splitlines()
        lines += ["  " + line for line in body]
        if slider_names and not unsuited:
            lines.append("with the sliders at infinity (thesis §4.1–4.2.4):")
            lines += ["  " + line for line in slider_closure_text(chain, plan, slider_names)]
    return "\n".join(lines) + "\n"
