"""One-degree-of-freedom chains (thesis ch. 6): their configuration spaces in distance
space (:mod:`.configuration_space`), their tracing into pieces joined at branch points
(:mod:`.tracing`) and the degrees of their coupler curves (:mod:`.coupler_curves`). The
Grübler chains are enumerated in :mod:`baranov.enumerate.grubler` and planned by
:func:`baranov.planner.one_dof_plans`."""

from .configuration_space import ConfigurationPoint, OneDofSystem, configurations_at, one_dof_system, sign_index
from .coupler_curves import CouplerCurveError, coupler_curve_degree
from .tracing import BranchPoint, Piece, Trace, trace

__all__ = ["BranchPoint", "ConfigurationPoint", "CouplerCurveError", "OneDofSystem", "Piece", "Trace",
           "configurations_at", "coupler_curve_degree", "one_dof_system", "sign_index", "trace"]
