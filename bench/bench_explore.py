"""How fast the explorer redraws while a dimension is dragged (issue 58): the page of each
scene opened in headless Chromium, one dimension swept back and forth by input events at
60 per second (what a mouse drag sends) for a few seconds, and the redraws that reached
the screen counted. A redraw is a round trip: the page posts the values, the server
solves (numeric backend), follows the modes and answers, the page draws every mode; while
one is in flight the latest values wait, so the rate is what the loop sustains.

    python bench/bench_explore.py [--seconds 4] [--runs 3] [--out docs/bench/explore-frame-rate.md]

Prints, per scene, the median over runs of the redraws per second, and the median time
of a redraw on the server alone (solve, matching, drawing data; the same values, in
process).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import tempfile
import threading
import time
from pathlib import Path

from baranov.explore import ExplorerServer, load_document, solve_frame
from baranov.explore.browser import launch_chromium, missing_browser
from baranov.explore.frames import frame_modes

ROOT = Path(__file__).resolve().parents[1]
#: (scene, the dimension swept, its range as factors of its value)
SCENES = [
    ("7-B1.json", "P2,P4", (0.9, 1.1)),
    ("7-B2.json", None, (0.95, 1.05)),
    ("7-B3.json", None, (0.95, 1.05)),
    ("7-B3-slider-P1.json", "P1,P5", (0.97, 1.03)),
    ("robot-I-3RPR.json", "actuator 2", (0.97, 1.03)),
    ("9-N2-random.json", None, (0.99, 1.01)),
]

DRAG = """async ([name, low, high, seconds]) => {
  const explorer = window.explorer;
  await explorer.idle();
  const start = performance.now(), first = explorer.state.redraws;
  let tick = 0;
  await new Promise(resolve => {
    const timer = setInterval(() => {
      const elapsed = (performance.now() - start) / 1000;
      if (elapsed >= seconds) { clearInterval(timer); resolve(); return; }
      const phase = (tick++ % 120) / 60;            // there and back in two seconds
      const fraction = phase <= 1 ? phase : 2 - phase;
      explorer.setValue(name, low + (high - low) * fraction);
    }, 1000 / 60);
  });
  const redraws = explorer.state.redraws - first;
  await explorer.idle();
  return {redraws, seconds: (performance.now() - start) / 1000, modes: explorer.state.frame.modes.length};
}"""


def swept(document, name: str | None):
    """The control swept: ``name``, or the first moving link's first squared distance."""
    if name is not None:
        return document.control(name)
    return next(c for c in document.controls if c.kind == "squared distance" and c.link != document.scene.ground)


def server_medians(document, control, factors, count: int = 30) -> float:
    """Median seconds of a redraw in process, along the same sweep."""
    values = {c.name: c.value for c in document.controls}
    frame = solve_frame(document, values)
    times = []
    for k in range(count):
        fraction = k / (count - 1)
        previous = {"values": dict(values), "modes": frame_modes(frame)}
        values[control.name] = control.value * (factors[0] + (factors[1] - factors[0]) * fraction)
        start = time.perf_counter()
        frame = solve_frame(document, values, previous=previous, next_id=frame["next_id"])
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def measure(browser, name: str, control_name: str | None, factors, seconds: float, runs: int) -> dict:
    document = load_document(ROOT / "examples" / name)
    control = swept(document, control_name)
    server = ExplorerServer(document)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.goto(server.url)
    page.evaluate("window.explorer.ready")
    rates, modes = [], 0
    for _ in range(runs):
        result = page.evaluate(DRAG, [control.name, control.value * factors[0], control.value * factors[1], seconds])
        rates.append(result["redraws"] / result["seconds"])
        modes = result["modes"]
    page.close()
    server.shutdown()
    server.server_close()
    return {"scene": name, "dimension": control.name, "modes": modes, "rate": statistics.median(rates),
            "rates": rates, "server": server_medians(document, control, factors)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=4.0, help="length of one drag (default 4)")
    parser.add_argument("--runs", type=int, default=3, help="drags per scene (default 3)")
    parser.add_argument("--out", type=Path, help="write the table (markdown) here, atomically")
    args = parser.parse_args()
    if missing_browser():
        raise SystemExit(f"bench_explore: {missing_browser()}")
    from playwright.sync_api import sync_playwright

    rows = []
    with sync_playwright() as playwright:
        browser = launch_chromium(playwright)
        for name, control, factors in SCENES:
            row = measure(browser, name, control, factors, args.seconds, args.runs)
            rows.append(row)
            print(f"{name:24} {row['dimension']:12} {row['modes']:3d} modes  {row['rate']:6.1f} redraws/s "
                  f"(runs {', '.join(f'{r:.1f}' for r in row['rates'])})  server {1000 * row['server']:7.1f} ms",
                  flush=True)
        browser.close()
    if args.out:
        write_table(args.out, rows, args)


def write_table(path: Path, rows: list[dict], args) -> None:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT).stdout.strip()
    lines = ["# The explorer's frame rate", "",
             f"`python bench/bench_explore.py --seconds {args.seconds:g} --runs {args.runs} --out {path}` at {commit} "
             f"({time.strftime('%Y-%m-%d')}; headless Chromium and the server in one process on this machine's "
             f"{os.cpu_count()} cores). A drag sends 60 input events a second, sweeping the dimension across the "
             "range given (factors of its value) and back; a redraw is the round trip from the page's request to "
             "every mode drawn. Median over the runs; the server's median is one redraw in process (solve with "
             "the numeric backend, modes followed, drawing data).", "",
             "| scene | dimension swept | range | modes at the end | redraws per second | server ms per redraw |",
             "|---|---|---|---|---|---|"]
    for row, (_, _, factors) in zip(rows, SCENES, strict=True):
        lines.append(f"| {row['scene']} | {row['dimension']} | ×{factors[0]:g}–{factors[1]:g} | {row['modes']} | "
                     f"{row['rate']:.1f} | {1000 * row['server']:.1f} |")
    with tempfile.NamedTemporaryFile("w", dir=path.parent, delete=False, suffix=".tmp") as handle:
        handle.write("\n".join(lines) + "\n")
    os.replace(handle.name, path)


if __name__ == "__main__":
    main()
