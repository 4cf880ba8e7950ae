"""The characteristic polynomial of a coupling-2 plan over Q from msolve's images of it
modulo primes.

The coupling-2 exact method (:mod:`baranov.solvers.exact.coupling_two`) needs the
characteristic polynomial P over Q, the assembly modes' values of the first parameter u.
Its image modulo a prime p costs 0.1–0.3 s on the nine-link trusses from the
resultants of the closure conditions (:func:`~baranov.solvers.exact.modular.candidate_images`).
msolve gets it in about 15 ms from the Cartesian system with a last variable
s = |P_j − P_i|² for the parameter's pair (i, j). That is the eliminating polynomial of
its rational parametrization over F_p, when s separates the solutions
(:func:`~baranov.solvers.msolve.eliminating_polynomial_modulo`). Its roots are s at every
complex solution, so every mode of the plan is among them. There are also configurations
the plan cannot express (joints coinciding); the caller's factor tests drop their factors.

P is lifted in one of two ways:

1. by Newton's iteration from one prime along the genuine curves
   (:func:`~baranov.solvers.exact.newton_lifting.newton_lifts`), when the modes are
   simple common points of the curves. The result is accepted when it reduces to msolve's
   image at a second prime;
2. otherwise by the Chinese remainder theorem over msolve's images at further primes
   (:func:`~baranov.solvers.exact.lifting_by_primes.lifted_from_images`). This happens on degenerate instances where the curves
   meet non-transversally at a mode, e.g. a mode at a domain edge. The number of primes
   is about twice P's coefficient bits divided by 30, at 15–20 ms each, against 0.7 s
   per prime for the resultants. Newton's iteration runs along the plan's own curves, but
   this lifting never touches the plan, so its result must also hold the plan's own image
   at one prime (:func:`holds_the_plans_image`).

Both are Monte Carlo steps like the rest of the coupling-2 lifting. A polynomial is
accepted only when it reduces to the image of a prime that was not used to make it.
"""

from __future__ import annotations

import os
import random
from collections import deque
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor
from itertools import chain, islice

import flint

from baranov.planner import Plan
from baranov.scene import Scene

from ..msolve import cartesian_system, eliminating_polynomial_of, exact_ground, find_msolve
from .characteristic import ExactMethodError
from .lifting_by_primes import lifted_from_images, primitive_polynomial, reduced_modulo
from .modular import candidate_images, random_prime
from .newton_lifting import newton_lifts, shape_position_split

#: Bits of the primes (msolve's sparse FGLM takes primes below 2^30).
MSOLVE_PRIME_BITS = 30

#: At most this many further images are asked of msolve (30 bits each).
MOST_PRIMES = 1 << 12


def msolve_images_apply(scene: Scene, plan: Plan | None = None) -> bool:
    """Whether msolve's eliminating polynomial is the characteristic polynomial's image.
    That needs the msolve binary, a first parameter of ``plan`` that is a distance (no
    slider in its pair: a slider's parameter is an oriented distance to its axis) and
    rational link areas. An irrational area needs an auxiliary
    root in the Cartesian system, which then also solves the linkage with that link
    mirrored. The ground's world coordinates must be exact too: a scene given by distances
    places its ground in floats (the 9/B28 example: √6610/3), and the Cartesian system then
    places it by its distances with an auxiliary root (it was a nearby instance in rounded
    coordinates, with another polynomial, before issue 55)."""
    sliders = {slider.joint for slider in scene.sliders}
    first = set(plan.parameters[0]) if plan is not None else sliders  # no plan: no slider at all
    return not first & sliders and find_msolve() is not None and exact_ground(scene)


def msolve_images(scene: Scene, plan: Plan, seed: int = 0) -> Iterator[flint.nmod_poly | None]:
    """msolve's images of the characteristic polynomial of ``plan``'s first parameter
    modulo successive random 30-bit primes (monic, square-free); None where msolve gives
    none at a prime (the parameter does not separate the solutions, positive dimension,
    the prime divides a denominator). Nothing if the Cartesian system needs an auxiliary
    root (an irrational link area: it would also solve the mirrored link). The images
    come in the order of the primes drawn from ``seed``, computed one per core ahead of
    the one awaited."""
    rng = random.Random(seed)
    variables, polynomials, _, auxiliary = cartesian_system(scene, distances=[plan.parameters[0]])
    if auxiliary:
        return
    # msolve runs one thread a prime: the next primes' runs go on beside the one awaited, one
    # per core, so that a lifting that takes hundreds of images waits for about 1/cores of them
    cores = len(os.sched_getaffinity(0))
    pool = ThreadPoolExecutor(max_workers=cores)
    running: deque = deque()
    try:
        while True:
            while len(running) < cores:
                running.append(pool.submit(eliminating_polynomial_of, variables, polynomials,
                                           random_prime(rng, MSOLVE_PRIME_BITS)))
            yield running.popleft().result()
    finally:  # a run still going finishes on its own; nobody waits for it
        pool.shutdown(wait=False, cancel_futures=True)


def characteristic_by_msolve(scene: Scene, plan: Plan, curves: Sequence[flint.fmpz_mpoly],
                             seed: int = 0) -> flint.fmpz_poly | None:
    """The characteristic polynomial of a coupling-2 ``plan`` over Z (primitive, leading
    coefficient positive) from msolve's images (module docstring): by Newton's iteration
    along the genuine ``curves`` from the first image, accepted when it reduces to the
    second; where that fails, by
    :func:`~baranov.solvers.exact.lifting_by_primes.lifted_from_images`. None where msolve's images do
    not apply (:func:`msolve_images_apply`), msolve gives no image at the first two
    primes, or the lifting fails; the caller then uses the resultants' images."""
    if not msolve_images_apply(scene, plan):
        return None
    images = msolve_images(scene, plan, seed)
    first, second = next(images, None), next(images, None)
    if first is None or second is None or first.degree() < 1:
        return None
    if first.degree() == second.degree():
        lifted = _by_newton(curves, first, second, images)
        if lifted is not None:
            return lifted
    if plans_image_divides(scene, plan, first, seed) is False:
        return None  # msolve's image is not the plan's: lifting it would be wasted
    lifted = lifted_from_images(chain([first, second], islice(images, MOST_PRIMES)), "msolve's images")
    return lifted if lifted is not None and holds_the_plans_image(scene, plan, lifted, seed) else None


def _by_newton(curves: Sequence[flint.fmpz_mpoly], first: flint.nmod_poly, second: flint.nmod_poly,
               images: Iterator[flint.nmod_poly | None]) -> flint.fmpz_poly | None:
    """P over Z from msolve's images: the part G whose roots are simple common points of
    the curves in shape position (:func:`~baranov.solvers.exact.newton_lifting.shape_position_split`
    of the first image) by Newton's iteration, accepted where its image divides the second;
    the rest R = P/G, of low degree (a mode at a singular or tangent point of the curves,
    two modes above one u: adversarial instances), by the Chinese remainder theorem over
    the quotients of msolve's images by G's (:func:`~baranov.solvers.exact.lifting_by_primes.lifted_from_images`,
    which checks R at further primes). None where G is empty or no lift is accepted. On
    11/N561 drawn with two joints at one point, R = one linear factor and P of degree 170
    came from five images instead of about a hundred."""
    good, coordinate, rest = shape_position_split(curves, first)
    if good.degree() < 1:
        return None
    lifted = next((lift for lift in newton_lifts(curves, good, coordinate)
                   if (second % reduced_modulo(lift, second.modulus())).is_zero()), None)
    if lifted is None:
        return None
    if rest.degree() < 1:
        return primitive_polynomial(lifted)

    def quotient(image: flint.nmod_poly | None) -> flint.nmod_poly | None:
        if image is None:
            return None
        quotient, remainder = divmod(image, reduced_modulo(lifted, image.modulus()))
        return quotient if remainder.is_zero() else None

    others = lifted_from_images(map(quotient, chain([first, second], islice(images, MOST_PRIMES))),
                                "msolve's images (the part Newton's iteration does not lift)")
    return None if others is None else primitive_polynomial(lifted) * others


def plans_image_divides(scene: Scene, plan: Plan, image: flint.nmod_poly, seed: int = 0) -> bool | None:
    """Whether the plan's own characteristic image modulo ``image``'s prime divides
    ``image`` (every value at which the plan's curves meet on one branch is a root of it);
    None where the plan gives no image at that prime. Checked on msolve's first image
    before the lifting by the Chinese remainder theorem: on a double-root adversarial
    instance of 11/N1 msolve's eliminating polynomial (degree 162) shared no root with
    the plan's (degree 161), and 84 images were lifted (40 s) before the check of the
    result rejected it."""
    try:
        _, own = candidate_images(scene, plan, image.modulus(), seed)
    except ExactMethodError:
        return None
    return (image % own).is_zero()


def holds_the_plans_image(scene: Scene, plan: Plan, polynomial: flint.fmpz_poly, seed: int = 0) -> bool:
    """Whether the plan's own characteristic image modulo a random 62-bit prime (the
    saturated one of :func:`~baranov.solvers.exact.modular.candidate_images`, from the
    closure conditions) divides ``polynomial`` there: every value of the first parameter
    at which the plan's curves meet on one branch is a root. This is the check of the
    lifting by the Chinese remainder theorem, which, unlike Newton's iteration, never
    touches the plan. It costs one set of resultants (0.1–0.7 s on nine links), so it is
    done only on the instances that need that lifting. False where no prime gives an
    image."""
    rng = random.Random(seed)
    for _ in range(3):
        prime = random_prime(rng)
        try:
            _, image = candidate_images(scene, plan, prime, seed)
        except ExactMethodError:  # the prime divides a denominator, or an image vanishes
            continue
        return (flint.nmod_poly([int(c) for c in polynomial.coeffs()], prime) % image).is_zero()
    return False
