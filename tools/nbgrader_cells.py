"""Write nbgrader's cell metadata into the chapters, so a teacher can use them with nbgrader.

Each exercise is a solution cell (its worked solution between ``### BEGIN
SOLUTION`` and ``### END SOLUTION``) followed by a check cell
(``correct_ex1 = selfcheck.check("1.1", p_tip_ex1)``).  This tool marks

- each solution cell as nbgrader's *autograded answer*:
  ``{"grade": false, "solution": true, "locked": false, "grade_id": "solution_1_1", ...}``;
- each check cell as a *locked autograder test* worth one point per part of
  its exercise (``twolink_course.exercises.get("1.1").parts``):
  ``{"grade": true, "solution": false, "locked": true, "points": 1, "grade_id": "check_1_1", ...}``,

- each inputs cell (the cell before a solution cell whose first line is
  ``# Inputs of exercise 1.1``: the names the answer cell computes from) as a
  locked cell nbgrader does not grade:
  ``{"grade": false, "solution": false, "locked": true, "grade_id": "inputs_1_1", ...}``
  (nbgrader restores it from the instructor's copy before grading; so does
  ``make grade``, which re-runs the answer cell on other inputs),

and ends each check cell with a hidden-test block whose value is the number of
parts answered correctly (``CheckReport.score``)::

    correct_ex1 = selfcheck.check("1.1", p_tip_ex1)
    ### BEGIN HIDDEN TESTS
    correct_ex1.score  # nbgrader's partial credit: the parts right
    ### END HIDDEN TESTS

nbgrader scores a code grade cell by its outputs (``nbgrader.utils.determine_grade``):
an error or anything on stderr gives 0, an ``execute_result`` that reads as a
number gives that many points (partial credit, at most the cell's points), and
no result at all gives full points; the score line makes a half-solved exercise
worth its correct parts.  ``nbgrader generate_assignment`` removes the hidden-test
block from the release (so does the student edition, ``tools/editions.py``),
and ``nbgrader autograde`` restores the check cells, block included, from the
instructor's copy before running a submission.  Every other cell loses a stale
``nbgrader`` key; all other metadata is kept.

Usage: ``python tools/nbgrader_cells.py [--check] [NOTEBOOK ...]`` (default: every
chapter, ``notebooks/0*.ipynb`` except ``00_*``).  Without ``--check`` it
rewrites the notebooks that differ (running it twice changes nothing); with
``--check`` it writes nothing, prints what differs and exits with status 1 if
anything does.

``python tools/nbgrader_cells.py --course DIR [--assignment ps1] [NOTEBOOK ...]``
writes an nbgrader course for the chapters (:func:`write_course`):
``DIR/source/ps1/`` holds each chapter ready for ``nbgrader
generate_assignment``, its release what the student edition is (each answer a
``name = ...`` stub, the Markdown for students: no instructor passage), its
check cells without the hidden-test block (a check gives its score itself while
grading, so nbgrader sees no locked cell change: no "checksum has changed"
warning); ``DIR/nbgrader_config.py`` sets the course, the stubs, a time limit
per cell and the grading switch ``TWOLINK_GRADING=1`` for every kernel nbgrader
starts (:data:`CONFIG`).
"""

from __future__ import annotations

import argparse
import ast
import copy
import json
import pathlib
import re
import sys
from collections.abc import Callable, Sequence
from typing import Any

import nbformat

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))
import editions  # noqa: E402
from editions import BEGIN as BEGIN_SOLUTION  # noqa: E402
from editions import BEGIN_HIDDEN, END_HIDDEN, strip_hidden_tests  # noqa: E402

from twolink_course import exercises  # noqa: E402

SCORE_COMMENT = "# nbgrader's partial credit: the parts right"
#: nbgrader's cell metadata format (nbgrader.nbgraderformat.v3).
SCHEMA_VERSION = 3
#: The first line of an exercise's inputs cell.
INPUTS_LINE = re.compile(r"^# Inputs of exercise (?P<number>\d+\.\d+)[ \t]*$")


def is_solution_cell(cell: dict[str, Any]) -> bool:
    """A code cell holding a worked solution between the solution markers."""
    return cell["cell_type"] == "code" and BEGIN_SOLUTION in _text(cell)


def is_check_cell(cell: dict[str, Any]) -> bool:
    """A code cell that calls the self-checks."""
    return cell["cell_type"] == "code" and "selfcheck.check" in _text(cell)


def inputs_cell_number(cell: dict[str, Any]) -> str | None:
    """The exercise whose inputs a code cell binds (first line ``# Inputs of exercise N.M``), or None.

    >>> inputs_cell_number({"cell_type": "code", "source": "# Inputs of exercise 4.1\\nq_ex1 = 1"})
    '4.1'
    """
    if cell["cell_type"] != "code":
        return None
    match = INPUTS_LINE.match(_text(cell).split("\n", 1)[0])
    return match["number"] if match else None


def _text(cell: dict[str, Any]) -> str:
    source = cell["source"]
    return source if isinstance(source, str) else "".join(source)


def check_call(source: str) -> tuple[str, str]:
    """``(exercise number, report name)`` of a check cell's source (its hidden tests aside).

    >>> check_call('correct_ex2 = selfcheck.check("2.1", q_elbow_up, up_within_limits)')
    ('2.1', 'correct_ex2')
    >>> check_call('selfcheck.check("2.1", q_elbow_up);')
    Traceback (most recent call last):
    ...
    ValueError: a check cell must be one assignment `name = selfcheck.check("N.M", ...)` (nbgrader scores it by name.score), got:
    selfcheck.check("2.1", q_elbow_up);
    """
    code = strip_hidden_tests(source)
    body = ast.parse(code).body
    statement = body[0] if len(body) == 1 else None
    if (
        isinstance(statement, ast.Assign)
        and len(statement.targets) == 1
        and isinstance(statement.targets[0], ast.Name)
        and isinstance(statement.value, ast.Call)
        and ast.unparse(statement.value.func) == "selfcheck.check"
        and statement.value.args
        and isinstance(statement.value.args[0], ast.Constant)
        and isinstance(statement.value.args[0].value, str)
    ):
        return statement.value.args[0].value, statement.targets[0].id
    raise ValueError(
        "a check cell must be one assignment "
        '`name = selfcheck.check("N.M", ...)` (nbgrader scores it by name.score), '
        f"got:\n{code}"
    )


def hidden_tests(report: str) -> str:
    """The hidden-test block that ends a check cell whose report is bound to ``report``.

    >>> print(hidden_tests("correct_ex1"))
    ### BEGIN HIDDEN TESTS
    correct_ex1.score  # nbgrader's partial credit: the parts right
    ### END HIDDEN TESTS
    """
    return f"{BEGIN_HIDDEN}\n{report}.score  {SCORE_COMMENT}\n{END_HIDDEN}"


def grade_id(kind: str, number: str) -> str:
    """nbgrader's name of an exercise's cell: ``grade_id("check", "1.2")`` is ``'check_1_2'``.

    >>> grade_id("solution", "7.4")
    'solution_7_4'
    """
    return f"{kind}_{number.replace('.', '_')}"


def solution_metadata(number: str) -> dict[str, Any]:
    """nbgrader's metadata of exercise ``number``'s solution cell (an autograded answer)."""
    return {
        "grade": False,
        "grade_id": grade_id("solution", number),
        "locked": False,
        "schema_version": SCHEMA_VERSION,
        "solution": True,
        "task": False,
    }


def inputs_metadata(number: str) -> dict[str, Any]:
    """nbgrader's metadata of exercise ``number``'s inputs cell (locked, not graded)."""
    return {
        "grade": False,
        "grade_id": grade_id("inputs", number),
        "locked": True,
        "schema_version": SCHEMA_VERSION,
        "solution": False,
        "task": False,
    }


def check_metadata(number: str, points: int) -> dict[str, Any]:
    """nbgrader's metadata of exercise ``number``'s check cell (locked autograder tests, one point a part)."""
    return {
        "grade": True,
        "grade_id": grade_id("check", number),
        "locked": True,
        "points": points,
        "schema_version": SCHEMA_VERSION,
        "solution": False,
        "task": False,
    }


def _parts(number: str) -> int:
    return len(exercises.get(number).parts)


def with_nbgrader_cells(
    notebook: Any, name: str = "notebook", parts: Callable[[str], int] = _parts
) -> Any:
    """A copy of ``notebook`` (nbformat's node or a JSON dict) with nbgrader's metadata written.

    Each solution cell must be followed by its check cell before the next
    solution cell; a check cell without a solution cell before it, or a
    solution cell without a check, is an error naming the cell; an inputs
    cell must come right before its exercise's solution cell.  ``parts``:
    the number of parts of an exercise (its check's points), from the store
    by default.
    """
    marked = copy.deepcopy(notebook)
    pending: int | None = None  # the solution cell waiting for its check
    inputs: dict[str, int] = {}  # exercise -> its inputs cell
    for index, cell in enumerate(marked["cells"]):
        metadata = cell.setdefault("metadata", {})
        if (number := inputs_cell_number(cell)) is not None:
            inputs[number] = index
            metadata.pop("nbgrader", None)  # written when its check is found
        elif is_solution_cell(cell):
            if pending is not None:
                raise ValueError(
                    f"{name} cell {pending}: a solution cell without a check cell after it"
                )
            pending = index
            metadata.pop("nbgrader", None)  # written when its check is found
        elif is_check_cell(cell):
            try:
                number, report = check_call(_text(cell))
            except ValueError as error:
                raise ValueError(f"{name} cell {index}: {error}") from None
            if pending is None:
                raise ValueError(
                    f"{name} cell {index}: the check of exercise {number} follows no solution cell"
                )
            if number in inputs:
                if inputs[number] != pending - 1:
                    raise ValueError(
                        f"{name} cell {inputs[number]}: the inputs cell of exercise "
                        f"{number} must come right before its solution cell (cell {pending})"
                    )
                marked["cells"][inputs.pop(number)]["metadata"]["nbgrader"] = (
                    inputs_metadata(number)
                )
            points = parts(number)
            marked["cells"][pending]["metadata"]["nbgrader"] = solution_metadata(number)
            metadata["nbgrader"] = check_metadata(number, points)
            cell["source"] = (
                strip_hidden_tests(_text(cell)).rstrip("\n")
                + "\n"
                + hidden_tests(report)
            )
            pending = None
        else:
            metadata.pop("nbgrader", None)
    if pending is not None:
        raise ValueError(
            f"{name} cell {pending}: a solution cell without a check cell after it"
        )
    if inputs:
        number, index = next(iter(inputs.items()))
        raise ValueError(
            f"{name} cell {index}: the inputs cell of exercise {number} has no check "
            "of that exercise after it"
        )
    return marked


def differences(before: Any, after: Any) -> list[str]:
    """What :func:`with_nbgrader_cells` changed, one line per cell and field."""
    found = []
    for index, (old, new) in enumerate(zip(before["cells"], after["cells"])):
        old_meta = old.get("metadata", {}).get("nbgrader")
        new_meta = new.get("metadata", {}).get("nbgrader")
        if old_meta != new_meta:
            found.append(
                f"cell {index}: metadata nbgrader is {old_meta}, expected {new_meta}"
            )
        if _text(old) != _text(new):
            found.append(
                f"cell {index}: source should end with the hidden-test block:\n"
                + _text(new)
            )
    return found


def chapters() -> list[pathlib.Path]:
    """The chapters: ``notebooks/0*.ipynb`` except ``00_*`` files."""
    return [
        path
        for path in sorted((ROOT / "notebooks").glob("0*.ipynb"))
        if not path.name.startswith("00_")
    ]


#: The course's nbgrader configuration (``DIR/nbgrader_config.py``).
CONFIG = """\
# nbgrader's configuration of the twolink course (written by tools/nbgrader_cells.py --course).
import os

c = get_config()
c.CourseDirectory.course_id = "twolink"
# Each answer cell of the release ends with its `name = ...` stubs, as in the student edition:
# the solution region is replaced by nothing.
c.ClearSolutions.code_stub = {{"python": ""}}
# Seconds per cell; nbgrader's default, 30, is short for a chapter's slower cells.
c.Execute.timeout = {timeout}
# The grading switch of twolink_course.runmode: every kernel nbgrader starts inherits it, so
# the heavy displays no answer depends on are skipped and each check gives its score as the
# cell's result (nbgrader's partial credit).
os.environ["TWOLINK_GRADING"] = "1"
"""


def _with_stubs(source: str, checked: set[str] | None) -> str:
    """A solution cell's source with the student edition's stubs before each solution region."""
    return editions.SOLUTION_BLOCK.sub(
        lambda match: editions.stub_source(match[0], checked) + match[0], source
    )


def course_source(notebook: dict[str, Any], name: str = "notebook") -> dict[str, Any]:
    """A chapter (JSON data) ready for ``nbgrader generate_assignment``: nbgrader's metadata,
    student Markdown, stubs before each solution region, no hidden-test block, no outputs."""
    marked = with_nbgrader_cells(notebook, name)
    cells = marked["cells"]
    for index, cell in enumerate(cells):
        source = _text(cell)
        if cell["cell_type"] == "markdown":
            cell["source"] = editions.student_markdown(source)
            continue
        if cell["cell_type"] != "code":
            continue
        if is_check_cell(cell):
            source = strip_hidden_tests(source)
        if is_solution_cell(cell):
            source = _with_stubs(source, editions.next_selfcheck_names(cells, index))
        cell["source"] = source
        cell["outputs"] = []
        cell["execution_count"] = None
    return marked


def write_course(
    notebooks: Sequence[pathlib.Path],
    folder: pathlib.Path,
    assignment: str = "ps1",
    timeout: int = 300,
) -> list[pathlib.Path]:
    """An nbgrader course in ``folder``: ``source/ASSIGNMENT/`` with each chapter, and its config."""
    source = folder / "source" / assignment
    source.mkdir(parents=True, exist_ok=True)
    written = []
    for path in notebooks:
        notebook = json.loads(path.read_text(encoding="utf-8"))
        target = source / path.name
        target.write_text(
            json.dumps(course_source(notebook, path.name), indent=1, ensure_ascii=False)
            + "\n",
            encoding="utf-8",
        )
        written.append(target)
    config = folder / "nbgrader_config.py"
    config.write_text(CONFIG.format(timeout=timeout), encoding="utf-8")
    return [*written, config]


def main(argv: Sequence[str] | None = None) -> int:
    """Mark (or with ``--check``, check) the notebooks; the exit status: 1 when ``--check`` finds a difference."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument(
        "--check",
        action="store_true",
        help="write nothing; say what differs and exit 1 if anything does",
    )
    parser.add_argument(
        "--course",
        type=pathlib.Path,
        help="write an nbgrader course for the chapters into this folder instead",
    )
    parser.add_argument(
        "--assignment", default="ps1", help="the course's assignment (default ps1)"
    )
    parser.add_argument(
        "notebooks", nargs="*", type=pathlib.Path, help="default: every chapter"
    )
    args = parser.parse_args(argv)
    if args.course is not None:
        for path in write_course(
            args.notebooks or chapters(), args.course, args.assignment
        ):
            print(path)
        return 0
    stale = 0
    for path in args.notebooks or chapters():
        notebook = nbformat.read(path, as_version=nbformat.NO_CONVERT)
        marked = with_nbgrader_cells(notebook, path.name)
        found = differences(notebook, marked)
        if not found:
            continue
        stale += 1
        if args.check:
            print(f"{path}: not marked for nbgrader (run tools/nbgrader_cells.py):")
            for line in found:
                print("  " + line.replace("\n", "\n    "))
        else:
            nbformat.write(marked, path)
            print(f"{path}: {len(found)} changes")
    return 1 if args.check and stale else 0


if __name__ == "__main__":
    sys.exit(main())
