"""The live explorer without a browser: its controls, the scenes they make, modes followed
between redraws, count changes, profiles and the server's JSON API (the page itself:
tests/test_explore_browser.py)."""

import json
import math
import subprocess
import sys
import threading
import urllib.error
import urllib.request
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shared import same_modes

from baranov.explore import (
    ControlError,
    ExplorerServer,
    count_changes,
    dimension_profile,
    document_data,
    document_scene,
    load_document,
    match_modes,
    solve_frame,
)
from baranov.explore.document import independent_pairs
from baranov.explore.frames import frame_modes
from baranov.robots.kinematics import forward_kinematics
from baranov.robots.model import load_robot
from baranov.scene import SceneError, load_scene, scene_from_dict, with_dimensions
from baranov.solvers import solve

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def initial_values(document) -> dict:
    return {control.name: control.value for control in document.controls}


def test_a_link_is_varied_by_the_independent_distances_of_a_trilateration():
    document = load_document(EXAMPLES / "7-B3-slider-P1.json")
    ground = [c.name for c in document.controls if c.link == "q1234" and c.kind == "squared distance"]
    assert ground == ["P1,P2", "P1,P3", "P2,P3", "P1,P4", "P2,P4"]  # 2k - 3 of the four-joint fixed link
    assert [c.name for c in document.controls if c.kind == "angle"] == ["P1 on q1234", "P1 on b15"]
    assert len(independent_pairs(tuple(f"P{k}" for k in range(1, 7)))) == 2 * 6 - 3


def test_the_document_at_its_own_values_is_the_scene_file():
    for name in ("7-B1.json", "7-B3-slider-P1.json", "9-B28.json"):
        document = load_document(EXAMPLES / name)
        scene, given = document_scene(document, initial_values(document)), load_scene(EXAMPLES / name)
        assert scene.exact and scene.known == given.known and scene.sliders == given.sliders


def test_a_moving_link_dimension_is_the_scene_with_that_dimension():
    document = load_document(EXAMPLES / "7-B1.json")
    scene = document_scene(document, {"P2,P4": 30.0, "P6,P8": 55.5})
    expected = with_dimensions(load_scene(EXAMPLES / "7-B1.json"), {"P2,P4": 30, "P6,P8": "55.5"})
    assert scene.known == expected.known
    assert same_modes(scene, solve(scene).assembly_modes, solve(expected).assembly_modes)


@settings(max_examples=25, deadline=None)
@given(st.floats(0.3, 1.7), st.floats(0.3, 1.7))
def test_the_fixed_link_keeps_its_first_joint_and_its_direction(first, second):
    """P1 of the ground q1234 stays at (1, 0) and P2 on the ray towards (8, 0); the
    changed distances are the values given, the unchanged ones of the first triangle
    stay, and the link remains a planar body (else a triangle inequality is named)."""
    document = load_document(EXAMPLES / "7-B3-slider-P1.json")
    values = {"P1,P2": 49 * first**2, "P1,P4": 29 * second**2}
    try:
        scene = document_scene(document, values)
    except SceneError as error:
        assert "q1234" in str(error) and "triangle inequality" in str(error)
        return
    world = {joint: tuple(map(float, point)) for joint, point in scene.world.items()}
    assert world["P1"] == (1.0, 0.0)
    assert abs(world["P2"][1]) < 1e-12 and world["P2"][0] > 1
    for name, value in values.items():
        a, b = name.split(",")
        assert math.dist(world[a], world[b]) ** 2 == pytest.approx(value, rel=1e-12)
    assert math.dist(world["P2"], world["P3"]) ** 2 == pytest.approx(34, rel=1e-12)


def test_dimensions_that_make_no_link_are_named():
    document = load_document(EXAMPLES / "7-B1.json")
    with pytest.raises(SceneError, match="link t247.*triangle inequality"):
        document_scene(document, {"P2,P4": 200.0})
    with pytest.raises(ControlError, match="P1,P9"):
        document_scene(document, {"P1,P9": 3.0})
    with pytest.raises(ControlError, match="not positive"):
        document_scene(document, {"P1,P2": -1})


def test_a_slider_angle_is_the_scene_with_that_angle_in_degrees():
    document = load_document(EXAMPLES / "7-B3-slider-P1.json")
    angle = document.control("P1 on b15")
    assert angle.value == pytest.approx(math.degrees(math.atan(10)))
    data = document_data(document, {"P1 on b15": 80.0})
    assert data["sliders"][0]["angles"]["b15"] == {"P5": 80.0}
    scene = document_scene(document, {"P1 on b15": 80.0})
    direction = scene.sliders[0].axis_on("b15").direction
    assert math.atan2(direction[1], direction[0]) == pytest.approx(math.radians(80))


def test_a_robot_is_varied_by_its_actuators():
    document = load_document(EXAMPLES / "robot-I-3RPR.json")
    assert [c.name for c in document.controls] == ["actuator 1", "actuator 2", "actuator 3"]
    frame = solve_frame(document, {"actuator 1": 2.5})
    robot, _ = load_robot(EXAMPLES / "robot-I-3RPR.json")
    poses = forward_kinematics(robot, [2.5, 11, 13])
    assert len(frame["modes"]) == len(poses) == 2
    for pose in poses:
        assert any(math.dist(mode["pose"]["position"], pose.position) < 1e-9 for mode in frame["modes"])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=1, max_size=8, unique=True),
       st.permutations(range(8)), st.floats(0, 0.01))
def test_modes_moved_a_little_and_reordered_are_matched_back(centres, order, shift):
    """Configurations 1 apart or more, moved by at most 1 % and listed in another order:
    each is matched to where it was."""
    if any(math.dist(a, b) < 1 for k, a in enumerate(centres) for b in centres[k + 1:]):
        return
    before = [{"P1": centre, "P2": (centre[0] + 1, centre[1])} for centre in centres]
    order = [k for k in order if k < len(before)]
    after = [{name: (x + shift, y - shift) for name, (x, y) in before[k].items()} for k in order]
    assert match_modes(before, after, size=20) == order


def test_a_mode_too_far_away_is_a_new_mode():
    assert match_modes([{"P1": (0.0, 0.0)}], [{"P1": (9.0, 0.0)}], size=10) == [None]
    assert match_modes([], [{"P1": (0.0, 0.0)}], size=10) == [None]


def test_every_change_of_a_count_is_found_to_the_tolerance():
    def count(t):
        return 8 if t < 0.25 else 6 if t < 0.6 else 10

    changes = count_changes(count, 8, 10, tolerance=1e-6)
    assert [(c.before, c.after) for c in changes] == [(8, 6), (6, 10)]
    assert [round(c.fraction, 5) for c in changes] == [0.25, 0.6]
    assert all(c.width <= 1e-6 for c in changes)


def drag(document, name, values, start=None):
    """Redraws along ``values`` of control ``name``, each following the previous."""
    current = initial_values(document)
    frame = solve_frame(document, current)
    frames = [frame]
    for value in values:
        previous = {"values": dict(current), "modes": frame_modes(frame)}
        current[name] = value
        frame = solve_frame(document, current, previous=previous, next_id=frame["next_id"])
        frames.append(frame)
    return frames


def test_a_mode_keeps_its_identity_while_it_moves():
    """7/B1, s2,4 from 25 to 50 in steps of 1: the count stays 8 and the modes cross in
    the parameter's order (their list order changes), but each id follows one mode: its
    configuration moves by little between redraws."""
    document = load_document(EXAMPLES / "7-B1.json")
    frames = drag(document, "P2,P4", [25 + k for k in range(1, 26)])
    assert all(len(frame["modes"]) == 8 for frame in frames)
    assert any([m["id"] for m in frame["modes"]] != list(range(8)) for frame in frames)
    for before, after in zip(frames, frames[1:], strict=False):
        at = {mode["id"]: mode["joints"] for mode in before["modes"]}
        for mode in after["modes"]:
            moved = max(math.dist(mode["joints"][joint], at[mode["id"]][joint]) for joint in mode["joints"])
            assert moved < 1.5


def test_where_two_modes_appear_is_reported_with_the_dimension_value():
    """7/B1 with s2,4 from 50 to 56: 8 modes, then 10. The event's value is bisected: the
    count is 8 just below it and 10 just above, by solves of the scene itself."""
    document = load_document(EXAMPLES / "7-B1.json")
    frames = drag(document, "P2,P4", [50.0, 56.0])
    (event,) = frames[-1]["events"]
    assert (event["kind"], event["before"], event["after"], event["dimension"]) == ("split", 8, 10, "P2,P4")
    assert len(event["configurations"]) == 2
    base = load_scene(EXAMPLES / "7-B1.json")
    width = 6 * 1e-4
    for value, count in ((event["value"] - width, 8), (event["value"] + width, 10)):
        assert len(solve(with_dimensions(base, {"P2,P4": value})).assembly_modes) == count
    assert {mode["id"] for mode in frames[-1]["modes"]} >= {mode["id"] for mode in frames[-2]["modes"]}


def test_a_profile_counts_the_modes_across_a_dimension():
    document = load_document(EXAMPLES / "7-B1.json")
    profile = dimension_profile(document, initial_values(document), "P1,P2", samples=9)
    base = load_scene(EXAMPLES / "7-B1.json")
    for value, count in zip(profile["values"], profile["counts"], strict=True):
        try:
            expected = len(solve(with_dimensions(base, {"P1,P2": value})).assembly_modes)
        except SceneError:
            expected = None
        assert count == expected
    for change in profile["changes"]:
        assert change["before"] != change["after"]


def test_a_frame_names_what_makes_no_linkage():
    document = load_document(EXAMPLES / "7-B1.json")
    frame = solve_frame(document, {"P2,P4": 200.0})
    assert frame["modes"] == [] and "triangle inequality" in frame["error"]


@pytest.fixture
def server():
    explorer = ExplorerServer(load_document(EXAMPLES / "7-B1.json"))
    thread = threading.Thread(target=explorer.serve_forever, daemon=True)
    thread.start()
    yield explorer
    explorer.shutdown()
    explorer.server_close()


def request(server, path: str, body=None):
    data = None if body is None else json.dumps(body).encode()
    with urllib.request.urlopen(urllib.request.Request(server.url.rstrip("/") + path, data=data), timeout=60) as answer:
        return answer.headers, answer.read()


def test_the_server_serves_the_page_and_the_first_redraw(server):
    headers, page = request(server, "/")
    assert b"explore.js" in page and headers["Content-Type"].startswith("text/html")
    for name in ("explore.js", "explore.css"):
        assert request(server, f"/static/{name}")[1]
    _, body = request(server, "/api/document")
    document = json.loads(body)
    assert document["title"] == "7-B1.json" and len(document["controls"]) == 15
    assert len(document["frame"]["modes"]) == 8 and document["frame"]["complete"]
    assert len(document["view"]) == 4


def test_the_server_solves_and_exports_what_baranov_solve_does(server, tmp_path):
    values = {"P2,P4": 30.0}
    _, body = request(server, "/api/solve", {"values": values})
    frame = json.loads(body)
    headers, exported = request(server, "/api/export/scene", {"values": values})
    assert "attachment" in headers["Content-Disposition"]
    scene = scene_from_dict(json.loads(exported))
    modes = solve(scene).assembly_modes
    assert len(modes) == len(frame["modes"])
    _, csv = request(server, "/api/export/modes", {"values": values, "format": "csv"})
    assert csv.decode().count("\n") == len(modes) + 1
    _, png = request(server, "/api/export/png", {"values": values})
    assert png.startswith(b"\x89PNG")


@pytest.mark.parametrize("path, body, message", [
    ("/api/solve", {"values": {"P9,P1": 3}}, "P9,P1"),
    ("/api/solve", {"values": {}, "method": "guess"}, "method 'guess'"),
    ("/api/profile", {"values": {}, "name": "nothing"}, "nothing"),
    ("/api/solve", {"values": {}, "previous": [1, 2]}, "previous"),
    ("/api/solve", {"values": {}, "previous": {"values": {}, "modes": [{"id": 1}]}}, "previous"),
    ("/api/nothing", {}, "no such request"),
])
def test_a_bad_request_is_answered_with_its_reason(server, path, body, message):
    with pytest.raises(urllib.error.HTTPError) as failure:
        request(server, path, body)
    assert failure.value.code in (400, 404)
    assert message in json.loads(failure.value.read())["error"]


def test_static_files_outside_the_page_are_not_served(server):
    for path in ("/static/../server.py", "/static/document.py", "/etc/passwd"):
        with pytest.raises(urllib.error.HTTPError) as failure:
            request(server, path)
        assert failure.value.code == 404


def test_the_command_refuses_a_bad_scene_in_one_line(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"links": []}')
    for args in (["explore", str(bad), "--no-browser"], ["explore", str(EXAMPLES / "7-B1.json"), "--method", "guess"]):
        result = subprocess.run([sys.executable, "-m", "baranov.cli", *args], capture_output=True, text=True, timeout=120)
        assert result.returncode == 2 and result.stdout == ""
        assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr


def test_a_moving_linkage_is_held_by_its_input():
    """The Stephenson six-bar, crank at 30°: the modes are the configurations of the
    linkage held there, as baranov solve finds them with the input's "degrees"."""
    document = load_document(EXAMPLES / "stephenson-six-bar.json")
    (control,) = [c for c in document.controls if c.kind == "input"]
    assert control.name == "input crank" and (control.low, control.high) == (-180, 180)
    frame = solve_frame(document, {"input crank": 30.0})
    data = json.loads((EXAMPLES / "stephenson-six-bar.json").read_text())
    data["inputs"][0]["degrees"] = 30
    scene = scene_from_dict(data)
    modes = solve(scene).assembly_modes
    assert len(frame["modes"]) == len(modes) == 4
    for mode in modes:
        assert any(max(math.dist(m["joints"][j], mode.joints[j]) for j in mode.joints) < 1e-9 for m in frame["modes"])


def test_a_moving_linkage_without_inputs_is_driven_by_its_plan_parameter():
    """The double butterfly names no input: the explorer drives s1,3, its one-DOF plan's
    first parameter, from a traced configuration."""
    document = load_document(EXAMPLES / "double-butterfly.json")
    (control,) = [c for c in document.controls if c.kind == "input"]
    assert control.name.startswith("input s")
    assert solve_frame(document, {})["modes"]  # the traced start assembles


def test_the_traced_motion_passes_through_the_configurations_drawn():
    """Four-bar with a coupler point: the traced pieces' (input, parameter) curve meets
    the crank value of every configuration the frame draws, and the coupler point's path
    is given along every piece."""
    from baranov.explore.traced_motion import traced_motion

    document = load_document(EXAMPLES / "four-bar-coupler-point.json")
    motion = traced_motion(document, {})
    assert motion["points"] == ["C"] and motion["loose_ends"] == 0
    assert len(motion["circuits"]) == 2 and {piece["circuit"] for piece in motion["pieces"]} == {0, 1}  # Grashof
    assert all(len(piece["paths"]["C"]) == len(piece["inputs"]) for piece in motion["pieces"])
    frame = solve_frame(document, {"input crank": 45.0})
    u, v = motion["parameter_joints"]
    for mode in frame["modes"]:
        value = math.dist(mode["joints"][u], mode["joints"][v]) ** 2
        nearest = min(abs(p - value) for piece in motion["pieces"]
                      for a, p in zip(piece["inputs"], piece["parameters"], strict=True) if abs(a - 45) < 8)
        assert nearest < 0.05 * max(piece_value for piece in motion["pieces"] for piece_value in piece["parameters"])


def test_the_command_serves_until_interrupted():
    """``baranov explore --no-browser`` prints its address, answers there, and stops on
    Ctrl-C (SIGINT) with exit status 0, also where it was started with SIGINT ignored (in
    the background of a script; a full suite run timed out here once)."""
    import signal

    process = subprocess.Popen([sys.executable, "-m", "baranov.cli", "explore", str(EXAMPLES / "7-B1.json"),
                                "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    try:
        line = process.stdout.readline()
        assert line.startswith("baranov explore: ") and "http://127.0.0.1:" in line
        url = line.split(" at ")[1].split()[0]
        with urllib.request.urlopen(url + "api/document", timeout=120) as answer:
            assert len(json.loads(answer.read())["frame"]["modes"]) == 8
    finally:
        process.send_signal(signal.SIGINT)
        _, errors = process.communicate(timeout=60)
    assert process.returncode == 0 and "Traceback" not in errors
