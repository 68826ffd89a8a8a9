"""Chapter 1 (DH forward kinematics): the references of exercises 1.1 to 1.4, with typical mistakes and hints."""

from __future__ import annotations

import numpy as np

from twolink import TwoLinkArm, arms, dh, to_absolute, to_relative
from twolink_course.exercises.spec import Case, ExerciseSpec, Mistake, PartSpec

CHAPTER = "01_dh_forward_kinematics"
Q_1_1_DEG = (45.0, -30.0)  # OSAKE arm
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


def exercise_1_1() -> ExerciseSpec:
    arm, q = arms.osake, np.radians(Q_1_1_DEG)
    return ExerciseSpec(
        "1.1",
        CHAPTER,
        (
            PartSpec(
                "p_tip_ex1",
                "tip position",
                "vector",
                expected=arm.fk(q),
                shape=(2,),
                unit="m",
                components=TIP,
                mistakes=(
                    Mistake(
                        arm.fk(np.asarray(Q_1_1_DEG)),
                        "this is the tip for the angles read as radians: cos and sin "
                        "take radians, so convert the degrees first",
                    ),
                    *(
                        Mistake(value, SLIPS[slip])
                        for slip, value in _wrong_tips(arm.l1, arm.l2, q).items()
                    ),
                ),
                hints=(
                    "Reread 'A1, A2 and T_0^2 = A1 A2 with sympy': the last column of "
                    "T_0^2 holds the tip's x and y.",
                    "Use the OSAKE arm's own lengths (osake.l1, osake.l2) and the "
                    "angles in radians; link 2 points along the sum of the two joint "
                    "angles.",
                ),
            ),
        ),
    )


def _product_1_2(
    q_deg: tuple[float, float], d1: float, d2: float
) -> tuple[np.ndarray, np.ndarray]:
    """A1 and A2 of the OSAKE rows with offsets d1, d2, at q_deg read as radians."""
    row1, row2 = arms.osake.dh_table()
    return (
        dh.dh_matrix(q_deg[0] + row1.theta_offset, d1, row1.a, row1.alpha),
        dh.dh_matrix(q_deg[1] + row2.theta_offset, d2, row2.a, row2.alpha),
    )


def exercise_1_2() -> ExerciseSpec:
    q, d1 = np.radians(Q_1_2_DEG), arms.osake.d
    A1, A2 = _product_1_2(q, d1, SPACER_1_2_M)
    T = A1 @ A2
    no_spacer = np.matmul(*_product_1_2(q, d1, 0.0))
    no_height = np.matmul(*_product_1_2(q, 0.0, SPACER_1_2_M))
    in_degrees = np.matmul(*_product_1_2(Q_1_2_DEG, d1, SPACER_1_2_M))
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
                        "this is the transform for the angles read as radians: "
                        "convert the degrees first",
                    ),
                    Mistake(
                        no_spacer,
                        "the spacer is missing: this is the plain OSAKE arm; use the "
                        "exercise's second row, with its own offset d",
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
                        SPACER_1_2_M,
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


def exercise_1_3() -> ExerciseSpec:
    arm, q_abs = arms.two_metre, np.radians(Q_ABS_1_3_DEG)
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
                    "T_0^2 holds the tip's x and y, for any lengths.",
                    "Take the lengths from the arm you are given (arm.l1, arm.l2), "
                    "not from one particular arm, and remember that link 2 points "
                    "along the sum of the two joint angles (q holds radians).",
                ),
            ),
        ),
    )


HIDDEN = {("1.4", "tip_position"): hidden_tip_cases}


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_1_1(), exercise_1_2(), exercise_1_3(), exercise_1_4()]
