"""Certified real roots of a one-parameter closure condition by interval branch-and-prune
(issue 56; the CUIK idea of Porta, Ros and Thomas, IEEE T-RO 21(2), 2005, on the plan's
parameter).

On every free-sign branch the closure condition f(s) of a coupling-1 plan (thesis
§3.2–3.3) is a function of one squared distance s over the searched domain [0, S], S the
squared sum of the link diameters (no two joints are farther apart: every assembly mode has
its s in it), narrowed by the triangle inequalities of the steps with s as a side
(:func:`parameter_domain`). The domain is cut into boxes (intervals X of s), each decided
by one evaluation of the plan's straight-line program on first-order Taylor models
(:mod:`baranov.closure.interval_program`: f = c + g (s − m) ± e on the box), its
derivative's models computed only where the values leave the box undecided:

* *excluded*: some triangle of the branch cannot be built anywhere in the box (a radicand
  certainly negative), or f's model cannot vanish on it;
* *contracted* to where the triangles at an edge can exist and f's linear model can vanish
  (c + g (s − m) within ±e of 0), where that is less than half the box;
* *certified*: every radicand is positive on the box, 0 ∉ f′(X) (f strictly monotone: one
  root at most), and the interval Newton operator N(X) = m − f(m)/f′(X) maps the box into
  its interior (Moore; Neumaier, *Interval methods for systems of equations*, 1990,
  Thm. 5.1.7): exactly one root lies in it, and the box is contracted by the same operator
  and the linear model. Where f is monotone but N(X) is not inside X (the root near an end
  of X, or rounding keeping f(m) too wide), the same test runs on a box three times as wide
  as the linear model's zero set, centred on it, with f(m) evaluated at the midpoint alone
  (a thin box: wide by rounding only, where the model's value at m carries the remainder
  of the whole box); such a box may reach past X, so a root certified twice is merged by
  its uniqueness boxes;
* otherwise bisected, down to a width of ``minimum_width`` × S; a box that small and not
  decided is *unresolved* and named with its reason: a domain edge inside it (a radicand's
  range holds 0: a root on a flat triangle, or only the edge itself), or a derivative that
  may vanish or is unbounded (a double root, joints that the plan divides by at one point).

Every branch's boxes run in one compiled loop (numba), in rounds: each round takes up to
``columns`` boxes of any branches and kind (searched, certified about a root's estimate,
contracted) off the work stack, evaluates them side by side
(:func:`~baranov.closure.interval_program.evaluate_models` over the columns), and decides
each as above; the order of the decisions changes, not the decisions. What the loop proves: each
certified box holds exactly one real root of its branch, and no real root of any branch
lies in the domain outside the certified and unresolved boxes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numba
import numpy as np

from baranov.closure import CompiledSystem
from baranov.closure.bilateration import parameter_triangles, step_sides
from baranov.closure.interval_program import (
    COLUMNS,
    EDGE,
    FEASIBLE,
    INFEASIBLE,
    enclosing,
    evaluate_models,
    instance_registers,
    interval_program,
    linear_model,
    load_box,
    model_range,
    new_registers,
    quadratic_terms,
    rounded_down,
    rounded_up,
)
from baranov.closure.straight_line import StraightLineProgram

#: A box's status where f's model (or a triangle) excludes it.
EXCLUDED = 3
#: Why a box was left undecided (:attr:`PrunedRoots.unresolved`'s last column).
AT_EDGE, FLAT_DERIVATIVE, OVER_BUDGET, AT_COINCIDENCE = 1, 2, 3, 4
REASONS = {AT_EDGE: "a domain edge of the branch (a triangle flat) lies in it",
           FLAT_DERIVATIVE: "the closure condition's derivative may vanish or is unbounded there (a double root, "
                            "or joints the plan divides by at one point)",
           OVER_BUDGET: "not examined within the evaluation budget",
           AT_COINCIDENCE: "a squared distance searched is within the smallest width of 0 there (its joints "
                           "nearly coincide, where the plan divides by it); the modes where they coincide come "
                           "from another plan"}
#: Boxes narrower than this fraction of the domain are not bisected further.
MINIMUM_WIDTH = 1e-12
#: ... times this within two widths of the domain's ends (:func:`_smallest_width`).
END_WIDTH = 1e-3
#: Box evaluations allowed per solve, over all branches (a complete 9-link solve takes a few
#: thousand; a linkage that moves, its condition 0 along a range, would take them all).
EVALUATION_BUDGET = 20_000
#: ... and at least this many per branch: random 11-link instances (32 branches) need up to
#: 124 000 boxes to be decided (every coupling-1 truss, seed 5: median 10 000, 99th
#: percentile 68 000), and at 400 a branch 116 of the 409 fell back to the searches
#: (docs/numeric.md, "Budget"). A linkage that moves spends it all, about 4 µs a box,
#: before the searches take over.
BOXES_PER_BRANCH = 4000


#: Boxes side by side in a round over many instances, which fill every column: a round's
#: fixed costs spread over more boxes (7/B1 sweep: 3.5 µs a box at 32, 1.6 at 128, measured).
#: One instance takes up to COLUMNS, 4 × its branches: rounds of 16 left 7/B1's frontier
#: waiting on the stack (7-link examples: 15 ms for the four at 2 × branches, 8 ms at 4 ×).
MANY_COLUMNS = 128


def evaluation_budget(branches: int) -> int:
    """Box evaluations allowed to a solve with ``branches`` free-sign branches."""
    return max(EVALUATION_BUDGET, BOXES_PER_BRANCH * branches)
#: Newton contractions of a certified box at most (each at least halves it, quadratically near the root).
CONTRACTIONS = 30


@dataclass(frozen=True)
class PrunedRoots:
    """What :func:`prune_one_parameter` proved.

    Attributes
    ----------
    roots
        (K, 3): lower end, upper end and branch index of each certified box,
        holding exactly one real root of that branch's closure condition.
    unresolved
        (U, 4): lower end, upper end, branch index and reason (AT_EDGE,
        FLAT_DERIVATIVE, OVER_BUDGET) of each undecided box, adjacent boxes merged.
    evaluations
        interval evaluations of the program made.
    domain
        the parameter's range searched, (lower, upper).
    boxes
        with ``record``: (E, 7), each box evaluated: lower end, upper end, branch
        index, work (SEARCH, CERTIFY, CONTRACT), decision (FEASIBLE, EDGE, EXCLUDED),
        whether f was monotone on it, and the program's status (FEASIBLE, EDGE,
        INFEASIBLE: a triangle that cannot exist).
    """

    roots: np.ndarray
    unresolved: np.ndarray
    evaluations: int
    domain: tuple[float, float]
    boxes: np.ndarray | None = None

    @property
    def complete(self) -> bool:
        """Every box of every branch was excluded or certified."""
        return len(self.unresolved) == 0


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _divide(al, ah, bl, bh):  # pragma: no cover - compiled
    """[al, ah] ÷ [bl, bh] (0 ∉ [bl, bh]), rounded outward."""
    q1, q2, q3, q4 = al / bl, al / bh, ah / bl, ah / bh
    return rounded_down(min(min(q1, q2), min(q3, q4))), rounded_up(max(max(q1, q2), max(q3, q4)))


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _linear_zeros(center, slope, rest, middle, radius, a, b):  # pragma: no cover - compiled
    """The part of [a, b] where center + slope (x − middle) ± rest can vanish, |x − middle| ≤ radius."""
    if slope == 0.0:
        return (a, b) if abs(center) <= rest else (1.0, 0.0)
    first, second = (-center - rest) / slope, (-center + rest) / slope
    low, high = min(first, second), max(first, second)
    return max(a, rounded_down(middle + rounded_down(low))), min(b, rounded_up(middle + rounded_up(high)))


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _newton_image(a, b, g0, g1, center, rest):  # pragma: no cover - compiled
    """N([a, b]) = m − f(m)/f′(X): f(m) in center ± rest, f′(X) in [g0, g1] (0 excluded)."""
    m = 0.5 * (a + b)
    q0, q1 = _divide(rounded_down(center - rest), rounded_up(center + rest), g0, g1)
    return rounded_down(m - q1), rounded_up(m - q0)


#: The order of the Taylor models the boxes are decided with (1 or 2).
ORDER = 1

#: The work on a box (:func:`_prune`): search it; test the box about f's linear model's
#: root for exactly one root; contract a box known to hold exactly one root.
SEARCH, CERTIFY, CONTRACT = 0, 1, 2


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _evaluated(instructions, values, registers, h, feasible, status, starts, residual, derivative, low, high, count,
               out):  # pragma: no cover - compiled
    """Evaluate the boxes [low[j], high[j]] loaded in the first ``count`` columns (their
    status starting from their instance's, ``starts[j]``): row j of
    ``out`` gets (status, f's center, slope and remainder, f′'s range low and high, and the
    part [z0, z1] of the box where the triangles at an edge can exist and f's linear model
    vanish); status EXCLUDED where that part is empty. f′'s models are computed only if
    some box is FEASIBLE and not excluded."""
    c, g, e, radius, scratch = registers
    for j in range(count):
        status[j] = starts[j]
        feasible[0, j], feasible[1, j] = -np.inf, np.inf
    evaluate_models(instructions[:values], c, g, h, e, radius, feasible, status, scratch, 1, count)
    needed = False
    for j in range(count):
        a, b = low[j], high[j]
        (center, rest), slope = linear_model(c, g, h, e, radius, residual, j, 1), g[0, residual, j]
        middle = 0.5 * (a + b)
        z0, z1 = max(a, rounded_down(middle + feasible[0, j])), min(b, rounded_up(middle + feasible[1, j]))
        if status[j] != INFEASIBLE:
            z0, z1 = _linear_zeros(center, slope, rest, middle, radius[0, j], z0, z1)
        kind = EXCLUDED if status[j] == INFEASIBLE or z0 > z1 else status[j]
        out[j, 0], out[j, 1], out[j, 2], out[j, 3] = kind, center, slope, rest
        out[j, 4], out[j, 5], out[j, 6], out[j, 7] = -np.inf, np.inf, z0, z1
        needed = needed or kind == FEASIBLE
    if needed:
        evaluate_models(instructions[values:], c, g, h, e, radius, feasible, status, scratch, 1, count)
        for j in range(count):
            if out[j, 0] == FEASIBLE:
                out[j, 4], out[j, 5] = model_range(c, g, h, e, radius, derivative, j)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _smallest_width(a, b, low, high, minimum_width, reference_low, reference_high):  # pragma: no cover - compiled
    """How narrow the box [a, b] of the domain [low, high] may be bisected: a width w =
    ``minimum_width`` × (``reference_high`` + the box's distance from the reference
    interval), END_WIDTH × w within two widths of an end of the domain, else w. The
    reference is the domain itself, except where a slider chain's parameter has no bound
    and the domain reaches far past the linkage's size: beyond it the width grows with
    the box's distance, a relative precision, so that the far boxes cost no more than the
    near ones.
    The domain ends where a triangle with the parameter as a side flattens; the root of
    that triangle's radicand R varies there like √(hi − s), so f varies by about
    |∂f/∂√R| √(R's range) across a box at the end: excluding it when f is 1e-2 and that
    derivative 3 takes R below 1e-5, a box 1e-14 of the domain's end wide (every
    coupling-1 truss of 11 links, seed 5: four instances decided that were not at 1e-12).
    Boxes at an end are few at each width, so the deeper bisection costs little."""
    width = minimum_width * (reference_high + max(0.0, reference_low - b, a - reference_high))
    near = 2.0 * (b - a)
    return END_WIDTH * width if a - low <= near or high - b <= near else width


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _split(stack, unresolved, a, b, k, status, z0, z1, minimum_width):  # pragma: no cover - compiled
    """An undecided box [a, b] of branch k: searched again as [z0, z1] where that is less
    than half of it, else bisected, or left unresolved below ``minimum_width``."""
    if z1 - z0 < 0.5 * (b - a):
        stack.append((z0, z1, k, SEARCH, 0.0, 0.0, 0.0, 0.0, 0))
    elif b - a <= minimum_width:
        unresolved.append((a, b, k, AT_EDGE if status == EDGE else FLAT_DERIVATIVE))
    else:
        middle = 0.5 * (z0 + z1)
        stack.append((middle, z1, k, SEARCH, 0.0, 0.0, 0.0, 0.0, 0))
        stack.append((z0, middle, k, SEARCH, 0.0, 0.0, 0.0, 0.0, 0))


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _prune(instructions, values, instance_c, instance_e, starts, instance_outputs, parameter, sign_registers, branches,
           residual, derivative, low, high, reference_low, reference_high, minimum_width, budget, columns, record, h
           ):  # pragma: no cover - compiled
    """The branch-and-prune loop of :func:`prune_instances` over every branch of every
    instance (the first ``values`` instructions compute the values, the rest the
    derivatives; instance i's registers ``instance_c[i]``, ``instance_e[i]``, its status
    ``starts[i]``, its domain [low[i], high[i]], the reference of its smallest widths
    [reference_low[i], reference_high[i]]: :func:`_smallest_width`): rounds of up to ``columns`` boxes of any
    instances, each round one evaluation of the program side by side. A box's branch
    index k stands for branch k mod B of instance k // B. With ``record``, every box
    evaluated is logged: (low, high, branch index, work kind, decision, f monotone, status)."""
    registers = new_registers(instance_c[0], instance_e[0], 1, columns)
    c, g, e, radius, _ = registers
    feasible, status, out = np.empty((2, columns)), np.empty(columns, dtype=np.int64), np.empty((columns, 8))
    column_starts = np.empty(columns, dtype=np.int64)
    parameters, box_low, box_high = np.array([parameter]), np.empty(1), np.empty(1)
    lows, highs = np.empty(columns), np.empty(columns)
    count = branches.shape[0]
    stack = [(low[0], high[0], 0, SEARCH, 0.0, 0.0, 0.0, 0.0, 0)]
    stack.pop()
    for i in range(low.shape[0] - 1, -1, -1):  # instance 0 first off the stack
        if starts[i] != INFEASIBLE:
            for k in range(count - 1, -1, -1):
                stack.append((low[i], high[i], i * count + k, SEARCH, 0.0, 0.0, 0.0, 0.0, 0))
    batch = [(0.0, 0.0, 0, 0, 0.0, 0.0, 0.0, 0.0, 0)]
    roots = [(0.0, 0.0, 0, 0.0, 0.0)]
    roots.pop()
    unresolved = [(0.0, 0.0, 0, 0)]
    unresolved.pop()
    evaluations = np.zeros(low.shape[0], dtype=np.int64)
    log = [(0.0, 0.0, 0, 0, 0.0, False, 0)]
    log.pop()
    slots = np.empty(columns, dtype=np.int64)  # each batch item's first column
    while len(stack) > 0:
        batch.clear()
        used = 0
        while len(stack) > 0 and used < columns - 1:
            item = stack.pop()
            a, b, k, kind, u0, u1 = item[0], item[1], item[2], item[3], item[4], item[5]
            i = k // count
            if evaluations[i] >= budget:  # a box being contracted holds its root already
                if kind == CONTRACT:
                    roots.append((a, b, k, u0, u1))
                else:
                    unresolved.append((a, b, k, OVER_BUDGET) if kind == SEARCH else (u0, u1, k, OVER_BUDGET))
                continue
            evaluations[i] += 1
            slots[len(batch)] = used
            # a certification or contraction also evaluates f at the box's midpoint alone (a
            # thin box): the Newton operator's f(m) is then wide by rounding only, not by the
            # box's remainder
            for thin in range(1 if kind == SEARCH else 2):
                low_end, high_end = (0.5 * (a + b), 0.5 * (a + b)) if thin else (a, b)
                box_low[0], box_high[0] = low_end, high_end
                lows[used], highs[used], column_starts[used] = low_end, high_end, starts[i]
                for r in instance_outputs:
                    c[r, used], e[r, used] = instance_c[i, r], instance_e[i, r]
                load_box(parameters, sign_registers, box_low, box_high, branches[k - i * count], c, g, e, radius, used)
                used += 1
            batch.append(item)
        if len(batch) == 0:
            continue
        _evaluated(instructions, values, registers, h, feasible, status, column_starts, residual, derivative, lows, highs,
                   used, out)
        for n in range(len(batch)):
            j = slots[n]
            a, b, k, kind, u0, u1, z0, z1, steps = batch[n]
            i = k // count
            decision, center, slope, rest, g0, g1 = out[j, 0], out[j, 1], out[j, 2], out[j, 3], out[j, 4], out[j, 5]
            monotone = decision == FEASIBLE and (g0 > 0.0 or g1 < 0.0)  # one root at most
            if record:
                log.append((a, b, k, kind, decision, monotone, status[j]))
            if kind == CONTRACT:
                _contract(stack, roots, a, b, k, u0, u1, steps, monotone, out[j + 1, 1], out[j + 1, 3], g0, g1,
                          out[j, 6], out[j, 7])
            elif kind == CERTIFY:
                _certify(stack, unresolved, a, b, k, u0, u1, z0, z1, decision, monotone, out[j + 1, 1], out[j + 1, 3],
                         g0, g1, _smallest_width(u0, u1, low[i], high[i], minimum_width, reference_low[i], reference_high[i]))
            elif decision != EXCLUDED:
                _search(stack, unresolved, a, b, k, decision, monotone, center, slope, rest, g0, g1,
                        out[j, 6], out[j, 7], _smallest_width(a, b, low[i], high[i], minimum_width,
                                                              reference_low[i], reference_high[i]))
    found = np.empty((len(roots), 5))
    for n in range(len(roots)):
        found[n, 0], found[n, 1], found[n, 2], found[n, 3], found[n, 4] = roots[n]
    left = np.empty((len(unresolved), 4))
    for n in range(len(unresolved)):
        left[n, 0], left[n, 1], left[n, 2], left[n, 3] = unresolved[n]
    boxes = np.empty((len(log), 7))
    for n in range(len(log)):
        a, b, k, kind, decision, monotone, state = log[n]
        boxes[n, 0], boxes[n, 1], boxes[n, 2], boxes[n, 3] = a, b, k, kind
        boxes[n, 4], boxes[n, 5], boxes[n, 6] = decision, monotone, state
    return found, left, evaluations, boxes


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _search(stack, unresolved, a, b, k, decision, monotone, center, slope, rest, g0, g1, z0, z1, minimum_width
            ):  # pragma: no cover - compiled
    """A searched box [a, b] of branch k, not excluded: where f is monotone, certified
    (then contracted) or narrowed and handed to a certification on a box about the
    linear model's root; else split."""
    if monotone:
        n0, n1 = _newton_image(a, b, g0, g1, center, rest)
        if n1 < a or n0 > b:
            return
        if a < n0 and n1 < b:  # exactly one root, in [n0, n1]
            stack.append((n0, n1, k, CONTRACT, a, b, 0.0, 0.0, 0))
            return
        z0, z1 = max(z0, n0), min(z1, n1)
        if z0 > z1:
            return
        if slope != 0.0:
            # f is monotone on [a, b], so its one root, if any, is in [z0, z1], where f's
            # linear model vanishes: certify it on a box three times as wide as that set,
            # centred on the model's root (it may reach past [a, b]: a root found twice is
            # merged by its uniqueness boxes)
            estimate, spread = 0.5 * (a + b) - center / slope, 3.0 * rest / abs(slope)
            stack.append((estimate - spread, estimate + spread, k, CERTIFY, a, b, z0, z1, 0))
            return
    _split(stack, unresolved, a, b, k, decision, z0, z1, minimum_width)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _certify(stack, unresolved, y0, y1, k, a, b, z0, z1, decision, monotone, center, rest, g0, g1,
             minimum_width):  # pragma: no cover - compiled
    """The box [y0, y1] about the linear model's root of a box [a, b] on which f is
    monotone, its root in [z0, z1] ⊆ [y0, y1]: no root in it (then none in [a, b]),
    exactly one (contracted, unless it lies outside [a, b]), or undecided ([a, b] split).
    ``center`` ± ``rest``: f at the box's midpoint, evaluated alone."""
    if decision == EXCLUDED:
        return
    if monotone:
        n0, n1 = _newton_image(y0, y1, g0, g1, center, rest)
        if n1 < y0 or n0 > y1:
            return
        if y0 < n0 and n1 < y1:
            if not (n1 < a or n0 > b):
                stack.append((n0, n1, k, CONTRACT, y0, y1, 0.0, 0.0, 0))
            return
    _split(stack, unresolved, a, b, k, FEASIBLE, z0, z1, minimum_width)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _contract(stack, roots, n0, n1, k, u0, u1, steps, monotone, center, rest, g0, g1, z0, z1
              ):  # pragma: no cover - compiled
    """A box [n0, n1] known to hold exactly one root (alone in [u0, u1]), shrunk to where
    f's linear model can vanish and to its Newton image while that takes off a tenth, at
    most CONTRACTIONS times; then a root. ``center`` ± ``rest``: f at the box's midpoint,
    evaluated alone (with the box's own model a certified box 1.4 wide stayed so, and its
    midpoint did not verify as a mode)."""
    if monotone:
        m0, m1 = _newton_image(n0, n1, g0, g1, center, rest)
        c0, c1 = max(z0, m0), min(z1, m1)
        if not (c0 > c1 or c1 - c0 >= 0.9 * (n1 - n0)):
            if steps + 1 < CONTRACTIONS:
                stack.append((c0, c1, k, CONTRACT, u0, u1, 0.0, 0.0, steps + 1))
            else:
                roots.append((c0, c1, k, u0, u1))
            return
    roots.append((n0, n1, k, u0, u1))



def prune_one_parameter(compiled: CompiledSystem, branches: np.ndarray, domain: tuple[float, float],
                        exact_known=None, minimum_width: float = MINIMUM_WIDTH,
                        budget: int = EVALUATION_BUDGET, slider_values=(),
                        reference: tuple[float, float] | None = None) -> PrunedRoots:
    """Every real root of a coupling-1 plan's closure condition in ``domain`` (an
    interval of the parameter holding every mode: :func:`parameter_domain`) on each of
    ``branches`` (B, m), certified or left in a named undecided box (module
    docstring). ``exact_known``: the known squared distances as exact numbers (a pair →
    int, Fraction, …), so that the boxes are decided for them and not for their floats;
    with slider joints, ``slider_values`` the exact numbers of their geometry
    (:func:`~baranov.closure.traced_sliders.exact_slider_constants`), and the domain is
    that of the parameter the program takes (a slider's t, not its searched value);
    ``reference``: the part of the domain the smallest widths are relative to (the
    domain where None; :func:`_smallest_width`). Cost: O(boxes × instructions); the boxes
    are about the roots' and edges' number times the bisections to isolate them.
    """
    inputs = instance_inputs(compiled.straight_line_program(), {**compiled.known, **(exact_known or {})},
                             compiled.fixed_signs, slider_values)
    return prune_instances(compiled.straight_line_program(), branches, [inputs], [domain], minimum_width, budget,
                           references=None if reference is None else [reference])[0]


def prune_instances(program: StraightLineProgram, branches: np.ndarray, inputs: Sequence[tuple], domains: Sequence,
                    minimum_width: float = MINIMUM_WIDTH, budget: int = EVALUATION_BUDGET,
                    record: bool = False, references: Sequence | None = None) -> list[PrunedRoots]:
    """:func:`prune_one_parameter` for many instances of one coupling-1 plan at once
    (``inputs``: each instance's :func:`instance_inputs`; ``domains``: its searched
    interval), their boxes side by side in the same rounds (a sweep fills every column,
    where one instance of a 7-link truss fills a few). The same boxes, decisions and
    roots as one instance at a time; ``budget`` is per instance. Cost
    O(instances × boxes × instructions), without Python work per box. ``record``: each
    result's ``boxes`` lists the boxes evaluated (a diagnostic: where the boxes go);
    ``references``: each instance's reference interval of the smallest widths (its domain
    where None)."""
    reduced = interval_program(program)
    source = reduced.program  # the program traced for intervals: its own registers
    registers = [instance_registers(reduced, *arguments) for arguments in inputs]
    low, high = (np.array([float(domain[end]) for domain in domains]) for end in (0, 1))
    reference_low, reference_high = (low, high) if references is None else (
        np.array([float(reference[end]) for reference in references]) for end in (0, 1))
    count = len(branches)
    columns = min(COLUMNS if len(inputs) == 1 else MANY_COLUMNS, max(8, 4 * count * len(inputs)))
    found, left, evaluations, boxes = _prune(reduced.instructions, reduced.values,
                                      np.array([center for center, _, _ in registers]),
                                      np.array([remainder for _, remainder, _ in registers]),
                                      np.array([status for _, _, status in registers], dtype=np.int64),
                                      reduced.instance_outputs, int(source.parameter_registers[0]),
                                      source.sign_registers, np.ascontiguousarray(branches, dtype=float),
                                      int(source.residual_registers[0]), int(reduced.residual_derivatives[0, 0]),
                                      low, high, reference_low, reference_high, minimum_width, budget, columns,
                                      record,
                                      quadratic_terms(ORDER, 1, len(registers[0][0]), columns))
    owner_found, owner_left = found[:, 2] // count, left[:, 2] // count
    pruned = []
    for i in range(len(inputs)):
        roots, unresolved = found[owner_found == i], left[owner_left == i]
        roots[:, 2] -= i * count
        unresolved[:, 2] -= i * count
        mine = boxes[boxes[:, 2] // count == i]
        mine[:, 2] -= i * count
        unresolved = _at_coincidence(unresolved, low[i], reference_high[i], minimum_width)
        pruned.append(PrunedRoots(_distinct(roots), _merged(unresolved), int(evaluations[i]), (low[i], high[i]), mine))
    return pruned


def _at_coincidence(boxes: np.ndarray, low: float, high: float, minimum_width: float) -> np.ndarray:
    """Undecided boxes (rows: ends, branch, reason) at a squared distance's 0 — the
    domain starts at 0 and the box ends within ``minimum_width`` × ``high`` (the reference
    interval's upper end) of it —
    given the reason AT_COINCIDENCE: the plan divides by the parameter there, so no box
    at 0 is ever decided, and the modes where its joints coincide come from another plan
    (:mod:`baranov.solvers.coincidence`)."""
    if low == 0.0:
        boxes[(boxes[:, 0] == 0.0) & (boxes[:, 1] <= minimum_width * high) & (boxes[:, 3] != OVER_BUDGET), 3] \
            = AT_COINCIDENCE
    return boxes


def instance_inputs(program: StraightLineProgram, known: Mapping, fixed_signs: Mapping, slider_values=()
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The inputs of the plan's program for one instance: the float intervals around the
    squared distances ``known`` (pair → number: exact ones, int, Fraction, …, enclosed
    exactly; floats as they are) and around the numbers of its slider geometry
    (``slider_values``, :func:`~baranov.closure.traced_sliders.exact_slider_constants`),
    and the link steps' orientation signs ``fixed_signs`` (triangle → ±1)."""
    return (*enclosing([known[pair] for pair in program.known_pairs] + list(slider_values)),
            np.array([fixed_signs[t] for t in program.fixed_triangles], float))


def _distinct(roots: np.ndarray) -> np.ndarray:
    """Certified roots (rows: enclosure, branch, uniqueness box) without repeats: two of
    one branch are one root where the enclosure of either lies in the other's uniqueness
    box (a box holding exactly one root). Returns rows (enclosure, branch), by value."""
    roots = roots[np.lexsort((roots[:, 0], roots[:, 2]))]
    kept: list[np.ndarray] = []
    for root in roots:
        same = [n for n, other in enumerate(kept) if other[2] == root[2] and (
            (other[3] <= root[0] and root[1] <= other[4]) or (root[3] <= other[0] and other[1] <= root[4]))]
        if not same:
            kept.append(root)
        elif root[1] - root[0] < kept[same[0]][1] - kept[same[0]][0]:
            kept[same[0]] = root
    distinct = np.array(kept).reshape(-1, 5)[:, :3]
    return distinct[np.argsort(distinct[:, 0], kind="stable")]


def _merged(boxes: np.ndarray) -> np.ndarray:
    """Undecided boxes with adjacent ones of the same branch and reason merged."""
    if len(boxes) == 0:
        return boxes
    boxes = boxes[np.lexsort((boxes[:, 0], boxes[:, 3], boxes[:, 2]))]
    merged = [boxes[0].copy()]
    for box in boxes[1:]:
        last = merged[-1]
        if box[2] == last[2] and box[3] == last[3] and box[0] <= last[1]:
            last[1] = max(last[1], box[1])
        else:
            merged.append(box.copy())
    return np.array(merged)


def parameter_domain(scene, plan, upper: float, index: int = 0) -> tuple[float, float]:
    """The range of a plan's parameter s (number ``index``) that can hold a mode: [0, ``upper``]
    (S, :func:`domain_upper_bound`) cut by every step whose triangle has s as one side and
    two known squared sides a, b, which exists only for (√a − √b)² ≤ s ≤ (√a + √b)²
    (the critical values of :func:`~.one_parameter.critical_values`), with the roots
    rounded outward; not a step with a slider joint, whose known distances are to the
    slider's points on two different links (a 7-link slider chain lost two of its ten
    modes when they cut it). O(steps).

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> scene = load_scene("examples/7-B1.json")
    >>> [round(end, 6) for end in parameter_domain(scene, solvable_plan(scene), 1e4)]
    [25.501244, 104.159745]
    """
    parameter = frozenset(plan.parameters[index])
    low, high = 0.0, upper
    sliders = {slider.joint for slider in scene.sliders}
    for step_index, position in parameter_triangles(plan, scene.known).items():
        step = plan.steps[step_index]
        sides = step_sides(step)
        if sides[position] != parameter or sliders.intersection(step.triangle):
            continue  # another parameter's; or a slider's distances, to its two points on different links
        (a_lo, a_hi), (b_lo, b_hi) = (_root_enclosure(scene.known[side]) for side in sides if side != parameter)
        difference = max(a_lo - b_hi, b_lo - a_hi, 0.0)
        low = max(low, math.nextafter(difference * difference, -math.inf) if difference > 0 else 0.0)
        total = math.nextafter(a_hi + b_hi, math.inf)
        high = min(high, math.nextafter(total * total, math.inf))
    return low, high


def _root_enclosure(value) -> tuple[float, float]:
    """An interval of floats holding √value (value exact: an int, Fraction, … or float)."""
    low, high = (float(x[0]) for x in enclosing([value]))
    return (max(0.0, math.nextafter(math.sqrt(max(low, 0.0)), -math.inf)),
            math.nextafter(math.sqrt(high), math.inf))


def searched_domain(scene, plan) -> tuple[float, float]:
    """The range of a coupling-1 plan's parameter that holds every mode of ``scene``:
    :func:`parameter_domain` within [0, S], S from the link diameters
    (:func:`domain_upper_bound`), every bound rounded outward from the exact dimensions.

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> scene = load_scene("examples/7-B1.json")
    >>> [round(end, 6) for end in searched_domain(scene, solvable_plan(scene))]
    [25.501244, 104.159745]
    """
    return parameter_domain(scene, plan, _diameters_bound(scene))


#: Relative widening of a bound computed in floats from exact dimensions (a shortest
#: path's sum of square roots: each step's rounding is below 2^-52 relative).
FLOAT_BOUND_SLACK = 1e-12


def slider_searched_domain(scene, plan, searched, index: int = 0) -> tuple[float, float] | None:
    """With slider joints, the range of a plan's parameter ``index``, as the plan's
    program takes it, that holds every mode: for a slider's oriented distance t, |t| at
    most the shortest path of link dimensions to the nearer of the slider's points
    (:meth:`~baranov.scene.Scene.largest_distance`: the distance to the axis is at most
    that to a point of it); for a squared distance, :func:`parameter_domain` below the
    square of that path, or where there is none, below the triangles' bounds alone. Rounded
    outward. None where nothing bounds it (``searched``: the compiled system's
    :class:`~baranov.closure.sliders.SearchedParameter` maps;
    :func:`unbounded_slider_domain` then)."""
    pair = tuple(plan.parameters[index])
    bound = scene.largest_distance(*pair) * (1 + FLOAT_BOUND_SLACK)
    mapping = searched.get(frozenset(pair))
    if not math.isfinite(bound):
        if mapping is not None and mapping.signed:
            return None
        domain = parameter_domain(scene, plan, math.inf, index)
        return domain if math.isfinite(domain[1]) else None
    if mapping is not None:
        return (-bound, bound) if mapping.signed else None
    return parameter_domain(scene, plan, math.nextafter(bound * bound, math.inf), index)


#: Where no path of link dimensions bounds a slider chain's parameter, the
#: branch-and-prune searches it out to this many times the linkage's size (a slider's t)
#: or its square (a squared distance). The sampling searches' first grid looks little past
#: 40 times the size. On the 57 such chains among 300 random 7- and 9-link slider chains
#: (seed 5), the modes were msolve's on every one both solve; on the 32 nine-link
#: coupling-2 ones, reaches 30, 1e3, 1e6 took 18.0, 21.0, 22.1 s (docs/numeric.md).
UNBOUNDED_REACH = 1e3


def unbounded_slider_domain(scene, plan, searched, index: int = 0
                            ) -> tuple[tuple[float, float], tuple[float, float]]:
    """For a slider chain's parameter ``index`` that no path of link dimensions bounds
    (:func:`slider_searched_domain` is None): the domain the branch-and-prune searches,
    UNBOUNDED_REACH times the linkage's size R out (|t| ≤ that; a squared distance
    :func:`parameter_domain` below its square), and the reference interval its smallest
    widths are relative to (|t| ≤ R, s ≤ R²): near the linkage the boxes are as narrow as
    on a bounded domain, far out they are relative to their distance. No mode beyond the
    domain is excluded: the certificate says so."""
    mapping = searched[frozenset(plan.parameters[index])]
    reach = math.nextafter(UNBOUNDED_REACH * mapping.scale, math.inf)
    if mapping.signed:
        return (-reach, reach), (-mapping.scale, mapping.scale)
    low, high = parameter_domain(scene, plan, math.nextafter(reach * reach, math.inf), index)
    return (low, high), (low, min(high, max(low, mapping.scale**2)))


def searched_box(scene, plan) -> tuple[tuple[float, float], ...]:
    """:func:`searched_domain` for each parameter of a plan (coupling 2: a box).

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> scene = load_scene("examples/9-B28.json")
    >>> [[round(end, 4) for end in interval] for interval in searched_box(scene, solvable_plan(scene))]
    [[8.1217, 6864.1005], [210.3078, 9676.5811]]
    """
    upper = _diameters_bound(scene)
    return tuple(parameter_domain(scene, plan, upper, index) for index in range(plan.number_of_parameters))


def _diameters_bound(scene) -> float:
    """:func:`domain_upper_bound` of the scene's links."""
    return domain_upper_bound([_root_enclosure(max(link.squared_distances.values()))[1] for link in scene.links])


def domain_upper_bound(diameters: list[float]) -> float:
    """S = (Σ link diameters)², rounded up: no two joints of an assembled linkage are
    farther apart than the sum of the link diameters (a path of links joins them), so
    every mode's squared distance lies in [0, S]."""
    total = 0.0
    for diameter in diameters:
        total = math.nextafter(total + math.nextafter(diameter, math.inf), math.inf)
    return math.nextafter(total * total, math.inf)


def compile_kernels() -> None:
    """Compile this module's kernels and the Taylor-model arithmetic (numba caches them
    on disk, about 13 s the first time) by one solve of a random pentad: ``make setup``
    runs it, so that a first ``baranov solve`` does not pay it."""
    from baranov.closure import sign_branches
    from baranov.enumerate import baranov_trusses
    from baranov.scene.instances import generic_integer_configuration, scene_of
    from baranov.solvers.coincidence import solvable_plan
    from baranov.solvers.placement import compile_scene

    chain = baranov_trusses(5)[0]
    scene = scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(0)))
    plan = solvable_plan(scene)
    prune_one_parameter(compile_scene(scene, plan), sign_branches(len(plan.free_sign_triangles)),
                        searched_domain(scene, plan), scene.known)
