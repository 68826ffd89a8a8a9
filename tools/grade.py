"""Grade returned student notebooks: ``make grade SUBMISSIONS=folder``.

Each ``*.ipynb`` in the folder (and its subfolders) is executed headless, in a
clean kernel, with a time limit; the lines the self-checks print
(``Exercise 2.1 (angles): correct.``) are read from its outputs.  Writes a CSV
(``student file, exercise, part, result`` with result ``passed``, ``not
solved`` or ``wrong``) and prints a one-line summary per notebook.  A notebook
that fails to run (an error in a cell, a timeout, invalid JSON) is reported on
its own CSV row (exercise ``-``, result ``failed to run: ...``), never skipped;
the checks it printed before failing still count.

Usage: ``python tools/grade.py FOLDER [--out grades.csv] [--timeout 300]``.
"""

from __future__ import annotations

import argparse
import csv
import pathlib
import sys
from collections.abc import Iterator, Sequence
from typing import Any

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from twolink.selfcheck import parse_line  # noqa: E402

RESULTS = {"correct": "passed", "not solved yet": "not solved", "wrong": "wrong"}


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
    return text + (f"; FAILED TO RUN: {failure}" if failure else "")


def grade_folder(
    folder: str | pathlib.Path, out: str | pathlib.Path, timeout: float = 300
) -> list[str]:
    """Grade every notebook under ``folder``; write the CSV ``out``; return the summary lines."""
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
    lines: list[str] = []
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["student file", "exercise", "part", "result"])
        for path in paths:
            name = str(path.relative_to(folder))
            rows, failure = grade_notebook(path, timeout=timeout)
            for number, part, result in rows:
                writer.writerow([name, number, part, result])
            if failure:
                writer.writerow([name, "-", "-", f"failed to run: {failure}"])
            line = summary_line(name, rows, failure)
            print(line, flush=True)
            lines.append(line)
    print(f"wrote {out}")
    return lines


def main(argv: Sequence[str] | None = None) -> None:
    """Grade the folder named on the command line."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("submissions", help="folder of returned notebooks")
    parser.add_argument(
        "--out", default=None, help="CSV to write (default: SUBMISSIONS/grades.csv)"
    )
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per cell")
    args = parser.parse_args(argv)
    grade_folder(
        args.submissions,
        args.out or str(pathlib.Path(args.submissions) / "grades.csv"),
        args.timeout,
    )


if __name__ == "__main__":
    main()
