"""Chapter 4 (statics, the wall): the references of exercises 4.1 to 4.3, with typical mistakes and hints."""

from __future__ import annotations

import numpy as np

from twolink import arms, ik
from twolink.exercises.spec import ExerciseSpec, Mistake, PartSpec

CHAPTER = "04_statics_wall"
Q_4_1_DEG, FORCE_4_1 = (30.0, 60.0), (0.0, -100.0)  # the tip pushes down on the scale
TOUCH_4_2, PUSH_4_2 = (3.0, 1.0), 200.0  # on the wall x = 3 m
Q_4_3_DEG, LOAD_KG_4_3 = (30.0, -60.0), 20.0
TORQUES = ("tau1", "tau2")


def exercise_4_1() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_4_1_DEG)
    force = np.asarray(FORCE_4_1)
    tau = arm.joint_torques(q, force)
    return ExerciseSpec(
        "4.1",
        CHAPTER,
        (
            PartSpec(
                "tau_ex1",
                "torques",
                "vector",
                expected=tau,
                shape=(2,),
                unit="N m",
                components=TORQUES,
                mistakes=(
                    Mistake(
                        -tau,
                        "these torques hold the tip against a force pointing UP; the "
                        "tip presses DOWN on the scale, so the force it exerts points "
                        "down",
                    ),
                    Mistake(
                        arm.jacobian(q) @ force,
                        "this is J F, the Jacobian times the force; torques come from "
                        "its transpose",
                    ),
                    Mistake(
                        arm.joint_torques(np.asarray(Q_4_1_DEG), force),
                        "these are the torques for the angles read as radians (30 rad, "
                        "60 rad): convert degrees first",
                    ),
                ),
                hints=(
                    "Reread 'tau = J^T F by virtual work': which force goes into it, "
                    "the one the tip exerts or the one it feels?",
                    "Write the force the tip exerts on the scale with its sign, then "
                    "use the Jacobian at the pose, with the angles in radians.",
                ),
            ),
        ),
    )


def exercise_4_2() -> ExerciseSpec:
    arm = arms.two_metre
    push = np.array([PUSH_4_2, 0.0])  # into the wall x = 3 m
    q_down = ik.closed_form(arm, TOUCH_4_2, elbow="down").q
    q_up = ik.closed_form(arm, TOUCH_4_2, elbow="up").q
    tau_down = arm.joint_torques(q_down, push)
    return ExerciseSpec(
        "4.2",
        CHAPTER,
        (
            PartSpec(
                "q_down_ex2",
                "configuration",
                "angles",
                expected=q_down,
                shape=(2,),
                unit="rad",
                components=("q1", "q2"),
                mistakes=(
                    Mistake(
                        q_up,
                        "this is the elbow-up configuration (q2 < 0): the exercise "
                        "asks for elbow down",
                    ),
                    Mistake(
                        np.degrees(q_down),
                        "these are degrees; the answer is in radians",
                    ),
                ),
                hints=(
                    "The tip's position fixes the arm's pose: chapter 2's inverse "
                    "kinematics, on the elbow-down branch.",
                    "Elbow down means q2 > 0; check your angles by putting them "
                    "through the forward kinematics.",
                ),
            ),
            PartSpec(
                "tau_down_ex2",
                "torques",
                "vector",
                expected=tau_down,
                shape=(2,),
                unit="N m",
                components=TORQUES,
                mistakes=(
                    Mistake(
                        arm.joint_torques(q_up, push),
                        "these are the torques of the elbow-up arm: joint 1's is the "
                        "same on both branches, joint 2's is not",
                    ),
                    Mistake(
                        -tau_down,
                        "these torques pull the tip away from the wall: the tip "
                        "pushes ON the wall, towards +x",
                    ),
                    Mistake(
                        arm.jacobian(q_down) @ push,
                        "this is J F, the Jacobian times the force; torques come from "
                        "its transpose",
                    ),
                ),
                hints=(
                    "Reread 'tau = J^T F by virtual work', with the force the tip "
                    "exerts on the wall.",
                    "Joint 1's torque is the force's moment about the base, joint "
                    "2's its moment about the elbow: both need your configuration.",
                ),
            ),
        ),
    )


def exercise_4_3() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_4_3_DEG)
    load = np.array([0.0, LOAD_KG_4_3 * arm.g])
    tau = arm.joint_torques(q, load) + arm.gravity(q)
    return ExerciseSpec(
        "4.3",
        CHAPTER,
        (
            PartSpec(
                "tau_ex3",
                "torques",
                "vector",
                expected=tau,
                shape=(2,),
                unit="N m",
                components=TORQUES,
                mistakes=(
                    Mistake(
                        arm.joint_torques(q, load),
                        "the links' own weight is missing: the motors hold the arm "
                        "as well as the load",
                    ),
                    Mistake(
                        arm.joint_torques(q, -load) + arm.gravity(q),
                        "the load's force points the wrong way: the tip holds the "
                        "load UP",
                    ),
                    Mistake(
                        arm.joint_torques(q, -load) - arm.gravity(q),
                        "every sign is reversed: these torques would hold the arm "
                        "and the load against a pull upwards",
                    ),
                ),
                hints=(
                    "Two things weigh on the motors here; reread 'With the arm's own "
                    "weight'.",
                    "The force the tip exerts on the load points up; the links' "
                    "weight adds torques of its own (the package has them for a "
                    "pose).",
                ),
            ),
        ),
    )


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_4_1(), exercise_4_2(), exercise_4_3()]
