"""Progress of a long solve, for a person watching a terminal (issue 26: ``baranov solve
examples/9-B28.json --method exact`` printed nothing for 35 s).

Backends name the stage they are in with :func:`report_stage` (a no-op unless someone
watches: the library and the catalog's workers pay one attribute lookup per stage); the
command line watches with :func:`watching`, which keeps one status line on a terminal —
the stage and the seconds elapsed — and erases it when the solve ends.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TextIO

_stage: list[str | None] = [None]  # the current stage while someone watches; None otherwise


def report_stage(text: str) -> None:
    """Say which stage a solve is in (e.g. ``"exact: deriving the characteristic
    polynomial"``); shown by :func:`watching` if it is active."""
    if _stage[0] is not None:
        _stage[0] = text


@contextmanager
def watching(stream: TextIO | None = None, interval: float = 0.5, delay: float = 1.0) -> Iterator[None]:
    """While inside, refresh one status line on ``stream`` every ``interval`` seconds —
    the latest stage and the seconds elapsed — starting after ``delay`` seconds (a quick
    solve prints nothing); erase it on leaving. Nothing at all unless ``stream`` is a
    terminal (piped output stays clean). ``stream``: sys.stderr as it is on entry (a
    default bound at import kept a closed capture stream in the tests)."""
    stream = stream or sys.stderr
    if not stream.isatty():
        yield
        return
    _stage[0] = "solving"
    start = time.monotonic()
    done = threading.Event()
    shown = [False]

    def refresh() -> None:
        while not done.wait(interval):
            elapsed = time.monotonic() - start
            if elapsed >= delay:
                stream.write(f"\r\x1b[K{_stage[0]} … {elapsed:.0f} s")
                stream.flush()
                shown[0] = True

    thread = threading.Thread(target=refresh, daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join()
        _stage[0] = None
        if shown[0]:
            stream.write("\r\x1b[K")
            stream.flush()
