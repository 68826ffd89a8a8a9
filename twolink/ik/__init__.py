"""Inverse kinematics of the planar 2R arm, several ways.

- :func:`closed_form`: cosine rule and atan2, both elbow branches, vectorised.
- :func:`newton`: Newton's method on the two FK equations with step control.
- :func:`minimize`: scipy optimisation, unconstrained least squares (the
  MATLAB ``fminunc`` analogue) or a constrained feasibility problem (``fmincon``).
- :func:`brute_force`: the best point of a joint-space grid.

The iterative solvers return an :class:`IKResult`; check ``success``.
"""

from .grid_search import brute_force
from .analytic import ELBOW_BRANCHES, closed_form
from .iterative import newton
from .optimize import minimize
from .result import IKResult
from .targets import REACH_RTOL, check_reachable

__all__ = [
    "closed_form",
    "newton",
    "minimize",
    "brute_force",
    "IKResult",
    "ELBOW_BRANCHES",
    "REACH_RTOL",
    "check_reachable",
]
