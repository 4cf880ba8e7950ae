"""Numeric evaluation of closure conditions, vectorised over parameter values and
free-sign branches (what a solving backend consumes).

Joint positions relative to the reference are complex numbers M_k (thesis §2.4: a
perpendicular matrix is a complex number), so a whole plan evaluates with numpy complex
arithmetic. A radicand that is negative — the triangle cannot be built for that
parameter value — yields NaN, which propagates to the residuals.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable, Collection, Mapping, Sequence
from itertools import product
from typing import NamedTuple

import numpy as np

from baranov.planner import parameter_name
from baranov.topology import KinematicChain
from baranov.topology.graphs import joints_of_links

from .bilateration import (
    dehomogenised,
    factored_radicand,
    parameter_triangles,
    place_joints,
    signed_root,
    small_term_radicand,
)
from .conditions import ClosureSystem, DistanceCondition, MatrixExpression
from .sliders import SearchedParameter, SliderGeometry, SliderPlacement, takes_root, turn_residual
from .straight_line import StraightLineProgram, compiled_kernel_in_use, count_numpy_seconds, run_program, trace_plan
from .traced_sliders import slider_constant_values

Triangle = tuple[str, str, str]
Pair = frozenset[str]


def sign_branches(count: int) -> np.ndarray:
    """All 2^count sign combinations, shape (2^count, count), first all +1.

    >>> sign_branches(2).tolist()
    [[1, 1], [1, -1], [-1, 1], [-1, -1]]
    """
    return np.array(list(product((1, -1), repeat=count)), dtype=int).reshape(2**count, count)


def distinct_branches(plan, sliders: Collection[str]) -> list[tuple[int, ...]]:
    """The sign branches of ``plan`` that can place differently when the joints
    ``sliders`` are sliders: ±1 for each free-sign step that takes a square root of its
    own (:func:`~.sliders.takes_root`), +1 alone for one whose slider construction reads
    no sign (a turned axis, a point on two axes): the other sign would place every joint
    alike, and evaluating it repeated the work (eight branches for one on a nine-link
    slider chain). In :func:`sign_branches`' order; all of them without sliders.

    Cost: O(2^m) tuples, m the free-sign steps that take a root.
    """
    return list(product(*(((1, -1) if takes_root(step, sliders) else (1,))
                          for step in plan.steps if step.free_sign)))


class CompiledSystem:
    """A closure system bound to concrete link dimensions.

    Parameters
    ----------
    system
        the closure system of a plan.
    known
        squared distance of every pair of joints on a common link.
    fixed_signs
        orientation sign (±1) of every fixed-sign (link-step) triangle of the
        plan, keyed by the step's triangle (i, j, k).
    sliders
        the slider joints (:class:`~.sliders.SliderGeometry`): the steps that
        touch one are placed by :class:`~.sliders.SliderPlacement`, a closure pair of
        a slider and a joint compares the joint's oriented distance to the axis.
    searched
        the parameters searched through a map
        (:class:`~.sliders.SearchedParameter`: an oriented distance t to a slider's
        axis, or a parameter without bound); :meth:`reported` gives them back.
    """

    def __init__(self, system: ClosureSystem, known: Mapping[Pair, float], fixed_signs: Mapping[Triangle, int],
                 sliders: Mapping[str, SliderGeometry] | None = None,
                 searched: Mapping[Pair, SearchedParameter] | None = None):
        self.system = system
        self.sliders = dict(sliders or {})
        self.searched = {frozenset(pair): mapping for pair, mapping in (searched or {}).items()}
        self.plan = system.plan
        self.known = {frozenset(k): float(v) for k, v in known.items()}
        self.fixed_signs = dict(fixed_signs)
        self.parameters = self.plan.parameters
        self.free_triangles = self.plan.free_sign_triangles
        self._parameter_index = {frozenset(p): n for n, p in enumerate(self.parameters)}
        free_steps = [index for index, step in enumerate(self.plan.steps) if step.free_sign]
        self._free_index = {index: n for n, index in enumerate(free_steps)}
        # the triangles bounding a parameter's domain, their radicands in the form that rounds
        # well near flat (as the traced program takes them: the two kernels agree bit for bit)
        self._factored = {} if self.sliders else parameter_triangles(self.plan, self.known)
        for step in self.plan.steps:
            if not step.free_sign and step.triangle not in self.fixed_signs:
                raise ValueError(f"triangle {step.triangle}: orientation sign of a link step missing")

    @functools.cached_property
    def parameter_names(self) -> tuple[str, ...]:
        """The parameters' names: s_{u,v}, or t_{u,v} for a slider's pair."""
        return tuple(parameter_name(pair, self.sliders) for pair in self.parameters)

    def reported(self, values: np.ndarray) -> np.ndarray:
        """Parameter values as searched (shape (..., p)) → as reported (``searched``)."""
        values = np.array(values, dtype=float)
        for n, pair in enumerate(self.parameters):
            if frozenset(pair) in self.searched:
                values[..., n] = self.searched[frozenset(pair)].value(values[..., n])
        return values

    def searched_values(self, values: np.ndarray) -> np.ndarray:
        """Parameter values as reported (shape (..., p)) → as searched: the inverse of
        :meth:`reported`, for values read back from a configuration."""
        values = np.array(values, dtype=float)
        for n, pair in enumerate(self.parameters):
            if frozenset(pair) in self.searched:
                values[..., n] = self.searched[frozenset(pair)].searched(values[..., n])
        return values

    def search_bound(self, n: int, bound: float) -> float:
        """The upper end of the searched range of parameter ``n``: ``bound`` (a squared
        distance's), or the map's scale² (``searched``)."""
        mapping = self.searched.get(frozenset(self.parameters[n]))
        return bound if mapping is None else mapping.scale**2

    def straight_line_program(self) -> StraightLineProgram:
        """The plan's straight-line program (:mod:`.straight_line`), traced once per plan,
        its link pairs and link steps, and its sliders' layout (their numbers are inputs)."""
        return self._program

    @functools.cached_property
    def _program(self) -> StraightLineProgram:
        return _straight_line_program(self.plan, tuple(self.known), tuple(self.fixed_signs), _slider_layout(self.sliders),
                                      self.sliders)

    @functools.cached_property
    def _slider_values(self) -> list[float]:
        """This instance's numbers for the program's slider inputs (once: every evaluation reads them)."""
        return slider_constant_values(self._program.slider_constants, self.sliders)

    def program_profile(self, parameter_values: np.ndarray, signs: np.ndarray, paired: bool = False) -> Profile:
        """:meth:`profile` (with ``paired``, before its first axis is dropped) by the
        plan's straight-line program (:mod:`.straight_line`), compiled: the same values
        bit for bit. Not for plans with slider joints."""
        values = np.asarray(parameter_values, dtype=float)
        values = values[:, None] if values.ndim == 1 else values
        signs = np.asarray(signs, dtype=float)
        residuals, failures, radicands, margins = self._run_program(values, signs, paired)
        shape = (1, len(values)) if paired else (len(signs), len(values))
        return Profile(residuals.reshape(*shape, residuals.shape[1]), failures.reshape(shape),
                       radicands.reshape(shape), margins.reshape(*shape, margins.shape[1]))

    def _run_program(self, values: np.ndarray, signs: np.ndarray, paired: bool, points: bool = False):
        """:func:`~.straight_line.run_program` of the plan's program on this instance at
        parameter ``values`` (N, p)."""
        program = self.straight_line_program()
        with np.errstate(invalid="ignore"):  # a searched value below 0 maps to NaN, as in the numpy kernel
            mapped = np.column_stack([self.searched[frozenset(pair)].value(values[:, n])
                                      if frozenset(pair) in self.searched else values[:, n]
                                      for n, pair in enumerate(self.parameters)]) if self.searched else values
        return run_program(program, [self.known[pair] for pair in program.known_pairs],
                           [self.fixed_signs[t] for t in program.fixed_triangles], mapped, signs, paired, points,
                           self._slider_values)

    def matrices(self, parameter_values: np.ndarray, signs: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
        """M_k for every joint, and s_ref, broadcast over branches and parameter values.

        ``parameter_values`` has shape (N, p) (p = number of parameters), ``signs`` shape
        (B, m) (m = free-sign triangles); results have shape (B, N).
        """
        placement = self._evaluate(parameter_values, signs, points=True)
        return placement.matrices(), placement.s_ref

    def first_failures(self, parameter_values: np.ndarray, signs: np.ndarray) -> np.ndarray:
        """For every branch and parameter value, the index of the first step whose triangle
        cannot be built (negative radicand), or the number of steps where all can; shape
        (B, N). Where neighbouring values fail at different steps, a feasible window may
        lie between them even if no sample falls inside it."""
        return self._evaluate(parameter_values, signs).failures

    def failure_profile(self, parameter_values: np.ndarray,
                        signs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`first_failures`; where a step fails, its radicand relative to the squared
        largest side (negative; NaN where all steps succeed); and the relative radicands of
        the free-sign steps, shape (B, N, free), NaN where undefined. A window between two
        values failing at the same step shows as a local maximum of that radicand; an
        undefined gap between two defined values, as a local minimum of one free-sign
        step's radicand."""
        placement = self._evaluate(parameter_values, signs, profile=True)
        return placement.failures, placement.radicands, placement.stacked_margins()

    def profile(self, parameter_values: np.ndarray, signs: np.ndarray, paired: bool = False) -> Profile:
        """In one evaluation, :meth:`residuals` and :meth:`failure_profile`: shapes (B, N, c),
        (B, N), (B, N) and (B, N, free); with ``paired``, point n on branch ``signs[n]``
        and shapes (N, c), (N,), (N,), (N, free). The values are those of the separate
        calls, bit for bit (the same arithmetic element by element)."""
        placement = self._evaluate(parameter_values, signs, profile=True, paired=paired)
        profile = Profile(self._closure_residuals(placement), placement.failures, placement.radicands,
                          placement.stacked_margins())
        return Profile(*(part[0] for part in profile)) if paired else profile

    def paired_matrices(self, parameter_values: np.ndarray, signs: np.ndarray) -> dict[str, np.ndarray]:
        """M_k for every joint, point n on branch ``signs[n]``; shape (N,). By the plan's
        compiled program where it is in use (the same values bit for bit), else numpy."""
        if not self.sliders and compiled_kernel_in_use():
            values = np.asarray(parameter_values, dtype=float)
            values = values[:, None] if values.ndim == 1 else values
            *_, points = self._run_program(values, np.asarray(signs, dtype=float), paired=True, points=True)
            return dict(zip(self.straight_line_program().joints, points.T, strict=True))
        matrices = self._evaluate(parameter_values, signs, paired=True, points=True).matrices()
        return {joint: value[0] for joint, value in matrices.items()}

    def paired_residuals(self, parameter_values: np.ndarray, signs: np.ndarray) -> np.ndarray:
        """Relative closure residuals of point n on branch ``signs[n]``: shape (N, c) for
        ``parameter_values`` of shape (N, p) and ``signs`` of shape (N, m) (candidates of
        different branches refined together)."""
        return self._closure_residuals(self._evaluate(parameter_values, signs, paired=True))[0]

    def paired_residuals_and_failures(self, parameter_values: np.ndarray,
                                      signs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """In one evaluation, for point n on branch ``signs[n]``: :meth:`paired_residuals`,
        shape (N, c), and :meth:`first_failures`, shape (N,)."""
        placement = self._evaluate(parameter_values, signs, paired=True)
        return self._closure_residuals(placement)[0], placement.failures[0]

    def _evaluate(self, parameter_values: np.ndarray, signs: np.ndarray, profile: bool = False,
                  paired: bool = False, points: bool = False):
        """The plan placed by the bilateration kernel (:func:`~.bilateration.place_joints`)
        in numpy floats over all branches × parameter values at once; or, where the
        compiled kernel is in use (:func:`~.straight_line.compiled_kernel_in_use`) and
        no ``points`` are asked for, its residuals and failure profile by the plan's
        compiled program (:meth:`program_profile`: the same values). Time spent in numpy
        counts towards the switch (:func:`~.straight_line.count_numpy_seconds`)."""
        if not points and compiled_kernel_in_use():
            return _ProgramPlacement(*self.program_profile(parameter_values, signs, paired))
        started = time.perf_counter()
        try:
            return self._placed(parameter_values, signs, profile, paired)
        finally:
            count_numpy_seconds(time.perf_counter() - started)

    def _placed(self, parameter_values: np.ndarray, signs: np.ndarray, profile: bool, paired: bool):
        """:meth:`_evaluate`'s placement."""
        values = np.asarray(parameter_values, dtype=float)
        if values.ndim == 1:
            values = values[:, None]
        signs = np.asarray(signs, dtype=float)
        shape = (1, values.shape[0]) if paired else (signs.shape[0], values.shape[0])
        parameter = [np.broadcast_to(values[None, :, n], shape) for n in range(values.shape[1])]
        steps = len(self.plan.steps)
        failures = np.full(shape, steps)
        radicands = np.full(shape, np.nan)
        margins: list[np.ndarray] = []
        relative: list[np.ndarray] = []  # the current step's radicand over its squared largest side

        def known(u: str, v: str):
            pair = frozenset((u, v))
            if pair in self.known:
                return self.known[pair], 1
            if pair in self._parameter_index:
                value = parameter[self._parameter_index[pair]]
                return (self.searched[pair].value(value) if pair in self.searched else value), 1
            return None

        def root(index, step, sides, radicand):
            if index in self._factored:
                radicand = factored_radicand(sides, self._factored[index], np.sqrt)
            if step.free_sign:
                column = signs[:, self._free_index[index]]
                sign = column[None, :] if paired else column[:, None]
            else:
                sign = self.fixed_signs[step.triangle]
            if profile:
                relative[:] = [radicand / np.maximum(np.maximum(sides[0], sides[1]), sides[2]) ** 2]
                if step.free_sign:  # a slider's step may take a constant radicand: broadcast
                    margins.append(np.broadcast_to(relative[0], shape))
            return signed_root(radicand, sides, sign)

        def after_step(index, step, point):
            nonlocal failures, radicands
            newly = (failures == steps) & ~np.isfinite(point[0] + point[1])  # NaN and ±inf survive the sum
            failures = np.where(newly, index, failures)
            if profile:  # a slider's link step takes no root: nothing to profile
                radicands = np.where(newly, relative[0] if relative else np.nan, radicands)
                relative.clear()
                if step.free_sign and len(margins) == self._free_index[index]:
                    # a free sign a slider construction does not use (two lines meet once)
                    margins.append(np.ones(shape))
            return True

        sliders = self._slider_placement(known, root) if self.sliders else None
        with np.errstate(invalid="ignore", divide="ignore"):  # an undefined step (NaN, s_ij = 0) is marked failed
            points, (s_ref, _), distance = place_joints(self.plan, known, root, reduced_point=dehomogenised,
                                                        after_step=after_step,
                                                        slider_step=sliders[1] if sliders else None,
                                                        slider_frame=sliders[2] if sliders else None)
        return _Placement(points, distance, s_ref, shape, failures, radicands, margins, sliders and sliders[0])

    def _slider_placement(self, known, root) -> tuple[SliderPlacement, Callable, Callable]:
        """The kernel's ``slider_step`` for the plan evaluated in numpy complex numbers."""
        def parameter(u: str, v: str):
            return known(u, v)[0] if frozenset((u, v)) in self._parameter_index else None

        def along_root(index, step, squared, radicand):
            # scaled to the form of a triangle radicand (sides³ → sides⁴) so that the
            # rounding threshold and the failure profile read it alike
            return root(index, step, (squared, 0.0, 0.0), radicand * squared) / np.sqrt(squared)

        placement = SliderPlacement(self.sliders, parameter, along_root)
        slider_step, slider_frame = placement.kernel_hooks(self.plan.reference, lambda point: point[0] + 1j * point[1],
                                                           lambda number: (number.real, number.imag, 1))
        return placement, slider_step, slider_frame

    def residuals(self, parameter_values: np.ndarray, signs: np.ndarray | None = None) -> np.ndarray:
        """Relative closure residuals (computed s_{u,v} - known s_{u,v}) / known s_{u,v},
        shape (B, N, c) for B branches (all 2^m when ``signs`` is None), N parameter
        values and c conditions. NaN where a radicand is negative."""
        if signs is None:
            signs = sign_branches(len(self.free_triangles))
        return self._closure_residuals(self._evaluate(parameter_values, signs))

    def _closure_residuals(self, placement: _Placement | _ProgramPlacement) -> np.ndarray:
        if isinstance(placement, _ProgramPlacement):
            return placement.residuals
        columns = []
        for u, v in self.plan.closure_pairs:
            if u in self.sliders or v in self.sliders:
                columns.append(self._slider_closure(placement, u, v))
                continue
            target = self.known[frozenset((u, v))]
            with np.errstate(invalid="ignore"):
                columns.append((placement.distance(u, v, computed=True)[0] - target) / target)
        if not columns:
            return np.zeros((*placement.shape, 0))
        # to the full (B, N) shape: a slider chain's closure can be free of the parameter
        # (a chain that moves: its residual a constant, which broke the root search)
        return np.stack([np.broadcast_to(column, placement.shape) for column in columns], axis=-1)

    def _slider_closure(self, placement: _Placement, u: str, v: str) -> np.ndarray:
        """The closure s_{i,v} of a slider P_i as δ → ∞
        (:meth:`~.sliders.SliderPlacement.closure`): P_v's oriented distance to the axis,
        computed, minus the link's, relative to the link's size; for two sliders of one
        link, sin θ of the error θ of the turn between their axes where cos θ ≥ 0
        (:func:`~.sliders.turn_residual`: θ = π, a reversed axis, is no root)."""
        slider, joint = (u, v) if u in self.sliders else (v, u)
        point = placement.points.get(joint)
        at = {joint: point[0] + 1j * point[1]} if point is not None else {}
        with np.errstate(invalid="ignore"):
            value = placement.sliders.closure(slider, joint, at, placement.s_ref)
            if joint in self.sliders:
                return turn_residual(value, lambda x: np.sqrt(np.where(x >= 0, x, np.nan)))
        geometry = self.sliders[slider]
        size = max(abs(z) for frame in geometry.offsets.values() for z in frame.values())
        return value.real / size


def _slider_layout(sliders: Mapping[str, SliderGeometry]) -> tuple:
    """What a slider program's instructions depend on besides the plan: each slider's
    links, the joints and sliders in its frames, the other sliders it turns to, and
    whether its unit is 1 (a hashable key; the numbers themselves are inputs)."""
    return tuple((name, geometry.links, tuple((link, tuple(sorted(frame))) for link, frame in geometry.offsets.items()),
                  tuple(sorted(geometry.turns)),
                  tuple((link, tuple(sorted(frame))) for link, frame in geometry.slider_offsets.items()),
                  type(geometry.unit) is int and geometry.unit == 1)
                 for name, geometry in sorted(sliders.items()))


_programs: dict = {}


def _straight_line_program(plan, known_pairs: tuple, fixed_triangles: tuple, layout: tuple,
                           sliders: Mapping[str, SliderGeometry]) -> StraightLineProgram:
    """A plan's program, traced once per plan (and its link pairs, link steps and slider
    layout: ``sliders`` is read for its layout only, so one program serves all its
    instances). At most 256 kept."""
    key = (plan, known_pairs, fixed_triangles, layout)
    if key not in _programs:
        if len(_programs) >= 256:
            _programs.pop(next(iter(_programs)))
        program = _programs[key] = trace_plan(plan, known_pairs, fixed_triangles, sliders or None)
        # what the interval program is made from: the same program with the radicands in
        # the form whose enclosures stay tight (closure/interval_program.py), traced on use
        program.derived["interval source"] = functools.partial(trace_plan, plan, known_pairs, fixed_triangles,
                                                               sliders or None, small_term_radicand)
    return _programs[key]


class Profile(NamedTuple):
    """Closure residuals and the failure profile of the same placements
    (:meth:`CompiledSystem.profile`)."""

    residuals: np.ndarray
    failures: np.ndarray
    radicands: np.ndarray
    margins: np.ndarray


class _ProgramPlacement(NamedTuple):
    """What the compiled program gives in place of a :class:`_Placement`: residuals and
    the failure profile, no points."""

    residuals: np.ndarray
    failures: np.ndarray
    radicands: np.ndarray
    margins: np.ndarray

    def stacked_margins(self) -> np.ndarray:
        return self.margins


class _Placement(NamedTuple):
    """A plan placed in numpy floats (:meth:`CompiledSystem._evaluate`): points (x, y, 1)
    in the frame M_a = 0, M_b = 1, the kernel's distance function, s_ref, the (B, N)
    shape, first failing steps, and the failure profile (radicands, free-sign margins)."""

    points: dict
    distance: Callable
    s_ref: np.ndarray | float
    shape: tuple[int, int]
    failures: np.ndarray
    radicands: np.ndarray
    margins: list
    sliders: SliderPlacement | None = None

    def stacked_margins(self) -> np.ndarray:
        """The free-sign steps' relative radicands, shape (B, N, free)."""
        return np.stack(self.margins, axis=-1) if self.margins else np.zeros((*self.failures.shape, 0))

    def matrices(self) -> dict[str, np.ndarray]:
        """M_k = x + i y for every joint, and for every slider its points P_i', P_i''
        on its two links, shape (B, N) (a step from link sides alone gives scalars:
        broadcast)."""
        with np.errstate(invalid="ignore"):  # an unplaced joint (x or y NaN or ∞) stays NaN
            at = {joint: x + 1j * y for joint, (x, y, _) in self.points.items()}
        if self.sliders is not None:  # two parallel axes meet at no point: ∞ or NaN, not a warning
            with np.errstate(invalid="ignore", divide="ignore"):
                at.update(self.sliders.slider_points(at, self.s_ref))
        return {joint: np.broadcast_to(np.asarray(value, complex), self.shape) for joint, value in at.items()}


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
