"""Run one graded notebook, isolated: a process of its own, its kernel in the sandbox, limits on time and output.

:class:`Runner` (used by ``tools/grade.py``) runs each notebook's
:func:`run_one` in a worker process of the grader's (one per notebook graded
at a time, started once: their imports cost a second each), waits at most
the notebook's time limit and a minute more, and kills the worker otherwise;
the kernel's sandbox (``bwrap --die-with-parent``) dies with it, and a new
worker takes its place.  Workers ignore Ctrl-C: the grader stops them
(:meth:`Runner.close`).  Workers are started with ``multiprocessing``'s
"spawn": a script that calls the grader must do so under ``if __name__ ==
"__main__":``.

:func:`run_one` runs the notebook with its kernel in the sandbox
(:class:`sandbox.SandboxKernelManager`: every cell's time limited, the whole
notebook's time limited by a watchdog, the outputs' size limited), its
temporary folders in the grader's scratch folder (mode 0700), and returns
only data: each probe cell's outputs (``tools/grading_probe.py``), the
cells that raised (numbered as in the returned file), the limits the
notebook ran into, in words, the CPU time it used (where control groups
count it) and why the run stopped early, if it did.

This module imports no numpy and no twolink: the grader's processes stay light.
"""

from __future__ import annotations

import dataclasses
import json
import multiprocessing
import os
import pathlib
import queue
import shutil
import signal
import subprocess
import tempfile
import threading
from collections.abc import Sequence
from typing import Any

import grading_probe  # tools/grading_probe.py (standard library only at import)
import nbformat
import sandbox  # tools/sandbox.py
from jupyter_client.manager import AsyncKernelManager
from jupyter_core.utils import run_sync
from nbclient import NotebookClient
from nbclient.exceptions import CellTimeoutError, DeadKernelError

#: The tag of the grader's probe cells (``grade_build.PROBE_TAG``).
PROBE_TAG = "grader-probe"
#: Set in every kernel: the package skips heavy cells that no answer needs.
VARIABLES = {"TWOLINK_GRADING": "1"}
#: The workers are fresh interpreters (a fork of the grader's threads could inherit a held lock).
CONTEXT = multiprocessing.get_context("spawn")


class OutputFlood(Exception):
    """A notebook's outputs grew past the limit."""


class HeadlessClient(NotebookClient):
    """Runs a notebook without a widget front end, counting the bytes of its outputs.

    Widget messages are ignored (jupyter/nbclient#312: emulating a front end
    can block); past ``max_output_bytes`` of outputs the run stops
    (:class:`OutputFlood`), so a flood of prints cannot fill the grader's memory.
    """

    max_output_bytes = 20_000_000

    def handle_comm_msg(self, outs: Any, msg: dict[str, Any], cell_index: int) -> None:
        return None

    def output(
        self, outs: Any, msg: dict[str, Any], display_id: Any, cell_index: int
    ) -> Any:
        self._output_bytes = getattr(self, "_output_bytes", 0) + len(
            json.dumps(msg.get("content", {}), default=str)
        )
        if self._output_bytes > self.max_output_bytes:
            raise OutputFlood(
                f"its outputs passed {self.max_output_bytes} bytes (the output limit)"
            )
        return super().output(outs, msg, display_id, cell_index)


@dataclasses.dataclass(frozen=True)
class Limits:
    """The time limits of one notebook (its resources: ``sandbox.Limits``)."""

    cell_seconds: float = 120.0
    notebook_seconds: float = 600.0
    resources: sandbox.Limits = sandbox.Limits()

    @property
    def overrun(self) -> str:
        """Why a notebook stopped at its time limit.

        >>> Limits(10, 60).overrun
        "stopped after 60 s (the notebook's time limit)"
        """
        return f"stopped after {self.notebook_seconds:g} s (the notebook's time limit)"


#: The time limits of ``make grade``.
DEFAULT_LIMITS = Limits()


@dataclasses.dataclass(frozen=True)
class Setting:
    """Where and how notebooks run: the scratch folder (0700), the sandbox's means (None: unsafe)."""

    scratch: pathlib.Path
    isolation: sandbox.Isolation | None
    limits: Limits = DEFAULT_LIMITS


def make_scratch() -> pathlib.Path:
    """The grader's scratch folder: every temporary folder of a run, readable by the grader alone."""
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="twolink-grade-")).resolve()
    scratch.chmod(0o700)
    return scratch


def remove_scratch(setting: Setting) -> None:
    """Remove the scratch folder, and any control group a killed worker left."""
    cgroups = setting.isolation.cgroups if setting.isolation else None
    if cgroups is not None:
        token = setting.scratch.name
        for folder in set(cgroups.folders.values()):
            for group in pathlib.Path(folder).glob(f"kernel-*-{token}-*"):
                sandbox.NotebookGroup(cgroups.version, {"any": group}).remove()
    shutil.rmtree(setting.scratch, ignore_errors=True)


def _manager(
    setting: Setting, workdir: pathlib.Path, submission: pathlib.Path | None
) -> AsyncKernelManager:
    if setting.isolation is None:
        return AsyncKernelManager(kernel_name="python3")
    return sandbox.SandboxKernelManager(
        workdir,
        setting.isolation,
        setting.limits.resources,
        user=sandbox.user_for(os.getpid()),  # one user per notebook running at once
        variables=VARIABLES,
        submission=submission,
        group_name=f"{setting.scratch.name}-{os.getpid()}",
    )


def execute(
    notebook: Any,
    setting: Setting,
    workdir: pathlib.Path,
    submission: pathlib.Path | None = None,
) -> tuple[str | None, dict[str, Any]]:
    """Run ``notebook`` in place; why it stopped early (or None), and what it used (its groups' counts)."""
    limits = setting.limits
    manager = _manager(setting, workdir, submission)
    client = HeadlessClient(
        notebook,
        km=manager,
        timeout=limits.cell_seconds,
        allow_errors=True,
        interrupt_on_timeout=True,
        resources={"metadata": {"path": str(workdir)}},
    )
    stopped = threading.Event()

    def stop() -> None:  # the whole notebook's budget
        stopped.set()
        process = getattr(manager.provisioner, "process", None)
        if process is not None:
            process.kill()

    watchdog = threading.Timer(limits.notebook_seconds, stop)
    watchdog.start()
    failure: str | None = None
    used: dict[str, Any] = {}
    environment_before = dict(os.environ)
    if setting.isolation is None:
        os.environ.update(VARIABLES)
    try:
        # the kernel's own stdout and stderr go nowhere: never to the teacher's terminal
        client.execute(
            cwd=str(workdir), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
    except DeadKernelError:
        failure = limits.overrun if stopped.is_set() else "the kernel died"
    except CellTimeoutError:
        failure = f"a cell ran longer than {limits.cell_seconds:g} s and could not be interrupted"
    except OutputFlood as error:
        failure = str(error)
    except Exception as error:  # the kernel could not start, and the like
        failure = (
            limits.overrun
            if stopped.is_set()
            else f"{type(error).__name__}: {error}"[:300]
        )
    finally:
        watchdog.cancel()
        os.environ.clear()
        os.environ.update(environment_before)
        # a kernel manager handed to nbclient is ours to stop: the kernel and,
        # in the sandbox, everything it started
        try:
            if manager.has_kernel:
                run_sync(manager.shutdown_kernel)(now=True)
        finally:
            if isinstance(manager, sandbox.SandboxKernelManager):
                used = manager.finish()
    return failure, used


def probe_reports(notebook: Any) -> dict[str, dict[str, Any]]:
    """By exercise: ``visible``, the probe's first report (a dict), or ``"silent"`` (it ran,
    published nothing) or ``"not run"``; ``draws``, its reports on hidden inputs by draw."""
    reports: dict[str, dict[str, Any]] = {}
    for cell in notebook.cells:
        if PROBE_TAG not in cell.metadata.get("tags", []):
            continue
        number = str(cell.metadata.get("twolink_probe", ""))
        found: dict[str, Any] = {
            "visible": "not run"
            if cell.get("execution_count") is None and not cell.outputs
            else "silent",
            "draws": {},
        }
        for output in cell.outputs:
            data = output.get("data", {}).get(grading_probe.MIME)
            if not isinstance(data, dict) or data.get("exercise") != number:
                continue
            if "draw" in data and isinstance(data["draw"], int):
                found["draws"].setdefault(data["draw"], data)
            elif not isinstance(found["visible"], dict):
                found["visible"] = data
        reports[number] = found
    return reports


def cell_errors(notebook: Any, positions: Sequence[int | None]) -> list[str]:
    """``cell N: Name: value`` for each of the returned notebook's cells that raised (N as in its file, from 1)."""
    errors = []
    for cell, position in zip(notebook.cells, positions):
        if PROBE_TAG in cell.metadata.get("tags", []):
            continue
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                where = f"cell {position}" if position else "a cell the grader put back"
                errors.append(
                    f"{where}: {output.get('ename', '?')}: {output.get('evalue', '')}"[
                        :200
                    ]
                )
    return errors


def run_one(
    notebook: Any,
    positions: Sequence[int | None],
    submission: bytes | None,
    setting: Setting,
) -> dict[str, Any]:
    """Run the graded ``notebook`` in a folder of its own in the scratch folder: its probes'
    reports, its cells' errors, the limits it ran into, its CPU time, why it stopped."""
    workdir = pathlib.Path(tempfile.mkdtemp(prefix="notebook-", dir=setting.scratch))
    try:
        copy = None
        if submission is not None:
            copy = workdir / "submission.ipynb"
            copy.write_bytes(submission)
            copy.chmod(0o644)
        failure, used = execute(notebook, setting, workdir, copy)
        errors = cell_errors(notebook, positions)
        limits = setting.limits.resources
        return {
            "reports": probe_reports(notebook),
            "errors": errors,
            "failure": failure,
            "limits": sandbox.overruns(used, limits)
            + sandbox.full_disk(errors, limits),
            "cpu_seconds": used.get("cpu_seconds"),
        }
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def _serve(connection: Any) -> None:
    """A worker's loop: run each notebook sent, send back what :func:`run_one` returns; stop at ``None``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the grader's to handle
    while True:
        try:
            task = connection.recv()
        except EOFError:  # the grader went away
            return
        if task is None:
            return
        notebook_text, positions, submission, setting = task
        # built by the grader: not validated again
        notebook = nbformat.from_dict(json.loads(notebook_text))
        connection.send(run_one(notebook, positions, submission, setting))


class Worker:
    """A process of the grader's that runs notebooks one after another; killed (and its sandbox with it) when one overruns."""

    def __init__(self) -> None:
        self.connection, child_end = CONTEXT.Pipe()
        self.process = CONTEXT.Process(target=_serve, args=(child_end,), daemon=True)
        self.process.start()
        child_end.close()
        # stop() is called from two threads on Ctrl-C (the grader's, and the one waiting on
        # this worker, which then sees the pipe end): its connection is closed once
        self._stopping = threading.Lock()

    def run(
        self,
        notebook: Any,
        positions: Sequence[int | None],
        submission: bytes | None,
        setting: Setting,
    ) -> dict[str, Any]:
        """What :func:`run_one` returns for ``notebook``; if the worker died or overran, a failure saying so (and it is stopped)."""
        try:
            self.connection.send(
                (json.dumps(notebook), list(positions), submission, setting)
            )
            if not self.connection.poll(setting.limits.notebook_seconds + 60):
                self.stop()
                return {"failure": setting.limits.overrun}
            ran = self.connection.recv()
            if isinstance(ran, dict):
                return ran
        except (EOFError, OSError):  # it died
            pass
        self.stop()
        return {
            "failure": f"the grader's process for it ended with code {self.process.exitcode}"
        }

    @property
    def usable(self) -> bool:
        """Whether it can run another notebook."""
        return self.process.is_alive() and not self.connection.closed

    def stop(self) -> None:
        """End the process (and so any sandbox it still holds); safe from several threads at once."""
        with self._stopping:
            if self.process.is_alive():
                self.process.kill()
            self.process.join(30)
            if not self.connection.closed:
                self.connection.close()


class Runner:
    """Workers for notebooks run ``jobs`` at a time: each started once (its imports paid once), replaced when stopped."""

    def __init__(self, setting: Setting) -> None:
        self.setting = setting
        self._idle: queue.SimpleQueue[Worker] = queue.SimpleQueue()
        self._all: list[Worker] = []
        self._lock = threading.Lock()
        self.closed = False

    def run(
        self,
        notebook: Any,
        positions: Sequence[int | None] = (),
        submission: bytes | None = None,
    ) -> dict[str, Any]:
        """:func:`run_one` for ``notebook`` in an idle worker; a failure saying why if the worker died or overran."""
        worker = self._idle_worker()
        if worker is None:
            with self._lock:
                if self.closed:
                    return {"failure": "grading was stopped (Ctrl-C)"}
                worker = Worker()
                self._all.append(worker)
        ran = worker.run(
            notebook,
            positions or range(1, len(notebook.cells) + 1),
            submission,
            self.setting,
        )
        if self.closed:
            return {"failure": "grading was stopped (Ctrl-C)"}
        if worker.usable:
            self._idle.put(worker)
        return ran

    def _idle_worker(self) -> Worker | None:
        """An idle worker still usable (stopped ones are dropped), or None."""
        while True:  # ends: the queue only shrinks here
            try:
                worker = self._idle.get_nowait()
            except queue.Empty:
                return None
            if worker.usable:
                return worker

    def close(self) -> None:
        """Stop every worker (a notebook running is stopped with it)."""
        with self._lock:
            self.closed = True
            for worker in self._all:
                worker.stop()
            self._all.clear()


def run_isolated(notebook: Any, setting: Setting) -> dict[str, Any]:
    """:func:`run_one` for one notebook in a worker of its own (a :class:`Runner` runs many)."""
    runner = Runner(setting)
    try:
        return runner.run(notebook)
    finally:
        runner.close()


def genuine_kernel(runner: Runner, probe_source: str) -> dict[str, Any]:
    """What a kernel started as the notebooks' are sees: the probe's fingerprints, the packages' files.

    Runs one cell in one of ``runner``'s workers (which goes on to grade notebooks),
    as a notebook runs, with ``probe_source`` (the probe as the notebooks run it); a
    kernel that cannot start gives ``{"failure": why}``.
    """
    code = (
        "import json, sys, twolink, twolink_course.selfcheck\n"
        "from IPython import get_ipython\n"
        "from IPython.display import publish_display_data\n"
        "_probe = {'__name__': 'grader_probe'}\n"
        f"exec(compile({probe_source!r}, '<grader probe>', 'exec'), _probe)\n"
        "publish_display_data({%r: {'exercise': 'setup', 'fingerprints': _probe['fingerprints'](get_ipython()),"
        " 'files': {'twolink': twolink.__file__, 'twolink_course': twolink_course.__file__,"
        " 'python': sys.executable}}})\n" % grading_probe.MIME
    )
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
    notebook.cells[0].metadata["tags"] = [PROBE_TAG]
    notebook.cells[0].metadata["twolink_probe"] = "setup"
    ran = runner.run(notebook)
    report = ran.get("reports", {}).get("setup", {}).get("visible")
    if not isinstance(report, dict):
        why = (
            ran.get("failure")
            or "; ".join(ran.get("errors") or [])
            or "it published nothing"
        )
        return {"failure": why}
    return report
