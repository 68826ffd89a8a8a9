"""Controllers for the simulated arm: torque laws ``tau(t, q, qd)`` that plug into :func:`twolink.simulate`.

Each controller is a small frozen object, checked once at construction,
whose ``__call__(t, q, qd)`` returns the two motor torques (N m):

- :class:`CartesianSpring`: a virtual spring at the tip,
  ``tau = J^T K (x0 - x)``: the motors make the arm feel as if the tip were
  tied to the rest point ``x0`` by a spring of stiffness ``K`` (N/m);
- :class:`Impedance`: the spring plus Cartesian damping ``-D xdot``
  (N s/m) and, optionally, gravity compensation ``+ g(q)``;
- :class:`JointPD`: a joint-space PD law ``Kp (q_ref - q) + Kd (qd_ref - qd)``
  with gravity compensation;
- :class:`ComputedTorque`: feedback linearisation,
  ``tau = M(q) (qdd_ref + Kd (qd_ref - qd) + Kp (q_ref - q)) + C(q, qd) qd + g(q)``,
  which makes the tracking error obey ``e'' + Kd e' + Kp e = 0``.

Joint references (:class:`twolink.references.JointReference`, re-exported
here) are callables of time or samples interpolated by a cubic spline.  Why ``tau = J^T F`` makes the tip feel a
force ``F``: by virtual work (chapter 4), motor torques ``J^T F`` do the same
work as a force ``F`` applied at the tip, so in ``M qdd + C qd + g = tau``
they act exactly like that force.  The Cartesian controllers' ``F`` is
therefore a ``force_on_tip`` (a virtual force acting on the tip); their
torques ``J^T force_on_tip`` are written
``-joint_torques(arm, q, force_by_tip=-force_on_tip)`` (minus the torques
that would hold the opposite force, :func:`twolink.kinematics.joint_torques`).  (Were the tip
held still by a wall, it would push on the wall with that same ``F``.)

Each controller also gives its derivatives at rest,
``torque_derivatives(t, q) -> (dtau/dq, dtau/dqd)``, from which
:func:`twolink.linearization.closed_loop_matrices` builds the linear model.

Examples
--------
>>> from twolink import arms, ik
>>> spring = CartesianSpring(arms.two_metre, stiffness=600.0, rest_point=[3.0, 1.0])
>>> q = ik.closed_form(arms.two_metre, [3.0, 0.0]).q
>>> spring.force_on_tip(q).round(9) + 0.0          # tip 1 m below the rest point: pulled up
array([  0., 600.])
>>> spring(0.0, q, [0.0, 0.0]).round(6)     # tau = J^T F: x F_y about the shoulder, 1.5 m x F_y about the elbow
array([1800.,  900.])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import (
    as_configuration,
    as_finite_scalar,
    as_flag,
    as_pairs,
    as_time,
    broadcast_shape,
    plain_state,
    real_array,
    require_arm,
)
from ._values import Value
from .dynamics import gravity_jacobian, mass_matrix_derivative
from .kinematics import jacobian_derivative, joint_torques
from .references import JointReference

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["CartesianSpring", "Impedance", "JointPD", "ComputedTorque"]

#: Relative tolerance of the symmetry and positive-semi-definiteness checks
#: of gain matrices (relative to the largest entry).
GAIN_RTOL = 1e-9


def gain_matrix(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """A stiffness or damping gain as a symmetric positive semi-definite 2x2 matrix.

    Parameters
    ----------
    value : float or array_like, shape (2, 2)
        A scalar ``k >= 0`` (meaning ``k I``, the same in every direction) or
        a symmetric positive semi-definite 2x2 matrix.
    name : str
        What the gain is, with its units, for error messages.

    Returns
    -------
    numpy.ndarray, shape (2, 2)
        A new, read-only array.

    Raises
    ------
    ValueError
        For NaN or infinite entries, a negative scalar, another shape, a
        matrix that is not symmetric, or one with a negative eigenvalue
        (a spring that pushes away in some direction).

    Examples
    --------
    >>> gain_matrix(600, "stiffness (N/m)")
    array([[600.,   0.],
           [  0., 600.]])
    >>> gain_matrix([[2.0, 1.0], [0.0, 2.0]], "stiffness (N/m)")
    Traceback (most recent call last):
    ...
    ValueError: stiffness (N/m) must be symmetric (K = K^T); got [[2.0, 1.0], [0.0, 2.0]]
    >>> gain_matrix(-5.0, "stiffness (N/m)")
    Traceback (most recent call last):
    ...
    ValueError: stiffness (N/m) must be >= 0.0; got -5.0
    """
    if np.ndim(value) == 0:
        scalar = as_finite_scalar(value, name, minimum=0.0)
        matrix = scalar * np.eye(2)
    else:
        matrix = np.array(
            real_array(value, name, "a number >= 0 or a 2x2 matrix of real numbers"),
            dtype=float,
        )
        if matrix.shape != (2, 2):
            raise ValueError(
                f"{name} must be a number >= 0 or a 2x2 matrix; got shape {matrix.shape}"
            )
        if not np.all(np.isfinite(matrix)):
            raise ValueError(f"{name} must have finite entries; got {matrix.tolist()}")
        scale = float(np.max(np.abs(matrix)))
        if abs(matrix[0, 1] - matrix[1, 0]) > GAIN_RTOL * scale:
            raise ValueError(
                f"{name} must be symmetric (K = K^T); got {matrix.tolist()}"
            )
        matrix = (matrix + matrix.T) / 2.0
        smallest = float(np.linalg.eigvalsh(matrix)[0])
        if smallest < -GAIN_RTOL * scale:
            raise ValueError(
                f"{name} must be positive semi-definite (no direction with a negative gain); "
                f"got {matrix.tolist()} with eigenvalue {smallest:.6g}"
            )
    matrix.setflags(write=False)
    return matrix


def _point(value: ArrayLike, name: str) -> NDArray[np.float64]:
    point = as_configuration(value, name, what="one (x, y) point", unit="metres").copy()
    point.setflags(write=False)
    return point


def _state(
    q: ArrayLike, qd: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(q, qd)`` as float arrays of shape ``(..., 2)`` whose leading axes broadcast, or a message naming both."""
    state = plain_state(q, qd)
    if state is not None:  # one state as a simulation passes it: nothing to convert
        return state
    q, qd = as_pairs(q, "q"), as_pairs(qd, "qd")
    if q.shape != qd.shape:
        broadcast_shape(q=q, qd=qd)
    return q, qd


@dataclass(frozen=True, eq=False, init=False)
class CartesianSpring(Value):
    """A virtual spring between the tip and a rest point: ``tau = J(q)^T K (x0 - x)``.

    The force on the tip is ``force_on_tip = K (x0 - x)``, pulling it towards the rest
    point ``x0``; the potential energy stored in the spring is
    ``(x0 - x)^T K (x0 - x) / 2`` and ``tau = -dV/dq``.  Nothing damps it
    and gravity is not compensated: on the simulated arm it oscillates.

    Parameters
    ----------
    arm : TwoLinkArm
    stiffness : float or array_like, shape (2, 2)
        ``K`` in N/m: a scalar (the same in every direction) or a symmetric
        positive semi-definite matrix (see :func:`gain_matrix`).
    rest_point : array_like, shape (2,)
        ``x0``, where the spring is relaxed, metres.

    Raises
    ------
    ValueError
        For a bad stiffness (negative, not symmetric, not PSD, NaN) or rest point.

    Examples
    --------
    >>> from twolink import arms
    >>> spring = CartesianSpring(arms.two_metre, 600.0, [3.0, 1.0])
    >>> float(spring.potential_energy([0.0, 0.0]))   # tip at (4, 0): 600 * 2 / 2
    600.0
    >>> CartesianSpring(arms.two_metre, float("nan"), [3.0, 1.0])
    Traceback (most recent call last):
    ...
    ValueError: stiffness K (N/m) must be finite; got nan
    """

    arm: TwoLinkArm
    stiffness: NDArray[np.float64]
    rest_point: NDArray[np.float64]

    def __init__(
        self, arm: TwoLinkArm, stiffness: ArrayLike, rest_point: ArrayLike
    ) -> None:
        object.__setattr__(self, "arm", require_arm(arm, "CartesianSpring's arm"))
        object.__setattr__(
            self, "stiffness", gain_matrix(stiffness, "stiffness K (N/m)")
        )
        object.__setattr__(self, "rest_point", _point(rest_point, "rest_point x0"))

    def force_on_tip(self, q: ArrayLike) -> NDArray[np.float64]:
        """The spring's force acting on the tip, ``K (x0 - x)``, N; ``q`` of shape ``(..., 2)``."""
        return (self.rest_point - self.arm.fk(q)) @ self.stiffness.T

    def torque(self, q: ArrayLike) -> NDArray[np.float64]:
        """The joint torques ``J(q)^T force_on_tip``, N m; vectorised over ``q`` ``(..., 2)``."""
        return -joint_torques(
            self.arm, q, force_by_tip=-self.force_on_tip(q)
        )  # J^T force_on_tip

    def potential_energy(self, q: ArrayLike) -> NDArray[np.float64]:
        """Energy stored in the spring, ``(x0 - x)^T K (x0 - x) / 2``, joules; shape ``(...)``."""
        stretch = self.rest_point - self.arm.fk(q)
        return 0.5 * np.einsum("...i,ij,...j->...", stretch, self.stiffness, stretch)

    def __call__(self, t: float, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The motor torques at time ``t`` (unused: checked) and state ``(q, qd)``, N m."""
        as_time(t)
        q, qd = _state(q, qd)  # qd unused: checked
        return self.torque(q)

    def torque_derivatives(
        self, t: float, q: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(dtau/dq, dtau/dqd)`` at ``(q, qd = 0)``, each 2x2 (N m/rad, N m s/rad).

        ``dtau/dq = sum_k dJ_ki/dq_j F_k - J^T K J`` (the spring's geometric
        stiffness and its stiffness felt at the joints); the spring does not
        depend on ``qd``.  What :func:`twolink.linearization.closed_loop_matrices`
        linearises with.

        Examples
        --------
        At the rest point only ``-J^T K J`` is left:

        >>> from twolink import arms, ik
        >>> q = ik.closed_form(arms.two_metre, [3.0, 1.0]).q
        >>> spring = CartesianSpring(arms.two_metre, 600.0, [3.0, 1.0])
        >>> by_q, by_qd = spring.torque_derivatives(0.0, q)
        >>> J = arms.two_metre.jacobian(q)
        >>> bool(np.allclose(by_q, -600.0 * J.T @ J)), bool(np.all(by_qd == 0.0))
        (True, True)
        """
        as_time(t)
        q = as_configuration(q)
        return _spring_stiffness(
            self.arm, q, self.force_on_tip(q), self.stiffness
        ), np.zeros((2, 2))


def _spring_stiffness(
    arm: TwoLinkArm,
    q: NDArray[np.float64],
    force_on_tip: NDArray[np.float64],
    stiffness: NDArray[np.float64],
) -> NDArray[np.float64]:
    """``d(J^T F)/dq`` for ``F = K (x0 - x(q))`` at one ``q``: ``sum_k dJ_ki/dq_j F_k - J^T K J``."""
    J = arm.jacobian(q)
    geometric = np.einsum("kij,k->ij", jacobian_derivative(arm, q), force_on_tip)
    return geometric - J.T @ stiffness @ J


@dataclass(frozen=True, eq=False, init=False)
class Impedance(Value):
    """Impedance control: a tip spring, Cartesian damping and gravity compensation.

    ``tau = J(q)^T (K (x0 - x) - D J(q) qd) [+ g(q)]``, the joint torques
    of the force on the tip ``force_on_tip = K (x0 - x) - D xdot``: the tip behaves like
    a mass on a spring ``K`` (N/m) and a damper ``D`` (N s/m) anchored at
    ``x0``; with ``gravity_compensation`` the motors also carry the arm's
    weight, so the rest point is where the tip comes to rest.

    Parameters
    ----------
    arm : TwoLinkArm
    stiffness : float or array_like, shape (2, 2)
        ``K`` in N/m (see :func:`gain_matrix`).
    damping : float or array_like, shape (2, 2)
        ``D`` in N s/m, a scalar or a symmetric PSD matrix.
    rest_point : array_like, shape (2,)
        ``x0`` in metres.
    gravity_compensation : bool
        Add ``arm.gravity(q)`` to the torques (default True).

    Examples
    --------
    At the rest point and at rest, the motors only hold the arm's weight:

    >>> from twolink import arms, ik
    >>> arm = arms.two_metre
    >>> control = Impedance(arm, stiffness=600.0, damping=50.0, rest_point=[3.0, 1.0])
    >>> q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    >>> bool(np.allclose(control(0.0, q_rest, [0.0, 0.0]), arm.gravity(q_rest)))
    True
    >>> Impedance(arm, 600.0, [[10.0, 20.0], [20.0, 10.0]], [3.0, 1.0])
    Traceback (most recent call last):
    ...
    ValueError: damping D (N s/m) must be positive semi-definite (no direction with a negative gain); got [[10.0, 20.0], [20.0, 10.0]] with eigenvalue -10
    """

    arm: TwoLinkArm
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    rest_point: NDArray[np.float64]
    gravity_compensation: bool = True

    def __init__(
        self,
        arm: TwoLinkArm,
        stiffness: ArrayLike,
        damping: ArrayLike,
        rest_point: ArrayLike,
        gravity_compensation: bool = True,
    ) -> None:
        object.__setattr__(self, "arm", require_arm(arm, "Impedance's arm"))
        object.__setattr__(
            self, "stiffness", gain_matrix(stiffness, "stiffness K (N/m)")
        )
        object.__setattr__(self, "damping", gain_matrix(damping, "damping D (N s/m)"))
        object.__setattr__(self, "rest_point", _point(rest_point, "rest_point x0"))
        object.__setattr__(
            self,
            "gravity_compensation",
            as_flag(gravity_compensation, "gravity_compensation"),
        )

    @property
    def spring(self) -> CartesianSpring:
        """The spring part alone, a :class:`CartesianSpring`."""
        return CartesianSpring(self.arm, self.stiffness, self.rest_point)

    def force_on_tip(self, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The force the controller makes act on the tip, ``K (x0 - x) - D xdot``, N; shape ``(..., 2)``."""
        q, qd = _state(q, qd)
        tip_velocity = (self.arm.jacobian(q) @ qd[..., None])[..., 0]
        return (
            self.rest_point - self.arm.fk(q)
        ) @ self.stiffness.T - tip_velocity @ self.damping.T

    def torque(self, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The motor torques ``J^T force_on_tip [+ g(q)]``, N m; vectorised over ``q`` and ``qd`` ``(..., 2)``."""
        tau = -joint_torques(
            self.arm, q, force_by_tip=-self.force_on_tip(q, qd)
        )  # J^T force_on_tip
        if self.gravity_compensation:
            tau = tau + self.arm.gravity(q)
        return tau

    def potential_energy(self, q: ArrayLike) -> NDArray[np.float64]:
        """Energy stored in the virtual spring, joules (see :meth:`CartesianSpring.potential_energy`)."""
        return self.spring.potential_energy(q)

    def __call__(self, t: float, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The motor torques at time ``t`` (unused: checked) and state ``(q, qd)``, N m."""
        as_time(t)
        return self.torque(q, qd)

    def torque_derivatives(
        self, t: float, q: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(dtau/dq, dtau/dqd)`` at ``(q, qd = 0)``, each 2x2.

        The spring's (see :meth:`CartesianSpring.torque_derivatives`) plus
        ``dg/dq`` with gravity compensation; ``dtau/dqd = -J^T D J``.

        Examples
        --------
        >>> from twolink import arms
        >>> control = Impedance(arms.two_metre, 600.0, 50.0, [3.0, 1.0])
        >>> by_q, by_qd = control.torque_derivatives(0.0, [0.3, 1.2])
        >>> J = arms.two_metre.jacobian([0.3, 1.2])
        >>> bool(np.allclose(by_qd, -50.0 * J.T @ J))
        True
        """
        as_time(t)
        q = as_configuration(q)
        J = self.arm.jacobian(q)
        by_q = _spring_stiffness(
            self.arm, q, self.spring.force_on_tip(q), self.stiffness
        )
        if self.gravity_compensation:
            by_q = by_q + gravity_jacobian(self.arm, q)
        return by_q, -J.T @ self.damping @ J


def _as_reference(reference: JointReference | ArrayLike) -> JointReference:
    if isinstance(reference, JointReference):
        return reference
    if callable(reference):
        raise ValueError(
            "reference must be a JointReference (for a trajectory: JointReference(position, velocity, "
            "acceleration) or JointReference.from_samples(t, q)) or a fixed configuration q_ref of shape (2,)"
        )
    return JointReference.constant(as_configuration(reference, "reference"))


@dataclass(frozen=True, eq=False, init=False)
class JointPD(Value):
    """Joint-space PD control with gravity compensation.

    ``tau = Kp (q_ref - q) + Kd (qd_ref - qd) [+ g(q)]``: a spring and a
    damper on each joint (coupled if the gains are full matrices).  The
    error is not wrapped: ``q_ref`` and ``q`` must be on the same turn.

    Parameters
    ----------
    arm : TwoLinkArm
    kp : float or array_like, shape (2, 2)
        Joint stiffness, N m/rad (see :func:`gain_matrix`).
    kd : float or array_like, shape (2, 2)
        Joint damping, N m s/rad.
    reference : JointReference or array_like, shape (2,)
        The reference trajectory, or a fixed configuration (radians).
    gravity_compensation : bool
        Add ``arm.gravity(q)`` (default True).

    Examples
    --------
    >>> from twolink import arms
    >>> hold = JointPD(arms.two_metre, kp=100.0, kd=20.0, reference=[0.0, 0.0], gravity_compensation=False)
    >>> hold(0.0, np.array([0.1, 0.0]), np.array([0.0, 1.0])).round(12)
    array([-10., -20.])
    """

    arm: TwoLinkArm
    kp: NDArray[np.float64]
    kd: NDArray[np.float64]
    reference: JointReference
    gravity_compensation: bool = True

    def __init__(
        self,
        arm: TwoLinkArm,
        kp: ArrayLike,
        kd: ArrayLike,
        reference: JointReference | ArrayLike,
        gravity_compensation: bool = True,
    ) -> None:
        object.__setattr__(self, "arm", require_arm(arm, "JointPD's arm"))
        object.__setattr__(self, "kp", gain_matrix(kp, "kp (joint stiffness, N m/rad)"))
        object.__setattr__(self, "kd", gain_matrix(kd, "kd (joint damping, N m s/rad)"))
        object.__setattr__(self, "reference", _as_reference(reference))
        object.__setattr__(
            self,
            "gravity_compensation",
            as_flag(gravity_compensation, "gravity_compensation"),
        )

    def __call__(self, t: float, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The motor torques at time ``t`` and state ``(q, qd)``, N m; vectorised over ``q`` and ``qd`` ``(..., 2)``.

        Examples
        --------
        >>> from twolink import arms
        >>> hold = JointPD(arms.two_metre, kp=100.0, kd=20.0, reference=[0.0, 0.0], gravity_compensation=False)
        >>> hold(0.0, [[0.1, 0.0], [0.0, 0.2]], [0.0, 1.0]).round(12)
        array([[-10., -20.],
               [  0., -40.]])
        >>> hold(0.0, [0.1, 0.0, 0.3], [0.0, 1.0])
        Traceback (most recent call last):
        ...
        ValueError: q must have shape (..., 2) (two joint angles or an x, y pair per row); got shape (3,)
        """
        q, qd = _state(q, qd)
        q_ref, qd_ref, _ = self.reference(as_time(t))
        # K e for each row e: e @ K^T
        tau = (q_ref - q) @ self.kp.T + (qd_ref - qd) @ self.kd.T
        if self.gravity_compensation:
            tau = tau + self.arm.gravity(q)
        return tau

    def torque_derivatives(
        self, t: float, q: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(dtau/dq, dtau/dqd) = (-Kp [+ dg/dq], -Kd)`` at ``(q, qd = 0)``.

        Examples
        --------
        >>> from twolink import TwoLinkArm
        >>> pd = JointPD(TwoLinkArm(1.0, 1.0, g=0.0), kp=10.0, kd=2.0, reference=[0.0, 1.0])
        >>> [derivative.round(12) + 0.0 for derivative in pd.torque_derivatives(0.0, [0.0, 1.0])]
        [array([[-10.,   0.],
               [  0., -10.]]), array([[-2.,  0.],
               [ 0., -2.]])]
        """
        as_time(t)
        q = as_configuration(q)
        by_q = (
            -self.kp + gravity_jacobian(self.arm, q)
            if self.gravity_compensation
            else -self.kp
        )
        return by_q, -self.kd


@dataclass(frozen=True, eq=False, init=False)
class ComputedTorque(Value):
    """Computed-torque control (feedback linearisation) tracking a joint reference.

    ``tau = M(q) v + C(q, qd) qd + g(q)`` with
    ``v = qdd_ref + Kd (qd_ref - qd) + Kp (q_ref - q)``: with a perfect model
    the arm's acceleration is ``v``, so the error ``e = q_ref - q`` obeys
    ``e'' + Kd e' + Kp e = 0`` whatever the pose; ``Kp = wn^2``,
    ``Kd = 2 wn`` makes it critically damped.

    Parameters
    ----------
    arm : TwoLinkArm
        The arm being controlled.
    kp : float or array_like, shape (2, 2)
        1/s^2 (gains on the error, before multiplying by ``M``).
    kd : float or array_like, shape (2, 2)
        1/s.
    reference : JointReference or array_like, shape (2,)
        The trajectory to track, or a fixed configuration.
    model : TwoLinkArm, optional
        The model the controller believes in (default: ``arm``); a different
        one shows what model errors do.

    Examples
    --------
    Starting on a fixed reference at rest, the torque is exactly the weight:

    >>> from twolink import arms
    >>> arm = arms.two_metre
    >>> control = ComputedTorque(arm, kp=400.0, kd=40.0, reference=[0.3, 0.6])
    >>> bool(np.allclose(control(0.0, np.array([0.3, 0.6]), np.zeros(2)), arm.gravity([0.3, 0.6])))
    True
    """

    arm: TwoLinkArm
    kp: NDArray[np.float64]
    kd: NDArray[np.float64]
    reference: JointReference
    model: TwoLinkArm

    def __init__(
        self,
        arm: TwoLinkArm,
        kp: ArrayLike,
        kd: ArrayLike,
        reference: JointReference | ArrayLike,
        model: TwoLinkArm | None = None,
    ) -> None:
        object.__setattr__(self, "arm", require_arm(arm, "ComputedTorque's arm"))
        object.__setattr__(self, "kp", gain_matrix(kp, "kp (1/s^2)"))
        object.__setattr__(self, "kd", gain_matrix(kd, "kd (1/s)"))
        object.__setattr__(self, "reference", _as_reference(reference))
        object.__setattr__(
            self,
            "model",
            arm if model is None else require_arm(model, "ComputedTorque's model"),
        )

    def commanded_acceleration(
        self, t: float, q: ArrayLike, qd: ArrayLike
    ) -> NDArray[np.float64]:
        """``v = qdd_ref + Kd (qd_ref - qd) + Kp (q_ref - q)``, rad/s^2; vectorised over ``q`` and ``qd`` ``(..., 2)``."""
        q, qd = _state(q, qd)
        return self._acceleration(t, q, qd)

    def _acceleration(
        self, t: float, q: NDArray[np.float64], qd: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        q_ref, qd_ref, qdd_ref = self.reference(as_time(t))
        # K e for each row e: e @ K^T
        return qdd_ref + (qd_ref - qd) @ self.kd.T + (q_ref - q) @ self.kp.T

    def __call__(self, t: float, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """The motor torques at time ``t`` and state ``(q, qd)``, N m; vectorised over ``q`` and ``qd`` ``(..., 2)``."""
        q, qd = _state(q, qd)
        return self.model.inverse_dynamics(q, qd, self._acceleration(t, q, qd))

    def torque_derivatives(
        self, t: float, q: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(dtau/dq, dtau/dqd)`` at ``(q, qd = 0)``, from the model.

        ``dtau/dq = dM/dq v - M Kp + dg/dq`` (``v`` the commanded
        acceleration, ``(dM/dq v)[:, k] = dM/dq_k v``) and
        ``dtau/dqd = -M Kd`` (the Coriolis term is quadratic in ``qd``).

        Examples
        --------
        On the reference at rest, with ``v = 0``: ``(-M Kp + dg/dq, -M Kd)``.

        >>> from twolink import arms, dynamics
        >>> control = ComputedTorque(arms.two_metre, kp=100.0, kd=20.0, reference=[0.3, 0.6])
        >>> by_q, by_qd = control.torque_derivatives(0.0, [0.3, 0.6])
        >>> M = arms.two_metre.mass_matrix([0.3, 0.6])
        >>> bool(np.allclose(by_q, -100.0 * M + dynamics.gravity_jacobian(arms.two_metre, [0.3, 0.6])))
        True
        """
        as_time(t)
        q = as_configuration(q)
        acceleration = self._acceleration(t, q, np.zeros(2))
        M = self.model.mass_matrix(q)
        by_q = -M @ self.kp + gravity_jacobian(self.model, q)
        by_q += np.einsum(
            "ijk,j->ik", mass_matrix_derivative(self.model, q), acceleration
        )
        return by_q, -M @ self.kd
