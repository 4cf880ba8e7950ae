"""Closure conditions of a bilateration plan, as exact expressions in bilateration matrices.

For a plan with reference p_{a,b} every located joint k has p_{a,k} = M_k p_{a,b}, with
M_a = 0, M_b = I and, for a step p_{i,k} = Z_{i,j,k} p_{i,j},
M_k = M_i + Z_{i,j,k} (M_j - M_i) (thesis §2.6–2.7). Perpendicular matrices commute, so
each M_k is a polynomial with integer coefficients in the commuting symbols Z_{i,j,k}.
A closure condition for a link dimension s_{u,v} is

    s_{u,v} = det(Ω) s_{a,b},   Ω = M_v - M_u,

e.g. the pentad's s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6 (thesis eq. 2.25).
A bilateration whose base distance s_{i,j} is neither a link dimension nor a parameter
uses the *computed* distance s_{i,j} = det(M_j - M_i) s_{a,b}; these appear as
:attr:`ClosureSystem.computed_distances`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING

from baranov.planner import DistanceKind, Plan
from baranov.topology import distance_name, natural_sort_key, thesis_subscript

if TYPE_CHECKING:  # sympy is imported where sympy equations are built: it costs 0.2 s
    import sympy

Triangle = tuple[str, str, str]
Monomial = tuple[Triangle, ...]  # Z factors, latest step first
Polynomial = tuple[tuple[Monomial, int], ...]  # sorted (monomial, coefficient) pairs


def _z_text(triangle: Triangle) -> str:
    return "Z" + ",".join(thesis_subscript(n) for n in triangle)


def _sorted_polynomial(terms: dict[Monomial, int]) -> Polynomial:
    return tuple(sorted(((m, c) for m, c in terms.items() if c), key=lambda mc: (len(mc[0]), mc[0])))


@dataclass(frozen=True)
class MatrixExpression:
    """A polynomial in bilateration matrices: Σ c · Z_{t1} Z_{t2} ... (the empty product is I)."""

    terms: Polynomial

    def text(self) -> str:
        """Thesis notation, e.g. ``I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4``."""
        return self._render(_z_text)

    def latex(self) -> str:
        return self._render(lambda t: "Z_{" + ",".join(thesis_subscript(n) for n in t) + "}")

    def _render(self, factor) -> str:
        parts = []
        for monomial, coefficient in self.terms:
            body = " ".join(factor(t) for t in monomial) or "I"
            magnitude = abs(coefficient)
            body = body if magnitude == 1 else f"{magnitude} {body}"
            parts.append(("- " if coefficient < 0 else "+ ") + body)
        text = " ".join(parts) or "0"
        return text[2:] if text.startswith("+ ") else "-" + text[2:] if text.startswith("- ") else text

    def triangles(self) -> set[Triangle]:
        return {t for monomial, _ in self.terms for t in monomial}


@dataclass(frozen=True)
class DistanceCondition:
    """``s_{u,v} = det(omega) s_ref``: a closure condition, or the definition of a computed distance."""

    pair: tuple[str, str]
    omega: MatrixExpression
    reference: tuple[str, str]

    def text(self) -> str:
        """e.g. ``s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6``."""
        return f"{distance_name(*self.pair)} = det({self.omega.text()}) {distance_name(*self.reference)}"

    def latex(self) -> str:
        u, v = (thesis_subscript(n) for n in self.pair)
        a, b = (thesis_subscript(n) for n in self.reference)
        return f"s_{{{u},{v}}} = \\det\\left({self.omega.latex()}\\right) s_{{{a},{b}}}"


@dataclass(frozen=True)
class ClosureSystem:
    """Everything a solver needs from a plan: its closure conditions, the computed
    distances they depend on, and the matrices M_k of every joint."""

    plan: Plan
    matrices: dict[str, MatrixExpression]
    conditions: tuple[DistanceCondition, ...]
    computed_distances: tuple[DistanceCondition, ...]

    def text(self) -> str:
        """All conditions, then the computed distances they use ("where ..."), one per line."""
        lines = [c.text() for c in self.conditions]
        lines += ["where " + c.text() for c in self.computed_distances]
        return "\n".join(lines)

    def latex(self) -> str:
        return "\\\\\n".join([c.latex() for c in self.conditions] + [c.latex() for c in self.computed_distances])

    @cached_property
    def sympy_conditions(self) -> list[sympy.Eq]:
        """The conditions as sympy equations in squared distances ``s_u_v`` and oriented
        areas ``A_i_j_k`` (see :func:`sympy_condition`)."""
        return [sympy_condition(c) for c in self.conditions]


@lru_cache(maxsize=1024)
def closure_system(plan: Plan) -> ClosureSystem:
    """Derive the closure conditions of ``plan`` (thesis §2.7); once per plan (cached:
    every solve of a linkage asks for them).

    >>> from baranov.literature.trusses import thesis_truss
    >>> from baranov.planner import bilateration_plans
    >>> plan = bilateration_plans(thesis_truss("5/B1").chain(), reference=("P1", "P6"))[0]
    >>> print(closure_system(plan).text())
    s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6
    """
    a, b = plan.reference
    matrices: dict[str, dict[Monomial, int]] = {a: {}, b: {(): 1}}
    for step in plan.steps:
        i, j = step.base
        m_i, m_j = matrices[i], matrices[j]
        # M_k = M_i + Z (M_j - M_i)
        result = dict(m_i)
        for monomial, coefficient in m_j.items():
            key = (step.triangle, *monomial)
            result[key] = result.get(key, 0) + coefficient
        for monomial, coefficient in m_i.items():
            key = (step.triangle, *monomial)
            result[key] = result.get(key, 0) - coefficient
        matrices[step.joint] = {m: c for m, c in result.items() if c}
    expressions = {k: MatrixExpression(_sorted_polynomial(v)) for k, v in matrices.items()}

    def difference(u: str, v: str) -> MatrixExpression:
        terms = dict(matrices[v])
        for monomial, coefficient in matrices[u].items():
            terms[monomial] = terms.get(monomial, 0) - coefficient
        return MatrixExpression(_sorted_polynomial(terms))

    def condition(pair) -> DistanceCondition:
        u, v = sorted(pair, key=natural_sort_key)  # s2,5 rather than s5,2, as the thesis writes
        return DistanceCondition((u, v), difference(u, v), plan.reference)

    conditions = tuple(condition(pair) for pair in plan.closure_pairs)
    computed = []
    seen = set()
    for step in plan.steps:
        if step.base_distance is DistanceKind.COMPUTED and frozenset(step.base) not in seen:
            seen.add(frozenset(step.base))
            computed.append(condition(step.base))
    return ClosureSystem(plan, expressions, conditions, tuple(computed))


def _s_symbol(u: str, v: str) -> sympy.Symbol:
    import sympy

    u, v = sorted((u, v), key=lambda n: (len(n), n))
    return sympy.Symbol(f"s_{thesis_subscript(u)}_{thesis_subscript(v)}", positive=True)


def _a_symbol(triangle: Triangle) -> sympy.Symbol:
    import sympy

    return sympy.Symbol("A_" + "_".join(thesis_subscript(n) for n in triangle), real=True)


def sympy_condition(condition: DistanceCondition) -> sympy.Eq:
    """``s_{u,v} = det(Ω) s_ref`` with every Z_{i,j,k} written out (thesis eq. 2.7) as
    (s_ij + s_ik - s_jk + 4 i A_ijk) / (2 s_ij), and det(Ω) = ``|Ω|²``, unexpanded."""
    import sympy

    total = sympy.Integer(0)
    for monomial, coefficient in condition.omega.terms:
        product = sympy.Integer(coefficient)
        for i, j, k in monomial:
            s_ij, s_ik, s_jk = _s_symbol(i, j), _s_symbol(i, k), _s_symbol(j, k)
            product *= (s_ij + s_ik - s_jk + 4 * sympy.I * _a_symbol((i, j, k))) / (2 * s_ij)
        total += product
    real, imaginary = total.as_real_imag()
    return sympy.Eq(_s_symbol(*condition.pair), (real**2 + imaginary**2) * _s_symbol(*condition.reference))
