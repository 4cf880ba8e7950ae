"""A one-degree-of-freedom linkage's whole motion for the explorer: its configuration
curve traced once (:func:`baranov.motion.trace`, thesis ch. 6), each piece with the input's
value along it, the plan's first parameter, and the path of every joint and tracer point
along it (the page draws the chosen ones as coupler curves, by default the scene's tracer
points, else its last joint, as ``baranov trace`` does, and places a configuration moved
along a piece from them)."""

from __future__ import annotations

from collections.abc import Mapping

from baranov.scene import tracer_positions

from .document import Document, document_scene
from .frames import SOLVING

#: Slices of the first parameter the explorer traces with (``baranov trace``: 400).
TRACE_STEPS = 200


def traced_motion(document: Document, values: Mapping[str, float], steps: int = TRACE_STEPS) -> dict:
    """The traced motion of a moving document at ``values``: ``input`` (the first input's
    control name), ``parameter`` (the plan's first parameter), ``points`` (the points
    drawn by default: :func:`~baranov.motion.tracer_paths.default_traced_points`) and
    ``pieces``, each with its ``signs``, ``closed``, ``inputs`` and ``parameters`` (one
    value per configuration along it) and ``paths`` (every joint and tracer point → [x, y]
    per configuration) and ``circuit`` (the index of its circuit); ``circuits`` (each
    circuit's pieces), ``loose_ends`` and ``branch_points`` as the trace counts them.
    Cost: the trace, about 0.1–1 s for six to eight links."""
    from baranov.motion import one_dof_system, trace
    from baranov.motion.driving import input_value
    from baranov.motion.tracer_paths import default_traced_points

    scene = document_scene(document, values)
    if scene.mobility == 0:
        raise ValueError(f"{document.title}: the linkage is rigid; only a moving linkage (mobility 1) is traced")
    with SOLVING:
        system = one_dof_system(scene)
        traced = trace(system, steps=steps)
    driver = scene.inputs[0]
    link_joints = {link.name: link.joints for link in scene.links}
    points = default_traced_points(scene)
    circuit_of_piece = {n: number for number, circuit in enumerate(traced.circuits) for n in circuit.pieces}
    pieces = []
    for index, piece in enumerate(traced.pieces):
        placed = [{**point.joints, **tracer_positions(scene.tracers, link_joints, point.joints)} for point in piece.points]
        pieces.append({"signs": list(piece.signs), "closed": piece.closed, "circuit": circuit_of_piece.get(index),
                       "inputs": [input_value(driver, point) for point in piece.points],
                       "parameters": [point.parameters[system.parameter_names[0]] for point in piece.points],
                       "paths": {name: [list(map(float, joints[name])) for joints in placed] for name in placed[0]}})
    return {"input": f"input {driver.name}", "input_kind": driver.kind, "parameter": system.parameter_names[0],
            "parameter_joints": list(system.plan.parameters[0]),
            "points": points, "pieces": pieces, "branch_points": len(traced.branch_points),
            "circuits": [list(circuit.pieces) for circuit in traced.circuits],
            "loose_ends": len(traced.loose_ends)}
