"""Chapter 3 (Jacobian and velocity): the references of exercises 3.1 to 3.6, with typical mistakes and hints.

Exercise 3.1 asks for a function, ``joint_rates(arm, q, v_tip)``, checked on
the visible cases below and graded on hidden ones (:data:`HIDDEN`) with the
package's Jacobian and joint rates switched off (:data:`FORBIDDEN`).  The value
parts of 3.1 to 3.4 and 3.6 read their data from an inputs cell and are graded
on hidden inputs too (:data:`RERUN`); 3.5 is worked on paper (the determinant
of J and its zeros, :data:`PEN_AND_PAPER`).
"""

from __future__ import annotations

import numpy as np
import scipy.optimize

from answers import Rerun
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


def _inputs_3_1() -> dict[str, object]:
    return {
        "arm_ex1": arms.two_metre,
        "q_ex1": np.radians(Q_3_1_DEG),
        "v_tip_ex1": np.array(V_TIP_3_1),
    }


def _answers_3_1(inputs: dict) -> dict[str, object]:
    return {
        "qd_ex1": inputs["arm_ex1"].joint_rates(inputs["q_ex1"], inputs["v_tip_ex1"])
    }


def _random_arm(rng: np.random.Generator, offset: bool = False) -> TwoLinkArm:
    """An arm like the chapter's: links of 5 cm to 3 m (and a base offset up to 0.2 m, if asked)."""
    l1, l2 = (round(float(v), 3) for v in rng.uniform(0.05, 3.0, 2))
    d = round(float(rng.uniform(-0.2, 0.2)), 3) if offset else 0.0
    return TwoLinkArm(l1=l1, l2=l2, d=d)


def _bent(rng: np.random.Generator) -> np.ndarray:
    """Joint angles (rad) with the elbow at least 15 deg from stretched or folded."""
    q2 = rng.choice([-1.0, 1.0]) * rng.uniform(np.radians(15.0), np.radians(165.0))
    return np.array([rng.uniform(-np.pi, np.pi), q2]).round(4)


def _hidden_3_1(rng: np.random.Generator) -> dict[str, object]:
    arm = _random_arm(rng)
    return {
        "arm_ex1": arm,
        "q_ex1": _bent(rng),
        "v_tip_ex1": (rng.uniform(-0.5, 0.5, 2) * arm.l1).round(4),
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
                    "for qd rather than inverting J; arm.jacobian and "
                    "arm.joint_rates are switched off while your function runs.",
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
                    "Call your function on arm_ex1, q_ex1 and v_tip_ex1 (the pose in "
                    "radians, the velocity x first): it solves J qd = v for qd.",
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


def _inputs_3_2() -> dict[str, object]:
    return {
        "arm_ex2": arms.osake,
        "q2_held_ex2": np.radians(Q2_3_2_DEG),
        "q1_rate_ex2": np.radians(RATE_3_2_DEG_S),
    }


def _answers_3_2(inputs: dict) -> dict[str, object]:
    arm, q2, rate = inputs["arm_ex2"], inputs["q2_held_ex2"], inputs["q1_rate_ex2"]
    return {
        "tip_speed_ex2": float(np.linalg.norm(arm.tip_velocity([0.0, q2], [rate, 0.0])))
    }


def _hidden_3_2(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex2": _random_arm(rng),
        "q2_held_ex2": round(float(rng.uniform(0.2, 3.0)), 4),
        "q1_rate_ex2": round(float(np.radians(rng.uniform(1.0, 30.0))), 5),
    }


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
                        "times omega in rad/s (q1_rate_ex2 holds rad/s)",
                    ),
                    Mistake(
                        (arm.l1 + arm.l2) * omega,
                        "this radius is l1 + l2, the stretched arm's: with the "
                        "elbow bent the tip is closer to the base",
                    ),
                    Mistake(
                        speed(np.array([0.0, Q2_3_2_DEG]), omega),
                        "this radius is that of the elbow angle in degrees read as "
                        "radians: q2_held_ex2 holds radians already",
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


#: The link ratios l2 / l1 of exercise 3.3's arms: the OSAKE arm's and the hidden ones'.
RATIOS_3_3 = (1.0, 1.5)


def _inputs_3_3() -> dict[str, object]:
    return {"arm_ex3": arms.osake}


def _answers_3_3(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex3"]
    best = roundest_3_3(arm)
    return {
        "q2_best_deg_ex3": np.degrees(best),
        "cond_best_ex3": condition_3_3(best, arm),
    }


def _hidden_3_3(rng: np.random.Generator) -> dict[str, object]:
    l1 = round(float(rng.uniform(0.05, 2.0)), 3)
    return {
        "arm_ex3": TwoLinkArm(l1=l1, l2=round(l1 * float(rng.uniform(*RATIOS_3_3)), 3))
    }


def _slack_3_3(arm: TwoLinkArm) -> float:
    """How much the condition number grows half a degree away from its minimum."""
    best = roundest_3_3(arm)
    near = best + np.radians(ANGLE_TOLERANCE_DEG_3_3) * np.array([-1.0, 1.0])
    return max(condition_3_3(q2, arm) for q2 in near) - condition_3_3(best, arm)


def exercise_3_3() -> ExerciseSpec:
    arm = arms.osake
    best = roundest_3_3(arm)
    cond_best = condition_3_3(best, arm)
    # the slack of an angle half a degree off, the largest over the exercise's link ratios
    slack = max(
        _slack_3_3(TwoLinkArm(l1=1.0, l2=ratio))
        for ratio in np.linspace(*RATIOS_3_3, 11)
    )
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
                    "(0°, 180°) in steps of 1° or finer with arm_ex3's Jacobian "
                    "and keep the angle where np.linalg.cond is smallest.",
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
                    "Take the smallest np.linalg.cond of arm_ex3's Jacobian over "
                    "your scan of q2 (of J itself, not of J J^T).",
                ),
            ),
        ),
    )


Q_3_4_DEG = (40.0, -70.0)  # the OSAKE arm


def _geometric_jacobian(arm: TwoLinkArm, q: np.ndarray) -> np.ndarray:
    return np.asarray(arm.geometric_jacobian(q), dtype=float)


def _inputs_3_4() -> dict[str, object]:
    return {"arm_ex4": arms.osake, "q_ex4": np.radians(Q_3_4_DEG)}


def _answers_3_4(inputs: dict) -> dict[str, object]:
    return {"J_geo_ex4": _geometric_jacobian(inputs["arm_ex4"], inputs["q_ex4"])}


def _hidden_3_4(rng: np.random.Generator) -> dict[str, object]:
    return {"arm_ex4": _random_arm(rng, offset=True), "q_ex4": _bent(rng)}


def exercise_3_4() -> ExerciseSpec:
    arm, q = arms.osake, np.radians(Q_3_4_DEG)
    J = _geometric_jacobian(arm, q)
    T_01, T_02 = arm.transforms(q)
    z, o1, o2 = np.array([0.0, 0.0, 1.0]), T_01[:3, 3], T_02[:3, 3]
    from_base = np.column_stack([np.cross(z, o2), np.cross(z, o2)])
    from_elbow = np.column_stack([np.cross(z, o2 - o1), np.cross(z, o2 - o1)])
    no_omega = J.copy()
    no_omega[3:] = 0.0
    return ExerciseSpec(
        "3.4",
        CHAPTER,
        (
            PartSpec(
                "J_geo_ex4",
                "geometric Jacobian",
                "matrix",
                expected=J,
                shape=(6, 2),
                mistakes=(
                    Mistake(
                        np.vstack([from_base, J[3:]]),
                        "both columns use the lever from the base: joint 2 turns "
                        "only link 2, about z_1 through the elbow o_1",
                    ),
                    Mistake(
                        np.vstack([from_elbow, J[3:]]),
                        "both columns use the lever from the elbow: joint 1 turns "
                        "the whole arm, about z_0 through the base o_0",
                    ),
                    Mistake(
                        no_omega,
                        "the angular rows are zero: each revolute joint turns the tip "
                        "frame at its own axis z_{i-1}, here (0, 0, 1)",
                    ),
                    Mistake(
                        np.vstack([-J[:3], J[3:]]),
                        "the linear rows have the wrong sign: the cross product is "
                        "z_{i-1} x (o_2 - o_{i-1}), in that order",
                    ),
                ),
                hints=(
                    "Reread 'The 6x2 geometric Jacobian, from the DH frames': each "
                    "column stacks z_{i-1} x (o_2 - o_{i-1}) over z_{i-1}.",
                    "Take z_0 = (0, 0, 1) and o_0 = 0 for the base, z_1 and o_1 from "
                    "the third and fourth columns of T_0^1 (arm_ex4.transforms(q_ex4)"
                    "[0]), and o_2 from T_0^2; np.cross does the cross products.",
                ),
            ),
        ),
    )


#: Exercise 3.5's bench arm, in metres, and the pose of its determinant, in degrees.
BENCH_3_5 = TwoLinkArm(l1=0.30, l2=0.20)
Q_3_5_DEG = (40.0, 30.0)
BY_HAND = Tolerance(significant=3)


def exercise_3_5() -> ExerciseSpec:
    arm, q = BENCH_3_5, np.radians(Q_3_5_DEG)
    det = float(np.linalg.det(arm.jacobian(q)))
    zeros = np.array([0.0, 180.0])  # q2 in (-180, 180] deg where sin q2 = 0
    return ExerciseSpec(
        "3.5",
        CHAPTER,
        (
            PartSpec(
                "det_J_ex5",
                "det J",
                "number",
                expected=det,
                unit="m²",
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        arm.l1 * arm.l2 * np.cos(q[1]),
                        "this is l1 l2 cos q2: the determinant has the sine of the "
                        "elbow angle",
                    ),
                    Mistake(
                        arm.l1 * arm.l2 * np.sin(q.sum()),
                        "this is l1 l2 sin(q1 + q2): q1 drops out of the determinant, "
                        "only the elbow angle q2 is left",
                    ),
                    Mistake(
                        arm.l1 * arm.l2,
                        "this is l1 l2, the determinant's largest value (at q2 = "
                        "90 deg): multiply by sin q2",
                    ),
                    Mistake(
                        arm.l1 * arm.l2 * Q_3_5_DEG[1],
                        "the angle went in degrees: sin of 30 deg, not 30 times l1 l2",
                    ),
                ),
                hints=(
                    "Reread 'Singularities: det J = l1 l2 sin q2'; derive it yourself "
                    "from the four entries of J.",
                    "det J = J11 J22 - J12 J21; expand the products and use "
                    "sin a cos b - cos a sin b = sin(a - b): q1 drops out.",
                ),
            ),
            PartSpec(
                "singular_q2_deg_ex5",
                "singular elbow angles",
                "vector",
                expected=zeros,
                shape=(2,),
                unit="deg",
                components=("first", "second"),
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        [90.0, -90.0],
                        "at +-90 deg det J is largest, l1 l2 in size: it is zero where "
                        "sin q2 = 0",
                    ),
                    Mistake(
                        [-90.0, 90.0],
                        "at +-90 deg det J is largest, l1 l2 in size: it is zero where "
                        "sin q2 = 0",
                    ),
                    Mistake(
                        [0.0, np.pi],
                        "the second angle is in radians; give both in degrees",
                    ),
                ),
                hints=(
                    "Reread 'Singularities: det J = l1 l2 sin q2': where is sin q2 "
                    "zero in a full turn of the elbow?",
                    "Two angles: the arm stretched and the arm folded; give them in "
                    "degrees, the smaller first, the folded one as a positive angle.",
                ),
            ),
        ),
    )


Q_3_6_DEG, DAMPING_3_6 = (30.0, 3.0), 0.1  # the 2 m arm nearly stretched; m/rad
V_TIP_3_6 = (
    0.1 * np.cos(np.radians(31.5)),
    0.1 * np.sin(np.radians(31.5)),
)  # m/s, along the arm


def _inputs_3_6() -> dict[str, object]:
    return {
        "arm_ex6": arms.two_metre,
        "q_ex6": np.radians(Q_3_6_DEG),
        "v_tip_ex6": np.array(V_TIP_3_6),
        "damping_ex6": DAMPING_3_6,
    }


def _answers_3_6(inputs: dict) -> dict[str, object]:
    arm, q, v = inputs["arm_ex6"], inputs["q_ex6"], inputs["v_tip_ex6"]
    return {
        "qd_exact_ex6": np.linalg.solve(arm.jacobian(q), v),
        "qd_dls_ex6": arm.joint_rates_dls(q, v, damping=inputs["damping_ex6"]),
    }


def _hidden_3_6(rng: np.random.Generator) -> dict[str, object]:
    arm = _random_arm(rng)
    q1 = float(rng.uniform(-np.pi, np.pi))
    q = np.array([q1, rng.choice([-1.0, 1.0]) * np.radians(rng.uniform(1.0, 8.0))])
    along = q1 + rng.uniform(-0.3, 0.3)
    speed = float(rng.uniform(0.05, 0.5)) * arm.l1
    return {
        "arm_ex6": arm,
        "q_ex6": q.round(5),
        "v_tip_ex6": (speed * np.array([np.cos(along), np.sin(along)])).round(5),
        "damping_ex6": round(float(rng.uniform(0.02, 0.2)) * min(arm.l1, arm.l2), 4),
    }


def exercise_3_6() -> ExerciseSpec:
    answers = _answers_3_6(_inputs_3_6())
    arm, q, v = arms.two_metre, np.radians(Q_3_6_DEG), np.array(V_TIP_3_6)
    J = arm.jacobian(q)
    exact, dls = (np.asarray(answers[name]) for name in ("qd_exact_ex6", "qd_dls_ex6"))
    return ExerciseSpec(
        "3.6",
        CHAPTER,
        (
            PartSpec(
                "qd_exact_ex6",
                "exact joint rates",
                "vector",
                expected=exact,
                shape=(2,),
                unit="rad/s",
                components=RATES,
                mistakes=(
                    Mistake(
                        J.T @ v,
                        "this is J^T v: the exact rates solve J qd = v",
                    ),
                    Mistake(
                        dls,
                        "these are the damped rates; part (a) asks for the exact "
                        "inverse, np.linalg.solve(J, v)",
                    ),
                ),
                hints=(
                    "Reread 'Resolved-rate motion past a singularity': the exact "
                    "inverse solves J qd = v.",
                    "np.linalg.solve(arm_ex6.jacobian(q_ex6), v_tip_ex6).",
                ),
            ),
            PartSpec(
                "qd_dls_ex6",
                "damped joint rates",
                "vector",
                expected=dls,
                shape=(2,),
                unit="rad/s",
                components=RATES,
                mistakes=(
                    Mistake(
                        J.T @ np.linalg.solve(J @ J.T + DAMPING_3_6 * np.eye(2), v),
                        "this damps with lambda, not lambda squared: J^T (J J^T + "
                        "lambda^2 I)^-1 v",
                    ),
                    Mistake(
                        exact,
                        "these are the exact rates: the damped inverse adds lambda^2 I "
                        "to J J^T before solving",
                    ),
                    Mistake(
                        np.linalg.solve(J @ J.T + DAMPING_3_6**2 * np.eye(2), v),
                        "the J^T in front is missing: qd = J^T (J J^T + lambda^2 I)^-1 "
                        "v",
                    ),
                ),
                hints=(
                    "Reread 'Resolved-rate motion past a singularity': the damped "
                    "least-squares inverse is J^T (J J^T + lambda^2 I)^-1.",
                    "Solve (J J^T + lambda^2 I) w = v for w with np.linalg.solve, "
                    "then qd = J^T w; lambda is damping_ex6, in m/rad. Its norm "
                    "stays below |v| / (2 lambda).",
                ),
            ),
        ),
    )


#: The visible inputs of each value exercise, a draw of hidden ones, and the references for any.
RERUN = {
    "3.1": Rerun(inputs=_inputs_3_1(), hidden=_hidden_3_1, answers=_answers_3_1),
    "3.2": Rerun(inputs=_inputs_3_2(), hidden=_hidden_3_2, answers=_answers_3_2),
    "3.3": Rerun(inputs=_inputs_3_3(), hidden=_hidden_3_3, answers=_answers_3_3),
    "3.4": Rerun(inputs=_inputs_3_4(), hidden=_hidden_3_4, answers=_answers_3_4),
    "3.6": Rerun(inputs=_inputs_3_6(), hidden=_hidden_3_6, answers=_answers_3_6),
}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("3.1", "joint_rates"): (
        "twolink.arm.TwoLinkArm.jacobian",
        "twolink.kinematics.jacobian",
        "twolink.kinematics.jacobian_from_trig",
        "twolink.arm.TwoLinkArm.geometric_jacobian",
        "twolink.dh.geometric_jacobian",
        "twolink.arm.TwoLinkArm.joint_rates",
        "twolink.velocity.joint_rates",
        "twolink.arm.TwoLinkArm.joint_rates_dls",
        "twolink.velocity.joint_rates_dls",
    ),
}

#: Parts worked on paper: checked on the visible values only, timed as pen-and-paper parts.
PEN_AND_PAPER = (("3.5", "det_J_ex5"), ("3.5", "singular_q2_deg_ex5"))


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_3_1(),
        exercise_3_2(),
        exercise_3_3(),
        exercise_3_4(),
        exercise_3_5(),
        exercise_3_6(),
    ]
