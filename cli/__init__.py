"""The ``baranov`` command line: ``baranov catalog`` (regenerate the catalog),
``baranov show`` (a truss, its plan and closure conditions) and ``baranov solve`` (every
assembly mode of a linkage); :func:`main` is the entry point."""

from .main import main

__all__ = ["main"]
