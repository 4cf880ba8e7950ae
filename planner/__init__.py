"""Bilateration plans: locate every joint of a rigid chain through the fewest unknown
distances (the coupling degree), with ranked alternatives and user constraints."""

from .plan import DistanceKind, Plan, Step, StepKind, parameter_name
from .search import ALTERNATIVE_PLANS, best_plan, bilateration_plans, coupling_degree, plan_avoiding
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
    "coupling_degree",
    "parameter_name",
    "plan_avoiding",
    "slider_plan",
    "slider_plan_obstacle",
]
