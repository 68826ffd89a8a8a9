"""The chapters with nbgrader: cell metadata, the course the README's recipe writes, and nbgrader's whole workflow.

``tools/nbgrader_cells.py`` marks each solution cell as nbgrader's autograded
answer, each inputs cell as locked and not graded, and each check cell as
locked autograder tests worth one point per part.  The quick tests check that
every chapter is marked and that the tool does what it says; the
infrastructure test follows the README's recipe: ``nbgrader_cells.py
--course`` writes the course (the grading switch in its configuration),
then ``nbgrader generate_assignment``, ``autograde``, ``generate_feedback``
and ``export`` run on one student's copy of chapter 1 (one exercise left
as released, one with a part wrong, the others solved), and nbgrader's points
are compared with ``tools/grade.py``'s for the same file, part by part; the
release shows no instructor text and autograde warns of no changed checksum.
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
import threading

import nbformat
import pytest

from twolink_course import exercises

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import grade  # noqa: E402
import nbgrader_cells  # noqa: E402

import answers  # noqa: E402

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
    rerun = (
        answers.rerun_specs()
    )  # graded on hidden inputs: an inputs cell, locked, no points
    assert graded == {
        **{f"check_{e.number.replace('.', '_')}": len(e.parts) for e in chapter},
        **{f"solution_{e.number.replace('.', '_')}": None for e in chapter},
        **{
            f"inputs_{e.number.replace('.', '_')}": None
            for e in chapter
            if e.number in rerun
        },
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


# ------------------------------------------------------------------ inputs cells, and the course for nbgrader

INPUTS = "# Inputs of exercise 1.1\nq_ex1 = np.radians([45.0, -30.0])"


def test_an_inputs_cell_is_marked_locked_and_not_graded():
    notebook = _exercise('correct_ex1 = selfcheck.check("1.1", p_tip_ex1)')
    notebook.cells.insert(1, nbformat.v4.new_code_cell(INPUTS))
    marked = nbgrader_cells.with_nbgrader_cells(notebook)
    assert marked.cells[1].metadata.nbgrader == nbgrader_cells.inputs_metadata("1.1")
    assert (
        marked.cells[1].metadata.nbgrader["locked"]
        and not marked.cells[1].metadata.nbgrader["grade"]
    )
    nbgraderformat = pytest.importorskip("nbgrader.nbgraderformat")
    nbgraderformat.MetadataValidator().validate_nb(marked)


def test_an_inputs_cell_away_from_its_solution_cell_is_refused():
    notebook = _exercise('correct_ex1 = selfcheck.check("1.1", p_tip_ex1)')
    notebook.cells.insert(1, nbformat.v4.new_code_cell(INPUTS))
    notebook.cells.insert(2, nbformat.v4.new_code_cell("x = 1"))
    with pytest.raises(
        ValueError,
        match="cell 1: the inputs cell of exercise 1.1 must come right before its solution cell .cell 3.",
    ):
        nbgrader_cells.with_nbgrader_cells(notebook)
    lonely = _exercise('correct_ex1 = selfcheck.check("1.1", p_tip_ex1)')
    lonely.cells.append(nbformat.v4.new_code_cell(INPUTS.replace("1.1", "1.2")))
    with pytest.raises(
        ValueError, match="the inputs cell of exercise 1.2 has no check"
    ):
        nbgrader_cells.with_nbgrader_cells(lonely)


@pytest.fixture(scope="module")
def course_source(tmp_path_factory):
    folder = tmp_path_factory.mktemp("course")
    written = nbgrader_cells.write_course(CHAPTERS[:1], folder)
    return folder, nbformat.read(written[0], as_version=4)


def test_the_course_for_nbgrader_has_the_student_edition_s_stubs_and_text(
    course_source,
):
    folder, notebook = course_source
    text = json.dumps(notebook)
    assert (
        "BEGIN INSTRUCTOR" not in text
        and "Each exercise cell holds a worked solution" not in text
    )
    solution = next(
        cell
        for cell in notebook.cells
        if cell.metadata.get("nbgrader", {}).get("solution")
    )
    stub, _, block = solution.source.partition("### BEGIN SOLUTION")
    assert (
        stub.rstrip().endswith("p_tip_ex1 = ...  # your code here")
        and "### END SOLUTION" in block
    )
    assert all(
        not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"
    )
    config = (folder / "nbgrader_config.py").read_text(encoding="utf-8")
    assert (
        'os.environ["TWOLINK_GRADING"] = "1"' in config
        and 'code_stub = {"python": ""}' in config
    )


def test_no_locked_cell_of_the_course_changes_between_source_and_release(course_source):
    """What made nbgrader warn "checksum has changed" for every check cell: hidden tests in a locked cell."""
    utils = pytest.importorskip("nbgrader.utils")
    _, notebook = course_source
    locked = [
        cell
        for cell in notebook.cells
        if cell.metadata.get("nbgrader", {}).get("locked")
    ]
    assert locked
    for cell in locked:
        released = copy.deepcopy(cell)
        released.source = nbgrader_cells.strip_hidden_tests(cell.source)
        assert utils.compute_checksum(released) == utils.compute_checksum(cell)
    # the chapters as they are (hidden tests in their check cells) would warn: the check can fail
    chapter = nbformat.read(CHAPTERS[0], as_version=4)
    check = next(cell for cell in chapter.cells if nbgrader_cells.is_check_cell(cell))
    released = copy.deepcopy(check)
    released.source = nbgrader_cells.strip_hidden_tests(check.source)
    assert utils.compute_checksum(released) != utils.compute_checksum(check)


# ------------------------------------------------------------------ nbgrader's whole workflow, beside make grade

#: The quickest chapter to run: one proves the agreement, part by part.
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


def start(command, cwd, timeout=COMMAND_BUDGET):
    """Start ``command`` in a process group of its own; :func:`finish` waits for it (``timeout`` s at most)."""
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("MPLBACKEND", "TWOLINK_GRADING")
    }
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


def in_thread(function, *args):
    """Start ``function(*args)`` in a thread; :func:`joined` waits for it."""
    outcome = {}

    def run():
        try:
            outcome["value"] = function(*args)
        except BaseException as error:  # SystemExit too: a refusal of the grader's
            outcome["error"] = error

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread, outcome


def joined(started, timeout=COMMAND_BUDGET):
    """Wait for an :func:`in_thread` call (``timeout`` s at most); what it returned, or raise what it raised."""
    thread, outcome = started
    thread.join(timeout)
    if thread.is_alive():
        pytest.fail(f"make grade ran longer than {timeout} s")
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("value")


def submitted(release, source, student):
    """A student's copy of a released notebook: the worked solutions typed in but for ``UNSOLVED_EXERCISE``, ``MIXED_EXERCISE`` with its last answer wrong."""
    notebook = copy.deepcopy(release)
    instructor = {
        cell.metadata.nbgrader["grade_id"]: cell.source
        for cell in source.cells
        if "nbgrader" in cell.metadata
    }
    mixed = nbgrader_cells.grade_id("solution", MIXED_EXERCISE)
    unsolved = nbgrader_cells.grade_id("solution", UNSOLVED_EXERCISE)
    for cell in notebook.cells:
        meta = cell.metadata.get("nbgrader", {})
        if meta.get("solution") and meta["grade_id"] != unsolved:
            text = instructor[meta["grade_id"]]
            cell.source = text.replace("### BEGIN SOLUTION\n", "").replace(
                "### END SOLUTION", ""
            )
            if meta["grade_id"] == mixed:
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
            if row["exercise"] == "(none)":
                continue
            key = row["student id"], row["chapter"], row["exercise"]
            results.setdefault(key, []).append(row["result"])
    return results


@pytest.mark.infrastructure
def test_nbgrader_s_workflow_from_the_readme_recipe_scores_as_make_grade_does(tmp_path):
    pytest.importorskip("nbgrader")
    course = tmp_path / "course"
    nbgrader_cells.main(
        [
            "--course",
            str(course),
            *(str(ROOT / "notebooks" / f"{c}.ipynb") for c in COURSE_CHAPTERS),
        ]
    )
    nbgrader = [sys.executable, "-m", "nbgrader"]
    finish(start([*nbgrader, "generate_assignment", "ps1"], course))

    returned = tmp_path / "returned"  # the same submissions, for tools/grade.py alone
    for chapter in COURSE_CHAPTERS:
        release = nbformat.read(course / "release" / "ps1" / f"{chapter}.ipynb", 4)
        source = nbformat.read(course / "source" / "ps1" / f"{chapter}.ipynb", 4)
        text = json.dumps(release)
        assert (
            "HIDDEN TESTS" not in text
            and "BEGIN SOLUTION" not in text
            and "BEGIN INSTRUCTOR" not in text
        )
        assert "Each exercise cell holds a worked solution" not in text
        for student in STUDENTS:
            notebook = submitted(release, source, student)
            for folder in (course / "submitted" / student / "ps1", returned / student):
                folder.mkdir(parents=True, exist_ok=True)
                nbformat.write(notebook, folder / f"{chapter}.ipynb")

    # make grade's command line, run here (its imports are this process's) beside nbgrader
    grade_args = [str(returned), "--out", str(tmp_path / "grades" / "grades.csv")]
    if shutil.which("bwrap") is None:
        grade_args.append("--unsafe")
    grading = in_thread(grade.main, grade_args)  # both graders at once: one core each
    started = []
    try:
        autograde = start(
            [*nbgrader, "autograde", "ps1"], course
        )  # the switch: from the course's config
        started.append(autograde)
        autograded = finish(autograde)
        # both read the gradebook autograde wrote, while make grade may still run
        feedback = start([*nbgrader, "generate_feedback", "ps1"], course)
        started.append(feedback)
        export = start([*nbgrader, "export"], course)
        started.append(export)
        for command in (feedback, export):
            finish(command)
    finally:
        for command in started:
            stop(command)
        joined(grading)
    assert "checksum" not in autograded.lower(), [
        line for line in autograded.splitlines() if "checksum" in line.lower()
    ]

    points = nbgrader_points(course)
    results = grader_results(tmp_path / "grades" / "grades.csv")
    numbers = {
        e.number: len(e.parts)
        for e in exercises.all_exercises()
        if e.chapter in COURSE_CHAPTERS
    }
    for (student, chapter, number), (score, most) in points.items():
        assert most == numbers[number], (chapter, number)
        expected = {UNSOLVED_EXERCISE: 0, MIXED_EXERCISE: most - 1}.get(number, most)
        assert score == expected, (student, number, score)
        graded = results.get((student, chapter, number), [])
        assert len(graded) == most and graded.count("passed") == score, (
            f"{student} {number}: nbgrader {score} points, make grade {graded}"
        )
    assert {(who, number) for who, _, number in points} == {
        (s, n) for s in STUDENTS for n in numbers
    }
    assert {UNSOLVED_EXERCISE, MIXED_EXERCISE} < set(
        numbers
    )  # and a solved one besides
    # generate_feedback and export: a feedback page per notebook, nbgrader's columns, the same totals
    for student in STUDENTS:
        for chapter in COURSE_CHAPTERS:
            assert (course / "feedback" / student / "ps1" / f"{chapter}.html").exists()
    with (course / "grades.csv").open(encoding="utf-8") as handle:
        exported = {row["student_id"]: row for row in csv.DictReader(handle)}
    with (tmp_path / "grades" / "gradebook.csv").open(encoding="utf-8") as handle:
        ours = list(csv.DictReader(handle))
    assert list(ours[0]) == list(next(iter(exported.values())))  # the same columns
    for student in STUDENTS:
        total = sum(float(row["score"]) for row in ours if row["student_id"] == student)
        assert float(exported[student]["score"]) == total, student
