"""Certified roots of coupling-1 closure conditions by interval branch-and-prune
(solvers/numeric/branch_and_prune.py, issue 56), against the exact backend (certified
real roots of the characteristic polynomial): where the branch-and-prune leaves no box
undecided, it certifies exactly as many roots as the exact backend lists modes, and every
exact mode's parameter lies in a certified box of its own branch."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from baranov.closure.evaluate import sign_branches
from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.numeric.branch_and_prune import (
    AT_EDGE,
    instance_inputs,
    parameter_domain,
    prune_instances,
    prune_one_parameter,
    searched_domain,
)
from baranov.solvers.placement import compile_scene
from baranov.solvers.verification import distance_bound

ROOT = Path(__file__).resolve().parents[1]
COUPLING_ONE = [(links, index) for links in (5, 7, 9) for index, chain in enumerate(baranov_trusses(links))
                if links < 9 or index % 3 == 0]


def _pruned(scene):
    plan = solvable_plan(scene)
    compiled = compile_scene(scene, plan)
    branches = sign_branches(len(plan.free_sign_triangles))
    domain = parameter_domain(scene, plan, distance_bound(scene) ** 2 * (1 + 1e-9))
    return plan, branches, prune_one_parameter(compiled, branches, domain, scene.known)


def _assert_same_as_exact(scene, plan, branches, pruned):
    exact = solve(scene, method="exact")
    assert exact.certificate.complete
    assert len(pruned.roots) == len(exact.assembly_modes)
    name = exact.parameters[0]
    for mode in exact.assembly_modes:
        value = mode.parameters[name]
        inside = [(low, high, k) for low, high, k in pruned.roots
                  if low - 1e-9 * abs(value) <= value <= high + 1e-9 * abs(value)]
        assert len(inside) == 1, (value, mode.signs)
        assert tuple(branches[int(inside[0][2])]) == tuple(mode.signs)


@pytest.mark.parametrize("example, modes", [("5-B1", 6), ("7-B1", 8), ("7-B2", 10), ("7-B3", 8)])
def test_the_examples_are_certified_complete(example, modes):
    """The pentad and thesis §3.3 (7/B1: 8 real roots of 14; 7/B2, 7/B3): every box
    decided, each certified box a few ulps wide."""
    scene = load_scene(ROOT / "examples" / f"{example}.json")
    plan, branches, pruned = _pruned(scene)
    assert pruned.complete and len(pruned.roots) == modes
    assert (pruned.roots[:, 1] - pruned.roots[:, 0] <= 1e-9 * pruned.roots[:, 1]).all()
    _assert_same_as_exact(scene, plan, branches, pruned)


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(COUPLING_ONE), st.integers(0, 2**32 - 1))
def test_random_coupling_one_instances_match_the_exact_backend(truss, seed):
    links, index = truss
    chain = baranov_trusses(links)[index]
    scene = scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(seed)))
    plan, branches, pruned = _pruned(scene)
    if plan.number_of_parameters != 1:
        return
    assert pruned.complete, pruned.unresolved
    _assert_same_as_exact(scene, plan, branches, pruned)


def test_a_mode_on_a_flat_triangle_is_left_undecided():
    """Thesis §5.1.3.1's double root T = 49, where both free-sign triangles are flat and
    the feasible domain is that one value: no box can be certified there, and the
    branch-and-prune names the box as a domain edge rather than deciding it."""
    scene = load_scene(ROOT / "examples" / "3-RPR-I.json")
    _, _, pruned = _pruned(scene)
    if pruned.complete:
        pytest.fail("3-RPR-I's mode at a flat triangle was decided")
    assert (pruned.unresolved[:, 3] == AT_EDGE).any()


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from([t for t in COUPLING_ONE if t[0] in (7, 9)]), st.integers(0, 2**32 - 1))
def test_instances_pruned_together_are_pruned_as_each_alone(truss, seed):
    """prune_instances over random instances of one truss (their boxes side by side in
    the same rounds) proves what prune_one_parameter proves of each: the same roots, boxes
    left undecided and number of evaluations."""
    links, index = truss
    rng = np.random.default_rng(seed)
    chain = baranov_trusses(links)[index]
    scenes = [scene_of(chain, generic_integer_configuration(chain, rng)) for _ in range(3)]
    plan = solvable_plan(scenes[0])
    if plan.number_of_parameters != 1:
        return
    branches = sign_branches(len(plan.free_sign_triangles))
    systems = [compile_scene(scene, plan) for scene in scenes]
    program = systems[0].straight_line_program()
    domains = [searched_domain(scene, plan) for scene in scenes]
    together = prune_instances(program, branches, [instance_inputs(program, scene.known, system.fixed_signs)
                                                   for scene, system in zip(scenes, systems, strict=True)], domains)
    for scene, system, domain, pruned in zip(scenes, systems, domains, together, strict=True):
        alone = prune_one_parameter(system, branches, domain, scene.known)
        assert pruned.evaluations == alone.evaluations
        assert np.array_equal(pruned.roots, alone.roots) and np.array_equal(pruned.unresolved, alone.unresolved)


@pytest.mark.parametrize("name", ["9-N7-flat-at-50", "9-N13-branch-cut"])
def test_the_searches_run_only_on_the_branches_left_undecided(name, monkeypatch):
    """Saved instances where the branch-and-prune leaves a box undecided at a flat
    triangle on a few branches (measured 2026-11-29: 2 and 4 of 16): the sampling
    searches run on exactly those branches, the others are proven, and the modes are
    the exact backend's."""
    import baranov.solvers.numeric.backend as backend
    from baranov.solvers.modes import signs_text

    searched: list[np.ndarray] = []
    searches = backend.one_parameter_roots

    def recorded(compiled, branches, *args, **kwargs):
        searched.append(branches)
        return searches(compiled, branches, *args, **kwargs)

    monkeypatch.setattr(backend, "one_parameter_roots", recorded)
    scene = load_scene(ROOT / "tests" / "regressions" / f"{name}.json")
    numeric = solve(scene)
    assert not numeric.certificate.complete and len(searched) == 1
    assert 0 < len(searched[0]) < 16
    left = {gap.split(" on branch ")[1].split(":")[0] for gap in numeric.certificate.gaps if " on branch " in gap}
    assert left == {signs_text(branch) for branch in searched[0]}
    exact = solve(scene, method="exact")
    assert sorted(round(m.parameters[n], 6) for m in numeric.assembly_modes for n in m.parameters) == \
        sorted(round(m.parameters[n], 6) for m in exact.assembly_modes for n in m.parameters)
