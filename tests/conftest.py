"""Shared fixtures: the thesis's small trusses with the thesis's joint numbering."""

import pytest

from baranov.topology import chain_from_link_graph

#: The pentad of thesis §2.7 (Fig. 2.5 right): ternary links 0 = {P1,P2,P3} and
#: 1 = {P4,P5,P6}; binary links 2 = P1–P4, 3 = P2–P5, 4 = P3–P6.
PENTAD_EDGES = [(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]


@pytest.fixture
def pentad():
    return chain_from_link_graph(PENTAD_EDGES)


@pytest.fixture
def triad():
    return chain_from_link_graph([(0, 1), (1, 2), (0, 2)])


# Property tests draw the same examples on every run (CI must not fail on an example no
# one has seen); random exploration for new misses is bench/sweep_numeric.py's job.
from hypothesis import settings  # noqa: E402

settings.register_profile("baranov", derandomize=True)
settings.load_profile("baranov")
