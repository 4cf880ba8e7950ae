"""Bad input, systematically (issue 22): every case below is run through the CLI as a user
would (``baranov ...`` in a scratch folder), and must give exit code 2, one line on stderr
starting ``baranov: error:``, no traceback, and leave the folder as it was.

``docs/input-errors.md`` is this table with the messages of a real run; regenerate it
with ``python tests/test_input_errors.py`` (a test checks that it is current).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from baranov.cli.main import main

REPO = Path(__file__).resolve().parents[1]
TRIAD = json.loads((REPO / "examples" / "3-B1.json").read_text(encoding="utf-8"))
PENTAD = json.loads((REPO / "examples" / "5-B1.json").read_text(encoding="utf-8"))
DOC = REPO / "docs" / "input-errors.md"


def _changed(example: dict, change) -> str:
    """``example`` (JSON data) with ``change`` applied to a copy, as text."""
    data = json.loads(json.dumps(example))
    change(data)
    return json.dumps(data)


def _triad(change) -> str:
    return _changed(TRIAD, change)


def _pentad(change) -> str:
    return _changed(PENTAD, change)


def _set(path: tuple, value):
    def change(data):
        target = data
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
    return change


def _delete(path: tuple):
    def change(data):
        target = data
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]
    return change


@dataclass(frozen=True)
class Case:
    """A bad input: what the user did, the files it needs, the command line."""

    what: str
    argv: tuple[str, ...]
    files: tuple[tuple[str, str], ...] = ()


def _scene(what: str, text: str) -> Case:
    return Case(what, ("solve", "scene.json"), (("scene.json", text),))


FOUR_BAR = {"links": [{"name": "g", "joints": {"P1": [0, 0], "P2": [4, 0]}},
                      {"name": "a", "joints": ["P1", "P3"], "squared_length": 1},
                      {"name": "b", "joints": ["P2", "P4"], "squared_length": 9},
                      {"name": "c", "joints": ["P3", "P4"], "squared_length": 16}], "ground": "g"}

CASES = [
    # scene files: syntax and structure
    _scene("not JSON", "{\"links\": ["),
    _scene("an empty file", ""),
    _scene("a JSON list instead of an object", "[1, 2]"),
    _scene("\"links\" not a list", json.dumps({"links": {}, "ground": "g"})),
    _scene("no ground", _triad(_delete(("ground",)))),
    _scene("a ground that is no link", _triad(_set(("ground",), "base"))),
    _scene("a misspelt top-level key", _triad(lambda d: d.update(grund=d.pop("ground")))),
    _scene("a misspelt link key", _triad(lambda d: d["links"][1].update(
        squared_lenght=d["links"][1].pop("squared_length")))),
    _scene("a link that is not an object", _triad(_set(("links", 1), "b13"))),
    _scene("a link without joints", _triad(_delete(("links", 1, "joints")))),
    _scene("joints as a string", _triad(_set(("links", 1, "joints"), "P1 P3"))),
    _scene("a joint with one coordinate", _triad(_set(("links", 0, "joints", "P1"), [1]))),
    _scene("a coordinate that is not a number", _triad(_set(("links", 0, "joints", "P1"), ["one", 3]))),
    _scene("a coordinate true", _triad(_set(("links", 0, "joints", "P1"), [True, 3]))),
    _scene("NaN in a file", _triad(lambda d: None).replace("[1, 3]", "[NaN, 3]")),
    _scene("Infinity in a file", _triad(lambda d: None).replace("[1, 3]", "[Infinity, 3]")),
    _scene("a rational with a zero denominator", _triad(_set(("links", 1, "squared_length"), "20/0"))),
    # scene files: values and geometry
    _scene("a negative squared length", _triad(_set(("links", 1, "squared_length"), -20))),
    _scene("a zero squared length", _triad(_set(("links", 1, "squared_length"), 0))),
    _scene("a squared length of 1e300", _triad(_set(("links", 1, "squared_length"), 1e300))),
    _scene("a squared length of 1e-120", _triad(_set(("links", 1, "squared_length"), 1e-120))),
    _scene("two joints of the ground at one point", _triad(_set(("links", 0, "joints", "P2"), [1, 3]))),
    _scene("squared_length on a ternary link", _pentad(_set(("links", 0, "squared_length"), 50))),
    _scene("a missing squared distance", _pentad(_delete(("links", 0, "squared_distances", "P2,P3")))),
    _scene("a squared-distance key that is no pair", _pentad(lambda d: d["links"][0]["squared_distances"].update(
        {"P1P2": d["links"][0]["squared_distances"].pop("P1,P2")}))),
    _scene("a squared distance to a joint of another link", _pentad(lambda d: d["links"][0]["squared_distances"].update(
        {"P1,P4": 3}))),
    _scene("a ternary link without orientation", _pentad(_delete(("links", 1, "orientation")))),
    _scene("an orientation other than cw/ccw", _pentad(_set(("links", 1, "orientation"), "clockwise"))),
    _scene("the triangle inequality violated", _pentad(_set(("links", 1, "squared_distances", "P5,P6"), 500))),
    # scene files: topology
    _scene("two links of one name", _triad(_set(("links", 2, "name"), "b13"))),
    _scene("a dangling joint", _triad(_set(("links", 2, "joints"), ["P2", "P9"]))),
    _scene("a joint on three links", _triad(lambda d: d["links"].append(
        {"name": "extra", "joints": ["P3", "P1"], "squared_length": 20}))),
    _scene("a mobile chain (a four-bar) given to solve", json.dumps(FOUR_BAR)),
    _scene("inputs given to a rigid linkage", _triad(_set(("inputs",), [{"name": "crank", "distance": ["P1", "P4"]}]))),
    _scene("more inputs than the mobility", json.dumps({**FOUR_BAR, "inputs": [
        {"name": "crank", "angle": ["P1", "P2", "P3"]}, {"name": "rocker", "angle": ["P2", "P1", "P4"]}]})),
    _scene("an angle input between joints of one link", json.dumps({**FOUR_BAR, "inputs": [
        {"name": "crank", "angle": ["P1", "P3", "P4"], "degrees": 30}]})),
    _scene("a distance input that a link fixes", json.dumps({**FOUR_BAR, "inputs": [
        {"name": "stroke", "distance": ["P3", "P4"], "squared_distance": 20}]})),
    _scene("an input value in the wrong unit", json.dumps({**FOUR_BAR, "inputs": [
        {"name": "crank", "angle": ["P1", "P2", "P3"], "squared_distance": 20}]})),
    # files and flags of solve
    Case("a scene file that does not exist", ("solve", "missing.json")),
    Case("a folder given as the scene", ("solve", "folder"), (("folder/keep", ""),)),
    Case("an unknown method", ("solve", "scene.json", "--method", "groebner"), (("scene.json", json.dumps(TRIAD)),)),
    Case("a negative time limit", ("solve", "scene.json", "--time-limit", "-1"), (("scene.json", json.dumps(TRIAD)),)),
    Case("a time limit for the exact method", ("solve", "scene.json", "--method", "exact", "--time-limit", "5"),
         (("scene.json", json.dumps(TRIAD)),)),
    Case("a plot into a missing folder", ("solve", "scene.json", "--plot", "no/such/modes.png"),
         (("scene.json", json.dumps(TRIAD)),)),
    Case("a plot named as another format", ("solve", "scene.json", "--plot", "modes.jpg"),
         (("scene.json", json.dumps(TRIAD)),)),
    # truss names and show
    Case("a thesis name that does not exist", ("show", "9/B29")),
    Case("a thesis name without its link count that several trusses have", ("show", "B1")),
    Case("an even link count", ("show", "8/N1")),
    Case("an id beyond the catalog", ("show", "7/N4")),
    Case("zero plans", ("show", "7/B1", "--plans", "0")),
    Case("a reference that is not a pair", ("show", "7/B1", "--reference", "P1")),
    Case("a chain file that is not JSON", ("show", "chain.json"), (("chain.json", "{oops"),)),
    # catalog
    Case("an even link count", ("catalog", "--links", "4", "--out", "out")),
    Case("more links than the catalog goes to", ("catalog", "--links", "17", "--out", "out")),
    Case("link counts that are no numbers", ("catalog", "--links", "three", "--out", "out")),
    Case("a descending range", ("catalog", "--links", "9-3", "--out", "out")),
    Case("zero workers", ("catalog", "--links", "3", "--workers", "0", "--out", "out")),
    Case("an output folder under a file", ("catalog", "--links", "3", "--out", "blocker/catalog"),
         (("blocker", "a file"),)),
    # the command line itself
    # baranov trace (one-degree-of-freedom chains)
    Case("a rigid chain given to trace", ("trace", "scene.json"), (("scene.json", json.dumps(TRIAD)),)),
    Case("trace: an eta triangle of two joints", ("trace", "scene.json", "--eta", "P1,P2"),
         (("scene.json", json.dumps(FOUR_BAR)),)),
    Case("trace: an unknown tracer joint", ("trace", "scene.json", "--tracer", "P9"),
         (("scene.json", json.dumps(FOUR_BAR)),)),
    Case("trace: --joints without --input", ("trace", "scene.json", "--joints"),
         (("scene.json", json.dumps(FOUR_BAR)),)),
    Case("trace: a chord tolerance of 0", ("trace", "scene.json", "--chord", "0"),
         (("scene.json", json.dumps(FOUR_BAR)),)),
    Case("trace: a tracer point on no link of the scene", ("trace", "scene.json"),
         (("scene.json", json.dumps({**FOUR_BAR, "tracers": [{"name": "C", "link": "d", "at": [1, 2]}]})),)),
    # baranov explore (the live page: checked before the server starts)
    Case("explore: a scene file that does not exist", ("explore", "missing.json", "--no-browser")),
    Case("explore: an unknown method", ("explore", "scene.json", "--method", "groebner", "--no-browser"),
         (("scene.json", json.dumps(TRIAD)),)),
    Case("explore: a port out of range", ("explore", "scene.json", "--port", "70000", "--no-browser"),
         (("scene.json", json.dumps(TRIAD)),)),
    Case("explore: a robot file without actuators", ("explore", "robot.json", "--no-browser"),
         (("robot.json", json.dumps({"legs": [{"type": "RpR", "base": [0, 0], "platform": [0, 0]},
                                               {"type": "RpR", "base": [4, 0], "platform": [6, 0]},
                                               {"type": "RpR", "base": [1, 8], "platform": [3, 4]}]})),)),
    Case("no command", ()),
    Case("an unknown command", ("draw", "7/B1")),
    Case("an unknown option", ("solve", "scene.json", "--exact"), (("scene.json", json.dumps(TRIAD)),)),
]


def _listing(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() if p.is_file() else b"/"
            for p in sorted(folder.rglob("*"))}


def run_case(case: Case, folder: Path) -> tuple[int, str, dict, dict]:
    """Run ``baranov`` on ``case`` in ``folder``: exit code, stderr, and the folder's
    contents before and after."""
    for name, text in case.files:
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text, encoding="utf-8")
    before = _listing(folder)
    stderr, previous = io.StringIO(), Path.cwd()
    os.chdir(folder)
    try:
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            try:
                code = main(list(case.argv))
            except SystemExit as stop:  # argparse's own exits, if any
                code = stop.code
    finally:
        os.chdir(previous)
    return code, stderr.getvalue(), before, _listing(folder)


@pytest.mark.parametrize("case", CASES, ids=[f"{n:02d}-{c.what}" for n, c in enumerate(CASES, 1)])
def test_bad_input_gives_one_line_and_exit_2(case, tmp_path):
    code, stderr, before, after = run_case(case, tmp_path)
    assert code == 2, stderr
    assert stderr.startswith("baranov: error: ") and stderr.count("\n") == 1, stderr
    assert "Traceback" not in stderr
    assert after == before, "the folder changed"


def test_there_are_at_least_forty_cases():
    assert len(CASES) >= 40


def render_table(folder: Path) -> str:
    """docs/input-errors.md: every case with the message of a real run."""
    lines = ["# Input errors", "",
             "Generated by `python tests/test_input_errors.py` from the cases of that test (each: exit",
             "code 2, this one line on stderr, no traceback, nothing written). Scene cases run",
             "`baranov solve scene.json` on the 3/B1 or 5/B1 example with one thing changed.", "",
             "| # | input | command | message |", "|---|---|---|---|"]
    for number, case in enumerate(CASES, 1):
        scratch = folder / f"{number:02d}"
        scratch.mkdir()
        _, stderr, _, _ = run_case(case, scratch)
        message = stderr.strip().replace("|", "\\|")
        command = " ".join(("baranov", *case.argv)).replace("|", "\\|")
        lines.append(f"| {number} | {case.what} | `{command}` | `{message}` |")
    return "\n".join(lines) + "\n"


def test_the_documented_table_is_current(tmp_path):
    assert DOC.read_text(encoding="utf-8") == render_table(tmp_path), \
        "docs/input-errors.md is stale: run python tests/test_input_errors.py"


if __name__ == "__main__":
    import tempfile

    with tempfile.TemporaryDirectory() as scratch:
        DOC.write_text(render_table(Path(scratch)), encoding="utf-8")
    print(f"wrote {DOC}", file=sys.stderr)
