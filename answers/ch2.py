"""Chapter 2 (inverse kinematics): the references of exercises 2.1 to 2.4, with typical mistakes and hints.

Exercise 2.4 asks for a function, ``elbow_up_angles(arm, p)``: the notebook's
self-check calls it on the visible cases below; the grader calls it on the
cases :data:`HIDDEN` draws from a seed the notebook never holds.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from twolink import TwoLinkArm, UnreachableError, arms, ik
from twolink.ik.grid_search import grid_axis
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "02_inverse_kinematics"
TARGET_2_1 = (12.0, 4.0)  # on arms.ten
ERROR_BOUND_2_2 = 0.01  # m
Q1_RANGE_DEG_2_2, Q2_RANGE_DEG_2_2 = (0.0, 90.0), (-90.0, 90.0)
TARGET_2_3 = (15.0, 16.0)  # out of arms.ten's reach
#: The visible calls of exercise 2.4: (l1, l2) and a target within reach.  One
#: target has x < 0 (atan(y/x) lands in the wrong quadrant), the other arms have
#: unequal links (swapping them changes the answer).
CASES_2_4 = (
    ((10.0, 10.0), (-6.0, 13.0)),
    ((2.0, 1.0), (1.5, 1.8)),
    ((0.5, 0.8), (0.3, -0.9)),
)
ANGLES = ("q1", "q2")


def _q1(arm: TwoLinkArm, p: tuple[float, float], q2: float) -> float:
    """q1 for a given q2: the second ``atan2`` of the closed form."""
    x, y = p
    return float(
        np.arctan2(y, x) - np.arctan2(arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.cos(q2))
    )


def _sin_typo(arm: TwoLinkArm, p: tuple[float, float], q2: float) -> float:
    """q1 with the typo ``l1 + l2 sin q2`` where ``l1 + l2 cos q2`` belongs."""
    x, y = p
    return float(
        np.arctan2(y, x) - np.arctan2(arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.sin(q2))
    )


def _up(arm: TwoLinkArm, p: tuple[float, float]) -> np.ndarray:
    return np.asarray(ik.closed_form(arm, p, elbow="up").q, dtype=float)


def _down(arm: TwoLinkArm, p: tuple[float, float]) -> np.ndarray:
    return np.asarray(ik.closed_form(arm, p, elbow="down").q, dtype=float)


def exercise_2_1() -> ExerciseSpec:
    arm, p = arms.ten, TARGET_2_1
    q_up, q_down = _up(arm, p), _down(arm, p)
    within = bool(arm.within_limits(q_up))
    return ExerciseSpec(
        "2.1",
        CHAPTER,
        (
            PartSpec(
                "q_elbow_up",
                "elbow-up angles",
                "angles",
                expected=q_up,
                shape=(2,),
                unit="rad",
                components=ANGLES,
                mistakes=(
                    Mistake(
                        q_down,
                        "this is the elbow-down solution (q2 > 0): the exercise asks "
                        "for elbow up",
                    ),
                    Mistake(
                        np.degrees(q_up),
                        "these are the elbow-up angles in degrees; the answer is in "
                        "radians",
                    ),
                    Mistake(
                        [q_up[0], q_up[0] + q_up[1]],
                        "your q2 is link 2's absolute direction (q1 + q2); q2 is "
                        "measured from link 1",
                    ),
                    Mistake(
                        [q_down[0], q_up[1]],
                        "your q1 belongs to the elbow-down branch: changing the sign "
                        "of q2 changes q1 too, so compute q1 from your own q2",
                    ),
                    Mistake(
                        [_sin_typo(arm, p, q_up[1]), q_up[1]],
                        "q2 is right but q1 is not: the second atan2 needs "
                        "l1 + l2 cos q2, not l1 + l2 sin q2",
                    ),
                ),
                hints=(
                    "Reread 'Why the branches are named by the sign of q2': which "
                    "sign of q2 is elbow up?",
                    "ik.closed_form takes the branch as elbow=...; put the angles "
                    "you find through arms.ten.fk and compare with the target.",
                ),
            ),
            PartSpec(
                "up_within_limits",
                "within the limits",
                "bool",
                expected=within,
                mistakes=(
                    Mistake(
                        not within,
                        "not so: compare each elbow-up angle with arms.ten's limits "
                        "(arms.ten.q_min and arms.ten.q_max, radians, q2 relative to "
                        "link 1), or let arms.ten.within_limits judge them",
                    ),
                ),
                hints=(
                    "Reread the chapter's introduction, where it gives the arm's "
                    "joint limits, and compare them with the angles you found.",
                    "Compare q1 with joint 1's limits and q2 with joint 2's, all in "
                    "radians (arms.ten.within_limits does exactly that); the answer "
                    "is a bool.",
                ),
            ),
        ),
    )


def _grid_counts(step: float) -> tuple[int, int]:
    (q1_low, q1_high), (q2_low, q2_high) = (
        np.radians(Q1_RANGE_DEG_2_2),
        np.radians(Q2_RANGE_DEG_2_2),
    )
    return len(grid_axis(q1_low, q1_high, step)), len(grid_axis(q2_low, q2_high, step))


def exercise_2_2() -> ExerciseSpec:
    arm = arms.ten
    step = 2 * ERROR_BOUND_2_2 / (arm.l1 + 2 * arm.l2)  # rad
    count_1, count_2 = _grid_counts(step)
    range_1, range_2 = (
        np.radians(np.ptp(Q1_RANGE_DEG_2_2)),
        np.radians(np.ptp(Q2_RANGE_DEG_2_2)),
    )
    return ExerciseSpec(
        "2.2",
        CHAPTER,
        (
            PartSpec(
                "step_1cm_deg",
                "grid step",
                "number",
                expected=np.degrees(step),
                unit="deg",
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        step,
                        "this is the step in radians; the exercise asks for degrees",
                    ),
                    Mistake(
                        np.degrees(step / 2),
                        "this step makes (a1 + 2 a2) times the step equal 1 cm: the "
                        "error bound is half of that, so the step can be larger",
                    ),
                    Mistake(
                        np.degrees(2 * ERROR_BOUND_2_2 / (arm.l1 + arm.l2)),
                        "this step uses a1 + a2; the error bound has a1 + 2 a2 (a "
                        "step of joint 1 turns link 2 as well)",
                    ),
                    Mistake(
                        np.degrees(2 * 1.0 / (arm.l1 + 2 * arm.l2)),
                        "this bound is 1 m, not 1 cm: the arm's lengths are in "
                        "metres, so write the bound in metres too",
                    ),
                ),
                hints=(
                    "Reread 'How brute-force cost grows with resolution': the error "
                    "bound is a formula in the step; set it equal to 1 cm.",
                    "Solve the bound for the step with the lengths and the bound in "
                    "metres: the step comes out in radians, and the exercise asks "
                    "for degrees.",
                ),
            ),
            PartSpec(
                "grid_points_1cm",
                "number of grid points",
                "number",
                expected=count_1 * count_2,
                unit="points",
                mistakes=(
                    Mistake(
                        (count_1 - 1) * (count_2 - 1),
                        "one point short on each axis: the grid holds both ends of "
                        "each range (its last spacing is shorter when the range is "
                        "not a whole number of steps)",
                    ),
                    Mistake(
                        (count_1 - 2) * (count_2 - 2),
                        "two points short on each axis: floor(range / step) counts "
                        "whole steps, not points, and the grid holds both ends of "
                        "each range",
                    ),
                    Mistake(
                        (range_1 / step) * (range_2 / step),
                        "not a whole number of points: range / step counts steps, "
                        "and a grid has a whole number of points on each axis",
                    ),
                    Mistake(
                        count_1 + count_2,
                        "this is the sum of the two axes' points; the grid pairs "
                        "every q1 with every q2, so the sizes multiply",
                    ),
                    Mistake(
                        (np.ceil(np.ptp(Q1_RANGE_DEG_2_2) / step) + 1)
                        * (np.ceil(np.ptp(Q2_RANGE_DEG_2_2) / step) + 1),
                        "far too many points: the ranges are in degrees and the step "
                        "in radians; divide quantities in the same unit",
                    ),
                ),
                hints=(
                    "Reread 'How brute-force cost grows with resolution': count the "
                    "points along each joint's axis, then combine the two axes.",
                    "Along one axis the grid holds the lower end, each step after it "
                    "below the upper end, and the upper end itself; ranges and step "
                    "in the same unit.",
                ),
            ),
        ),
    )


def _message_2_3() -> str:
    try:
        ik.closed_form(arms.ten, TARGET_2_3)
    except UnreachableError as error:
        return str(error)
    raise AssertionError(f"{TARGET_2_3} should be out of reach of arms.ten")


def exercise_2_3() -> ExerciseSpec:
    arm = arms.ten
    message = _message_2_3()
    distance = float(np.hypot(*TARGET_2_3))
    beyond = distance - arm.reach[1]
    return ExerciseSpec(
        "2.3",
        CHAPTER,
        (
            PartSpec(
                "unreachable_message",
                "error message",
                "text",
                expected=message,
                mistakes=(
                    Mistake(
                        repr(UnreachableError(message)),
                        "this is repr(error), with the class name and quotes around "
                        "the message; keep str(error)",
                    ),
                    Mistake(
                        f"UnreachableError: {message}",
                        "this is the line a traceback prints, with the error's class "
                        "in front; the message is str(error) alone",
                    ),
                ),
                hints=(
                    "Reread the pitfall on acos of a number outside its domain: it "
                    "shows how the package reports a target out of reach.",
                    "Call ik.closed_form inside try / except UnreachableError as "
                    "error, and keep str(error): a str, not the error itself.",
                ),
            ),
            PartSpec(
                "distance_beyond_reach",
                "distance beyond the reach",
                "number",
                expected=beyond,
                unit="m",
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        -beyond,
                        "the sign is reversed: a target beyond the reach lies a "
                        "positive distance beyond it",
                    ),
                    Mistake(
                        distance,
                        "this is the target's distance from the base; the exercise "
                        "asks how far beyond the reach it lies",
                    ),
                    Mistake(
                        distance**2 - arm.reach[1] ** 2,
                        "this is a difference of squared distances: take the square "
                        "root of x^2 + y^2 before you subtract the reach",
                    ),
                    Mistake(
                        distance - arm.l1,
                        "this subtracts one link's length; the reach is the arm "
                        "outstretched, both links in a line",
                    ),
                ),
                hints=(
                    "Reread 'A double root and a two-branch target': how far from the "
                    "base does the arm reach when it is straight?",
                    "Subtract the arm's largest reach (arms.ten.reach holds it) from "
                    "the target's distance from the base; out of reach, the "
                    "difference is positive.",
                ),
            ),
        ),
    )


def _arm_argument(lengths: tuple[float, float]) -> dict[str, dict[str, float]]:
    return {"arm": {"l1": float(lengths[0]), "l2": float(lengths[1])}}


def _case(lengths: tuple[float, float], p: tuple[float, float]) -> Case:
    arm = TwoLinkArm(l1=lengths[0], l2=lengths[1])
    return Case(
        {"arm": _arm_argument(lengths), "p": [float(p[0]), float(p[1])]},
        _up(arm, p).tolist(),
    )


def _each_visible(
    mistaken: Callable[[TwoLinkArm, tuple[float, float]], object],
) -> list:
    """What a mistaken ``elbow_up_angles`` returns on each visible case."""
    return [
        np.asarray(mistaken(TwoLinkArm(l1=lengths[0], l2=lengths[1]), p), dtype=float)
        for lengths, p in CASES_2_4
    ]


def _atan_instead_of_atan2(arm: TwoLinkArm, p: tuple[float, float]) -> list[float]:
    x, y = p
    q2 = _up(arm, p)[1]
    q1 = np.arctan(y / x) - np.arctan2(
        arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.cos(q2)
    )
    return [float(q1), float(q2)]


def _links_swapped(arm: TwoLinkArm, p: tuple[float, float]) -> np.ndarray:
    return _up(TwoLinkArm(l1=arm.l2, l2=arm.l1), p)


def _absolute_q2(arm: TwoLinkArm, p: tuple[float, float]) -> list[float]:
    q1, q2 = _up(arm, p)
    return [q1, q1 + q2]


def _q1_of_the_other_branch(arm: TwoLinkArm, p: tuple[float, float]) -> list[float]:
    q2 = _up(arm, p)[1]
    return [_q1(arm, p, -q2), q2]


def _q1_with_the_sin_typo(arm: TwoLinkArm, p: tuple[float, float]) -> list[float]:
    q2 = _up(arm, p)[1]
    return [_sin_typo(arm, p, q2), q2]


def exercise_2_4() -> ExerciseSpec:
    output = PartSpec(
        "q",
        "elbow-up angles",
        "angles",
        shape=(2,),
        unit="rad",
        components=ANGLES,
    )
    return ExerciseSpec(
        "2.4",
        CHAPTER,
        (
            PartSpec(
                "elbow_up_angles",
                "function elbow_up_angles",
                "function",
                cases=tuple(_case(lengths, p) for lengths, p in CASES_2_4),
                output=output,
                mistakes=(
                    Mistake(
                        _each_visible(_down),
                        "your function returns the elbow-down solution (q2 > 0): it "
                        "should return elbow up",
                    ),
                    Mistake(
                        _each_visible(lambda arm, p: np.degrees(_up(arm, p))),
                        "your function returns degrees; return radians",
                    ),
                    Mistake(
                        _each_visible(_atan_instead_of_atan2),
                        "right for x > 0 only: atan(y / x) loses the quadrant of a "
                        "target with x < 0; use atan2(y, x)",
                    ),
                    Mistake(
                        _each_visible(_links_swapped),
                        "right only when the links are equal: l1 and l2 are swapped "
                        "somewhere in your formulas",
                    ),
                    Mistake(
                        _each_visible(_absolute_q2),
                        "your q2 is link 2's absolute direction (q1 + q2); return q2 "
                        "measured from link 1",
                    ),
                    Mistake(
                        _each_visible(_q1_of_the_other_branch),
                        "your q1 belongs to the elbow-down branch: compute q1 from "
                        "the q2 you return",
                    ),
                    Mistake(
                        _each_visible(_q1_with_the_sin_typo),
                        "q2 is right but q1 is not: the second atan2 needs "
                        "l1 + l2 cos q2, not l1 + l2 sin q2",
                    ),
                ),
                hints=(
                    "Reread 'Closed form: the cosine rule, then atan2' and 'Why the "
                    "branches are named by the sign of q2': the function does for "
                    "any arm what exercise 2.1 did for one.",
                    "Take the lengths from the arm you are given (arm.l1, arm.l2), "
                    "choose the sign of q2 that puts the elbow up, and use atan2, "
                    "which keeps the quadrant of every target.",
                    "Test it yourself on targets in every quadrant and on arms with "
                    "unequal links: arm.fk of what it returns must land on p.",
                ),
            ),
        ),
    )


def hidden_2_4(rng: np.random.Generator, count: int) -> list[Case]:
    """``count`` arms and targets within reach, drawn with ``rng``: the grader's cases.

    Link lengths from 0.3 m to 3 m (to the centimetre); targets in every
    direction, at a distance from the base between the reach's ends, kept a
    tenth of the reach's width away from them (the two branches distinct).
    """
    visible = {(lengths, p) for lengths, p in CASES_2_4}
    cases: list[Case] = []
    while len(cases) < count:
        l1, l2 = np.round(rng.uniform(0.3, 3.0, 2), 2)
        low, high = abs(l1 - l2), l1 + l2
        margin = 0.1 * (high - low)
        distance = rng.uniform(low + margin, high - margin)
        direction = rng.uniform(-np.pi, np.pi)
        p = (
            round(float(distance * np.cos(direction)), 3),
            round(float(distance * np.sin(direction)), 3),
        )
        if not low + 0.5 * margin < np.hypot(*p) < high - 0.5 * margin:
            continue  # rounding moved it towards an end of the reach
        lengths = (float(l1), float(l2))
        if (lengths, p) in visible:
            continue
        cases.append(_case(lengths, p))
    return cases


#: The grader's hidden cases, by (exercise, part): generator(rng, count) -> cases.
HIDDEN = {("2.4", "elbow_up_angles"): hidden_2_4}


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_2_1(), exercise_2_2(), exercise_2_3(), exercise_2_4()]
