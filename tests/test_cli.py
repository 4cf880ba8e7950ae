"""The `baranov catalog` command: output, determinism, resume, atomicity, bad input."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from baranov.catalog import iter_objects
from baranov.cli.main import main
from baranov.enumerate.crosscheck import find_geng
from baranov.solvers.msolve import find_msolve

REPO = Path(__file__).resolve().parents[1]


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "baranov.cli", *args], capture_output=True, text=True)


def test_catalog_files_and_fields(tmp_path):
    assert main(["catalog", "--links", "3,5,7", "--out", str(tmp_path), "--quiet", "--workers", "1",
                 "--slider-modes", "5"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    expected = ["slider-chains-3.jsonl", "slider-chains-5.jsonl", "summary.md", "trusses-3.jsonl", "trusses-5.jsonl",
                "trusses-7.jsonl"]
    assert [n for n in names if n not in ("crosscheck.json", "grubler-chains.json")] == expected
    if find_geng() is not None:  # the Grübler chains counted to 8 links beside the trusses to 7
        assert json.loads((tmp_path / "grubler-chains.json").read_text())["counts"] == {"4": 1, "6": 2, "8": 16}
    pentad = list(iter_objects(tmp_path / "trusses-5.jsonl"))
    mapping = pentad[0].pop("thesis_joint_names")  # validity: tests/test_literature.py
    assert pentad[0].pop("coupling_degree") == 1
    plan, conditions = pentad[0].pop("plan"), pentad[0].pop("closure_conditions")
    assert pentad[0].pop("assembly_modes_evidence").startswith("degree of the characteristic polynomial in s")
    assert len(plan["parameters"]) == len(plan["closure_pairs"]) == len(conditions) == 1
    assert len(plan["steps"]) == 4 and len(plan["free_sign_triangles"]) == 2
    assert conditions[0].startswith("s") and " = det(" in conditions[0]
    assert sorted(mapping) == sorted(mapping.values()) == ["P1", "P2", "P3", "P4", "P5", "P6"]
    assert pentad == [{
        "id": "5/N1", "name": "5/B1",
        "name_evidence": "isomorphic to the truss of thesis §2.7, eq. (2.24)-(2.25): ternary links "
                         "△P1P3P2, △P4P5P6; binary links P1P4 (Z6,1,4), P3P6 (Z1,6,3), P2P5 (closure s2,5)",
        "link_graph6": "DFw", "links": 5,
        "joints": {"P1": [0, 3], "P2": [0, 4], "P3": [1, 3], "P4": [1, 4], "P5": [2, 3], "P6": [2, 4]},
        "link_degrees": [2, 2, 2, 3, 3], "automorphism_group_order": 12,
        "link_orbits": [[0, 1, 2], [3, 4]], "joint_orbits": [["P1", "P2", "P3", "P4", "P5", "P6"]],
        "planar": True, "assur_groups": 2, "slider_chains": 10, "assembly_modes": 6, "realization_count": 6,
    }]
    sevens = list(iter_objects(tmp_path / "trusses-7.jsonl"))
    assert [e["id"] for e in sevens] == ["7/N1", "7/N2", "7/N3"]
    assert [e["name"] for e in sevens] == ["7/B3", "7/B1", "7/B2"]
    assert sum(e["assur_groups"] for e in sevens) == 10


@pytest.mark.slow  # 14 s (2026-11-28)
def test_rerun_is_byte_identical_and_reuses_complete_files(tmp_path, capsys):
    # 3-7 links: with 9, the coupling-2 polynomials take about 13 minutes
    args = ["catalog", "--links", "3-7", "--out", str(tmp_path), "--workers", "2", "--slider-modes", "5"]
    assert main(args) == 0
    first = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    capsys.readouterr()
    assert main(args) == 0
    assert "reusing" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == first
    # one worker gives the same bytes
    assert main(["catalog", "--links", "3-7", "--out", str(tmp_path), "--force", "--workers", "1",
                 "--slider-modes", "5"]) == 0
    for name in ("trusses-3.jsonl", "trusses-5.jsonl", "trusses-7.jsonl", "slider-chains-3.jsonl", "slider-chains-5.jsonl"):
        assert (tmp_path / name).read_bytes() == first[name]


def test_truncated_file_is_recomputed(tmp_path):
    args = ["catalog", "--links", "7", "--out", str(tmp_path), "--quiet", "--slider-modes", "0"]
    assert main(args) == 0
    good = (tmp_path / "trusses-7.jsonl").read_bytes()
    (tmp_path / "trusses-7.jsonl").write_bytes(good[: len(good) // 2])
    assert main(args) == 0
    assert (tmp_path / "trusses-7.jsonl").read_bytes() == good
    assert not list(tmp_path.glob(".*.tmp"))


@pytest.mark.parametrize("workers", ["1", "2"])
def test_committed_small_catalogs_regenerate_byte_identically(tmp_path, workers):
    """In this process (one worker) and on an embedded Dask cluster (two), the same bytes:
    where the work ran does not show in the output (issue 20); no shard is left behind."""
    committed = REPO / "catalog"
    assert main(["catalog", "--links", "3-7", "--out", str(tmp_path), "--quiet", "--workers", workers,
                 "--no-crosscheck", "--slider-modes", "5"]) == 0
    for name in ["trusses-3.jsonl", "trusses-5.jsonl", "trusses-7.jsonl", "slider-chains-3.jsonl", "slider-chains-5.jsonl"]:
        assert (tmp_path / name).read_bytes() == (committed / name).read_bytes(), name
    assert not (tmp_path / ".shards").exists()
    if workers == "2":
        return
    # the 386 slider chains of 7 links take minutes: a sample, recomputed one by one
    from baranov.catalog.slider_chains import slider_chain_entry

    sevens = {e["id"]: e["link_graph6"] for e in list(iter_objects(committed / "trusses-7.jsonl"))}
    chains = list(iter_objects(committed / "slider-chains-7.jsonl"))
    for chain in chains[::40]:
        entry = slider_chain_entry((sevens[chain["truss"]], tuple(chain["sliders"]), "msolve_agrees" in chain))
        assert {"truss": chain["truss"], "truss_name": chain["truss_name"], **entry} == chain


@pytest.mark.slow
def test_committed_catalog_regenerates_byte_identically(tmp_path):
    """All of `make catalog` (about 12 minutes: the coupling-2 nine-link polynomials). The
    nine-link slider chains, the 15-link census and the 13-link compact file are opt-in
    (`--slider-modes 9`, `make catalog-15`, `make catalog-13-modes`): their committed files
    (and the 13-link cross-check) are carried over, as `make catalog` leaves them, and enter
    the summary."""
    committed = REPO / "catalog"
    for opt_in in [committed / "slider-chains-9.jsonl", *committed.glob("census-*.json"),
                   *committed.glob("trusses-*.jsonl.gz")]:  # the 13-link one: catalog/publish.py
        if opt_in.exists():
            (tmp_path / opt_in.name).write_bytes(opt_in.read_bytes())
    published = {links: check for links, check in json.loads((committed / "crosscheck.json").read_text()).items()
                 if int(links) > 11}  # published with their compact files; 3-11 are recomputed
    if published:
        (tmp_path / "crosscheck.json").write_text(json.dumps(published))
    assert main(["catalog", "--links", "3-11", "--out", str(tmp_path), "--quiet", "--workers", "2"]) == 0
    for name in ["trusses-3.jsonl", "trusses-5.jsonl", "trusses-7.jsonl", "trusses-9.jsonl", "trusses-11.jsonl",
                 "slider-chains-3.jsonl", "slider-chains-5.jsonl", "slider-chains-7.jsonl"]:
        assert (tmp_path / name).read_bytes() == (committed / name).read_bytes(), name
    if find_geng() is not None:  # the summary records the cross-check, which needs geng
        assert (tmp_path / "summary.md").read_bytes() == (committed / "summary.md").read_bytes()
        assert (tmp_path / "crosscheck.json").read_bytes() == (committed / "crosscheck.json").read_bytes()


def test_summary_is_printed(tmp_path):
    result = run("catalog", "--links", "3,5", "--out", str(tmp_path), "--quiet")
    assert result.returncode == 0
    assert "| 5 | 1 |" in result.stdout
    assert result.stderr == ""


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--links", "4"], "--links 4: a Baranov truss has an odd number of links, at least 3"),
        (["--links", "1"], "--links 1: a Baranov truss has an odd number of links"),
        (["--links", "x"], "--links x: expected odd link counts"),
        (["--links", "3,x"], "--links 3,x: expected odd link counts"),
        (["--links", "17"], "--links 17: the catalog goes up to 15 links"),
        (["--workers", "0"], "--workers 0: must be at least 1"),
        (["--bogus"], "unrecognized arguments: --bogus"),
    ],
)
def test_bad_input_is_one_line_exit_2_nothing_written(tmp_path, args, message):
    out = tmp_path / "out"
    result = run("catalog", "--out", str(out), *args)
    assert result.returncode == 2
    assert result.stderr.startswith(f"baranov: error: {message}")
    assert result.stderr.count("\n") == 1
    assert "Traceback" not in result.stderr
    assert result.stdout == ""
    assert not out.exists()


def test_unwritable_out_is_one_line_exit_2(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    result = run("catalog", "--links", "3", "--out", str(blocker / "catalog"))
    assert result.returncode == 2
    assert result.stderr.startswith(f"baranov: error: --out {blocker / 'catalog'}: cannot write there")
    assert result.stderr.count("\n") == 1
    assert blocker.read_text() == "x"


def test_no_command_is_an_error():
    result = run()
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1


def test_show_thesis_truss_in_thesis_numbering():
    result = run("show", "5/B1", "--reference", "P1,P6")
    assert result.returncode == 0, result.stderr
    assert "automorphism group order 12" in result.stdout
    assert "coupling degree 1" in result.stdout
    assert "s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6" in result.stdout


def test_show_latex_catalog_id_graph6_and_file(tmp_path):
    latex = run("show", "5/B1", "--reference", "P1,P6", "--latex")
    assert r"s_{2,5} = \det\left(I - Z_{1,3,2} Z_{1,6,3} - Z_{6,4,5} Z_{6,1,4}\right) s_{1,6}" in latex.stdout
    by_id = run("show", "7/N2", "--catalog", str(REPO / "catalog"))
    assert by_id.returncode == 0 and by_id.stdout.startswith("7/N2 (7/B1)")
    assert run("show", "DFw").stdout.startswith("DFw — the catalog's 5/N1 (5/B1)\nlinks 5, joints 6")
    edges = tmp_path / "pentad.txt"
    edges.write_text("# the pentad\n0 2\n0 3\n0 4\n1 2\n1 3\n1 4\n")
    assert "coupling degree 1" in run("show", str(edges)).stdout
    links = tmp_path / "triad.json"
    links.write_text('{"links": [["P1", "P2"], ["P2", "P3"], ["P3", "P1"]]}')
    assert "coupling degree 0" in run("show", str(links)).stdout
    assert "plan 3 of 3" in run("show", "7/B3", "--plans", "3").stdout


def test_show_reads_a_scene_file_as_its_linkage():
    """``baranov show examples/7-B1.json`` (a scene) shows its chain and plans; it was
    read as a chain file and refused ("joint name: lies on 7 links")."""
    result = run("show", str(REPO / "examples" / "7-B3-section-4.2.1.json"))
    assert result.returncode == 0, result.stderr
    assert "links 7, joints 9" in result.stdout and "parameters s1,6" in result.stdout
    sliders = run("show", str(REPO / "examples" / "7-B3-sliders-P8-P9.json"))
    assert sliders.returncode == 0, sliders.stderr
    assert "slider joints: P8, P9 (an Assur kinematic chain derived from this truss" in sliders.stdout
    assert "solve it with --method msolve" not in sliders.stdout  # every backend solves sliders now


def test_show_sliders_prints_the_thesis_substitutions_and_case():
    """``baranov show <truss> --sliders …`` (issue 17): the slider plan, the truss's closure
    conditions, the substitutions d_{i,j} = δ + d_{i′,j} sin α of thesis §4.2.2 and the
    case of each slider; on the §4.2.3 scene the cosine theorem with the angle between the
    two axes, and the order of the limits."""
    one = run("show", str(REPO / "examples" / "7-B3-slider-P9.json"))
    assert one.returncode == 0, one.stderr
    for line in ("P9 (δ1): P9′ on link t569, P9″ on link t789; §4.2.2", "d5,9 = δ1 + d5,9′ sin α1",
                 "d7,9 = δ1 + d7,9″ sin α3", "closure: the leading coefficient of each condition as δ1 → ∞"):
        assert line in one.stdout
    two = run("show", str(REPO / "examples" / "7-B3-sliders-P8-P9.json")).stdout
    assert "s8,9 = d7,8² + d7,9² − 2 d7,8 d7,9 cos ∠P8∞P7P9∞" in two and "δ1 → ∞ then δ2 → ∞" in two
    end = run("show", str(REPO / "examples" / "7-B3-slider-P1.json")).stdout
    assert "parameters t1,6" in end and "§4.2.4: it ends the variable segment, so the unknown is t1,6" in end
    by_name = run("show", "7/B1", "--sliders", "P4")
    assert by_name.returncode == 0 and "slider joints: P4" in by_name.stdout and "δ1 → ∞" in by_name.stdout
    unsuited = run("show", "9/N3", "--sliders", "P5,P6,P11").stdout  # every 7-link chain has a plan now
    assert "none of the 46 best plans suits these sliders (the best: step P5 from P11, P6: three sliders)" in unsuited


def test_show_count_counts_the_modes_and_checks_them_on_the_plan():
    """``baranov show 7/B1 --count``: the catalog's count (characteristic degree on random
    instances) and, with msolve, the same number from the best plan as one system; for a
    slider chain its own count."""
    result = run("show", "7/B1", "--count")
    assert result.returncode == 0, result.stderr
    assert "assembly modes over C: 14 (degree of the characteristic polynomial" in result.stdout
    if find_msolve() is not None:
        assert "best plan as one polynomial system modulo random primes: 14 (the same;" in result.stdout
    else:
        assert "not checked on the best plan's system: msolve not found" in result.stdout
    sliders = run("show", "7/B1", "--sliders", "P8,P9", "--count")
    assert sliders.returncode == 0, sliders.stderr
    assert "assembly modes over C: 12 (slider chain" in sliders.stdout


@pytest.mark.parametrize("name", ["7/b1", "7-B1", "7-b1"])
def test_show_takes_a_truss_name_in_any_case_and_with_a_dash(name, capsys):
    """Issue 57: `show 7/b1` was refused with "did you mean 7/B1?", and `show 7-B1` (the
    examples' file names) read as graph6."""
    assert main(["show", name]) == 0
    assert capsys.readouterr().out.startswith("7/B1")


def test_show_titles_a_catalog_id_once(capsys):
    """Issue 57: `show 11/N123` printed "11/N123 (11/N123)"."""
    assert main(["show", "11/N123"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == "11/N123"


@pytest.mark.parametrize(("example", "title"), [
    ("9-B28.json", "the catalog's 9/N28 (9/B28)"),
    ("7-B1.json", "the catalog's 7/N2 (7/B1)"),
    ("11-watt-baranov.json", "the catalog's 11/N64, the Watt–Baranov truss of thesis §3.6.2.1"),
    ("13-watt-baranov.json", "the catalog's 13/N206, the Watt–Baranov truss of thesis §3.6.2.2"),
])
def test_show_of_a_file_names_the_catalog_truss(example, title, capsys):
    """Issue 57: a truss read from a file is named by the catalog truss isomorphic to it
    (canonical link graphs), and the Watt–Baranov trusses by the literature's name: this
    checks LITERATURE_NAMES against the thesis's examples."""
    assert main(["show", str(REPO / "examples" / example)]) == 0
    assert capsys.readouterr().out.splitlines()[0] == f"{REPO / 'examples' / example} — {title}"


def test_show_names_the_watt_baranov_truss_by_its_id(capsys):
    assert main(["show", "11/N64"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == "11/N64 — the Watt–Baranov truss of thesis §3.6.2.1"


def test_show_takes_a_thesis_name_without_its_link_count_where_unique(capsys):
    assert main(["show", "B28"]) == 0
    assert capsys.readouterr().out.startswith("9/B28")


def test_show_finds_catalog_names_from_any_folder(tmp_path):
    """The catalog is package data: a name identified only in catalog/trusses-9.jsonl (9/B5)
    resolves wherever the command runs."""
    result = subprocess.run([sys.executable, "-m", "baranov.cli", "show", "9/B5"], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0 and result.stdout.startswith("9/N4 (9/B5)")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["9/B29"], "9/B29: no such truss in the catalog (names 9/B1, 9/B2, 9/B3 …; ids 9/N1..9/N28)"),
        (["B1"], "B1: several thesis trusses have this name: 3/B1, 5/B1, 7/B1, 9/B1"),
        (["zzz"], "graph6 'zzz': not a valid graph6 string"),
        (["5/B1", "--reference", "P1,P9"], "joint P9: no such joint in this chain"),
        (["5/B1", "--reference", "P1"], "--reference P1: two joints, e.g. P2,P3"),
        (["5/B1", "--parameter", "P1,P2"], "no bilateration plan meets"),
        (["5/B1", "--plans", "0"], "--plans 0: must be at least 1"),
        (["Cl"], "mobility F = 3(L-1) - 2J = 1"),  # graph6 of a four-bar linkage
        (["7/B1", "--sliders", "P1,P12"], "--sliders P1,P12: P12 is no joint of this chain"),
        (["3/B1", "--sliders", "P1,P2,P3"], "--sliders P1,P2,P3: they close the loop of links"),
    ],
)
def test_show_bad_input(args, message):
    result = run("show", *args)
    assert result.returncode == 2
    assert result.stderr.startswith("baranov: error: ") and message in result.stderr
    assert result.stderr.count("\n") == 1 and result.stdout == ""


def test_solve_table_and_json():
    table = run("solve", str(REPO / "examples" / "5-B1.json"))
    assert table.returncode == 0 and "coupling degree 1, 6 assembly modes (numeric)" in table.stdout
    data = json.loads(run("solve", str(REPO / "examples" / "3-B1.json"), "--json").stdout)
    assert data["method"] == "numeric" and data["coupling_degree"] == 0 and data["parameters"] == []
    points = sorted(tuple(round(c, 9) for c in m["joints"]["P3"]) for m in data["assembly_modes"])
    assert points == [(1.8, 7.4), (5.4, 3.8)]
    assert all(m["max_residual"] < 1e-12 and len(m["signs"]) == 1 for m in data["assembly_modes"])


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (None, "cannot read"),
        ("{not json", "not valid JSON"),
        ('{"links": []}', "scene: \"links\" is empty"),
        ('{"links": [{"name": "a", "joints": ["P1", "P2"], "squared_length": 0}], "ground": "a"}',
         "link a: squared distance P1,P2 = 0 must be positive"),
    ],
)
def test_solve_bad_input(tmp_path, content, message):
    path = tmp_path / "scene.json"
    if content is not None:
        path.write_text(content)
    result = run("solve", str(path))
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.startswith("baranov: error: ") and message in result.stderr
    assert result.stderr.count("\n") == 1


def test_solve_plot_writes_a_png(tmp_path):
    target = tmp_path / "modes.png"
    result = run("solve", str(REPO / "examples" / "5-B1.json"), "--plot", str(target))
    assert result.returncode == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert result.stderr == f"wrote {target}\n"  # issue 57: it said nothing
    assert not list(tmp_path.glob(".*.tmp"))
    missing = run("solve", str(REPO / "examples" / "5-B1.json"), "--plot", str(tmp_path / "no" / "x.png"))
    assert missing.returncode == 2 and "does not exist" in missing.stderr
    # issue 57: a .jpg name had been given PNG bytes
    jpeg = run("solve", str(REPO / "examples" / "5-B1.json"), "--plot", str(tmp_path / "modes.jpg"))
    assert jpeg.returncode == 2 and "give the file a .png name" in jpeg.stderr and not (tmp_path / "modes.jpg").exists()


def test_exact_solve_says_what_it_certifies():
    """The exact backend prints its certificate (docs/exact.md, "What the exact backend
    guarantees") and puts it in the JSON."""
    example = Path(__file__).resolve().parents[1] / "examples" / "7-B1.json"
    result = run("solve", str(example), "--method", "exact")
    assert result.returncode == 0, result.stderr
    assert "assembly modes: certified complete" in result.stdout
    data = json.loads(run("solve", str(example), "--method", "exact", "--json").stdout)
    assert data["certificate"] == {"complete": True, "probabilistic": None, "gaps": []}


def test_exact_solve_names_a_double_root():
    """3-RPR-I (thesis §5.1.3.1): degree 6 with a double real root at s1,5 = 49 and one
    mode; the output says why there are two roots and one mode (issue 26)."""
    result = run("solve", str(REPO / "examples" / "3-RPR-I.json"), "--method", "exact")
    assert result.returncode == 0, result.stderr
    assert ("characteristic polynomial in s1,5: degree 6, 2 real roots counted with multiplicity "
            "(1 distinct; 49 double: modes merge there)") in result.stdout


def test_characteristic_lines_name_roots_without_modes():
    """A real root of the norm whose configurations are complex on every branch gives
    no mode, and the output says so (a solution with its modes removed stands in)."""
    from dataclasses import replace

    from baranov.cli.output import characteristic_lines
    from baranov.scene import load_scene
    from baranov.solvers import solve

    solution = solve(load_scene(REPO / "examples" / "5-B1.json"), method="exact")
    lines = characteristic_lines(replace(solution, assembly_modes=solution.assembly_modes[1:]))
    assert lines[0].endswith("degree 6, 6 real roots, isolated in certified enclosures")
    first = solution.assembly_modes[0].parameters["s1,5"]
    assert lines[1].startswith("  monic: s1,5⁶ − 283.8018265 s1,5⁵")  # thesis §3.2.3 prints −283.8018
    assert lines[2].startswith(f"1 real root ({first:.10g}) gives no assembly mode")


@pytest.mark.parametrize("args", [["--time-limit", "5", "--method", "exact"], ["--time-limit", "0"],
                                  ["--time-limit", "-1"]])
def test_time_limit_is_positive_and_numeric_only(args):
    result = run("solve", str(REPO / "examples" / "7-B1.json"), *args)
    assert result.returncode == 2
    assert result.stderr.startswith(f"baranov: error: --time-limit {args[1]}: a positive number of seconds")
    assert result.stderr.count("\n") == 1 and result.stdout == ""


@pytest.mark.parametrize("example", ["3-B1", "5-B1", "7-B1", "9-B28", "3-RPR-I", "3-RPR-II", "3-RPR-IV", "11-watt-baranov"])
def test_solve_output_fits_100_columns(example, capsys):
    """The default table (mode, parameters, signs, residual) and the --joints listing stay
    within 100 columns (rows of 206 and 288 columns before; the undecided sentences of
    3-RPR-I and II are wrapped); --format csv has a column per
    joint coordinate and a row per mode."""
    path = str(REPO / "examples" / f"{example}.json")
    for extra in ([], ["--joints"]):
        assert main(["solve", path, *extra]) == 0
        out = capsys.readouterr().out
        assert max(len(line) for line in out.splitlines()) <= 100, out
    assert main(["solve", path, "--format", "csv"]) == 0
    rows = list(__import__("csv").reader(capsys.readouterr().out.splitlines()))
    header, body = rows[0], rows[1:]
    assert header[0] == "mode" and header[-1].endswith("_y") and all(len(row) == len(header) for row in body)


def test_a_catalog_folder_of_an_earlier_version_is_converted_not_recomputed(tmp_path, capsys):
    """Before JSON lines (issue 20) a catalog file was a JSON list, ``trusses-<L>.json``:
    such a folder is reused, its files rewritten as JSON lines, byte-identical to a fresh
    run's, and the old files removed."""
    committed = REPO / "catalog"
    for name in ("trusses-7", "slider-chains-5"):
        objects = list(iter_objects(committed / f"{name}.jsonl"))
        (tmp_path / f"{name}.json").write_text(json.dumps(objects, indent=1))
    assert main(["catalog", "--links", "7", "--out", str(tmp_path), "--no-crosscheck", "--slider-modes", "0"]) == 0
    assert "7 links: reusing" in capsys.readouterr().err
    assert (tmp_path / "trusses-7.jsonl").read_bytes() == (committed / "trusses-7.jsonl").read_bytes()
    assert not (tmp_path / "trusses-7.json").exists()
    assert (tmp_path / "slider-chains-5.json").exists()  # not asked for (5 links): left as it was


def test_catalog_files_are_read_line_by_line(tmp_path):
    """Each line of a catalog file is one complete JSON object (a reader can stream it);
    a line cut short is reported with its number."""
    path = REPO / "catalog" / "trusses-9.jsonl"
    lines = path.read_text().splitlines()
    assert [json.loads(line)["id"] for line in lines] == [f"9/N{i}" for i in range(1, 29)]
    from baranov.catalog.files import load_complete_objects

    assert load_complete_objects(path, ("id",)) == [json.loads(line) for line in lines]
    broken = tmp_path / "trusses-9.jsonl"
    broken.write_text("\n".join(lines[:3] + [lines[3][:40]]))
    with pytest.raises(ValueError, match="line 4: not JSON"):
        list(iter_objects(broken))
    assert load_complete_objects(broken, ("id",)) is None


def test_assembly_modes_are_counted_up_to_the_links_asked(tmp_path, capsys):
    """``--assembly-modes L`` (issue 20: 13 links are opt-in): below L no counts, and a
    file written without them is recomputed, not reused, once they are asked for."""
    args = ["catalog", "--links", "7", "--out", str(tmp_path), "--no-crosscheck", "--slider-modes", "0", "--quiet"]
    assert main([*args, "--assembly-modes", "5"]) == 0
    entries = list(iter_objects(tmp_path / "trusses-7.jsonl"))
    assert [(e["assembly_modes"], e["realization_count"]) for e in entries] == [(None, None)] * 3
    assert entries[0]["assembly_modes_evidence"].startswith("not derived: 7 links (baranov catalog --assembly-modes")
    assert main(args) == 0
    assert (tmp_path / "trusses-7.jsonl").read_bytes() == (REPO / "catalog" / "trusses-7.jsonl").read_bytes()
    assert main([*args, "--assembly-modes", "-1"]) == 2
    assert "--assembly-modes -1: a number of links" in capsys.readouterr().err


def test_a_compact_gzip_file_beside_the_full_one_from_13_links(tmp_path, monkeypatch):
    """From 13 links on (here lowered to 7), ``trusses-<L>.jsonl.gz`` holds the compact
    fields of every entry, byte-identical from run to run (issue 20: the committed 13-link
    results)."""
    import baranov.catalog.build as build
    from baranov.catalog.entries import COMPACT_FIELDS

    monkeypatch.setattr(build, "COMPACT_FROM_LINKS", 7)
    args = ["catalog", "--links", "5,7", "--out", str(tmp_path), "--no-crosscheck", "--slider-modes", "0", "--quiet"]
    assert main(args) == 0
    assert not (tmp_path / "trusses-5.jsonl.gz").exists()
    compact = list(iter_objects(tmp_path / "trusses-7.jsonl.gz"))
    full = list(iter_objects(tmp_path / "trusses-7.jsonl"))
    assert compact == [{field: entry[field] for field in COMPACT_FIELDS} for entry in full]
    first = (tmp_path / "trusses-7.jsonl.gz").read_bytes()
    assert main(args) == 0
    assert (tmp_path / "trusses-7.jsonl.gz").read_bytes() == first


@pytest.mark.parametrize("method, sentence", [
    ("exact", "the linkage cannot be assembled with these dimensions (certified)"),
    ("numeric", "the linkage cannot be assembled with these dimensions (certified)"),
    pytest.param("msolve", "no assembly mode found; that none exists is not proven",
                 marks=pytest.mark.skipif(find_msolve() is None, reason="msolve not installed")),
])
def test_no_mode_is_called_unassemblable_only_with_a_proof(tmp_path, method, sentence, capsys):
    """A triad whose two arms (√20 + √2 < √50) cannot reach across the ground: the exact
    and numeric backends prove it (a complete certificate); msolve, whose answer carries
    no certificate, says only that it found no mode (issue 55)."""
    scene = tmp_path / "short-arms.json"
    scene.write_text(json.dumps({"ground": "ground", "links": [
        {"name": "ground", "joints": {"P1": [1, 3], "P2": [6, 8]}},
        {"name": "b13", "joints": ["P1", "P3"], "squared_length": 20},
        {"name": "b23", "joints": ["P2", "P3"], "squared_length": 2}]}))
    assert main(["solve", str(scene), "--method", method]) == 0
    assert sentence in capsys.readouterr().out


def test_solve_help_lists_every_method():
    """Issue 57: `solve --help` named numeric, exact and msolve only; homotopy appeared in
    the error for `--method foo` alone."""
    from baranov.solvers.backends import available_backends

    result = run("solve", "--help")
    text = " ".join(result.stdout.split())
    assert result.returncode == 0 and all(f"{name}:" in text for name in available_backends())


@pytest.mark.parametrize("method", ["numeric", "exact"])
def test_solve_in_the_thesis_parameter(method, capsys):
    """Issue 57: 7/B1's modes in s2,3, as thesis §3.3 publishes them (the best plan's
    parameter is s1,4)."""
    assert main(["solve", str(REPO / "examples" / "7-B1.json"), "--parameter", "P2,P3", "--method", method]) == 0
    out = capsys.readouterr().out
    assert "coupling degree 1, 8 assembly modes" in out and "s2,3" in out and "39.83534598" in out


def test_show_of_an_unknown_name_says_what_it_takes(capsys):
    """Issue 57: `show foo` said only "graph6 'foo': not a valid graph6 string"."""
    assert main(["show", "foo"]) == 2
    assert "foo: not a truss name (e.g. 9/B28, 7-b1, 11/N123), an existing file, or a valid graph6 string" in \
        capsys.readouterr().err


def test_a_baseline_reports_the_coupling_degree_and_flags_what_does_not_verify(capsys):
    """Issue 57: `--method cartesian` printed "coupling degree 0" and rows at residual
    1.0 without a word; `loop-equations` said coupling degree 0 for a chain of degree 1."""
    assert main(["solve", str(REPO / "examples" / "7-B1.json"), "--method", "cartesian"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].startswith(f"{REPO / 'examples' / '7-B1.json'}: coupling degree 1,")
    rows = [line for line in out.splitlines() if re.fullmatch(r" *\d+ +\d\.\de[-+]\d\d", line)]
    unverified = sum(float(row.split()[-1]) >= 1e-8 for row in rows)
    assert unverified > 0 and f"{unverified} of {len(rows)} rows are not assembly modes" in out
    assert main(["solve", str(REPO / "examples" / "7-B1.json"), "--method", "loop-equations"]) == 0
    out = capsys.readouterr().out
    assert "coupling degree 1, 8 assembly modes (loop-equations)" in out and "are not assembly modes" not in out


def test_solve_holds_a_crank_given_its_angle(tmp_path, capsys):
    """Issue 57 friction 2: a one-DOF scene whose crank input has "degrees" is solved with
    the crank held there (its two configurations, the crank's tip at 30°), where solve
    had refused it for its mobility; without a value it is still refused, pointing to
    trace and to "degrees"."""
    data = json.loads((REPO / "examples" / "four-bar-coupler-point.json").read_text())
    data["inputs"][0]["degrees"] = 30
    path = tmp_path / "held.json"
    path.write_text(json.dumps(data))
    assert main(["solve", str(path), "--json"]) == 0
    modes = json.loads(capsys.readouterr().out)["assembly_modes"]
    assert len(modes) == 2
    for mode in modes:
        assert mode["joints"]["P1"] == [0.0, 0.0]
        assert mode["joints"]["P2"] == pytest.approx([3 ** 0.5, 1.0], abs=1e-12)
    assert main(["solve", str(path)]) == 0
    assert "input crank held at 30°" in capsys.readouterr().out
    assert main(["solve", str(REPO / "examples" / "four-bar-coupler-point.json")]) == 2
    assert 'or hold its crank by giving its input "degrees"' in capsys.readouterr().err
