"""``baranov trace``: the configuration space of a one-degree-of-freedom linkage traced in
distance space, its pieces and branch points, and the coupler curves (thesis ch. 6)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path


def add_trace_parser(commands) -> None:
    trace = commands.add_parser("trace", help="trace the configuration space of a one-degree-of-freedom linkage")
    trace.add_argument("scene", type=Path, help="scene JSON file of a chain with mobility 1 (see examples/)")
    trace.add_argument("--parameter", action="append", metavar="PAIR",
                       help="a plan parameter (repeatable), e.g. --parameter P2,P4 --parameter P1,P6 (thesis §6.2); "
                            "default: the best plan's")
    trace.add_argument("--eta", metavar="TRIANGLES",
                       help="the triangles whose oriented areas' signs make η, most significant first, e.g. "
                            "P2,P4,P10;P1,P3,P6;P1,P6,P5;P4,P9,P7 (default: the plan's free-sign triangles)")
    trace.add_argument("--tracer", action="append", metavar="JOINT", help="a joint whose path to draw (repeatable)")
    trace.add_argument("--steps", type=int, default=400, help="resolution: slices of the first parameter (default 400)")
    trace.add_argument("--fixed", metavar="LINK",
                       help="kinematic inversion: draw and list the configurations with this link fixed (its first "
                            "joint at the origin, its second on the x axis) instead of the scene's ground")
    trace.add_argument("--degree", action="store_true",
                       help="also the algebraic degree of each tracer's coupler curve and of a generic point's on "
                            "each moving link (exact dimensions and msolve needed; seconds to a minute per curve)")
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
    from baranov.catalog.files import write_atomically
    from baranov.motion import one_dof_system, sign_index, trace
    from baranov.scene import load_scene

    from .main import UsageError

    if args.steps < 8:
        raise UsageError(f"--steps {args.steps}: at least 8")
    if args.plot is not None and not args.plot.parent.is_dir():
        raise UsageError(f"--plot {args.plot}: folder {args.plot.parent} does not exist")
    scene = load_scene(args.scene)
    parameters = None
    if args.parameter:
        parameters = [tuple(name.strip() for name in pair.split(",")) for pair in args.parameter]
        if any(len(pair) != 2 for pair in parameters):
            raise UsageError(f"--parameter {args.parameter}: pairs of joints, e.g. P2,P4")
    system = one_dof_system(scene, parameters)
    triangles = _triangles(args.eta, system.plan.free_sign_triangles)
    joints = {joint.name for joint in scene.chain.joints}
    unknown = sorted({name for triangle in triangles for name in triangle} - joints)
    if unknown:
        raise UsageError(f"--eta: joint {unknown[0]}: no such joint in this chain")
    tracers = args.tracer or [sorted(joints - set(scene.world), key=lambda n: int(n[1:]) if n[1:].isdigit() else 0)[-1]]
    if set(tracers) - joints:
        raise UsageError(f"--tracer {sorted(set(tracers) - joints)[0]}: no such joint in this chain")
    degrees = _degrees(scene, tracers) if args.degree else {}
    if args.fixed is not None:
        from baranov.motion.inversion import fixed_frame_joints

        fixed_frame_joints(scene, args.fixed)  # refused before tracing
    traced = trace(system, steps=args.steps)
    fixed = None
    if args.fixed is not None and traced.pieces:
        from baranov.motion.inversion import inverted

        traced = inverted(traced, scene, args.fixed)
        first = traced.pieces[0].points[0]
        fixed = {joint: first.joints[joint] for joint in scene.link_of(args.fixed).joints}
    if args.plot is not None:
        from baranov.motion.drawing import render_trace

        write_atomically(args.plot, render_trace(system, traced, tracers, triangles, fixed))
    if args.json:
        print(json.dumps({
            "parameters": list(system.parameter_names),
            "fixed_link": args.fixed or scene.ground,
            "eta_triangles": [list(t) for t in triangles],
            "pieces": [{"eta": sign_index(piece.points[0], triangles), "signs": list(piece.signs),
                        "closed": piece.closed,
                        "points": [{**point.parameters, "joints": {j: list(p) for j, p in point.joints.items()}}
                                   for point in piece.points]} for piece in traced.pieces],
            "branch_points": [{"pieces": [list(end) for end in bp.pieces], **bp.parameters}
                              for bp in traced.branch_points],
            "loose_ends": [list(end) for end in traced.loose_ends],
            "jumps": list(traced.jumps),
            **({"coupler_curve_degrees": degrees} if args.degree else {})}, indent=1))
        return 0
    print(f"{args.scene}: {len(traced.pieces)} pieces in ({', '.join(system.parameter_names)}), "
          f"{len(traced.branch_points)} branch points, {len(traced.loose_ends)} piece ends not joined")
    print("piece  eta  signs  points  " + "  ".join(f"{name} range" for name in system.parameter_names))
    for number, piece in enumerate(traced.pieces):
        ranges = "  ".join(f"[{min(p.parameters[n] for p in piece.points):.6g}, "
                           f"{max(p.parameters[n] for p in piece.points):.6g}]" for n in system.parameter_names)
        signs = "".join("+" if s > 0 else "-" for s in piece.signs)
        print(f"{number:5d}  {sign_index(piece.points[0], triangles):3d}  {signs}  {len(piece.points):6d}"
              f"{' (closed)' if piece.closed else ''}  {ranges}")
    for sentence in traced.jumps:
        print(f"jump: {sentence}")
    if degrees:
        print("coupler-curve degrees: " + ", ".join(f"{where} {degree}" for where, degree in degrees.items()))
    return 0


def _degrees(scene, tracers: list[str]) -> dict[str, int | str]:
    """The coupler-curve degree of each tracer joint ("fixed" on the ground) and of a
    generic point of each moving link (:func:`baranov.motion.coupler_curve_degree`)."""
    from baranov.motion import coupler_curve_degree
    from baranov.solvers.msolve import MsolveUnavailable

    from .main import UsageError

    moving = [link for link in scene.links if link.name != scene.ground]
    try:
        degrees: dict[str, int | str] = {}
        for joint in tracers:
            link = next((link.name for link in moving if joint in link.joints), None)
            fixed = link is None or joint in scene.world
            degrees[joint] = "fixed" if fixed else coupler_curve_degree(scene, link, joint=joint)
        for link in moving:
            degrees[f"{link.name} (generic point)"] = coupler_curve_degree(scene, link.name, seed=0)
    except MsolveUnavailable as error:
        raise UsageError(f"--degree: {error}") from None
    return degrees
