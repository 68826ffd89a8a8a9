"""Velocity kinematics of the planar 2R arm: tip velocity, joint rates, manipulability, ellipses.

``v_tip = J(q) qd`` maps joint rates (rad/s) to the tip's linear velocity
(m/s).  Inverting it gives the joint rates for a wanted tip velocity, which
fails at the singular configurations ``sin q2 = 0`` (arm stretched or folded,
``det J = l1 l2 sin q2 = 0``).  Functions here take the arm (anything with
``l1`` and ``l2``) and are vectorised over leading axes like
:mod:`twolink.kinematics`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_count, as_finite_scalar, as_pairs, finite_result, require_arm
from ._values import Value, freeze
from .errors import SingularityError
from .kinematics import (
    SINGULARITY_TOL,
    evaluate_blockwise,
    fk,
    jacobian,
    jacobian_from_trig,
    reduced_angles,
    require_nonsingular,
)

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "tip_velocity",
    "joint_rates",
    "joint_rates_dls",
    "manipulability",
    "Ellipse",
    "velocity_ellipse",
    "force_ellipse",
]

# SINGULARITY_TOL is :data:`twolink.kinematics.SINGULARITY_TOL` (the same object), the
# default tolerance of :func:`joint_rates` on ``|sin q2|``, re-exported here for callers
# that import it with the velocity functions.


def _broadcast_pairs(
    q: ArrayLike, other: ArrayLike, other_name: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    q_pairs: NDArray[np.float64] = as_pairs(q, "q")
    other_pairs: NDArray[np.float64] = as_pairs(other, other_name)
    try:
        shape = np.broadcast_shapes(q_pairs.shape, other_pairs.shape)
    except ValueError as exc:
        raise ValueError(
            f"q of shape {q_pairs.shape} and {other_name} of shape {other_pairs.shape} do not broadcast"
        ) from exc
    return np.broadcast_to(q_pairs, shape), np.broadcast_to(other_pairs, shape)


def tip_velocity(arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
    """Linear velocity of the tip, ``v_tip = J(q) qd``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    qd : array_like, shape (..., 2)
        Joint rates in rad/s (broadcast against ``q``).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``(xdot, ydot)`` in m/s.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> TwoLinkArm(1.0, 1.0).tip_velocity([0.0, np.pi / 2], [1.0, 0.0]).round(12)
    array([-1.,  1.])
    """
    q, qd = _broadcast_pairs(q, qd, "qd")
    with np.errstate(over="ignore", invalid="ignore"):
        v_tip = np.einsum("...ij,...j->...i", jacobian(arm, q), qd)
    return finite_result(v_tip, "tip velocities (m/s)", "qd is too large for this arm")


def _sin_q2(q: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.sin(q[..., 1])


def joint_rates(
    arm: TwoLinkArm, q: ArrayLike, v_tip: ArrayLike, tol: float = SINGULARITY_TOL
) -> NDArray[np.float64]:
    """Joint rates that give the tip velocity ``v_tip``: ``qd = J(q)^-1 v_tip``.

    Solved in closed form, ``J^-1 = adj(J) / det J`` with
    ``det J = l1 l2 sin q2`` (block by block), refusing configurations
    within ``tol`` of a singularity, where the rates grow like ``1 / sin q2``.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    v_tip : array_like, shape (..., 2)
        Wanted tip velocity ``(xdot, ydot)`` in m/s (broadcast against ``q``).
    tol : float
        Smallest accepted ``|sin q2| = |det J| / (l1 l2)`` (dimensionless, >= 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Joint rates in rad/s.

    Raises
    ------
    twolink.SingularityError
        If ``|sin q2| <= tol`` anywhere (the test of
        :func:`twolink.kinematics.require_nonsingular`); the message gives the
        configuration, ``|sin q2|``, ``|det J|`` and the tolerance, and
        advises :func:`joint_rates_dls` there.
    ValueError
        For NaN/inf input, wrong shapes or a negative ``tol``.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0)
    >>> arm.joint_rates([0.0, np.pi / 2], [-1.0, 1.0]).round(12) + 0.0
    array([1., 0.])
    >>> arm.joint_rates([0.3, 0.0], [0.0, 1.0])
    Traceback (most recent call last):
    ...
    twolink.errors.SingularityError: solving for the joint rates needs J invertible, but q = (0.3, 0) rad is singular: |sin q2| = 0 <= tol = 1e-06 (|det J| = 0 m^2, the arm is stretched or folded); the joint rates are unbounded there: use joint_rates_dls
    """
    require_arm(arm)
    q, v_tip = _broadcast_pairs(q, v_tip, "v_tip")
    try:
        require_nonsingular(arm, q, "solving for the joint rates", tol)
    except SingularityError as error:
        raise SingularityError(
            f"{error}; the joint rates are unbounded there: use joint_rates_dls"
        ) from None
    scale = _row_scale(v_tip)
    unit = v_tip / scale
    q_flat, unit_flat = reduced_angles(q).reshape(-1, 2), unit.reshape(-1, 2)
    qd = np.empty(q.shape)
    with np.errstate(over="ignore", invalid="ignore"):
        evaluate_blockwise(
            _rates_of_angles,
            (arm.l1, arm.l2),
            (q_flat[:, 0], q_flat[:, 1], unit_flat[:, 0], unit_flat[:, 1]),
            qd.reshape(-1, 2),
        )
        qd *= scale
    return finite_result(
        qd, "joint rates qd (rad/s)", "v_tip is too large for this (near-singular) pose"
    )


def _rates_of_angles(l1, l2, q1, q2, vx, vy):
    """``J^-1 v = adj(J) v / det J`` for a block of (reduced) angles, ``det J = l1 l2 sin q2``, with numpy."""
    q12 = q1 + q2
    j11, j12, j21, j22 = jacobian_from_trig(
        l1, l2, np.cos(q1), np.sin(q1), np.cos(q12), np.sin(q12)
    )
    det = l1 * l2 * np.sin(q2)
    return (j22 * vx - j12 * vy) / det, (j11 * vy - j21 * vx) / det


def _row_scale(v_tip: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest ``|component|`` of each velocity, shape ``(..., 1)`` (1 for a zero velocity).

    The solvers work on ``v_tip / scale``, of size one, and multiply the
    result back: a tiny (even subnormal) or huge velocity then loses no
    accuracy inside the solve, only in the final, correctly rounded product.
    """
    scale = np.maximum(np.abs(v_tip[..., 0]), np.abs(v_tip[..., 1]))[..., None]
    scale[scale == 0.0] = 1.0
    return scale


def _accurate_svd(
    arm: TwoLinkArm, q: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """``J = U diag(s) V^T`` with the smaller singular value accurate to its last bits.

    :func:`numpy.linalg.svd` gets the singular vectors right, but the
    smaller singular value only to ``eps * |J|`` (about 1e-16 at an exactly
    singular pose).  ``s_min = |det J| / s_max`` with ``det J = l1 l2 sin q2``
    (no cancellation) is exact: 0 at a singularity.
    """
    U, singular_values, Vt = np.linalg.svd(jacobian(arm, q))
    s_max = singular_values[..., 0]
    det = np.abs(arm.l1 * arm.l2 * _sin_q2(q))
    singular_values[..., 1] = np.divide(
        det, s_max, out=np.zeros_like(det), where=s_max > 0.0
    )
    return U, singular_values, Vt


def joint_rates_dls(
    arm: TwoLinkArm, q: ArrayLike, v_tip: ArrayLike, damping: float
) -> NDArray[np.float64]:
    """Damped-least-squares joint rates ``qd = J^T (J J^T + damping^2 I)^-1 v_tip``.

    The rates minimise ``|J qd - v_tip|^2 + damping^2 |qd|^2``: they stay
    bounded (at most ``|v_tip| / (2 damping)``) at and near singularities,
    at the price of a tip velocity error there.  Far from singularities
    (every singular value of ``J`` much larger than ``damping``) they tend to
    the exact :func:`joint_rates`.

    Computed from the singular value decomposition ``J = U S V^T`` as
    ``qd = V diag(s / (s^2 + damping^2)) U^T v_tip`` (:func:`numpy.linalg.svd`
    for ``U`` and ``V``; the smaller singular value as ``|det J| / s_max``,
    exactly 0 at a singular pose), not from the normal equations, whose
    matrix ``J J^T + damping^2 I`` loses ``damping^2`` to round-off (or is
    singular) for small damping at a singular pose: accurate to round-off for
    any ``damping > 0``, at the singularity too (where the factor of the zero
    singular value is 0).

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.
    v_tip : array_like, shape (..., 2)
        Wanted tip velocity in m/s (broadcast against ``q``).
    damping : float
        Damping ``lambda`` in metres per radian (the units of ``J``), >= 0.
        ``0`` means no damping: the exact inverse, which raises
        :class:`twolink.SingularityError` at a singularity (see
        :func:`joint_rates`).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Joint rates in rad/s.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0)
    >>> qd = arm.joint_rates_dls([0.3, 0.0], [0.0, 1.0], damping=0.1)
    >>> bool(np.all(np.isfinite(qd))), bool(np.linalg.norm(qd) <= 1.0 / (2 * 0.1))
    (True, True)
    >>> np.allclose(arm.joint_rates_dls([0.3, 1.0], [0.0, 1.0], damping=1e-9),
    ...             arm.joint_rates([0.3, 1.0], [0.0, 1.0]))
    True
    """
    damping = as_finite_scalar(damping, "damping (m/rad)", minimum=0.0)
    if damping == 0.0:
        return joint_rates(arm, q, v_tip)
    q, v_tip = _broadcast_pairs(q, v_tip, "v_tip")
    U, singular_values, Vt = _accurate_svd(arm, q)
    scale = _row_scale(v_tip)
    weights = np.einsum("...ji,...j->...i", U, v_tip / scale)  # U^T v
    # s / (s^2 + lambda^2) as (s / r) / r with r = hypot(s, lambda): no overflow or underflow of the squares
    radius = np.hypot(singular_values, damping)
    weights *= singular_values / radius / radius
    with np.errstate(over="ignore", invalid="ignore"):
        qd = np.einsum("...ji,...j->...i", Vt, weights) * scale
    return finite_result(
        qd, "joint rates qd (rad/s)", "v_tip is too large for this damping"
    )


def manipulability(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """Yoshikawa's manipulability ``w = sqrt(det(J J^T)) = |l1 l2 sin q2|``.

    The area of the velocity ellipse divided by pi: zero at singularities,
    largest (``l1 l2``) with the links at right angles.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (...)
        In m^2 (per rad^2).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> TwoLinkArm(2.0, 1.5).manipulability([[0.4, np.pi / 2], [0.4, 0.0]])
    array([3., 0.])
    """
    q_pairs: NDArray[np.float64] = as_pairs(q, "q")
    require_arm(arm)
    return np.abs(arm.l1 * arm.l2 * _sin_q2(q_pairs))


@dataclass(frozen=True, eq=False)
class Ellipse(Value):
    """An ellipse (or a batch of them) ready to draw.

    Attributes
    ----------
    centre : numpy.ndarray, shape (..., 2)
        Centre, usually the tip position (m).
    semi_axes : numpy.ndarray, shape (..., 2)
        Semi-axis lengths, largest first (``inf`` for an unbounded axis).
    directions : numpy.ndarray, shape (..., 2, 2)
        Unit vectors of the axes as columns: ``directions[..., :, k]`` goes
        with ``semi_axes[..., k]``.
    """

    centre: NDArray[np.float64]
    semi_axes: NDArray[np.float64]
    directions: NDArray[np.float64]

    def __post_init__(self) -> None:
        freeze(self)

    @property
    def angle(self) -> NDArray[np.float64]:
        """Angle of the major axis from the x-axis, radians in ``(-pi/2, pi/2]``."""
        major = self.directions[..., :, 0]
        angle = np.arctan2(major[..., 1], major[..., 0])
        return np.where(
            angle <= -np.pi / 2,
            angle + np.pi,
            np.where(angle > np.pi / 2, angle - np.pi, angle),
        )

    def points(
        self, n: int = 64, scale: float = 1.0, clip: float | None = None
    ) -> NDArray[np.float64]:
        """Points on the boundary, ``(..., n, 2)``, for ``ax.plot`` or ``ax.fill``.

        Parameters
        ----------
        n : int
            Number of points (the first is repeated at the end: ``n`` >= 3).
        scale : float
            Drawing scale: metres of figure per unit of the ellipse's quantity
            (e.g. m per (m/s)).
        clip : float, optional
            Longest semi-axis drawn, after scaling (for unbounded axes).

        Examples
        --------
        >>> circle = Ellipse(np.zeros(2), np.ones(2), np.eye(2))
        >>> circle.points(n=5).round(12)
        array([[ 1.,  0.],
               [ 0.,  1.],
               [-1.,  0.],
               [-0., -1.],
               [ 1., -0.]])
        """
        n = as_count(n, "n (boundary points)", minimum=3, maximum=10_000_000)
        scale = as_finite_scalar(scale, "scale", minimum=0.0, strictly=True)
        lengths = np.asarray(self.semi_axes, dtype=float) * scale
        if clip is not None:
            lengths = np.minimum(
                lengths, as_finite_scalar(clip, "clip", minimum=0.0, strictly=True)
            )
        elif not np.all(np.isfinite(lengths)):
            raise ValueError(
                "the ellipse has an unbounded axis (a singular configuration): pass clip="
            )
        phase = np.linspace(0.0, 2.0 * np.pi, int(n))
        unit_circle = np.stack([np.cos(phase), np.sin(phase)], axis=-1)  # (n, 2)
        local = unit_circle * lengths[..., None, :]  # (..., n, 2)
        return self.centre[..., None, :] + np.einsum(
            "...ij,...nj->...ni", self.directions, local
        )


def _svd(
    arm: TwoLinkArm, q: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    q_pairs: NDArray[np.float64] = as_pairs(q, "q")
    U, singular_values, _ = np.linalg.svd(jacobian(arm, q_pairs))
    return q_pairs, U, singular_values


def velocity_ellipse(arm: TwoLinkArm, q: ArrayLike) -> Ellipse:
    """The tip velocities reachable with unit joint speed, ``{J qd : |qd| <= 1}``.

    Semi-axes are the singular values of ``J`` (m/s per rad/s), along the left
    singular vectors (the eigenvectors of ``J J^T``); centred at the tip.
    At a singularity the minor axis is zero: the tip cannot move along the
    arm.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    Ellipse

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> ellipse = velocity_ellipse(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2])
    >>> ellipse.centre.round(12), (ellipse.semi_axes ** 2).round(12)
    (array([1., 1.]), array([2.618034, 0.381966]))
    """
    q, U, singular_values = _svd(arm, q)
    return Ellipse(centre=fk(arm, q), semi_axes=singular_values, directions=U)


def force_ellipse(arm: TwoLinkArm, q: ArrayLike) -> Ellipse:
    """The tip forces that unit joint torque can hold, ``{F : |J^T F| <= 1}``.

    Semi-axes are ``1 / sigma`` (N per N m) for the singular values ``sigma``
    of ``J``, along the same directions as the velocity ellipse: where the
    tip moves easily it pushes weakly, and the other way round.  At a
    singularity the major axis is ``inf``: a force along the stretched (or
    folded) arm needs no torque at all.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    Ellipse
        ``semi_axes`` largest first (``inf`` where ``J`` is exactly singular).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> ellipse = force_ellipse(TwoLinkArm(1.0, 1.0), [0.0, np.pi / 2])
    >>> (1 / ellipse.semi_axes ** 2).round(12)
    array([0.381966, 2.618034])
    """
    q, U, singular_values = _svd(arm, q)
    inverse = np.full_like(singular_values, np.inf)
    np.divide(1.0, singular_values, out=inverse, where=singular_values > 0.0)
    return Ellipse(
        centre=fk(arm, q), semi_axes=inverse[..., ::-1], directions=U[..., :, ::-1]
    )
