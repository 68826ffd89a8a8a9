"""The course as the grader knows it, and a returned notebook's exercise cells found by what they are.

:class:`Course` holds the released chapters (from the instructor's notebooks)
and the references (the repository's ``answers`` package, or any object with
its functions: a test's small course).  For each exercise a chapter keeps the
released check cell and inputs cell; :func:`locate` finds an exercise's cells
in a returned notebook by nbgrader's ``grade_id`` (``check_1_2``,
``solution_1_2``, ``inputs_1_2``) and, where a notebook lost its metadata
(an id-less save, a copy and paste), by content: the check cell by its
``selfcheck.check("1.2", ...)`` call, the inputs cell by its first line
``# Inputs of exercise 1.2``, the answer cell as the nearest code cell before
the check (after the inputs cell) that assigns one of the exercise's answers
(the last such cell where the check was deleted).  Cell ids are never
used: Colab, JupyterLab 3 and VS Code drop or renumber them.

:func:`match_chapter` tells which chapter a notebook is: the chapter whose
exercises its check cells and ``grade_id`` s name, else the one it shares
most cells with; the file name only breaks a tie.
"""

from __future__ import annotations

import ast
import dataclasses
import json
import pathlib
import re
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import course_map  # tools/course_map.py
import editions  # tools/editions.py
import grade_read  # tools/grade_read.py
from grade_read import Cell, Returned
from nbgrader_cells import INPUTS_LINE, check_call

from twolink_course.exercises.spec import ExerciseSpec


def check_number(cell: Cell) -> str | None:
    """The exercise a code cell checks (``"2.1"``), or None if it is no check cell as the chapters write them.

    >>> check_number(Cell("code", 'correct_ex1 = selfcheck.check("2.1", q)'))
    '2.1'
    >>> check_number(Cell("code", 'print("selfcheck.check")')) is None
    True
    """
    if cell.kind != "code" or "selfcheck.check" not in cell.source:
        return None
    try:
        return check_call(cell.source)[0]
    except (ValueError, SyntaxError):
        return None


def inputs_number(cell: Cell) -> str | None:
    """The exercise whose inputs a code cell binds (its first line ``# Inputs of exercise N.M``), or None.

    >>> inputs_number(Cell("code", "# Inputs of exercise 4.1\\narm_ex1 = arms.two_metre"))
    '4.1'
    """
    if cell.kind != "code":
        return None
    match = INPUTS_LINE.match(cell.source.split("\n", 1)[0])
    return match["number"] if match else None


def assigned(source: str) -> set[str]:
    """The names a cell binds at its top level (nothing for a cell that does not parse).

    >>> sorted(assigned("a = 1\\nb, c = f()\\ndef g(): pass\\nd += 1"))
    ['a', 'b', 'c', 'd', 'g']
    """
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return set()
    return set(editions.assigned_names(ast.unparse(tree)))


@dataclasses.dataclass(frozen=True)
class Released:
    """An exercise's released cells: the check cell's source and the inputs cell's (or None)."""

    number: str
    check: str
    inputs: str | None


@dataclasses.dataclass(frozen=True)
class Chapter:
    """A released chapter: its exercises, their cells, and every code cell of its two editions."""

    stem: str
    exercises: tuple[ExerciseSpec, ...]
    released: Mapping[str, Released]
    sources: frozenset[str]
    digest: str

    @property
    def numbers(self) -> list[str]:
        """Its exercises' numbers, in order."""
        return [exercise.number for exercise in self.exercises]


def read_chapter(
    path: pathlib.Path, exercises: Sequence[ExerciseSpec]
) -> Chapter | None:
    """The released chapter at ``path`` (None: it has no exercise of ``exercises``)."""
    data = json.loads(path.read_text(encoding="utf-8"))
    cells = list(grade_read.parse(json.dumps(data)).cells)
    specs = tuple(e for e in exercises if e.chapter == path.stem)
    if not specs:
        return None
    released = {}
    for exercise in specs:
        checks = [c for c in cells if check_number(c) == exercise.number]
        if not checks:
            raise ValueError(
                f"{path.name}: exercise {exercise.number} has no check cell"
            )
        inputs = [c.source for c in cells if inputs_number(c) == exercise.number]
        released[exercise.number] = Released(
            exercise.number,
            editions.strip_hidden_tests(checks[0].source),
            inputs[0] if inputs else None,
        )
    student = editions.student_notebook(data)
    sources = {c.source for c in cells if c.kind == "code" and c.source.strip()}
    sources |= {
        "".join(c["source"]) if isinstance(c["source"], list) else c["source"]
        for c in student["cells"]
        if c["cell_type"] == "code"
    }
    return Chapter(
        path.stem, specs, released, frozenset(sources), editions.exercise_digest(data)
    )


@dataclasses.dataclass(frozen=True)
class Course:
    """The released chapters and the references the grader judges with.

    ``references``: the repository's ``answers`` package or an object with its
    functions ``all_exercises()``, ``rerun_specs()``, ``hidden_cases(number,
    part, seed, count)`` and ``hidden_draws(rerun, number, seed, count)``, and
    optionally ``on_paper()`` (the value parts of re-run exercises that are
    worked on paper: judged on the notebook's values only).
    """

    chapters: Mapping[str, Chapter]
    exercises: list[ExerciseSpec]
    reruns: Mapping[str, Any]
    hidden_cases: Callable[..., Any]
    hidden_draws: Callable[..., Any]
    on_paper: frozenset[tuple[str, str]] = frozenset()

    @classmethod
    def read(cls, folder: pathlib.Path, references: Any) -> Course:
        """The chapters of ``folder`` (``NN_*.ipynb``) with the exercises of ``references``."""
        exercises = references.all_exercises()
        chapters = {}
        for path in course_map.chapters(folder):
            chapter = read_chapter(path, exercises)
            if chapter is not None:
                chapters[chapter.stem] = chapter
        reruns = references.rerun_specs()
        for number in reruns:
            owner = next((c for c in chapters.values() if number in c.released), None)
            if owner is None or owner.released[number].inputs is None:
                raise ValueError(
                    f"exercise {number} is graded on hidden inputs (RERUN) but its chapter "
                    "has no inputs cell (# Inputs of exercise ...) to re-run its answer cell on"
                )
        return cls(
            chapters,
            exercises,
            reruns,
            references.hidden_cases,
            references.hidden_draws,
            frozenset(getattr(references, "on_paper", frozenset)()),
        )


# ------------------------------------------------------------------ a returned notebook


@dataclasses.dataclass(frozen=True)
class Where:
    """Where an exercise's cells are in a returned notebook (indices of its cells, or None)."""

    check: int | None
    solution: int | None
    inputs: int | None


_GRADE_ID = re.compile(r"^(?P<kind>check|solution|inputs)_(?P<number>\d+_\d+)$")


def _by_grade_id(cells: Sequence[Cell]) -> dict[tuple[str, str], int]:
    found: dict[tuple[str, str], int] = {}
    for index, cell in enumerate(cells):
        match = _GRADE_ID.match(cell.grade_id or "")
        if match and cell.kind == "code":
            key = (match["kind"], match["number"].replace("_", "."))
            found.setdefault(key, index)
    return found


def locate(cells: Sequence[Cell], exercise: ExerciseSpec) -> Where:
    """Where ``exercise``'s check, answer and inputs cells are in ``cells``."""
    ids = _by_grade_id(cells)
    number = exercise.number
    check = ids.get(("check", number))
    if check is None:
        check = next(
            (i for i, c in enumerate(cells) if check_number(c) == number), None
        )
    inputs = ids.get(("inputs", number))
    if inputs is None:
        inputs = next(
            (i for i, c in enumerate(cells) if inputs_number(c) == number), None
        )
    solution = ids.get(("solution", number))
    if solution is None:
        names = {part.name for part in exercise.parts}
        first = (
            inputs + 1
            if inputs is not None and (check is None or inputs < check)
            else 0
        )
        last = check - 1 if check is not None else len(cells) - 1
        solution = next(
            (
                i
                for i in range(last, first - 1, -1)
                if cells[i].kind == "code"
                and check_number(cells[i]) is None
                and inputs_number(cells[i]) is None
                and assigned(cells[i].source) & names
            ),
            None,
        )
    return Where(check, solution, inputs)


def match_chapter(
    returned: Returned, name: str, chapters: Mapping[str, Chapter]
) -> Chapter | None:
    """The chapter ``returned`` is: the one its exercises' cells name, else the one it
    shares most code cells with; the file name breaks a tie.  None: no cell of any chapter."""
    named: dict[str, int] = {}
    for cell in returned.cells:
        numbers = {check_number(cell), inputs_number(cell)}
        match = _GRADE_ID.match(cell.grade_id or "")
        if match:
            numbers.add(match["number"].replace("_", "."))
        for chapter in chapters.values():
            if numbers & set(chapter.numbers):
                named[chapter.stem] = named.get(chapter.stem, 0) + 1

    def score(chapter: Chapter) -> tuple[int, int, bool]:
        shared = sum(1 for cell in returned.cells if cell.source in chapter.sources)
        return (
            named.get(chapter.stem, 0),
            shared,
            pathlib.Path(name).name.startswith(chapter.stem[:3]),
        )

    best = max(chapters.values(), key=score, default=None)
    if best is None or score(best)[:2] == (0, 0):
        return None
    return best
