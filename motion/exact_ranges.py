"""The ranges of a one-parameter configuration space computed exactly, and the traced
pieces certified against them (thesis ch. 6, issue 19).

A chain whose configuration space has one parameter s (the four-bar, the six-bars, twelve
of the sixteen eight-bars) has, on each sign vector of its plan's free-sign triangles,
ranges of s on which every triangle can be built (thesis §6.4). A range ends where a
triangle turns flat: a real root of that triangle's radicand Δ_k on the branch. Over the
radical tower of the plan (:func:`~baranov.solvers.exact.characteristic.radical_tower`),
the norm of Δ_k over the inner radicals is an integer polynomial in s
(:func:`~baranov.solvers.exact.characteristic.radicand_norm`) that vanishes wherever
Δ_k does on any branch. Its real roots, isolated in ball arithmetic (python-flint), cut
(0, upper] into open intervals on each of which every radicand of every branch keeps its
sign: the innermost radicand that changed sign would be continuous there (its inner
radicands keep theirs) and vanish at a root of its norm. So one ball evaluation of the
branch's radicands inside an interval (:func:`~baranov.solvers.exact.characteristic.placed_points`)
decides the whole interval, and one at a root decides whether two defined neighbours
join there. The result is every range of every branch, each end the real root of an
irreducible integer polynomial; a ball that cannot decide is reported, never guessed.

A traced piece (:func:`~baranov.motion.tracing.trace`) is *certified* when an exact range
of its branch has both its ends (within END_MATCH of the parameter's range): the piece is
then one connected range, with ends known to 60 digits. An exact range no piece traces is
one the tracer missed.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import flint

from baranov.closure.bilateration import triangle_radicand
from baranov.solvers.exact.characteristic import computed_distance, placed_points, radical_tower, radicand_norm

from .configuration_space import OneDofSystem
from .tracing import Trace

#: A range's end matches a traced end within this fraction of the parameter's range (the
#: tracer locates an edge by bisection to 1e-13 of it).
END_MATCH = 1e-9
#: An end of the searched interval (0 or the parameter's bound) matches within this
#: fraction of the range.
SEARCHED_END_MATCH = 1e-7
#: Bits of the balls that isolate the roots and test the radicands (about 60 digits).
PRECISION = 200


@dataclass(frozen=True)
class RangeEnd:
    """An end of a range: ``value`` (a ball), a real root of the irreducible integer
    polynomial ``polynomial`` (coefficients, lowest degree first) where the free-sign
    triangles ``triangles`` are flat on the range's branch; or, with ``polynomial`` None,
    an end of the searched interval (0, or the bound of the parameter)."""

    value: flint.arb
    polynomial: tuple[int, ...] | None = None
    triangles: tuple[tuple[str, str, str], ...] = ()

    def digits(self, count: int = 30) -> str:
        """The value to ``count`` significant digits (the ball's radius is far smaller)."""
        return self.value.str(count, radius=False)


@dataclass(frozen=True)
class ExactRange:
    """A range of the parameter on the branch ``signs`` on which every joint is placed,
    its ends computed exactly (module docstring)."""

    signs: tuple[int, ...]
    low: RangeEnd
    high: RangeEnd

    def holds(self, low: float, high: float, upper: float) -> bool:
        """Whether a traced range from ``low`` to ``high`` has this range's ends (an end
        of the searched interval within SEARCHED_END_MATCH)."""
        return all(abs(float(end.value.mid()) - value) <= (END_MATCH if end.polynomial else SEARCHED_END_MATCH) * upper
                   for end, value in ((self.low, low), (self.high, high)))


@dataclass(frozen=True)
class ExactRanges:
    """Every range of every branch (:attr:`ranges`), and the stretches of the parameter
    where a ball could not decide whether a branch is defined (:attr:`undecided`, as
    sentences)."""

    ranges: tuple[ExactRange, ...]
    undecided: tuple[str, ...] = ()


def exact_ranges(system: OneDofSystem) -> ExactRanges:
    """Every range of the one-parameter configuration space of ``system`` (an exact
    scene), per sign branch, ends exact (module docstring).

    >>> from pathlib import Path
    >>> from baranov.scene import load_scene
    >>> from baranov.motion import one_dof_system
    >>> scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / "four-bar-coupler-point.json")
    >>> found = exact_ranges(one_dof_system(scene))   # crank 2, coupler 6: |P1P3| from 4 to 8
    >>> len(found.ranges), found.undecided, found.ranges[0].low.polynomial, found.ranges[0].high.digits(5)
    (4, (), (-16, 1), '64.000')

    Raises :class:`~baranov.solvers.exact.ExactMethodError` for an inexact scene and
    ``ValueError`` for a two-parameter space. Cost: one norm per free-sign triangle (m
    norm steps each, thesis §3.6.2: the degree doubles per step), its real roots, and one
    ball placement per branch and interval between roots and per root.
    """
    if len(system.parameter_names) != 1:
        raise ValueError(f"parameters {', '.join(system.parameter_names)}: exact ranges need a one-parameter space")
    saved, flint.ctx.prec = flint.ctx.prec, PRECISION
    try:
        ends = _ends(system)
        ranges, undecided = [], []
        for signs in system.branches:
            signs = tuple(int(s) for s in signs)
            found, unsure = _branch_ranges(system, signs, ends)
            ranges += found
            undecided += unsure
    finally:
        flint.ctx.prec = saved
    return ExactRanges(tuple(ranges), tuple(undecided))


def certified_pieces(system: OneDofSystem, traced: Trace, exact: ExactRanges) -> tuple[list[ExactRange | None],
                                                                                       list[ExactRange]]:
    """For every piece of ``traced``, the exact range of its branch with its ends (None:
    not certified); and the exact ranges no piece traces."""
    name, upper = system.parameter_names[0], system.upper[0]
    matched, used = [], set()
    for piece in traced.pieces:
        low, high = sorted((piece.points[0].parameters[name], piece.points[-1].parameters[name]))
        match = next((n for n, candidate in enumerate(exact.ranges)
                      if candidate.signs == tuple(piece.signs) and candidate.holds(low, high, upper)), None)
        matched.append(None if match is None else exact.ranges[match])
        used.add(match)
    return matched, [candidate for n, candidate in enumerate(exact.ranges) if n not in used]


def _ends(system: OneDofSystem) -> list[RangeEnd]:
    """The real roots in (0, upper) of every free-sign radicand's norm, sorted, balls that
    overlap merged (their triangles joined), between the ends 0 and upper."""
    tower = radical_tower(system.scene, system.plan)
    triangles = [step.triangle for step in system.plan.steps if step.free_sign]
    upper = flint.arb(system.upper[0])
    roots: list[RangeEnd] = []
    for n, triangle in enumerate(triangles):
        _, factors = radicand_norm(tower, n).factor()
        for factor, _ in factors:
            coefficients = tuple(int(c) for c in factor.coeffs())
            roots += [RangeEnd(root.real, coefficients, (triangle,)) for root, _ in factor.complex_roots()
                      if root.imag.is_zero() and root.real > 0 and not root.real > upper]
    merged: list[RangeEnd] = []
    for end in sorted(roots, key=lambda root: float(root.value.mid())):
        if merged and merged[-1].value.overlaps(end.value):
            merged[-1] = RangeEnd(merged[-1].value, merged[-1].polynomial, merged[-1].triangles + end.triangles)
        else:
            merged.append(end)
    # a root at the bound (the chain between the parameter's joints stretched) is that end
    top = [] if merged and merged[-1].value.overlaps(upper) else [RangeEnd(upper)]
    return [RangeEnd(flint.arb(0))] + merged + top


def _branch_ranges(system: OneDofSystem, signs: tuple[int, ...], ends: list[RangeEnd]):
    """The ranges of one branch: the open intervals between consecutive ``ends`` where
    its radicands are positive, joined across an end where they are positive too."""
    ranges, undecided, start = [], [], None
    for n in range(len(ends) - 1):
        low, high = ends[n], ends[n + 1]
        inside = _defined(system, signs, (low.value + high.value) / 2)
        if inside is None:
            undecided.append(f"{system.parameter_names[0]} in ({low.digits(12)}, {high.digits(12)}) on branch "
                             f"{signs}: the radicands' signs are not decided at {PRECISION} bits")
        if not inside:
            continue
        start = start or low
        joins = n + 1 < len(ends) - 1 and _defined(system, signs, high.value)
        if not joins:
            ranges.append(ExactRange(signs, _flat_at(system, signs, start), _flat_at(system, signs, high)))
            start = None
    return ranges, undecided


def _flat_at(system: OneDofSystem, signs: tuple[int, ...], end: RangeEnd) -> RangeEnd:
    """``end`` with its triangles narrowed to those flat on the branch (all of them where
    the balls cannot tell)."""
    if end.polynomial is None:
        return end
    radicands = _radicands(system, signs, end.value)
    if radicands is None:
        return end
    flat = tuple(triangle for triangle in end.triangles if radicands.get(triangle, flint.acb(0)).real.contains(0))
    return RangeEnd(end.value, end.polynomial, flat or end.triangles)


def _defined(system: OneDofSystem, signs: tuple[int, ...], value: flint.arb) -> bool | None:
    """Whether every free-sign radicand on branch ``signs`` is positive at ``value``: True,
    False (one is certainly negative or zero, or a step cannot be placed), or None (a
    ball cannot tell)."""
    radicands = _radicands(system, signs, value)
    if radicands is None:
        return False
    if all(radicand.real > 0 for radicand in radicands.values()):
        return True
    if any(radicand.real <= 0 for radicand in radicands.values()):
        return False
    return None


def _radicands(system: OneDofSystem, signs: tuple[int, ...], value: flint.arb) -> dict | None:
    """The free-sign radicands (16 A², balls) of the plan on branch ``signs`` at parameter
    ``value``, keyed by triangle; None where the plan cannot place a step (a radicand
    certainly negative, or a base distance 0)."""
    scene, plan = system.scene, system.plan
    points, reference, _ = placed_points(scene, plan, [flint.acb(value)], signs, real_only=True)
    if points is None:
        return None
    parameter = frozenset(plan.parameters[0])

    def side(u: str, v: str) -> flint.acb:
        pair = frozenset((u, v))
        if pair in scene.known:
            known = Fraction(scene.known[pair])
            return flint.acb(flint.fmpq(known.numerator, known.denominator))
        return flint.acb(value) if pair == parameter else computed_distance(points, u, v, reference)

    return {step.triangle: triangle_radicand(side(step.triangle[0], step.triangle[1]),
                                             side(step.triangle[0], step.triangle[2]),
                                             side(step.triangle[1], step.triangle[2]))
            for step in plan.steps if step.free_sign}
