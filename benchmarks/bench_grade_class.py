"""A class graded: ``make grade`` on every chapter returned by every student, sandboxed, JOBS at a time.

Builds a folder of returned notebooks (each student returns the seven
chapters: the instructor's worked solutions for even-numbered students, the
untouched student edition for odd ones), grades it with ``tools/grade.py``
exactly as ``make grade`` does, checks that every part got the verdict its
notebook deserves, and prints the throughput beside the target on these
2-core machines: 350 chapter notebooks (50 students x 7 chapters) within 15
minutes.

Run with ``.venv/bin/python benchmarks/bench_grade_class.py`` (``--students
50``, the default, is the whole class, about a quarter of an hour;
``--quick``: one student, chapter 1; ``--jobs N``: notebooks at a time).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import os
import platform
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tools")]

import course_map  # noqa: E402
import editions  # noqa: E402
import grade  # noqa: E402
import sandbox  # noqa: E402

from twolink_course.display import markdown_table  # noqa: E402

TARGET_NOTEBOOKS = 350
TARGET_MINUTES = 15.0


def build_class(
    folder: Path, students: int, chapters: list[Path], student_edition: Path
) -> dict[str, str]:
    """Write each student's returned chapters into ``folder``; the verdict each file deserves."""
    deserved = {}
    for student in range(students):
        for chapter in chapters:
            name = f"student{student:02d}_{chapter.name}"
            solved = student % 2 == 0
            source = chapter if solved else student_edition / chapter.name
            shutil.copyfile(source, folder / name)
            deserved[name] = "passed" if solved else "not solved"
    return deserved


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument(
        "--students", type=int, default=50, help="students in the class (default 50)"
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=None,
        help="notebooks at a time (default: one per core)",
    )
    parser.add_argument(
        "--quick", action="store_true", help="one student, chapter 1 (a smoke run)"
    )
    args = parser.parse_args()
    chapters = course_map.chapters(ROOT / "notebooks")
    students = args.students
    if args.quick:
        chapters, students = chapters[:1], 1
    jobs = args.jobs or os.cpu_count() or 1
    unsafe = sandbox.unavailable() is not None
    with tempfile.TemporaryDirectory(prefix="twolink-class-") as scratch:
        student_edition = Path(scratch) / "student"
        editions.build_student(ROOT / "notebooks", student_edition)
        submissions = Path(scratch) / "submissions"
        submissions.mkdir()
        deserved = build_class(submissions, students, chapters, student_edition)
        out = Path(scratch) / "grades" / "grades.csv"
        started = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):  # its line per notebook
            grade.grade_folder(submissions, out, jobs=jobs, unsafe=unsafe)
        seconds = time.perf_counter() - started
        with out.open(encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
    wrong = sorted(
        {
            row["student file"]
            for row in rows
            if row["result"] != deserved[row["student file"]]
        }
    )
    if wrong:
        raise SystemExit(f"graded other than deserved: {wrong[:5]}")
    notebooks = len(deserved)
    per_minute = notebooks / seconds * 60
    print(
        f"# A class graded ({platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()})\n"
    )
    print(
        markdown_table(
            [
                "notebooks",
                "jobs",
                "sandbox",
                "seconds",
                "notebooks per minute",
                f"{TARGET_NOTEBOOKS} notebooks [min]",
                "target [min]",
            ],
            [
                [
                    str(notebooks),
                    str(jobs),
                    "no (unsafe)" if unsafe else "bubblewrap",
                    f"{seconds:.0f}",
                    f"{per_minute:.1f}",
                    f"{TARGET_NOTEBOOKS / per_minute:.1f}",
                    f"<= {TARGET_MINUTES:g}",
                ]
            ],
        )
    )
    print(
        f"\nEvery one of the {len(rows)} parts got the verdict its notebook deserves (passed or not solved)."
    )


if __name__ == "__main__":
    main()
