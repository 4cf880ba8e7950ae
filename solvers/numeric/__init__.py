"""The numeric backend (thesis §3.2–3.3): every root of the closure conditions on every
free-sign branch in floating point — one parameter (:mod:`.one_parameter`), two
(:mod:`.two_parameter`) — polished on the link constraints (:mod:`.polish`) and
verified; the driver is :mod:`.backend` (docs/numeric.md)."""

from .backend import solve_numeric

__all__ = ["solve_numeric"]
