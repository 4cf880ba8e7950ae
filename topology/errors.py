"""Exceptions raised for invalid kinematic-chain topologies."""

from __future__ import annotations


class TopologyError(ValueError):
    """A kinematic chain is malformed, or is not of the kind an operation needs.

    The message names the offending links or joints, e.g.
    ``links L2, L5: two joints between the same pair of links``.
    """
