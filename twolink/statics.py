"""Statics of the planar 2R arm: pushing on a wall.

The joint torques that hold a force ``force_by_tip`` that the tip exerts on
its surroundings are ``tau = J(q)^T force_by_tip``
(:func:`twolink.kinematics.joint_torques`); the surroundings push back on the
tip with ``-force_by_tip``.  This module solves the course's wall problem in
closed form: where must the arm touch a straight wall so that link 2 is
perpendicular to it, and what torques push with a given normal force there?
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import (
    InputTypeError,
    as_configuration,
    as_finite_scalar,
    as_pairs,
    require_arm,
)
from ._values import Value, freeze
from .errors import UnreachableError
from .kinematics import REACH_RTOL, fk, joint_torques

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["Wall", "WallContact", "wall_contact"]

_POINT = {"what": "one (x, y) point", "unit": "metres"}


@dataclass(frozen=True, init=False, eq=False)
class Wall(Value):
    """A straight wall (a line in the arm's plane): a point on it and a normal.

    Parameters
    ----------
    point : array_like, shape (2,)
        Any point of the wall, metres.
    normal : array_like, shape (2,)
        A normal vector (any length > 0, either sign); stored as a unit vector.

    Raises
    ------
    ValueError
        For NaN/inf entries, wrong shapes or a zero normal.

    Examples
    --------
    >>> wall = Wall.through([4.0, 0.0], [0.0, 4.0])
    >>> wall.normal.round(6), round(wall.distance_from_base(), 6)
    (array([0.707107, 0.707107]), 2.828427)
    >>> Wall([1.0, 0.0], [0.0, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: the wall's normal must be a non-zero vector; got (0, 0)
    """

    point: NDArray[np.float64]
    normal: NDArray[np.float64]

    def __init__(self, point: ArrayLike, normal: ArrayLike) -> None:
        on_wall = as_configuration(point, "wall point", **_POINT)
        direction = as_configuration(
            normal, "wall normal", what="one (x, y) vector", unit="any length"
        )
        length = float(np.hypot(direction[0], direction[1]))
        if not length > 0.0:
            raise ValueError(
                f"the wall's normal must be a non-zero vector; got ({direction[0]:.6g}, {direction[1]:.6g})"
            )
        object.__setattr__(self, "point", on_wall.copy())
        object.__setattr__(self, "normal", direction / length)
        freeze(self)

    @classmethod
    def through(cls, p_a: ArrayLike, p_b: ArrayLike) -> Wall:
        """The wall through two distinct points ``p_a`` and ``p_b`` (metres).

        Examples
        --------
        >>> Wall.through([0.0, 1.0], [0.0, 1.0])
        Traceback (most recent call last):
        ...
        ValueError: a wall through two points needs two distinct points; got (0, 1) twice
        """
        first = as_configuration(p_a, "wall point p_a", **_POINT)
        along = as_configuration(p_b, "wall point p_b", **_POINT) - first
        if not np.hypot(along[0], along[1]) > 0.0:
            raise ValueError(
                f"a wall through two points needs two distinct points; got ({first[0]:.6g}, {first[1]:.6g}) twice"
            )
        return cls(point=first, normal=np.array([along[1], -along[0]]))

    def signed_distance(self, p: ArrayLike) -> NDArray[np.float64]:
        """``normal . (p - point)`` for points ``p`` ``(..., 2)``, metres (0 on the wall)."""
        return (as_pairs(p, "p") - self.point) @ self.normal

    def distance_from_base(self) -> float:
        """Distance from the base (the origin) to the wall, metres."""
        return abs(float(self.point @ self.normal))

    def into_wall(self) -> NDArray[np.float64]:
        """Unit normal pointing from the base's side into the wall.

        The given normal if the wall passes through the base.
        """
        return -self.normal if self.point @ self.normal < 0.0 else self.normal.copy()


def as_wall(wall: Wall | ArrayLike) -> Wall:
    """``wall`` as a :class:`Wall`: a wall itself, or the wall through two points ``((x_a, y_a), (x_b, y_b))``.

    Raises
    ------
    ValueError
        For anything else (also ``None``), naming what is accepted.

    Examples
    --------
    >>> as_wall([[4.0, 0.0], [0.0, 4.0]]).normal.round(6)
    array([0.707107, 0.707107])
    >>> as_wall("x + y = 4")
    Traceback (most recent call last):
    ...
    ValueError: wall must be a twolink.statics.Wall or two points ((x_a, y_a), (x_b, y_b)) on the line; got 'x + y = 4'
    """
    if isinstance(wall, Wall):
        return wall
    try:
        points = np.asarray(wall, dtype=float)
    except (TypeError, ValueError):
        points = None
    if points is not None and points.shape == (2, 2):
        return Wall.through(points[0], points[1])
    raise ValueError(
        f"wall must be a twolink.statics.Wall or two points ((x_a, y_a), (x_b, y_b)) on the line; got {wall!r}"
    )


@dataclass(frozen=True, eq=False)
class WallContact(Value):
    """The arm pushing on a wall with link 2 perpendicular to it (see :func:`wall_contact`).

    Row ``k`` of every array is one contact configuration.

    Attributes
    ----------
    wall : Wall
    force_magnitude : float
        Normal force, newtons.
    force_by_tip : numpy.ndarray, shape (2,)
        The force the tip exerts ON the wall, ``force_magnitude * n``, with
        ``n`` the unit normal pointing away from the base into the wall.  The
        wall pushes back on the tip with ``-force_by_tip``.
    elbow : tuple of str
        ``"down"`` (``q2 > 0``), ``"up"`` (``q2 < 0``), or one configuration
        ``"stretched"`` (``q2 = 0``) / ``"folded"`` (``q2 = pi``) where the two
        branches meet.
    q : numpy.ndarray, shape (k, 2)
        Joint angles, radians (``q1`` in ``(-pi, pi]``).
    p_contact : numpy.ndarray, shape (k, 2)
        The contact points (tip positions) on the wall, metres.
    tau_wall : numpy.ndarray, shape (k, 2)
        ``J(q)^T force_by_tip``: the joint torques that hold the wall force, N m.
    tau_gravity : numpy.ndarray, shape (k, 2)
        The arm's own gravity torques ``g(q)`` (zeros unless requested), N m.
    tau : numpy.ndarray, shape (k, 2)
        What the motors supply: ``tau_wall + tau_gravity``, N m.
    within_limits : numpy.ndarray of bool, shape (k,)
        Whether each configuration respects the arm's joint limits.
    """

    wall: Wall
    force_magnitude: float
    force_by_tip: NDArray[np.float64]
    elbow: tuple[str, ...]
    q: NDArray[np.float64]
    p_contact: NDArray[np.float64]
    tau_wall: NDArray[np.float64]
    tau_gravity: NDArray[np.float64]
    tau: NDArray[np.float64]
    within_limits: NDArray[np.bool_]

    def __post_init__(self) -> None:
        freeze(self)

    def branch(self, elbow: str) -> int:
        """Row index of the configuration named ``elbow`` (``"down"``, ``"up"``, ...)."""
        if not isinstance(elbow, str) or elbow not in self.elbow:
            raise ValueError(
                f"elbow must be one of this contact's configurations {self.elbow}; got {elbow!r}"
            )
        return self.elbow.index(elbow)


def wall_contact(
    arm: TwoLinkArm, wall: Wall, force_magnitude: float, include_gravity: bool = False
) -> WallContact:
    """Contact configurations pushing on ``wall`` with link 2 perpendicular to it, and their torques.

    Condition: the tip lies on the wall and link 2 points along the wall's
    normal ``n`` (unit, from the base's side into the wall), so the tip
    pushes straight into the wall with ``F = force_magnitude * n``.  With
    ``phi`` the direction of ``n`` and ``d = n . point`` the base-to-wall
    distance, ``q1 + q2 = phi`` and ``l1 cos(q1 - phi) + l2 = d`` give in
    closed form

        ``q2 = +-acos((d - l2) / l1)``,  ``q1 = phi - q2``,

    two configurations (elbow ``"down"`` and ``"up"``) mirrored about the
    normal through the base, one where ``acos`` is 0 or pi.  The torques are
    ``tau = J(q)^T force_by_tip`` with ``force_by_tip = F`` the force the
    tip exerts on the wall, pointing into it (the wall pushes back on the
    tip with ``-F``); ``tau2 = 0`` because ``F`` acts along link 2.

    Parameters
    ----------
    arm : TwoLinkArm
    wall : Wall
        If the wall passes through the base, its given normal says which
        side the tip pushes towards.
    force_magnitude : float
        Normal force in newtons (>= 0).
    include_gravity : bool
        Add the arm's own gravity torques ``arm.gravity(q)`` (the ``g(q)`` of
        ``M qdd + C qd + g = tau``: gravity along -y, a vertical arm) to
        ``tau``.  Off by default (a horizontal arm, or gravity handled
        elsewhere).

    Returns
    -------
    WallContact

    Raises
    ------
    twolink.UnreachableError
        If no configuration satisfies the condition: the wall's distance from
        the base must lie in ``[|l2 - l1|, l1 + l2]`` (the elbow is
        ``l2`` from the wall, so at most ``l1`` from the base).  Walls within
        ``REACH_RTOL * (l1 + l2)`` of either limit (round-off) are solved as
        the one stretched or folded configuration there.
    ValueError
        For a negative or non-finite force, or ``wall`` not a :class:`Wall`.

    Examples
    --------
    The course's wall: ``x + y = 4``, arm ``l1 = l2 = 2`` m, 500 N.

    >>> from twolink import arms
    >>> contact = wall_contact(arms.two_metre, Wall.through([4.0, 0.0], [0.0, 4.0]), 500.0)
    >>> contact.elbow
    ('down', 'up')
    >>> np.degrees(contact.q).round(4)
    array([[-20.5302,  65.5302],
           [110.5302, -65.5302]])
    >>> contact.p_contact.round(4)
    array([[3.2872, 0.7128],
           [0.7128, 3.2872]])
    >>> contact.force_by_tip.round(3)
    array([353.553, 353.553])
    >>> contact.tau.round(2) + 0.0
    array([[ 910.18,    0.  ],
           [-910.18,    0.  ]])
    """
    require_arm(arm)
    if not isinstance(include_gravity, (bool, np.bool_)):
        raise InputTypeError(
            f"include_gravity must be True or False; got {include_gravity!r}"
        )
    if not isinstance(wall, Wall):
        raise ValueError(
            "wall must be a twolink.statics.Wall (Wall(point, normal) or Wall.through(p_a, p_b)); "
            f"got {type(wall).__name__}"
        )
    force_magnitude = as_finite_scalar(
        force_magnitude, "force_magnitude (N)", minimum=0.0
    )
    normal = wall.into_wall()
    distance = float(wall.point @ normal)
    r_low, r_high = abs(arm.l2 - arm.l1), arm.l1 + arm.l2
    # 1 - cos q2 and 1 + cos q2 with cos q2 = (d - l2) / l1, each accurate near its own end
    one_minus_c2 = (r_high - distance) / arm.l1
    one_plus_c2 = (distance + arm.l1 - arm.l2) / arm.l1
    slack = REACH_RTOL * r_high / arm.l1
    if one_minus_c2 < -slack or one_plus_c2 < -slack:
        raise UnreachableError(
            f"the wall is {distance:.6g} m from the base; with link 2 perpendicular to a wall the tip "
            f"can push on walls at distances in [{r_low:.6g}, {r_high:.6g}] m (l1={arm.l1:.6g}, l2={arm.l2:.6g})"
        )
    phi = float(np.arctan2(normal[1], normal[0]))
    if (
        one_minus_c2 <= slack
    ):  # at the reach limit within round-off: one stretched configuration
        elbow: tuple[str, ...] = ("stretched",)
        q2_values = [0.0]
    elif one_plus_c2 <= slack:
        elbow, q2_values = ("folded",), [np.pi]
    else:
        q2 = 2.0 * float(
            np.arctan2(np.sqrt(one_minus_c2), np.sqrt(one_plus_c2))
        )  # acos(cos q2), well conditioned
        elbow, q2_values = ("down", "up"), [q2, -q2]
    q = np.array([[phi - value, value] for value in q2_values])
    q[:, 0] = np.arctan2(np.sin(q[:, 0]), np.cos(q[:, 0]))
    q[:, 0] = np.where(q[:, 0] == -np.pi, np.pi, q[:, 0])
    force_by_tip = force_magnitude * normal
    tau_wall = joint_torques(arm, q, force_by_tip)
    tau_gravity = (
        np.asarray(arm.gravity(q), dtype=float)
        if include_gravity
        else np.zeros_like(tau_wall)
    )
    return WallContact(
        wall=wall,
        force_magnitude=force_magnitude,
        force_by_tip=force_by_tip,
        elbow=elbow,
        q=q,
        p_contact=fk(arm, q),
        tau_wall=tau_wall,
        tau_gravity=tau_gravity,
        tau=tau_wall + tau_gravity,
        within_limits=np.asarray(arm.within_limits(q)),
    )
