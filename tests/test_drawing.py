"""Pictures of assembly modes (solvers/drawing.py): no text runs into another text (a
title, the heading, another joint label) or into a panel it does not belong to, for every
example (issue 26)."""

from pathlib import Path

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from baranov.planner import best_plan
from baranov.scene import load_scene
from baranov.solvers import solve
from baranov.solvers.drawing import modes_figure, render_modes
from baranov.solvers.msolve import find_msolve

#: The scene examples of rigid linkages (``robot-*.json`` are robot files, drawn through
#: ``baranov robot --plot``; linkages that move, the double butterfly and the six-bar, are
#: drawn by ``baranov trace --plot``).
EXAMPLES = sorted(p.stem for p in (Path(__file__).resolve().parents[1] / "examples").glob("*.json")
                  if not p.stem.startswith("robot-") and load_scene(p).mobility == 0)
#: At most this fraction of an example's joint labels may cross a link, bar or slider axis
#: (measured with this layout: 38 of the 568 labels of the all-revolute examples, where 107
#: crossed with labels pushed straight away from the centre; 44 of 671 with the slider
#: chains; 26 of 168 on the crowded 9-B28).
CROSSING = 0.2
#: The 76 modes of 13-watt-baranov in panels a ninth as wide: 380 of its 1368 labels cross
#: a link (measured; labels placed farther out ran into the titles instead).
CROWDED = 0.3


def _figure(example: str):
    scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / f"{example}.json")
    if scene.sliders:
        if find_msolve() is None:
            pytest.skip("slider chains are solved by msolve, not installed")
        return modes_figure(scene, solve(scene, method="msolve"))
    if best_plan(scene.chain).number_of_parameters > 2:  # only the homotopy solves coupling degree 3
        return modes_figure(scene, solve(scene, method="homotopy"))
    return modes_figure(scene, solve(scene))


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


#: Examples whose drawing is known to break a bound: the layout defect, measured.
KNOWN_CROWDED = {"9-N2-random": "35 of 144 joint labels cross a link (2026-11-29): two quaternary links whose "
                                "polygons overlap in most of the 12 modes, and no label position clear of them"}


def _example_param(name: str):
    if name in KNOWN_CROWDED:
        return pytest.param(name, marks=pytest.mark.xfail(reason=KNOWN_CROWDED[name], strict=True))
    return pytest.param(name, marks=pytest.mark.slow) if name.startswith("13-") else name


@pytest.mark.parametrize("example", [_example_param(name) for name in EXAMPLES])  # the 13-link ones: 27 s and 17 s
def test_titles_and_labels_do_not_collide(example):
    figure = _figure(example)
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
    labels = crossing = outside = 0
    for axis, frame in zip(panels, frames, strict=True):
        segments = _segments(axis)
        boxes = [text.get_window_extent(renderer) for text in axis.texts]
        assert not any(_overlap(a, b) for n, a in enumerate(boxes) for b in boxes[n + 1:]), "two joint labels overlap"
        for text in axis.texts:
            box = text.get_window_extent(renderer)
            assert not any(_overlap(box, title) for title in titles), f"label {text.get_text()} on a title"
            assert not _overlap(box, heading)
            labels += 1
            crossing += any(_crosses(start, end, box) for start, end in segments)
            outside += not (frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1)
    bound = CROWDED if example.startswith("13-") else CROSSING
    assert crossing <= bound * labels, f"{crossing} of {labels} joint labels cross a link"
    # a label out of its panel runs into the next one (13-watt-baranov: 2 of 1368, measured)
    assert outside <= (0.002 * labels if example.startswith("13-") else 0), f"{outside} labels leave their panel"


def _segments(axis) -> list:
    """Every bar, slider axis and edge of a filled link, in display coordinates."""
    segments = [axis.transData.transform(line.get_xydata()) for line in axis.lines if len(line.get_xydata()) == 2]
    for patch in axis.patches:
        corners = patch.get_transform().transform(patch.get_path().vertices)
        segments += [(corners[n], corners[(n + 1) % len(corners)]) for n in range(len(corners))]
    return segments


def _crosses(start, end, box) -> bool:
    """Whether the segment meets the box (Liang–Barsky clipping)."""
    dx, dy = end[0] - start[0], end[1] - start[1]
    low, high = 0.0, 1.0
    for p, q in ((-dx, start[0] - box.x0), (dx, box.x1 - start[0]), (-dy, start[1] - box.y0), (dy, box.y1 - start[1])):
        if p == 0:
            if q < 0:
                return False
        elif p < 0:
            low = max(low, q / p)
        else:
            high = min(high, q / p)
    return low <= high


def test_a_png_is_written():
    scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / "3-B1.json")
    assert render_modes(scene, solve(scene)).startswith(b"\x89PNG")
