"""Bilateration matrices as complex numbers.

A perpendicular matrix [[a, -b], [b, a]] acts on plane vectors as multiplication by the
complex number a + ib acts on x + iy; such matrices add and multiply like complex numbers
and det = |a + ib|² (thesis §2.4). A bilateration matrix (thesis eq. 2.7)

    Z_{i,j,k} = 1/(2 s_{i,j}) [[s_{i,j} + s_{i,k} - s_{j,k}, -4 A_{i,j,k}],
                              [4 A_{i,j,k}, s_{i,j} + s_{i,k} - s_{j,k}]]

is therefore the complex number (s_{i,j} + s_{i,k} - s_{j,k} + 4i A_{i,j,k}) / (2 s_{i,j}),
where A_{i,j,k} = ±¼ √((s_{i,j} + s_{i,k} + s_{j,k})² - 2(s_{i,j}² + s_{i,k}² + s_{j,k}²))
is the oriented area of △P_i P_j P_k, positive when P_k lies left of p_{i,j}.

This module is the project's one bilateration kernel (issue 16): :func:`place_joints`
places a plan's joints step by step, :func:`triangle_radicand`, :func:`bilaterated` and
:func:`squared_distance` are the formulas, written once and run in every arithmetic the
backends use — numpy float arrays (closure residuals, :mod:`.evaluate`), flint complex
balls (certified placements, ``solvers/exact/characteristic.py: placed_points``), polynomials
over the exact radical tower (``radical_tower``, also modulo primes) and plain floats
(a link's own frame, ``scene/model.py``). Points are homogeneous (x, y, w) so that the
tower needs no division; floats and balls divide through after each step
(:func:`dehomogenised`). An arithmetic supplies only its product (the tower's keeps
normal form), the signed square root of a step's radicand, and its lowest terms. A new
joint type (a slider: a point at infinity, w = 0) is an extension here, in one place.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import Any

import numpy as np

#: A radicand above −this times the squared largest side is rounding noise around 0 (a
#: flat triangle), not a triangle that does not exist: where a radicand touches 0 (a
#: double zero, joints in line at a mode), rounding makes it a few ulps negative over a
#: stretch ~1e-8 wide, and Brent's bracket hit NaN there (issue 25's 7/N3 instance at
#: s1,9 = 13).
RADICAND_NOISE = 1e-13


def triangle_radicand(s_ij, s_ik, s_jk, multiply: Callable[[Any, Any], Any] = operator.mul):
    """16 A_{i,j,k}² = (s_ij + s_ik + s_jk)² − 2 (s_ij² + s_ik² + s_jk²), the Cayley–Menger
    form of the squared area from the three squared sides (thesis eq. 2.7), in any
    arithmetic that adds and multiplies: floats, numpy arrays, flint balls, polynomials
    (``multiply`` the exact tower's product in normal form). Homogeneous of degree 2: the
    sides scaled by d give the radicand scaled by d². O(1) operations.

    >>> triangle_radicand(25, 9, 16)  # 3-4-5 right triangle: 16 · 6²
    576
    """
    total = s_ij + s_ik + s_jk
    return (multiply(total, total)
            - 2 * (multiply(s_ij, s_ij) + multiply(s_ik, s_ik) + multiply(s_jk, s_jk)))


def small_term_radicand(s_ij, s_ik, s_jk, multiply: Callable[[Any, Any], Any] = operator.mul):
    """:func:`triangle_radicand` as 4 s_ik s_jk − (s_ik + s_jk − s_ij)²: the same number,
    in the form in which s_ij, the side between the joints a step starts from (the side a
    plan computes), enters one term, s_ik + s_jk − s_ij = 2 √(s_ik s_jk) cos θ_k, no larger
    than the others. An enclosure of s_ij of width w then widens the radicand's by about
    2 (s_ik + s_jk − s_ij) w, where the symmetric form's (s_ij + s_ik + s_jk)² and 2 s_ij²
    widen it by about 4 (s_ij + s_ik + s_jk) w each, and they cancel only in the exact
    value: on 9/B28 a box's radicand enclosure was 100 times its range. The interval
    program takes this form (closure/interval_program.py); the float kernels keep the
    symmetric one, whose rounding the searches of degenerate instances were tuned on
    (with this form four saved double-root and flat-valley instances were answered
    differently, 2026-11-29). O(1) operations.

    >>> small_term_radicand(25, 9, 16)  # 3-4-5 right triangle: 16 · 6²
    576
    """
    cosine = s_ik + s_jk - s_ij
    return 4 * multiply(s_ik, s_jk) - multiply(cosine, cosine)


def factored_radicand(sides, position: int, root: Callable[[Any], Any]):
    """:func:`triangle_radicand` of ``sides`` as (x − (√a − √b)²)((√a + √b)² − x), x the
    side at ``position`` and a, b the other two, ``root`` their square root: the same
    number, 4ab − (a + b − x)², in the form that rounds well where x varies and a, b are
    fixed. Near a flat triangle the Cayley–Menger form cancels terms of size (a + b + x)²
    to a value near 0 (on an 11-link truss, rounding of about 1e-6 against a radicand of
    1e-5 at the end of the parameter's domain); here x − (√a ± √b)² is exact to a few
    ulps of x, so the radicand to a few ulps of itself. O(1) operations.

    >>> import math
    >>> factored_radicand((25, 9, 16), 0, math.sqrt)  # 3-4-5: 16 · 6²
    576.0
    """
    x = sides[position]
    a, b = (side for n, side in enumerate(sides) if n != position)
    root_a, root_b = root(a), root(b)
    difference, total = root_a - root_b, root_a + root_b
    return (x - difference * difference) * (total * total - x)


def step_sides(step) -> tuple[frozenset, frozenset, frozenset]:
    """The pairs of a step's three sides in the order :func:`place_joints` forms them:
    (P_i P_j, P_i P_k, P_j P_k) for base (P_i, P_j) and new joint P_k."""
    (i, j), k = step.base, step.joint
    return frozenset((i, j)), frozenset((i, k)), frozenset((j, k))


def parameter_triangles(plan, known_pairs) -> dict[int, int]:
    """The steps of ``plan`` whose triangle has one of its parameters as a side and its
    two other sides among ``known_pairs`` (the triangles that bound the parameter's
    domain): step index → the parameter's position among the sides (s_ij, s_ik, s_jk) as
    :func:`place_joints` forms them. Their radicands are taken in
    :func:`factored_radicand`'s form by the float kernels. O(steps)."""
    parameters = {frozenset(pair) for pair in plan.parameters}
    found = {}
    for index, step in enumerate(plan.steps):
        sides = step_sides(step)
        at = [n for n, side in enumerate(sides) if side in parameters]
        if len(at) == 1 and all(side in known_pairs for n, side in enumerate(sides) if n != at[0]):
            found[index] = at[0]
    return found


#: A point in homogeneous coordinates (x, y, w), the point (x/w, y/w); a squared distance
#: as (numerator, denominator). Python's ints 0 and 1 stand for themselves in every
#: arithmetic (a product by 1 is not formed).
Point = tuple[Any, Any, Any]
Fraction2 = tuple[Any, Any]


def _times(multiply, first, second):
    """first × second, with the ints 0 and 1 taken as themselves (no product formed)."""
    if type(first) is int:
        if first == 1:
            return second
        if first == 0:
            return 0
    if type(second) is int:
        if second == 1:
            return first
        if second == 0:
            return 0
    return multiply(first, second)


def bilaterated(p_i: Point, p_j: Point, sides: tuple[Any, Any, Any], signed_root,
                multiply: Callable[[Any, Any], Any] = operator.mul) -> Point:
    """P_k from P_i, P_j and the squared distances s_ij, s_ik, s_jk over their common
    denominator (``sides``, :func:`common_sides`): the bilateration p_{i,k} = Z_{i,j,k}
    p_{i,j} of thesis eq. (2.7), with Z = (s_ij + s_ik − s_jk + 4i A)/(2 s_ij) acting as a
    complex number, in homogeneous coordinates so that only sums and products are formed
    (the exact tower has no division). ``signed_root`` is ±√ of :func:`triangle_radicand`
    of ``sides``, i.e. 4 A times the common denominator. O(1) operations.

    >>> bilaterated((0, 0, 1), (5, 0, 1), (25, 9, 16), 24)  # P_k = (9/5, 12/5)
    (90, 120, 50)
    """
    first, second, third = sides
    (x_i, y_i, w_i), (x_j, y_j, w_j) = p_i, p_j
    real = first + second - third
    if type(w_i) is int and type(w_j) is int and w_i == w_j == 1:  # affine points (floats, balls): w = 1 skipped
        u, v, scale = x_j - x_i, y_j - y_i, 2 * first
        return (multiply(x_i, scale) + multiply(real, u) - multiply(signed_root, v),
                multiply(y_i, scale) + multiply(real, v) + multiply(signed_root, u), scale)
    u = _times(multiply, x_j, w_i) - _times(multiply, x_i, w_j)
    v = _times(multiply, y_j, w_i) - _times(multiply, y_i, w_j)
    scale_j = _times(multiply, 2 * first, w_j)
    x = _times(multiply, x_i, scale_j) + _times(multiply, real, u) - _times(multiply, signed_root, v)
    y = _times(multiply, y_i, scale_j) + _times(multiply, real, v) + _times(multiply, signed_root, u)
    return x, y, _times(multiply, scale_j, w_i)


def common_sides(s_ij: Fraction2, s_ik: Fraction2, s_jk: Fraction2, multiply=operator.mul):
    """The three squared sides (numerator, denominator) over their common denominator
    d_ij d_ik d_jk (numerators only), the form :func:`triangle_radicand` and
    :func:`bilaterated` work in."""
    (n_ij, d_ij), (n_ik, d_ik), (n_jk, d_jk) = s_ij, s_ik, s_jk
    if type(d_ij) is int and type(d_ik) is int and type(d_jk) is int and d_ij == d_ik == d_jk == 1:
        return n_ij, n_ik, n_jk  # floats and balls: no denominators
    return (_times(multiply, _times(multiply, n_ij, d_ik), d_jk), _times(multiply, _times(multiply, n_ik, d_ij), d_jk),
            _times(multiply, _times(multiply, n_jk, d_ij), d_ik))


def squared_distance(p_u: Point, p_v: Point, reference: Fraction2, multiply=operator.mul) -> Fraction2:
    """s_{u,v} = ``|p_v − p_u|²`` s_{a,b} as (numerator, denominator), for points placed in
    the frame p_a = 0, p_b = 1 (thesis §2.4: computed distances carry the reference
    distance s_{a,b}). Coordinates are squared separately, so complex coordinates (at
    complex parameter values) give the polynomial continuation, not ``|·|²``.

    >>> squared_distance((0, 0, 1), (3, 4, 1), (1, 1))
    (25, 1)
    """
    (x_u, y_u, w_u), (x_v, y_v, w_v) = p_u, p_v
    x = _times(multiply, x_v, w_u) - _times(multiply, x_u, w_v)
    y = _times(multiply, y_v, w_u) - _times(multiply, y_u, w_v)
    both = _times(multiply, w_u, w_v)
    return (_times(multiply, _times(multiply, x, x) + _times(multiply, y, y), reference[0]),
            _times(multiply, _times(multiply, both, both), reference[1]))


def dehomogenised(point: Point) -> Point:
    """(x/w, y/w, 1): in floats and balls the point is divided through after every step
    (products of w's would overflow, or widen)."""
    x, y, w = point
    return x / w, y / w, 1


def place_joints(plan, known: Callable[[str, str], Fraction2 | None], signed_root, *,
                 multiply: Callable[[Any, Any], Any] = operator.mul,
                 reduced_point: Callable[[Point], Point] | None = None,
                 reduced_distance: Callable[[Fraction2], Fraction2] | None = None,
                 after_step: Callable[[int, Any, Point], bool] | None = None,
                 slider_step: Callable[[int, Any, dict, Fraction2, Callable], Point | None] | None = None,
                 slider_frame: Callable[[], tuple[dict[str, Point], Fraction2] | None] | None = None,
                 radicand: Callable = triangle_radicand,
                 steps: tuple[int, int] | None = None,
                 start: tuple[dict[str, Point], Fraction2] | None = None,
                 ) -> tuple[dict[str, Point], Fraction2, Callable[[str, str], Fraction2]]:
    """Every joint of ``plan`` placed by bilateration, one step after another (thesis
    §2.5), in one arithmetic: the single kernel that numeric residuals, ball placements,
    the exact radical tower and the scene's link frames all run through.

    Parameters
    ----------
    plan
        a :class:`~baranov.planner.Plan` (reference pair, steps, closure pairs).
    known
        (numerator, denominator) of s_{u,v} for a link's pair or a parameter,
        None for a pair the plan computes.
    signed_root
        ``signed_root(index, step, sides, radicand)``: ±√radicand for the
        step's orientation (``sides``: s_ij, s_ik, s_jk over their common
        denominator, numerators only, :func:`common_sides`).
    multiply
        the arithmetic's product (the exact tower's keeps normal form).
    reduced_point, reduced_distance
        lowest terms (floats divide through; the tower
        cancels a gcd); identity by default.
    after_step
        called with (index, step, new point); False stops the placement.
    slider_step
        ``slider_step(index, step, points, reference, distance)`` places a
        step that touches a slider joint (:class:`~.sliders.SliderPlacement`: the
        limit of its bilateration) and returns the new point, or the axis direction
        as a point for a slider located; None for a step it leaves to bilateration.
    slider_frame
        for a reference pair that holds a slider, the frame on its axis:
        the other joint placed, and s_ref (world units: 1); None otherwise.
    radicand
        ``radicand(s_ij, s_ik, s_jk, multiply)``: a step's 16 A² from its sides,
        :func:`triangle_radicand` (every arithmetic but the interval program's
        source, which takes :func:`small_term_radicand`).
    steps, start
        place only the steps ``range(*steps)``, going on from ``start``: the
        points and reference distance that the steps before left (placed into,
        not copied). Sign branches that share their first steps place them once
        (:func:`~baranov.solvers.exact.characteristic.placed_on_branches`).

    Returns
    -------
        (points, the reference distance s_{a,b}, a function giving s_{u,v} for any pair
        of placed joints: known, else computed). The reference joints sit at 0 and 1.
        O(steps) kernel calls.
    """
    reduced_point = reduced_point or (lambda point: point)
    reduced_distance = reduced_distance or (lambda pair: pair)
    a, b = plan.reference
    started = start if start is not None else slider_frame() if slider_frame is not None else None
    if started is None:
        points: dict[str, Point] = {a: (0, 0, 1), b: (1, 0, 1)}
        reference = known(a, b)  # a link's pair or a parameter: nothing is computed yet
    else:
        points, reference = started
    first, last = steps if steps is not None else (0, len(plan.steps))

    def distance(u: str, v: str, computed: bool = False) -> Fraction2:
        value = None if computed else known(u, v)
        if value is not None:
            return value
        return reduced_distance(squared_distance(points[u], points[v], reference, multiply))

    for index in range(first, last):
        step = plan.steps[index]
        i, j = step.base
        k = step.joint
        placed = slider_step(index, step, points, reference, distance) if slider_step is not None else None
        if placed is None:
            sides = common_sides(distance(i, j), distance(i, k), distance(j, k), multiply)
            root = signed_root(index, step, sides, radicand(*sides, multiply))
            placed = points[k] = reduced_point(bilaterated(points[i], points[j], sides, root, multiply))
        if after_step is not None and after_step(index, step, placed) is False:
            break
    return points, reference, distance


def oriented_area(s_ij, s_ik, s_jk, sign):
    """A_{i,j,k} from the three squared distances and the orientation sign (±1), thesis
    eq. (2.7). NaN where the radicand is negative (the triangle does not exist). Sign 0
    takes the triangle as flat (area 0) whatever the radicand: a candidate at a fold of
    the domain, where rounding leaves the radicand a few ulps below 0 (solvers/numeric/backend.py,
    ``_roots_at_folds``). Vectorised over numpy arrays.

    >>> float(oriented_area(25.0, 9.0, 16.0, 1))  # 3-4-5 right triangle: area 6
    6.0
    """
    s_ij, s_ik, s_jk = (np.asarray(x, dtype=float) for x in (s_ij, s_ik, s_jk))
    return signed_root(triangle_radicand(s_ij, s_ik, s_jk), (s_ij, s_ik, s_jk), sign) / 4


def signed_root(radicand, sides, sign):
    """sign · √radicand in floats (numpy arrays): NaN where the radicand is negative
    beyond rounding (RADICAND_NOISE relative to the largest squared side: the triangle
    does not exist), 0 where it is within rounding of 0 or where ``sign`` is 0 (the
    triangle taken flat). The straight-line program runs this rule as its instructions
    ``GUARDED_ROOT`` and ``FLAT_ZERO`` (:mod:`.straight_line`; equal bit for bit,
    ``tests/test_straight_line.py``)."""
    s_ij, s_ik, s_jk = sides
    noise = -RADICAND_NOISE * np.maximum(np.maximum(s_ij, s_ik), s_jk) ** 2
    # no errstate needed: the square root sees only values ≥ 0 and NaN, which raise nothing
    root = sign * np.sqrt(np.where(radicand >= noise, np.maximum(radicand, 0.0), np.nan))
    if type(sign) is int:  # a link step's fixed orientation
        return root if sign != 0 else np.zeros_like(root)
    flat = np.asarray(sign) == 0
    if not flat.any():  # the usual case: no flat triangle asked for
        return root
    return np.where(flat, 0.0, root)


def bilateration_matrix(s_ij, s_ik, s_jk, sign):
    """Z_{i,j,k} as a complex number (array), so that p_{i,k} = Z_{i,j,k} p_{i,j}.

    >>> z = bilateration_matrix(25.0, 9.0, 16.0, 1)   # P_i=(0,0), P_j=(5,0), P_k=(9/5, 12/5)
    >>> complex(np.round(z * 5, 12))                   # p_{i,k} = Z p_{i,j}
    (1.8+2.4j)
    """
    area = oriented_area(s_ij, s_ik, s_jk, sign)
    s_ij, s_ik, s_jk = (np.asarray(x, dtype=float) for x in (s_ij, s_ik, s_jk))
    with np.errstate(invalid="ignore", divide="ignore"):  # s_ij = 0: no bilateration (NaN)
        return (s_ij + s_ik - s_jk + 4j * area) / (2 * s_ij)


def perpendicular_matrix(z) -> np.ndarray:
    """The 2×2 perpendicular matrix [[a, -b], [b, a]] of the complex number a + ib.

    >>> perpendicular_matrix(1 + 2j).tolist()
    [[1.0, -2.0], [2.0, 1.0]]
    """
    z = complex(z)
    return np.array([[z.real, -z.imag], [z.imag, z.real]])
