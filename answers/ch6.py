"""Chapter 6 (spring and impedance control): the references of exercises 6.1 to 6.5, with typical mistakes and hints.

Exercises 6.1, 6.2, 6.3 and 6.5 are graded on hidden inputs too (``RERUN``);
6.4's function on hidden cases (``HIDDEN``) with the package's spring laws
switched off (``FORBIDDEN``).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.optimize
from numpy.typing import NDArray

from answers import Rerun
from answers._draws import first_valid
from twolink import arms, controllers, ik, linearization
from twolink.arm import TwoLinkArm
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "06_spring_impedance_control"
K_SOURCE, REST_POINT = 600.0, (3.0, 1.0)  # N/m, m: the chapter's spring
K_6_1, TIP_6_1 = ((600.0, 0.0), (0.0, 200.0)), (2.6, 0.3)  # held on the elbow-up branch
SAG_LIMIT_6_3 = 0.005  # m
Q_6_5_DEG, K_WALL_6_5, PUSH_6_5 = (-20.0, 70.0), 1e5, 300.0  # deg, N/m, N
TORQUES = ("tau1", "tau2")
#: 6.4's visible calls: (l1, l2), q (rad), p_rest (m), k (N/m)
CASES_6_4 = (
    ((2.0, 2.0), (0.3, 0.9), (3.0, 1.0), 600.0),
    ((1.0, 0.5), (-0.4, 2.1), (0.2, 1.1), 150.0),
    ((0.6, 1.5), (2.5, -1.2), (-1.0, -0.5), 40.0),
)


def _arm() -> TwoLinkArm:
    return arms.two_metre


def _q_rest() -> NDArray[np.float64]:
    """The 2 m arm's elbow-down pose with the tip at the rest point (3, 1)."""
    return ik.closed_form(_arm(), REST_POINT, elbow="down").q


def _spring_torque(arm: TwoLinkArm, q, p_rest, stiffness) -> NDArray[np.float64]:
    spring = controllers.CartesianSpring(arm, stiffness, np.asarray(p_rest, float))
    return np.asarray(spring.torque(np.asarray(q, float)), dtype=float)


def _inputs_6_1() -> dict[str, object]:
    return {
        "arm_ex1": _arm(),
        "K_ex1": np.array(K_6_1),
        "p_rest_ex1": np.array(REST_POINT),
        "p_tip_ex1": np.array(TIP_6_1),
    }


def _answers_6_1(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex1"]
    q_up = ik.closed_form(arm, inputs["p_tip_ex1"], elbow="up").q
    return {"tau_ex1": _spring_torque(arm, q_up, inputs["p_rest_ex1"], inputs["K_ex1"])}


def _hidden_6_1(rng: np.random.Generator) -> dict[str, object]:
    arm = _random_arm(rng)
    q_up = np.array(
        [rng.uniform(-np.pi, np.pi), -rng.uniform(np.radians(30), np.radians(150))]
    )
    return {
        "arm_ex1": arm,
        "K_ex1": np.diag(rng.uniform(100.0, 1000.0, 2).round(0)),
        "p_rest_ex1": _random_pose_point(rng, arm),
        "p_tip_ex1": arm.fk(q_up).round(3),
    }


def exercise_6_1() -> ExerciseSpec:
    arm, K = _arm(), np.array(K_6_1)
    q_up = ik.closed_form(arm, TIP_6_1, elbow="up").q
    q_down = ik.closed_form(arm, TIP_6_1, elbow="down").q
    force = K @ (np.asarray(REST_POINT) - arm.fk(q_up))
    tau = _answers_6_1(_inputs_6_1())["tau_ex1"]
    return ExerciseSpec(
        "6.1",
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
                        _spring_torque(arm, q_down, REST_POINT, K),
                        "these are the torques of the elbow-down arm (q2 > 0): the "
                        "exercise holds the tip on the elbow-up branch",
                    ),
                    Mistake(
                        -tau,
                        "the sign is reversed: the spring pulls the tip TOWARDS the "
                        "rest point, so its force is K (x0 - x)",
                    ),
                    Mistake(
                        _spring_torque(arm, q_up, REST_POINT, K_SOURCE),
                        "these are the torques of the scalar spring k = 600 N/m; this "
                        "spring is softer vertically: use the whole matrix K",
                    ),
                    Mistake(
                        _spring_torque(arm, q_up, REST_POINT, np.diag([200.0, 600.0])),
                        "the stiffnesses are swapped: 600 N/m acts along x and "
                        "200 N/m along y",
                    ),
                    Mistake(
                        arm.jacobian(q_up) @ force,
                        "this is J F, the Jacobian times the force; torques come from "
                        "its transpose",
                    ),
                    Mistake(
                        tau + arm.gravity(q_up),
                        "these include the links' weight, g(q): the exercise asks for "
                        "the spring's torques only",
                    ),
                ),
                hints=(
                    "Reread 'The idea: torques that feel like a spring': the spring "
                    "gives a force at the tip, and the motors make it with J^T.",
                    "First the pose: inverse kinematics on the elbow-up branch (q2 < "
                    "0). Then the force K (x0 - x) at that tip, then J^T at that pose.",
                ),
            ),
        ),
    )


def _inputs_6_2() -> dict[str, object]:
    return {"arm_ex2": _arm(), "k_ex2": K_SOURCE, "p_rest_ex2": np.array(REST_POINT)}


def _answers_6_2(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex2"]
    q = ik.closed_form(arm, inputs["p_rest_ex2"], elbow="down").q
    Lambda = linearization.tip_mass(arm, q)
    masses = np.linalg.eigvalsh(Lambda)  # light, heavy
    d_c = 2.0 * np.sqrt(inputs["k_ex2"] * masses[1])
    return {
        "Lambda_ex2": Lambda,
        "masses_ex2": masses,
        "d_c_ex2": float(d_c),
        "zeta_light_ex2": float(d_c / (2.0 * np.sqrt(inputs["k_ex2"] * masses[0]))),
    }


def _random_pose_point(rng: np.random.Generator, arm: TwoLinkArm) -> np.ndarray:
    """A tip point reached elbow down with the elbow bent 30 to 150 deg."""
    q = np.array(
        [rng.uniform(-np.pi, np.pi), rng.uniform(np.radians(30), np.radians(150))]
    )
    return arm.fk(q).round(3)


def _random_arm(rng: np.random.Generator) -> TwoLinkArm:
    """An arm of uniform rods like the chapter's: 1 to 3 m, 0.5 to 3 kg."""
    return TwoLinkArm(
        *rng.uniform(1.0, 3.0, 2).round(2), *rng.uniform(0.5, 3.0, 2).round(2)
    )


def _hidden_6_2(rng: np.random.Generator) -> dict[str, object]:
    arm = _random_arm(rng)
    return {
        "arm_ex2": arm,
        "k_ex2": round(float(rng.uniform(100.0, 3000.0)), 0),
        "p_rest_ex2": _random_pose_point(rng, arm),
    }


def exercise_6_2() -> ExerciseSpec:
    inputs = _inputs_6_2()
    reference = _answers_6_2(inputs)
    Lambda, masses = reference["Lambda_ex2"], reference["masses_ex2"]
    d_c, zeta = reference["d_c_ex2"], reference["zeta_light_ex2"]
    q = _q_rest()
    J, M = _arm().jacobian(q), _arm().mass_matrix(q)
    by_hand = Tolerance(significant=3)
    return ExerciseSpec(
        "6.2",
        CHAPTER,
        (
            PartSpec(
                "Lambda_ex2",
                "tip mass",
                "matrix",
                expected=Lambda,
                shape=(2, 2),
                unit="kg",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        J @ np.linalg.inv(M) @ J.T,
                        "this is J M^-1 J^T, the tip's acceleration per newton; the "
                        "tip mass is its inverse",
                    ),
                    Mistake(
                        J @ M @ J.T,
                        "this is J M J^T; the tip mass is (J M^-1 J^T)^-1, with the "
                        "inverse of M inside",
                    ),
                    Mistake(
                        M,
                        "this is the mass matrix M of the joints; the tip mass is what "
                        "a push at the tip feels, (J M^-1 J^T)^-1",
                    ),
                ),
                hints=(
                    "Reread 'The mass the tip feels' in section 5: a push F at the tip "
                    "accelerates it by J M^-1 J^T F.",
                    "Find the rest pose by inverse kinematics (elbow down), take J and "
                    "M there, form J M^-1 J^T and invert it.",
                ),
            ),
            PartSpec(
                "masses_ex2",
                "masses felt",
                "vector",
                expected=masses,
                shape=(2,),
                unit="kg",
                components=("light", "heavy"),
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        masses[::-1],
                        "the heavy mass comes first: give the light one first",
                    ),
                    Mistake(
                        np.diag(Lambda),
                        "these are the diagonal entries of Lambda; the masses felt "
                        "along the two directions are its eigenvalues",
                    ),
                ),
                hints=(
                    "Section 5: the masses felt are the eigenvalues of the tip mass.",
                    "For a 2x2 matrix they solve lambda^2 - (trace) lambda + det = 0 "
                    "(or np.linalg.eigvalsh, which returns them ascending).",
                ),
            ),
            PartSpec(
                "d_c_ex2",
                "critical damping",
                "number",
                expected=d_c,
                unit="N s/m",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        float(2.0 * np.sqrt(K_SOURCE * masses[0])),
                        "this is critical for the light direction; the heavy direction "
                        "needs more, and a smaller d leaves it oscillating",
                    ),
                    Mistake(
                        float(np.sqrt(K_SOURCE * masses[1])),
                        "half the damping: critical damping is d = 2 sqrt(k m), the "
                        "factor 2 is missing",
                    ),
                    Mistake(
                        float(2.0 * np.sqrt(K_SOURCE / masses[1])),
                        "this is 2 sqrt(k / m), twice the natural frequency; critical "
                        "damping is 2 sqrt(k m)",
                    ),
                ),
                hints=(
                    "Section 4: a mass-spring-damper is critically damped at "
                    "d = 2 sqrt(k m).",
                    "Each direction is a mass-spring-damper with its own mass; the "
                    "heavy one has the smallest damping ratio, so take its mass.",
                ),
            ),
            PartSpec(
                "zeta_light_ex2",
                "light direction's damping ratio",
                "number",
                expected=zeta,
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        1.0,
                        "1 is the heavy direction's ratio under d_c (critical by its "
                        "choice); the light direction's mass is smaller, so its ratio "
                        "d / (2 sqrt(k lambda_light)) is larger",
                    ),
                    Mistake(
                        float(1.0 / zeta),
                        "this is upside down: zeta = d / (2 sqrt(k lambda))",
                    ),
                ),
                hints=(
                    "Section 5: zeta = d / (2 sqrt(k lambda)), with the mass of the "
                    "direction you ask about.",
                    "Put d_c and the light mass (the smaller eigenvalue) into that "
                    "formula: the light direction is overdamped, zeta > 1.",
                ),
            ),
        ),
    )


#: The stiffnesses between which exercise 6.3's boundary lies, for its inputs and every
#: hidden draw (the exercise states them as the root finder's bracket), N/m.
BRACKET_6_3 = (500.0, 50_000.0)


def _boundary_stiffness(
    arm: TwoLinkArm, rest: np.ndarray, limit: float, component: slice = slice(None)
) -> float:
    """The stiffness (N/m) at which the uncompensated arm's tip rests exactly ``limit`` from ``rest``."""
    q_rest = ik.closed_form(arm, rest, elbow="down").q

    def miss(stiffness_value: float) -> float:
        controller = controllers.Impedance(
            arm, stiffness_value, 0.0, rest, gravity_compensation=False
        )
        resting = arm.fk(linearization.equilibrium(arm, controller, q_rest))
        return float(np.linalg.norm((resting - rest)[component]))

    return float(
        scipy.optimize.brentq(
            lambda k: miss(k) - limit, *BRACKET_6_3, xtol=1e-9, rtol=1e-14
        )
    )


def _inputs_6_3() -> dict[str, object]:
    return {
        "arm_ex3": _arm(),
        "p_rest_ex3": np.array(REST_POINT),
        "sag_limit_ex3": SAG_LIMIT_6_3,
    }


def _answers_6_3(inputs: dict) -> dict[str, object]:
    boundary = _boundary_stiffness(
        inputs["arm_ex3"], np.asarray(inputs["p_rest_ex3"]), inputs["sag_limit_ex3"]
    )
    return {"k_ex3": math.ceil(boundary)}


def _draw_6_3(rng: np.random.Generator) -> dict[str, object] | None:
    q = np.array([rng.uniform(-1.0, 1.5), rng.uniform(np.radians(40), np.radians(140))])
    inputs = {
        "arm_ex3": _arm(),
        "p_rest_ex3": _arm().fk(q).round(3),
        "sag_limit_ex3": round(float(rng.uniform(0.002, 0.02)), 3),
    }
    try:
        _answers_6_3(inputs)
    except ValueError:  # the boundary outside the bracket (or no resting pose)
        return None
    return inputs


def _hidden_6_3(rng: np.random.Generator) -> dict[str, object]:
    """The chapter's arm resting elsewhere, with another limit: its boundary inside the bracket."""
    return first_valid(_draw_6_3, rng, what="exercise 6.3's hidden inputs")


def exercise_6_3() -> ExerciseSpec:
    rest = np.array(REST_POINT)
    boundary = _boundary_stiffness(_arm(), rest, SAG_LIMIT_6_3)
    k = _answers_6_3(_inputs_6_3())["k_ex3"]
    J = _arm().jacobian(_q_rest())
    linear = float(
        np.linalg.norm(np.linalg.solve(J.T, _arm().gravity(_q_rest()))) / SAG_LIMIT_6_3
    )
    return ExerciseSpec(
        "6.3",
        CHAPTER,
        (
            PartSpec(
                "k_ex3",
                "stiffness in whole N/m",
                "number",
                expected=k,
                unit="N/m",
                tolerance=Tolerance(atol=1e-9, rtol=0.0),
                mistakes=(
                    Mistake(
                        boundary,
                        "this is the boundary itself, where the tip rests exactly at the "
                        "limit; the exercise asks for the smallest whole N/m that keeps "
                        "it within: the next whole number up",
                    ),
                    Mistake(
                        float(math.floor(boundary)),
                        "rounded down: this stiffness is below the boundary, so the tip "
                        "rests further than the limit; round up",
                    ),
                    Mistake(
                        K_SOURCE,
                        "this is the chapter's spring, k = 600 N/m: with it the tip "
                        "rests more than 5 mm away",
                    ),
                    Mistake(
                        float(
                            math.ceil(
                                _boundary_stiffness(_arm(), rest, SAG_LIMIT_6_3 / 10)
                            )
                        ),
                        "this keeps the tip within 0.5 mm: 5 mm is 0.005 m",
                    ),
                    Mistake(
                        float(
                            math.ceil(
                                _boundary_stiffness(
                                    _arm(), rest, SAG_LIMIT_6_3, slice(1, 2)
                                )
                            )
                        ),
                        "this bounds the vertical drop only; the tip also moves "
                        "sideways: bound its distance from the rest point",
                    ),
                    Mistake(
                        float(math.ceil(linear)),
                        "close, but this is the linear estimate at the rest pose; the "
                        "arm sags into another pose, where J and g(q) differ: solve "
                        "for the true resting pose",
                    ),
                ),
                hints=(
                    "Reread the Pitfall 'forgetting gravity': the tip rests where "
                    "the spring balances the weight, closer for a stiffer spring.",
                    "Write the distance of the resting tip from the rest point as a "
                    "function of k (linearization.equilibrium finds the resting pose), "
                    "find where it equals the limit with a root finder, and round up.",
                ),
            ),
        ),
    )


def _case_6_4(lengths, q, p_rest, k) -> Case:
    arm = TwoLinkArm(l1=lengths[0], l2=lengths[1])
    return Case(
        {
            "arm": {"arm": {"l1": float(lengths[0]), "l2": float(lengths[1])}},
            "q": [float(v) for v in q],
            "p_rest": [float(v) for v in p_rest],
            "k": float(k),
        },
        _spring_torque(arm, q, p_rest, k).tolist(),
    )


def _wrong_6_4(how: str) -> list[list[float]]:
    """What a mistaken spring_torques returns on each visible case."""
    values = []
    for lengths, q, p_rest, k in CASES_6_4:
        arm = TwoLinkArm(l1=lengths[0], l2=lengths[1])
        swapped = TwoLinkArm(l1=lengths[1], l2=lengths[0])
        q, p_rest = np.asarray(q), np.asarray(p_rest)
        J, p = arm.jacobian(q), arm.fk(q)
        value = {
            "sign": J.T @ (k * (p - p_rest)),
            "J": J @ (k * (p_rest - p)),
            "anchored": J.T @ (k * p),
            "swapped": swapped.jacobian(q).T @ (k * (p_rest - swapped.fk(q))),
            "gravity": J.T @ (k * (p_rest - p)) + arm.gravity(q),
        }[how]
        values.append(np.asarray(value, dtype=float).tolist())
    return values


def exercise_6_4() -> ExerciseSpec:
    output = PartSpec(
        "tau",
        "torques",
        "vector",
        shape=(2,),
        unit="N m",
        components=TORQUES,
        tolerance=Tolerance(atol=1e-7, rtol=1e-7),
    )
    return ExerciseSpec(
        "6.4",
        CHAPTER,
        (
            PartSpec(
                "spring_torques",
                "spring torques function",
                "function",
                cases=tuple(_case_6_4(*case) for case in CASES_6_4),
                output=output,
                mistakes=(
                    Mistake(
                        _wrong_6_4("sign"),
                        "your spring pushes the tip away from p_rest: its force is "
                        "k (p_rest - x), towards the rest point",
                    ),
                    Mistake(
                        _wrong_6_4("J"),
                        "your function returns J F, the Jacobian times the force; "
                        "torques come from its transpose",
                    ),
                    Mistake(
                        _wrong_6_4("anchored"),
                        "your spring is anchored at the origin (F = k x): the force "
                        "must depend on p_rest - x",
                    ),
                    Mistake(
                        _wrong_6_4("swapped"),
                        "your function swaps the links: l1 is the shoulder's link, "
                        "l2 the elbow's",
                    ),
                    Mistake(
                        _wrong_6_4("gravity"),
                        "your function adds the weight of the links: return the "
                        "spring's torques only",
                    ),
                ),
                hints=(
                    "Reread 'The idea: torques that feel like a spring': the "
                    "function is the spring law for any arm, pose, rest point and "
                    "stiffness.",
                    "Use the arm's own forward kinematics and Jacobian at q, the "
                    "force k (p_rest - x) at the tip, and the transpose of the "
                    "Jacobian; no weight.",
                ),
            ),
        ),
    )


def _hidden_6_4(rng: np.random.Generator, count: int) -> list[Case]:
    """Random arms, poses, rest points (anywhere within twice the reach) and stiffnesses."""
    cases = []
    while len(cases) < count:
        lengths = np.round(rng.uniform(0.2, 3.0, 2), 3)
        q = np.round(rng.uniform(-np.pi, np.pi, 2), 4)
        reach = lengths.sum()
        p_rest = np.round(rng.uniform(-1.5 * reach, 1.5 * reach, 2), 3)
        k = float(np.round(rng.uniform(10.0, 2000.0), 1))
        case = _case_6_4(tuple(lengths), tuple(q), tuple(p_rest), k)
        if all(case.arguments != _case_6_4(*c).arguments for c in CASES_6_4):
            cases.append(case)
    return cases


HIDDEN = {("6.4", "spring_torques"): _hidden_6_4}


def _inputs_6_5() -> dict[str, object]:
    return {
        "arm_ex5": _arm(),
        "q_ex5": np.radians(Q_6_5_DEG),
        "k_tip_ex5": K_SOURCE,
        "k_wall_ex5": K_WALL_6_5,
        "push_ex5": PUSH_6_5,
    }


def _answers_6_5(inputs: dict) -> dict[str, object]:
    J = inputs["arm_ex5"].jacobian(inputs["q_ex5"])
    k, push = inputs["k_tip_ex5"], inputs["push_ex5"]
    return {
        "K_joint_ex5": J.T @ (k * np.eye(2)) @ J,
        "offset_ex5": float(push / k + push / inputs["k_wall_ex5"]),
    }


def _hidden_6_5(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex5": _random_arm(rng),
        "q_ex5": np.array([rng.uniform(-np.pi, np.pi), rng.uniform(0.3, 2.8)]).round(4),
        "k_tip_ex5": round(float(rng.uniform(100.0, 3000.0)), 0),
        "k_wall_ex5": round(float(rng.uniform(1e4, 1e6)), -3),
        "push_ex5": round(float(rng.uniform(50.0, 800.0)), 0),
    }


def exercise_6_5() -> ExerciseSpec:
    inputs = _inputs_6_5()
    reference = _answers_6_5(inputs)
    K_joint, offset = reference["K_joint_ex5"], reference["offset_ex5"]
    J = _arm().jacobian(inputs["q_ex5"])
    by_hand = Tolerance(significant=3)
    return ExerciseSpec(
        "6.5",
        CHAPTER,
        (
            PartSpec(
                "K_joint_ex5",
                "joint stiffness",
                "matrix",
                expected=K_joint,
                shape=(2, 2),
                unit="N m/rad",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        J @ (K_SOURCE * np.eye(2)) @ J.T,
                        "this is J K J^T; a tip stiffness felt at the joints is J^T K J "
                        "(a joint motion dq moves the tip by J dq, and tau = J^T F)",
                    ),
                    Mistake(
                        K_SOURCE * np.eye(2),
                        "this is the tip's stiffness itself; at the joints it is "
                        "J^T K J, which depends on the pose",
                    ),
                    Mistake(
                        np.linalg.inv(J).T @ (K_SOURCE * np.eye(2)) @ np.linalg.inv(J),
                        "this is the other way round, J^-T K J^-1: a joint stiffness "
                        "felt at the tip; the exercise goes from the tip to the joints",
                    ),
                ),
                hints=(
                    "Reread section 6's two formulas relating K_tip and K_joint.",
                    "Take the Jacobian at q_ex5, and sandwich the tip's stiffness "
                    "(k times the identity) between J^T and J.",
                ),
            ),
            PartSpec(
                "offset_ex5",
                "rest point behind the wall",
                "number",
                expected=offset,
                unit="m",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        float(inputs["push_ex5"] / inputs["k_tip_ex5"]),
                        "this is the spring's stretch alone; the wall gives way by "
                        "push / k_wall as well, and the tip rests that far inside it",
                    ),
                    Mistake(
                        float(inputs["k_tip_ex5"] / inputs["push_ex5"]),
                        "this is upside down: a spring of stiffness k pushes with F "
                        "when stretched by F / k",
                    ),
                ),
                hints=(
                    "Reread section 7: the rest point sits behind the contact by the "
                    "spring's stretch, and the wall's own give is added.",
                    "Stretch = push / k; the wall, a spring of stiffness k_wall, gives "
                    "way by push / k_wall; the offset is their sum.",
                ),
            ),
        ),
    )


#: The value exercises graded on hidden inputs too: the inputs cell, a hidden draw, the references.
RERUN = {
    "6.1": Rerun(inputs=_inputs_6_1(), hidden=_hidden_6_1, answers=_answers_6_1),
    "6.2": Rerun(inputs=_inputs_6_2(), hidden=_hidden_6_2, answers=_answers_6_2),
    "6.3": Rerun(inputs=_inputs_6_3(), hidden=_hidden_6_3, answers=_answers_6_3),
    "6.5": Rerun(inputs=_inputs_6_5(), hidden=_hidden_6_5, answers=_answers_6_5),
}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("6.4", "spring_torques"): (
        "twolink.controllers.CartesianSpring",
        "twolink.controllers.Impedance",
        "twolink.arm.TwoLinkArm.joint_torques",
        "twolink.kinematics.joint_torques",
        "twolink_course.sources.me639.correct_spring_torques_dh",
    ),
}

#: No part of this chapter is worked on paper alone.
PEN_AND_PAPER: tuple[tuple[str, str], ...] = ()


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_6_1(),
        exercise_6_2(),
        exercise_6_3(),
        exercise_6_4(),
        exercise_6_5(),
    ]
