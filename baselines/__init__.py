"""Baselines a user would otherwise pick, behind the same interface as the project's
backends (a :class:`baranov.solvers.Solution`): Cartesian least squares from random
starts, loop equations eliminated by resultants, and the characteristic polynomial
rounded to floats. Used by ``bench/speed_vs_accuracy.py`` and the stability study."""

from .cartesian import cartesian_size, solve_cartesian
from .float_polynomial import FloatPolynomialError, float_roots, solve_float_polynomial
from .loop_equations import (
    LoopEquationError,
    loop_equations,
    loop_size,
    solve_loop_equations,
)

__all__ = [
    "FloatPolynomialError", "LoopEquationError", "cartesian_size", "float_roots", "loop_equations", "loop_size",
    "solve_cartesian", "solve_float_polynomial", "solve_loop_equations",
]
