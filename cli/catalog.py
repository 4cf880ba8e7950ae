"""The catalog regeneration job: every Baranov truss with its invariants, as JSON files
and a Markdown summary next to the literature values.

Output (all written atomically, byte-identical from run to run):

* ``trusses-<L>.json`` — a JSON list, one object per truss, in catalog order
  (:func:`baranov.enumerate.truss_sort_key`);
* ``crosscheck.json`` — per link count, the result of the independent brute-force
  enumeration (:mod:`baranov.enumerate.crosscheck`), when geng is available;
* ``summary.md`` — tables built from the files above.

An existing ``trusses-<L>.json`` that has every field is reused unless ``force``.
"""

from __future__ import annotations

import json
import multiprocessing
import sys
from collections import Counter
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from tqdm import tqdm

from baranov.closure import closure_system
from baranov.enumerate import baranov_link_graphs
from baranov.enumerate.appendix_a import appendix_a_labelling, link_pairs_required, names_by_closure_conditions
from baranov.enumerate.crosscheck import baranov_link_graphs_by_filter, find_geng
from baranov.enumerate.literature import (
    APPENDIX_A_ASSEMBLY_MODES,
    name_by_invariants,
    nine_link_signature,
    thesis_joint_names,
    thesis_name,
)
from baranov.enumerate.sliders import count_slider_chains
from baranov.enumerate.trusses import canonical_trusses
from baranov.planner import best_plan
from baranov.solvers.configuration import parameter_name
from baranov.solvers.mode_counts import characteristic_degree
from baranov.topology import (
    KinematicChain,
    adjacency_masks,
    automorphism_group,
    chain_from_link_graph,
    is_planar,
)
from baranov.topology.automorphisms import link_graph_certificate
from baranov.topology.realizations import realization_count

from .files import write_atomically

#: Literature values (thesis Table 3.1 after Yang & Yao 1994; slider chains: thesis ch. 4).
LITERATURE = {
    3: {"trusses": 1, "assur_groups": 1, "slider_chains": 3},
    5: {"trusses": 1, "assur_groups": 2, "slider_chains": 10},
    7: {"trusses": 3, "assur_groups": 10, "slider_chains": None},
    9: {"trusses": 28, "assur_groups": 173, "slider_chains": None},
    11: {"trusses": 239, "assur_groups": 5442, "slider_chains": None},
    13: {"trusses": None, "assur_groups": 251638, "slider_chains": None},
}

#: Coupling-degree distribution, thesis Table 3.1 (after Yang & Yao 1994).
LITERATURE_COUPLING = {3: {0: 1}, 5: {1: 1}, 7: {1: 3}, 9: {1: 24, 2: 4}, 11: {1: 197, 2: 42}}

#: Slider chains are counted over all 2^J joint subsets; done up to this many links.
SLIDER_CHAINS_MAX_LINKS = 11

ENTRY_FIELDS = (
    "id", "name", "name_evidence", "thesis_joint_names", "link_graph6", "links", "joints", "link_degrees",
    "automorphism_group_order", "coupling_degree", "plan", "closure_conditions",
    "link_orbits", "joint_orbits", "planar", "assur_groups", "slider_chains",
    "assembly_modes", "assembly_modes_evidence", "realization_count",
)

#: Assembly modes are counted up to this many links (coupling degrees 1 and 2), as the
#: degree of the characteristic polynomial modulo a prime (:mod:`baranov.solvers.modular`).
#: Per 11-link truss (two instances; bench/sweep_assembly_modes.py): coupling 1 median
#: 0.21 s, max 0.76 s; coupling 2 median 5.0 s, max 70 s. 13 links (thousands of trusses)
#: are left to a separate run.
ASSEMBLY_MODES_MAX_LINKS = 11

Progress = Callable[[str], None]


def nine_link_name(chain: KinematicChain, identifier: str,
                   signature: tuple[int, int, bool]) -> tuple[str, str | None, dict[str, str] | None]:
    """(name, evidence, {joint: thesis joint}) of a nine-link truss that is not isomorphic
    to a recorded one: the thesis name whose Appendix A closure conditions fit it
    (:func:`~baranov.enumerate.appendix_a.appendix_a_labelling`) among those with its
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


def truss_entry(item: tuple[str, str]) -> dict:
    """The catalog object of one truss, from its project id and canonical graph6.

    ``name`` is the thesis name where the truss is isomorphic to one recorded in
    :mod:`baranov.enumerate.literature`, or for nine links where the Appendix A closure
    conditions or invariants single it out (:func:`nine_link_name`); ``name_evidence``
    says how. Otherwise the project id.
    """
    identifier, graph6 = item
    chain = chain_from_link_graph(graph6)
    group = automorphism_group(chain)
    sliders = count_slider_chains(chain, group) if chain.number_of_links <= SLIDER_CHAINS_MAX_LINKS else None
    published = thesis_name(chain)
    plan = best_plan(chain)
    if plan.number_of_parameters in (1, 2) and chain.number_of_links <= ASSEMBLY_MODES_MAX_LINKS:
        modes, degrees = characteristic_degree(chain)
        evidence = (f"degree of the characteristic polynomial in {parameter_name(plan.parameters[0])} modulo a random "
                    f"62-bit prime, on random integer-coordinate instances: {', '.join(map(str, degrees))}")
        if plan.number_of_parameters == 2:
            evidence += (f" (after eliminating {parameter_name(plan.parameters[1])} by resultants; common points on "
                         "different sign branches, undefined points and points at infinity removed)")
    elif plan.number_of_parameters == 0:
        modes = 2 ** len(plan.free_sign_triangles)
        evidence = "coupling degree 0: one configuration per sign branch of the free triangles"
    else:
        modes = None
        evidence = f"not derived: more than {ASSEMBLY_MODES_MAX_LINKS} links"
    count, planar = realization_count(chain), is_planar(chain)
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


def dump_entries(entries: list[dict]) -> str:
    """JSON list with one truss per line (compact, diff-friendly, deterministic)."""
    lines = [json.dumps(entry, separators=(",", ":"), ensure_ascii=False) for entry in entries]
    return "[\n" + ",\n".join(lines) + "\n]\n"


def load_entries(path: Path) -> list[dict] | None:
    """The entries of an existing catalog file, or None if absent, unreadable or incomplete."""
    try:
        entries = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(entries, list) or not entries:
        return None
    if not all(isinstance(e, dict) and all(field in e for field in ENTRY_FIELDS) for e in entries):
        return None
    return entries


def catalog_links(links: int, workers: int, show_progress: bool) -> list[dict]:
    """Enumerate the trusses with ``links`` links and compute every catalog entry."""
    trusses = canonical_trusses(baranov_link_graphs(links, workers))
    items = [(f"{links}/N{i + 1}", graph6) for i, (graph6, _) in enumerate(trusses)]
    bar = tqdm(total=len(items), desc=f"{links} links", unit="truss", disable=not show_progress, file=sys.stderr)
    entries = []
    # Worker processes are spawned, not forked: a forked worker deadlocked once flint and
    # lnumber had run in the parent.
    if workers > 1 and len(items) > 16:
        order = list(range(len(items)))
        if links <= ASSEMBLY_MODES_MAX_LINKS:
            # Coupling-2 counts cost ~10x coupling-1 ones: the costliest first, so that
            # no worker is left with a long tail.
            coupling = [best_plan(chain_from_link_graph(graph6)).number_of_parameters for _, graph6 in items]
            order.sort(key=lambda i: -coupling[i])
        with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
            futures = {pool.submit(truss_entry, items[i]): i for i in order}
            done: dict[int, dict] = {}
            for future in as_completed(futures):
                done[futures[future]] = future.result()
                bar.update()
        entries = [done[i] for i in range(len(items))]
    else:
        for item in items:
            entries.append(truss_entry(item))
            bar.update()
    bar.close()
    return entries


def crosscheck_links(links: int, entries: list[dict], workers: int) -> dict:
    """Run the brute-force enumeration and compare its classes with the catalog's."""
    candidates, graphs = baranov_link_graphs_by_filter(links, workers)
    ours = {link_graph_certificate(adjacency_masks(chain_from_link_graph(e["link_graph6"]))) for e in entries}
    theirs = {link_graph_certificate(masks) for masks in graphs}
    return {
        "method": "geng -c -d2 L J:J, filtered by the Baranov predicate, deduplicated with pynauty",
        "candidates": candidates,
        "trusses": len(graphs),
        "same_isomorphism_classes": ours == theirs,
    }


def build_catalog(
    link_counts: Iterable[int],
    out: Path,
    workers: int = 1,
    force: bool = False,
    crosscheck: bool = True,
    show_progress: bool = False,
    log: Progress = lambda message: None,
) -> str:
    """Regenerate (or reuse) the catalog files for ``link_counts`` in ``out``; return the summary."""
    crosscheck_path = out / "crosscheck.json"
    try:
        checks = {int(k): v for k, v in json.loads(crosscheck_path.read_text(encoding="utf-8")).items()}
    except (OSError, ValueError):
        checks = {}
    geng = find_geng() if crosscheck else None
    for links in sorted(set(link_counts)):
        path = out / f"trusses-{links}.json"
        entries = None if force else load_entries(path)
        if entries is None:
            log(f"{links} links: enumerating")
            entries = catalog_links(links, workers, show_progress)
            write_atomically(path, dump_entries(entries))
        else:
            log(f"{links} links: reusing {path}")
        if geng and (force or links not in checks or checks[links].get("trusses") != len(entries)):
            log(f"{links} links: brute-force cross-check")
            checks[links] = crosscheck_links(links, entries, workers)
            write_atomically(crosscheck_path, json.dumps({str(k): checks[k] for k in sorted(checks)}, indent=2) + "\n")
    summary = render_summary(out, checks)
    write_atomically(out / "summary.md", summary)
    return summary


def _cell(value) -> str:
    return "—" if value is None else str(value)


def render_summary(out: Path, checks: dict[int, dict]) -> str:
    """Markdown tables from every ``trusses-<L>.json`` in ``out`` and the cross-checks."""
    catalogs = {}
    for path in sorted(out.glob("trusses-*.json")):
        entries = load_entries(path)
        if entries:
            catalogs[entries[0]["links"]] = entries
    lines = [
        "# Baranov truss catalog — summary",
        "",
        "Regenerated by `baranov catalog`; do not edit by hand. Literature values: thesis",
        "Table 3.1 (after Yang & Yao 1994) and thesis ch. 4 (slider chains). Method A: the",
        "library's generator; method B: brute force over nauty's geng output.",
        "",
        "| links | trusses (method A) | trusses (method B) | trusses (literature) | Assur groups "
        "| Assur groups (literature) | slider chains | slider chains (literature) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for links in sorted(set(catalogs) | set(LITERATURE)):
        entries = catalogs.get(links)
        literature = LITERATURE.get(links, {})
        check = checks.get(links)
        if entries is None:
            a_count = assur = sliders = None
        else:
            a_count = len(entries)
            assur = sum(e["assur_groups"] for e in entries)
            slider_values = [e["slider_chains"] for e in entries]
            sliders = None if None in slider_values else sum(slider_values)
        b_count = None
        if check:
            same = "yes" if check["same_isomorphism_classes"] else "NO"
            b_count = f"{check['trusses']} (of {check['candidates']} candidates; same classes: {same})"
        lines.append(
            f"| {links} | {_cell(a_count)} | {_cell(b_count)} | {_cell(literature.get('trusses'))} | "
            f"{_cell(assur)} | {_cell(literature.get('assur_groups'))} | {_cell(sliders)} | "
            f"{_cell(literature.get('slider_chains'))} |"
        )
    lines += ["", "## Invariants per link count", ""]
    lines += [
        "| links | non-planar | automorphism group orders (order: trusses) "
        "| largest link degree (degree: trusses) |",
        "|---|---|---|---|",
    ]
    for links, entries in sorted(catalogs.items()):
        orders = Counter(e["automorphism_group_order"] for e in entries)
        degrees = Counter(max(e["link_degrees"]) for e in entries)
        lines.append(
            f"| {links} | {sum(not e['planar'] for e in entries)} | "
            + ", ".join(f"{k}: {v}" for k, v in sorted(orders.items()))
            + " | "
            + ", ".join(f"{k}: {v}" for k, v in sorted(degrees.items()))
            + " |"
        )
    lines += ["", "## Coupling degree", "",
              "Fewest unknown distances of a bilateration plan (`baranov.planner`), as trusses per degree.", "",
              "| links | this catalog | Yang & Yao (thesis Table 3.1) |", "|---|---|---|"]
    for links, entries in sorted(catalogs.items()):
        ours = Counter(e["coupling_degree"] for e in entries)
        theirs = LITERATURE_COUPLING.get(links)
        lines.append(
            f"| {links} | " + ", ".join(f"{d}: {n}" for d, n in sorted(ours.items())) + " | "
            + (", ".join(f"{d}: {n}" for d, n in sorted(theirs.items())) if theirs else "—") + " |"
        )
    lines += ["", "## Assembly modes", "",
              "Degree of the characteristic polynomial (`assembly_modes`, derived modulo random 62-bit primes on random",
              "integer-coordinate instances, coupling degrees 1 and 2 up to " + str(ASSEMBLY_MODES_MAX_LINKS) + " links;",
              "`baranov.solvers.modular`, equal to the degree over Q wherever both were derived) and the realization-count",
              "identity (`realization_count`, pyrigi; `baranov.topology.realizations`), as count: trusses.", "",
              "| links | assembly modes (characteristic polynomial) | realization count | trusses where both are known "
              "| of them equal |", "|---|---|---|---|---|"]
    for links, entries in sorted(catalogs.items()):
        derived = Counter(e["assembly_modes"] for e in entries if e["assembly_modes"] is not None)
        counted = Counter(e["realization_count"] for e in entries)
        both = [e for e in entries if e["assembly_modes"] is not None]
        lines.append(
            f"| {links} | " + (", ".join(f"{k}: {v}" for k, v in sorted(derived.items())) or "—") + " | "
            + ", ".join(f"{k}: {v}" for k, v in sorted(counted.items())) + f" | {len(both)} | "
            + f"{sum(e['assembly_modes'] == e['realization_count'] for e in both)} |"
        )
    if 9 in catalogs:
        ours = sorted(e["realization_count"] for e in catalogs[9])
        published = sorted(APPENDIX_A_ASSEMBLY_MODES.values())
        by_name = all(e["assembly_modes"] in (None, APPENDIX_A_ASSEMBLY_MODES.get(e["name"])) for e in catalogs[9])
        lines += ["", "Thesis Appendix A lists the assembly modes of the 28 nine-link trusses 9/B1-9/B28; as a "
                  "multiset they " + ("equal" if ours == published else "DIFFER from") + " the realization counts above, "
                  "and under the thesis names every derived nine-link degree " + ("equals" if by_name else "does NOT equal")
                  + " its Appendix A value.",
                  "", "Nine-link thesis names given (`name_evidence` in the catalog says how each was identified): "
                  + ", ".join(sorted((e["name"] for e in catalogs[9] if e["name"].startswith("9/B")),
                                     key=lambda n: int(n[3:]))) + "."]
    lines += ["", "## Where this differs from the literature", "", *DISCREPANCY_NOTE, ""]
    return "\n".join(lines)


DISCREPANCY_NOTE = [
    "The thesis's Table 3.1 gives, for 11 links, 239 trusses (Yang & Yao 1994, topologies never",
    "published) and 5442 Assur groups. These two numbers contradict each other: removing one",
    "link of an 11-link truss gives at most 11 different Assur groups, so 239 trusses give at",
    "most 2629. Both enumerations here (the library's generator and the brute-force filter over",
    "every connected 11-link graph with 15 joints and no link with fewer than two joints) find the",
    "same 562 trusses, which give 5438 Assur groups: within 4 of the published 5442, and far from",
    "what 239 trusses allow. At 13 links the same computation gives 251638 Assur groups, exactly",
    "the published value. We therefore take 239 to be wrong. We could not find the cause of the",
    "4-group difference at 11 links; 5438 was confirmed a second way, by counting",
    "non-isomorphic (truss, removed link) pairs with vertex-coloured nauty certificates",
    "(`tests/test_enumeration.py`). See `docs/enumeration.md`.",
    "",
    "Coupling degrees agree with Yang & Yao for 3-9 links. For 11 links the published split",
    "197 + 42 covers the 239 trusses above; over the 562 found here it is 409 + 153 (no truss",
    "needs 3 parameters). See `docs/planner.md`.",
]
