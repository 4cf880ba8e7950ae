"""The explorer's screenshots and animation in docs/images/ (docs/explore.md), made by
driving its page in headless Chromium: a 7/B1 truss while |P2P4| passes the value where two
modes appear, a slider chain, a robot's poses as small multiples, and a Stephenson six-bar
with its whole motion. Rerun after a change to the page:

    python docs/site/explore_pictures.py

Needs Playwright and Chromium (``make setup`` installs both where it can).
"""

from __future__ import annotations

import io
import threading
from pathlib import Path

from baranov.explore import ExplorerServer, load_document
from baranov.explore.browser import launch_chromium, missing_browser

ROOT = Path(__file__).resolve().parents[2]
IMAGES = ROOT / "docs" / "images"
VIEWPORT = {"width": 1280, "height": 820}


def opened(browser, name: str):
    server = ExplorerServer(load_document(ROOT / "examples" / name))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    page = browser.new_page(viewport=VIEWPORT)
    page.goto(server.url)
    page.evaluate("window.explorer.ready")
    return server, page


def set_value(page, name: str, value: float) -> None:
    page.evaluate("([name, value]) => window.explorer.setValue(name, value)", [name, value])
    page.evaluate("window.explorer.idle()")


def closed(server, page) -> None:
    page.close()
    server.shutdown()
    server.server_close()


def truss(browser) -> None:
    """7/B1 with |P2P4| just past the value where modes 9 and 10 appear, its profile shown."""
    server, page = opened(browser, "7-B1.json")
    page.evaluate("window.explorer.activate('P2,P4')")
    page.wait_for_function("window.explorer.state.profile !== null")
    for value in (50.0, 53.5):
        set_value(page, "P2,P4", value)
    page.screenshot(path=IMAGES / "explore-7-B1.png")
    frames = []
    for k in range(36):  # |P2P4|² from 46 to 60 and back: two modes appear, then leave
        value = 46 + 14 * (k / 18 if k <= 18 else (36 - k) / 18)
        set_value(page, "P2,P4", value)
        frames.append(page.screenshot(clip={"x": 315, "y": 60, "width": 965, "height": 640}))
    save_animation(frames, IMAGES / "explore-7-B1.gif")
    closed(server, page)


def slider_chain(browser) -> None:
    server, page = opened(browser, "7-B3-slider-P1.json")
    set_value(page, "P1 on b15", 81.0)
    page.screenshot(path=IMAGES / "explore-slider-chain.png")
    closed(server, page)


def robot(browser) -> None:
    server, page = opened(browser, "robot-I-3RPR.json")
    set_value(page, "actuator 1", 2.5)
    page.select_option("#layout", "multiples")
    page.screenshot(path=IMAGES / "explore-robot.png")
    closed(server, page)


def six_bar(browser) -> None:
    server, page = opened(browser, "stephenson-six-bar.json")
    page.wait_for_function("window.explorer.state.motion !== undefined && window.explorer.state.motion !== null")
    set_value(page, "input crank", 30.0)
    page.screenshot(path=IMAGES / "explore-six-bar.png")
    closed(server, page)


def save_animation(frames: list[bytes], path: Path) -> None:
    """PNG screenshots as a looping GIF at 0.65 of their size (Pillow, which matplotlib brings)."""
    from PIL import Image

    images = [Image.open(io.BytesIO(frame)).convert("RGB") for frame in frames]
    images = [image.resize((int(0.65 * image.width), int(0.65 * image.height)), Image.LANCZOS) for image in images]
    palette = [image.quantize(colors=96, method=Image.Quantize.MEDIANCUT) for image in images]
    palette[0].save(path, save_all=True, append_images=palette[1:], duration=120, loop=0, optimize=True)


def main() -> None:
    if missing_browser():
        raise SystemExit(f"explore_pictures: {missing_browser()}")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = launch_chromium(playwright)
        for make in (truss, slider_chain, robot, six_bar):
            make(browser)
            print(make.__name__, "done", flush=True)
        browser.close()


if __name__ == "__main__":
    main()
