"""The status line of a long solve (solvers/progress.py, issue 26)."""

from __future__ import annotations

import io
import time

from baranov.solvers.progress import report_stage, watching


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_terminal_sees_the_stage_and_the_time_then_a_clean_line():
    terminal = Terminal()
    with watching(terminal, interval=0.02, delay=0.0):
        report_stage("exact: deriving the characteristic polynomial")
        time.sleep(0.2)
    text = terminal.getvalue()
    assert "\r\x1b[Kexact: deriving the characteristic polynomial … 0 s" in text
    assert text.endswith("\r\x1b[K")  # erased: the table starts on a clean line


def test_a_quick_solve_or_a_pipe_prints_nothing():
    terminal = Terminal()
    with watching(terminal, interval=0.02, delay=10.0):
        report_stage("numeric: sign branch 1 of 8")
    assert terminal.getvalue() == ""
    pipe = io.StringIO()
    with watching(pipe, interval=0.02, delay=0.0):
        report_stage("numeric: sign branch 1 of 8")
        time.sleep(0.1)
    assert pipe.getvalue() == ""


def test_stages_are_ignored_when_nobody_watches():
    report_stage("exact: anything")  # no error, no state kept
    terminal = Terminal()
    with watching(terminal, interval=0.02, delay=0.0):
        time.sleep(0.1)
    assert "anything" not in terminal.getvalue() and "solving … 0 s" in terminal.getvalue()
