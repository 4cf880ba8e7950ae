"""The coupling-2 candidate polynomial lifted by Newton's iteration from one prime
(baranov.solvers.exact.newton_lifting) against its lifting by primes, and the exact
backend on it."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shared import same_modes

from baranov.enumerate import baranov_trusses
from baranov.planner import best_plan
from baranov.scene import load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import solve
from baranov.solvers.exact import coupling_two, msolve_images, newton_lifting
from baranov.solvers.exact.characteristic import exact_plan
from baranov.solvers.exact.coupling_two import PLANE, genuine_curves, shared_curves
from baranov.solvers.exact.lifting_by_primes import lifted_from_images
from baranov.solvers.exact.modular import candidate_images, lifted_characteristic_polynomial
from baranov.solvers.exact.msolve_images import characteristic_by_msolve
from baranov.solvers.exact.newton_lifting import candidate_by_newton
from baranov.solvers.msolve import eliminating_polynomial_modulo, find_msolve

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
NINE = baranov_trusses(9)
COUPLING_TWO = [truss for truss in NINE if best_plan(truss).number_of_parameters == 2]  # 9/B25–B28
needs_msolve = pytest.mark.skipif(find_msolve() is None, reason="msolve binary not installed (make installs it)")


def _curves(scene, plan):
    curves = genuine_curves(scene, plan)
    shared = shared_curves(curves, scene, plan)
    common = math.prod(shared, start=PLANE.constant(1))
    return (curves[0] / common, curves[1] / common) if shared else curves


def _both_ways(truss, seed):
    scene = scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed)))
    plan = best_plan(truss)
    return candidate_by_newton(scene, plan, _curves(scene, plan)), lifted_characteristic_polynomial(
        scene, plan, saturated=False)


@pytest.mark.slow  # 27 s (2026-11-28)
@settings(max_examples=3, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_newton_and_primes_give_the_same_candidate_polynomial(seed):
    """On random instances of 9/B25 (the cheapest coupling-2 truss by primes): the
    candidate polynomial over Z from one prime by Newton's iteration is the one lifted
    from ~36 primes by the Chinese remainder theorem, coefficient for coefficient."""
    by_newton, by_primes = _both_ways(COUPLING_TWO[0], seed)
    assert by_newton is not None and by_newton == by_primes


@pytest.mark.slow
@pytest.mark.parametrize("index", range(4))
@pytest.mark.parametrize("seed", range(3))
def test_newton_and_primes_agree_on_every_coupling_two_nine_link_truss(index, seed):
    by_newton, by_primes = _both_ways(COUPLING_TWO[index], seed)
    assert by_newton is not None and by_newton == by_primes


def test_the_exact_backend_lifts_by_newton_and_keeps_its_modes(monkeypatch):
    """The 9/B28 example of the thesis (58 modes over C, 14 real): solved without the
    lifting by primes (it would raise here), with the modes of the numeric backend."""
    scene = load_scene(EXAMPLES / "9-B28.json")
    numeric = solve(scene, method="numeric").assembly_modes

    def by_primes(*args, **kwargs):
        raise AssertionError("lifted by primes: Newton's iteration did not apply")

    monkeypatch.setattr(coupling_two, "lifted_characteristic_polynomial", by_primes)
    solution = solve(scene, method="exact")
    assert solution.characteristic_polynomial.polynomial.degree() == 58
    assert solution.certificate.complete
    assert same_modes(scene, solution.assembly_modes, numeric) and len(numeric) == 14



def _instance(index: int, seed: int):
    truss = COUPLING_TWO[index]
    return scene_of(truss, generic_integer_configuration(truss, np.random.default_rng(seed))), best_plan(truss)


@needs_msolve
def test_an_msolve_image_that_is_not_the_plans_is_not_lifted():
    """The check before the lifting by primes: msolve's image passes on a generic
    instance; a polynomial of the same degree whose roots are not the plan's fails (as
    msolve's image did on a double-root instance of 11/N1, where 84 images were lifted
    before the result was rejected)."""
    scene, plan = _instance(0, 1)
    image = eliminating_polynomial_modulo(scene, plan.parameters[0], 1073741789)
    assert msolve_images.plans_image_divides(scene, plan, image) is True
    assert msolve_images.plans_image_divides(scene, plan, image + 1) is False  # monic, same degree, no common root


@needs_msolve
@pytest.mark.parametrize("index", range(4))
def test_msolve_image_is_the_saturated_characteristic_image(index):
    """msolve's eliminating polynomial of the first parameter over F_p (Cartesian system)
    is the characteristic polynomial's image that the resultants of the closure
    conditions give at the same prime, saturated: two eliminations that share nothing."""
    scene, plan = _instance(index, 1)
    prime = 1073741789
    assert eliminating_polynomial_modulo(scene, plan.parameters[0], prime) == candidate_images(scene, plan, prime)[1]


@needs_msolve
@pytest.mark.parametrize("index", range(4))
def test_the_characteristic_polynomial_is_the_same_with_and_without_msolve(index, monkeypatch):
    """The polynomial lifted from msolve's images divides the candidate lifted from the
    resultants' images, and the exact backend keeps the same characteristic polynomial
    and modes either way."""
    scene, plan = _instance(index, 2)
    curves = _curves(scene, plan)
    from_msolve = characteristic_by_msolve(scene, plan, curves)
    assert from_msolve is not None and from_msolve.degree() > 0
    assert candidate_by_newton(scene, plan, curves) % from_msolve == 0
    with_msolve = solve(scene, method="exact")
    monkeypatch.setattr(msolve_images, "find_msolve", lambda: None)
    assert characteristic_by_msolve(scene, plan, curves) is None
    without = solve(scene, method="exact")
    assert with_msolve.characteristic_polynomial.polynomial == without.characteristic_polynomial.polynomial
    assert same_modes(scene, with_msolve.assembly_modes, without.assembly_modes)
    assert with_msolve.certificate.complete and without.certificate.complete


def _adversarial(index: int, kind: str, number: int, seed: int = 2611):
    """bench/adversarial.py's instance (9 links, truss N(index + 1))."""
    from baranov.scene.adversarial import ADVERSARIAL_KINDS, adversarial_scene

    truss = NINE[index]
    rng = np.random.default_rng([seed, 9, index, ADVERSARIAL_KINDS.index(kind), number])
    return adversarial_scene(truss, kind, rng)[0], best_plan(truss)


@needs_msolve
@pytest.mark.parametrize("index, kind, number, seed", [(27, "domain-edge", 0, 2611), (1, "coincident", 1, 62)])
def test_the_part_newton_does_not_lift_is_lifted_by_primes(index, kind, number, seed):
    """9/N28 drawn with a mode at a domain edge, 9/N2 with two joints at one point: at one
    root of msolve's image the curves meet non-transversally, so Newton's iteration on the
    whole image yields nothing. The image is split (shape_position_split): Newton's
    iteration lifts the rest of it, and the one root left over is lifted by the Chinese
    remainder theorem over msolve's images divided by the lifted part. The product is
    the polynomial that msolve's images alone give by primes (other primes: an
    independent lifting), holds the plan's own image, and the exact backend lists
    msolve's modes, certified."""
    scene, plan = _adversarial(index, kind, number, seed)
    curves = _curves(scene, plan)
    image = next(msolve_images.msolve_images(scene, plan))
    assert next(newton_lifting.newton_lifts(curves, image), None) is None
    good, _, rest = newton_lifting.shape_position_split(curves, image)
    assert rest.degree() == 1 and good * rest == image
    lifted = characteristic_by_msolve(scene, plan, curves)
    assert lifted == lifted_from_images(msolve_images.msolve_images(scene, plan, seed=7))
    assert msolve_images.holds_the_plans_image(scene, plan, lifted, seed=5)
    exact, oracle = solve(scene, method="exact"), solve(scene, method="msolve")
    assert exact.certificate.complete
    assert same_modes(scene, exact.assembly_modes, oracle.assembly_modes)


@needs_msolve
def test_a_ground_in_floats_is_left_to_the_resultants():
    """The 9/B28 example is given by distances, its ground placed in floats: msolve's
    Cartesian system places it by those distances with an auxiliary root (it then solves
    the mirrored ground too), so msolve's images are not used."""
    scene = load_scene(EXAMPLES / "9-B28.json")
    assert not msolve_images.exact_ground(scene) and not msolve_images.msolve_images_apply(scene)
    assert characteristic_by_msolve(scene, best_plan(scene.chain), genuine_curves(scene, best_plan(scene.chain))) is None


@needs_msolve
def test_a_slider_chain_lifts_from_msolve_images_when_its_first_parameter_is_a_distance(monkeypatch):
    """A coupling-2 slider chain whose plan's first parameter is a distance between two
    revolute joints (s1,11; sliders P8, P10, P12): msolve's Cartesian model, which fixes
    each axis with its sense, gives the characteristic polynomial's images, and the lifted
    polynomial is the one of the plan's own resultants (2.2 s against 4.6 s measured);
    where the first parameter is a slider's oriented distance they do not apply."""
    scene = load_scene(Path(__file__).parent / "scenes" / "9-slider-chain-coupling-2.json")
    plan = exact_plan(scene)
    assert not set(plan.parameters[0]) & {slider.joint for slider in scene.sliders}
    assert msolve_images.msolve_images_apply(scene, plan)
    with_msolve, _ = coupling_two.characteristic_polynomial_two(scene, plan)
    monkeypatch.setattr(coupling_two, "characteristic_by_msolve", lambda *arguments, **keywords: None)
    without, _ = coupling_two.characteristic_polynomial_two(scene, plan)
    assert with_msolve.polynomial == without.polynomial and with_msolve.polynomial.degree() == 22
    slider_first = dataclasses.replace(plan, parameters=(("P1", "P8"), *plan.parameters[1:]))
    assert not msolve_images.msolve_images_apply(scene, slider_first)


@needs_msolve
def test_the_plans_own_images_split_where_msolve_gives_none():
    """9/N2 drawn at a double root: s does not separate the Cartesian solutions, so msolve
    gives no image of s's polynomial; the plan's own images are lifted by Newton's
    iteration where the curves' common points are simple and in shape position, the
    rest with the saturated part by primes. The candidate is the one the resultants'
    images give by primes alone."""
    scene, plan = _adversarial(1, "double-root", 0, 62)
    assert next(msolve_images.msolve_images(scene, plan)) is None
    curves = _curves(scene, plan)
    by_newton = candidate_by_newton(scene, plan, curves)
    assert by_newton is not None and by_newton == lifted_characteristic_polynomial(scene, plan, saturated=False)
