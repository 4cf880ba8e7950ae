"""The exact backend (thesis §3.2–3.5): the characteristic polynomial of a plan over the
radical tower (:mod:`.characteristic`; coupling degree 2 by resultants modulo primes and
lifting: :mod:`.resultant`, :mod:`.modular`, :mod:`.coupling_two`, :mod:`.fibers`), its
real roots isolated in certified enclosures, and every assembly mode at them with what
is certified about the list (:mod:`.backend`, docs/exact.md)."""

from .backend import solve_exact
from .characteristic import CharacteristicPolynomial, ExactMethodError, characteristic_polynomial

__all__ = ["CharacteristicPolynomial", "ExactMethodError", "characteristic_polynomial", "solve_exact"]
