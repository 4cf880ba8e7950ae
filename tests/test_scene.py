"""The scene layer (scene/): every input error names the offending link, joint or value
(one SceneError), exact inputs stay exact, and each link's own frame keeps its
dimensions."""

import json
import re
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import pytest

from baranov.scene import SceneError, load_scene, scene_from_dict

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d["links"][2].update(squared_length=-4), "link b14: squared distance P1,P4 = -4 must be positive"),
        (lambda d: d["links"][2].update(squared_length="x"), "link b14, squared_length: 'x' is not a number"),
        (lambda d: d["links"][2].update(squared_length=float("nan")), "not a finite number"),
        (lambda d: d["links"][0]["squared_distances"].update({"P1,P2": 1000}),
         "link t123: squared distances of P1, P2, P3 violate the triangle inequality"),
        (lambda d: d["links"][0].pop("orientation"), "link t123: \"orientation\" must be"),
        # a typo (P7 for P6): both names are named (issue 57)
        (lambda d: d["links"][4].update(joints=["P3", "P7"]),
         "joint P6: dangling, only on link t456 (and P7 only on link b36: one name misspelt?)"),
        (lambda d: d.update(ground="nowhere"), "ground 'nowhere': no link of that name"),
        (lambda d: d["links"].pop(), "joint P3: dangling, only on link t123"),
        (lambda d: d["links"][0]["squared_distances"].pop("P2,P3"), "link t123: squared distance P2,P3 missing"),
    ],
)
def test_scene_errors_name_the_link(change, message):
    data = json.loads((EXAMPLES / "5-B1.json").read_text())
    change(data)
    with pytest.raises(SceneError, match=re.escape(message)):
        scene_from_dict(data)


def test_a_mobile_topology_is_a_scene_and_an_over_constrained_one_an_error():
    """A four-bar (F = 1) is a scene (tests/test_scene_inputs.py); a four-bar whose
    coupler is also jointed to the ground (F = −1) is not."""
    four_bar = {"links": [
        {"name": "ground", "joints": {"A": [0, 0], "D": [4, 0]}},
        {"name": "crank", "joints": ["A", "B"], "squared_length": 1},
        {"name": "coupler", "joints": ["B", "C"], "squared_length": 16},
        {"name": "rocker", "joints": ["C", "D"], "squared_length": 4},
    ], "ground": "ground"}
    assert scene_from_dict(four_bar).mobility == 1
    braced = {"links": [
        {"name": "ground", "joints": {"A": [0, 0], "D": [4, 0], "E": [2, 3]}},
        {"name": "crank", "joints": ["A", "B"], "squared_length": 1},
        {"name": "coupler", "joints": {"B": [0, 0], "C": [4, 0], "E": [2, 2]}},
        {"name": "rocker", "joints": ["C", "D"], "squared_length": 4},
    ], "ground": "ground"}
    with pytest.raises(SceneError, match=r"topology: mobility F = 3\(L-1\) - 2J = -1"):
        scene_from_dict(braced)


def test_inconsistent_quaternary_distances():
    data = {"links": [
        {"name": "q", "joints": ["P1", "P2", "P3", "P4"], "orientation": "ccw",
         "squared_distances": {"P1,P2": 25, "P1,P3": 25, "P2,P3": 50, "P1,P4": 25, "P2,P4": 50, "P3,P4": 7}},
        {"name": "a", "joints": ["P1", "P5"], "squared_length": 1},
    ], "ground": "q"}
    with pytest.raises(SceneError, match="link q: squared distances are not those of a planar body"):
        scene_from_dict(data)


def test_exactness_is_tracked():
    exact = load_scene(EXAMPLES / "5-B1.json")
    assert exact.exact and exact.known[frozenset(("P1", "P2"))] == Fraction(50)
    data = json.loads((EXAMPLES / "5-B1.json").read_text())
    data["links"][2]["squared_length"] = 52.0
    assert not scene_from_dict(data).exact
    data["links"][2]["squared_length"] = "104/2"
    assert scene_from_dict(data).known[frozenset(("P1", "P4"))] == Fraction(52)


def test_coincident_joints_in_coordinates():
    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    data["links"][0]["joints"]["P2"] = [1, 3]  # on top of P1
    with pytest.raises(SceneError, match=r"link ground: squared distance P1,P2 = 0 must be positive"):
        scene_from_dict(data)


def test_decimal_literals_of_a_file_are_exact(tmp_path):
    """2.5 in a JSON file is 5/2 to its author: the scene is exact, the exact backend
    takes it; a Python float stays a binary float (inexact)."""
    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    data["links"][2]["squared_length"] = 18.5
    path = tmp_path / "decimal.json"
    path.write_text(json.dumps(data))
    scene = load_scene(path)
    assert scene.exact and scene.known[frozenset(("P2", "P3"))] == Fraction(37, 2)
    assert not scene_from_dict(data).exact
    data["links"][2]["squared_length"] = Decimal("0.1")
    assert scene_from_dict(data).known[frozenset(("P2", "P3"))] == Fraction(1, 10)


@pytest.mark.parametrize("where, key, message", [
    (None, "grund", "scene: unknown key 'grund' (did you mean \"ground\"?)"),
    (1, "squared_lenght", "link b13: unknown key 'squared_lenght' (did you mean \"squared_length\"?)"),
    (None, "mass", "scene: unknown key 'mass' (expected one of links, ground, inputs, sliders, tracers, comment"),
])
def test_unknown_keys_are_errors_with_a_suggestion(where, key, message):
    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    target = data if where is None else data["links"][where]
    target[key] = 1
    with pytest.raises(SceneError) as error:
        scene_from_dict(data)
    assert str(error.value).startswith(message)


@pytest.mark.parametrize("value", [2.5e300, 1e-120])
def test_extreme_magnitudes_are_refused_with_a_message(value):
    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    data["links"][1]["squared_length"] = value
    with pytest.raises(SceneError, match=r"link b13: squared distance P1,P3 = .* is out of range: .*rescale"):
        scene_from_dict(data)


def test_unicode_and_very_long_names_and_a_10_mb_file_are_accepted(tmp_path):
    """Names are any strings (a joint named by 5000 accented letters, a link with a Greek
    letter); a 10 MB scene file (a long comment) loads and solves."""
    from baranov.solvers import solve

    data = json.loads((EXAMPLES / "3-B1.json").read_text())
    long = "P" + "é" * 5000
    for link in data["links"]:
        if isinstance(link["joints"], dict):
            continue
        link["joints"] = [long if joint == "P3" else joint for joint in link["joints"]]
    data["links"][1]["name"] = "bâton-β"
    data["comment"] = "x" * 10_000_000
    path = tmp_path / "big.json"
    path.write_text(json.dumps(data, ensure_ascii=False), encoding="utf-8")
    modes = solve(load_scene(path), method="exact").assembly_modes
    assert sorted(round(mode.joints[long][0], 9) for mode in modes) == [1.8, 5.4]
