"""Certified real roots of two closure conditions in two parameters by interval
branch-and-prune with the Krawczyk test (issue 56; coupling degree 2, e.g. 9/B25–B28,
thesis §3.4.1).

On every free-sign branch a coupling-2 plan closes with f_1(s, t) = f_2(s, t) = 0 in two
squared distances. The searched domain is a box: each parameter in [0, S] (S the squared
sum of the link diameters) cut by the triangle inequalities of the steps with it as a side
(:func:`~.branch_and_prune.parameter_domain`). Each box X = [low, high] is decided by one
evaluation of the plan's straight-line program on first-order Taylor models
(:mod:`baranov.closure.interval_program`: f_i = c_i + g_i · u ± e_i, u = x − m over the box),
the derivatives' models computed only where the values leave it undecided:

* *excluded*: a triangle of the branch cannot be built anywhere in X (a radicand certainly
  negative), or some f_i's model cannot vanish on X;
* *contracted* to where both linear models can vanish — for each f_i and axis k,
  g_ik u_k ∈ [−c_i − e_i, −c_i + e_i] − g_ij u_j (the hull consistency of the linear
  relaxation, two passes) — and, where the triangles are proper on X, to its Krawczyk
  image;
* *certified* where the Krawczyk operator

      K(X) = m − Y f(m) + (I − Y J(X)) (X − m),   Y ≈ J(m)⁻¹ (any float matrix),

  maps X into its interior (Krawczyk 1969; Moore 1977; Neumaier, *Interval methods for
  systems of equations*, 1990, Thm. 5.1.7 and §5.2 — the test HomotopyContinuation.jl's
  ``certify`` runs): X then holds exactly one root, which lies in K(X); f(m) is the
  models' value at u = 0 (c ± e) and J(X) the range of the derivatives' models. The
  certified box is narrowed by K while that takes off a tenth;
* otherwise split across its wider side (relative to the domain), down to
  ``minimum_width`` × the domain on both sides; a box that small and not decided is
  *unresolved*, named with its reason (a domain edge — a triangle flat — crossing it, or a
  Jacobian that may be singular: a tangential intersection, a double root).

What it proves: each certified box holds exactly one real root of its branch, and no real
root of any branch lies in the domain outside the certified and unresolved boxes. Two
certified boxes are disjoint but for their boundaries, and a certified root lies in the
interior of its box, so no root is certified twice.
"""

from __future__ import annotations

import numba
import numpy as np

from baranov.closure import CompiledSystem
from baranov.closure import interval_program as models

from .branch_and_prune import (
    AT_EDGE,
    CONTRACTIONS,
    EVALUATION_BUDGET,
    FLAT_DERIVATIVE,
    MINIMUM_WIDTH,
    OVER_BUDGET,
    PrunedRoots,
    instance_inputs,
)

_COMPILE = dict(cache=True, nogil=True, error_model="numpy")
#: Outcomes of one box: _NEAR is undecided with a Krawczyk image that meets the box.
_EXCLUDED, _CERTIFIED, _UNDECIDED, _NEAR = 0, 1, 2, 3
#: Where a box is split across its wider side (off the middle: a root at the middle of a
#: box, e.g. of a box drawn about a mode, would lie on the boundary of both halves, and
#: the Krawczyk test certifies a root in a box's interior only).
SPLIT_AT = 0.4921875
#: Edge symbols of the models (:func:`~baranov.closure.interval_program._edge_root`): the
#: roots at the first domain edges a box holds, each a symbol of its own.
EDGE_SYMBOLS = 2


@numba.njit(**_COMPILE)
def _scaled(y, low, high):  # pragma: no cover - compiled
    """y × [low, high], rounded outward."""
    first, second = y * low, y * high
    return models.rounded_down(min(first, second)), models.rounded_up(max(first, second))


@numba.njit(**_COMPILE)
def _hull_consistent(center, slopes, rest, u_low, u_high):  # pragma: no cover - compiled
    """Narrow [u_low, u_high] (2,) to where some center_i + slopes_i · u ± rest_i can be 0
    for both i (two passes over both models and both axes); False where nothing is left."""
    for _ in range(2):
        for i in range(2):
            for k in range(2):
                j = 1 - k
                if slopes[i, k] == 0.0:
                    continue
                other_low, other_high = _scaled(slopes[i, j], u_low[j], u_high[j])
                top_low = models.rounded_down(models.rounded_down(-center[i] - rest[i]) - other_high)
                top_high = models.rounded_up(models.rounded_up(-center[i] + rest[i]) - other_low)
                a, b = top_low / slopes[i, k], top_high / slopes[i, k]
                u_low[k] = max(u_low[k], models.rounded_down(min(a, b)))
                u_high[k] = min(u_high[k], models.rounded_up(max(a, b)))
                if u_low[k] > u_high[k]:
                    return False
    return True


@numba.njit(**_COMPILE)
def _krawczyk(middle, radius, center, rest, jacobian, image):  # pragma: no cover - compiled
    """K(X) (module docstring) into ``image`` (2, 2: low, high per axis) for the box of
    ``middle`` ± ``radius``, f(m) in center ± rest, J(X) in ``jacobian`` (2, 2, 2); False
    where J's midpoint is singular (no preconditioner)."""
    m00, m01 = 0.5 * (jacobian[0, 0, 0] + jacobian[0, 0, 1]), 0.5 * (jacobian[0, 1, 0] + jacobian[0, 1, 1])
    m10, m11 = 0.5 * (jacobian[1, 0, 0] + jacobian[1, 0, 1]), 0.5 * (jacobian[1, 1, 0] + jacobian[1, 1, 1])
    determinant = m00 * m11 - m01 * m10
    if not (abs(determinant) > 0.0 and np.isfinite(determinant)):
        return False
    y = np.array([[m11, -m01], [-m10, m00]]) / determinant
    for i in range(2):
        low, high = middle[i], middle[i]
        spread = 0.0
        for j in range(2):
            f_low, f_high = _scaled(y[i, j], models.rounded_down(center[j] - rest[j]), models.rounded_up(center[j] + rest[j]))
            low, high = models.rounded_down(low - f_high), models.rounded_up(high - f_low)
        for k in range(2):
            entry_low, entry_high = (1.0, 1.0) if i == k else (0.0, 0.0)
            for j in range(2):
                product_low, product_high = _scaled(y[i, j], jacobian[j, k, 0], jacobian[j, k, 1])
                entry_low, entry_high = models.rounded_down(entry_low - product_high), models.rounded_up(entry_high - product_low)
            spread = models.rounded_up(spread + models.rounded_up(max(abs(entry_low), abs(entry_high)) * radius[k]))
        image[i, 0], image[i, 1] = models.rounded_down(low - spread), models.rounded_up(high + spread)
    return np.isfinite(image).all()


@numba.njit(**_COMPILE)
def _examine(instructions, values, start, work, parameters, sign_registers, signs, residuals, derivatives, box, narrowed
             ):  # pragma: no cover - compiled
    """Decide ``box`` (lo0, hi0, lo1, hi1) on the branch ``signs`` by one evaluation:
    (_EXCLUDED | _CERTIFIED | _UNDECIDED, status); ``narrowed`` (4,) receives the box cut to
    where roots can be (the Krawczyk image for a certified box)."""
    c, g, h, e, radii, scratch, feasible, statuses, low, high = work  # one column: one box
    low[0], high[0], low[1], high[1] = box[0], box[1], box[2], box[3]
    models.load_box(parameters, sign_registers, low, high, signs, c, g, e, radii, 0)
    statuses[0] = start  # the instance's status
    for k in range(4):
        feasible[k, 0] = -np.inf if k % 2 == 0 else np.inf
    models.evaluate_models(instructions[:values], c, g, h, e, radii, feasible, statuses, scratch, 2, 1)
    status, radius = statuses[0], radii[:2, 0].copy()
    if status == models.INFEASIBLE:
        return _EXCLUDED, status
    center, rest, slopes = np.empty(2), np.empty(2), np.empty((2, 2))
    for i in range(2):
        center[i], rest[i] = models.linear_model(c, g, h, e, radii, residuals[i], 0, 2)
        slopes[i, 0], slopes[i, 1] = g[0, residuals[i], 0], g[1, residuals[i], 0]
    # where the triangles at an edge can exist (the radicands' models), then where both
    # conditions' models can vanish
    u_low = np.array([max(-radius[0], feasible[0, 0]), max(-radius[1], feasible[2, 0])])
    u_high = np.array([min(radius[0], feasible[1, 0]), min(radius[1], feasible[3, 0])])
    if u_low[0] > u_high[0] or u_low[1] > u_high[1]:
        return _EXCLUDED, status
    if not _hull_consistent(center, slopes, rest, u_low, u_high):
        return _EXCLUDED, status
    middle = np.array([c[parameters[0], 0], c[parameters[1], 0]])
    for k in range(2):
        narrowed[2 * k] = max(low[k], models.rounded_down(middle[k] + u_low[k]))
        narrowed[2 * k + 1] = min(high[k], models.rounded_up(middle[k] + u_high[k]))
    if status != models.FEASIBLE:
        return _UNDECIDED, status
    models.evaluate_models(instructions[values:], c, g, h, e, radii, feasible, statuses, scratch, 2, 1)
    jacobian, image = np.empty((2, 2, 2)), np.empty((2, 2))
    for i in range(2):
        for k in range(2):
            jacobian[i, k, 0], jacobian[i, k, 1] = models.model_range(c, g, h, e, radii, derivatives[i, k], 0)
    if not _krawczyk(middle, radius, center, rest, jacobian, image):
        return _UNDECIDED, status
    inside = True
    for k in range(2):
        if image[k, 1] < low[k] or image[k, 0] > high[k]:
            return _EXCLUDED, status
        inside = inside and low[k] < image[k, 0] and image[k, 1] < high[k]
        narrowed[2 * k] = max(narrowed[2 * k], image[k, 0])
        narrowed[2 * k + 1] = min(narrowed[2 * k + 1], image[k, 1])
    if narrowed[0] > narrowed[1] or narrowed[2] > narrowed[3]:
        return _EXCLUDED, status
    return (_CERTIFIED if inside else _NEAR), status


@numba.njit(**_COMPILE)
def _contracted(instructions, values, start, work, parameters, sign_registers, signs, residuals, derivatives, box
                ):  # pragma: no cover - compiled
    """A certified box's root enclosure narrowed by Krawczyk images while each takes off
    a tenth (quadratically near the root); (enclosure (4,), evaluations)."""
    evaluations = 0
    current, narrowed = box.copy(), np.empty(4)
    for _ in range(CONTRACTIONS):
        evaluations += 1
        outcome, _ = _examine(instructions, values, start, work, parameters, sign_registers, signs, residuals, derivatives,
                              current, narrowed)
        if outcome != _CERTIFIED:
            break
        shrunk = max(narrowed[1] - narrowed[0] - 0.9 * (current[1] - current[0]),
                     narrowed[3] - narrowed[2] - 0.9 * (current[3] - current[2])) <= 0.0
        current[:] = narrowed
        if not shrunk:
            break
    return current, evaluations


@numba.njit(**_COMPILE)
def _prune_plane(instructions, values, base_c, base_e, start, parameters, sign_registers, branches, residuals, derivatives,
                 domain, minimum_width, budget, h, symbols):  # pragma: no cover - compiled
    """The branch-and-prune loop of :func:`prune_two_parameters` over every branch."""
    c, g, e, radii, scratch = models.new_registers(base_c, base_e, symbols, 1)
    work = (c, g, h, e, radii, scratch, np.empty((4, 1)), np.empty(1, dtype=np.int64),
            np.empty(2), np.empty(2))
    stack = [(domain.copy(), 0)]
    stack.pop()
    for k in range(branches.shape[0]):
        stack.append((domain.copy(), k))
    roots = [(np.empty(4), 0, np.empty(4))]
    roots.pop()
    unresolved = [(np.empty(4), 0, 0)]
    unresolved.pop()
    evaluations = 0
    narrowed = np.empty(4)
    while len(stack) > 0:
        box, k = stack.pop()
        if evaluations >= budget:
            unresolved.append((box, k, OVER_BUDGET))
            continue
        evaluations += 1
        outcome, status = _examine(instructions, values, start, work, parameters, sign_registers, branches[k], residuals,
                                   derivatives, box, narrowed)
        if outcome == _EXCLUDED:
            continue
        widths = np.array([box[1] - box[0], box[3] - box[2]])
        kept = np.array([narrowed[1] - narrowed[0], narrowed[3] - narrowed[2]])
        uniqueness = box.copy()
        if outcome == _NEAR and kept[0] <= 0.5 * widths[0] and kept[1] <= 0.5 * widths[1]:
            # every root of the box lies in ``narrowed``: certify it on a box half as wide
            # again about it, which may reach past this one (a root found twice is merged
            # by its uniqueness boxes)
            evaluations += 1
            for n in range(4):
                uniqueness[n] = narrowed[n] + (narrowed[n] - narrowed[n ^ 1]) * 0.25
            outcome, _ = _examine(instructions, values, start, work, parameters, sign_registers, branches[k], residuals,
                                  derivatives, uniqueness.copy(), narrowed)
            if outcome == _CERTIFIED and not (narrowed[1] < box[0] or narrowed[0] > box[1] or narrowed[3] < box[2]
                                              or narrowed[2] > box[3]):
                pass
            elif outcome in (_CERTIFIED, _EXCLUDED):
                continue  # its one root, if any, lies outside this box: none in it
            else:
                narrowed[:] = box  # undecided: split this box
                kept[:] = widths
        if outcome == _CERTIFIED:
            enclosure, spent = _contracted(instructions, values, start, work, parameters, sign_registers, branches[k],
                                           residuals, derivatives, narrowed)
            evaluations += spent
            roots.append((enclosure, k, uniqueness))
            continue
        if kept[0] * kept[1] < 0.5 * widths[0] * widths[1]:
            stack.append((narrowed.copy(), k))
            continue
        relative = kept / (domain[1::2] - domain[0::2])
        if relative[0] <= minimum_width and relative[1] <= minimum_width:
            unresolved.append((box, k, AT_EDGE if status == models.EDGE else FLAT_DERIVATIVE))
            continue
        axis = 0 if relative[0] >= relative[1] else 1
        middle = narrowed[2 * axis] + SPLIT_AT * (narrowed[2 * axis + 1] - narrowed[2 * axis])
        upper, lower = narrowed.copy(), narrowed.copy()
        upper[2 * axis], lower[2 * axis + 1] = middle, middle
        stack.append((upper, k))
        stack.append((lower, k))
    found = np.empty((len(roots), 9))
    for n in range(len(roots)):
        enclosure, k, uniqueness = roots[n]
        found[n, 0], found[n, 1], found[n, 2], found[n, 3], found[n, 4] = \
            enclosure[0], enclosure[2], enclosure[1], enclosure[3], k
        found[n, 5:] = uniqueness
    left = np.empty((len(unresolved), 6))
    for n in range(len(unresolved)):
        box, k, why = unresolved[n]
        left[n, 0], left[n, 1], left[n, 2], left[n, 3], left[n, 4], left[n, 5] = box[0], box[2], box[1], box[3], k, why
    return found, left, evaluations


def prune_two_parameters(compiled: CompiledSystem, branches: np.ndarray,
                         domain: tuple[tuple[float, float], tuple[float, float]], exact_known=None,
                         minimum_width: float = MINIMUM_WIDTH, budget: int = EVALUATION_BUDGET,
                         order: int = 2, edge_symbols: int = EDGE_SYMBOLS) -> PrunedRoots:
    """Every real root of a coupling-2 plan's two closure conditions in ``domain`` (one
    interval per parameter holding every mode: :func:`~.branch_and_prune.searched_box`)
    on each of ``branches`` (B, m), certified or left in a named undecided box (module
    docstring). ``exact_known``: the known squared distances as exact numbers (pair →
    int, Fraction, …). Not for plans with slider joints. Cost O(boxes × instructions).

    Rows of the result: ``roots`` (lower ends (2), upper ends (2), branch index);
    ``unresolved`` the same and the reason.
    """
    program = compiled.straight_line_program()
    reduced = models.interval_program(program)
    inputs = instance_inputs(program, {**compiled.known, **(exact_known or {})}, compiled.fixed_signs)
    base_c, base_e, start = models.instance_registers(reduced, *inputs)
    box = np.array([float(end) for interval in domain for end in interval])
    derivatives = np.ascontiguousarray(reduced.residual_derivatives, dtype=np.int64)
    source = reduced.program  # the program traced for intervals: its own registers
    found, left, evaluations = _prune_plane(
        reduced.instructions, reduced.values, base_c, base_e, start, np.ascontiguousarray(source.parameter_registers),
        source.sign_registers, np.ascontiguousarray(branches, dtype=float),
        np.ascontiguousarray(source.residual_registers), derivatives, box, minimum_width, budget,
        models.quadratic_terms(order, 2 + edge_symbols, len(base_c), 1), 2 + edge_symbols)
    return PrunedRoots(_distinct(found), left, evaluations, tuple(map(tuple, box.reshape(2, 2))))


def _distinct(found: np.ndarray) -> np.ndarray:
    """Certified roots (rows: enclosure lower ends, upper ends, branch, uniqueness box
    lo0, hi0, lo1, hi1) without repeats: two of one branch are one root where the
    enclosure of either lies in the other's uniqueness box. Rows (enclosure, branch)."""
    kept: list[np.ndarray] = []
    for row in found[np.lexsort((found[:, 1], found[:, 0]))]:
        if not any(other[4] == row[4] and (_inside(row, other) or _inside(other, row)) for other in kept):
            kept.append(row)
    return np.array(kept).reshape(-1, 9)[:, :5]


def _inside(row: np.ndarray, other: np.ndarray) -> bool:
    """Whether ``row``'s enclosure lies in ``other``'s uniqueness box."""
    return bool(other[5] <= row[0] and row[2] <= other[6] and other[7] <= row[1] and row[3] <= other[8])
