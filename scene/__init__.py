"""The scene: a concrete linkage — links with their dimensions (squared distances or
joint coordinates), a ground link — as users write it (JSON) and as every backend reads
it; its validation (one clear error naming the offending link, joint or value); and
random instances of a truss built from integer configurations (thesis §2.1: the
dimensions of a Baranov truss); adversarial and hard instances (issue 25); the scene
with some dimensions replaced, for sweeps and batches (:mod:`~baranov.scene.dimensions`);
and, for a linkage with mobility F > 0, its named inputs (:mod:`~baranov.scene.inputs`)
and the points of links whose paths a trace draws (:mod:`~baranov.scene.tracers`)."""

from .dimensions import dimension_names, link_entry, load_instances, with_dimensions
from .inputs import SceneInput, angle_as_distance
from .instances import generic_integer_configuration, instance_dict, scene_of
from .model import Scene, SceneError, SceneLink, load_scene, scene_from_dict
from .numbers import Number, rational_sqrt
from .tracers import TracerPoint, tracer_positions

__all__ = [
    "Number",
    "Scene",
    "SceneError",
    "SceneInput",
    "SceneLink",
    "TracerPoint",
    "angle_as_distance",
    "dimension_names",
    "generic_integer_configuration",
    "instance_dict",
    "link_entry",
    "load_instances",
    "load_scene",
    "rational_sqrt",
    "scene_from_dict",
    "scene_of",
    "tracer_positions",
    "with_dimensions",
]
