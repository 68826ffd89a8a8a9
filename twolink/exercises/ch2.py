"""Chapter 2 (inverse kinematics): exercises 2.1 to 2.3."""

from __future__ import annotations

import numpy as np

from .. import arms, ik
from ..conventions import wrap_angle
from ..errors import UnreachableError
from ..ik.grid_search import grid_axis
from .registry import (
    Part,
    Wrong,
    boolean,
    close,
    matches,
    numbers,
    reference,
    register,
    scalar,
)

CHAPTER = "02_inverse_kinematics"
TARGET_2_1 = (12.0, 4.0)
ERROR_BOUND_2_2 = 0.01  # m
Q1_RANGE_DEG_2_2, Q2_RANGE_DEG_2_2 = (0.0, 90.0), (-90.0, 90.0)
TARGET_2_3 = (15.0, 16.0)


def judge_elbow_up_2_1(answer: object, siblings: dict[str, object]) -> None:
    q = numbers(answer, (2,))
    if np.allclose(arms.ten.fk(np.radians(q)), TARGET_2_1, atol=1e-6):
        raise Wrong("these are degrees; the answer is in radians")
    miss = float(np.linalg.norm(arms.ten.fk(q) - TARGET_2_1))
    if miss > 1e-9:
        raise Wrong(f"the tip lands {miss:.3g} m from the target (12, 4)")
    if wrap_angle(q[1]) > 0:
        raise Wrong("this is the elbow-down solution (q2 > 0)")


@reference
def within_limits_2_1() -> bool:
    """Whether the elbow-up solution for (12, 4) respects arms.ten's limits."""
    return bool(
        arms.ten.within_limits(ik.closed_form(arms.ten, TARGET_2_1, elbow="up").q)
    )


def judge_limits_2_1(answer: object, siblings: dict[str, object]) -> None:
    if boolean(answer) != within_limits_2_1():
        raise Wrong(
            f"the elbow-up solution is {'within' if within_limits_2_1() else 'outside'} the limits"
        )


@reference
def step_2_2() -> float:
    """The grid step (rad) that makes (a1 + 2 a2) step / 2 equal 1 cm."""
    return 2 * ERROR_BOUND_2_2 / (arms.ten.l1 + 2 * arms.ten.l2)


@reference
def grid_counts_2_2() -> tuple[int, int]:
    """Points along each joint's axis at that step (ik.brute_force's grid, both ends of each range on it)."""
    step = step_2_2()
    (q1_low, q1_high), (q2_low, q2_high) = (
        np.radians(Q1_RANGE_DEG_2_2),
        np.radians(Q2_RANGE_DEG_2_2),
    )
    return len(grid_axis(q1_low, q1_high, step)), len(grid_axis(q2_low, q2_high, step))


def judge_step_2_2(answer: object, siblings: dict[str, object]) -> None:
    step_deg = scalar(answer)
    if matches(close, step_deg, step_2_2(), rtol=1e-9):
        raise Wrong("this is the step in radians; the task asks for degrees")
    close(step_deg, np.degrees(step_2_2()), rtol=1e-9)


def judge_points_2_2(answer: object, siblings: dict[str, object]) -> None:
    points = scalar(answer)
    if abs(points - round(points)) > 1e-6:
        raise Wrong(
            f"{points:.6g} is not a whole number of grid points: count points, not range / step"
        )
    count_1, count_2 = grid_counts_2_2()
    if round(points) == (count_1 - 1) * (count_2 - 1):
        raise Wrong(
            "one point short on each axis: the grid holds both ends of each range "
            "(its last spacing is shorter when the range is not a whole number of steps)"
        )
    if round(points) == (count_1 - 2) * (count_2 - 2):
        raise Wrong(
            "two points short on each axis: floor(range / step) counts steps, not points, "
            "and the grid holds both ends of each range"
        )
    if round(points) != count_1 * count_2:
        raise Wrong(
            f"not the grid's size (off by {abs(round(points) - count_1 * count_2)} points)"
        )


@reference
def message_2_3() -> str:
    """The message of the UnreachableError for (15, 16) on arms.ten."""
    try:
        ik.closed_form(arms.ten, TARGET_2_3)
    except UnreachableError as error:
        return str(error)
    raise AssertionError("(15, 16) should be out of reach of arms.ten")


def judge_message_2_3(answer: object, siblings: dict[str, object]) -> None:
    if isinstance(answer, BaseException):
        raise Wrong(
            f"this is the {type(answer).__name__} itself; keep its message, str(error)"
        )
    if not isinstance(answer, str):
        raise Wrong(f"expected the message (a str), got a {type(answer).__name__}")
    if answer.strip() != message_2_3():
        raise Wrong("not the message ik.closed_form raises for (15, 16)")


def judge_distance_2_3(answer: object, siblings: dict[str, object]) -> None:
    distance = scalar(answer)
    expected = float(np.hypot(*TARGET_2_3) - arms.ten.reach[1])
    if matches(close, distance, -expected, atol=1e-9):
        raise Wrong("the sign is reversed: beyond the reach the distance is positive")
    close(distance, expected, atol=1e-9)


register(
    "2.1",
    Part(
        "q_elbow_up",
        "angles",
        judge_elbow_up_2_1,
        "elbow up means q2 <= 0; check your answer with arms.ten.fk",
    ),
    Part(
        "up_within_limits",
        "limits",
        judge_limits_2_1,
        "q2 must lie in [-90, 90] deg on arms.ten",
    ),
    chapter=CHAPTER,
)
register(
    "2.2",
    Part(
        "step_1cm_deg",
        "step",
        judge_step_2_2,
        "solve (a1 + 2 a2) step / 2 = 0.01 m for the step, in radians, then convert",
    ),
    Part(
        "grid_points_1cm",
        "grid points",
        judge_points_2_2,
        "points per joint = ceil(range / step) + 1 (both ends of each range are on the grid); multiply the two",
    ),
    chapter=CHAPTER,
)
register(
    "2.3",
    Part(
        "unreachable_message",
        "message",
        judge_message_2_3,
        "str(error) of the UnreachableError you caught",
    ),
    Part(
        "distance_beyond_reach",
        "distance",
        judge_distance_2_3,
        "distance from the base minus a1 + a2",
    ),
    chapter=CHAPTER,
)
