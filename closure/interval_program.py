"""A plan's straight-line program run over a box of parameter values, with its
derivatives, in first-order Taylor models (issue 56).

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

Square roots of a step. A radicand whose range is certainly negative makes the box
*infeasible* on that branch (:data:`INFEASIBLE`). A range that holds 0 is a domain edge in
the box (:data:`EDGE`): the root, which exists only on part of the box, is enclosed by the
constant model of [0, √U], and its derivative is unbounded. (A symbol of its own for such
a root, to keep what follows linear in it, saved 11 % of the boxes on 7/B1 and 16 % on a
nine-link truss but cost as much in a third symbol on every operation: the same times.)
With one
parameter the radicand's model also bounds the part of the box where the triangle can
exist (c + g u + e ≥ 0): a contraction of the box towards its feasible side. The float program's rounding guard (a
radicand a rounding error below 0 taken as 0) is not applied: the models hold the values
of exact arithmetic. The free signs and the link steps' orientation signs are exact (±1,
or 0 for a flat triangle); the program's constants are small integers and powers of two
(exact); the known squared distances enter as models of the intervals around them (exact
where the float is).

Derivatives. With them, each register also holds, for each parameter, a Taylor model of
its partial derivative over the box (forward mode on the same program: (ab)′ = a′b + ab′,
(a/b)′ = (a′ − (a/b) b′)/b, (√a)′ = a′/(2√a)), whose range is the interval Jacobian that
interval Newton and the Krawczyk test need, tight to first order in the box's width.
"""

from __future__ import annotations

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
    1 and 2 (``extra_constants``). ``residual_derivatives`` (c, p): the register of each
    residual's derivative by each parameter, −1 where it is 0."""

    instructions: np.ndarray
    values: int
    registers: int
    program: StraightLineProgram
    extra_constants: np.ndarray
    residual_derivatives: np.ndarray


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
    >>> len(program.instructions), len(interval_program(program).instructions)
    (276, 383)
    """
    if "interval" not in program.derived:
        program.derived["interval"] = _differentiated(program)
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
    return IntervalProgram(np.array(out + tail, dtype=np.int64).reshape(-1, 5), len(out), registers[0], program,
                           extra, residual_derivatives)


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

_COMPILE = dict(cache=True, nogil=True, error_model="numpy")

#: Relative rounding slack of a model's center and slopes (each a correctly rounded sum of
#: at most two correctly rounded terms: within 2^-51.4 of the magnitudes of its terms)
#: and of the remainders' own rounding.
_SLACK = 2.0**-50
#: An absolute slack covering underflow (at most 2^-1074 per operation).
_TINY = 1e-300
#: Symbols of a model: the parameters (at most two).
SYMBOLS = 2


@numba.njit(**_COMPILE)
def _up(x):  # pragma: no cover - compiled
    """A float above every real within a few ulps of the nonnegative ``x``."""
    return x * (1.0 + _SLACK) + _TINY


@numba.njit(**_COMPILE)
def rounded_down(x):  # pragma: no cover - compiled
    """A float below every real within a few ulps of ``x`` (any sign)."""
    return x - (abs(x) * _SLACK + _TINY) if abs(x) < np.inf else x


@numba.njit(**_COMPILE)
def rounded_up(x):  # pragma: no cover - compiled
    """A float above every real within a few ulps of ``x`` (any sign)."""
    return x + (abs(x) * _SLACK + _TINY) if abs(x) < np.inf else x


@numba.njit(**_COMPILE)
def _deviation(g, e, radius):  # pragma: no cover - compiled
    """R = Σ|g_k| ρ_k + e, rounded up: how far the model's values lie from its center."""
    total = e
    for k in range(SYMBOLS):
        total += abs(g[k]) * radius[k]
    return _up(total)


@numba.njit(**_COMPILE)
def _sum(c, g, e, d, a, b, sign, radius):  # pragma: no cover - compiled
    """Model d = a + sign × b."""
    magnitude = abs(c[a]) + abs(c[b])
    remainder = e[a] + e[b]
    c_d = c[a] + sign * c[b]
    for k in range(SYMBOLS):
        magnitude += (abs(g[a, k]) + abs(g[b, k])) * radius[k]
        g[d, k] = g[a, k] + sign * g[b, k]
    c[d], e[d] = c_d, _up(remainder + _SLACK * magnitude)


@numba.njit(**_COMPILE)
def _product(ca, ga, ea, cb, gb, eb, radius, g_out):  # pragma: no cover - compiled
    """The model a × b from the parts of a and b: (c, e), slopes written to ``g_out``
    (which may be ``ga`` or ``gb``: each slope is read before it is written)."""
    if ea == np.inf or eb == np.inf:
        for k in range(SYMBOLS):
            g_out[k] = 0.0
        return 0.0, np.inf
    deviation_a, deviation_b = _deviation(ga, ea, radius), _deviation(gb, eb, radius)
    c = ca * cb
    magnitude = abs(c)
    for k in range(SYMBOLS):
        x, y = ca * gb[k], cb * ga[k]
        magnitude += (abs(x) + abs(y)) * radius[k]
        g_out[k] = x + y
    e = abs(ca) * eb + abs(cb) * ea + deviation_a * deviation_b + _SLACK * magnitude
    return c, _up(e)


@numba.njit(**_COMPILE)
def _reciprocal(cb, gb, eb, radius, g_out):  # pragma: no cover - compiled
    """The model 1/b: (c, e), slopes to ``g_out``; e = ∞ where b's range holds 0."""
    deviation = _deviation(gb, eb, radius)
    low, high = rounded_down(cb - deviation), rounded_up(cb + deviation)
    if eb == np.inf or (low <= 0.0 <= high):
        for k in range(SYMBOLS):
            g_out[k] = 0.0
        return 0.0, np.inf
    nearest = min(abs(low), abs(high))
    c = 1.0 / cb
    square = c * c
    magnitude = abs(c)
    for k in range(SYMBOLS):
        g_out[k] = -gb[k] * square
        magnitude += abs(g_out[k]) * radius[k]
    e = eb * square + deviation * deviation * square / nearest + _SLACK * magnitude
    return c, _up(_up(e))


@numba.njit(**_COMPILE)
def _root(c, g, e, d, a, radius, feasible):  # pragma: no cover - compiled
    """Model d = √a and the status of its step; at an edge, the constant model of
    [0, √U], and ``feasible`` narrowed (module docstring)."""
    deviation = _deviation(g[a], e[a], radius)
    low, high = rounded_down(c[a] - deviation), rounded_up(c[a] + deviation)
    if high < 0.0:
        return INFEASIBLE
    for k in range(SYMBOLS):
        g[d, k] = 0.0
    if e[a] == np.inf:
        c[d], e[d] = 0.0, np.inf
        return EDGE
    if low > 0.0:
        root = np.sqrt(c[a])
        floor = np.sqrt(low) * (1.0 - _SLACK)
        twice = 2.0 * root
        magnitude = root
        for k in range(SYMBOLS):
            g[d, k] = g[a, k] / twice
            magnitude += abs(g[d, k]) * radius[k]
        quadratic = deviation * deviation / (twice * (floor + root) * (floor + root) * (1.0 - _SLACK))
        c[d], e[d] = root, _up(_up(e[a] / twice + quadratic) + _SLACK * magnitude)
        return FEASIBLE
    if feasible.shape[0] == 2 and g[a, 1] == 0.0 and g[a, 0] != 0.0:  # one parameter
        reach = rounded_up(c[a] + e[a])  # c + g u + e ≥ 0 for some u
        if g[a, 0] > 0.0:
            feasible[0] = max(feasible[0], rounded_down(-reach / g[a, 0]))
        else:
            feasible[1] = min(feasible[1], rounded_up(-reach / g[a, 0]))
    top = rounded_up(np.sqrt(high))
    c[d], e[d] = 0.5 * top, _up(0.5 * top)
    return EDGE


@numba.njit(**_COMPILE)
def evaluate_models(instructions, c, g, e, radius, feasible):  # pragma: no cover - compiled
    """Run the differentiated program's ``instructions`` on the registers' models (``c``
    (R,), ``g`` (R, SYMBOLS), ``e`` (R,)), the inputs filled in; ``radius`` (SYMBOLS,) the
    box's half-widths. Returns the box's status (FEASIBLE,
    EDGE, or INFEASIBLE at the first radicand certainly below 0). With one parameter,
    ``feasible`` (2,) is narrowed to the range of u_0 where every radicand at an edge can
    be ≥ 0 (an empty array: not asked)."""
    status = FEASIBLE
    scratch, other = np.empty(SYMBOLS), np.empty(SYMBOLS)
    for index in range(instructions.shape[0]):
        opcode, d, a, b = instructions[index, 0], instructions[index, 1], instructions[index, 2], instructions[index, 3]
        if opcode == ADD:
            _sum(c, g, e, d, a, b, 1.0, radius)
        elif opcode == SUBTRACT:
            _sum(c, g, e, d, a, b, -1.0, radius)
        elif opcode == MULTIPLY:
            c[d], e[d] = _product(c[a], g[a], e[a], c[b], g[b], e[b], radius, g[d])
        elif opcode == DIVIDE:
            cr, er = _reciprocal(c[b], g[b], e[b], radius, scratch)
            c[d], e[d] = _product(c[a], g[a], e[a], cr, scratch, er, radius, other)
            for k in range(SYMBOLS):
                g[d, k] = other[k]
        elif opcode == NEGATE:
            c[d], e[d] = -c[a], e[a]
            for k in range(SYMBOLS):
                g[d, k] = -g[a, k]
        elif opcode == GUARDED_ROOT:
            step = _root(c, g, e, d, a, radius, feasible)
            if step == INFEASIBLE:
                return INFEASIBLE
            if step == EDGE:
                status = EDGE
        elif opcode == FLAT_ZERO:  # a: the sign (exact); 0 asks for the flat triangle
            if c[a] == 0.0 and e[a] == 0.0:
                c[d], e[d] = 0.0, 0.0
                for k in range(SYMBOLS):
                    g[d, k] = 0.0
            else:
                c[d], e[d] = c[b], e[b]
                for k in range(SYMBOLS):
                    g[d, k] = g[b, k]
        elif opcode == MAXIMUM:  # not on a residual's path: selected, or a constant model of the hull
            deviation_a, deviation_b = _deviation(g[a], e[a], radius), _deviation(g[b], e[b], radius)
            if c[a] - deviation_a >= c[b] + deviation_b or c[b] - deviation_b >= c[a] + deviation_a:
                chosen = a if c[a] - deviation_a >= c[b] + deviation_b else b
                c[d], e[d] = c[chosen], e[chosen]
                for k in range(SYMBOLS):
                    g[d, k] = g[chosen, k]
            else:
                low = max(c[a] - deviation_a, c[b] - deviation_b)
                high = max(c[a] + deviation_a, c[b] + deviation_b)
                c[d], e[d] = 0.5 * (low + high), _up(0.5 * (high - low) + _SLACK * (abs(low) + abs(high)))
                for k in range(SYMBOLS):
                    g[d, k] = 0.0
        elif opcode == UNBOUNDED:
            c[d], e[d] = 0.0, np.inf
            for k in range(SYMBOLS):
                g[d, k] = 0.0
    return status


@numba.njit(**_COMPILE)
def model_range(c, g, e, radius, register):  # pragma: no cover - compiled
    """The range [low, high] of a register's model over the box."""
    if register < 0:
        return 0.0, 0.0
    deviation = _deviation(g[register], e[register], radius)
    return rounded_down(c[register] - deviation), rounded_up(c[register] + deviation)


@numba.njit(**_COMPILE)
def load_box(base_c, base_e, parameter_registers, sign_registers, low, high, signs, c, g, e, radius
             ):  # pragma: no cover - compiled
    """The registers' models for one instance (``base_c``, ``base_e``: constants, known
    distances and link signs; NaN elsewhere) on the box [low, high] (p,) and the branch
    ``signs``; ``radius`` set to the box's half-widths."""
    for r in range(c.shape[0]):  # loops: numba compiles slice assignments slowly (5 s here)
        c[r], e[r] = base_c[r], base_e[r]
        for k in range(SYMBOLS):
            g[r, k] = 0.0
    for k in range(SYMBOLS):
        radius[k] = 0.0
    for k in range(low.shape[0]):
        r = parameter_registers[k]
        middle = 0.5 * (low[k] + high[k])
        c[r], e[r] = middle, 0.0
        g[r, k] = 1.0
        radius[k] = rounded_up(max(middle - low[k], high[k] - middle))
    for k in range(sign_registers.shape[0]):
        c[sign_registers[k]], e[sign_registers[k]] = signs[k], 0.0


@numba.njit(**_COMPILE)
def _evaluate_boxes(instructions, base_c, base_e, parameter_registers, sign_registers, box_lo, box_hi, signs,
                    outputs, derivatives):  # pragma: no cover - compiled
    """:func:`evaluate_models` on each box (rows of ``box_lo``/``box_hi``, on the branch
    of the same row of ``signs``): the outputs' ranges, their derivatives' ranges
    (``derivatives``: (c, p) registers), and the status."""
    count, parameters = box_lo.shape
    registers = base_c.shape[0]
    values = np.empty((count, outputs.shape[0], 2))
    jacobians = np.zeros((count, outputs.shape[0], parameters, 2))
    status = np.empty(count, dtype=np.int64)
    c, e, g = np.empty(registers), np.empty(registers), np.zeros((registers, SYMBOLS))
    radius, feasible = np.zeros(SYMBOLS), np.empty(0)
    for n in range(count):
        load_box(base_c, base_e, parameter_registers, sign_registers, box_lo[n], box_hi[n], signs[n], c, g, e, radius)
        status[n] = evaluate_models(instructions, c, g, e, radius, feasible)
        for m in range(outputs.shape[0]):
            values[n, m, 0], values[n, m, 1] = model_range(c, g, e, radius, outputs[m])
            for k in range(parameters):
                jacobians[n, m, k, 0], jacobians[n, m, k, 1] = model_range(c, g, e, radius, derivatives[m, k])
    return values, jacobians, status


def instance_registers(program: IntervalProgram, known_lo: np.ndarray, known_hi: np.ndarray,
                       fixed_signs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The registers' centers and remainders with one instance's inputs filled in: the
    program's constants and the differentiation's (exact), the known squared distances
    (their intervals ``known_lo``..``known_hi``, in ``known_pairs`` order) and the link
    steps' signs; NaN elsewhere."""
    source = program.program
    center, remainder = np.full(program.registers, np.nan), np.full(program.registers, np.nan)
    center[source.constant_registers], remainder[source.constant_registers] = source.constant_values, 0.0
    extra = program.extra_constants[:, 0].astype(np.int64)
    center[extra], remainder[extra] = program.extra_constants[:, 1], 0.0
    known_lo, known_hi = np.asarray(known_lo, float), np.asarray(known_hi, float)
    middle = 0.5 * (known_lo + known_hi)
    center[source.known_registers] = middle
    remainder[source.known_registers] = np.maximum(known_hi - middle, middle - known_lo) * (1 + 2.0**-49)
    center[source.fixed_sign_registers], remainder[source.fixed_sign_registers] = fixed_signs, 0.0
    return center, remainder


def enclosing(values) -> tuple[np.ndarray, np.ndarray]:
    """Float intervals around exact numbers (ints, Fractions, Decimals, floats): the float
    itself where it is exact, else its two neighbours."""
    low, high = [], []
    for value in values:
        nearest = float(value)
        exact = isinstance(value, float) or Fraction(nearest) == Fraction(value)
        low.append(nearest if exact else float(np.nextafter(nearest, -np.inf)))
        high.append(nearest if exact else float(np.nextafter(nearest, np.inf)))
    return np.array(low), np.array(high)


def evaluate_boxes(program: IntervalProgram, known_lo: np.ndarray, known_hi: np.ndarray, fixed_signs: np.ndarray,
                   box_lo: np.ndarray, box_hi: np.ndarray, signs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each box (rows of ``box_lo``, ``box_hi``: (N, p)) on the branch of the same row of
    ``signs`` (N, m): the ranges of the closure residuals' models (N, c, 2), of their
    partial derivatives' models (N, c, p, 2) and the box's status (N,): FEASIBLE, EDGE or
    INFEASIBLE (then the ranges are meaningless). O(N × instructions), compiled."""
    source = program.program
    center, remainder = instance_registers(program, known_lo, known_hi, fixed_signs)
    return _evaluate_boxes(
        program.instructions, center, remainder, source.parameter_registers, source.sign_registers,
        np.ascontiguousarray(box_lo, dtype=float), np.ascontiguousarray(box_hi, dtype=float),
        np.ascontiguousarray(signs, dtype=float), source.residual_registers, program.residual_derivatives)
