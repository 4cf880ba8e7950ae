"""Bilateration matrices as complex numbers.

A perpendicular matrix [[a, -b], [b, a]] acts on plane vectors as multiplication by the
complex number a + ib acts on x + iy; such matrices add and multiply like complex numbers
and det = |a + ib|² (thesis §2.4). A bilateration matrix (thesis eq. 2.7)

    Z_{i,j,k} = 1/(2 s_{i,j}) [[s_{i,j} + s_{i,k} - s_{j,k}, -4 A_{i,j,k}],
                              [4 A_{i,j,k}, s_{i,j} + s_{i,k} - s_{j,k}]]

is therefore the complex number (s_{i,j} + s_{i,k} - s_{j,k} + 4i A_{i,j,k}) / (2 s_{i,j}),
where A_{i,j,k} = ±¼ √((s_{i,j} + s_{i,k} + s_{j,k})² - 2(s_{i,j}² + s_{i,k}² + s_{j,k}²))
is the oriented area of △P_i P_j P_k, positive when P_k lies left of p_{i,j}.
"""

from __future__ import annotations

import numpy as np

#: A radicand above −this times the squared largest side is rounding noise around 0 (a
#: flat triangle), not a triangle that does not exist: where a radicand touches 0 (a
#: double zero, joints in line at a mode), rounding makes it a few ulps negative over a
#: stretch ~1e-8 wide, and Brent's bracket hit NaN there (issue 25's 7/N3 instance at
#: s1,9 = 13).
RADICAND_NOISE = 1e-13


def oriented_area(s_ij, s_ik, s_jk, sign):
    """A_{i,j,k} from the three squared distances and the orientation sign (±1), thesis
    eq. (2.7). NaN where the radicand is negative (the triangle does not exist). Sign 0
    takes the triangle as flat (area 0) whatever the radicand: a candidate at a fold of
    the domain, where rounding leaves the radicand a few ulps below 0 (solvers/numeric.py,
    ``_roots_at_folds``). Vectorised over numpy arrays.

    >>> float(oriented_area(25.0, 9.0, 16.0, 1))  # 3-4-5 right triangle: area 6
    6.0
    """
    s_ij, s_ik, s_jk = (np.asarray(x, dtype=float) for x in (s_ij, s_ik, s_jk))
    radicand = (s_ij + s_ik + s_jk) ** 2 - 2 * (s_ij**2 + s_ik**2 + s_jk**2)
    noise = -RADICAND_NOISE * np.maximum(np.maximum(s_ij, s_ik), s_jk) ** 2
    with np.errstate(invalid="ignore"):
        area = sign * np.sqrt(np.where(radicand >= noise, np.maximum(radicand, 0.0), np.nan)) / 4
    flat = np.asarray(sign) == 0
    if not flat.any():  # the usual case: no flat triangle asked for
        return area
    return np.where(flat, 0.0, area)


def bilateration_matrix(s_ij, s_ik, s_jk, sign):
    """Z_{i,j,k} as a complex number (array), so that p_{i,k} = Z_{i,j,k} p_{i,j}.

    >>> z = bilateration_matrix(25.0, 9.0, 16.0, 1)   # P_i=(0,0), P_j=(5,0), P_k=(9/5, 12/5)
    >>> complex(np.round(z * 5, 12))                   # p_{i,k} = Z p_{i,j}
    (1.8+2.4j)
    """
    area = oriented_area(s_ij, s_ik, s_jk, sign)
    s_ij, s_ik, s_jk = (np.asarray(x, dtype=float) for x in (s_ij, s_ik, s_jk))
    with np.errstate(invalid="ignore", divide="ignore"):  # s_ij = 0: no bilateration (NaN)
        return (s_ij + s_ik - s_jk + 4j * area) / (2 * s_ij)


def perpendicular_matrix(z) -> np.ndarray:
    """The 2×2 perpendicular matrix [[a, -b], [b, a]] of the complex number a + ib.

    >>> perpendicular_matrix(1 + 2j).tolist()
    [[1.0, -2.0], [2.0, 1.0]]
    """
    z = complex(z)
    return np.array([[z.real, -z.imag], [z.imag, z.real]])
