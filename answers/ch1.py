"""Chapter 1 (DH forward kinematics): the references of exercises 1.1 to 1.5, with typical mistakes and hints.

Exercises 1.1 to 1.3 are graded on hidden inputs too (``RERUN``: their inputs
cells name the arm and the angles); 1.4 asks for a function, graded on hidden
cases (``HIDDEN``) with the package's forward kinematics switched off
(``FORBIDDEN``); 1.5 is worked on paper (the DH table and two frames of an arm
drawn by hand) and checked on its own numbers (``PEN_AND_PAPER``).
"""

from __future__ import annotations

import numpy as np

from answers import Rerun
from twolink import TwoLinkArm, arms, dh, to_absolute, to_relative
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "01_dh_forward_kinematics"
# OSAKE arm: q1 != 45 deg, where a flipped q2 and swapped sine and cosine would coincide
Q_1_1_DEG = (50.0, -30.0)
Q_1_2_DEG = (120.0, -45.0)  # OSAKE arm with link 2 raised on a spacer
SPACER_1_2_M = 0.02  # the second DH row's offset d, m
Q_ABS_1_3_DEG = (60.0, 150.0)  # 2 m arm, link angles from the x-axis
#: the visible calls of tip_position(arm, q): (l1, l2) in metres, q in radians
TIP_CASES_1_4 = (
    ((0.1, 0.115), (0.3, 1.2)),
    ((2.0, 2.0), (-2.0, 0.5)),
    ((0.3, 1.7), (2.5, -1.0)),
)
TIP = ("x", "y")


def _tip_output() -> PartSpec:
    return PartSpec(
        "p_tip", "tip position", "vector", shape=(2,), unit="m", components=TIP
    )


def _tip_case(l1: float, l2: float, q: tuple[float, float]) -> Case:
    expected = TwoLinkArm(l1=l1, l2=l2).fk(np.asarray(q, dtype=float))
    return Case({"arm": {"arm": {"l1": l1, "l2": l2}}, "q": list(q)}, expected.tolist())


def _wrong_tips(l1: float, l2: float, q: np.ndarray) -> dict[str, list[float]]:
    """The tip (x, y) as four typical slips of the formula compute it."""
    (c1, s1), (c2, s2) = (np.cos(q[0]), np.sin(q[0])), (np.cos(q[1]), np.sin(q[1]))
    c12, s12 = np.cos(q[0] + q[1]), np.sin(q[0] + q[1])
    return {
        "sine for cosine": [l1 * s1 + l2 * s12, l1 * c1 + l2 * c12],
        "links swapped": [l2 * c1 + l1 * c12, l2 * s1 + l1 * s12],
        "q2 as absolute": [l1 * c1 + l2 * c2, l1 * s1 + l2 * s2],
        "first term only": [l1 * c1 + l2 * c1 * c2, l1 * s1 + l2 * s1 * c2],
    }


#: what each slip of the formula is, in words, for the function and for the number
SLIPS = {
    "sine for cosine": "sine and cosine are swapped: x goes with the cosines, y with "
    "the sines",
    "links swapped": "the link lengths are swapped: l1 goes with link 1's angle q1, "
    "l2 with link 2's direction q1 + q2",
    "q2 as absolute": "q2 is used as link 2's direction (an absolute angle); in the "
    "DH convention q2 is measured from link 1, so link 2 points along q1 + q2",
    "first term only": "only the first term of each angle-sum formula is kept "
    "(cos q1 cos q2 for cos(q1 + q2)): the hand-expanded transform of the Pitfalls",
}


def _function_mistakes() -> tuple[Mistake, ...]:
    """The typical wrong tip_position functions, by what they return on the visible cases."""
    visible = [(l1, l2, np.asarray(q)) for (l1, l2), q in TIP_CASES_1_4]
    mistakes = [
        Mistake(
            [_wrong_tips(l1, l2, q)[slip] for l1, l2, q in visible],
            f"in your function, {SLIPS[slip]}",
        )
        for slip in SLIPS
    ]
    mistakes.append(
        Mistake(
            [
                TwoLinkArm(l1=l1, l2=l2).fk(np.radians(q)).tolist()
                for l1, l2, q in visible
            ],
            "your function converts q to radians again: it is given radians already",
        )
    )
    osake = TwoLinkArm(l1=arms.osake.l1, l2=arms.osake.l2)
    mistakes.append(
        Mistake(
            [osake.fk(q).tolist() for _, _, q in visible],
            "your function uses the OSAKE arm's lengths whatever arm it is given: take "
            "them from its argument arm",
        )
    )
    return tuple(mistakes)


def hidden_tip_cases(rng: np.random.Generator, count: int) -> list[Case]:
    """Hidden calls of ``tip_position``: random arms (links 0.05 to 3 m), random angles."""
    cases = []
    while len(cases) < count:
        l1, l2 = (round(float(v), 3) for v in rng.uniform(0.05, 3.0, size=2))
        q = tuple(round(float(v), 4) for v in rng.uniform(-np.pi, np.pi, size=2))
        if ((l1, l2), q) not in TIP_CASES_1_4:
            cases.append(_tip_case(l1, l2, q))
    return cases


def _inputs_1_1() -> dict[str, object]:
    return {"arm_ex1": arms.osake, "q_ex1": np.radians(Q_1_1_DEG)}


def _answers_1_1(inputs: dict) -> dict[str, object]:
    return {"p_tip_ex1": inputs["arm_ex1"].fk(inputs["q_ex1"])}


def _random_arm(rng: np.random.Generator, offset: bool = False) -> TwoLinkArm:
    """An arm like the chapter's: links 5 cm to 3 m (and a base offset of -0.2 to 0.2 m, if asked)."""
    l1, l2 = (round(float(value), 3) for value in rng.uniform(0.05, 3.0, size=2))
    if not offset:
        return TwoLinkArm(l1=l1, l2=l2)
    return TwoLinkArm(l1=l1, l2=l2, d=round(float(rng.uniform(-0.2, 0.2)), 3))


def _angles(rng: np.random.Generator) -> np.ndarray:
    """Joint angles in radians, each more than 5 deg from 0 and +-90 deg (no slip vanishes there)."""
    while True:
        q = rng.uniform(-np.pi, np.pi, size=2).round(4)
        if np.all(np.abs(np.sin(2 * q)) > np.sin(np.radians(10.0))):
            return q


def _hidden_1_1(rng: np.random.Generator) -> dict[str, object]:
    return {"arm_ex1": _random_arm(rng), "q_ex1": _angles(rng)}


def exercise_1_1() -> ExerciseSpec:
    inputs = _inputs_1_1()
    arm, q = inputs["arm_ex1"], inputs["q_ex1"]
    assert isinstance(arm, TwoLinkArm) and isinstance(q, np.ndarray)
    return ExerciseSpec(
        "1.1",
        CHAPTER,
        (
            PartSpec(
                "p_tip_ex1",
                "tip position",
                "vector",
                expected=_answers_1_1(inputs)["p_tip_ex1"],
                shape=(2,),
                unit="m",
                components=TIP,
                mistakes=(
                    Mistake(
                        arm.fk(np.asarray(Q_1_1_DEG)),
                        "this is the tip for the angles read as radians: cos and sin "
                        "take radians, so convert the degrees first",
                    ),
                    Mistake(
                        arm.fk(q * [1.0, -1.0]),
                        "this is the tip with q2's sign flipped: q_ex1 holds q2 "
                        "negative, link 2 turned clockwise from link 1",
                    ),
                    *(
                        Mistake(value, SLIPS[slip])
                        for slip, value in _wrong_tips(arm.l1, arm.l2, q).items()
                    ),
                ),
                hints=(
                    "Reread 'A1, A2 and T_0^2 = A1 A2 with sympy': the last column of "
                    "T_0^2 holds the tip's x and y.",
                    "Use the arm's own lengths (arm_ex1.l1, arm_ex1.l2) and the "
                    "angles q_ex1, in radians; link 2 points along the sum of the two "
                    "joint angles.",
                ),
            ),
        ),
    )


def _inputs_1_2() -> dict[str, object]:
    return {
        "arm_ex2": arms.osake,
        "q_ex2": np.radians(Q_1_2_DEG),
        "d2_ex2": SPACER_1_2_M,
    }


def _product_1_2(
    arm: TwoLinkArm, q: np.ndarray, d1: float, d2: float
) -> tuple[np.ndarray, np.ndarray]:
    """A1 and A2 of ``arm``'s DH rows with the offsets d1, d2, at the angles q (used as given)."""
    row1, row2 = arm.dh_table()
    return (
        dh.dh_matrix(q[0] + row1.theta_offset, d1, row1.a, row1.alpha),
        dh.dh_matrix(q[1] + row2.theta_offset, d2, row2.a, row2.alpha),
    )


def _answers_1_2(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex2"]
    A1, A2 = _product_1_2(arm, inputs["q_ex2"], arm.d, inputs["d2_ex2"])
    T = A1 @ A2
    return {"T_02_ex2": T, "z_tip_ex2": T[2, 3], "x_axis_ex2": T[:3, 0]}


def _hidden_1_2(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex2": _random_arm(rng, offset=True),
        "q_ex2": _angles(rng),
        "d2_ex2": round(float(rng.uniform(0.01, 0.1)), 3),
    }


def exercise_1_2() -> ExerciseSpec:
    inputs = _inputs_1_2()
    arm, q, d2 = inputs["arm_ex2"], inputs["q_ex2"], inputs["d2_ex2"]
    assert isinstance(arm, TwoLinkArm) and isinstance(q, np.ndarray)
    assert isinstance(d2, float)
    d1 = arm.d
    A1, A2 = _product_1_2(arm, q, d1, d2)
    T = A1 @ A2
    no_spacer = np.matmul(*_product_1_2(arm, q, d1, 0.0))
    no_height = np.matmul(*_product_1_2(arm, q, 0.0, d2))
    in_degrees = np.matmul(*_product_1_2(arm, np.degrees(q), d1, d2))
    return ExerciseSpec(
        "1.2",
        CHAPTER,
        (
            PartSpec(
                "T_02_ex2",
                "T_02",
                "matrix",
                expected=T,
                shape=(4, 4),
                mistakes=(
                    Mistake(
                        A2 @ A1,
                        "this is A2 @ A1: the product runs from the base outwards, "
                        "A1 @ A2",
                    ),
                    Mistake(
                        in_degrees,
                        "this is the transform for the angles in degrees read as "
                        "radians: q_ex2 holds radians already",
                    ),
                    Mistake(
                        no_spacer,
                        "the spacer is missing: this is the plain OSAKE arm; use the "
                        "exercise's second row, with its own offset d2_ex2",
                    ),
                    Mistake(
                        no_height,
                        "the first row's offset d is missing: the OSAKE arm's plane "
                        "sits above the base frame",
                    ),
                    Mistake(
                        T.T,
                        "this is the transpose of T_02: the translation belongs in "
                        "the last column, not the last row",
                    ),
                ),
                hints=(
                    "Reread 'Multiplying transforms: loops versus numpy @': one DH "
                    "matrix per row of the DH table, then one product.",
                    "Build each DH matrix from its own row's theta offset, d, a and "
                    "alpha, with that joint's angle in radians; the order of the "
                    "product is the order of the links from the base.",
                ),
            ),
            PartSpec(
                "z_tip_ex2",
                "tip height",
                "number",
                expected=T[2, 3],
                unit="m",
                mistakes=(
                    Mistake(
                        d1,
                        "this is the first row's offset alone: the spacer's offset "
                        "in the second row adds to it",
                    ),
                    Mistake(
                        d2,
                        "this is the spacer's offset alone: the first row's offset "
                        "d adds to it",
                    ),
                    Mistake(
                        0.0,
                        "a height of zero drops both offsets: the tip sits above the "
                        "base frame",
                    ),
                    Mistake(
                        T[1, 3],
                        "this is the tip's y (row 2 of the last column); the height "
                        "is its z",
                    ),
                    Mistake(
                        T[0, 3],
                        "this is the tip's x (row 1 of the last column); the height "
                        "is its z",
                    ),
                    Mistake(
                        100.0 * T[2, 3],
                        "this is the height in centimetres; the package works in "
                        "metres",
                    ),
                ),
                hints=(
                    "Reread 'Offsets on both rows add up': where does T_0^2 keep "
                    "the tip's position, and what do the two offsets do to it?",
                    "The tip's x, y, z are the first three entries of the last "
                    "column of your T_02; the height is the one along z.",
                ),
            ),
            PartSpec(
                "x_axis_ex2",
                "tip x axis",
                "vector",
                expected=T[:3, 0],
                shape=(3,),
                components=("x", "y", "z"),
                mistakes=(
                    Mistake(
                        T[:3, 2],
                        "this is the tip frame's z axis (the third column); its x "
                        "axis is the first column",
                    ),
                    Mistake(
                        T[:3, 1],
                        "this is the tip frame's y axis (the second column); its x "
                        "axis is the first column",
                    ),
                    Mistake(
                        T[0, :3],
                        "this is the first row of the rotation block; the frame's "
                        "axes are its columns",
                    ),
                    Mistake(
                        A1[:3, 0],
                        "this is frame 1's x axis, along link 1 (from A1 alone); "
                        "the tip frame's x axis lies along link 2",
                    ),
                    Mistake(
                        T[:3, 3],
                        "this is the tip's position (the last column), not a direction",
                    ),
                ),
                hints=(
                    "Reread 'A1, A2 and T_0^2 = A1 A2 with sympy': which block of "
                    "T_0^2 is a rotation, and what do its columns say?",
                    "Each column of the rotation block is one axis of the tip frame, "
                    "written in the base frame; the x axis is the first, and it lies "
                    "along link 2.",
                ),
            ),
        ),
    )


def _inputs_1_3() -> dict[str, object]:
    return {"arm_ex3": arms.two_metre, "q_abs_ex3": np.radians(Q_ABS_1_3_DEG)}


def _answers_1_3(inputs: dict) -> dict[str, object]:
    q_rel = to_relative(inputs["q_abs_ex3"])
    return {"q_rel_ex3": q_rel, "p_tip_ex3": inputs["arm_ex3"].fk(q_rel)}


def _hidden_1_3(rng: np.random.Generator) -> dict[str, object]:
    return {"arm_ex3": _random_arm(rng), "q_abs_ex3": _angles(rng)}


def exercise_1_3() -> ExerciseSpec:
    inputs = _inputs_1_3()
    arm, q_abs = inputs["arm_ex3"], inputs["q_abs_ex3"]
    assert isinstance(arm, TwoLinkArm) and isinstance(q_abs, np.ndarray)
    q_rel = to_relative(q_abs)
    q_backwards = np.array([q_abs[0], q_abs[0] - q_abs[1]])
    return ExerciseSpec(
        "1.3",
        CHAPTER,
        (
            PartSpec(
                "q_rel_ex3",
                "relative angles",
                "angles",
                expected=q_rel,
                shape=(2,),
                unit="rad",
                components=("q1", "q2"),
                mistakes=(
                    Mistake(
                        to_absolute(q_abs),
                        "this converts the wrong way (to_absolute): the angles given "
                        "are already absolute",
                    ),
                    Mistake(
                        np.degrees(q_rel),
                        "these are degrees; the answer is in radians",
                    ),
                    Mistake(
                        q_abs,
                        "these are the absolute angles unchanged: link 2's relative "
                        "angle is measured from link 1, not from the x-axis",
                    ),
                    Mistake(
                        q_backwards,
                        "q2 has the wrong sign: it is link 2's angle minus link 1's, "
                        "not the other way round",
                    ),
                ),
                hints=(
                    "Reread 'Relative (DH) versus absolute angles': which of the two "
                    "angles is the same in both conventions?",
                    "The relative q2 is the angle from link 1 to link 2; "
                    "twolink.to_relative does the conversion, in radians.",
                ),
            ),
            PartSpec(
                "p_tip_ex3",
                "tip",
                "vector",
                expected=arm.fk(q_rel),
                shape=(2,),
                unit="m",
                components=TIP,
                mistakes=(
                    Mistake(
                        arm.fk(q_abs),
                        "this is arm.fk of the absolute angles; the package takes "
                        "relative (DH) angles",
                    ),
                    Mistake(
                        arm.fk(np.degrees(q_rel)),
                        "this is the tip for relative angles in degrees read as "
                        "radians: give arm.fk radians",
                    ),
                    Mistake(
                        arm.fk(to_absolute(q_abs)),
                        "this is arm.fk of to_absolute's angles: the conversion went "
                        "the wrong way",
                    ),
                    Mistake(
                        arm.fk(q_backwards),
                        "this is the tip for a relative q2 of the wrong sign: link 2's "
                        "angle minus link 1's",
                    ),
                ),
                hints=(
                    "Reread 'Relative (DH) versus absolute angles': which angles "
                    "does arm.fk expect?",
                    "Feed arm.fk the relative angles you found, in radians; on this "
                    "arm link 2 should point the way the absolute angle says.",
                ),
            ),
        ),
    )


def exercise_1_4() -> ExerciseSpec:
    return ExerciseSpec(
        "1.4",
        CHAPTER,
        (
            PartSpec(
                "tip_position",
                "tip_position(arm, q)",
                "function",
                cases=tuple(
                    _tip_case(*lengths, angles) for lengths, angles in TIP_CASES_1_4
                ),
                output=_tip_output(),
                mistakes=_function_mistakes(),
                hints=(
                    "Reread 'A1, A2 and T_0^2 = A1 A2 with sympy': the last column of "
                    "T_0^2 holds the tip's x and y, for any lengths; arm.fk and "
                    "arm.transforms are switched off while your function runs.",
                    "Take the lengths from the arm you are given (arm.l1, arm.l2), "
                    "not from one particular arm, and remember that link 2 points "
                    "along the sum of the two joint angles (q holds radians).",
                ),
            ),
        ),
    )


#: Exercise 1.5's bench arm: link lengths and the height of its plane, m; the pose drawn, deg.
BENCH_1_5 = TwoLinkArm(l1=0.30, l2=0.20, d=0.05)
Q_1_5_DEG = (90.0, -90.0)
#: A pen-and-paper answer may be typed to 3 significant figures.
BY_HAND = Tolerance(significant=3)


def exercise_1_5() -> ExerciseSpec:
    arm, q = BENCH_1_5, np.radians(Q_1_5_DEG)
    table = np.array(
        [[row.d, row.a, np.degrees(row.alpha)] for row in arm.dh_table()], dtype=float
    )
    T_01, T_02 = arm.transforms(q)
    o1, x2 = T_01[:3, 3], T_02[:3, 0]
    return ExerciseSpec(
        "1.5",
        CHAPTER,
        (
            PartSpec(
                "dh_ex5",
                "DH table (d, a, alpha)",
                "matrix",
                expected=table,
                shape=(2, 3),
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        table[:, [1, 0, 2]],
                        "d and a are swapped: d is the offset along the joint axis "
                        "(the height), a the length along the new x axis",
                    ),
                    Mistake(
                        table + [[0.0, 0.0, 90.0], [0.0, 0.0, 90.0]],
                        "a twist of 90 deg tilts the next joint axis: on a planar arm "
                        "every joint axis is parallel to the one before, so alpha = 0",
                    ),
                    Mistake(
                        table + [[0.0, 0.0, 0.0], [arm.d, 0.0, 0.0]],
                        "the height is counted twice: one offset d, in the first row, "
                        "lifts the whole plane (offsets along parallel axes add up)",
                    ),
                    Mistake(
                        table * [[100.0, 100.0, 1.0], [100.0, 100.0, 1.0]],
                        "these are centimetres; the table is in metres",
                    ),
                ),
                hints=(
                    "Reread 'The DH convention in one matrix' and 'The frames on the "
                    "arm': which of the four numbers of a row is a length along x, "
                    "which an offset along z, which a twist?",
                    "Each row is (d, a, alpha) for one link: the plane's height goes "
                    "into the first row's d (0 in the second), each link's length "
                    "into its a, and parallel joint axes mean no twist.",
                ),
            ),
            PartSpec(
                "o1_ex5",
                "origin of frame 1",
                "vector",
                expected=o1,
                shape=(3,),
                unit="m",
                components=("x", "y", "z"),
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        o1 * [1.0, 1.0, 0.0],
                        "frame 1 sits in the arm's plane, at the height d: its z is "
                        "not 0",
                    ),
                    Mistake(
                        T_02[:3, 3],
                        "this is the tip, frame 2's origin; frame 1 sits at the elbow, "
                        "the end of link 1",
                    ),
                    Mistake(
                        [arm.l1, 0.0, arm.d],
                        "this is the elbow at q1 = 0; at q1 = 90 deg link 1 points "
                        "along y",
                    ),
                ),
                hints=(
                    "Reread 'The frames on the arm': each frame sits at the end of "
                    "its link.",
                    "Frame 1 is at the elbow: link 1's length along the direction "
                    "q1, at the height of the arm's plane.",
                ),
            ),
            PartSpec(
                "x2_ex5",
                "tip frame's x axis",
                "vector",
                expected=x2,
                shape=(3,),
                components=("x", "y", "z"),
                tolerance=BY_HAND,
                mistakes=(
                    Mistake(
                        T_01[:3, 0],
                        "this is x1, along link 1; the tip frame's x axis lies along "
                        "link 2",
                    ),
                    Mistake(
                        [0.0, 0.0, 1.0],
                        "this is a z axis, out of the page; x2 lies in the arm's "
                        "plane, along link 2",
                    ),
                    Mistake(
                        [0.0, -1.0, 0.0],
                        "this direction is q2 = -90 deg taken from the x-axis; q2 is "
                        "measured from link 1, so link 2 points along q1 + q2",
                    ),
                ),
                hints=(
                    "Reread 'The frames on the arm': which way does each x axis point?",
                    "x2 points along link 2, at the angle q1 + q2 from the base's x "
                    "axis; it is a unit vector in the plane (z = 0).",
                ),
            ),
        ),
    )


#: The visible inputs of each value exercise, a draw of hidden ones, and the references for any.
RERUN = {
    "1.1": Rerun(inputs=_inputs_1_1(), hidden=_hidden_1_1, answers=_answers_1_1),
    "1.2": Rerun(inputs=_inputs_1_2(), hidden=_hidden_1_2, answers=_answers_1_2),
    "1.3": Rerun(inputs=_inputs_1_3(), hidden=_hidden_1_3, answers=_answers_1_3),
}

HIDDEN = {("1.4", "tip_position"): hidden_tip_cases}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("1.4", "tip_position"): (
        "twolink.arm.TwoLinkArm.fk",
        "twolink.kinematics.fk",
        "twolink.arm.TwoLinkArm.joint_positions",
        "twolink.kinematics.joint_positions",
        "twolink.arm.TwoLinkArm.transforms",
        "twolink.dh.transforms",
        "twolink.kinematics.tip_from_trig",
    ),
}

#: Parts worked on paper: checked on the visible values only, timed as pen-and-paper parts.
PEN_AND_PAPER = (("1.5", "dh_ex5"), ("1.5", "o1_ex5"), ("1.5", "x2_ex5"))


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_1_1(),
        exercise_1_2(),
        exercise_1_3(),
        exercise_1_4(),
        exercise_1_5(),
    ]
