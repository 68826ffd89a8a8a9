"""A class graded: ``make grade`` on every chapter returned by every student, sandboxed, JOBS at a time.

Builds a folder of returned notebooks (each student returns the seven
chapters: the instructor's worked solutions for even-numbered students, the
untouched student edition for odd ones), grades it with ``tools/grade.py``
exactly as ``make grade`` does, checks that every part got the verdict its
notebook deserves, and prints the throughput beside the target on these
2-core machines: 350 chapter notebooks (50 students x 7 chapters) within 15
minutes.

Where the notebooks go: the CPU time of each notebook's kernel and sandbox
(counted by its control groups, where the machine has them), per chapter,
and the grader's own (its main process and workers, counted by a control
group of this script's), per notebook; ``--no-prune`` grades every cell up to
the last check, as before the grader cut notebooks to what their answers need,
for comparison.  Timings vary with the machine's load: the load average is
printed with them; compare runs side by side.

Run with ``.venv/bin/python benchmarks/bench_grade_class.py`` (``--students
50``, the default, is the whole class; ``--quick``: one student, chapter 1;
``--jobs N``: notebooks at a time).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import platform
import shutil
import statistics
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


class OwnGroup:
    """A cpuacct control group holding this process and the processes it starts (the grader and
    its workers; each kernel is counted by its own groups)."""

    def __init__(self) -> None:
        cgroups = sandbox.Cgroups.detect()
        self.path: Path | None = None
        if (
            cgroups is not None
            and cgroups.version == 1
            and "cpuacct" in cgroups.folders
        ):
            self.path = Path(cgroups.folders["cpuacct"], f"twolink-bench-{os.getpid()}")
            self.path.mkdir()
            (self.path / "cgroup.procs").write_text(str(os.getpid()), encoding="ascii")
            self.parent = Path(cgroups.folders["cpuacct"])

    def seconds(self) -> float | None:
        if self.path is None:
            return None
        return int((self.path / "cpuacct.usage").read_text(encoding="ascii")) / 1e9

    def close(self) -> None:
        if self.path is None:
            return
        (self.parent / "cgroup.procs").write_text(str(os.getpid()), encoding="ascii")
        deadline = time.monotonic() + 10
        while True:
            try:
                self.path.rmdir()
                return
            except OSError:  # its last processes exiting
                if time.monotonic() > deadline:
                    return
                time.sleep(0.1)


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
    parser.add_argument(
        "--no-prune",
        action="store_true",
        help="run every cell up to the last check (for comparison)",
    )
    args = parser.parse_args()
    chapters = course_map.chapters(ROOT / "notebooks")
    students = args.students
    if args.quick:
        chapters, students = chapters[:1], 1
    jobs = args.jobs or os.cpu_count() or 1
    unsafe = sandbox.unavailable() is not None
    graded: list[grade.Graded] = []
    with tempfile.TemporaryDirectory(prefix="twolink-class-") as scratch:
        student_edition = Path(scratch) / "student"
        editions.build_student(ROOT / "notebooks", student_edition)
        submissions = Path(scratch) / "submissions"
        submissions.mkdir()
        deserved = build_class(submissions, students, chapters, student_edition)
        out = Path(scratch) / "grades" / "grades.csv"
        group = OwnGroup()
        load_before = os.getloadavg()[0]
        started = time.perf_counter()
        try:
            with contextlib.redirect_stdout(io.StringIO()):  # its line per notebook
                grade.grade_folder(
                    submissions,
                    out,
                    jobs=jobs,
                    unsafe=unsafe,
                    prune=not args.no_prune,
                    graded_out=graded,
                )
            seconds = time.perf_counter() - started
            grader_cpu = group.seconds()
        finally:
            group.close()
        load_after = os.getloadavg()[0]
    wrong = sorted(
        {g.file for g in graded for v in g.verdicts if v.result != deserved[g.file]}
        | {g.file for g in graded if g.failure}
    )
    if wrong or len(graded) != len(deserved):
        raise SystemExit(
            f"graded other than deserved: {wrong[:5]} ({len(graded)} of {len(deserved)} graded)"
        )
    notebooks = len(deserved)
    per_minute = notebooks / seconds * 60
    kernels = [g.cpu_seconds for g in graded]
    counted = all(k is not None for k in kernels) and grader_cpu is not None
    print(
        f"# A class graded ({platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
        f"load average {load_before:.1f} before, {load_after:.1f} after)\n"
    )
    print(
        markdown_table(
            [
                "notebooks",
                "jobs",
                "sandbox",
                "cells",
                "seconds",
                "notebooks per minute",
                f"{TARGET_NOTEBOOKS} notebooks [min]",
                "target [min]",
                "CPU-s per notebook",
            ],
            [
                [
                    str(notebooks),
                    str(jobs),
                    "no (unsafe)" if unsafe else "bubblewrap",
                    "all up to the last check"
                    if args.no_prune
                    else "what the answers need",
                    f"{seconds:.0f}",
                    f"{per_minute:.1f}",
                    f"{TARGET_NOTEBOOKS / per_minute:.1f}",
                    f"<= {TARGET_MINUTES:g}",
                    f"{(sum(kernels) + grader_cpu) / notebooks:.2f}"
                    if counted
                    else "not counted here",  # type: ignore[arg-type, operator]
                ]
            ],
        )
    )
    if counted:
        print("\nWhere the CPU time goes, seconds per notebook (median, max):\n")
        for chapter in chapters:
            for solved in (True, False):
                mine = [
                    g.cpu_seconds
                    for g in graded
                    if g.chapter == chapter.stem
                    and (deserved[g.file] == "passed") == solved
                ]
                if mine:
                    print(
                        f"- {chapter.stem}, {'solved' if solved else 'untouched'}: kernel and sandbox "
                        f"{statistics.median(mine):.2f}, {max(mine):.2f}"  # type: ignore[type-var]
                    )
        print(
            f"- the grader itself (reading, building, judging, its workers): "
            f"{grader_cpu / notebooks:.2f} per notebook"  # type: ignore[operator]
        )
    print(
        f"\nEvery one of the {sum(len(g.verdicts) for g in graded)} parts got the verdict its notebook deserves."
    )


if __name__ == "__main__":
    main()
