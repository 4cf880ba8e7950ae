"""Data and helpers shared by several test modules (a test module imports this one, never
another test module)."""

from baranov.enumerate import baranov_trusses
from baranov.planner import coupling_degree
from baranov.solvers.verification import same_mode

#: Published real roots (thesis §3.3.x.3 and §4.2.1) and the distance they are given in.
SEVEN_LINK_EXAMPLES = {
    "7-B1": (("P2", "P3"), [39.8353, 41.6616, 42.6537, 78.9181, 81.8425, 106.0, 121.9444, 122.6125]),
    "7-B2": (("P4", "P8"), [1.1161, 1.2002, 7.3517, 10.418, 17.0, 27.5995, 52.9281, 53.7863, 56.0905, 61.5796]),
    "7-B3": (("P1", "P4"), [5.2357, 6.732, 9.8004, 16.9536, 39.1049, 45.3566, 48.4498, 61.0]),
    "7-B3-section-4.2.1": (("P1", "P6"), [88.57, 90.8322]),
}


WATT_BARANOV = {  # thesis §3.6.2.1 and §3.6.2.2, roots s1,3
    "11-watt-baranov": (("P1", "P3"), [30.6486, 39.0249, 47.1860, 48.6406, 69.9863, 77.3161, 90.1506, 130.0, 132.2178,
                        134.2206, 134.9836, 140.6611, 142.9286, 143.7773, 148.1286, 151.6614]),
    "13-watt-baranov": (("P1", "P3"), [14.1226, 14.1508, 14.1846, 14.2289, 14.4123, 14.4852, 14.7185, 15.0578, 15.1158,
                        15.6861, 15.8268, 15.8328, 16.0193, 17.0205, 17.8216, 18.2916, 19.0286, 19.1581,
                        20.2651, 22.1260, 22.5020, 24.4759, 25.1965, 28.7237, 31.0109, 31.5115, 34.0693,
                        37.7304, 38.0758, 44.4875, 48.4166, 51.7518, 55.1186, 55.5625, 59.3880, 59.6226,
                        66.0245, 68.2321, 70.9035, 71.8207, 73.0411, 73.2584, 76.8581, 85.1396, 89.9046,
                        92.3656, 93.7643, 93.9066, 100.1256, 101.6541, 110.7250, 119.8610, 121.8404,
                        122.2387, 129.0033, 130.0000, 130.1666, 134.9545, 135.4180, 137.5075, 137.9792,
                        139.1001, 141.3430, 141.3607, 142.7141, 144.1643, 144.3299, 144.3842, 144.7027,
                        145.9600, 146.3519, 148.9932, 149.3873, 149.8649, 149.8708, 149.8813]),
}


PUBLISHED_EXAMPLES = {**SEVEN_LINK_EXAMPLES, **WATT_BARANOV}

#: Every truss to 9 links that a one-parameter plan solves.
SOLVABLE = [t for links in (3, 5, 7, 9) for t in baranov_trusses(links) if coupling_degree(t) <= 1]


def same_modes(scene, first, second) -> bool:
    """Whether two lists of modes are the same modes (:func:`same_mode`), in any order."""
    return len(first) == len(second) and all(any(same_mode(m, n, scene) for n in second) for m in first)
