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
Plans with slider joints (complex arithmetic, ``closure/sliders.py``) are not traced.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from .bilateration import RADICAND_NOISE, dehomogenised, place_joints

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

    def _binary(self, opcode: int, first, second) -> Traced:
        return self.recorder.emit(opcode, self.recorder.operand(first), self.recorder.operand(second))

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
    and its relative radicand (``FIRST_FAILURE``)."""

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


def trace_plan(plan, known_pairs: tuple[frozenset, ...], fixed_triangles: tuple) -> StraightLineProgram:
    """The straight-line program of :meth:`CompiledSystem.profile <.evaluate.CompiledSystem.profile>`
    for ``plan`` (no slider joints), with the squared distances of ``known_pairs`` and the
    orientation signs of the link steps ``fixed_triangles`` as inputs, so that one program
    serves every instance of the plan. O(steps) instructions."""
    recorder = Recorder()
    inputs = {pair: recorder.input() for pair in known_pairs}
    parameters = [recorder.input() for _ in plan.parameters]
    fixed = {triangle: recorder.input() for triangle in fixed_triangles}
    free_steps = [index for index, step in enumerate(plan.steps) if step.free_sign]
    signs = {index: recorder.input() for index in free_steps}
    parameter_index = {frozenset(pair): n for n, pair in enumerate(plan.parameters)}
    margins: list[Traced] = []
    relative: list = []

    def known(u: str, v: str):
        pair = frozenset((u, v))
        if pair in inputs:
            return inputs[pair], 1
        if pair in parameter_index:
            return parameters[parameter_index[pair]], 1
        return None

    def root(index, step, sides, radicand):
        largest = traced_maximum(traced_maximum(sides[0], sides[1]), sides[2])
        relative[:] = [radicand / largest ** 2]
        noise = -RADICAND_NOISE * largest ** 2
        sign = signs[index] if step.free_sign else fixed[step.triangle]
        guarded = recorder.emit(GUARDED_ROOT, recorder.operand(radicand), recorder.operand(noise))
        signed = sign * guarded
        if step.free_sign:
            margins.append(relative[0])
        # a free sign 0 asks for the triangle taken flat; a link step's sign is ±1
        return recorder.emit(FLAT_ZERO, sign.register, signed.register)

    def after_step(index, step, point):
        recorder.emit(FIRST_FAILURE, recorder.operand(point[0] + point[1]), recorder.operand(relative[0]), index)
        relative.clear()
        return True

    points, _, distance = place_joints(plan, known, root, reduced_point=dehomogenised, after_step=after_step)
    residuals = []
    for u, v in plan.closure_pairs:
        target = inputs[frozenset((u, v))]
        residuals.append(recorder.operand((distance(u, v, computed=True)[0] - target) / target))
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
        steps=len(plan.steps))


#: Points per block of the compiled loop: the registers of a block stay in cache.
BLOCK = 256


def _run(instructions, registers, constant_registers, constant_values, input_registers, inputs,
         sign_registers, signs, paired, output_registers, steps):  # pragma: no cover - compiled by numba
    """The compiled loop of :func:`run_program` (numba, nopython): the program over every
    point, block by block, instruction by instruction."""
    points = inputs.shape[0] if paired else inputs.shape[0] * signs.shape[0]
    values = inputs.shape[0]
    outputs = np.empty((points, output_registers.shape[0]))
    failures = np.full(points, steps, dtype=np.int64)
    radicands = np.full(points, np.nan)
    memory = np.empty((registers, BLOCK))
    for start in range(0, points, BLOCK):
        size = min(BLOCK, points - start)
        for n in range(constant_registers.shape[0]):
            memory[constant_registers[n], :size] = constant_values[n]
        for i in range(size):
            point = start + i
            row = point if paired else point % values
            branch = point if paired else point // values
            for n in range(input_registers.shape[0]):
                memory[input_registers[n], i] = inputs[row, n]
            for n in range(sign_registers.shape[0]):
                memory[sign_registers[n], i] = signs[branch, n]
        for instruction in range(instructions.shape[0]):
            opcode, d, a = instructions[instruction, 0], instructions[instruction, 1], instructions[instruction, 2]
            b, c = instructions[instruction, 3], instructions[instruction, 4]
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
            elif opcode == FIRST_FAILURE:
                for i in range(size):
                    if failures[start + i] == steps and not np.isfinite(memory[a, i]):
                        failures[start + i] = c
                        radicands[start + i] = memory[b, i]
        for n in range(output_registers.shape[0]):
            for i in range(size):
                outputs[start + i, n] = memory[output_registers[n], i]
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
                signs: np.ndarray, paired: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Run ``program`` on one instance (``known``: the squared distances of
    ``program.known_pairs``; ``fixed_signs``: the signs of ``program.fixed_triangles``)
    at ``parameters`` (N, p) on the branches ``signs`` (B, m): every branch at every
    value (B·N points, branch-major), or with ``paired`` point n on branch n. Returns the
    closure residuals (points, c), the first failing steps (points,), their relative
    radicands (points,) and the free-sign steps' relative radicands (points, free).
    O(points × instructions), compiled (numba, on first use; cached on disk)."""
    global _compiled_loop
    if _compiled_loop is None:
        import numba

        _compiled_loop = numba.njit(cache=True, nogil=True, error_model="numpy")(_run)  # x/0: inf, NaN
    constant_registers = np.concatenate([program.constant_registers, program.known_registers,
                                         program.fixed_sign_registers])
    constant_values = np.concatenate([program.constant_values, np.asarray(known, dtype=float),
                                      np.asarray(fixed_signs, dtype=float)])
    outputs = np.concatenate([program.residual_registers, program.margin_registers])
    values, failures, radicands = _compiled_loop(
        program.instructions, program.registers, constant_registers, constant_values, program.parameter_registers,
        np.ascontiguousarray(parameters, dtype=float), program.sign_registers,
        np.ascontiguousarray(signs, dtype=float), paired, outputs, program.steps)
    closures = len(program.residual_registers)
    return values[:, :closures], failures, radicands, values[:, closures:]
