"""Grade returned student notebooks: ``make grade SUBMISSIONS=folder [JOBS=n]``.

Verdicts come from answers, never from text.  For each ``*.ipynb`` under the
folder (subfolders too):

1. Its chapter is the one it shares most cells with (same source; cell ids
   repeat across chapters); the file name only breaks a tie.
2. Every output is cleared; each check cell is restored from the course's
   own copy of the chapter (matched by cell id), so an edited check cell
   runs as released and a deleted one leaves its exercise "not solved";
   after each check cell the grader adds a probe cell
   (``tools/grading_probe.py``) that takes the answers out of the kernel as
   data (a function part: its return values on the exercise's visible calls
   and on hidden ones drawn from a seed the kernel never holds).  Cells after
   the last check cell (summary, casebook) are not run.
3. The notebook runs in a sandbox (``tools/sandbox.py``: bubblewrap, a user
   of its own, limits on memory, CPU time, processes, file size; no network;
   only its own temporary folder writable; the submissions, the grades and
   the instructor's files invisible), with a time limit per cell and for the
   whole notebook, a limit on the size of its outputs, and everything it
   started killed at its end (``tools/grade_run.py``: worker processes,
   one per notebook graded at a time, ``JOBS``, one per core by default; a
   worker that overruns is killed with its sandbox and replaced).  Where no sandbox
   can be had, grading refuses and says why, unless ``--unsafe``
   (``make grade UNSAFE=1``).
4. Outside the kernel, each part is judged against the exercise's
   specification (:func:`twolink_course.exercises.judging.judge`): ``passed``,
   ``wrong`` or ``not solved``; every part of a notebook whose probe finds
   the self-check, the judging or store modules, the serializer or a builtin
   replaced, or whose probe cell publishes nothing, is ``tampered``; parts
   a notebook that stopped (its kernel died, a limit) never reached are
   ``failed to run``.

``SUBMISSIONS/grades.csv`` (``student file, exercise, part, result``) is
rewritten whole after each notebook, atomically, so an interrupted run keeps
everything graded so far.  A notebook that stopped early gets a row with
exercise ``(none)`` and result ``failed to run: why``; a path that is not a
regular file (a symlink, a FIFO) or is larger than ``MAX_NOTEBOOK_BYTES``
is not opened: its row says ``refused: why``.  A cell that a spreadsheet
would read as a formula gets a leading ``'``; names are printed with
control characters escaped.  Heavy cells that no answer depends on are
skipped by the package while ``TWOLINK_GRADING=1`` (set in the sandbox).

Usage: ``python tools/grade.py FOLDER [--out grades.csv] [--timeout 120]
[--max-wall 600] [--jobs N] [--seed S] [--unsafe]``.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import dataclasses
import io
import os
import pathlib
import secrets
import stat
import sys
import tempfile
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import nbformat
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
TOOLS = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(ROOT), str(TOOLS)]
import course_map  # noqa: E402  (tools/course_map.py)
import grading_probe  # noqa: E402  (tools/grading_probe.py)
import sandbox  # noqa: E402  (tools/sandbox.py)
from grade_run import DEFAULT_LIMITS, PROBE_TAG, Limits, Runner  # noqa: E402  (tools/grade_run.py)
from nbgrader_cells import check_call  # noqa: E402  (tools/nbgrader_cells.py)

import answers  # noqa: E402  (the repository's readable references)
from twolink_course import exercises  # noqa: E402
from twolink_course.exercises import judging  # noqa: E402
from twolink_course.exercises.spec import Case, ExerciseSpec, PartSpec  # noqa: E402

PASSED, WRONG, NOT_SOLVED, TAMPERED, FAILED = (
    "passed",
    "wrong",
    "not solved",
    "tampered",
    "failed to run",
)
RESULTS = (PASSED, NOT_SOLVED, WRONG, TAMPERED, FAILED)
#: Larger files are refused unread (a chapter notebook with its outputs is ~1 MB).
MAX_NOTEBOOK_BYTES = 50_000_000
#: What a spreadsheet reads as the start of a formula.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
HEADER = ["student file", "exercise", "part", "result"]
#: Hidden calls per function part.
HIDDEN_CALLS = 20
#: What the submissions' sandboxes must not see, besides the submissions and the grades.
INSTRUCTOR_ONLY = [
    ROOT / name for name in ("notebooks", "build", "answers", "tests", ".git")
]


def csv_cell(value: str) -> str:
    """``value`` safe in a spreadsheet: a leading ``'`` when it would start a formula.

    >>> csv_cell("=SUM(A1)"), csv_cell("passed"), csv_cell("-1+2")
    ("'=SUM(A1)", 'passed', "'-1+2")
    """
    return "'" + value if value.startswith(FORMULA_STARTS) else value


def shown(name: str) -> str:
    r"""``name`` for the terminal: control characters (a newline, an escape) written as escapes.

    >>> print(shown("ada" + chr(10) + "bob: 9 passed"))
    ada\nbob: 9 passed
    """
    return "".join(
        character if character.isprintable() else repr(character)[1:-1]
        for character in name
    )


def refusal(path: pathlib.Path) -> str | None:
    """Why ``path`` is not opened (not a regular file, too large), or None."""
    try:
        info = os.lstat(path)
    except OSError as error:
        return f"refused: cannot stat it ({error.strerror})"
    if stat.S_ISLNK(info.st_mode):
        return "refused: a symbolic link, not a regular file"
    if not stat.S_ISREG(info.st_mode):
        return "refused: not a regular file (a FIFO, a device or a socket)"
    if info.st_size > MAX_NOTEBOOK_BYTES:
        return f"refused: {info.st_size} bytes, more than {MAX_NOTEBOOK_BYTES}"
    return None


# ------------------------------------------------------------------ the release


@dataclasses.dataclass(frozen=True)
class Chapter:
    """A chapter as released: its check cells by cell id, and its exercises' specifications."""

    stem: str
    check_cells: Mapping[str, tuple[str, Any]]  # cell id -> (exercise number, cell)
    exercises: tuple[ExerciseSpec, ...]
    sources: frozenset[str]  # every cell's source, to recognise the chapter


def check_number(cell: Any) -> str | None:
    """The exercise a code cell checks (``"2.1"``), or None if it is no check cell as the chapters write them.

    >>> check_number(nbformat.v4.new_code_cell('correct_ex1 = selfcheck.check("2.1", q)'))
    '2.1'
    >>> check_number(nbformat.v4.new_code_cell('print("selfcheck.check")')) is None
    True
    """
    if cell.get("cell_type") != "code" or "selfcheck.check" not in "".join(
        cell.get("source", "")
    ):
        return None
    try:
        return check_call("".join(cell.get("source", "")))[0]
    except (ValueError, SyntaxError):
        return None


def release_chapters(folder: pathlib.Path = ROOT / "notebooks") -> dict[str, Chapter]:
    """The course's chapters, read from the instructor's copies in ``folder``."""
    every = exercises.all_exercises()
    chapters = {}
    for path in course_map.chapters(folder):
        notebook = nbformat.read(path, as_version=4)
        checks = {
            cell.id: (number, cell)
            for cell in notebook.cells
            if (number := check_number(cell)) is not None
        }
        specs = tuple(e for e in every if e.chapter == path.stem)
        if checks and specs:
            sources = frozenset(
                cell.source for cell in notebook.cells if cell.source.strip()
            )
            chapters[path.stem] = Chapter(path.stem, checks, specs, sources)
    return chapters


def match_chapter(
    notebook: Any, name: str, chapters: Mapping[str, Chapter]
) -> Chapter | None:
    """The chapter ``notebook`` shares most cells with (same source); the file name breaks a tie.

    Cell ids cannot tell the chapters apart (each chapter numbers its cells
    from 0), and a student may rename the file, edit or delete check cells.
    """

    def score(chapter: Chapter) -> tuple[int, bool]:
        shared = sum(
            1 for cell in notebook.cells if cell.get("source") in chapter.sources
        )
        return shared, pathlib.Path(name).name.startswith(chapter.stem[:3])

    best = max(chapters.values(), key=score, default=None)
    if best is None or score(best) == (0, False):
        return None
    return best


# ------------------------------------------------------------------ the plan


@dataclasses.dataclass(frozen=True)
class Plan:
    """What every notebook is asked: each function part's calls (visible then hidden cases)."""

    calls: Mapping[tuple[str, str], tuple[Case, ...]]

    @classmethod
    def drawn(cls, seed: int, count: int = HIDDEN_CALLS) -> Plan:
        """The visible cases of every function part, then ``count`` hidden ones from ``seed``."""
        calls = {}
        for exercise in exercises.all_exercises():
            for part in exercise.parts:
                if part.kind == "function":
                    hidden = answers.hidden_cases(
                        exercise.number, part.name, seed, count
                    )
                    calls[exercise.number, part.name] = (*part.cases, *hidden)
        return cls(calls)

    def request(self, exercise: ExerciseSpec) -> dict[str, Any]:
        """What the probe after ``exercise``'s check cell is asked (plain data)."""
        return {
            "exercise": exercise.number,
            "names": [part.name for part in exercise.parts],
            "calls": {
                part.name: [dict(case.arguments) for case in self.calls[key]]
                for part in exercise.parts
                if (key := (exercise.number, part.name)) in self.calls
            },
        }


def probe_cell(request: Mapping[str, Any]) -> Any:
    """The cell that publishes the answers of ``request["exercise"]`` (the probe's source, run in a namespace of its own)."""
    source = (
        f"# Added by the grader: the answers of exercise {request['exercise']}, as data.\n"
        f"_grader_probe = {{'__name__': 'grader_probe'}}\n"
        f"exec(compile({grading_probe_source()!r}, '<grader probe>', 'exec'), _grader_probe)\n"
        f"_grader_probe['report']({dict(request)!r}, get_ipython().user_ns)\n"
        "del _grader_probe\n"
    )
    cell = nbformat.v4.new_code_cell(source, metadata={"tags": [PROBE_TAG]})
    cell.id = f"grader-probe-{request['exercise'].replace('.', '-')}"
    return cell


def grading_probe_source() -> str:
    """The probe's source text (``tools/grading_probe.py``)."""
    return pathlib.Path(grading_probe.__file__).read_text(encoding="utf-8")


def graded_notebook(
    submission: Any, chapter: Chapter, plan: Plan
) -> tuple[Any, list[str]]:
    """``submission`` made ready to run: outputs cleared, check cells restored, a probe after each; the exercises probed.

    Cells after the last check cell are dropped; a check cell the submission
    deleted (no cell with its id) is not put back: its exercise is not probed.
    """
    specs = {exercise.number: exercise for exercise in chapter.exercises}
    cells = []
    probed: list[str] = []
    for cell in submission.cells:
        cell = nbformat.from_dict(dict(cell))
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
        release = chapter.check_cells.get(cell.get("id"))
        if release is None:
            cells.append(cell)
            continue
        number, released = release
        cells.append(
            nbformat.from_dict(dict(released, outputs=[], execution_count=None))
        )
        if number in specs and number not in probed:
            cells.append(probe_cell(plan.request(specs[number])))
            probed.append(number)
    last_probe = max(
        (
            i
            for i, cell in enumerate(cells)
            if PROBE_TAG in cell.metadata.get("tags", [])
        ),
        default=-1,
    )
    notebook = nbformat.from_dict(dict(submission))
    notebook.cells = cells[: last_probe + 1]
    return notebook, probed


# ------------------------------------------------------------------ verdicts


def decoded(data: Any) -> Any:
    """An answer as the probe encoded it, back as a value :func:`judging.judge` reads (untrusted data: never evaluated).

    >>> decoded({"numbers": [1.0, 2.0]}), decoded({"unsolved": True}), decoded({"bool": False})
    (array([1., 2.]), Ellipsis, False)
    >>> type(decoded({"unreadable": "DataFrame"})).__name__
    'DataFrame'
    """
    if not isinstance(data, dict):
        return _unreadable("object")
    try:
        if data.get("unsolved") is True or data.get("missing") is True:
            return ...
        if "bool" in data and isinstance(data["bool"], bool):
            return data["bool"]
        if "text" in data and isinstance(data["text"], str):
            return data["text"]
        if "numbers" in data:
            numbers = np.asarray(data["numbers"], dtype=float)
            return float(numbers) if numbers.ndim == 0 else numbers
        if "complex" in data:
            real, imaginary = data["complex"]
            return np.asarray(real, dtype=float) + 1j * np.asarray(
                imaginary, dtype=float
            )
        if "unreadable" in data:
            return _unreadable(str(data["unreadable"]))
    except (TypeError, ValueError, OverflowError):
        pass
    return _unreadable("object")


def _unreadable(name: str) -> Any:
    """An object whose type carries ``name``, so that the judge's message names what was given."""
    name = name if name.isidentifier() else "object"
    return type(name, (), {"__repr__": lambda self: f"<a {name}>"})()


def _replay(results: Sequence[Any]) -> Callable[..., Any]:
    """A function returning ``results`` one call after another (a raised error raised again, by name)."""
    remaining = list(results)

    def replayed(**arguments: Any) -> Any:
        result = remaining.pop(0) if remaining else {"unreadable": "nothing"}
        if isinstance(result, dict) and "raised" in result:
            name = str(result["raised"])
            error = type(name if name.isidentifier() else "Exception", (Exception,), {})
            raise error(str(result.get("message", "")))
        return decoded(result)

    return replayed


def judge_part(part: PartSpec, data: Any, cases: Sequence[Case]) -> str:
    """``passed``, ``wrong`` or ``not solved`` for the encoded answer ``data`` of ``part``."""
    if (
        not isinstance(data, dict)
        or data.get("missing") is True
        or data.get("unsolved") is True
    ):
        return NOT_SOLVED
    if part.kind == "function":
        calls = data.get("calls")
        if not isinstance(calls, list):
            return WRONG
        if len(calls) == 1 and isinstance(calls[0], dict) and calls[0].get("unsolved"):
            return NOT_SOLVED
        verdict = judging.judge_function(part, _replay(calls), cases)
    else:
        verdict = judging.judge(part, decoded(data))
    return PASSED if verdict.right else WRONG


def expected_fingerprints() -> dict[str, str]:
    """The probe's fingerprints of the genuine modules (as this grader imports them)."""
    import IPython.display  # noqa: F401  (watched: imported so that it is fingerprinted)

    from twolink_course import selfcheck

    return grading_probe.fingerprints({"selfcheck": selfcheck})


def verdicts(
    chapter: Chapter,
    probed: Sequence[str],
    ran: Mapping[str, Any],
    plan: Plan,
    genuine: Mapping[str, str],
) -> tuple[list[tuple[str, str, str]], list[str]]:
    """One row ``(exercise, part, result)`` per part of the chapter, and the signs of tampering found."""
    reports = ran.get("reports", {})
    if not isinstance(reports, dict):
        reports = {}
    tampering: list[str] = []
    for number in probed:
        report = reports.get(number, "not run")
        if report == "silent" or (report != "not run" and not isinstance(report, dict)):
            tampering.append(f"the probe after check {number} published nothing")
        elif isinstance(report, dict):
            found = report.get("fingerprints")
            if not isinstance(found, dict):
                tampering.append(f"the probe after check {number} sent no fingerprints")
                continue
            changed = sorted(k for k, v in genuine.items() if found.get(k) != v)
            if changed:
                tampering.append(
                    f"replaced before check {number}: {', '.join(changed[:4])}"
                )
    rows = []
    for exercise in chapter.exercises:
        report = reports.get(exercise.number, "not run")
        for part in exercise.parts:
            if tampering:
                result = TAMPERED
            elif exercise.number not in probed:
                result = NOT_SOLVED  # its check cell was deleted
            elif not isinstance(report, dict):
                result = FAILED
            else:
                answers_ = report.get("answers")
                data = answers_.get(part.name) if isinstance(answers_, dict) else None
                cases = plan.calls.get((exercise.number, part.name), ())
                result = judge_part(part, data, cases)
            rows.append((exercise.number, part.label, result))
    return rows, tampering


# ------------------------------------------------------------------ one notebook, many


@dataclasses.dataclass(frozen=True)
class Graded:
    """One notebook's rows ``(exercise, part, result)``, why it stopped early (or None), and notes for the summary."""

    rows: list[tuple[str, str, str]]
    failure: str | None
    notes: list[str]


def grade_notebook(
    path: pathlib.Path,
    chapters: Mapping[str, Chapter],
    plan: Plan,
    genuine: Mapping[str, str],
    runner: Runner,
    *,
    hidden: Sequence[pathlib.Path] = (),
    unsafe: bool = False,
    limits: Limits = DEFAULT_LIMITS,
) -> Graded:
    """Grade one returned notebook (refused, unreadable, not a chapter: a failure saying so)."""
    reason = refusal(path)
    if reason is not None:
        return Graded([], reason, [])
    try:
        submission = nbformat.read(path, as_version=4)
        nbformat.validate(submission)  # every cell as nbformat 4 says
    except Exception as error:  # invalid JSON, not a notebook
        first = str(error).splitlines()[0] if str(error) else ""
        return Graded([], f"unreadable ({type(error).__name__}: {first})"[:300], [])
    chapter = match_chapter(submission, path.name, chapters)
    if chapter is None:
        return Graded(
            [], "not a chapter of the course (no cell of any chapter in it)", []
        )
    notebook, probed = graded_notebook(submission, chapter, plan)
    ran = runner.run(notebook, hidden=hidden, unsafe=unsafe, limits=limits)
    rows, tampering = verdicts(chapter, probed, ran, plan, genuine)
    notes = [f"TAMPERED: {sign}" for sign in tampering[:1]]
    deleted = [e.number for e in chapter.exercises if e.number not in probed]
    if deleted:
        notes.append(f"check cell deleted: {', '.join(deleted)}")
    errors = ran.get("errors") or []
    if errors:
        notes.append(f"{len(errors)} cell(s) raised; the first: {errors[0]}")
    return Graded(rows, ran.get("failure"), notes)


def summary_line(name: str, graded: Graded) -> str:
    """One line: the file, how many parts passed / not solved / wrong / ..., any failure and notes."""
    if graded.failure and graded.failure.startswith("refused:"):
        return f"{name}: REFUSED{graded.failure[7:]}"
    counts = {
        result: sum(1 for row in graded.rows if row[2] == result) for result in RESULTS
    }
    text = f"{name}: " + ", ".join(
        f"{count} {result}"
        for result, count in counts.items()
        if count or result in (PASSED, NOT_SOLVED, WRONG)
    )
    if graded.failure:
        text += f"; FAILED TO RUN: {shown(graded.failure)}"
    for note in graded.notes:
        text += f"; {shown(note)}"
    return text


def write_csv(out: pathlib.Path, rows: Sequence[Sequence[str]]) -> None:
    """Write the whole CSV atomically: a temporary file in the same folder, renamed over ``out``."""
    text = io.StringIO(newline="")
    writer = csv.writer(text)
    writer.writerow(HEADER)
    writer.writerows([csv_cell(str(cell)) for cell in row] for row in rows)
    descriptor, temporary = tempfile.mkstemp(
        dir=out.parent, prefix=".grades-", suffix=".csv"
    )
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8", newline="") as handle:
            handle.write(text.getvalue())
        os.replace(temporary, out)
    except BaseException:
        pathlib.Path(temporary).unlink(missing_ok=True)
        raise


def table_rows(name: str, graded: Graded) -> list[list[str]]:
    """The CSV rows of one notebook."""
    table = [[name, number, part, result] for number, part, result in graded.rows]
    if graded.failure:
        result = (
            graded.failure
            if graded.failure.startswith("refused:")
            else f"{FAILED}: {graded.failure}"
        )
        table.append([name, "(none)", "(none)", result])
    return table


def grade_folder(
    folder: str | pathlib.Path,
    out: str | pathlib.Path,
    *,
    jobs: int | None = None,
    unsafe: bool = False,
    limits: Limits = DEFAULT_LIMITS,
    seed: int | None = None,
) -> list[str]:
    """Grade every notebook under ``folder``, ``jobs`` at a time; write the CSV ``out``; return the summary lines."""
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise SystemExit(
            f"SUBMISSIONS={folder}: not a folder (give the folder of returned notebooks)"
        )
    paths = sorted(
        path
        for path in folder.rglob("*.ipynb")
        if ".ipynb_checkpoints" not in path.parts
    )
    if not paths:
        raise SystemExit(f"SUBMISSIONS={folder}: no .ipynb files in it")
    jobs = jobs or os.cpu_count() or 1
    if jobs < 1:
        raise SystemExit(f"JOBS={jobs}: give at least 1 notebook at a time")
    if not unsafe:
        reason = sandbox.unavailable()
        if reason is not None:
            raise SystemExit(
                f"cannot sandbox the notebooks: {reason}. Grading untrusted notebooks "
                "without a sandbox lets them read and change your files and the grades; "
                "if you accept that, pass --unsafe (make grade UNSAFE=1)"
            )
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    chapters = release_chapters()
    plan = Plan.drawn(secrets.randbits(32) if seed is None else seed)
    genuine = expected_fingerprints()
    hidden = [folder.resolve(), out.parent.resolve(), *INSTRUCTOR_ONLY]
    graded: dict[pathlib.Path, list[list[str]]] = {}
    lines: list[str] = []
    runner = Runner()
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = {
                pool.submit(
                    grade_notebook, path, chapters, plan, genuine, runner,
                    hidden=hidden, unsafe=unsafe, limits=limits,
                ): path
                for path in paths
            }  # fmt: skip
            for future in concurrent.futures.as_completed(futures):
                path = futures[future]
                name = str(path.relative_to(folder))
                result = future.result()
                graded[path] = table_rows(name, result)
                write_csv(out, [row for p in paths if p in graded for row in graded[p]])
                line = summary_line(shown(name), result)
                print(line, flush=True)
                lines.append(line)
    finally:
        runner.close()
    print(f"wrote {shown(str(out))}")
    return lines


def main(argv: Sequence[str] | None = None) -> None:
    """Grade the folder named on the command line."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("submissions", nargs="?", help="folder of returned notebooks")
    parser.add_argument(
        "--out", default=None, help="CSV to write (default: SUBMISSIONS/grades.csv)"
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
        help="the hidden calls' seed (default: a random one)",
    )
    parser.add_argument(
        "--unsafe",
        action="store_true",
        help="run the notebooks without a sandbox (only for notebooks you trust)",
    )
    args = parser.parse_args(argv)
    limits = Limits(args.timeout, args.max_wall)
    if not args.submissions:
        parser.error("give the folder of returned notebooks")
    grade_folder(
        args.submissions,
        args.out or str(pathlib.Path(args.submissions) / "grades.csv"),
        jobs=args.jobs,
        unsafe=args.unsafe,
        limits=limits,
        seed=args.seed,
    )


if __name__ == "__main__":
    main()
