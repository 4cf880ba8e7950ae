"""Stability study: where each method fails, on instances made to be hard (issue 6).

Writes ``docs/stability.md``; every number in it comes from this run.

    python bench/stability.py [--time-limit 60]

Cases: the six 3-RPR examples of thesis §5.1.3; a family whose two assembly modes merge
(a 3-RPR pentad at a singular configuration, one leg lengthened by δ); a mode at a branch
boundary (a free-sign triangle of zero area); nearly collinear ternary links; nearly
coincident joints; and the conditioning of the modes under a relative perturbation ε of
every link dimension. The scenes come from :mod:`baranov.scene.hard_instances`, which
tests/test_stability.py uses too.
"""

from __future__ import annotations

import argparse
import math
import time
from fractions import Fraction
from pathlib import Path

import numpy as np
from speed_vs_accuracy import outcome, timed_run

from baranov.enumerate import baranov_trusses
from baranov.scene import Scene, load_scene
from baranov.scene.hard_instances import (
    SINGULAR_BASE,
    SINGULAR_PLATFORM,
    branch_boundary_scene,
    coincident_joints_scene,
    collinear_platform_scene,
    merging_scene,
    perturbed_scene,
)
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import characteristic_polynomial
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.verification import RESIDUAL_TOLERANCE, distance_bound, same_mode

ROOT = Path(__file__).resolve().parents[1]
METHODS = ("numeric", "exact", "cartesian-100", "loop-equations", "float64-polynomial", "mpmath100-polynomial")
#: Assembly modes the thesis reports for the 3-RPR examples of §5.1.3 (Figs. 5.2–5.7).
THESIS_MODES = {"I": 1, "II": 4, "III": 4, "IV": 4, "V": 4, "VI": 2}


def _cell(scene, result, reference) -> str:
    solution, _, status = result
    if solution is None:
        return status.split(":")[0]
    found, missed, spurious = outcome(scene, solution, reference)
    return f"{found} / {missed} / {spurious}"


def three_rpr(limit: float) -> list[str]:
    lines = ["| example | thesis modes | reference | " + " | ".join(METHODS) + " |",
             "|---|---:|---|" + "---|" * len(METHODS)]
    for name, expected in THESIS_MODES.items():
        scene = load_scene(ROOT / "examples" / f"3-RPR-{name}.json")
        results = {m: timed_run(m, scene, limit) for m in METHODS}
        source = "exact" if results["exact"][0] else "numeric"
        reference = results[source][0].assembly_modes
        kind = source if source == "exact" else "numeric; exact fails: irrational input"
        cells = [_cell(scene, results[m], reference) for m in METHODS]
        lines.append(f"| {name} | {expected} | {len(reference)} ({kind}) | " + " | ".join(cells) + " |")
    return lines


def merging(limit: float) -> list[str]:
    lines = ["| δ | certified separation of the two roots (relative) | " + " | ".join(
        f"{m}: modes near" for m in METHODS) + " |", "|---|---|" + "---|" * len(METHODS)]
    original = merging_scene(Fraction(0))
    centre = {j: complex(float(x), float(y)) for j, (x, y) in {**SINGULAR_BASE, **SINGULAR_PLATFORM}.items()}
    scale = distance_bound(original)
    for exponent in range(2, 26, 2):
        delta = Fraction(36, 10 ** exponent)
        scene = merging_scene(delta)
        roots = sorted(float(r.mid()) for r in characteristic_polynomial(scene).real_roots())
        target = _parameter_at(scene, centre)
        near = sorted(roots, key=lambda r: abs(r - target))[:2]
        separation = abs(near[0] - near[1]) / target if len(near) == 2 else math.nan
        cells = []
        for method in METHODS:
            solution, _, status = timed_run(method, scene, limit)
            if solution is None:
                cells.append(status.split(":")[0])
                continue
            close = [m for m in solution.assembly_modes if m.max_residual < RESIDUAL_TOLERANCE and max(
                abs(complex(*m.joints[j]) - centre[j]) for j in centre) < 0.05 * scale]
            cells.append(str(len(close)))
        lines.append(f"| 36·10^-{exponent} | {separation:.2g} | " + " | ".join(cells) + " |")
    return lines


def _parameter_at(scene: Scene, points: dict[str, complex]) -> float:
    u, v = solvable_plan(scene).parameters[0]
    return abs(points[u] - points[v]) ** 2


def families(limit: float) -> list[str]:
    cases = [("branch boundary (7-link, flat free-sign triangle)", branch_boundary_scene())]
    cases += [(f"nearly collinear platform, height {h}", collinear_platform_scene(Fraction(h)))
              for h in ("1/10", "1/1000", "1/100000", "1/10000000")]
    cases += [(f"nearly coincident joints P1, P4, distance {g}", coincident_joints_scene(Fraction(g)))
              for g in ("1/100", "1/10000", "1/1000000", "1/100000000")]
    lines = ["| case | reference modes (exact) | " + " | ".join(METHODS) + " |",
             "|---|---:|" + "---|" * len(METHODS)]
    for label, scene in cases:
        results = {m: timed_run(m, scene, limit) for m in METHODS}
        reference = results["exact"][0].assembly_modes
        lines.append(f"| {label} | {len(reference)} | " + " | ".join(
            _cell(scene, results[m], reference) for m in METHODS) + " |")
    return lines


def conditioning(limit: float) -> list[str]:
    """Change of the modes (joint displacement relative to the linkage's size) divided by
    ε, per method; the exact backend's figure is the linkage's own sensitivity."""
    rng = np.random.default_rng(11)
    truss = baranov_trusses(7)[1]
    coordinates = generic_integer_configuration(truss, rng)
    base_scene = scene_of(truss, coordinates)
    links = [(link.name, {j: coordinates[j] for j in link.joints}) for link in base_scene.links]
    links.sort(key=lambda item: item[0] != base_scene.ground)
    methods = ("numeric", "exact", "cartesian-100", "float64-polynomial", "mpmath100-polynomial")
    original = {m: timed_run(m, base_scene, limit)[0] for m in methods}
    reference = original["exact"].assembly_modes
    scale = distance_bound(base_scene)
    lines = ["| ε | " + " | ".join(methods) + " |", "|---|" + "---|" * len(methods)]
    for exponent in (3, 6, 9, 12):
        epsilon = 10.0 ** -exponent
        scene = perturbed_scene(links, epsilon, np.random.default_rng(0))  # one direction for every ε
        cells = []
        for method in methods:
            before = [m for m in (original[method].assembly_modes if original[method] else ())
                      if m.max_residual < RESIDUAL_TOLERANCE and any(same_mode(m, r, base_scene) for r in reference)]
            solution = timed_run(method, scene, limit)[0]
            after = [m for m in (solution.assembly_modes if solution else ()) if m.max_residual < RESIDUAL_TOLERANCE]
            ratios = [min(max(math.dist(m.joints[j], n.joints[j]) for j in m.joints) for n in after) / scale / epsilon
                      for m in before] if after else []
            cells.append(f"{np.median(ratios):.3g} ({len(before)} of {len(reference)} modes)" if ratios else "no modes")
        lines.append(f"| 1e-{exponent} | " + " | ".join(cells) + " |")
    return lines


def one_dof() -> list[str]:
    """Issue 19's stability cases of the driven motion against the numeric backend on the
    linkage rigidified at the input (:func:`baranov.motion.driving.rigidified`): a
    double-rocker's dead point, a change-point four-bar through its in-line
    configuration, and one random configuration of each eight-bar."""
    from baranov.enumerate.grubler import grubler_chains
    from baranov.motion import one_dof_system, trace
    from baranov.motion.continuation import linkage_curve
    from baranov.motion.driving import (
        _with_extrema,
        crank_of,
        distinct_configurations,
        driven_motion,
        input_value,
        rigidified,
    )
    from baranov.scene import SceneInput, scene_from_dict
    from baranov.scene.instances import instance_dict
    from baranov.solvers import solve
    from baranov.solvers.msolve import compare_modes

    def four_bar(ground, crank, coupler, rocker):
        return scene_from_dict({"ground": "frame", "links": [
            {"name": "frame", "joints": {"P1": [0, 0], "P4": [ground, 0]}},
            {"name": "crank", "joints": ["P1", "P2"], "squared_length": crank ** 2},
            {"name": "coupler", "joints": ["P2", "P3"], "squared_length": coupler ** 2},
            {"name": "rocker", "joints": ["P3", "P4"], "squared_length": rocker ** 2}]})

    def compared(scene, driver, angle):
        system = one_dof_system(scene)
        found = [p.joints for p in distinct_configurations(driven_motion(system, trace(system), driver, [angle]),
                                                           angle, 360)]
        modes = [m.joints for m in solve(rigidified(scene, driver, angle), method="numeric").assembly_modes]
        missed, spurious, _ = compare_modes(found, modes)
        return f"{len(found)} / {len(modes)} / {missed} / {spurious}"

    crank = SceneInput("crank", "angle", ("P1", "P4", "P2"))
    rocker = four_bar(6, 5, 2, 7)
    system = one_dof_system(rocker)
    sampled = max(input_value(crank, p) for piece in trace(system).pieces for p in piece.points)
    refined = max(input_value(crank, p) for piece in trace(system).pieces
                  for p in _with_extrema(system, linkage_curve(rocker, system.plan.free_sign_triangles), crank,
                                         piece).points)
    dead = math.degrees(math.acos(-1 / 3))
    lines = ["| case | crank angle | driven / numeric / missed / spurious |", "|---|---|---|"]
    lines += [f"| double-rocker (6, 5, 2, 7), dead point arccos(−1/3) = {dead:.7f}° | dead point {offset:+g}° | "
              f"{compared(rocker, crank, dead + offset)} |" for offset in (-1e-2, -1e-5, 1e-5)]
    change = four_bar(5, 2, 4, 3)
    lines += [f"| change-point (5, 2, 4, 3), every joint in line at 180° | {angle:g}° | "
              f"{compared(change, crank, angle)} |" for angle in (180.0, 179.0, -179.0)]
    lines += ["", f"The double-rocker's highest sampled crank angle: {sampled:.7f}°; located as an extremum "
                  f"of the input: {refined:.10f}° ({refined - dead:+.1e}° from arccos(−1/3)).", ""]
    rows = ["| eight-bar | pieces | configurations compared | missed / spurious |", "|---|---|---|---|"]
    for index, chain in enumerate(grubler_chains(8)):
        rng = np.random.default_rng([19, 8, index])
        drawn = generic_integer_configuration(chain, rng)
        scene = next(s for s in (scene_from_dict(instance_dict(chain, drawn, g)) for g in range(8)) if crank_of(s))
        driver = crank_of(scene)
        system = one_dof_system(scene)
        traced = trace(system)
        branches = driven_motion(system, traced, driver, -180 + 30 * np.arange(12))
        total = missed = spurious = 0
        for angle in -180 + 30 * np.arange(12):
            found = [p.joints for p in distinct_configurations(branches, float(angle), 360)]
            modes = [m.joints for m in solve(rigidified(scene, driver, float(angle)), method="numeric").assembly_modes]
            counts = compare_modes(found, modes)
            total, missed, spurious = total + len(modes), missed + counts[0], spurious + counts[1]
        rows.append(f"| {index} | {len(traced.pieces)} | {total} | {missed} / {spurious} |")
    return lines + rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds per solve")
    args = parser.parse_args()
    start = time.perf_counter()
    sections = {"rpr": three_rpr(args.time_limit), "merging": merging(args.time_limit),
                "families": families(args.time_limit), "conditioning": conditioning(args.time_limit),
                "one_dof": one_dof()}
    collinear = ROOT / "docs" / "bench" / "collinear-joints.md"
    sections["collinear"] = [collinear.read_text(encoding="utf-8").strip() if collinear.exists()
                             else "(not run: see the command above)"]
    # one report per run (bench/adversarial.py --report): 7 and 9 links, 11 links, earlier commits
    reports = sorted((ROOT / "docs" / "bench").glob("adversarial*.md"))
    sections["adversarial"] = ["\n\n".join(f"### {report.stem}\n\n" + report.read_text(encoding="utf-8").strip()
                                            for report in reports) or "(not run: see the command above)"]
    text = TEMPLATE.format(limit=args.time_limit, elapsed=time.perf_counter() - start,
                           **{k: "\n".join(v) for k, v in sections.items()})
    (ROOT / "docs" / "stability.md.tmp").write_text(text, encoding="utf-8")
    (ROOT / "docs" / "stability.md.tmp").replace(ROOT / "docs" / "stability.md")
    print(text)


TEMPLATE = """# Stability: where methods fail

Generated by `python bench/stability.py` (`make bench`); do not edit by hand. Time limit
{limit:g} s per solve; the run took {elapsed:.0f} s. Methods as in
[benchmarks.md](benchmarks.md). Cells read *found / missed / spurious* against the
reference modes (a mode is found when a reported mode lies within 1e-6 of the
linkage's size and is verified to 1e-8; spurious: reported but not a verified reference
mode). tests/test_stability.py pins the project's backends on these cases.

## The six 3-RPR examples of thesis §5.1.3

Reference: the exact backend's modes (the numeric backend's for Example V, whose input is
irrational); the thesis column is the number of modes the thesis reports (Figs. 5.2–5.7).

{rpr}

## Two assembly modes merging

The pentad drawn at a singular configuration (the three leg lines meet at one point,
two assembly modes coincide), leg P1P4 lengthened from squared length 36 by δ: the two
modes separate like √δ. Second column: the relative distance between the two real roots of
the characteristic polynomial nearest the drawn configuration (certified, flint/arb);
then, per method, how many verified modes it reports within 5 % of the linkage's size of
the drawn configuration (2 = both resolved).

{merging}

## Branch boundary, nearly collinear links, nearly coincident joints

{families}

## Joints in line (issue 28)

Random integer configurations of every nine-link truss with three or four joints on one
line (vertical, horizontal, diagonal, antidiagonal in turn; coordinates in [−4, 4]²;
`baranov.scene.hard_instances.collinear_joints_configuration`), both backends: does each
return the generating configuration, do they agree mode for mode, is the exact solve
certified complete. The report below is written by `bench/sweep_collinear.py --out
docs/bench/collinear-joints.md` (not rerun by this script: `make bench-collinear`, 11 min measured) and copied
here. Before it, issue 28's instance (`tests/regressions/9-B28-joints-in-line.json`) lost
a mode in the exact backend; the first runs of the sweep then found ten instances where a
backend lost or doubled a mode, in six ways (five numeric, one exact), each caused by a
flat triangle or coincident joints in a mode; one instance of each is saved in
tests/regressions/ (`9-B28-joints-in-line-fold.json`, `9-joints-in-line-*.json`) with
what was lost and why, and all are fixed (docs/exact.md, "What the exact backend
guarantees"; docs/numeric-log.md, "Flat triangles").

{collinear}

## Adversarial instances against msolve (issue 25)

Instances drawn as users type them (`baranov.scene.adversarial`): every joint at an
integer point of a small box (`small-box`, [−3, 3]²), three or four joints on one line
(`collinear`), two joints of different links at one point (`coincident`), a free-sign
triangle of the plan flat so that the generating mode is on the edge of the parameters'
domain (`domain-edge`), and configurations where the framework with its ground pinned is
infinitesimally flexible, so that two modes merge there (`double-root`, [−2, 2]²; exact
rank of the rigidity matrix). Both backends are compared, configuration by configuration
(every joint within 1e-6 of the linkage's size: with the ground fixed, all pairwise
distances), with msolve's real solutions of the Cartesian system
(`baranov.solvers.msolve`: each rigid link imposed exactly, its orientation included),
which shares no code with the backends. The report below is written by
`bench/adversarial.py --report docs/bench/adversarial*.md` (`make bench-adversarial`, not
rerun by this script), one report per run, and copied here.

The first runs (1156 instances of the same generator — 630 of 7 links, 526 of 9 — before
the fixes) found, among
others: the exact backend certifying a list that missed a mode at s1,10 = 0 (9/N2), or
that missed the modes where base joints of its plan coincide and no other plan is defined
(7/N2, 9/N3, 9/N5, 9/N8 — up to 8 of 14 modes), and certifying 8 isolated modes of a
linkage that in fact moves (7/N2 drawn with P1 = P6 = P8); the numeric backend missing
modes at double roots and at coincidences, and running over 300 s on five instances
(rounding noise where a triangle is flat along a branch or the linkage moves). Each cause
is explained in docs/exact.md (step 9) and docs/numeric-log.md ("Adversarial instances"), one
instance of each saved in tests/regressions/ (tests/test_adversarial.py checks them
against msolve).

A run at commit 1321092 (1489 instances, 7 and 9 links, 10 per truss and kind) left these
open: near-copies of a singular mode flat to rounding (numeric, 9/N15 and 9/N22), a mode
missed at a domain edge (numeric, 9/N21 and 9/N24), two coupling-2 solves of 9/N18 over a
minute, and 9/N17 (two joints of one link at one point) refused by both backends. A second
run at commit cf3048e (3022 of 3100 instances, 20 per truss and kind; report
`adversarial-cf3048e` below) found four more, each fixed since with its instance saved:
a tangential root beside a simple one and a root below the first sample (numeric,
9/N6 and 9/N7: docs/numeric-log.md), a genuine factor left undecided by flint's branch cut
(exact, not certified, 9/N13: docs/exact.md step 4), and 9/N17 drawn with two joints of
one link at one point, which no plan can solve — both backends now say it moves (msolve:
positive-dimensional) instead of only refusing it. The fixes before that run: noise roots
in a flat valley around a singular mode are one mode, reported as *undecided* (9/N15,
9/N22), a root 8.7e-8 past a domain edge (9/N24), two triangles flat at one touching point
(9/N21), and the coupling-2 slow cases (9/N18: Newton retried failed steps on 10⁵ starts,
candidates were verified one at a time): its two slowest small-box instances took 46 and
36 s before, 18 and 13 s after (one bench worker running beside both measurements).

The third run (`adversarial-e0f302d` below: `make bench-adversarial`, 930 new instances of 7 and 9
links and 44 of eleven-link trusses, at commit e0f302d) found no miss on 7 and 9 links,
but the time bound fails there: a coupling-1 instance of 9/N10 drawn at a flexible
configuration took the numeric backend 198 s (p99/median 409 on that truss), where the
closure condition is noise over long stretches and every noise sign change was bracketed
(profile: 16 470 Brent brackets, 500 773 plan evaluations; 32 s once the re-sampling
beside roots and of local minima was capped, 1.4 s since sign changes and minima that
rounding decides are one stretch — docs/numeric-log.md, `tests/regressions/9-N10-noise-brackets.json`); and
the exact backend ran over its 300 s limit on 8 of the 14 coupling-2 eleven-link instances
(issue 24: the coupling-2 lifting is 100× slower than msolve there). On 11/N561 (coupling
2, double-root) the numeric backend placed a singular mode 2e-4 from msolve's (1 missed,
1 spurious): of the 648 verified configurations in its flat valley it reported the one
nearest all others; now the one nearest the middle of the valley's parameter box, 1.2e-6
from msolve's, 1.2e-4 after the bilateration kernel changed the rounding (a singular mode
located coarsely; `tests/regressions/11-N561-double-root.json`).

The fourth run (`adversarial-6b7e07d` below: 4500 seven-link instances, 300 per truss and
kind, and the first 1582 of 5600 nine-link ones, instance by instance over all trusses
and kinds, at the solving code of commit 6b7e07d) found one miss in 6059 finite
instances, numeric, none exact: 9/N4 drawn at a domain edge, a triangle touching flat
beside a sample failing at an earlier step (fixed, `9-N4-touching-beside-earlier-failure.json`).
It counted as a failure an instance that is not one: 7/N2 drawn with P2 on P7, where
msolve finds a positive-dimensional solution set but the linkage does not move — a
complex curve passes through an isolated real mode, which the numeric backend reports
(`7-N2-complex-curve.json`; the bench now tests such modes for a real motion). Its time
bound fails on four nine-link trusses: p99/median 34.4 (9/N18) and 28.0 (9/N28), both
coupling 2, where one movable 9/N18 instance (four joints at one point) ran past 300 s
(fixed since, below), and 18.5 (9/N17) and 17.4 (9/N8), coupling 1, whose slowest
instances spent their time on shallow minima and crowded noise (11.4 → 3.1 s and
14.1 → 1.9 s alone since: docs/numeric-log.md).

The fifth run (`adversarial-1174e5b` below: at the solving code of commit 1174e5b, 4500
seven-link and 2790 nine-link instances, then stopped) found no missed mode in 7265
finite instances, and six kinds of failure, five fixed since (their instances saved in
tests/regressions/) and one open:

- 9/N18 drawn with four joints at one point (the fourth run's open instance) moves along
  the line s2,5 = 2, which both closure conditions share: the numeric backend's Newton
  converged to 450 066 distinct points of it (over 300 s), the exact backend raised a bare
  ValueError. Both now raise MovableLinkageError: the numeric one continues a path of
  verified configurations along the Jacobian's kernel, the exact one finds a real
  configuration on the common factor of its two curves
  (`movable/9-N18-shared-curve.json`; docs/numeric.md, "Coupling degree 2").
- 9/N27 and 9/N18 (coupling 2): the exact backend crashed with OverflowError inside
  python-flint 0.9's `fmpz_mpoly.factor`, whose factor-sorting key converts coefficients
  to a C int; it now factors over Q where that happens (`9-N27-flint-factor-overflow.json`).
  The crash also stalled the run for 35 minutes (the bench caught only ValueError, and
  its pool then waited on every queued instance); the bench now records any exception.
- 9/N8 drawn at a double root: the numeric backend listed a fifth mode verified to
  6.3e-9, a minimum of |f| just above 0 that polishing does not close
  (`9-N8-near-double-root.json`); such near misses are now named in `undecided`.
- 9/N19 drawn at a double root: the closure condition is flat to rounding on
  [8.9899, 9], where the domain ends in the mode; the middle of the stretch was listed
  as a mode on two branches (`9-N19-flat-valley-at-edge.json`); a stretch cut off by the
  domain now gives its edge.
- 9/N12 drawn with two joints of one link at one point: no plan avoids that pair as a
  base and both backends refused the scene, where msolve lists 4 modes; both now list
  msolve's modes, verified (`9-N12-no-plan-coincident-input.json`).
- 9/N28 drawn with joints in line: the exact backend ran over 300 s (issue 24: the
  coupling-2 lifting; 81–142 s on five more 9/N28 instances). Open.

Its numeric time bound failed on 9/N28 (p99/median 41: one small-box instance took
133 s, where the two conditions' zero curves run within a cell of each other along a long
arc and every suspect cell started Newton; 16 s with Newton started only at local minima,
docs/numeric-log.md) and on 9/N18 (the movable instance). A check of the changed coupling-2
search against msolve (90 instances of 9/N18, 9/N27 and 9/N28, seed 77): 0 missed,
0 spurious, numeric median 2.8 s, max 18.4 s, p99/median per truss at most 6.1.
Because the fixes changed the solving code, the 10⁴-instance count restarted with a
sixth run on fresh instances (seed 27; rows in bench/results/adversarial.jsonl). At the
solving code of commit d8991b4 its 4500 seven-link instances gave one failure, a numeric
miss: 7/N1 drawn at a double root, a mode where the branch's domain begins with one
triangle flat and another nearly so, whose fold candidate took both flat
(`7-N1-fold-one-of-two-flat.json`; docs/numeric-log.md). Fixed, and the sixth run began again
at the fixing commit (0277a59): 4500 seven-link instances without a failure, then 692
nine-link ones without a miss, until one solve ran the machine out of memory: 9/N9 drawn at
a double root, movable (msolve: positive-dimensional; the exact backend says so at once),
where the feasible domain flickers at rounding noise (5248 defined/undefined transitions
on one branch, each given an edge search) and the numeric backend grew past 24 GB. The
kernel killed that worker, which broke the run's process pool, and the queued nine-link
instances were lost. The failing step of the plan flickers with rounding noise there, and
the window refinement multiplied its cells by up to 64 per level (215 million samples at
the fourth); it now stops past 4096 cells, and the solve raises MovableLinkageError in
51 s with 194 MB (`movable/9-N9-domain-flicker.json`; still slow). The bench also caps
each worker's memory now (`--memory`, 8 GiB), so that a runaway solve is recorded as an
error.

The seventh run (`adversarial-b153983` below: seed 28, at the solving code of commit
b153983, where that 9/N9 solve takes 2.6 s since all domain edges of a branch are searched
together) ran its 4200 nine-link instances and found two numeric misses, both fixed: 9/N17
drawn at a double root, whose branch is defined at one point only, between two steps that
fail on either side (`9-N17-crossing-radicands.json`), and 9/N2 (coupling 2) drawn at a
double root, whose branch is defined only on a line of the parameter plane
(`9-N2-ridge-domain.json`). 1402 of its nine-link rows were lost from the results file (a
`git stash` in the working copy replaced the file while the run appended to it; the run's
log kept both failures). A run at the first fix (3270841, seed 29) found a third miss in its
first 698 instances: 9/N12 in a small box, six modes on a stretch below one where a
free-sign triangle is flat, whose ±1 branches had been replaced by the flat one
(`9-N12-flat-on-a-stretch.json`). The count restarted at the commit with the three fixes
(c2da5af, seed 30): in 1800 nine-link instances one more miss, 9/N18 (coupling 2) drawn at a
double root, whose two near-tangent modes 0.046 apart were merged as one singular valley and
then dropped as a near miss (`9-N18-two-roots-one-valley.json`); fixed, and the count
restarted again at that commit (1c67c01, seed 31). The slider work then changed the
solving code twice: a run at faf85ef (seed 32) gave 3634 nine-link instances without a miss
in either backend, and one at 66d6af0 (seed 33, `adversarial-66d6af0` below) all 4200
nine-link and 1254 seven-link instances with the exact backend 0 / 0 and one numeric miss:
9/N27 drawn at a double root, where link L5 has its joints in line and the mode sits in a
valley of the link dimensions flat to rounding 1.4e-2 wide, whose representative was
2.4e-4 from msolve's mode (`9-N27-double-root-25.json`; fixed by refining valleys on the
rigid-link model, docs/numeric-log.md). The count restarted at that fix (6a629ab, seed 34; 149
nine-link instances, 0 / 0 in both backends) and, once the notation change of issue 26 had
renamed the parameters, at 88e104a (seed 35): 3919 nine-link instances, the exact
backend 0 / 0, the numeric one three misses, all coupling 2 and singular: 9/N2 drawn at a
double root where one condition touches 0 inside the domain (`9-N2-touching-inside.json`),
and 9/N27 and 9/N28 with modes on an edge line along which one condition vanishes
(`9-N27-edge-double-root.json`, `9-N28-modes-on-edge-line.json`); fixed (docs/numeric-log.md),
and the count restarted at that fix (d4f5a64, seed 36, `adversarial-d4f5a64` below): all
4200 nine-link instances, 0 missed and 0 spurious in both backends; then, in the first 2374
seven-link instances, **the exact backend certified 4 of 8 modes, twice, on 7/N2**
(small-box 30 and double-root 107; the numeric backend found all 8). The 4 missed modes
have P1 = P8 (s1,8 = 0): clearing the denominators of eq. 2.7 had removed the factor s1,8
from the characteristic polynomial, and the exact backend only examined coincidences at
its roots. Both backends now examine every joint pair the plan divides by, the
parameter's own joints included (2ae9a11, docs/exact.md step 9;
`7-N2-parameter-joints-coincide*.json`). Since that fix the exact backend has certified
no incomplete list, and missed a mode only where it said so: all modes, certified, on 7093
instances at 2ae9a11 (seed 37, `adversarial-2ae9a11` below), 7035 at 5ae6c72 (seed 38,
`adversarial-5ae6c72`), and 7378 of 7379 at 3eb446264259 (seed 39, `adversarial-97681e7`:
all 6000 seven-link and 1404 nine-link instances), where the one other, 9/N21 double-root
6, was not certified: the norm of its closure condition vanishes identically in the best
plan's parameter s8,10, and the exact backend listed no mode where msolve lists one. A
vanishing norm belongs to the parametrisation, not always to the linkage: another
parameter (s7,12) gives a certified polynomial with that mode, and the exact backend now
tries other parameters where the norm vanishes (ffd6819, docs/exact.md;
`9-N21-vanishing-norm-seed39.json`). **At that fix (solving code b1d66af6ef8f, commit
0d3aac6, seed 40, `adversarial-0d3aac6` below) the exact backend listed every mode and
certified every list on all 10 163 finite instances of 7 and 9 links (6000 and 4200
drawn, 37 movable, said so), 0 missed and 0 spurious: issue 25's target for the exact
backend.** The numeric backend missed 3 modes there (2 spurious): 9/N19 collinear 15, a
tangential root two sampling cells from a crossing one (fixed at 5bc4a33, docs/numeric-log.md;
`9-N19-collinear-15-seed40.json`), and two coupling-2 singular modes (9/N18 double-root 9
and 9/N28 domain-edge 21, each with two joints at one point) reported as a valley of
verified configurations whose representative lies 1e-3 and 2e-3 from msolve's mode (open:
`tests/regressions/open/*-seed40.json`). Earlier runs found numeric misses of the same
kinds, a tangential root beside a crossing one or a shallow root (seed 37, 7/N2; seed 38,
7/N1; a random robot), each fixed with its instance saved (docs/numeric-log.md). Solve times
were measured beside other jobs on both cores. On 11 links (every 56th truss, 53 of 55
instances) the exact backend was 0 / 0 too, but ran over the run's 300 s limit on three
coupling-2 instances (11/N393, 11/N561), where the numeric backend took 3-4 s; the
numeric backend listed one spurious mode (11/N57 double-root 0, open). The issue-25
targets not met yet: no numeric miss at one commit, and the time bound (numeric p99/median per truss at
most 11.8 where the target is 10, max 40.1 s; the exact backend's coupling-2 outliers up
to 134.3 s on 9/N28, where msolve takes under 1 s).

**Seed 41** (solving code 6d0004611ed8, commit 9445ea6, `adversarial-9445ea6` below)
restarted the count after the three open numeric cases of seed 40 were fixed (9445ea6:
singular valleys refined by pseudo-inverse Gauss–Newton steps on the rigid-link model, one
root per stretch where f's sign is rounding noise; docs/numeric-log.md). On all 6000
seven-link and 4200 nine-link instances (10 157 finite, 43 movable and said so by both
backends) the exact backend again listed every mode and certified every list, 0 missed
and 0 spurious. The numeric backend missed 2 modes, both at a domain edge on 9 links:
9/N7 domain-edge 3 (coupling 1: an undefined gap between the first two defined samples,
its mode at the gap's far edge; fixed at fad5713, `9-N7-domain-edge-3-seed41.json`) and
9/N27 domain-edge 8 (coupling 2: both conditions dip to 0 and back within less than a
grid cell next to the domain's edge where a radicand nearly vanishes; fixed by samples
between the boundary and the grid spaced uniformly in √ of the distance, and a polish on
the rigid-link model, `9-N27-domain-edge-8-seed41.json`, docs/numeric-log.md). **The numeric time bound holds
in this run: p99/median per truss at most 7.7 (target 10), max 33.8 s.** On 11 links
(every 56th truss, one instance per kind) 50 of 55 instances ran before the session's end
(11/N561's five did not): both backends 0 / 0 on all 50, every exact list certified, but
the exact backend again ran over the 300 s limit on one coupling-2 instance (11/N393
coincident 0), where the numeric backend took under 11 s.

**Seed 42** (solving code bfcbb37321bb, commit aa0ddac, `adversarial-aa0ddac` below)
restarted the count after 9/N27 domain-edge 8 of seed 41 was fixed (aa0ddac: samples
between the domain's boundary and the grid, spaced uniformly in √ of the distance; a polish
on the rigid-link model). On all 6000 seven-link and 4200 nine-link instances (10 168
finite, 32 movable and said so by both backends) the exact backend again listed every mode
and certified every list of a rigid linkage, 0 missed and 0 spurious. The numeric backend
missed 3 modes and listed 2 spurious ones, on 3 instances, all fixed since (90f80bd, dcc3ae2,
9b7aa8f: docs/numeric-log.md): 9/N27 small-box 14 (coupling 2: a valley of 1447
configurations from a regular mode to msolve's mode with P1 = P11; a float member 1.5e-3
away stood for it, and merging the valley took 40 s of a 51 s solve),
9/N18 double-root 27 (coupling 2: a simple root 3.9e-3 from a double root merged into its
valley, the hump between them 4e-13, below the cut of 1e-11) and 7/N1 double-root 131
(a valley flat to rounding on both models, whose rigid-model refinement stopped 2.5e-4 from
the mode). **The numeric time bound holds in this run: p99/median per truss at most 6.7
(target 10), max 51.1 s (9/N27 small-box 14, now 14 s).** On 11 links (every 56th truss, one instance per kind) 52
of 55 instances ran before the count was stopped for the session's CI (11/N561's last
three did not): the numeric backend 0 missed and 0 spurious on all 52 (max 9.1 s), the
exact one 0 / 0 on 49, every list certified, and over the 300 s limit on three coupling-2
instances of 11/N393 (collinear, coincident and domain-edge 0), where the numeric backend
took 3–9 s.

**Seed 43** (solving code 5da9b3df928e, commit 18a6a0c, `adversarial-18a6a0c` below) ran
the whole count again after seed 42's three numeric misses were fixed: 6000 seven-link,
4200 nine-link and 55 eleven-link instances (10 214 finite, 41 movable and said so by both
backends). The exact backend listed every mode of every finite instance it finished, 0
missed and 0 spurious, and certified every list (10 207), but ran over the 300 s limit on 7
coupling-2 eleven-link instances (four of 11/N393, three of 11/N561), where the numeric
backend took 3.6–9.7 s. The numeric backend missed one mode on one instance, fixed since
(391df54): 9/N13 domain-edge 1, a simple mode 3.4e-8 inside the domain's edge at s2,3 = 9,
which `flattened_mode` snapped flat onto the mode at the edge, 0.31 away, because the
snapped configuration still verified (residual 5.7e-9); a snap may now move no joint by more
than 1e-4 of the linkage's size. **The numeric time bound holds on every truss: p99/median
at most 9.6 (target 10).** One nine-link solve exceeded 60 s: 9/N2 domain-edge 13 (coupling
2) took 118 s, 96 s of it 60 full Gauss–Newton steps on 97 204 stalled boundary samples.
They now go in rounds that keep only configurations near a mode or still converging, and
the same solve took 40 s (dd77a65, docs/numeric-log.md). So this count is not the clean one
either. The next count runs at the solving code with these fixes.

**Seed 44** (solving code 7d1e088ab793, commit 692a323, `adversarial-692a323` below) ran
the whole count at the solving code with seed 43's two fixes: `make bench-adversarial
INSTANCES=30 INSTANCES_7=400 SEED=44`, 6000 seven-link, 4200 nine-link and 55 eleven-link
instances (every 56th truss, one per kind), 10 208 finite (620 of coupling degree 2) and 47
movable, said so by both backends on all 47. **Both backends: 0 missed and 0 spurious
modes**, mode for mode against msolve, on every instance they finished: the numeric
backend on all 10 208, the exact backend on 10 204, every list certified complete. The
exact backend ran over the 300 s limit on four coupling-2 eleven-link instances (11/N393
coincident 0; 11/N561 collinear, coincident and domain-edge 0), where the numeric backend
took 3.5–4.0 s and msolve 7.4–9.3 s (the exact backend's speed at coupling degree 2 is issue
24's). Four singular modes (9/N25, 9/N18 twice, 9/N28: a double root, or a mode at a domain
edge where two merge) the numeric backend located within 1e-4 of the linkage's size but not
within 1e-6, as floats allow where a root is double (counted neither missed nor spurious,
as in every run). **The numeric time bound holds: p99/median per truss at most 4.1 (target
10), no nine-link solve over 60 s (max 12.2 s).** This is the first count with every target
of issue 25 met at one solving code.

**Seed 46** (solving code 5f9eff8fce8d, commit 34540d0, `adversarial-34540d0` below), a
check of issue 21's and 24's later changes (the two-parameter search's bookkeeping, the
exact backend's norms and lifting), not a full count: 280 nine-link instances (two per
truss and kind) and 150 seven-link ones (ten per truss and kind), 429 finite and one
movable, said so by both backends. Both backends: 0 missed and 0 spurious, every exact
list certified. Numeric p99/median per truss at most 16.6: with two to ten instances per
truss and kind the p99 is the slowest instance (3.6 s at most), so this is no count of the
time bound.

**Seed 57** (solving code 7110cdaa6024, commit bcfc339, `adversarial-bcfc339` below), a
check of issue 56's latest changes to the float kernels (the factored radicand of the
triangles that bound the parameter, the branch-and-prune's midpoint evaluated alone), not
a full count: 560 nine-link instances (four per truss and kind) and 600 seven-link ones
(40 per truss and kind), 1157 finite and three movable, said so by both backends. **Both
backends: 0 missed and 0 spurious modes**, mode for mode against msolve. The report's
"certified" columns give, per kind, the share the numeric backend proves complete by its
branch-and-prune alone: 57–76 % of the small-box, collinear and coincident instances (the
rest have a root on a flat triangle or where joints the plan divides by meet, left to the
searches and named in the certificate; at 9 links also the coupling-2 trusses, which it
never certifies), none of the domain-edge and double-root ones (by construction a mode on
a flat triangle, or a double root: a box that holds one is undecidable in floats). The
exact backend certified every list of a rigid linkage (the three it left uncertified are
the three movable double-root instances).

**Seed 58** (solving code 4b00f0ba365f, commit f128c1b, `adversarial-f128c1b` below), a
check of issue 56's changes to the interval arithmetic (the interval program's radicands
in the small-term form 4 s_ik s_jk − (s_ik + s_jk − s_ij)², second-order models, the
compiled arithmetic specialised on the order), not a full count: 560 nine-link instances
(four per truss and kind) and 600 seven-link ones (40 per truss and kind), 1155 finite and
five movable, said so by both backends. **Both backends: 0 missed and 0 spurious modes**,
mode for mode against msolve. Certified by the numeric backend's branch-and-prune alone:
71–84 % of the seven-link small-box, collinear and coincident instances and 56–71 % of the
nine-link ones (seed 57: 57–76 % over both), none of the domain-edge and double-root ones.

**Seed 59** (solving code 84da1a205f0b, commit 76afa0b, `adversarial-76afa0b` below), at
the certified coupling-2 path: 560 nine-link and 600 seven-link instances, 1156 finite and
four movable, said so by both backends. **Both backends: 0 missed and 0 spurious modes.**
Certified by the branch-and-prune alone: 69–80 % of the seven-link small-box, collinear and
coincident instances, 56–76 % of the nine-link ones (coupling-2 trusses included now).

**Seed 60** (solving code a1009259c625, the code of a520b2c, `adversarial-a5f816a` and
`adversarial-sliders-a5f816a` below), a check of the boxes at a squared distance's 0, the
compiled kernel on slider chains and the deduplicated polish, not a full count: 140
nine-link trusses (one per truss and kind) and 150 seven-link ones, all finite. **Both
backends: 0 missed and 0 spurious modes**; certified by the branch-and-prune: 67–87 % of
the seven-link small-box, collinear and coincident instances, 54–71 % of the nine-link
ones. On 155 slider chains of the same kinds (154 finite, one movable, said so by both),
the exact backend 0 / 0 with every list certified; **the numeric backend missed one mode**
of a nine-link double-root chain (9/N18, coupling 2), with its answer *not* certified: its
parameter s2,5 has no bound of link dimensions, so only the sampling searches ran, and
they missed the mode (4.721978, 3.176008) on branch -++- (the double root itself, (9, 4),
was found; missed at 35fcb6a too). Saved as
tests/regressions/sliders/adversarial-9-N18-unbounded-parameters-seed60.json, fixed at
9144e15 (the branch-and-prune searches such parameters out to 1000 times the linkage's size).
The branch-and-prune certified 11 of 15 seven-link and 74 of 139 nine-link slider chains.

**Seed 61** (solving code 4ce6050e8373, the code of 9144e15, `adversarial-9144e15` and
`adversarial-sliders-9144e15` below), after unbounded slider parameters were given to the
branch-and-prune: 140 nine-link trusses (one per truss and kind) and 150 seven-link ones
(288 finite, 2 movable, said so by both). **Both backends: 0 missed and 0 spurious
modes**; certified by the branch-and-prune: 70–87 % of the seven-link small-box, collinear
and coincident instances, 54–89 % of the nine-link ones. On 155 slider chains (153 finite,
2 movable, said so by both): **both backends 0 / 0**; the numeric backend certified 12 of
15 seven-link and 81 of 138 nine-link chains; one exact list is not certified, a chain no
bilateration plan suits (9/N5 small-box, sliders P4 P5 P6 P9 P11 P12), whose 3 modes are
msolve's, verified, in both backends, which say that msolve's Cartesian system has 3
complex solutions where a generic instance has 4.

**Slider chains** (`bench/adversarial.py --sliders`: each kind's configuration with a random
admissible slider set and axes of rational length; rows in
bench/results/adversarial-sliders.jsonl, reports `adversarial-sliders-*` below; docs/sliders.md).
Seed 1 (150 seven-link instances, at f4b650c) found one instance both backends got wrong, the
exact one certified: two modes of a 7/N2 chain in which two axes that the plan crosses to
place a joint are parallel, where the plan divides by 0. It also found a numeric crash on a
chain that moves and 6 exact lists left uncertified. A pilot sweep had found two more misses
where the parameter's joints coincide. All are fixed (msolve lists the modes where two axes
the plan crosses are parallel, as where a base pair coincides) and saved in
tests/regressions/sliders/. Seed 2, after the fixes (at ba5c628: 150 seven-link and 70
nine-link instances, 219 finite): both backends 0 missed and 0 spurious, 2 exact lists not
certified, numeric median 0.82 s and max 7.7 s.

{adversarial}

## Conditioning

A random 7-link instance (catalog truss 7/#1 in catalog order, seed 11); every joint
coordinate of every link moved by a relative ε, in one random direction. Cells: median of
(joint displacement / linkage size) / ε over the modes, and the number
of the reference modes the method found on the unperturbed instance (each is followed to
the nearest verified mode the method finds after the perturbation). Where a method is
accurate, its figure equals the exact backend's (the linkage's own sensitivity, the same
for every ε since the perturbation has one direction); where ε is below its accuracy, its
figure grows like 1/ε.

{conditioning}

## One-degree-of-freedom chains: the driven motion (issue 19)

`baranov trace --input` lists every configuration at each input value from the traced
configuration space (docs/motion.md). Here it is compared, mode for mode, with the numeric
backend on the rigid linkage the crank held at that angle leaves
(`baranov.motion.driving.rigidified`). Four-bars by their link lengths (frame, crank,
coupler, rocker); a configuration at a branch point ends several pieces and is counted
once. Then each eight-bar Grübler chain, one random integer configuration (seed
[19, 8, index]) with a crank pinned to the fixed link, at the twelve crank angles
−180°, −150°, …, 150°.

{one_dof}

## Known failures of the project's backends (pinned in tests/test_stability.py)

- Nearly coincident joints (a leg much shorter than the other sides of its bilateration
  triangle): the area radicand (s_ij + s_ik + s_jk)² − 2 (s_ij² + s_ik² + s_jk²), evaluated in floats,
  cancels. The numeric backend takes the radicand of a triangle with the plan's parameter
  s as a side and two fixed sides a, b in the factored form (s − (√a − √b)²)((√a + √b)² −
  s) (`closure/bilateration.py: factored_radicand`), exact to a few ulps of itself; it
  certifies both modes down to a leg of 1e-8 (rows "nearly coincident joints" above),
  where with the Cayley–Menger form it found no candidate from a leg of 1e-6 on (and
  polished candidates that missed the 1e-8 verification at 1e-4). The exact backend maps
  its certified roots to branches and places the joints in ball arithmetic from the exact
  dimensions, raising the precision while a branch is undecided or a configuration misses
  the verification, and finds both modes down to a leg of 1e-8 too. Kahan's stable form of
  Heron's formula, tried for every triangle of the numeric backend, fixed the 1e-4 row but
  lost a mode of 3-RPR II at its exactly flat triangles, lost the branch-boundary mode
  when combined with the expanded form, and made the backend about 18 % slower; it was
  not kept.
- A link 1e-8 of its size from collinear: rounding the dimensions to floats moves the
  roots of the float closure condition by ~4e-6 (relative); the numeric backend reports
  configurations that hold every dimension to 1e-8 at those shifted parameter values. The
  exact backend used to map its certified roots to branches with the float condition and
  found no branch; it now does so in ball arithmetic (row "height 1/10000000").
- Modes closer than 1e-6 of the linkage's size are one mode for the numeric backend and
  the baselines: that is the tolerance at which they identify modes. The exact backend
  reports one mode per certified real root and branch, so it keeps them apart as long as
  the roots are distinct (section "Two assembly modes merging").
"""


if __name__ == "__main__":
    main()
