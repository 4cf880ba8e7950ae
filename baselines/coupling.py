"""The coupling degree a baseline reports beside its modes."""

from __future__ import annotations

from baranov.scene import Scene


def chain_coupling_degree(scene: Scene) -> int:
    """The coupling degree of ``scene``'s chain: the number of parameters of its best
    plan (with slider joints, its best slider plan; thesis §2.6), which a baseline reports
    though it solves without a plan (it had reported 0 for every chain).

    >>> from baranov.scene import load_scene
    >>> chain_coupling_degree(load_scene("examples/7-B1.json"))
    1
    """
    from baranov.planner import best_plan
    from baranov.solvers.coincidence import solvable_plan

    try:
        return solvable_plan(scene).number_of_parameters
    except ValueError:  # no plan is defined for these dimensions: the chain's best plan
        return best_plan(scene.chain).number_of_parameters
