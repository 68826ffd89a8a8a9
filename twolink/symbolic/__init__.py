"""Symbolic (sympy) derivations behind the numeric code.

Imported on demand (``from twolink import symbolic``) because sympy is slow to
import; the numeric package never needs it.
"""

from .kinematics import dh_matrix, planar_fk, planar_symbols

__all__ = ["dh_matrix", "planar_fk", "planar_symbols"]
