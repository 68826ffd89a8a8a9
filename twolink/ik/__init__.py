"""Inverse kinematics of the planar 2R arm, several ways.

- :func:`closed_form`: cosine rule and atan2, both elbow branches, vectorised.
- :func:`newton`: Newton's method on the two FK equations with step control.
- :func:`minimize`: scipy optimisation, unconstrained least squares (the
  MATLAB ``fminunc`` analogue) or a constrained feasibility problem (``fmincon``).
- :func:`brute_force`: the best point of a joint-space grid.
- :func:`solutions_within_limits`: both closed-form branches, moved into the
  joint limits, and which of them reach each point within the limits.

Every solver returns an :class:`IKResult`, a frozen dataclass built when the
solver ends: the angles ``q``, and ``success``, ``residual`` (recomputed by
forward kinematics), ``within_limits``, ``iterations`` and a ``message``
(Python numbers for one target, arrays for a batch); check ``success``
before using ``q``.
"""

from .analytic import closed_form
from .grid_search import brute_force
from .iterative import newton
from .limits import LIMIT_TOL, solutions_within_limits
from .optimize import minimize
from .result import IKResult

__all__ = [
    "closed_form",
    "newton",
    "minimize",
    "brute_force",
    "IKResult",
    "solutions_within_limits",
    "LIMIT_TOL",
]
