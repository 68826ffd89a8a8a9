"""Rigid-body dynamics of the planar 2R arm: ``M(q) qdd + C(q, qd) qd + g(q) = tau``.

The links are rods with their centres of mass at mid-link and inertias
``arm.inertias`` about those centres (``m l**2 / 12`` for uniform rods).
Gravity of magnitude ``arm.g`` acts along ``-y`` in the arm's plane (a
vertical arm; ``g = 0`` is a horizontal arm).  Angles follow the DH /
relative convention and ``tau`` are the torques of the DH motors (motor 2 at
the elbow, on link 1).  The formulas are the ones :mod:`twolink.symbolic`
derives by Euler-Lagrange (the tests compare the two to 1e-12):

* ``M11 = alpha + 2 beta cos q2``, ``M12 = M21 = delta + beta cos q2``,
  ``M22 = delta``, with ``alpha = I1 + I2 + m1 lc1^2 + m2 (l1^2 + lc2^2)``,
  ``beta = m2 l1 lc2``, ``delta = I2 + m2 lc2^2`` and ``lc = l / 2``;
* ``C = h [[qd2, qd1 + qd2], [-qd1, 0]]`` with ``h = -beta sin q2``;
* ``g1 = gamma1 cos q1 + gamma2 cos(q1 + q2)``, ``g2 = gamma2 cos(q1 + q2)``
  with ``gamma1 = (m1 lc1 + m2 l1) g`` and ``gamma2 = m2 lc2 g``.

Each is written once, in a private helper that works on Python floats and on
numpy arrays alike (:func:`_mass_terms`, :func:`_coriolis_terms`,
:func:`_gravity_terms`, and :func:`_inverse` and :func:`_forward` built on
them); the public functions are vectorised over leading axes, evaluating the
helpers on numpy arrays block by block, and evaluate them on Python floats
with :mod:`math` for a single state (what an ODE solver or a controller calls
thousands of times).

Forward dynamics solves the 2x2 system ``M qdd = rhs`` with the closed-form
inverse ``M^-1 = [[M22, -M12], [-M12, M11]] / det M``, written without
cancellation: ``det M = M11 M22 - M12^2`` expands to
``(I1 + m1 lc1^2) delta + m2 l1^2 I2 + (m2 l1 lc2 sin q2)^2``, a sum of
non-negative terms (the tests derive it with sympy), so that very unequal
links (length ratios from 1e-9 to 1e9) keep full accuracy; the tests check it
against a 50-digit mpmath reference.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import kinematics
from ._derived import derived
from ._validate import (
    as_pairs,
    broadcast_shape,
    finite_result,
    pair_floats,
    real_array,
    require_arm,
    state_floats,
    torque_floats,
)
from .errors import SimulationError
from .kinematics import LARGE_ANGLE, reduced_angles, reduced_pair

_LARGE = LARGE_ANGLE  # bound once for the one-state paths

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "mass_matrix",
    "coriolis",
    "gravity",
    "mass_matrix_derivative",
    "gravity_jacobian",
    "inverse_dynamics",
    "forward_dynamics",
    "energy",
    "state_derivative",
]


class _Constants(NamedTuple):
    """The arm's parameters gathered into the few numbers the formulas use."""

    alpha: float
    beta: float
    delta: float
    gamma1: float
    gamma2: float
    det_min: float
    link1: float


def _constants(arm):
    """The arm's :class:`_Constants`, computed once per :class:`twolink.TwoLinkArm`."""
    return derived(arm, "dynamics", _compute_constants)


def _compute_constants(arm):
    try:
        inertia_1, inertia_2 = arm.inertias
    except AttributeError:
        require_arm(arm)
        raise
    lc1, lc2 = arm.l1 / 2.0, arm.l2 / 2.0
    link_1_about_base = inertia_1 + arm.m1 * lc1 * lc1
    delta = inertia_2 + arm.m2 * lc2 * lc2
    # alpha - delta: link 1 about the base plus link 2's mass at the elbow (a sum of
    # non-negative terms, kept apart so that the solve never subtracts delta back out)
    link1 = link_1_about_base + arm.m2 * arm.l1 * arm.l1
    return _Constants(
        link1 + delta,  # alpha
        arm.m2 * arm.l1 * lc2,  # beta
        delta,
        (arm.m1 * lc1 + arm.m2 * arm.l1) * arm.g,  # gamma1
        arm.m2 * lc2 * arm.g,  # gamma2
        # det M = det_min + (beta sin q2)^2 with det_min = (I1 + m1 lc1^2) delta + m2 l1^2 I2,
        # its value at cos q2 = +-1: non-negative terms only, so zero means exactly singular.
        link_1_about_base * delta + arm.m2 * arm.l1 * arm.l1 * inertia_2,  # det_min
        link1,
    )


def _invertible_constants(arm):
    constants = _constants(arm)
    if not constants.det_min > 0.0:
        raise ValueError(
            "forward dynamics needs an invertible mass matrix, but this arm's mass matrix is singular "
            "(or so light that its determinant underflows) "
            f"(at least when stretched or folded; m1={arm.m1}, m2={arm.m2}, inertias={arm.inertias}): "
            "give link 2 mass and inertia, and link 1 mass or inertia"
        )
    return constants


# ---------------------------------------------------------------- the formulas (floats or arrays)
def _mass_terms(alpha, beta, delta, cos_q2):
    """``(M11, M12, M22) = (alpha + 2 beta cos q2, delta + beta cos q2, delta)``."""
    beta_cos = beta * cos_q2
    return alpha + 2.0 * beta_cos, delta + beta_cos, delta


def _coriolis_terms(beta, sin_q2, qd1, qd2):
    """``(C11, C12, C21) = (h qd2, h (qd1 + qd2), -h qd1)`` with ``h = -beta sin q2``; ``C22 = 0``."""
    h = -beta * sin_q2
    return h * qd2, h * (qd1 + qd2), -h * qd1


def _gravity_terms(gamma1, gamma2, cos_q1, cos_q12):
    """``(g1, g2) = (gamma1 cos q1 + gamma2 cos q12, gamma2 cos q12)``."""
    g2 = gamma2 * cos_q12
    return gamma1 * cos_q1 + g2, g2


def _mass_of_angle(alpha, beta, delta, q2):
    """``(M11, M12, M21, M22)`` of a block of ``q2``, with numpy (:func:`_mass_terms`)."""
    m11, m12, m22 = _mass_terms(alpha, beta, delta, np.cos(q2))
    return m11, m12, m12, m22


def _coriolis_of_state(beta, q2, qd1, qd2):
    """``(C11, C12, C21, C22)`` of a block of states, with numpy (:func:`_coriolis_terms`)."""
    c11, c12, c21 = _coriolis_terms(beta, np.sin(q2), qd1, qd2)
    return c11, c12, c21, 0.0


def _forward(constants, cos, sin, q1, q2, qd1, qd2, tau1, tau2):
    """Joint accelerations ``(qdd1, qdd2)``; ``cos``/``sin`` from :mod:`math` (floats) or numpy (arrays).

    Solves ``M qdd = rhs`` without cancellation.  With ``A1 = alpha - delta``
    (link 1 about the base plus link 2's mass at the elbow),
    ``det M = M11 M22 - M12^2 = det_min + (beta sin q2)^2``, a sum of
    non-negative terms; and the right-hand side is used as ``r2`` and
    ``d1 = r1 - r2`` (link 1's own balance, in which the large terms of
    link 2 do not appear), so that ``alpha`` (which rounds away ``A1`` when
    link 1 is tiny) is never formed:
    ``qdd1 = (delta d1 - beta c2 r2) / det``,
    ``qdd2 = ((A1 + beta c2) r2 - (delta + beta c2) d1) / det``.
    """
    _, beta, delta, gamma1, gamma2, det_min, link1 = constants
    h = -beta * sin(q2)
    qd12 = qd1 + qd2
    r2 = tau2 + h * qd1 * qd1 - gamma2 * cos(q1 + q2)
    d1 = tau1 - tau2 - h * qd12 * qd12 - gamma1 * cos(q1)
    beta_cos = beta * cos(q2)
    det = det_min + h * h
    return (
        (delta * d1 - beta_cos * r2) / det,
        ((link1 + beta_cos) * r2 - (delta + beta_cos) * d1) / det,
    )


def _inverse(constants, cos, sin, q1, q2, qd1, qd2, qdd1, qdd2):
    """Joint torques ``(tau1, tau2) = M qdd + C qd + g``; ``cos``/``sin`` from :mod:`math` (floats) or numpy (arrays)."""
    alpha, beta, delta, gamma1, gamma2 = constants[:5]
    m11, m12, m22 = _mass_terms(alpha, beta, delta, cos(q2))
    c11, c12, c21 = _coriolis_terms(beta, sin(q2), qd1, qd2)
    g1, g2 = _gravity_terms(gamma1, gamma2, cos(q1), cos(q1 + q2))
    return m11 * qdd1 + m12 * qdd2 + (
        c11 * qd1 + c12 * qd2 + g1
    ), m12 * qdd1 + m22 * qdd2 + (c21 * qd1 + g2)


def _blockwise(formula, constants, q, qd, last):
    """Evaluate ``formula`` with numpy on broadcast ``(..., 2)`` arrays, block by block.

    ``formula`` is :func:`_forward` (``last`` is ``tau``) or :func:`_inverse`
    (``last`` is ``qdd``).
    """
    shape = broadcast_shape(
        **{"q": q, "qd": qd, "tau" if formula is _forward else "qdd": last}
    )
    q_flat, qd_flat, last_flat = (
        np.broadcast_to(array, shape).reshape(-1, 2)
        for array in (reduced_angles(q), qd, last)
    )
    columns = (
        q_flat[:, 0],
        q_flat[:, 1],
        qd_flat[:, 0],
        qd_flat[:, 1],
        last_flat[:, 0],
        last_flat[:, 1],
    )
    result = np.empty(shape)
    with np.errstate(
        over="ignore", invalid="ignore"
    ):  # an overflow is reported by the caller, not warned
        kinematics.evaluate_blockwise(
            formula, (constants, np.cos, np.sin), columns, result.reshape(-1, 2)
        )
    return result


# ---------------------------------------------------------------- public functions
def mass_matrix(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The mass (inertia) matrix ``M(q)``, symmetric positive definite.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians (relative convention).

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2)
        In kg m^2.  Only ``q2`` matters: the arm's inertia depends on its
        shape, not on where it points.

    Examples
    --------
    Stretched out, two 2 m, 3 kg rods are one 4 m, 6 kg rod: ``M11`` is its
    inertia about the end, ``6 * 4**2 / 3 = 32`` kg m^2.

    >>> from twolink import TwoLinkArm
    >>> mass_matrix(TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0), [0.0, 0.0]).round(12)
    array([[32., 10.],
           [10.,  4.]])
    """
    constants = _constants(arm)
    alpha, beta, delta = constants.alpha, constants.beta, constants.delta
    angles = pair_floats(q)
    if angles is not None:  # one pose on floats: the same terms with math
        m11_one, m12_one, m22_one = _mass_terms(alpha, beta, delta, math.cos(angles[1]))
        M_one = np.empty((2, 2))  # then four item assignments: faster than np.array
        M_one[0, 0], M_one[0, 1], M_one[1, 0], M_one[1, 1] = (
            m11_one,
            m12_one,
            m12_one,
            m22_one,
        )
        return M_one
    q = as_pairs(q, "q")
    M = np.empty(q.shape[:-1] + (2, 2))
    kinematics.evaluate_blockwise(
        _mass_of_angle,
        (alpha, beta, delta),
        (q.reshape(-1, 2)[:, 1],),
        M.reshape(-1, 4),
    )
    return M


def coriolis(arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
    """The Coriolis and centrifugal matrix ``C(q, qd)`` (Christoffel form).

    ``C[i, j] = sum_k Gamma_ijk qd_k`` with the Christoffel symbols
    ``Gamma_ijk = (dM_ij/dq_k + dM_ik/dq_j - dM_jk/dq_i) / 2`` of ``M``.
    Several matrices give the same vector ``C qd``; this choice makes
    ``dM/dt - 2 C`` skew-symmetric, so ``qd^T (dM/dt - 2C) qd = 0`` (the
    arm's passivity, which energy-based controllers rely on).

    ``C = h [[qd2, qd1 + qd2], [-qd1, 0]]`` with ``h = -m2 l1 lc2 sin q2``:
    ``h qd2^2`` in row 1 is the centrifugal torque of link 2 swinging about
    the elbow, ``2 h qd1 qd2`` the Coriolis coupling, and ``-h qd1^2`` in row
    2 the centrifugal pull of link 1's rotation on link 2.

    Parameters
    ----------
    arm : TwoLinkArm
    q, qd : array_like, shape (..., 2)
        Joint angles (rad) and joint rates (rad/s); leading axes broadcast.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2)
        In kg m^2 / s; ``C qd`` is in newton-metres.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> coriolis(TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0), [0.0, np.pi / 2], [1.0, 0.0]).round(12)
    array([[-0., -6.],
           [ 6.,  0.]])
    """
    q = as_pairs(q, "q")
    qd = as_pairs(qd, "qd")
    shape = broadcast_shape(q=q, qd=qd)
    q_flat, qd_flat = (
        np.broadcast_to(array, shape).reshape(-1, 2) for array in (q, qd)
    )
    C = np.empty(shape[:-1] + (2, 2))
    kinematics.evaluate_blockwise(
        _coriolis_of_state,
        (_constants(arm).beta,),
        (q_flat[:, 1], qd_flat[:, 0], qd_flat[:, 1]),
        C.reshape(-1, 4),
    )
    return C


def gravity(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The gravity torques ``g(q) = dV/dq``, the ``g`` of ``M qdd + C qd + g = tau``.

    The torques the motors must supply to hold the arm still at ``q``
    (gravity along ``-y`` with magnitude ``arm.g``; zero for ``arm.g = 0``).

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        In newton-metres.

    Examples
    --------
    Holding the 2 m arm (1 kg rods) straight out along x:

    >>> from twolink import TwoLinkArm
    >>> gravity(TwoLinkArm(2.0, 2.0, m1=1.0, m2=1.0, g=10.0), [0.0, 0.0]).round(12)
    array([40., 10.])
    """
    constants = _constants(arm)
    angles = pair_floats(q)
    if angles is not None:  # one pose on floats: the same terms with math
        q1_one, q2_one = reduced_pair(*angles)
        g1_one, g2_one = _gravity_terms(
            constants.gamma1,
            constants.gamma2,
            math.cos(q1_one),
            math.cos(q1_one + q2_one),
        )
        torques_one = np.empty(
            2
        )  # then two item assignments: faster than np.array of a tuple
        torques_one[0], torques_one[1] = g1_one, g2_one
        return torques_one
    q = as_pairs(q, "q")
    q1, q12 = kinematics.link_angles(q)
    torques = np.empty(q.shape)
    torques[..., 0], torques[..., 1] = _gravity_terms(
        constants.gamma1, constants.gamma2, np.cos(q1), np.cos(q12)
    )
    return torques


def mass_matrix_derivative(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The derivative of the mass matrix with respect to the joint angles, ``dM/dq``.

    ``dM[..., i, j, k] = d M_ij / d q_k`` (index ``k`` last, as in
    :func:`twolink.kinematics.jacobian_derivative`).  ``M`` depends on
    ``q2`` only: ``dM/dq1 = 0`` and
    ``dM/dq2 = -beta sin q2 [[2, 1], [1, 0]]`` with ``beta = m2 l1 lc2``.
    The Christoffel symbols of :func:`coriolis` are built from it.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2, 2)
        In kg m^2 per radian.

    Examples
    --------
    Two 2 m, 3 kg rods with the elbow at a right angle (``beta = 6`` kg m^2):

    >>> from twolink import TwoLinkArm
    >>> dM = mass_matrix_derivative(TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0), [0.0, np.pi / 2])
    >>> dM[..., 1].round(12)
    array([[-12.,  -6.],
           [ -6.,   0.]])
    >>> bool(np.all(dM[..., 0] == 0.0))
    True
    """
    q = as_pairs(q, "q")
    change = -_constants(arm).beta * np.sin(q[..., 1])
    dM = np.zeros(q.shape[:-1] + (2, 2, 2))
    dM[..., 0, 0, 1] = 2.0 * change
    dM[..., 0, 1, 1] = change
    dM[..., 1, 0, 1] = change
    return dM


def gravity_jacobian(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The derivative of the gravity torques, ``dg/dq`` (symmetric: the Hessian of the potential energy).

    ``G[..., i, j] = d g_i / d q_j``:
    ``[[-gamma1 sin q1 - gamma2 sin q12, -gamma2 sin q12], [-gamma2 sin q12, -gamma2 sin q12]]``
    with ``gamma1 = (m1 lc1 + m2 l1) g`` and ``gamma2 = m2 lc2 g``.  It is
    the gravity part of the stiffness of the linearised arm (see
    :mod:`twolink.linearization`): ``-dg/dq`` acts as a joint spring.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (..., 2)
        Joint angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2, 2)
        In newton-metres per radian.

    Examples
    --------
    Straight up, the weight is balanced, and tipping either joint away
    lowers the potential energy (``dg/dq`` negative definite: unstable):

    >>> from twolink import TwoLinkArm
    >>> gravity_jacobian(TwoLinkArm(2.0, 2.0, m1=1.0, m2=1.0, g=10.0), [np.pi / 2, 0.0]).round(12)
    array([[-40., -10.],
           [-10., -10.]])
    """
    q = as_pairs(q, "q")
    constants = _constants(arm)
    q1, q12 = kinematics.link_angles(q)
    by_q2 = -constants.gamma2 * np.sin(q12)
    G = np.empty(q.shape[:-1] + (2, 2))
    G[..., 0, 0] = -constants.gamma1 * np.sin(q1) + by_q2
    G[..., 0, 1] = by_q2
    G[..., 1, 0] = by_q2
    G[..., 1, 1] = by_q2
    return G


def inverse_dynamics(
    arm: TwoLinkArm,
    q: ArrayLike,
    qd: ArrayLike,
    qdd: ArrayLike,
    force_by_tip: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Joint torques for a motion: ``tau = M(q) qdd + C(q, qd) qd + g(q) [+ J^T force_by_tip]``.

    Parameters
    ----------
    arm : TwoLinkArm
    q, qd, qdd : array_like, shape (..., 2)
        Joint angles (rad), rates (rad/s) and accelerations (rad/s^2);
        leading axes broadcast.
    force_by_tip : array_like, shape (..., 2), optional
        Force the tip exerts on its surroundings (N), as in
        :func:`twolink.kinematics.joint_torques`: the surroundings push
        back on the tip with ``-force_by_tip``, and the motors pay
        ``J(q)^T force_by_tip`` more.  For a force ``force_on_tip`` acting
        on the tip, pass ``force_by_tip=-force_on_tip``.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Motor torques in newton-metres.

    Examples
    --------
    At rest the motors only hold the weight, ``tau = g(q)``; pressing down
    on a table with 10 N at the tip costs ``J^T (0, -10)`` more:

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(2.0, 2.0, m1=1.0, m2=1.0, g=10.0)
    >>> inverse_dynamics(arm, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]).round(12)
    array([40., 10.])
    >>> inverse_dynamics(arm, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], force_by_tip=[0.0, -10.0]).round(12)
    array([  0., -10.])
    """
    if force_by_tip is None:
        state = state_floats(q, qd, qdd)
        if state is not None:
            q1, q2, qd1, qd2, qdd1, qdd2 = state
            if not (-_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE):
                q1, q2 = reduced_pair(q1, q2)
            tau1, tau2 = _inverse(
                _constants(arm), math.cos, math.sin, q1, q2, qd1, qd2, qdd1, qdd2
            )
            if math.isfinite(tau1 + tau2):
                tau = np.empty(
                    2
                )  # then two item assignments: faster than np.array of a tuple
                tau[0], tau[1] = tau1, tau2
                return tau
    q = as_pairs(q, "q")
    qd = as_pairs(qd, "qd")
    qdd = as_pairs(qdd, "qdd")
    if force_by_tip is None:
        tau = _blockwise(_inverse, _constants(arm), q, qd, qdd)
    else:
        force_by_tip = as_pairs(force_by_tip, "force_by_tip")
        broadcast_shape(q=q, qd=qd, qdd=qdd, force_by_tip=force_by_tip)
        tau = _blockwise(
            _inverse, _constants(arm), q, qd, qdd
        ) + kinematics.joint_torques(arm, q, force_by_tip)
    return finite_result(
        tau,
        "joint torques tau (N m)",
        "the rates or accelerations are too large for this arm",
    )


def forward_dynamics(
    arm: TwoLinkArm,
    q: ArrayLike,
    qd: ArrayLike,
    tau: ArrayLike,
    force_by_tip: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Joint accelerations ``qdd = M(q)^-1 (tau - C(q, qd) qd - g(q) [- J^T force_by_tip])``.

    ``M qdd = rhs`` is solved with the closed-form inverse of the 2x2 mass
    matrix, its determinant written as a sum of non-negative terms (positive
    for an arm with mass; no cancellation, so links of very unequal length
    keep full accuracy).  One state (all arguments of shape ``(2,)``) takes a lean path on
    Python floats; anything else is vectorised.

    Parameters
    ----------
    arm : TwoLinkArm
        Link 2 needs mass and inertia, link 1 mass or inertia, or ``M`` is
        singular.
    q, qd : array_like, shape (..., 2)
        Joint angles (rad) and rates (rad/s).
    tau : array_like, shape (..., 2)
        Motor torques (N m).  Leading axes of all arguments broadcast.
    force_by_tip : array_like, shape (..., 2), optional
        Force the tip exerts on its surroundings (N); the surroundings push
        back on the tip with ``-force_by_tip``, which costs the motors
        ``J^T force_by_tip``.  A force ``force_on_tip`` acting on the tip
        (a push, a spring, see :mod:`twolink.contact`) adds
        ``J^T force_on_tip`` to ``tau``: pass ``force_by_tip=-force_on_tip``.

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Joint accelerations in rad/s^2.

    Raises
    ------
    ValueError
        For arguments of the wrong shape, non-finite values, or an arm whose
        mass matrix is singular.

    Examples
    --------
    Released from rest straight out along x, the arm starts to fall
    (``qdd1 < 0``) and bends at the elbow:

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(2.0, 2.0, m1=1.0, m2=1.0, g=10.0)
    >>> forward_dynamics(arm, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]).round(6)
    array([-6.428571,  8.571429])
    >>> forward_dynamics(arm, [0.0, 0.0], [0.0, 0.0], arm.gravity([0.0, 0.0])).round(12)
    array([0., 0.])
    """
    if force_by_tip is None:
        state = state_floats(q, qd, tau)
        if state is not None:
            q1, q2, qd1, qd2, tau1, tau2 = state
            if not (-_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE):
                q1, q2 = reduced_pair(q1, q2)
            qdd1, qdd2 = _forward(
                _invertible_constants(arm),
                math.cos,
                math.sin,
                q1,
                q2,
                qd1,
                qd2,
                tau1,
                tau2,
            )
            if math.isfinite(qdd1 + qdd2):
                qdd = np.empty(
                    2
                )  # then two item assignments: faster than np.array of a tuple
                qdd[0], qdd[1] = qdd1, qdd2
                return qdd
    q = as_pairs(q, "q")
    qd = as_pairs(qd, "qd")
    tau = as_pairs(tau, "tau")
    if force_by_tip is not None:
        force_by_tip = as_pairs(force_by_tip, "force_by_tip")
        broadcast_shape(q=q, qd=qd, tau=tau, force_by_tip=force_by_tip)
        tau = tau - kinematics.joint_torques(arm, q, force_by_tip)
    qdd = _blockwise(_forward, _invertible_constants(arm), q, qd, tau)
    return finite_result(
        qdd,
        "joint accelerations qdd (rad/s^2)",
        "the torques or rates are too large for this arm",
    )


def energy(
    arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Kinetic and potential energy ``(T, V)`` of the arm.

    ``T = qd^T M(q) qd / 2`` and ``V = g (m1 y_c1 + m2 y_c2)``, zero with
    both centres of mass at the height of the base.

    Parameters
    ----------
    arm : TwoLinkArm
    q, qd : array_like, shape (..., 2)
        Joint angles (rad) and rates (rad/s); leading axes broadcast.

    Returns
    -------
    kinetic, potential : numpy.ndarray, shape (...)
        In joules.

    Examples
    --------
    Link 1 upright (3 kg rods of 2 m), link 2 spinning at 1 rad/s: link 2
    about its end has inertia ``m l^2 / 3 = 4`` kg m^2.

    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0, g=10.0)
    >>> [float(e) for e in energy(arm, [np.pi / 2, 0.0], [0.0, 1.0])]
    [2.0, 120.0]
    """
    q = as_pairs(q, "q")
    qd = as_pairs(qd, "qd")
    shape = broadcast_shape(q=q, qd=qd)[:-1]
    constants = _constants(arm)
    m11, m12, m22 = _mass_terms(
        constants.alpha, constants.beta, constants.delta, np.cos(q[..., 1])
    )
    qd1, qd2 = qd[..., 0], qd[..., 1]
    q1, q12 = kinematics.link_angles(q)
    kinetic = 0.5 * (m11 * qd1 * qd1 + 2.0 * m12 * qd1 * qd2 + m22 * qd2 * qd2)
    potential = constants.gamma1 * np.sin(q1) + constants.gamma2 * np.sin(q12)
    return np.broadcast_to(kinetic, shape).copy(), np.broadcast_to(
        potential, shape
    ).copy()


def state_derivative(
    arm: TwoLinkArm,
    torque: Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]
    | None = None,
) -> Callable[[float, NDArray[np.float64]], list[float]]:
    """The right-hand side ``f(t, x)`` of ``dx/dt = (qd, qdd)`` for an ODE solver.

    The state is ``x = (q1, q2, qd1, qd2)``: a float array of shape ``(4,)``,
    as an ODE solver passes it, or any sequence of four finite real numbers.
    The arm is checked once, here; the returned function reads a float array
    without further checks, so that a solver can call it many thousand times
    cheaply (use :func:`twolink.simulate` rather than calling it yourself),
    and checks anything else (a list, an array of another shape or type).

    Parameters
    ----------
    arm : TwoLinkArm
    torque : callable, optional
        ``torque(t, q, qd) -> tau`` (two numbers, N m), for example a
        controller; ``None`` for free motion.  A result that is not two
        finite numbers raises :class:`ValueError` naming the time; a state
        that is not finite raises :class:`twolink.SimulationError` naming
        the time and the state.

    Returns
    -------
    callable
        ``f(t, x) -> [qd1, qd2, qdd1, qdd2]`` (a list of floats).  It raises
        :class:`ValueError` (or :class:`twolink.errors.InputTypeError`)
        naming ``state`` for a state that is not four finite real numbers.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> f = state_derivative(TwoLinkArm(2.0, 2.0, g=10.0))
    >>> np.round(f(0.0, np.array([0.0, 0.0, 0.0, 0.0])), 6)
    array([ 0.      ,  0.      , -6.428571,  8.571429])
    >>> f(0.0, [0.0, 0.0, 0.0, 0.0]) == f(0.0, np.zeros(4))
    True
    >>> f(0.0, [0.0, 0.0, 0.0])
    Traceback (most recent call last):
    ...
    ValueError: state must be four finite real numbers (q1, q2, qd1, qd2), shape (4,); got shape (3,)
    >>> g = state_derivative(TwoLinkArm(2.0, 2.0), lambda t, q, qd: [float("nan"), 0.0])
    >>> g(0.5, np.zeros(4))
    Traceback (most recent call last):
    ...
    ValueError: torque(t, q, qd) returned non-finite torques [nan  0.] at t = 0.5
    """
    constants = _invertible_constants(arm)
    if torque is not None and not callable(torque):
        raise ValueError(
            f"torque must be None or a callable torque(t, q, qd) -> tau; got {torque!r}"
        )
    cos, sin, read = math.cos, math.sin, _state_floats

    def right_hand_side(t, state):
        q1, q2, qd1, qd2, state = read(t, state)
        if not (-_LARGE <= q1 <= _LARGE and -_LARGE <= q2 <= _LARGE):
            q1, q2 = reduced_pair(q1, q2)
        if torque is None:
            tau1 = tau2 = 0.0
        else:
            tau1, tau2 = torque_floats(torque(t, state[:2].copy(), state[2:].copy()), t)
        qdd1, qdd2 = _forward(constants, cos, sin, q1, q2, qd1, qd2, tau1, tau2)
        return [qd1, qd2, qdd1, qdd2]

    return right_hand_side


_STATE_WORDS = "four finite real numbers (q1, q2, qd1, qd2), shape (4,)"


def _state_floats(t, state):
    """``(q1, q2, qd1, qd2, state)``: the state of :func:`state_derivative` as four floats and a float array.

    A float array of four, as a solver passes it, is read without checks; a
    non-finite one is the motion blowing up (:class:`twolink.SimulationError`
    naming the time and the state).  Anything else (a list, an array of
    another shape or type) is checked, with an error naming ``state``.
    """
    try:
        q1, q2, qd1, qd2 = state.tolist()
        finite = math.isfinite(q1 + q2 + qd1 + qd2)
    except (AttributeError, TypeError, ValueError):
        values = real_array(state, "state", _STATE_WORDS)
        if values.shape != (4,):
            raise ValueError(
                f"state must be {_STATE_WORDS}; got shape {values.shape}"
            ) from None
        if not np.all(np.isfinite(values)):
            raise ValueError(f"state must be {_STATE_WORDS}; got {state!r}") from None
        q1, q2, qd1, qd2 = values.tolist()
        return q1, q2, qd1, qd2, values
    if not finite:
        _raise_blow_up(t, state)
    return q1, q2, qd1, qd2, state


def _raise_blow_up(t, state):
    raise SimulationError(
        f"the motion blew up at t = {t:.6g} s: the state is not finite (or overflows), "
        f"q = ({state[0]:.6g}, {state[1]:.6g}) rad, qd = ({state[2]:.6g}, {state[3]:.6g}) rad/s"
    )
