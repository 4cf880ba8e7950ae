"""Pictures of assembly modes (solvers/drawing.py): no text runs into another text or
into a panel it does not belong to, for every example (issue 26)."""

import json
from pathlib import Path

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from baranov.scene import load_scene
from baranov.solvers import solve
from baranov.solvers.drawing import modes_figure, render_modes

EXAMPLES = sorted(p.stem for p in (Path(__file__).resolve().parents[1] / "examples").glob("*.json")
                  if not p.stem.startswith(("11-", "13-")) and "sliders" not in json.loads(p.read_text()))


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


@pytest.mark.parametrize("example", EXAMPLES)
def test_titles_and_labels_do_not_collide(example):
    scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / f"{example}.json")
    figure = modes_figure(scene, solve(scene))
    renderer = FigureCanvasAgg(figure).get_renderer()
    figure.draw(renderer)
    panels = [axis for axis in figure.axes if axis.axison]
    frames = [axis.get_window_extent(renderer) for axis in panels]
    titles = [axis.title.get_window_extent(renderer) for axis in panels]
    heading = figure._suptitle.get_window_extent(renderer)
    for n, title in enumerate(titles):
        assert not _overlap(title, heading), f"title {n + 1} runs into the heading"
        assert not any(_overlap(title, frame) for frame in frames), f"title {n + 1} runs into a panel"
        assert not any(_overlap(title, other) for m, other in enumerate(titles) if m != n)
    for axis in panels:
        for text in axis.texts:
            box = text.get_window_extent(renderer)
            assert not any(_overlap(box, title) for title in titles), f"label {text.get_text()} on a title"
            assert not _overlap(box, heading)


def test_a_png_is_written():
    scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / "3-B1.json")
    assert render_modes(scene, solve(scene)).startswith(b"\x89PNG")
