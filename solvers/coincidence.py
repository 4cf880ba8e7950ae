"""Assembly modes where a plan is undefined: two joints that a bilateration uses as its
base coincide.

A plan's bilateration Z_{i,j,k} divides by s_{i,j} (thesis eq. 2.7), so at a configuration
with P_i = P_j the plan cannot place the next joint, and a root of the characteristic
polynomial there can be neither confirmed nor ruled out by that plan. Thesis §5.1.3.2 has
such a case: a 3-RPR robot whose characteristic polynomial has a quadruple root at
T = s1,5 = 0, "that leads to two valid configurations", found there by two bilaterations
that do not use P1 P5 as a base. Here the scene is solved again with the best plan none
of whose bases (nor its reference) is a coincident pair, and its modes at the parameter
values in question are kept.

Two joints can coincide only if a known distance between them is 0 or absent, and every
joint with known distances to both is equally far from each; the extra solve is skipped
otherwise (for generic dimensions it always is).

Joints that coincide by the scene's own dimensions (a link with a squared distance 0,
coalescent attachments, thesis §5.1.3.3) must never be a base: :func:`solvable_plan`
chooses the plan accordingly.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from itertools import combinations

import numpy as np

from baranov.closure import sign_branches
from baranov.planner import ALTERNATIVE_PLANS, Plan, SliderPlanError, best_plan, plan_avoiding, slider_plan
from baranov.scene import Scene
from baranov.topology import TopologyError

from .modes import AssemblyMode, Certificate, MovableLinkageError, Solution, SolverError
from .msolve import find_msolve, msolve_modes
from .msolve_backend import MSOLVE_MONTE_CARLO, checked_against_generic_count, described_mode, verified_modes
from .placement import compile_scene
from .verification import RESIDUAL_TOLERANCE, distance_bound, joint_residual, same_mode, sorted_modes


def coincidence_possible(scene: Scene, pair: frozenset[str]) -> bool:
    """Whether the two joints of ``pair`` can coincide (see the module docstring). A
    slider is no witness: its known distances are to two different points, one on each of
    its links (a 7/N3 chain with sliders at P1, P4, P6, P8, P9, drawn with P2 on P7: P1's
    distances to P2 and to P7 differ, which had ruled the coincidence out, and both
    backends lost the two modes at s2,7 = 0, the exact one certified).

    Cost: O(number of known distances)."""
    if pair in scene.known:
        return scene.known[pair] == 0
    u, v = tuple(pair)
    sliders = {slider.joint for slider in scene.sliders}
    for w in {joint for key in scene.known for joint in key} - pair - sliders:
        to_u, to_v = scene.known.get(frozenset((u, w))), scene.known.get(frozenset((v, w)))
        if to_u is not None and to_v is not None and to_u != to_v:
            return False
    return True


class NoPlanError(SolverError):
    """No bilateration plan is defined for the scene: two joints at known distance 0 are
    a base of every plan tried."""


def solvable_plan(scene: Scene, extra_parameters: int = 0) -> Plan:
    """The best plan with no joint pair at known distance 0 as its reference or a base;
    raises :class:`NoPlanError` (naming the pair) if none of the ALTERNATIVE_PLANS best
    has that property (:class:`MovableLinkageError` if msolve finds the linkage moves).
    ``extra_parameters``: for a slider chain, plans with up to that many parameters more
    than the fewest are tried where no plan of the fewest suits its sliders
    (:func:`~baranov.planner.sliders.slider_plan`)."""
    if scene.sliders:
        try:
            plan = slider_plan(scene.chain, [slider.joint for slider in scene.sliders],
                               extra_parameters=extra_parameters)
        except SliderPlanError as error:
            raise NoPlanError(str(error)) from None
        undefined = slider_plan_undefined(scene, plan)
        if undefined is not None:
            raise NoPlanError(f"sliders {', '.join(s.joint for s in scene.sliders)}: the slider plan {undefined}")
        return plan
    plan = plan_avoiding(scene.chain, scene.coincident_pairs)
    if plan is None:
        names = ", ".join(sorted(",".join(sorted(pair)) for pair in scene.coincident_pairs))
        message = (f"joints {names}: coincident (squared distance 0), and none of the {ALTERNATIVE_PLANS} best "
                   "plans avoids them as a bilateration base")
        if find_msolve() is not None and scene.exact and msolve_modes(scene).status == "infinite":
            # said rather than only refused (issue 25's 9/N17, two joints of one link at one point)
            raise MovableLinkageError(f"{message}; msolve: the linkage moves with these dimensions "
                                      "(a positive-dimensional solution set, over the complex numbers)")
        raise NoPlanError(message)
    return plan


def bounded_slider_plan(scene: Scene, plan: Plan) -> Plan:
    """For a slider chain whose ``plan`` has a parameter that no path of link dimensions
    bounds (:meth:`~baranov.scene.Scene.largest_distance` infinite: the sampling searches
    then map it through a tangent, and the interval branch-and-prune cannot search it),
    of coupling degree 1, the best slider plan with one parameter that is bounded, if one
    is defined for the scene's dimensions; else ``plan``. O(the plan search with a parameter constraint:
    3–15 ms on random 7- and 9-link chains)."""
    if (not scene.sliders or plan.number_of_parameters != 1
            or all(math.isfinite(scene.largest_distance(*pair)) for pair in plan.parameters)):
        return plan
    sliders = {slider.joint for slider in scene.sliders}
    joints = sorted(joint.name for joint in scene.chain.joints)
    bounded = [pair for pair in combinations(joints, 2)
               if not set(pair) <= sliders and math.isfinite(scene.largest_distance(*pair))]
    try:
        other = slider_plan(scene.chain, sorted(sliders), parameters=bounded)
    except (SliderPlanError, TopologyError):
        return plan
    if other.number_of_parameters != plan.number_of_parameters or slider_plan_undefined(scene, other) is not None:
        return plan
    return other


#: Samples per parameter of the probe of :func:`slider_plan_undefined`.
PROBES = 32
#: A closure condition whose median size over the probe exceeds this divides by a
#: rounding-level 0 (issue 18's degenerate random robots: medians 1.5e16 to 3.2e16; the
#: slider regressions and examples: 0.45 to 10.7).
DIVIDED_BY_ROUNDING = 1e12


def slider_plan_undefined(scene: Scene, plan: Plan) -> str | None:
    """Why a slider chain's ``plan`` is undefined for the scene's dimensions, or None.

    Undefined means that the plan divides by 0, not that its triangles cannot be built:

    * by an exact 0: a bilateration base (or the reference) of two joints at known
      squared distance 0, or a slider construction of an exact 0 (two joints of a
      slider's link at one point, an axis through them undefined);
    * where msolve can list the modes instead (an exact scene): at none of PROBES samples
      per parameter over its searched range, on any branch, is the closure condition
      defined, and at some of them it is 0/0 (a step's radicand NaN, or every step built
      and the condition NaN: two parallel axes fixed in one link, "a point on two axes"
      dividing by 0); or it divides by a rounding-level 0 at most samples
      (DIVIDED_BY_ROUNDING).

    Samples at which a triangle cannot be built (a radicand below 0) say nothing of
    definedness: a plan whose feasible range falls between two samples is defined (issue
    55: a 7/N3 chain with sliders P1, P7 whose real range of t1,9 is [-44.3, -41.7], 2.6
    wide between samples 5.1 apart, was declared undefined and handed to msolve). Found
    by issue 18's random robots: the exact backend raised ZeroDivisionError and the
    numeric one found 0 of msolve's modes. Cost: one vectorised evaluation of PROBES^p
    points × 2^m branches."""
    coincident = ({frozenset(plan.reference)} | {frozenset(step.base) for step in plan.steps}) & scene.coincident_pairs
    if coincident:
        pairs = ", ".join(sorted(",".join(sorted(pair)) for pair in coincident))
        return f"divides by 0 for these dimensions (joints {pairs} at one point are a bilateration base)"
    try:
        compiled = compile_scene(scene, plan)
        upper = [compiled.search_bound(n, scene.largest_distance(u, v) ** 2) for n, (u, v) in enumerate(plan.parameters)]
        axes = [np.linspace(0, math.sqrt(bound), PROBES + 1)[1:] ** 2 for bound in upper]
        points = np.stack([grid.ravel() for grid in np.meshgrid(*axes, indexing="ij")], axis=-1) if axes else np.zeros((1, 0))
        with np.errstate(all="ignore"):
            profile = compiled.profile(points, sign_branches(len(plan.free_sign_triangles)))
    except ZeroDivisionError:
        return "divides by 0 for these dimensions (two joints of a slider's link at one point?)"
    if find_msolve() is None or not scene.exact:
        return None
    residuals = profile.residuals
    built = profile.failures == len(plan.steps)
    defined = np.isfinite(residuals).all(axis=-1) & (built if residuals.shape[-1] == 0 else True)
    if not defined.any():
        zero_over_zero = (built & ~defined) | (~built & np.isnan(profile.radicands))
        if not zero_over_zero.any():
            return None  # no triangle of the plan can be built at the samples: a narrow range, not a division
        return (f"is undefined (0/0) at {int(zero_over_zero.sum())} and defined at none of its {defined.size} "
                "samples of its parameters and branches (two parallel axes fixed in one link?)")
    finite = np.abs(residuals[np.isfinite(residuals)])
    if finite.size and np.median(finite) > DIVIDED_BY_ROUNDING:
        return (f"divides by a rounding-level 0 at most of its {len(points)} probe points (its closure "
                f"condition's median size {np.median(finite):.1e}; two parallel axes?)")
    return None


#: What a solution found without a plan says of its modes.
NO_PLAN_NOTE = ("no bilateration plan is defined (joints {pairs} coincide in every plan's base): the modes are "
                "msolve's, on the Cartesian system, each verified on the link dimensions")
#: The same where no plan suits a slider chain's sliders.
NO_SLIDER_PLAN_NOTE = ("no bilateration plan suits the slider joints ({reason}): the modes are msolve's, on the "
                       "Cartesian system, each verified on the link dimensions and the sliders")


def modes_without_plan(scene: Scene, error: NoPlanError) -> tuple[Plan, tuple[AssemblyMode, ...], Certificate]:
    """Where no plan is defined (``error`` from :func:`solvable_plan`), every mode by
    msolve on the Cartesian system (no plan needed), each verified on the link
    dimensions and described in the terms of the best plan (returned too, though it is
    undefined at the coincidence); and the certificate: complete (one Monte Carlo step,
    msolve's) where msolve's count of complex solutions is the generic count
    (:func:`~.msolve_backend.checked_against_generic_count`), else not, with the note
    saying why no plan served. Raises
    ``error`` again without msolve, for a scene with float dimensions, or where msolve
    fails or a mode does not verify (issue 25: 9/N12 drawn with P1 and P9 of one link at
    one point, which both backends refused where msolve lists 4 modes)."""
    if find_msolve() is None or not scene.exact:
        raise error
    plan = best_plan(scene.chain)
    try:
        modes = verified_modes(scene, plan)
    except MovableLinkageError:
        raise
    except SolverError as failure:
        raise NoPlanError(f"{error}; {failure}") from None
    pairs = ", ".join(sorted("=".join(sorted(pair)) for pair, value in scene.known.items() if value == 0))
    # no pair coincides: a slider chain that none of the plans tried suits (planner/sliders.py)
    note = NO_PLAN_NOTE.format(pairs=pairs) if pairs else NO_SLIDER_PLAN_NOTE.format(reason=error)
    checked, comparison = checked_against_generic_count(scene)
    certificate = (Certificate(True, f"{note}; {comparison}; {MSOLVE_MONTE_CARLO}") if checked else
                   Certificate(False, None, (f"{note}; {comparison}",)))
    return plan, sorted_modes(modes), certificate


def with_coincident_modes(scene: Scene, plan: Plan, pairs: Iterable[frozenset[str]], values: list[float],
                          modes: tuple[AssemblyMode, ...],
                          solver: Callable[[Plan], Solution]) -> tuple[tuple[AssemblyMode, ...], bool]:
    """``modes`` and the modes at which ``plan``'s first parameter takes one of ``values``
    and the joints of ``pairs`` coincide, found by ``solver`` with an alternative plan;
    and whether that settles them: True if no pair can coincide, else as
    :func:`_with_alternative_modes`."""
    pairs = set(pairs)
    if not any(coincidence_possible(scene, pair) for pair in pairs):
        return modes, True
    scale = distance_bound(scene) ** 2

    def at_values(measured: list[float], mode: AssemblyMode) -> list[float] | None:
        closest = min(values, key=lambda r: abs(measured[0] - r))
        return [closest, *measured[1:]] if abs(measured[0] - closest) <= 1e-9 * scale else None

    return _with_alternative_modes(scene, plan, pairs, modes, solver, at_values)


def computed_base_pairs(scene: Scene, plan: Plan, with_parameters: bool = False) -> set[frozenset[str]]:
    """The joint pairs that ``plan`` uses as a bilateration base (or reference) whose
    distance is not a known dimension — nor a parameter, unless ``with_parameters`` —
    and that can coincide (:func:`coincidence_possible`): where they do, the plan divides
    by 0."""
    parameters = set() if with_parameters else {frozenset(pair) for pair in plan.parameters}
    pairs = {frozenset(plan.reference)} | {frozenset(step.base) for step in plan.steps}
    return {pair for pair in pairs - parameters if pair not in scene.known and coincidence_possible(scene, pair)}


def with_modes_of_coincident_joints(scene: Scene, plan: Plan, pairs: set[frozenset[str]],
                                    modes: tuple[AssemblyMode, ...],
                                    solver: Callable[[Plan], Solution]) -> tuple[tuple[AssemblyMode, ...], bool]:
    """``modes`` and the modes of another plan's solve in which the joints of one of
    ``pairs`` coincide (within 1e-6 of the linkage's size): the modes ``plan`` cannot
    reach, wherever they are (found by the collinear-joints sweep, 9/N19: P3 = P11 at
    s1,10 = 34.6 in four modes); settled as :func:`_with_alternative_modes` says."""
    scale = distance_bound(scene)

    def coincident(measured: list[float], mode: AssemblyMode) -> list[float] | None:
        near = any(_squared_distance(mode, *sorted(pair)) < (1e-6 * scale) ** 2 for pair in pairs)
        return measured if near else None

    return _with_alternative_modes(scene, plan, pairs, modes, solver, coincident)


def _with_alternative_modes(scene: Scene, plan: Plan, pairs: set[frozenset[str]], modes: tuple[AssemblyMode, ...],
                            solver: Callable[[Plan], Solution],
                            accept: Callable[[list[float], AssemblyMode], list[float] | None]
                            ) -> tuple[tuple[AssemblyMode, ...], bool]:
    """``modes`` and the new modes of ``solver``'s solve with the best plan avoiding
    ``pairs`` that ``accept`` takes: it gets ``plan``'s parameters measured on the
    configuration and the mode, and returns the parameter values to report, or None.
    Added modes carry ``plan``'s free-sign orientations (0 where flat). Also whether that
    settles the coincidences: the alternative plan exists and its solve is complete (an
    exact solve's certificate; a numeric solve counts)."""
    alternative = plan_avoiding(scene.chain, pairs)
    if alternative is None:
        return modes, False
    found = list(modes)
    solution = solver(alternative)
    for mode in solution.assembly_modes:
        values = accept([_squared_distance(mode, *pair) for pair in plan.parameters], mode)
        if values is not None and not any(same_mode(mode, other, scene) for other in found):
            found.append(described_mode(scene, plan, mode.joints, mode.max_residual, values))
    certificate = getattr(solution, "certificate", None)
    return sorted_modes(found), certificate is None or certificate.complete


#: What a certificate says of the modes :func:`with_modes_from_msolve` adds.
MSOLVE_NOTE = ("msolve lists the modes where the plan's base joints coincide "
               "(a multi-modular Gröbner basis over Q, correct with high probability)")


def with_modes_from_msolve(scene: Scene, plan: Plan, pairs: Iterable[frozenset[str]],
                           modes: tuple[AssemblyMode, ...], parallel: Iterable[frozenset[str]] = ()
                           ) -> tuple[tuple[AssemblyMode, ...], bool, tuple[str, ...]]:
    """``modes`` and every mode in which the joints of one of ``pairs`` coincide, or the
    axes of one of the slider pairs ``parallel`` are parallel, solved by msolve on the
    Cartesian system with P_u = P_v (or the axes' cross product) added
    (:mod:`baranov.solvers.msolve`, which needs no plan); whether msolve ran (not without
    its binary, nor for a scene with float dimensions); and what it could not settle, one
    sentence per pair: a positive-dimensional solution set (the linkage moves while those
    joints coincide: issue 25's 7/N2 instance, which rotates about P1 = P6 = P8 — no plan
    sees such a continuum, and an alternative plan had reported it complete), or a failure.

    Where no bilateration plan is defined at a coincidence, this is what decides it
    (issue 25: 9/N10 with P11 = P7, whose only plan avoiding that base is undefined where
    P8 = P9; none of the truss's 88 plans avoids both)."""
    if find_msolve() is None or not scene.exact:
        return modes, False, ()
    found, gaps = list(modes), []
    conditions = [("coincident", pair, f"joints {'='.join(sorted(pair))}", "coincide")
                  for pair in sorted(pairs, key=sorted) if coincidence_possible(scene, pair)]
    conditions += [("parallel", pair, f"the axes of {' and '.join(sorted(pair))}", "are parallel")
                   for pair in sorted(parallel, key=sorted)]
    for kind, pair, where, verb in conditions:
        result = msolve_modes(scene, **{kind: [pair]})
        if result.status == "infinite":
            gaps.append(f"the linkage is movable where {where} {verb} (msolve: a positive-dimensional "
                        "solution set); its configurations there are not isolated modes")
        elif result.status != "finite":
            gaps.append(f"{where} may {verb.replace('are ', 'be ')} and msolve failed: {result.message}")
        for configuration in result.configurations:
            residual = joint_residual(scene, {j: complex(*p) for j, p in configuration.items()})
            mode = AssemblyMode({}, (), configuration, residual)
            if residual >= RESIDUAL_TOLERANCE:
                gaps.append(f"msolve's mode with {where} does not verify (residual {residual:.1e})")
            else:  # msolve's configuration replaces a float one of the same mode (3-RPR-II: 5.9e-10 off s1,5 = 0)
                found = [other for other in found if not same_mode(mode, other, scene)]
                found.append(described_mode(scene, plan, configuration, residual))
    return sorted_modes(found), True, tuple(gaps)


def with_modes_where_undefined(scene: Scene, plan: Plan, pairs: set[frozenset[str]], modes: tuple[AssemblyMode, ...],
                               alternative: Callable[[tuple[AssemblyMode, ...]], tuple[tuple[AssemblyMode, ...], bool]]
                               ) -> tuple[tuple[AssemblyMode, ...], bool, tuple[str, ...]]:
    """``modes`` and the modes where the joints of one of ``pairs`` coincide (where
    ``plan`` divides by 0): listed by msolve where it can run
    (:func:`with_modes_from_msolve`), otherwise — or where msolve failed — by
    ``alternative`` (modes ↦ modes with another plan's, and whether that settles them:
    :func:`with_coincident_modes`, :func:`with_modes_of_coincident_joints`). Returns the
    modes, whether msolve listed them, and what neither settled (one sentence each; a
    sentence with "movable" where msolve found a continuum, which no plan would see)."""
    found, by_msolve, unsettled = with_modes_from_msolve(scene, plan, pairs, modes)
    if (by_msolve and not unsettled) or any("movable" in gap for gap in unsettled):
        return found, by_msolve, unsettled
    found, covered = alternative(found)
    if covered:
        return found, False, ()
    return found, by_msolve, unsettled or unexamined_coincidences(pairs)


def division_pairs(scene: Scene, plan: Plan) -> tuple[set[frozenset[str]], set[frozenset[str]]]:
    """The joint pairs ``plan`` divides by that can coincide: its bases and reference whose
    distance is not known (:func:`computed_base_pairs`; parameters included for coupling
    2), and its parameters' own joints. A slider joint's pairs are left out: a step with a
    slider is a limit construction, which divides by no squared distance of it
    (closure/sliders.py). O(steps · known distances)."""
    sliders = {slider.joint for slider in scene.sliders}
    bases = {pair for pair in computed_base_pairs(scene, plan, with_parameters=plan.number_of_parameters == 2)
             if not pair & sliders}
    parameters = {frozenset(pair) for pair in plan.parameters
                  if not set(pair) & sliders and coincidence_possible(scene, frozenset(pair))}
    return bases, parameters


def with_modes_where_plan_divides_by_zero(scene: Scene, plan: Plan, modes: tuple[AssemblyMode, ...],
                                          solver: Callable[[Plan], Solution] | None
                                          ) -> tuple[tuple[AssemblyMode, ...], bool, tuple[str, ...]]:
    """``modes`` and the modes where two joints that ``plan`` divides by coincide: its
    bases and reference whose distance is not known (:func:`computed_base_pairs`), and its
    parameters' own joints (s = 0, where the first bilateration that uses a parameter as
    its base is undefined). Both backends call this with ``solver`` their own solve with
    another plan.

    The parameter's own coincidence is never a root of the characteristic polynomial
    that the plan could decide: clearing the denominators s_{i,j} of eq. 2.7 can remove
    the factor s altogether (issue 25's 7/N2, small-box 30 of seed 36: four of its eight
    modes have P1 = P8, s1,8 = 0, and the exact backend had certified the other four).

    Listed by msolve where it can run, otherwise by ``solver`` (:func:`with_modes_where_undefined`;
    None: no other plan, as for a slider chain, whose other plans are not slider plans);
    returns the modes, whether msolve listed them and what neither settled."""
    two = plan.number_of_parameters == 2
    bases, parameters = division_pairs(scene, plan)
    axes = parallel_axis_pairs(scene, plan)
    if axes:  # only msolve lists these: no other plan is a slider plan
        modes, parallel_by_msolve, parallel_gaps = with_modes_from_msolve(scene, plan, (), modes, axes)
        if not parallel_by_msolve:
            parallel_gaps = tuple(f"the axes of {' and '.join(sorted(pair))} may be parallel, where the plan "
                                  "divides by 0: modes there are not examined (msolve cannot run)"
                                  for pair in sorted(axes, key=sorted))
    else:
        parallel_by_msolve, parallel_gaps = False, ()
    if not bases | parameters:
        return modes, parallel_by_msolve, parallel_gaps

    def alternative(found: tuple[AssemblyMode, ...]) -> tuple[tuple[AssemblyMode, ...], bool]:
        if solver is None:
            return found, False
        if two:  # along curves of the plane, not at one value (9/N27: v = 0)
            return with_modes_of_coincident_joints(scene, plan, parameters | bases, found, solver)
        covered = True
        if parameters:  # at s = 0 only
            found, covered = with_coincident_modes(scene, plan, parameters, [0.0], found, solver)
        if bases:
            found, settled = with_modes_of_coincident_joints(scene, plan, bases, found, solver)
            covered = covered and settled
        return found, covered

    found, by_msolve, unsettled = with_modes_where_undefined(scene, plan, bases | parameters, modes, alternative)
    return found, by_msolve or parallel_by_msolve, unsettled + parallel_gaps


def parallel_axis_pairs(scene: Scene, plan: Plan) -> set[frozenset[str]]:
    """The pairs of sliders on no common link whose axes ``plan`` crosses: the base of a
    step located from two sliders (closure/sliders.py: point_on_two_axes). Where the two
    axes are parallel the plan divides by 0, and its modes there are missed: a 7/N2 chain
    with sliders P3, P6, P8, P9 had two of its four modes with the axes of P3 and P9
    parallel, which both backends missed, the exact one certified. (Two sliders of one
    link keep the angle the link fixes between them; axes fixed parallel in a link make
    the plan undefined everywhere: :func:`slider_plan_undefined`.) O(steps + links)."""
    sliders = {slider.joint for slider in scene.sliders}
    shared = {frozenset(pair) for link in scene.links for pair in combinations(link.joints, 2)}
    return {frozenset(step.base) for step in plan.steps if set(step.base) <= sliders} - shared


def unexamined_coincidences(pairs: set[frozenset[str]]) -> tuple[str, ...]:
    """The gaps for ``pairs`` whose coincidences neither msolve nor another plan settled."""
    return tuple(f"joints {'='.join(sorted(pair))} (a bilateration base) may coincide: modes where they do "
                 "are not examined" for pair in sorted(pairs, key=sorted))


def _squared_distance(mode: AssemblyMode, u: str, v: str) -> float:
    (xu, yu), (xv, yv) = mode.joints[u], mode.joints[v]
    return (xu - xv) ** 2 + (yu - yv) ** 2
