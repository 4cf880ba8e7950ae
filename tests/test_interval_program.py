"""The plan's straight-line program on intervals (closure/interval_program.py, issue 56):
at every point of a box the exact value of each closure residual and of its partial
derivatives lies in the computed intervals, in first- and second-order models;
a box called infeasible holds no point where the branch's triangles exist. The oracle is
the same program run on flint's arb balls at 256 bits, with forward-mode derivatives, at
points of random boxes of random instances of every truss to nine links (coupling 1 and
2)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from flint import arb, ctx
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from baranov.closure import interval_program as models
from baranov.closure.evaluate import sign_branches
from baranov.closure.interval_program import (
    FEASIBLE,
    INFEASIBLE,
    enclosing,
    evaluate_boxes,
    interval_program,
)
from baranov.closure.straight_line import (
    ADD,
    DIVIDE,
    FIRST_FAILURE,
    FLAT_ZERO,
    GUARDED_ROOT,
    MAXIMUM,
    MULTIPLY,
    NEGATE,
    SUBTRACT,
)
from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.placement import compile_scene

ROOT = Path(__file__).resolve().parents[1]
TRUSSES = [(links, index) for links in (5, 7, 9) for index in range(len(baranov_trusses(links)))]


def _arb_program(reduced, known, fixed_signs, point, signs, registers=None):
    """(feasible, residuals, derivatives): the plan's program (all of it, not the reduced
    and differentiated one) at ``point`` in arb balls with dual numbers (value,
    gradient); feasible False where a radicand is certainly negative, None where one
    holds 0. ``registers``: a dict that receives every register's value."""
    program = reduced.program
    p = len(point)
    value: dict[int, arb] = {}
    gradient: dict[int, list[arb]] = {}
    zero = [arb(0)] * p
    for register, constant in zip(program.constant_registers, program.constant_values, strict=True):
        value[int(register)], gradient[int(register)] = arb(float(constant)), zero
    for register, number in zip(program.known_registers, known, strict=True):
        value[int(register)], gradient[int(register)] = arb(number.numerator) / number.denominator, zero
    for register, sign in zip(program.fixed_sign_registers, fixed_signs, strict=True):
        value[int(register)], gradient[int(register)] = arb(float(sign)), zero
    for k, register in enumerate(program.parameter_registers):
        value[int(register)] = arb(float(point[k]))
        gradient[int(register)] = [arb(1) if j == k else arb(0) for j in range(p)]
    for register, sign in zip(program.sign_registers, signs, strict=True):
        value[int(register)], gradient[int(register)] = arb(float(sign)), zero
    feasible = True
    for opcode, d, a, b, _ in program.instructions.tolist():
        if opcode == FIRST_FAILURE:
            continue
        x, dx = value[a], gradient[a]
        y, dy = (value[b], gradient[b]) if b in value else (None, None)  # a root's b: the float guard's
        if opcode == ADD:
            value[d], gradient[d] = x + y, [u + v for u, v in zip(dx, dy, strict=True)]
        elif opcode == SUBTRACT:
            value[d], gradient[d] = x - y, [u - v for u, v in zip(dx, dy, strict=True)]
        elif opcode == MULTIPLY:
            value[d], gradient[d] = x * y, [u * y + x * v for u, v in zip(dx, dy, strict=True)]
        elif opcode == DIVIDE:
            q = x / y
            value[d], gradient[d] = q, [(u - q * v) / y for u, v in zip(dx, dy, strict=True)]
        elif opcode == MAXIMUM:
            value[d], gradient[d] = (x, dx) if x.mid() >= y.mid() else (y, dy)
        elif opcode == NEGATE:
            value[d], gradient[d] = -x, [-u for u in dx]
        elif opcode == GUARDED_ROOT:
            if x < 0:
                return False, None, None
            if not x > 0:
                feasible = None
                x = x.union(arb(0)).intersection(arb(0).union(x.upper()))
            root = x.sqrt()
            value[d], gradient[d] = root, [u / (2 * root) for u in dx]
        elif opcode == FLAT_ZERO:
            value[d], gradient[d] = (arb(0), zero) if x == 0 else (y, dy)
    outputs = [int(r) for r in program.residual_registers]
    if registers is not None:
        registers.update(value)
    return feasible, [value[r] for r in outputs], [gradient[r] for r in outputs]


def _instance(truss, seed):
    """A random integer instance: (rng, compiled system, program, known distances, link
    steps' signs, the parameters at the generating configuration)."""
    links, index = truss
    rng = np.random.default_rng(seed)
    chain = baranov_trusses(links)[index]
    coordinates = generic_integer_configuration(chain, rng)
    scene = scene_of(chain, coordinates)
    plan = solvable_plan(scene)
    compiled = compile_scene(scene, plan)
    program = compiled.straight_line_program()
    known = [scene.known[pair] for pair in program.known_pairs]
    fixed = np.array([compiled.fixed_signs[t] for t in program.fixed_triangles], float)
    generating = np.array([float((coordinates[u][0] - coordinates[v][0]) ** 2 + (coordinates[u][1] - coordinates[v][1]) ** 2)
                           for u, v in plan.parameters])
    return rng, compiled, program, known, fixed, generating


def _example(name: str):
    """(scene, compiled system, interval program, known distances' enclosures, link
    steps' signs) of examples/``name``."""
    scene = load_scene(ROOT / "examples" / name)
    compiled = compile_scene(scene, solvable_plan(scene))
    program = compiled.straight_line_program()
    known = enclosing([scene.known[pair] for pair in program.known_pairs])
    fixed = np.array([compiled.fixed_signs[t] for t in program.fixed_triangles], float)
    return scene, compiled, interval_program(program), known, fixed


def _contains(interval, ball) -> bool:
    return float(interval[0]) <= float(ball.lower()) and float(ball.upper()) <= float(interval[1])


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(TRUSSES), st.integers(0, 2**32 - 1))
def test_the_intervals_hold_the_exact_values_at_every_point_of_the_box(truss, seed):
    rng, compiled, program, known, fixed, generating = _instance(truss, seed)
    reduced = interval_program(program)
    size = float(max(compiled.known.values()))
    p = len(compiled.parameters)
    branches = sign_branches(len(compiled.free_triangles)).astype(float)
    ctx.prec = 256
    for draw in range(12):  # boxes around the generating configuration's parameters, and anywhere
        width = size * 10.0 ** rng.uniform(-8, 0, p)
        low = generating - width * rng.uniform(0, 1, p) if draw % 3 else rng.uniform(0, 2 * size, p)
        branch = branches[rng.integers(len(branches))]
        order = 1 + draw % 2  # first- and second-order models, with 0, 1 or 2 edge symbols
        values, jacobians, status = evaluate_boxes(reduced, *enclosing(known), fixed, low[None], (low + width)[None],
                                                   branch[None], order=order, edge_symbols=(draw // 2) % 3)
        for point in low + width * rng.uniform(0, 1, (4, p)):
            feasible, residuals, gradients = _arb_program(reduced, known, fixed, point, branch)
            if status[0] == INFEASIBLE:
                assert feasible is False, "a box called infeasible holds a feasible point"
                continue
            if feasible is False:
                continue
            for c, ball in enumerate(residuals):
                assert _contains(values[0, c], ball), (order, values[0, c], ball)
                if feasible and status[0] == FEASIBLE:
                    for k in range(p):
                        assert _contains(jacobians[0, c, k], gradients[c][k]), (order, k)
    ctx.prec = 53


def test_the_models_are_tight_to_second_order():
    """7/B1 (the thesis example), the box [45, 45 + w] of s1,4 on every branch: the
    ranges of the residual and of its derivative exceed their true ranges (sampled) by
    terms of order w²: measured (2026-11-29), at w = 0.001 by at most 6 % and 0.3 %, at
    w = 0.01 by at most 60 % and 12 % (the branch whose residual barely moves), at w = 1 by
    up to 17 and 6 times (plain interval arithmetic: 200 times at w = 0.001); in
    second-order models by at most 1.2 % and 0.6 % at w = 0.01, 50 % and 21 % at w = 1."""
    scene, compiled, reduced, known, fixed = _example("7-B1.json")
    branches = sign_branches(len(compiled.free_triangles)).astype(float)
    for order, width, factor in ((1, 0.001, 1.15), (1, 0.01, 2.5), (2, 0.01, 1.05), (2, 1.0, 2.0)):
        low = np.full((len(branches), 1), 45.0)
        values, jacobians, status = evaluate_boxes(reduced, *known, fixed, low, low + width, branches, order=order)
        assert (status == FEASIBLE).all()
        points = np.linspace(45.0, 45.0 + width, 401)
        residuals = compiled.residuals(points[:, None], branches)[..., 0]
        slopes = np.diff(residuals, axis=1) / np.diff(points)
        for b in range(len(branches)):
            assert values[b, 0, 1] - values[b, 0, 0] <= factor * np.ptp(residuals[b]) + 1e-12
            assert jacobians[b, 0, 0, 1] - jacobians[b, 0, 0, 0] <= factor * np.ptp(slopes[b]) + 1e-12


def test_second_order_models_are_tight_to_third_order():
    """9/B28 (coupling 2), the box mode ± w about its mode at (s1,12, s1,11) ≈ (489.0,
    441.1): the second-order models' ranges of both residuals and of their four partial
    derivatives exceed the sampled ranges by terms of order w³, measured at w = 1 by
    5.4 % of a residual's range and 12-22 % of a derivative's; the first-order models' by
    terms of order w²: 3.4 times and 7-12 times (2026-11-29, the radicands in
    closure/bilateration.py: small_term_radicand's form)."""
    scene, compiled, reduced, known, fixed = _example("9-B28.json")
    mode = np.array([489.02096252, 441.08647381])
    signs = next(branch for branch in sign_branches(len(compiled.free_triangles)).astype(float)
                 if np.abs(compiled.residuals(mode[None], branch[None])[0, 0]).max() < 1e-6)
    grid = np.linspace(-1.0, 1.0, 41)
    points = mode + np.array([[a, b] for a in grid for b in grid])
    step = 1e-5
    sampled = [compiled.residuals(points, signs[None])[0]]
    for k in range(2):
        shift = np.eye(2)[k] * step
        sampled.append((compiled.residuals(points + shift, signs[None])[0]
                        - compiled.residuals(points - shift, signs[None])[0]) / (2 * step))
    excess = {}
    for order in (1, 2):
        values, jacobians, status = evaluate_boxes(reduced, *known, fixed, (mode - 1.0)[None], (mode + 1.0)[None],
                                                   signs[None], order=order)
        assert status[0] == FEASIBLE
        ranges = [values[0]] + [jacobians[0, :, k] for k in range(2)]
        for got, true in zip(ranges, sampled, strict=True):
            assert (got[:, 0] <= true.min(axis=0) + 1e-12).all() and (true.max(axis=0) <= got[:, 1] + 1e-12).all()
        excess[order] = [float(((got[:, 1] - got[:, 0]) / np.ptp(true, axis=0)).max() - 1)
                         for got, true in zip(ranges, sampled, strict=True)]
    assert excess[2][0] < 0.1 and max(excess[2][1:]) < 0.3, excess
    assert excess[1][0] > 2 and max(excess[1][1:]) > 5, excess


def test_the_models_hold_the_values_beside_a_domain_edge():
    """Boxes of 9/B28 that a domain edge crosses (a triangle of the branch flat inside the
    box), where the root at the edge and the large remainders of roots beside it become
    symbols of their own (0, 1 or 2 of them): at the points of the box where the branch
    exists, the exact value of every register lies in its model's range. The boxes are
    drawn about the points of a coarse grid where feasibility changes between neighbours,
    at five widths."""
    scene, compiled, reduced, known, fixed = _example("9-B28.json")
    source = reduced.program
    exact_known = [scene.known[pair] for pair in source.known_pairs]
    branches = sign_branches(len(compiled.free_triangles)).astype(float)
    axes = [np.linspace(10.0, 6800.0, 24), np.linspace(250.0, 9600.0, 24)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 2)
    defined = ~np.isnan(compiled.residuals(grid, branches)).any(axis=2).reshape(len(branches), 24, 24)
    base_c, base_e, start = models.instance_registers(reduced, *known, fixed)
    written = reduced.instructions[:reduced.values, 1]
    rng = np.random.default_rng(3)
    ctx.prec = 256
    checked = 0
    for k in range(len(branches)):
        for i, j in np.argwhere(defined[k, 1:, :] != defined[k, :-1, :])[::3]:
            middle = np.array([axes[0][i] + 0.5 * (axes[0][1] - axes[0][0]), axes[1][j]])
            for width, symbols, order in ((300.0, 2, 2), (30.0, 1, 2), (30.0, 2, 1), (3.0, 2, 2), (0.3, 1, 2)):
                low = middle - width * rng.uniform(0.2, 0.8, 2)
                c, g, e, radius, scratch = models.new_registers(base_c, base_e, 2 + symbols, 1)
                h = models.quadratic_terms(order, 2 + symbols, len(base_c), 1)
                models.load_box(source.parameter_registers, source.sign_registers, low, low + width, branches[k], c, g, e,
                                radius, 0)
                status, feasible_part = np.array([start]), np.array([[-np.inf], [np.inf]] * 2)
                models.evaluate_models(reduced.instructions[:reduced.values], c, g, h, e, radius, feasible_part, status,
                                       scratch, 2, 1)
                if status[0] != models.EDGE:
                    continue
                ranges = [models.model_range(c, g, h, e, radius, register, 0) for register in written]
                for point in low + width * rng.uniform(0, 1, (6, 2)):
                    exact: dict = {}
                    if _arb_program(reduced, exact_known, fixed, point, branches[k], exact)[0] is not True:
                        continue
                    checked += 1
                    for register, interval in zip(written, ranges, strict=True):
                        assert _contains(interval, exact[register]), (k, low, width, symbols, order, register)
    ctx.prec = 53
    assert checked >= 80, checked  # points of boxes that an edge crosses
