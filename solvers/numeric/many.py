"""Many instances of one coupling-1 plan solved together (issue 56, the batch API): one
branch-and-prune over the boxes of every instance side by side
(:func:`~baranov.solvers.numeric.branch_and_prune.prune_instances`), then each instance's
certified roots read back and verified as a single solve's
(:func:`~baranov.solvers.numeric.backend.modes_of_pruned`).

An instance whose boxes are not all decided, or whose certified roots do not all verify,
gets no solution here: :func:`~baranov.solvers.batch.solve_many` solves it alone, with
the searches a single solve falls back on. So a batch answers exactly as single solves
do (tests/test_batch.py), the certified instances at the cost of their boxes.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from baranov.closure import sign_branches
from baranov.closure.straight_line import run_program
from baranov.planner import Plan
from baranov.scene import Scene

from ..modes import Solution
from ..placement import compile_scene, mode_of, placed_from_ground
from ..verification import RESIDUAL_TOLERANCE, joint_residuals, sorted_modes
from .backend import certificate_of_pruned, modes_of_pruned
from .branch_and_prune import PrunedRoots, evaluation_budget, instance_inputs, prune_instances, searched_domain


def solve_certified_many(scenes: Sequence[Scene], plan: Plan) -> list[Solution | None]:
    """For each of ``scenes`` (instances of one linkage without sliders, ``plan`` of
    coupling degree 1), its numeric :class:`Solution` where the branch-and-prune certifies
    it complete, else None. Cost: the boxes of every instance, evaluated in rounds of
    boxes of any instances side by side; then one run of the plan's program over every
    certified root (the joints' positions) and one verification of them all."""
    if plan.number_of_parameters != 1 or any(scene.sliders for scene in scenes):
        raise ValueError("solve_certified_many: instances of a coupling-1 plan without sliders")
    branches = sign_branches(len(plan.free_sign_triangles))
    template = compile_scene(scenes[0], plan)
    program = template.straight_line_program()
    signs = [{t: scene.orientation(t) for t in program.fixed_triangles} for scene in scenes]
    pruned = prune_instances(program, branches, [instance_inputs(program, scene.known, fixed)
                                                 for scene, fixed in zip(scenes, signs, strict=True)],
                             [searched_domain(scene, plan) for scene in scenes], budget=evaluation_budget(len(branches)))
    decided = [n for n, roots in enumerate(pruned) if roots.complete]
    modes = _verified_modes([scenes[n] for n in decided], template, branches, [pruned[n] for n in decided],
                            [signs[n] for n in decided])
    solutions: list[Solution | None] = [None] * len(scenes)
    for n, found in zip(decided, modes, strict=True):
        if found is None:  # a root that did not verify at once: the single solve's read-back polishes it
            found, certificate = modes_of_pruned(scenes[n], compile_scene(scenes[n], plan), branches, pruned[n])
        else:
            certificate = certificate_of_pruned(template, branches, pruned[n], found)
        if certificate.complete:
            solutions[n] = Solution.of_plan("numeric", scenes[n], plan, found, certificate=certificate)
    return solutions


def _verified_modes(instances: Sequence[Scene], template, branches: np.ndarray, pruned: list[PrunedRoots],
                    signs: list[dict]) -> list[tuple | None]:
    """The modes of the certified roots of ``instances`` (their ``pruned`` roots and link
    signs ``signs``): every root's configuration computed by one run of
    the plan's program (each row with its instance's dimensions), placed from the ground
    link (every instance's), and verified on its instance; None for an instance with a
    root that does not verify as it is (which :func:`modes_of_pruned` then polishes)."""
    if not instances:
        return []
    program, scene = template.straight_line_program(), instances[0]
    rows = np.concatenate([roots.roots for roots in pruned])
    owner = np.repeat(np.arange(len(pruned)), [len(roots.roots) for roots in pruned])
    values = 0.5 * (rows[:, :1] + rows[:, 1:2])
    known = np.array([[float(instance.known[pair]) for pair in program.known_pairs] for instance in instances])
    fixed = np.array([[fixed[t] for t in program.fixed_triangles] for fixed in signs], float).reshape(len(instances), -1)
    *_, points = run_program(program, known[owner].reshape(len(rows), -1), fixed[owner], values,
                             branches[rows[:, 2].astype(int)].astype(float), paired=True, points=True)
    placed = placed_from_ground(scene, dict(zip(program.joints, points.T, strict=True)))  # the ground is every instance's
    joints = sorted(placed)
    configurations = np.stack([placed[j] for j in joints], axis=1)
    residual = joint_residuals(scene, joints, configurations, instances, owner)
    found: list[tuple | None] = []
    for index in range(len(instances)):
        mine = np.flatnonzero(owner == index)
        if (residual[mine] >= RESIDUAL_TOLERANCE).any():
            found.append(None)
            continue
        found.append(sorted_modes(mode_of(template, joints, values[k], branches[int(rows[k, 2])], configurations[k],
                                          residual[k]) for k in mine))
    return found
