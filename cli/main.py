"""Command-line interface: ``baranov catalog``, ``baranov show`` and ``baranov solve``.

Bad input gives a one-line message on stderr and exit code 2, with nothing written.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import signal
import sys
import textwrap
from pathlib import Path

from baranov.catalog.tasks import ClusterLost

from .arguments import parameter_pair
from .explore import add_explore_parser, run_explore
from .trace import add_trace_parser, run_trace

# the library is imported inside each command, so that --help and --version start fast

#: ``--slider-modes`` goes up to this many links (the slider sets are tabulated over 2^J
#: joint subsets; 11 links would mean millions of chains).
SLIDER_MODES_LIMIT = 9
#: The catalog command accepts link counts up to this one (13 links: entries; 15 links: a
#: census of counts, about half an hour on two cores; docs/catalog-15.md).
CATALOG_MAX_LINKS = 15


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit code 2."""


def check_picture(path: Path | None, option: str = "--plot") -> None:
    """A picture a command is asked to write: its folder must exist and its name end in
    .png (the drawings are PNG; a .jpg name had been given PNG bytes)."""
    if path is None:
        return
    if not path.parent.is_dir():
        raise UsageError(f"{option} {path}: folder {path.parent} does not exist")
    if path.suffix.lower() != ".png":
        raise UsageError(f"{option} {path}: the picture is a PNG image; give the file a .png name")


def write_picture(path: Path, data: bytes) -> None:
    """``data`` written atomically to ``path``, and a line on stderr saying so."""
    from baranov.catalog.files import write_atomically

    write_atomically(path, data)
    print(f"wrote {path}", file=sys.stderr)


class _MethodsHelp(argparse.HelpFormatter):
    """Expands ``{methods}`` in a help text to the registered backends, each with its one
    line: imported only when help is printed (the backends' package takes seconds)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = super()._get_help_string(action) or ""
        if "{methods}" in text:
            from baranov.solvers.backends import BACKENDS

            text = text.replace("{methods}", "; ".join(f"{name}: {entry.summary}" for name, entry in BACKENDS.items()))
        return text


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, no usage block
        if message.endswith("required: command"):  # a bare `baranov`
            message = ("a command is required: catalog, show, solve, trace, explore, robot or robots "
                       "(baranov --help lists them, baranov COMMAND --help shows one)")
        raise UsageError(message)


def parse_link_counts(text: str) -> list[int]:
    """``"3,5,7"`` or ``"3-11"`` (odd counts in the range) → sorted link counts."""
    counts: set[int] = set()
    for part in text.split(","):
        part = part.strip()
        try:
            if "-" in part:
                low, high = (int(x) for x in part.split("-", 1))
                if low > high or low % 2 == 0:
                    raise UsageError(f"--links {text}: a range must go from an odd count up, e.g. 3-11")
                counts.update(range(low, high + 1, 2))
            else:
                counts.add(int(part))
        except ValueError:
            raise UsageError(f"--links {text}: expected odd link counts such as 3,5,7 or 3-11") from None
    from baranov.enumerate import check_link_count

    for links in sorted(counts):
        try:
            check_link_count(links)
        except ValueError as error:
            raise UsageError(f"--links {links}: {str(error).split(': ', 1)[1]}") from None
        if links > CATALOG_MAX_LINKS:
            raise UsageError(f"--links {links}: the catalog goes up to {CATALOG_MAX_LINKS} links")
    return sorted(counts)


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="baranov", description="Position analysis of planar linkages by bilateration.")
    parser.add_argument("--version", action="version", version=f"baranov {_version()}")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    catalog = commands.add_parser("catalog", help="regenerate the catalog of Baranov trusses")
    catalog.add_argument("--links", default="3-11",
                         help="odd link counts, e.g. 3,5,7 or 3-11 (default 3-11; 13 and 15 are opt-in, 15 as counts "
                              "only)")
    catalog.add_argument("--out", default="catalog", type=Path, help="output folder (default: catalog/)")
    catalog.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="worker processes (default: all cores)")
    catalog.add_argument("--scheduler", metavar="ADDRESS",
                         help="run the tasks on this Dask scheduler (e.g. tcp://host:8786; its workers need baranov "
                              "installed) instead of an embedded cluster of --workers processes")
    catalog.add_argument("--force", action="store_true", help="recompute even where complete files exist")
    catalog.add_argument("--no-crosscheck", action="store_true", help="skip the brute-force enumeration with geng")
    catalog.add_argument("--slider-modes", type=int, default=7, metavar="L",
                         help="assembly modes of the slider chains up to L links (default 7; 9 is opt-in: 47 702 "
                              "chains; 0: none)")
    catalog.add_argument("--assembly-modes", type=int, default=11, metavar="L",
                         help="count the trusses' assembly modes up to L links (default 11; 13 is opt-in: hours per "
                              "hundred coupling-2 trusses, docs/catalog-13.md)")
    catalog.add_argument("--quiet", action="store_true", help="print no progress")
    show = commands.add_parser("show", help="topology, plan and closure conditions of one chain")
    show.add_argument("chain", help="thesis name (9/B28), catalog id (11/N123), graph6 string, or a file")
    show.add_argument("--latex", action="store_true", help="closure conditions in LaTeX")
    show.add_argument("--reference", help="fix the reference pair, e.g. P1,P6")
    show.add_argument("--parameter", action="append", help="allow this parameter pair (repeatable), e.g. P1,P6")
    show.add_argument("--plans", type=int, default=1, help="show the N best plans (default 1)")
    show.add_argument("--count", action="store_true",
                      help="count the assembly modes over C on random instances, and check the count on the best "
                           "plan as one polynomial system (msolve)")
    show.add_argument("--sliders", metavar="JOINTS",
                      help="turn these joints into sliders, e.g. P8,P9: the chain's closure condition with the "
                           "sliders at infinity (thesis ch. 4)")
    show.add_argument("--catalog", type=Path,
                      help="catalog folder for names and ids (default: the installed catalog)")
    solve = commands.add_parser("solve", help="every assembly mode of a linkage given as a scene file",
                                formatter_class=_MethodsHelp)
    solve.add_argument("scene", type=Path, help="scene JSON file (see examples/)")
    solve.add_argument("--method", default="numeric",
                       help="solving backend (default numeric) — {methods}")
    solve.add_argument("--format", choices=("table", "json", "csv"), default="table",
                       help="table (default: mode, parameters, signs, residual), json, or csv (with every joint)")
    solve.add_argument("--parameter", action="append", metavar="PAIR",
                       help="solve in the best plan whose parameters are among these pairs (repeatable), e.g. P2,P3 or s2,3 "
                            "as thesis §3.3 publishes 7/B1 (numeric and exact; default: the best plan)")
    solve.add_argument("--json", action="store_true", help="the same as --format json")
    solve.add_argument("--joints", action="store_true", help="table: each mode's joint coordinates below its row")
    solve.add_argument("--plot", type=Path, help="draw every assembly mode into this PNG file")
    solve.add_argument("--time-limit", type=float, metavar="SECONDS",
                       help="numeric method: stop searching after this long and name what was left undecided")
    solve.add_argument("--batch", type=Path, metavar="INSTANCES",
                       help="solve many instances of the scene: a CSV file whose header names dimensions "
                            "(\"P1,P2\") and whose rows give their squared distances, or JSON lines "
                            "{\"P1,P2\": 17, ...}; prints one JSON line per instance")
    solve.add_argument("--out", type=Path, help="--batch: write the JSON lines to this file (atomically) "
                                                "instead of standard output")
    solve.add_argument("--workers", type=int, default=1, help="--batch: solve the instances in this many "
                                                              "processes (default 1)")
    robot = commands.add_parser("robot", help="forward kinematics of a fully-parallel planar robot given as a file")
    robot.add_argument("robot", type=Path, help="robot JSON file: three legs, their geometry and the actuators "
                       "(format: docs/robots.md, Robot files)")
    robot.add_argument("--actuators", help="actuator values, e.g. 1,11,13 (default: the file's)")
    robot.add_argument("--method", default="numeric", choices=("numeric", "exact", "msolve"), help="solving backend")
    robot.add_argument("--parameter", help="solve in a plan with this parameter pair, e.g. P1,P6 (thesis §5.2.2); "
                       "default: the best plan")
    robot.add_argument("--json", action="store_true", help="the solution as baranov solve --json, with the poses")
    robot.add_argument("--plot", type=Path, help="draw every pose (the locked robot's assembly modes) into this PNG file")
    add_trace_parser(commands)
    add_explore_parser(commands)
    robots = commands.add_parser("robots", help="the fully-parallel planar robots: their ten families (thesis §5.2)")
    robots.add_argument("--json", action="store_true", help="a list of families as JSON")
    return parser


def run_robot(args: argparse.Namespace) -> int:
    """``baranov robot FILE``: every platform pose of the robot at its actuator values."""
    import json

    from baranov.robots import load_robot, robot_family, robot_solution
    from baranov.solvers import ExactSolution

    from .output import characteristic_lines, pose_table

    robot, actuators = load_robot(args.robot)
    if args.actuators is not None:
        actuators = [value.strip() for value in args.actuators.split(",")]
    if actuators is None:
        raise UsageError(f"{args.robot}: no actuator values: give --actuators a,b,c or \"actuators\" in the file")
    check_picture(args.plot)
    parameter = None
    if args.parameter is not None:
        parameter = parameter_pair(args.parameter)
        if args.method == "msolve":
            raise UsageError("--parameter: msolve describes its modes in the best plan; use --method numeric or exact")
    solution, poses = robot_solution(robot, actuators, args.method, parameter)
    family = robot_family(robot.legs).name
    if args.plot is not None:
        from baranov.robots import locked_scene
        from baranov.robots.drawing import render_robot  # matplotlib only when drawing

        write_picture(args.plot, render_robot(robot, locked_scene(robot, actuators), solution))
    shown = [{"position": list(p.position), "angle": p.angle} for p in poses]
    if args.json:
        print(json.dumps({**solution.to_dict(), "family": family, "poses": shown}, indent=1))
        return 0
    legs = "-".join(str(leg) for leg in robot.legs)
    print(f"{args.robot}: robot {legs}, family {family}, {len(poses)} pose{'s' if len(poses) != 1 else ''} "
          f"({args.method})")
    if isinstance(solution, ExactSolution) and solution.characteristic_polynomial is not None:
        print("\n".join(characteristic_lines(solution)))  # Γ of thesis §5.2, as `solve --method exact` prints it
    if not poses:
        print("no pose: the legs cannot all reach the platform with these actuator values (the locked robot has "
              "no real assembly mode)")
        return 0
    print("\n".join(pose_table(poses, solution.parameters)))
    return 0


def run_robots(args: argparse.Namespace) -> int:
    """``baranov robots``: the family table, every count computed (thesis Table 5.3)."""
    import json
    from dataclasses import asdict

    from baranov.literature.robots import THESIS_ROBOT_FAMILIES
    from baranov.robots import all_robots, robot_families

    families = robot_families()
    if args.json:
        print(json.dumps([asdict(family) for family in families], indent=1))
        return 0
    robots = all_robots()
    print(f"{len(robots)} fully-parallel planar robots ({sum(all(leg.passive != 'PP' for leg in legs) for legs in robots)}"
          " without a PP leg); locked, each is a slider chain of the pentad 5/B1 (thesis §5.2, Table 5.3)\n")
    print("| family | sliders of the locked pentad | leg architectures | robots | assembly modes | thesis |")
    print("|---|---|---|---|---|---|")
    for family in families:
        _, robots_published, modes_published = THESIS_ROBOT_FAMILIES.get(family.name, ((), None, None))
        print(f"| {family.name} | {', '.join(family.sliders) or 'none'} | {', '.join(family.architectures)} | "
              f"{family.robots} | {family.assembly_modes} | {robots_published} robots, {modes_published} "
              f"mode{'' if modes_published == 1 else 's'} |")
    return 0


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("baranov")
    except PackageNotFoundError:
        return "unknown (not installed)"


def run_solve(args: argparse.Namespace) -> int:
    from baranov.scene import load_scene
    from baranov.solvers import ExactSolution, available_backends
    from baranov.solvers import solve as solve_scene
    from baranov.solvers.progress import watching
    from baranov.solvers.verification import RESIDUAL_TOLERANCE

    from .output import characteristic_lines, mode_table

    if args.method not in available_backends():
        raise UsageError(f"--method {args.method}: choose from {', '.join(available_backends())}")
    check_picture(args.plot)
    if args.time_limit is not None and (args.method != "numeric" or not args.time_limit > 0):
        raise UsageError(f"--time-limit {args.time_limit:g}: a positive number of seconds, for the numeric method")
    scene = load_scene(args.scene)
    options = {"time_limit": args.time_limit} if args.time_limit is not None else {}
    if args.parameter:
        options["plan"] = _plan_with_parameters(scene, args.parameter, args.method)
    if args.batch is not None or args.out is not None or args.workers != 1:
        return run_batch(args, scene, options)
    with watching():  # a status line on a terminal while the solve runs
        solution = solve_scene(scene, method=args.method, **options)
    if args.plot is not None:
        from baranov.solvers.drawing import render_modes  # matplotlib only when drawing

        write_picture(args.plot, render_modes(scene, solution))
    form = "json" if args.json else args.format
    if form == "json":
        print(json.dumps(solution.to_dict(), indent=1))
        return 0
    if form == "csv":
        print(solution.to_csv(), end="")
        return 0
    modes = solution.assembly_modes
    print(f"{args.scene}: coupling degree {solution.coupling_degree}, "
          f"{len(modes)} assembly mode{'s' if len(modes) != 1 else ''} ({solution.method})")
    width = shutil.get_terminal_size((100, 24)).columns if sys.stdout.isatty() else 100
    for driver in (scene.inputs if scene.mobility > 0 else ()):
        if driver.value is not None:  # solved held there (baranov.motion.driving.solve_held)
            print(f"input {driver.name} held at {driver.value}°: the configurations of the rigid linkage it makes")
    if isinstance(solution, ExactSolution) and solution.characteristic_polynomial is not None:
        print("\n".join(characteristic_lines(solution)))
    if solution.certificate is not None:
        print(textwrap.fill(f"assembly modes: {solution.certificate.summary()}", width=width, subsequent_indent="  ",
                            break_on_hyphens=False))
    for sentence in solution.undecided:  # long sentences: wrapped, continuation indented
        print(textwrap.fill(f"undecided: {sentence}", width=width, subsequent_indent="  ", break_on_hyphens=False))
    if not modes:  # "cannot be assembled" only on a proof (issue 55)
        proven = solution.certificate is not None and solution.certificate.complete
        print("the linkage cannot be assembled with these dimensions (certified)" if proven else
              "no assembly mode found; that none exists is not proven (see the certificate and the undecided lines)")
        return 0
    print("\n".join(mode_table(solution, joints=args.joints, width=width)))
    unverified = sum(mode.max_residual >= RESIDUAL_TOLERANCE for mode in modes)
    if unverified:  # a baseline lists what it converged to, unverified (issue 57)
        print(textwrap.fill(f"{unverified} of {len(modes)} rows are not assembly modes: their largest relative "
                            f"error over the link dimensions is {RESIDUAL_TOLERANCE:.0e} or more (e.g. a link "
                            "placed mirrored); this method does not verify what it reports", width=width,
                            subsequent_indent="  "))
    if solution.free_sign_triangles:
        triangles = ", ".join("△" + "".join(triangle) for triangle in solution.free_sign_triangles)
        print(textwrap.fill(f"signs: the orientation of the plan's free-sign triangles {triangles} in each mode "
                            "(+ counter-clockwise, - clockwise, 0 flat)", width=width, subsequent_indent="  "))
    if not args.joints:
        print("(joint coordinates: --joints, or --format csv / json)")
    return 0


def _plan_with_parameters(scene, texts: list[str], method: str):
    """``--parameter P2,P3`` (repeatable): the best plan of the scene's chain (with its
    sliders, the best slider plan) whose parameters are among these pairs."""
    if method not in ("numeric", "exact"):
        raise UsageError(f"--parameter: the {method} method does not solve by a plan; use --method numeric or exact")
    pairs = [parameter_pair(text) for text in texts]
    if scene.sliders:
        from baranov.planner import slider_plan

        return slider_plan(scene.chain, [slider.joint for slider in scene.sliders], parameters=pairs)
    from baranov.planner import bilateration_plans

    return bilateration_plans(scene.chain, 1, parameters=pairs)[0]


def run_batch(args: argparse.Namespace, scene, options: dict) -> int:
    """``baranov solve SCENE --batch INSTANCES``: every instance checked first (a bad one
    stops the batch before any solve, naming its line), then solved in order, one JSON
    line each (``{"instance": k, "dimensions": {...}, ...}`` with the solution of
    ``--json``, or ``"error"`` for an instance the backend refuses)."""
    from baranov.catalog.files import write_atomically
    from baranov.scene import load_instances
    from baranov.solvers import SolverError, solve_many
    from baranov.solvers.progress import watching

    if args.batch is None:
        raise UsageError(f"--{'out' if args.out is not None else 'workers'}: for --batch only")
    if args.workers < 1:
        raise UsageError(f"--workers {args.workers}: must be at least 1")
    if args.plot is not None or args.joints or args.json or args.format != "table":
        raise UsageError("--batch: prints JSON lines; --plot, --joints, --json and --format are for one solve")
    if args.out is not None and not args.out.parent.is_dir():
        raise UsageError(f"--out {args.out}: folder {args.out.parent} does not exist")
    instances = load_instances(args.batch)  # solve_many checks every instance before the first solve
    lines: list[str] = []

    def emit(number: int, result) -> None:
        line = {"instance": number, "dimensions": {k: str(v) for k, v in instances[number - 1].items()}}
        line.update({"error": str(result)} if isinstance(result, SolverError) else result.to_dict())
        lines.append(json.dumps(line))
        if args.out is None:
            print(lines[-1], flush=True)

    with watching():
        results = solve_many(scene, instances, method=args.method, return_errors=True, on_solution=emit,
                             workers=args.workers, **options)
    if args.out is not None:
        write_atomically(args.out, "".join(line + "\n" for line in lines))
    failed = sum(1 for result in results if isinstance(result, SolverError))
    if failed:
        print(f"baranov: {failed} of {len(results)} instances not solved (their lines say why)", file=sys.stderr)
    return 0


def run_catalog(args: argparse.Namespace) -> int:
    from baranov.catalog import build_catalog
    from baranov.catalog.files import check_writable_folder, folder_lock, remove_stale_temporaries
    from baranov.catalog.tasks import kill_worker_processes

    link_counts = parse_link_counts(args.links)
    if args.workers < 1:
        raise UsageError(f"--workers {args.workers}: must be at least 1")
    if args.scheduler is not None and not re.fullmatch(r"(tcp|tls|inproc|ucx)://\S+", args.scheduler):
        raise UsageError(f"--scheduler {args.scheduler}: a Dask scheduler address such as tcp://host:8786")
    if not 0 <= args.slider_modes <= SLIDER_MODES_LIMIT:
        raise UsageError(f"--slider-modes {args.slider_modes}: slider chains are counted up to {SLIDER_MODES_LIMIT} "
                         "links (47 702 chains there)")
    if args.assembly_modes < 0:
        raise UsageError(f"--assembly-modes {args.assembly_modes}: a number of links, 0 or more")
    try:
        check_writable_folder(args.out)
    except OSError as error:
        raise UsageError(f"--out {args.out}: cannot write there ({error.strerror or error})") from None
    log = (lambda message: None) if args.quiet else (lambda message: print(message, file=sys.stderr))
    # installed, not inherited: a job started in the background of a script ignores SIGINT
    def stop(signum: int, frame) -> None:
        kill_worker_processes()  # at once, whatever the job is doing (a cluster still starting too)
        raise KeyboardInterrupt  # SIGTERM stops the job like Ctrl-C: workers terminated, one line

    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, stop)
    with folder_lock(args.out):
        remove_stale_temporaries(args.out)
        summary = build_catalog(
            link_counts,
            args.out,
            workers=args.workers,
            force=args.force,
            crosscheck=not args.no_crosscheck,
            slider_modes=args.slider_modes,
            assembly_modes=args.assembly_modes,
            show_progress=not args.quiet,  # a bar on a terminal, a line every 5 min in a log
            log=log,
            scheduler=args.scheduler,
        )
    print(summary, end="")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``baranov`` command."""
    try:
        args = _parser().parse_args(argv)
        if args.command == "catalog":
            return run_catalog(args)
        if args.command == "solve":
            return run_solve(args)
        if args.command == "robots":
            return run_robots(args)
        if args.command == "robot":
            return run_robot(args)
        if args.command == "trace":
            return run_trace(args)
        if args.command == "explore":
            return run_explore(args)
        if args.command == "show":
            if args.plans < 1:
                raise UsageError(f"--plans {args.plans}: must be at least 1")
            from .show import show

            print(show(args.chain, args.catalog, args.latex, args.reference, args.parameter, args.plans,
                       args.sliders, args.count), end="")
            return 0
    except (UsageError, ValueError) as error:
        print(f"baranov: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("baranov: interrupted; complete catalog files are kept, rerun to resume", file=sys.stderr)
        return 130
    except ClusterLost as error:
        print(f"baranov: error: {error}", file=sys.stderr)
        return 1
    except BrokenPipeError:  # output piped into e.g. `head`: stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
