"""Denavit-Hartenberg parameters, homogeneous transforms and the geometric Jacobian.

Standard (distal) DH: ``A_i = Rot_z(theta_i) Trans_z(d_i) Trans_x(a_i) Rot_x(alpha_i)``.
For the planar 2R arm the table is::

    link  theta  d  a   alpha
    1     q1*    d  l1  0
    2     q2*    0  l2  0

(``*`` marks the joint variable; ``d`` is the base offset along z, 6.5 cm on the
OSAKE desk arm, 0 for the plain planar arm).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_finite_scalar, as_pairs, real_array, require_arm

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["DHRow", "dh_matrix", "dh_table", "transforms", "geometric_jacobian"]


class DHRow(NamedTuple):
    """One row of a DH table: joint variable name, its offset, and d, a, alpha.

    ``theta = joint + theta_offset``; lengths in metres, angles in radians.
    """

    joint: str
    theta_offset: float
    d: float
    a: float
    alpha: float


def dh_matrix(
    theta: ArrayLike, d: float, a: float, alpha: float
) -> NDArray[np.float64]:
    """Homogeneous transform of one DH row, vectorised over ``theta``.

    Parameters
    ----------
    theta : array_like
        Joint angle(s) in radians.
    d, a, alpha : float
        Offset along z (m), length along x (m), twist about x (rad).

    Returns
    -------
    numpy.ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> dh_matrix(np.pi / 2, 0.5, 2.0, 0.0).round(12) + 0.0
    array([[ 0. , -1. ,  0. ,  0. ],
           [ 1. ,  0. ,  0. ,  2. ],
           [ 0. ,  0. ,  1. ,  0.5],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    theta = real_array(theta, "theta (rad)")
    d = as_finite_scalar(d, "d (m)")
    a = as_finite_scalar(a, "a (m)")
    alpha = as_finite_scalar(alpha, "alpha (rad)")
    if not np.all(np.isfinite(theta)):
        raise ValueError("theta must be finite angles in radians")
    ct, st = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(alpha), np.sin(alpha)
    A = np.zeros(theta.shape + (4, 4))
    A[..., 0, 0] = ct
    A[..., 0, 1] = -st * ca
    A[..., 0, 2] = st * sa
    A[..., 0, 3] = a * ct
    A[..., 1, 0] = st
    A[..., 1, 1] = ct * ca
    A[..., 1, 2] = -ct * sa
    A[..., 1, 3] = a * st
    A[..., 2, 1] = sa
    A[..., 2, 2] = ca
    A[..., 2, 3] = d
    A[..., 3, 3] = 1.0
    return A


def dh_table(arm: TwoLinkArm) -> tuple[DHRow, DHRow]:
    """The arm's DH table as two :class:`DHRow` rows.

    Examples
    --------
    >>> from twolink import arms
    >>> for row in dh_table(arms.osake):
    ...     print(row)
    DHRow(joint='q1', theta_offset=0.0, d=0.065, a=0.1, alpha=0.0)
    DHRow(joint='q2', theta_offset=0.0, d=0.0, a=0.115, alpha=0.0)
    """
    require_arm(arm)
    return (
        DHRow("q1", 0.0, arm.d, arm.l1, 0.0),
        DHRow("q2", 0.0, 0.0, arm.l2, 0.0),
    )


def transforms(
    arm: TwoLinkArm, q: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Frame 1 and frame 2 (tip) in the base frame: ``(T_01, T_02 = A1 @ A2)``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    tuple of numpy.ndarray, each shape (..., 4, 4)
        ``T_02[..., :2, 3]`` equals ``arm.fk(q)`` and ``T_02[..., 2, 3]`` is ``d``.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> T_01, T_02 = transforms(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2])
    >>> T_02[:3, 3].round(12)
    array([1., 1., 0.])
    """
    q = as_pairs(q, "q")
    row1, row2 = dh_table(arm)
    A1 = dh_matrix(q[..., 0] + row1.theta_offset, row1.d, row1.a, row1.alpha)
    A2 = dh_matrix(q[..., 1] + row2.theta_offset, row2.d, row2.a, row2.alpha)
    return A1, A1 @ A2


def geometric_jacobian(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The 6x2 geometric Jacobian ``[Jv; Jw]`` built from the DH frames.

    Column i is ``[z_{i-1} x (o_2 - o_{i-1}); z_{i-1}]`` for a revolute joint.
    For the planar arm both z axes are ``[0, 0, 1]``, so the angular rows are
    ``[0, 0, 1]`` for both joints and the first two linear rows equal
    :meth:`TwoLinkArm.jacobian`.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 6, 2)
        Rows ``vx, vy, vz, wx, wy, wz`` per unit joint rate.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> geometric_jacobian(TwoLinkArm(1.0, 1.0), [0.0, 0.0]).round(12) + 0.0
    array([[0., 0.],
           [2., 1.],
           [0., 0.],
           [0., 0.],
           [0., 0.],
           [1., 1.]])
    """
    T_01, T_02 = transforms(arm, q)
    identity = np.broadcast_to(np.eye(4), T_01.shape)
    o_tip = T_02[..., :3, 3]
    columns = []
    for T_prev in (identity, T_01):
        z_axis = T_prev[..., :3, 2]
        origin = T_prev[..., :3, 3]
        columns.append(
            np.concatenate([np.cross(z_axis, o_tip - origin), z_axis], axis=-1)
        )
    return np.stack(columns, axis=-1)
