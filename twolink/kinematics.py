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

from ._validate import arm_lengths, as_finite_scalar, as_pairs, broadcast_shape, pair_floats, require_arm
from .errors import SingularityError, UnreachableError

__all__ = [
    "fk",
    "joint_positions",
    "jacobian",
    "joint_torques",
    "reach",
    "REACH_RTOL",
    "distance_outside_reach",
    "require_within_reach",
    "SINGULARITY_TOL",
    "require_nonsingular",
]

#: Points up to ``REACH_RTOL * (l1 + l2)`` outside the reach annulus count as
#: inside it (round-off at full stretch or full fold); anything further is
#: out of reach (:func:`require_within_reach`).
REACH_RTOL = 1e-10

#: Configurations with ``|sin q2|`` at most this are treated as singular
#: (stretched or folded) by :func:`require_nonsingular`.
SINGULARITY_TOL = 1e-6


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
        l1, l2 = arm_lengths(arm)
        p_tip = np.empty(2)  # then two item assignments: faster than np.array of a list
        p_tip[0] = l1 * math.cos(q1) + l2 * math.cos(q12)
        p_tip[1] = l1 * math.sin(q1) + l2 * math.sin(q12)
        return p_tip
    q = as_pairs(q, "q")
    l1, l2 = arm_lengths(arm)
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
    arm_lengths(arm)
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
        l1, l2 = arm_lengths(arm)
        c12 = l2 * math.cos(q12)
        s12 = l2 * math.sin(q12)
        J = np.array([-l1 * math.sin(q1) - s12, -s12, l1 * math.cos(q1) + c12, c12])
        J.shape = (2, 2)
        return J
    q = as_pairs(q, "q")
    arm_lengths(arm)
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
    l1, l2 = arm_lengths(arm)
    return (abs(l1 - l2), l1 + l2)


def distance_outside_reach(arm, p):
    """How far each point lies outside the reach annulus ``[r_min, r_max]`` (0 inside), metres.

    This is the smallest tip error any configuration can achieve.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> distance_outside_reach(TwoLinkArm(1.0, 1.0), [[3.0, 4.0], [1.0, 0.0]])
    array([3., 0.])
    """
    p = as_pairs(p, "p")
    r_min, r_max = reach(arm)
    distance = np.hypot(p[..., 0], p[..., 1])
    return np.maximum(0.0, np.maximum(distance - r_max, r_min - distance))


def require_within_reach(arm, p, what="target"):
    """Return points ``p`` as an array, or raise naming the first one outside the reach annulus.

    The package's one reach test and one message: the point, its distance
    from the base, the reach interval and the link lengths.  Points within
    ``REACH_RTOL * (l1 + l2)`` of the annulus count as inside (round-off).

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Points in metres (finite).
    what : str
        What a point is called in the message (``"target"``, ``"path point"``).

    Raises
    ------
    twolink.UnreachableError
        Naming the first point out of reach (its index in a batch, and how
        many are out).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> require_within_reach(TwoLinkArm(1.0, 1.0), [3.0, 4.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: target (3, 4) is 5 m from the base; this arm reaches distances in [0, 2] m (l1=1, l2=1)
    >>> require_within_reach(TwoLinkArm(1.0, 1.0), [[1.0, 0.0], [0.0, 2.5]], what="path point")
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: path point (0, 2.5) (index (1,), first of 1) is 2.5 m from the base; this arm reaches distances in [0, 2] m (l1=1, l2=1)
    """
    p = as_pairs(p, what if what == "target" else f"{what} p")
    l1, l2 = arm_lengths(arm)
    r_min, r_max = abs(l1 - l2), l1 + l2
    slack = REACH_RTOL * r_max
    distance = np.hypot(p[..., 0], p[..., 1])
    outside = (distance > r_max + slack) | (distance < r_min - slack)
    if np.any(outside):
        index = tuple(int(i) for i in np.argwhere(outside)[0]) if np.ndim(outside) else ()
        x, y = p[index]
        where = f" (index {index}, first of {int(np.count_nonzero(outside))})" if np.ndim(outside) else ""
        raise UnreachableError(
            f"{what} ({x:.6g}, {y:.6g}){where} is {float(distance[index]):.6g} m from the base; "
            f"this arm reaches distances in [{r_min:.6g}, {r_max:.6g}] m (l1={l1:.6g}, l2={l2:.6g})"
        )
    return p


def require_nonsingular(arm, q, what, tol=SINGULARITY_TOL):
    """Raise :class:`~twolink.SingularityError` where ``|sin q2| <= tol`` (stretched or folded arm).

    The package's one singularity test and one message.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    what : str
        What needs the Jacobian invertible, for the message (e.g.
        ``"the tip mass"``); the advice, if any, can follow a colon.
    tol : float
        Smallest ``|sin q2|`` accepted.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``q`` as an array.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> require_nonsingular(TwoLinkArm(1.0, 1.0), [0.3, 0.0], "the tip stiffness")
    Traceback (most recent call last):
    ...
    twolink.errors.SingularityError: the tip stiffness needs J invertible, but q = (0.3, 0) rad is singular: |sin q2| = 0 <= tol = 1e-06 (|det J| = 0 m^2, the arm is stretched or folded)
    """
    q = as_pairs(q, "q")
    tol = as_finite_scalar(tol, "tol (smallest |sin q2|)", minimum=0.0)
    l1, l2 = arm_lengths(arm)
    sin_q2 = np.abs(np.sin(q[..., 1]))
    near = sin_q2 <= tol
    if np.any(near):
        index = tuple(int(i) for i in np.argwhere(near)[0]) if near.ndim else ()
        q1, q2 = q[index]
        where = f" (index {index}, first of {int(np.count_nonzero(near))})" if near.ndim else ""
        raise SingularityError(
            f"{what} needs J invertible, but q = ({q1:.6g}, {q2:.6g}) rad{where} is singular: |sin q2| = "
            f"{float(sin_q2[index]):.3g} <= tol = {tol:.3g} (|det J| = {l1 * l2 * float(sin_q2[index]):.3g} m^2, "
            "the arm is stretched or folded)"
        )
    return q
