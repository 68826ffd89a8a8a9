"""Run one graded notebook, isolated: a process of its own, its kernel in the sandbox, limits on time and output.

:class:`Runner` (used by ``tools/grade.py``) runs each notebook's
:func:`run_one` in a worker process of the grader's (one per notebook graded
at a time, started once: their imports cost a second each), waits at most
the notebook's time limit and a minute more, and kills the worker otherwise;
the kernel's sandbox (``bwrap --die-with-parent``) dies with it, and a new
worker takes its place.  Workers are started with ``multiprocessing``'s
"spawn": a script that calls the grader must do so under
``if __name__ == "__main__":``.  :func:`run_one` runs the notebook in a
temporary folder of its own (:func:`execute`: nbclient, the kernel started
by ``sandbox.SandboxKernelManager``, every cell's time limited, the whole
notebook's time limited by a watchdog, the outputs' size limited) and
returns only data: each probe cell's report (``tools/grading_probe.py``),
the cells that raised, and why the run stopped early, if it did.

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

#: The tag of the grader's probe cells.
PROBE_TAG = "grader-probe"
#: Set in every sandbox: the package skips heavy cells that no answer needs.
ENVIRONMENT = {"TWOLINK_GRADING": "1"}
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
    """The time limits of one notebook (the sandbox's own limits are in ``sandbox.Limits``)."""

    cell_seconds: float = 120.0
    notebook_seconds: float = 600.0

    @property
    def overrun(self) -> str:
        """Why a notebook stopped at its time limit.

        >>> Limits(10, 60).overrun
        "stopped after 60 s (the notebook's time limit)"
        """
        return f"stopped after {self.notebook_seconds:g} s (the notebook's time limit)"


#: The time limits of ``make grade``.
DEFAULT_LIMITS = Limits()


def execute(
    notebook: Any,
    workdir: pathlib.Path,
    *,
    unsafe: bool,
    hidden: Sequence[pathlib.Path],
    limits: Limits,
) -> str | None:
    """Run ``notebook`` in place, in ``workdir`` (in the sandbox unless ``unsafe``); why it stopped early, or None."""
    if unsafe:
        manager: AsyncKernelManager = AsyncKernelManager(kernel_name="python3")
    else:
        manager = sandbox.SandboxKernelManager(
            workdir,
            hidden=hidden,
            limits=sandbox.Limits(cpu_seconds=int(limits.notebook_seconds)),
            user=sandbox.user_for(os.getpid()),  # one user per notebook running at once
            environment=ENVIRONMENT,
        )
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
    environment_before = dict(os.environ)
    if unsafe:
        os.environ.update(ENVIRONMENT)
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
                manager.cleanup_runtime()
    return failure


def probe_reports(notebook: Any) -> dict[str, Any]:
    """Each probe cell's report (a dict), or ``"silent"`` (it ran, published nothing) or ``"not run"``, by exercise."""
    reports: dict[str, Any] = {}
    for cell in notebook.cells:
        if PROBE_TAG not in cell.metadata.get("tags", []):
            continue
        number = cell.id.removeprefix("grader-probe-").replace("-", ".")
        found: Any = (
            "not run"
            if cell.get("execution_count") is None and not cell.outputs
            else "silent"
        )
        for output in cell.outputs:
            data = output.get("data", {}).get(grading_probe.MIME)
            if isinstance(data, dict) and data.get("exercise") == number:
                found = data
        reports[number] = found
    return reports


def cell_errors(notebook: Any) -> list[str]:
    """``cell N: Name: value`` for each of the submission's cells that raised (N counted from 1, the probes not counted)."""
    errors = []
    position = 0
    for cell in notebook.cells:
        if PROBE_TAG in cell.metadata.get("tags", []):
            continue
        position += 1
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                errors.append(
                    f"cell {position}: {output.get('ename', '?')}: {output.get('evalue', '')}"[
                        :200
                    ]
                )
    return errors


def run_one(
    notebook: Any, hidden: Sequence[pathlib.Path], unsafe: bool, limits: Limits
) -> dict[str, Any]:
    """Run the graded ``notebook`` in a temporary folder of its own: its probes' reports, its cells' errors, why it stopped."""
    workdir = pathlib.Path(tempfile.mkdtemp(prefix="twolink-grade-"))
    try:
        copy = workdir / "submission.ipynb"
        copy.write_text(json.dumps(notebook), encoding="utf-8")
        failure = execute(
            notebook, workdir, unsafe=unsafe, hidden=hidden, limits=limits
        )
        return {
            "reports": probe_reports(notebook),
            "errors": cell_errors(notebook),
            "failure": failure,
        }
    finally:
        shutil.rmtree(workdir, ignore_errors=True)


def _serve(connection: Any) -> None:
    """A worker's loop: run each notebook sent, send back what :func:`run_one` returns; stop at ``None``."""
    while True:
        try:
            task = connection.recv()
        except EOFError:  # the grader went away
            return
        if task is None:
            return
        notebook_text, hidden, unsafe, limits = task
        # built and validated by the grader: not validated again
        notebook = nbformat.from_dict(json.loads(notebook_text))
        connection.send(
            run_one(notebook, [pathlib.Path(h) for h in hidden], unsafe, limits)
        )


class Worker:
    """A process of the grader's that runs notebooks one after another; killed (and its sandbox with it) when one overruns."""

    def __init__(self) -> None:
        self.connection, child_end = CONTEXT.Pipe()
        self.process = CONTEXT.Process(target=_serve, args=(child_end,), daemon=True)
        self.process.start()
        child_end.close()

    def run(
        self,
        notebook: Any,
        hidden: Sequence[pathlib.Path],
        unsafe: bool,
        limits: Limits,
    ) -> dict[str, Any]:
        """What :func:`run_one` returns for ``notebook``; if the worker died or overran, a failure saying so (and it is stopped)."""
        try:
            self.connection.send(
                (json.dumps(notebook), [str(h) for h in hidden], unsafe, limits)
            )
            if not self.connection.poll(limits.notebook_seconds + 60):
                self.stop()
                return {"failure": limits.overrun}
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
        """End the process (and so any sandbox it still holds)."""
        if self.process.is_alive():
            self.process.kill()
        self.process.join(30)
        if not self.connection.closed:
            self.connection.close()


class Runner:
    """Workers for notebooks run ``jobs`` at a time: each started once (its imports paid once), replaced when stopped."""

    def __init__(self) -> None:
        self._idle: queue.SimpleQueue[Worker] = queue.SimpleQueue()
        self._all: list[Worker] = []
        self._lock = threading.Lock()

    def run(
        self,
        notebook: Any,
        *,
        hidden: Sequence[pathlib.Path],
        unsafe: bool,
        limits: Limits,
    ) -> dict[str, Any]:
        """:func:`run_one` for ``notebook`` in an idle worker; a failure saying why if the worker died or overran."""
        worker = self._idle_worker()
        if worker is None:
            worker = Worker()
            with self._lock:
                self._all.append(worker)
        ran = worker.run(notebook, hidden, unsafe, limits)
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
        """Stop every worker."""
        with self._lock:
            for worker in self._all:
                worker.stop()
            self._all.clear()


def run_isolated(
    notebook: Any,
    *,
    hidden: Sequence[pathlib.Path],
    unsafe: bool,
    limits: Limits,
) -> dict[str, Any]:
    """:func:`run_one` for one notebook in a worker of its own (a :class:`Runner` runs many)."""
    runner = Runner()
    try:
        return runner.run(notebook, hidden=hidden, unsafe=unsafe, limits=limits)
    finally:
        runner.close()
