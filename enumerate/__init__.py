"""Enumeration of Baranov trusses and of the chains derived from them."""

from .trusses import baranov_link_graphs, baranov_trusses, check_link_count, truss_sort_key

__all__ = ["baranov_link_graphs", "baranov_trusses", "check_link_count", "truss_sort_key"]
