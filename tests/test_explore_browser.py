"""The explorer's page in a real browser (headless Chromium driven by Playwright): every
mode drawn, a dimension moved, the redraw equal to ``baranov solve`` on the same
dimensions, for a truss, a slider chain and a robot. Skipped, with the reason, where
Playwright or Chromium is missing (``make test`` installs both where it can)."""

import json
import math
import threading
from pathlib import Path

import pytest

from baranov.explore import ExplorerServer, document_scene, load_document
from baranov.explore.browser import launch_chromium, missing_browser
from baranov.robots.kinematics import forward_kinematics
from baranov.robots.model import load_robot
from baranov.scene import load_scene, scene_from_dict, with_dimensions
from baranov.solvers import solve

pytestmark = pytest.mark.skipif(missing_browser() is not None, reason=str(missing_browser()))

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = launch_chromium(playwright)
        yield chromium
        chromium.close()


@pytest.fixture
def page_of(browser, tmp_path):
    servers, pages = [], []

    def open_page(name: str):
        server = ExplorerServer(load_document(EXAMPLES / name))
        threading.Thread(target=server.serve_forever, daemon=True).start()
        servers.append(server)
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        errors = []
        page.on("pageerror", lambda error: errors.append(str(error)))
        page.errors = errors
        page.goto(server.url)
        page.evaluate("window.explorer.ready")
        pages.append(page)
        return page

    yield open_page
    for page in pages:
        page.screenshot(path=tmp_path / "page.png")  # kept by pytest's tmp_path for a look
        assert page.errors == []
        page.close()
    for server in servers:
        server.shutdown()
        server.server_close()


def drawn(page) -> list[dict]:
    """The modes the page drew: one SVG group each, and the data it drew them from."""
    count = page.evaluate("document.querySelectorAll('#drawings g.mode').length")
    modes = page.evaluate("window.explorer.state.frame.modes.map(m => ({id: m.id, joints: m.joints}))")
    assert count == len(modes)
    return modes


def same_configurations(page_modes, modes, size) -> bool:
    return len(page_modes) == len(modes) and all(
        any(max(math.dist(shown["joints"][j], mode.joints[j]) for j in mode.joints) < 1e-6 * size for shown in page_modes)
        for mode in modes)


def move(page, name: str, value: float) -> float:
    """Drag: the control's range input set and its input event fired, as a mouse does;
    the value the page took (a range input rounds to its step)."""
    page.evaluate("""([name, value]) => {
        const row = document.querySelector(`.control[data-name="${CSS.escape(name)}"]`);
        const range = row.querySelector('input[type=range]');
        range.value = value;
        range.dispatchEvent(new Event('input'));
    }""", [name, value])
    page.evaluate("window.explorer.idle()")
    return page.evaluate(f"window.explorer.state.values[{name!r}]")


def test_a_truss_redraws_its_modes_as_a_dimension_moves(page_of):
    page = page_of("7-B1.json")
    assert len(drawn(page)) == 8
    assert "certified complete" in page.inner_text("#certificate")
    value = move(page, "P2,P4", math.sqrt(55.0))  # the page shows lengths: |P2P4| ≈ √55
    assert value == pytest.approx(55, rel=1e-3)
    scene = with_dimensions(load_scene(EXAMPLES / "7-B1.json"), {"P2,P4": value})
    modes = solve(scene).assembly_modes
    assert len(modes) == 10
    assert same_configurations(drawn(page), modes, 30)
    assert "2 modes appear" in page.inner_text("#events")
    page.select_option("#layout", "multiples")
    assert page.evaluate("document.querySelectorAll('#drawings svg').length") == 10


def test_a_slider_chain_redraws_as_a_slider_angle_moves(page_of):
    page = page_of("7-B3-slider-P1.json")
    assert len(drawn(page)) == 2
    assert page.evaluate("document.querySelectorAll('#drawings .axis').length") == 2  # one axis per mode
    value = move(page, "P1 on b15", 80.0)
    scene = document_scene(load_document(EXAMPLES / "7-B3-slider-P1.json"), {"P1 on b15": value})
    assert same_configurations(drawn(page), solve(scene).assembly_modes, 40)


def test_a_robot_redraws_its_poses_as_an_actuator_moves(page_of):
    page = page_of("robot-I-3RPR.json")
    value = move(page, "actuator 1", 2.5)
    robot, _ = load_robot(EXAMPLES / "robot-I-3RPR.json")
    poses = forward_kinematics(robot, [value, 11, 13])
    shown = page.evaluate("window.explorer.state.frame.modes.map(m => m.pose.position)")
    assert len(drawn(page)) == len(poses) == 2
    assert all(any(math.dist(p, pose.position) < 1e-6 for p in shown) for pose in poses)
    assert "platform at" in page.inner_text("#legend")


def test_the_page_names_dimensions_that_make_no_linkage(page_of):
    page = page_of("7-B1.json")
    page.fill('.control[data-name="P2,P4"] input[type=number]', "14")  # |P2P4| = 14 > 6 + 3.6
    page.press('.control[data-name="P2,P4"] input[type=number]', "Enter")
    page.evaluate("window.explorer.idle()")
    assert "triangle inequality" in page.inner_text("#error")


def test_the_scene_export_is_the_scene_drawn(page_of, tmp_path):
    page = page_of("7-B1.json")
    value = move(page, "P6,P8", 8.0)
    with page.expect_download() as download:
        page.click('[data-export="scene"]')
    path = tmp_path / "exported.json"
    download.value.save_as(path)
    scene = load_scene(path)
    assert float(scene.known[frozenset(("P6", "P8"))]) == value
    assert same_configurations(drawn(page), solve(scene).assembly_modes, 30)


def test_a_moving_linkage_shows_its_motion_and_follows_its_input(page_of):
    """The four-bar with a coupler point: the traced motion drawn (its curve and the
    coupler point's path), the input moved by a click on the curve, and the configurations
    drawn equal to the linkage held there."""
    page = page_of("four-bar-coupler-point.json")
    page.wait_for_function("window.explorer.state.motion != null")
    assert page.evaluate("document.querySelectorAll('#motion .piece').length") >= 1
    assert page.evaluate("document.querySelectorAll('#drawing .path').length") >= 1
    assert page.inner_text("#motion-note").startswith("(2 circuits, 4 pieces")
    box = page.locator("#motion").bounding_box()
    page.mouse.click(box["x"] + 0.75 * box["width"], box["y"] + box["height"] / 2)  # the crank at 90°
    page.evaluate("window.explorer.idle()")
    value = page.evaluate("window.explorer.state.values['input crank']")
    assert value == pytest.approx(90, abs=2)
    data = json.loads((EXAMPLES / "four-bar-coupler-point.json").read_text())
    data["inputs"][0]["degrees"] = value
    scene = scene_from_dict(data)
    modes = solve(scene).assembly_modes
    assert len(modes) == 2 and same_configurations(drawn(page), modes, 20)


def test_a_followed_piece_is_drawn_as_the_mode_it_passes_through(page_of):
    """Stephenson six-bar: following a traced piece sets the crank to each of its points'
    values and highlights the drawn configuration that is that point (within 1e-6 of the
    linkage's size: the traced point, verified on the dimensions, is an assembly mode of
    the linkage held there)."""
    page = page_of("stephenson-six-bar.json")
    page.wait_for_function("window.explorer.state.motion != null")
    count = len(page.evaluate("window.explorer.state.motion.pieces[2]")["inputs"])
    for index in (count // 5, count // 2, 4 * count // 5):
        page.evaluate("k => window.explorer.follow(2, k)", index)
        page.evaluate("window.explorer.idle()")
        piece = page.evaluate("window.explorer.state.motion.pieces[2]")
        assert page.evaluate("window.explorer.state.values['input crank']") == piece["inputs"][index]
        shown = page.evaluate("""() => { const s = window.explorer.state;
            return s.frame.modes.find(m => m.id === s.highlighted).joints; }""")
        assert max(math.dist(shown[name], piece["paths"][name][index]) for name in shown) < 1e-6 * 30


def test_reset_brings_back_the_file(page_of):
    page = page_of("7-B1.json")
    move(page, "P2,P4", 7.4)
    page.click("#reset")
    page.evaluate("window.explorer.idle()")
    assert page.evaluate("window.explorer.state.values['P2,P4']") == 25
    assert len(drawn(page)) == 8


def test_the_exact_method_redraws_the_same_modes_with_its_certificate(page_of):
    page = page_of("7-B1.json")
    numeric = drawn(page)
    page.select_option("#method", "exact")
    page.evaluate("window.explorer.idle()")
    assert "certified complete" in page.inner_text("#certificate")
    exact = drawn(page)
    assert len(exact) == len(numeric) == 8
    assert all(any(max(math.dist(a["joints"][j], b["joints"][j]) for j in a["joints"]) < 1e-9 for b in numeric)
               for a in exact)
    assert {mode["id"] for mode in exact} == {mode["id"] for mode in numeric}  # the same modes keep their colours
