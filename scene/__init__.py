"""The scene: a concrete linkage — links with their dimensions (squared distances or
joint coordinates), a ground link — as users write it (JSON) and as every backend reads
it; its validation (one clear error naming the offending link, joint or value); and
random instances of a truss built from integer configurations (thesis §2.1: the
dimensions of a Baranov truss)."""

from .instances import generic_integer_configuration, instance_dict, scene_of
from .model import Scene, SceneError, SceneLink, load_scene, rational_sqrt, scene_from_dict

__all__ = [
    "Scene",
    "SceneError",
    "SceneLink",
    "generic_integer_configuration",
    "instance_dict",
    "load_scene",
    "rational_sqrt",
    "scene_from_dict",
    "scene_of",
]
