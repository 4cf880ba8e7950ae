"""Results of a solver: assembly modes with their configurations."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


class SolverError(ValueError):
    """The scene is valid but this method cannot solve it (the message says why)."""


@dataclass(frozen=True)
class AssemblyMode:
    """One assembly mode of a linkage.

    Attributes:
        parameters: value of each plan parameter, keyed like ``"s1,6"``.
        signs: the free-sign branch (±1 per free-sign triangle of the plan).
        joints: world coordinates of every joint.
        max_residual: largest relative error over all link dimensions (and 1.0 for a
            rigid link found mirrored, which is never reported as a mode).
    """

    parameters: dict[str, float]
    signs: tuple[int, ...]
    joints: dict[str, tuple[float, float]]
    max_residual: float


@dataclass(frozen=True)
class Solution:
    """All assembly modes of a scene found by one method."""

    method: str
    coupling_degree: int
    parameters: tuple[str, ...]
    free_sign_triangles: tuple[tuple[str, str, str], ...]
    assembly_modes: tuple[AssemblyMode, ...]
    characteristic_polynomial: Any = None  # a CharacteristicPolynomial (exact method)

    def to_dict(self) -> dict:
        """The JSON form printed by ``baranov solve --json``."""
        result = {
            "method": self.method,
            "coupling_degree": self.coupling_degree,
            "parameters": list(self.parameters),
            "assembly_modes": [
                {"parameters": m.parameters, "signs": list(m.signs),
                 "joints": {k: list(v) for k, v in m.joints.items()}, "max_residual": m.max_residual}
                for m in self.assembly_modes
            ],
        }
        if self.characteristic_polynomial is not None:
            result["characteristic_polynomial"] = self.characteristic_polynomial.to_dict()
        return result
