"""Numeric evaluation of closure conditions, vectorised over parameter values and
free-sign branches (what a solving backend consumes).

Joint positions relative to the reference are complex numbers M_k (thesis §2.4: a
perpendicular matrix is a complex number), so a whole plan evaluates with numpy complex
arithmetic. A radicand that is negative — the triangle cannot be built for that
parameter value — yields NaN, which propagates to the residuals.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from itertools import product

import numpy as np

from baranov.topology import KinematicChain
from baranov.topology.graphs import joints_of_links

from .bilateration import bilateration_matrix
from .conditions import ClosureSystem, DistanceCondition, MatrixExpression

Triangle = tuple[str, str, str]
Pair = frozenset[str]


def sign_branches(count: int) -> np.ndarray:
    """All 2^count sign combinations, shape (2^count, count), first all +1.

    >>> sign_branches(2).tolist()
    [[1, 1], [1, -1], [-1, 1], [-1, -1]]
    """
    return np.array(list(product((1, -1), repeat=count)), dtype=int).reshape(2**count, count)


class CompiledSystem:
    """A closure system bound to concrete link dimensions.

    Args:
        system: the closure system of a plan.
        known: squared distance of every pair of joints on a common link.
        fixed_signs: orientation sign (±1) of every fixed-sign (link-step) triangle of the
            plan, keyed by the step's triangle (i, j, k).
    """

    def __init__(self, system: ClosureSystem, known: Mapping[Pair, float], fixed_signs: Mapping[Triangle, int]):
        self.system = system
        self.plan = system.plan
        self.known = {frozenset(k): float(v) for k, v in known.items()}
        self.fixed_signs = dict(fixed_signs)
        self.parameters = self.plan.parameters
        self.free_triangles = self.plan.free_sign_triangles
        self._parameter_index = {frozenset(p): n for n, p in enumerate(self.parameters)}
        for step in self.plan.steps:
            if not step.free_sign and step.triangle not in self.fixed_signs:
                raise ValueError(f"triangle {step.triangle}: orientation sign of a link step missing")

    def matrices(self, parameter_values: np.ndarray, signs: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
        """M_k for every joint, and s_ref, broadcast over branches and parameter values.

        ``parameter_values`` has shape (N, p) (p = number of parameters), ``signs`` shape
        (B, m) (m = free-sign triangles); results have shape (B, N).
        """
        matrices, s_ref, *_ = self._evaluate(parameter_values, signs)
        return matrices, s_ref

    def first_failures(self, parameter_values: np.ndarray, signs: np.ndarray) -> np.ndarray:
        """For every branch and parameter value, the index of the first step whose triangle
        cannot be built (negative radicand), or the number of steps where all can; shape
        (B, N). Where neighbouring values fail at different steps, a feasible window may
        lie between them even if no sample falls inside it."""
        return self._evaluate(parameter_values, signs)[2]

    def failure_profile(self, parameter_values: np.ndarray,
                        signs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`first_failures`; where a step fails, its radicand relative to the squared
        largest side (negative; NaN where all steps succeed); and the relative radicands of
        the free-sign steps, shape (B, N, free), NaN where undefined. A window between two
        values failing at the same step shows as a local maximum of that radicand; an
        undefined gap between two defined values, as a local minimum of one free-sign
        step's radicand."""
        _, _, failures, radicands, margins = self._evaluate(parameter_values, signs, profile=True)
        return failures, radicands, np.stack(margins, axis=-1) if margins else np.zeros((*failures.shape, 0))

    def paired_matrices(self, parameter_values: np.ndarray, signs: np.ndarray) -> dict[str, np.ndarray]:
        """M_k for every joint, point n on branch ``signs[n]``; shape (N,)."""
        matrices, *_ = self._evaluate(parameter_values, signs, paired=True)
        return {joint: value[0] for joint, value in matrices.items()}

    def paired_residuals(self, parameter_values: np.ndarray, signs: np.ndarray) -> np.ndarray:
        """Relative closure residuals of point n on branch ``signs[n]``: shape (N, c) for
        ``parameter_values`` of shape (N, p) and ``signs`` of shape (N, m) (candidates of
        different branches refined together)."""
        matrices, s_ref, *_ = self._evaluate(parameter_values, signs, paired=True)
        return self._closure_residuals(matrices, s_ref)[0]

    def paired_residuals_and_failures(self, parameter_values: np.ndarray,
                                      signs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """In one evaluation, for point n on branch ``signs[n]``: :meth:`paired_residuals`,
        shape (N, c), and :meth:`first_failures`, shape (N,)."""
        matrices, s_ref, failures, *_ = self._evaluate(parameter_values, signs, paired=True)
        return self._closure_residuals(matrices, s_ref)[0], failures[0]

    def _evaluate(self, parameter_values: np.ndarray, signs: np.ndarray, profile: bool = False,
                  paired: bool = False):
        values = np.asarray(parameter_values, dtype=float)
        if values.ndim == 1:
            values = values[:, None]
        signs = np.asarray(signs, dtype=float)
        shape = (1, values.shape[0]) if paired else (signs.shape[0], values.shape[0])
        parameter = [np.broadcast_to(values[None, :, n], shape) for n in range(values.shape[1])]
        a, b = self.plan.reference
        s_ref = self._distance(a, b, parameter, None, {})
        matrices: dict[str, np.ndarray] = {a: np.zeros(shape, complex), b: np.ones(shape, complex)}
        failures = np.full(shape, len(self.plan.steps))
        radicands = np.full(shape, np.nan)
        margins = []
        free = 0
        for index, step in enumerate(self.plan.steps):
            i, j = step.base
            k = step.joint
            s_ij = self._distance(i, j, parameter, s_ref, matrices)
            s_ik = self._distance(i, k, parameter, s_ref, matrices)
            s_jk = self._distance(j, k, parameter, s_ref, matrices)
            if step.free_sign:
                sign = signs[:, free][None, :] if paired else signs[:, free][:, None]
                free += 1
            else:
                sign = self.fixed_signs[step.triangle]
            z = bilateration_matrix(s_ij, s_ik, s_jk, sign)
            with np.errstate(invalid="ignore"):  # an undefined step (inf · 0) is NaN: marked failed below
                matrices[k] = matrices[i] + z * (matrices[j] - matrices[i])
            failed = ~np.isfinite(matrices[k])
            newly = (failures == len(self.plan.steps)) & failed
            failures = np.where(newly, index, failures)
            if profile:
                with np.errstate(invalid="ignore"):
                    scale = np.maximum(np.maximum(s_ij, s_ik), s_jk) ** 2
                    radicand = ((s_ij + s_ik + s_jk) ** 2 - 2 * (s_ij**2 + s_ik**2 + s_jk**2)) / scale
                radicands = np.where(newly, radicand, radicands)
                if step.free_sign:
                    margins.append(radicand)
        return matrices, s_ref, failures, radicands, margins

    def _distance(self, u: str, v: str, parameter, s_ref, matrices) -> np.ndarray:
        pair = frozenset((u, v))
        if pair in self.known:
            return self.known[pair]
        if pair in self._parameter_index:
            return parameter[self._parameter_index[pair]]
        return np.abs(matrices[v] - matrices[u]) ** 2 * s_ref

    def residuals(self, parameter_values: np.ndarray, signs: np.ndarray | None = None) -> np.ndarray:
        """Relative closure residuals (computed s_{u,v} - known s_{u,v}) / known s_{u,v},
        shape (B, N, c) for B branches (all 2^m when ``signs`` is None), N parameter
        values and c conditions. NaN where a radicand is negative."""
        if signs is None:
            signs = sign_branches(len(self.free_triangles))
        matrices, s_ref = self.matrices(parameter_values, signs)
        return self._closure_residuals(matrices, s_ref)

    def _closure_residuals(self, matrices: dict[str, np.ndarray], s_ref: np.ndarray) -> np.ndarray:
        shape = np.shape(next(iter(matrices.values())))
        columns = []
        for u, v in self.plan.closure_pairs:
            target = self.known[frozenset((u, v))]
            columns.append((np.abs(matrices[v] - matrices[u]) ** 2 * s_ref - target) / target)
        if not columns:
            return np.zeros((*shape, 0))
        return np.stack(columns, axis=-1)


def known_distances(chain: KinematicChain, coordinates: Mapping[str, Sequence[float]]) -> dict[Pair, float]:
    """Squared distances of all joint pairs on a common link, from joint coordinates."""
    known = {}
    for names in joints_of_links(chain):
        for x in range(len(names)):
            for y in range(x + 1, len(names)):
                p, q = np.asarray(coordinates[names[x]], float), np.asarray(coordinates[names[y]], float)
                known[frozenset((names[x], names[y]))] = float(np.sum((p - q) ** 2))
    return known


def orientation_sign(coordinates: Mapping[str, Sequence[float]], triangle: Triangle) -> int:
    """Sign of the oriented area A_{i,j,k}: +1 when P_k lies left of p_{i,j}."""
    (xi, yi), (xj, yj), (xk, yk) = (coordinates[n] for n in triangle)
    cross = (xj - xi) * (yk - yi) - (yj - yi) * (xk - xi)
    return 1 if cross > 0 else -1


def compile_from_coordinates(system: ClosureSystem, chain: KinematicChain, coordinates) -> CompiledSystem:
    """Bind ``system`` to the dimensions of the configuration ``coordinates`` (joint name
    → (x, y)); link-step signs are read from the same configuration."""
    signs = {s.triangle: orientation_sign(coordinates, s.triangle) for s in system.plan.steps if not s.free_sign}
    return CompiledSystem(system, known_distances(chain, coordinates), signs)


def true_parameters_and_signs(system: ClosureSystem, coordinates) -> tuple[np.ndarray, np.ndarray]:
    """The parameter values and free signs that the configuration ``coordinates`` realises."""
    def squared(u, v):
        return float(np.sum((np.asarray(coordinates[u], float) - np.asarray(coordinates[v], float)) ** 2))

    values = np.array([[squared(u, v) for u, v in system.plan.parameters]])
    signs = np.array([[orientation_sign(coordinates, t) for t in system.plan.free_sign_triangles]], dtype=float)
    return values, signs


def value_at_configuration(expression: MatrixExpression, coordinates) -> complex:
    """Ω evaluated at a configuration, with Z_{i,j,k} = (P_k - P_i) / (P_j - P_i) as complex
    numbers (exactly what bilateration computes there, thesis eq. 2.6).

    An expression is right for a closure s_{u,v} = det(Ω) s_{a,b} exactly when
    |Ω|² s_{a,b} = s_{u,v} on every configuration; this needs no radicals, so it checks
    the *structure* of a derivation or a transcription independently of the evaluator.
    """
    point = {name: complex(*coordinates[name]) for name in coordinates}
    total = 0j
    for monomial, coefficient in expression.terms:
        product = complex(coefficient)
        for i, j, k in monomial:
            product *= (point[k] - point[i]) / (point[j] - point[i])
        total += product
    return total


def condition_residual_at_configuration(condition: DistanceCondition, coordinates) -> float:
    """Relative residual of ``s_{u,v} = det(Ω) s_ref`` at a configuration (see
    :func:`value_at_configuration`)."""
    def squared(u, v):
        return abs(complex(*coordinates[v]) - complex(*coordinates[u])) ** 2

    target = squared(*condition.pair)
    value = abs(value_at_configuration(condition.omega, coordinates)) ** 2 * squared(*condition.reference)
    return (value - target) / target


__all__ = [
    "condition_residual_at_configuration",
    "value_at_configuration",
    "CompiledSystem",
    "compile_from_coordinates",
    "known_distances",
    "orientation_sign",
    "sign_branches",
    "true_parameters_and_signs",
]
