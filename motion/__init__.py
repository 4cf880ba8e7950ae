"""One-degree-of-freedom chains (thesis ch. 6): their configuration spaces in distance
space (:mod:`.configuration_space`), their tracing into pieces joined at branch points
(:mod:`.tracing`), its ranges computed exactly for one parameter (:mod:`.exact_ranges`) and the
degrees of their coupler curves (:mod:`.coupler_curves`). The
Grübler chains are enumerated in :mod:`baranov.enumerate.grubler` and planned by
:func:`baranov.planner.one_dof_plans`."""

from .configuration_space import ConfigurationPoint, OneDofSystem, configurations_at, one_dof_system, sign_index
from .coupler_curves import CouplerCurveError, coupler_curve_degree
from .dead_points import DeadPoint, dead_points
from .exact_ranges import ExactRange, ExactRanges, RangeEnd, certified_pieces, exact_ranges
from .tracing import BranchPoint, Circuit, Piece, SingularPoint, Trace, circuit_of, trace

__all__ = ["BranchPoint", "Circuit", "ConfigurationPoint", "CouplerCurveError", "DeadPoint", "ExactRange", "ExactRanges",
           "OneDofSystem", "Piece", "RangeEnd", "SingularPoint", "Trace", "certified_pieces", "circuit_of",
           "configurations_at", "coupler_curve_degree", "dead_points", "exact_ranges", "one_dof_system", "sign_index", "trace"]
