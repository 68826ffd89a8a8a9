"""Stiffness felt at the tip, in joint space and in Cartesian space, and its ellipse.

A spring law seen from the tip: a small displacement ``dx`` of the tip at
rest makes the controller push back with ``dF = -K_tip dx``.  The same law
seen from the joints: ``dtau = -K_joint dq``.  With ``dx = J dq`` and
``tau = J^T F`` (chapter 4), at a configuration where the spring is
relaxed (no preload force),

    ``K_joint = J^T K_tip J``   and   ``K_tip = J^-T K_joint J^-1``.

A Cartesian spring (:class:`twolink.controllers.CartesianSpring`) fixes
``K_tip`` and lets ``K_joint`` change with the pose; a joint-space spring
(:class:`twolink.controllers.JointPD`) fixes ``K_joint``, so the stiffness
felt at the tip changes with the pose and becomes unbounded along the arm
when it is stretched.

Examples
--------
>>> from twolink import TwoLinkArm
>>> arm = TwoLinkArm(1.0, 1.0)
>>> K_joint = joint_stiffness(arm, [0.0, np.pi / 2], 100.0)
>>> bool(np.allclose(tip_stiffness(arm, [0.0, np.pi / 2], K_joint), 100.0 * np.eye(2)))
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_configuration
from .controllers import gain_matrix
from .errors import SingularityError
from .kinematics import fk, jacobian, require_nonsingular
from .velocity import Ellipse

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["joint_stiffness", "tip_stiffness", "stiffness_ellipse"]


def joint_stiffness(
    arm: TwoLinkArm, q: ArrayLike, tip_stiffness: ArrayLike
) -> NDArray[np.float64]:
    """The joint stiffness ``J^T K_tip J`` (N m/rad) that a tip stiffness amounts to at ``q``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians.
    tip_stiffness : float or array_like, shape (2, 2)
        ``K_tip`` in N/m (see :func:`twolink.controllers.gain_matrix`).

    Returns
    -------
    numpy.ndarray, shape (2, 2)

    Examples
    --------
    Stretched along x, the joints can only move the tip along y, with lever
    arms of 2 m (shoulder) and 1 m (elbow): ``K_joint = k [[4, 2], [2, 1]]``,
    a singular matrix (turning the joints as ``dq = (1, -2)`` moves the tip
    by nothing, to first order, and meets no spring):

    >>> from twolink import TwoLinkArm
    >>> joint_stiffness(TwoLinkArm(1.0, 1.0), [0.0, 0.0], 100.0).round(12)
    array([[400., 200.],
           [200., 100.]])
    """
    q = as_configuration(q)
    K_tip = gain_matrix(tip_stiffness, "tip stiffness (N/m)")
    J = jacobian(arm, q)
    K_joint = J.T @ K_tip @ J
    return (K_joint + K_joint.T) / 2.0


def tip_stiffness(
    arm: TwoLinkArm, q: ArrayLike, joint_stiffness: ArrayLike
) -> NDArray[np.float64]:
    """The stiffness ``J^-T K_joint J^-1`` (N/m) felt at the tip for a joint stiffness at ``q``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians, away from singularities.
    joint_stiffness : float or array_like, shape (2, 2)
        ``K_joint`` in N m/rad.

    Returns
    -------
    numpy.ndarray, shape (2, 2)

    Raises
    ------
    twolink.SingularityError
        When the arm is stretched or folded (``|sin q2| <=``
        :data:`twolink.kinematics.SINGULARITY_TOL`, the test of
        :func:`twolink.kinematics.require_nonsingular`): along the arm the tip
        cannot be moved, its stiffness is unbounded.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> tip_stiffness(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2], 100.0).round(12)
    array([[100., 100.],
           [100., 200.]])
    >>> tip_stiffness(TwoLinkArm(1.0, 1.0), [0.3, 0.0], 100.0)
    Traceback (most recent call last):
    ...
    twolink.errors.SingularityError: the tip stiffness needs J invertible, but q = (0.3, 0) rad is singular: |sin q2| = 0 <= tol = 1e-06 (|det J| = 0 m^2, the arm is stretched or folded); along the arm the tip stiffness is unbounded
    """
    q = as_configuration(q)
    K_joint = gain_matrix(joint_stiffness, "joint stiffness (N m/rad)")
    try:
        require_nonsingular(arm, q, "the tip stiffness")
    except SingularityError as error:
        raise SingularityError(
            f"{error}; along the arm the tip stiffness is unbounded"
        ) from None
    J_inverse = np.linalg.inv(jacobian(arm, q))
    K_tip = J_inverse.T @ K_joint @ J_inverse
    return (K_tip + K_tip.T) / 2.0


def stiffness_ellipse(
    arm: TwoLinkArm, q: ArrayLike, tip_stiffness: ArrayLike
) -> Ellipse:
    """The stiffness ellipse at the tip: the restoring force for each unit displacement.

    ``{K d : |d| = 1}``: semi-axes are the eigenvalues of ``K`` (N/m),
    largest first, along its eigenvectors; centred at the tip ``fk(q)``.
    A circle means the tip feels the same spring in every direction.
    Draw it with :func:`twolink_course.plot.draw_ellipse` and a ``scale`` in metres
    of figure per N/m.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians (only the tip position is used).
    tip_stiffness : float or array_like, shape (2, 2)
        ``K_tip`` in N/m, e.g. from :func:`tip_stiffness`.

    Returns
    -------
    twolink.velocity.Ellipse

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> ellipse = stiffness_ellipse(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2], [[300.0, 0.0], [0.0, 100.0]])
    >>> ellipse.centre.round(12), ellipse.semi_axes, float(ellipse.angle)
    (array([1., 1.]), array([300., 100.]), 0.0)
    """
    q = as_configuration(q)
    K_tip = gain_matrix(tip_stiffness, "tip stiffness (N/m)")
    eigenvalues, eigenvectors = np.linalg.eigh(K_tip)
    return Ellipse(
        centre=fk(arm, q),
        semi_axes=eigenvalues[::-1].copy(),
        directions=eigenvectors[:, ::-1].copy(),
    )
