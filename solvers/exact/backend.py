"""Exact backend: assembly modes from the certified real roots of the characteristic
polynomial (thesis §3.2–3.6: "the coefficients had to be computed in exact rational
arithmetic").

1. derive the characteristic polynomial of the best plan in exact rational arithmetic
   (:func:`baranov.solvers.exact.characteristic.characteristic_polynomial`);
2. isolate its real roots with certified enclosures (flint/arb);
3. map every real root to the sign branches on which the radical closure condition holds
   there, in ball arithmetic (flint arb) from the exact dimensions, and build the
   configurations from the same balls; verify them like the numeric backend. (Evaluating
   the condition in floats instead lost both modes of a pentad whose platform is 1e-8 of
   its width from collinear: rounding the dimensions moves the float condition's roots
   by ~4e-6 there, docs/stability.md);
4. wherever the plan itself is undefined — a bilateration's base joints coincide, as at
   T = s1,5 = 0 in thesis §5.1.3.2 — msolve or another plan lists the modes
   (:func:`~baranov.solvers.coincidence.with_modes_where_plan_divides_by_zero`): for every
   pair that can coincide, not only at the roots of the polynomial, which clearing the
   denominators can lose (issue 25's 7/N2 at s1,8 = 0).

Coupling degree 0 needs no polynomial: every branch is a candidate. Coupling degree 2
(thesis §3.4.1.3) eliminates the second parameter (:mod:`baranov.solvers.exact.coupling_two`);
the second parameter of a mode is a real common root of the two genuine curves above the
first, computed exactly (:mod:`baranov.solvers.exact.fibers`).

Every solve carries a :class:`~baranov.solvers.modes.Certificate`: complete when each step
above was exact or checked on the instance, with the gaps listed otherwise (docs/exact.md,
"What the exact backend guarantees").
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import flint
import numpy as np

from baranov.closure import distinct_branches
from baranov.planner import Plan, coupling_degree, parameter_name, plans_avoiding
from baranov.scene import Scene

from ..candidates import assembly_modes
from ..coincidence import (
    MSOLVE_NOTE,
    NoPlanError,
    coincidence_possible,
    division_pairs,
    modes_without_plan,
    solvable_plan,
    unexamined_coincidences,
    with_modes_where_plan_divides_by_zero,
)
from ..modes import AssemblyMode, Certificate, ExactSolution, SolverError
from ..placement import compile_scene, placed_from_ground
from ..progress import report_stage
from ..verification import RESIDUAL_TOLERANCE, joint_residual, same_mode, sorted_modes
from .characteristic import (
    TEST_BITS,
    CharacteristicPolynomial,
    ExactMethodError,
    characteristic_polynomial,
    exact_plan,
    residual_verdict,
    residuals_on_branches,
    with_slider_points,
)
from .coupling_two import characteristic_polynomial_two, common_points
from .fibers import Fiber
from .roots import complex_roots

#: A branch is a candidate at a real root when its closure residual's ball there contains
#: 0 and is narrower than this (relative; the configuration is then verified to 1e-8 on
#: every link dimension).
BRANCH_TOLERANCE = 1e-6

#: Precisions (bits) at which a real root and its branch residuals are evaluated, in turn,
#: while some branch is undecided; coupling degree 2 starts higher, since the second
#: parameter is isolated from a curve with coefficients of hundreds of bits.
ROOT_BITS = (64, 256, 1024)
ROOT_BITS_TWO = (256, 1024, 4096)


def solve_exact(scene: Scene, plan: Plan | None = None, *, coincidences: bool = True) -> ExactSolution:
    """All assembly modes of ``scene`` (coupling degree 0, 1 or 2) by the exact method;
    the result (:class:`~baranov.solvers.modes.ExactSolution`) carries the characteristic
    polynomial (in the first parameter) and the certificate.
    ``coincidences=False`` skips step 4 (used by step 4 itself). Where the plan is chosen
    here and the norm of its closure condition vanishes identically, other parameters are
    tried (:func:`by_other_parameters`)."""
    chosen = plan is None
    try:
        plan = plan or exact_plan(scene)
    except NoPlanError as error:  # no plan is defined: msolve's modes, verified
        by_more = by_one_more_parameter(scene)  # only a chosen plan raises here
        if by_more is not None:
            return by_more
        described, modes, certificate = modes_without_plan(scene, error)
        return ExactSolution.of_plan("exact", scene, described, modes, certificate=certificate)
    branches = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    polynomial: CharacteristicPolynomial | None = None
    gaps: tuple[str, ...] = ()
    notes: list[str] = []  # the Monte Carlo steps taken
    if plan.number_of_parameters == 0:
        modes = assembly_modes(scene, compile_scene(scene, plan),
                               [(np.zeros(0), np.array(branch, dtype=int)) for branch in branches])
    elif plan.number_of_parameters == 1:
        report_stage("exact: deriving the characteristic polynomial")
        polynomial = characteristic_polynomial(scene, plan)
        report_stage(f"exact: isolating the real roots (degree {polynomial.degree}) and placing the modes")
        modes, gaps = modes_at_real_roots(scene, plan, polynomial, branches)
    elif plan.number_of_parameters == 2:
        report_stage("exact: the characteristic polynomial from its images modulo primes (coupling degree 2)")
        polynomial, fibers = characteristic_polynomial_two(scene, plan)
        report_stage(f"exact: isolating the real roots (degree {polynomial.degree}) and placing the modes")
        modes, gaps = modes_at_real_roots(scene, plan, polynomial, branches, fibers)
        notes.append(LIFTING_NOTE)
    else:
        raise ExactMethodError(
            f"coupling degree {plan.number_of_parameters}: the exact method solves coupling degrees 0 to 2; "
            "--method homotopy solves any (docs/homotopy.md)")
    zero_settled = False  # the parameter's joints coinciding (s = 0) examined, or impossible
    if plan.number_of_parameters and coincidences:
        solver = None if scene.sliders else (lambda other: solve_exact(scene, other, coincidences=False))
        modes, by_msolve, unsettled = with_modes_where_plan_divides_by_zero(scene, plan, modes, solver)
        gaps += unsettled
        notes += [MSOLVE_NOTE] if by_msolve else []
        zero_settled = not unsettled
    elif plan.number_of_parameters:
        gaps += unexamined_coincidences(set().union(*division_pairs(scene, plan)))
    if polynomial is not None and polynomial.vanishing:
        # issue 25's 9/N20 (msolve: positive-dimensional; numeric: the condition vanishes along
        # s8,10 in (0, 68)): the norm is 0 and only the contents divided out (powers of the
        # parameter) were left, which had been certified with 8 modes
        # issue 25's 7/N2 drawn with P2 on P7: the norm vanishes too, but no real configuration
        # moves (msolve: positive-dimensional over C; a complex curve through an isolated real mode)
        gaps += ("the norm of the closure condition vanishes identically: on some branch, possibly complex, it "
                 "holds for every value of the parameter, so the linkage moves or a complex curve of solutions "
                 "passes through its real ones; the real modes are not certified",)
    elif polynomial is not None and polynomial.shared_curves:
        plane = ", ".join(parameter_name(pair) for pair in plan.parameters)
        gaps += tuple(f"both closure conditions hold along the curve {curve} = 0 in (u, v) = ({plane}) "
                      "on some branch, with no real configuration found on it: a continuum of complex solutions; "
                      "real modes on that curve are not certified" for curve in polynomial.shared_curves)
    elif polynomial is not None and not polynomial.factors:
        gaps += ("the characteristic polynomial has no factor but powers of the parameter: a degenerate "
                 "instance (it may move) that this plan cannot decide",)
    if polynomial is not None:
        gaps += _undecided_factors(scene, plan, polynomial, zero_settled)
    solution = ExactSolution.of_plan("exact", scene, plan, modes, characteristic_polynomial=polynomial,
                                     certificate=Certificate(not gaps, "; ".join(notes) or None, gaps))
    if chosen and coincidences and polynomial is not None and polynomial.vanishing and not scene.sliders:
        return by_other_parameters(scene, plan) or solution
    return solution


#: How many other choices of parameters :func:`by_other_parameters` tries.
OTHER_PARAMETERS = 3


def by_other_parameters(scene: Scene, plan: Plan) -> ExactSolution | None:
    """The certified solution of the best plan, among the ALTERNATIVE_PLANS best that
    avoid the scene's coincident joints, whose parameters differ from ``plan``'s and whose
    solve leaves no gap; the first OTHER_PARAMETERS such choices are tried; None if none
    certifies.

    Where ``plan``'s closure condition has a norm identically 0, the characteristic
    polynomial is lost for that parametrisation only, not always for the linkage: a
    complex curve of solutions can project onto the whole axis of one distance and onto a
    point of another. Issue 25's 9/N21 (seed 39: P6 on P12, six joints on one line) has a
    norm 0 in s8,10 and a certified polynomial with its one mode in s7,12; a linkage that
    moves leaves gaps with every plan (its norms vanish too, or the solve says it moves).

    Cost: up to OTHER_PARAMETERS exact solves."""
    tried = {frozenset(map(frozenset, plan.parameters))}
    for other in plans_avoiding(scene.chain, scene.coincident_pairs):
        parameters = frozenset(map(frozenset, other.parameters))
        if parameters in tried:
            continue
        if len(tried) > OTHER_PARAMETERS:
            return None
        tried.add(parameters)
        try:
            solution = solve_exact(scene, other)
        except SolverError:
            continue
        if solution.certificate.complete:
            return solution
    return None


def by_one_more_parameter(scene: Scene) -> ExactSolution | None:
    """For a slider chain of coupling degree 1 that no plan of one parameter suits (its
    sliders stand where every such plan needs a revolute joint: planner/sliders.py), the
    solution by the best slider plan of two parameters, if it is defined for the scene and
    its solve leaves no gap; else None (msolve's checked answer is then the route).

    Of the 3095 nine-link slider chains of the catalog counted by msolve, 3020 have such a
    plan (docs/bench/slider-plans-with-more-parameters.md; twelve of them solved there, all
    certified with msolve's modes). Of six other random instances, four were certified this
    way; one plan of two was undefined for the dimensions, and one characteristic
    polynomial had no factor but powers of the parameter: those two went to msolve.

    Cost: one exact solve of coupling degree 2."""
    if not scene.sliders or coupling_degree(scene.chain) != 1:
        return None
    try:  # the plan of one parameter raised NoPlanError already, so this one has two
        plan = solvable_plan(scene, extra_parameters=1)
    except NoPlanError:
        return None
    try:
        solution = solve_exact(scene, plan)
    except SolverError:
        return None
    return solution if solution.certificate.complete else None


#: What the coupling-2 certificate says of its one Monte Carlo step.
LIFTING_NOTE = "the polynomial is lifted from its images modulo random 62-bit primes"


def _undecided_factors(scene: Scene, plan: Plan, polynomial: CharacteristicPolynomial,
                       zero_settled: bool) -> tuple[str, ...]:
    """The gaps left by the dropped factors that ``plan`` could not decide
    (``polynomial.degenerate``) with a positive real root and no coincident joint pair to
    blame: undecided at the highest precision. Those with a coincident pair are settled
    with every other coincidence the plan divides by
    (:func:`~baranov.solvers.coincidence.with_modes_where_plan_divides_by_zero`), and so is
    the factor s itself where the parameter is a squared distance and its joints' meeting
    was examined (``zero_settled``) or cannot happen: its one root, s = 0, is that meeting
    (thesis §5.2.2's robots II and IV, where the slider plan could not decide s1,5 = 0)."""
    sliders = {slider.joint for slider in scene.sliders}
    name = parameter_name(plan.parameters[0], sliders)
    pair = frozenset(plan.parameters[0])
    meeting_known = not pair & sliders and (zero_settled or not coincidence_possible(scene, pair))
    gaps = []
    for factor, coincident in polynomial.degenerate:
        if meeting_known and factor.degree() == 1 and factor.coeffs()[0] == 0:
            continue
        real = [float(root.real.mid()) for root, _ in complex_roots(factor) if root.imag == 0 and root.real >= 0]
        if real and not coincident:
            gaps.append(f"a factor of degree {factor.degree()} with real roots near "
                        f"{name} = {real[0]:.6g} could not be decided at {TEST_BITS[-1]} bits")
    return tuple(gaps)


def modes_at_real_roots(scene: Scene, plan: Plan, polynomial: CharacteristicPolynomial,
                        branches: Sequence[Sequence[int]],
                        fibers: Sequence[Fiber] | None = None) -> tuple[tuple[AssemblyMode, ...], tuple[str, ...]]:
    """The verified assembly modes at the positive real roots of ``polynomial``; for
    coupling degree 2, at the real common points (u, v > 0) of the two genuine curves
    above each root u, one :class:`~baranov.solvers.exact.fibers.Fiber` per factor (exact).

    Each root is enclosed at ROOT_BITS[0] bits (ROOT_BITS_TWO for coupling 2) and every
    branch's closure residuals are evaluated over the enclosure in ball arithmetic from
    the exact dimensions (:func:`~baranov.solvers.exact.characteristic.closure_residuals`): a
    branch where a ball excludes 0 is ruled out (rigorously); where every ball contains 0
    and is narrower than BRANCH_TOLERANCE of its closure distance, the configuration (the
    balls' midpoints of the same placement) is built and verified to RESIDUAL_TOLERANCE on every link dimension. Branches still
    undecided, or whose configuration fails the verification (joints 1e-5 apart place
    too coarsely at 64 bits), are evaluated again with a tighter root at the next
    precision. Modes at distinct roots are distinct (their parameter differs), however
    close; at one root, branches that place every joint alike (a flat free-sign triangle)
    are one mode.

    Returns the modes and the *gaps* (roots at which some branch stayed undecided at the
    highest precision). A branch on which the plan is undefined at a root (a base's joints
    coincide) is ruled out here; such modes are the coincidences' (step 4).

    Cost: O(real roots × 2^m × steps) ball operations (m free-sign triangles), plus a
    root isolation per precision used."""
    sliders = [slider.joint for slider in scene.sliders]
    names = tuple(parameter_name(pair, sliders) for pair in plan.parameters)
    every_branch = [tuple(int(s) for s in b) for b in branches]
    zero = coincidence_possible(scene, frozenset(plan.parameters[0]))
    # t: an oriented distance to a slider's axis, of either sign (thesis §4.2.4)
    signed = tuple(bool(set(pair) & set(sliders)) for pair in plan.parameters)
    modes: list[AssemblyMode] = []
    gaps: list[str] = []
    previous = flint.ctx.prec
    try:
        for number, (factor, _) in enumerate(polynomial.factors):
            fiber = None if fibers is None else fibers[number]
            undecided: dict[int, list[tuple[int, ...]]] | None = None
            found: dict[int, list[AssemblyMode]] = {}
            for bits in ROOT_BITS if fibers is None else ROOT_BITS_TWO:
                flint.ctx.prec = bits
                roots = sorted((root.real for root, _ in complex_roots(factor) if root.imag == 0),
                               key=lambda r: float(r.mid()))
                if undecided is None:
                    undecided = {index: every_branch for index in range(len(roots))}
                    found = {index: [] for index in undecided}
                for index, signs_list in list(undecided.items()):
                    points = _parameter_points(roots[index], fiber, zero, signed)
                    still = _modes_at_root(scene, plan, points, signs_list, names, found[index])
                    if still:
                        undecided[index] = sorted(still)
                    else:
                        del undecided[index]
                if not undecided:
                    break
            modes += [mode for at_root in found.values() for mode in at_root]
            gaps += [f"{names[0]} ≈ {float(roots[index].mid()):.6g}: sign branches undecided at {bits} bits"
                     for index in undecided or {}]
    finally:
        flint.ctx.prec = previous
    return sorted_modes(modes), tuple(gaps)


def _modes_at_root(scene: Scene, plan: Plan, points: list | None, signs_list: list[tuple[int, ...]],
                   names: tuple[str, ...], found: list[AssemblyMode]) -> set[tuple[int, ...]]:
    """One round of :func:`modes_at_real_roots` at one root: every branch of
    ``signs_list`` at every parameter point (None: not isolated at this precision). New
    verified modes are appended to ``found``; returns the branches still undecided."""
    if points is None:  # the second parameter could not be isolated: more bits
        return set(signs_list)
    still = set()
    for point in points:
        for signs, residuals, placed, _ in residuals_on_branches(scene, plan, point, signs_list, real_only=True):
            verdict = residual_verdict(residuals, BRANCH_TOLERANCE)
            if verdict is False:
                continue
            mode = _ball_configuration(scene, placed, point, signs, names) if verdict else None
            if mode is None or mode.max_residual >= RESIDUAL_TOLERANCE:
                still.add(signs)  # too wide, or placed too coarsely: more bits
            elif not any(same_mode(mode, other, scene) for other in found):
                found.append(mode)
    return still


def _parameter_points(root: flint.arb, fiber: Fiber | None, zero: bool,
                      signed: tuple[bool, ...] = (False, False)) -> list[tuple[flint.acb, ...]] | None:
    """The parameter values to try at a real root: (root,) for coupling 1; the real common
    points (root, v) of the two curves for coupling 2, v > 0 for a squared distance;
    None if they cannot be decided at this precision (a ball straddling 0, or roots not
    isolated); [] where root < 0 (a squared distance), or root = 0 unless ``zero`` (the
    parameter's joints can coincide: issue 25's 9/N2 instance, a mode at s1,10 = 0 that
    was skipped). A parameter that is ``signed`` (a slider's t, thesis §4.2.4) takes
    every real value: the second one was kept only where positive until 2026-11-26, which
    lost every mode of 9/B28 with sliders P1, P2, P7, P8, P11 (t10,1 < 0 in all four)."""
    at_zero = zero and root.is_exact() and root == 0
    if not root > 0 and not at_zero and not signed[0]:
        return None if root.contains(0) and not root.is_exact() else []
    if fiber is None:
        return [(flint.acb(root),)]
    common = common_points(fiber, flint.acb(root))
    if common is None:
        return None
    if signed[1]:
        return [(u, flint.acb(v.real)) for u, v in common if v.imag.contains(0)]
    if any(v.imag.contains(0) and v.real.contains(0) and not v.real.is_exact() for _, v in common):
        return None
    return [(u, flint.acb(v.real)) for u, v in common if v.imag.contains(0) and v.real > 0]


def _ball_configuration(scene: Scene, points: dict, parameters: tuple[flint.acb, ...], signs: tuple[int, ...],
                        names: tuple[str, ...]) -> AssemblyMode:
    """The configuration from the plan's points placed in ball arithmetic
    (:func:`~baranov.solvers.exact.characteristic.placed_points`) at ``parameters``."""
    matrices = {joint: np.array([complex(float(x.real.mid()), float(y.real.mid()))])
                for joint, (x, y) in with_slider_points(points).items()}
    placed = {joint: complex(value[0]) for joint, value in placed_from_ground(scene, matrices).items()}
    if not all(math.isfinite(p.real) and math.isfinite(p.imag) for p in placed.values()):
        return AssemblyMode({}, signs, {}, math.inf)
    return AssemblyMode({name: float(value.real.mid()) for name, value in zip(names, parameters, strict=True)},
                        signs, {j: (p.real, p.imag) for j, p in sorted(placed.items())}, joint_residual(scene, placed))
