"""Symbolic (sympy) derivations behind the numeric code.

Imported on demand (``from twolink import symbolic``) because sympy is slow to
import; the numeric package never needs it.
"""

from .dynamics import (
    EquationsOfMotion,
    NumericDynamics,
    christoffel_coriolis,
    dynamics_symbols,
    equations_of_motion,
    lambdify_dynamics,
    time_derivative,
)
from .kinematics import dh_matrix, planar_fk, planar_symbols

__all__ = [
    "dh_matrix",
    "planar_fk",
    "planar_symbols",
    "dynamics_symbols",
    "equations_of_motion",
    "EquationsOfMotion",
    "christoffel_coriolis",
    "time_derivative",
    "lambdify_dynamics",
    "NumericDynamics",
]
