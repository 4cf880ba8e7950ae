"""Bilateration plans: the data.

A plan locates every joint of a rigid chain relative to a **reference** vector
p_ref = p_{a,b} between two joints (thesis §2.6–2.7, §3.4.1): each later joint k is
located from two located joints i, j by one bilateration, p_{i,k} = Z_{i,j,k} p_{i,j}
(thesis eq. 2.6), so that every located joint carries a perpendicular matrix M_k with
p_{a,k} = M_k p_ref, and M_k = M_i + Z_{i,j,k}(M_j - M_i).

Steps come in three kinds:

* ``link`` — i, j, k lie on one rigid link: all three distances are link dimensions and
  the sign of the oriented area A_{i,j,k} is fixed by the link's shape;
* ``cross`` — s_{i,k} and s_{j,k} are dimensions of the two different links that joint k
  connects; s_{i,j} is a link dimension, a parameter or computed through the plan
  (s_{i,j} = det(M_j - M_i) s_ref, thesis eq. 2.20); the sign of A_{i,j,k} is free;
* ``parameter`` — no joint can be located any more, so an unknown squared distance
  s_{i,k} becomes a parameter and k is located from it and a known s_{j,k}; free sign.

Every link dimension the plan does not enforce is a **closure condition**
s_{u,v} = det(M_v - M_u) s_ref. The minimum number of parameters over all plans is the
chain's coupling degree (thesis ch. 3).
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass
from enum import Enum

from baranov.topology import distance_name, thesis_subscript


def parameter_name(pair: tuple[str, str], sliders: Collection[str] = ()) -> str:
    """The name of a plan's parameter, the squared distance of a joint pair (thesis §2.2):
    ``("P1", "P6")`` → ``"s1,6"``; where one joint is a slider (among ``sliders``), the
    oriented distance t of the other to its axis (thesis §4.2.4): ``"t1,6"``.

    >>> parameter_name(("P1", "P6")), parameter_name(("P1", "P6"), sliders=["P1"])
    ('s1,6', 't1,6')
    """
    if set(pair) & set(sliders):  # oriented, so in the order given
        return f"t{thesis_subscript(pair[0])},{thesis_subscript(pair[1])}"
    return distance_name(*pair)


class StepKind(str, Enum):
    """How a step locates its joint (see the module docstring)."""

    LINK = "link"
    CROSS = "cross"
    PARAMETER = "parameter"


class DistanceKind(str, Enum):
    """Where the squared distance s_{i,j} of a step's base comes from."""

    KNOWN = "known"          # a link dimension
    PARAMETER = "parameter"  # one of the plan's unknowns
    COMPUTED = "computed"    # det(M_j - M_i) s_ref through the plan


@dataclass(frozen=True)
class Step:
    """Locate ``joint`` (k) from ``base`` = (i, j): p_{i,k} = Z_{i,j,k} p_{i,j}.

    Attributes
    ----------
    joint
        the located joint k.
    base
        the two located joints (i, j).
    kind
        link, cross or parameter step.
    link
        the rigid link of a ``link`` step (its shape fixes the sign), else None.
    base_distance
        whether s_{i,j} is known, a parameter, or computed.
    radical_depth
        nesting of square roots in M_k: 0 when every radicand is a
        constant, 1 when a radicand holds a parameter, 1 + d when it holds a
        distance computed from matrices of depth d.
    """

    joint: str
    base: tuple[str, str]
    kind: StepKind
    link: int | None
    base_distance: DistanceKind
    radical_depth: int

    @property
    def triangle(self) -> tuple[str, str, str]:
        """The triangle (i, j, k) of the bilateration, in the thesis's Z_{i,j,k} order."""
        return (self.base[0], self.base[1], self.joint)

    @property
    def free_sign(self) -> bool:
        """Whether the sign of the oriented area A_{i,j,k} is a branch to explore."""
        return self.kind is not StepKind.LINK


@dataclass(frozen=True)
class Plan:
    """A complete bilateration plan for a rigid chain.

    Attributes
    ----------
    reference
        the pair (a, b) of the reference vector p_{a,b}.
    parameters
        the unknown squared distances, as joint pairs; the reference pair
        first when it is not a link dimension.
    steps
        the bilaterations, in order; every joint but a and b is located once.
    closure_pairs
        link dimensions the plan does not enforce: each gives a closure
        condition s_{u,v} = det(M_v - M_u) s_ref.
    orientation_checks
        triangles (u, v, x) of a rigid link whose orientation the
        plan does not fix by construction; a configuration must show the link's sign.
    """

    reference: tuple[str, str]
    parameters: tuple[tuple[str, str], ...]
    steps: tuple[Step, ...]
    closure_pairs: tuple[tuple[str, str], ...]
    orientation_checks: tuple[tuple[str, str, str], ...] = ()

    @property
    def number_of_parameters(self) -> int:
        return len(self.parameters)

    @property
    def free_sign_triangles(self) -> tuple[tuple[str, str, str], ...]:
        """Triangles whose orientation sign is free: 2^m branches for m of them."""
        return tuple(step.triangle for step in self.steps if step.free_sign)

    @property
    def radical_depth(self) -> int:
        """Deepest nesting of square roots over all steps."""
        return max((step.radical_depth for step in self.steps), default=0)

    def ranking_key(self) -> tuple:
        """Plans compare by: fewer parameters; fewer closure conditions and orientation
        checks beyond one per parameter; fewer free-sign triangles; shallower, then
        fewer, nested radicals; then names, so the order is total and deterministic."""
        extra = len(self.closure_pairs) + len(self.orientation_checks) - len(self.parameters)
        depths = sorted((step.radical_depth for step in self.steps), reverse=True)
        return (
            len(self.parameters),
            extra,
            len(self.free_sign_triangles),
            tuple(depths),
            self.reference,
            self.parameters,
            tuple(step.triangle for step in self.steps),
        )

    def to_dict(self) -> dict:
        """JSON-ready form (used by the catalog)."""
        return {
            "reference": list(self.reference),
            "parameters": [list(p) for p in self.parameters],
            "steps": [
                {"joint": s.joint, "base": list(s.base), "kind": s.kind.value, "link": s.link,
                 "base_distance": s.base_distance.value}
                for s in self.steps
            ],
            "free_sign_triangles": [list(t) for t in self.free_sign_triangles],
            "closure_pairs": [list(p) for p in self.closure_pairs],
            "orientation_checks": [list(t) for t in self.orientation_checks],
        }

    def describe(self, sliders: Collection[str] = ()) -> str:
        """Multi-line text in the thesis's notation; a parameter with one of ``sliders``
        is named t (:func:`parameter_name`).

        Example line: ``P2 = Z1,3,2 (link L0)``.
        """
        a, b = self.reference
        lines = [f"reference pair {a}, {b}"]
        if self.parameters:
            lines.append("parameters " + ", ".join(parameter_name(pair, sliders) for pair in self.parameters))
        for step in self.steps:
            i, j, k = step.triangle
            how = {StepKind.LINK: f"link L{step.link}, fixed sign", StepKind.CROSS: "free sign",
                   StepKind.PARAMETER: "free sign, parameter"}[step.kind]
            lines.append(f"{k}: Z{thesis_subscript(i)},{thesis_subscript(j)},{thesis_subscript(k)} ({how})")
        for u, v in self.closure_pairs:
            lines.append(f"closure {distance_name(u, v)}")
        for u, v, x in self.orientation_checks:
            lines.append(f"orientation check A{thesis_subscript(u)},{thesis_subscript(v)},{thesis_subscript(x)}")
        return "\n".join(lines)
