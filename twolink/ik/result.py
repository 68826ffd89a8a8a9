"""The result object shared by every inverse-kinematics solver."""

from dataclasses import dataclass

import numpy as np

__all__ = ["IKResult"]


@dataclass(frozen=True)
class IKResult:
    """What an IK solver found, and whether to trust it.

    Modelled on the Robotics Toolbox's ``IKSolution``: always check
    ``success`` before using ``q``.  For a batch of targets every field has the
    batch's leading shape.

    Attributes
    ----------
    q : numpy.ndarray, shape (..., 2)
        Joint angles in radians (the best found, even when ``success`` is false).
    success : numpy.ndarray of bool, shape (...)
        True where the solver met its tolerance.
    iterations : numpy.ndarray of int, shape (...)
        Iterations (or function evaluations, or grid points) spent per target.
    residual : numpy.ndarray, shape (...)
        ``|fk(q) - p|`` in metres, recomputed from ``q`` by the caller-facing
        wrapper, never taken from the solver's own bookkeeping.
    method : str
        Which solver produced this result.
    message : str
        A sentence on the outcome: why it failed, where.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.newton(arms.ten, [10.0, 10.0], q0=[0.5, 1.0])
    >>> bool(result.success), result.method
    (True, 'newton')
    >>> bool(result.residual < 1e-9)
    True
    """

    q: np.ndarray
    success: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    method: str
    message: str

    @property
    def all_success(self):
        """True when every target in the batch was solved."""
        return bool(np.all(self.success))
