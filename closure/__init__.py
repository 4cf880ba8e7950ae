"""Closure conditions in bilateration matrices: derivation from a plan, symmetric
variants from automorphisms, text/LaTeX/sympy forms, and compiled numeric evaluators."""

from .bilateration import bilateration_matrix, oriented_area, perpendicular_matrix
from .conditions import ClosureSystem, DistanceCondition, MatrixExpression, closure_system, sympy_condition

__all__ = [
    "ClosureSystem",
    "DistanceCondition",
    "MatrixExpression",
    "bilateration_matrix",
    "closure_system",
    "oriented_area",
    "perpendicular_matrix",
    "sympy_condition",
]
