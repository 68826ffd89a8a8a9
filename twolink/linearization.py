"""The closed loop near an equilibrium: linear models for python-control, tip mass, critical damping.

An arm driven by a controller ``tau(t, q, qd)`` and pushed at the tip by a
force ``force_on_tip = F`` (N, acting on the tip; the tip exerts
``force_by_tip = -F`` on whatever pushes it) obeys

    ``M(q) qdd + C(q, qd) qd + g(q) = tau(t, q, qd) + J(q)^T F``.

With the state ``x = (q1, q2, qd1, qd2)``, the input ``u = F`` (named
:data:`INPUTS`, ``Fx_on_tip`` and ``Fy_on_tip``) and the output the tip
position, this is ``xdot = f(x, u)``, ``y = fk(q)``.  At an
equilibrium ``(q*, 0)`` (``tau(t, q*, 0) = g(q*)``) the Coriolis term is
quadratic in ``qd`` and ``M^-1`` multiplies a zero net torque, so

    ``A = [[0, I], [M^-1 (dtau/dq - dg/dq), M^-1 dtau/dqd]]``,
    ``B = [[0], [M^-1 J^T]]``,  ``C = [J, 0]``,  ``D = 0``.

:func:`linearize` builds this from the analytic derivatives of the
controllers in :mod:`twolink.controllers` (their ``torque_derivatives``
method; finite differences of the torque for any other callable) and returns a :func:`control.ss` system, so poles,
damping ratios, step and frequency responses come from python-control.
:func:`closed_loop_system` gives the nonlinear system as a
:func:`control.nlsys` (its ``.linearize`` is an independent, numerical route).

For impedance control at its rest point with gravity compensated the linear
model is, in tip coordinates, ``Lambda dx'' + D dx' + K dx = F`` with the
tip mass ``Lambda = J^-T M J^-1`` (:func:`tip_mass`); :func:`critical_damping`
chooses ``D`` from it.

python-control is imported inside the functions that need it, so
``import twolink`` stays light.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._optional import require
from ._validate import (
    InputTypeError,
    as_configuration,
    as_finite_scalar,
    require_arm,
    require_callable,
    torque_floats,
)
from .controllers import gain_matrix
from .dynamics import gravity_jacobian
from .kinematics import joint_torques, require_nonsingular

if TYPE_CHECKING:
    from .arm import TwoLinkArm

#: ``controller(t, q, qd) -> tau``, two torques in N m.
Controller = Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]

__all__ = [
    "STATES",
    "INPUTS",
    "OUTPUTS",
    "tip_mass",
    "critical_damping",
    "equilibrium",
    "closed_loop_matrices",
    "linearize",
    "closed_loop_system",
]

#: Names of the state, input and output signals of the systems built here:
#: states ``q1 q2`` (rad) and ``qd1 qd2`` (rad/s); inputs the force acting on
#: the tip, ``Fx_on_tip Fy_on_tip`` (N; a ``force_on_tip``); outputs the tip
#: position ``x y`` (m).
STATES = ("q1", "q2", "qd1", "qd2")
INPUTS = ("Fx_on_tip", "Fy_on_tip")
OUTPUTS = ("x", "y")


def tip_mass(arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
    """The mass felt at the tip, ``Lambda = J^-T M J^-1 = (J M^-1 J^T)^-1``, kg.

    A force ``force_on_tip = F`` on the tip of the arm at rest gives the tip the
    acceleration ``Lambda^-1 F``.  ``Lambda`` is symmetric positive definite
    and depends on the pose: heavy along some directions, light along others.

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        Joint angles in radians, away from singularities.

    Returns
    -------
    numpy.ndarray, shape (2, 2)

    Raises
    ------
    twolink.SingularityError
        At a stretched or folded arm (along the arm the tip cannot move, its
        mass is unbounded).

    Examples
    --------
    Link 1 along x, link 2 straight up from the elbow at ``(1, 0)``, 3 kg
    rods of 1 m.  Across link 2 (along x) only link 2 swings, about the
    elbow: ``(m2 l2^2 / 3) / l2^2 = 1`` kg.  Along link 2 (along y) link 1
    turns (``m1 / 3 = 1`` kg at its end) and carries all of link 2 (3 kg):
    4 kg.

    >>> from twolink import TwoLinkArm
    >>> tip_mass(TwoLinkArm(1.0, 1.0, m1=3.0, m2=3.0, g=0.0), [0.0, np.pi / 2]).round(12) + 0.0
    array([[1., 0.],
           [0., 4.]])
    """
    q = require_nonsingular(arm, as_configuration(q), "the tip mass")
    J = arm.jacobian(q)
    J_inverse = np.linalg.inv(J)
    Lambda = J_inverse.T @ arm.mass_matrix(q) @ J_inverse
    return (Lambda + Lambda.T) / 2.0


_DAMPING_KINDS = ("scalar", "matrix")


def critical_damping(
    arm: TwoLinkArm, q: ArrayLike, stiffness: ArrayLike, kind: str = "scalar"
) -> float | NDArray[np.float64]:
    """Damping that makes the linearised impedance loop at ``q`` critically damped.

    At the rest point (gravity compensated) the loop is
    ``Lambda dx'' + D dx' + K dx = 0`` (``Lambda`` from :func:`tip_mass`).

    - ``kind="scalar"`` (needs ``K = k I``): ``D = d I`` with
      ``d = 2 sqrt(k lambda_max)``, ``lambda_max`` the largest eigenvalue of
      ``Lambda``.  The heavy mode is critically damped, the light one
      overdamped: the smallest scalar damping with no oscillation at all.
    - ``kind="matrix"``: ``D = 2 Lambda^1/2 (Lambda^-1/2 K Lambda^-1/2)^1/2 Lambda^1/2``,
      which makes every mode critically damped (damping ratio 1 in each).

    Parameters
    ----------
    arm : TwoLinkArm
    q : array_like, shape (2,)
        The pose of the rest point, radians.
    stiffness : float or array_like, shape (2, 2)
        ``K`` in N/m.
    kind : {"scalar", "matrix"}

    Returns
    -------
    float or numpy.ndarray, shape (2, 2)
        ``d`` in N s/m (scalar kind) or ``D`` (matrix kind).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm = TwoLinkArm(1.0, 1.0, m1=3.0, m2=3.0, g=0.0)
    >>> round(critical_damping(arm, [0.0, np.pi / 2], 100.0), 9)      # 2 sqrt(100 * 4)
    40.0
    >>> critical_damping(arm, [0.0, np.pi / 2], 100.0, kind="matrix").round(9) + 0.0
    array([[20.,  0.],
           [ 0., 40.]])
    """
    if kind not in _DAMPING_KINDS:
        raise ValueError(f"kind must be one of {_DAMPING_KINDS}; got {kind!r}")
    K = gain_matrix(stiffness, "stiffness K (N/m)")
    Lambda = tip_mass(arm, q)
    if kind == "scalar":
        if not (K[0, 1] == 0.0 and K[0, 0] == K[1, 1]):
            raise ValueError(
                "kind='scalar' needs the same stiffness in every direction (a scalar k, or k I); "
                f"got K = {K.tolist()}: use kind='matrix'"
            )
        return float(2.0 * np.sqrt(K[0, 0] * np.linalg.eigvalsh(Lambda)[-1]))
    import scipy.linalg  # here, not at the top: import twolink stays light

    root = np.real(scipy.linalg.sqrtm(Lambda))
    inverse_root = np.linalg.inv(root)
    omega = np.real(scipy.linalg.sqrtm(inverse_root @ K @ inverse_root))
    D = 2.0 * root @ omega @ root
    return (D + D.T) / 2.0


_CONTROLLER = "a callable controller(t, q, qd) -> tau (two torques, N m)"


def _controller(controller: object) -> Controller:
    return require_callable(controller, "controller", _CONTROLLER)


def _net_torque(
    arm: TwoLinkArm, controller: Controller, t: float, q: NDArray[np.float64]
) -> NDArray[np.float64]:
    try:
        tau = torque_floats(controller(t, q, np.zeros(2)), t)
    except ValueError as error:
        raise ValueError(
            f"the controller {str(error).removeprefix('torque(t, q, qd) ')} at q = {q}"
        ) from None
    return np.array(tau) - arm.gravity(q)


def _name(name: object) -> str | None:
    """A system's ``name``: None or a string (python-control would take anything and print it)."""
    if name is not None and not isinstance(name, str):
        raise InputTypeError(
            f"name must be None or a string (the system's name); got {name!r} ({type(name).__name__})"
        )
    return name


def equilibrium(
    arm: TwoLinkArm,
    controller: Controller,
    q0: ArrayLike,
    t: float = 0.0,
    tol: float = 1e-12,
) -> NDArray[np.float64]:
    """A configuration where the controller holds the arm at rest: ``tau(t, q, 0) = g(q)``.

    Solved with :func:`scipy.optimize.root` from ``q0``.  For impedance
    control without gravity compensation this is where the tip sags to:
    the spring's pull balances the weight.

    Parameters
    ----------
    arm : TwoLinkArm
    controller : callable
        ``controller(t, q, qd) -> tau``.
    q0 : array_like, shape (2,)
        Where to start looking, radians (picks the elbow branch).
    t : float
        Time at which the controller is evaluated.
    tol : float
        Tolerance passed to the root finder.

    Returns
    -------
    numpy.ndarray, shape (2,)

    Raises
    ------
    ValueError
        If the root finder does not converge (no equilibrium near ``q0``).

    Examples
    --------
    >>> from twolink import arms, controllers, ik
    >>> spring = controllers.CartesianSpring(arms.two_metre, 600.0, [3.0, 1.0])
    >>> q_sag = equilibrium(arms.two_metre, spring, ik.closed_form(arms.two_metre, [3.0, 1.0]).q)
    >>> arms.two_metre.fk(q_sag).round(4)      # gravity pulls the tip about 2 cm below the rest point
    array([2.9912, 0.9787])
    """
    require_arm(arm)
    controller = _controller(controller)
    start = as_configuration(q0, "q0")
    t = as_finite_scalar(t, "t (s)")
    tol = as_finite_scalar(tol, "tol", minimum=0.0, strictly=True)
    import scipy.optimize

    solution = scipy.optimize.root(
        lambda q: _net_torque(arm, controller, t, q), start, tol=tol
    )
    if not solution.success:
        raise ValueError(
            f"no equilibrium found near q0 = {start} rad: {solution.message}"
        )
    return solution.x


def _finite_difference(
    function: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x: NDArray[np.float64],
    step: float,
) -> NDArray[np.float64]:
    columns = []
    for index in range(len(x)):
        offset = np.zeros(len(x))
        offset[index] = step * max(1.0, abs(x[index]))
        columns.append(
            (function(x + offset) - function(x - offset)) / (2.0 * offset[index])
        )
    return np.column_stack(columns)


def _torque_derivatives(
    controller: Controller, t: float, q: NDArray[np.float64], step: float = 1e-6
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(dtau/dq, dtau/dqd)`` at ``(q, qd = 0)``: the controller's own ``torque_derivatives``, else central differences."""
    analytic: Any = getattr(controller, "torque_derivatives", None)
    if callable(analytic):
        by_q, by_qd = analytic(t, q)
        return np.asarray(by_q, dtype=float), np.asarray(by_qd, dtype=float)
    zero = np.zeros(2)
    by_q = _finite_difference(
        lambda q_trial: np.asarray(controller(t, q_trial, zero), dtype=float), q, step
    )
    by_qd = _finite_difference(
        lambda qd_trial: np.asarray(controller(t, q, qd_trial), dtype=float), zero, step
    )
    return by_q, by_qd


def closed_loop_matrices(
    arm: TwoLinkArm,
    controller: Controller,
    q_eq: ArrayLike,
    t: float = 0.0,
    tol: float = 1e-6,
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]
]:
    """The matrices ``(A, B, C, D)`` of the closed loop linearised at the equilibrium ``(q_eq, 0)``.

    See the module docstring for the formulas; states ``(q1, q2, qd1, qd2)``,
    inputs the force acting on the tip ``force_on_tip = (Fx, Fy)`` in N
    (``B = [[0], [M^-1 J^T]]``: it adds ``J^T force_on_tip`` to the
    torques), outputs the tip's displacement ``(x, y)`` in m.  Needs no
    python-control.

    Parameters
    ----------
    arm : TwoLinkArm
    controller : callable
        ``controller(t, q, qd) -> tau``.  One with a method
        ``torque_derivatives(t, q) -> (dtau/dq, dtau/dqd)`` at ``qd = 0``
        (the controllers of :mod:`twolink.controllers`) is differentiated
        analytically, any other callable by central differences.
    q_eq : array_like, shape (2,)
        The equilibrium configuration, radians (for example from
        :func:`equilibrium`).
    t : float
        Time at which the controller is evaluated.
    tol : float
        Largest joint acceleration (rad/s^2) accepted at ``(q_eq, 0)``.

    Returns
    -------
    A, B, C, D : numpy.ndarray
        Shapes (4, 4), (4, 2), (2, 4), (2, 2).

    Raises
    ------
    ValueError
        If ``(q_eq, 0)`` is not an equilibrium (the message gives the
        acceleration there).

    Examples
    --------
    A joint PD loop on the horizontal arm is ``qdd = M^-1 (-Kp q - Kd qd)``:

    >>> from twolink import TwoLinkArm, controllers
    >>> arm = TwoLinkArm(2.0, 2.0, g=0.0)
    >>> pd = controllers.JointPD(arm, kp=10.0, kd=2.0, reference=[0.0, 1.0])
    >>> A, B, C, D = closed_loop_matrices(arm, pd, [0.0, 1.0])
    >>> bool(np.allclose(A[2:, :2], -10.0 * np.linalg.inv(arm.mass_matrix([0.0, 1.0]))))
    True
    >>> closed_loop_matrices(arm, pd, [0.0, 0.5])
    Traceback (most recent call last):
    ...
    ValueError: q_eq = (0, 0.5) rad is not an equilibrium of the closed loop: at rest there the arm accelerates at qdd = (-3.83, 12.6) rad/s^2 (tolerance 1e-06); find one with twolink.linearization.equilibrium
    """
    require_arm(arm)
    controller = _controller(controller)
    q_eq = as_configuration(q_eq, "q_eq")
    t = as_finite_scalar(t, "t (s)")
    tol = as_finite_scalar(tol, "tol (rad/s^2)", minimum=0.0)
    M = arm.mass_matrix(q_eq)
    acceleration = np.linalg.solve(M, _net_torque(arm, controller, t, q_eq))
    if np.max(np.abs(acceleration)) > tol:
        raise ValueError(
            f"q_eq = ({q_eq[0]:.6g}, {q_eq[1]:.6g}) rad is not an equilibrium of the closed loop: "
            f"at rest there the arm accelerates at qdd = ({acceleration[0]:.3g}, {acceleration[1]:.3g}) rad/s^2 "
            f"(tolerance {tol:.3g}); find one with twolink.linearization.equilibrium"
        )
    by_q, by_qd = _torque_derivatives(controller, t, q_eq)
    J = arm.jacobian(q_eq)
    A = np.zeros((4, 4))
    A[:2, 2:] = np.eye(2)
    A[2:, :2] = np.linalg.solve(M, by_q - gravity_jacobian(arm, q_eq))
    A[2:, 2:] = np.linalg.solve(M, by_qd)
    B = np.zeros((4, 2))
    B[2:, :] = np.linalg.solve(M, J.T)
    C = np.zeros((2, 4))
    C[:, :2] = J
    return A, B, C, np.zeros((2, 2))


def linearize(
    arm: TwoLinkArm,
    controller: Controller,
    q_eq: ArrayLike,
    t: float = 0.0,
    tol: float = 1e-6,
    name: str | None = None,
) -> Any:
    """The closed loop linearised at ``(q_eq, 0)`` as a python-control state-space system.

    Parameters are those of :func:`closed_loop_matrices`; ``name`` names the
    system (python-control numbers unnamed ones ``sys[k]``).

    Returns
    -------
    control.StateSpace
        States ``q1 q2 qd1 qd2`` (deviations, rad and rad/s), inputs
        ``Fx_on_tip Fy_on_tip`` (the force acting on the tip, N), outputs
        ``x y`` (tip displacement, m).
        ``control.poles``, ``control.damp``, ``control.step_response``,
        ``control.bode_plot`` all apply.

    Examples
    --------
    Impedance control at its rest point, critically damped:

    >>> import control
    >>> from twolink import arms, controllers, ik
    >>> arm = arms.two_metre
    >>> q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    >>> d = critical_damping(arm, q_rest, 600.0)
    >>> loop = linearize(arm, controllers.Impedance(arm, 600.0, d, [3.0, 1.0]), q_rest, name="impedance")
    >>> wn, zeta, poles = control.damp(loop, doprint=False)
    >>> bool(np.all(poles.real < 0)), bool(np.allclose(zeta, 1.0))
    (True, True)
    >>> control.dcgain(loop).round(9) + 0.0     # a steady push F moves the tip by K^-1 F
    array([[0.001667, 0.      ],
           [0.      , 0.001667]])
    """
    control = require("control", "twolink.linearization.linearize")
    name = _name(name)
    A, B, C, D = closed_loop_matrices(arm, controller, q_eq, t=t, tol=tol)
    options: dict[str, Any] = {
        "states": list(STATES),
        "inputs": list(INPUTS),
        "outputs": list(OUTPUTS),
    }
    if name is not None:
        options["name"] = name
    return control.ss(A, B, C, D, **options)


def closed_loop_system(
    arm: TwoLinkArm, controller: Controller, name: str | None = None
) -> Any:
    """The nonlinear closed loop as a python-control :func:`control.nlsys`.

    ``xdot = (qd, M^-1 (tau(t, q, qd) + J^T force_on_tip - C qd - g))``,
    ``y = fk(q)``, with the input ``force_on_tip`` (the force acting on the
    tip) and the same signal names as :func:`linearize`; its
    ``.linearize(x_eq, [0, 0])`` is python-control's own (numerical)
    linearisation, and ``control.input_output_response`` simulates it.

    Examples
    --------
    >>> from twolink import arms, controllers, ik
    >>> arm = arms.two_metre
    >>> q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    >>> impedance = controllers.Impedance(arm, 600.0, 50.0, [3.0, 1.0])
    >>> numerical = closed_loop_system(arm, impedance).linearize(np.concatenate([q_rest, [0.0, 0.0]]), [0.0, 0.0])
    >>> bool(np.allclose(numerical.A, linearize(arm, impedance, q_rest).A, rtol=1e-4, atol=1e-3))
    True
    """
    control = require("control", "twolink.linearization.closed_loop_system")
    require_arm(arm)
    controller = _controller(controller)
    name = _name(name)

    def update(
        t: float,
        state: NDArray[np.float64],
        force_on_tip: NDArray[np.float64],
        params: Any,
    ) -> NDArray[np.float64]:
        q, qd = state[:2], state[2:]
        # J^T force_on_tip, the joint torque of the input force acting on the tip (force_by_tip = -force_on_tip)
        tau = np.asarray(controller(t, q, qd), dtype=float) - joint_torques(
            arm, q, force_by_tip=-force_on_tip
        )
        return np.concatenate([qd, arm.forward_dynamics(q, qd, tau)])

    def output(
        t: float,
        state: NDArray[np.float64],
        force_on_tip: NDArray[np.float64],
        params: Any,
    ) -> NDArray[np.float64]:
        return arm.fk(state[:2])

    options: dict[str, Any] = {
        "states": list(STATES),
        "inputs": list(INPUTS),
        "outputs": list(OUTPUTS),
    }
    if name is not None:
        options["name"] = name
    return control.nlsys(update, output, **options)
