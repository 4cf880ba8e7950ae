"""Certified roots of two closure conditions by interval branch-and-prune with the
Krawczyk test (solvers/numeric/branch_and_prune_plane.py, issue 56), against the exact
backend's certified modes of 9/B28 (thesis §3.4.1): a box about each exact mode
certifies exactly that mode on its branch, boxes away from every mode certify nothing,
and over the whole searched box every certified root is a mode and every mode is
certified or in a box left undecided. The numeric backend runs it first on coupling-2
plans: a certified answer equals the exact one, and where it leaves boxes undecided the
sampling searches run on their branches alone (docs/numeric.md, "Certified coupling 2")."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import baranov.solvers.numeric.backend as backend
from baranov.closure.evaluate import sign_branches
from baranov.enumerate import baranov_trusses
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.msolve import compare_modes, find_msolve
from baranov.solvers.numeric.branch_and_prune import searched_box
from baranov.solvers.numeric.branch_and_prune_plane import prune_two_parameters
from baranov.solvers.placement import compile_scene
from baranov.solvers.verification import same_mode

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def b28():
    scene = load_scene(ROOT / "examples" / "9-B28.json")
    plan = solvable_plan(scene)
    exact = solve(scene, method="exact")
    assert exact.certificate.complete and len(exact.assembly_modes) == 14
    return scene, compile_scene(scene, plan), sign_branches(len(plan.free_sign_triangles)), exact


def _mode_point(exact, compiled, mode) -> np.ndarray:
    return np.array([mode.parameters[name] for name in compiled.parameter_names])


def test_a_box_about_each_mode_certifies_that_mode(b28):
    scene, compiled, branches, exact = b28
    for mode in exact.assembly_modes:
        point = _mode_point(exact, compiled, mode)
        branch = np.array([mode.signs], float)
        pruned = prune_two_parameters(compiled, branch, tuple((x - 1.0, x + 1.0) for x in point), scene.known)
        assert pruned.complete and len(pruned.roots) == 1, mode
        low, high = pruned.roots[0, :2], pruned.roots[0, 2:4]
        assert (low <= point + 1e-9 * abs(point)).all() and (point - 1e-9 * abs(point) <= high).all()
        # narrowed by the Krawczyk images to the rounding of f's models (about 1e-10 of the
        # larger parameter here), from the box's width 2
        assert (high - low <= 1e-8 * abs(point).max()).all()


def test_boxes_away_from_the_modes_certify_nothing(b28):
    scene, compiled, branches, exact = b28
    rng = np.random.default_rng(0)
    box = searched_box(scene, compiled.plan)
    points = [_mode_point(exact, compiled, mode) for mode in exact.assembly_modes]
    tried = 0
    while tried < 10:
        center = np.array([rng.uniform(*interval) for interval in box])
        if min(np.abs(center - point).max() for point in points) < 20:
            continue
        tried += 1
        pruned = prune_two_parameters(compiled, branches, tuple((x - 4.0, x + 4.0) for x in center), scene.known,
                                      budget=3000)
        assert len(pruned.roots) == 0


def test_the_whole_box_excludes_no_mode(b28):
    """The searched box of 9/B28 down to boxes of 2⁻⁸ of its sides (about 80 000 boxes,
    half of the modes certified, docs/bench/numeric-plane.md): each certified root is an
    exact mode on its branch, and each exact mode lies in a certified root's enclosure or
    in a box left undecided on its branch: the exclusions (a condition's model, a
    triangle, the radicands' hull at an edge) removed no mode."""
    scene, compiled, branches, exact = b28
    box = searched_box(scene, compiled.plan)
    pruned = prune_two_parameters(compiled, branches, box, scene.known, minimum_width=2.0**-8, budget=2_000_000)
    assert len(pruned.roots) >= 7
    points = [(_mode_point(exact, compiled, mode), branches.tolist().index(list(mode.signs)))
              for mode in exact.assembly_modes]

    def holds(row, point, branch) -> bool:
        slack = 1e-9 * np.abs(point)
        return int(row[4]) == branch and (row[:2] - slack <= point).all() and (point <= row[2:4] + slack).all()

    for row in pruned.roots:
        assert sum(holds(row, *where) for where in points) == 1, row
    for where in points:
        assert any(holds(row, *where) for row in pruned.roots) or any(holds(row, *where) for row in pruned.unresolved), where


def _same_modes(scene, first, second) -> bool:
    return len(first) == len(second) and all(any(same_mode(m, n, scene) for n in second) for m in first)


def test_the_backend_certifies_a_decided_plane_and_searches_only_undecided_branches(monkeypatch):
    """Random 9/N27 instances (seed 7), at a budget of 3000 boxes a branch: the first is
    decided whole (certified, 4 modes), the second leaves boxes undecided on one branch of
    16 (measured 2026-11-29; the default budget decides it whole), whose modes the sampling
    searches then find there alone; both equal the exact backend's."""
    monkeypatch.setattr(backend, "PLANE_BUDGET", 3000)
    searched: list[int] = []
    searches = backend.two_parameter_roots

    def recorded(compiled, branches, *args, **kwargs):
        searched.append(len(branches))
        return searches(compiled, branches, *args, **kwargs)

    monkeypatch.setattr(backend, "two_parameter_roots", recorded)
    truss, rng = baranov_trusses(9)[26], np.random.default_rng(7)
    for certified in (True, False):
        scene = scene_of(truss, generic_integer_configuration(truss, rng))
        searched.clear()
        numeric, exact = solve(scene), solve(scene, method="exact")
        assert numeric.certificate.complete is certified
        assert searched == ([] if certified else [1])
        assert _same_modes(scene, numeric.assembly_modes, exact.assembly_modes)
        if not certified:
            assert "undecided on branches -+-- " in numeric.certificate.gaps[0]


@pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")
def test_a_slider_chain_of_coupling_two_is_certified_by_the_plane_pruner():
    """A random nine-link slider chain of coupling 2 (rational axes; seed 2 of
    bench_numeric's generator, its third chain): the two-parameter branch-and-prune runs on
    its slider program — a slider's t and squared distances as the program takes them,
    the geometry's exact numbers enclosed — decides its whole box, and its 2 modes are
    msolve's."""
    scene = load_scene(Path(__file__).parent / "scenes" / "9-slider-chain-coupling-2.json")
    numeric = solve(scene)
    assert numeric.certificate.complete
    assert "interval branch-and-prune of (s1,11, s1,9)" in numeric.certificate.proof
    expected = solve(scene, method="msolve")
    missed, spurious, _ = compare_modes([mode.joints for mode in numeric.assembly_modes],
                                        [mode.joints for mode in expected.assembly_modes])
    assert len(numeric.assembly_modes) == 2 and (missed, spurious) == (0, 0)


@pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")
def test_boxes_where_a_parameter_s_joints_coincide_are_left_without_searching_the_branches(monkeypatch):
    """A slider chain's squared distance s1,11 is searched from 0, where the plan divides
    by it: the boxes there are never decided (they used to take the whole budget of every
    branch, bisected along s1,9 down to 2e-300 wide). They are left as one reason, every
    other box decided, no branch handed to the sampling searches (which sample no closer
    to 0), and the 12 modes are msolve's."""
    scene = load_scene(Path(__file__).parent / "scenes" / "9-slider-chain-coincidence.json")

    def no_search(*arguments, **keywords):
        raise AssertionError("a branch was handed to the sampling searches")

    monkeypatch.setattr(backend, "two_parameter_roots", no_search)
    numeric = solve(scene)
    assert not numeric.certificate.complete
    assert "s1,10 × s1,11 in [" in numeric.certificate.gaps[0] and "× [0, " in numeric.certificate.gaps[0]
    assert "joints nearly coincide" in numeric.certificate.gaps[0]
    assert "every other box is decided" in numeric.certificate.gaps[-1]
    expected = solve(scene, method="msolve")
    missed, spurious, _ = compare_modes([mode.joints for mode in numeric.assembly_modes],
                                        [mode.joints for mode in expected.assembly_modes])
    assert len(numeric.assembly_modes) == 12 and (missed, spurious) == (0, 0)


@pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")
def test_parameters_no_path_of_link_dimensions_bounds_are_pruned_out_to_a_reach(monkeypatch):
    """Adversarial seed 60, 9/N18 with five sliders: no path of link dimensions bounds
    s2,5 or s2,9, so the branch-and-prune used not to run, and the sampling searches
    missed the mode (4.721978, 3.176008) on branch -++-. Both are now searched out to
    UNBOUNDED_REACH times the linkage's size: every box there is decided but those at
    s = 0, no branch goes to the searches, and the 6 modes are msolve's. The certificate
    is not complete: it says how far out the parameters were searched."""
    scene = load_scene(Path(__file__).parent / "regressions" / "sliders" /
                       "adversarial-9-N18-unbounded-parameters-seed60.json")

    def no_search(*arguments, **keywords):
        raise AssertionError("a branch was handed to the sampling searches")

    monkeypatch.setattr(backend, "two_parameter_roots", no_search)
    numeric = solve(scene)
    assert not numeric.certificate.complete
    assert numeric.certificate.gaps[-1].startswith("no path of link dimensions bounds s2,5, s2,9: the branch-and-prune "
                                                   "searched s2,5 in [0, 1.18365e+10], s2,9 in [0, 1.18365e+10]")
    assert any(mode.signs == (-1, 1, 1, -1) and abs(mode.parameters["s2,5"] - 4.721978) < 1e-6
               for mode in numeric.assembly_modes)
    expected = solve(scene, method="msolve")
    missed, spurious, _ = compare_modes([mode.joints for mode in numeric.assembly_modes],
                                        [mode.joints for mode in expected.assembly_modes])
    assert len(numeric.assembly_modes) == 6 and (missed, spurious) == (0, 0)
