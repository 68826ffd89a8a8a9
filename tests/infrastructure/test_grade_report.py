"""What the teacher hands on (tools/grade_report.py): grades, a gradebook in nbgrader's export columns,
points and totals, a feedback file per student; any file name escaped; returned twice and missing flagged."""

import csv
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade_report  # noqa: E402
from grade_report import Graded  # noqa: E402
from grade_verdicts import Verdict  # noqa: E402

CHAPTERS = {"01_dh": {"1.1": 1, "1.2": 2}, "02_ik": {"2.1": 1}}
MULLER = os.fsdecode(b"M\xfcller")  # a Latin-1 name, as unzip leaves it: not UTF-8


def verdicts(chapter, results):
    numbers = {"01_dh": ["1.1", "1.2", "1.2"], "02_ik": ["2.1"]}[chapter]
    return [
        Verdict(
            number,
            f"part {i}",
            result,
            "" if result == "passed" else "your tip is 2 cm too far",
        )
        for i, (number, result) in enumerate(zip(numbers, results))
    ]


@pytest.fixture
def written(tmp_path):
    notebooks = [
        Graded(
            "ada/01_dh.ipynb",
            "ada",
            "01_dh",
            verdicts("01_dh", ["passed"] * 3),
            modified=100.0,
        ),
        Graded(
            "ada/02_ik.ipynb",
            "ada",
            "02_ik",
            verdicts("02_ik", ["wrong"]),
            modified=100.0,
        ),
        # bob returns chapter 1 twice: the later file counts
        Graded(
            "bob/01_dh.ipynb",
            "bob",
            "01_dh",
            verdicts("01_dh", ["passed", "wrong", "wrong"]),
            modified=50.0,
        ),
        Graded(
            "bob/01_dh_final.ipynb",
            "bob",
            "01_dh",
            verdicts("01_dh", ["passed", "passed", "not solved"]),
            modified=90.0,
        ),
        Graded(
            f"{MULLER}/01_dh.ipynb",
            grade_report.text(MULLER),
            "01_dh",
            verdicts("01_dh", ["passed"] * 3),
            modified=1.0,
        ),
        Graded(
            "=cmd|' /C calc'!A0.ipynb",
            "=cmd|' /C calc'!A0",
            None,
            [],
            "unreadable (not JSON)",
        ),
    ]
    grade_report.write_grades(tmp_path / "grades.csv", notebooks)
    students = grade_report.write_gradebook(tmp_path, notebooks, CHAPTERS)
    returned = grade_report.class_chapters(notebooks, CHAPTERS)
    grade_report.write_feedback(tmp_path, students, {c: CHAPTERS[c] for c in returned})
    return tmp_path


def rows(path):
    with path.open(encoding="utf-8", newline="") as handle:
        return list(csv.DictReader(handle))


def test_the_gradebook_has_nbgrader_s_export_columns_and_a_row_per_student_and_chapter(
    written,
):
    with (written / "gradebook.csv").open(encoding="utf-8") as handle:
        header = handle.readline().strip()
    assert (
        header
        == "assignment,duedate,timestamp,student_id,last_name,first_name,email,raw_score,late_submission_penalty,score,max_score"
    )
    found = {
        (row["student_id"], row["assignment"]): row
        for row in rows(written / "gradebook.csv")
    }
    assert (
        found["ada", "01_dh"]["score"] == "3.0"
        and found["ada", "01_dh"]["max_score"] == "3.0"
    )
    assert found["ada", "02_ik"]["score"] == "0.0"
    assert found["bob", "01_dh"]["score"] == "2.0"  # the file modified last
    assert (
        found["bob", "02_ik"]["score"] == "0.0"
        and found["bob", "02_ik"]["timestamp"] == ""
    )  # not returned
    assert found["M\\xfcller", "01_dh"]["score"] == "3.0"
    assert found["ada", "01_dh"]["timestamp"].startswith("1970-01-01 00:01:40")


def test_points_per_exercise_totals_and_flags(written):
    found = {row["student_id"]: row for row in rows(written / "points.csv")}
    assert list(found["ada"])[:5] == ["student_id", "1.1", "1.2", "2.1", "total"]
    assert (found["ada"]["1.2"], found["ada"]["total"], found["ada"]["max_score"]) == (
        "2",
        "3",
        "4",
    )
    assert found["bob"]["total"] == "2"
    assert (
        "chapter 01_dh returned 2 times (bob/01_dh.ipynb, bob/01_dh_final.ipynb): bob/01_dh_final.ipynb counts"
        in found["bob"]["flags"]
    )
    assert (
        "missing: 02_ik" in found["bob"]["flags"]
        and "missing" not in found["ada"]["flags"]
    )


def test_every_part_is_a_row_with_its_message_and_names_are_escaped(written):
    found = rows(written / "grades.csv")
    assert [
        row["result"] for row in found if row["student file"] == "bob/01_dh.ipynb"
    ] == ["passed", "wrong", "wrong"]
    assert (
        found[1]["points"] == "1" and found[3]["message"] == "your tip is 2 cm too far"
    )
    assert any(row["student file"] == "M\\xfcller/01_dh.ipynb" for row in found)
    formula = [row for row in found if row["exercise"] == "(none)"]
    assert (
        formula[0]["student file"].startswith("'=cmd")
        and formula[0]["result"] == "failed to run: unreadable (not JSON)"
    )
    assert not list(
        written.glob(".grades-*")
    )  # the atomic writes left no temporary file


def test_a_feedback_file_per_student_with_each_verdict_and_message(written):
    files = sorted(path.name for path in (written / "feedback").iterdir())
    assert files == ["=cmd|' _C calc'!A0.md", "M_xfcller.md", "ada.md", "bob.md"]
    text = (written / "feedback" / "bob.md").read_text(encoding="utf-8")
    assert text.startswith("# Feedback: bob\n\nTotal: 2 of 4 points.")
    assert "- chapter 01_dh returned 2 times" in text and "- missing: 02_ik" in text
    assert "| 1.2 | part 2 | not solved | your tip is 2 cm too far |" in text
    assert "## 01_dh (bob/01_dh_final.ipynb): 2 of 3 points" in text


@pytest.mark.parametrize(
    "name, student",
    [
        ("ada/ps1/01_dh.ipynb", "ada"),
        ("bob_01_dh.ipynb", "bob"),
        ("01_dh.ipynb", "01_dh"),
        ("cy-02-answers.ipynb", "cy-answers"),
    ],
)
def test_the_student_is_the_first_folder_or_the_name_without_the_chapter(name, student):
    assert (
        grade_report.student_of(pathlib.PurePath(name), ["01_dh", "02_ik"]) == student
    )


@pytest.mark.parametrize(
    "value, written",
    [
        ("=1+1", "'=1+1"),
        ("+1", "'+1"),
        ("-1", "'-1"),
        ("@SUM(A1)", "'@SUM(A1)"),
        ("\tx", "'\tx"),
        ("passed", "passed"),
    ],
)
def test_csv_cells_never_start_a_formula(value, written):
    assert grade_report.csv_cell(value) == written


def test_a_summary_line_cannot_be_forged_by_a_name():
    graded = Graded(
        grade_report.text("a.ipynb\nmallory.ipynb: 9 passed"),
        "a",
        "01_dh",
        verdicts("02_ik", ["passed"]),
    )
    line = grade_report.summary_line(graded)
    assert "\n" not in line and line.startswith(
        "a.ipynb\\nmallory.ipynb: 9 passed: 1 passed"
    )
