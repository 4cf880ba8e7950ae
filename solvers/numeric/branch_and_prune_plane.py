"""Certified real roots of two closure conditions in two parameters by interval
branch-and-prune with the Krawczyk test (issue 56; coupling degree 2, e.g. 9/B25–B28,
thesis §3.4.1).

On every free-sign branch a coupling-2 plan closes with f_1(s, t) = f_2(s, t) = 0 in two
squared distances. The searched domain is a box: each parameter in [0, S] (S the squared
sum of the link diameters) cut by the triangle inequalities of the steps with it as a side
(:func:`~.branch_and_prune.parameter_domain`). Each box X = [low, high] is decided by one
evaluation of the plan's straight-line program on second-order Taylor models with two
edge symbols (:mod:`baranov.closure.interval_program`; their first-order part
f_i = c_i + g_i · u ± e_i, u = x − m over the box, decides),
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

The boxes are evaluated in rounds of up to COLUMNS, of any branch and any work — boxes
to search, boxes about a Krawczyk image's roots to certify, certified boxes to contract
(:data:`_SEARCH`, :data:`_CERTIFY`, :data:`_CONTRACT`) — side by side in the registers'
columns (:mod:`baranov.closure.interval_program`), the derivatives only where some box of
the round needs them: the decisions of a one-box-at-a-time search in another order (on
9/B28's whole box the same boxes, roots and undecided boxes, in 1.1-1.2 s against 1.5-2.0 s).

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
    AT_COINCIDENCE,
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


#: The work on a box (:func:`_prune_plane`): search it; test the box about the roots a
#: Krawczyk image left for exactly one root; contract a box known to hold exactly one root.
_SEARCH, _CERTIFY, _CONTRACT = 0, 1, 2
#: Boxes evaluated side by side in a round (columns of the registers).
COLUMNS = 32


@numba.njit(**_COMPILE)
def _narrowed(c, g, h, e, radii, feasible, status, parameters, residuals, box, j, narrowed, center, rest
              ):  # pragma: no cover - compiled
    """After the values' evaluation of ``box`` (lo0, hi0, lo1, hi1) in column ``j``: _EXCLUDED
    where a triangle cannot exist or no root can lie in it, else ``narrowed`` (4,) receives
    the box cut to where the triangles at an edge can exist and both conditions' linear
    models vanish, ``center``/``rest`` (2,) f(m)'s models, and the outcome is _UNDECIDED
    at an edge, _NEAR where the derivatives are needed."""
    if status == models.INFEASIBLE:
        return _EXCLUDED
    slopes = np.empty((2, 2))
    for i in range(2):
        center[i], rest[i] = models.linear_model(c, g, h, e, radii, residuals[i], j, 2)
        slopes[i, 0], slopes[i, 1] = g[0, residuals[i], j], g[1, residuals[i], j]
    u_low = np.array([max(-radii[0, j], feasible[0, j]), max(-radii[1, j], feasible[2, j])])
    u_high = np.array([min(radii[0, j], feasible[1, j]), min(radii[1, j], feasible[3, j])])
    if u_low[0] > u_high[0] or u_low[1] > u_high[1] or not _hull_consistent(center, slopes, rest, u_low, u_high):
        return _EXCLUDED
    for k in range(2):
        middle = c[parameters[k], j]
        narrowed[2 * k] = max(box[2 * k], models.rounded_down(middle + u_low[k]))
        narrowed[2 * k + 1] = min(box[2 * k + 1], models.rounded_up(middle + u_high[k]))
    return _UNDECIDED if status != models.FEASIBLE else _NEAR


@numba.njit(**_COMPILE)
def _krawczyk_outcome(c, g, h, e, radii, parameters, derivatives, box, j, narrowed, center, rest
                      ):  # pragma: no cover - compiled
    """After the derivatives' evaluation of ``box`` in column ``j`` (its triangles proper):
    _CERTIFIED where the Krawczyk image lies in the box's interior (``narrowed`` cut to
    it), _EXCLUDED where it misses the box, _NEAR where it meets it, _UNDECIDED where J's
    midpoint is singular."""
    jacobian, image = np.empty((2, 2, 2)), np.empty((2, 2))
    for i in range(2):
        for k in range(2):
            jacobian[i, k, 0], jacobian[i, k, 1] = models.model_range(c, g, h, e, radii, derivatives[i, k], j)
    middle = np.array([c[parameters[0], j], c[parameters[1], j]])
    if not _krawczyk(middle, radii[:2, j], center, rest, jacobian, image):
        return _UNDECIDED
    inside = True
    for k in range(2):
        if image[k, 1] < box[2 * k] or image[k, 0] > box[2 * k + 1]:
            return _EXCLUDED
        inside = inside and box[2 * k] < image[k, 0] and image[k, 1] < box[2 * k + 1]
        narrowed[2 * k] = max(narrowed[2 * k], image[k, 0])
        narrowed[2 * k + 1] = min(narrowed[2 * k + 1], image[k, 1])
    if narrowed[0] > narrowed[1] or narrowed[2] > narrowed[3]:
        return _EXCLUDED
    return _CERTIFIED if inside else _NEAR


@numba.njit(**_COMPILE)
def _evaluate_round(instructions, values, registers, h, parameters, residuals, derivatives, boxes, statuses, n, narrowed,
                    outcomes, centers, rests):  # pragma: no cover - compiled
    """Decide the ``n`` boxes loaded in the registers' first columns (rows of ``boxes``):
    the values of all, then the derivatives of all where some box's triangles are proper
    and its roots not excluded; each box's outcome, status and narrowed box."""
    c, g, e, radii, scratch, feasible = registers
    models.evaluate_models(instructions[:values], c, g, h, e, radii, feasible, statuses, scratch, 2, n)
    needed = False
    for j in range(n):
        outcomes[j] = _narrowed(c, g, h, e, radii, feasible, statuses[j], parameters, residuals, boxes[j], j,
                                narrowed[j], centers[j], rests[j])
        needed = needed or outcomes[j] == _NEAR
    if not needed:
        return
    models.evaluate_models(instructions[values:], c, g, h, e, radii, feasible, statuses, scratch, 2, n)
    for j in range(n):
        if outcomes[j] == _NEAR:
            outcomes[j] = _krawczyk_outcome(c, g, h, e, radii, parameters, derivatives, boxes[j], j, narrowed[j],
                                            centers[j], rests[j])


@numba.njit(**_COMPILE)
def _searched(stack, unresolved, box, k, outcome, status, narrowed, domain, reference, minimum_width
              ):  # pragma: no cover - compiled
    """What follows from a searched box's outcome (not certified, not excluded): a
    certification about the roots its Krawczyk image left (a box half as wide again about
    them, which may reach past this one: a root found twice is merged by its uniqueness
    boxes), its narrowed part searched, its halves, or the box left unresolved."""
    widths = np.array([box[1] - box[0], box[3] - box[2]])
    kept = np.array([narrowed[1] - narrowed[0], narrowed[3] - narrowed[2]])
    if outcome == _NEAR and kept[0] <= 0.5 * widths[0] and kept[1] <= 0.5 * widths[1]:
        uniqueness = narrowed.copy()
        for n in range(4):
            uniqueness[n] = narrowed[n] + (narrowed[n] - narrowed[n ^ 1]) * 0.25
        stack.append((uniqueness, k, _CERTIFY, box.copy(), 0))
        return
    _split(stack, unresolved, box, k, status, narrowed, domain, reference, minimum_width)


@numba.njit(**_COMPILE)
def _split(stack, unresolved, box, k, status, narrowed, domain, reference, minimum_width
           ):  # pragma: no cover - compiled
    """An undecided box: left unresolved (AT_COINCIDENCE) where it lies within
    ``minimum_width`` of a squared distance's 0 — the plan divides by it there, and
    narrowing towards that point shrank boxes to 2e-300 wide (90 000 boxes on one slider
    chain) —, else searched again as ``narrowed`` where that is less than half of it, else
    split across its wider side (relative to the domain) at SPLIT_AT, or left unresolved
    below ``minimum_width``. Widths are relative to the ``reference`` box (the domain,
    except where a slider chain's parameter has no bound), grown by the box's distance
    from it: a relative precision far past the linkage's size."""
    widths = np.array([box[1] - box[0], box[3] - box[2]])
    kept = np.array([narrowed[1] - narrowed[0], narrowed[3] - narrowed[2]])
    relative = np.empty(2)
    for side in range(2):
        beyond = max(0.0, reference[2 * side] - narrowed[2 * side + 1], narrowed[2 * side] - reference[2 * side + 1])
        relative[side] = kept[side] / (reference[2 * side + 1] - reference[2 * side] + beyond)
    for side in range(2):  # the plan divides by a squared distance at its 0: no box there is ever decided
        if domain[2 * side] == 0.0 and narrowed[2 * side] == 0.0 and relative[side] <= minimum_width:
            unresolved.append((narrowed.copy(), k, AT_COINCIDENCE))
            return
    if kept[0] * kept[1] < 0.5 * widths[0] * widths[1]:
        stack.append((narrowed.copy(), k, _SEARCH, narrowed.copy(), 0))
        return
    if relative[0] <= minimum_width and relative[1] <= minimum_width:
        unresolved.append((box.copy(), k, AT_EDGE if status == models.EDGE else FLAT_DERIVATIVE))
        return
    axis = 0 if relative[0] >= relative[1] else 1
    middle = narrowed[2 * axis] + SPLIT_AT * (narrowed[2 * axis + 1] - narrowed[2 * axis])
    upper, lower = narrowed.copy(), narrowed.copy()
    upper[2 * axis], lower[2 * axis + 1] = middle, middle
    stack.append((upper, k, _SEARCH, upper, 0))
    stack.append((lower, k, _SEARCH, lower, 0))


@numba.njit(**_COMPILE)
def _decided(stack, roots, unresolved, item, outcome, status, narrowed, domain, reference, minimum_width
             ):  # pragma: no cover - compiled
    """Act on one box's outcome by its work: a searched box is dropped, certified (then
    contracted), or followed up (:func:`_searched`); a certification's box certified about
    a root in the searched box is contracted, one whose root (if any) lies outside it
    leaves none in it, else the searched box is split; a certified box is narrowed by
    Krawczyk images while each takes off a tenth (at most CONTRACTIONS times), then its
    root is recorded with its uniqueness box."""
    box, k, work, other, steps = item
    if work == _SEARCH:
        if outcome == _CERTIFIED:
            stack.append((narrowed.copy(), k, _CONTRACT, box, 0))
        elif outcome != _EXCLUDED:
            _searched(stack, unresolved, box, k, outcome, status, narrowed, domain, reference, minimum_width)
    elif work == _CERTIFY:
        searched = other
        if outcome == _CERTIFIED and not (narrowed[1] < searched[0] or narrowed[0] > searched[1]
                                          or narrowed[3] < searched[2] or narrowed[2] > searched[3]):
            stack.append((narrowed.copy(), k, _CONTRACT, box, 0))
        elif outcome != _CERTIFIED and outcome != _EXCLUDED:
            _split(stack, unresolved, searched, k, status, searched, domain, reference, minimum_width)
    elif outcome != _CERTIFIED:
        roots.append((box, k, other))
    else:
        shrunk = max(narrowed[1] - narrowed[0] - 0.9 * (box[1] - box[0]),
                     narrowed[3] - narrowed[2] - 0.9 * (box[3] - box[2])) <= 0.0
        if shrunk and steps + 1 < CONTRACTIONS:
            stack.append((narrowed.copy(), k, _CONTRACT, other, steps + 1))
        else:
            roots.append((narrowed.copy(), k, other))


@numba.njit(**_COMPILE)
def _prune_plane(instructions, values, base_c, base_e, start, parameters, sign_registers, branches, residuals, derivatives,
                 domain, reference, minimum_width, budget, h, symbols):  # pragma: no cover - compiled
    """The branch-and-prune loop of :func:`prune_two_parameters` over every branch: rounds
    of up to COLUMNS boxes of any branch and work, each one evaluation side by side; at
    most ``budget`` evaluations on each branch."""
    c, g, e, radii, scratch = models.new_registers(base_c, base_e, symbols, COLUMNS)
    registers = (c, g, e, radii, scratch, np.empty((4, COLUMNS)))
    feasible = registers[5]
    stack = [(domain.copy(), 0, _SEARCH, domain.copy(), 0)]
    stack.pop()
    for k in range(branches.shape[0] - 1, -1, -1):
        stack.append((domain.copy(), k, _SEARCH, domain.copy(), 0))
    roots = [(np.empty(4), 0, np.empty(4))]
    roots.pop()
    unresolved = [(np.empty(4), 0, 0)]
    unresolved.pop()
    batch = [(domain.copy(), 0, _SEARCH, domain.copy(), 0)]  # typed by its first item
    boxes, statuses = np.empty((COLUMNS, 4)), np.empty(COLUMNS, dtype=np.int64)
    narrowed, outcomes = np.empty((COLUMNS, 4)), np.empty(COLUMNS, dtype=np.int64)
    centers, rests = np.empty((COLUMNS, 2)), np.empty((COLUMNS, 2))
    low, high = np.empty(2), np.empty(2)
    evaluations = np.zeros(branches.shape[0], dtype=np.int64)
    while len(stack) > 0:
        batch.clear()
        while len(stack) > 0 and len(batch) < COLUMNS:
            item = stack.pop()
            if evaluations[item[1]] >= budget:  # a box being contracted holds its root already
                box, k, work, other, _ = item
                if work == _CONTRACT:
                    roots.append((box, k, other))
                else:
                    unresolved.append((box if work == _SEARCH else other, k, OVER_BUDGET))
                continue
            evaluations[item[1]] += 1
            j = len(batch)
            boxes[j] = item[0]
            low[0], high[0], low[1], high[1] = item[0][0], item[0][1], item[0][2], item[0][3]
            models.load_box(parameters, sign_registers, low, high, branches[item[1]], c, g, e, radii, j)
            statuses[j] = start
            for n in range(4):
                feasible[n, j] = -np.inf if n % 2 == 0 else np.inf
            batch.append(item)
        if len(batch) == 0:
            continue
        _evaluate_round(instructions, values, registers, h, parameters, residuals, derivatives, boxes, statuses,
                        len(batch), narrowed, outcomes, centers, rests)
        for j in range(len(batch)):
            _decided(stack, roots, unresolved, batch[j], outcomes[j], statuses[j], narrowed[j], domain, reference,
                     minimum_width)
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
    return found, left, evaluations.sum()


def prune_two_parameters(compiled: CompiledSystem, branches: np.ndarray,
                         domain: tuple[tuple[float, float], tuple[float, float]], exact_known=None,
                         minimum_width: float = MINIMUM_WIDTH, budget: int = EVALUATION_BUDGET,
                         order: int = 2, edge_symbols: int = EDGE_SYMBOLS, slider_values=(),
                         reference: tuple[tuple[float, float], tuple[float, float]] | None = None) -> PrunedRoots:
    """Every real root of a coupling-2 plan's two closure conditions in ``domain`` (one
    interval per parameter holding every mode: :func:`~.branch_and_prune.searched_box`)
    on each of ``branches`` (B, m), certified or left in a named undecided box (module
    docstring). ``exact_known``: the known squared distances as exact numbers (pair →
    int, Fraction, …); ``budget``: box evaluations allowed on each branch (a branch past
    it leaves its boxes undecided, the others go on). With slider joints, ``slider_values``
    the exact numbers of their geometry, and the domain is that of the parameters the
    program takes (a slider's t, not its searched value); ``reference``: the part of the
    domain the smallest widths are relative to (the domain where None; :func:`_split`).
    Cost O(boxes × instructions).

    Rows of the result: ``roots`` (lower ends (2), upper ends (2), branch index);
    ``unresolved`` the same and the reason.
    """
    program = compiled.straight_line_program()
    reduced = models.interval_program(program)
    inputs = instance_inputs(program, {**compiled.known, **(exact_known or {})}, compiled.fixed_signs, slider_values)
    base_c, base_e, start = models.instance_registers(reduced, *inputs)
    box = np.array([float(end) for interval in domain for end in interval])
    widths_of = box if reference is None else np.array([float(end) for interval in reference for end in interval])
    derivatives = np.ascontiguousarray(reduced.residual_derivatives, dtype=np.int64)
    source = reduced.program  # the program traced for intervals: its own registers
    found, left, evaluations = _prune_plane(
        reduced.instructions, reduced.values, base_c, base_e, start, np.ascontiguousarray(source.parameter_registers),
        source.sign_registers, np.ascontiguousarray(branches, dtype=float),
        np.ascontiguousarray(source.residual_registers), derivatives, box, widths_of, minimum_width, budget,
        models.quadratic_terms(order, 2 + edge_symbols, len(base_c), COLUMNS), 2 + edge_symbols)
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
