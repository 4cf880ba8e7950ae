"""Results of a solver: assembly modes with their configurations."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from typing import Any

from baranov.planner import parameter_name
from baranov.topology import natural_sort_key


class SolverError(ValueError):
    """The scene is valid but this method cannot solve it (the message says why)."""


class MovableLinkageError(SolverError):
    """With these dimensions the linkage moves: its configurations form a continuum, not
    isolated assembly modes (a closure condition vanishing along an interval, or msolve's
    positive-dimensional answer)."""


def signs_text(signs) -> str:
    """A free-sign branch as written in tables: ``(1, -1, 0)`` → ``"+-0"`` (0: flat)."""
    return "".join("+" if s > 0 else "-" if s < 0 else "0" for s in signs)


@dataclass(frozen=True)
class AssemblyMode:
    """One assembly mode of a linkage.

    Attributes
    ----------
    parameters
        value of each plan parameter, keyed like ``"s1,6"``.
    signs
        the free-sign branch (±1 per free-sign triangle of the plan).
    joints
        world coordinates of every joint.
    max_residual
        largest relative error over all link dimensions (and 1.0 for a
        rigid link found mirrored, which is never reported as a mode).
    """

    parameters: dict[str, float]
    signs: tuple[int, ...]
    joints: dict[str, tuple[float, float]]
    max_residual: float


@dataclass(frozen=True)
class Certificate:
    """What an exact solve proves about its list of assembly modes (docs/exact.md, "What
    the exact backend guarantees").

    Attributes
    ----------
    complete
        every real assembly mode is in the list: each step from the closure
        conditions to the configurations was exact or checked at run time on this
        instance (``gaps`` is empty).
    probabilistic
        a step whose result is correct with overwhelming probability but
        not proved (coupling degree 2: the polynomial lifted from its images modulo
        random primes), or None.
    gaps
        what could not be certified on this instance, one sentence each (e.g. a
        real root where the plan is undefined and no other plan could decide).
    """

    complete: bool
    probabilistic: str | None = None
    gaps: tuple[str, ...] = ()
    #: how completeness was proven, where the method says (the numeric backend: the
    #: interval branch-and-prune's domain and boxes)
    proof: str | None = None

    def summary(self) -> str:
        """One line for the command line."""
        if not self.complete:
            return "NOT certified complete: " + "; ".join(self.gaps)
        if self.probabilistic:
            return f"certified complete (one Monte Carlo step: {self.probabilistic})"
        return f"certified complete ({self.proof})" if self.proof else "certified complete"

    def to_dict(self) -> dict:
        """The JSON form, in ``baranov solve --json``."""
        result = {"complete": self.complete, "probabilistic": self.probabilistic, "gaps": list(self.gaps)}
        if self.proof:
            result["proof"] = self.proof
        return result


@dataclass(frozen=True)
class Solution:
    """All assembly modes of a scene found by one method. A backend with more to say
    returns a subclass (the exact one: :class:`ExactSolution`)."""

    method: str
    coupling_degree: int
    parameters: tuple[str, ...]
    free_sign_triangles: tuple[tuple[str, str, str], ...]
    assembly_modes: tuple[AssemblyMode, ...]
    #: what the method could not resolve, one sentence each (numeric: e.g. a stretch where
    #: the closure condition is flat to rounding, reported as one mode)
    undecided: tuple[str, ...] = ()
    #: what is proven about the list of modes; None where the method proves nothing
    certificate: Certificate | None = None

    @classmethod
    def of_plan(cls, method: str, scene, plan, modes: tuple[AssemblyMode, ...], **extra) -> Solution:
        """The solution of ``method`` in the terms of ``plan`` (its coupling degree,
        parameter names — t for a pair with one of ``scene``'s slider joints, as the
        modes' parameters are named — and free-sign triangles), with the fields only
        ``cls`` has in ``extra``."""
        sliders = [slider.joint for slider in scene.sliders]
        names = tuple(parameter_name(pair, sliders) for pair in plan.parameters)
        return cls(method, plan.number_of_parameters, names, plan.free_sign_triangles, modes, **extra)

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
        if self.undecided:
            result["undecided"] = list(self.undecided)
        if self.certificate is not None:
            result["certificate"] = self.certificate.to_dict()
        return result

    def to_csv(self) -> str:
        """The CSV form printed by ``baranov solve --format csv``: mode, parameter values,
        signs, residual, then x and y of every joint (full precision)."""
        modes = self.assembly_modes
        joint_names = sorted(modes[0].joints, key=natural_sort_key) if modes else []
        stream = io.StringIO()
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(["mode", *self.parameters, "signs", "max_residual",
                         *(f"{name}_{axis}" for name in joint_names for axis in "xy")])
        for number, mode in enumerate(modes, 1):
            writer.writerow([number, *(repr(v) for v in mode.parameters.values()), signs_text(mode.signs),
                             repr(mode.max_residual), *(repr(c) for name in joint_names for c in mode.joints[name])])
        return stream.getvalue()


@dataclass(frozen=True)
class ExactSolution(Solution):
    """The exact backend's result: the modes, the characteristic polynomial they come from
    (a :class:`~baranov.solvers.exact.characteristic.CharacteristicPolynomial`; None for
    coupling degree 0) and what is certified about them."""

    characteristic_polynomial: Any = None
    certificate: Certificate = Certificate(False, None, ("no certificate",))

    def to_dict(self) -> dict:
        result = super().to_dict()
        if self.characteristic_polynomial is not None:
            result["characteristic_polynomial"] = self.characteristic_polynomial.to_dict()
        return result
