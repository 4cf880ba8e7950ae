"""One redraw of the explorer: every assembly mode at a set of dimensions, each with the
identity it had in the previous redraw, the places where modes met or appeared on the way,
and the solve's certificate; and a dimension's profile (the number of real modes across its
range).

Everything here returns plain JSON-ready dictionaries; :mod:`baranov.explore.server`
sends them to the page.
"""

from __future__ import annotations

import math
import threading
import time
import warnings
from collections.abc import Mapping, Sequence

from baranov.scene import SceneError
from baranov.solvers import Solution, SolverError, solve
from baranov.solvers.drawing import mode_shapes
from baranov.solvers.modes import signs_text
from baranov.solvers.verification import distance_bound

from .continuity import count_changes, match_modes
from .document import Document, document_robot, document_scene

#: Bisection of a change in the number of modes: to this fraction of the way between two
#: redraws, or of a profile's step; COARSE_TOLERANCE where one solve takes longer than
#: SLOW_SOLVE seconds (a coupling-2 nine-link truss: 0.2 s), so that a redraw with an event
#: stays within about a second.
EVENT_TOLERANCE = 1e-4
COARSE_TOLERANCE = 1e-2
SLOW_SOLVE = 0.02
#: Seconds a profile may spend on its samples; fewer samples (at least PROFILE_FEWEST)
#: where solves are slow.
PROFILE_BUDGET = 3.0
PROFILE_FEWEST = 11
#: One solve at a time in a process: the backends' plan and kernel caches are shared, and
#: a long task (a profile, a trace) lets redraws in between its solves.
SOLVING = threading.RLock()


def solve_document(document: Document, values: Mapping[str, float], method: str = "numeric"):
    """The scene the document makes with ``values``, its solution, and for a robot the
    robot and each mode's pose (None for a scene). Raises SceneError or SolverError."""
    with SOLVING, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if document.kind == "robot":
            from baranov.robots.kinematics import robot_solution

            scene, robot, actuators, _ = document_robot(document, values)
            solution, poses = robot_solution(robot, actuators, method)
            return scene, solution, (robot, poses)
        scene = document_scene(document, values)
        if scene.mobility > 0 and scene.inputs[0].kind == "distance":
            return scene, sliced_solution(scene), None
        return scene, solve(scene, method=method), None


def sliced_solution(scene) -> Solution:
    """The configurations of a moving scene whose distance input is held: the slice of
    its configuration curve where its one-degree-of-freedom plan's first parameter (the
    input's pair, else SolverError) has the input's value (:func:`baranov.motion.configurations_at`:
    sampled, not certified). The backends hold crank angles only (``solve_held``)."""
    from baranov.motion import one_dof_system
    from baranov.motion.configuration_space import configurations_at

    driver = scene.inputs[0]
    system = one_dof_system(scene)
    if set(system.plan.parameters[0]) != set(driver.joints):
        first = ",".join(system.plan.parameters[0])
        raise SolverError(f"input {driver.name}: held where it is the plan's first parameter ({first}) or a crank "
                          "angle; baranov trace SCENE --input NAME drives any input")
    modes = tuple(configurations_at(system, float(driver.value)))
    return Solution.of_plan("numeric (a slice of the traced motion)", scene, system.plan, modes,
                            undecided=("a slice of the configuration curve, sampled: a fold between samples can be "
                                       "missed",))


def mode_count(document: Document, values: Mapping[str, float]) -> int | None:
    """The number of real assembly modes (numeric backend), None where the dimensions make
    no linkage or the linkage moves."""
    try:
        return len(solve_document(document, values)[1].assembly_modes)
    except (SceneError, SolverError):
        return None


def view_box(document: Document, frame: Mapping) -> list[float]:
    """[x, y, width, height] holding every mode of ``frame`` and the fixed link, with a
    margin: the page keeps it while dimensions change, so that the drawing stays still."""
    points = [tuple(map(float, p)) for p in document.scene.world.values()]
    points += [tuple(p) for mode in frame.get("modes", []) for p in mode["joints"].values()]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    extent = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    margin = 0.12 * extent
    return [min(xs) - margin, min(ys) - margin, max(xs) - min(xs) + 2 * margin, max(ys) - min(ys) + 2 * margin]


def solve_frame(document: Document, values: Mapping[str, float], method: str = "numeric",
                previous: Mapping | None = None, next_id: int = 0) -> dict:
    """The redraw at ``values``: ``modes`` (each with ``id``, ``signs``, ``parameters``,
    ``joints``, ``residual``, ``shapes`` (:func:`~baranov.solvers.drawing.mode_shapes`)
    and for a robot ``pose``), ``certificate`` (a sentence) and ``complete``, ``events``
    (where modes met or appeared since ``previous``), ``seconds``, ``next_id``; or
    ``error`` (a sentence) where the dimensions make no linkage or the linkage moves.

    ``previous``: the last redraw as the page has it, ``{"values": {...}, "modes":
    [{"id": 3, "joints": {...}}, ...]}``. A mode keeps the id of the previous mode it
    continues (:func:`~baranov.explore.continuity.match_modes`); a new one takes
    ``next_id`` and up."""
    start = time.perf_counter()
    try:
        scene, solution, robot_poses = solve_document(document, values, method)
    except (SceneError, SolverError) as error:
        return {"error": str(error), "modes": [], "events": [], "next_id": next_id,
                "seconds": time.perf_counter() - start}
    size = distance_bound(document.scene)
    modes = solution.assembly_modes
    earlier = list(previous["modes"]) if previous else []
    matched = match_modes([mode["joints"] for mode in earlier], [mode.joints for mode in modes], size)
    ids = []
    for index in matched:
        ids.append(earlier[index]["id"] if index is not None else next_id)
        next_id += index is None
    frame = {"modes": [_mode_entry(scene, mode, ident, size) for mode, ident in zip(modes, ids, strict=True)],
             **_certificate_entry(solution), "next_id": next_id}
    if robot_poses is not None:
        _add_poses(frame["modes"], *robot_poses, modes)
    lost = len(earlier) - sum(index is not None for index in matched)
    tolerance = EVENT_TOLERANCE if time.perf_counter() - start < SLOW_SOLVE else COARSE_TOLERANCE
    frame["events"] = (_events(document, previous["values"], values, len(earlier), len(modes), size, tolerance)
                       if previous and (lost or len(earlier) != len(modes)) else [])
    frame["seconds"] = time.perf_counter() - start
    return frame


def dimension_profile(document: Document, values: Mapping[str, float], name: str, samples: int = 101) -> dict:
    """The number of real modes (numeric backend) at ``samples`` values of the control
    ``name`` across its range, the others at ``values``, and each value where the number
    changes (bisected to :data:`EVENT_TOLERANCE` of a step): for which values of a
    dimension the linkage assembles, and in how many ways. ``counts`` has None where the
    dimensions make no linkage or it moves. Where one solve is slow, fewer samples (the
    :data:`PROFILE_BUDGET`), a coarser bisection, and past twice the budget the changes
    placed halfway between their samples."""
    control = document.control(name)
    start = time.perf_counter()
    first = mode_count(document, {**values, name: control.low})  # timed: how many samples the budget allows
    seconds = time.perf_counter() - start
    samples = max(min(samples, int(PROFILE_BUDGET / max(seconds, 1e-9))), PROFILE_FEWEST)
    tolerance = EVENT_TOLERANCE if seconds < SLOW_SOLVE else COARSE_TOLERANCE
    grid = [control.low + (control.high - control.low) * k / (samples - 1) for k in range(samples)]
    counts = [first] + [mode_count(document, {**values, name: value}) for value in grid[1:]]
    changes = []
    deadline = start + 2 * PROFILE_BUDGET
    for k in range(samples - 1):
        bisect = time.perf_counter() < deadline  # past the budget a change is placed between its samples
        if counts[k] != counts[k + 1] and None not in (counts[k], counts[k + 1]) and bisect:
            low, high = grid[k], grid[k + 1]

            def count(fraction: float, low=low, high=high) -> int:
                return mode_count(document, {**values, name: low + (high - low) * fraction}) or 0

            for change in count_changes(count, counts[k], counts[k + 1], tolerance):
                changes.append({"value": low + (high - low) * change.fraction, "before": change.before,
                                "after": change.after})
        elif counts[k] != counts[k + 1]:
            changes.append({"value": (grid[k] + grid[k + 1]) / 2, "before": counts[k], "after": counts[k + 1]})
    return {"name": name, "values": grid, "counts": counts, "changes": changes}


def _joints_entry(joints: Mapping) -> dict[str, list[float]]:
    return {name: [float(x), float(y)] for name, (x, y) in joints.items()}


def _mode_entry(scene, mode, ident: int, size: float) -> dict:
    return {"id": ident, "signs": signs_text(mode.signs), "parameters": mode.parameters,
            "joints": _joints_entry(mode.joints), "residual": mode.max_residual,
            "shapes": mode_shapes(scene, mode.joints, size)}


def _add_poses(entries: list[dict], robot, poses, modes) -> None:
    """Each robot mode's platform pose, and its actuated prismatic joints as blocks."""
    from baranov.robots.drawing import actuator_blocks

    for entry, pose, mode in zip(entries, poses, modes, strict=True):
        entry["pose"] = {"position": list(pose.position), "angle": math.degrees(pose.angle)}
        xs, ys = zip(*mode.joints.values(), strict=True)
        entry["shapes"]["blocks"] = actuator_blocks(robot, mode.joints, max(max(xs) - min(xs), max(ys) - min(ys)))


def _certificate_entry(solution: Solution) -> dict:
    certificate = solution.certificate
    if certificate is None:
        why = "; ".join(solution.undecided) or f"the {solution.method} method proves nothing about completeness"
        return {"certificate": f"not certified: {why}", "complete": False, "undecided": list(solution.undecided)}
    return {"certificate": certificate.summary(), "complete": certificate.complete and not certificate.probabilistic,
            "undecided": list(solution.undecided)}


def _events(document: Document, before: Mapping[str, float], after: Mapping[str, float], count_before: int,
            count_after: int, size: float, tolerance: float = EVENT_TOLERANCE) -> list[dict]:
    """Where the number of real modes changed on the straight way from ``before`` to
    ``after`` (bisected, numeric backend): each with the kind ("merge": modes met and left
    the real plane, "split": they appeared), the dimensions there, and the configurations
    of the modes that met or appeared, just on their side."""
    names = sorted(after.keys() & before.keys())

    def at(fraction: float) -> dict[str, float]:
        return {name: before[name] + (after[name] - before[name]) * fraction for name in names}

    def count(fraction: float) -> int:
        return mode_count(document, at(fraction)) or 0

    events = []
    moved = max(names, key=lambda name: abs(after[name] - before[name]) / max(abs(before[name]), 1e-12), default=None)
    for change in count_changes(count, count_before, count_after, tolerance):
        low, high = change.fraction - change.width / 2, change.fraction + change.width / 2
        more, fewer = (low, high) if change.before > change.after else (high, low)
        ghosts = _unmatched(document, at(more), at(fewer), size)
        values = at(change.fraction)
        events.append({"kind": "merge" if change.before > change.after else "split", "before": change.before,
                       "after": change.after, "values": values, "dimension": moved,
                       "value": values.get(moved) if moved else None, "configurations": ghosts})
    return events


def _unmatched(document: Document, more: Mapping, fewer: Mapping, size: float) -> list[dict]:
    """The configurations at ``more`` that no configuration at ``fewer`` continues, each
    with its joints and shapes."""
    try:
        scene, solution, _ = solve_document(document, more)
        few = solve_document(document, fewer)[1].assembly_modes
    except (SceneError, SolverError):
        return []
    many = solution.assembly_modes
    matched = set(match_modes([mode.joints for mode in many], [mode.joints for mode in few], size))
    return [{"joints": _joints_entry(mode.joints), "shapes": mode_shapes(scene, mode.joints, size)}
            for k, mode in enumerate(many) if k not in matched]


def frame_modes(frame: Mapping) -> Sequence[Mapping]:
    """The modes of a redraw as the next redraw's ``previous`` needs them."""
    return [{"id": mode["id"], "joints": mode["joints"]} for mode in frame["modes"]]
