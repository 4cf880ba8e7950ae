"""Fuzzing the scene loader and the solvers (issue 22): random JSON structures and random
perturbations of the example scenes give a scene or a :class:`ValueError` subclass with a
message, and a scene gives a solution or such an error, never another exception.

The default suite draws FUZZ_EXAMPLES cases per test; ``make fuzz`` runs the long version
(``BARANOV_FUZZ_EXAMPLES``, 10⁴ by default there).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from baranov.scene import scene_from_dict
from baranov.solvers import solve
from baranov.solvers.msolve import find_msolve

REPO = Path(__file__).resolve().parents[1]
SMALL_EXAMPLES = ["3-B1", "5-B1", "7-B1", "7-B2"]
SLIDER_EXAMPLES = ["7-B3-slider-P9", "7-B3-sliders-P8-P9", "7-B3-slider-P1"]
EXAMPLES = {name: json.loads((REPO / "examples" / f"{name}.json").read_text(encoding="utf-8"))
            for name in SMALL_EXAMPLES + SLIDER_EXAMPLES}
FUZZ_EXAMPLES = int(os.environ.get("BARANOV_FUZZ_EXAMPLES", "60"))
FUZZ = settings(max_examples=FUZZ_EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow],
                derandomize="BARANOV_FUZZ_EXAMPLES" not in os.environ)

SCALARS = (st.none() | st.booleans() | st.integers(-10**30, 10**30)
           | st.floats(allow_nan=True, allow_infinity=True) | st.text(max_size=12)
           | st.sampled_from(["9/5", "-1", "0", "1e400", "P1,P2", "ccw", "cw", "P1", "ground", "2.5", "1/0",
                            "pi - atan(5/2)", "atan2(0, 0)", "atan(1/0)", "2 pi", "pi/3 + atan(1e400)"]))
JSON_VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=4)
                           | st.dictionaries(st.sampled_from(["links", "ground", "name", "joints", "squared_length",
                                                              "squared_distances", "orientation", "P1", "x",
                                                              "sliders", "joint", "angles", "inputs", "angle",
                                                              "distance", "degrees", "squared_distance"])
                                             | st.text(max_size=6), inner, max_size=4), max_leaves=12)


def _accepts_or_explains(call):
    """Run ``call``: a result, or a ValueError subclass with a one-line message."""
    try:
        return call()
    except ValueError as error:
        message = str(error)
        assert message and "\n" not in message, repr(message)
        return None


@FUZZ
@given(JSON_VALUES)
def test_random_json_gives_a_scene_or_a_scene_error(data):
    _accepts_or_explains(lambda: scene_from_dict(data))


def _paths(value, prefix=()):
    """Every path (keys and indices) into a JSON structure."""
    yield prefix
    if isinstance(value, dict):
        for key, item in value.items():
            yield from _paths(item, (*prefix, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from _paths(item, (*prefix, index))


def _mutated(data: dict, draw) -> dict:
    """``data`` with one to three random changes. Most change one number of the scene
    (scaled by -1, 0, 1e-9, 1/2, 2 or 1e9, nudged by 1e-12, or replaced by a small
    integer or decimal), which keeps it a scene with other dimensions; the others replace
    any value by a random JSON value, delete a key, or duplicate a link."""
    data = json.loads(json.dumps(data))
    for _ in range(draw(st.integers(1, 3))):
        paths = [p for p in _paths(data) if p and p[0] != "comment"]
        numbers = [p for p in paths if _is_number(_at(data, p))]
        kind = draw(st.sampled_from(["scale", "nudge", "small", "scale", "nudge", "small", "replace", "delete",
                                     "duplicate"]))
        pool = numbers if kind in ("scale", "nudge", "small") and numbers else paths
        if not pool:
            break
        path = draw(st.sampled_from(pool))
        parent, old = _at(data, path[:-1]), _at(data, path)
        if kind == "scale" and _is_number(old):
            parent[path[-1]] = old * draw(st.sampled_from([-1, 0, 1e-9, 0.5, 2, 1e9]))
        elif kind == "nudge" and _is_number(old):
            parent[path[-1]] = old + 1e-12 * (abs(old) + 1)
        elif kind == "small" and _is_number(old):
            parent[path[-1]] = draw(st.integers(-5, 60) | st.decimals(-5, 60, places=2).map(float))
        elif kind == "delete":
            del parent[path[-1]]
        elif kind == "duplicate" and isinstance(parent, list):
            parent.append(json.loads(json.dumps(old)))
        else:
            parent[path[-1]] = draw(JSON_VALUES)
    return data


def _at(data, path: tuple):
    for key in path:
        data = data[key]
    return data


def _is_number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


@FUZZ
@given(st.sampled_from(SMALL_EXAMPLES), st.sampled_from(["numeric", "exact"]), st.data())
def test_perturbed_examples_give_modes_or_an_error(name, method, data):
    scene_data = _mutated(EXAMPLES[name], data.draw)
    scene = _accepts_or_explains(lambda: scene_from_dict(scene_data))
    if scene is None or (method == "exact" and not scene.exact):
        event("no scene" if scene is None else "inexact")
        return
    options = {"time_limit": 20.0} if method == "numeric" else {}
    solution = _accepts_or_explains(lambda: solve(scene, method=method, **options))
    event(f"{method}: {'solved' if solution is not None else 'refused'}")
    if solution is not None:
        for mode in solution.assembly_modes:
            assert all(math.isfinite(c) for point in mode.joints.values() for c in point)


@FUZZ
@given(st.sampled_from(SLIDER_EXAMPLES), st.data())
def test_perturbed_slider_chains_give_modes_or_an_error(name, data):
    """Slider scenes (angles, joints, links perturbed): a scene or a SceneError; a scene
    gives msolve's verified modes or a SolverError (the numeric method refuses sliders)."""
    scene_data = _mutated(EXAMPLES[name], data.draw)
    scene = _accepts_or_explains(lambda: scene_from_dict(scene_data))
    if scene is None:
        event("no scene")
        return
    method = "msolve" if find_msolve() is not None and scene.exact else "numeric"
    solution = _accepts_or_explains(lambda: solve(scene, method=method))
    event(f"{method}: {'solved' if solution is not None else 'refused'}")
    if solution is not None:
        for mode in solution.assembly_modes:
            assert all(math.isfinite(c) for point in mode.joints.values() for c in point)
