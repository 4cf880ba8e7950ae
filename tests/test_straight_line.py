"""The bilateration kernel traced into a straight-line program and run compiled
(closure/straight_line.py, issue 21) gives the numpy evaluation's values bit for bit:
closure residuals, first failing steps, their relative radicands and the free-sign
margins, and the joints' positions (NaNs alike, whatever their sign bit), on every branch or
point by point, at random parameter values (inside and
outside the feasible domain, 0, negative) and with signs 0 (triangles taken flat)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import baranov.closure.straight_line as straight_line
from baranov.closure.evaluate import _ProgramPlacement, sign_branches
from baranov.closure.straight_line import KernelChoiceError, Recorder, trace_plan
from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.placement import compile_scene

ROOT = Path(__file__).resolve().parents[1]
#: The examples and every saved regression without sliders (flat triangles, coincident
#: joints, narrow windows: the cases the searches were fixed for).
SCENES = sorted(path for folder in (ROOT / "examples", ROOT / "tests" / "regressions")
                for path in folder.glob("*.json") if "slider" not in path.name)
TRUSSES = [(links, index) for links in (3, 5, 7, 9) for index in range(len(baranov_trusses(links)))]
TRUSSES += [(11, index) for index in range(0, len(baranov_trusses(11)), 37)]


def _numpy_profile(compiled, values, signs, paired):
    """What CompiledSystem.profile computed before the straight-line program: the kernel
    in numpy arrays."""
    placement = compiled._placed(values, signs, profile=True, paired=paired)
    return (compiled._closure_residuals(placement), placement.failures, placement.radicands,
            placement.stacked_margins())


def _bits(array) -> bytes:
    """The array's bytes, every NaN made one NaN (a NaN's sign bit differs between the
    numpy and the compiled arithmetic on some NaN propagations, and nothing reads it)."""
    array = np.ascontiguousarray(array).copy()
    if array.dtype.kind == "f":
        array[np.isnan(array)] = np.nan
    return array.dtype.str.encode() + repr(array.shape).encode() + array.tobytes()


def _assert_same(compiled, values, signs):
    for paired in (False, True):
        chosen = signs[np.arange(len(values)) % len(signs)] if paired else signs
        traced = compiled.program_profile(values, chosen, paired)
        expected = _numpy_profile(compiled, values, chosen, paired)
        for part, mine, numpy_value in zip(traced._fields, traced, expected, strict=True):
            assert _bits(mine) == _bits(numpy_value), f"{part} differs (paired={paired})"
    # the joints' positions (read-back of the modes: CompiledSystem.paired_matrices)
    chosen = signs[np.arange(len(values)) % len(signs)]
    *_, points = compiled._run_program(values, chosen, paired=True, points=True)
    expected = compiled._placed(values, chosen, profile=False, paired=True).matrices()
    program = compiled.straight_line_program()
    assert sorted(program.joints) == sorted(expected)
    for n, joint in enumerate(program.joints):
        assert _bits(points[:, n]) == _bits(expected[joint][0]), f"{joint}'s position differs"


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(TRUSSES), st.integers(0, 2**32 - 1))
def test_traced_program_equals_the_numpy_kernel_bit_for_bit(truss, seed):
    links, index = truss
    rng = np.random.default_rng(seed)
    chain = baranov_trusses(links)[index]
    scene = scene_of(chain, generic_integer_configuration(chain, rng))
    compiled = compile_scene(scene, solvable_plan(scene))
    size = max(compiled.known.values())
    count = len(compiled.parameters)
    values = np.concatenate([rng.uniform(0, 4 * size, (60, count)), rng.uniform(-size, 0, (4, count)),
                             np.zeros((2, count)), np.full((2, count), 1e12)])
    branches = sign_branches(len(compiled.free_triangles))
    flat = rng.integers(-1, 2, (3, branches.shape[1])).astype(float)  # a sign 0: the triangle taken flat
    _assert_same(compiled, values, np.concatenate([branches, flat]))


@pytest.mark.parametrize("path", SCENES, ids=lambda path: path.stem)
def test_traced_program_on_the_examples_and_regressions(path):
    try:
        scene = load_scene(path)
    except ValueError:
        pytest.skip("not a scene (a robot or a chain that moves)")
    try:
        compiled = compile_scene(scene, solvable_plan(scene))
    except ValueError:
        pytest.skip("no bilateration plan")
    if compiled.sliders:
        pytest.skip("slider chains are evaluated in numpy complex numbers")
    rng = np.random.default_rng(1)
    size = max(compiled.known.values())
    values = rng.uniform(0, 4 * size, (300, len(compiled.parameters)))
    _assert_same(compiled, values, sign_branches(len(compiled.free_triangles)))


def test_one_program_serves_every_instance_of_a_plan():
    chain = baranov_trusses(7)[0]
    scenes = [scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(seed))) for seed in (1, 2)]
    plans = [solvable_plan(scene) for scene in scenes]
    assert plans[0] == plans[1]
    programs = [trace_plan(plan, tuple(compile_scene(scene, plan).known), tuple(compile_scene(scene, plan).fixed_signs))
                for scene, plan in zip(scenes, plans, strict=True)]
    assert np.array_equal(programs[0].instructions, programs[1].instructions)


def test_traced_arithmetic_records_what_python_evaluates():
    recorder = Recorder()
    x = recorder.input()
    y = 2 * x + 1
    assert len(recorder.instructions) == 2 and y.register == recorder.registers - 1
    with pytest.raises(ValueError, match="power 3"):
        x ** 3


def test_no_points_give_empty_shapes():
    chain = baranov_trusses(7)[0]
    scene = scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(3)))
    compiled = compile_scene(scene, solvable_plan(scene))
    branches = sign_branches(len(compiled.free_triangles))
    _assert_same(compiled, np.zeros((0, 1)), branches)
    assert compiled.paired_residuals(np.zeros((0, 1)), branches[:0]).shape == (0, 1)


def _compiled(compiled, values, branches) -> bool:
    """Whether the evaluation ran the compiled program."""
    return isinstance(compiled._evaluate(values, branches), _ProgramPlacement)


def test_the_kernel_in_use_follows_baranov_kernel(monkeypatch):
    """``auto`` switches once the process has spent SWITCH_AFTER_SECONDS in numpy
    evaluations (or has loaded the compiled loop); ``numpy`` and ``compiled`` force one."""
    chain = baranov_trusses(7)[0]
    scene = scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(4)))
    compiled = compile_scene(scene, solvable_plan(scene))
    branches = sign_branches(len(compiled.free_triangles))
    values = np.linspace(1, 50, 7)[:, None]
    monkeypatch.setattr(straight_line, "_compiled_loop", None)
    monkeypatch.setattr(straight_line, "_numpy_seconds", 0.0)
    monkeypatch.setenv("BARANOV_KERNEL", "auto")
    assert not _compiled(compiled, values, branches)
    compiled.residuals(values, branches)  # a numpy evaluation, counted
    assert 0 < straight_line._numpy_seconds < straight_line.SWITCH_AFTER_SECONDS
    monkeypatch.setattr(straight_line, "_numpy_seconds", straight_line.SWITCH_AFTER_SECONDS)
    assert _compiled(compiled, values, branches)
    monkeypatch.setenv("BARANOV_KERNEL", "numpy")
    assert not _compiled(compiled, values, branches)
    monkeypatch.setenv("BARANOV_KERNEL", "compiled")
    monkeypatch.setattr(straight_line, "_numpy_seconds", 0.0)
    assert _compiled(compiled, values, branches)
    monkeypatch.setenv("BARANOV_KERNEL", "fast")
    with pytest.raises(KernelChoiceError, match="BARANOV_KERNEL='fast'"):
        compiled.residuals(values, branches)


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([t for t in TRUSSES if t[0] == 7]), st.integers(0, 2**32 - 1))
def test_rows_of_many_instances_run_as_each_instance_alone(truss, seed):
    """run_program with each row's own known distances and link signs (a batch of
    instances of one plan) gives each row what a run on its instance alone gives, bit
    for bit."""
    links, index = truss
    rng = np.random.default_rng(seed)
    chain = baranov_trusses(links)[index]
    scenes = [scene_of(chain, generic_integer_configuration(chain, rng)) for _ in range(3)]
    plan = solvable_plan(scenes[0])
    systems = [compile_scene(scene, plan) for scene in scenes]
    program = systems[0].straight_line_program()
    branches = sign_branches(len(plan.free_sign_triangles))
    owner = np.arange(12) % len(scenes)
    values = rng.uniform(0, 4 * max(systems[0].known.values()), (12, plan.number_of_parameters))
    signs = branches[np.arange(12) % len(branches)].astype(float)
    known = np.array([[system.known[pair] for pair in program.known_pairs] for system in systems])[owner]
    fixed = np.array([[system.fixed_signs[t] for t in program.fixed_triangles] for system in systems])[owner]
    together = straight_line.run_program(program, known, fixed.reshape(12, -1), values, signs, paired=True,
                                         points=True)
    for row in range(12):
        alone = systems[owner[row]]._run_program(values[row:row + 1], signs[row:row + 1], paired=True, points=True)
        for part, mine, expected in zip(("residuals", "failures", "radicands", "margins", "points"), together, alone,
                                        strict=True):
            assert _bits(mine[row:row + 1]) == _bits(expected), part


def _slider_scene(seed: int):
    """A random slider chain of a random 7- or 9-link truss (a random admissible slider
    set, random axes; rational or float dimensions), with its plan, or None where no plan
    with parameters suits it."""
    from baranov.scene import scene_from_dict
    from baranov.scene.slider_instances import random_slider_set, slider_instance_dict
    from baranov.solvers.coincidence import NoPlanError

    rng = np.random.default_rng(seed)
    trusses = baranov_trusses(7 if seed % 2 else 9)
    truss = trusses[rng.integers(len(trusses))]
    scene = scene_from_dict(slider_instance_dict(truss, random_slider_set(truss, rng), rng, rational=bool(seed % 3)))
    try:
        plan = solvable_plan(scene)
    except NoPlanError:
        return None
    return (scene, plan, rng) if plan.number_of_parameters else None


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 10**6))
def test_slider_plans_traced_give_the_numpy_kernels_values(seed):
    """A plan with slider joints traced into a program (closure/traced_sliders.py: its
    constructions on traced complex numbers, each slider's geometry an input) gives the
    numpy evaluation's residuals, first failing steps, radicands and margins: the failing
    steps and NaNs alike, the values to rounding (a complex quotient is formed as a product
    by the conjugate, where numpy scales it). One program serves every instance of the
    plan's slider layout."""
    case = _slider_scene(seed)
    if case is None:
        return
    scene, plan, rng = case
    compiled = compile_scene(scene, plan)
    branches = sign_branches(len(plan.free_sign_triangles))
    values = rng.uniform(0.0, 1.0, (40, plan.number_of_parameters)) ** 2 * 4 * max(scene.known.values(), default=1)
    traced = compiled.program_profile(values, branches)
    expected = _numpy_profile(compiled, values, branches, False)
    for part, mine, numpy_value in zip(traced._fields, traced, expected, strict=True):
        mine, numpy_value = np.asarray(mine, float), np.asarray(numpy_value, float)
        assert mine.shape == numpy_value.shape, part
        assert (np.isnan(mine) == np.isnan(numpy_value)).all(), f"{part}: NaNs differ"
        defined = ~np.isnan(mine)
        np.testing.assert_allclose(mine[defined], numpy_value[defined], rtol=1e-9, atol=1e-9, err_msg=part)
    assert compiled.straight_line_program().slider_constants
