"""A plan's straight-line program run over a box of parameter values, with its
derivatives, in Taylor models of the first or second order (issue 56).

The bilateration kernel, traced once per plan into a :class:`~.straight_line.StraightLineProgram`
(its fifth arithmetic), is run here on a *box* — one closed interval per parameter,
[m_k − ρ_k, m_k + ρ_k] — so that one evaluation decides the box (the CUIK idea of Porta,
Ros and Thomas, "A branch-and-prune solver for distance constraints", IEEE T-RO 21(2),
2005, with the box shrunk to the plan's one or two parameters, every other distance a
function of them).

Plain interval arithmetic is useless here: along the program's 200-odd operations the
dependency problem compounds, and on 7/B1 a box of width 0.001 in s1,4 gives the closure
residual an interval 200 times wider than its range, its derivative an interval 100 times
wider than its range even on boxes of width 0.03 (measured). Each register therefore holds
a *first-order Taylor model* (an affine form with a remainder: Stolfi and de Figueiredo,
*Self-validated numerical methods and applications*, 1997; Berz and Makino's Taylor models
of order 1)

    v = c + Σ_k g_k u_k + ε,   |u_k| ≤ ρ_k,   |ε| ≤ e,

which holds the register's exact value at every point m + u of the box: the linear
dependence on the parameters is carried exactly and only the second-order terms and
rounding go to the remainder e, so a model's range c ± (Σ|g_k|ρ_k + e) is tight to second
order in the box's width. The operations (u the box's symbols, R = Σ|g_k|ρ_k + e a
model's deviation from c):

* a ± b: c_a ± c_b, g_a ± g_b, e_a + e_b;
* a × b: c_a c_b, c_a g_b + c_b g_a, |c_a| e_b + |c_b| e_a + R_a R_b;
* 1/b on a range [L, U] ∌ 0: 1/c, −g/c², e/c² + R²/(c² min(|L|, |U|)) (the Lagrange
  remainder of 1/x at c); a ÷ b = a × (1/b), the whole line where the range holds 0;
* √a on a range [L, U], L > 0: √c, g/(2√c), e/(2√c) + R²/(2√c (√L + √c)²);
* a rounding slack of 2^-50 times the magnitudes of every term computed is added to each
  remainder (each c and g_k is a sum of at most three correctly rounded terms), and the
  remainders themselves are rounded up.

Second order. A model may also carry the quadratic terms exactly,

    v = c + Σ_k g_k u_k + Σ_{k≤l} h_kl u_k u_l + ε,

so that only third-order terms and rounding go to the remainder (Q = Σ|h_kl| ρ_k ρ_l, a
model's deviation R = L + Q + e with L = Σ|g_k| ρ_k):

* a × b: h = c_a h_b + c_b h_a + (g_a u)(g_b u); e = |c_a| e_b + |c_b| e_a + L_a (Q_b + e_b)
  + (Q_a + e_a)(L_b + Q_b + e_b);
* 1/b = 1/c − δ/c² + δ²/c³ − δ³/(c³ b) (δ = b − c): the linear part of δ² kept in h, the
  rest of it and R³/(|c|³ min(|L|, |U|)) in e;
* √a = √c + δ/(2√c) − δ²/(8 c√c) + δ³/(16 ξ^{5/2}), ξ ≥ L: R³/(16 L^{5/2}) in e, where
  that is smaller than the first-order form's remainder (away from an edge); else the
  first-order form, h_a/(2√c) kept.

A range c + Σ h_kk ρ_k²/2 ± (L + Σ_k |h_kk| ρ_k²/2 + Σ_{k<l} |h_kl| ρ_k ρ_l + e) (a
square's term lies in [0, h_kk ρ_k²]); what decides a box reads the first-order model
that is (:func:`linear_model`). On 9/B28 about a mode, a box of half-width 1 gives the
residuals' ranges 5 % wider than their sampled ranges and the derivatives' 12-22 %
(first order: 3.4 and 7-12 times); `tests/test_interval_program.py`. A box costs about
2.2 times as much (6400 random boxes of 7/B1: 1.5 against 3.3 µs). The quadratic terms h are an argument of the compiled
arithmetic, None for first order (:func:`quadratic_terms`), so that numba compiles each
order apart.

Square roots of a step. A radicand whose range is certainly negative makes the box
*infeasible* on that branch (:data:`INFEASIBLE`). A range that holds 0 is a domain edge in
the box (:data:`EDGE`): the root, which exists only on the part of the box where its
radicand x is in [0, r²] (r ≥ √U), is enclosed there by the chord and the parallel
tangent, x/r ≤ √x ≤ x/r + r/4, a model that keeps x's slopes, or — where more of x's range
lies below 0 than above, so that the chord's slope would carry the infeasible part's values
— by the interval [0, r] (:func:`_interval_root`); its derivative is unbounded.

Edge symbols. Registers made by :func:`new_registers` with more symbols than parameters
carry *edge symbols* besides the box's parameters (rows k ≥ p of g, radius 0 until
taken, then 1): the uncertainty r/8 of a root at an edge (:func:`_edge_root`), and the
remainder of a proper root above 5 % of its linear part's bound (beside an edge, where
the radicand varies by a large factor over the box: :func:`_remainder_symbol`), each
become a symbol of their own, so that they are counted once however often the root is
used and cancel where the values cancel (affine arithmetic's new noise symbols). The
two-parameter search takes two (on 9/B28 down to boxes of 2⁻⁸ of the sides, 79 946 →
43 989 boxes, 7 → 8 of 14 modes certified, the time about the same: a box costs twice
as much); in one parameter, where an edge is a point, a symbol saved 11 % of the boxes
on 7/B1 and 16 % on a nine-link truss but cost as much a box, so it takes none. With one
parameter the radicand's model also bounds the part of the box where the triangle can
exist (c + Σ g_k u_k + e ≥ 0, one linear inequality's hull consistency, with one
parameter or two): a contraction of the box towards its feasible side. The float program's rounding guard (a
radicand a rounding error below 0 taken as 0) is not applied: the models hold the values
of exact arithmetic. The free signs and the link steps' orientation signs are exact (±1,
or 0 for a flat triangle); the program's constants are small integers and powers of two
(exact); the known squared distances enter as models of the intervals around them (exact
where the float is).

Boxes side by side. The registers hold K boxes as K columns (c (R + 1, K), g (p, R + 1,
K), e (R + 1, K)), and each instruction runs over all columns in its innermost loops: the
instruction is decoded once for K boxes and the loops vectorise (7/B1: about 0.8 µs a box
in a batch of 32, 6.6 µs one at a time, measured). The branch-and-prune evaluates its
boxes in such rounds.

Derivatives. With them, each register also holds, for each parameter, a Taylor model of
its partial derivative over the box (forward mode on the same program: (ab)′ = a′b + ab′,
(a/b)′ = (a′ − (a/b) b′)/b, (√a)′ = a′/(2√a)), whose range is the interval Jacobian that
interval Newton and the Krawczyk test need, tight to first order in the box's width.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numba
import numpy as np

from .straight_line import (
    ADD,
    DIVIDE,
    FIRST_FAILURE,
    FLAT_ZERO,
    GUARDED_ROOT,
    MAXIMUM,
    MULTIPLY,
    NEGATE,
    SUBTRACT,
    StraightLineProgram,
)

#: Box status: every radicand certainly ≥ 0 in the box.
FEASIBLE = 0
#: Some radicand's interval contains 0: the box holds a domain edge of this branch.
EDGE = 1
#: Some radicand is certainly < 0 in the box: no configuration of this branch in it.
INFEASIBLE = 2


#: An opcode of the differentiated program only: the register is unbounded (the
#: derivative of a maximum, which no residual depends on).
UNBOUNDED = 99


@dataclass(frozen=True)
class IntervalProgram:
    """A plan's straight-line program reduced to what decides a box and differentiated:
    the instructions that the closure residuals and the radicands of the signed roots
    depend on (the failure profile, the relative radicands and the float rounding guard's
    threshold dropped), then the instructions of their partial derivatives (forward mode
    as a transformation of the program, :func:`interval_program`; the first ``values``
    rows compute the values, so that a box their models decide needs no more), over
    ``registers`` registers: the program's, then the derivatives' and the constants
    1 and 2 (``extra_constants``). ``program``: the program it is made from, with its own
    registers: a plan's float program traced again with its radicands in
    :func:`~.bilateration.small_term_radicand`'s form (its ``derived["interval source"]``),
    else the program itself. ``residual_derivatives`` (c, p): the register of each
    residual's derivative by each parameter, −1 where it is 0.

    The rows that depend on neither a parameter nor a free sign (a third of 7/B1's values,
    nearly half of the 13-link Watt–Baranov truss's: the steps built from known distances
    alone) are not in ``instructions`` but in ``instance_instructions``, run once per
    instance by :func:`instance_registers`: their models have no slopes, so they are the
    same on every box, bit for bit. ``instance_outputs``: the registers holding instance
    values (known distances, link signs, those rows' results) that ``instructions`` read."""

    instructions: np.ndarray
    values: int
    registers: int
    program: StraightLineProgram
    extra_constants: np.ndarray
    residual_derivatives: np.ndarray
    instance_instructions: np.ndarray
    instance_outputs: np.ndarray


def interval_program(program: StraightLineProgram) -> IntervalProgram:
    """The instructions of ``program`` that its residuals and signed roots need (a
    backward pass), then those of their derivatives by the parameters (a forward pass:
    (a ± b)′ = a′ ± b′, (ab)′ = a′b + ab′, (a/b)′ = (a′ − (a/b) b′)/b, (√r)′ = r′/(2√r), a
    derivative known to be 0 not computed). O(instructions × parameters), once per
    program (cached on it).

    >>> from baranov.scene import load_scene
    >>> from baranov.solvers.placement import compile_scene
    >>> from baranov.solvers.coincidence import solvable_plan
    >>> scene = load_scene("examples/7-B1.json")
    >>> program = compile_scene(scene, solvable_plan(scene)).straight_line_program()
    >>> reduced = interval_program(program)
    >>> len(program.instructions), len(reduced.instance_instructions), reduced.values, len(reduced.instructions)
    (294, 85, 118, 265)
    """
    if "interval" not in program.derived:
        source = program.derived.get("interval source")
        program.derived["interval"] = _differentiated(source() if source is not None else program)
    return program.derived["interval"]


def _differentiated(program: StraightLineProgram) -> IntervalProgram:
    """:func:`interval_program`, made."""
    needed = _needed(program)
    registers = [program.registers]
    constants: dict[float, int] = {}

    def new() -> int:
        registers[0] += 1
        return registers[0] - 1

    def constant(value: float) -> int:
        if value not in constants:
            constants[value] = new()
        return constants[value]

    out: list[tuple[int, int, int, int, int]] = []
    tail: list[tuple[int, int, int, int, int]] = []  # the derivatives, after every value

    def emit(opcode: int, a: int, b: int = -1) -> int:
        d = new()
        tail.append((opcode, d, a, b, 0))
        return d

    parameters = len(program.parameter_registers)
    derivative: list[dict[int, int]] = [{int(r): constant(1.0)} for r in program.parameter_registers]
    for row, keep in zip(program.instructions.tolist(), needed, strict=True):
        if not keep:
            continue
        opcode, d, a, b, c = row
        out.append((opcode, d, a, b, c))
        for wrt in derivative:
            value = _derivative(opcode, d, a, b, wrt, emit, constant)
            if value is not None:
                wrt[d] = value
    residual_derivatives = np.array([[wrt.get(int(r), -1) for wrt in derivative] for r in program.residual_registers],
                                    dtype=np.int64).reshape(len(program.residual_registers), parameters)
    extra = np.array(sorted((register, value) for value, register in constants.items()), dtype=float).reshape(-1, 2)
    _require_single_assignment(out + tail)
    per_box = _per_box(program, out + tail)
    instance = [row for row, box in zip(out + tail, per_box, strict=True) if not box]
    values = [row for row, box in zip(out, per_box[:len(out)], strict=True) if box]
    derivatives = [row for row, box in zip(tail, per_box[len(out):], strict=True) if box]
    written = {row[1] for row in values + derivatives}
    read = {r for _, _, a, b, _ in values + derivatives for r in (a, b) if r >= 0 and r not in written}
    varying = set(program.parameter_registers.tolist()) | set(program.sign_registers.tolist())
    constant = set(program.constant_registers.tolist()) | set(constants.values())
    return IntervalProgram(np.array(values + derivatives, dtype=np.int64).reshape(-1, 5), len(values), registers[0],
                           program, extra, residual_derivatives, np.array(instance, dtype=np.int64).reshape(-1, 5),
                           np.array(sorted(read - varying - constant), dtype=np.int64))


def _per_box(program: StraightLineProgram, rows: list[tuple[int, int, int, int, int]]) -> list[bool]:
    """Whether each row depends on a parameter or a free sign (else its result is an
    instance's, the same on every box)."""
    varying = np.zeros(max([program.registers] + [row[1] + 1 for row in rows]), dtype=bool)
    varying[program.parameter_registers] = varying[program.sign_registers] = True
    flags = []
    for _, d, a, b, _ in rows:
        varying[d] = varying[a] or (b >= 0 and varying[b])
        flags.append(bool(varying[d]))
    return flags


def _require_single_assignment(instructions: list[tuple[int, int, int, int, int]]) -> None:
    """The compiled arithmetic writes a register while it reads the operands: each
    register must be written once, by an instruction that does not read it."""
    written = [d for _, d, _, _, _ in instructions]
    if len(set(written)) != len(written) or any(d in (a, b) for _, d, a, b, _ in instructions):
        raise AssertionError("the interval program is not in single-assignment form")


def _needed(program: StraightLineProgram) -> np.ndarray:
    """Which instructions the residuals and the signed roots' radicands depend on."""
    instructions = program.instructions
    needed = np.zeros(program.registers, dtype=bool)
    needed[program.residual_registers] = True
    keep = np.zeros(len(instructions), dtype=bool)
    for index in range(len(instructions) - 1, -1, -1):
        opcode, d, a, b, _ = (int(x) for x in instructions[index])
        if opcode == FIRST_FAILURE:
            continue
        if opcode == GUARDED_ROOT:  # its radicand decides feasibility; its threshold is the float guard's
            keep[index] = needed[a] = True
            continue
        if needed[d]:
            keep[index] = True
            needed[a] = True
            if b >= 0:
                needed[b] = True
    return keep


def _derivative(opcode, d, a, b, wrt, emit, constant):
    """The register of the derivative of instruction (opcode, d, a, b) by one parameter
    (``wrt``: register → its derivative's register, absent where 0), emitting what it
    takes; None where it is 0."""
    da, db = wrt.get(a), wrt.get(b) if b >= 0 else None
    if opcode == GUARDED_ROOT:  # r′ / (2√r); b is the float guard's threshold
        return emit(DIVIDE, da, emit(MULTIPLY, constant(2.0), d)) if da is not None else None
    if opcode == FLAT_ZERO:  # a: the sign (an input); b the signed root
        return emit(FLAT_ZERO, a, db) if db is not None else None
    if da is None and db is None:
        return None
    if opcode == ADD:
        return da if db is None else db if da is None else emit(ADD, da, db)
    if opcode == SUBTRACT:
        return da if db is None else emit(NEGATE, db) if da is None else emit(SUBTRACT, da, db)
    if opcode == NEGATE:
        return emit(NEGATE, da)
    if opcode == MULTIPLY:
        first = emit(MULTIPLY, da, b) if da is not None else None
        second = emit(MULTIPLY, a, db) if db is not None else None
        return first if second is None else second if first is None else emit(ADD, first, second)
    if opcode == DIVIDE:  # (a′ − q b′) / b, q = a/b = d
        top = da if db is None else emit(SUBTRACT, da, emit(MULTIPLY, d, db)) if da is not None else \
            emit(NEGATE, emit(MULTIPLY, d, db))
        return emit(DIVIDE, top, b)
    return emit(UNBOUNDED, a)  # MAXIMUM


# --- the compiled arithmetic (numba, nopython; cached on disk) ------------------------------
#
# A model's parts live in three arrays indexed by register: centers c (R,), slopes
# g (R, p) — one column per parameter of the box — and remainders e (R,); the
# operations take register numbers, not views (the program is in SSA form: a destination
# is never an operand), which made an evaluation 3.5 times faster than views of a
# two-symbol layout on 7/B1 (7.3 → about 2 µs for its 220 value instructions). One
# register past the program's is scratch (a quotient's reciprocal).

_COMPILE = dict(cache=True, nogil=True, error_model="numpy")

#: Relative rounding slack of a model's center and slopes (each a correctly rounded sum of
#: at most two correctly rounded terms: within 2^-51.4 of the magnitudes of its terms)
#: and of the remainders' own rounding.
_SLACK = 2.0**-50
#: The first row of the scratch array that holds, for second-order models, the bounds
#: ρ_k ρ_l of the terms u_k u_l (rows before it: a product's and a sum's work).
_PRODUCTS = 5
#: An absolute slack covering underflow (at most 2^-1074 per operation).
_TINY = 1e-300
#: A proper root's remainder above this share of its linear part's bound becomes a symbol
#: of its own where one is free (:func:`_remainder_symbol`).
_SYMBOL_REMAINDER = 0.05


@numba.njit(inline="always", **_COMPILE)
def _up(x):  # pragma: no cover - compiled
    """A float above every real within a few ulps of the nonnegative ``x``."""
    return x * (1.0 + _SLACK) + _TINY


@numba.njit(inline="always", **_COMPILE)
def rounded_down(x):  # pragma: no cover - compiled
    """A float below every real within a few ulps of ``x`` (any sign)."""
    return x - (abs(x) * _SLACK + _TINY) if abs(x) < np.inf else x


@numba.njit(inline="always", **_COMPILE)
def rounded_up(x):  # pragma: no cover - compiled
    """A float above every real within a few ulps of ``x`` (any sign)."""
    return x + (abs(x) * _SLACK + _TINY) if abs(x) < np.inf else x


# The registers of K boxes side by side (one column each): c (R + 1, K), g (p, R + 1, K),
# e (R + 1, K), radius (p, K). Every operation loops over the columns innermost, so that
# one instruction is decoded once for K boxes and its loops vectorise: on 7/B1 a box
# costs about 0.8 µs in a batch of 32 against 6.6 µs one at a time (measured).


@numba.njit(inline="always", **_COMPILE)
def _linear_bound(g, r, radius, j):  # pragma: no cover - compiled
    """L = Σ|g_k| ρ_k of register ``r`` in column ``j`` (not rounded)."""
    total = 0.0
    for k in range(g.shape[0]):
        total += abs(g[k, r, j]) * radius[k, j]
    return total


@numba.njit(inline="always", **_COMPILE)
def _quadratic_bound(h, r, radius, j):  # pragma: no cover - compiled
    """Q = Σ|h_kl| ρ_k ρ_l of register ``r`` in column ``j`` (0 for first-order models;
    not rounded)."""
    total, q = 0.0, 0
    if h is None:
        return total
    for k in range(radius.shape[0]):
        for m in range(k, radius.shape[0]):
            total += abs(h[q, r, j]) * radius[k, j] * radius[m, j]
            q += 1
    return total


@numba.njit(inline="always", **_COMPILE)
def _deviation(g, h, e, r, radius, j):  # pragma: no cover - compiled
    """R = L + Q + e of register ``r`` in column ``j``, rounded up: how far its values
    lie from its center."""
    return _up(_linear_bound(g, r, radius, j) + _quadratic_bound(h, r, radius, j) + e[r, j])


@numba.njit(inline="always", **_COMPILE)
def linear_model(c, g, h, e, radius, r, j, parameters):  # pragma: no cover - compiled
    """(center, remainder) of the first-order model in the first ``parameters`` symbols
    (the box's parameters) that register ``r``'s model is over the box of column ``j``
    (their slopes unchanged): a square's term h_kk u_k², in [0, h_kk ρ_k²], moves the
    center by half its range and adds the other half to the remainder, a product's term
    h_kl u_k u_l adds its bound, and an edge symbol's term g_k u_k (k ≥ ``parameters``)
    its bound. The model itself for first-order models without edge symbols."""
    if h is None and parameters == g.shape[0]:
        return c[r, j], e[r, j]
    center, rest, q = c[r, j], e[r, j], 0
    for k in range(parameters, g.shape[0]):
        rest += abs(g[k, r, j]) * radius[k, j]
    if h is None:
        return center, _up(rest + _SLACK * (abs(center) + rest))
    for k in range(radius.shape[0]):
        for m in range(k, radius.shape[0]):
            bound = abs(h[q, r, j]) * radius[k, j] * radius[m, j]
            if k == m:
                center += 0.5 * h[q, r, j] * radius[k, j] * radius[k, j]
                rest += 0.5 * bound
            else:
                rest += bound
            q += 1
    return center, _up(rest + _SLACK * (abs(c[r, j]) + abs(center) + rest))


@numba.njit(inline="always", **_COMPILE)
def _unbounded(c, g, h, e, d, j):  # pragma: no cover - compiled
    """Register ``d`` of column ``j``: the whole line."""
    c[d, j], e[d, j] = 0.0, np.inf
    for k in range(g.shape[0]):
        g[k, d, j] = 0.0
    if h is not None:
        for q in range(h.shape[0]):
            h[q, d, j] = 0.0


@numba.njit(inline="always", **_COMPILE)
def _copy(c, g, h, e, d, a, sign, n):  # pragma: no cover - compiled
    """Register ``d`` = ``sign`` × register ``a`` (sign ±1: exact)."""
    for j in range(n):
        c[d, j], e[d, j] = sign * c[a, j], e[a, j]
    for k in range(g.shape[0]):
        for j in range(n):
            g[k, d, j] = sign * g[k, a, j]
    if h is not None:
        for q in range(h.shape[0]):
            for j in range(n):
                h[q, d, j] = sign * h[q, a, j]


@numba.njit(inline="always", **_COMPILE)
def _sum(c, g, h, e, d, a, b, sign, radius, scratch, n):  # pragma: no cover - compiled
    """Model d = a + sign × b."""
    magnitude = scratch[2]
    for j in range(n):
        magnitude[j] = abs(c[a, j]) + abs(c[b, j])
    for k in range(g.shape[0]):
        for j in range(n):
            magnitude[j] += (abs(g[k, a, j]) + abs(g[k, b, j])) * radius[k, j]
            g[k, d, j] = g[k, a, j] + sign * g[k, b, j]
    if h is not None:
        for q in range(h.shape[0]):
            for j in range(n):
                h[q, d, j] = h[q, a, j] + sign * h[q, b, j]
                magnitude[j] += (abs(h[q, a, j]) + abs(h[q, b, j])) * scratch[_PRODUCTS + q, j]
    for j in range(n):
        c[d, j], e[d, j] = c[a, j] + sign * c[b, j], _up(e[a, j] + e[b, j] + _SLACK * magnitude[j])


@numba.njit(inline="always", **_COMPILE)
def _square_terms(h, g, d, a, b, factor, j):  # pragma: no cover - compiled
    """h_d += factor × (g_a u)(g_b u), as coefficients of u_k u_l (k ≤ l)."""
    q = 0
    for k in range(g.shape[0]):
        for m in range(k, g.shape[0]):
            term = g[k, a, j] * g[k, b, j] if k == m else g[k, a, j] * g[m, b, j] + g[m, a, j] * g[k, b, j]
            h[q, d, j] += factor * term
            q += 1


@numba.njit(inline="always", **_COMPILE)
def _product(c, g, h, e, d, a, b, radius, scratch, n):  # pragma: no cover - compiled
    """Model d = a × b. With a = c_a + L_a + R_a (L_a the linear part, |L_a| ≤ Σ|g_k|ρ_k;
    R_a = Q_a + ε_a the quadratic part and the remainder): the model keeps c_a c_b +
    c_a (L_b + Q_b) + c_b (L_a + Q_a), and L_a L_b in h for second order; the remainder
    bounds c_a ε_b + c_b ε_a + L_a R_b + R_a (L_b + R_b), and L_a L_b for first order."""
    linear_a, linear_b, magnitude = scratch[0], scratch[1], scratch[2]
    for j in range(n):
        linear_a[j], linear_b[j], magnitude[j] = 0.0, 0.0, abs(c[a, j] * c[b, j])
    for k in range(g.shape[0]):
        for j in range(n):
            slope_a, slope_b = g[k, a, j], g[k, b, j]
            linear_a[j] += abs(slope_a) * radius[k, j]
            linear_b[j] += abs(slope_b) * radius[k, j]
            x, y = c[a, j] * slope_b, c[b, j] * slope_a
            magnitude[j] += (abs(x) + abs(y)) * radius[k, j]
            g[k, d, j] = x + y
    if h is None:
        for j in range(n):
            ca, cb = c[a, j], c[b, j]
            c[d, j] = ca * cb
            e[d, j] = _up(abs(ca) * e[b, j] + abs(cb) * e[a, j] + _up(linear_a[j] + e[a, j]) * _up(linear_b[j] + e[b, j])
                          + _SLACK * magnitude[j])
    else:
        _second_order_product(c, g, h, e, d, a, b, radius, scratch, n)
    # an unbounded factor (e = ∞) gives ∞ or 0 × ∞ = NaN: checked after the arithmetic,
    # in a loop of its own, so that the arithmetic's loops stay free of branches
    for j in range(n):
        if not e[d, j] < np.inf:
            _unbounded(c, g, h, e, d, j)


@numba.njit(**_COMPILE)
def _second_order_product(c, g, h, e, d, a, b, radius, scratch, n):  # pragma: no cover - compiled
    """The quadratic terms and the remainder of :func:`_product` for second-order models
    (its slopes and scratch rows 0-2 filled in). Not inlined: the first-order loops stay
    as small as they were (inlined, this code made a first-order box 30 % slower)."""
    linear_a, linear_b, magnitude = scratch[0], scratch[1], scratch[2]
    quadratic_a, quadratic_b = scratch[3], scratch[4]
    for j in range(n):
        quadratic_a[j], quadratic_b[j] = 0.0, 0.0
    q = 0
    for k in range(g.shape[0]):
        for m in range(k, g.shape[0]):
            for j in range(n):
                cross = g[k, a, j] * g[k, b, j] if k == m else g[k, a, j] * g[m, b, j] + g[m, a, j] * g[k, b, j]
                h[q, d, j] = c[a, j] * h[q, b, j] + c[b, j] * h[q, a, j] + cross
                quadratic_a[j] += abs(h[q, a, j]) * scratch[_PRODUCTS + q, j]
                quadratic_b[j] += abs(h[q, b, j]) * scratch[_PRODUCTS + q, j]
                magnitude[j] += (abs(c[a, j] * h[q, b, j]) + abs(c[b, j] * h[q, a, j]) + abs(cross)
                                 ) * scratch[_PRODUCTS + q, j]
            q += 1
    for j in range(n):
        ca, cb = c[a, j], c[b, j]
        c[d, j] = ca * cb
        rest_a, rest_b = _up(quadratic_a[j] + e[a, j]), _up(quadratic_b[j] + e[b, j])
        e[d, j] = _up(abs(ca) * e[b, j] + abs(cb) * e[a, j] + _up(linear_a[j]) * rest_b
                      + rest_a * _up(linear_b[j] + rest_b) + _SLACK * magnitude[j])


@numba.njit(**_COMPILE)
def _reciprocal(c, g, h, e, d, b, radius, n):  # pragma: no cover - compiled
    """Model d = 1/b; the whole line where b's range holds 0. With δ = b − c_b:
    1/b = 1/c − δ/c² + δ²/c³ − δ³/(c³ b), the last term bounded (second order; first
    order: δ²/(c² b) bounded)."""
    for j in range(n):
        deviation = _deviation(g, h, e, b, radius, j)
        low, high = rounded_down(c[b, j] - deviation), rounded_up(c[b, j] + deviation)
        if e[b, j] == np.inf or (low <= 0.0 <= high):
            _unbounded(c, g, h, e, d, j)
            continue
        nearest = min(abs(low), abs(high))
        center = 1.0 / c[b, j]
        square = center * center
        magnitude = abs(center)
        for k in range(g.shape[0]):
            g[k, d, j] = -g[k, b, j] * square
            magnitude += abs(g[k, d, j]) * radius[k, j]
        c[d, j] = center
        if h is None:
            e[d, j] = _up(_up(e[b, j] * square + deviation * deviation * square / nearest + _SLACK * magnitude))
        else:
            cube = square * center
            for q in range(h.shape[0]):
                h[q, d, j] = -h[q, b, j] * square
            _square_terms(h, g, d, b, b, cube, j)
            magnitude += _quadratic_bound(h, d, radius, j)
            linear = _up(_linear_bound(g, b, radius, j))
            rest = _up(_quadratic_bound(h, b, radius, j) + e[b, j])
            e[d, j] = _up(_up(e[b, j] * square + (2.0 * linear * rest + rest * rest) * abs(cube)
                              + deviation * deviation * deviation * abs(cube) / nearest) + _SLACK * magnitude)


@numba.njit(**_COMPILE)
def _root(c, g, h, e, d, a, radius, feasible, status, scratch, parameters, n):  # pragma: no cover - compiled
    """Model d = √a, and each column's status worsened by its step (module docstring);
    at an edge, the chord model (with an edge symbol of its own where one is free), and
    ``feasible`` narrowed."""
    for j in range(n):
        deviation = _deviation(g, h, e, a, radius, j)
        low, high = rounded_down(c[a, j] - deviation), rounded_up(c[a, j] + deviation)
        if high < 0.0:
            status[j] = INFEASIBLE
            _unbounded(c, g, h, e, d, j)
        elif e[a, j] == np.inf:
            status[j] = max(status[j], EDGE)
            _unbounded(c, g, h, e, d, j)
        elif low > 0.0:
            _proper_root(c, g, h, e, d, a, radius, deviation, low, j)
            if parameters < g.shape[0] and e[d, j] > _SYMBOL_REMAINDER * _linear_bound(g, d, radius, j):
                _remainder_symbol(g, h, e, d, radius, scratch, parameters, j)
        else:
            status[j] = max(status[j], EDGE)
            if feasible.shape[0] == 2 * parameters:
                _feasible_part(c, g, h, e, a, radius, feasible, parameters, j)
            r = rounded_up(np.sqrt(high))
            if deviation > r * r:  # most of the radicand's range below 0: the chord's slope spans more than [0, r]
                _interval_root(c, g, h, e, d, radius, scratch, parameters, r, j)
            else:
                _edge_root(c, g, h, e, d, a, radius, scratch, parameters, r, j)


@numba.njit(inline="always", **_COMPILE)
def _interval_root(c, g, h, e, d, radius, scratch, parameters, r, j):  # pragma: no cover - compiled
    """Model d = √a where a's range [L, U] holds 0 and r ≥ √U, by the interval [0, r]: its
    half-width an edge symbol of its own where one is free. Narrower than the chord model
    (:func:`_edge_root`, whose range is [L/r, r + r/4]) where −L > U: over a box that the
    edge crosses near its feasible corner, the chord's slope carries the radicand's values
    on the infeasible part (on 9/B28's whole box, 43 989 → 41 707 boxes)."""
    _unbounded(c, g, h, e, d, j)  # no slopes, no quadratic terms; c and e set below
    half = 0.5 * r  # exact
    rest = half
    k = _taken_symbol(h, radius, scratch, parameters, j)
    if k >= 0:
        g[k, d, j], rest = half, 0.0
    c[d, j], e[d, j] = half, _up(rest + _SLACK * r)


@numba.njit(inline="always", **_COMPILE)
def _edge_root(c, g, h, e, d, a, radius, scratch, parameters, r, j):  # pragma: no cover - compiled
    """Model d = √a where a's range [L, U] holds 0 and r ≥ √U: where the radicand x is in
    [0, r²] (the rest of the box is infeasible), x/r ≤ √x ≤ x/r + r/4 (chord and parallel
    tangent), so √x = x/r + r/8 + (r/8) ε with some ε in [−1, 1] at each point: ε is an
    *edge symbol* of its own (a row k ≥ ``parameters`` of g whose radius is still 0, then
    set to 1), so that what follows stays linear in it and its uncertainty is counted once
    however often the root is used (affine arithmetic's new noise symbol: Stolfi and de
    Figueiredo 1997); where every edge symbol is taken, r/8 goes to the remainder."""
    eighth = 0.125 * r  # exact: r/8 is r with its exponent lowered
    magnitude = abs(c[a, j]) / r + eighth
    for k in range(g.shape[0]):
        g[k, d, j] = g[k, a, j] / r
        magnitude += abs(g[k, d, j]) * radius[k, j]
    if h is not None:
        for q in range(h.shape[0]):
            h[q, d, j] = h[q, a, j] / r
        magnitude += _quadratic_bound(h, d, radius, j)
    rest = eighth
    k = _taken_symbol(h, radius, scratch, parameters, j)
    if k >= 0:  # a free edge symbol: a had no term in it
        g[k, d, j], rest = eighth, 0.0
    c[d, j], e[d, j] = c[a, j] / r + eighth, _up(e[a, j] / r + rest + _SLACK * magnitude)


@numba.njit(inline="always", **_COMPILE)
def _remainder_symbol(g, h, e, d, radius, scratch, parameters, j):  # pragma: no cover - compiled
    """Register d's remainder e made a symbol of its own, where one is free: at each point
    of the box the remainder is e ε for some ε in [−1, 1], and what follows stays linear
    in that ε (where the radicand varies by a large factor over the box, e.g. next to a
    flat triangle, √'s remainder is a large part of its range, and values that cancel in
    exact arithmetic cancel in their symbols' terms, not in their remainders: on a 9/B28
    box beside a domain edge, two values whose difference varies by 0.006 had remainders
    of 0.1 each)."""
    k = _taken_symbol(h, radius, scratch, parameters, j)
    if k >= 0:
        g[k, d, j], e[d, j] = e[d, j], 0.0


@numba.njit(inline="always", **_COMPILE)
def _taken_symbol(h, radius, scratch, parameters, j):  # pragma: no cover - compiled
    """The first free edge symbol of column ``j`` (radius 0: no register has a term in
    it), taken (radius 1, and the second-order bounds ρ_k ρ_l refreshed); −1 where every
    one is taken."""
    for k in range(parameters, radius.shape[0]):
        if radius[k, j] == 0.0:
            radius[k, j] = 1.0
            if h is not None:
                _products(radius, scratch, j)
            return k
    return -1


@numba.njit(inline="always", **_COMPILE)
def _products(radius, scratch, j):  # pragma: no cover - compiled
    """The bounds ρ_k ρ_l of the second-order terms u_k u_l (k ≤ l) of column ``j``, into
    ``scratch``'s rows from _PRODUCTS."""
    q = 0
    for k in range(radius.shape[0]):
        for m in range(k, radius.shape[0]):
            scratch[_PRODUCTS + q, j] = radius[k, j] * radius[m, j]
            q += 1


@numba.njit(inline="always", **_COMPILE)
def _feasible_part(c, g, h, e, a, radius, feasible, parameters, j):  # pragma: no cover - compiled
    """Narrow ``feasible`` (rows 2k, 2k + 1: the range of the parameter u_k, column ``j``)
    to where the radicand in register ``a`` can be ≥ 0: its first-order model
    c + Σ g_k u_k ± e is, only where g_k u_k ≥ −(c + e) − max Σ_{l≠k} g_l u_l over the
    others' ranges (the hull consistency of one linear inequality; one pass over the
    axes)."""
    center, rest = linear_model(c, g, h, e, radius, a, j, parameters)
    reach = rounded_up(center + rest)
    for k in range(parameters):
        slope = g[k, a, j]
        if slope == 0.0:
            continue
        others = 0.0
        for m in range(parameters):
            if m != k:
                low = max(feasible[2 * m, j], -radius[m, j])
                high = min(feasible[2 * m + 1, j], radius[m, j])
                others = rounded_up(others + max(g[m, a, j] * low, g[m, a, j] * high))
        bound = rounded_up(reach + others)
        if slope > 0.0:
            feasible[2 * k, j] = max(feasible[2 * k, j], rounded_down(-bound / slope))
        else:
            feasible[2 * k + 1, j] = min(feasible[2 * k + 1, j], rounded_up(-bound / slope))


@numba.njit(inline="always", **_COMPILE)
def _proper_root(c, g, h, e, d, a, radius, deviation, low, j):  # pragma: no cover - compiled
    """Model d = √a where a's range [low, ·] is above 0. With δ = a − c_a:
    √a = √c + δ/(2√c) − δ²/(2√c (√a + √c)²) (first order: the last term bounded), or
    √c + δ/(2√c) − δ²/(8 c√c) + δ³/(16 ξ^{5/2}) (second order: the last term bounded), the
    second-order form where its remainder is the smaller (away from an edge: the cubic term
    grows like 1/low^{5/2})."""
    root = np.sqrt(c[a, j])
    floor = np.sqrt(low) * (1.0 - _SLACK)
    twice = 2.0 * root
    magnitude = root
    for k in range(g.shape[0]):
        g[k, d, j] = g[k, a, j] / twice
        magnitude += abs(g[k, d, j]) * radius[k, j]
    c[d, j] = root
    first = _up(deviation * deviation / (twice * (floor + root) * (floor + root) * (1.0 - _SLACK)))
    if h is not None:
        for q in range(h.shape[0]):
            h[q, d, j] = h[q, a, j] / twice
        linear = _up(_linear_bound(g, a, radius, j))
        rest = _up(_quadratic_bound(h, a, radius, j) + e[a, j])
        eighth = 1.0 / (8.0 * c[a, j] * root) * (1.0 + 4 * _SLACK)
        second = _up(_up(2.0 * linear * rest + rest * rest) * eighth
                     + deviation * deviation * deviation / (16.0 * low * low * floor * (1.0 - 4 * _SLACK)))
        if second < first:  # the quadratic term is kept exactly: it cancels downstream
            _square_terms(h, g, d, a, a, -1.0 / (8.0 * c[a, j] * root), j)
            first = second
        magnitude += _quadratic_bound(h, d, radius, j)
    e[d, j] = _up(_up(e[a, j] / twice + first) + _SLACK * magnitude)


@numba.njit(**_COMPILE)
def _maximum(c, g, h, e, d, a, b, radius, n):  # pragma: no cover - compiled
    """Model d = max(a, b): the larger where the ranges are apart, else a constant model
    of the hull (no residual depends on it)."""
    for j in range(n):
        deviation_a, deviation_b = _deviation(g, h, e, a, radius, j), _deviation(g, h, e, b, radius, j)
        larger = -1
        if c[a, j] - deviation_a >= c[b, j] + deviation_b:
            larger = a
        elif c[b, j] - deviation_b >= c[a, j] + deviation_a:
            larger = b
        if larger >= 0:
            c[d, j], e[d, j] = c[larger, j], e[larger, j]
            for k in range(g.shape[0]):
                g[k, d, j] = g[k, larger, j]
            if h is not None:
                for q in range(h.shape[0]):
                    h[q, d, j] = h[q, larger, j]
            continue
        low = max(c[a, j] - deviation_a, c[b, j] - deviation_b)
        high = max(c[a, j] + deviation_a, c[b, j] + deviation_b)
        c[d, j], e[d, j] = 0.5 * (low + high), _up(0.5 * (high - low) + _SLACK * (abs(low) + abs(high)))
        for k in range(g.shape[0]):
            g[k, d, j] = 0.0
        if h is not None:
            for q in range(h.shape[0]):
                h[q, d, j] = 0.0


@numba.njit(**_COMPILE)
def _flat_zero(c, g, h, e, d, a, b, n):  # pragma: no cover - compiled
    """Register ``d``: 0 where the sign in ``a`` is exactly 0 (the flat triangle asked
    for), else register ``b``."""
    for j in range(n):
        flat = c[a, j] == 0.0 and e[a, j] == 0.0
        c[d, j], e[d, j] = (0.0, 0.0) if flat else (c[b, j], e[b, j])
        for k in range(g.shape[0]):
            g[k, d, j] = 0.0 if flat else g[k, b, j]
        if h is not None:
            for q in range(h.shape[0]):
                h[q, d, j] = 0.0 if flat else h[q, b, j]


@numba.njit(**_COMPILE)
def evaluate_models(instructions, c, g, h, e, radius, feasible, status, scratch, parameters, n
                    ):  # pragma: no cover - compiled
    """Run the differentiated program's ``instructions`` on the registers' models of K
    boxes side by side (``c`` (R + 1, K), ``g`` (p, R + 1, K), ``h`` (q, R + 1, K),
    ``e`` (R + 1, K): the program's R registers and a scratch one, the inputs filled in;
    q = 0 for first-order models, p(p + 1)/2 for second order; ``radius`` (p, K) the
    boxes' half-widths; ``scratch`` (5 + q, K)), over the first ``n`` columns (the boxes
    loaded: a round need not fill them all). Each column's ``status`` (K,), FEASIBLE on
    entry, is set to EDGE where a radicand's range holds 0 and INFEASIBLE where one is
    certainly below 0 (the column's later values are then meaningless). ``feasible``
    (2p, K), rows 2k and 2k + 1 the range of u_k (from ±∞), is narrowed to where every
    radicand at an edge can be ≥ 0 (an array (0, K): not asked)."""
    spare = c.shape[0] - 1
    if h is not None:  # second order: ρ_k ρ_l, a row per term u_k u_l
        for j in range(n):
            _products(radius, scratch, j)
    for index in range(instructions.shape[0]):
        opcode, d, a, b = instructions[index, 0], instructions[index, 1], instructions[index, 2], instructions[index, 3]
        if opcode == MULTIPLY:
            _product(c, g, h, e, d, a, b, radius, scratch, n)
        elif opcode == ADD:
            _sum(c, g, h, e, d, a, b, 1.0, radius, scratch, n)
        elif opcode == SUBTRACT:
            _sum(c, g, h, e, d, a, b, -1.0, radius, scratch, n)
        elif opcode == DIVIDE:
            _reciprocal(c, g, h, e, spare, b, radius, n)
            _product(c, g, h, e, d, a, spare, radius, scratch, n)
        elif opcode == NEGATE:
            _copy(c, g, h, e, d, a, -1.0, n)
        elif opcode == GUARDED_ROOT:
            _root(c, g, h, e, d, a, radius, feasible, status, scratch, parameters, n)
        elif opcode == FLAT_ZERO:  # a: the sign (exact); 0 asks for the flat triangle
            _flat_zero(c, g, h, e, d, a, b, n)
        elif opcode == MAXIMUM:
            _maximum(c, g, h, e, d, a, b, radius, n)
        elif opcode == UNBOUNDED:
            for j in range(n):
                _unbounded(c, g, h, e, d, j)


@numba.njit(**_COMPILE)
def model_range(c, g, h, e, radius, register, j):  # pragma: no cover - compiled
    """The range [low, high] of a register's model over the box of column ``j``."""
    if register < 0:
        return 0.0, 0.0
    center, rest = linear_model(c, g, h, e, radius, register, j, g.shape[0])
    deviation = _up(_linear_bound(g, register, radius, j) + rest)
    return rounded_down(center - deviation), rounded_up(center + deviation)


@numba.njit(**_COMPILE)
def new_registers(base_c, base_e, symbols, columns):  # pragma: no cover - compiled
    """The registers (c, g, e, radius, scratch) of ``columns`` boxes of one instance
    (``base_c``, ``base_e``: constants, known distances and link signs; NaN elsewhere),
    every slope 0, over ``symbols`` symbols: the box's parameters, then any edge symbols
    (:func:`_edge_root`). Once per instance: a box then sets only its parameters and
    signs (:func:`load_box`), as every other register is written by the program (in SSA
    form) before it is read. Second-order models add :func:`quadratic_terms`."""
    registers = base_c.shape[0] + 1  # and a spare one, for 1/b in a ÷ b
    c, e = np.empty((registers, columns)), np.empty((registers, columns))
    g = np.zeros((symbols, registers, columns))
    for r in range(base_c.shape[0]):  # loops: numba compiles slice assignments slowly (5 s here)
        for j in range(columns):
            c[r, j], e[r, j] = base_c[r], base_e[r]
    return c, g, e, np.zeros((symbols, columns)), np.empty((_PRODUCTS + symbols * (symbols + 1) // 2, columns))


def quadratic_terms(order: int, symbols: int, registers: int, columns: int) -> np.ndarray | None:
    """The quadratic coefficients h (q, R + 1, K) of second-order models in ``symbols``
    symbols (q = p(p + 1)/2 for p symbols, zero), or None for first order: the compiled arithmetic is specialised on it, so that
    first-order models run the first-order code alone (with the second-order code beside
    it, measured 30 % slower a box)."""
    if order == 1:
        return None
    if order != 2:
        raise ValueError(f"order {order}: Taylor models of order 1 or 2")
    return np.zeros((symbols * (symbols + 1) // 2, registers + 1, columns))


@numba.njit(**_COMPILE)
def load_box(parameter_registers, sign_registers, low, high, signs, c, g, e, radius, j):  # pragma: no cover - compiled
    """The box [low, high] (p,) and the branch ``signs`` into column ``j`` of registers
    made by :func:`new_registers`; its half-widths into ``radius``, and every edge symbol
    free (radius 0)."""
    for k in range(low.shape[0]):
        r = parameter_registers[k]
        middle = 0.5 * (low[k] + high[k])
        c[r, j], e[r, j] = middle, 0.0
        for q in range(g.shape[0]):
            g[q, r, j] = 1.0 if q == k else 0.0
        radius[k, j] = rounded_up(max(middle - low[k], high[k] - middle))
    for k in range(low.shape[0], radius.shape[0]):
        radius[k, j] = 0.0
    for k in range(sign_registers.shape[0]):
        c[sign_registers[k], j], e[sign_registers[k], j] = signs[k], 0.0


#: Boxes evaluated side by side (columns of the registers): enough for the loops to
#: vectorise, few enough for the registers of a 13-link plan to stay in cache (its
#: example: 63 ms at 64, 69-80 ms at 32, measured).
COLUMNS = 64


@numba.njit(**_COMPILE)
def _evaluate_boxes(instructions, base_c, base_e, initial, parameter_registers, sign_registers, box_lo, box_hi, signs,
                    outputs, derivatives, h, symbols):  # pragma: no cover - compiled
    """:func:`evaluate_models` on each box (rows of ``box_lo``/``box_hi``, on the branch
    of the same row of ``signs``), COLUMNS at a time: the outputs' ranges, their
    derivatives' ranges (``derivatives``: (c, p) registers), and the status (from the
    instance's, ``initial``)."""
    count, parameters = box_lo.shape
    values = np.empty((count, outputs.shape[0], 2))
    jacobians = np.zeros((count, outputs.shape[0], parameters, 2))
    status = np.empty(count, dtype=np.int64)
    c, g, e, radius, scratch = new_registers(base_c, base_e, symbols, COLUMNS)
    feasible = np.empty((0, COLUMNS))
    column_status = np.empty(COLUMNS, dtype=np.int64)
    for start in range(0, count, COLUMNS):
        width = min(COLUMNS, count - start)
        for j in range(width):
            load_box(parameter_registers, sign_registers, box_lo[start + j], box_hi[start + j], signs[start + j],
                     c, g, e, radius, j)
            column_status[j] = initial
        evaluate_models(instructions, c, g, h, e, radius, feasible, column_status, scratch, parameters, width)
        for j in range(width):
            n = start + j
            status[n] = column_status[j]
            for m in range(outputs.shape[0]):
                values[n, m, 0], values[n, m, 1] = model_range(c, g, h, e, radius, outputs[m], j)
                for k in range(parameters):
                    jacobians[n, m, k, 0], jacobians[n, m, k, 1] = model_range(c, g, h, e, radius, derivatives[m, k], j)
    return values, jacobians, status



def instance_registers(program: IntervalProgram, known_lo: np.ndarray, known_hi: np.ndarray,
                       fixed_signs: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """The registers' centers and remainders with one instance's inputs filled in: the
    program's constants and the differentiation's (exact), the known squared distances
    (their intervals ``known_lo``..``known_hi``, in ``known_pairs`` order, then those of
    the slider geometry's numbers in ``slider_constants`` order), the link
    steps' signs and the models of the rows that depend on them alone
    (``instance_instructions``); NaN elsewhere. And the status those rows leave (FEASIBLE,
    EDGE or INFEASIBLE: a triangle of known sides alone), every box's status to start from."""
    source = program.program
    center, remainder = np.full(program.registers + 1, np.nan), np.full(program.registers + 1, np.nan)
    center[source.constant_registers], remainder[source.constant_registers] = source.constant_values, 0.0
    extra = program.extra_constants[:, 0].astype(np.int64)
    center[extra], remainder[extra] = program.extra_constants[:, 1], 0.0
    known_lo, known_hi = np.asarray(known_lo, float), np.asarray(known_hi, float)
    middle = 0.5 * (known_lo + known_hi)
    inputs = np.concatenate([source.known_registers, source.slider_constant_registers])
    center[inputs] = middle
    remainder[inputs] = np.maximum(known_hi - middle, middle - known_lo) * (1 + 2.0**-49)
    center[source.fixed_sign_registers], remainder[source.fixed_sign_registers] = fixed_signs, 0.0
    status = _instance_models(program.instance_instructions, center, remainder)
    return center[:-1], remainder[:-1], status


@numba.njit(**_COMPILE)
def _instance_models(instructions, center, remainder):  # pragma: no cover - compiled
    """Run the instance rows on one column of models without slopes (the same arithmetic
    as a box's, its slopes all 0), in place; the status they leave."""
    c, e = center.reshape((-1, 1)), remainder.reshape((-1, 1))
    status = np.full(1, FEASIBLE, dtype=np.int64)
    evaluate_models(instructions, c, np.zeros((0, c.shape[0], 1)), None, e, np.zeros((0, 1)), np.empty((0, 1)), status,
                    np.empty((_PRODUCTS, 1)), 0, 1)
    return status[0]


def enclosing(values) -> tuple[np.ndarray, np.ndarray]:
    """Float intervals around exact numbers (ints, Fractions, Decimals, floats): the float
    itself where it is exact, else its two neighbours."""
    low, high = [], []
    for value in values:
        nearest = float(value)
        # floats and integers below 2^53 (a scene's whole numbers are Fractions) are exact
        # floats: no Fraction built (a solve encloses every dimension, and Fractions cost
        # 0.4 ms of a 7-link solve)
        whole = value.numerator if isinstance(value, Fraction) and value.denominator == 1 else value
        exact = isinstance(whole, float) or (isinstance(whole, int) and abs(whole) <= 2**53) or (
            Fraction(nearest) == Fraction(value))
        low.append(nearest if exact else math.nextafter(nearest, -math.inf))
        high.append(nearest if exact else math.nextafter(nearest, math.inf))
    return np.array(low), np.array(high)


def evaluate_boxes(program: IntervalProgram, known_lo: np.ndarray, known_hi: np.ndarray, fixed_signs: np.ndarray,
                   box_lo: np.ndarray, box_hi: np.ndarray, signs: np.ndarray,
                   order: int = 1, edge_symbols: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each box (rows of ``box_lo``, ``box_hi``: (N, p)) on the branch of the same row of
    ``signs`` (N, m), in Taylor models of ``order`` 1 or 2 with up to ``edge_symbols`` edge
    symbols (:func:`_edge_root`): the ranges of the closure residuals' models (N, c, 2), of their
    partial derivatives' models (N, c, p, 2) and the box's status (N,): FEASIBLE, EDGE or
    INFEASIBLE (then the ranges are meaningless). O(N × instructions), compiled."""
    source = program.program
    center, remainder, initial = instance_registers(program, known_lo, known_hi, fixed_signs)
    return _evaluate_boxes(
        program.instructions, center, remainder, initial, source.parameter_registers, source.sign_registers,
        np.ascontiguousarray(box_lo, dtype=float), np.ascontiguousarray(box_hi, dtype=float),
        np.ascontiguousarray(signs, dtype=float), source.residual_registers, program.residual_derivatives,
        quadratic_terms(order, len(source.parameter_registers) + edge_symbols, len(center), COLUMNS),
        len(source.parameter_registers) + edge_symbols)
