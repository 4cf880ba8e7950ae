"""Pages of the documentation site made from the code and the data, before each build
(docs/conf.py calls :func:`generate_pages`; ``python docs/site/generate.py`` runs it
alone): the command-line reference from the argument parser, and the catalog pages from
the committed catalog files. Written under docs/generated/ (not committed); never edited
by hand.
"""

from __future__ import annotations

import gzip
import hashlib
import html
import json
import sys
from pathlib import Path

#: Where the generated pages go, under docs/.
GENERATED = "generated"
#: Trusses up to this many links get a page each; the 13-link class a table.
PAGE_LINKS = 11
#: The trusses' structural diagrams, under GENERATED.
DRAWINGS = "catalog-drawings"


def generate_pages(docs: Path) -> None:
    """Write the CLI reference and the catalog pages under ``docs``/generated/."""
    out = docs / GENERATED
    out.mkdir(exist_ok=True)
    _write(out / "cli.md", cli_reference())
    catalog = docs.parent / "catalog"
    entries = {links: _entries(catalog / f"trusses-{links}.jsonl") for links in range(3, PAGE_LINKS + 1, 2)}
    thirteen = _entries(catalog / "trusses-13.jsonl.gz")
    _write(out / "catalog.md", catalog_index({**{links: len(found) for links, found in entries.items()},
                                              13: len(thirteen)}))
    for links, found in entries.items():
        drawings = {entry["id"]: truss_drawing(entry, out / DRAWINGS) for entry in found}
        _write(out / f"catalog-{links}.md", links_page(links, found, _slider_counts(catalog / f"slider-chains-{links}.jsonl"),
                                                       drawings))
    _write(out / "catalog-13.md", thirteen_table(thirteen))


def _write(path: Path, text: str) -> None:
    """Write ``text`` unless the file holds it already (Sphinx rebuilds what changed)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def cli_reference() -> str:
    """The ``--help`` of ``baranov`` and of each of its commands, as the parser prints it."""
    from baranov.cli.main import _parser

    parser = _parser()
    parser.prog = "baranov"
    lines = ["# Command-line reference", "",
             "Generated from the argument parser (`baranov COMMAND --help` prints the same).", "",
             "```text", parser.format_help().rstrip(), "```", ""]
    commands = next(action for action in parser._actions if action.dest == "command")
    for name, command in commands.choices.items():
        command.prog = f"baranov {name}"
        lines += [f"## baranov {name}", "", "```text", command.format_help().rstrip(), "```", ""]
    return "\n".join(lines)


def truss_drawing(entry: dict, folder: Path) -> str:
    """The path, relative to the catalog pages, of the structural diagram of a catalog
    truss (:func:`baranov.topology.diagram_svg`), drawn unless a drawing of the same joints
    exists: its name holds a hash of the truss's joints (about 25 ms a drawing, 15 s for
    the 595 trusses to 11 links)."""
    from baranov.topology import chain_from_links, diagram_svg

    digest = hashlib.sha1(json.dumps(entry["joints"], sort_keys=True).encode()).hexdigest()[:10]
    path = folder / f"{_slug(entry['id'])}-{digest}.svg"
    if not path.exists():
        links: dict[int, list[str]] = {}
        for joint, pair in entry["joints"].items():
            for link in pair:
                links.setdefault(link, []).append(joint)
        _write(path, diagram_svg(chain_from_links([links[link] for link in sorted(links)])))
    return f"{folder.name}/{path.name}"


def _entries(path: Path) -> list[dict]:
    opener = gzip.open if path.suffix == ".gz" else open
    with opener(path, "rt", encoding="utf-8") as handle:
        return [json.loads(line) for line in handle if line.strip()]


def _slider_counts(path: Path) -> dict[str, list[dict]]:
    """truss id → its slider chains (sliders, assembly modes, method)."""
    counts: dict[str, list[dict]] = {}
    if path.exists():
        for row in _entries(path):
            counts.setdefault(row["truss"], []).append(row)
    return counts


def _slug(truss_id: str) -> str:
    return truss_id.replace("/", "-")


def _modes(entry: dict) -> str:
    modes = entry.get("assembly_modes")
    return "—" if modes is None else str(modes)


def catalog_index(counts: dict[int, int]) -> str:
    """The catalog's front page: what it holds, one line per link count (``counts``:
    links → trusses)."""
    lines = ["# The catalog, browsable", "",
             "Every Baranov truss to 13 links, generated from the catalog files in `catalog/` "
             "(`make catalog` regenerates them; the catalog page of the user guide says how they are made and "
             "checked). Each truss up to 11 links has a section with its plan, closure conditions, symmetry, "
             "coupling degree, number of assembly modes and slider chains; the 13-link class is one table to "
             "search and sort.", "", "| links | trusses | page |", "|---|---|---|"]
    for links in range(3, PAGE_LINKS + 1, 2):
        lines.append(f"| {links} | {counts[links]} | [{links}-link trusses](catalog-{links}.md) |")
    lines += [f"| 13 | {counts[13]} | [the 13-link table](catalog-13.md) |", "", "```{toctree}", ":hidden:", ""]
    lines += [f"catalog-{links}" for links in range(3, PAGE_LINKS + 1, 2)] + ["catalog-13", "```", ""]
    return "\n".join(lines)


def links_page(links: int, entries: list[dict], sliders: dict[str, list[dict]],
               drawings: dict[str, str] | None = None) -> str:
    """One link count: a table of its trusses, each linked to its section (with its
    drawing, ``drawings``: truss id → image path)."""
    lines = [f"# {links}-link Baranov trusses", "", f"{len(entries)} trusses (catalog/trusses-{links}.jsonl).", "",
             "| truss | thesis name | link degrees | coupling degree | automorphisms | assembly modes | "
             "slider chains |", "|---|---|---|---|---|---|---|"]
    for entry in entries:
        name = entry.get("name") if entry.get("name") != entry["id"] else ""
        lines.append(f"| [{entry['id']}](#{_slug(entry['id']).lower()}) | {name} | "
                     f"{' '.join(map(str, entry['link_degrees']))} | {entry.get('coupling_degree', '—')} | "
                     f"{entry.get('automorphism_group_order', '—')} | {_modes(entry)} | "
                     f"{len(sliders.get(entry['id'], []))} |")
    for entry in entries:
        lines += ["", f"({_slug(entry['id']).lower()})=",
                  truss_section(entry, sliders.get(entry["id"], []), (drawings or {}).get(entry["id"]))]
    return "\n".join(lines) + "\n"


def truss_section(entry: dict, sliders: list[dict], drawing: str | None = None) -> str:
    """One truss: its joints, plan, closure conditions and counts, as the catalog holds them
    (under a rubric, not a section: hundreds of sections would each enter the site's
    navigation, which every page copies)."""
    title = entry["id"] + (f" ({entry['name']})" if entry.get("name") and entry["name"] != entry["id"] else "")
    lines = ["```{rubric} " + title, "```", "",
             f"`baranov show {entry['id']}` prints this truss; `baranov.truss(\"{entry['id']}\")` returns it.", "",
             *([f"![structural diagram of {entry['id']}: k-ary links grey, binary links bars]({drawing})", ""]
               if drawing else []),
             f"- links: {entry['links'] if 'links' in entry else len(entry['link_degrees'])}, link degrees "
             f"{' '.join(map(str, entry['link_degrees']))} (graph6 of the link graph: `{entry['link_graph6']}`)",
             f"- automorphism group order: {entry.get('automorphism_group_order', '—')}",
             f"- coupling degree: {entry.get('coupling_degree', '—')}",
             f"- assembly modes over the complex numbers (generic dimensions): {_modes(entry)}"]
    if entry.get("assembly_modes_evidence"):
        lines.append(f"  ({entry['assembly_modes_evidence']})")
    if entry.get("name_evidence"):
        lines.append(f"- thesis name: {entry['name_evidence']}")
    if entry.get("joints"):
        joints = ", ".join(f"{joint}: links {a}, {b}" for joint, (a, b) in entry["joints"].items())
        lines += ["", "**Joints**", "", joints]
    plan = entry.get("plan")
    if plan:
        parameters = ", ".join(f"s{u[1:]},{v[1:]}" for u, v in plan["parameters"]) or "none"
        lines += ["", "**Bilateration plan**", "",
                  f"Reference p{plan['reference'][0][1:]},{plan['reference'][1][1:]}; parameters: {parameters}.", "",
                  "| joint | from | kind | base distance |", "|---|---|---|---|"]
        for step in plan["steps"]:
            lines.append(f"| {step['joint']} | {step['base'][0]}, {step['base'][1]} | {step['kind']} | "
                         f"{step['base_distance']} |")
    if entry.get("closure_conditions"):
        lines += ["", "**Closure conditions**", "", "```text", *entry["closure_conditions"], "```"]
    if sliders:
        lines += ["", "**Slider chains**", "",
                  f"{len(sliders)} chains with slider joints derived from it (catalog/slider-chains-"
                  f"{len(entry['link_degrees'])}.jsonl), by number of sliders: how many chains have each number "
                  "of assembly modes.", "", "| sliders | chains | assembly modes (chains) |", "|---|---|---|"]
        for count in sorted({len(row["sliders"]) for row in sliders}):
            mine = [row for row in sliders if len(row["sliders"]) == count]
            tally: dict = {}
            for row in mine:
                tally[row.get("assembly_modes")] = tally.get(row.get("assembly_modes"), 0) + 1
            spread = ", ".join(f"{'—' if modes is None else modes} ({number})"
                               for modes, number in sorted(tally.items(), key=lambda item: (item[0] is None, item[0] or 0),
                                                           reverse=True))
            lines.append(f"| {count} | {len(mine)} | {spread} |")
    return "\n".join(lines) + "\n"


def thirteen_table(entries: list[dict]) -> str:
    """The 13-link class as one table, sortable by a click on a heading and filtered by a
    search field (a few lines of JavaScript in the page itself)."""
    columns = ["truss", "link degrees", "coupling degree", "automorphisms", "Assur groups", "assembly modes"]
    rows = "\n".join(
        "<tr>" + "".join(f"<td>{html.escape(str(value))}</td>" for value in (
            entry["id"], " ".join(map(str, entry["link_degrees"])), entry.get("coupling_degree", ""),
            entry.get("automorphism_group_order", ""), entry.get("assur_groups", ""), _modes(entry))) + "</tr>"
        for entry in entries)
    head = "".join(f'<th data-column="{n}">{html.escape(name)}</th>' for n, name in enumerate(columns))
    return f"""# 13-link Baranov trusses

{len(entries)} trusses (catalog/trusses-13.jsonl.gz). Type in the field to keep the rows that
contain the text (e.g. `13/N206` or a link-degree sequence); click a heading to sort by it.

```{{raw}} html
<input id="truss-filter" type="search" placeholder="filter rows" style="width: 100%; margin: 0.5em 0">
<table id="truss-table" class="docutils"><thead><tr>{head}</tr></thead><tbody>
{rows}
</tbody></table>
<script>
(function () {{
  const table = document.getElementById("truss-table");
  const body = table.tBodies[0];
  document.getElementById("truss-filter").addEventListener("input", function (event) {{
    const text = event.target.value.trim().toLowerCase();
    for (const row of body.rows) row.style.display = row.textContent.toLowerCase().includes(text) ? "" : "none";
  }});
  for (const cell of table.tHead.rows[0].cells) {{
    cell.style.cursor = "pointer";
    cell.addEventListener("click", function () {{
      const n = Number(cell.dataset.column), ascending = cell.dataset.order !== "ascending";
      cell.dataset.order = ascending ? "ascending" : "descending";
      const key = r => {{ const t = r.cells[n].textContent, x = Number(t.replace(/^13\\/N/, ""));
                          return Number.isNaN(x) ? t : x; }};
      const rows = Array.from(body.rows).sort((a, b) => (key(a) > key(b) ? 1 : key(a) < key(b) ? -1 : 0)
                                                       * (ascending ? 1 : -1));
      body.append(...rows);
    }});
  }}
}})();
</script>
```
"""


if __name__ == "__main__":
    generate_pages(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1])
