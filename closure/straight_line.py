"""The bilateration kernel traced once per plan into a straight-line program, run compiled.

The numeric backend evaluates a plan's closure conditions hundreds of times per solve,
mostly on a few points at a time (the lock-step rounds of ``solvers/numeric``), where the
numpy arithmetic of :func:`~.bilateration.place_joints` costs its Python and per-array
overhead, about 0.3 ms an evaluation, whatever the number of points (issue 21). Here the
kernel runs once with *traced* values (:class:`Traced`): every sum, product, quotient and
signed root it forms becomes one instruction of a :class:`StraightLineProgram`, whose
inputs are the parameters, the known squared distances and the orientation signs. The
program is then run over all points by one compiled loop (:func:`run_program`, numba),
instruction after instruction over blocks of points: the same arithmetic, in the same
order, as the numpy evaluation (``closure/evaluate.py``), so the values are equal bit for
bit (``tests/test_straight_line.py``), at a cost of a few microseconds for a few points.

It is the kernel's fifth arithmetic, not a second copy of its formulas: the formulas are
those of :mod:`.bilateration`, run once on :class:`Traced` values. The two primitives a
float arithmetic supplies itself — the signed square root of a radicand with its rounding
guard (:func:`~.bilateration.signed_root`) and the first failing step — are instructions.
Plans with slider joints are traced too: their constructions (``closure/sliders.py``)
run on traced complex numbers (:mod:`.traced_sliders`), each slider's geometry an input.
"""

from __future__ import annotations

import operator
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .bilateration import (
    RADICAND_NOISE,
    dehomogenised,
    factored_radicand,
    parameter_triangles,
    place_joints,
    triangle_radicand,
)

#: NaN as one object, so that the recorder keeps one register for it (NaN ≠ NaN).
NOT_A_NUMBER = float("nan")

# Opcodes. Binary: registers[d] = registers[a] (op) registers[b].
ADD, SUBTRACT, MULTIPLY, DIVIDE, MAXIMUM, NEGATE, GUARDED_ROOT, FLAT_ZERO, FIRST_FAILURE = range(9)


@dataclass
class Recorder:
    """The program being traced: instructions (opcode, d, a, b, c) and the registers that
    hold constants."""

    instructions: list[tuple[int, int, int, int, int]] = field(default_factory=list)
    constants: dict[tuple[float, bool], int] = field(default_factory=dict)
    registers: int = 0

    def new_register(self) -> int:
        self.registers += 1
        return self.registers - 1

    def input(self) -> Traced:
        """A register filled before the run (a parameter, distance or sign)."""
        return Traced(self, self.new_register())

    def constant(self, value: float) -> Traced:
        """The register holding ``value`` (one per distinct value, bits included: −0.0 is
        not 0.0)."""
        key = (float(value), np.signbit(float(value)))
        if key not in self.constants:
            self.constants[key] = self.new_register()
        return Traced(self, self.constants[key])

    def emit(self, opcode: int, a: int, b: int = -1, c: int = -1) -> Traced:
        register = self.new_register()
        self.instructions.append((opcode, register, a, b, c))
        return Traced(self, register)

    def operand(self, value) -> int:
        return value.register if isinstance(value, Traced) else self.constant(value).register


class Traced:
    """A value of the traced arithmetic: the register an instruction writes. Sums,
    differences, products and quotients with other traced values or Python numbers
    record an instruction in the order Python evaluates them, as numpy would compute
    them."""

    __slots__ = ("recorder", "register")

    def __init__(self, recorder: Recorder, register: int):
        self.recorder, self.register = recorder, register

    def _binary(self, opcode: int, first, second):
        if isinstance(first, complex | TracedComplex) or isinstance(second, complex | TracedComplex):
            # a complex operand (a slider's construction): the real promoted, as numpy promotes a float array
            return _COMPLEX_OPERATIONS[opcode](_promoted(first), _promoted(second))
        return self.recorder.emit(opcode, self.recorder.operand(first), self.recorder.operand(second))

    # a real as a complex number, for the slider constructions (closure/sliders.py)
    def conjugate(self) -> Traced:
        return self

    @property
    def real(self) -> Traced:
        return self

    @property
    def imag(self) -> float:
        return 0.0

    def __add__(self, other):
        return self._binary(ADD, self, other)

    def __radd__(self, other):
        return self._binary(ADD, other, self)

    def __sub__(self, other):
        return self._binary(SUBTRACT, self, other)

    def __rsub__(self, other):
        return self._binary(SUBTRACT, other, self)

    def __mul__(self, other):
        return self._binary(MULTIPLY, self, other)

    def __rmul__(self, other):
        return self._binary(MULTIPLY, other, self)

    def __truediv__(self, other):
        return self._binary(DIVIDE, self, other)

    def __rtruediv__(self, other):
        return self._binary(DIVIDE, other, self)

    def __neg__(self):
        return self.recorder.emit(NEGATE, self.register)

    def __pow__(self, exponent):
        if exponent != 2:
            raise ValueError(f"traced power {exponent}: only squares occur in the kernel")
        return self * self  # numpy's square of a float array is x·x


def _parts(value) -> tuple[Any, Any]:
    """(real, imaginary) of a traced or plain number, the imaginary part of a real 0.0."""
    if isinstance(value, TracedComplex):
        return value.real, value.imag
    if isinstance(value, complex):
        return value.real, value.imag
    return value, 0.0


class TracedComplex:
    """A complex number of the traced arithmetic: real and imaginary parts, each a traced
    real or a Python float."""

    __slots__ = ("real", "imag")

    def __init__(self, real, imag):
        self.real, self.imag = real, imag

    def conjugate(self) -> TracedComplex:
        return TracedComplex(self.real, -self.imag)

    def __neg__(self) -> TracedComplex:
        return TracedComplex(-self.real, -self.imag)

    def __add__(self, other) -> TracedComplex:
        (a, b), (c, d) = _parts(self), _parts(other)
        return TracedComplex(a + c, b + d)

    def __radd__(self, other) -> TracedComplex:
        (a, b), (c, d) = _parts(other), _parts(self)
        return TracedComplex(a + c, b + d)

    def __sub__(self, other) -> TracedComplex:
        (a, b), (c, d) = _parts(self), _parts(other)
        return TracedComplex(a - c, b - d)

    def __rsub__(self, other) -> TracedComplex:
        (a, b), (c, d) = _parts(other), _parts(self)
        return TracedComplex(a - c, b - d)

    def __mul__(self, other) -> TracedComplex:
        return _product(_parts(self), _parts(other))

    def __rmul__(self, other) -> TracedComplex:
        return _product(_parts(other), _parts(self))

    def __truediv__(self, other) -> TracedComplex:
        return _quotient(_parts(self), other)

    def __rtruediv__(self, other) -> TracedComplex:
        return _quotient(_parts(other), self)


def _product(first, second) -> TracedComplex:
    (a, b), (c, d) = first, second
    return TracedComplex(a * c - b * d, a * d + b * c)


def _quotient(numerator, denominator) -> TracedComplex:
    """(a + ib)/(c + id) = (a + ib)(c − id)/(c² + d²); by a real, each part divided."""
    a, b = numerator
    if not isinstance(denominator, TracedComplex | complex):
        return TracedComplex(a / denominator, b / denominator)
    c, d = _parts(denominator)
    modulus = c * c + d * d
    return TracedComplex((a * c + b * d) / modulus, (b * c - a * d) / modulus)


def _promoted(value):
    """A traced real as a traced complex number with imaginary part 0.0; others as they are."""
    return TracedComplex(value, 0.0) if isinstance(value, Traced) else value


#: The traced complex arithmetic of each binary opcode.
_COMPLEX_OPERATIONS = {ADD: operator.add, SUBTRACT: operator.sub, MULTIPLY: operator.mul, DIVIDE: operator.truediv}


def traced_maximum(first, second):
    """np.maximum of traced values or numbers (NaN propagates)."""
    for value in (first, second):
        if isinstance(value, Traced):
            return value._binary(MAXIMUM, first, second)
    return np.maximum(first, second)


@dataclass(frozen=True)
class StraightLineProgram:
    """A plan's closure residuals and failure profile as instructions over registers.

    ``instructions`` has rows (opcode, d, a, b, c); the input registers are
    ``parameter_registers`` (one per parameter), ``known_registers`` (one per known
    squared distance, in ``known_pairs`` order) and ``sign_registers`` (one per free-sign
    step); ``fixed_sign_registers`` hold the link steps' orientation signs (in
    ``fixed_triangles`` order). Outputs: ``residual_registers`` (one per closure pair),
    ``margin_registers`` (the free-sign steps' relative radicands), the first failing step
    and its relative radicand (``FIRST_FAILURE``), and ``point_registers`` (J, 2): the
    coordinates of each of ``joints`` in the plan's frame (M_k = x + i y, thesis §2.2)."""

    instructions: np.ndarray
    registers: int
    constant_registers: np.ndarray
    constant_values: np.ndarray
    parameter_registers: np.ndarray
    known_pairs: tuple[frozenset, ...]
    known_registers: np.ndarray
    fixed_triangles: tuple
    fixed_sign_registers: np.ndarray
    sign_registers: np.ndarray
    residual_registers: np.ndarray
    margin_registers: np.ndarray
    steps: int
    joints: tuple[str, ...] = ()
    point_registers: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    #: With slider joints: each input of their geometry (:mod:`.traced_sliders`), and its register.
    slider_constants: tuple = ()
    slider_constant_registers: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    #: The layouts of :func:`program_layout` made so far, by branch set (None: paired).
    layouts: dict = field(default_factory=dict, compare=False, repr=False)
    #: Forms derived from the program once (the interval program of
    #: :func:`~.interval_program.interval_program`), by name.
    derived: dict = field(default_factory=dict, compare=False, repr=False)


def trace_plan(plan, known_pairs: tuple[frozenset, ...], fixed_triangles: tuple,
               sliders: Mapping | None = None, radicand: Callable = triangle_radicand) -> StraightLineProgram:
    """The straight-line program of :meth:`CompiledSystem.profile <.evaluate.CompiledSystem.profile>`
    for ``plan``, with the squared distances of ``known_pairs``, the orientation signs of
    the link steps ``fixed_triangles`` and, with slider joints (``sliders``: joint →
    :class:`~.sliders.SliderGeometry`, whose numbers are read only for their layout), each
    slider's geometry as inputs, so that one program serves every instance of the plan
    (with the parameters as :class:`~.evaluate.CompiledSystem` maps them: a slider's t,
    not its searched value). ``radicand``: the form of the steps' triangle radicands
    (:func:`~.bilateration.place_joints`'s; default :func:`~.bilateration.triangle_radicand`,
    the float kernels'; the interval program's source takes
    :func:`~.bilateration.small_term_radicand`), but for the triangles that bound a
    parameter (:func:`~.bilateration.factored_radicand`). O(steps) instructions."""
    recorder = Recorder()
    inputs = {pair: recorder.input() for pair in known_pairs}
    parameters = [recorder.input() for _ in plan.parameters]
    fixed = {triangle: recorder.input() for triangle in fixed_triangles}
    free_steps = [index for index, step in enumerate(plan.steps) if step.free_sign]
    signs = {index: recorder.input() for index in free_steps}
    parameter_index = {frozenset(pair): n for n, pair in enumerate(plan.parameters)}
    margins: list[Traced] = []
    relative: list = []
    # a slider's steps take no triangle, and its parameter may be a t, not a distance
    factored = {} if sliders else parameter_triangles(plan, inputs)

    def input_root(value):
        return recorder.emit(GUARDED_ROOT, recorder.operand(value), recorder.operand(0.0))

    def known(u: str, v: str):
        pair = frozenset((u, v))
        if pair in inputs:
            return inputs[pair], 1
        if pair in parameter_index:
            return parameters[parameter_index[pair]], 1
        return None

    def root(index, step, sides, area16):
        if index in factored:
            area16 = factored_radicand(sides, factored[index], input_root)
        largest = traced_maximum(traced_maximum(sides[0], sides[1]), sides[2])
        relative[:] = [area16 / largest ** 2]
        noise = -RADICAND_NOISE * largest ** 2
        sign = signs[index] if step.free_sign else fixed[step.triangle]
        guarded = recorder.emit(GUARDED_ROOT, recorder.operand(area16), recorder.operand(noise))
        signed = sign * guarded
        if step.free_sign:
            margins.append(relative[0])
        # a free sign 0 asks for the triangle taken flat; a link step's sign is ±1
        return recorder.emit(FLAT_ZERO, sign.register, signed.register)

    def after_step(index, step, point):
        # a slider's link step takes no root (no radicand), and a free sign that a slider
        # construction does not use (two lines meet once) has margin 1, as in numpy's kernel
        radicand = relative[0] if relative else NOT_A_NUMBER
        recorder.emit(FIRST_FAILURE, recorder.operand(point[0] + point[1]), recorder.operand(radicand), index)
        if step.free_sign and len(margins) == free_steps.index(index):
            margins.append(recorder.constant(1.0))
        relative.clear()
        return True

    hooks = None
    if sliders:
        from .traced_sliders import traced_slider_placement

        hooks = traced_slider_placement(recorder, plan, sliders, lambda u, v: known(u, v)[0]
                                        if frozenset((u, v)) in parameter_index else None, root)
    points, (reference, _), distance = place_joints(
        plan, known, root, reduced_point=dehomogenised, after_step=after_step,
        slider_step=hooks.slider_step if hooks else None, slider_frame=hooks.slider_frame if hooks else None,
        radicand=radicand)
    residuals = []
    for u, v in plan.closure_pairs:
        if hooks and (u in sliders or v in sliders):
            residuals.append(recorder.operand(hooks.closure(u, v, points, reference)))
            continue
        target = inputs[frozenset((u, v))]
        residuals.append(recorder.operand((distance(u, v, computed=True)[0] - target) / target))
    joints = tuple(sorted(points))  # before the constants are listed: a reference joint's are constants
    point_registers = [[recorder.operand(points[joint][0]), recorder.operand(points[joint][1])] for joint in joints]
    constants = sorted(recorder.constants.items(), key=lambda item: item[1])
    return StraightLineProgram(
        instructions=np.array(recorder.instructions, dtype=np.int64).reshape(-1, 5),
        registers=recorder.registers,
        constant_registers=np.array([register for _, register in constants], dtype=np.int64),
        constant_values=np.array([value for (value, _), _ in constants], dtype=float),
        parameter_registers=np.array([p.register for p in parameters], dtype=np.int64),
        known_pairs=tuple(known_pairs), known_registers=np.array([inputs[p].register for p in known_pairs], dtype=np.int64),
        fixed_triangles=tuple(fixed_triangles),
        fixed_sign_registers=np.array([fixed[t].register for t in fixed_triangles], dtype=np.int64),
        sign_registers=np.array([signs[i].register for i in free_steps], dtype=np.int64),
        residual_registers=np.array(residuals, dtype=np.int64),
        margin_registers=np.array([m.register for m in margins], dtype=np.int64),
        steps=len(plan.steps), joints=joints, point_registers=np.array(point_registers, dtype=np.int64).reshape(-1, 2),
        slider_constants=tuple(path for path, _ in hooks.inputs) if hooks else (),
        slider_constant_registers=np.array([r.register for _, r in hooks.inputs] if hooks else [], dtype=np.int64))


#: Values per block of the compiled loop, at most: the slots of a block stay in cache.
BLOCK = 256
#: Bytes of slots a block may take (:func:`run_program`).
BLOCK_BYTES = 1 << 20


@dataclass(frozen=True)
class Layout:
    """A program's instructions over *slots*, for a set of *lanes* evaluated side by side
    at every row of values (:func:`program_layout`). In the paired layout there is one
    lane, and each row holds its parameters and its signs. In the layout of a branch set,
    each branch is a lane, and a register that depends on k of the free signs has one
    slot per distinct choice of those k signs among the branches. The branches share the
    plan's steps up to their first free sign, so on the examples this is 6–32 % of the
    instructions one run per branch executes (7/B1 24 %, 9/B28 27 %, 13-link Watt–Baranov
    6 %).

    ``operations`` has rows (opcode, d, a, b, c) over slots (FIRST_FAILURE: d is the lane);
    ``row_slots`` are filled from each row's inputs, ``constant_slots`` with
    ``constant_values`` (the branch sets' signs), ``instance_slots`` with the instance's
    constants (the program's constants, known distances, link steps' signs, in
    :func:`run_program`'s order); ``output_slots`` (lanes, outputs)."""

    operations: np.ndarray
    slots: int
    row_slots: np.ndarray
    constant_slots: np.ndarray
    constant_values: np.ndarray
    instance_slots: np.ndarray
    output_slots: np.ndarray


def program_layout(program: StraightLineProgram, signs: np.ndarray | None) -> Layout:
    """The :class:`Layout` of ``program`` with every branch of ``signs`` (B, m) a lane, or
    paired (``signs`` None: one lane, the signs are row inputs). Made once per program and
    branch set. O(instructions × B)."""
    key = None if signs is None else (signs.shape, signs.tobytes())
    if key not in program.layouts:
        if len(program.layouts) > 64:  # branch sets of one plan are few; a bound all the same
            program.layouts.clear()
        program.layouts[key] = _paired_layout(program) if signs is None else _branch_layout(program, signs)
    return program.layouts[key]


def _instance_registers(program: StraightLineProgram) -> np.ndarray:
    return np.concatenate([program.constant_registers, program.known_registers, program.fixed_sign_registers,
                           program.slider_constant_registers])


def _outputs(program: StraightLineProgram) -> np.ndarray:
    return np.concatenate([program.residual_registers, program.margin_registers, program.point_registers.reshape(-1)])


def _paired_layout(program: StraightLineProgram) -> Layout:
    operations = program.instructions.copy()
    operations[operations[:, 0] == FIRST_FAILURE, 1] = 0  # one lane
    empty = np.zeros(0, dtype=np.int64)
    return Layout(operations, program.registers, np.concatenate([program.parameter_registers, program.sign_registers]),
                  empty, np.zeros(0), _instance_registers(program), _outputs(program)[None, :])


def _branch_layout(program: StraightLineProgram, signs: np.ndarray) -> Layout:
    """Each register's dependence on the free signs (a bit mask), its slots (one per
    distinct choice of those signs among the branches), and each operation's operands
    read from the slot of a branch of its class."""
    masks = np.zeros(program.registers, dtype=np.int64)
    masks[program.sign_registers] = 1 << np.arange(len(program.sign_registers))
    for _, d, a, b, _ in program.instructions.tolist():
        masks[d] = masks[a] | (masks[b] if b >= 0 else 0)
    # mask → (a branch of each class, in class order; the class of each branch)
    classes: dict[int, tuple[list[int], np.ndarray]] = {}
    for mask in set(masks.tolist()):
        columns = [k for k in range(signs.shape[1]) if mask >> k & 1]
        _, first, inverse = np.unique(signs[:, columns], axis=0, return_index=True, return_inverse=True)
        classes[mask] = (first.tolist(), inverse.reshape(-1))
    counts = np.array([len(classes[mask][0]) for mask in masks.tolist()], dtype=np.int64)
    base = np.concatenate([[0], np.cumsum(counts)[:-1]])

    def slot(register: int, branch: int) -> int:
        return int(base[register] + classes[int(masks[register])][1][branch])

    operations = []
    for opcode, d, a, b, c in program.instructions.tolist():
        if opcode == FIRST_FAILURE:  # per lane: the failing step is a branch's
            operations += [(opcode, lane, slot(a, lane), slot(b, lane), c) for lane in range(len(signs))]
            continue
        operations += [(opcode, int(base[d]) + k, slot(a, branch), slot(b, branch) if b >= 0 else -1, c)
                       for k, branch in enumerate(classes[int(masks[d])][0])]
    sign_slots, sign_values = [], []
    for column, register in enumerate(program.sign_registers.tolist()):
        for branch in classes[int(masks[register])][0]:
            sign_slots.append(slot(register, branch))
            sign_values.append(signs[branch, column])
    outputs = _outputs(program)
    return Layout(np.array(operations, dtype=np.int64).reshape(-1, 5), int(counts.sum()),
                  base[program.parameter_registers], np.array(sign_slots, dtype=np.int64),
                  np.array(sign_values, dtype=float), base[_instance_registers(program)],
                  np.array([[slot(r, lane) for r in outputs.tolist()] for lane in range(len(signs))],
                           dtype=np.int64).reshape(len(signs), len(outputs)))


def _run(operations, slots, constant_slots, constant_values, row_slots, rows, output_slots, steps,
         block):  # pragma: no cover - compiled by numba
    """The compiled loop of :func:`run_program` (numba, nopython): the operations over
    every row, block by block, operation by operation, every lane at once."""
    count, lanes = rows.shape[0], output_slots.shape[0]
    outputs = np.empty((lanes, count, output_slots.shape[1]))
    failures = np.full((lanes, count), steps, dtype=np.int64)
    radicands = np.full((lanes, count), np.nan)
    memory = np.empty((slots, block))
    for start in range(0, count, block):
        size = min(block, count - start)
        for n in range(constant_slots.shape[0]):
            memory[constant_slots[n], :size] = constant_values[n]
        for n in range(row_slots.shape[0]):
            for i in range(size):
                memory[row_slots[n], i] = rows[start + i, n]
        for operation in range(operations.shape[0]):
            opcode, d, a = operations[operation, 0], operations[operation, 1], operations[operation, 2]
            b, c = operations[operation, 3], operations[operation, 4]
            if opcode == ADD:
                for i in range(size):
                    memory[d, i] = memory[a, i] + memory[b, i]
            elif opcode == SUBTRACT:
                for i in range(size):
                    memory[d, i] = memory[a, i] - memory[b, i]
            elif opcode == MULTIPLY:
                for i in range(size):
                    memory[d, i] = memory[a, i] * memory[b, i]
            elif opcode == DIVIDE:
                for i in range(size):
                    memory[d, i] = memory[a, i] / memory[b, i]
            elif opcode == MAXIMUM:  # numpy's: the first if it is NaN or not smaller
                for i in range(size):
                    x, y = memory[a, i], memory[b, i]
                    memory[d, i] = x if (x >= y or x != x) else y
            elif opcode == NEGATE:
                for i in range(size):
                    memory[d, i] = -memory[a, i]
            elif opcode == GUARDED_ROOT:  # √max(r, 0) where r ≥ noise, else NaN (signed_root)
                for i in range(size):
                    r = memory[a, i]
                    memory[d, i] = np.sqrt(r if r >= 0.0 else 0.0) if r >= memory[b, i] else np.nan
            elif opcode == FLAT_ZERO:
                for i in range(size):
                    memory[d, i] = 0.0 if memory[a, i] == 0.0 else memory[b, i]
            elif opcode == FIRST_FAILURE:  # d: the lane
                for i in range(size):
                    if failures[d, start + i] == steps and not np.isfinite(memory[a, i]):
                        failures[d, start + i] = c
                        radicands[d, start + i] = memory[b, i]
        for lane in range(lanes):
            for n in range(output_slots.shape[1]):
                for i in range(size):
                    outputs[lane, start + i, n] = memory[output_slots[lane, n], i]
    return outputs, failures, radicands


_compiled_loop = None

#: Seconds of numpy evaluation after which a process switches to the compiled kernel
#: (``BARANOV_KERNEL=auto``, the default). Loading numba and the compiled loop costs
#: about 0.5 s (measured: the import 0.25–0.37 s, the first call 0.24 s from numba's disk
#: cache), which a one-off solve of a 7-link truss (20 ms) never pays back: that one stays
#: in numpy, while a sweep, a batch or a coupling-2 solve switches within its first half
#: second and then spends at most twice what the better kernel alone would have.
SWITCH_AFTER_SECONDS = 0.5

_numpy_seconds = 0.0


def count_numpy_seconds(seconds: float) -> None:
    """Add ``seconds`` of evaluation in numpy arrays to this process's count."""
    global _numpy_seconds
    _numpy_seconds += seconds


def compiled_kernel_in_use() -> bool:
    """Whether evaluations run the compiled program: ``BARANOV_KERNEL=compiled`` always,
    ``numpy`` never, ``auto`` (default) once this process has spent
    :data:`SWITCH_AFTER_SECONDS` in numpy evaluations. Either gives the same values."""
    choice = os.environ.get("BARANOV_KERNEL", "auto")
    if choice not in ("auto", "compiled", "numpy"):
        raise KernelChoiceError(f"BARANOV_KERNEL={choice!r}: 'auto', 'compiled' or 'numpy'")
    if choice == "auto":
        return _compiled_loop is not None or _numpy_seconds >= SWITCH_AFTER_SECONDS
    return choice == "compiled"


class KernelChoiceError(ValueError):
    """An unknown ``BARANOV_KERNEL`` value."""


def run_program(program: StraightLineProgram, known: np.ndarray, fixed_signs: np.ndarray, parameters: np.ndarray,
                signs: np.ndarray, paired: bool = False, points: bool = False,
                slider_values=()) -> tuple[np.ndarray, ...]:
    """Run ``program`` on one instance (``known``: the squared distances of
    ``program.known_pairs``; ``fixed_signs``: the signs of ``program.fixed_triangles``)
    at ``parameters`` (N, p) on the branches ``signs`` (B, m): every branch at every
    value (B·N points, branch-major; the branches' common steps evaluated once,
    :class:`Layout`), or with ``paired`` point n on branch n. Returns the closure
    residuals (points, c), the first failing steps (points,), their relative radicands
    (points,) and the free-sign steps' relative radicands (points, free); with ``points``
    also each joint's position M_k = x + i y in the plan's frame (points, J: complex, in
    ``program.joints`` order). With ``paired``, ``known`` (N, k) and ``fixed_signs``
    (N, f) may give each point its own instance (many instances of one plan at once; not
    for slider chains). ``slider_values``: the instance's slider geometry in the order of
    ``program.slider_constants`` (:func:`~.traced_sliders.slider_constant_values`).
    O(points × instructions), compiled (numba, on first use; cached on disk)."""
    global _compiled_loop
    if _compiled_loop is None:
        import numba

        _compiled_loop = numba.njit(cache=True, nogil=True, error_model="numpy")(_run)  # x/0: inf, NaN
    parameters = np.ascontiguousarray(parameters, dtype=float)
    signs = np.ascontiguousarray(signs, dtype=float)
    layout = program_layout(program, None if paired else signs)
    rows = np.concatenate([parameters, signs if signs.ndim == 2 else signs[:, None]], axis=1) if paired else parameters
    known, fixed_signs = np.asarray(known, dtype=float), np.asarray(fixed_signs, dtype=float)
    instance_slots, row_slots = layout.instance_slots, layout.row_slots
    if paired and known.ndim == 2:  # each row its own instance: its known distances and link signs are row inputs
        if len(program.slider_constants):
            raise ValueError("run_program: instances row by row are not available for slider chains")
        constants = len(program.constant_values)
        rows = np.concatenate([rows, known, fixed_signs.reshape(len(rows), -1)], axis=1)
        instance_slots, row_slots = instance_slots[:constants], np.concatenate([row_slots, instance_slots[constants:]])
        instance = program.constant_values
    else:
        instance = np.concatenate([program.constant_values, known, fixed_signs, np.asarray(slider_values, float)])
    values, failures, radicands = _compiled_loop(
        layout.operations, layout.slots, np.concatenate([instance_slots, layout.constant_slots]),
        np.concatenate([instance, layout.constant_values]), row_slots, np.ascontiguousarray(rows), layout.output_slots,
        program.steps, max(1, min(BLOCK, BLOCK_BYTES // (8 * layout.slots), len(rows))))
    values, failures, radicands = values.reshape(-1, values.shape[-1]), failures.reshape(-1), radicands.reshape(-1)
    closures, margins = len(program.residual_registers), len(program.residual_registers) + len(program.margin_registers)
    profile = values[:, :closures], failures, radicands, values[:, closures:margins]
    if not points:
        return profile
    with np.errstate(invalid="ignore"):  # x + i y as numpy's kernel forms it (an unplaced joint: NaN or ∞)
        return (*profile, values[:, margins::2] + 1j * values[:, margins + 1::2])
