"""twolink.selfcheck: verdicts on right, wrong and unsolved answers, and the lines read back."""

import contextlib
import io

import numpy as np
import pytest

from twolink import arms, exercises, selfcheck


def test_check_arguments_and_messages():
    with pytest.raises(KeyError, match="no exercise '9.9'"):
        selfcheck.check("9.9", 1.0)
    with pytest.raises(TypeError, match="no part 'p_tip'"):
        selfcheck.check("1.1", p_tip=[0.0, 0.0])
    with pytest.raises(TypeError, match="1 parts"):
        selfcheck.check("1.1", [0.0, 0.0], [1.0, 1.0])
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        report = selfcheck.check("2.1", [0.0, 0.0])
    line = printed.getvalue().splitlines()[0]
    assert (
        selfcheck.parse_line(line) == ("2.1", "angles", "wrong") and not report.passed
    )
    assert "m from the target" in line and " Hint: " in line


# ---------------------------------------------------------------- verdicts
RIGHT_TIP = arms.osake.fk(np.radians([45.0, -30.0]))


def checked(*answers, **named_answers):
    """``selfcheck.check(...)`` with what it printed."""
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        report = selfcheck.check(*answers, **named_answers)
    return report, printed.getvalue().splitlines()


def test_a_right_answer_is_correct():
    report, lines = checked("1.1", RIGHT_TIP)
    assert report.passed
    assert [result.status for result in report] == [selfcheck.CORRECT]
    assert lines == ["Exercise 1.1 (tip position): correct."]
    assert report[0] == ("1.1", "tip position", "correct", lines[0])


@pytest.mark.parametrize(
    "wrong",
    [RIGHT_TIP + [0.01, 0.0], arms.osake.fk([45.0, -30.0]), "abc", [1.0, 2.0, 3.0]],
    ids=["off by a centimetre", "degrees as radians", "a string", "three numbers"],
)
def test_a_wrong_answer_is_wrong_with_a_reason_and_the_hint(wrong):
    report, lines = checked("1.1", wrong)
    assert not report.passed and report[0].status == selfcheck.WRONG
    assert lines[0].startswith("Exercise 1.1 (tip position): wrong: ")
    assert " Hint: " in lines[0] and len(lines) == 1


@pytest.mark.parametrize("unsolved", [..., None], ids=["ellipsis", "None"])
def test_an_answer_left_as_the_stub_is_not_solved_yet(unsolved):
    report, lines = checked("1.1", unsolved)
    assert not report.passed and report[0].status == selfcheck.NOT_SOLVED
    assert lines == [
        "Exercise 1.1 (tip position): not solved yet "
        "(replace the ... in p_tip_ex1 with your answer)."
    ]


def test_a_part_not_given_is_not_solved_and_answers_can_be_named():
    by_position, _ = checked("2.1")
    assert [result.status for result in by_position] == [selfcheck.NOT_SOLVED] * 2
    report, lines = checked("1.1", p_tip_ex1=RIGHT_TIP)
    assert report.passed and lines == ["Exercise 1.1 (tip position): correct."]


def test_an_answer_given_twice_is_refused():
    with pytest.raises(TypeError, match="'p_tip_ex1' of exercise 1.1 is given twice"):
        selfcheck.check("1.1", RIGHT_TIP, p_tip_ex1=RIGHT_TIP)


def test_a_judge_that_fails_on_an_answer_reports_it_instead_of_raising(monkeypatch):
    def crashing_judge(answer, siblings):
        raise ZeroDivisionError("no")

    part = exercises.Part("x", "the x", crashing_judge, "think again")
    monkeypatch.setitem(exercises.REGISTRY, "99.1", exercises.Exercise("99.1", (part,)))
    report, lines = checked("99.1", 1.0)
    assert report[0].status == selfcheck.WRONG
    assert lines == [
        "Exercise 99.1 (the x): wrong: could not use your x (ZeroDivisionError: no). "
        "Hint: think again"
    ]


# ---------------------------------------------------------------- reading the printed lines back
@pytest.mark.parametrize(
    "answer, status",
    [(RIGHT_TIP, "correct"), ([0.0, 0.0], "wrong"), (..., "not solved yet")],
    ids=["correct", "wrong", "not solved"],
)
def test_parse_line_reads_back_every_line_check_prints(answer, status):
    _, lines = checked("1.1", answer)
    assert selfcheck.parse_line(lines[0]) == ("1.1", "tip position", status)


@pytest.mark.parametrize(
    "line", ["", "Exercise 1.1", "exercise 1.1: correct", "Exercise one: correct."]
)
def test_parse_line_gives_none_for_other_lines(line):
    assert selfcheck.parse_line(line) is None
