"""Bilateration plans: locate every joint of a rigid chain through the fewest unknown
distances (the coupling degree), with ranked alternatives and user constraints; and of a
one-degree-of-freedom chain, whose configuration space they parametrise (thesis §6.4)."""

from .plan import DistanceKind, Plan, Step, StepKind, parameter_name
from .search import (
    ALTERNATIVE_PLANS,
    best_plan,
    bilateration_plans,
    clear_plan_cache,
    coupling_degree,
    one_dof_plans,
    parametrising_distances,
    plan_avoiding,
    plans_avoiding,
)
from .sliders import SliderPlanError, slider_plan, slider_plan_obstacle

__all__ = [
    "ALTERNATIVE_PLANS",
    "DistanceKind",
    "Plan",
    "Step",
    "SliderPlanError",
    "StepKind",
    "best_plan",
    "bilateration_plans",
    "clear_plan_cache",
    "coupling_degree",
    "one_dof_plans",
    "parameter_name",
    "parametrising_distances",
    "plan_avoiding",
    "plans_avoiding",
    "slider_plan",
    "slider_plan_obstacle",
]
