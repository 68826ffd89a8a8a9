"""Grade returned student notebooks: ``make grade SUBMISSIONS=folder``.

Each ``*.ipynb`` in the folder (and its subfolders) is executed headless, in a
clean kernel, with a time limit; the lines the self-checks print
(``Exercise 2.1 (angles): correct.``) are read from its outputs.  Writes a CSV
(``student file, exercise, part, result`` with result ``passed``, ``not
solved`` or ``wrong``) and prints a one-line summary per notebook.  A notebook
that fails to run (an error in a cell, a timeout, invalid JSON) is reported on
its own CSV row (exercise ``(none)``, result ``failed to run: ...``), never
skipped; the checks it printed before failing still count.  A path that is not
a regular file (a symlink, a FIFO, a device) or is larger than
``MAX_NOTEBOOK_BYTES`` is not opened: its row says ``refused: ...``.

The CSV is rewritten whole after each notebook, atomically (a temporary file
renamed over it), so an interrupted run keeps everything graded so far; a cell
that a spreadsheet would read as a formula (starting with ``=``, ``+``, ``-``,
``@``, a tab or a carriage return) is written with a leading ``'``; names are
printed with control characters escaped.  Notebooks are graded ``JOBS`` at a
time (one per core by default).

Usage: ``python tools/grade.py FOLDER [--out grades.csv] [--timeout 300] [--jobs N]``.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import csv
import io
import os
import pathlib
import stat
import sys
import tempfile
from collections.abc import Iterator, Sequence
from typing import Any

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from twolink.selfcheck import parse_line  # noqa: E402

RESULTS = {"correct": "passed", "not solved yet": "not solved", "wrong": "wrong"}
#: Larger files are refused unread (a chapter notebook with its outputs is ~1 MB).
MAX_NOTEBOOK_BYTES = 50_000_000
#: What a spreadsheet reads as the start of a formula.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
HEADER = ["student file", "exercise", "part", "result"]


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


class HeadlessClient(NotebookClient):
    """Runs a notebook without emulating a widget front end (jupyter/nbclient#312: the emulation can block)."""

    def handle_comm_msg(self, outs: Any, msg: dict[str, Any], cell_index: int) -> None:
        return None


def _output_lines(notebook: Any) -> Iterator[str]:
    for cell in notebook.cells:
        if cell.cell_type != "code":
            continue
        for output in cell.get("outputs", []):
            if output.get("output_type") == "stream":
                yield from "".join(output.get("text", "")).splitlines()


def grade_notebook(
    path: str | pathlib.Path, timeout: float = 300, kernel_name: str = "python3"
) -> tuple[list[tuple[str, str, str]], str | None]:
    """Run one notebook; return ``(rows, failure)``: rows ``(exercise, part, result)``, failure a str or None."""
    try:
        notebook = nbformat.read(path, as_version=4)
    except Exception as error:  # invalid JSON, not a notebook
        return (
            [],
            f"unreadable ({type(error).__name__}: {str(error).splitlines()[0] if str(error) else ''})",
        )
    failure: str | None = None
    client = HeadlessClient(
        notebook,
        timeout=timeout,
        kernel_name=kernel_name,
        resources={"metadata": {"path": str(ROOT / "notebooks")}},
    )
    try:
        client.execute()
    except CellTimeoutError:
        failure = f"timeout (a cell ran longer than {timeout} s)"
    except CellExecutionError as error:
        failure = f"error: {error.ename}: {error.evalue}"[:200]
    except DeadKernelError:
        failure = "the kernel died"
    except Exception as error:  # the kernel could not start, and the like
        failure = f"{type(error).__name__}: {error}"[:200]
    rows: list[tuple[str, str, str]] = []
    for line in _output_lines(notebook):
        parsed = parse_line(line)
        if parsed:
            number, part, status = parsed
            rows.append((number, part, RESULTS[status]))
    return rows, failure


def summary_line(
    name: str, rows: Sequence[tuple[str, str, str]], failure: str | None
) -> str:
    """One line: the file, how many parts passed / not solved / wrong, and any failure."""
    counts = {
        result: sum(1 for row in rows if row[2] == result)
        for result in RESULTS.values()
    }
    text = f"{name}: {counts['passed']} passed, {counts['not solved']} not solved, {counts['wrong']} wrong"
    if failure and failure.startswith("refused:"):
        return f"{name}: {failure.upper()[:7]}{failure[7:]}"
    return text + (f"; FAILED TO RUN: {failure}" if failure else "")


def _grade_one(
    path: pathlib.Path, timeout: float
) -> tuple[list[tuple[str, str, str]], str | None]:
    reason = refusal(path)
    if reason is not None:
        return [], reason
    return grade_notebook(path, timeout=timeout)


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


def grade_folder(
    folder: str | pathlib.Path,
    out: str | pathlib.Path,
    timeout: float = 300,
    jobs: int | None = None,
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
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    graded: dict[pathlib.Path, list[list[str]]] = {}
    lines: list[str] = []
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(_grade_one, path, timeout): path for path in paths}
        for future in concurrent.futures.as_completed(futures):
            path = futures[future]
            name = str(path.relative_to(folder))
            rows, failure = future.result()
            table = [[name, number, part, result] for number, part, result in rows]
            if failure:
                result = (
                    failure
                    if failure.startswith("refused:")
                    else f"failed to run: {failure}"
                )
                table.append([name, "(none)", "(none)", result])
            graded[path] = table
            write_csv(out, [row for p in paths if p in graded for row in graded[p]])
            line = summary_line(shown(name), rows, failure)
            print(line, flush=True)
            lines.append(line)
    print(f"wrote {shown(str(out))}")
    return lines


def main(argv: Sequence[str] | None = None) -> None:
    """Grade the folder named on the command line."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("submissions", help="folder of returned notebooks")
    parser.add_argument(
        "--out", default=None, help="CSV to write (default: SUBMISSIONS/grades.csv)"
    )
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per cell")
    parser.add_argument(
        "--jobs",
        type=int,
        default=None,
        help="notebooks graded at a time (default: one per core)",
    )
    args = parser.parse_args(argv)
    grade_folder(
        args.submissions,
        args.out or str(pathlib.Path(args.submissions) / "grades.csv"),
        args.timeout,
        args.jobs,
    )


if __name__ == "__main__":
    main()
