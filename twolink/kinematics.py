"""Forward kinematics and the analytic Jacobian of the planar 2R arm.

Functions here take the arm (anything with ``l1`` and ``l2`` attributes) and
joint angles in the DH / relative convention: ``q1`` is link 1 from the x-axis,
``q2`` is link 2 relative to link 1.  All are vectorised over leading axes.
:class:`twolink.TwoLinkArm` exposes them as methods.

Each formula is written once, as a function of the link angles' cosines and
sines (:func:`tip_from_trig`, :func:`jacobian_from_trig`,
:func:`torques_from_jacobian`), read beside the textbook.  Link 2's absolute angle
is the sum ``q1 + q2``: joint angles larger than :data:`LARGE_ANGLE` are
first reduced exactly (:func:`reduced_angles`), so that the sum never rounds
a small angle away beside a large one (``1e17 + 0.5`` is ``1e17``) nor
overflows.  One configuration
(a pair of floats, shape ``(2,)``) evaluates it on Python floats with the
:mod:`math` module (what a loop, a widget or a controller calls thousands of
times); a batch evaluates the same function on numpy arrays, block by block
(:func:`evaluate_blockwise`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import (
    arm_lengths,
    as_finite_scalar,
    as_pairs,
    broadcast_shape,
    pair_floats,
)
from .errors import SingularityError, UnreachableError

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "fk",
    "joint_positions",
    "jacobian",
    "jacobian_derivative",
    "jacobian_rate",
    "joint_torques",
    "reach",
    "REACH_RTOL",
    "distance_outside_reach",
    "SINGULARITY_TOL",
]

#: Points up to ``REACH_RTOL * (l1 + l2)`` outside the reach annulus count as
#: inside it (round-off at full stretch or full fold); anything further is
#: out of reach (:func:`require_within_reach`).
REACH_RTOL = 1e-10

#: Configurations with ``|sin q2|`` at most this are treated as singular
#: (stretched or folded) by :func:`require_nonsingular`.
SINGULARITY_TOL = 1e-6

#: A float (one configuration, evaluated with :mod:`math`) or a numpy array
#: of them (a batch, evaluated with numpy): the formulas below take either.
Values = Any

# the one-configuration paths' functions, bound once (a module attribute lookup costs a few % of a call)
_cos, _sin, _empty = math.cos, math.sin, np.empty


# ---------------------------------------------------------------- the formulas (floats or arrays)
def tip_from_trig(
    l1: float, l2: float, c1: Values, s1: Values, c12: Values, s12: Values
) -> tuple[Values, Values]:
    """The tip ``(x, y) = (l1 c1 + l2 c12, l1 s1 + l2 s12)``.

    ``c1, s1`` are ``cos q1, sin q1`` and ``c12, s12`` are ``cos(q1 + q2),
    sin(q1 + q2)``: floats (from :mod:`math`) or arrays (from numpy).

    Examples
    --------
    >>> tip_from_trig(2.0, 1.0, 1.0, 0.0, 0.0, 1.0)  # q = (0, pi/2)
    (2.0, 1.0)
    """
    return l1 * c1 + l2 * c12, l1 * s1 + l2 * s12


def jacobian_from_trig(
    l1: float, l2: float, c1: Values, s1: Values, c12: Values, s12: Values
) -> tuple[Values, Values, Values, Values]:
    """The Jacobian's entries ``(J11, J12, J21, J22)``, the derivatives of :func:`tip_from_trig`.

    ``J = [[-l1 s1 - l2 s12, -l2 s12], [l1 c1 + l2 c12, l2 c12]]``; floats or
    arrays, as :func:`tip_from_trig`.

    Examples
    --------
    >>> jacobian_from_trig(1.0, 1.0, 1.0, 0.0, 0.0, 1.0)  # q = (0, pi/2)
    (-1.0, -1.0, 1.0, 0.0)
    """
    j12 = -l2 * s12
    j22 = l2 * c12
    return -l1 * s1 + j12, j12, l1 * c1 + j22, j22


def torques_from_jacobian(
    j11: Values, j12: Values, j21: Values, j22: Values, fx: Values, fy: Values
) -> tuple[Values, Values]:
    """``tau = J^T F``: ``(J11 Fx + J21 Fy, J12 Fx + J22 Fy)``, floats or arrays.

    Examples
    --------
    >>> torques_from_jacobian(-1.0, -1.0, 1.0, 0.0, 0.0, 10.0)
    (10.0, 0.0)
    """
    return j11 * fx + j21 * fy, j12 * fx + j22 * fy


#: Joint angles up to this size (rad) are used as they are: their sum ``q1 + q2`` is then within
#: 4e-15 rad of exact.  Larger ones are reduced exactly first (:func:`reduced_angles`).
LARGE_ANGLE = 32.0
_LARGE = LARGE_ANGLE  # bound once for the one-configuration paths


def reduced_pair(q1: float, q2: float) -> tuple[float, float]:
    """``(q1, q2)`` with each angle larger than :data:`LARGE_ANGLE` reduced exactly into ``(-pi, pi]``.

    ``atan2(sin q, cos q)``: :mod:`math`'s ``sin`` and ``cos`` reduce an
    angle exactly however large it is, so the reduced angle has its cosine
    and sine to round-off.

    Examples
    --------
    >>> q1, q2 = reduced_pair(1e17, 0.5)
    >>> abs(math.cos(q1 + q2) - math.cos(1e17 + 0.5)) > 0.1   # the plain sum rounds the 0.5 away
    True
    >>> round(math.cos(q1 + q2) - (math.cos(1e17) * math.cos(0.5) - math.sin(1e17) * math.sin(0.5)), 14)
    0.0
    """
    if -LARGE_ANGLE <= q1 <= LARGE_ANGLE and -LARGE_ANGLE <= q2 <= LARGE_ANGLE:
        return q1, q2
    if not -LARGE_ANGLE <= q1 <= LARGE_ANGLE:
        q1 = math.atan2(math.sin(q1), math.cos(q1))
    if not -LARGE_ANGLE <= q2 <= LARGE_ANGLE:
        q2 = math.atan2(math.sin(q2), math.cos(q2))
    return q1, q2


def reduced_angles(q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Angles ``q`` (any shape) with those larger than :data:`LARGE_ANGLE` reduced exactly, as :func:`reduced_pair`.

    ``q`` itself (two passes over it: its largest and smallest entry) when none is.

    Examples
    --------
    >>> reduced_angles(np.array([[0.5, 2.0], [3 * np.pi + 64 * np.pi, 1.0]])).round(12)
    array([[0.5       , 2.        ],
           [3.14159265, 1.        ]])
    """
    if not q.size or (-LARGE_ANGLE <= q.min() and q.max() <= LARGE_ANGLE):
        return q
    return np.where(np.abs(q) > LARGE_ANGLE, np.arctan2(np.sin(q), np.cos(q)), q)


def link_angles(
    q: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The link angles ``(q1, q1 + q2)`` of configurations ``q`` ``(..., 2)``, large angles reduced first.

    Examples
    --------
    >>> link_angles(np.array([0.5, 0.25]))
    (array(0.5), array(0.75))
    """
    q = reduced_angles(q)
    q1 = q[..., 0]
    return np.asarray(q1), np.asarray(q1 + q[..., 1])


def angle_sum_trig(
    c1: Values, s1: Values, c2: Values, s2: Values
) -> tuple[Values, Values]:
    """``(cos(a + b), sin(a + b)) = (c1 c2 - s1 s2, s1 c2 + c1 s2)`` from the cosines and sines of ``a`` and ``b``.

    Examples
    --------
    >>> angle_sum_trig(0.0, 1.0, 0.0, 1.0)  # a = b = pi / 2
    (-1.0, 0.0)
    """
    return c1 * c2 - s1 * s2, s1 * c2 + c1 * s2


def _tip_of_angles(
    l1: float, l2: float, q1: NDArray[np.float64], q2: NDArray[np.float64]
) -> tuple[Values, Values]:
    """:func:`tip_from_trig` of a block of (reduced) angles, evaluated with numpy."""
    q12 = q1 + q2
    return tip_from_trig(l1, l2, np.cos(q1), np.sin(q1), np.cos(q12), np.sin(q12))


def _jacobian_of_angles(
    l1: float, l2: float, q1: NDArray[np.float64], q2: NDArray[np.float64]
) -> tuple[Values, Values, Values, Values]:
    """:func:`jacobian_from_trig` of a block of (reduced) angles, evaluated with numpy."""
    q12 = q1 + q2
    return jacobian_from_trig(l1, l2, np.cos(q1), np.sin(q1), np.cos(q12), np.sin(q12))


#: Rows per block of the vectorised paths: the temporaries of one block stay
#: in the CPU cache, which is faster than whole-array numpy on large batches.
BLOCK_ROWS = 8192


def evaluate_blockwise(
    formula: Callable[..., Sequence[Values]],
    constants: tuple[Any, ...],
    columns: Sequence[NDArray[np.float64]],
    out: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Fill ``out`` (shape ``(n, m)``) with ``formula(*constants, *columns)``, block by block.

    ``columns`` are ``n``-long arrays; ``formula`` returns ``m`` arrays
    (or numbers), the columns of ``out``.

    Examples
    --------
    >>> q = np.array([[0.0, np.pi / 2], [0.0, 0.0]])
    >>> evaluate_blockwise(_tip_of_angles, (2.0, 1.0), (q[:, 0], q[:, 1]), np.empty((2, 2))).round(12)
    array([[2., 1.],
           [3., 0.]])
    """
    for start in range(0, len(out), BLOCK_ROWS):
        block = slice(start, start + BLOCK_ROWS)
        for column, values in enumerate(
            formula(*constants, *(array[block] for array in columns))
        ):
            out[block, column] = values
    return out


def fk(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
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
        if not (-_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE):
            q1, q2 = reduced_pair(q1, q2)
        q12 = q1 + q2
        l1, l2 = arm_lengths(arm)
        p_tip = _empty(2)  # then two item assignments: faster than np.array of a tuple
        p_tip[0], p_tip[1] = tip_from_trig(
            l1, l2, _cos(q1), _sin(q1), _cos(q12), _sin(q12)
        )
        return p_tip
    q = as_pairs(q, "q")
    l1, l2 = arm_lengths(arm)
    p_tips = np.empty(q.shape)
    q = reduced_angles(q)
    flat = q.reshape(-1, 2)
    evaluate_blockwise(
        _tip_of_angles, (l1, l2), (flat[:, 0], flat[:, 1]), p_tips.reshape(-1, 2)
    )
    return p_tips


def joint_positions(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
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
    l1, l2 = arm_lengths(arm)
    q1, q12 = link_angles(q)
    c1, s1 = np.cos(q1), np.sin(q1)
    points = np.zeros(q.shape[:-1] + (3, 2))
    points[..., 1, 0] = l1 * c1
    points[..., 1, 1] = l1 * s1
    points[..., 2, 0], points[..., 2, 1] = tip_from_trig(
        l1, l2, c1, s1, np.cos(q12), np.sin(q12)
    )
    return points


def jacobian(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
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
        if not (-_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE):
            q1, q2 = reduced_pair(q1, q2)
        q12 = q1 + q2
        l1, l2 = arm_lengths(arm)
        J = _empty((2, 2))  # then four item assignments: faster than np.array of a list
        J[0, 0], J[0, 1], J[1, 0], J[1, 1] = jacobian_from_trig(
            l1, l2, _cos(q1), _sin(q1), _cos(q12), _sin(q12)
        )
        return J
    q = as_pairs(q, "q")
    l1, l2 = arm_lengths(arm)
    Js = np.empty(q.shape[:-1] + (2, 2))
    q = reduced_angles(q)
    flat = q.reshape(-1, 2)
    evaluate_blockwise(
        _jacobian_of_angles, (l1, l2), (flat[:, 0], flat[:, 1]), Js.reshape(-1, 4)
    )
    return Js


def joint_torques(
    arm: TwoLinkArm, q: ArrayLike, force_by_tip: ArrayLike
) -> NDArray[np.float64]:
    """Static joint torques ``tau = J(q)^T force_by_tip`` that hold a tip force.

    ``force_by_tip`` is the force the tip exerts on the environment (for
    example on a wall), in newtons; the environment pushes back on the tip
    with ``-force_by_tip``.  The motors must supply ``tau`` to hold it (with
    the arm at rest; gravity is not included: add ``arm.gravity(q)``).

    This is the package's one computation of ``J^T F``.  By virtual work
    (``tau . qd = F . v_tip``) the same product is also the joint torque
    that a force ``force_on_tip`` acting on the tip from outside puts on the
    joints: it enters ``M qdd + C qd + g = tau + J^T force_on_tip``, so
    holding it at rest takes ``tau = -J^T force_on_tip``, consistent with
    ``force_by_tip = -force_on_tip``.  So :mod:`twolink.contact`,
    :mod:`twolink.controllers` and :mod:`twolink.linearization` write the
    torque of a force acting on the tip as
    ``-joint_torques(arm, q, force_by_tip=-force_on_tip)``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    force_by_tip : array_like, shape (..., 2)
        Force ``(Fx, Fy)`` the tip exerts on the environment, in newtons;
        leading axes broadcast with ``q``'s.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Joint torques in newton-metres.

    Examples
    --------
    The straight 4 m arm pushing up with 10 N on a ceiling at its tip:

    >>> from twolink import TwoLinkArm
    >>> joint_torques(TwoLinkArm(2.0, 2.0), [0.0, 0.0], [0.0, 10.0]).round(12)
    array([40., 20.])
    """
    pair = pair_floats(q)
    force_pair = pair_floats(force_by_tip) if pair is not None else None
    if pair is not None and force_pair is not None:
        q1, q2 = reduced_pair(*pair)
        q12 = q1 + q2
        l1, l2 = arm_lengths(arm)
        J_entries = jacobian_from_trig(l1, l2, _cos(q1), _sin(q1), _cos(q12), _sin(q12))
        tau = _empty(2)  # then two item assignments: faster than np.array of a tuple
        tau[0], tau[1] = torques_from_jacobian(*J_entries, *force_pair)
        return tau
    q = as_pairs(q, "q")
    force_by_tip = as_pairs(force_by_tip, "force_by_tip")
    shape = broadcast_shape(q=q, force_by_tip=force_by_tip)
    J = jacobian(arm, q)
    taus = np.empty(shape)
    taus[..., 0], taus[..., 1] = torques_from_jacobian(
        J[..., 0, 0],
        J[..., 0, 1],
        J[..., 1, 0],
        J[..., 1, 1],
        force_by_tip[..., 0],
        force_by_tip[..., 1],
    )
    return taus


def jacobian_derivative(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The derivative of the Jacobian with respect to the joint angles, ``dJ/dq``.

    ``dJ[..., i, j, k] = d J_ij / d q_k = d^2 p_i / (d q_j d q_k)``: index
    ``i`` is the tip coordinate (x, y), ``j`` the Jacobian's column (joint)
    and ``k`` the joint differentiated by; symmetric in ``j`` and ``k``.
    With ``(x2, y2) = l2 (cos q12, sin q12)`` the tip relative to the elbow
    and ``(x, y)`` the tip,

    ``dJ/dq1 = -[[x, x2], [y, y2]]`` and ``dJ/dq2 = -[[x2, x2], [y2, y2]]``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2, 2)
        In metres per radian squared; ``dJ[..., k]`` is ``dJ/dq_k``.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> dJ = jacobian_derivative(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2])
    >>> dJ[..., 0].round(12) + 0.0      # dJ/dq1: tip at (1, 1), elbow at (1, 0)
    array([[-1.,  0.],
           [-1., -1.]])
    >>> dJ[..., 1].round(12) + 0.0      # dJ/dq2
    array([[ 0.,  0.],
           [-1., -1.]])
    """
    q = as_pairs(q, "q")
    l1, l2 = arm_lengths(arm)
    q1, q12 = link_angles(q)
    x2, y2 = l2 * np.cos(q12), l2 * np.sin(q12)
    dJ = np.empty(q.shape[:-1] + (2, 2, 2))
    dJ[..., 0, 0, 0] = -(l1 * np.cos(q1) + x2)
    dJ[..., 1, 0, 0] = -(l1 * np.sin(q1) + y2)
    for i, relative in ((0, x2), (1, y2)):
        dJ[..., i, 0, 1] = dJ[..., i, 1, 0] = dJ[..., i, 1, 1] = -relative
    return dJ


def jacobian_rate(arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
    """The time derivative of the Jacobian along a motion, ``Jdot = sum_k dJ/dq_k qd_k``.

    The tip's acceleration is ``a = J qdd + Jdot qd``.  With ``(x, y)`` the
    tip and ``(x2, y2)`` the tip relative to the elbow,
    ``Jdot = -[[x qd1 + x2 qd2, x2 (qd1 + qd2)], [y qd1 + y2 qd2, y2 (qd1 + qd2)]]``
    (see :func:`jacobian_derivative`).

    Parameters
    ----------
    arm : TwoLinkArm
    q, qd : array_like, shape (..., 2)
        Joint angles (rad) and rates (rad/s); leading axes broadcast.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2)
        In metres per radian per second.

    Examples
    --------
    Link 1 turning at 1 rad/s with the elbow locked: the tip moves on a
    circle, and ``Jdot qd`` is its centripetal acceleration ``-p``:

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0)
    >>> Jdot = jacobian_rate(arm, [0.0, np.pi / 2], [1.0, 0.0])
    >>> (Jdot @ [1.0, 0.0]).round(12) + 0.0, arm.fk([0.0, np.pi / 2]).round(12)
    (array([-1., -1.]), array([1., 1.]))
    """
    q = as_pairs(q, "q")
    qd = as_pairs(qd, "qd")
    shape = broadcast_shape(q=q, qd=qd)
    l1, l2 = arm_lengths(arm)
    q1, q12 = link_angles(q)
    x2, y2 = l2 * np.cos(q12), l2 * np.sin(q12)
    qd1, qd2 = qd[..., 0], qd[..., 1]
    qd12 = qd1 + qd2
    Jdot = np.empty(shape[:-1] + (2, 2))
    Jdot[..., 0, 0] = -(l1 * np.cos(q1) * qd1 + x2 * qd12)
    Jdot[..., 0, 1] = -x2 * qd12
    Jdot[..., 1, 0] = -(l1 * np.sin(q1) * qd1 + y2 * qd12)
    Jdot[..., 1, 1] = -y2 * qd12
    return Jdot


def reach(arm: TwoLinkArm) -> tuple[float, float]:
    """Reach interval ``(r_min, r_max) = (|l1 - l2|, l1 + l2)`` in metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> [round(r, 12) for r in reach(TwoLinkArm(0.1, 0.115))]
    [0.015, 0.215]
    """
    l1, l2 = arm_lengths(arm)
    return (abs(l1 - l2), l1 + l2)


def distance_outside_reach(arm: TwoLinkArm, p: ArrayLike) -> NDArray[np.float64]:
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


def require_within_reach(
    arm: TwoLinkArm, p: ArrayLike, what: str = "target"
) -> NDArray[np.float64]:
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
        index = (
            tuple(int(i) for i in np.argwhere(outside)[0]) if np.ndim(outside) else ()
        )
        x, y = p[index]
        where = (
            f" (index {index}, first of {int(np.count_nonzero(outside))})"
            if np.ndim(outside)
            else ""
        )
        raise UnreachableError(
            f"{what} ({x:.6g}, {y:.6g}){where} is {_distance_words(float(distance[index]), r_min, r_max, slack)}; "
            f"this arm reaches distances in [{r_min:.6g}, {r_max:.6g}] m (l1={l1:.6g}, l2={l2:.6g})"
        )
    return p


def _distance_words(distance: float, r_min: float, r_max: float, slack: float) -> str:
    """``"5 m from the base"``, with the digits and the overshoot that set it apart from the reach it misses.

    Just outside the round-off tolerance, 6 digits print the distance as the
    reach itself ("4 m from the base; reaches [0, 4] m"): then the distance
    takes as many digits as it needs, and the message says by how much it
    misses.
    """
    bound = r_max if distance > r_max else r_min
    if f"{distance:.6g}" != f"{bound:.6g}":
        return f"{distance:.6g} m from the base"
    digits = next(n for n in range(7, 18) if f"{distance:.{n}g}" != f"{bound:.{n}g}")
    side = "beyond the outer" if distance > r_max else "inside the inner"
    return (
        f"{distance:.{digits}g} m from the base, {abs(distance - bound):.3g} m {side} reach circle "
        f"(more than the round-off tolerance REACH_RTOL (l1 + l2) = {slack:.3g} m)"
    )


def require_nonsingular(
    arm: TwoLinkArm, q: ArrayLike, what: str, tol: float = SINGULARITY_TOL
) -> NDArray[np.float64]:
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
        where = (
            f" (index {index}, first of {int(np.count_nonzero(near))})"
            if near.ndim
            else ""
        )
        raise SingularityError(
            f"{what} needs J invertible, but q = ({q1:.6g}, {q2:.6g}) rad{where} is singular: |sin q2| = "
            f"{float(sin_q2[index]):.3g} <= tol = {tol:.3g} (|det J| = {l1 * l2 * float(sin_q2[index]):.3g} m^2, "
            "the arm is stretched or folded)"
        )
    return q
