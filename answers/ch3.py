"""Chapter 3 (Jacobian and velocity): the references of exercises 3.1 to 3.3, with typical mistakes and hints.

Exercise 3.1 asks for a function, ``joint_rates(arm, q, v_tip)``, checked on
the visible cases below and graded on hidden ones (:data:`HIDDEN`).
"""

from __future__ import annotations

import numpy as np
import scipy.optimize

from twolink import TwoLinkArm, arms
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "03_jacobian_velocity"
Q_3_1_DEG, V_TIP_3_1 = (20.0, 70.0), (0.0, 0.2)  # the 2 m arm; tip straight up, m/s
Q2_3_2_DEG, RATE_3_2_DEG_S = 90.0, 5.0  # the OSAKE arm, joint 2 held, joint 1 turning
ANGLE_TOLERANCE_DEG_3_3 = 0.5  # the roundest elbow angle, to half a degree
RATES = ("qd1", "qd2")

#: The visible calls of ``joint_rates(arm, q, v_tip)``: (l1, l2), q (rad), v_tip (m/s).
VISIBLE_3_1 = (
    ((0.1, 0.115), (0.3, 1.2), (0.01, -0.02)),
    ((1.0, 0.5), (-0.5, -2.0), (0.1, 0.0)),
    ((2.0, 2.0), (2.5, 0.8), (-0.3, 0.1)),
)


def _rates_case(l1: float, l2: float, q: object, v_tip: object) -> Case:
    arm = TwoLinkArm(l1=l1, l2=l2)
    q, v_tip = np.asarray(q, dtype=float), np.asarray(v_tip, dtype=float)
    return Case(
        {
            "arm": {"arm": {"l1": l1, "l2": l2}},
            "q": q.tolist(),
            "v_tip": v_tip.tolist(),
        },
        arm.joint_rates(q, v_tip).tolist(),
    )


def _mistaken_rates(
    l1: float, l2: float, q: object, v_tip: object
) -> dict[str, object]:
    """What the typical mistaken functions return for one call."""
    arm, swapped = TwoLinkArm(l1=l1, l2=l2), TwoLinkArm(l1=l2, l2=l1)
    q, v_tip = np.asarray(q, dtype=float), np.asarray(v_tip, dtype=float)
    J = arm.jacobian(q)
    right = arm.joint_rates(q, v_tip)
    return {
        "transpose": J.T @ v_tip,
        "forward": J @ v_tip,
        "sign": -right,
        "swapped": swapped.joint_rates(q, v_tip),
        "absolute": np.array([right[0], right[0] + right[1]]),
        "no determinant": np.linalg.det(J) * right,  # adj(J) v: the 1/det J left out
    }


def exercise_3_1() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_3_1_DEG)
    v_tip = np.asarray(V_TIP_3_1)
    J = arm.jacobian(q)
    qd = arm.joint_rates(q, v_tip)
    visible = tuple(_rates_case(*lengths, q_, v_) for lengths, q_, v_ in VISIBLE_3_1)
    mistaken = [_mistaken_rates(*lengths, q_, v_) for lengths, q_, v_ in VISIBLE_3_1]

    def on_visible(name: str) -> list[list[float]]:
        return [np.asarray(m[name]).tolist() for m in mistaken]

    return ExerciseSpec(
        "3.1",
        CHAPTER,
        (
            PartSpec(
                "joint_rates",
                "joint-rate function",
                "function",
                cases=visible,
                output=PartSpec(
                    "qd",
                    "joint rates",
                    "vector",
                    shape=(2,),
                    unit="rad/s",
                    components=RATES,
                ),
                mistakes=(
                    Mistake(
                        on_visible("transpose"),
                        "your function returns J^T v, the transpose times the "
                        "velocity: the joint rates solve J qd = v_tip",
                    ),
                    Mistake(
                        on_visible("forward"),
                        "your function returns J v, the Jacobian times the velocity "
                        "(that maps joint rates to a tip velocity): the joint rates "
                        "solve J qd = v_tip",
                    ),
                    Mistake(
                        on_visible("sign"),
                        "your rates have every sign reversed: they move the tip "
                        "opposite to v_tip; check the signs of J's entries",
                    ),
                    Mistake(
                        on_visible("swapped"),
                        "your Jacobian has l1 and l2 swapped: link 1 (arm.l1) runs "
                        "from the base to the elbow, link 2 (arm.l2) from the elbow "
                        "to the tip",
                    ),
                    Mistake(
                        on_visible("absolute"),
                        "your second rate is that of link 2's absolute angle (from "
                        "the x axis): q2 is measured from link 1, so its rate is "
                        "relative too",
                    ),
                    Mistake(
                        on_visible("no determinant"),
                        "your rates are det J times too large: an inverse written "
                        "out by hand needs the division by the determinant",
                    ),
                ),
                hints=(
                    "Reread 'Tip velocity from joint rates, and back': the joint "
                    "rates are what J(q) maps onto the wanted tip velocity.",
                    "Build J from arm.l1, arm.l2 and q as in 'The Jacobian: "
                    "differentiate the forward kinematics' (column j: the tip "
                    "velocity of joint j at unit rate), then solve the 2x2 system "
                    "for qd rather than inverting J.",
                ),
            ),
            PartSpec(
                "qd_ex1",
                "joint rates",
                "vector",
                expected=qd,
                shape=(2,),
                unit="rad/s",
                components=RATES,
                mistakes=(
                    Mistake(
                        J.T @ v_tip,
                        "this is J^T v, the transpose times the velocity: the joint "
                        "rates solve J qd = v",
                    ),
                    Mistake(
                        J @ v_tip,
                        "this is J v, the Jacobian times the velocity: the joint "
                        "rates solve J qd = v",
                    ),
                    Mistake(
                        -qd,
                        "the signs are reversed: these rates move the tip straight "
                        "down",
                    ),
                    Mistake(
                        arm.joint_rates(q, v_tip[::-1]),
                        "these rates move the tip sideways (along x): straight up "
                        "is a velocity along y",
                    ),
                    Mistake(
                        arm.joint_rates(np.asarray(Q_3_1_DEG), v_tip),
                        "these rates use the Jacobian at the angles read as radians "
                        "(20 rad, 70 rad): convert degrees first",
                    ),
                    Mistake(
                        np.degrees(qd),
                        "these rates are in °/s; the exercise asks for rad/s",
                    ),
                    Mistake(
                        np.array([qd[0], qd[0] + qd[1]]),
                        "the second rate is that of link 2's absolute angle (from "
                        "the x axis): q2 is measured from link 1",
                    ),
                ),
                hints=(
                    "Reread 'Tip velocity from joint rates, and back'; your "
                    "joint_rates function does the work.",
                    "Write the tip velocity straight up as a vector (x first), use "
                    "the pose in radians, and solve J qd = v for qd.",
                ),
            ),
        ),
    )


def hidden_joint_rates(rng: np.random.Generator, count: int) -> list[Case]:
    """``count`` calls of ``joint_rates`` on random arms, poses away from the singularities and tip velocities."""
    cases = []
    for _ in range(count):
        l1, l2 = (float(v) for v in np.round(rng.uniform(0.05, 3.0, 2), 3))
        q2 = rng.choice([-1.0, 1.0]) * rng.uniform(0.25, np.pi - 0.25)
        q = np.array([rng.uniform(-np.pi, np.pi), q2])
        v_tip = rng.uniform(-1.0, 1.0, 2) * max(l1, l2)
        cases.append(_rates_case(l1, l2, q, v_tip))
    return cases


HIDDEN = {("3.1", "joint_rates"): hidden_joint_rates}


def exercise_3_2() -> ExerciseSpec:
    arm = arms.osake
    q = np.radians([0.0, Q2_3_2_DEG])
    omega = np.radians(RATE_3_2_DEG_S)  # rad/s

    def speed(q_: object, rate: float, on: TwoLinkArm = arm) -> float:
        return float(np.linalg.norm(on.tip_velocity(q_, [rate, 0.0])))

    right = speed(q, omega)
    return ExerciseSpec(
        "3.2",
        CHAPTER,
        (
            PartSpec(
                "tip_speed_ex2",
                "tip speed",
                "number",
                expected=right,
                unit="m/s",
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        speed(q, RATE_3_2_DEG_S),
                        "this is r times the rate in °/s: the linear speed is r "
                        "times omega in rad/s",
                    ),
                    Mistake(
                        (arm.l1 + arm.l2) * omega,
                        "this radius is l1 + l2, the stretched arm's: with the "
                        "elbow bent the tip is closer to the base",
                    ),
                    Mistake(
                        speed(np.array([0.0, Q2_3_2_DEG]), omega),
                        "this radius is that of the elbow angle read as radians: "
                        "convert q2 to radians first",
                    ),
                    Mistake(
                        omega,
                        "this is the arm's angular velocity omega (rad/s); the "
                        "exercise asks for the tip's linear speed, in m/s",
                    ),
                    Mistake(1000 * right, "this is in mm/s; the exercise asks for m/s"),
                    Mistake(100 * right, "this is in cm/s; the exercise asks for m/s"),
                ),
                hints=(
                    "Reread 'The OSAKE circle: how fast does the tip move?': with "
                    "joint 2 held, the whole arm turns rigidly about the base.",
                    "The tip moves on a circle about the base: its radius is the "
                    "base-to-tip distance at this elbow angle, and the rate must be "
                    "in rad/s.",
                ),
            ),
        ),
    )


def condition_3_3(q2: float, arm: TwoLinkArm = arms.osake) -> float:
    """sigma_max / sigma_min of ``arm``'s Jacobian at elbow angle ``q2`` (rad); q1 does not change it."""
    return float(np.linalg.cond(arm.jacobian([0.0, q2])))


def roundest_3_3(arm: TwoLinkArm = arms.osake) -> float:
    """The elbow angle in (0, pi) of the smallest condition number (rad), by a bounded scalar search."""
    found = scipy.optimize.minimize_scalar(
        lambda q2: condition_3_3(q2, arm),
        bounds=(0.05, np.pi - 0.05),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return float(found.x)


def exercise_3_3() -> ExerciseSpec:
    arm = arms.osake
    best = roundest_3_3(arm)
    cond_best = condition_3_3(best, arm)
    near = best + np.radians(ANGLE_TOLERANCE_DEG_3_3) * np.array([-1.0, 1.0])
    slack = max(condition_3_3(q2, arm) for q2 in near) - cond_best
    equal = TwoLinkArm(l1=arm.l1, l2=arm.l1)  # an equal-link arm (the 2 m arm's shape)
    swapped = TwoLinkArm(l1=arm.l2, l2=arm.l1)
    other_ratio = (
        "an arm of other proportions (equal links, like the 2 m arm, or the table's "
        "arm_line, whose curve is the same): use the OSAKE arm's link lengths"
    )
    return ExerciseSpec(
        "3.3",
        CHAPTER,
        (
            PartSpec(
                "q2_best_deg_ex3",
                "elbow angle",
                "number",
                expected=np.degrees(best),
                unit="deg",
                tolerance=Tolerance(atol=ANGLE_TOLERANCE_DEG_3_3, rtol=0.0),
                mistakes=(
                    Mistake(best, "this is in radians; the exercise asks for degrees"),
                    Mistake(
                        90.0,
                        "at 90° the ellipse is largest (the manipulability peaks), "
                        "not roundest",
                    ),
                    Mistake(
                        np.degrees(roundest_3_3(equal)),
                        f"this is the roundest elbow angle of {other_ratio}",
                    ),
                    Mistake(
                        np.degrees(roundest_3_3(swapped)),
                        "this is the roundest elbow angle with l1 and l2 swapped: "
                        "link 1 (10 cm) runs from the base to the elbow",
                    ),
                    Mistake(
                        -np.degrees(best),
                        "this is the mirror elbow (q2 < 0), as round as the one "
                        "asked for; the exercise asks for q2 between 0° and 180°",
                    ),
                ),
                hints=(
                    "Reread 'The velocity ellipse': its semi-axes are the singular "
                    "values of J, and a round ellipse has them equal.",
                    "Only q2 changes the ellipse's shape (q1 turns it): scan q2 over "
                    "(0°, 180°) in steps of 1° or finer with the OSAKE arm's "
                    "Jacobian and keep the angle where np.linalg.cond is smallest.",
                ),
            ),
            PartSpec(
                "cond_best_ex3",
                "condition number",
                "number",
                expected=cond_best,
                unit="",
                tolerance=Tolerance(atol=slack + 1e-9, rtol=0.0),
                mistakes=(
                    Mistake(
                        1.0 / cond_best,
                        "this is sigma_min / sigma_max; the condition number is "
                        "sigma_max / sigma_min (at least 1)",
                    ),
                    Mistake(
                        cond_best**2,
                        "this is the condition number of J J^T (or J^T J), the "
                        "square of J's",
                    ),
                    Mistake(
                        condition_3_3(np.pi / 2, arm),
                        "this is the condition number at q2 = 90°, where the "
                        "ellipse is largest, not where it is roundest",
                    ),
                    Mistake(
                        condition_3_3(roundest_3_3(equal), equal),
                        f"this is the smallest condition number of {other_ratio}",
                    ),
                    Mistake(
                        condition_3_3(roundest_3_3(swapped), swapped),
                        "this is the smallest condition number with l1 and l2 "
                        "swapped: link 1 runs from the base to the elbow",
                    ),
                ),
                hints=(
                    "The condition number of J is sigma_max / sigma_min, never "
                    "below 1; reread 'The velocity ellipse'.",
                    "Take the smallest np.linalg.cond of the OSAKE arm's Jacobian "
                    "over your scan of q2 (of J itself, not of J J^T).",
                ),
            ),
        ),
    )


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_3_1(), exercise_3_2(), exercise_3_3()]
