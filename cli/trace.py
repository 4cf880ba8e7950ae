"""``baranov trace``: the configuration space of a one-degree-of-freedom linkage traced in
distance space, its pieces and branch points, and the coupler curves (thesis ch. 6)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from .arguments import parameter_pair


def add_trace_parser(commands) -> None:
    trace = commands.add_parser("trace", help="trace the configuration space of a one-degree-of-freedom linkage")
    trace.add_argument("scene", type=Path, help="scene JSON file of a chain with mobility 1 (see examples/)")
    trace.add_argument("--parameter", action="append", metavar="PAIR",
                       help="a plan parameter (repeatable), e.g. --parameter P2,P4 --parameter P1,P6 (thesis §6.2); "
                            "default: the best plan's")
    trace.add_argument("--eta", metavar="TRIANGLES",
                       help="the triangles whose oriented areas' signs make η, most significant first, e.g. "
                            "P2,P4,P10;P1,P3,P6;P1,P6,P5;P4,P9,P7 (default: the plan's free-sign triangles)")
    trace.add_argument("--tracer", action="append", metavar="POINT",
                       help="a joint or a scene's tracer point (\"tracers\") whose path to draw (repeatable); "
                            "default: the scene's tracer points, else its last joint")
    trace.add_argument("--steps", type=int, default=400,
                       help="slices of the first parameter on which loops are sought (default 400; a circuit between "
                            "two slices is missed; two parameters: steps/8 slices)")
    trace.add_argument("--chord", type=float, default=1e-3,
                       help="the traced polylines stay within this fraction of the linkage's size of the "
                            "configuration curve (default 1e-3)")
    trace.add_argument("--input", metavar="INPUT",
                       help="drive the linkage: a scene input's name, an angle 'P1,P4,P2' (at P1 from P4 to P2, "
                            "degrees) or a distance 'P2,P5' (squared); lists every configuration at each value of "
                            "--grid, per traced piece, in order along it")
    trace.add_argument("--grid", type=int, default=36, metavar="N",
                       help="input values: N angles evenly round the circle, or N distances evenly over the "
                            "traced range (default 36)")
    trace.add_argument("--animate", type=Path, metavar="GIF",
                       help="with --input: an animation of the linkage moving from the piece with the most "
                            "driven configurations on through its branch points, the tracers' paths behind it")
    trace.add_argument("--fixed", metavar="LINK",
                       help="kinematic inversion: draw and list the configurations with this link fixed (its first "
                            "joint at the origin, its second on the x axis) instead of the scene's ground")
    trace.add_argument("--degree", action="store_true",
                       help="also the algebraic degree of each tracer's coupler curve and of a generic point's on "
                            "each moving link (exact dimensions and msolve needed; seconds to a minute per curve)")
    trace.add_argument("--joints", action="store_true",
                       help="with --input: every driven configuration's joint coordinates below its piece's line")
    trace.add_argument("--json", action="store_true", help="the pieces and branch points as JSON")
    trace.add_argument("--plot", type=Path, help="draw the configuration space and the coupler curves into this PNG")


def _triangles(text: str | None, default) -> list[tuple[str, str, str]]:
    from .main import UsageError

    if text is None:
        return [tuple(triangle) for triangle in default]
    triangles = [tuple(name.strip() for name in part.split(",")) for part in text.split(";")]
    if any(len(triangle) != 3 for triangle in triangles):
        raise UsageError(f"--eta {text}: triangles of three joints separated by ';', e.g. P2,P4,P10;P1,P3,P6")
    return triangles


def run_trace(args: argparse.Namespace) -> int:
    """Trace the scene's configuration space; print a summary, or JSON; draw it."""
    from baranov.motion import dead_points, one_dof_system, trace
    from baranov.scene import load_scene

    from .main import UsageError, check_picture, write_picture

    if args.steps < 8:
        raise UsageError(f"--steps {args.steps}: at least 8")
    if not 1e-9 <= args.chord <= 0.1:
        raise UsageError(f"--chord {args.chord:g}: between 1e-9 and 0.1 of the linkage's size")
    check_picture(args.plot)
    scene = load_scene(args.scene)
    parameters = None
    if args.parameter:
        parameters = [parameter_pair(pair) for pair in args.parameter]
    system = one_dof_system(scene, parameters)
    triangles, tracers, driver = _checked_options(args, scene, system)
    degrees = _degrees(scene, tracers) if args.degree else {}
    traced = trace(system, steps=args.steps, chord=args.chord)
    exact = _exact_ranges(system, traced)
    driven = _driven(system, traced, driver, args.grid) if driver is not None else []
    dead = dead_points(system, traced, driver) if driver is not None else []  # in the scene's frame, before --fixed
    if scene.tracers:
        from baranov.motion.tracer_paths import driven_with_tracer_points, traced_with_tracer_points

        traced, driven = traced_with_tracer_points(scene, traced), driven_with_tracer_points(scene, driven)
    fixed = None
    if args.fixed is not None and traced.pieces:
        from baranov.motion.inversion import inverted

        traced = inverted(traced, scene, args.fixed)
        first = traced.pieces[0].points[0]
        fixed = {joint: first.joints[joint] for joint in scene.link_of(args.fixed).joints}
    if args.plot is not None:
        from baranov.motion.drawing import render_trace

        write_picture(args.plot, render_trace(system, traced, tracers, triangles, fixed))
    if args.animate is not None:
        _animate(args.animate, scene, traced, driven, tracers, driver)
    if args.json:
        print(json.dumps(_as_json(args, scene, system, traced, triangles, degrees, driver, driven, exact, dead),
                         indent=1))
    else:
        _print_summary(args, system, traced, triangles, degrees, driver, driven, exact, dead)
    return 0


def _exact_ranges(system, traced):
    """One parameter and an exact scene: (the exact range of each piece or None, the exact
    ranges not traced, the undecided stretches) (:mod:`baranov.motion.exact_ranges`);
    else None."""
    from baranov.motion.exact_ranges import certified_pieces, exact_ranges

    if len(system.parameter_names) != 1 or not system.scene.exact:
        return None
    found = exact_ranges(system)
    return (*certified_pieces(system, traced, found), found.undecided)


def _end_json(end) -> dict:
    return {"value": end.digits(30), "polynomial": list(end.polynomial) if end.polynomial else None,
            "flat": [list(triangle) for triangle in end.triangles]}


def _range_json(exact_range) -> dict:
    return {"signs": list(exact_range.signs), "low": _end_json(exact_range.low), "high": _end_json(exact_range.high)}


def _checked_options(args: argparse.Namespace, scene, system):
    """The η triangles, the tracers and the input, each checked against the scene (one
    line naming what is wrong), and --fixed, --grid and --animate, before tracing."""
    from .main import UsageError

    triangles = _triangles(args.eta, system.plan.free_sign_triangles)
    joints = {joint.name for joint in scene.chain.joints}
    unknown = sorted({name for triangle in triangles for name in triangle} - joints)
    if unknown:
        raise UsageError(f"--eta: joint {unknown[0]}: no such joint in this chain")
    points = joints | {tracer.name for tracer in scene.tracers}
    from baranov.motion.tracer_paths import default_traced_points

    tracers = args.tracer or default_traced_points(scene)
    if set(tracers) - points:
        raise UsageError(f"--tracer {sorted(set(tracers) - points)[0]}: no such joint or tracer point in this scene")
    if args.fixed is not None:
        from baranov.motion.inversion import fixed_frame_joints

        fixed_frame_joints(scene, args.fixed)
    driver = _driver(scene, args.input) if args.input is not None else None
    if args.grid < 1:
        raise UsageError(f"--grid {args.grid}: at least 1")
    if args.joints and driver is None:
        raise UsageError("--joints: give --input too: the coordinates are those of the driven configurations")
    if args.animate is not None and (driver is None or not args.animate.parent.is_dir()):
        raise UsageError(f"--animate {args.animate}: " + ("give --input too: the animation follows the driven motion"
                                                         if driver is None else
                                                         f"folder {args.animate.parent} does not exist"))
    return triangles, tracers, driver


def _point(point, tracers: frozenset[str] = frozenset()) -> dict:
    """A traced configuration as JSON: its parameters, its joints and, apart, the scene's
    tracer points (``tracers``: their names)."""
    result = {**point.parameters, "joints": {j: list(p) for j, p in point.joints.items() if j not in tracers}}
    if tracers:
        result["tracers"] = {name: list(point.joints[name]) for name in sorted(tracers)}
    return result


def _eta(piece, triangles) -> int:
    from baranov.motion import sign_index

    return sign_index(piece.middle, triangles)


def _as_json(args, scene, system, traced, triangles, degrees, driver, driven, exact=None, dead=()) -> dict:
    names = frozenset(tracer.name for tracer in scene.tracers)
    result = {
        "parameters": list(system.parameter_names),
        "fixed_link": args.fixed or scene.ground,
        "eta_triangles": [list(t) for t in triangles],
        "circuits": [{"pieces": list(circuit.pieces), "branch_points": list(circuit.branch_points),
                      "singular_points": list(circuit.singular_points)} for circuit in traced.circuits],
        "pieces": [{"eta": _eta(piece, triangles), "signs": list(piece.signs), "closed": piece.closed,
                    "points": [_point(point, names) for point in piece.points]} for piece in traced.pieces],
        "branch_points": [{"pieces": [list(end) for end in bp.pieces], **bp.parameters,
                           "flat": [list(triangle) for triangle in bp.flat]} for bp in traced.branch_points],
        "singular_points": [{"pieces": list(sp.pieces), **_point(sp.point, names)} for sp in traced.singular_points],
        "loose_ends": [list(end) for end in traced.loose_ends],
        "unfinished": list(traced.unfinished),
        "jumps": list(traced.jumps),
    }
    if exact is not None:
        matched, untraced, undecided = exact
        for piece, exact_range in zip(result["pieces"], matched, strict=True):
            piece["exact_range"] = None if exact_range is None else _range_json(exact_range)
        result["untraced_ranges"] = [_range_json(exact_range) for exact_range in untraced]
        result["undecided_ranges"] = list(undecided)
    if args.degree:
        result["coupler_curve_degrees"] = degrees
    if driver is not None:
        result["dead_points"] = [{"circuit": point.circuit, "value": point.value, "maximum": point.maximum,
                                  **_point(point.point)} for point in dead]
        result["driven"] = [{"piece": branch.piece, "input": driver.name, "values": list(branch.values),
                             "points": [_point(point, names) for point in branch.points]} for branch in driven]
    return result


def _print_summary(args, system, traced, triangles, degrees, driver, driven, exact=None, dead=()) -> None:
    from baranov.motion.drawing import branches_text

    from .output import joint_lines

    noun = "circuit" if len(traced.circuits) == 1 else "circuits"
    print(f"{args.scene}: {len(traced.circuits)} {noun}, {len(traced.pieces)} pieces in "
          f"({', '.join(system.parameter_names)}), {len(traced.branch_points)} branch points, "
          f"{len(traced.singular_points)} singular configurations, {len(traced.loose_ends)} piece ends not joined")
    for number, circuit in enumerate(traced.circuits):
        print(f"circuit {number}: {branches_text(len(circuit.pieces))} (pieces {_listed(circuit.pieces)}), "
              f"{len(circuit.branch_points)} branch points"
              + (f", singular configurations {_listed(circuit.singular_points)}" if circuit.singular_points else ""))
    for sentence in traced.unfinished:
        print(f"unfinished: {sentence}")
    print("piece  eta  signs  points  " + "  ".join(f"{name} range" for name in system.parameter_names))
    for number, piece in enumerate(traced.pieces):
        ranges = "  ".join(f"[{min(p.parameters[n] for p in piece.points):.6g}, "
                           f"{max(p.parameters[n] for p in piece.points):.6g}]" for n in system.parameter_names)
        signs = "".join("+" if s > 0 else "-" for s in piece.signs)
        print(f"{number:5d}  {_eta(piece, triangles):3d}  {signs}  {len(piece.points):6d}"
              f"{' (closed)' if piece.closed else ''}  {ranges}")
    for sentence in traced.jumps:
        print(f"jump: {sentence}")
    if exact is not None:
        matched, untraced, undecided = exact
        print(f"exact ranges: {sum(r is not None for r in matched)} of {len(matched)} pieces certified (one connected "
              f"range each, ends exact), {len(untraced)} ranges not traced")
        for exact_range in untraced:
            print(f"  not traced: {system.parameter_names[0]} in [{exact_range.low.digits(12)}, "
                  f"{exact_range.high.digits(12)}] on signs {exact_range.signs}")
        for sentence in undecided:
            print(f"  undecided: {sentence}")
    if driver is not None:
        unit = "°" if driver.kind == "angle" else ""
        print(f"driven by {driver.name} ({driver.kind} {','.join(driver.joints)}), {args.grid} values: "
              f"{sum(len(b.points) for b in driven)} configurations on {len(driven)} pieces")
        for branch in driven:
            noun = "configuration" if len(branch.points) == 1 else "configurations"
            print(f"  piece {branch.piece:3d}: {len(branch.points):4d} {noun}, from {branch.values[0]:.6g}{unit} "
                  f"to {branch.values[-1]:.6g}{unit}")
            for value, point in zip(branch.values, branch.points, strict=True) if args.joints else ():
                lines = joint_lines(point.joints, indent=8)
                print(f"    {driver.name} = {value:.6g}{unit}:\n" + "\n".join(lines))
        _print_dead_points(traced, driver, dead, unit)
    if degrees:
        print("coupler-curve degrees: " + ", ".join(f"{where} {degree}" for where, degree in degrees.items()))


def _print_dead_points(traced, driver, dead, unit: str) -> None:
    """Per circuit, the input's dead points and the branches they cut it into (Chase and
    Mirth: none, one branch driven round in full)."""
    from baranov.motion.drawing import branches_text

    for number in range(len(traced.circuits)):
        here = [point for point in dead if point.circuit == number]
        values = ", ".join(f"{'max' if point.maximum else 'min'} {point.value:.6g}{unit}" for point in here)
        noun = "dead point" if len(here) == 1 else "dead points"
        print(f"  circuit {number}: {len(here)} {noun} of {driver.name}" + (f" ({values})" if here else "")
              + f", {branches_text(max(len(here), 1))} relative to it")


def _listed(numbers) -> str:
    """Indices as runs: 0-3, 7, 9-10."""
    runs: list[list[int]] = []
    for n in numbers:
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    return ", ".join(f"{run[0]}-{run[-1]}" if len(run) > 1 else f"{run[0]}" for run in runs)


def _driver(scene, text: str):
    """The input named ``text`` in the scene, or the angle (three joints) or distance (two
    joints) it lists."""
    from baranov.scene import SceneInput

    from .main import UsageError

    named = {entry.name: entry for entry in scene.inputs}
    if text in named:
        return named[text]
    joints = [name.strip() for name in text.split(",")]
    known = {joint.name for joint in scene.chain.joints}
    if len(joints) not in (2, 3) or not all(joints):
        raise UsageError(f"--input {text}: a scene input's name, three joints (an angle) or two (a distance)")
    unknown = [joint for joint in joints if joint not in known]
    if unknown:
        raise UsageError(f"--input {text}: joint {unknown[0]}: no such joint in this chain")
    if len(set(joints)) != len(joints):
        raise UsageError(f"--input {text}: a joint named twice; an angle needs three joints, a distance two")
    return SceneInput(text, "angle" if len(joints) == 3 else "distance", tuple(joints))


def _driven(system, traced, driver, count: int):
    """The driven motion at ``count`` values: angles evenly round the circle, distances
    evenly over the traced range."""
    import numpy as np

    from baranov.motion.driving import driven_motion, input_value

    if driver.kind == "angle":
        grid = -180.0 + 360.0 * np.arange(count) / count
    else:
        reached = [input_value(driver, point) for piece in traced.pieces for point in piece.points]
        grid = np.linspace(min(reached), max(reached), count) if reached else np.zeros(0)
    return driven_motion(system, traced, driver, grid)


def _animate(path: Path, scene, traced, driven, tracers: list[str], driver) -> None:
    """The GIF of the motion from the longest driven piece on through its branch points
    (:func:`baranov.motion.driving.followed`), written atomically."""
    from baranov.motion.animation import render_animation
    from baranov.motion.driving import followed

    from .main import UsageError, write_picture

    if not driven:
        raise UsageError(f"--animate {path}: the input reaches none of its --grid values on the traced pieces")
    longest = max(driven, key=lambda branch: len(branch.points))
    motion = followed(traced, driven, longest.piece)
    write_picture(path, render_animation(scene, motion, tracers, driver.name, "°" if driver.kind == "angle" else ""))


def _degrees(scene, tracers: list[str]) -> dict[str, int | str]:
    """The coupler-curve degree of each tracer joint ("fixed" on the ground) and of a
    generic point of each moving link (:func:`baranov.motion.coupler_curve_degree`)."""
    from baranov.motion import coupler_curve_degree
    from baranov.scene.tracers import exact_ratio

    from .main import UsageError

    moving = [link for link in scene.links if link.name != scene.ground]
    points = {tracer.name: tracer for tracer in scene.tracers}
    try:
        degrees: dict[str, int | str] = {}
        for name in tracers:
            if name in points:
                degrees[name] = _tracer_point_degree(scene, points[name], exact_ratio(points[name]))
                continue
            link = next((link.name for link in moving if name in link.joints), None)
            fixed = link is None or name in scene.world
            degrees[name] = "fixed" if fixed else coupler_curve_degree(scene, link, joint=name)
        for link in moving:
            degrees[f"{link.name} (generic point)"] = coupler_curve_degree(scene, link.name, seed=0)
    except RuntimeError as error:  # msolve missing (MsolveUnavailable) or failing
        raise UsageError(f"--degree: {error}") from None
    return degrees


def _tracer_point_degree(scene, tracer, ratio) -> int | str:
    """The coupler-curve degree of a tracer point: "fixed" on the ground link; its (λ, μ)
    must be rational (the elimination is exact)."""
    from baranov.motion import coupler_curve_degree

    from .main import UsageError

    if tracer.link == scene.ground:
        return "fixed"
    if ratio is None:
        raise UsageError(f"--degree: tracer {tracer.name}: its place on link {tracer.link} is not rational "
                         "(give the link by rational coordinates)")
    return coupler_curve_degree(scene, tracer.link, ratio)
