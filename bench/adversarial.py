"""Adversarial completeness run (issue 25): random trusses drawn as a user would type them
(scene/adversarial.py: small boxes, joints in line, joints at one point, modes at a
domain edge, double roots), solved by both backends and by msolve on the Cartesian system
(baranov.solvers.msolve, which shares no code with the backends), compared mode for mode.

Every finished instance is appended to ``--out`` (JSON lines) with the version of the
solving code it ran on (:func:`code_version`: the git trees of the packages a solve
touches), so an interrupted run resumes where it stopped — in a later session too, from
the rows committed under bench/results/, as long as that code has not changed; a change
starts the count again. ``--report`` writes the Markdown summary of the rows of the
current code version that ``bench/stability.py`` includes in docs/stability.md;
``--failures`` receives every instance a backend got wrong, as a scene file ready for
tests/regressions/. (The solvers live in baranov.solvers; msolve in
baranov.solvers.msolve shares no code with the backends.)
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import resource
import shlex
import signal
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import numpy as np

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene.adversarial import ADVERSARIAL_KINDS, adversarial_scene, adversarial_slider_scene
from baranov.scene.instances import instance_dict
from baranov.solvers import MovableLinkageError, solve
from baranov.solvers.msolve import compare_modes, match_configurations, msolve_modes

METHODS = ("numeric", "exact")
ROOT = Path(__file__).resolve().parents[1]
#: The packages a solve runs through: rows of one version of these are one run.
SOLVING_CODE = ("topology", "enumerate", "planner", "closure", "scene", "solvers")


def code_version() -> str:
    """A short hash of the committed trees of SOLVING_CODE, with ``-dirty`` if they have
    uncommitted changes; ``unknown`` outside a git checkout."""
    trees = subprocess.run(["git", "rev-parse", *(f"HEAD:{folder}" for folder in SOLVING_CODE)], cwd=ROOT,
                           capture_output=True, text=True)
    if trees.returncode != 0:
        return "unknown"
    dirty = subprocess.run(["git", "status", "--porcelain", "--", *SOLVING_CODE], cwd=ROOT, capture_output=True,
                           text=True).stdout.strip()
    return hashlib.sha1(trees.stdout.encode()).hexdigest()[:12] + ("-dirty" if dirty else "")


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout


def timed(function, seconds: float):
    """(result, wall seconds) of ``function()``, or (None, seconds) if it ran over
    (SIGALRM: the worker's main thread)."""
    signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    start = time.perf_counter()
    try:
        result = function()
    except _Timeout:
        result = None
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    return result, time.perf_counter() - start


def instance(links: int, index: int, kind: str, number: int, seed: int, sliders: bool = False
             ) -> tuple[object, dict[str, tuple], dict]:
    """The scene of one instance, its generating configuration and its JSON form: a truss
    (:func:`~baranov.scene.adversarial.adversarial_scene`) or, with ``sliders``, a slider
    chain drawn from the same kind of configuration (:func:`adversarial_slider_scene`),
    from its own stream of random numbers."""
    truss = baranov_trusses(links)[index]
    rng = np.random.default_rng([seed, links, index, ADVERSARIAL_KINDS.index(kind), number, *([1] if sliders else [])])
    if sliders:
        data, scene = adversarial_slider_scene(truss, kind, rng)
        return scene, {joint: tuple(point) for joint, point in data["generating_configuration"].items()}, data
    scene, coordinates = adversarial_scene(truss, kind, rng)
    return scene, coordinates, instance_dict(truss, coordinates)


def run(links: int, index: int, kind: str, number: int, seed: int, methods: tuple[str, ...],
        timeout: float, code: str = "unknown", sliders: bool = False) -> dict:
    """One instance: msolve's modes, each backend's, and what each backend missed or added."""
    scene, coordinates, data = instance(links, index, kind, number, seed, sliders)
    row = {"key": f"{links}/N{index + 1}/{kind}/{number}" + ("/sliders" if sliders else ""), "links": links,
           "truss": f"{links}/N{index + 1}", "kind": kind, "instance": number,
           "coupling_degree": coupling_degree(scene.chain), "code": code, "seed": seed}
    if sliders:
        row["sliders"] = [slider.joint for slider in scene.sliders]
    oracle = msolve_modes(scene, timeout=timeout)
    row.update(msolve_status=oracle.status, msolve_seconds=oracle.seconds, msolve_modes=len(oracle.configurations),
               msolve_message=oracle.message)
    generating = {j: (float(x), float(y)) for j, (x, y) in coordinates.items()}
    if oracle.status == "finite":
        row["msolve_has_generating"] = not match_configurations(list(oracle.configurations), [generating])[0]
    for method in methods:
        try:
            solution, seconds = timed(lambda method=method: solve(scene, method=method), timeout)
        except Exception as error:  # noqa: BLE001 - SolverError (movable, cannot solve), or a crash to record
            row[f"{method}_seconds"] = 0.0
            row[f"{method}_status"] = "movable" if isinstance(error, MovableLinkageError) else "error"
            row[f"{method}_message"] = str(error) if isinstance(error, ValueError) else f"{type(error).__name__}: {error}"
            continue
        row[f"{method}_seconds"] = seconds
        if solution is None:
            row[f"{method}_status"] = "timeout"
            continue
        found = [mode.joints for mode in solution.assembly_modes]
        row[f"{method}_status"] = "solved"
        row[f"{method}_modes"] = len(found)
        row[f"{method}_has_generating"] = compare_modes(found, [generating])[0] == 0  # coarsely, at a singular mode
        if oracle.status == "finite":
            row[f"{method}_missed"], row[f"{method}_spurious"], row[f"{method}_coarse"] = compare_modes(
                found, list(oracle.configurations))
        if solution.certificate is not None:  # the numeric backend's too (issue 56)
            row[f"{method}_certified"] = solution.certificate.complete
            row[f"{method}_gaps"] = list(solution.certificate.gaps)
    if failed(row, methods):
        row["scene"] = data
    return row


def failed(row: dict, methods: tuple[str, ...]) -> bool:
    """Whether a backend lost or added a mode, timed out, or the oracle could not decide;
    for a positive-dimensional solution set (msolve), whether a backend failed to say so
    or to leave it uncertified (the numeric backend's real modes there are checked at
    report time, :func:`on_real_motion`: the complex curve may meet the reals only at
    isolated modes)."""
    if row["msolve_status"] == "infinite":
        return any(row.get(f"{m}_status") not in ("movable", "solved") or row.get(f"{m}_certified") is True
                   for m in methods)
    if row["msolve_status"] != "finite":
        return True
    # an uncertified exact list is a failure; the numeric backend proves what it can
    return any(row.get(f"{m}_status") != "solved" or row.get(f"{m}_missed") or row.get(f"{m}_spurious")
               or not row.get(f"{m}_has_generating") or (m == "exact" and row.get(f"{m}_certified") is False)
               for m in methods)


def save_failure(row: dict, folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    sliders = "-sliders-" + "-".join(row["sliders"]) if "sliders" in row else ""
    name = f"{row['truss'].replace('/', '-')}{sliders}-{row['kind']}-{row['instance']}-seed{row['seed']}.json"
    summary = {k: v for k, v in row.items() if k not in ("scene", "key")}
    text = json.dumps({"comment": f"adversarial run (bench/adversarial.py): {json.dumps(summary)}",
                       **row["scene"]}, indent=1)
    (folder / name).write_text(text + "\n", encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--links", default="7,9", help="link counts, comma-separated (default 7,9)")
    parser.add_argument("--kinds", default=",".join(ADVERSARIAL_KINDS))
    parser.add_argument("--trusses", help="only these trusses (e.g. 9/N21,9/N7)")
    parser.add_argument("--every", type=int, default=1, help="only every K-th truss of each link count (N1, N1+K, …)")
    parser.add_argument("--instances", type=int, default=10, help="instances per truss and kind (default 10)")
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--seed", type=int, default=25)
    parser.add_argument("--sliders", action="store_true",
                        help="slider chains: each instance's configuration with a random admissible slider set and "
                             "axes of rational length (scene/adversarial.py: adversarial_slider_scene); keep their "
                             "rows in their own --out")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per solve (default 600)")
    parser.add_argument("--memory", type=float, default=8.0,
                        help="GiB of address space per worker (default 8): a runaway solve raises MemoryError, "
                             "recorded as an error, instead of the kernel killing the worker and the pool with it")
    parser.add_argument("--out", type=Path, required=True, help="JSON lines, appended; a rerun resumes")
    parser.add_argument("--report", type=Path, help="write the Markdown summary of --out here")
    parser.add_argument("--failures", type=Path, help="save every failed instance here as a scene file")
    parser.add_argument("--report-only", action="store_true", help="run nothing: write --report from --out")
    parser.add_argument("--note", default="", help="a sentence for the report (e.g. the commit of the run)")
    parser.add_argument("--any-code", action="store_true", help="--report-only: rows of every code version")
    parser.add_argument("--code", help="--report-only: rows of this code version (default: the checkout's)")
    args = parser.parse_args(argv)
    code = args.code or code_version()
    if args.report_only:
        write_report(args, argv, current_rows(args.out, None if args.any_code else code), tuple(args.methods.split(",")))
        return 0
    methods = tuple(args.methods.split(","))
    done = {(row["key"], row["seed"]) for row in current_rows(args.out, code)}
    wanted = set(args.trusses.split(",")) if args.trusses else None
    # instance by instance over all trusses and kinds, so that a run stopped early covers them evenly
    suffix = "/sliders" if args.sliders else ""
    tasks = [(links, index, kind, number, args.seed, methods, args.timeout, code, args.sliders)
             for links in map(int, args.links.split(",")) for number in range(args.instances)
             for index in range(len(baranov_trusses(links)))
             if (wanted is None or f"{links}/N{index + 1}" in wanted) and index % args.every == 0
             for kind in args.kinds.split(",")
             if (f"{links}/N{index + 1}/{kind}/{number}{suffix}", args.seed) not in done]
    print(f"{len(tasks)} instances to run ({len(done)} already in {args.out} for solving code {code})", flush=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with ProcessPoolExecutor(args.workers, initializer=_limit_memory, initargs=(args.memory,)) as pool, \
            args.out.open("a", encoding="utf-8") as out:
        futures = [pool.submit(run, *task) for task in tasks]
        for n, future in enumerate(as_completed(futures), 1):
            try:
                row = future.result()
            except Exception as error:  # noqa: BLE001 - a worker lost: say so, keep the other rows coming
                print(f"LOST {type(error).__name__}: {error}", flush=True)
                continue
            out.write(json.dumps(row) + "\n")
            out.flush()
            if failed(row, methods):
                print("FAILED", json.dumps({k: v for k, v in row.items() if k != "scene"}), flush=True)
                if args.failures is not None:
                    save_failure(row, args.failures)
            if n % 50 == 0:
                print(f"{n}/{len(tasks)} done", flush=True)
    write_report(args, argv, current_rows(args.out, code), methods)
    return 0


def _limit_memory(gibibytes: float) -> None:
    """Worker initializer: cap the address space (issue 25's sixth run: one 9/N9 solve grew
    past 24 GB, the kernel killed its worker, and the broken pool lost every queued
    instance)."""
    limit = int(gibibytes * 2**30)
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


def current_rows(path: Path, code: str | None) -> list[dict]:
    """The rows of ``path`` whose solving code is ``code`` (all rows for None), each
    instance once."""
    if not path.exists():
        return []
    rows, seen = [], set()
    for line in path.read_text().splitlines():
        row = json.loads(line) if line.strip() else None
        if row is None or (code is not None and row.get("code") != code) or (row["key"], row.get("seed")) in seen:
            continue  # another code version, or an instance run twice (two processes on one file): the first counts
        seen.add((row["key"], row.get("seed")))
        rows.append(row)
    return rows


def write_report(args: argparse.Namespace, argv: list[str] | None, rows: list[dict], methods: tuple[str, ...]) -> None:
    """Print the summary of ``rows``; write it with the per-kind table to ``--report``."""
    report = summary(rows, methods)
    print("\n".join(report))
    if args.report is not None:
        arguments = list(argv if argv is not None else sys.argv[1:])
        if "--note" in arguments:  # the note is printed on its own
            del arguments[arguments.index("--note"):arguments.index("--note") + 2]
        command = "python bench/adversarial.py " + shlex.join(arguments)
        versions = ", ".join(sorted({row.get("code", "unrecorded") for row in rows}))
        head = (f"{args.note} Command: `{command}` ({len(rows)} instances in {args.out}; solving code "
                f"{versions}).").strip()
        text = "\n".join([head, "", *report, "", *table(rows, methods)]) + "\n"
        args.report.with_suffix(".tmp").write_text(text, encoding="utf-8")
        args.report.with_suffix(".tmp").replace(args.report)


def on_real_motion(scene, joints: dict[str, tuple[float, float]], step: float = 1e-2) -> bool:
    """Whether the configuration ``joints`` of ``scene`` lies on a real motion, by a local
    test: along each infinitesimal motion d (the null space of the constraints' Jacobian,
    ground link fixed; its basis and 8 random mixtures), the nearest configuration at
    offset ``step`` × the linkage's size along d, by least squares. On a real motion one
    of them satisfies the constraints (residual at rounding); at an isolated real point of
    a complex curve the residual grows like step² in every direction (issue 25's 7/N2 drawn
    with P2 on P7: 5.7e-6 at 1e-2, 5.4e-4 at 1e-1). Numerical evidence, not a proof."""
    from scipy.optimize import least_squares

    names = sorted(joints)
    index = {name: n for n, name in enumerate(names)}
    pairs = [(index[u], index[v], float(value)) for (u, v), value in
             ((tuple(sorted(pair)), value) for pair, value in scene.known.items())]
    fixed = [index[name] for name in scene.link_of(scene.ground).joints]
    start = np.array([joints[name] for name in names], float).ravel()
    anchor = start.reshape(-1, 2)[fixed]
    size = max(1.0, float(np.ptp(start.reshape(-1, 2), axis=0).max()))

    def constraints(x: np.ndarray) -> np.ndarray:
        points = x.reshape(-1, 2)
        lengths = [np.sum((points[u] - points[v]) ** 2) - value for u, v, value in pairs]
        return np.concatenate([np.array(lengths) / size ** 2, (points[fixed] - anchor).ravel() / size])

    jacobian = np.array([(constraints(start + 1e-7 * e) - constraints(start - 1e-7 * e)) / 2e-7
                         for e in np.eye(len(start))]).T
    _, singular, vt = np.linalg.svd(jacobian)
    rank = int(np.sum(singular > 1e-6 * singular[0]))
    null = vt[rank:]
    if not len(null):
        return False
    rng = np.random.default_rng(0)
    directions = list(null) + [d / np.linalg.norm(d) for d in rng.standard_normal((8, len(null))) @ null]
    for direction in directions:
        offset = step * size

        def pushed(x: np.ndarray, direction=direction, offset=offset) -> np.ndarray:
            return np.concatenate([constraints(x), [(direction @ (x - start) - offset) / size]])

        found = least_squares(pushed, start + offset * direction, xtol=1e-15, ftol=1e-15, gtol=1e-15)
        if np.abs(constraints(found.x)).max() < 1e-10:
            return True
    return False


def complex_curves(rows: list[dict]) -> str:
    """The report's sentence on rows where msolve found a positive-dimensional set and the
    numeric backend reported real modes: each mode re-solved and tested by
    :func:`on_real_motion`."""
    # (slider chains aside: on_real_motion knows the link dimensions only)
    reported = [r for r in rows if r["msolve_status"] == "infinite" and r.get("numeric_status") == "solved"
                and "sliders" not in r]
    if not reported:
        return ""
    moving = 0
    for row in reported:
        links, index = int(row["truss"].split("/")[0]), int(row["truss"].split("/N")[1]) - 1
        scene, _, _ = instance(links, index, row["kind"], row["instance"], row["seed"], "sliders" in row)
        moving += any(on_real_motion(scene, mode.joints) for mode in solve(scene, method="numeric").assembly_modes)
    return (f"; on {len(reported)} of them the numeric backend reported real modes instead, and a local test "
            f"(bench/adversarial.py: on_real_motion) put {moving} of those instances on a real motion — the others' "
            "modes are isolated real points of a complex curve, which msolve cannot list")


def percentile_ratio(times: list[float]) -> float:
    """p99 over median of solve times."""
    return float(np.percentile(times, 99) / np.median(times)) if times else math.nan


def summary(rows: list[dict], methods: tuple[str, ...]) -> list[str]:
    finite = [r for r in rows if r["msolve_status"] == "finite"]
    lines = [f"- msolve: {len(finite)} of {len(rows)} instances solved (finite); "
             f"{sum(1 for r in finite if not r['msolve_has_generating'])} without the generating configuration; "
             f"{sum(r['msolve_modes'] for r in finite)} real modes in all"]
    movable = [r for r in rows if r["msolve_status"] == "infinite"]
    if movable:
        lines.append(f"- {len(movable)} positive-dimensional solution sets (msolve: the linkage moves, or a complex "
                     f"curve of solutions); said so by the numeric "
                     f"backend (MovableLinkageError) on {sum(r.get('numeric_status') == 'movable' for r in movable)}, "
                     f"by the exact one (not certified, or MovableLinkageError) on "
                     f"{sum(r.get('exact_certified') is False or r.get('exact_status') == 'movable' for r in movable)}"
                     + complex_curves(rows))
    for method in methods:
        mine = [r for r in finite if r.get(f"{method}_status") == "solved"]
        times = [r[f"{method}_seconds"] for r in rows if r.get(f"{method}_status") in ("solved", "timeout")]
        uncertified = sum(1 for r in mine if r.get(f"{method}_certified") is False)
        ratios = [percentile_ratio([r[f"{method}_seconds"] for r in rows
                                    if r["truss"] == t and r.get(f"{method}_status") in ("solved", "timeout")])
                  for t in {r["truss"] for r in rows}]
        lines.append(
            f"- {method}: {sum(r[f'{method}_missed'] for r in mine)} missed and "
            f"{sum(r[f'{method}_spurious'] for r in mine)} spurious modes on {len(mine)} instances "
            f"({sum(1 for r in mine if r[f'{method}_missed'] or r[f'{method}_spurious'])} instances wrong, "
            f"{sum(r.get(f'{method}_coarse', 0) for r in mine)} modes located only to 1e-4 (singular), "
            f"{sum(1 for r in rows if r.get(f'{method}_status') == 'timeout')} timeouts, "
            f"{sum(1 for r in rows if r.get(f'{method}_status') == 'error')} refused (SolverError)"
            + f", {uncertified} not certified complete"
            + f"); solve time median {np.median(times):.2f} s, max {max(times):.1f} s; "
            f"p99/median per truss at most {max(ratios):.1f}")
    return lines


def table(rows: list[dict], methods: tuple[str, ...]) -> list[str]:
    """Per link count and kind: instances, real modes, misses, the instances each method
    certified complete (of those it solved; "—" where the rows predate certificates), time
    quantiles."""
    header = "| links | kind | instances | real modes (msolve) | " + " | ".join(
        f"{m} missed / spurious | {m} certified | {m} median s | {m} p99 s" for m in methods) + " | msolve median s |"
    lines = [header, "|" + "---|" * (4 + 4 * len(methods) + 1)]
    for links in sorted({r["links"] for r in rows}):
        for kind in ADVERSARIAL_KINDS:
            mine = [r for r in rows if r["links"] == links and r["kind"] == kind]
            if not mine:
                continue
            cells = [str(links), kind, str(len(mine)), str(sum(r["msolve_modes"] for r in mine))]
            for m in methods:
                times = [r[f"{m}_seconds"] for r in mine if f"{m}_seconds" in r]
                solved = [r for r in mine if r.get(f"{m}_status") == "solved"]
                known = [r for r in solved if f"{m}_certified" in r]
                certified = f"{sum(bool(r[f'{m}_certified']) for r in known)} of {len(solved)}" if known else "—"
                cells += [f"{sum(r.get(f'{m}_missed', 0) for r in mine)} / {sum(r.get(f'{m}_spurious', 0) for r in mine)}",
                          certified, f"{np.median(times):.2f}", f"{np.percentile(times, 99):.2f}"]
            cells.append(f"{np.median([r['msolve_seconds'] for r in mine]):.2f}")
            lines.append("| " + " | ".join(cells) + " |")
    return lines


if __name__ == "__main__":
    sys.exit(main())
