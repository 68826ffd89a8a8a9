"""Grading time per chapter: each chapter run headless up to its last self-check, switch off and on.

The grader (``make grade``) runs every returned chapter in a fresh kernel and
reads only the self-checks, so it runs the cells up to the last
``selfcheck.check(`` cell.  This script does the same with nbclient (outputs
cleared first; the kernel in ``notebooks/``; comm messages ignored, no widget
front end, as the grader does) in these settings:

- ``off``: as taught (``TWOLINK_GRADING`` and ``MPLBACKEND`` unset: the inline
  backend, figures rendered to PNG, videos encoded, explorers drawn);
- ``on``: ``TWOLINK_GRADING=1`` (:mod:`twolink_course.runmode`: no video, no explorer
  picture, no figure PNG, one call per timing);
- ``on, agg``: the switch and ``MPLBACKEND=agg`` (``plt.show()`` shows nothing);
- ``on, 1 BLAS thread`` (``--all``): the switch and ``OPENBLAS_NUM_THREADS=1``
  (OpenBLAS's threads wait for work spinning: with two kernels on two cores
  they could take turns on them);
- ``off, agg`` (``--all``): ``MPLBACKEND=agg`` alone.

Each cell of the table is the median over ``--runs`` fresh kernels of the
wall time of one notebook, the kernel's start included (what one grading job
costs); the settings take turns, so all see the same load.  Every run's
self-check lines (the check cells' printed output) are compared with the
``off`` run's: "same checks" says whether they were identical in every run.
The last row projects a class from those sequential times: 50 students x 7
chapters, two notebooks at a time (the chapters' sum x 50 / 2, a floor: two
kernels on two cores contend).  The throughput table measures it instead:
every chapter ``--rounds`` times, ``--jobs`` notebooks at a time, each in a
worker process with a fresh kernel, off and on (and on with one BLAS thread
with ``--all``; the real grader adds its sandbox and its probes).
``--cells`` also lists, per chapter, the cells above 0.2 s in the ``off`` and
``on`` runs and what makes each heavy.

Run with ``.venv/bin/python benchmarks/bench_grading.py`` (``--chapters 03 07``
for some, ``--runs 5``, ``--cells``; ``--quick``: chapter 1, one run, off and
on).  Timings are printed, never asserted (``tests/course/test_runmode.py`` checks
that the switch leaves every self-check line unchanged).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import multiprocessing
import os
import platform
import re
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tools")]

import course_map  # noqa: E402

from twolink_course.display import markdown_table  # noqa: E402
from twolink_course.runmode import VARIABLE  # noqa: E402

#: A check cell: its stream output is what the grader reads.
CHECK = "selfcheck.check("
#: Settings: name -> environment variables added to the kernel's (both are removed first).
SETTINGS = {
    "off": {},
    "on": {VARIABLE: "1"},
    "on, agg": {VARIABLE: "1", "MPLBACKEND": "agg"},
    "on, 1 BLAS thread": {VARIABLE: "1", "OPENBLAS_NUM_THREADS": "1"},
    "off, agg": {"MPLBACKEND": "agg"},
}
#: Variables the settings control, removed from the kernel's environment first.
CONTROLLED = ("MPLBACKEND", VARIABLE, "OPENBLAS_NUM_THREADS")
#: The settings of the throughput table.
PARALLEL_SETTINGS = ("off", "on", "on, 1 BLAS thread")
#: A cell slower than this is listed by ``--cells``, seconds.
HEAVY_SECONDS = 0.2
#: The class the grader must grade in ``TARGET_MINUTES``, two notebooks at a time.
STUDENTS, TARGET_MINUTES, JOBS = 50, 15, 2
#: Longest a cell may run here, seconds (a budget: a hung cell fails the run).
CELL_TIMEOUT = 300

#: What makes a cell heavy, from its code: (pattern, reason), every match listed.
REASONS = [
    (r"animation_html", "animation (an H.264 video when off)"),
    (
        r"explorer\.Explorer\(|explorer_figure\(",
        "explorer (ipympl canvas and a draw when off)",
    ),
    (r"^# NBVAL_IGNORE_OUTPUT\n\w*explorer\w*\s*$", "explorer shown (a PNG when off)"),
    (r"timing\.\w+\(", "timing (calibrated batches when off)"),
    (r"plt\.show\(\)", "figure (a PNG when off)"),
    (r"^\s*(import|from) \w", "imports"),
    (r"\bsp\.|symbolic\.|\bme\.", "sympy"),
    (r"engine\.|mujoco", "MuJoCo"),
    (r"simulate\(|trajectory\.|ik\.", "simulation or IK sweep"),
]


class HeadlessClient(NotebookClient):
    """Runs a notebook without emulating a widget front end, as the grader does."""

    def handle_comm_msg(self, outs: Any, msg: dict[str, Any], cell_index: int) -> None:
        return None


def graded_part(path: Path) -> Any:
    """The notebook up to its last check cell, outputs cleared."""
    notebook = nbformat.read(path, as_version=4)
    checks = [
        index
        for index, cell in enumerate(notebook.cells)
        if cell.cell_type == "code" and CHECK in cell.source
    ]
    if not checks:
        raise ValueError(f"{path.name} has no {CHECK} cell")
    notebook.cells = notebook.cells[: checks[-1] + 1]
    for cell in notebook.cells:
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
    return notebook


def kernel_environment(setting: str) -> dict[str, str]:
    env = {key: value for key, value in os.environ.items() if key not in CONTROLLED}
    env.update(SETTINGS[setting])
    return env


def _seconds(cell: Any) -> float:
    stamps = cell.metadata.get("execution", {})
    start, end = stamps.get("iopub.execute_input"), stamps.get("shell.execute_reply")
    if not (start and end):
        return 0.0
    parse = datetime.datetime.fromisoformat
    return (
        parse(end.replace("Z", "+00:00")) - parse(start.replace("Z", "+00:00"))
    ).total_seconds()


def check_lines(notebook: Any) -> list[str]:
    """The lines the check cells printed (stream outputs), in order."""
    lines = []
    for cell in notebook.cells:
        if cell.cell_type == "code" and CHECK in cell.source:
            for output in cell.outputs:
                if output.get("output_type") == "stream":
                    lines += "".join(output.get("text", "")).splitlines()
    return lines


def run(path: Path, setting: str) -> dict[str, Any]:
    """One fresh kernel: wall seconds, the check lines, the per-cell seconds, a failure or None."""
    notebook = graded_part(path)
    client = HeadlessClient(
        notebook,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        record_timing=True,
        resources={"metadata": {"path": str(ROOT / "notebooks")}},
    )
    failure = None
    start = time.perf_counter()
    try:
        client.execute(env=kernel_environment(setting))
    except CellExecutionError as error:
        failure = f"{error.ename}: {error.evalue}"[:120]
    seconds = time.perf_counter() - start
    cells = [
        (index, _seconds(cell), cell.source)
        for index, cell in enumerate(notebook.cells)
        if cell.cell_type == "code"
    ]
    return {
        "seconds": seconds,
        "checks": check_lines(notebook),
        "cells": cells,
        "failure": failure,
    }


def _timed_run(path: Path, setting: str) -> tuple[float, bool]:
    """One notebook in a worker process: its wall seconds and whether it ran through."""
    result = run(path, setting)
    return result["seconds"], result["failure"] is None


def _started(seconds: float) -> int:
    """A worker's first task: it is up (its imports done) and waits, so each worker gets one."""
    time.sleep(seconds)
    return os.getpid()


def throughput(
    pool: concurrent.futures.Executor, paths: list[Path], setting: str, rounds: int
) -> tuple[int, float, int]:
    """Every chapter ``rounds`` times through ``pool``: (notebooks, wall seconds, failures)."""
    work = [path for _ in range(rounds) for path in paths]
    start = time.perf_counter()
    done = list(pool.map(_timed_run, work, [setting] * len(work)))
    wall = time.perf_counter() - start
    return len(work), wall, sum(not ran for _, ran in done)


def cell_text(text: str) -> str:
    """``text`` as one markdown table cell (no bar, no line break)."""
    return " ".join(text.split()).replace("|", "\\|")


def reasons(source: str) -> str:
    found = [
        reason
        for pattern, reason in REASONS
        if re.search(pattern, source, flags=re.MULTILINE)
    ]
    return ", ".join(dict.fromkeys(found)) or "computation"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--chapters", nargs="*", help="chapter numbers, e.g. 03 07")
    parser.add_argument(
        "--runs", type=int, default=3, help="fresh kernels per chapter and setting"
    )
    parser.add_argument(
        "--all", action="store_true", help="also MPLBACKEND=agg without the switch"
    )
    parser.add_argument(
        "--cells", action="store_true", help="list the cells above 0.2 s"
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=JOBS,
        help=f"notebooks at a time for the throughput rows (default {JOBS}; 0: none)",
    )
    parser.add_argument(
        "--rounds",
        type=int,
        default=2,
        help="times each chapter is graded in the throughput rows (default 2)",
    )
    parser.add_argument(
        "--quick", action="store_true", help="chapter 1, one run, off and on"
    )
    args = parser.parse_args(argv)
    if not 1 <= args.runs <= 50:
        parser.error(f"--runs must be 1 to 50; got {args.runs}")
    if not 0 <= args.jobs <= 16 or not 1 <= args.rounds <= 20:
        parser.error("--jobs must be 0 to 16 and --rounds 1 to 20")
    paths = course_map.chapters(ROOT / "notebooks")
    settings = ["off", "on", "on, agg"] + (
        ["on, 1 BLAS thread", "off, agg"] if args.all else []
    )
    if args.quick:
        paths, args.runs, settings, args.jobs = paths[:1], 1, ["off", "on"], 0
    elif args.chapters:
        paths = [path for path in paths if path.name[:2] in args.chapters]
    if not paths:
        parser.error("no chapter matched --chapters")

    results: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for _ in range(args.runs):
        for path in paths:
            for setting in settings:
                results.setdefault((path.name, setting), []).append(run(path, setting))

    print(
        f"# Grading time per chapter, up to its last self-check: median of {args.runs} "
        f"fresh kernel(s), kernel start included ({platform.machine()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, load average "
        f"{os.getloadavg()[0]:.1f} at the end)\n"
    )
    rows, totals = [], {setting: 0.0 for setting in settings}
    for path in paths:
        reference = results[(path.name, "off")][0]["checks"]
        row: list[str] = [path.stem]
        same = True
        for setting in settings:
            runs = results[(path.name, setting)]
            failed = [r["failure"] for r in runs if r["failure"]]
            median = statistics.median(r["seconds"] for r in runs)
            totals[setting] += median
            row.append(
                f"{median:.2f}"
                + (f" (failed: {cell_text(failed[0])})" if failed else "")
            )
            same = same and all(r["checks"] == reference for r in runs)
        row += [str(len(reference)), "yes" if same and reference else "NO"]
        rows.append(row)
    count = len(paths)
    rows.append(
        ["mean per notebook"]
        + [f"{totals[s] / count:.2f}" for s in settings]
        + ["", ""]
    )
    if count == 7:  # the whole course: what a class costs
        rows.append(
            [f"{STUDENTS} students x 7, {JOBS} at a time [min]"]
            + [f"{STUDENTS * totals[s] / JOBS / 60:.1f}" for s in settings]
            + [f"target {TARGET_MINUTES}", ""]
        )
    print(
        markdown_table(
            ["chapter", *(f"{s} [s]" for s in settings), "check lines", "same checks"],
            rows,
        )
    )
    if args.jobs:
        rows = []
        # spawned, not forked: the parent holds ZeroMQ sockets a fork must not share
        context = multiprocessing.get_context("spawn")
        with concurrent.futures.ProcessPoolExecutor(
            args.jobs, mp_context=context
        ) as pool:
            # the workers started before the clock does, as a grader's pool is
            list(pool.map(_started, [1.0] * args.jobs))
            measured = {
                setting: throughput(pool, paths, setting, args.rounds)
                for setting in PARALLEL_SETTINGS
                if setting in settings
            }
        for setting, (notebooks, wall, failures) in measured.items():
            per_notebook = wall / notebooks
            rows.append(
                [
                    setting,
                    str(notebooks),
                    str(args.jobs),
                    f"{wall:.1f}",
                    f"{per_notebook:.2f}",
                    f"{60 * notebooks / wall:.1f}",
                    f"{STUDENTS * 7 * per_notebook / 60:.1f}",
                    str(failures),
                ]
            )
        print(
            f"\n# Throughput: the chapters above, {args.rounds} time(s) each, "
            f"{args.jobs} at a time (a worker process each, a fresh kernel per notebook); target "
            f"{STUDENTS * 7} notebooks in {TARGET_MINUTES} min\n"
        )
        print(
            markdown_table(
                [
                    "setting",
                    "notebooks",
                    "at a time",
                    "wall [s]",
                    "wall per notebook [s]",
                    "notebooks per minute",
                    f"{STUDENTS * 7} notebooks [min]",
                    "failed",
                ],
                rows,
            )
        )
    if args.cells:
        for path in paths:
            print(f"\n## {path.stem}: cells above {HEAVY_SECONDS:g} s (first run)\n")
            listed = []
            for setting in ("off", "on"):
                for index, seconds, source in results[(path.name, setting)][0]["cells"]:
                    if seconds > HEAVY_SECONDS:
                        first = cell_text(source.splitlines()[0][:60]) if source else ""
                        listed.append(
                            [
                                setting,
                                str(index),
                                f"{seconds:.2f}",
                                reasons(source),
                                first,
                            ]
                        )
            print(
                markdown_table(
                    ["setting", "cell", "seconds", "heavy because", "first line"],
                    listed,
                )
                if listed
                else "none"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
