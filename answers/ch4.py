"""Chapter 4 (statics, the wall): the references of exercises 4.1 to 4.4, with typical mistakes and hints."""

from __future__ import annotations

import numpy as np

from twolink import TwoLinkArm, arms, ik, to_relative
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "04_statics_wall"
Q_4_1_DEG, FORCE_4_1 = (30.0, 60.0), (0.0, -100.0)  # the tip pushes down on the scale
TOUCH_4_2, PUSH_4_2 = (3.0, 1.0), 200.0  # on the wall x = 3 m
Q_4_3_DEG, LOAD_KG_4_3 = (30.0, -60.0), 20.0
#: Exercise 4.4's visible calls: (l1, l2) in m, q in rad, the force by the tip in N.
CASES_4_4 = (
    ((2.0, 2.0), (0.4, 1.2), (300.0, -100.0)),
    ((1.0, 0.5), (2.1, -0.8), (-40.0, 90.0)),
    ((0.3, 1.2), (-1.0, 2.6), (0.0, -50.0)),
)
TORQUES = ("tau1", "tau2")
#: Torques a learner may compute by hand: right at the 3 significant figures asked.
BY_HAND = Tolerance(significant=3)


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
                tolerance=BY_HAND,
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
                tolerance=BY_HAND,
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
                    Mistake(
                        np.array([q_down[0], q_down.sum()]),
                        "your second angle is link 2's direction from the x-axis (an "
                        "absolute angle); q2 is measured from link 1",
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
                tolerance=BY_HAND,
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
                    Mistake(
                        PUSH_4_2 * np.array([arm.l1 + arm.l2, arm.l2]),
                        "this is the force times the links' lengths; a moment is the "
                        "force times its lever arm, the distance from the joint to the "
                        "force's line, measured at right angles to the force",
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
    q_deg = np.asarray(Q_4_3_DEG)
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
                tolerance=BY_HAND,
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
                    Mistake(
                        arm.joint_torques(q, load / arm.g) + arm.gravity(q),
                        "the load enters as its mass in kg: the force the tip "
                        "exerts is its weight, in newtons",
                    ),
                    Mistake(
                        arm.joint_torques(q_deg, load) + arm.gravity(q_deg),
                        "these are the torques for the angles read as radians (30 rad, "
                        "-60 rad): convert degrees first",
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


def _case_4_4(lengths, q, force) -> Case:
    """One call of ``wall_torques``, its right return value computed by the package."""
    arm = TwoLinkArm(*lengths)
    return Case(
        {
            "arm": {"arm": {"l1": float(lengths[0]), "l2": float(lengths[1])}},
            "q": [float(v) for v in q],
            "force_by_tip": [float(v) for v in force],
        },
        arm.joint_torques(q, force).tolist(),
    )


def _mistaken_4_4(torques) -> list[list[float]]:
    """What a mistaken ``wall_torques`` returns on the visible calls:
    ``torques(arm, q, force)`` for each."""
    return [
        np.asarray(
            torques(TwoLinkArm(*lengths), np.asarray(q), np.asarray(force)), dtype=float
        ).tolist()
        for lengths, q, force in CASES_4_4
    ]


def _base_only_for_tau1(arm, q, force):
    tau = arm.joint_torques(q, force)
    return [tau[0] - tau[1], tau[1]]  # the moment about the base of F at the elbow


def exercise_4_4() -> ExerciseSpec:
    cases = tuple(_case_4_4(*case) for case in CASES_4_4)
    return ExerciseSpec(
        "4.4",
        CHAPTER,
        (
            PartSpec(
                "wall_torques",
                "torque function",
                "function",
                cases=cases,
                output=PartSpec(
                    "tau",
                    "torques",
                    "vector",
                    shape=(2,),
                    unit="N m",
                    components=TORQUES,
                ),
                mistakes=(
                    Mistake(
                        _mistaken_4_4(lambda arm, q, f: -arm.joint_torques(q, f)),
                        "every torque has the wrong sign: either your force is the one "
                        "acting ON the tip, or your cross product is F x r; the torque "
                        "of the force the tip exerts is r x F, r from the joint",
                    ),
                    Mistake(
                        _mistaken_4_4(lambda arm, q, f: arm.jacobian(q) @ f),
                        "your function returns J F, the Jacobian times the force; "
                        "torques come from its transpose",
                    ),
                    Mistake(
                        _mistaken_4_4(
                            lambda arm, q, f: arm.joint_torques(np.radians(q), f)
                        ),
                        "your function converts q from degrees; q is already in "
                        "radians",
                    ),
                    Mistake(
                        _mistaken_4_4(
                            lambda arm, q, f: arm.joint_torques(to_relative(q), f)
                        ),
                        "your function points link 2 at the angle q2 from the x-axis; "
                        "q2 is measured from link 1, so link 2 points at q1 + q2",
                    ),
                    Mistake(
                        _mistaken_4_4(
                            lambda arm, q, f: TwoLinkArm(arm.l2, arm.l1).joint_torques(
                                q, f
                            )
                        ),
                        "your function swaps the links' lengths: l1 is link 1's, "
                        "from the base to the elbow",
                    ),
                    Mistake(
                        _mistaken_4_4(_base_only_for_tau1),
                        "your tau1 is the moment about the base of a force at the "
                        "elbow; the force acts at the tip, so tau1's lever runs from "
                        "the base to the tip",
                    ),
                    Mistake(
                        _mistaken_4_4(
                            lambda arm, q, f: arm.joint_torques(q, f)[[0, 0]]
                        ),
                        "your tau2 is the force's moment about the base; motor 2 "
                        "sits at the elbow, so tau2 is the moment about the elbow",
                    ),
                ),
                hints=(
                    "Reread 'The same torques from free-body diagrams': each motor "
                    "holds the moment of the tip's force about its own joint.",
                    "Find the elbow and the tip from q first; each torque is then a "
                    "planar cross product of the vector from its joint to the tip "
                    "with the force.",
                    "Link 2 points at the angle q1 + q2 from the x-axis, q is in "
                    "radians, and the cross product's order matters: r x F, not "
                    "F x r.",
                ),
            ),
        ),
    )


def _hidden_4_4(rng: np.random.Generator, count: int) -> list[Case]:
    """``count`` calls of ``wall_torques`` the notebook never makes: random arms
    (links 0.2 to 3 m), any angles and forces up to 500 N in each direction."""
    return [
        _case_4_4(
            rng.uniform(0.2, 3.0, 2).round(3),
            rng.uniform(-np.pi, np.pi, 2).round(4),
            rng.uniform(-500.0, 500.0, 2).round(1),
        )
        for _ in range(count)
    ]


#: The function parts' hidden cases, by (exercise, part): drawn from the grader's seed.
HIDDEN = {("4.4", "wall_torques"): _hidden_4_4}


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_4_1(), exercise_4_2(), exercise_4_3(), exercise_4_4()]
