"""What counts as an assembly mode (solvers/verification.py): configurations of several
instances of one linkage verified at once are verified as each on its own instance, a
mirrored link included."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from baranov.enumerate import baranov_trusses
from baranov.scene import with_dimensions
from baranov.scene.instances import generic_integer_configuration, scene_of
from baranov.solvers.verification import joint_residuals


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2), st.integers(0, 2**32 - 1))
def test_configurations_of_many_instances_verify_as_each_alone(index, seed):
    """Instances of a random 7-link truss with one moving link's dimensions changed, and
    configurations near (and mirrored from) each instance's generating one: the residuals
    with ``instances``/``owner`` equal those against each instance, bit for bit."""
    rng = np.random.default_rng(seed)
    chain = baranov_trusses(7)[index]
    start = generic_integer_configuration(chain, rng)
    scene = scene_of(chain, start)
    moving = next(link for link in scene.links if link.name != scene.ground and len(link.joints) == 2)
    pair = next(iter(moving.squared_distances))
    instances = [with_dimensions(scene, {tuple(pair): moving.squared_distances[pair] + shift}) for shift in (0, 3, 7)]
    joints = sorted(start)
    base = np.array([complex(*map(float, start[j])) for j in joints])
    points = base + rng.normal(0, 1e-3, (9, len(joints))) + 1j * rng.normal(0, 1e-3, (9, len(joints)))
    points[4] = points[4].conjugate()  # every link mirrored
    owner = np.arange(9) % 3
    together = joint_residuals(scene, joints, points, instances, owner)
    for row in range(9):
        alone = joint_residuals(instances[owner[row]], joints, points[row:row + 1])
        assert together[row].tobytes() == alone.tobytes()
    assert together[4] >= 1.0
