"""Grade returned student notebooks: ``make grade SUBMISSIONS=folder [JOBS=n]``.

Verdicts come from answers, never from text.  For each ``*.ipynb`` under the
folder (subfolders too; ``.ipynb_checkpoints`` skipped):

1. It is read as any notebook a student can return (``tools/grade_read.py``:
   a JupyterLab, Colab or VS Code save, nbformat 3, cells without ids); a
   symbolic link, a FIFO or an oversized file is refused unread.  Its chapter
   is the one its exercise cells name (``tools/grade_release.py``).
2. Its exercise cells are found by nbgrader's ``grade_id`` or by content;
   each inputs cell is restored from the course's own copy, and in place of
   each check cell a probe cell takes the answers out of the kernel as data (a function part: its return values on the visible calls and on
   hidden ones; a value exercise graded on hidden inputs: the answer cell
   re-run on draws of inputs the student never saw, drawn from a seed only
   the grader holds), and the notebook is cut to what the answers need
   (``tools/grade_build.py``, ``tools/grade_prune.py``).
3. It runs in a sandbox (``tools/sandbox.py``: bubblewrap, a user of its
   own, only the system, Python and the packages visible, no network, the
   environment from an allow-list; memory, processes and files limited per
   notebook), with time limits per cell and per notebook, its outputs'
   size limited, everything it started killed at its end, ``JOBS`` at a
   time (``tools/grade_run.py``).  Where no sandbox can be had, grading
   refuses and says why, unless ``--unsafe`` (``make grade UNSAFE=1``).
4. Outside the kernel each part is judged (``tools/grade_verdicts.py``):
   ``passed``, ``wrong`` or ``not solved`` with a message in words;
   ``tampered`` for every part of a notebook that changed what the probe
   relies on; ``failed to run`` for parts a notebook that stopped early never
   reached.

Before any notebook runs, the setup is checked and a mistake refused with
one sentence saying what to change (a folder that is not one, an output file
the kernels could read, no sandbox, a kernel that cannot start or imports
another copy of the course than the grader's).  The output folder (the
CSV's) gets ``grades.csv``, ``gradebook.csv``, ``points.csv`` and
``feedback/`` (``tools/grade_report.py``), rewritten after each notebook, so
Ctrl-C (which stops within seconds) or a crash keeps everything graded.
Every temporary folder is in one scratch folder readable by the grader
alone, removed at the end whatever happens.

Usage: ``python tools/grade.py FOLDER [--out grades.csv] [--timeout 120]
[--max-wall 600] [--jobs N] [--seed S] [--unsafe]``; ``python tools/grade.py
--how`` prints how each part is graded (hidden inputs, hidden calls, or the
notebook's own values only).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import dataclasses
import json
import os
import pathlib
import secrets
import signal
import sys
import tempfile
import types
from collections.abc import Mapping, Sequence
from typing import Any

ROOT = pathlib.Path(__file__).resolve().parent.parent
TOOLS = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(ROOT), str(TOOLS)]
import grade_report  # noqa: E402  (tools/grade_report.py)
import sandbox  # noqa: E402  (tools/sandbox.py)
from grade_build import PROBE_SOURCE, PROBE_TAG, build  # noqa: E402
from grade_plan import Plan  # noqa: E402
from grade_read import (  # noqa: E402
    MAX_NOTEBOOK_BYTES,
    Returned,
    Unreadable,
    read_bytes,
    read_returned,
)
from grade_release import Chapter, Course, match_chapter  # noqa: E402
from grade_report import Graded, summary_line, text  # noqa: E402
from grade_run import (  # noqa: E402
    DEFAULT_LIMITS,
    Limits,
    Runner,
    Setting,
    genuine_kernel,
    make_scratch,
    remove_scratch,
)
from grade_verdicts import (  # noqa: E402
    FAILED,
    NOT_SOLVED,
    PASSED,
    TAMPERED,
    WRONG,
    methods,
    verdicts,
)

import answers  # noqa: E402  (the repository's readable references)
import twolink  # noqa: E402
import twolink_course  # noqa: E402
from twolink_course import exercises  # noqa: E402

#: The repository's references: the exercises as stored (the store holds what answers/
#: computes, tests/course/test_exercises_stored.py; it decodes in milliseconds where computing the
#: references takes seconds), the hidden calls and inputs from answers/.
REFERENCES = types.SimpleNamespace(
    all_exercises=exercises.all_exercises,
    rerun_specs=answers.rerun_specs,
    hidden_cases=answers.hidden_cases,
    hidden_draws=answers.hidden_draws,
    on_paper=answers.on_paper,
)

__all__ = [
    "grade_folder",
    "main",
    "PASSED",
    "WRONG",
    "NOT_SOLVED",
    "TAMPERED",
    "FAILED",
    "PROBE_TAG",
]


class SetupError(SystemExit):
    """A setup mistake, refused before any notebook runs: one sentence saying what to change."""


@dataclasses.dataclass(frozen=True)
class Options:
    """How a run grades: jobs at a time, sandboxed or not, time and resource limits, the seed, pruning."""

    jobs: int | None = None
    unsafe: bool = False
    limits: Limits = DEFAULT_LIMITS
    seed: int | None = None
    prune: bool = True


def readable_by_kernels() -> list[pathlib.Path]:
    """What every sandboxed kernel reads: the system's folders, Python, the packages."""
    return [pathlib.Path(name) for name in sandbox.SYSTEM] + sandbox.needed_paths()


def check_folders(folder: pathlib.Path, out: pathlib.Path, unsafe: bool) -> None:
    """Refuse a submissions folder or an output file that will not do, in one sentence each."""
    if not folder.is_dir():
        raise SetupError(
            f"SUBMISSIONS={folder}: not a folder (give the folder of returned notebooks)"
        )
    if out.is_dir():
        raise SetupError(
            f"--out {out}: a folder; give the CSV file to write (e.g. {out / 'grades.csv'})"
        )
    if out.suffix.lower() == ".ipynb":
        raise SetupError(f"--out {out}: a notebook's name; give a .csv file")
    if not unsafe:
        for path, what in ((folder, "SUBMISSIONS"), (out.parent, "--out")):
            for shared in readable_by_kernels():
                if path.resolve().is_relative_to(shared.resolve()):
                    raise SetupError(
                        f"{what} {path} is inside {shared}, which every student's kernel "
                        "can read: put it elsewhere (a folder of your own)"
                    )
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=out.parent, prefix=".grades-check-"):
            pass
    except OSError as error:
        raise SetupError(
            f"--out {out}: cannot write in {out.parent} ({error.strerror}): give a folder you can write"
        ) from None


def check_kernel(runner: Runner) -> dict[str, str]:
    """Start one kernel as the notebooks' will be (in one of ``runner``'s workers): refuse if it
    cannot start or imports another copy of the course than the grader's; its fingerprints,
    the genuine ones."""
    found = genuine_kernel(runner, PROBE_SOURCE)
    if "failure" in found:
        raise SetupError(
            f"a kernel could not start in the sandbox ({text(str(found['failure']))[:300]}): "
            "run make grade from the course's venv (make install), or see README.md, For teachers"
        )
    mine = {"twolink": twolink.__file__, "twolink_course": twolink_course.__file__}
    theirs = found.get("files", {})
    for name, path in mine.items():
        if not isinstance(theirs, dict) or theirs.get(name) != path:
            raise SetupError(
                f"the kernels import {name} from {theirs.get(name) if isinstance(theirs, dict) else '?'}, "
                f"the grader from {path}: run the grader with the Python of the venv the course is "
                "installed in (.venv/bin/python tools/grade.py, or make grade)"
            )
    fingerprints = found.get("fingerprints")
    if not isinstance(fingerprints, dict):
        raise SetupError(
            "the kernel's check sent no fingerprints: the probe could not run in it"
        )
    return {str(k): str(v) for k, v in fingerprints.items()}


def edition_warnings(
    course: Course, build_folder: pathlib.Path = ROOT / "build" / "student"
) -> list[str]:
    """Warnings when the student edition in ``build/student`` (``make student``) was built from
    chapters whose exercises differ from this checkout's (its notebooks' ``twolink_edition``)."""
    recorded: dict[str, Any] = {}
    commit = "?"
    for path in sorted(build_folder.glob("*.ipynb")):
        try:
            metadata = json.loads(path.read_text(encoding="utf-8")).get("metadata", {})
        except (OSError, ValueError):
            continue
        edition = (
            metadata.get("twolink_edition") if isinstance(metadata, dict) else None
        )
        if isinstance(edition, dict):
            recorded[path.stem] = edition.get("digest")
            commit = str(edition.get("commit", "?"))
    if not recorded:
        return []
    return differing(
        course,
        {"commit": commit, "digests": recorded},
        f"the student edition in {build_folder}",
    )


def differing(course: Course, edition: Mapping[str, Any], what: str) -> list[str]:
    """What differs between ``edition`` (its ``commit`` and chapter ``digests``) and this checkout's chapters."""
    digests = edition.get("digests", {})
    if not isinstance(digests, dict):
        return []
    changed = sorted(
        stem
        for stem, chapter in course.chapters.items()
        if stem in digests and digests[stem] != chapter.digest
    )
    if not changed:
        return []
    commit = str(edition.get("commit", "?"))[:12]
    return [
        f"{what} was built from commit {commit}, whose exercises of {', '.join(changed)} differ "
        f"from this checkout's: grade with the edition's commit (git checkout {commit})"
    ]


@dataclasses.dataclass(frozen=True)
class Prepared:
    """A returned notebook read and matched (``chapter`` None: ``graded`` says why it is not run)."""

    path: pathlib.Path
    name: str
    student: str
    modified: float
    returned: Returned | None = None
    chapter: Chapter | None = None
    graded: Graded | None = None


def prepare(path: pathlib.Path, folder: pathlib.Path, course: Course) -> Prepared:
    """Read ``path`` and find its chapter (refused, unreadable, not a chapter: its row, final)."""
    relative = path.relative_to(folder)
    name = text(str(relative))
    student = grade_report.student_of(relative, list(course.chapters))
    modified = path.lstat().st_mtime
    try:
        returned = read_returned(path, MAX_NOTEBOOK_BYTES)
    except Unreadable as error:
        reason = str(error)
        reason = reason if reason.startswith("refused:") else f"unreadable ({reason})"
        final = Graded(name, student, None, [], reason[:300], modified=modified)
        return Prepared(path, name, student, modified, graded=final)
    chapter = match_chapter(returned, path.name, course.chapters)
    if chapter is None:
        why = "not a chapter of the course (no cell of any chapter in it)"
        final = Graded(name, student, None, [], why, modified=modified)
        return Prepared(path, name, student, modified, graded=final)
    return Prepared(path, name, student, modified, returned, chapter)


def grade_one(
    prepared: Prepared,
    course: Course,
    plan: Plan,
    genuine: Mapping[str, str],
    runner: Runner,
    options: Options,
) -> Graded:
    """Grade one returned notebook, read and matched."""
    returned, chapter = prepared.returned, prepared.chapter
    assert returned is not None and chapter is not None
    built = build(returned, chapter, plan, prune=options.prune)
    notes = list(built.notes)
    if returned.edition is not None:
        notes += differing(
            course,
            {
                "commit": returned.edition.get("commit"),
                "digests": {chapter.stem: returned.edition.get("digest")},
            },
            "this notebook's edition",
        )
    try:
        submission: bytes | None = read_bytes(prepared.path, MAX_NOTEBOOK_BYTES)
    except OSError:
        submission = None
    ran = runner.run(built.notebook, built.positions, submission)
    rows, signs = verdicts(chapter.exercises, built.probed, ran, plan, genuine)
    notes[:0] = [f"TAMPERED: {sign}" for sign in signs[:1]]
    errors = ran.get("errors") or []
    if errors:
        notes.append(f"{len(errors)} cell(s) raised; the first: {errors[0]}")
    return Graded(
        prepared.name,
        prepared.student,
        chapter.stem,
        rows,
        ran.get("failure"),
        notes,
        list(ran.get("limits") or []),
        prepared.modified,
        ran.get("cpu_seconds"),
    )


def crashed(prepared: Prepared, error: BaseException) -> Graded:
    """The row of a notebook whose grading failed in the grader itself: the run goes on."""
    return Graded(
        prepared.name,
        prepared.student,
        prepared.chapter.stem if prepared.chapter else None,
        [],
        f"the grader failed on it ({type(error).__name__}: {text(str(error))[:200]}): "
        "grade it again, or report it",
        modified=prepared.modified,
    )


def submissions(folder: pathlib.Path) -> list[pathlib.Path]:
    """Every ``*.ipynb`` under ``folder``, in order, checkpoints left out (symbolic links included, to be refused)."""
    return sorted(
        pathlib.Path(root, name)
        for root, _, files in os.walk(folder)
        for name in files
        if name.endswith(".ipynb")
        and ".ipynb_checkpoints" not in pathlib.Path(root).parts
    )


def grade_folder(
    folder: str | pathlib.Path,
    out: str | pathlib.Path,
    *,
    jobs: int | None = None,
    unsafe: bool = False,
    limits: Limits = DEFAULT_LIMITS,
    seed: int | None = None,
    course: Course | None = None,
    prune: bool = True,
    graded_out: list[Graded] | None = None,
) -> list[str]:
    """Grade every notebook under ``folder``, ``jobs`` at a time; write the grades, gradebook and
    feedback beside ``out``; return the summary lines.  ``course``: the repository's by default;
    ``graded_out``: a list that gets each notebook's :class:`grade_report.Graded` (its CPU time too)."""
    folder, out = pathlib.Path(folder), pathlib.Path(out)
    options = Options(jobs, unsafe, limits, seed, prune)
    check_folders(folder, out, unsafe)
    paths = submissions(folder)
    if not paths:
        raise SetupError(f"SUBMISSIONS={folder}: no .ipynb files in it")
    workers = jobs or os.cpu_count() or 1
    if workers < 1:
        raise SetupError(f"JOBS={workers}: give at least 1 notebook at a time")
    if not unsafe:
        reason = sandbox.unavailable()
        if reason is not None:
            raise SetupError(
                f"cannot sandbox the notebooks: {reason}. Grading untrusted notebooks "
                "without a sandbox lets them read and change your files and the grades; "
                "if you accept that, pass --unsafe (make grade UNSAFE=1)"
            )
    try:
        course = course or Course.read(ROOT / "notebooks", REFERENCES)
    except ValueError as error:
        raise SetupError(
            f"the course's chapters and answers/ disagree: {error}"
        ) from None
    plan = Plan.drawn(course, secrets.randbits(32) if seed is None else seed)
    chapters = {
        stem: {e.number: len(e.parts) for e in chapter.exercises}
        for stem, chapter in course.chapters.items()
    }
    scratch = make_scratch()
    setting = Setting(
        scratch, None if unsafe else sandbox.Isolation.detect(scratch), limits
    )
    graded: dict[pathlib.Path, Graded] = {}
    lines: list[str] = []

    def record(path: pathlib.Path, result: Graded) -> None:
        graded[path] = result
        if graded_out is not None:
            graded_out.append(result)
        grade_report.write_grades(out, [graded[p] for p in paths if p in graded])
        line = summary_line(result)
        print(line, flush=True)
        lines.append(line)

    runner = Runner(setting)
    interrupted = False
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=workers)
    try:
        prepared = [prepare(path, folder, course) for path in paths]
        runnable = [item for item in prepared if item.graded is None]
        genuine = check_kernel(runner) if runnable else {}
        how = (
            "UNSAFE: no sandbox"
            if setting.isolation is None
            else f"sandboxed: {setting.isolation.words()}; {limits.resources.words()}"
        )
        print(f"grading {len(paths)} notebooks, {workers} at a time; {how}", flush=True)
        for warning in edition_warnings(course):
            print(f"WARNING: {warning}", flush=True)
        for item in prepared:
            if item.graded is not None:
                record(item.path, item.graded)
        futures = {
            pool.submit(grade_one, item, course, plan, genuine, runner, options): item
            for item in runnable
        }
        for future in concurrent.futures.as_completed(futures):
            item = futures[future]
            try:
                result = future.result()
            except (
                Exception
            ) as error:  # the grader's own failure on one file: the run goes on
                result = crashed(item, error)
            record(item.path, result)
    except KeyboardInterrupt:
        interrupted = True
        signal.signal(
            signal.SIGINT, signal.SIG_IGN
        )  # cleaning up: a second Ctrl-C waits
    finally:
        runner.close()  # a notebook still running stops with its worker
        pool.shutdown(wait=True, cancel_futures=True)
        remove_scratch(setting)
    done = [graded[p] for p in paths if p in graded]
    grade_report.write_grades(out, done)
    class_students = grade_report.write_gradebook(out.parent, done, chapters)
    returned = grade_report.class_chapters(done, chapters)
    grade_report.write_feedback(
        out.parent, class_students, {c: chapters[c] for c in returned}
    )
    if interrupted:
        print(
            f"stopped (Ctrl-C): {len(done)} of {len(paths)} notebooks graded, written to "
            f"{text(str(out))} with the gradebook, points and feedback; the others were "
            "not graded",
            flush=True,
        )
        raise SystemExit(130)
    print(
        f"wrote {text(str(out))}, the gradebook, points and feedback beside it",
        flush=True,
    )
    return lines


def how_graded(course: Course | None = None) -> str:
    """How each part of the course is graded, as a Markdown table (``grade.py --how``)."""
    course = course or Course.read(ROOT / "notebooks", REFERENCES)
    plan = Plan.drawn(course, 0)
    rows = methods(course.exercises, plan, on_paper=course.on_paper)
    return "\n".join(
        [
            "| exercise | part | graded on |",
            "|---|---|---|",
            *(f"| {number} | {part} | {how} |" for number, part, how in rows),
        ]
    )


def main(argv: Sequence[str] | None = None) -> None:
    """Grade the folder named on the command line."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("submissions", nargs="?", help="folder of returned notebooks")
    parser.add_argument(
        "--out",
        default=None,
        help="CSV to write (default: SUBMISSIONS/grades.csv); the gradebook, points and feedback go beside it",
    )
    parser.add_argument(
        "--timeout", type=float, default=Limits.cell_seconds, help="seconds per cell"
    )
    parser.add_argument(
        "--max-wall",
        type=float,
        default=Limits.notebook_seconds,
        help="seconds per notebook, all cells",
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=None,
        help="notebooks graded at a time (default: one per core)",
    )
    parser.add_argument(
        "--seed",
        type=int,
        default=None,
        help="the hidden calls' and inputs' seed (default: a random one)",
    )
    parser.add_argument(
        "--unsafe",
        action="store_true",
        help="run the notebooks without a sandbox (only for notebooks you trust)",
    )
    parser.add_argument(
        "--how",
        action="store_true",
        help="print how each part of the course is graded, and grade nothing",
    )
    args = parser.parse_args(argv)
    if args.how:
        print(how_graded())
        return
    if not args.submissions:
        parser.error("give the folder of returned notebooks")
    grade_folder(
        args.submissions,
        args.out or str(pathlib.Path(args.submissions) / "grades.csv"),
        jobs=args.jobs,
        unsafe=args.unsafe,
        limits=Limits(args.timeout, args.max_wall),
        seed=args.seed,
    )


if __name__ == "__main__":
    main()
