"""What the teacher hands on: the grades per part, a gradebook, totals, and a feedback file per student.

In the output folder (the CSV's):

- ``grades.csv``: one row per part of every returned notebook (student id,
  student file, chapter, exercise, part, result, points, message), and one
  row per notebook that stopped early, was refused or ran into a limit;
- ``gradebook.csv``: nbgrader's export columns (``assignment, duedate,
  timestamp, student_id, last_name, first_name, email, raw_score,
  late_submission_penalty, score, max_score``), one row per student and
  chapter, an assignment being a chapter, a chapter not returned scoring 0 as
  nbgrader's export gives it, so a learning platform takes it as it takes
  nbgrader's;
- ``points.csv``: per student, the points of each exercise, the total, the
  most possible, and the flags (a chapter returned twice, chapters missing,
  notebooks that failed to run);
- ``feedback/STUDENT.md``: per student, each part's verdict and what to look
  at, in words (never a hidden input), the notes on each notebook, and the
  flags.

A student is the first folder under the submissions folder
(``submitted/ada/ps1/01_dh.ipynb`` is ``ada``'s, as nbgrader and learning
platforms lay them out), else the file name without the chapter's name.
A chapter returned twice counts once: the file modified last.  Every text
that comes from a file name is escaped: a name that is not UTF-8 (Latin-1
"Müller" from a zip) as ``M\\xfcller``, control characters as escapes, a
cell a spreadsheet would read as a formula with a leading ``'``.
"""

from __future__ import annotations

import csv
import dataclasses
import datetime
import io
import os
import pathlib
import re
import tempfile
from collections.abc import Mapping, Sequence

from grade_verdicts import FAILED, PASSED, RESULTS, Verdict

#: What a spreadsheet reads as the start of a formula.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
GRADES_HEADER = [
    "student id",
    "student file",
    "chapter",
    "exercise",
    "part",
    "result",
    "points",
    "message",
]
#: nbgrader's ``export`` columns (nbgrader.plugins.export.CsvExportPlugin).
GRADEBOOK_HEADER = [
    "assignment",
    "duedate",
    "timestamp",
    "student_id",
    "last_name",
    "first_name",
    "email",
    "raw_score",
    "late_submission_penalty",
    "score",
    "max_score",
]


def text(name: str) -> str:
    r"""``name`` as text anyone can read and write: bytes that were not UTF-8 as ``\xNN``,
    control characters (a newline, an escape) as escapes.

    >>> print(text("M" + chr(0xDCFC) + "ller"), text("ada" + chr(10) + "bob"))
    M\xfcller ada\nbob
    """
    name = name.encode("utf-8", "surrogateescape").decode("utf-8", "backslashreplace")
    return "".join(
        character if character.isprintable() else repr(character)[1:-1]
        for character in name
    )


def csv_cell(value: str) -> str:
    """``value`` safe in a spreadsheet: a leading ``'`` when it would start a formula.

    >>> csv_cell("=SUM(A1)"), csv_cell("passed"), csv_cell("-1+2")
    ("'=SUM(A1)", 'passed', "'-1+2")
    """
    return "'" + value if value.startswith(FORMULA_STARTS) else value


@dataclasses.dataclass
class Graded:
    """One returned notebook graded: who, which chapter, each part's verdict, and what happened."""

    file: str  # relative to the submissions folder, escaped
    student: str
    chapter: str | None
    verdicts: list[Verdict]
    failure: str | None = None
    notes: list[str] = dataclasses.field(default_factory=list)
    limits: list[str] = dataclasses.field(default_factory=list)
    modified: float = 0.0
    cpu_seconds: float | None = None

    @property
    def points(self) -> int:
        return sum(verdict.points for verdict in self.verdicts)

    @property
    def refused(self) -> bool:
        return bool(self.failure and self.failure.startswith("refused:"))


def student_of(relative: pathlib.PurePath, stems: Sequence[str]) -> str:
    """The student a returned file belongs to: its first folder, else its name without the chapter's.

    >>> student_of(pathlib.PurePath("ada/ps1/01_dh.ipynb"), ["01_dh"])
    'ada'
    >>> student_of(pathlib.PurePath("bob_01_dh.ipynb"), ["01_dh"]), student_of(pathlib.PurePath("01_dh.ipynb"), ["01_dh"])
    ('bob', '01_dh')
    """
    if len(relative.parts) > 1:
        return text(relative.parts[0])
    stem = relative.stem
    for chapter in sorted(stems, key=len, reverse=True):
        stem = stem.replace(chapter, "")
    stem = re.sub(r"(?:(?<=^)|(?<=[_\-. ]))\d\d(?:[_\-. ]|$)", "", stem).strip("_-. ")
    return text(stem or relative.stem)


def summary_line(graded: Graded) -> str:
    """One line: the file, how many parts passed / not solved / wrong / ..., any failure and notes."""
    if graded.refused and graded.failure:
        return f"{graded.file}: REFUSED{graded.failure[7:]}"
    counts = {
        result: sum(1 for v in graded.verdicts if v.result == result)
        for result in RESULTS
    }
    line = f"{graded.file}: " + ", ".join(
        f"{count} {result}"
        for result, count in counts.items()
        if count or result in (PASSED, "not solved", "wrong")
    )
    if graded.failure:
        line += f"; FAILED TO RUN: {text(graded.failure)}"
    for note in [*graded.limits, *graded.notes]:
        line += f"; {text(note)}"
    return line


def _write(
    out: pathlib.Path, header: Sequence[str], rows: Sequence[Sequence[object]]
) -> None:
    """Write a whole CSV atomically: a temporary file in the same folder, renamed over ``out``."""
    buffer = io.StringIO(newline="")
    writer = csv.writer(buffer)
    writer.writerow(header)
    writer.writerows([csv_cell(text(str(cell))) for cell in row] for row in rows)
    descriptor, temporary = tempfile.mkstemp(
        dir=out.parent, prefix=f".{out.stem}-", suffix=".csv"
    )
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="") as handle:
            handle.write(buffer.getvalue())
        os.replace(temporary, out)
    except BaseException:
        pathlib.Path(temporary).unlink(missing_ok=True)
        raise


def grade_rows(graded: Graded) -> list[list[object]]:
    """The ``grades.csv`` rows of one notebook."""
    rows: list[list[object]] = [
        [
            graded.student,
            graded.file,
            graded.chapter or "",
            v.number,
            v.part,
            v.result,
            v.points,
            v.message,
        ]
        for v in graded.verdicts
    ]
    if graded.failure:
        result = graded.failure if graded.refused else f"{FAILED}: {graded.failure}"
        rows.append(
            [
                graded.student,
                graded.file,
                graded.chapter or "",
                "(none)",
                "(none)",
                result,
                0,
                "",
            ]
        )
    for limit in graded.limits:
        rows.append(
            [
                graded.student,
                graded.file,
                graded.chapter or "",
                "(none)",
                "(limit)",
                f"limit: {limit}",
                0,
                "",
            ]
        )
    return rows


def write_grades(out: pathlib.Path, notebooks: Sequence[Graded]) -> None:
    """``grades.csv``, rewritten whole after each notebook (an interrupted run keeps what it graded)."""
    _write(
        out, GRADES_HEADER, [row for graded in notebooks for row in grade_rows(graded)]
    )


@dataclasses.dataclass
class Student:
    """One student's chapters: the notebook that counts per chapter, and the flags."""

    name: str
    counted: dict[str, Graded]
    flags: list[str]


def students(notebooks: Sequence[Graded], chapters: Sequence[str]) -> list[Student]:
    """Each student's counted notebook per chapter (a chapter returned twice: the file modified
    last), with flags: returned twice, chapters missing (returned by others of the class), not a chapter."""
    by_name: dict[str, list[Graded]] = {}
    for graded in notebooks:
        by_name.setdefault(graded.student, []).append(graded)
    returned_by_class = {g.chapter for g in notebooks if g.chapter}
    found = []
    for name in sorted(by_name):
        counted: dict[str, Graded] = {}
        flags = []
        for chapter in chapters:
            files = [g for g in by_name[name] if g.chapter == chapter]
            if len(files) > 1:
                files.sort(key=lambda g: (g.modified, g.file))
                flags.append(
                    f"chapter {chapter} returned {len(files)} times "
                    f"({', '.join(g.file for g in files)}): {files[-1].file} counts (modified last)"
                )
            if files:
                counted[chapter] = files[-1]
        missing = [c for c in chapters if c in returned_by_class and c not in counted]
        if missing:
            flags.append(f"missing: {', '.join(missing)}")
        for graded in by_name[name]:
            if graded.chapter is None:
                flags.append(
                    f"{graded.file}: {graded.failure or 'not a chapter of the course'}"
                )
            elif graded.failure and not graded.refused:
                flags.append(f"{graded.file} failed to run: {graded.failure}")
        found.append(Student(name, counted, flags))
    return found


def class_chapters(
    notebooks: Sequence[Graded], chapters: Mapping[str, Mapping[str, int]]
) -> list[str]:
    """The chapters someone of the class returned, in course order (the gradebook's assignments)."""
    return [c for c in chapters if any(g.chapter == c for g in notebooks)]


def write_gradebook(
    folder: pathlib.Path,
    notebooks: Sequence[Graded],
    chapters: Mapping[str, Mapping[str, int]],
) -> list[Student]:
    """``gradebook.csv`` (nbgrader's export columns) and ``points.csv`` (points per exercise, total, flags).

    ``chapters``: each chapter's exercises and their points (parts), in order.
    """
    returned = class_chapters(notebooks, chapters)
    class_students = students(notebooks, list(chapters))
    gradebook, points = [], []
    numbers = [n for c in returned for n in chapters[c]]
    for student in class_students:
        row_points: dict[str, int] = {}
        for chapter in returned:
            graded = student.counted.get(chapter)
            most = sum(chapters[chapter].values())
            score = graded.points if graded else 0
            stamp = (
                datetime.datetime.fromtimestamp(
                    graded.modified, datetime.UTC
                ).isoformat(" ", "seconds")
                if graded
                else ""
            )
            gradebook.append(
                [
                    chapter,
                    "",
                    stamp,
                    student.name,
                    "",
                    "",
                    "",
                    float(score),
                    0.0,
                    float(score),
                    float(most),
                ]
            )
            for number in chapters[chapter]:
                row_points[number] = sum(
                    v.points
                    for v in (graded.verdicts if graded else [])
                    if v.number == number
                )
        total = sum(row_points.values())
        most = sum(p for c in returned for p in chapters[c].values())
        points.append(
            [
                student.name,
                *(row_points[n] for n in numbers),
                total,
                most,
                "; ".join(student.flags),
            ]
        )
    _write(folder / "gradebook.csv", GRADEBOOK_HEADER, gradebook)
    _write(
        folder / "points.csv",
        ["student_id", *numbers, "total", "max_score", "flags"],
        points,
    )
    return class_students


def _cell(value: str) -> str:
    """Text safe in a Markdown table cell."""
    return text(value).replace("|", "\\|") or " "


def feedback(student: Student, chapters: Mapping[str, Mapping[str, int]]) -> str:
    """A student's feedback file, in Markdown; ``chapters``: those the class returned (a chapter
    the student did not return counts 0 of its points, as in the gradebook)."""
    returned = [c for c in chapters if c in student.counted]
    total = sum(student.counted[c].points for c in returned)
    most = sum(sum(points.values()) for points in chapters.values())
    lines = [
        f"# Feedback: {text(student.name)}",
        "",
        f"Total: {total} of {most} points.",
    ]
    if student.flags:
        lines += ["", "Please note:", *(f"- {text(flag)}" for flag in student.flags)]
    for chapter in returned:
        graded = student.counted[chapter]
        lines += [
            "",
            f"## {chapter} ({text(graded.file)}): {graded.points} of {sum(chapters[chapter].values())} points",
            "",
            "| exercise | part | result | what to look at |",
            "|---|---|---|---|",
            *(
                f"| {v.number} | {_cell(v.part)} | {v.result} | {_cell(v.message)} |"
                for v in graded.verdicts
            ),
        ]
        for note in [
            *([graded.failure] if graded.failure else []),
            *graded.limits,
            *graded.notes,
        ]:
            lines.append(f"\n- {text(note)}")
    return "\n".join(lines) + "\n"


def write_feedback(
    folder: pathlib.Path,
    class_students: Sequence[Student],
    chapters: Mapping[str, Mapping[str, int]],
) -> list[pathlib.Path]:
    """``feedback/STUDENT.md`` for every student (names made safe for a file); ``chapters``:
    the class's (:func:`class_chapters`), each with its exercises' points."""
    out = folder / "feedback"
    out.mkdir(exist_ok=True)
    written = []
    for student in class_students:
        name = re.sub(r"[/\\\x00]|^\.+", "_", student.name) or "_"
        path = out / f"{name}.md"
        path.write_text(feedback(student, chapters), encoding="utf-8")
        written.append(path)
    return written
