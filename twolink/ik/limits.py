"""Inverse kinematics within the joint limits: both closed-form branches, moved into the limits.

A joint angle and the same angle plus a whole turn are one physical
configuration, but a limit interval holds at most one of them (unless it is
wider than a turn).  :func:`move_into_limits` picks, per angle, the turn that
lies in the limits when there is one; :func:`solutions_within_limits` applies
it to both closed-form branches at each point.  :mod:`twolink.workspace`
builds its reachability tests on these, and ``ik.closed_form(...,
elbow="auto")`` its choice of branch.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_finite_scalar, as_pairs, require_arm
from ..kinematics import REACH_RTOL, distance_outside_reach
from .analytic import closed_form
from .turns import LIMIT_TOL, free_q1_at_base, move_into_limits

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["solutions_within_limits"]


def solutions_within_limits(
    arm: TwoLinkArm, p: ArrayLike, tol: float = LIMIT_TOL
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Both closed-form IK branches at each point, moved into the limits where possible.

    Each joint angle is moved by a multiple of ``2 pi`` (the same physical
    configuration) into the limit interval when it can be
    (:func:`move_into_limits`); absolute limits are applied to the link
    angles ``(q1, q1 + q2)``.  Unlike :func:`twolink.ik.closed_form`, points
    out of reach are not refused: they are answered, and marked invalid.
    At the base of an arm with ``l1 == l2``, which the folded arm reaches
    with every ``q1``, both branches take the ``q1`` of
    :func:`free_q1_at_base` (one within the limits) when there is one, as
    ``ik.closed_form(..., elbow="auto")`` does.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Tip positions, metres.
    tol : float
        Slack in radians at each limit.

    Returns
    -------
    q_both : numpy.ndarray, shape (..., 2, 2)
        ``[..., 0, :]`` the elbow-down branch (``q2 >= 0`` before moving),
        ``[..., 1, :]`` elbow-up (the branch axis is the second last, next to
        the angles; ``ik.closed_form(..., elbow="both").q`` has it first).
        For points outside the reach annulus these are the angles of the
        nearest point of the annulus (never NaN): read ``valid`` before
        using them.
    valid : numpy.ndarray of bool, shape (..., 2)
        Whether each branch reaches the point within the limits.

    Examples
    --------
    >>> from twolink import arms
    >>> q_both, valid = solutions_within_limits(arms.ten, [10.0, 10.0])
    >>> np.degrees(q_both).round(6), valid
    (array([[  0.,  90.],
           [ 90., -90.]]), array([ True,  True]))
    >>> solutions_within_limits(arms.ten, [5.0, -15.0])[1]
    array([False, False])
    """
    require_arm(arm)
    points: NDArray[np.float64] = as_pairs(p, "p")
    tol = as_finite_scalar(tol, "tol (rad)", minimum=0.0)
    r_min, r_max = arm.reach
    distance = np.hypot(points[..., 0], points[..., 1])
    # inside the reach by the one reach test's tolerance (kinematics.require_within_reach)
    in_reach = distance_outside_reach(arm, points) <= REACH_RTOL * r_max
    # points outside the annulus are projected onto it, so that the closed form never raises
    safe = np.where(distance > 0.0, distance, 1.0)
    direction = np.where(
        distance[..., None] > 0.0, points / safe[..., None], np.array([1.0, 0.0])
    )
    p_projected = np.where(
        in_reach[..., None],
        points,
        direction * np.clip(distance, r_min, r_max)[..., None],
    )
    # a copy of its own (the result's arrays are read-only), C-contiguous
    q_both = np.moveaxis(closed_form(arm, p_projected, elbow="both").q, 0, -2).copy()
    valid = np.broadcast_to(in_reach[..., None], q_both.shape[:-1]).copy()
    if arm.has_limits:
        at_base, free_q1 = free_q1_at_base(arm, points)
        if free_q1 is not None:
            q_both[at_base & in_reach, :, 0] = free_q1
        q_both, inside = move_into_limits(arm, q_both, tol)
        valid &= inside
    return q_both, valid
