"""Progress of the catalog job: a bar on a terminal, a line every few minutes in a log.

The 13-link assembly modes take hours (docs/catalog-13.md), usually run with the output
sent to a file (``nohup make catalog-13-modes > log``). A tqdm bar written to a file is
one endless line of carriage returns, so there the job prints a plain line instead, at
most every :data:`LINE_SECONDS`: the count done, and from the second line on the rate
over the last interval and the time left at that rate.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

from tqdm import tqdm

#: Seconds between two progress lines in a log (nothing is printed before the first).
LINE_SECONDS = 300.0


class ProgressLines:
    """The ``update``/``close`` of a tqdm bar, as a line on ``stream`` at most every
    ``every`` seconds, e.g. ``"13 links: 8 040 of 20 437 trusses (39.3 %), 240 trusses an
    hour over the last 6 min, about 51 h 39 min left"``, and on ``close`` a last line
    with the final count if any line was written."""

    def __init__(self, total: int, description: str, unit: str, stream: TextIO, every: float = LINE_SECONDS,
                 clock=time.monotonic):
        self.total, self.description, self.unit, self.stream, self.every, self.clock = (
            total, description, unit, stream, every, clock)
        self.done = 0
        self.last: tuple[float, int] | None = None  # (time, count) of the last line
        self.start = clock()

    def update(self, count: int = 1) -> None:
        self.done += count
        now = self.clock()
        if now - (self.last[0] if self.last else self.start) >= self.every:
            self.stream.write(self.line(now) + "\n")
            self.stream.flush()
            self.last = (now, self.done)

    def line(self, now: float) -> str:
        """The line at time ``now``: counts, and with a previous line, rate and time left."""
        share = 100 * self.done / self.total if self.total else 100.0
        units = self.unit + ("es" if self.unit.endswith("s") else "s")
        text = f"{self.description}: {self.done:,} of {self.total:,} {units} ({share:.1f} %)".replace(",", " ")
        if self.last is not None and now > self.last[0]:
            rate = (self.done - self.last[1]) / (now - self.last[0])  # per second, over the last interval
            hourly = f"{rate * 3600:,.0f}".replace(",", " ")
            text += f", {hourly} {units} an hour over the last {(now - self.last[0]) / 60:.0f} min"
            if rate > 0 and self.done < self.total:
                text += f", about {_duration((self.total - self.done) / rate)} left"
        return text

    def close(self) -> None:
        if self.last is not None and self.last[1] != self.done:
            self.stream.write(self.line(self.clock()) + "\n")
            self.stream.flush()


def _duration(seconds: float) -> str:
    """``"3 h 20 min"``, ``"12 min"``."""
    minutes = round(seconds / 60)
    return f"{minutes // 60} h {minutes % 60} min" if minutes >= 60 else f"{minutes} min"


def progress_bar(total: int, description: str, unit: str, show: bool, stream: TextIO | None = None):
    """What the catalog's stages advance as their jobs finish (``update(n)``, ``close()``):
    a tqdm bar on a terminal, :class:`ProgressLines` elsewhere, and a disabled bar where
    ``show`` is false (``--quiet``)."""
    stream = stream or sys.stderr
    if show and not stream.isatty():
        return ProgressLines(total, description, unit, stream)
    return tqdm(total=total, desc=description, unit=unit, disable=not show, file=stream)
