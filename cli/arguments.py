"""Command-line values shared by several commands, parsed in one place."""

from __future__ import annotations

import re


class ArgumentError(ValueError):
    """A command-line value that cannot be read (reported in one line, exit code 2)."""


#: The thesis's notation of a squared distance, s2,3 for s_{2,3} = |P2 P3|².
_THESIS_PAIR = re.compile(r"^s(\d+),(\d+)$")


def parameter_pair(text: str, option: str = "--parameter") -> tuple[str, str]:
    """The two joints of a parameter given as ``P2,P3`` or in the thesis's notation
    ``s2,3`` (joints P2 and P3).

    >>> parameter_pair("P2,P3"), parameter_pair("s2,3"), parameter_pair(" A , B ")
    (('P2', 'P3'), ('P2', 'P3'), ('A', 'B'))
    """
    thesis = _THESIS_PAIR.match(text.strip())
    if thesis:
        return f"P{thesis[1]}", f"P{thesis[2]}"
    parts = tuple(name.strip() for name in text.split(","))
    if len(parts) != 2 or not all(parts):
        raise ArgumentError(f"{option} {text}: two joints, e.g. P2,P3 (or s2,3)")
    return parts
