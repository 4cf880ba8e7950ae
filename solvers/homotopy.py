"""Every complex solution of the Cartesian system by a total-degree homotopy, for any
coupling degree: the numeric method for trusses whose plans need three parameters (the
45 thirteen-link trusses of coupling degree 3, which the bilateration backends do not
solve), and a check of the others.

**The system.** The Cartesian system of :func:`~baranov.solvers.msolve.cartesian_system`
(each moving link: its first two joints' squared distance, and linear placement
equations for its other joints) has, for a rigid truss of L links, L − 1 quadratic
equations and as many linear ones as it takes to fix every other joint. The linear ones
are solved exactly (``fmpq_mat.rref``) and substituted, which leaves m quadratic
equations q_i(y) = 0 in m unknowns y (m = L − 1, plus one per link with an irrational
area, whose square root is an unknown), homogenised as Y^T Q_i Y with Y = (y_0, y).

**The homotopy** (Sommese, Wampler, *The Numerical Solution of Systems of Polynomials
Arising in Engineering and Science*, 2005, §8.4): from the start system
g_i = y_i² − y_0² (its 2^m solutions (1, ±1, …, ±1)),

    H(Y, t) = (1 − t) γ g(Y) + t q(Y),     c · Y = 1,

with a random complex γ, and a random affine chart c so that paths that go to infinity
stay bounded in projective space (Y_0 → 0). With probability one every path is smooth
for t < 1 and every isolated solution of q is the end of at least one path (ibid.,
Theorem 8.4.1). Paths are followed all together (numpy, one batched linear solve per
stage): a Runge–Kutta predictor on dY/dt = −H_Y⁻¹ H_t and three Newton corrections,
the step halved where the corrector does not contract and doubled after three successes.

**What is checked.** A path is taken to infinity once t > 1 − ENDGAME with |Y_0| / |Y|
below a tenth of the least value a real configuration can have (so never where a real
mode could end), or where its step collapses there below nine tenths of it. Every path's
last point is polished by Newton's method at t = 1, and the nonsingular solutions are
kept once each, with the conjugate of each non-real one (the equations are real). Two
paths ending at the same nonsingular solution mean one jumped: then every path is
followed again with another γ and a smaller largest step, up to :data:`ATTEMPTS` times,
and the solutions found are pooled. A path that fails, or a duplicate that stays, is
said in ``undecided``. The number of distinct finite solutions is the instance's number
of complex assembly modes (the catalog's count) but for complex solutions far larger than
any real configuration, whose paths may be taken to infinity (13/N20086: a conjugate pair
at |y| ≈ 4.9·10³ scaled, against real coordinates below 9: docs/homotopy.md); the real
ones, refined by Newton's method in real arithmetic, are the modes. Cost: 2^m paths
(4 096 for 13 links), each some hundred steps of O(m³).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from fractions import Fraction

import flint
import numpy as np

from baranov.scene import Scene

from .modes import Solution, SolverError
from .msolve import cartesian_system
from .msolve_backend import description_plan, modes_of_configurations
from .verification import distance_bound

#: Newton corrections per step; a step is accepted when the last correction is below
#: CORRECTION (relative to |Y|) and the corrections contract.
CORRECTIONS = 3
CORRECTION = 1e-8
#: Corrections below this (relative) are rounding: they need not contract. Near an
#: ill-conditioned solution Newton's corrections stall at about the condition number
#: times 1e-16 instead of contracting: 13/N20086 has complex solutions with |y| ≈ 2·10³
#: to 5·10³ (scaled) and condition numbers 4·10¹⁰ to 6·10¹¹. With 1e-12 here, 51 of its
#: paths had their steps collapse near t = 1 (none with a tenth of CORRECTION).
ROUNDING = CORRECTION / 10
#: The largest and smallest steps in t; a path whose step falls below the smallest fails.
LARGEST_STEP = 0.05
SMALLEST_STEP = 1e-9
#: At most this many steps per path.
MOST_STEPS = 5000
#: An end is at infinity when |Y_0| / |Y| is below this.
AT_INFINITY = 1e-7
#: Paths to infinity end in singular points, where the steps collapse: after
#: t = 1 − ENDGAME a path with |Y_0| / |Y| below DIVERGING is taken to infinity and
#: left there. A real configuration has
#: |Y_0| / |Y| ≥ 1 / √(1 + m B²) for B its largest coordinate over the scale: where B
#: is known, :func:`solve_system` takes a tenth of that instead of DIVERGING.
ENDGAME = 1e-2
DIVERGING = 1e-3
#: A path whose step collapses in the endgame is taken to infinity below this many
#: times the diverging ratio: nine tenths of the least ratio of a real configuration, so
#: that it cannot be ending at a real mode (a real double mode, singular too, lies above).
COLLAPSED = 9
#: Path statuses returned by :func:`track`.
FINISHED, INFINITE, FAILED = 0, 1, 2
#: A solution is real when its imaginary parts are below this (relative to its size).
REAL = 1e-6
#: Ends closer than this (relative to the larger) are one solution: a large complex
#: solution reached by two paths can differ by 3e-7 after polishing (a 9-link instance).
SAME = 1e-6
#: Solutions from another attempt (another γ), or from a path's last point, are new
#: beyond this: two attempts' copies of an ill-conditioned solution (|y| ≈ 150 on
#: 13/N4962) differed by 7e-6.
POOLED = 1e-4
#: Tracking attempts (another γ, half the largest step each time).
ATTEMPTS = 3


@dataclass(frozen=True)
class QuadraticSystem:
    """m homogenised quadratic equations Y^T Q_i Y = 0 in Y = (y_0, y_1, …, y_m) and the
    map back to the Cartesian system's variables (in its order): x = offset + directions ·
    (scale y), y in the scaled unknowns."""

    forms: np.ndarray  # (m, m + 1, m + 1) real symmetric
    offset: np.ndarray  # (n,) x at y = 0
    directions: np.ndarray  # (n, m) ∂x/∂y
    scale: float

    @property
    def unknowns(self) -> int:
        return self.forms.shape[0]

    def cartesian(self, y: np.ndarray) -> np.ndarray:
        """The Cartesian variables at solutions ``y`` (K, m) of the scaled unknowns."""
        return self.offset + (self.scale * y) @ self.directions.T


@dataclass
class HomotopyResult:
    """The finite solutions (scaled unknowns, complex (K, m)), how many paths were
    followed and how many ended at infinity, and what failed."""

    solutions: np.ndarray
    paths: int
    at_infinity: int
    seconds: float
    undecided: list[str] = field(default_factory=list)


def _matrix(polynomial: dict, index: dict[str, int], size: int) -> np.ndarray:
    """The symmetric matrix M with polynomial = (1, x)^T M (1, x) (degree at most 2)."""
    matrix = np.zeros((size + 1, size + 1))
    for monomial, coefficient in polynomial.items():
        positions = [index[v] + 1 for v in monomial] + [0] * (2 - len(monomial))
        if len(positions) != 2:
            raise ValueError(f"the Cartesian system has a term of degree {len(monomial)}: quadratic systems only")
        i, j = positions
        matrix[i, j] += float(coefficient) / (1 if i == j else 2)
        if i != j:
            matrix[j, i] += float(coefficient) / 2
    return matrix


def quadratic_system(variables: list[str], polynomials: list[dict], scale: float = 1.0) -> QuadraticSystem:
    """The system's linear equations solved exactly and substituted into its quadratic
    ones (module docstring), the unknowns divided by ``scale`` and each equation by its
    largest coefficient. Raises ValueError where the quadratic equations are not as many
    as the unknowns left (the linkage is not rigid, or the system is inconsistent)."""
    index = {v: n for n, v in enumerate(variables)}
    size = len(variables)
    linear = [p for p in polynomials if max((len(m) for m in p), default=0) <= 1]
    quadratic = [p for p in polynomials if max((len(m) for m in p), default=0) == 2]
    rows = [[p.get((v,), 0) for v in variables] + [p.get((), 0)] for p in linear]
    entries = [flint.fmpq(Fraction(c).numerator, Fraction(c).denominator) for row in rows for c in row]
    reduced, rank = flint.fmpq_mat(len(rows), size + 1, entries).rref() if rows else (None, 0)
    pivots, offset = [], np.zeros(size)
    directions_exact = []
    for r in range(rank):
        row = [reduced[r, c] for c in range(size + 1)]
        pivot = next(c for c in range(size + 1) if row[c] != 0)  # the constant column: 0 = c ≠ 0
        if pivot == size:
            raise ValueError("the linear equations of the Cartesian system are inconsistent")
        pivots.append(pivot)
        directions_exact.append(row)
    free = [c for c in range(size) if c not in pivots]
    directions = np.zeros((size, len(free)))
    for c, f in enumerate(free):
        directions[f, c] = 1.0
    for pivot, row in zip(pivots, directions_exact, strict=True):  # x_p = −Σ row_f x_f − row_const
        offset[pivot] = -float(row[size])
        for c, f in enumerate(free):
            directions[pivot, c] = -float(row[f])
    if len(quadratic) != len(free):
        raise ValueError(f"{len(quadratic)} quadratic equations in {len(free)} unknowns after the linear ones: "
                         "the linkage is not rigid with these dimensions")
    substitution = np.zeros((size + 1, len(free) + 1))  # (1, x) = S (1, y)
    substitution[0, 0] = 1.0
    substitution[1:, 0] = offset
    substitution[1:, 1:] = directions * scale
    forms = np.array([substitution.T @ _matrix(p, index, size) @ substitution for p in quadratic])
    forms /= np.abs(forms).max(axis=(1, 2), keepdims=True)
    return QuadraticSystem(forms, offset, directions, scale)


def _jacobian(forms: np.ndarray, chart: np.ndarray, gamma: complex, t: np.ndarray, y: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(H_Y with the chart's row, H, H_t) at (Y, t) for every path: (P, m + 1, m + 1),
    (P, m + 1), (P, m + 1); H_t = q(Y) − γ g(Y), and 0 for the chart, which does not move.
    The target's rows 2 Q_i Y of all paths are one matrix product, and the start system's
    rows, two entries each, are added in place: built as full arrays and combined (an
    einsum and three passes over (P, m, m + 1) arrays), they took four fifths of the
    11-link example's time."""
    paths, width = y.shape
    m = width - 1
    target_rows = 2 * (y @ forms.reshape(m * width, width).T).reshape(paths, m, width)  # ∂(Y^T Q_i Y)/∂Y
    target = 0.5 * np.einsum("pij,pj->pi", target_rows, y)
    start = y[:, 1:] ** 2 - y[:, :1] ** 2
    weight = ((1 - t) * gamma)[:, None]
    jacobian = np.empty((paths, width, width), dtype=complex)
    np.multiply(t[:, None, None], target_rows, out=jacobian[:, :-1])
    diagonal = np.arange(m)
    jacobian[:, diagonal, diagonal + 1] += weight * (2 * y[:, 1:])  # ∂(y_i² − y_0²)/∂y_i
    jacobian[:, :-1, 0] -= weight * (2 * y[:, :1])  # ∂(y_i² − y_0²)/∂y_0
    jacobian[:, -1] = chart
    values = np.empty((paths, width), dtype=complex)
    values[:, :-1] = weight * start + t[:, None] * target
    values[:, -1] = y @ chart - 1
    rate = np.zeros(y.shape, dtype=complex)
    rate[:, :-1] = target - gamma * start
    return jacobian, values, rate


def _solve(matrices: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """A⁻¹ b for every path; NaN for a singular A (that path's step then fails). Where
    the batch holds a singular matrix it is halved until the singular ones stand alone:
    solving the others one by one made 25 000 solves, half of the 13-link example's time
    (7 singular matrices among ~3 800)."""
    try:
        return np.linalg.solve(matrices, vectors[..., None])[..., 0]
    except np.linalg.LinAlgError:
        if len(matrices) == 1:
            return np.full(vectors.shape, np.nan, dtype=np.result_type(matrices, vectors))
        half = len(matrices) // 2
        return np.concatenate([_solve(matrices[:half], vectors[:half]), _solve(matrices[half:], vectors[half:])])


def _velocity(forms, chart, gamma, t, y) -> np.ndarray:
    """dY/dt = −H_Y⁻¹ H_t along every path."""
    jacobian, _, rate = _jacobian(forms, chart, gamma, t, y)
    return -_solve(jacobian, rate)


def _corrected(forms, chart, gamma, t, y) -> tuple[np.ndarray, np.ndarray]:
    """Newton's corrections at t: the corrected points and whether they converged."""
    size = np.linalg.norm(y, axis=1)
    previous = np.full(len(y), np.inf)
    contracting = np.ones(len(y), dtype=bool)
    for _ in range(CORRECTIONS):
        jacobian, values, _ = _jacobian(forms, chart, gamma, t, y)
        step = _solve(jacobian, values)
        y = y - step
        change = np.linalg.norm(step, axis=1) / size
        contracting &= (change <= np.minimum(previous, 1.0)) | (change < ROUNDING)  # at rounding, no contraction
        previous = change
    return y, contracting & (previous < CORRECTION) & np.all(np.isfinite(y), axis=1)


def track(forms: np.ndarray, rng: np.random.Generator, largest_step: float = LARGEST_STEP,
          diverging: float = DIVERGING) -> tuple[np.ndarray, np.ndarray]:
    """Every path of the total-degree homotopy for ``forms`` from t = 0 to 1 (module
    docstring): the last points Y (P, m + 1) and each path's status: FINISHED at t = 1,
    INFINITE (after t = 1 − ENDGAME, |Y_0| below ``diverging`` of |Y|, or below
    COLLAPSED times that where the step collapses), or FAILED (its step fell below the
    smallest otherwise)."""
    m = forms.shape[0]
    gamma = complex(np.exp(2j * np.pi * rng.random()))
    chart = rng.normal(size=m + 1) + 1j * rng.normal(size=m + 1)
    signs = np.array(np.meshgrid(*([[1.0, -1.0]] * m), indexing="ij")).reshape(m, -1).T
    y = np.hstack([np.ones((len(signs), 1)), signs]).astype(complex)
    y /= (y @ chart)[:, None]
    paths = len(y)
    t = np.zeros(paths)
    step = np.full(paths, largest_step / 4)
    successes = np.zeros(paths, dtype=int)
    done = np.zeros(paths, dtype=bool)
    failed = np.zeros(paths, dtype=bool)
    infinite = np.zeros(paths, dtype=bool)
    for _ in range(MOST_STEPS):
        active = np.flatnonzero(~done & ~failed & ~infinite)
        if not len(active):
            break
        ya, ta = y[active], t[active]
        last = step[active] >= 1 - ta
        h = np.where(last, 1 - ta, step[active])
        k1 = _velocity(forms, chart, gamma, ta, ya)
        k2 = _velocity(forms, chart, gamma, ta + h / 2, ya + (h / 2)[:, None] * k1)
        k3 = _velocity(forms, chart, gamma, ta + h / 2, ya + (h / 2)[:, None] * k2)
        k4 = _velocity(forms, chart, gamma, ta + h, ya + h[:, None] * k3)
        predicted = ya + (h / 6)[:, None] * (k1 + 2 * k2 + 2 * k3 + k4)
        corrected, converged = _corrected(forms, chart, gamma, ta + h, predicted)
        accepted = active[converged]
        y[accepted] = corrected[converged]
        t[accepted] = np.where(last[converged], 1.0, ta[converged] + h[converged])  # t = 1 exactly at the end
        successes[accepted] += 1
        grow = accepted[successes[accepted] >= 3]
        step[grow] = np.minimum(2 * step[grow], largest_step)
        successes[grow] = 0
        rejected = active[~converged]
        step[rejected] /= 2
        successes[rejected] = 0
        done |= t >= 1
        ratio = np.abs(y[:, 0]) / np.linalg.norm(y, axis=1)
        endgame = (t > 1 - ENDGAME) & ~done
        infinite |= endgame & (ratio < diverging)
        collapsed = (step < SMALLEST_STEP) & ~done & ~infinite
        infinite |= collapsed & endgame & (ratio < COLLAPSED * diverging)  # singular, and not a real mode
        failed |= collapsed & ~infinite
    return y, np.where(done, FINISHED, np.where(infinite, INFINITE, FAILED))


def _distinct(points: np.ndarray, tolerance: float = SAME) -> tuple[np.ndarray, int]:
    """``points`` (K, m) without repeats (within ``tolerance`` relative to the larger of
    two), and how many were repeats. O(K²) comparisons, one array operation per point."""
    largest = np.abs(points).max(axis=1, initial=0.0)
    kept: list[int] = []
    for k, point in enumerate(points):
        if kept:
            limit = tolerance * np.maximum(max(1.0, largest[k]), largest[kept])
            if (np.abs(points[kept] - point).max(axis=1) <= limit).any():
                continue
        kept.append(k)
    return points[kept].reshape(-1, points.shape[1]), len(points) - len(kept)


def _polished(system: QuadraticSystem, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method at t = 1 on the affine equations, from the ends y (K, m): the
    points and whether each converged to a nonsingular solution."""
    forms = system.forms
    for _ in range(8):
        full = np.hstack([np.ones((len(y), 1)), y])
        rows = 2 * np.einsum("ijk,pk->pij", forms, full)[:, :, 1:]
        values = np.einsum("ijk,pj,pk->pi", forms, full, full)
        y = y - _solve(rows, values)
    full = np.hstack([np.ones((len(y), 1)), y])
    values = np.abs(np.einsum("ijk,pj,pk->pi", forms, full, full)).max(axis=1)
    rows = 2 * np.einsum("ijk,pk->pij", forms, full)[:, :, 1:]
    conditioned = np.zeros(len(y), dtype=bool)
    finite = np.isfinite(rows).all(axis=(1, 2))  # an end near infinity overflows; the SVD would not converge
    conditioned[finite] = np.linalg.cond(rows[finite]) < 1e12
    return y, (values < 1e-10 * np.maximum(1.0, np.abs(full).max(axis=1) ** 2)) & conditioned


def _finite_ends(system: QuadraticSystem, ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Which path ends (P, m + 1) lead by Newton's method at t = 1 to a nonsingular finite
    solution, and those solutions (in path order)."""
    chart = np.abs(ends[:, 0]) >= AT_INFINITY * np.linalg.norm(ends, axis=1)
    reached = np.zeros(len(ends), dtype=bool)
    with np.errstate(all="ignore"):  # ends near infinity overflow: they do not converge
        points, converged = _polished(system, ends[chart, 1:] / ends[chart, :1])
    reached[np.flatnonzero(chart)[converged]] = True
    return reached, points[converged]


def _with_conjugates(system: QuadraticSystem, found: np.ndarray) -> np.ndarray:
    """``found`` (K, m) and the complex conjugate of each non-real solution, polished at
    t = 1 and kept where Newton's method converges and it is not already among them (the
    conjugates already found are dropped as repeats): the equations are real, so the
    conjugate of a solution is one. A path that ends at one
    of a pair does not make the other's path end well (13/N20086: a solution with
    |y| ≈ 1.9·10³ reached, its conjugate not). O(K²)."""
    size = np.maximum(1.0, np.abs(found).max(axis=1, initial=0.0))
    non_real = np.abs(found.imag).max(axis=1, initial=0.0) > REAL * size
    conjugates = found[non_real].conj()
    if not len(conjugates):
        return found
    with np.errstate(all="ignore"):
        polished, converged = _polished(system, conjugates)
    return _distinct(np.vstack([found, polished[converged]]), POOLED)[0]


def _how_complex(ends: np.ndarray) -> str:
    """How far from real the failed paths' last points are (the least of max |Im y| / |y|
    over them), so that a reader can judge whether a real mode could be among them."""
    if not len(ends):
        return ""
    with np.errstate(all="ignore"):
        points = ends[:, 1:] / ends[:, :1]
        least = float(np.nanmin(np.abs(points.imag).max(axis=1) / np.abs(points).max(axis=1)))
    return f" (their last points' imaginary parts: at least {least:.2g} of their size)"


def solve_system(system: QuadraticSystem, seed: int = 0, bound: float = 0.0) -> HomotopyResult:
    """Every finite solution of ``system`` (module docstring), in its scaled unknowns;
    ``bound``: the largest coordinate (scaled) of a real solution, if known."""
    diverging = 0.1 / math.sqrt(1 + system.unknowns * bound**2) if bound else DIVERGING
    start = time.perf_counter()
    rng = np.random.default_rng(seed)
    found = np.zeros((0, system.unknowns), dtype=complex)
    undecided: list[str] = []
    largest_step = LARGEST_STEP
    at_infinity = 0
    for attempt in range(ATTEMPTS):
        ends, status = track(system.forms, rng, largest_step, diverging)
        reached, points = _finite_ends(system, ends)
        finished = reached & (status == FINISHED)
        own, repeats = _distinct(points[finished[reached]])
        # a path taken to infinity, or whose step collapsed, may still be near a finite
        # solution: Newton's method at t = 1 from its last point settles it (kept if new)
        found, _ = _distinct(np.vstack([found, own, points[~finished[reached]]]), POOLED)
        at_infinity = int((~reached & (status != FAILED)).sum())
        failures = int((~reached & (status == FAILED)).sum()) + int((~reached & (status == FINISHED) & (
            np.abs(ends[:, 0]) >= AT_INFINITY * np.linalg.norm(ends, axis=1))).sum())
        if not repeats and not failures:
            undecided = []
            break
        undecided = [f"homotopy: {failures} of {len(ends)} paths failed{_how_complex(ends[~reached & (status == FAILED)])}"
                     f" and {repeats} ended at a solution another path had reached (path jumping) in {attempt + 1} "
                     "attempts; the solutions found are pooled, and a solution may be missing"]
        largest_step /= 2
    found = _with_conjugates(system, found)
    return HomotopyResult(found, len(ends), at_infinity, time.perf_counter() - start, undecided)


def homotopy_configurations(scene: Scene, seed: int = 0) -> tuple[list[dict[str, tuple[float, float]]],
                                                                    HomotopyResult]:
    """Every real configuration of ``scene`` (exact dimensions) from the finite solutions
    of its Cartesian system, refined in real arithmetic, and the homotopy's result."""
    variables, polynomials, names, signs = cartesian_system(scene, rounded_ground=True)
    scale = max(1.0, max(abs(float(x)) for point in scene.world.values() for x in point))
    scale = max(scale, math.sqrt(max(float(v) for link in scene.links for v in link.squared_distances.values())))
    system = quadratic_system(variables, polynomials, scale)
    reach = distance_bound(scene) + max(abs(float(x)) for point in scene.world.values() for x in point)
    result = solve_system(system, seed, reach / scale)
    real = result.solutions[np.abs(result.solutions.imag).max(axis=1, initial=0.0) <= REAL]
    refined, converged = _polished(system, real.real)
    index = {v: n for n, v in enumerate(variables)}
    configurations = []
    for x in system.cartesian(refined[converged]):
        if any(x[index[m]] * sign < 0 for m, sign in signs.items()):
            continue  # the auxiliary square root has the wrong sign: a mirrored link
        point = {j: (float(x[index[a]]), float(x[index[b]])) for j, (a, b) in names.items()}
        point.update({scene.point_name(scene.ground, j): (float(a), float(b)) for j, (a, b) in scene.world.items()})
        configurations.append(point)
    return configurations, result


def solve_homotopy(scene: Scene, seed: int = 0) -> Solution:
    """All real assembly modes of ``scene`` (exact dimensions, revolute joints) from every
    complex solution of its Cartesian system (module docstring), each verified on every
    link dimension and described in the terms of the truss's best plan, whatever its
    coupling degree. What the homotopy could not settle is in ``undecided``. Raises
    :class:`SolverError` for inexact dimensions or a system that is not square after its
    linear equations (a linkage that is not rigid).

    >>> from baranov.scene import load_scene
    >>> solution = solve_homotopy(load_scene("examples/7-B1.json"))
    >>> len(solution.assembly_modes), solution.undecided
    (8, ())
    """
    if not scene.exact:
        raise SolverError("the homotopy method needs exact dimensions (integers, decimals or fractions such as "
                          "\"9/5\"; a float from Python is binary): its linear equations are solved exactly")
    try:
        configurations, result = homotopy_configurations(scene, seed)
    except ValueError as error:
        raise SolverError(f"homotopy: {error}") from None
    plan = description_plan(scene)
    modes = modes_of_configurations(scene, plan, configurations, "homotopy")
    return Solution.of_plan("homotopy", scene, plan, modes, undecided=tuple(result.undecided))
