"""Equations of motion of the planar 2R arm by Euler-Lagrange, in sympy.

Two models of the same machine:

``"relative"``
    The DH model: coordinates ``(q1, q2)`` with ``q2`` measured from link 1;
    motor 1 on the ground turns link 1, motor 2 sits at the elbow on link 1
    and turns link 2 relative to link 1 (its reaction acts on link 1).
``"absolute"``
    Coordinates ``(theta1, theta2)``, both link angles measured from the
    x-axis; motor 1 turns link 1 and motor 2 sits *on the ground* and drives
    link 2 through a belt or parallel linkage (1:1), so its reaction acts on
    the ground.

Both links are uniform rods: centres of mass at mid-link, inertias ``I1``,
``I2`` about the centres (``m l**2 / 12`` for a rod; kept as symbols so that
an arm's override can be used).  Gravity ``g`` acts along ``-y`` in the
arm's plane.  The derivation returns

    ``M(q) qdd + C(q, qd) qd + g(q) = Q``

with ``Q`` the generalised forces of the motor torques, found by virtual
work, and ``C`` built from the Christoffel symbols of ``M`` (so that
``dM/dt - 2 C`` is skew-symmetric).

sympy has no type information: its names (``sp.Symbol``, ``sp.Matrix``,
``sp.Expr``) are ``Any`` to a type checker, and the annotations here say
what is meant.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np
import sympy as sp
from numpy.typing import ArrayLike, NDArray

from .._validate import as_configuration, is_real_number, require_arm
from .._values import Value
from ..errors import InputTypeError
from .kinematics import planar_symbols

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = [
    "dynamics_symbols",
    "EquationsOfMotion",
    "equations_of_motion",
    "christoffel_coriolis",
    "time_derivative",
    "NumericDynamics",
    "lambdify_dynamics",
]

MODELS = ("relative", "absolute")


def dynamics_symbols() -> dict[str, sp.Symbol]:
    """The symbols of the dynamics: coordinates, rates, parameters and torques.

    Builds on :func:`twolink.symbolic.planar_symbols` (``q1, q2, l1, l2``).

    Returns
    -------
    dict
        Keys ``q1 q2 qd1 qd2 qdd1 qdd2`` (relative coordinates and their
        derivatives), ``theta1 theta2 thetad1 thetad2 thetadd1 thetadd2``
        (absolute link angles), ``l1 l2 m1 m2 I1 I2 g`` (parameters),
        ``tau1 tau2`` (DH motor torques) and ``u1 u2`` (torques of the
        belt-driven arm's motors, both on the ground).  Names render as
        LaTeX with dots (``\\dot{q}_{1}``).

    Examples
    --------
    >>> symbols = dynamics_symbols()
    >>> symbols["qd1"], symbols["m2"].is_nonnegative
    (\\dot{q}_{1}, True)
    """
    symbols = dict(planar_symbols())
    del symbols["d"]
    real = {"real": True}
    symbols.update(
        {
            "qd1": sp.Symbol(r"\dot{q}_{1}", **real),
            "qd2": sp.Symbol(r"\dot{q}_{2}", **real),
            "qdd1": sp.Symbol(r"\ddot{q}_{1}", **real),
            "qdd2": sp.Symbol(r"\ddot{q}_{2}", **real),
            "theta1": sp.Symbol(r"\theta_{1}", **real),
            "theta2": sp.Symbol(r"\theta_{2}", **real),
            "thetad1": sp.Symbol(r"\dot{\theta}_{1}", **real),
            "thetad2": sp.Symbol(r"\dot{\theta}_{2}", **real),
            "thetadd1": sp.Symbol(r"\ddot{\theta}_{1}", **real),
            "thetadd2": sp.Symbol(r"\ddot{\theta}_{2}", **real),
            "m1": sp.Symbol("m1", nonnegative=True),
            "m2": sp.Symbol("m2", nonnegative=True),
            "I1": sp.Symbol("I1", nonnegative=True),
            "I2": sp.Symbol("I2", nonnegative=True),
            "g": sp.Symbol("g", real=True),
            "tau1": sp.Symbol(r"\tau_{1}", **real),
            "tau2": sp.Symbol(r"\tau_{2}", **real),
            "u1": sp.Symbol("u1", **real),
            "u2": sp.Symbol("u2", **real),
        }
    )
    return symbols


def _expression(value: object, name: str) -> sp.Expr | sp.MatrixBase:
    """``value`` as a sympy expression (or matrix of them): an expression or a real number, never a string (sympy would parse it)."""
    if isinstance(value, (sp.Expr, sp.MatrixBase)):
        return value
    if is_real_number(value) and math.isfinite(float(value)):  # type: ignore[arg-type]
        return sp.sympify(value, strict=True)
    raise InputTypeError(
        f"{name} must be a sympy expression (or a finite real number); got {value!r} ({type(value).__name__})"
    )


def _symbols(values: object, name: str, count: int | None = None) -> list[sp.Symbol]:
    """``values`` as a list of sympy symbols (``count`` of them when given), or an error naming ``name``.

    A list, a tuple or a sympy vector (``Matrix([q1, q2])``) of symbols.
    """
    if not isinstance(values, (list, tuple, sp.MatrixBase)) or not all(
        isinstance(value, sp.Symbol) for value in values
    ):
        raise InputTypeError(
            f"{name} must be a list, tuple or sympy vector of sympy symbols; got {values!r} ({type(values).__name__})"
        )
    if count is not None and len(values) != count:
        raise ValueError(
            f"{name} must hold one symbol per coordinate, {count}; got {len(values)}"
        )
    return list(values)


def time_derivative(
    expr: sp.Expr,
    coordinates: Sequence[sp.Symbol],
    rates: Sequence[sp.Symbol],
    accelerations: Sequence[sp.Symbol],
) -> sp.Expr:
    """Total time derivative of ``expr(q, qd)`` by the chain rule.

    ``d/dt f = sum_j (df/dq_j qd_j + df/dqd_j qdd_j)``: what Euler-Lagrange
    needs, without turning the coordinates into functions of time.

    Parameters
    ----------
    expr : sympy expression
        A function of the coordinates and rates.
    coordinates, rates, accelerations : sequence of sympy.Symbol
        ``q_j``, ``qd_j`` and ``qdd_j``, in the same order.

    Returns
    -------
    sympy expression

    Examples
    --------
    >>> x, v, a = sp.symbols("x v a")
    >>> time_derivative(x**2 * v, [x], [v], [a])
    a*x**2 + 2*v**2*x
    >>> time_derivative(x, [x], "v", [a])
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: rates must be a list, tuple or sympy vector of sympy symbols; got 'v' (str)
    """
    expr = _expression(expr, "expr")
    coordinates = _symbols(coordinates, "coordinates")
    rates = _symbols(rates, "rates", len(coordinates))
    accelerations = _symbols(accelerations, "accelerations", len(coordinates))
    return sum(
        sp.diff(expr, coordinate) * rate + sp.diff(expr, rate) * acceleration
        for coordinate, rate, acceleration in zip(coordinates, rates, accelerations)
    )


def christoffel_coriolis(
    M: sp.Matrix, coordinates: Sequence[sp.Symbol], rates: Sequence[sp.Symbol]
) -> sp.Matrix:
    """The Coriolis/centrifugal matrix from the Christoffel symbols of ``M``.

    ``C[i, j] = sum_k Gamma_ijk qd_k`` with
    ``Gamma_ijk = (dM_ij/dq_k + dM_ik/dq_j - dM_jk/dq_i) / 2``.  Many matrices
    give the same vector ``C qd``; this one makes ``dM/dt - 2 C``
    skew-symmetric (the passivity property controllers rely on).

    Parameters
    ----------
    M : sympy.Matrix, shape (n, n)
        The mass matrix, a function of the coordinates.
    coordinates, rates : sequence of sympy.Symbol
        ``q_k`` and ``qd_k``, ``n`` of each.

    Returns
    -------
    sympy.Matrix, shape (n, n)
        ``C``, simplified.

    Examples
    --------
    >>> q, qd = sp.symbols("q qd")
    >>> christoffel_coriolis(sp.Matrix([[2 + sp.cos(q)]]), [q], [qd])
    Matrix([[-qd*sin(q)/2]])
    """
    coordinates = _symbols(coordinates, "coordinates")
    rates = _symbols(rates, "rates", len(coordinates))
    size = len(coordinates)
    if not isinstance(M, sp.MatrixBase) or M.shape != (size, size):
        raise InputTypeError(
            f"M must be a sympy matrix of shape ({size}, {size}), one row and column per coordinate; "
            f"got {M!r} ({type(M).__name__})"
        )
    C = sp.zeros(size, size)
    for i in range(size):
        for j in range(size):
            C[i, j] = sum(
                sp.Rational(1, 2)
                * (
                    sp.diff(M[i, j], coordinates[k])
                    + sp.diff(M[i, k], coordinates[j])
                    - sp.diff(M[j, k], coordinates[i])
                )
                * rates[k]
                for k in range(size)
            )
    return sp.simplify(C)


@dataclass(frozen=True)
class EquationsOfMotion:
    """``M(q) qdd + C(q, qd) qd + g(q) = Q`` of one model, with what it came from.

    All matrices are immutable sympy matrices (safe to share).

    Attributes
    ----------
    model : str
        ``"relative"`` or ``"absolute"``.
    q, qd, qdd : sympy.ImmutableMatrix, shape (2, 1)
        Generalised coordinates, rates and accelerations.
    kinetic, potential, lagrangian : sympy.Expr
        ``T``, ``V`` and ``L = T - V``.
    euler_lagrange : sympy.ImmutableMatrix, shape (2, 1)
        ``d/dt dL/dqd - dL/dq`` as derived, before sorting into M, C, g.
    M, C, g : sympy.ImmutableMatrix
        Mass matrix (2x2), Coriolis/centrifugal matrix (2x2, Christoffel
        form) and gravity vector (2x1).
    torques : sympy.ImmutableMatrix, shape (2, 1)
        The motor torques (``tau1, tau2`` for the DH arm, ``u1, u2`` for the
        arm whose motor 2 is on the ground).
    Q : sympy.ImmutableMatrix, shape (2, 1)
        Generalised forces of the motor torques, by virtual work.
    parameters : tuple of sympy.Symbol
        ``(l1, l2, m1, m2, I1, I2, g)``.
    """

    model: str
    q: sp.ImmutableMatrix
    qd: sp.ImmutableMatrix
    qdd: sp.ImmutableMatrix
    kinetic: sp.Expr
    potential: sp.Expr
    lagrangian: sp.Expr
    euler_lagrange: sp.ImmutableMatrix
    M: sp.ImmutableMatrix
    C: sp.ImmutableMatrix
    g: sp.ImmutableMatrix
    torques: sp.ImmutableMatrix
    Q: sp.ImmutableMatrix
    parameters: tuple[sp.Symbol, ...]

    def residual(self) -> sp.Matrix:
        """``M qdd + C qd + g - (d/dt dL/dqd - dL/dq)``, simplified: zero when M, C, g are right.

        Examples
        --------
        >>> equations_of_motion("relative").residual()
        Matrix([
        [0],
        [0]])
        """
        return sp.simplify(
            sp.expand(
                self.M * self.qdd + self.C * self.qd + self.g - self.euler_lagrange
            )
        )


def equations_of_motion(model: str = "relative") -> EquationsOfMotion:
    """Derive the equations of motion of the 2R arm by Euler-Lagrange.

    Kinetic energy ``T = sum_i (m_i |v_ci|^2 + I_i w_i^2) / 2`` with ``v_ci``
    the velocity of the centre of mass of link ``i`` and ``w_i`` its
    *absolute* angular velocity (``qd1 + qd2`` for link 2 in the DH model);
    potential energy ``V = g (m1 y_c1 + m2 y_c2)``.  Then
    ``M = d^2 T / dqd^2``, ``g = dV/dq``, ``C`` from the Christoffel symbols
    of ``M``, and ``Q`` from the virtual work of the motor torques.

    The result is cached (the function is pure and the matrices immutable).

    Parameters
    ----------
    model : {"relative", "absolute"}
        DH coordinates with the elbow motor on link 1, or absolute link
        angles with motor 2 on the ground (belt drive).

    Returns
    -------
    EquationsOfMotion

    Raises
    ------
    ValueError
        For an unknown model.

    Examples
    --------
    >>> eom = equations_of_motion("relative")
    >>> eom.M[1, 1]
    I2 + l2**2*m2/4
    >>> eom.Q.T
    Matrix([[\\tau_{1}, \\tau_{2}]])
    >>> equations_of_motion("absolute").Q.T
    Matrix([[u1, u2]])
    """
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}; got {model!r}")
    return _derived_equations(model)


@cache
def _derived_equations(model: str) -> EquationsOfMotion:
    """:func:`equations_of_motion` of a checked model name, derived once (the result is immutable)."""
    s = dynamics_symbols()
    l1, l2, m1, m2, I1, I2, g = (
        s[name] for name in ("l1", "l2", "m1", "m2", "I1", "I2", "g")
    )
    if model == "relative":
        q = [s["q1"], s["q2"]]
        qd = [s["qd1"], s["qd2"]]
        qdd = [s["qdd1"], s["qdd2"]]
        link_angles = [q[0], q[0] + q[1]]
        torques = [s["tau1"], s["tau2"]]
        # Motor 1 turns link 1 against the ground; motor 2 turns link 2
        # against link 1, so it does work on the relative angle.
        work = torques[0] * link_angles[0] + torques[1] * (
            link_angles[1] - link_angles[0]
        )
    else:
        q = [s["theta1"], s["theta2"]]
        qd = [s["thetad1"], s["thetad2"]]
        qdd = [s["thetadd1"], s["thetadd2"]]
        link_angles = list(q)
        torques = [s["u1"], s["u2"]]
        # Both motors sit on the ground: each does work on its link's absolute angle.
        work = torques[0] * link_angles[0] + torques[1] * link_angles[1]

    elbow = sp.Matrix([l1 * sp.cos(link_angles[0]), l1 * sp.sin(link_angles[0])])
    centre_1 = elbow / 2
    centre_2 = (
        elbow
        + sp.Matrix([l2 * sp.cos(link_angles[1]), l2 * sp.sin(link_angles[1])]) / 2
    )
    rates = sp.Matrix(qd)
    v_c1 = centre_1.jacobian(q) * rates
    v_c2 = centre_2.jacobian(q) * rates
    omega = [
        sum(sp.diff(angle, coordinate) * rate for coordinate, rate in zip(q, qd))
        for angle in link_angles
    ]
    kinetic = sp.trigsimp(
        sp.expand(
            (
                m1 * v_c1.dot(v_c1)
                + I1 * omega[0] ** 2
                + m2 * v_c2.dot(v_c2)
                + I2 * omega[1] ** 2
            )
            / 2
        )
    )
    potential = g * (m1 * centre_1[1] + m2 * centre_2[1])
    lagrangian = kinetic - potential

    euler_lagrange = sp.Matrix(
        [
            time_derivative(sp.diff(lagrangian, rate), q, qd, qdd)
            - sp.diff(lagrangian, coordinate)
            for coordinate, rate in zip(q, qd)
        ]
    )
    M = sp.simplify(sp.hessian(kinetic, qd))
    gravity = sp.Matrix([sp.diff(potential, coordinate) for coordinate in q])
    C = christoffel_coriolis(M, q, qd)
    generalised_forces = sp.Matrix([sp.diff(work, coordinate) for coordinate in q])
    return EquationsOfMotion(
        model=model,
        q=sp.ImmutableMatrix(q),
        qd=sp.ImmutableMatrix(qd),
        qdd=sp.ImmutableMatrix(qdd),
        kinetic=kinetic,
        potential=potential,
        lagrangian=lagrangian,
        euler_lagrange=sp.ImmutableMatrix(euler_lagrange),
        M=sp.ImmutableMatrix(M),
        C=sp.ImmutableMatrix(C),
        g=sp.ImmutableMatrix(gravity),
        torques=sp.ImmutableMatrix(torques),
        Q=sp.ImmutableMatrix(generalised_forces),
        parameters=(l1, l2, m1, m2, I1, I2, g),
    )


@dataclass(frozen=True, eq=False)
class NumericDynamics(Value):
    """Numeric ``M``, ``C`` and ``g`` lambdified from an :class:`EquationsOfMotion`.

    Each function evaluates one state (``q``, ``qd`` of shape ``(2,)``, in the
    model's own coordinates) with the parameters of a
    :class:`~twolink.TwoLinkArm` (``l1, l2, m1, m2, arm.inertias, g``).
    Made by :func:`lambdify_dynamics`; an independent reference for the
    hand-written numeric code in :mod:`twolink.dynamics`.
    """

    model: str
    _mass_matrix: Callable[..., Any] = field(compare=False, repr=False)
    _coriolis: Callable[..., Any] = field(compare=False, repr=False)
    _gravity: Callable[..., Any] = field(compare=False, repr=False)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickled as its model's name: lambdified functions do not pickle, and follow from it."""
        return lambdify_dynamics, (self.model,)

    @staticmethod
    def _parameters(arm: TwoLinkArm) -> tuple[float, ...]:
        inertia_1, inertia_2 = require_arm(arm).inertias
        return (arm.l1, arm.l2, arm.m1, arm.m2, inertia_1, inertia_2, arm.g)

    def mass_matrix(self, arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
        """``M(q)``, shape (2, 2), for one configuration ``q`` of shape (2,)."""
        return np.asarray(
            self._mass_matrix(*as_configuration(q, "q"), *self._parameters(arm)),
            dtype=np.float64,
        )

    def coriolis(
        self, arm: TwoLinkArm, q: ArrayLike, qd: ArrayLike
    ) -> NDArray[np.float64]:
        """``C(q, qd)``, shape (2, 2), for one state (``q``, ``qd`` of shape (2,))."""
        return np.asarray(
            self._coriolis(
                *as_configuration(q, "q"),
                *as_configuration(
                    qd, "qd", what="one pair of joint rates", unit="rad/s"
                ),
                *self._parameters(arm),
            ),
            dtype=np.float64,
        )

    def gravity(self, arm: TwoLinkArm, q: ArrayLike) -> NDArray[np.float64]:
        """``g(q)``, shape (2,), for one configuration ``q`` of shape (2,)."""
        return np.asarray(
            self._gravity(*as_configuration(q, "q"), *self._parameters(arm)),
            dtype=np.float64,
        ).reshape(2)


def lambdify_dynamics(equations: EquationsOfMotion | str) -> NumericDynamics:
    """Turn derived equations of motion into numeric functions (numpy).

    Parameters
    ----------
    equations : EquationsOfMotion or str
        The derivation, or a model name passed to :func:`equations_of_motion`.

    Returns
    -------
    NumericDynamics

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> numeric = lambdify_dynamics("relative")
    >>> arm = TwoLinkArm(2.0, 2.0, m1=3.0, m2=3.0, g=0.0)
    >>> numeric.mass_matrix(arm, [0.0, 0.0])
    array([[32., 10.],
           [10.,  4.]])
    """
    if isinstance(equations, str):
        if equations not in MODELS:
            raise ValueError(
                f"equations must be an EquationsOfMotion or a model name, one of {MODELS}; got {equations!r}"
            )
        equations = equations_of_motion(equations)
    elif not isinstance(equations, EquationsOfMotion):
        raise InputTypeError(
            "equations must be a model name ('relative' or 'absolute') or an EquationsOfMotion; "
            f"got {equations!r} ({type(equations).__name__})"
        )
    q, qd, parameters = (
        list(equations.q),
        list(equations.qd),
        list(equations.parameters),
    )
    return NumericDynamics(
        model=equations.model,
        _mass_matrix=sp.lambdify(q + parameters, equations.M, modules="numpy"),
        _coriolis=sp.lambdify(q + qd + parameters, equations.C, modules="numpy"),
        _gravity=sp.lambdify(q + parameters, equations.g, modules="numpy"),
    )
