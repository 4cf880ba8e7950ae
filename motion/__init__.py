"""One-degree-of-freedom chains (thesis ch. 6): their configuration spaces in distance
space (:mod:`.configuration_space`) and their tracing into pieces joined at branch points
(:mod:`.tracing`). The Grübler chains are enumerated in :mod:`baranov.enumerate.grubler`
and planned by :func:`baranov.planner.one_dof_plans`."""

from .configuration_space import ConfigurationPoint, OneDofSystem, configurations_at, one_dof_system, sign_index
from .tracing import BranchPoint, Piece, Trace, trace

__all__ = ["BranchPoint", "ConfigurationPoint", "OneDofSystem", "Piece", "Trace", "configurations_at",
           "one_dof_system", "sign_index", "trace"]
