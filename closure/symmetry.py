"""Symmetric closure conditions from automorphisms (thesis §2.7.1, Appendix A).

An automorphism of a chain permutes its joints and maps the chain onto itself, so
renaming the joints of a plan by it gives a valid plan of the same chain, and renaming a
closure condition gives a valid condition of that symmetric plan. The thesis uses this
to write one condition and obtain the others: for the pentad, [1 2 3 4 5 6 → 1 3 2 4 6 5]
maps s2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6 to
s3,6 = det(I - Z1,2,3 Z1,5,2 - Z5,4,6 Z5,1,4) s1,5; for 9/B25–B28, a permutation that
maps the parameter set onto itself turns the first condition into the second.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from baranov.planner import Plan, Step
from baranov.topology import Automorphism, KinematicChain, list_automorphisms

from .conditions import (
    ClosureSystem,
    DistanceCondition,
    MatrixExpression,
    _sorted_polynomial,
    closure_system,
)


def joint_mapping(chain: KinematicChain, automorphism: Automorphism) -> dict[str, str]:
    """The automorphism as a map joint name → image joint name."""
    return {joint.name: image for joint, image in zip(chain.joints, automorphism.joints, strict=True)}


def permute_expression(expression: MatrixExpression, mapping: Mapping[str, str]) -> MatrixExpression:
    """Rename the joints of every Z_{i,j,k} in ``expression``."""
    terms: dict = {}
    for monomial, coefficient in expression.terms:
        key = tuple(tuple(mapping[n] for n in triangle) for triangle in monomial)
        terms[key] = terms.get(key, 0) + coefficient
    return MatrixExpression(_sorted_polynomial(terms))


def permute_condition(condition: DistanceCondition, mapping: Mapping[str, str]) -> DistanceCondition:
    """Rename the joints of a condition: the thesis's "application of the permutation".

    >>> from baranov.literature.trusses import thesis_truss
    >>> from baranov.planner import bilateration_plans
    >>> plan = bilateration_plans(thesis_truss("5/B1").chain(), reference=("P1", "P6"))[0]
    >>> condition = closure_system(plan).conditions[0]
    >>> condition.text()
    's2,5 = det(I - Z1,3,2 Z1,6,3 - Z6,4,5 Z6,1,4) s1,6'
    >>> swap = {"P1": "P1", "P2": "P3", "P3": "P2", "P4": "P4", "P5": "P6", "P6": "P5"}
    >>> permute_condition(condition, swap).text()
    's3,6 = det(I - Z1,2,3 Z1,5,2 - Z5,4,6 Z5,1,4) s1,5'
    """
    return DistanceCondition(
        tuple(mapping[n] for n in condition.pair),
        permute_expression(condition.omega, mapping),
        tuple(mapping[n] for n in condition.reference),
    )


def permute_plan(plan: Plan, mapping: Mapping[str, str], link_mapping: Mapping[int, int] | None = None) -> Plan:
    """Rename the joints (and links, when ``link_mapping`` is given) of a plan."""
    def rename(names):
        return tuple(mapping[n] for n in names)

    steps = tuple(
        Step(mapping[s.joint], rename(s.base), s.kind,
             s.link if s.link is None or link_mapping is None else link_mapping[s.link],
             s.base_distance, s.radical_depth)
        for s in plan.steps
    )
    return Plan(
        reference=rename(plan.reference),
        parameters=tuple(rename(p) for p in plan.parameters),
        steps=steps,
        closure_pairs=tuple(rename(p) for p in plan.closure_pairs),
        orientation_checks=tuple(rename(t) for t in plan.orientation_checks),
    )


def _plan_identity(plan: Plan) -> tuple:
    """What makes two plans the same construction, independent of step order among
    equivalent presentations: reference, parameter set, and the set of steps."""
    return (
        frozenset(plan.reference),
        frozenset(frozenset(p) for p in plan.parameters),
        frozenset((s.joint, s.base, s.kind) for s in plan.steps),
    )


def symmetric_variants(plan: Plan, chain: KinematicChain) -> list[tuple[Automorphism, Plan]]:
    """One plan per image of ``plan`` under the automorphism group (the identity first):
    ``|Aut| / |stabiliser|`` plans, all with the same ranking qualities, among which a solver
    may pick the best conditioned for given dimensions.

    >>> from baranov.literature.trusses import thesis_truss
    >>> from baranov.planner import bilateration_plans
    >>> pentad = thesis_truss("5/B1").chain()
    >>> plan = bilateration_plans(pentad, reference=("P1", "P6"))[0]
    >>> variants = symmetric_variants(plan, pentad)  # |Aut| = 12, stabiliser of order 2
    >>> len(variants), variants[1][1].reference
    (6, ('P1', 'P5'))
    """
    seen = set()
    variants = []
    for automorphism in list_automorphisms(chain):
        image = permute_plan(plan, joint_mapping(chain, automorphism), dict(enumerate(automorphism.links)))
        identity = _plan_identity(image)
        if identity not in seen:
            seen.add(identity)
            variants.append((automorphism, image))
    return variants


def conditions_by_symmetry(system: ClosureSystem, chain: KinematicChain) -> list[tuple[Automorphism, ClosureSystem]]:
    """Automorphisms (not the identity) that map the plan's set of parameters onto itself,
    with the closure system of the permuted plan: its conditions are valid equations in
    the *same* parameters, e.g. the second condition of a coupling-degree-2 truss from the
    first (Appendix A, 9/B25–B28)."""
    parameters = frozenset(frozenset(p) for p in system.plan.parameters)
    result = []
    for automorphism in list_automorphisms(chain)[1:]:
        mapping = joint_mapping(chain, automorphism)
        if frozenset(frozenset(mapping[n] for n in p) for p in parameters) != parameters:
            continue
        image = permute_plan(system.plan, mapping, dict(enumerate(automorphism.links)))
        result.append((automorphism, closure_system(image)))
    return result


@dataclass(frozen=True)
class SymmetricFormulation:
    """A plan's first closure condition and its image under an automorphism that maps the
    plan's parameter set onto itself: two conditions in the same parameters, the second
    derived by permutation (Appendix A's treatment of 9/B25–B28).

    Attributes
    ----------
    plan
        the plan the first condition comes from.
    automorphism
        the permutation that derives the second condition.
    system
        the plan's closure system.
    image
        the closure system of the permuted plan (its first condition is the
        derived one; its computed distances are the ones the derived condition uses).
    """

    plan: Plan
    automorphism: Automorphism
    system: ClosureSystem
    image: ClosureSystem

    @property
    def conditions(self) -> tuple[DistanceCondition, DistanceCondition]:
        return self.system.conditions[0], self.image.conditions[0]


def symmetric_formulation(chain: KinematicChain, count: int = 10**6) -> SymmetricFormulation | None:
    """The best-ranked minimal plan (among the ``count`` best) whose parameter set an
    automorphism preserves while moving its first closure condition to another link
    dimension, or ``None`` if there is none.

    >>> from baranov.literature.trusses import thesis_truss
    >>> found = symmetric_formulation(thesis_truss("9/B28").chain())
    >>> [c.pair for c in found.conditions]
    [('P3', 'P4'), ('P3', 'P8')]
    """
    from baranov.planner import (
        bilateration_plans,  # deferred: planner imports are heavy
    )

    for plan in bilateration_plans(chain, count=count):
        if not plan.closure_pairs:
            return None
        system = closure_system(plan)
        for automorphism, image in conditions_by_symmetry(system, chain):
            if frozenset(image.conditions[0].pair) != frozenset(system.conditions[0].pair):
                return SymmetricFormulation(plan, automorphism, system, image)
    return None
