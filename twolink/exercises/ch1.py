"""Chapter 1 (DH forward kinematics): exercises 1.1 to 1.3."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import arms
from ..conventions import to_relative
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

CHAPTER = "01_dh_forward_kinematics"
Q_1_1_DEG = (45.0, -30.0)  # OSAKE arm
Q_1_2_DEG = (120.0, -45.0)  # OSAKE arm
Q_ABS_1_3_DEG = (60.0, 150.0)  # 2 m arm, link angles from the x-axis


@reference
def tip_1_1() -> NDArray[np.float64]:
    """The OSAKE tip at q = (45, -30) deg (x, y in metres)."""
    return arms.osake.fk(np.radians(Q_1_1_DEG))


def judge_tip_1_1(answer: object, siblings: dict[str, object]) -> None:
    p_tip = numbers(answer, (2,))
    if matches(close, p_tip, arms.osake.fk(np.array(Q_1_1_DEG)), atol=1e-9):
        raise Wrong(
            "this is the tip for the angles read as radians (45 rad, -30 rad): convert degrees first"
        )
    close(p_tip, tip_1_1(), atol=1e-9)


@reference
def transform_1_2() -> NDArray[np.float64]:
    """T_02 of the OSAKE arm at q = (120, -45) deg."""
    return arms.osake.transforms(np.radians(Q_1_2_DEG))[1]


def judge_transform_1_2(answer: object, siblings: dict[str, object]) -> None:
    T_02 = numbers(answer, (4, 4))
    A1, _ = arms.osake.transforms(np.radians(Q_1_2_DEG))
    A2 = np.linalg.solve(A1, transform_1_2())
    if matches(close, T_02, A2 @ A1, atol=1e-9):
        raise Wrong("this is A2 @ A1: the product runs from the base outwards, A1 @ A2")
    close(T_02, transform_1_2(), atol=1e-9)


def judge_height_1_2(answer: object, siblings: dict[str, object]) -> None:
    close(scalar(answer), transform_1_2()[2, 3], atol=1e-9)


def judge_axis_1_2(answer: object, siblings: dict[str, object]) -> None:
    axis = numbers(answer, (3,))
    if matches(close, axis, transform_1_2()[:3, 2], atol=1e-9):
        return None
    if matches(close, axis, transform_1_2()[2, :3], atol=1e-9):
        raise Wrong(
            "this is the third row of the rotation block; the z axis is its third column"
        )
    close(axis, transform_1_2()[:3, 2], atol=1e-9)


@reference
def relative_1_3() -> NDArray[np.float64]:
    """The 2 m arm's relative angles for link angles (60, 150) deg."""
    return to_relative(np.radians(Q_ABS_1_3_DEG))


def judge_relative_1_3(answer: object, siblings: dict[str, object]) -> None:
    q_rel = numbers(answer, (2,))
    if matches(
        angles_close, q_rel, np.degrees(relative_1_3()), atol=1e-6, period=360.0
    ):
        raise Wrong("these are degrees; the answer is in radians")
    angles_close(q_rel, relative_1_3(), atol=1e-9)


def judge_tip_1_3(answer: object, siblings: dict[str, object]) -> None:
    p_tip = numbers(answer, (2,))
    if matches(close, p_tip, arms.two_metre.fk(np.radians(Q_ABS_1_3_DEG)), atol=1e-9):
        raise Wrong(
            "this is arm.fk of the absolute angles; the package takes relative (DH) angles"
        )
    close(p_tip, arms.two_metre.fk(relative_1_3()), atol=1e-9)


register(
    "1.1",
    Part(
        "p_tip_ex1",
        "tip position",
        judge_tip_1_1,
        "x = l1 cos q1 + l2 cos(q1 + q2), y likewise with sin; angles in radians",
    ),
    chapter=CHAPTER,
)
register(
    "1.2",
    Part(
        "T_02_ex2",
        "T_02",
        judge_transform_1_2,
        "T_02 = A1 @ A2, with theta_i = q_i + offset and d, a, alpha from osake.dh_table()",
    ),
    Part(
        "z_tip_ex2",
        "tip height",
        judge_height_1_2,
        "the height is the third entry of the last column",
    ),
    Part(
        "z_axis_ex2",
        "tip z axis",
        judge_axis_1_2,
        "the z axis is the third column of the rotation block",
    ),
    chapter=CHAPTER,
)
register(
    "1.3",
    Part(
        "q_rel_ex3",
        "relative angles",
        judge_relative_1_3,
        "q2 = q2_abs - q1; q1 is the same in both conventions",
    ),
    Part(
        "p_tip_ex3", "tip", judge_tip_1_3, "feed arm.fk the relative angles, in radians"
    ),
    chapter=CHAPTER,
)
