"""The slider constructions planned for the bilateration kernel (docs/sliders.md), tried
in plain complex floats on the three 7/B3 slider chains of thesis §4.2.2–4.2.4 before
they enter the kernel: the 7/B3 plan of examples/7-B3-section-4.2.1.json (reference
P1 P2, parameter s1,6; P3, P4 on the ground; P6, P5 free; P9 from P6, P5; P7 free from
P9, P4; P8 from P9, P7; closure s2,8) with every step that touches a slider replaced by
its limit: the axis from two points of known signed distance, a point from the axis and
a point, the second axis turned by the angle their link fixes, and a closure on a signed
distance. Prints the real roots found by sampling and Brent on every sign branch; the
published ones are 49.5561, 50.1965, 50.6270, 85.0000 (§4.2.2), 48.1037, 85.0000,
88.2000, 88.5483 (§4.2.3, with the erratum α7 = π − atan(4/5)) and t = 7.4867, 8.7825
(§4.2.4).

Run: ``python bench/slider_constructions.py``. Signed distances h and along-axis steps
are read off the links' shapes in the axis frames of examples/7-B3-slider-*.json.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.optimize import brentq

P1, P2, P3, P4 = 1 + 0j, 8 + 0j, 3 + 3j, 6 + 2j  # the ground link q1234


def bilateration(p_i: complex, p_j: complex, s_ij: float, s_ik: float, s_jk: float, sign: int) -> complex | None:
    """P_k from P_i, P_j (thesis eq. 2.7), None where the triangle does not exist."""
    radicand = (s_ij + s_ik + s_jk) ** 2 - 2 * (s_ij ** 2 + s_ik ** 2 + s_jk ** 2)
    if radicand < 0:
        return None
    return p_i + (s_ij + s_ik - s_jk + 1j * sign * math.sqrt(radicand)) / (2 * s_ij) * (p_j - p_i)


def off_axis(anchor: complex, direction: complex, h_anchor: float, h_target: float, squared: float,
             sign: int) -> complex | None:
    """The point at signed distance ``h_target`` from the axis (unit ``direction``) and
    √``squared`` from ``anchor`` (whose signed distance is ``h_anchor``): the limit of a
    bilateration whose first vertex goes to infinity (paper 003's circle and line)."""
    step = h_target - h_anchor
    if squared - step ** 2 < 0:
        return None
    return anchor + (sign * math.sqrt(squared - step ** 2) + 1j * step) * direction


def first_steps(s16: float, signs) -> tuple[complex, complex, complex] | None:
    """P6, P5 and the unit direction of slider P9's axis, placed from P6, P5 of link t569
    (P5, P6 at signed distances 5 and 2, one unit apart along the axis, in its frame)."""
    p6 = bilateration(P1, P3, 13, s16, 36, signs[0])
    p5 = bilateration(p6, P1, s16, 10, 101, signs[1]) if p6 is not None else None
    if p5 is None:
        return None
    return p6, p5, (p5 - p6) * (1 - 3j) / 10  # (P5 − P6)(along − iΔh)/s5,6 with along 1, Δh 3


def through_p7(s16: float, signs) -> tuple[complex, complex] | None:
    """P7 (free sign, from P4 and slider P9's axis: signed distances −5 for P7 and, for
    P4, 2 plus its offset from P6 across the axis) and the axis's unit direction."""
    placed = first_steps(s16, signs)
    if placed is None:
        return None
    p6, _, axis = placed
    p7 = off_axis(P4, axis, 2 + ((P4 - p6) * axis.conjugate()).imag, -5, 52, signs[2])
    return None if p7 is None else (p7, axis)


def slider_p9(s16: float, signs) -> float:
    """§4.2.2: s2,8 − 82 with P9 a slider (P7 → P8 on link t789: one unit along the axis,
    three across)."""
    placed = through_p7(s16, signs)
    return math.nan if placed is None else abs(placed[0] + (1 + 3j) * placed[1] - P2) ** 2 - 82


def sliders_p8_p9(s16: float, signs) -> float:
    """§4.2.3: P2's signed distance to slider P8's axis, minus its own 4√2 (P8 a slider
    too; its axis turned by 45° from P9's in link t789, through P8' = P7 + (1 + 3i) u)."""
    placed = through_p7(s16, signs)
    if placed is None:
        return math.nan
    p7, axis = placed
    second = axis * complex(math.cos(math.pi / 4), math.sin(math.pi / 4))
    return ((P2 - (p7 + (1 + 3j) * axis)) * second.conjugate()).imag - math.sqrt(82) * 4 / math.sqrt(41)


def slider_p1(t: float, signs) -> float:
    """§4.2.4: s2,8 − 82 with P1 a slider whose axis is the line P1 P2 (the frame's real
    axis); the parameter t is P6's signed distance to it."""
    p6 = off_axis(P3, 1, 3, t, 36, signs[0])
    p5 = off_axis(p6, 1, t, 10, 10, signs[1]) if p6 is not None else None
    p9 = bilateration(p6, p5, 10, 13, 29, -1) if p5 is not None else None
    p7 = bilateration(p9, P4, abs(P4 - p9) ** 2, 34, 52, signs[2]) if p9 is not None else None
    if p7 is None:
        return math.nan
    return abs(bilateration(p9, p7, 34, 20, 10, 1) - P2) ** 2 - 82


def roots(condition, low: float, high: float) -> list[float]:
    """Every sign change of ``condition`` on 40 000 samples of [low, high], on each of the
    8 sign branches, refined by Brent."""
    grid = np.linspace(low, high, 40001)
    found = []
    for signs in itertools.product((1, -1), repeat=3):
        values = np.array([condition(x, signs) for x in grid])
        for i in np.flatnonzero(np.isfinite(values[:-1]) & np.isfinite(values[1:]) & (values[:-1] * values[1:] < 0)):
            found.append(brentq(condition, grid[i], grid[i + 1], args=(signs,)))
    return sorted(found)


if __name__ == "__main__":
    for name, condition, low, high in (("§4.2.2 slider P9, s1,6", slider_p9, 0.01, 200),
                                       ("§4.2.3 sliders P8, P9, s1,6", sliders_p8_p9, 0.01, 200),
                                       ("§4.2.4 slider P1, t", slider_p1, -20, 20)):
        print(f"{name}: " + ", ".join(f"{root:.4f}" for root in roots(condition, low, high)))
