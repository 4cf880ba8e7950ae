"""Progress of the catalog job (catalog/progress.py): a bar on a terminal, plain lines
every few minutes in a log."""

from __future__ import annotations

import io

from tqdm import tqdm

from baranov.catalog.progress import ProgressLines, progress_bar


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


class Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_a_log_gets_a_line_every_interval_with_rate_and_time_left():
    log, clock = io.StringIO(), Clock()
    lines = ProgressLines(20437, "13 links", "truss", log, every=300, clock=clock)
    lines.update(8000)  # shards restored at once: no line yet
    clock.now = 299
    lines.update(8)
    assert log.getvalue() == ""
    clock.now = 300
    lines.update(8)
    assert log.getvalue() == "13 links: 8 016 of 20 437 trusses (39.2 %)\n"
    clock.now = 660
    lines.update(24)  # 24 trusses in 6 min: 240 an hour, 12 397 left
    assert log.getvalue().splitlines()[-1] == (
        "13 links: 8 040 of 20 437 trusses (39.3 %), 240 trusses an hour over the last 6 min, about 51 h 39 min left")
    clock.now = 720
    lines.update(12397)
    lines.close()  # the final count, since the last line said less
    assert log.getvalue().splitlines()[-1] == (
        "13 links: 20 437 of 20 437 trusses (100.0 %), 743 820 trusses an hour over the last 1 min")  # no "left"
    assert len(log.getvalue().splitlines()) == 3


def test_a_short_stage_writes_nothing():
    log, clock = io.StringIO(), Clock()
    lines = ProgressLines(10, "7 links", "truss", log, every=300, clock=clock)
    clock.now = 12
    lines.update(10)
    lines.close()
    assert log.getvalue() == ""


def test_the_stream_decides_between_bar_and_lines():
    assert isinstance(progress_bar(10, "7 links", "truss", True, io.StringIO()), ProgressLines)
    bar = progress_bar(10, "7 links", "truss", True, Terminal())
    assert isinstance(bar, tqdm) and not bar.disable
    bar.close()
    quiet = progress_bar(10, "7 links", "truss", False, io.StringIO())
    assert isinstance(quiet, tqdm) and quiet.disable
