"""The chapters with nbgrader: cell metadata, and real nbgrader scoring as ``make grade`` does.

``tools/nbgrader_cells.py`` marks each solution cell as nbgrader's autograded
answer and each check cell as locked autograder tests worth one point per part,
ending with a hidden-test line whose value (``CheckReport.score``) nbgrader takes
as partial credit.  The quick tests check that every chapter is marked and that
the tool does what it says; the infrastructure test runs ``nbgrader
generate_assignment`` and ``nbgrader autograde`` on a throwaway course of one
chapter and compares nbgrader's points with the ``passed`` rows of
``tools/grade.py`` for the same submissions, part by part.
"""

import copy
import csv
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys

import nbformat
import pytest

from twolink_course import exercises

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import nbgrader_cells  # noqa: E402

CHAPTERS = nbgrader_cells.chapters()


# ------------------------------------------------------------------ the chapters are marked


@pytest.mark.parametrize("path", CHAPTERS, ids=[path.name for path in CHAPTERS])
def test_every_chapter_carries_the_metadata_the_tool_writes(path):
    notebook = nbformat.read(path, as_version=nbformat.NO_CONVERT)
    marked = nbgrader_cells.with_nbgrader_cells(notebook, path.name)
    assert nbgrader_cells.differences(notebook, marked) == [], (
        f"{path.name}: run `python tools/nbgrader_cells.py`, then `make notebooks`"
    )
    graded = {
        cell.metadata.nbgrader["grade_id"]: cell.metadata.nbgrader.get("points")
        for cell in notebook.cells
        if "nbgrader" in cell.metadata
    }
    chapter = [e for e in exercises.all_exercises() if e.chapter == path.stem]
    assert chapter, path.name
    assert graded == {
        **{f"check_{e.number.replace('.', '_')}": len(e.parts) for e in chapter},
        **{f"solution_{e.number.replace('.', '_')}": None for e in chapter},
    }


@pytest.mark.parametrize("path", CHAPTERS, ids=[path.name for path in CHAPTERS])
def test_nbgrader_accepts_every_chapter(path):
    # nbgrader's own check of its metadata (requirements.txt installs nbgrader)
    nbgraderformat = pytest.importorskip("nbgrader.nbgraderformat")
    notebook = nbformat.read(path, as_version=nbformat.NO_CONVERT)
    nbgraderformat.MetadataValidator().validate_nb(notebook)
    # and a chapter whose check cell lost its points is refused: the check can fail
    check = next(cell for cell in notebook.cells if nbgrader_cells.is_check_cell(cell))
    del check.metadata.nbgrader["points"]
    with pytest.raises(nbgraderformat.ValidationError, match="does not have points"):
        nbgraderformat.MetadataValidator().validate_nb(notebook)


def test_the_check_mode_exits_1_and_says_what_differs(tmp_path, capsys):
    copy_path = tmp_path / CHAPTERS[0].name
    notebook = nbformat.read(CHAPTERS[0], as_version=nbformat.NO_CONVERT)
    check = next(cell for cell in notebook.cells if nbgrader_cells.is_check_cell(cell))
    number, report = nbgrader_cells.check_call(check.source)
    check.metadata.nbgrader["points"] = 99
    check.source = nbgrader_cells.strip_hidden_tests(check.source)
    nbformat.write(notebook, copy_path)
    assert nbgrader_cells.main(["--check", str(copy_path)]) == 1
    said = capsys.readouterr().out
    assert f"{copy_path}: not marked for nbgrader" in said
    assert "'points': 99" in said and f"{report}.score" in said
    before = copy_path.read_bytes()
    assert nbgrader_cells.main([str(copy_path)]) == 0  # writes
    assert copy_path.read_bytes() == CHAPTERS[0].read_bytes()
    assert copy_path.read_bytes() != before
    assert nbgrader_cells.main([str(copy_path)]) == 0  # idempotent: nothing to write
    assert copy_path.read_bytes() == CHAPTERS[0].read_bytes()
    capsys.readouterr()
    assert nbgrader_cells.main(["--check", str(copy_path)]) == 0
    assert capsys.readouterr().out == ""


def _exercise(
    check_source, solution="### BEGIN SOLUTION\np_tip_ex1 = 1\n### END SOLUTION"
):
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [
        nbformat.v4.new_markdown_cell("# Exercise", metadata={"nbgrader": {}}),
        nbformat.v4.new_code_cell(solution, metadata={"tags": ["keep"]}),
        nbformat.v4.new_code_cell(check_source),
    ]
    return notebook


def test_the_tool_keeps_other_metadata_and_marks_one_point_a_part():
    notebook = _exercise('correct_ex1 = selfcheck.check("1.1", p_tip_ex1)')
    marked = nbgrader_cells.with_nbgrader_cells(notebook)
    markdown, solution, check = marked.cells
    assert "nbgrader" not in markdown.metadata  # stale: not an exercise cell
    assert solution.metadata == {
        "tags": ["keep"],
        "nbgrader": nbgrader_cells.solution_metadata("1.1"),
    }
    assert solution.metadata.nbgrader["grade_id"] == "solution_1_1"
    assert check.metadata.nbgrader["points"] == len(exercises.get("1.1").parts)
    assert check.source.splitlines() == [
        'correct_ex1 = selfcheck.check("1.1", p_tip_ex1)',
        "### BEGIN HIDDEN TESTS",
        "correct_ex1.score  # nbgrader's partial credit: the parts right",
        "### END HIDDEN TESTS",
    ]
    assert notebook.cells[2].source.count("\n") == 0  # the original is untouched


@pytest.mark.parametrize(
    "check, solution, message",
    [
        (
            'selfcheck.check("1.1", p_tip_ex1);',
            None,
            "cell 2: a check cell must be one assignment",
        ),
        (
            'r = selfcheck.check("1.1", p_tip_ex1)',
            "p_tip_ex1 = 1",
            "follows no solution",
        ),
        (
            "x = 1",
            None,
            "cell 1: a solution cell without a check cell after it",
        ),
    ],
    ids=["bare expression", "no solution before", "no check after"],
)
def test_the_tool_refuses_an_exercise_it_cannot_mark(check, solution, message):
    notebook = _exercise(check, *([solution] if solution else []))
    with pytest.raises(ValueError, match=message):
        nbgrader_cells.with_nbgrader_cells(notebook)


def test_nbstripout_keeps_the_nbgrader_metadata(tmp_path):
    path = tmp_path / "exercise.ipynb"
    marked = nbgrader_cells.with_nbgrader_cells(
        _exercise('correct_ex1 = selfcheck.check("1.1", p_tip_ex1)')
    )
    nbformat.write(marked, path)
    subprocess.run(
        [
            sys.executable,
            "-m",
            "nbstripout",
            "--keep-output",
            "--keep-count",
            str(path),
        ],
        check=True,
        timeout=60,
    )
    stripped = nbformat.read(path, as_version=4)
    assert [cell.metadata.get("nbgrader") for cell in stripped.cells] == [
        cell.metadata.get("nbgrader") for cell in marked.cells
    ]


# ------------------------------------------------------------------ real nbgrader, beside make grade

#: The quickest chapter to run (about 6 s here): one proves the agreement, part by part.
COURSE_CHAPTERS = ["01_dh_forward_kinematics"]
#: The one student solves every exercise but two: this one is left as released (its stub),
UNSOLVED_EXERCISE = "1.1"
#: and this one has one part wrong (its last answer doubled): full, none and all-but-one
#: points, each compared with make grade's, from one submission.
MIXED_EXERCISE = "1.3"
STUDENTS = ("mixed",)
BIN = pathlib.Path(sys.executable).parent
#: Seconds one nbgrader or grader command may take (each is killed after that).
COMMAND_BUDGET = 600


def start(command, cwd, timeout=COMMAND_BUDGET, **variables):
    """Start ``command`` in a process group of its own; :func:`finish` waits for it (``timeout`` s at most)."""
    env = {key: value for key, value in os.environ.items() if key != "MPLBACKEND"}
    env.update(variables)
    env["PATH"] = f"{BIN}{os.pathsep}{env.get('PATH', '')}"  # nbgrader runs `alembic`
    process = subprocess.Popen(
        command,
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    return process, timeout


def stop(started):
    """Kill a :func:`start`-ed command's process group (the kernels it started included)."""
    try:
        os.killpg(started[0].pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def finish(started):
    """Wait for a :func:`start`-ed command, then :func:`stop` it; its output."""
    process, timeout = started
    try:
        output, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        stop(started)
        output, _ = process.communicate()
        pytest.fail(f"{process.args} ran longer than {timeout} s:\n{output[-3000:]}")
    finally:
        stop(started)  # kernels it left behind
    assert process.returncode == 0, f"{process.args} failed:\n{output[-3000:]}"
    return output


def submitted(release, source, student):
    """A student's copy of a released notebook: ``mixed`` (see ``UNSOLVED_EXERCISE``)."""
    notebook = copy.deepcopy(release)
    instructor = {cell.id: cell.source for cell in source.cells}
    mixed = nbgrader_cells.grade_id("solution", MIXED_EXERCISE)
    unsolved = nbgrader_cells.grade_id("solution", UNSOLVED_EXERCISE)
    for cell in notebook.cells:
        meta = cell.metadata.get("nbgrader", {})
        if meta.get("solution") and meta["grade_id"] != unsolved:
            cell.source = instructor[cell.id]
            if student == "mixed" and meta["grade_id"] == mixed:
                name = exercises.get(MIXED_EXERCISE).parts[-1].name
                cell.source += f"\n{name} = 2 * {name}  # one answer wrong\n"
    return notebook


def nbgrader_points(course):
    """``{(student, chapter, exercise): (score, max_score)}`` from nbgrader's gradebook."""
    from nbgrader.api import Gradebook

    points = {}
    with Gradebook(f"sqlite:///{course / 'gradebook.db'}") as gradebook:
        for student in STUDENTS:
            for chapter in COURSE_CHAPTERS:
                notebook = gradebook.find_submission_notebook(chapter, "ps1", student)
                for grade in notebook.grades:
                    number = grade.name.removeprefix("check_").replace("_", ".")
                    points[student, chapter, number] = (grade.score, grade.max_score)
    return points


def grader_results(grades):
    """``{(student, chapter, exercise): [result of each part]}`` from ``tools/grade.py``'s CSV."""
    results = {}
    with grades.open(newline="", encoding="utf-8") as file:
        for row in csv.DictReader(file):
            student, name = pathlib.PurePath(row["student file"]).parts[-2:]
            key = student, pathlib.PurePath(name).stem, row["exercise"]
            results.setdefault(key, []).append(row["result"])
    return results


@pytest.mark.infrastructure
def test_nbgrader_scores_each_exercise_as_make_grade_does(tmp_path):
    pytest.importorskip("nbgrader")
    course = tmp_path / "course"
    (course / "source" / "ps1").mkdir(parents=True)
    for chapter in COURSE_CHAPTERS:
        shutil.copy(ROOT / "notebooks" / f"{chapter}.ipynb", course / "source" / "ps1")
    (course / "nbgrader_config.py").write_text(
        "c = get_config()\n"
        'c.CourseDirectory.course_id = "twolink"\n'
        "c.Execute.timeout = 300  # seconds per cell; nbgrader's default is 30\n",
        encoding="utf-8",
    )
    nbgrader = [sys.executable, "-m", "nbgrader"]
    finish(start([*nbgrader, "generate_assignment", "ps1"], course))

    returned = tmp_path / "returned"  # the same submissions, for tools/grade.py alone
    for chapter in COURSE_CHAPTERS:
        release = nbformat.read(course / "release" / "ps1" / f"{chapter}.ipynb", 4)
        source = nbformat.read(course / "source" / "ps1" / f"{chapter}.ipynb", 4)
        assert "HIDDEN TESTS" not in json.dumps(release) and "BEGIN SOLUTION" not in (
            json.dumps(release)
        )
        for student in STUDENTS:
            notebook = submitted(release, source, student)
            for folder in (course / "submitted" / student / "ps1", returned / student):
                folder.mkdir(parents=True, exist_ok=True)
                nbformat.write(notebook, folder / f"{chapter}.ipynb")

    grade = [sys.executable, str(ROOT / "tools" / "grade.py"), str(returned)]
    grade += ["--out", str(tmp_path / "grades" / "grades.csv")]
    (tmp_path / "grades").mkdir()
    helped = subprocess.run(
        [*grade[:2], "--help"], capture_output=True, text=True, timeout=60
    )
    if "--unsafe" in helped.stdout and shutil.which("bwrap") is None:
        grade.append("--unsafe")
    grading = start(grade, ROOT)  # both graders at once: one core each
    # the package's grading switch, as make grade sets it: heavy displays skipped
    autograde = start([*nbgrader, "autograde", "ps1"], course, TWOLINK_GRADING="1")
    try:
        finish(autograde)
    except BaseException:
        stop(grading)
        raise
    finish(grading)

    points = nbgrader_points(course)
    results = grader_results(tmp_path / "grades" / "grades.csv")
    numbers = {
        e.number: len(e.parts)
        for e in exercises.all_exercises()
        if e.chapter in COURSE_CHAPTERS
    }
    for student in STUDENTS:
        for (who, chapter, number), (score, most) in points.items():
            if who != student:
                continue
            assert most == numbers[number], (chapter, number)
            expected = {UNSOLVED_EXERCISE: 0, MIXED_EXERCISE: most - 1}.get(
                number, most
            )
            assert score == expected, (student, number, score)
            graded = results.get((student, chapter, number), [])
            assert len(graded) == most and graded.count("passed") == score, (
                f"{student} {number}: nbgrader {score} points, make grade {graded}"
            )
    covered = {(who, number) for who, _, number in points}
    assert covered == {(s, n) for s in STUDENTS for n in numbers}
    assert {UNSOLVED_EXERCISE, MIXED_EXERCISE} < set(
        numbers
    )  # and a solved one besides
