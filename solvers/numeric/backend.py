"""Numeric backend: every assembly mode of a scene over all free-sign branches, in stages
(:func:`solve_numeric`):

1. *compile*: the best plan (a bounded one for a slider chain), its straight-line program;
2. *prune and certify* (:func:`_certified`): the plan's program on intervals decides the
   searched domain of every branch — one evaluation a branch for coupling degree 0, the
   interval branch-and-prune over one or two parameters for coupling 1 and 2
   (:mod:`~baranov.solvers.numeric.branch_and_prune`,
   :mod:`~baranov.solvers.numeric.branch_and_prune_plane`); where it decides everything,
   its modes are the answer and the certificate says what is proven;
3. *resolve what is left* (:func:`_searched`): on the branches with an undecided box
   only, the sampling searches (thesis §3.2–3.3: "the roots can be quickly obtained for
   the combinations of signs ... using a standard numerical procedure";
   :mod:`~baranov.solvers.numeric.one_parameter`,
   :mod:`~baranov.solvers.numeric.two_parameter`, points where Newton stalls next to the
   domain boundary polished on the link constraints, :mod:`baranov.solvers.polish`);
4. *read back and verify*: every candidate, certified or searched, becomes a
   configuration placed from the ground link, kept only if every link dimension holds
   (relative residual below ``1e-8``) and no rigid link is mirrored; modes found on
   several branches are reported once; then the modes where joints the plan divides by
   coincide, and (without sliders) clusters merged and near misses dropped.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from baranov.closure import CompiledSystem, distinct_branches
from baranov.closure.interval_program import EDGE, FEASIBLE, evaluate_boxes, interval_program
from baranov.closure.traced_sliders import exact_slider_constants
from baranov.planner import Plan, parameter_name
from baranov.scene import Scene

from ..candidates import assembly_modes
from ..coincidence import (
    NoPlanError,
    bounded_slider_plan,
    modes_without_plan,
    solvable_plan,
    with_modes_where_plan_divides_by_zero,
)
from ..mode_clusters import merged_clusters
from ..modes import AssemblyMode, Certificate, MovableLinkageError, Solution, SolverError, signs_text
from ..placement import NEARLY_FLAT, compile_scene, placed_from_ground, polished_mode, read_back, slider_geometry
from ..polish import polish_configurations, polish_on_constraints
from ..verification import RESIDUAL_TOLERANCE, distance_bound, placement_residuals
from .branch_and_prune import (
    AT_COINCIDENCE,
    REASONS,
    UNBOUNDED_REACH,
    PrunedRoots,
    evaluation_budget,
    instance_inputs,
    prune_one_parameter,
    searched_box,
    slider_searched_domain,
    unbounded_slider_domain,
)
from .branch_and_prune_plane import prune_two_parameters
from .one_parameter import critical_values, one_parameter_roots, roots_at_critical_values
from .two_parameter import ridge_roots, shared_curve, two_parameter_roots


def solve_numeric(scene: Scene, plan: Plan | None = None, samples: int = 4000, *,
                  coincidences: bool = True, time_limit: float | None = None) -> Solution:
    """All assembly modes of ``scene`` (coupling degree 0, 1 or 2) by the numeric method.
    ``coincidences=False`` skips the modes where the parameter's joints coincide (solved
    with another plan, :mod:`baranov.solvers.coincidence`; used by that solve itself).
    ``time_limit`` (seconds): once it has passed, the branches (coupling 1) or the cells
    of the parameter plane (coupling 2) not yet searched are left, and the solution's
    ``undecided`` names them; the modes found are verified as always."""
    try:
        plan = plan or bounded_slider_plan(scene, solvable_plan(scene))
    except NoPlanError as error:  # no plan is defined: msolve's modes, verified
        described, modes, certificate = modes_without_plan(scene, error)
        return Solution.of_plan("numeric", scene, described, modes, certificate=certificate)
    compiled = compile_scene(scene, plan)
    # a slider chain's distinct branches only: where no construction reads a sign, both place alike
    rows = distinct_branches(plan, [slider.joint for slider in scene.sliders])
    branches = np.array(rows, dtype=int).reshape(len(rows), len(plan.free_sign_triangles))
    degree = plan.number_of_parameters
    if time_limit is not None and not time_limit >= 0:
        raise SolverError(f"time_limit {time_limit}: must be a number of seconds, 0 or more")
    deadline = time.monotonic() + time_limit if time_limit is not None else math.inf
    if degree > 2:
        raise SolverError(f"coupling degree {degree}: the numeric method solves coupling degrees 0 to 2; "
                          "--method homotopy solves any (docs/homotopy.md)")
    # prune and certify; then the searches resolve the branches left, and every
    # candidate is read back and verified (docs/numeric.md)
    certified, certificate, searched = _certified(scene, plan, compiled, branches, deadline)
    if certificate.complete:
        return Solution.of_plan("numeric", scene, plan, certified, certificate=certificate)
    candidates, polished, undecided = _searched(scene, plan, compiled, searched, samples, deadline) \
        if len(searched) else ([], None, [])
    candidates += _candidates_of(compiled, certified)
    modes = assembly_modes(scene, compiled, candidates, polished)
    if degree > 0 and coincidences:
        modes, unsettled = _modes_of_coincident_joints(scene, plan, samples, modes)
        undecided += unsettled
    if scene.sliders:  # no clusters merged nor near misses filtered on slider chains yet (docs/sliders.md)
        return Solution.of_plan("numeric", scene, plan, modes, undecided=tuple(undecided), certificate=certificate)
    modes, valleys = merged_clusters(scene, compiled, modes)  # after the coincidences: they may be the mode
    modes, near_misses = _without_near_misses(scene, compiled, modes)
    return Solution.of_plan("numeric", scene, plan, modes, undecided=tuple(undecided) + valleys + near_misses,
                            certificate=certificate)


def _certified(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray, deadline: float
               ) -> tuple[tuple[AssemblyMode, ...], Certificate, np.ndarray]:
    """The interval stage, by the plan's coupling degree (0: one evaluation a branch; 1
    and 2: branch-and-prune): the modes it certified, its certificate, and the branches
    it left to the searches."""
    if plan.number_of_parameters == 0:
        modes, certificate = _certified_construction(scene, compiled, branches)
        return modes, certificate, branches[:0] if certificate.complete else branches
    if plan.number_of_parameters == 1:
        return _certified_modes(scene, plan, compiled, branches, deadline)
    return _certified_plane(scene, plan, compiled, branches, deadline)


def _searched(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray, samples: int,
              deadline: float) -> tuple[list, tuple | None, list[str]]:
    """The search stage on ``branches`` (those the interval stage left), by the coupling
    degree: candidate roots, configurations to polish on the link constraints (or None),
    and what was left unsearched (time limit, too many cells)."""
    undecided: list[str] = []
    if plan.number_of_parameters == 0:
        return [(np.zeros(0), branch) for branch in branches], None, undecided
    if plan.number_of_parameters == 1:
        candidates, near = one_parameter_roots(compiled, branches, _upper_bounds(scene, plan, compiled)[0], samples,
                                                undecided, deadline)
        polished = None
        if near:  # a root where f is not smooth (a singular mode): polished on the links, then verified
            polished = _polished(scene, compiled, np.array([v for v, _ in near]), np.array([b for _, b in near]))
        return candidates + roots_at_critical_values(compiled, branches, critical_values(scene, plan)), polished, undecided
    upper = _upper_bounds(scene, plan, compiled)
    candidates, (stalled, stalled_branches), (unsearched, reason) = two_parameter_roots(compiled, branches, upper,
                                                                                       deadline)
    candidates += ridge_roots(compiled, branches, upper)
    _require_no_shared_curve(scene, compiled, branches, candidates)
    polished = _polished(scene, compiled, stalled, branches[stalled_branches])
    return candidates, polished, _unsearched_cells(compiled, branches, unsearched, reason)


def _candidates_of(compiled: CompiledSystem, modes: tuple[AssemblyMode, ...]) -> list[tuple[np.ndarray, np.ndarray]]:
    """Modes (certified roots, verified) as candidates beside the searches' own (their
    parameters as searched: a slider's t through its map)."""
    return [(compiled.searched_values(np.array([mode.parameters[name] for name in compiled.parameter_names])),
             np.array(mode.signs)) for mode in modes]


#: Box evaluations allowed to the two-parameter branch-and-prune on each branch (about
#: 15 µs each): on 24 random coupling-2 nine-link instances, 3000 decided 13, 6000
#: decided 18, 12 000 decided 22 at the same median solve (docs/numeric.md).
PLANE_BUDGET = 12_000
#: The same for slider chains: on 15 random nine-link coupling-2 slider chains (seeds 1
#: and 2), 3000 certified 8 at a mean solve of 0.63 s against 0.93 s by the sampling
#: searches alone; 12 000 made the undecided ones slower (docs/numeric.md).
SLIDER_PLANE_BUDGET = 3000


#: Seconds one box evaluation of the branch-and-prune takes at most, about (7/B1: 6 µs;
#: 11 links, 64 branches: more): what a time limit allows is counted in evaluations.
SECONDS_PER_BOX = 20e-6


def _certified_modes(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray,
                     deadline: float = math.inf) -> tuple[tuple[AssemblyMode, ...], Certificate, np.ndarray]:
    """A coupling-1 plan's modes by interval branch-and-prune
    (:mod:`~baranov.solvers.numeric.branch_and_prune`), each certified root read back,
    polished and verified; the certificate: complete where every box of the domain
    was decided and every certified root verified as a distinct mode, else its gaps say
    which boxes are left to the searches; and the branches left to the searches: those
    with an undecided box (all of them where the branch-and-prune did not run or a root
    did not verify). Before ``deadline`` (time.monotonic()), in as many evaluations as fit."""
    inputs = _pruning_inputs(scene, plan, compiled, branches, deadline)
    if inputs.reason:
        return (), Certificate(False, None, (inputs.reason,)), branches
    searched = inputs.branches
    pruned = prune_one_parameter(compiled, searched, inputs.box[0], scene.known,
                                 budget=int(min(evaluation_budget(len(searched)), inputs.remaining / SECONDS_PER_BOX)),
                                 slider_values=inputs.slider_values, reference=inputs.reference[0])
    modes, certificate = modes_of_pruned(scene, compiled, searched, pruned)
    left = _branches_left(branches, searched, modes, pruned, branch_column=2)
    return modes, _within_reach(certificate, inputs, compiled.parameter_names), left


@dataclass(frozen=True)
class _PruningInputs:
    """What a branch-and-prune of either kind runs on (:func:`_pruning_inputs`)."""

    box: tuple  # one interval per parameter, as the program takes it (a slider's t)
    reference: tuple  # the intervals its smallest widths are relative to
    slider_values: list  # the exact numbers of the slider geometry (none without sliders)
    branches: np.ndarray  # the branches to search (a slider chain's distinct ones)
    reason: str = ""  # why it cannot run
    unbounded: tuple[int, ...] = ()  # the parameters no path of link dimensions bounds (UNBOUNDED_REACH)
    remaining: float = math.inf  # seconds left before the deadline


def _pruning_inputs(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray,
                    deadline: float) -> _PruningInputs:
    """What a branch-and-prune of either kind runs on, before ``deadline``."""
    if scene.sliders:
        inputs = _slider_inputs(scene, plan, compiled, branches)
    else:
        box = searched_box(scene, plan)
        inputs = _PruningInputs(box, box, [], branches)
    remaining = deadline - time.monotonic()
    if not inputs.reason and remaining <= 0:
        return replace(inputs, remaining=remaining, reason="the time limit passed before the branch-and-prune ran")
    return replace(inputs, remaining=remaining)


def _within_reach(certificate: Certificate, inputs: _PruningInputs, names: tuple[str, ...]) -> Certificate:
    """A branch-and-prune's certificate where some parameters had no bound: not complete,
    and a last gap says how far out they were searched (:data:`UNBOUNDED_REACH`)."""
    if not inputs.unbounded:
        return certificate
    searched = ", ".join(f"{names[n]} in [{inputs.box[n][0]:.6g}, {inputs.box[n][1]:.6g}]" for n in inputs.unbounded)
    sentence = (f"no path of link dimensions bounds {', '.join(names[n] for n in inputs.unbounded)}: the "
                f"branch-and-prune searched {searched} ({UNBOUNDED_REACH:g} times the linkage's size); a mode "
                "beyond is not excluded (the sampling searches look there only on the branches left to them)")
    return Certificate(False, certificate.probabilistic, (*certificate.gaps, sentence), certificate.proof)


def _branches_left(branches: np.ndarray, searched: np.ndarray, modes: tuple, pruned: PrunedRoots,
                   branch_column: int) -> np.ndarray:
    """The branches a branch-and-prune over ``searched`` leaves to the searches: those with
    an undecided box (``pruned.unresolved``'s column ``branch_column`` holds the branch
    index), or all of ``branches`` where its certified roots did not verify as as many
    distinct ``modes``."""
    if len(modes) != len(pruned.roots):
        return branches
    searchable = pruned.unresolved[pruned.unresolved[:, -1] != AT_COINCIDENCE]  # below the searches' own floor
    return searched[np.unique(searchable[:, branch_column].astype(int))]


def _certified_plane(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray,
                     deadline: float = math.inf) -> tuple[tuple[AssemblyMode, ...], Certificate, np.ndarray]:
    """A coupling-2 plan's modes by the two-parameter interval branch-and-prune
    (:mod:`~baranov.solvers.numeric.branch_and_prune_plane`), each certified root read
    back, polished and verified; the certificate (complete where every box of the searched
    box was decided and every certified root verified as a distinct mode); and the
    branches left to the searches: those with an undecided box (all of them where the
    branch-and-prune did not run or a root did not verify)."""
    inputs = _pruning_inputs(scene, plan, compiled, branches, deadline)
    if inputs.reason:
        return (), Certificate(False, None, (inputs.reason,)), branches
    searched = inputs.branches
    budget = SLIDER_PLANE_BUDGET if scene.sliders else PLANE_BUDGET
    pruned = prune_two_parameters(compiled, searched, inputs.box, scene.known, slider_values=inputs.slider_values,
                                  budget=int(min(budget, inputs.remaining / SECONDS_PER_BOX / len(searched))),
                                  reference=inputs.reference)
    candidates = [(_searched_values(compiled, 0.5 * (row[0:2] + row[2:4])), searched[int(row[4])])
                  for row in pruned.roots]
    modes = assembly_modes(scene, compiled, candidates, distinct=True)
    certificate = _within_reach(_plane_certificate(compiled, searched, pruned, modes), inputs,
                                compiled.parameter_names)
    return modes, certificate, _branches_left(branches, searched, modes, pruned, branch_column=4)


def _plane_certificate(compiled: CompiledSystem, searched: np.ndarray, pruned: PrunedRoots,
                       modes: tuple[AssemblyMode, ...]) -> Certificate:
    """The certificate of a two-parameter branch-and-prune over the branches ``searched``
    whose certified roots verified as ``modes``: complete where every box was decided and
    every root verified as a distinct mode; else its gaps name the undecided boxes."""
    (low_s, high_s), (low_t, high_t) = pruned.domain
    where = f"({', '.join(compiled.parameter_names)}) in [{low_s:.6g}, {high_s:.6g}] × [{low_t:.6g}, {high_t:.6g}]"
    if len(modes) != len(pruned.roots):
        return Certificate(False, None, (f"{len(pruned.roots)} roots certified, {len(modes)} verified as "
                                         "distinct modes: every branch searched by sampling",))
    if len(pruned.unresolved):
        return Certificate(False, None, (*_plane_gaps(compiled, searched, pruned.unresolved),
                                         f"interval branch-and-prune of {where}: these boxes are not decided; "
                                         + _what_follows(pruned.unresolved)))
    proof = (f"interval branch-and-prune of {where}, {len(searched)} branches: each root alone in its box "
             f"(Krawczyk), the rest excluded; {pruned.evaluations} boxes")
    return Certificate(True, None, (), proof)


def _what_follows(unresolved: np.ndarray) -> str:
    """What becomes of a branch-and-prune's undecided boxes (rows ending in their reason):
    the sampling searches take their branches, except where every box is at a squared
    distance's 0 (below where the searches sample)."""
    if np.all(unresolved[:, -1] == AT_COINCIDENCE):
        return ("every other box is decided; no search samples that close to 0, and the modes where those joints "
                "coincide come from another plan")
    return "the modes on their branches come from the sampling searches"


def _plane_gaps(compiled: CompiledSystem, branches: np.ndarray, unresolved: np.ndarray) -> tuple[str, ...]:
    """One sentence for each reason the two-parameter branch-and-prune left boxes
    undecided (``unresolved`` rows: lower ends, upper ends, branch index, reason): how
    many, on which branches, within which bounding box."""
    names = " × ".join(compiled.parameter_names)
    sentences = []
    for why in sorted(REASONS):
        boxes = unresolved[unresolved[:, 5] == why]
        if not len(boxes):
            continue
        low, high = boxes[:, 0:2].min(axis=0), boxes[:, 2:4].max(axis=0)
        counts = ", ".join(f"{signs_text(branches[k])} {int((boxes[:, 4] == k).sum())}"
                           for k in np.unique(boxes[:, 4].astype(int)))
        sentences.append(f"{len(boxes)} boxes of {names} in [{low[0]:.6g}, {high[0]:.6g}] × [{low[1]:.6g}, "
                         f"{high[1]:.6g}] undecided on branches {counts}: {REASONS[why]}")
    return tuple(sentences)


def _slider_inputs(scene: Scene, plan: Plan, compiled: CompiledSystem, branches: np.ndarray) -> _PruningInputs:
    """For a slider chain's branch-and-prune: the searched domain of each parameter (out
    to UNBOUNDED_REACH times the linkage's size where no path of link dimensions bounds
    it), the exact numbers of its slider geometry, and why it cannot run: a slider frame
    that is irrational in world units (its numbers then have no exact enclosure here)."""
    box, reference, unbounded = [], [], []
    for index in range(plan.number_of_parameters):
        domain = widths_of = slider_searched_domain(scene, plan, compiled.searched, index)
        if domain is None:
            unbounded.append(index)
            domain, widths_of = unbounded_slider_domain(scene, plan, compiled.searched, index)
        box.append(domain)
        reference.append(widths_of)
    exact = exact_slider_constants(compiled.straight_line_program().slider_constants,
                                   slider_geometry(scene, number=lambda pair: pair), compiled.sliders)
    reason = "" if exact is not None else ("a slider frame is irrational in world units: its numbers are not "
                                           "enclosed exactly, so the interval branch-and-prune does not run")
    return _PruningInputs(tuple(box), tuple(reference), exact or [], branches, reason, tuple(unbounded))


def _searched_values(compiled: CompiledSystem, values: np.ndarray) -> np.ndarray:
    """The parameters' values as the program takes them (a slider's t) back to their
    searched values (what the compiled system's residuals and the read-back take)."""
    mapped = []
    for pair, value in zip(compiled.parameters, values, strict=True):
        mapping = compiled.searched.get(frozenset(pair))
        mapped.append(float(value) if mapping is None else float(mapping.searched(value)))
    return np.array(mapped)


def modes_of_pruned(scene: Scene, compiled: CompiledSystem, branches: np.ndarray,
                    pruned: PrunedRoots) -> tuple[tuple[AssemblyMode, ...], Certificate]:
    """The modes of a coupling-1 plan's certified roots (``pruned``), each read back,
    polished and verified, and the certificate: complete where every box of the domain
    was decided and every certified root verified as a distinct mode; else its gaps name
    the boxes left to the searches."""
    candidates = [(_searched_values(compiled, np.array([0.5 * (low + high)])), branches[int(k)])
                  for low, high, k in pruned.roots]
    modes = assembly_modes(scene, compiled, candidates, distinct=True)
    name = compiled.parameter_names[0]
    gaps = tuple(f"{name} in [{low:.10g}, {high:.10g}] on branch {signs_text(branches[int(k)])}: {REASONS[int(why)]}"
                 for low, high, k, why in pruned.unresolved)
    if gaps:
        return modes, Certificate(False, None, (*gaps, "these boxes are not decided by the branch-and-prune: "
                                                + _what_follows(pruned.unresolved)))
    return modes, certificate_of_pruned(compiled, branches, pruned, modes)


def certificate_of_pruned(compiled: CompiledSystem, branches: np.ndarray, pruned: PrunedRoots,
                          modes: tuple[AssemblyMode, ...]) -> Certificate:
    """The certificate of a branch-and-prune that decided every box (``pruned``) and of
    the ``modes`` verified from its roots: complete where each root verified as a mode."""
    if len(modes) != len(pruned.roots):
        return Certificate(False, None, (f"{len(pruned.roots)} roots certified, {len(modes)} verified as "
                                         "distinct modes",))
    low, high = pruned.domain
    proof = (f"interval branch-and-prune of {compiled.parameter_names[0]} in [{low:.6g}, {high:.6g}], "
             f"{len(branches)} branches: each root alone in its box, the rest excluded; {pruned.evaluations} boxes")
    return Certificate(True, None, (), proof)


def _certified_construction(scene: Scene, compiled: CompiledSystem, branches: np.ndarray
                            ) -> tuple[tuple[AssemblyMode, ...], Certificate]:
    """A plan without parameters (a construction: coupling degree 0) on every branch,
    evaluated once in interval arithmetic from the exact dimensions
    (:func:`~baranov.closure.interval_program.evaluate_boxes` on an empty box): a branch
    with a radicand certainly negative has no mode, one with every radicand certainly
    positive has exactly one, read back and verified. Complete where no radicand's
    interval holds 0 (a flat triangle) and every such mode verifies."""
    if scene.sliders:
        return (), Certificate(False, None, ("slider chains are not yet run through the interval program",))
    program = compiled.straight_line_program()
    empty = np.zeros((len(branches), 0))
    inputs = instance_inputs(program, scene.known, compiled.fixed_signs)
    _, _, status = evaluate_boxes(interval_program(program), *inputs, empty, empty, branches)
    if (status == EDGE).any() or len(program.residual_registers):
        return (), Certificate(False, None, ("a triangle of the construction may be flat: the interval evaluation "
                                             "decides no mode on that branch",))
    proper = branches[status == FEASIBLE]
    modes = assembly_modes(scene, compiled, [(np.zeros(0), branch) for branch in proper], distinct=True)
    if len(modes) != len(proper):
        return modes, Certificate(False, None, (f"{len(proper)} branches proper, {len(modes)} verified as modes",))
    proof = (f"the construction evaluated in interval arithmetic on each of its {len(branches)} branches: every "
             f"triangle proper on {len(proper)}, one that cannot exist on the others")
    return modes, Certificate(True, None, (), proof)


def _upper_bounds(scene: Scene, plan: Plan, compiled: CompiledSystem) -> tuple[float, ...]:
    """The upper end of each parameter's searched range: the squared sum of the link
    diameters for one parameter, the squared shortest path of link dimensions between
    its joints for two (:meth:`Scene.largest_distance`); with sliders, that path, or the
    map of a slider's t or an unbounded parameter (:class:`SearchedParameter`)."""
    if plan.number_of_parameters == 1 and not scene.sliders:
        return (distance_bound(scene) ** 2,)
    return tuple(compiled.search_bound(n, scene.largest_distance(u, v) ** 2) for n, (u, v) in enumerate(plan.parameters))


#: A verified mode whose residual stays above this after NEAR_MISS_STEPS polishing steps
#: is a near miss, not a mode (:func:`_without_near_misses`).
NEAR_MISS = 1e-11
NEAR_MISS_STEPS = 200


def _without_near_misses(scene: Scene, compiled: CompiledSystem,
                         modes: tuple[AssemblyMode, ...]) -> tuple[tuple[AssemblyMode, ...], tuple[str, ...]]:
    """``modes`` without the near misses, and one sentence for each: a configuration
    that verifies to RESIDUAL_TOLERANCE but that Gauss–Newton on the link constraints
    cannot bring below NEAR_MISS. A real root, simple or multiple, polishes to rounding
    (1e-16 to 1e-15 measured); a minimum of |f| just above 0 — two complex roots with a
    small imaginary part, next to where the dimensions were drawn at a double root — stays
    where it is (issue 25: 9/N8 drawn at a double root, a "mode" at s1,11 = 10.1709 with
    residual 6.3e-9 after 200 steps, which msolve and the exact backend do not list).
    Floating point cannot tell such a pair from a real double root; the sentence says so,
    and the exact backend decides."""
    kept, sentences = [], []
    for mode in modes:
        if mode.max_residual > NEAR_MISS:
            polished = polished_mode(scene, compiled, mode, NEAR_MISS_STEPS)
            if polished.max_residual > NEAR_MISS:
                values = ", ".join(f"{name} ≈ {value:.6g}" for name, value in mode.parameters.items())
                sentences.append(f"{values} on branch {signs_text(mode.signs)}: a configuration within "
                                 f"{polished.max_residual:.1e} of closing that polishing does not close: a minimum "
                                 "of the closure condition just above 0 (two complex roots) or a real double root, "
                                 "which floating point cannot tell apart; not listed as a mode (the exact backend "
                                 "decides)")
                continue
        kept.append(mode)
    return tuple(kept), tuple(sentences)


def _require_no_shared_curve(scene: Scene, compiled: CompiledSystem, branches: np.ndarray, candidates) -> None:
    """Raise :class:`MovableLinkageError` where the two closure conditions share a curve
    (:func:`~baranov.solvers.numeric.two_parameter.shared_curve`) whose points are
    distinct, verified real configurations: the linkage moves."""
    found = shared_curve(compiled, branches, candidates)
    if found is None:
        return
    path, branch = found
    moving = assembly_modes(scene, compiled, [(point, branch) for point in path])
    if len(moving) < len(path):
        return
    names = [parameter_name(pair) for pair in compiled.parameters]
    low, high = path.min(axis=0), path.max(axis=0)
    where = ", ".join(f"{name} from {a:.6g} to {b:.6g}" for name, a, b in zip(names, low, high, strict=True))
    raise MovableLinkageError(
        f"the linkage moves with these dimensions: both closure conditions vanish along a curve ({where}, "
        f"signs {signs_text(branch)}) whose points are {len(path)} distinct verified configurations, "
        "a continuum rather than isolated assembly modes")


def _unsearched_cells(compiled: CompiledSystem, branches: np.ndarray, cells, reason: str) -> list[str]:
    """One sentence per branch with cells of the √ plane left unsearched (by the time
    limit, or a level with too many suspect cells: ``reason``): their bounding box in the
    parameters."""
    names = " × ".join(parameter_name(pair) for pair in compiled.parameters)
    sentences = []
    for b in np.unique(cells.branch):
        mine = cells.branch == b
        low, high = cells.low[mine].min(axis=0) ** 2, cells.high[mine].max(axis=0) ** 2
        sentences.append(f"{names} in [{low[0]:.6g}, {high[0]:.6g}] × [{low[1]:.6g}, {high[1]:.6g}] on branch "
                         f"{signs_text(branches[b])}: {int(mine.sum())} cells not searched: {reason}")
    return sentences


def _modes_of_coincident_joints(scene: Scene, plan: Plan, samples: int, modes: tuple[AssemblyMode, ...]
                                ) -> tuple[tuple[AssemblyMode, ...], list[str]]:
    """``modes`` and the modes where joints the plan divides by coincide, and what neither
    msolve nor another plan settled
    (:func:`~baranov.solvers.coincidence.with_modes_where_plan_divides_by_zero`: msolve
    with an exact scene, else another plan, which can itself be undefined elsewhere —
    issue 25: 9/N3, 9/N5 missed 2-4 modes so; msolve only for a slider chain, whose other
    plans are not slider plans: a 7/N3 chain drawn with P9 on P1 had four of its six modes
    at s1,9 = 0); a continuum there raises :class:`MovableLinkageError`."""
    solver = None if scene.sliders else (lambda other: solve_numeric(scene, other, samples, coincidences=False))
    modes, _, unsettled = with_modes_where_plan_divides_by_zero(scene, plan, modes, solver)
    movable = [gap for gap in unsettled if "movable" in gap]
    if movable:
        raise MovableLinkageError(movable[0])
    return modes, list(unsettled)


#: Full Gauss–Newton steps (:func:`_polished_on_links`) where the monotone ones stall.
SINGULAR_POLISH_STEPS = 60
#: The full steps are taken in rounds of this many; after each, a configuration goes on
#: only while its residual is below SINGULAR_NEAR or fell tenfold in the round.
SINGULAR_ROUND = 10
SINGULAR_NEAR = 1e-6
#: Gauss–Newton steps on the rigid-link model after the polish on the link dimensions.
RIGID_POLISH_STEPS = 5


def _polished_on_links(scene: Scene, joints: list[str], points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`polish_configurations`, then, where it stalled above RESIDUAL_TOLERANCE,
    SINGULAR_POLISH_STEPS full steps (``monotone=False``) from where it stopped, kept
    where they end lower. At a singular mode Gauss–Newton converges only linearly and
    its steps need not lower the largest residual, so the monotone steps stop early: a
    mode drawn at a double root on the domain's edge, a flat triangle of the plan and a
    condition vanishing all along that edge, stalled at 7e-8 from a start 1.4e-3 away in
    the parameter, and full steps reached 1.5e-13 in 30 (issue 25, seed 35: 9/N27
    (s1,10, s1,11) = (4, 1), 9/N28 (s1,9, s1,11) = (5, 29)).

    The full steps go in rounds of SINGULAR_ROUND; a configuration stays while it is near
    a mode (residual below SINGULAR_NEAR) or still converging (its residual fell tenfold
    in the round: even linear convergence at a singular mode, the error halved per step,
    divides the residual by 4^10 in a round). Issue 25's 9/N2 domain-edge 13 (seed 43)
    polished 116 589 boundary samples and Newton points: 97 204 stalled between 1e-3 and
    1, and 60 full steps for all of them took 96 of the solve's 118 s."""
    points, residual = polish_configurations(scene, joints, points)
    stalled = np.flatnonzero(residual >= RESIDUAL_TOLERANCE)
    current, current_residual = points[stalled], residual[stalled]
    for _ in range(SINGULAR_POLISH_STEPS // SINGULAR_ROUND):
        if not stalled.size:
            break
        current, after = polish_configurations(scene, joints, current, SINGULAR_ROUND, monotone=False)
        lower = after < residual[stalled]
        points[stalled[lower]], residual[stalled[lower]] = current[lower], after[lower]
        going = (after >= RESIDUAL_TOLERANCE) & ((after < SINGULAR_NEAR) | (after < 0.1 * current_residual))
        stalled, current, current_residual = stalled[going], current[going], after[going]
    return points, residual


def _distinct_configurations(scene: Scene, points: np.ndarray) -> np.ndarray:
    """``points`` (complex (K, J)) without the rows equal to an earlier one to 1e-9 of the
    linkage's size: many starts (boundary samples of neighbouring cells) polish onto the
    same mode, and polishing it again and verifying it once per start only costs time
    (9-link slider chain, seed 1's second of coupling 2: 806 polished onto one mode)."""
    if len(points) < 2:
        return points
    grain = 1e-9 * distance_bound(scene)
    keys = np.round(np.concatenate([points.real, points.imag], axis=1) / grain)
    _, first = np.unique(keys, axis=0, return_index=True)
    return points[np.sort(first)]


def _polished(scene: Scene, compiled: CompiledSystem, values: np.ndarray, signs: np.ndarray):
    """Configurations ``(joints, points (K, J) complex, parameters, branches)`` from
    approximate roots, polished on the link constraints (:func:`polish_configurations`),
    their parameters and branches read back; for :func:`assembly_modes`, which verifies
    them as they are."""
    if len(values) == 0:
        return None
    placed = placed_from_ground(scene, compiled.paired_matrices(values, signs))
    joints = sorted(placed)
    if not joints:
        return None
    complex_points = np.stack([placed[j] for j in joints], axis=1)
    usable = np.isfinite(complex_points).all(axis=1)
    if scene.sliders:  # every constraint, sliders included (solvers/polish.py)
        points, residual = polish_on_constraints(scene, joints, complex_points[usable])
    else:
        points, residual = _polished_on_links(scene, joints, np.stack([complex_points.real, complex_points.imag],
                                                                       axis=-1)[usable])
        points = points[..., 0] + 1j * points[..., 1]
    # the link dimensions cannot see a joint leave the line of a link with joints in line
    # (a cost of δ² only); the rigid-link model can: on issue 25's 9/N27 (seed 41, link L3
    # P8 P1 P7 in line) a mode polished on the dimensions alone stood 3e-7 from msolve's
    points, _ = polish_on_constraints(scene, joints, _distinct_configurations(scene, points[residual < RESIDUAL_TOLERANCE]),
                                      RIGID_POLISH_STEPS, model=placement_residuals)
    at = {j: points[:, n] for n, j in enumerate(joints)}
    parameters, branch = read_back(compiled, at, scene=scene)
    # at a double root on the domain's edge the polished joints are right to ~√ε only, a
    # flat triangle reads back ±1 and its radicand comes out negative: try it flat too
    # (tests/regressions/9-N28-double-root.json)
    _, flattened = read_back(compiled, at, NEARLY_FLAT, scene=scene)
    changed = (flattened != branch).any(axis=1)
    return (joints, np.concatenate([points, points[changed]]), np.concatenate([parameters, parameters[changed]]),
            np.concatenate([branch, flattened[changed]]))
