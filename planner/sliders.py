"""Plans for chains with slider joints (thesis ch. 4): a truss plan whose steps the
slider constructions of :mod:`baranov.closure.sliders` can run.

A slider chain has the plans of its Baranov truss (the sliders taken as revolute joints,
thesis §4.2: "the closure conditions for the Baranov trusses ... can be directly used");
every step that touches a slider becomes the limit of its bilateration; a reference pair
with a slider puts the frame on its axis (thesis §4.2.4). A few steps have no such limit
among the constructions implemented: a reference or parameter pair made of two sliders
(the thesis avoids them: "can always be avoided because all kinematic loops of an Assur
kinematic chain contain at least one revolute joint"), and a slider located from two
sliders unless all three are joints of one link whose two axes are already placed
together (thesis §5.2.1.3: every joint of a non-binary link a slider; the link's two
placed axes fix it, and its third axis with it). A closure pair of two sliders (two
joints of one link, as every closure pair) compares the turn between their placed axes
with the link's (thesis §4.2.3's cosine theorem). A parameter pair with one slider is the
oriented distance t of the other joint to its axis (thesis §4.2.4).
"""

from __future__ import annotations

from collections.abc import Collection

from baranov.topology import KinematicChain, TopologyError

from .plan import Plan, StepKind
from .search import bilateration_plans

#: How many of the best plans of each number of parameters :func:`slider_plan` tries: all
#: those of a nine-link truss of coupling degree 1 (at most 132), and, on 9/B25–B28, the
#: suitable plan of 73 slider chains of the catalog that the 50 best lacked
#: (bench/slider_plans_with_more_parameters.py). The search costs ≤ 0.1 s a truss, cached.
SLIDER_PLANS = 300


class SliderPlanError(TopologyError):
    """No plan of the truss's best ones suits the slider joints; the message says why."""


def slider_plan_obstacle(plan: Plan, sliders: Collection[str]) -> str | None:
    """Why the slider constructions cannot run ``plan`` with the slider joints
    ``sliders``, or None if they can. O(steps).

    >>> from baranov.literature.trusses import thesis_truss
    >>> from baranov.planner import best_plan
    >>> plan = best_plan(thesis_truss("5/B1").chain())
    >>> slider_plan_obstacle(plan, plan.reference)
    'reference pair p1,2 joins two sliders'
    """
    sliders = set(sliders)

    def name(pair: tuple[str, str]) -> str:
        return "p" + ",".join(joint.lstrip("P") for joint in pair)

    if set(plan.reference) <= sliders:
        return f"reference pair {name(plan.reference)} joins two sliders"
    for pair in plan.parameters:
        if set(pair) <= sliders:
            return f"parameter pair {name(pair)} joins two sliders"
    together: set[frozenset[str]] = set()  # pairs placed by one step, hence consistent
    for step in plan.steps:
        if set(step.triangle) <= sliders and not (step.kind is StepKind.LINK and frozenset(step.base) in together):
            return f"step {step.joint} from {', '.join(step.base)}: three sliders"
        together.update(frozenset((step.joint, joint)) for joint in step.base)
    return None


def slider_plan(chain: KinematicChain, sliders: Collection[str], count: int = SLIDER_PLANS,
                parameters: Collection[tuple[str, str]] | None = None, extra_parameters: int = 0) -> Plan:
    """The best plan of ``chain`` (with ``sliders`` taken as revolute joints), among its
    ``count`` best, that the slider constructions can run (:func:`slider_plan_obstacle`);
    raises :class:`SliderPlanError` naming the best plan's obstacle if none can. The best
    plan itself when there are no sliders. ``parameters``: only plans whose parameters are
    among these pairs (thesis §5.2.2 works in s1,6). ``extra_parameters``: where none of
    the fewest parameters suits, the ``count`` best with one more, and so on up to this
    many more (9/N24 with sliders P1, P2, P4, P6, P8, P10, P11: none of its 300 best plans
    of one parameter suits, its best of two does; tests/test_sliders.py).
    Cost: that of :func:`~baranov.planner.bilateration_plans` with ``count`` plans, once
    per number of parameters tried.

    >>> from baranov.literature.trusses import thesis_truss
    >>> from baranov.planner import best_plan
    >>> truss = thesis_truss("7/B3").chain()
    >>> slider_plan(truss, ["P1"]) == best_plan(truss)  # a slider in the reference: the frame on its axis
    True
    """
    first = None
    for extra in range(extra_parameters + 1 if sliders else 1):
        try:
            plans = bilateration_plans(chain, count if sliders else 1, parameters=parameters, extra_parameters=extra)
        except TopologyError:
            if not extra:
                raise
            break  # no plan with that many parameters meets ``parameters``
        if not plans:
            raise SliderPlanError(f"no plan of the chain has its parameters among {sorted(parameters or ())}")
        first = first or plans
        for plan in plans:
            if slider_plan_obstacle(plan, sliders) is None:
                return plan
    more = f", nor of their best with up to {extra_parameters} more parameters" if extra_parameters else ""
    raise SliderPlanError(f"sliders {', '.join(sorted(sliders))}: none of the {len(first)} best plans suits them "
                          f"(the best: {slider_plan_obstacle(first[0], sliders)}){more}")
