"""Chapter 2 (inverse kinematics): the references of exercises 2.1 to 2.5, with typical mistakes and hints.

Exercises 2.1, 2.2, 2.3 and 2.5 read their data from an inputs cell and are
graded on hidden inputs too (``RERUN``).  Exercise 2.4 asks for a function,
``elbow_up_angles(arm, p)``: the notebook's self-check calls it on the visible
cases below; the grader calls it on the cases :data:`HIDDEN` draws from a seed
the notebook never holds, with the package's IK solvers switched off
(``FORBIDDEN``).  2.5's choice of reason is worked on paper (``PEN_AND_PAPER``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from answers import Rerun
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
TARGET_2_1 = (14.0, 9.0)  # on arms.ten: elbow up within the limits, elbow down not
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


def _inputs_2_1() -> dict[str, object]:
    return {"arm_ex1": arms.ten, "p_ex1": np.array(TARGET_2_1)}


def _answers_2_1(inputs: dict) -> dict[str, object]:
    arm, p = inputs["arm_ex1"], tuple(inputs["p_ex1"])
    q_up = _up(arm, p)
    return {"q_elbow_up": q_up, "up_within_limits": bool(arm.within_limits(q_up))}


def _ten_like(l1: float, l2: float) -> TwoLinkArm:
    """An arm with arms.ten's joint limits and the given link lengths."""
    return TwoLinkArm(l1=l1, l2=l2, q_min=arms.ten.q_min, q_max=arms.ten.q_max)


def _hidden_2_1(rng: np.random.Generator) -> dict[str, object]:
    """A target where one branch respects the limits and the other does not (the bool tells them apart)."""
    while True:
        arm = _ten_like(*(round(float(v), 1) for v in rng.uniform(5.0, 15.0, 2)))
        low, high = arm.reach
        distance = rng.uniform(low + 0.1 * (high - low), high - 0.1 * (high - low))
        direction = rng.uniform(-0.5, 2.0)
        p = np.round(distance * np.array([np.cos(direction), np.sin(direction)]), 2)
        q_both = ik.closed_form(arm, p, elbow="both").q
        if len(set(arm.within_limits(q_both).tolist())) == 2:
            return {"arm_ex1": arm, "p_ex1": p}


def exercise_2_1() -> ExerciseSpec:
    inputs = _inputs_2_1()
    arm, p = arms.ten, TARGET_2_1
    q_up, q_down = _up(arm, p), _down(arm, p)
    within = bool(_answers_2_1(inputs)["up_within_limits"])
    assert within != bool(
        arm.within_limits(q_down)
    )  # the bool tells the branches apart
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
                    "you find through arm_ex1.fk and compare with the target.",
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
                        "not so for the elbow-up branch (the elbow-down branch gives "
                        "this answer): compare each elbow-up angle with the arm's "
                        "limits (arm_ex1.q_min and arm_ex1.q_max, radians, q2 relative "
                        "to link 1), or let arm_ex1.within_limits judge them",
                    ),
                ),
                hints=(
                    "Reread the chapter's introduction, where it gives the arm's "
                    "joint limits, and compare them with the angles you found.",
                    "Compare q1 with joint 1's limits and q2 with joint 2's, all in "
                    "radians (arm_ex1.within_limits does exactly that), for the "
                    "elbow-up angles; the answer is a bool.",
                ),
            ),
        ),
    )


def _grid_counts(arm: TwoLinkArm, step: float) -> tuple[int, int]:
    """The points of ik.brute_force's grid along each joint's range (the arm's limits)."""
    assert arm.q_min is not None and arm.q_max is not None
    (q1_low, q2_low), (q1_high, q2_high) = arm.q_min, arm.q_max
    return len(grid_axis(q1_low, q1_high, step)), len(grid_axis(q2_low, q2_high, step))


def _inputs_2_2() -> dict[str, object]:
    return {"arm_ex2": arms.ten, "error_bound_ex2": ERROR_BOUND_2_2}


def _answers_2_2(inputs: dict) -> dict[str, object]:
    arm, bound = inputs["arm_ex2"], inputs["error_bound_ex2"]
    step = 2 * bound / (arm.l1 + 2 * arm.l2)
    count_1, count_2 = _grid_counts(arm, step)
    return {"step_deg_ex2": np.degrees(step), "grid_points_ex2": count_1 * count_2}


def _hidden_2_2(rng: np.random.Generator) -> dict[str, object]:
    lengths = (round(float(v), 1) for v in rng.uniform(5.0, 15.0, 2))
    return {
        "arm_ex2": _ten_like(*lengths),
        "error_bound_ex2": round(float(rng.uniform(0.005, 0.05)), 3),
    }


def exercise_2_2() -> ExerciseSpec:
    arm = arms.ten
    step = 2 * ERROR_BOUND_2_2 / (arm.l1 + 2 * arm.l2)  # rad
    count_1, count_2 = _grid_counts(arm, step)
    range_1, range_2 = (
        np.radians(np.ptp(Q1_RANGE_DEG_2_2)),
        np.radians(np.ptp(Q2_RANGE_DEG_2_2)),
    )
    return ExerciseSpec(
        "2.2",
        CHAPTER,
        (
            PartSpec(
                "step_deg_ex2",
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
                        "this step makes (a1 + 2 a2) times the step equal the bound: "
                        "the error bound is half of that, so the step can be larger",
                    ),
                    Mistake(
                        np.degrees(2 * ERROR_BOUND_2_2 / (arm.l1 + arm.l2)),
                        "this step uses a1 + a2; the error bound has a1 + 2 a2 (a "
                        "step of joint 1 turns link 2 as well)",
                    ),
                    Mistake(
                        np.degrees(2 * 1.0 / (arm.l1 + 2 * arm.l2)),
                        "this bound is 1 m, not 1 cm: the arm's lengths are in "
                        "metres, and so is error_bound_ex2",
                    ),
                ),
                hints=(
                    "Reread 'How brute-force cost grows with resolution': the error "
                    "bound is a formula in the step; set it equal to error_bound_ex2.",
                    "Solve the bound for the step with the lengths (arm_ex2.l1, "
                    "arm_ex2.l2) and error_bound_ex2, all in metres: the step comes "
                    "out in radians, and the exercise asks for degrees.",
                ),
            ),
            PartSpec(
                "grid_points_ex2",
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
                    "Along one axis (from arm_ex2.q_min to arm_ex2.q_max) the grid "
                    "holds the lower end, each step after it below the upper end, and "
                    "the upper end itself; ranges and step in the same unit.",
                ),
            ),
        ),
    )


def _message_2_3(arm: TwoLinkArm, p: tuple[float, float]) -> str:
    try:
        ik.closed_form(arm, p)
    except UnreachableError as error:
        return str(error)
    raise AssertionError(f"{p} should be out of reach of {arm}")


def _inputs_2_3() -> dict[str, object]:
    return {"arm_ex3": arms.ten, "p_ex3": np.array(TARGET_2_3)}


def _answers_2_3(inputs: dict) -> dict[str, object]:
    arm, p = inputs["arm_ex3"], inputs["p_ex3"]
    return {
        "unreachable_message": _message_2_3(arm, tuple(p)),
        "distance_beyond_reach": float(np.hypot(*p)) - arm.reach[1],
    }


def _hidden_2_3(rng: np.random.Generator) -> dict[str, object]:
    """A target 5 % to 50 % beyond the reach of an arm like arms.ten, in any direction."""
    arm = _ten_like(*(round(float(v), 1) for v in rng.uniform(5.0, 15.0, 2)))
    distance = arm.reach[1] * rng.uniform(1.05, 1.5)
    direction = rng.uniform(-np.pi, np.pi)
    p = np.round(distance * np.array([np.cos(direction), np.sin(direction)]), 1)
    return {"arm_ex3": arm, "p_ex3": p}


def exercise_2_3() -> ExerciseSpec:
    arm = arms.ten
    message = _message_2_3(arm, TARGET_2_3)
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
                    "Call ik.closed_form(arm_ex3, p_ex3) inside try / except "
                    "UnreachableError as error, and keep str(error): a str, not the "
                    "error itself.",
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
                    "Subtract the arm's largest reach (arm_ex3.reach holds it) from "
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
                    "which keeps the quadrant of every target; the package's IK "
                    "solvers are switched off while your function runs.",
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


#: Exercise 2.5: one machine's time per solve of each method (s), and the loop's budget (s).
SECONDS_2_5 = {
    "closed form": 3.2e-6,
    "newton": 9.7e-6,
    "minimize (BFGS)": 9.4e-4,
    "minimize (SLSQP)": 2.9e-4,
    "brute force, 1° grid": 2.7e-4,
}
BUDGET_2_5 = 1e-3
#: The margin a real-time verdict asks for: the time fits the budget this many times over.
MARGIN_2_5 = 3.0
#: 2.5's stated reasons, by letter, and the right one.
REASONS_2_5 = {
    "a": "yes: it fits the budget, as measured",
    "b": "not as measured: a margin that small vanishes on a slower machine or in a "
    "slow cycle, so a real-time verdict asks for the time to fit several times over",
    "c": "no: only a closed form can ever run in real time",
}
REASON_2_5 = "b"


def _inputs_2_5() -> dict[str, object]:
    return {
        "seconds_per_solve_ex5": dict(SECONDS_2_5),
        "budget_ex5": BUDGET_2_5,
        "margin_ex5": MARGIN_2_5,
    }


def _answers_2_5(inputs: dict) -> dict[str, object]:
    seconds = np.array(list(inputs["seconds_per_solve_ex5"].values()))
    margins = inputs["budget_ex5"] / seconds
    return {
        "margins_ex5": margins,
        "fit_with_margin_ex5": int(np.count_nonzero(margins >= inputs["margin_ex5"])),
    }


def _hidden_2_5(rng: np.random.Generator) -> dict[str, object]:
    """Other times per solve (1 us to 10 ms), none within 5 % of the margin's edge."""
    while True:
        seconds = {
            name: float(f"{10.0 ** rng.uniform(-6.0, -2.0):.2g}")
            for name in SECONDS_2_5
        }
        margins = BUDGET_2_5 / np.array(list(seconds.values()))
        if np.all(np.abs(margins / MARGIN_2_5 - 1.0) > 0.05):
            return {
                "seconds_per_solve_ex5": seconds,
                "budget_ex5": BUDGET_2_5,
                "margin_ex5": MARGIN_2_5,
            }


def exercise_2_5() -> ExerciseSpec:
    answers = _answers_2_5(_inputs_2_5())
    margins = np.asarray(answers["margins_ex5"])
    seconds = np.array(list(SECONDS_2_5.values()))
    count = int(answers["fit_with_margin_ex5"])
    return ExerciseSpec(
        "2.5",
        CHAPTER,
        (
            PartSpec(
                "margins_ex5",
                "margins",
                "vector",
                expected=margins,
                shape=(len(SECONDS_2_5),),
                components=tuple(SECONDS_2_5),
                mistakes=(
                    Mistake(
                        seconds / BUDGET_2_5,
                        "these are the shares of the budget (time / budget); the "
                        "margin is how many times the time fits the budget, budget / "
                        "time",
                    ),
                    Mistake(
                        100 * seconds / BUDGET_2_5,
                        "these are the shares of the budget in percent; the margin is "
                        "budget / time",
                    ),
                    Mistake(
                        margins * 1e6,
                        "the times are in seconds and the budget too: divide them as "
                        "they are, without converting one of them",
                    ),
                ),
                hints=(
                    "Reread 'Which method can run in real time?': a margin says how "
                    "many times one solve fits into the budget.",
                    "Divide budget_ex5 by each time of seconds_per_solve_ex5, in the "
                    "dict's order (list(seconds_per_solve_ex5.values())).",
                ),
            ),
            PartSpec(
                "fit_with_margin_ex5",
                "methods with the margin",
                "number",
                expected=count,
                unit="methods",
                mistakes=(
                    Mistake(
                        int(np.count_nonzero(margins >= 1.0)),
                        "this counts every method that fits the budget at all; the "
                        "question asks for those that fit margin_ex5 times over",
                    ),
                    Mistake(
                        len(SECONDS_2_5) - count,
                        "this counts the methods without the margin",
                    ),
                ),
                hints=(
                    "Reread 'Which method can run in real time?': a method counts "
                    "when its margin is at least margin_ex5.",
                    "Count the margins you computed that are >= margin_ex5 "
                    "(np.count_nonzero of the comparison).",
                ),
            ),
            PartSpec(
                "reason_ex5",
                "reason",
                "text",
                expected=REASON_2_5,
                mistakes=(
                    Mistake(
                        "a",
                        "it fits on the machine that measured it, once; a control "
                        "loop must meet every deadline, on the machine it runs on",
                    ),
                    Mistake(
                        "c",
                        "too strong: iterative solvers do run in real time on real "
                        "robots, when their time fits the budget with room to spare",
                    ),
                ),
                hints=(
                    "Reread 'Which method can run in real time?' and the margin the "
                    "chapter asks for.",
                    "Think of the same code on a machine three times slower, or in a "
                    "cycle where the computer is busy with something else.",
                ),
            ),
        ),
    )


#: The visible inputs of each value exercise, a draw of hidden ones, and the references for any.
RERUN = {
    "2.1": Rerun(inputs=_inputs_2_1(), hidden=_hidden_2_1, answers=_answers_2_1),
    "2.2": Rerun(inputs=_inputs_2_2(), hidden=_hidden_2_2, answers=_answers_2_2),
    "2.3": Rerun(inputs=_inputs_2_3(), hidden=_hidden_2_3, answers=_answers_2_3),
    "2.5": Rerun(inputs=_inputs_2_5(), hidden=_hidden_2_5, answers=_answers_2_5),
}

#: The grader's hidden cases, by (exercise, part): generator(rng, count) -> cases.
HIDDEN = {("2.4", "elbow_up_angles"): hidden_2_4}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("2.4", "elbow_up_angles"): (
        "twolink.ik.closed_form",
        "twolink.ik.analytic.closed_form",
        "twolink.ik.newton",
        "twolink.ik.iterative.newton",
        "twolink.ik.minimize",
        "twolink.ik.optimize.minimize",
        "twolink.ik.brute_force",
        "twolink.ik.grid_search.brute_force",
    ),
}

#: Parts worked on paper (a choice among stated reasons): checked on the visible value only.
PEN_AND_PAPER = (("2.5", "reason_ex5"),)


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_2_1(),
        exercise_2_2(),
        exercise_2_3(),
        exercise_2_4(),
        exercise_2_5(),
    ]
