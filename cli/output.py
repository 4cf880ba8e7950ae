"""What ``baranov solve`` prints: a compact table that fits the terminal, the joints on
demand, or CSV (JSON is :meth:`~baranov.solvers.modes.Solution.to_dict`)."""

from __future__ import annotations

import csv
import io

from baranov.solvers.modes import Solution, signs_text
from baranov.topology import natural_sort_key


def coordinate(value: float) -> str:
    """A coordinate to 10 significant digits, trailing zeros dropped (1.8, not
    1.8000000000000003 or 1.8000)."""
    text = f"{value:.10g}"
    return "0" if text == "-0" else text


def mode_table(solution: Solution, joints: bool = False, width: int = 100) -> list[str]:
    """One row per mode: its number, parameter values, sign vector and residual; with
    ``joints``, each mode's joint coordinates below its row, wrapped at ``width``. The
    rows stay narrow whatever the linkage (a 12-joint truss printed 288 columns before)."""
    modes = solution.assembly_modes
    header = ["mode", *solution.parameters, "signs", "max residual"]
    rows = [[str(number), *(f"{value:.10g}" for value in mode.parameters.values()), signs_text(mode.signs),
             f"{mode.max_residual:.1e}"] for number, mode in enumerate(modes, 1)]
    widths = [max(len(header[c]), *(len(row[c]) for row in rows)) for c in range(len(header))]
    lines = ["  ".join(cell.rjust(w) for cell, w in zip(header, widths, strict=True))]
    for row, mode in zip(rows, modes, strict=True):
        lines.append("  ".join(cell.rjust(w) for cell, w in zip(row, widths, strict=True)))
        if joints:
            lines += _wrapped([f"{name} = ({coordinate(x)}, {coordinate(y)})"
                               for name, (x, y) in sorted(mode.joints.items(), key=lambda item: natural_sort_key(item[0]))],
                              width, indent=6)
    return lines


#: Names of root multiplicities.
MULTIPLICITY = {2: "double", 3: "triple", 4: "quadruple"}
#: Multiple roots and rootless roots listed by name (more are counted).
LISTED = 5


def characteristic_lines(solution) -> list[str]:
    """What ``baranov solve --method exact`` says of the characteristic polynomial: its
    degree and real roots, naming the multiple ones (where modes merge: thesis §3.3.3,
    and 3-RPR-I's double root at 49 printed "2 real roots" above "1 assembly mode"
    without a word, issue 26) and the real roots that give no assembly mode (their
    configurations are not real on any branch)."""
    polynomial = solution.characteristic_polynomial
    roots = polynomial.distinct_real_roots()
    total = sum(multiplicity for _, multiplicity in roots)
    line = (f"characteristic polynomial in {polynomial.variable}: degree {polynomial.degree}, "
            f"{total} real root{'s' if total != 1 else ''}")
    multiple = [(root, multiplicity) for root, multiplicity in roots if multiplicity > 1]
    if multiple:
        named = ", ".join(f"{_shown(root)} {MULTIPLICITY.get(m, f'of multiplicity {m}')}" for root, m in multiple[:LISTED])
        line += (f" counted with multiplicity ({len(roots)} distinct; {named}{' …' if len(multiple) > LISTED else ''}:"
                 " modes merge there)")
    lines = [line + ", isolated in certified enclosures"]
    values = [mode.parameters.get(polynomial.variable) for mode in solution.assembly_modes]
    rootless = [root for root, _ in roots if not any(value is not None and _within(root, value) for value in values)]
    if rootless:
        named = ", ".join(_shown(root) for root in rootless[:LISTED]) + (" …" if len(rootless) > LISTED else "")
        lines.append(f"{len(rootless)} real root{'s' if len(rootless) != 1 else ''} ({named}) "
                     f"give{'s' if len(rootless) == 1 else ''} no assembly mode: no real configuration on any branch")
    return lines


def _shown(root) -> str:
    return coordinate(float(root.mid()))


def _within(root, value: float) -> bool:
    middle, radius = float(root.mid()), float(root.rad())
    return abs(value - middle) <= radius + 1e-9 * max(1.0, abs(middle))


def _wrapped(items: list[str], width: int, indent: int) -> list[str]:
    lines, current = [], ""
    for item in items:
        candidate = f"{current}   {item}" if current else " " * indent + item
        if current and len(candidate) > width:
            lines.append(current)
            candidate = " " * indent + item
        current = candidate
    return lines + ([current] if current else [])


def modes_csv(solution: Solution) -> str:
    """The modes as CSV: mode, parameter values, signs, residual, then x and y of every
    joint (full precision)."""
    modes = solution.assembly_modes
    joint_names = sorted(modes[0].joints, key=natural_sort_key) if modes else []
    stream = io.StringIO()
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(["mode", *solution.parameters, "signs", "max_residual",
                     *(f"{name}_{axis}" for name in joint_names for axis in "xy")])
    for number, mode in enumerate(modes, 1):
        writer.writerow([number, *(repr(v) for v in mode.parameters.values()), signs_text(mode.signs),
                         repr(mode.max_residual), *(repr(c) for name in joint_names for c in mode.joints[name])])
    return stream.getvalue()
