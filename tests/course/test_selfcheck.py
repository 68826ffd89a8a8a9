"""twolink_course.selfcheck: verdicts on right, wrong and unsolved answers, and the lines read back."""

import collections
import contextlib
import io
import re

import numpy as np
import pytest

from twolink import arms
from twolink_course import exercises, selfcheck


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
        selfcheck.parse_line(line) == ("2.1", "elbow-up angles", "wrong")
        and not report.passed
    )
    assert "this is the elbow-down" not in line and re.search(
        r" Hint \d+ of \d+: ", line
    )


# ---------------------------------------------------------------- verdicts
RIGHT_TIP = arms.osake.fk(np.radians([50.0, -30.0]))


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
    [RIGHT_TIP + [0.01, 0.0], arms.osake.fk([50.0, -30.0]), "abc", [1.0, 2.0, 3.0]],
    ids=["off by a centimetre", "degrees as radians", "a string", "three numbers"],
)
def test_a_wrong_answer_is_wrong_with_a_reason_and_the_hint(wrong):
    report, lines = checked("1.1", wrong)
    assert not report.passed and report[0].status == selfcheck.WRONG
    assert lines[0].startswith("Exercise 1.1 (tip position): wrong: ")
    assert re.search(r"\. Hint [12] of 2: ", lines[0]) and len(lines) == 1


def test_hints_go_from_a_nudge_to_a_more_specific_step_with_the_tries(monkeypatch):
    monkeypatch.setattr(selfcheck, "_WRONG_TRIES", collections.Counter())
    hints = exercises.get("1.1").parts[0].hints
    shown = [checked("1.1", [0.0, 0.0])[1][0] for _ in range(len(hints) + 1)]
    for tier, line in enumerate(shown[: len(hints)], start=1):
        assert line.endswith(f"Hint {tier} of {len(hints)}: {hints[tier - 1]}")
    assert shown[-1].endswith(f"Hint {len(hints)} of {len(hints)}: {hints[-1]}")
    # a mistake named in words, or the miss sized: never a bare tolerance
    assert "allowed" not in " ".join(shown) and "off by" not in " ".join(shown)


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


def test_an_answer_that_breaks_reading_is_wrong_with_what_was_expected():
    class Hostile:
        def __float__(self):
            raise ZeroDivisionError("no")

    report, lines = checked("1.1", [Hostile(), 1.0])
    assert report[0].status == selfcheck.WRONG
    assert lines[0].startswith(
        "Exercise 1.1 (tip position): wrong: expected numbers in m, got a Hostile"
    )


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


# ---------------------------------------------------------------- the score nbgrader reads
def test_score_counts_the_correct_parts_only():
    q_rel = np.radians([60.0, 90.0])  # exercise 1.3: absolute (60, 150) deg, relative
    p_tip = arms.two_metre.fk(q_rel)
    right, _ = checked("1.3", q_rel, p_tip)
    half, _ = checked("1.3", q_rel, 2 * p_tip)
    unsolved, _ = checked("1.3", ..., ...)
    wrong, _ = checked("1.3", q_rel + 1.0, 2 * p_tip)
    assert [result.status for result in half] == [selfcheck.CORRECT, selfcheck.WRONG]
    assert (right.score, half.score, unsolved.score, wrong.score) == (2, 1, 0, 0)
    assert all(type(report.score) is int for report in (right, half, wrong))
    assert right.passed and not half.passed
