"""Reading matrix expressions written in the thesis's notation.

Grammar (white space optional; ``−`` and ``-`` both mean minus)::

    expression := ["+" | "-"] term (("+" | "-") term)*
    term       := factor factor*                       (juxtaposition is the product)
    factor     := "I" | "Z" i "," j "," k | "Ω" a "," b "," c "," d | "Ω" n | "(" expression ")"

``Z i,j,k`` is the bilateration matrix Z_{i,j,k} of joints P_i, P_j, P_k; ``Ω a,b,c,d`` is
the thesis's shorthand Z_{a,c,d} Z_{a,b,c} (thesis eq. 3.7–3.8, so that
p_{a,d} = Ω_{a,b,c,d} p_{a,b}); ``Ω n`` (one index) names an expression given in
``named`` (Appendix A's Ω1). Products of perpendicular matrices commute (thesis §2.4), so
the result is a polynomial in the Z symbols.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from .conditions import MatrixExpression, Monomial, _sorted_polynomial

_TOKEN = re.compile(r"\s*(?:(?P<z>Z\s*\d+\s*,\s*\d+\s*,\s*\d+)|(?P<omega>Ω\s*\d+(?:\s*,\s*\d+)*)|(?P<op>[-−+()])|(?P<i>I))")

Terms = dict[Monomial, int]


def _tokens(text: str) -> list[tuple[str, str]]:
    tokens, position = [], 0
    text = text.strip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        if not match or match.end() == position:
            raise ValueError(f"cannot read {text[position:position + 12]!r} in matrix expression {text!r}")
        kind = match.lastgroup
        value = match.group(kind).replace(" ", "")
        tokens.append((kind, "-" if value == "−" else value))
        position = match.end()
    return tokens


def _multiply(left: Terms, right: Terms) -> Terms:
    result: Terms = {}
    for m1, c1 in left.items():
        for m2, c2 in right.items():
            key = tuple(sorted(m1 + m2, reverse=True))
            result[key] = result.get(key, 0) + c1 * c2
    return {m: c for m, c in result.items() if c}


def _add(left: Terms, right: Terms, sign: int) -> Terms:
    result = dict(left)
    for m, c in right.items():
        result[m] = result.get(m, 0) + sign * c
    return {m: c for m, c in result.items() if c}


def _z(indices: list[str]) -> Terms:
    return {(tuple(f"P{n}" for n in indices),): 1}


def parse_matrix_expression(text: str, named: Mapping[str, MatrixExpression] | None = None) -> MatrixExpression:
    """Parse a thesis-notation matrix expression into a :class:`MatrixExpression`.

    Monomials are stored with their Z factors in decreasing name order, so two
    expressions compare equal exactly when they are the same polynomial.

    >>> parse_matrix_expression("I − Z1,3,2Z1,6,3 − Z6,4,5 Z6,1,4").text()
    'I - Z1,6,3 Z1,3,2 - Z6,4,5 Z6,1,4'
    >>> parse_matrix_expression("Ω3,2,4,5").text()
    'Z3,4,5 Z3,2,4'
    """
    named = {key.replace("Ω", ""): value for key, value in (named or {}).items()}
    tokens = _tokens(text)
    position = 0

    def peek() -> tuple[str, str] | None:
        return tokens[position] if position < len(tokens) else None

    def take() -> tuple[str, str]:
        nonlocal position
        token = tokens[position]
        position += 1
        return token

    def expression() -> Terms:
        sign = 1
        if peek() and peek()[1] in "+-" and peek()[0] == "op":
            sign = -1 if take()[1] == "-" else 1
        result = _add({}, term(), sign)
        while peek() and peek()[0] == "op" and peek()[1] in "+-":
            sign = -1 if take()[1] == "-" else 1
            result = _add(result, term(), sign)
        return result

    def term() -> Terms:
        result = factor()
        while peek() and not (peek()[0] == "op" and peek()[1] in "+-)"):
            result = _multiply(result, factor())
        return result

    def factor() -> Terms:
        if peek() is None:
            raise ValueError(f"matrix expression {text!r} ends early")
        kind, value = take()
        if kind == "i":
            return {(): 1}
        if kind == "z":
            return _z(value[1:].split(","))
        if kind == "omega":
            indices = value[1:].split(",")
            if len(indices) == 4:
                a, b, c, d = indices
                return _multiply(_z([a, c, d]), _z([a, b, c]))
            if len(indices) == 1 and indices[0] in named:
                return {tuple(sorted(m, reverse=True)): c for m, c in named[indices[0]].terms}
            raise ValueError(f"Ω{value[1:]} in {text!r}: expected Ωa,b,c,d or a named expression")
        if value == "(":
            inner = expression()
            if peek() != ("op", ")"):
                raise ValueError(f"missing ')' in matrix expression {text!r}")
            take()
            return inner
        raise ValueError(f"unexpected {value!r} in matrix expression {text!r}")

    result = expression()
    if peek() is not None:
        raise ValueError(f"unexpected {peek()[1]!r} in matrix expression {text!r}")
    return MatrixExpression(_sorted_polynomial(result))


def canonical_form(expression: MatrixExpression) -> MatrixExpression:
    """The same polynomial with every monomial's factors in decreasing name order
    (plans store them latest-step first), for comparing expressions."""
    terms: Terms = {}
    for monomial, coefficient in expression.terms:
        key = tuple(sorted(monomial, reverse=True))
        terms[key] = terms.get(key, 0) + coefficient
    return MatrixExpression(_sorted_polynomial(terms))
