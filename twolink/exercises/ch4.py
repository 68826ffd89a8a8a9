"""Chapter 4 (statics, the wall): exercises 4.1 to 4.3."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import arms
from ..statics import Wall, WallContact, wall_contact
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

CHAPTER = "04_statics_wall"
Q_4_1_DEG, FORCE_4_1 = (30.0, 60.0), (0.0, -100.0)  # the tip pushes down on the scale
WALL_X_4_2, PUSH_4_2 = 3.0, 200.0
Q_4_3_DEG, LOAD_KG_4_3 = (30.0, -60.0), 20.0


def judge_torques_4_1(answer: object, siblings: dict[str, object]) -> None:
    tau = numbers(answer, (2,))
    expected = arms.two_metre.joint_torques(np.radians(Q_4_1_DEG), FORCE_4_1)
    if matches(close, tau, -expected, atol=1e-9):
        raise Wrong("the sign is reversed: the tip pushes DOWN, F = (0, -100) N")
    if matches(
        close,
        tau,
        arms.two_metre.jacobian(np.radians(Q_4_1_DEG)) @ np.asarray(FORCE_4_1),
        atol=1e-9,
    ):
        raise Wrong("this is J F; the torques are J^T F")
    close(tau, expected, atol=1e-9)


@reference
def contact_4_2() -> WallContact:
    """The 2 m arm pushing 200 N on the wall x = 3 m, link 2 perpendicular: both branches."""
    return wall_contact(
        arms.two_metre,
        Wall(np.array([WALL_X_4_2, 0.0]), np.array([1.0, 0.0])),
        PUSH_4_2,
    )


def judge_configuration_4_2(answer: object, siblings: dict[str, object]) -> None:
    q = numbers(answer, (2,))
    contact = contact_4_2()
    if matches(angles_close, q, contact.q[contact.branch("up")], atol=1e-6):
        raise Wrong("this is the elbow-up configuration (q2 < 0)")
    if matches(
        angles_close,
        q,
        np.degrees(contact.q[contact.branch("down")]),
        atol=1e-6,
        period=360.0,
    ):
        raise Wrong("these are degrees; the answer is in radians")
    angles_close(q, contact.q[contact.branch("down")], atol=1e-9)


def judge_torque_4_2(answer: object, siblings: dict[str, object]) -> None:
    tau1 = scalar(answer)
    contact = contact_4_2()
    if matches(close, tau1, contact.tau[contact.branch("up"), 0], atol=1e-9):
        raise Wrong("this is joint 1's torque on the elbow-up branch")
    close(tau1, contact.tau[contact.branch("down"), 0], atol=1e-9)


@reference
def torques_4_3() -> NDArray[np.float64]:
    """Motor torques holding a 20 kg load at q = (30, -60) deg, the links' weight included."""
    arm = arms.two_metre
    q = np.radians(Q_4_3_DEG)
    return arm.joint_torques(q, [0.0, LOAD_KG_4_3 * arm.g]) + arm.gravity(q)


def judge_torques_4_3(answer: object, siblings: dict[str, object]) -> None:
    tau = numbers(answer, (2,))
    arm, q = arms.two_metre, np.radians(Q_4_3_DEG)
    if matches(close, tau, arm.joint_torques(q, [0.0, LOAD_KG_4_3 * arm.g]), atol=1e-9):
        raise Wrong("the links' own weight is missing: add arm.gravity(q)")
    if matches(
        close,
        tau,
        arm.joint_torques(q, [0.0, -LOAD_KG_4_3 * arm.g]) + arm.gravity(q),
        atol=1e-9,
    ):
        raise Wrong("the load's force points the wrong way: the tip holds the load UP")
    close(tau, torques_4_3(), atol=1e-9)


register(
    "4.1",
    Part(
        "tau_ex1",
        "torques",
        judge_torques_4_1,
        "the tip pushes DOWN on the scale: F = (0, -100) N; tau = J^T F",
    ),
    chapter=CHAPTER,
)
register(
    "4.2",
    Part(
        "q_down_ex2",
        "configuration",
        judge_configuration_4_2,
        "cos q1 = (3 - l2) / l1 and q1 + q2 = 0; elbow down means q2 > 0",
    ),
    Part(
        "tau1_down_ex2",
        "torque",
        judge_torque_4_2,
        "the moment of F = (200, 0) N about the base",
    ),
    chapter=CHAPTER,
)
register(
    "4.3",
    Part(
        "tau_ex3",
        "torques",
        judge_torques_4_3,
        "the tip holds the load UP: F = (0, +m g); add arm.gravity(q) for the links",
    ),
    chapter=CHAPTER,
)
