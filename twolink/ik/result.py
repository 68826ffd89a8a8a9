"""The result object shared by every inverse-kinematics solver."""

import math
from dataclasses import dataclass

import numpy as np

from ..kinematics import fk

__all__ = ["IKResult", "assemble_result", "assemble_pair_result"]


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
    within_limits : numpy.ndarray of bool, shape (...)
        Whether each ``q`` respects the arm's joint limits (all true for an
        arm without limits).  :func:`twolink.ik.newton` and the unconstrained
        :func:`twolink.ik.minimize` ignore the limits: check this field.

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
    within_limits: np.ndarray = None

    @property
    def all_success(self):
        """True when every target in the batch was solved."""
        return bool(np.all(self.success))


def assemble_result(arm, p, q_flat, iterations, threshold, method, solved_message, failure_detail):
    """Build an :class:`IKResult` with the residual recomputed by forward kinematics.

    Every solver ends here, so success is always judged the same way: the
    FK distance from ``fk(q)`` to the target, never the solver's own claim.

    Parameters
    ----------
    arm : TwoLinkArm
    p : numpy.ndarray, shape (..., 2)
        The targets as given (their leading shape is the result's).
    q_flat : numpy.ndarray, shape (n, 2)
        Solutions, one row per flattened target.
    iterations : numpy.ndarray of int, shape (n,)
    threshold : numpy.ndarray or float
        Success where the residual is at most this (metres).
    method : str
    solved_message : str
        The message when every target is solved.
    failure_detail : callable
        ``failure_detail(index, residual)`` describes the first failed
        target (flat index) for the message.
    """
    residual = np.hypot(*(fk(arm, q_flat) - p.reshape(-1, 2)).T)
    success = residual <= threshold
    failures = int(np.count_nonzero(~success))
    if failures:
        first = int(np.flatnonzero(~success)[0])
        message = f"failed for {failures} of {success.size} targets (first: flat index {first}, {failure_detail(first, residual[first])})"
    else:
        message = solved_message
    shape = p.shape[:-1]
    within = arm.within_limits(q_flat)
    if arm.has_limits and not np.all(within):
        message += f"; {int(np.count_nonzero(~within))} of {within.size} answers violate the joint limits (see within_limits)"
    return IKResult(
        q=q_flat.reshape(p.shape),
        success=success.reshape(shape),
        iterations=np.asarray(iterations).reshape(shape),
        residual=residual.reshape(shape),
        method=method,
        message=message,
        within_limits=within.reshape(shape),
    )


def assemble_pair_result(arm, target, q1, q2, iterations, threshold, method, solved_message, failure_detail):
    """:func:`assemble_result` for one target solved on floats: the same fields, types and message.

    The residual is recomputed from ``(q1, q2)`` by forward kinematics (the
    expressions of :func:`twolink.kinematics.fk`); ``success``,
    ``iterations``, ``residual`` and ``within_limits`` are 0-d arrays, ``q``
    has shape ``(2,)``, as for a target of shape ``(2,)`` on the vectorised
    path.  ``failure_detail(residual)`` describes a failure.
    """
    l1, l2 = arm.l1, arm.l2
    q12 = q1 + q2
    residual = math.hypot(
        l1 * math.cos(q1) + l2 * math.cos(q12) - target[0], l1 * math.sin(q1) + l2 * math.sin(q12) - target[1]
    )
    success = residual <= threshold
    message = solved_message if success else f"failed for 1 of 1 targets (first: flat index 0, {failure_detail(residual)})"
    within = bool(arm.within_limits((q1, q2))) if arm.has_limits else True
    if not within:
        message += "; 1 of 1 answers violate the joint limits (see within_limits)"
    # IKResult(...) field by field, without the frozen dataclass's seven object.__setattr__ calls
    # (IKResult has no __post_init__; the instance is the same)
    q = np.empty(2)
    q[0], q[1] = q1, q2
    result = object.__new__(IKResult)
    result.__dict__.update(
        q=q,
        success=np.array(success),
        iterations=np.array(iterations),
        residual=np.array(residual),
        method=method,
        message=message,
        within_limits=np.array(within),
    )
    return result
