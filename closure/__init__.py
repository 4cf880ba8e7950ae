"""Closure conditions in bilateration matrices: derivation from a plan, symmetric
variants from automorphisms, text/LaTeX/sympy forms, and compiled numeric evaluators."""

from .bilateration import (
    bilaterated,
    bilateration_matrix,
    oriented_area,
    perpendicular_matrix,
    place_joints,
    squared_distance,
    triangle_radicand,
)
from .conditions import (
    ClosureSystem,
    DistanceCondition,
    MatrixExpression,
    closure_system,
    sympy_condition,
)
from .evaluate import CompiledSystem, compile_from_coordinates, distinct_branches, sign_branches
from .notation import parse_matrix_expression
from .symmetry import (
    SymmetricFormulation,
    conditions_by_symmetry,
    permute_condition,
    permute_plan,
    symmetric_formulation,
    symmetric_variants,
)

__all__ = [
    "ClosureSystem",
    "CompiledSystem",
    "compile_from_coordinates",
    "conditions_by_symmetry",
    "parse_matrix_expression",
    "permute_condition",
    "permute_plan",
    "distinct_branches",
    "sign_branches",
    "SymmetricFormulation",
    "symmetric_formulation",
    "symmetric_variants",
    "DistanceCondition",
    "MatrixExpression",
    "bilaterated",
    "bilateration_matrix",
    "closure_system",
    "oriented_area",
    "perpendicular_matrix",
    "place_joints",
    "squared_distance",
    "sympy_condition",
    "triangle_radicand",
]
