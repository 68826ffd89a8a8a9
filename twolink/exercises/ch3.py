"""Chapter 3 (Jacobian and velocity): exercises 3.1 to 3.3."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import arms
from ..arm import TwoLinkArm
from ..sources import compsys726
from .registry import (
    Part,
    Wrong,
    angles_close,
    close,
    matches,
    numbers,
    reference,
    register,
    scalar,
)

CHAPTER = "03_jacobian_velocity"
Q_3_1_DEG = (20.0, 70.0)
V_TIP_3_1 = (0.0, 0.2)  # m/s, straight up
Q2_3_2_DEG, RATE_3_2_DEG_S = 90.0, 5.0
ANGLE_TOLERANCE_DEG_3_3 = 0.5


@reference
def rates_3_1() -> NDArray[np.float64]:
    """Joint rates of the 2 m arm at (20, 70) deg for a tip moving up at 0.2 m/s."""
    return arms.two_metre.joint_rates(np.radians(Q_3_1_DEG), V_TIP_3_1)


def judge_rates_3_1(answer: object, siblings: dict[str, object]) -> None:
    qd = numbers(answer, (2,))
    J = arms.two_metre.jacobian(np.radians(Q_3_1_DEG))
    if matches(close, qd, J.T @ np.asarray(V_TIP_3_1), atol=1e-9):
        raise Wrong("this is J^T v; the joint rates solve J qd = v (J^-1 v)")
    close(qd, rates_3_1(), atol=1e-9)


@reference
def speed_3_2() -> float:
    """Tip speed (m/s) of the OSAKE arm, q2 = 90 deg held, joint 1 at 5 deg/s."""
    velocity = arms.osake.tip_velocity(
        np.radians([0.0, Q2_3_2_DEG]), np.radians([RATE_3_2_DEG_S, 0.0])
    )
    return float(np.linalg.norm(velocity))


def judge_speed_3_2(answer: object, siblings: dict[str, object]) -> None:
    speed = scalar(answer)
    if matches(close, speed, np.degrees(speed_3_2()), rtol=1e-9):
        raise Wrong("this is r times 5 with omega left in deg/s: convert to rad/s")
    close(speed, speed_3_2(), atol=1e-9)


def arm_3_3() -> TwoLinkArm:
    """The table's arm of chapter 3 (COMPSYS726, in metres)."""
    return TwoLinkArm(l1=compsys726.A1 / 100, l2=compsys726.A2 / 100)


def condition_3_3(q2: ArrayLike) -> NDArray[np.float64]:
    """Condition number sigma_max / sigma_min of J at elbow angle(s) ``q2`` (rad); it depends on q2 only."""
    arm = arm_3_3()
    q2 = np.atleast_1d(np.asarray(q2, dtype=float))
    return np.linalg.cond(arm.jacobian(np.stack([np.zeros_like(q2), q2], axis=-1)))


@reference
def roundest_3_3() -> float:
    """The elbow angle (rad, in (0, pi)) of the roundest velocity ellipse: cos q2 = -2 l1 l2 / (l1^2 + 2 l2^2)."""
    arm = arm_3_3()
    return float(np.arccos(-2 * arm.l1 * arm.l2 / (arm.l1**2 + 2 * arm.l2**2)))


def judge_angle_3_3(answer: object, siblings: dict[str, object]) -> None:
    q2_deg = scalar(answer)
    best_deg = np.degrees(roundest_3_3())
    if matches(close, q2_deg, roundest_3_3(), atol=np.radians(ANGLE_TOLERANCE_DEG_3_3)):
        raise Wrong("this is in radians; the task asks for degrees")
    if matches(angles_close, q2_deg, 90.0, atol=ANGLE_TOLERANCE_DEG_3_3, period=360.0):
        raise Wrong("90 deg gives the largest manipulability, not the roundest ellipse")
    slack = ANGLE_TOLERANCE_DEG_3_3 * (1 + 1e-9)
    if not matches(
        angles_close, q2_deg, -best_deg, atol=slack, period=360.0
    ):  # the mirror elbow is as round
        angles_close(q2_deg, best_deg, atol=slack, period=360.0)


@reference
def condition_best_3_3() -> tuple[float, float]:
    """The smallest condition number, and what an angle within the tolerance can give."""
    best = float(condition_3_3(roundest_3_3())[0])
    offsets = np.radians(ANGLE_TOLERANCE_DEG_3_3) * np.array([-1.0, 1.0]) * (1 + 1e-9)
    slack = float(np.max(condition_3_3(roundest_3_3() + offsets)) - best)
    return best, slack + 1e-9


def judge_condition_3_3(answer: object, siblings: dict[str, object]) -> None:
    value = scalar(answer)
    best, slack = condition_best_3_3()
    if matches(close, value, 1.0 / best, atol=slack):
        raise Wrong(
            "this is sigma_min / sigma_max; the condition number is sigma_max / sigma_min (>= 1)"
        )
    if matches(close, value, best**2, atol=4 * slack):
        raise Wrong("this is the condition number of J J^T, the square of J's")
    close(value, best, atol=slack)


register(
    "3.1",
    Part(
        "qd_ex1",
        "joint rates",
        judge_rates_3_1,
        "solve J(q) qd = (0, 0.2); angles in radians",
    ),
    chapter=CHAPTER,
)
register(
    "3.2",
    Part(
        "tip_speed_ex2",
        "tip speed",
        judge_speed_3_2,
        "speed = r * omega with r = |p| and omega in rad/s",
    ),
    chapter=CHAPTER,
)
register(
    "3.3",
    Part(
        "q2_best_deg_ex3",
        "angle",
        judge_angle_3_3,
        "np.linalg.cond(arm_line.jacobian(q)) depends on q2 only; scan q2 in degrees with a step of at most 1 deg",
    ),
    Part(
        "cond_best_ex3",
        "condition number",
        judge_condition_3_3,
        "the smallest sigma_max / sigma_min over your scan (np.linalg.cond of J)",
    ),
    chapter=CHAPTER,
)
