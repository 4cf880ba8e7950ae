"""Analytic 3-RPR robots (thesis §5.1.2, Table 5.1): the geometric conditions that
simplify the characteristic polynomial, and whether a characteristic polynomial is
solvable by radicals (its Galois group).

The conditions, on the base triangle P1 P2 P3 and the platform triangle P4 P5 P6 (leg k
joins P_k and P_{k+3}):

* C1: two attachments coincide, on the base or on the platform;
* C2: the base and the platform attachments are each collinear;
* C3: the two triangles are similar (P_k ↔ P_{k+3}, the same orientation);
* C4: the two triangles are mirror images of each other (congruent, opposite
  orientations; thesis example VI). Mirror images at another scale are not analytic in
  general: on base (0, 0), (6, 0), (2, 4) and platform (0, 0), (3, 0), (1, −2) the sextic
  came out irreducible with an unsolvable Galois group for leg lengths 3, 7, 5
  (tests/test_robots.py).

C2 takes both triangles flat, a coincident pair included (two points are collinear).

A robot is *analytic* when its characteristic polynomial is solvable by radicals, that
is when its Galois group is solvable; the thesis's example VI (C4) has an irreducible
sextic that is (§5.1.2).
"""

from __future__ import annotations

from fractions import Fraction

from baranov.scene import Scene

#: Relative tolerance of the conditions for float dimensions (exact ones are compared exactly).
TOLERANCE = 1e-9


def analytic_conditions(scene: Scene) -> tuple[str, ...]:
    """The conditions C1–C4 that the locked 3-RPR ``scene`` (joints named as in thesis
    §5.1: base P1–P3, platform P4–P6) satisfies, e.g. ``("C3",)``.

    >>> from pathlib import Path
    >>> from baranov.scene import load_scene
    >>> examples = Path(__file__).resolve().parents[1] / "examples"
    >>> [analytic_conditions(load_scene(examples / f"3-RPR-{n}.json")) for n in ("I", "III", "IV", "V", "VI")]
    [(), ('C1',), ('C2',), ('C3',), ('C4',)]
    """
    base = [scene.known[frozenset(pair)] for pair in (("P1", "P2"), ("P1", "P3"), ("P2", "P3"))]
    platform = [scene.known[frozenset(pair)] for pair in (("P4", "P5"), ("P4", "P6"), ("P5", "P6"))]
    conditions = []
    if any(_zero(s, max(base)) for s in base) or any(_zero(s, max(platform)) for s in platform):
        conditions.append("C1")
    flat = [_zero(_doubled_area_squared(*sides), max(sides) ** 2) for sides in (base, platform)]
    if all(flat):
        conditions.append("C2")
    ratios = [p / b if b else None for p, b in zip(platform, base, strict=True)]
    similar = None not in ratios and all(_zero(r - ratios[0], ratios[0]) for r in ratios)
    if similar:  # flat similar triangles are their own mirror images: C3
        same = any(flat) or scene.orientation(("P1", "P2", "P3")) == scene.orientation(("P4", "P5", "P6"))
        if same:
            conditions.append("C3")
        elif _zero(ratios[0] - 1, 1):
            conditions.append("C4")
    return tuple(conditions)


def galois_group(coefficients) -> tuple[str, int, bool]:
    """The Galois group of the polynomial with these ``coefficients`` (highest degree
    first; exact, degree at most 6, irreducible): its name, order and whether it is
    solvable (sympy's ``galois_group``).

    >>> galois_group([1, 0, -2])  # T² − 2
    ('S2TransitiveSubgroups.S2', 2, True)
    """
    import sympy  # only here: a heavy import

    variable = sympy.Symbol("T")
    polynomial = sympy.Poly([sympy.Rational(str(Fraction(c))) for c in coefficients], variable)
    group, _ = sympy.galois_group(polynomial)
    name, _ = sympy.galois_group(polynomial, by_name=True)
    return str(name), int(group.order()), bool(group.is_solvable)


def _zero(value, scale) -> bool:
    if isinstance(value, Fraction) and isinstance(scale, Fraction):
        return value == 0
    return abs(float(value)) <= TOLERANCE * max(abs(float(scale)), 1.0)


def _doubled_area_squared(a, b, c):
    """16 · area² of a triangle from its squared sides (Heron): 0 when it is flat."""
    return 4 * a * b - (a + b - c) ** 2

