"""The surroundings pushing on the tip: a stiff spring wall and external tip forces in a simulation.

:func:`twolink.simulate` integrates ``M qdd + C qd + g = tau`` with the
torques of a controller.  A force ``F_env`` that the surroundings apply to
the tip enters the same equation as ``J(q)^T F_env`` (virtual work), so
:class:`TipForce` wraps a controller and adds that term; :class:`SpringWall`
models a wall as a stiff spring (with optional damping) that pushes back
only when the tip is inside it.

Sign conventions: here ``F_env`` is the force *on the tip*.  Statics
(:mod:`twolink.statics`, :func:`twolink.kinematics.joint_torques`) names the
force the tip exerts on the wall, which is ``-F_env``.

Examples
--------
>>> from twolink import arms, statics
>>> wall = SpringWall(statics.Wall.through([4.0, 0.0], [0.0, 4.0]), stiffness=1e5)
>>> float(wall.penetration([2.0, 2.0])), float(wall.penetration([2.1, 2.0]))   # on the wall, 7 cm in
(0.0, 0.0707)
>>> wall.force([2.1, 2.0], [0.0, 0.0]).round(6)             # pushes the tip back out, along -n
array([-5000., -5000.])
"""

from dataclasses import dataclass

import numpy as np

from ._validate import as_finite_scalar, as_pairs
from .controllers import _require_arm

__all__ = ["SpringWall", "TipForce"]


@dataclass(frozen=True, eq=False)
class SpringWall:
    """A wall modelled as a stiff spring and damper that only pushes.

    With ``n`` the unit normal pointing from the base's side into the wall
    and ``s = n . (p - point)`` the penetration of the tip ``p``, the wall
    pushes on the tip with ``F = -max(0, k s + c n . v) n`` when ``s > 0``,
    and with nothing otherwise (it never pulls the tip in).

    Parameters
    ----------
    wall : twolink.statics.Wall
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

    wall: object
    stiffness: float
    damping: float = 0.0

    def __post_init__(self):
        if not all(hasattr(self.wall, name) for name in ("point", "into_wall")):
            raise ValueError(f"wall must be a twolink.statics.Wall; got {type(self.wall).__name__}")
        object.__setattr__(self, "stiffness", as_finite_scalar(self.stiffness, "wall stiffness (N/m)", minimum=0.0, strictly=True))
        object.__setattr__(self, "damping", as_finite_scalar(self.damping, "wall damping (N s/m)", minimum=0.0))

    @property
    def normal(self):
        """Unit normal from the base's side into the wall."""
        return self.wall.into_wall()

    def penetration(self, p):
        """How far the tip ``p`` ``(..., 2)`` is inside the wall, metres (0 outside)."""
        return np.maximum(0.0, (as_pairs(p, "p") - self.wall.point) @ self.normal)

    def force(self, p, v):
        """The force the wall applies to the tip at ``p`` moving at ``v``, N, shape ``(..., 2)``."""
        normal = self.normal
        depth = (as_pairs(p, "p") - self.wall.point) @ normal
        push = self.stiffness * depth + self.damping * (as_pairs(v, "v") @ normal)
        magnitude = np.where(depth > 0.0, np.maximum(push, 0.0), 0.0)
        return -np.multiply.outer(magnitude, normal)

    def __call__(self, t, p, v):
        return self.force(p, v)


@dataclass(frozen=True, eq=False)
class TipForce:
    """A controller's torques plus an external force on the tip: ``tau + J(q)^T F_env``.

    Pass it to :func:`twolink.simulate` as the ``torque``: the arm then moves
    as if the surroundings pushed on its tip with ``F_env``.  The result's
    ``tau`` is the sum; :meth:`motor_torque` gives the controller's part.

    Parameters
    ----------
    arm : TwoLinkArm
    controller : callable or None
        ``controller(t, q, qd) -> tau`` (N m); ``None`` for no motor torques.
    force : callable or array_like, shape (2,)
        The force on the tip, N: a constant, or ``force(t, p_tip, v_tip)``
        (for example a :class:`SpringWall`).

    Examples
    --------
    Hanging straight down, a 10 N sideways push on the tip of the
    horizontal 2 m arm needs 40 N m at the shoulder to resist:

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(2.0, 2.0, g=0.0)
    >>> pushed = TipForce(arm, None, [10.0, 0.0])
    >>> pushed(0.0, np.array([-np.pi / 2, 0.0]), np.zeros(2)).round(12)
    array([40., 20.])
    """

    arm: object
    controller: object
    force: object

    def __post_init__(self):
        _require_arm(self.arm, type(self).__name__)
        if self.controller is not None and not callable(self.controller):
            raise ValueError(f"controller must be None or a callable (t, q, qd) -> tau; got {self.controller!r}")
        if not callable(self.force):
            constant = as_pairs(self.force, "force (N)")
            if constant.shape != (2,):
                raise ValueError(f"a constant force must have shape (2,) (Fx, Fy in N); got {constant.shape}")
            constant = constant.copy()
            constant.setflags(write=False)
            object.__setattr__(self, "force", constant)

    def tip_force(self, t, q, qd):
        """The force on the tip, N, at one state (``q``, ``qd`` of shape ``(2,)``)."""
        q, qd = _one_state(q, qd)
        if not callable(self.force):
            return self.force
        v_tip = self.arm.jacobian(q) @ qd
        force = as_pairs(self.force(t, self.arm.fk(q), v_tip), "force(t, p_tip, v_tip)")
        if force.shape != (2,):
            raise ValueError(f"force(t, p_tip, v_tip) must return shape (2,) (Fx, Fy in N); got shape {force.shape}")
        return force

    def motor_torque(self, t, q, qd):
        """The controller's torques alone, N m (zeros without a controller)."""
        if self.controller is None:
            return np.zeros(2)
        tau = as_pairs(self.controller(t, q, qd), "controller(t, q, qd)")
        if tau.shape != (2,):
            raise ValueError(f"controller(t, q, qd) must return shape (2,) (N m); got shape {tau.shape}")
        return tau

    def __call__(self, t, q, qd):
        q, qd = _one_state(q, qd)
        return self.motor_torque(t, q, qd) + self.arm.jacobian(q).T @ self.tip_force(t, q, qd)


def _one_state(q, qd):
    q, qd = as_pairs(q, "q"), as_pairs(qd, "qd")
    if q.shape != (2,) or qd.shape != (2,):
        raise ValueError(f"TipForce works on one state: q and qd of shape (2,); got q of shape {q.shape} and qd of shape {qd.shape}")
    return q, qd
