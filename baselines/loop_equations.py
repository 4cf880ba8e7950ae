"""Loop-equation baseline: the classical analytical route the thesis replaces (§1.2, §3.1).

Every link but the ground turns by an unknown angle θ_L; a spanning tree of the link
graph (links as vertices, joints as edges) places each joint through a chain of rotated
link vectors from the ground, and every joint off the tree closes one independent loop:
its position reached through either of its links must agree — two scalar equations per
loop, linear in cos θ_L and sin θ_L. The tangent-half-angle substitution
x_L = tan(θ_L / 2), cos θ = (1 − x²)/(1 + x²), sin θ = 2x/(1 + x²), cleared of
denominators, makes them polynomial; sympy's resultants then eliminate one variable at a
time down to one univariate polynomial, whose real roots (isolated by flint) are
substituted back level by level. A truss of n links has n − 1 angles and n − 1 equations.

Link vectors are taken from each link's shape in the scene as rationals (exact for
instances built from rational coordinates). The substitution cannot represent θ = π
(x = ∞), and the resultants carry extraneous factors; both are part of what the baseline
measures.
"""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import mpmath
import networkx as nx
import numpy as np
import sympy

from baranov.scene import Scene
from baranov.solvers import Solution, SolverError
from baranov.solvers.modes import AssemblyMode
from baranov.solvers.verification import joint_residual, same_mode, sorted_modes

from .coupling import chain_coupling_degree

#: Back-substitution keeps a value where every polynomial of the level vanishes to this,
#: relative to the sum of the absolute values of its terms there.
VANISHING = 1e-6


class LoopEquationError(SolverError):
    """The loop-equation elimination broke down (a resultant vanished identically)."""


def loop_equations(scene: Scene) -> tuple[list[sympy.Poly], list[sympy.Symbol], dict]:
    """The tangent-half-angle loop equations of ``scene``: polynomials over QQ, their
    variables ``x_<link>`` (one per moving link), and what places the joints from a
    solution (used by :func:`solve_loop_equations`).

    >>> from baranov.scene import load_scene
    >>> equations, variables, _ = loop_equations(load_scene("examples/5-B1.json"))
    >>> len(equations), len(variables)
    (4, 4)
    """
    links = {link.name: link for link in scene.links}
    graph = nx.MultiGraph()
    graph.add_nodes_from(links)
    owners: dict[str, list[str]] = {}
    for link in scene.links:
        for joint in link.joints:
            owners.setdefault(joint, []).append(link.name)
    for joint, names in owners.items():
        if len(names) != 2:
            raise LoopEquationError(f"joint {joint}: on {len(names)} links; loop equations need binary joints")
        graph.add_edge(*names, key=joint)
    parent: dict[str, tuple[str, str]] = {}  # link -> (joint to its parent, parent link)
    for u, v, joint in nx.edge_bfs(graph, scene.ground):
        if v not in parent and v != scene.ground:
            parent[v] = (joint, u)
    moving = [link.name for link in scene.links if link.name != scene.ground]
    variables = {name: sympy.Symbol(f"x_{name}") for name in moving}
    vectors = {name: {j: (Fraction(x), Fraction(y)) for j, (x, y) in links[name].local.items()} for name in links}
    world = {j: (Fraction(float(x)), Fraction(float(y))) for j, (x, y) in scene.world.items()}

    def position(joint: str, link: str):
        """Position of ``joint`` reached through ``link``: (x, y, links rotated on the way)."""
        if link == scene.ground:
            return sympy.Rational(world[joint][0]), sympy.Rational(world[joint][1]), set()
        entry, above = parent[link]
        x0, y0, used = position(entry, above)
        (ax, ay), (bx, by) = vectors[link][entry], vectors[link][joint]
        dx, dy = sympy.Rational(bx - ax), sympy.Rational(by - ay)
        t = variables[link]
        cos, sin = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
        return x0 + cos * dx - sin * dy, y0 + sin * dx + cos * dy, used | {link}

    equations = []
    tree_joints = {joint for joint, _ in parent.values()}
    for joint, (first, second) in owners.items():
        if joint in tree_joints:
            continue
        ax, ay, used_a = position(joint, first)
        bx, by, used_b = position(joint, second)
        clearing = sympy.Mul(*[1 + variables[name] ** 2 for name in used_a | used_b])
        for expression in (ax - bx, ay - by):
            numerator = sympy.cancel(sympy.together(expression * clearing))
            equations.append(sympy.Poly(numerator, *variables.values(), domain="QQ"))
    return equations, list(variables.values()), {"parent": parent, "vectors": vectors, "world": world,
                                                 "variables": variables}


def eliminate(equations: list[sympy.Poly], variables: list[sympy.Symbol]) -> list[list[sympy.Poly]]:
    """Levels of successive resultant elimination: level k holds polynomials in the
    first k variables; the last variable is eliminated first, the pivot being the
    polynomial of lowest degree in it."""
    levels = [equations]
    current = equations
    for variable in reversed(variables[1:]):
        having = [p for p in current if p.degree(variable) > 0]
        rest = [p for p in current if p.degree(variable) <= 0]
        if not having:
            raise LoopEquationError(f"variable {variable} occurs in no equation")
        pivot = min(having, key=lambda p: p.degree(variable))
        reduced = []
        for other in having:
            if other is pivot:
                continue
            first, second = pivot, other
            common = sympy.gcd(first, second)
            if common.degree(variable) > 0:  # a shared component: eliminate what is left of each
                first, second = sympy.quo(first, common), sympy.quo(second, common)
            resultant = sympy.Poly(sympy.resultant(first.as_expr(), second.as_expr(), variable), *variables,
                                   domain="QQ")
            if resultant.is_zero:
                raise LoopEquationError(f"the resultant eliminating {variable} vanishes identically")
            reduced.append(resultant.sqf_part().primitive()[1])
        current = reduced + rest
        levels.append(current)
    return levels[::-1]


def solve_loop_equations(scene: Scene) -> Solution:
    """Assembly modes from the loop equations, eliminated by resultants (see the module
    docstring). Modes carry no parameters or signs; they are reported unverified."""
    equations, variables, placing = loop_equations(scene)
    levels = eliminate(equations, variables)
    univariate = [p for p in levels[0] if not p.is_zero]
    others = [_substituted(p, variables[0], {}) for p in univariate[1:]]
    partial = [[root] for root in _real_roots(univariate[0], variables[0])
               if all(_vanishes(c, root) for c in others)]
    for k in range(1, len(variables)):
        extended = []
        for values in partial:
            known = dict(zip(variables[:k], values, strict=True))
            for root in _candidate_values(levels[k], variables[k], known):
                extended.append([*values, root])
        partial = extended
    modes: list[AssemblyMode] = []
    for values in partial:
        points = _joint_positions(scene, placing, dict(zip(variables, values, strict=True)))
        mode = AssemblyMode({}, (), {j: (p.real, p.imag) for j, p in sorted(points.items())},
                            joint_residual(scene, points))
        if not any(same_mode(mode, other, scene) for other in modes):
            modes.append(mode)
    return Solution("loop-equations", chain_coupling_degree(scene), (), (), sorted_modes(modes))


def loop_size(scene: Scene) -> tuple[int, int]:
    """(unknowns, equations) of the loop formulation: one angle per moving link, two
    equations per independent loop."""
    joints = {j for link in scene.links for j in link.joints}
    loops = len(joints) - len(scene.links) + 1
    return len(scene.links) - 1, 2 * loops


def _real_roots(polynomial: sympy.Poly, variable: sympy.Symbol) -> list[float]:
    coefficients = polynomial.as_poly(variable).all_coeffs()[::-1]
    denominator = math.lcm(*[sympy.Rational(c).q for c in coefficients])
    integer = flint.fmpz_poly([int(sympy.Rational(c) * denominator) for c in coefficients])
    roots = []
    for factor, _ in integer.factor()[1]:
        roots += [float(root.real.mid()) for root, _ in factor.complex_roots() if root.imag == 0]
    return sorted(roots)


def _candidate_values(polynomials: list[sympy.Poly], variable: sympy.Symbol, known: dict) -> list[float]:
    """Real values of ``variable`` at which every polynomial of the level that contains
    it vanishes, the other variables fixed at ``known`` (coefficients in mpmath, whose
    exponent range does not overflow; roots of the lowest-degree one by numpy)."""
    univariate = [_substituted(p, variable, known) for p in polynomials if p.degree(variable) > 0]
    usable = [c for c in univariate if len(c) > 1]
    if not usable:
        return []
    pivot = min(usable, key=len)
    largest = max(abs(c) for c in pivot)
    values = []
    for root in np.roots([float(c / largest) for c in pivot]):
        if abs(root.imag) <= 1e-6 * max(1.0, abs(root)) and all(_vanishes(c, root.real) for c in univariate):
            values.append(float(root.real))
    return values


def _substituted(polynomial: sympy.Poly, variable: sympy.Symbol, known: dict) -> list:
    """Coefficients (mpmath, highest degree first) of ``polynomial`` in ``variable`` with
    the other variables set to ``known``."""
    position = polynomial.gens.index(variable)
    coefficients = [mpmath.mpf(0)] * (polynomial.degree(variable) + 1)
    for monomial, coefficient in zip(polynomial.monoms(), polynomial.coeffs(), strict=True):
        term = mpmath.mpf(coefficient.p) / coefficient.q
        for gen, exponent in zip(polynomial.gens, monomial, strict=True):
            if exponent and gen != variable:
                term *= mpmath.mpf(known[gen]) ** exponent
        coefficients[polynomial.degree(variable) - monomial[position]] += term
    while len(coefficients) > 1 and coefficients[0] == 0:  # the leading term vanished at ``known``
        coefficients.pop(0)
    return coefficients


def _vanishes(coefficients: list, value: float) -> bool:
    """Whether the polynomial (coefficients highest first) vanishes at ``value`` relative
    to the size of its terms there."""
    terms = [c * mpmath.mpf(value) ** (len(coefficients) - 1 - n) for n, c in enumerate(coefficients)]
    return abs(sum(terms)) <= VANISHING * max(sum(abs(t) for t in terms), mpmath.mpf(10) ** -300)


def _joint_positions(scene: Scene, placing: dict, values: dict) -> dict[str, complex]:
    parent, vectors, world, variables = placing["parent"], placing["vectors"], placing["world"], placing["variables"]
    angles = {link: 2 * math.atan(values[symbol]) for link, symbol in variables.items()}
    points = {j: complex(float(x), float(y)) for j, (x, y) in world.items()}
    for link, (entry, _) in parent.items():  # breadth-first order: the entry joint is placed
        rotation = complex(math.cos(angles[link]), math.sin(angles[link]))
        ex, ey = vectors[link][entry]
        for joint, (x, y) in vectors[link].items():
            if joint != entry:
                points[joint] = points[entry] + rotation * complex(float(x - ex), float(y - ey))
    return points
