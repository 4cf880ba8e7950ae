"""What ``baranov solve`` prints: a compact table that fits the terminal, the joints on
demand, or CSV (JSON is :meth:`~baranov.solvers.modes.Solution.to_dict`)."""

from __future__ import annotations

from collections.abc import Mapping

from baranov.solvers.modes import Solution, signs_text
from baranov.topology import natural_sort_key

#: A coordinate within this fraction of the linkage's size of 0 is printed as 0: rounding
#: noise (-4.44e-16 for a joint on an axis), below the residuals the modes verify to.
NOISE = 1e-12


def coordinate(value: float, size: float = 0.0) -> str:
    """A coordinate to 10 significant digits, trailing zeros dropped (1.8, not
    1.8000000000000003 or 1.8000), and 0 within NOISE × ``size`` (the linkage's size) of 0.

    >>> coordinate(3.0000000000000004), coordinate(-4.44e-16, size=9.0), coordinate(-0.0)
    ('3', '0', '0')
    """
    text = "0" if abs(value) <= NOISE * size else f"{value:.10g}"
    return "0" if text == "-0" else text


def mode_table(solution: Solution, joints: bool = False, width: int = 100) -> list[str]:
    """One row per mode: its number, parameter values, sign vector and residual; with
    ``joints``, each mode's joint coordinates below its row, wrapped at ``width``. The
    rows stay narrow whatever the linkage (a 12-joint truss printed 288 columns before)."""
    modes = solution.assembly_modes
    header = ["mode", *solution.parameters, "signs", "max residual"]
    rows = [[str(number), *(f"{value:.10g}" for value in mode.parameters.values()), signs_text(mode.signs),
             f"{mode.max_residual:.1e}"] for number, mode in enumerate(modes, 1)]
    aligned = _aligned(header, rows)
    lines = aligned[:1]
    for line, mode in zip(aligned[1:], modes, strict=True):
        lines.append(line)
        if joints:
            lines += joint_lines(mode.joints, width, indent=6)
    return lines


def joint_lines(joints: Mapping[str, tuple[float, float]], width: int = 100, indent: int = 6) -> list[str]:
    """Joint coordinates ``P1 = (x, y)`` in natural order (P2 before P10), wrapped at
    ``width`` and indented by ``indent``; rounding noise shown as 0 (:func:`coordinate`).

    >>> print("\\n".join(joint_lines({"P10": (1.5, 0.0), "P2": (3.0000000000000004, -4e-16)}, indent=2)))
      P2 = (3, 0)   P10 = (1.5, 0)
    """
    size = max(max(abs(x), abs(y)) for x, y in joints.values())
    return _wrapped([f"{name} = ({coordinate(x, size)}, {coordinate(y, size)})"
                     for name, (x, y) in sorted(joints.items(), key=lambda item: natural_sort_key(item[0]))],
                    width, indent)


def pose_table(poses, parameters: tuple[str, ...]) -> list[str]:
    """A robot's platform poses (:class:`~baranov.robots.kinematics.Pose`), one aligned row
    each: number, position, angle in degrees, the plan's parameters.

    >>> from baranov.robots.kinematics import Pose
    >>> print("\\n".join(pose_table([Pose((-1.0, -4.4e-16), 3.141592653589793, {}, {"s1,6": 32.0})],
    ...                             ("s1,6",))))
    pose   x  y  angle (degrees)  s1,6
       1  -1  0              180    32
    """
    import math

    header = ["pose", "x", "y", "angle (degrees)", *parameters]
    rows = []
    for number, pose in enumerate(poses, 1):
        size = max(abs(pose.position[0]), abs(pose.position[1]), 1.0)
        rows.append([str(number), coordinate(pose.position[0], size), coordinate(pose.position[1], size),
                     f"{math.degrees(pose.angle):.10g}", *(f"{pose.parameters[name]:.10g}" for name in parameters)])
    return _aligned(header, rows)


def _aligned(header: list[str], rows: list[list[str]]) -> list[str]:
    """The header and rows as lines, each column right-aligned to its widest cell."""
    widths = [max(len(header[c]), *(len(row[c]) for row in rows)) for c in range(len(header))]
    return ["  ".join(cell.rjust(w) for cell, w in zip(row, widths, strict=True)) for row in [header, *rows]]


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
    if polynomial.degree <= PRINTED_DEGREE:  # short enough to compare with a published Γ (thesis §3.2.3, §5.2)
        lines.append(f"  monic: {monic_text(polynomial.monic_coefficients(), polynomial.variable)}")
    values = [mode.parameters.get(polynomial.variable) for mode in solution.assembly_modes]
    rootless = [root for root, _ in roots if not any(value is not None and _within(root, value) for value in values)]
    if rootless:
        named = ", ".join(_shown(root) for root in rootless[:LISTED]) + (" …" if len(rootless) > LISTED else "")
        lines.append(f"{len(rootless)} real root{'s' if len(rootless) != 1 else ''} ({named}) "
                     f"give{'s' if len(rootless) == 1 else ''} no assembly mode: no real configuration on any branch")
    return lines


#: Characteristic polynomials up to this degree are printed (monic, 10 digits).
PRINTED_DEGREE = 8
_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def monic_text(coefficients, variable: str) -> str:
    """A polynomial from its coefficients (highest degree first, leading 1) as the thesis
    prints one, to 10 significant digits.

    >>> from fractions import Fraction
    >>> monic_text([1, Fraction(-672063, 1000), 0, 5], "s1,6")
    's1,6³ − 672.063 s1,6² + 5'
    """
    degree, terms = len(coefficients) - 1, []
    for power, value in zip(range(degree, -1, -1), coefficients, strict=True):
        if value == 0:
            continue
        magnitude = f"{abs(float(value)):.10g}"
        monomial = variable + (str(power).translate(_SUPERSCRIPTS) if power > 1 else "") if power else ""
        body = monomial if magnitude == "1" and monomial else f"{magnitude} {monomial}".strip()
        sign = "−" if value < 0 else "+"
        terms.append(body if not terms and value > 0 else f"{sign} {body}" if terms else f"−{body}")
    return " ".join(terms) or "0"


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
