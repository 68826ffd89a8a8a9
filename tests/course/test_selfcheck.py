"""twolink_course.selfcheck: verdicts on right, wrong and unsolved answers, and the lines read back."""

import collections
import contextlib
import io
import re

import numpy as np
import pytest

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
#: Exercise 1.1's answer on its visible inputs, as stored (the chapter's inputs may change).
RIGHT_TIP = np.asarray(exercises.get("1.1").parts[0].expected, dtype=float)


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
    [RIGHT_TIP + [0.01, 0.0], -RIGHT_TIP, "abc", [1.0, 2.0, 3.0]],
    ids=["off by a centimetre", "mirrored", "a string", "three numbers"],
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
    q_rel, p_tip = (  # exercise 1.3's two parts, as stored
        np.asarray(part.expected, dtype=float) for part in exercises.get("1.3").parts
    )
    right, _ = checked("1.3", q_rel, p_tip)
    half, _ = checked("1.3", q_rel, 2 * p_tip)
    unsolved, _ = checked("1.3", ..., ...)
    wrong, _ = checked("1.3", q_rel + 1.0, 2 * p_tip)
    assert [result.status for result in half] == [selfcheck.CORRECT, selfcheck.WRONG]
    assert (right.score, half.score, unsolved.score, wrong.score) == (2, 1, 0, 0)
    assert all(type(report.score) is int for report in (right, half, wrong))
    assert right.passed and not half.passed


# ---------------------------------------------------------------- in a kernel: an answer never assigned, the score
def run_in_a_kernel(sources, grading):
    """Run ``sources`` as cells of a fresh kernel (the grading switch on or off); each cell's outputs."""
    import os

    import nbformat
    from nbclient import NotebookClient

    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source) for source in sources]
    )
    environment = {k: v for k, v in os.environ.items() if k != "TWOLINK_GRADING"}
    if grading:
        environment["TWOLINK_GRADING"] = "1"
    NotebookClient(
        notebook, timeout=120, allow_errors=True, kernel_name="python3"
    ).execute(env=environment)
    return [cell.outputs for cell in notebook.cells]


CELLS = [
    "import numpy as np\nfrom twolink import arms\nfrom twolink_course import selfcheck",
    "p_tip_ex1 = undefined_name + 1",
    'correct_ex1 = selfcheck.check("1.1", p_tip_ex1)',
    "another_undefined_name",
    # the stored answer (whatever the chapter's inputs): the check's result is its points
    "from twolink_course import exercises\np_tip_ex1 = exercises.get('1.1').parts[0].expected",
    'correct_ex1 = selfcheck.check("1.1", p_tip_ex1)',
]


@pytest.mark.infrastructure
@pytest.mark.parametrize("grading", [False, True], ids=["learning", "grading"])
def test_a_check_of_an_answer_never_assigned_says_so_in_a_sentence(grading):
    outputs = run_in_a_kernel(CELLS, grading)
    [error] = outputs[2]
    assert error.output_type == "error" and error.ename == "NameError"  # still 0 points
    assert error.evalue == selfcheck.not_checked("1.1", "p_tip_ex1")
    assert len(error.traceback) == 1  # the sentence, no traceback
    [other] = outputs[3]  # any other cell: the usual traceback
    assert other.evalue == "name 'another_undefined_name' is not defined"
    assert len(other.traceback) > 1
    results = [o for o in outputs[5] if o.output_type == "execute_result"]
    if grading:  # nbgrader's partial credit: the parts right, as the cell's result
        assert [r.data["text/plain"] for r in results] == ["1"]
    else:
        assert results == []
