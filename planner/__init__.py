"""Bilateration plans: locate every joint of a rigid chain through the fewest unknown
distances (the coupling degree), with ranked alternatives and user constraints."""

from .plan import DistanceKind, Plan, Step, StepKind
from .search import best_plan, bilateration_plans, coupling_degree

__all__ = ["DistanceKind", "Plan", "Step", "StepKind", "best_plan", "bilateration_plans", "coupling_degree"]
