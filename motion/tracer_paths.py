"""The paths of a scene's tracer points (:mod:`baranov.scene.tracers`: points of links that
are not joints, such as a coupler point) along a trace and a driven motion: each traced
configuration carries its tracers' coordinates beside its joints', under the tracers'
names, so that drawing, animation and kinematic inversion treat them as they treat a
joint (an inversion moves them rigidly with the rest)."""

from __future__ import annotations

from dataclasses import replace

from baranov.scene import Scene, tracer_positions

from .configuration_space import ConfigurationPoint
from .driving import DrivenBranch
from .tracing import Trace


def default_traced_points(scene: Scene) -> list[str]:
    """The points a trace draws when none are named: the scene's tracer points, else its
    last moving joint (by number, P12 after P9)."""
    moving = {joint.name for joint in scene.chain.joints} - set(scene.world)
    last = sorted(moving, key=lambda name: int(name[1:]) if name[1:].isdigit() else 0)[-1]
    return [tracer.name for tracer in scene.tracers] or [last]


def with_tracer_points(scene: Scene, point: ConfigurationPoint) -> ConfigurationPoint:
    """``point`` with the coordinates of every tracer of ``scene`` added to its joints.
    O(tracers)."""
    if not scene.tracers:
        return point
    link_joints = {link.name: link.joints for link in scene.links}
    return replace(point, joints={**point.joints, **tracer_positions(scene.tracers, link_joints, point.joints)})


def traced_with_tracer_points(scene: Scene, traced: Trace) -> Trace:
    """Every configuration of every piece of ``traced`` with its tracers
    (:func:`with_tracer_points`). O(points × tracers)."""
    pieces = tuple(replace(piece, points=tuple(with_tracer_points(scene, point) for point in piece.points))
                   for piece in traced.pieces)
    return replace(traced, pieces=pieces)


def driven_with_tracer_points(scene: Scene, driven: list[DrivenBranch]) -> list[DrivenBranch]:
    """Every configuration of a driven motion with its tracers (:func:`with_tracer_points`)."""
    return [replace(branch, points=tuple(with_tracer_points(scene, point) for point in branch.points))
            for branch in driven]
