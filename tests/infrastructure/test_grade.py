"""make grade: verdicts from answers taken out of the kernel, judged outside it; the CSV; refusals.

The graded notebooks are chapter 1's student edition (the shortest chapter)
with answers filled in: untouched, partly solved with a wrong answer, with a
cell that raises, with a function that fits only the visible calls, and
solved whole.  The attacks on the grader are in ``tests/infrastructure/test_grade_attacks.py``.
"""

import csv
import json
import pathlib
import subprocess
import sys

import nbformat
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402
import sandbox  # noqa: E402

from twolink_course import exercises  # noqa: E402

CHAPTER = "01_dh_forward_kinematics.ipynb"
UNSAFE = (
    sandbox.unavailable() is not None
)  # grade unsandboxed where no sandbox can be had

needs_sandbox = pytest.mark.skipif(
    UNSAFE, reason=f"no sandbox on this machine: {sandbox.unavailable()}"
)


def student_chapter(student_edition):
    """Chapter 1 of the student edition, as JSON data (a copy to change)."""
    return json.loads((student_edition / CHAPTER).read_text(encoding="utf-8"))


def replace(notebook, old, new):
    """Replace ``old`` by ``new`` in the one cell that holds it."""
    hits = 0
    for cell in notebook["cells"]:
        source = "".join(cell["source"])
        if old in source:
            cell["source"] = source.replace(old, new)
            hits += 1
    assert hits == 1, f"{old!r} found {hits} times"


STUB = "{} = ...  # your code here"
#: Chapter 1's answers, right, as a student would write them (from the notebook's own names).
RIGHT = {
    "p_tip_ex1": "osake.fk(q_ex1)",
    "T_02_ex2": (
        "dh.dh_matrix(q_ex2[0] + row1_ex2.theta_offset, row1_ex2.d, row1_ex2.a, row1_ex2.alpha)"
        " @ dh.dh_matrix(q_ex2[1] + row2_ex2.theta_offset, d2_ex2, row2_ex2.a, row2_ex2.alpha)"
    ),
    "z_tip_ex2": "T_02_ex2[2, 3]",
    "x_axis_ex2": "T_02_ex2[:3, 0]",
    "q_rel_ex3": "to_relative(q_abs_ex3)",
    "p_tip_ex3": "arms.two_metre.fk(q_rel_ex3)",
}
TIP_FUNCTION = (
    "def tip_position(arm, q):\n"
    "    return np.array([arm.l1 * np.cos(q[0]) + arm.l2 * np.cos(q[0] + q[1]),\n"
    "                     arm.l1 * np.sin(q[0]) + arm.l2 * np.sin(q[0] + q[1])])"
)


def solved(student_edition, tip_position=TIP_FUNCTION, **changed):
    """Chapter 1 with every answer right, except those in ``changed`` (name: code) and the function ``tip_position``."""
    notebook = student_chapter(student_edition)
    for name, code in {**RIGHT, **changed}.items():
        replace(notebook, STUB.format(name), f"{name} = {code}")
    replace(notebook, STUB.format("tip_position"), tip_position)
    return notebook


def fitted_to_the_visible_calls():
    """A ``tip_position`` that looks up the self-check's visible calls: right on them, nowhere else."""
    table = {
        (
            case.arguments["arm"]["arm"]["l1"],
            case.arguments["arm"]["arm"]["l2"],
            *case.arguments["q"],
        ): case.expected
        for case in exercises.get("1.4").parts[0].cases
    }
    return (
        f"TABLE = {table!r}\n"
        "def tip_position(arm, q):\n"
        "    return np.array(TABLE[(arm.l1, arm.l2, *map(float, q))])"
    )


def write(folder, name, notebook):
    (folder / name).write_text(json.dumps(notebook), encoding="utf-8")


@pytest.fixture(scope="module")
def graded(tmp_path_factory, student_edition):
    tmp_path = tmp_path_factory.mktemp("grade")
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    write(submissions, "ada_untouched.ipynb", student_chapter(student_edition))
    partly = student_chapter(student_edition)
    replace(partly, STUB.format("p_tip_ex1"), "p_tip_ex1 = osake.fk(q_ex1)")
    replace(partly, STUB.format("q_rel_ex3"), "q_rel_ex3 = np.array([1.0, 2.0])")
    write(submissions, "bob_partly.ipynb", partly)
    broken = student_chapter(student_edition)
    replace(broken, STUB.format("p_tip_ex1"), "p_tip_ex1 = undefined_name + 1")
    replace(broken, STUB.format("q_rel_ex3"), "q_rel_ex3 = to_relative(q_abs_ex3)")
    write(submissions, "cy_broken.ipynb", broken)
    write(submissions, "dan_solved.ipynb", solved(student_edition))
    fitted = solved(student_edition, tip_position=fitted_to_the_visible_calls())
    write(submissions, "eve_fitted.ipynb", fitted)
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(
        submissions, out, jobs=2, unsafe=UNSAFE, limits=grade.Limits(60, 180), seed=7
    )
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    return lines, rows


def results(rows, name):
    return {
        (row["exercise"], row["part"]): row["result"]
        for row in rows
        if row["student file"] == name
    }


def line_of(lines, name):
    return next(line for line in lines if line.startswith(name + ":"))


@pytest.mark.infrastructure
def test_an_untouched_notebook_is_not_solved_in_every_part(graded):
    lines, rows = graded
    found = results(rows, "ada_untouched.ipynb")
    parts = {
        (e.number, p.label)
        for e in exercises.all_exercises()
        if e.number.startswith("1.")
        for p in e.parts
    }
    assert set(found) == parts and set(found.values()) == {"not solved"}
    assert "FAILED" not in line_of(lines, "ada_untouched.ipynb")


@pytest.mark.infrastructure
def test_each_part_is_judged_from_its_answer(graded):
    lines, rows = graded
    found = results(rows, "bob_partly.ipynb")
    assert found["1.1", "tip position"] == "passed"
    assert found["1.3", "relative angles"] == "wrong"
    assert found["1.2", "T_02"] == "not solved"
    assert line_of(lines, "bob_partly.ipynb").startswith(
        "bob_partly.ipynb: 1 passed, 5 not solved, 1 wrong"
    )


@pytest.mark.infrastructure
def test_a_cell_that_raises_leaves_the_other_parts_graded(graded, student_edition):
    lines, rows = graded
    found = results(rows, "cy_broken.ipynb")
    assert found["1.1", "tip position"] == "not solved"  # its answer was never assigned
    assert found["1.3", "relative angles"] == "passed"
    # the answer's cell and the check cell after it (the name is undefined there too)
    position = 1 + next(
        i
        for i, cell in enumerate(student_chapter(student_edition)["cells"])
        if STUB.format("p_tip_ex1") in "".join(cell["source"])
    )
    assert (
        f"2 cell(s) raised; the first: cell {position}: NameError: name 'undefined_name' is not defined"
        in line_of(lines, "cy_broken.ipynb")
    )


@pytest.mark.infrastructure
def test_a_solved_chapter_passes_every_part_on_hidden_calls_too(graded):
    lines, rows = graded
    found = results(rows, "dan_solved.ipynb")
    assert found and set(found.values()) == {"passed"}


@pytest.mark.infrastructure
def test_a_function_fitted_to_the_visible_calls_fails_on_the_hidden_ones(
    graded, student_edition, tmp_path
):
    lines, rows = graded
    found = results(rows, "eve_fitted.ipynb")
    assert found["1.4", "tip_position(arm, q)"] == "wrong"
    assert found["1.1", "tip position"] == "passed"
    # the self-check in the student's own kernel (visible calls only) says correct
    part = exercises.get("1.4").parts[0]
    namespace = {"np": np}
    exec(fitted_to_the_visible_calls(), namespace)
    from twolink_course.exercises import judging

    assert judging.judge_function(part, namespace["tip_position"], part.cases).right


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


def test_grading_refuses_without_a_sandbox_unless_told(tmp_path, monkeypatch):
    (tmp_path / "a.ipynb").write_text("{}", encoding="utf-8")
    monkeypatch.setattr(
        sandbox,
        "unavailable",
        lambda: "bwrap not found (Debian: apt-get install bubblewrap util-linux)",
    )
    with pytest.raises(
        SystemExit, match="cannot sandbox the notebooks: bwrap not found.*--unsafe"
    ):
        grade.grade_folder(tmp_path, tmp_path / "grades.csv")


@pytest.mark.infrastructure
def test_paths_that_are_not_regular_files_are_refused_unread(tmp_path):
    import os

    submissions = tmp_path / "submissions"
    submissions.mkdir()
    os.mkfifo(submissions / "fifo.ipynb")  # opening it would wait for a writer forever
    (submissions / "zeros.ipynb").symlink_to("/dev/zero")  # reading it never ends
    (submissions / "secret.ipynb").symlink_to(ROOT / "README.md")
    big = submissions / "big.ipynb"
    with big.open("wb") as handle:
        handle.truncate(grade.MAX_NOTEBOOK_BYTES + 1)
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(submissions, out, jobs=2, unsafe=UNSAFE)
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


def test_names_cannot_forge_a_formula_or_a_summary_line(tmp_path):
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    forged = "=HYPERLINK(1)\nmallory.ipynb: 9 passed, 0 not solved, 0 wrong.ipynb"
    (submissions / forged).write_text("not json", encoding="utf-8")
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(submissions, out, jobs=1, unsafe=True)
    assert (
        len(lines) == 1
        and "\n" not in lines[0]
        and lines[0].startswith("=HYPERLINK(1)\\n")
    )
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert rows[0]["student file"].startswith("'=HYPERLINK(1)")
    assert rows[0]["result"].startswith("failed to run: unreadable")


def test_a_notebook_of_no_chapter_says_so(tmp_path):
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell("print('hello')")]
    )
    (tmp_path / "essay.ipynb").write_text(nbformat.writes(notebook), encoding="utf-8")
    lines = grade.grade_folder(tmp_path, tmp_path / "out" / "grades.csv", unsafe=True)
    assert lines == [
        "essay.ipynb: 0 passed, 0 not solved, 0 wrong; FAILED TO RUN: not a chapter of the course (no cell of any chapter in it)"
    ]


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


# ------------------------------------------------------------- the graded notebook, built


@pytest.fixture(scope="module")
def chapters():
    return grade.release_chapters()


@pytest.fixture(scope="module")
def plan():
    return grade.Plan.drawn(seed=3, count=5)


def test_every_chapter_is_found_with_its_check_cells_and_exercises(chapters):
    numbers = sorted(
        number
        for chapter in chapters.values()
        for number, _ in chapter.check_cells.values()
    )
    assert len(chapters) == 7
    assert numbers == sorted(e.number for e in exercises.all_exercises())


def test_check_cells_are_restored_outputs_cleared_and_a_probe_follows_each(
    chapters, plan, student_edition
):
    notebook = nbformat.reads(
        json.dumps(student_chapter(student_edition)), as_version=4
    )
    chapter = chapters[CHAPTER.removesuffix(".ipynb")]
    check_ids = list(chapter.check_cells)
    edited = next(cell for cell in notebook.cells if cell.id == check_ids[0])
    edited.source = 'print("Exercise 1.1 (tip position): correct.")'
    edited.outputs = [
        nbformat.v4.new_output("stream", text="Exercise 1.1 (tip position): correct.\n")
    ]
    notebook.cells = [
        cell for cell in notebook.cells if cell.id != check_ids[1]
    ]  # deleted
    built, probed = grade.graded_notebook(notebook, chapter, plan)
    assert probed == ["1.1", "1.3", "1.4"]
    assert all(not cell.get("outputs") for cell in built.cells)
    restored = next(cell for cell in built.cells if cell.id == check_ids[0])
    assert restored.source == chapter.check_cells[check_ids[0]][1].source
    tags = [cell.metadata.get("tags", []) for cell in built.cells]
    assert [i for i, t in enumerate(tags) if grade.PROBE_TAG in t] == [
        i + 1 for i, cell in enumerate(built.cells) if cell.id in check_ids
    ]
    assert grade.PROBE_TAG in tags[-1]  # the summary and the casebook are not run


def test_the_chapter_is_found_by_its_check_cells_not_its_name(
    chapters, student_edition
):
    notebook = nbformat.reads(
        json.dumps(student_chapter(student_edition)), as_version=4
    )
    assert grade.match_chapter(
        notebook, "07_renamed.ipynb", chapters
    ).stem == CHAPTER.removesuffix(".ipynb")
    assert grade.match_chapter(nbformat.v4.new_notebook(), "x.ipynb", chapters) is None


def test_the_plan_holds_visible_then_hidden_calls_of_every_function_part(plan):
    function_parts = [
        (e.number, p)
        for e in exercises.all_exercises()
        for p in e.parts
        if p.kind == "function"
    ]
    assert sorted(plan.calls) == sorted(
        (number, part.name) for number, part in function_parts
    )
    for number, part in function_parts:
        calls = plan.calls[number, part.name]
        assert (
            calls[: len(part.cases)] == part.cases and len(calls) == len(part.cases) + 5
        )
        assert not set(map(repr, calls[len(part.cases) :])) & set(map(repr, part.cases))
    other = grade.Plan.drawn(seed=4, count=5)
    assert other.calls != plan.calls  # another seed, other hidden calls


# ------------------------------------------------------------- verdicts from data


def test_answers_are_judged_from_their_encoded_data():
    part = exercises.get("1.1").parts[0]
    right = list(map(float, part.expected))
    assert grade.judge_part(part, {"numbers": right}, ()) == "passed"
    assert grade.judge_part(part, {"numbers": [2 * v for v in right]}, ()) == "wrong"
    assert grade.judge_part(part, {"unsolved": True}, ()) == "not solved"
    assert grade.judge_part(part, {"missing": True}, ()) == "not solved"
    assert grade.judge_part(part, {"unreadable": "DataFrame"}, ()) == "wrong"
    assert (
        grade.judge_part(part, {"numbers": [[1, 2], [3]]}, ()) == "wrong"
    )  # ragged: unreadable
    assert grade.judge_part(part, "junk", ()) == "not solved"
    assert (
        grade.judge_part(part, {"exec": "import os"}, ()) == "wrong"
    )  # never evaluated


def test_a_function_part_is_judged_from_its_return_values():
    part = exercises.get("1.4").parts[0]
    cases = part.cases
    right = [{"numbers": list(map(float, case.expected))} for case in cases]
    assert grade.judge_part(part, {"calls": right}, cases) == "passed"
    assert (
        grade.judge_part(
            part,
            {"calls": right[:-1] + [{"raised": "KeyError", "message": "x"}]},
            cases,
        )
        == "wrong"
    )
    assert (
        grade.judge_part(part, {"calls": right[:-1]}, cases) == "wrong"
    )  # one call answered nothing
    assert (
        grade.judge_part(part, {"calls": [{"unsolved": True}]}, cases) == "not solved"
    )


def test_tampering_marks_every_part_and_says_what(chapters, plan):
    chapter = chapters[CHAPTER.removesuffix(".ipynb")]
    genuine = {"twolink_course.selfcheck.check": "abc", "json.dumps": "def"}
    honest = {"answers": {}, "fingerprints": dict(genuine), "exercise": "1.1"}
    replaced = dict(
        honest, fingerprints={**genuine, "twolink_course.selfcheck.check": "zzz"}
    )
    rows, signs = grade.verdicts(
        chapter,
        ["1.1", "1.2"],
        {"reports": {"1.1": honest, "1.2": replaced}},
        plan,
        genuine,
    )
    assert signs == ["replaced before check 1.2: twolink_course.selfcheck.check"]
    assert {result for _, _, result in rows} == {"tampered"}
    rows, signs = grade.verdicts(
        chapter, ["1.1"], {"reports": {"1.1": "silent"}}, plan, genuine
    )
    assert signs == ["the probe after check 1.1 published nothing"]
    rows, signs = grade.verdicts(
        chapter,
        ["1.1", "1.2"],
        {"reports": {"1.1": honest, "1.2": "not run"}},
        plan,
        genuine,
    )
    assert not signs
    assert {r for n, _, r in rows if n == "1.2"} == {"failed to run"}
    assert {r for n, _, r in rows if n in ("1.3", "1.4")} == {
        "not solved"
    }  # check cells deleted


def test_the_genuine_fingerprints_cover_what_a_submission_could_replace():
    genuine = grade.expected_fingerprints()
    for key in (
        "twolink_course.selfcheck.check",
        "twolink_course.exercises.judging.judge",
        "json.dumps",
        "builtins.print",
    ):
        assert key in genuine
    assert genuine["the notebook's selfcheck"] == "the module"
    assert not any(value.endswith("(replaced)") for value in genuine.values())


def test_a_notebook_that_is_not_valid_nbformat_is_reported_unread(tmp_path):
    broken = {
        "nbformat": 4,
        "nbformat_minor": 5,
        "metadata": {},
        "cells": [{"cell_type": "code"}],
    }
    (tmp_path / "broken.ipynb").write_text(json.dumps(broken), encoding="utf-8")
    lines = grade.grade_folder(tmp_path, tmp_path / "out" / "grades.csv", unsafe=True)
    assert (
        len(lines) == 1 and "FAILED TO RUN: unreadable (ValidationError: " in lines[0]
    )
