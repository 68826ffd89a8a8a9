"""The surroundings pushing on the tip: a stiff spring wall and external tip forces in a simulation.

:func:`twolink.simulate` integrates ``M qdd + C qd + g = tau`` with the
torques of a controller.  A force ``force_on_tip`` that the surroundings
apply to the tip enters the same equation as ``J(q)^T force_on_tip``
(virtual work; :func:`twolink.kinematics.joint_torques` computes it), so
:class:`TipForce` wraps a controller and adds that term; :class:`SpringWall`
models a wall as a stiff spring (with optional damping) that pushes back
only when the tip is inside it.

Sign conventions: everything here is a ``force_on_tip``, the force acting
*on* the tip.  Statics (:mod:`twolink.statics`,
:func:`twolink.kinematics.joint_torques`) and the ``force_by_tip`` of
:func:`twolink.dynamics.forward_dynamics` name the force the tip exerts on
the wall, which is ``force_by_tip = -force_on_tip``: holding a
``force_on_tip`` at rest takes the motors ``tau = -J^T force_on_tip``.

Examples
--------
>>> from twolink import arms, statics
>>> wall = SpringWall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), stiffness=1e5)
>>> float(wall.penetration([2.0, 2.0])), float(wall.penetration([2.1, 2.0]))   # on the wall, 7 cm in
(0.0, 0.0707)
>>> wall.force_on_tip([2.1, 2.0], [0.0, 0.0]).round(6)      # pushes the tip back out, along -n
array([-5000., -5000.])
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import (
    as_configuration,
    as_finite_scalar,
    as_pairs,
    as_time,
    plain_state,
    require_arm,
)
from ._values import Value
from .kinematics import joint_torques
from .statics import Wall, as_wall

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["SpringWall", "TipForce"]

#: ``force_on_tip(t, p_tip, v_tip) -> (Fx, Fy)``: a force on the tip that depends on time, tip position and velocity.
TipForceFunction = Callable[
    [float, NDArray[np.float64], NDArray[np.float64]], ArrayLike
]
#: ``controller(t, q, qd) -> tau``.
TorqueFunction = Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]


@dataclass(frozen=True, eq=False, init=False)
class SpringWall(Value):
    """A wall modelled as a stiff spring and damper that only pushes.

    With ``n`` the unit normal pointing from the base's side into the wall
    and ``s = n . (p - point)`` the penetration of the tip ``p``, the wall
    pushes on the tip with ``force_on_tip = -max(0, k s + c n . v) n`` when
    ``s > 0``, and with nothing otherwise (it never pulls the tip in).  The
    tip pushes on the wall with ``force_by_tip = -force_on_tip``.

    Parameters
    ----------
    wall : twolink.statics.Wall or array_like, shape (2, 2)
        The wall, or two points on it (see :func:`twolink.statics.as_wall`).
    stiffness : float
        ``k`` in N/m (> 0): large for a hard wall (the contact force is ``k s``).
    damping : float
        ``c`` in N s/m (>= 0): absorbs the impact.

    Examples
    --------
    >>> from twolink import statics
    >>> SpringWall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), stiffness=0.0)
    Traceback (most recent call last):
    ...
    ValueError: wall stiffness (N/m) must be > 0.0; got 0.0
    """

    wall: Wall
    stiffness: float
    damping: float = 0.0

    def __init__(
        self, wall: Wall | ArrayLike, stiffness: float, damping: float = 0.0
    ) -> None:
        object.__setattr__(self, "wall", as_wall(wall))
        object.__setattr__(
            self,
            "stiffness",
            as_finite_scalar(
                stiffness, "wall stiffness (N/m)", minimum=0.0, strictly=True
            ),
        )
        object.__setattr__(
            self,
            "damping",
            as_finite_scalar(damping, "wall damping (N s/m)", minimum=0.0),
        )

    @property
    def normal(self) -> NDArray[np.float64]:
        """Unit normal from the base's side into the wall."""
        return self.wall.into_wall()

    def penetration(self, p: ArrayLike) -> NDArray[np.float64]:
        """How far the tip ``p`` ``(..., 2)`` is inside the wall, metres (0 outside)."""
        return np.maximum(0.0, (as_pairs(p, "p") - self.wall.point) @ self.normal)

    def force_on_tip(self, p: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """The force the wall applies to the tip at ``p`` moving at ``v``, N, shape ``(..., 2)``."""
        normal = self.normal
        depth = (as_pairs(p, "p") - self.wall.point) @ normal
        push = self.stiffness * depth + self.damping * (as_pairs(v, "v") @ normal)
        magnitude = np.where(depth > 0.0, np.maximum(push, 0.0), 0.0)
        return -np.multiply.outer(magnitude, normal)

    def __call__(self, t: float, p: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """:meth:`force_on_tip` at ``p`` and ``v`` (any time ``t``, checked): what :class:`TipForce` calls."""
        as_time(t)
        return self.force_on_tip(p, v)


@dataclass(frozen=True, eq=False, init=False)
class TipForce(Value):
    """A controller's torques plus a force acting on the tip: ``tau + J(q)^T force_on_tip``.

    Pass it to :func:`twolink.simulate` as the ``torque``: the arm then moves
    as if the surroundings pushed on its tip with ``force_on_tip``, the
    same as ``forward_dynamics(q, qd, tau, force_by_tip=-force_on_tip)``.
    The result's ``tau`` is the sum; :meth:`motor_torque` gives the
    controller's part.

    Parameters
    ----------
    arm : TwoLinkArm
    controller : callable or None
        ``controller(t, q, qd) -> tau`` (N m); ``None`` for no motor torques.
    force_on_tip : callable or array_like, shape (2,)
        The force acting on the tip, N: a constant, or
        ``force_on_tip(t, p_tip, v_tip)`` (for example a :class:`SpringWall`).

    Examples
    --------
    Hanging straight down, a 10 N sideways push on the tip of the
    horizontal 2 m arm adds 40 N m at the shoulder and 20 N m at the elbow
    (the motors would need the opposite to resist):

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(2.0, 2.0, g=0.0)
    >>> pushed = TipForce(arm, None, [10.0, 0.0])
    >>> pushed(0.0, np.array([-np.pi / 2, 0.0]), np.zeros(2)).round(12)
    array([40., 20.])
    """

    arm: TwoLinkArm
    controller: TorqueFunction | None
    force_on_tip: TipForceFunction | NDArray[np.float64]

    def __init__(
        self,
        arm: TwoLinkArm,
        controller: TorqueFunction | None,
        force_on_tip: TipForceFunction | ArrayLike,
    ) -> None:
        object.__setattr__(self, "arm", require_arm(arm, "TipForce's arm"))
        if controller is not None and not callable(controller):
            raise ValueError(
                f"controller must be None or a callable (t, q, qd) -> tau; got {controller!r}"
            )
        object.__setattr__(self, "controller", controller)
        if callable(force_on_tip):
            object.__setattr__(self, "force_on_tip", force_on_tip)
        else:
            constant = as_configuration(
                force_on_tip, "force_on_tip", what="one force (Fx, Fy)", unit="N"
            ).copy()
            constant.setflags(write=False)
            object.__setattr__(self, "force_on_tip", constant)

    def force_on_tip_at(
        self, t: float, q: ArrayLike, qd: ArrayLike
    ) -> NDArray[np.float64]:
        """The force acting on the tip, N, at one state (``q``, ``qd`` of shape ``(2,)``)."""
        t = as_time(t)
        q, qd = _one_state(q, qd)
        force_on_tip = self.force_on_tip
        if not callable(force_on_tip):
            return force_on_tip
        v_tip = self.arm.jacobian(q) @ qd
        value = as_pairs(
            force_on_tip(t, self.arm.fk(q), v_tip), "force_on_tip(t, p_tip, v_tip)"
        )
        if value.shape != (2,):
            raise ValueError(
                f"force_on_tip(t, p_tip, v_tip) must return shape (2,) (Fx, Fy in N); got shape {value.shape}"
            )
        return value

    def motor_torque(
        self, t: float, q: ArrayLike, qd: ArrayLike
    ) -> NDArray[np.float64]:
        """The controller's torques alone, N m (zeros without a controller)."""
        t = as_time(t)
        q, qd = _one_state(q, qd)
        if self.controller is None:
            return np.zeros(2)
        tau = as_pairs(self.controller(t, q, qd), "controller(t, q, qd)")
        if tau.shape != (2,):
            raise ValueError(
                f"controller(t, q, qd) must return shape (2,) (N m); got shape {tau.shape}"
            )
        return tau

    def __call__(self, t: float, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """``motor_torque + J(q)^T force_on_tip`` at time ``t`` and state ``(q, qd)``, N m."""
        q, qd = _one_state(q, qd)
        # the joint torque of a force acting on the tip, J^T force_on_tip: minus the torque that holds
        # the force the tip exerts back, force_by_tip = -force_on_tip (kinematics.joint_torques)
        force_on_tip = self.force_on_tip_at(t, q, qd)
        return self.motor_torque(t, q, qd) - joint_torques(
            self.arm, q, force_by_tip=-force_on_tip
        )


def _one_state(
    q: ArrayLike, qd: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    state = plain_state(q, qd)
    if state is not None:  # one state as a simulation passes it: nothing to convert
        return state
    return as_configuration(q), as_configuration(
        qd, "qd", what="one pair of joint rates", unit="rad/s"
    )
