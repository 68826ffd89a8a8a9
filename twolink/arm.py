"""The :class:`TwoLinkArm` model: parameters, checks and kinematics methods.

The class holds the physical parameters and checks them once, at construction.
The computations live in small modules (:mod:`twolink.kinematics`,
:mod:`twolink.dh`, ...); the methods here are thin, documented entry points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import dh, dynamics, kinematics, velocity
from ._derived import attach_cache
from ._validate import (
    LENGTH_RANGE,
    as_finite_scalar,
    as_pairs,
    pair_floats,
    real_array,
)

__all__ = ["TwoLinkArm"]

_LIMIT_CONVENTIONS = ("relative", "absolute")

#: Representable ranges of the parameters: within them every square and
#: product the kinematics and dynamics form (up to l^4 m^2) stays a normal
#: float64, so nothing overflows to inf or underflows to 0 (LENGTH_RANGE,
#: [1e-50, 1e50] m, is the package's for every length).
MASS_MAX = 1e50
INERTIA_MAX = 1e150
G_MAX = 1e50
OFFSET_MAX = 1e150


def _within(value: float, name: str, low: float, high: float) -> float:
    if value != 0.0 and not low <= abs(value) <= high:
        allowed = (
            f"[{low:.0e}, {high:.0e}]"
            if low > 0.0
            else f"0 or up to {high:.0e} in size"
        )
        raise ValueError(
            f"{name} = {value:.6g} is outside the representable range {allowed} "
            "(its squares and products in the dynamics would overflow or underflow); rescale the units"
        )
    return value


def _as_limit_pair(value: ArrayLike | None, name: str) -> tuple[float, float] | None:
    if value is None:
        return None
    values = real_array(value, name, "None or two angles in radians").ravel().tolist()
    if np.ndim(value) != 1 or len(values) != 2:
        raise ValueError(f"{name} must be None or two angles in radians; got {value!r}")
    pair = (values[0], values[1])
    if not all(np.isfinite(pair)):
        raise ValueError(f"{name} must be finite angles in radians; got {pair}")
    return pair


@dataclass(frozen=True)
class TwoLinkArm:
    """A planar two-link (2R) arm with uniform-rod links.

    Angles follow the DH / relative convention: ``q1`` is link 1 from the
    x-axis, ``q2`` is link 2 relative to link 1, both in radians.  Lengths are
    in metres, masses in kg.

    Parameters
    ----------
    l1, l2 : float
        Link lengths (> 0), metres.
    m1, m2 : float
        Link masses (>= 0), kg.  Each link is a uniform rod with its centre of
        mass at mid-link.
    g : float
        Gravitational acceleration (m/s^2) along -y in the arm's plane
        (a vertical arm); ``g=0`` models a horizontal arm.
    d : float
        Base offset along z (the first DH row's ``d``), metres.
    q_min, q_max : pair of float, optional
        Joint limits in radians, ``q_min <= q_max`` component-wise; ``None``
        for no limits.  Read in the convention named by ``limit_convention``.
        Any pair of real numbers (a list, an array) is accepted and stored as
        a tuple of two floats.
    I1, I2 : float, optional
        Link inertias about their centres of mass (kg m^2); ``None`` gives the
        uniform rod value ``m l^2 / 12``.
    limit_convention : {"relative", "absolute"}
        Whether ``q_min``/``q_max`` bound the relative angles ``(q1, q2)`` or
        the absolute link angles ``(q1, q1 + q2)`` (a belt-driven arm).

    Raises
    ------
    ValueError
        For non-positive or non-finite lengths, negative or non-finite masses
        or inertias, non-finite ``g`` or ``d``, parameters outside the
        representable ranges (lengths in ``LENGTH_RANGE`` = [1e-50, 1e50] m,
        masses up to 1e50 kg, inertias up to 1e150 kg m^2, ``|g|`` up to
        1e50 m/s^2), limits given on one side only,
        ``q_min > q_max``, or an unknown ``limit_convention``.

    Examples
    --------
    >>> arm = TwoLinkArm(l1=2.0, l2=2.0)
    >>> arm.fk([np.pi / 2, -np.pi / 2]).round(12)
    array([2., 2.])
    >>> arm.reach
    (0.0, 4.0)
    >>> TwoLinkArm(l1=-1.0, l2=1.0)
    Traceback (most recent call last):
    ...
    ValueError: l1 (link 1 length, m) must be > 0.0; got -1.0
    """

    l1: float
    l2: float
    m1: float = 1.0
    m2: float = 1.0
    g: float = 9.81
    d: float = 0.0
    q_min: tuple[float, float] | None = None
    q_max: tuple[float, float] | None = None
    I1: float | None = None
    I2: float | None = None
    limit_convention: str = "relative"

    def __post_init__(self) -> None:
        scalars = {
            "l1": as_finite_scalar(
                self.l1, "l1 (link 1 length, m)", minimum=0.0, strictly=True
            ),
            "l2": as_finite_scalar(
                self.l2, "l2 (link 2 length, m)", minimum=0.0, strictly=True
            ),
            "m1": as_finite_scalar(self.m1, "m1 (link 1 mass, kg)", minimum=0.0),
            "m2": as_finite_scalar(self.m2, "m2 (link 2 mass, kg)", minimum=0.0),
            "g": as_finite_scalar(self.g, "g (m/s^2)"),
            "d": as_finite_scalar(self.d, "d (base offset, m)"),
        }
        q_min = _as_limit_pair(self.q_min, "q_min")
        q_max = _as_limit_pair(self.q_max, "q_max")
        for name in ("I1", "I2"):
            value = getattr(self, name)
            if value is not None:
                scalars[name] = as_finite_scalar(
                    value, f"{name} (inertia, kg m^2)", minimum=0.0
                )
                _within(scalars[name], f"{name} (inertia, kg m^2)", 0.0, INERTIA_MAX)
        _within(scalars["l1"], "l1 (link 1 length, m)", *LENGTH_RANGE)
        _within(scalars["l2"], "l2 (link 2 length, m)", *LENGTH_RANGE)
        _within(scalars["m1"], "m1 (link 1 mass, kg)", 0.0, MASS_MAX)
        _within(scalars["m2"], "m2 (link 2 mass, kg)", 0.0, MASS_MAX)
        _within(scalars["g"], "g (m/s^2)", 0.0, G_MAX)
        _within(scalars["d"], "d (base offset, m)", 0.0, OFFSET_MAX)
        if q_min is None or q_max is None:
            if q_min is not None or q_max is not None:
                raise ValueError(
                    "q_min and q_max must be given together (or both None)"
                )
        elif np.any(np.array(q_min) > np.array(q_max)):
            raise ValueError(
                f"q_min must be <= q_max component-wise; got q_min={q_min}, q_max={q_max} (radians)"
            )
        if (
            not isinstance(self.limit_convention, str)
            or self.limit_convention not in _LIMIT_CONVENTIONS
        ):
            raise ValueError(
                f"limit_convention must be one of {_LIMIT_CONVENTIONS}; got {self.limit_convention!r}"
            )
        for name, value in scalars.items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "q_min", q_min)
        object.__setattr__(self, "q_max", q_max)
        # constants derived from the parameters, computed on first use by the
        # modules that need them (read and written only by the module _derived)
        attach_cache(self)

    # ------------------------------------------------------------------ parameters
    @property
    def reach(self) -> tuple[float, float]:
        """Reach interval ``(r_min, r_max) = (|l1 - l2|, l1 + l2)`` in metres."""
        return kinematics.reach(self)

    @property
    def inertias(self) -> tuple[float, float]:
        """Link inertias about their centres of mass, ``(I1, I2)`` in kg m^2.

        Uniform rods (``m l^2 / 12``) unless ``I1``/``I2`` were given.

        Examples
        --------
        >>> TwoLinkArm(1.0, 2.0, m1=12.0, m2=3.0).inertias
        (1.0, 1.0)
        """
        inertia_1 = self.m1 * self.l1**2 / 12.0 if self.I1 is None else self.I1
        inertia_2 = self.m2 * self.l2**2 / 12.0 if self.I2 is None else self.I2
        return (inertia_1, inertia_2)

    @property
    def has_limits(self) -> bool:
        """True when the arm has joint limits."""
        return self.q_min is not None

    def within_limits(
        self, q: ArrayLike, tol: float = 1e-12
    ) -> bool | NDArray[np.bool_]:
        """Whether configurations respect the joint limits.

        Parameters
        ----------
        q : array_like, shape (..., 2)
            Relative joint angles in radians (converted to absolute link
            angles first when ``limit_convention == "absolute"``).
        tol : float
            Slack in radians, so that a configuration exactly on a limit
            counts as inside.

        Returns
        -------
        bool or numpy.ndarray of bool, shape (...)
            For one configuration (``q`` of shape ``(2,)``) a Python bool;
            for a batch an array of bool.  True (all true) when the arm has
            no limits.

        Examples
        --------
        >>> from twolink import arms
        >>> arms.ten.within_limits([[0.5, 1.0], [-0.5, 1.0]])
        array([ True, False])
        >>> arms.ten.within_limits([0.5, 1.0]), TwoLinkArm(1.0, 1.0).within_limits([9.0, 9.0])
        (True, True)
        """
        pair = pair_floats(q)
        q1: float | NDArray[np.float64]
        q2: float | NDArray[np.float64]
        if pair is not None:  # one configuration: the formula on floats
            q1, q2 = pair
            leading: tuple[int, ...] = ()
        else:  # a batch (or an unusual pair): on arrays
            angles = as_pairs(q, "q")
            q1, q2, leading = angles[..., 0], angles[..., 1], angles.shape[:-1]
        tol = as_finite_scalar(tol, "tol (rad)", minimum=0.0)
        one = leading == ()
        if self.q_min is None or self.q_max is None:
            return True if one else np.ones(leading, dtype=bool)
        angle_2 = (
            q1 + q2 if self.limit_convention == "absolute" else q2
        )  # q2 itself or link 2 from the x-axis
        (low_1, low_2), (high_1, high_2) = self.q_min, self.q_max
        inside = (
            (low_1 - tol <= q1)
            & (q1 <= high_1 + tol)
            & (low_2 - tol <= angle_2)
            & (angle_2 <= high_2 + tol)
        )
        return bool(inside) if one else inside

    # ------------------------------------------------------------------ kinematics
    def fk(self, q: ArrayLike) -> NDArray[np.float64]:
        """Tip position ``(..., 2)`` for joint angles ``q`` ``(..., 2)``; see :func:`twolink.kinematics.fk`."""
        return kinematics.fk(self, q)

    def joint_positions(self, q: ArrayLike) -> NDArray[np.float64]:
        """Base, elbow and tip ``(..., 3, 2)``; see :func:`twolink.kinematics.joint_positions`."""
        return kinematics.joint_positions(self, q)

    def jacobian(self, q: ArrayLike) -> NDArray[np.float64]:
        """Analytic Jacobian ``(..., 2, 2)``; see :func:`twolink.kinematics.jacobian`."""
        return kinematics.jacobian(self, q)

    def joint_torques(
        self, q: ArrayLike, force_by_tip: ArrayLike
    ) -> NDArray[np.float64]:
        """Static torques ``tau = J^T force_by_tip`` ``(..., 2)`` that hold the force the tip exerts.

        ``force_by_tip`` (N, shape ``(..., 2)``) is the force the tip exerts
        ON the environment; the environment pushes back with
        ``-force_by_tip``, and the motors hold the arm still with these
        torques (N m).  See :func:`twolink.kinematics.joint_torques`.

        Examples
        --------
        >>> TwoLinkArm(1.0, 1.0).joint_torques([0.0, 0.0], [0.0, -10.0]).round(12)
        array([-20., -10.])
        """
        return kinematics.joint_torques(self, q, force_by_tip)

    def dh_table(self) -> tuple[dh.DHRow, dh.DHRow]:
        """The DH table as two rows; see :func:`twolink.dh.dh_table`."""
        return dh.dh_table(self)

    def transforms(
        self, q: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(T_01, T_02)`` homogeneous transforms; see :func:`twolink.dh.transforms`."""
        return dh.transforms(self, q)

    def geometric_jacobian(self, q: ArrayLike) -> NDArray[np.float64]:
        """The 6x2 geometric Jacobian; see :func:`twolink.dh.geometric_jacobian`."""
        return dh.geometric_jacobian(self, q)

    # --- velocity
    def tip_velocity(self, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """Tip velocity ``J(q) qd`` ``(..., 2)`` in m/s; see :func:`twolink.velocity.tip_velocity`."""
        return velocity.tip_velocity(self, q, qd)

    def joint_rates(
        self, q: ArrayLike, v_tip: ArrayLike, tol: float = velocity.SINGULARITY_TOL
    ) -> NDArray[np.float64]:
        """Joint rates ``J^-1 v_tip``, raising ``SingularityError`` when ``|sin q2| <= tol``; see :func:`twolink.velocity.joint_rates`."""
        return velocity.joint_rates(self, q, v_tip, tol=tol)

    def joint_rates_dls(
        self, q: ArrayLike, v_tip: ArrayLike, damping: float
    ) -> NDArray[np.float64]:
        """Damped-least-squares joint rates (bounded at singularities); see :func:`twolink.velocity.joint_rates_dls`."""
        return velocity.joint_rates_dls(self, q, v_tip, damping)

    def manipulability(self, q: ArrayLike) -> NDArray[np.float64]:
        """Yoshikawa's manipulability ``|l1 l2 sin q2|`` ``(...)``; see :func:`twolink.velocity.manipulability`."""
        return velocity.manipulability(self, q)

    # --- dynamics
    def mass_matrix(self, q: ArrayLike) -> NDArray[np.float64]:
        """Mass matrix ``M(q)`` ``(..., 2, 2)``; see :func:`twolink.dynamics.mass_matrix`."""
        return dynamics.mass_matrix(self, q)

    def coriolis(self, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
        """Coriolis matrix ``C(q, qd)`` ``(..., 2, 2)``, ``dM/dt - 2C`` skew; see :func:`twolink.dynamics.coriolis`."""
        return dynamics.coriolis(self, q, qd)

    def gravity(self, q: ArrayLike) -> NDArray[np.float64]:
        """Gravity torques ``g(q)`` ``(..., 2)`` of ``M qdd + C qd + g = tau``; see :func:`twolink.dynamics.gravity`."""
        return dynamics.gravity(self, q)

    def inverse_dynamics(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        qdd: ArrayLike,
        force_by_tip: ArrayLike | None = None,
    ) -> NDArray[np.float64]:
        """Torques ``tau = M qdd + C qd + g [+ J^T force_by_tip]`` ``(..., 2)``.

        ``force_by_tip`` (N, optional) is the force the tip exerts ON the
        environment (which pushes back with ``-force_by_tip``);
        ``J^T force_by_tip`` is the torque that holds it.  See
        :func:`twolink.dynamics.inverse_dynamics`.
        """
        return dynamics.inverse_dynamics(self, q, qd, qdd, force_by_tip)

    def forward_dynamics(
        self,
        q: ArrayLike,
        qd: ArrayLike,
        tau: ArrayLike,
        force_by_tip: ArrayLike | None = None,
    ) -> NDArray[np.float64]:
        """Accelerations ``qdd = M^-1 (tau - C qd - g [- J^T force_by_tip])`` ``(..., 2)``.

        ``force_by_tip`` (N, optional) is the force the tip exerts ON the
        environment (which pushes back with ``-force_by_tip``); the part
        ``J^T force_by_tip`` of ``tau`` holds it and does not accelerate the
        arm.  See :func:`twolink.dynamics.forward_dynamics`.
        """
        return dynamics.forward_dynamics(self, q, qd, tau, force_by_tip)

    def energy(
        self, q: ArrayLike, qd: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Kinetic and potential energy ``(T, V)``, each ``(...)``; see :func:`twolink.dynamics.energy`."""
        return dynamics.energy(self, q, qd)
