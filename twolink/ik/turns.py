"""Joint angles moved by whole turns into the joint limits (the layer below the closed form's ``elbow="auto"``).

:func:`move_into_limits` and :func:`free_q1_at_base` need no inverse
kinematics, so both :mod:`twolink.ik.analytic` and :mod:`twolink.ik.limits`
import them from here; :mod:`twolink.ik.limits` re-exports them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_finite_scalar, as_pairs, require_arm

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["LIMIT_TOL", "move_into_limits"]

#: Slack (radians) with which a configuration on a joint limit counts as inside.
#: At a stretched or folded pose the tip pins the angles down only to about
#: the square root of machine epsilon (1.5e-8 rad), so a point traced by a
#: configuration on a limit needs this much slack to be recognised.
LIMIT_TOL = 1e-7

#: Within this distance of the base (relative to the reach ``l1 + l2``) the
#: direction of a point is round-off: an arm with ``l1 == l2`` folded
#: (``q2 = pi``) reaches its base with every ``q1``, and fk of a folded
#: configuration lands a few ``eps`` from the base in a direction that says
#: nothing about ``q1``.
BASE_ROUND_OFF = 64 * float(np.finfo(float).eps)

_TWO_PI = 2.0 * np.pi


def _turns_into_range(
    angles: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    tol: float,
) -> NDArray[np.float64]:
    """Whole turns (radians, a multiple of 2 pi) that move each angle into ``[low - tol, high + tol]``.

    The turn to the angle's representative in ``[low - tol, low - tol + 2 pi)``
    where that lies inside and the angle does not; 0 elsewhere (an angle
    already inside is returned unchanged, not rounded through a modulo).
    """
    inside_now = (angles >= low - tol) & (angles <= high + tol)
    representative = np.mod(angles - low + tol, _TWO_PI)
    representative += low - tol
    inside_moved = representative <= high + tol
    turns = _TWO_PI * np.round((representative - angles) / _TWO_PI)
    turns[inside_now | ~inside_moved] = 0.0
    return turns


def move_into_limits(
    arm: TwoLinkArm, q: ArrayLike, tol: float = LIMIT_TOL
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Configurations moved by whole turns into the arm's joint limits, where a turn does that.

    Each joint angle (each link angle ``(q1, q1 + q2)`` for absolute limits)
    already within its limit interval is left exactly as it is; any other is
    moved by the multiple of ``2 pi`` that brings it in, if one does (else
    it too is left as it is).  The tip does not move.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Relative joint angles, radians.
    tol : float
        Slack in radians at each limit.

    Returns
    -------
    moved : numpy.ndarray, shape (..., 2)
        The configurations, moved where that helps (relative angles).
    inside : numpy.ndarray of bool, shape (...)
        Whether each moved configuration is within the limits (with ``tol``);
        all true for an arm without limits.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0, q_min=(0.0, 0.0), q_max=(1.5 * np.pi, 0.5 * np.pi))
    >>> moved, inside = move_into_limits(arm, [[-0.5 * np.pi, 0.25], [0.5, -1.0]])
    >>> (moved / np.pi).round(6), inside
    (array([[ 1.5     ,  0.079577],
           [ 0.159155, -0.31831 ]]), array([ True, False]))
    >>> move_into_limits(arm, [0.5, 0.25])[0] == [0.5, 0.25]  # already inside: exactly as given
    array([ True,  True])
    """
    require_arm(arm)
    angles: NDArray[np.float64] = as_pairs(q, "q")
    tol = as_finite_scalar(tol, "tol (rad)", minimum=0.0)
    if arm.q_min is None or arm.q_max is None:
        return angles.copy(), np.ones(angles.shape[:-1], dtype=np.bool_)
    low, high = np.asarray(arm.q_min, dtype=float), np.asarray(arm.q_max, dtype=float)
    if arm.limit_convention == "relative":
        turns = _turns_into_range(angles, low, high, tol)
    else:  # turn link 1 by t1 and link 2 by t2: q1 by t1, q2 = (q1 + q2) - q1 by t2 - t1
        link_angles = angles.copy()
        link_angles[..., 1] += angles[..., 0]
        turns = _turns_into_range(link_angles, low, high, tol)
        turns[..., 1] -= turns[..., 0]
    moved = angles + turns
    # inside by the arm's own test of the moved angles: a representative a hair
    # inside a limit can be an angle that rounds to a hair outside it
    return moved, np.asarray(arm.within_limits(moved, tol=tol), dtype=np.bool_)


def free_q1_at_base(
    arm: TwoLinkArm, points: NDArray[np.float64]
) -> tuple[NDArray[np.bool_], float | None]:
    """Where ``points`` are the base of an arm with ``l1 == l2``, and a ``q1`` with which the folded arm is within limits.

    At the base (within ``BASE_ROUND_OFF * (l1 + l2)``, for an arm whose
    ``|l1 - l2|`` is that small too) the folded arm ``q2 = pi`` reaches the
    point with every ``q1``, while the closed form picks the ``q1`` of the
    round-off direction of the point.  The one choice of ``q1`` there, made
    for :func:`solutions_within_limits` and ``ik.closed_form(...,
    elbow="auto")`` alike: the lowest ``q1`` within the limits whose folded
    configuration is within them (``None`` when there is none, or the arm
    has no limits).

    Parameters
    ----------
    arm : TwoLinkArm
    points : numpy.ndarray, shape (..., 2)
        Tip positions, metres (checked by the caller).

    Returns
    -------
    at_base : numpy.ndarray of bool, shape (...)
        Where the point is the base of an equal-link arm (all false otherwise).
    q1 : float or None
        A ``q1`` for those points, or ``None``.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0, q_min=(1.0, np.pi), q_max=(2.0, np.pi + 1.0))
    >>> free_q1_at_base(arm, np.array([[0.0, 1e-16], [0.5, 0.0]]))
    (array([ True, False]), 1.0)
    >>> free_q1_at_base(TwoLinkArm(1.0, 1.0, q_min=(0.0, 0.0), q_max=(1.0, 3.0)), np.zeros(2))
    (array(True), None)
    """
    r_min, r_max = arm.reach
    if r_min > BASE_ROUND_OFF * r_max:  # the base is out of reach
        return np.zeros(points.shape[:-1], dtype=np.bool_), None
    at_base = np.asarray(
        np.hypot(points[..., 0], points[..., 1]) <= BASE_ROUND_OFF * r_max
    )
    if arm.q_min is None or arm.q_max is None:
        return at_base, None
    (low_1, low_2), (high_1, high_2) = arm.q_min, arm.q_max
    if arm.limit_convention == "relative":
        q1 = low_1  # q2 = pi is within its limits by some whole turn, or no q1 will do
    else:  # link angles (q1, q1 + pi): q1 in [low_1, high_1] and in [low_2 - pi, high_2 - pi] + 2 pi k
        turn = np.ceil((low_1 - (high_2 - np.pi)) / _TWO_PI)
        q1 = max(low_1, float(low_2 - np.pi + _TWO_PI * turn))
    folded_inside = q1 <= high_1 and bool(move_into_limits(arm, [q1, np.pi])[1])
    return at_base, q1 if folded_inside else None
