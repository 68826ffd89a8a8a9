"""make grade: verdicts from answers taken out of the kernel and judged outside it; a class graded; refusals.

Two graded runs, each notebook in a fresh sandboxed kernel:

- the course's chapters: chapter 1's student edition untouched, answered
  every way (a cell that raises, a part left as released, a part wrong, a
  function fitted to the visible calls, an exercise solved) and solved as
  Colab saves it, beside every other chapter as the instructor solved it:
  each chapter is run once, cut to what its answers need (what nbval's run of
  the chapters cannot show: the cut chapter, the sandbox, the grader's probes
  and hidden inputs);
- a class of the small course of ``tests/_grading_course.py`` (a value
  exercise graded on hidden inputs, a function with the one-liner
  forbidden, a yes/no), each student in a folder of their own: the same
  honest answers saved by five tools, answers typed in, the one-liner, nan,
  a chapter returned twice, a name that is not UTF-8, an essay.

Setup mistakes are refused before any notebook runs; Ctrl-C stops within
seconds and leaves nothing behind.  The attacks are in
``tests/infrastructure/test_grade_attacks.py``.
"""

import csv
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import nbformat
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path[:0] = [str(ROOT), str(ROOT / "tools"), str(ROOT / "tests")]
import _grading_course as course_9  # noqa: E402
import course_map  # noqa: E402
import editions  # noqa: E402
import grade  # noqa: E402
import grade_plan  # noqa: E402
import grade_release  # noqa: E402
import sandbox  # noqa: E402

from twolink_course import exercises  # noqa: E402
from twolink_course.exercises import judging  # noqa: E402

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
#: The first parts of exercises 1.1 and 1.3 (by name, as the store has them).
TIP_1_1, RELATIVE_1_3 = (exercises.get(n).parts[0].name for n in ("1.1", "1.3"))


def instructor_solutions():
    """Chapter 1's worked solutions by ``grade_id``, as a student would type them (no markers)."""
    notebook = json.loads((ROOT / "notebooks" / CHAPTER).read_text(encoding="utf-8"))
    return {
        cell["metadata"]["nbgrader"]["grade_id"]: "".join(cell["source"])
        .replace("### BEGIN SOLUTION\n", "")
        .replace("### END SOLUTION", "")
        for cell in notebook["cells"]
        if cell["metadata"].get("nbgrader", {}).get("solution")
    }


def with_solutions(notebook, numbers, tip_position=None):
    """``notebook`` with the worked solutions of ``numbers`` typed in (1.4's function ``tip_position`` if given)."""
    solutions = instructor_solutions()
    chosen = {f"solution_{n.replace('.', '_')}" for n in numbers}
    for cell in notebook["cells"]:
        grade_id = cell["metadata"].get("nbgrader", {}).get("grade_id")
        if grade_id in chosen:
            cell["source"] = solutions[grade_id]
            if grade_id == "solution_1_4" and tip_position is not None:
                cell["source"] = tip_position
    return notebook


def solved(student_edition, tip_position=None):
    """Chapter 1 with every exercise's worked solution typed in (1.4's function ``tip_position`` if given)."""
    numbers = [
        e.number for e in exercises.all_exercises() if e.chapter + ".ipynb" == CHAPTER
    ]
    return with_solutions(student_chapter(student_edition), numbers, tip_position)


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
    return f"TABLE = {table!r}\ndef tip_position(arm, q):\n    return np.array(TABLE[(arm.l1, arm.l2, *map(float, q))])"


def as_colab(notebook):
    """``notebook`` as Colab saves it: no cell ids, nbformat 4.0, Colab's metadata, nbgrader's gone."""
    notebook = json.loads(json.dumps(notebook))
    for cell in notebook["cells"]:
        cell.pop("id", None)
        cell["metadata"] = {"id": "x" + str(len(cell["source"]))}
    notebook["nbformat_minor"] = 0
    notebook["metadata"] = {
        "colab": {"provenance": []},
        "kernelspec": {"name": "python3", "display_name": "Python 3"},
    }
    return notebook


def write(folder, name, notebook):
    (folder / name).write_text(json.dumps(notebook), encoding="utf-8")


#: The instructor's chapters graded beside chapter 1's student edition (chapter 1 is graded solved as Colab saves it).
INSTRUCTOR_CHAPTERS = [
    path for path in course_map.chapters(ROOT / "notebooks") if path.name != CHAPTER
]


def mixed(student_edition):
    """Chapter 1 of the student edition answered every way: 1.1 raises, 1.2 left as released,
    1.3's first part wrong and its second left, 1.4 fitted to the visible calls, 1.5 solved."""
    notebook = with_solutions(
        student_chapter(student_edition),
        ["1.4", "1.5"],
        tip_position=fitted_to_the_visible_calls(),
    )
    replace(notebook, STUB.format(TIP_1_1), f"{TIP_1_1} = undefined_name + 1")
    replace(
        notebook,
        STUB.format(RELATIVE_1_3),
        f"{RELATIVE_1_3} = np.array([1.0, 2.0])",
    )
    return notebook


@pytest.fixture(scope="module")
def graded(tmp_path_factory, student_edition):
    """Chapter 1's student edition untouched, answered every way, and solved (saved by Colab),
    with every other chapter as the instructor solved it: one run, each chapter cut to what its
    answers need, in a fresh sandboxed kernel."""
    tmp_path = tmp_path_factory.mktemp("grade")
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    write(submissions, "ada_untouched.ipynb", student_chapter(student_edition))
    write(submissions, "bob_mixed.ipynb", mixed(student_edition))
    write(submissions, "fay_colab.ipynb", as_colab(solved(student_edition)))
    for path in INSTRUCTOR_CHAPTERS:
        (submissions / path.name).write_bytes(path.read_bytes())
    out = tmp_path / "grades.csv"
    found = []
    lines = grade.grade_folder(
        submissions,
        out,
        jobs=2,
        unsafe=UNSAFE,
        limits=grade.Limits(60, 180),
        seed=7,
        graded_out=found,
    )
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    return lines, rows, {g.file: g for g in found}


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
    lines, rows, _ = graded
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
    lines, rows, _ = graded
    found = results(rows, "bob_mixed.ipynb")
    assert found["1.5", "DH table (d, a, alpha)"] == "passed"
    assert found["1.3", "relative angles"] == "wrong"
    assert found["1.3", "tip"] == found["1.2", "T_02"] == "not solved"
    assert list(found.values()).count("passed") == len(exercises.get("1.5").parts)
    assert line_of(lines, "bob_mixed.ipynb").startswith(
        f"bob_mixed.ipynb: 3 passed, {len(found) - 5} not solved, 2 wrong"
    )


@pytest.mark.infrastructure
def test_a_cell_that_raises_leaves_the_other_parts_graded(graded, student_edition):
    lines, rows, _ = graded
    found = results(rows, "bob_mixed.ipynb")
    assert found["1.1", "tip position"] == "not solved"  # its answer was never assigned
    assert found["1.5", "origin of frame 1"] == "passed"
    # numbered as in the file the teacher has
    position = 1 + next(
        i
        for i, cell in enumerate(student_chapter(student_edition)["cells"])
        if STUB.format(TIP_1_1) in "".join(cell["source"])
    )
    assert (
        f"1 cell(s) raised; the first: cell {position}: NameError: name 'undefined_name' is not defined"
        in line_of(lines, "bob_mixed.ipynb")
    )


@pytest.mark.infrastructure
def test_a_solved_chapter_saved_by_colab_passes_every_part_on_hidden_calls_too(graded):
    """Colab drops the cells' ids and nbgrader's metadata: every exercise is found by its content."""
    lines, rows, _ = graded
    parts = set(results(rows, "ada_untouched.ipynb"))
    assert results(rows, "fay_colab.ipynb") == dict.fromkeys(parts, "passed")


@pytest.mark.infrastructure
def test_a_function_fitted_to_the_visible_calls_fails_on_the_hidden_ones(graded):
    lines, rows, _ = graded
    found = results(rows, "bob_mixed.ipynb")
    assert found["1.4", "tip_position(arm, q)"] == "wrong"
    # the self-check in the student's own kernel (visible calls only) says correct
    part = exercises.get("1.4").parts[0]
    namespace = {"np": np}
    exec(fitted_to_the_visible_calls(), namespace)
    assert judging.judge_function(part, namespace["tip_position"], part.cases).right


@pytest.mark.infrastructure
def test_every_chapter_solved_passes_cut_to_what_its_answers_need(graded):
    """Chapter 1 typed into the student edition (saved by Colab), the others as the instructor solved them."""
    _, _, found = graded
    solved = [found["fay_colab.ipynb"]] + [found[p.name] for p in INSTRUCTOR_CHAPTERS]
    assert {g.chapter for g in solved} == {
        p.stem for p in course_map.chapters(ROOT / "notebooks")
    }
    for chapter in solved:
        assert {v.result for v in chapter.verdicts} == {"passed"}, chapter.file
        assert not chapter.notes and not chapter.failure, (
            chapter.file,
            chapter.notes,
            chapter.failure,
        )  # no cell raised


# ------------------------------------------------------------------ a class of the small course


def typed_numbers():
    """Exercise 9.1's answers typed in as the store (or a classmate, or the self-check's messages) gives them."""
    tip, reach = (part.expected for part in course_9.exercises()[0].parts)
    return (
        f"p_ex1 = np.array({[float(v) for v in tip]!r})\nreach_ex1 = {float(reach)!r}"
    )


@pytest.fixture(scope="module")
def a_class(tmp_path_factory):
    tmp_path = tmp_path_factory.mktemp("class")
    course_9.write_course(tmp_path / "course")
    course = grade_release.Course.read(tmp_path / "course", course_9.REFERENCES)
    submissions = tmp_path / "submissions"
    name = course_9.STEM + ".ipynb"
    right = course_9.RIGHT
    for student, tool in [("ada", "jupyterlab4"), ("bob", "colab"), ("cy", "vscode")]:
        course_9.returned(submissions / student, name, right, tool=tool)
    course_9.returned(submissions / "fay", name, {**right, "9.1": typed_numbers()})
    course_9.returned(
        submissions / "gus",
        name,
        {**right, "9.2": "def tip(arm, q):\n    return arm.fk(q)"},
    )
    course_9.returned(
        submissions / "hal",
        name,
        {
            **right,
            "9.1": "p_ex1 = np.full(2, np.nan)\nreach_ex1 = np.inf",
            "9.3": "faster_ex3 = float('nan')",
        },
    )
    course_9.returned(submissions / "ivy", name)  # untouched
    # returned twice: the later file counts
    older = course_9.returned(
        submissions / "jo", "first_try.ipynb", {**right, "9.3": "faster_ex3 = False"}
    )
    os.utime(older, (1_000_000, 1_000_000))
    course_9.returned(  # renamed, saved by JupyterLab 3
        submissions / "jo", "homework.ipynb", right, tool="jupyterlab3"
    )
    course_9.returned(submissions / "kim", "essay.ipynb", right).write_text(
        "{}", encoding="utf-8"
    )
    latin = pathlib.Path(os.fsdecode(bytes(submissions) + b"/M\xfcller"))
    course_9.returned(latin, name, right, tool="nbformat3")
    out = tmp_path / "out" / "grades.csv"
    graded = []
    lines = grade.grade_folder(
        submissions,
        out,
        jobs=2,
        unsafe=UNSAFE,
        seed=21,
        course=course,
        graded_out=graded,
    )
    plan = grade_plan.Plan.drawn(course, 21)
    return {
        "lines": lines,
        "out": out.parent,
        "graded": {g.file: g for g in graded},
        "plan": plan,
    }


def verdict_of(a_class, file):
    return {
        (v.number, v.part): (v.result, v.message)
        for v in a_class["graded"][file].verdicts
    }


@pytest.mark.infrastructure
@pytest.mark.parametrize("student", ["ada", "bob", "cy", "jo", "M\\xfcller"])
def test_honest_answers_pass_however_they_were_saved_and_named(a_class, student):
    file = next(
        f
        for f in a_class["graded"]
        if f.startswith(student + "/") and "first_try" not in f
    )
    assert {result for result, _ in verdict_of(a_class, file).values()} == {"passed"}, (
        file
    )


@pytest.mark.infrastructure
def test_numbers_typed_in_earn_nothing_where_the_answer_cell_is_run_on_other_inputs(
    a_class,
):
    found = verdict_of(a_class, f"fay/{course_9.STEM}.ipynb")
    for part in ("tip", "reach"):
        result, message = found["9.1", part]
        assert result == "wrong" and message.startswith(
            "right on the exercise's inputs but not on other inputs"
        )
    assert (
        found["9.3", "faster"][0] == "passed"
    )  # a yes/no: graded on the notebook's own values


@pytest.mark.infrastructure
def test_the_package_s_one_liner_fails_where_it_is_forbidden(a_class):
    assert verdict_of(a_class, f"gus/{course_9.STEM}.ipynb")["9.2", "tip(arm, q)"] == (
        "wrong",
        "this exercise asks you to write it yourself: arm.fk is the package's answer",
    )


@pytest.mark.infrastructure
def test_nan_and_inf_earn_nothing_and_an_untouched_notebook_is_not_solved(a_class):
    found = verdict_of(a_class, f"hal/{course_9.STEM}.ipynb")
    assert found["9.1", "tip"] == (
        "wrong",
        "your tip contains nan (not a number): compute finite numbers",
    )
    assert found["9.1", "reach"] == (
        "wrong",
        "your reach is infinite: compute a finite number",
    )
    assert found["9.3", "faster"][0] == "wrong"
    assert {
        r for r, _ in verdict_of(a_class, f"ivy/{course_9.STEM}.ipynb").values()
    } == {"not solved"}


@pytest.mark.infrastructure
def test_the_gradebook_points_and_feedback_of_the_class(a_class):
    folder = a_class["out"]
    with (folder / "gradebook.csv").open(encoding="utf-8") as handle:
        gradebook = {row["student_id"]: row for row in csv.DictReader(handle)}
    assert gradebook["ada"]["score"] == "4.0" and gradebook["ada"]["max_score"] == "4.0"
    assert gradebook["fay"]["score"] == "2.0" and gradebook["jo"]["score"] == "4.0"
    assert (
        gradebook["kim"]["score"] == "0.0" and gradebook["M\\xfcller"]["score"] == "4.0"
    )
    with (folder / "points.csv").open(encoding="utf-8") as handle:
        points = {row["student_id"]: row for row in csv.DictReader(handle)}
    assert (
        "returned 2 times" in points["jo"]["flags"]
        and "jo/homework.ipynb counts" in points["jo"]["flags"]
    )
    assert "missing: 09_synthetic" in points["kim"]["flags"]
    feedback = {
        path.name: path.read_text(encoding="utf-8")
        for path in (folder / "feedback").iterdir()
    }
    assert set(feedback) >= {"ada.md", "fay.md", "M_xfcller.md", "kim.md"}
    assert (
        "| 9.1 | tip | wrong | right on the exercise's inputs but not on other inputs"
        in feedback["fay.md"]
    )
    # no hidden input, no reference of a hidden draw in any feedback
    hidden = []
    for draw in a_class["plan"].draws["9.1"]:
        hidden += [f"{v:.4f}" for v in draw.inputs["q_ex1"]["array"]["values"]]
        hidden += [f"{v:.3f}" for v in np.ravel(draw.references["p_ex1"])]
    for text in feedback.values():
        assert not [value for value in hidden if value in text]


@pytest.mark.infrastructure
def test_a_file_name_that_is_not_utf8_is_graded_and_written_escaped(a_class):
    with (a_class["out"] / "grades.csv").open(encoding="utf-8") as handle:
        names = {row["student file"] for row in csv.DictReader(handle)}
    assert f"M\\xfcller/{course_9.STEM}.ipynb" in names
    assert any(
        line.startswith(f"M\\xfcller/{course_9.STEM}.ipynb: 4 passed")
        for line in a_class["lines"]
    )


# ------------------------------------------------------------------ setup mistakes, refused before anything runs


@pytest.fixture(scope="module")
def small_course(tmp_path_factory):
    """The small course: what the refusals below need of a course, read in milliseconds."""
    folder = tmp_path_factory.mktemp("small-course")
    course_9.write_course(folder)
    return grade_release.Course.read(folder, course_9.REFERENCES)


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


@pytest.mark.parametrize(
    "out, message",
    [
        ("{folder}", "a folder; give the CSV file to write"),
        ("{folder}/grades.ipynb", "a notebook's name; give a .csv file"),
        ("/dev/null/grades.csv", "cannot write in /dev/null"),
        (
            f"{sys.prefix}/grades.csv",
            "which every student's kernel can read: put it elsewhere",
        ),
    ],
    ids=["a folder", "a notebook", "not writable", "read by the kernels"],
)
def test_an_output_that_will_not_do_is_refused_in_one_sentence(tmp_path, out, message):
    (tmp_path / "a.ipynb").write_text("{}", encoding="utf-8")
    with pytest.raises(grade.SetupError, match=message) as refused:
        grade.check_folders(
            tmp_path, pathlib.Path(out.format(folder=tmp_path)), unsafe=False
        )
    assert "\n" not in str(refused.value)
    assert not (pathlib.Path(sys.prefix) / "grades.csv").exists()


def test_the_csv_may_be_written_in_the_repository_the_kernels_do_not_see_it(tmp_path):
    grade.check_folders(
        tmp_path, ROOT / "grades.csv", unsafe=False
    )  # refused before: "code -9"
    assert not (ROOT / "grades.csv").exists()


def test_a_kernel_that_cannot_start_or_imports_another_copy_is_refused(
    monkeypatch, tmp_path
):
    runner = grade.Runner(grade.Setting(tmp_path, None))  # no worker until a run
    monkeypatch.setattr(
        grade, "genuine_kernel", lambda runner, source: {"failure": "the kernel died"}
    )
    with pytest.raises(
        grade.SetupError,
        match=r"^a kernel could not start in the sandbox \(the kernel died\)",
    ):
        grade.check_kernel(runner)
    other = {"files": {"twolink": "/elsewhere/twolink/__init__.py"}, "fingerprints": {}}
    monkeypatch.setattr(grade, "genuine_kernel", lambda runner, source: other)
    with pytest.raises(
        grade.SetupError,
        match="the kernels import twolink from /elsewhere.*run the grader with the Python of the venv",
    ):
        grade.check_kernel(runner)


def test_an_exercise_graded_on_hidden_inputs_needs_its_inputs_cell(tmp_path):
    course_9.write_course(tmp_path)
    chapter = json.loads(
        (tmp_path / f"{course_9.STEM}.ipynb").read_text(encoding="utf-8")
    )
    chapter["cells"] = [
        cell for cell in chapter["cells"] if cell["source"] != course_9.INPUTS
    ]
    (tmp_path / f"{course_9.STEM}.ipynb").write_text(
        json.dumps(chapter), encoding="utf-8"
    )
    with pytest.raises(
        ValueError,
        match="exercise 9.1 is graded on hidden inputs .RERUN. but its chapter has no inputs cell",
    ):
        grade_release.Course.read(tmp_path, course_9.REFERENCES)


def test_names_cannot_forge_a_formula_or_a_summary_line(tmp_path, small_course):
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    forged = "=HYPERLINK(1)\nmallory.ipynb: 9 passed, 0 not solved, 0 wrong.ipynb"
    (submissions / forged).write_text("not json", encoding="utf-8")
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(
        submissions, out, jobs=1, unsafe=True, course=small_course
    )
    assert (
        len(lines) == 1
        and "\n" not in lines[0]
        and lines[0].startswith("=HYPERLINK(1)\\n")
    )
    with out.open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert rows[0]["student file"].startswith("'=HYPERLINK(1)")
    assert rows[0]["result"].startswith("failed to run: unreadable")


def test_a_notebook_of_no_chapter_says_so(tmp_path, small_course):
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell("print('hello')")]
    )
    (tmp_path / "essay.ipynb").write_text(nbformat.writes(notebook), encoding="utf-8")
    lines = grade.grade_folder(
        tmp_path, tmp_path / "out" / "grades.csv", unsafe=True, course=small_course
    )
    assert lines == [
        "essay.ipynb: 0 passed, 0 not solved, 0 wrong; FAILED TO RUN: not a chapter of the course (no cell of any chapter in it)"
    ]


def test_a_notebook_that_is_not_valid_nbformat_is_reported_unread(
    tmp_path, small_course
):
    broken = {
        "nbformat": 4,
        "nbformat_minor": 5,
        "metadata": {},
        "cells": [{"cell_type": "code"}],
    }
    (tmp_path / "broken.ipynb").write_text(json.dumps(broken), encoding="utf-8")
    lines = grade.grade_folder(
        tmp_path, tmp_path / "out" / "grades.csv", unsafe=True, course=small_course
    )
    assert lines == [
        "broken.ipynb: 0 passed, 0 not solved, 0 wrong; FAILED TO RUN: unreadable (cell 1 has no source)"
    ]


@pytest.mark.infrastructure
def test_paths_that_are_not_regular_files_are_refused_unread(tmp_path, small_course):
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    os.mkfifo(submissions / "fifo.ipynb")
    (submissions / "zeros.ipynb").symlink_to("/dev/zero")
    (submissions / "secret.ipynb").symlink_to(ROOT / "README.md")
    with (submissions / "big.ipynb").open("wb") as handle:
        handle.truncate(grade.MAX_NOTEBOOK_BYTES + 1)
    out = tmp_path / "grades.csv"
    lines = grade.grade_folder(
        submissions, out, jobs=2, unsafe=UNSAFE, course=small_course
    )
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


# ------------------------------------------------------------------ the edition's commit


def test_the_edition_records_its_commit_and_grading_warns_when_the_chapters_differ(
    tmp_path,
):
    course = grade_release.Course.read(ROOT / "notebooks", grade.REFERENCES)
    written = editions.build_student(ROOT / "notebooks", tmp_path)
    commit = editions.record_edition(written)
    assert commit == editions.commit_of() and commit != "unknown"
    first = json.loads((tmp_path / CHAPTER).read_text(encoding="utf-8"))
    assert first["metadata"]["twolink_edition"] == {
        "commit": commit,
        "digest": course.chapters[CHAPTER[:-6]].digest,
    }
    assert grade.edition_warnings(course, tmp_path) == []
    # the checkout moved on: chapter 1's check of 1.1 changed since the edition was made
    first["metadata"]["twolink_edition"]["digest"] = "0" * 12
    (tmp_path / CHAPTER).write_text(json.dumps(first), encoding="utf-8")
    [warning] = grade.edition_warnings(course, tmp_path)
    assert (
        "exercises of 01_dh_forward_kinematics differ from this checkout's" in warning
    )
    assert f"git checkout {commit[:12]}" in warning


# ------------------------------------------------------------------ the course install is enough


def requirement_names(path):
    names = []
    for line in path.read_text(encoding="utf-8").splitlines():
        line = line.split("#")[0].strip()
        if line and not line.startswith("-"):
            names.append(
                line.split("==")[0].split("[")[0].strip().lower().replace("_", "-")
            )
    return names


def closure(names):
    """Every distribution ``names`` bring, by their installed metadata (markers of extras left out)."""
    import importlib.metadata as metadata
    import re

    found, todo = set(), list(names)
    while todo:
        name = todo.pop()
        if name in found:
            continue
        found.add(name)
        try:
            requires = metadata.requires(name) or []
        except metadata.PackageNotFoundError:
            continue
        for requirement in requires:
            if "extra ==" in requirement:
                continue
            todo.append(
                re.split(r"[ ;<>=!~\[(]", requirement, maxsplit=1)[0]
                .lower()
                .replace("_", "-")
            )
    return found


def test_the_course_install_is_enough_for_make_student_and_make_grade():
    import ast
    import importlib.metadata as metadata

    course = closure([*requirement_names(ROOT / "requirements.txt"), "twolink"])
    distributions = metadata.packages_distributions()
    tools = ["grade", "grade_build", "grade_plan", "grade_prune", "grade_read", "grade_release", "grade_report",
             "grade_run", "grade_verdicts", "grading_probe", "sandbox", "editions", "install_cell", "nbgrader_cells", "course_map", "build_answers"]  # fmt: skip
    missing = []
    for tool in tools:
        tree = ast.parse((ROOT / "tools" / f"{tool}.py").read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom) and not node.level
                else []
            )
            for name in names:
                top = name.split(".")[0]
                if (
                    top in sys.stdlib_module_names
                    or top in tools
                    or (ROOT / "tools" / f"{top}.py").is_file()  # a tool of its own
                    or top
                    in (
                        "answers",
                        "twolink",
                        "twolink_course",
                        "jupyter_server_mathjax",
                    )
                ):
                    continue
                owners = {
                    d.lower().replace("_", "-") for d in distributions.get(top, [])
                }
                if not owners & course:
                    missing.append(f"{tool}: {top}")
    assert not missing, (
        f"make grade / make student need more than requirements.txt: {missing}"
    )
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    for target in ("student", "grade"):
        assert f"\n{target}: $(COURSE_STAMP)\n" in makefile


# ------------------------------------------------------------------ Ctrl-C


@pytest.mark.infrastructure
def test_ctrl_c_stops_within_seconds_writes_what_is_graded_and_leaves_nothing(tmp_path):
    course_9.write_course(tmp_path / "course")
    submissions = tmp_path / "submissions"
    slow = {**course_9.RIGHT, "9.3": "import time\ntime.sleep(60)\nfaster_ex3 = True"}
    course_9.returned(submissions, "a_quick.ipynb", course_9.RIGHT)
    for name in ("b_slow", "c_slow", "d_slow"):
        course_9.returned(submissions, f"{name}.ipynb", slow)
    script = (
        "import sys, pathlib\n"
        f"sys.path[:0] = [{str(ROOT)!r}, {str(ROOT / 'tools')!r}, {str(ROOT / 'tests')!r}]\n"
        "if __name__ == '__main__':  # the grader's workers import this file: not the grader\n"
        "    import grade, grade_release, _grading_course as c\n"
        f"    course = grade_release.Course.read(pathlib.Path({str(tmp_path / 'course')!r}), c.REFERENCES)\n"
        f"    grade.grade_folder({str(submissions)!r}, {str(tmp_path / 'out' / 'grades.csv')!r}, jobs=1, unsafe={UNSAFE}, course=course)\n"
    )
    (tmp_path / "run.py").write_text(script, encoding="utf-8")
    # the grader's scratch folder is made here (a short path: the kernels' sockets are in it),
    # so that what this run leaves is told apart from other runs'
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="twolink-test-"))
    kernels = f"ipykernel_launcher.*{scratch}"
    process = subprocess.Popen(
        [sys.executable, str(tmp_path / "run.py")],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
        env={**os.environ, "TMPDIR": str(scratch)},
    )
    try:
        for (
            line
        ) in process.stdout:  # wait for the first graded notebook, then press Ctrl-C
            if line.startswith("a_quick.ipynb:"):
                break
        if UNSAFE:  # its kernels' command lines name no folder of this run's
            time.sleep(3)
        else:
            deadline = time.monotonic() + 60
            while not running(kernels) and time.monotonic() < deadline:
                time.sleep(0.1)  # the slow one's kernel starts
            assert running(kernels), "the second notebook's kernel never started"
        os.killpg(
            process.pid, signal.SIGINT
        )  # the terminal sends it to the whole group
        pressed = time.monotonic()
        output, _ = process.communicate(timeout=60)
        seconds = time.monotonic() - pressed
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    left = sorted(scratch.iterdir())
    shutil.rmtree(scratch, ignore_errors=True)
    assert process.returncode == 130, output
    assert seconds < 20, f"{seconds:.0f} s after Ctrl-C"
    assert "stopped (Ctrl-C): 1 of 4 notebooks graded" in output
    with (tmp_path / "out" / "grades.csv").open(encoding="utf-8") as handle:
        assert {row["student file"] for row in csv.DictReader(handle)} == {
            "a_quick.ipynb"
        }
    assert (tmp_path / "out" / "feedback" / "a_quick.md").exists()
    assert left == [], "a temporary folder was left"
    # a sandboxed kernel ends when the worker that started it is killed (bubblewrap's
    # --die-with-parent): a moment after the grader has exited, within the same 20 s
    while running(kernels) and time.monotonic() < pressed + 20:
        time.sleep(0.1)
    assert not running(kernels), "a kernel outlived Ctrl-C by 20 s"


def running(pattern):
    """The command lines of running processes that match ``pattern`` (``pgrep -f``)."""
    found = subprocess.run(
        ["pgrep", "-a", "-f", pattern], capture_output=True, text=True, timeout=30
    )
    return found.stdout.strip()


def test_the_grader_s_temporary_folders_are_its_own():
    setting_scratch = grade.make_scratch()
    try:
        assert (setting_scratch.stat().st_mode & 0o777) == 0o700
    finally:
        setting_scratch.rmdir()


def test_how_each_part_is_graded_is_printed_for_the_teacher(tmp_path):
    course_9.write_course(tmp_path)
    table = grade.how_graded(grade_release.Course.read(tmp_path, course_9.REFERENCES))
    assert table.splitlines()[:2] == [
        "| exercise | part | graded on |",
        "|---|---|---|",
    ]
    assert (
        "| 9.1 | reach_ex1 | the exercise's inputs and 3 hidden draws of them |"
        in table
    )
    assert (
        "| 9.2 | tip | its visible calls and 20 hidden ones, with arm.fk, kinematics.fk unavailable |"
        in table
    )
    assert (
        "| 9.3 | faster_ex3 | the exercise's inputs only (no inputs cell to re-run) |"
        in table
    )
