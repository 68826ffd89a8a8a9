"""The judging of one answer: equivalent forms accepted, typical mistakes named, other misses sized in words."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from twolink_course.exercises.judging import Unusable, judge, read_answer
from twolink_course.exercises.spec import Case, Mistake, PartSpec, Tolerance

POINT = PartSpec(
    "p_tip",
    "tip",
    "vector",
    expected=[0.3, 0.4],
    shape=(2,),
    unit="m",
    components=("x", "y"),
)
TORQUES = PartSpec(
    "tau",
    "torques",
    "vector",
    expected=[10.0, -4.0],
    shape=(2,),
    unit="N m",
    components=("tau1", "tau2"),
    mistakes=(Mistake([-10.0, 4.0], "the sign is reversed"),),
)
ANGLES = PartSpec(
    "q",
    "angles",
    "angles",
    expected=[0.5, -1.0],
    shape=(2,),
    unit="rad",
    components=("q1", "q2"),
)
SPEED = PartSpec(
    "v",
    "tip speed",
    "number",
    expected=0.0133333333,
    unit="m/s",
    tolerance=Tolerance(significant=3),
)
FLAG = PartSpec("ok", "reachable", "bool", expected=True)


@pytest.mark.parametrize(
    "answer",
    [
        [10.0, -4.0],
        (10, -4),
        np.array([10.0, -4.0]),
        np.array([[10.0], [-4.0]]),
        sp.Matrix([10, -4]),
        [sp.Integer(10), sp.Float(-4.0)],
        [np.float32(10.0), np.int64(-4)],
    ],
    ids=[
        "list",
        "tuple",
        "array",
        "column",
        "sympy matrix",
        "sympy numbers",
        "numpy scalars",
    ],
)
def test_equivalent_forms_of_a_vector_are_right(answer):
    assert judge(TORQUES, answer).right


@settings(max_examples=50, deadline=None)
@given(st.integers(-3, 3), st.integers(-3, 3))
def test_angles_are_right_up_to_whole_turns(turns_1, turns_2):
    answer = np.array([0.5, -1.0]) + 2 * np.pi * np.array([turns_1, turns_2])
    assert judge(ANGLES, answer).right


def test_sympy_numbers_and_expressions():
    assert judge(PartSpec("r", "ratio", "number", expected=2**0.5), sp.sqrt(2)).right
    x = sp.Symbol("x")
    message = judge(
        PartSpec("r", "ratio", "number", expected=2**0.5), sp.sqrt(x)
    ).message
    assert "expression in x" in message and ".subs" in message


@pytest.mark.parametrize("answer", [0.0133, 0.01333, "0.0133"[:0] or 0.013333333333])
def test_a_hand_rounded_number_is_right_at_the_precision_asked(answer):
    assert judge(SPEED, answer).right


def test_a_number_rounded_below_the_precision_asked_is_wrong_with_its_miss():
    verdict = judge(SPEED, 0.013)
    assert not verdict.right
    assert verdict.message == "your tip speed is 0.00033 m/s too small"


@pytest.mark.parametrize(
    "answer, message",
    [
        (0, "a yes/no answer is True or False; got 0 (a int)"),
        ("no", "a yes/no answer is True or False; got 'no' (a str)"),
        (None, "a yes/no answer is True or False; got None (a NoneType)"),
    ],
)
def test_a_yes_no_answer_is_a_bool_and_anything_else_says_so(answer, message):
    assert judge(FLAG, answer) == (False, message)


def test_bools_of_numpy_are_bools():
    assert judge(FLAG, np.bool_(True)).right and not judge(FLAG, False).right


def test_a_typical_mistake_is_named():
    assert judge(TORQUES, [-10, 4]) == (False, "the sign is reversed")


@pytest.mark.parametrize(
    "answer, message",
    [
        ([12.5, -4.0], "tau1 is 2.5 N m too large"),
        ([10.0, -7.0], "tau2 is 3.0 N m too small"),
        ([12.0, -3.0], "tau1 is 2.0 N m too large and tau2 is 1.0 N m too large"),
    ],
)
def test_another_miss_gives_the_quantity_its_unit_size_and_direction(answer, message):
    assert judge(TORQUES, answer) == (False, message)


def test_a_point_misses_by_a_distance_and_a_direction():
    message = judge(POINT, [0.213, 0.38]).message
    assert (
        message
        == "your tip is 8.9 cm from the right point: 8.7 cm to the left of and 2.0 cm below it"
    )


def test_angle_misses_are_told_in_degrees():
    assert (
        judge(ANGLES, [0.5 + np.radians(12.0), -1.0]).message == "q1 is 12° too large"
    )


def test_a_matrix_miss_names_the_entry():
    part = PartSpec(
        "T", "transform", "matrix", expected=np.eye(3).tolist(), shape=(3, 3), unit="m"
    )
    answer = np.eye(3)
    answer[1, 2] = 0.5
    assert (
        judge(part, answer).message
        == "entry (row 2, column 3) of your transform is 0.50 m too large"
    )


@pytest.mark.parametrize(
    "answer, message",
    [
        ([1.0, 2.0, 3.0], "expected 2 numbers (shape (2,)) in N m, got shape (3,)"),
        ("10, -4", "expected numbers in N m, got a str"),
        ([10.0, np.nan], "your answer contains nan or inf"),
        ([10.0, 1j], "expected real numbers, got a complex one"),
        ([[1.0, 2.0], [3.0]], "could not read your numbers"),
    ],
)
def test_unusable_answers_say_what_was_expected(answer, message):
    verdict = judge(TORQUES, answer)
    assert not verdict.right and verdict.message.startswith(message)


def test_read_answer_refuses_true_as_a_number():
    with pytest.raises(Unusable, match="a bool"):
        read_answer(SPEED, True)


def _tip(arm, q):
    return arm.fk(q)


FUNCTION = PartSpec(
    "tip_position",
    "tip function",
    "function",
    cases=(
        Case({"arm": {"arm": {"l1": 1.0, "l2": 2.0}}, "q": [0.0, 0.0]}, [3.0, 0.0]),
        Case(
            {"arm": {"arm": {"l1": 1.0, "l2": 1.0}}, "q": [0.0, np.pi / 2]}, [1.0, 1.0]
        ),
    ),
    output=PartSpec("p", "tip", "vector", shape=(2,), unit="m", components=("x", "y")),
    mistakes=(
        Mistake([[3.0, 0.0], [1.0 + np.cos(np.radians(90.0)), 1.0]], "unused"),
        Mistake(
            [[3.0, 0.0], [2.0, 0.0]],
            "you added the angles of both links to link 1 only",
        ),
    ),
)


def test_a_right_function_passes_on_every_case():
    assert judge(FUNCTION, _tip).right


def test_a_function_that_raises_is_told_where():
    def broken(arm, q):
        raise ValueError("nope")

    message = judge(FUNCTION, broken).message
    assert message.startswith(
        "your function raised ValueError: nope when called with arm=TwoLinkArm(l1=1, l2=2)"
    )


def test_a_function_mistake_is_named_and_another_miss_shows_the_case():
    def first_link_only(arm, q):
        return np.array([arm.l1 + arm.l2, 0.0]) if q[1] == 0 else np.array([2.0, 0.0])

    assert (
        judge(FUNCTION, first_link_only).message
        == "you added the angles of both links to link 1 only"
    )

    def off(arm, q):
        return arm.fk(q) + [0.0, 0.05]

    message = judge(FUNCTION, off).message
    assert message.startswith(
        "called with arm=TwoLinkArm(l1=1, l2=2), q=[0, 0], your tip is 5.0 cm"
    )


def test_something_else_than_a_function():
    assert (
        judge(FUNCTION, [3.0, 0.0]).message
        == "expected a function (def ...), got a list"
    )
