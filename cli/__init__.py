"""The ``baranov`` command line: catalog regeneration (and, later, show/solve)."""
