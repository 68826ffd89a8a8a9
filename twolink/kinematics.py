"""Forward kinematics and the analytic Jacobian of the planar 2R arm.

Functions here take the arm (anything with ``l1`` and ``l2`` attributes) and
joint angles in the DH / relative convention: ``q1`` is link 1 from the x-axis,
``q2`` is link 2 relative to link 1.  All are vectorised over leading axes.
:class:`twolink.TwoLinkArm` exposes them as methods.

One configuration (a pair of floats, shape ``(2,)``) takes a lean path on
Python floats and the :mod:`math` module (what a loop, a widget or a
controller calls thousands of times); it computes the same expressions, in
the same order, as the vectorised path (the tests compare the two to 1e-12).
"""

import math

import numpy as np

from ._validate import as_pairs, broadcast_shape, pair_floats, require_arm

__all__ = ["fk", "joint_positions", "jacobian", "joint_torques", "reach"]


def fk(arm, q):
    """Tip position ``x = l1 c1 + l2 c12``, ``y = l1 s1 + l2 s12``.

    Parameters
    ----------
    arm : TwoLinkArm
        The arm (only ``l1`` and ``l2`` are used).
    q : array_like, shape (..., 2)
        Joint angles in radians (relative convention).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Tip position ``(x, y)`` in metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> TwoLinkArm(2.0, 1.0).fk([0.0, np.pi / 2]).round(12)
    array([2., 1.])
    """
    pair = pair_floats(q)
    if pair is not None:
        q1, q2 = pair
        q12 = q1 + q2
        l1, l2 = _lengths(arm)
        p_tip = np.empty(2)  # then two item assignments: faster than np.array of a list
        p_tip[0] = l1 * math.cos(q1) + l2 * math.cos(q12)
        p_tip[1] = l1 * math.sin(q1) + l2 * math.sin(q12)
        return p_tip
    q = as_pairs(q, "q")
    l1, l2 = _lengths(arm)
    q1 = q[..., 0]
    q12 = q1 + q[..., 1]
    p_tip = np.empty(q.shape)
    p_tip[..., 0] = l1 * np.cos(q1)
    p_tip[..., 0] += l2 * np.cos(q12)
    p_tip[..., 1] = l1 * np.sin(q1)
    p_tip[..., 1] += l2 * np.sin(q12)
    return p_tip


def joint_positions(arm, q):
    """Positions of the base, the elbow and the tip.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 3, 2)
        Rows are base ``(0, 0)``, elbow and tip, each ``(x, y)`` in metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> TwoLinkArm(1.0, 1.0).joint_positions([np.pi / 2, -np.pi / 2]).round(12)
    array([[0., 0.],
           [0., 1.],
           [1., 1.]])
    """
    q = as_pairs(q, "q")
    _lengths(arm)
    points = np.zeros(q.shape[:-1] + (3, 2))
    q1 = q[..., 0]
    q12 = q1 + q[..., 1]
    points[..., 1, 0] = arm.l1 * np.cos(q1)
    points[..., 1, 1] = arm.l1 * np.sin(q1)
    points[..., 2, 0] = points[..., 1, 0] + arm.l2 * np.cos(q12)
    points[..., 2, 1] = points[..., 1, 1] + arm.l2 * np.sin(q12)
    return points


def jacobian(arm, q):
    """Analytic Jacobian ``d(x, y) / d(q1, q2)``.

    ``J = [[-l1 s1 - l2 s12, -l2 s12], [l1 c1 + l2 c12, l2 c12]]`` and
    ``det J = l1 l2 sin(q2)``: singular when the arm is stretched or folded.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2)
        ``J[..., i, j] = d p_i / d q_j`` in metres per radian.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> J = TwoLinkArm(1.0, 1.0).jacobian([0.0, np.pi / 2])
    >>> J.round(12)
    array([[-1., -1.],
           [ 1.,  0.]])
    >>> float(np.linalg.det(J))
    1.0
    """
    pair = pair_floats(q)
    if pair is not None:
        q1, q2 = pair
        q12 = q1 + q2
        l1, l2 = _lengths(arm)
        c12 = l2 * math.cos(q12)
        s12 = l2 * math.sin(q12)
        J = np.array([-l1 * math.sin(q1) - s12, -s12, l1 * math.cos(q1) + c12, c12])
        J.shape = (2, 2)
        return J
    q = as_pairs(q, "q")
    _lengths(arm)
    q1 = q[..., 0]
    q12 = q1 + q[..., 1]
    c12 = arm.l2 * np.cos(q12)
    s12 = arm.l2 * np.sin(q12)
    J = np.empty(q.shape[:-1] + (2, 2))
    J[..., 0, 0] = -arm.l1 * np.sin(q1)
    J[..., 0, 0] -= s12
    J[..., 0, 1] = -s12
    J[..., 1, 0] = arm.l1 * np.cos(q1)
    J[..., 1, 0] += c12
    J[..., 1, 1] = c12
    return J


def joint_torques(arm, q, force):
    """Static joint torques ``tau = J(q)^T F`` that hold a tip force.

    ``force`` is the force the tip exerts on the environment (for example on a
    wall), in newtons.  The motors must supply ``tau`` to hold it; the
    environment pushes back on the tip with ``-F``.  Gravity is not included.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    force : array_like, shape (..., 2)
        Force ``(Fx, Fy)`` exerted by the tip, in newtons.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Joint torques in newton-metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> TwoLinkArm(2.0, 2.0).joint_torques([0.0, 0.0], [0.0, 10.0]).round(12)
    array([40., 20.])
    """
    q = as_pairs(q, "q")
    force = as_pairs(force, "force")
    broadcast_shape(q=q, force=force)
    J = jacobian(arm, q)
    return np.einsum("...ji,...j->...i", J, force)


def reach(arm):
    """Reach interval ``(r_min, r_max) = (|l1 - l2|, l1 + l2)`` in metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> [round(r, 12) for r in reach(TwoLinkArm(0.1, 0.115))]
    [0.015, 0.215]
    """
    l1, l2 = _lengths(arm)
    return (abs(l1 - l2), l1 + l2)


def _lengths(arm):
    """``(l1, l2)``, or an error naming ``arm`` when it is not an arm (free when it is one)."""
    try:
        return arm.l1, arm.l2
    except AttributeError:
        require_arm(arm)
        raise
