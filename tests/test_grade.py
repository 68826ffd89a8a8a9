"""make grade: returned notebooks run headless, a CSV and a line per notebook, failures reported.

Uses the student edition of chapter 1 (the shortest): one untouched, one with
an exercise solved and one answered wrongly, and one broken (a cell raises).
"""

import csv
import json
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402

CHAPTER = "01_dh_forward_kinematics.ipynb"


def _student_chapter(student_edition):
    return json.loads((student_edition / CHAPTER).read_text(encoding="utf-8"))


def _replace(notebook, old, new):
    hits = 0
    for cell in notebook["cells"]:
        source = "".join(cell["source"])
        if old in source:
            cell["source"] = source.replace(old, new)
            hits += 1
    assert hits == 1, f"{old!r} found {hits} times"


@pytest.fixture(scope="module")
def graded(tmp_path_factory, student_edition):
    tmp_path = tmp_path_factory.mktemp("grade")
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    untouched = _student_chapter(student_edition)
    (submissions / "ada_untouched.ipynb").write_text(
        json.dumps(untouched), encoding="utf-8"
    )
    solved = _student_chapter(student_edition)
    _replace(solved, "p_tip_ex1 = ...  # your code here", "p_tip_ex1 = osake.fk(q_ex1)")
    _replace(
        solved, "q_rel_ex3 = ...  # your code here", "q_rel_ex3 = np.array([1.0, 2.0])"
    )
    (submissions / "bob_solved.ipynb").write_text(json.dumps(solved), encoding="utf-8")
    broken = _student_chapter(student_edition)
    _replace(
        broken, "p_tip_ex1 = ...  # your code here", "p_tip_ex1 = undefined_name + 1"
    )
    (submissions / "cy_broken.ipynb").write_text(json.dumps(broken), encoding="utf-8")
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(submissions, out, timeout=120, jobs=2)
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    return lines, rows


def _results(rows, name):
    return {
        (row["exercise"], row["part"]): row["result"]
        for row in rows
        if row["student file"] == name
    }


@pytest.mark.infrastructure
def test_untouched_notebook_is_all_not_solved(graded):
    lines, rows = graded
    results = _results(rows, "ada_untouched.ipynb")
    assert results and set(results.values()) == {"not solved"}
    assert {exercise for exercise, _ in results} == {"1.1", "1.2", "1.3"}
    assert any(
        line.startswith("ada_untouched.ipynb: 0 passed,") and "FAILED" not in line
        for line in lines
    )


@pytest.mark.infrastructure
def test_solved_and_wrong_parts_are_graded(graded):
    lines, rows = graded
    results = _results(rows, "bob_solved.ipynb")
    assert [
        result for (exercise, _), result in results.items() if exercise == "1.1"
    ] == ["passed"]
    assert "wrong" in [
        result for (exercise, _), result in results.items() if exercise == "1.3"
    ]
    assert any(
        line.startswith("bob_solved.ipynb: 1 passed,") and " 1 wrong" in line
        for line in lines
    )


@pytest.mark.infrastructure
def test_a_notebook_that_fails_to_run_is_reported(graded):
    lines, rows = graded
    failed = [
        row
        for row in rows
        if row["student file"] == "cy_broken.ipynb"
        and row["result"].startswith("failed to run")
    ]
    assert len(failed) == 1 and "NameError" in failed[0]["result"]
    assert any(
        line.startswith("cy_broken.ipynb:")
        and "FAILED TO RUN: error: NameError" in line
        for line in lines
    )


def test_make_grade_needs_a_folder():
    result = subprocess.run(
        ["make", "-s", "grade", "SUBMISSIONS="],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert result.returncode != 0 and "usage: make grade SUBMISSIONS=" in result.stdout
    with pytest.raises(SystemExit, match="not a folder"):
        grade.grade_folder(ROOT / "no-such-folder", ROOT / "build" / "unused.csv")


@pytest.mark.infrastructure
def test_paths_that_are_not_regular_files_are_refused_unread(tmp_path):
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    os.mkfifo(submissions / "fifo.ipynb")  # opening it would wait for a writer forever
    (submissions / "zeros.ipynb").symlink_to("/dev/zero")  # reading it never ends
    (submissions / "secret.ipynb").symlink_to(ROOT / "README.md")
    big = submissions / "big.ipynb"
    with big.open("wb") as handle:
        handle.truncate(grade.MAX_NOTEBOOK_BYTES + 1)
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(submissions, out, timeout=5, jobs=2)
    with out.open(encoding="utf-8") as handle:
        rows = {row["student file"]: row["result"] for row in csv.DictReader(handle)}
    assert (
        rows["fifo.ipynb"]
        == "refused: not a regular file (a FIFO, a device or a socket)"
    )
    assert (
        rows["zeros.ipynb"]
        == rows["secret.ipynb"]
        == "refused: a symbolic link, not a regular file"
    )
    assert (
        rows["big.ipynb"].startswith("refused: ")
        and "bytes, more than" in rows["big.ipynb"]
    )
    assert "#" not in out.read_text(encoding="utf-8")  # nothing of README.md copied
    assert len(lines) == 4 and all(": REFUSED: " in line for line in lines)
    assert not list(
        tmp_path.glob(".grades-*")
    )  # the atomic write left no temporary file


@pytest.mark.infrastructure
def test_names_cannot_forge_a_formula_or_a_summary_line(tmp_path):
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    forged = "=HYPERLINK(1)\nmallory.ipynb: 9 passed, 0 not solved, 0 wrong.ipynb"
    (submissions / forged).write_text("not json", encoding="utf-8")
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(submissions, out, timeout=5, jobs=1)
    assert (
        len(lines) == 1
        and "\n" not in lines[0]
        and lines[0].startswith("=HYPERLINK(1)\\n")
    )
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert rows[0]["student file"].startswith("'=HYPERLINK(1)")
    assert rows[0]["result"].startswith("failed to run: unreadable")


@pytest.mark.parametrize(
    "value, written",
    [
        ("=1+1", "'=1+1"),
        ("+1", "'+1"),
        ("-1", "'-1"),
        ("@SUM(A1)", "'@SUM(A1)"),
        ("\tx", "'\tx"),
        ("passed", "passed"),
        ("1.1", "1.1"),
    ],
)
def test_csv_cells_never_start_a_formula(value, written):
    assert grade.csv_cell(value) == written
