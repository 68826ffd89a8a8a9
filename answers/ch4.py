"""Chapter 4 (statics, the wall): the references of exercises 4.1 to 4.5, with typical mistakes and hints.

Exercises 4.1 to 4.3 are graded on hidden inputs too (``RERUN``); 4.4's
function on hidden cases (``HIDDEN``) with the package's one-liners switched
off (``FORBIDDEN``); 4.5 is worked on paper and checked on its own numbers and
its choice of reason (``PEN_AND_PAPER``).
"""

from __future__ import annotations

import numpy as np

from answers import Rerun
from twolink import TwoLinkArm, arms, ik, to_relative, velocity
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "04_statics_wall"
Q_4_1_DEG, PUSH_4_1 = (30.0, 60.0), 100.0  # the tip pushes down on the scale, N
FORCE_4_1 = (0.0, -PUSH_4_1)
TOUCH_4_2, PUSH_4_2 = (3.0, 1.0), 200.0  # on the wall x = 3 m
Q_4_3_DEG, LOAD_KG_4_3 = (30.0, -60.0), 20.0
Q_4_5_DEG = (0.0, 90.0)  # the force ellipse by hand, on the 2 m arm
REASONS_4_5 = ("a", "b", "c")
#: Exercise 4.4's visible calls: (l1, l2) in m, q in rad, the force by the tip in N.
CASES_4_4 = (
    ((2.0, 2.0), (0.4, 1.2), (300.0, -100.0)),
    ((1.0, 0.5), (2.1, -0.8), (-40.0, 90.0)),
    ((0.3, 1.2), (-1.0, 2.6), (0.0, -50.0)),
)
TORQUES = ("tau1", "tau2")
#: Torques a learner may compute by hand: right at the 3 significant figures asked.
BY_HAND = Tolerance(significant=3)


def _inputs_4_1() -> dict[str, object]:
    return {
        "arm_ex1": arms.two_metre,
        "q_ex1": np.radians(Q_4_1_DEG),
        "push_ex1": PUSH_4_1,
    }


def _answers_4_1(inputs: dict) -> dict[str, object]:
    force = np.array([0.0, -float(inputs["push_ex1"])])
    return {"tau_ex1": inputs["arm_ex1"].joint_torques(inputs["q_ex1"], force)}


def _random_arm(rng: np.random.Generator, masses: bool = False) -> TwoLinkArm:
    """An arm like the chapter's: links 0.5 to 3 m (uniform rods of 0.5 to 5 kg if asked)."""
    lengths = rng.uniform(0.5, 3.0, 2).round(2)
    if not masses:
        return TwoLinkArm(*lengths)
    return TwoLinkArm(*lengths, *rng.uniform(0.5, 5.0, 2).round(2))


def _bent_pose(rng: np.random.Generator, elbow: str = "either") -> np.ndarray:
    """Joint angles (rad) with the elbow bent at least 15 deg from straight or folded."""
    q2 = rng.uniform(np.radians(15.0), np.radians(165.0)) * rng.choice([-1.0, 1.0])
    if elbow == "down":
        q2 = abs(q2)
    return np.array([rng.uniform(-np.pi, np.pi), q2]).round(4)


def _hidden_4_1(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex1": _random_arm(rng),
        "q_ex1": _bent_pose(rng),
        "push_ex1": round(float(rng.uniform(20.0, 500.0)), 1),
    }


def exercise_4_1() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_4_1_DEG)
    force = np.asarray(FORCE_4_1)
    tau = _answers_4_1(_inputs_4_1())["tau_ex1"]
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


def _inputs_4_2() -> dict[str, object]:
    return {
        "arm_ex2": arms.two_metre,
        "p_touch_ex2": np.array(TOUCH_4_2),
        "push_ex2": PUSH_4_2,
    }


def _answers_4_2(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex2"]
    q_down = ik.closed_form(arm, inputs["p_touch_ex2"], elbow="down").q
    push = np.array([float(inputs["push_ex2"]), 0.0])  # horizontally, towards +x
    return {"q_down_ex2": q_down, "tau_down_ex2": arm.joint_torques(q_down, push)}


def _hidden_4_2(rng: np.random.Generator) -> dict[str, object]:
    arm = _random_arm(rng)
    return {
        "arm_ex2": arm,
        "p_touch_ex2": arm.fk(_bent_pose(rng, elbow="down")).round(3),
        "push_ex2": round(float(rng.uniform(20.0, 500.0)), 1),
    }


def exercise_4_2() -> ExerciseSpec:
    arm = arms.two_metre
    push = np.array([PUSH_4_2, 0.0])  # into the wall x = 3 m
    reference = _answers_4_2(_inputs_4_2())
    q_down, tau_down = reference["q_down_ex2"], reference["tau_down_ex2"]
    q_up = ik.closed_form(arm, TOUCH_4_2, elbow="up").q
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


def _inputs_4_3() -> dict[str, object]:
    return {
        "arm_ex3": arms.two_metre,
        "q_ex3": np.radians(Q_4_3_DEG),
        "load_kg_ex3": LOAD_KG_4_3,
    }


def _answers_4_3(inputs: dict) -> dict[str, object]:
    arm, q = inputs["arm_ex3"], inputs["q_ex3"]
    load = np.array([0.0, float(inputs["load_kg_ex3"]) * arm.g])  # the tip holds it up
    return {"tau_ex3": arm.joint_torques(q, load) + arm.gravity(q)}


def _hidden_4_3(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex3": _random_arm(rng, masses=True),
        "q_ex3": _bent_pose(rng),
        "load_kg_ex3": round(float(rng.uniform(1.0, 50.0)), 1),
    }


def exercise_4_3() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_4_3_DEG)
    load = np.array([0.0, LOAD_KG_4_3 * arm.g])
    tau = _answers_4_3(_inputs_4_3())["tau_ex3"]
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


def _semi_axes_4_5(q: np.ndarray) -> np.ndarray:
    return velocity.force_ellipse(arms.two_metre, q).semi_axes  # the longest first


def exercise_4_5() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_4_5_DEG)
    J = arm.jacobian(q)
    axes = _semi_axes_4_5(q)
    sigma = np.linalg.svd(J, compute_uv=False)
    eigenvalues = np.linalg.eigvalsh(J @ J.T)[::-1]  # of J J^T, the largest first
    return ExerciseSpec(
        "4.5",
        CHAPTER,
        (
            PartSpec(
                "J_ex5",
                "Jacobian",
                "matrix",
                expected=J,
                shape=(2, 2),
                unit="m",
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        arm.jacobian(np.asarray(Q_4_5_DEG)),
                        "this is the Jacobian for the angles read as radians (0 rad, "
                        "90 rad): at q2 = 90 deg, sin q12 = 1 and cos q12 = 0",
                    ),
                    Mistake(
                        J.T,
                        "this is J transposed: the rows of J are x and y, its columns "
                        "the joints",
                    ),
                    Mistake(
                        J[:, ::-1],
                        "the columns are swapped: the first column belongs to joint 1, "
                        "-l1 s1 - l2 s12 on top",
                    ),
                ),
                hints=(
                    "Reread the Jacobian of chapter 3, restated in this exercise: "
                    "put in s1 = sin 0, c1 = cos 0, s12 = sin 90 deg, c12 = cos 90 deg.",
                    "With q1 = 0 and q1 + q2 = 90 deg: s1 = 0, c1 = 1, s12 = 1, c12 "
                    "= 0; each entry is then a sum of l1 and l2 times these.",
                ),
            ),
            PartSpec(
                "force_axes_ex5",
                "force ellipse semi-axes",
                "vector",
                expected=axes,
                shape=(2,),
                unit="N per N m",
                components=("longest", "shortest"),
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        sigma,
                        "these are the singular values sigma = sqrt(lambda) of J (the "
                        "velocity ellipse's semi-axes); the force ellipse's are their "
                        "inverses, 1 / sigma",
                    ),
                    Mistake(
                        axes[::-1],
                        "the shortest comes first: give the longest semi-axis first",
                    ),
                    Mistake(
                        1.0 / eigenvalues[::-1],
                        "these are 1 / lambda, with lambda the eigenvalues of J J^T; "
                        "the singular values are their square roots, sigma = sqrt(lambda)",
                    ),
                ),
                hints=(
                    "Reread section 6's derivation: |J^T F| <= 1 is an ellipse with "
                    "semi-axes 1 / sigma_i.",
                    "J J^T is [[8, -4], [-4, 4]] m^2 here; its eigenvalues solve "
                    "lambda^2 - 12 lambda + 16 = 0; sigma = sqrt(lambda), the "
                    "semi-axes 1 / sigma, the longest from the smallest sigma.",
                ),
            ),
            PartSpec(
                "reason_ex5",
                "reason",
                "text",
                expected="b",
                mistakes=(
                    Mistake(
                        "a",
                        "the force ellipse is for the same unit torque at every pose: "
                        "the motors are not stronger anywhere. What changes is the "
                        "lever a force along the arm has about the joints",
                    ),
                    Mistake(
                        "c",
                        "det J = l1 l2 sin q2 is zero when the arm is straight, not "
                        "largest: the Jacobian loses a direction there",
                    ),
                ),
                hints=(
                    "Reread section 6's two bullets on what happens as sigma_2 "
                    "goes to 0 along the arm.",
                    "A force's torque about a joint is its moment, r x F: what is "
                    "that moment when F points along the line through the joint?",
                ),
            ),
        ),
    )


#: The function parts' hidden cases, by (exercise, part): drawn from the grader's seed.
HIDDEN = {("4.4", "wall_torques"): _hidden_4_4}

#: The value exercises graded on hidden inputs too: the inputs cell, a hidden draw, the references.
RERUN = {
    "4.1": Rerun(inputs=_inputs_4_1(), hidden=_hidden_4_1, answers=_answers_4_1),
    "4.2": Rerun(inputs=_inputs_4_2(), hidden=_hidden_4_2, answers=_answers_4_2),
    "4.3": Rerun(inputs=_inputs_4_3(), hidden=_hidden_4_3, answers=_answers_4_3),
}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("4.4", "wall_torques"): (
        "twolink.arm.TwoLinkArm.joint_torques",
        "twolink.kinematics.joint_torques",
        "twolink.arm.TwoLinkArm.jacobian",
        "twolink.kinematics.jacobian",
        "twolink.arm.TwoLinkArm.geometric_jacobian",
        "twolink.dh.geometric_jacobian",
    ),
}

#: Parts worked on paper (a derivation, a choice among stated reasons): checked on
#: the visible values only, and timed as pen-and-paper parts.
PEN_AND_PAPER = (
    ("4.5", "J_ex5"),
    ("4.5", "force_axes_ex5"),
    ("4.5", "reason_ex5"),
)


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_4_1(),
        exercise_4_2(),
        exercise_4_3(),
        exercise_4_4(),
        exercise_4_5(),
    ]
