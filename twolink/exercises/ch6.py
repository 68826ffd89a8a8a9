"""Chapter 6 (spring and impedance control): exercises 6.1 to 6.3."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import arms, controllers, ik, linearization
from ..arm import TwoLinkArm
from .registry import (
    Part,
    Wrong,
    close,
    matches,
    numbers,
    reference,
    register,
    scalar,
    usable,
)

CHAPTER = "06_spring_impedance_control"
STIFFNESS_SOURCE, REST_POINT = 600.0, (3.0, 1.0)  # N/m, m: the source's spring
K_6_1, TIP_6_1 = ((600.0, 0.0), (0.0, 200.0)), (3.0, 0.5)
SAG_LIMIT_6_3 = 0.005  # m


def _arm() -> TwoLinkArm:
    return arms.two_metre


@reference
def q_rest() -> NDArray[np.float64]:
    """The 2 m arm's elbow-down configuration with the tip at the rest point (3, 1)."""
    return ik.closed_form(_arm(), REST_POINT, elbow="down").q


@reference
def torques_6_1() -> NDArray[np.float64]:
    """The anisotropic spring's joint torques with the tip held at (3, 0.5), elbow up."""
    spring = controllers.CartesianSpring(_arm(), np.array(K_6_1), np.array(REST_POINT))
    return spring.torque(ik.closed_form(_arm(), TIP_6_1, elbow="up").q)


def judge_torques_6_1(answer: object, siblings: dict[str, object]) -> None:
    tau = numbers(answer, (2,))
    spring = controllers.CartesianSpring(_arm(), np.array(K_6_1), np.array(REST_POINT))
    if matches(
        close,
        tau,
        spring.torque(ik.closed_form(_arm(), TIP_6_1, elbow="down").q),
        atol=1e-6,
    ):
        raise Wrong("these are the torques on the elbow-down branch (q2 > 0)")
    if matches(close, tau, -torques_6_1(), atol=1e-6):
        raise Wrong(
            "the sign is reversed: the spring pulls the tip towards the rest point, F = K (x0 - x)"
        )
    close(tau, torques_6_1(), atol=1e-6)


@reference
def damping_6_2() -> NDArray[np.float64]:
    """The damping matrix that makes every mode of the loop at (3, 1) critically damped."""
    return np.asarray(
        linearization.critical_damping(
            _arm(), q_rest(), STIFFNESS_SOURCE, kind="matrix"
        ),
        dtype=float,
    )


@reference
def poles_6_2() -> NDArray[np.float64]:
    """Each mode of the tip (omega^2 an eigenvalue of k Lambda^-1) a double pole at -omega, sorted."""
    omega = np.sqrt(
        np.linalg.eigvalsh(
            STIFFNESS_SOURCE * np.linalg.inv(linearization.tip_mass(_arm(), q_rest()))
        )
    )
    return np.sort(np.repeat(-omega, 2))


def judge_damping_6_2(answer: object, siblings: dict[str, object]) -> None:
    D = numbers(answer, (2, 2))
    if matches(
        close,
        D,
        linearization.critical_damping(_arm(), q_rest(), STIFFNESS_SOURCE) * np.eye(2),
        atol=1e-6,
    ):
        raise Wrong(
            "this is the scalar critical damping times the identity: the light mode is then overdamped"
        )
    close(D, damping_6_2(), atol=1e-6)


def judge_poles_6_2(answer: object, siblings: dict[str, object]) -> None:
    try:
        values = np.asarray(answer, dtype=complex).ravel()
    except (TypeError, ValueError):
        raise Wrong(
            f"expected four poles (numbers), got a {type(answer).__name__}"
        ) from None
    if values.shape != (4,):
        raise Wrong(
            f"expected four poles (the loop has four states), got {values.size}"
        )
    if not np.all(np.isfinite(values)):
        raise Wrong("your poles contain nan or inf")
    if np.max(np.abs(values.imag)) >= 1e-3:
        raise Wrong(
            "some poles are complex: that loop oscillates, it is not critically damped"
        )
    close(np.sort(values.real), poles_6_2(), atol=1e-3)


def judge_ratios_6_2(answer: object, siblings: dict[str, object]) -> None:
    zeta = numbers(answer, (4,))
    if np.allclose(np.sort(zeta), np.sort(np.abs(poles_6_2())), atol=1e-3):
        raise Wrong(
            "these are the natural frequencies wn, control.damp's first output; zeta is the second"
        )
    close(zeta, np.ones(4), atol=1e-6)
    poles = usable(
        siblings, "poles_ex2", lambda value: np.asarray(value, dtype=complex).reshape(4)
    )
    if poles is not None and np.all(np.isfinite(poles)) and np.all(np.abs(poles) > 0):
        if not np.allclose(
            np.sort(zeta), np.sort(-poles.real / np.abs(poles)), atol=1e-6
        ):
            raise Wrong("these are not the damping ratios of your poles, -Re(p) / |p|")


def sag_6_3(stiffness_value: float) -> float:
    """How far (m) the vertical arm's tip rests from (3, 1) under a scalar spring without gravity compensation."""
    controller = controllers.Impedance(
        _arm(), stiffness_value, 0.0, np.array(REST_POINT), gravity_compensation=False
    )
    return float(
        np.linalg.norm(
            _arm().fk(linearization.equilibrium(_arm(), controller, q_rest()))
            - REST_POINT
        )
    )


def judge_stiffness_6_3(answer: object, siblings: dict[str, object]) -> None:
    k = scalar(answer)
    if k <= 0:
        raise Wrong("a stiffness is positive")
    sag = sag_6_3(k)
    if sag > SAG_LIMIT_6_3 + 1e-9:
        raise Wrong(
            f"with k = {k:.6g} N/m the tip rests {1000 * sag:.3g} mm from (3, 1), more than 5 mm"
        )
    if sag_6_3(0.99 * k) <= SAG_LIMIT_6_3:
        raise Wrong(
            "not the smallest: a 1 % softer spring also keeps the sag within 5 mm"
        )


register(
    "6.1",
    Part(
        "tau_ex1",
        "torques",
        judge_torques_6_1,
        "F = K (x0 - x) at the held tip; tau = J^T F on the elbow-up branch (q2 < 0)",
    ),
    chapter=CHAPTER,
)
register(
    "6.2",
    Part(
        "D_ex2",
        "damping matrix",
        judge_damping_6_2,
        "D = 2 Lambda^1/2 Omega Lambda^1/2 with Omega = (k Lambda^-1)^1/2",
    ),
    Part(
        "poles_ex2",
        "poles",
        judge_poles_6_2,
        "control.poles(linearization.linearize(arm, controller, q_rest)) with your D_ex2 in "
        "controllers.Impedance: four real poles, two double ones",
    ),
    Part(
        "zeta_ex2",
        "damping ratios",
        judge_ratios_6_2,
        "control.damp(loop, doprint=False)[1]: zeta = -Re(p) / |p| for each of your poles; all four should be 1",
    ),
    chapter=CHAPTER,
)
register(
    "6.3",
    Part(
        "k_ex3",
        "stiffness",
        judge_stiffness_6_3,
        "the sag shrinks like 1/k: find where it equals 5 mm",
    ),
    chapter=CHAPTER,
)
