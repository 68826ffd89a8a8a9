"""One graded notebook, run isolated (tools/grade_run.py): what a kernel that misbehaves gets.

Tiny notebooks (no chapter), so each case costs a kernel's start: a kernel
that kills itself, stops itself, loops, floods its output, or runs well,
each run by the same grader's worker (started once, as ``make grade`` starts
its workers), which leaves nothing in the scratch folder (the grader's
alone) after each notebook; the scratch folder removed at the end.
"""

import dataclasses
import pathlib
import sys
import threading
import time

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade_run  # noqa: E402
import sandbox  # noqa: E402

UNSAFE = sandbox.unavailable() is not None
LIMITS = grade_run.Limits(cell_seconds=3, notebook_seconds=15)
#: The notebook limit a stopped kernel waits for: well longer than a kernel takes to start (the
#: watchdog kills the kernel it started; one still starting is stopped a minute later).
STOPPED_LIMITS = grade_run.Limits(cell_seconds=3, notebook_seconds=8)


@pytest.fixture(scope="module")
def runner():
    """A runner of the grader's with one worker, shared by the tests (``runner.setting`` is each test's)."""
    scratch = grade_run.make_scratch()
    isolation = None if UNSAFE else sandbox.Isolation.detect(scratch)
    base = grade_run.Setting(scratch, isolation, LIMITS)
    found = grade_run.Runner(base)
    yield found
    found.close()
    grade_run.remove_scratch(base)
    assert not scratch.exists()


@pytest.fixture
def setting(runner):
    """The runner's setting with :data:`LIMITS`; after the test, nothing of a notebook left in the scratch folder."""
    runner.setting = dataclasses.replace(runner.setting, limits=LIMITS)
    yield runner.setting
    left = {path.name for path in runner.setting.scratch.iterdir()}
    # at most the one-process filter, written where there are no control groups
    assert left <= {"one-process.bpf"}, left


def ran(runner, *sources):
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source) for source in sources]
    )
    return runner.run(notebook)


def probe(number="1.1", draw=None):
    data = {"exercise": number, "answers": {}}
    if draw is not None:
        data["draw"] = draw
    cell = nbformat.v4.new_code_cell(
        "from IPython.display import publish_display_data\n"
        f"publish_display_data({{{grade_run.grading_probe.MIME!r}: {data!r}}})",
        metadata={"tags": [grade_run.PROBE_TAG], "twolink_probe": number},
    )
    return cell


@pytest.mark.infrastructure
def test_a_kernel_that_runs_well_reports_its_probes_and_errors(runner, setting):
    notebook = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_code_cell("x = 1"),
            probe("1.1"),
            nbformat.v4.new_code_cell("1 / 0"),
            probe("1.2"),
        ]
    )
    notebook.cells[3].source += "\n" + probe("1.2", draw=0).source.splitlines()[-1]
    result = runner.run(notebook, [1, None, 5, None])
    assert result["failure"] is None
    assert result["reports"]["1.1"] == {
        "visible": {"exercise": "1.1", "answers": {}},
        "draws": {},
    }
    # the error did not stop the run; a draw's report is kept apart
    assert result["reports"]["1.2"]["visible"]["exercise"] == "1.2"
    assert result["reports"]["1.2"]["draws"] == {
        0: {"exercise": "1.2", "answers": {}, "draw": 0}
    }
    assert result["errors"] == ["cell 5: ZeroDivisionError: division by zero"]
    if not UNSAFE:
        assert result["cpu_seconds"] > 0 and result["limits"] == []


@pytest.mark.infrastructure
@pytest.mark.skipif(
    UNSAFE,
    reason="without a sandbox a kernel that kills its process group kills the test",
)
def test_a_kernel_that_kills_itself_is_reported_dead(runner, setting):
    assert (
        ran(runner, "import os, signal\nos.killpg(0, signal.SIGKILL)", "print(2)")[
            "failure"
        ]
        == "the kernel died"
    )


@pytest.mark.infrastructure
@pytest.mark.skipif(
    UNSAFE,
    reason="a stopped kernel outside a sandbox would stop the test's process group",
)
def test_a_stopped_kernel_is_stopped_at_the_notebook_limit(runner, setting):
    runner.setting = dataclasses.replace(setting, limits=STOPPED_LIMITS)
    result = ran(
        runner, "import os, signal\nos.kill(os.getpid(), signal.SIGSTOP)", "print(2)"
    )
    assert result["failure"] == "stopped after 8 s (the notebook's time limit)"


@pytest.mark.infrastructure
def test_a_loop_is_interrupted_at_the_cell_limit_and_the_run_goes_on(runner, setting):
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell("while True:\n    pass"), probe("1.1")]
    )
    result = runner.run(notebook)
    assert result["failure"] is None
    assert result["reports"]["1.1"]["visible"]["exercise"] == "1.1"
    assert result["errors"][0].startswith("cell 1: KeyboardInterrupt")


@pytest.mark.infrastructure
def test_an_output_flood_is_stopped_at_the_output_limit(runner, setting):
    result = ran(runner, "for _ in range(60):\n    print('x' * 1_000_000)")
    assert (
        result["failure"]
        == f"its outputs passed {grade_run.HeadlessClient.max_output_bytes} bytes (the output limit)"
    )


class EndedProcess:
    """A worker's process (in place of multiprocessing's) that has already ended, killed."""

    exitcode = -11

    def __init__(self, **kwargs):
        pass

    def start(self):
        pass

    def is_alive(self):
        return False

    def join(self, timeout):
        pass


def test_a_process_that_answers_nothing_is_reported(monkeypatch):
    class Silent:
        closed = False

        def send(self, task):
            pass

        def poll(self, timeout):
            return True

        def recv(self):
            raise EOFError

        def close(self):
            self.closed = True

    monkeypatch.setattr(grade_run.CONTEXT, "Pipe", lambda: (Silent(), Silent()))

    monkeypatch.setattr(grade_run.CONTEXT, "Process", EndedProcess)
    result = grade_run.run_isolated(
        nbformat.v4.new_notebook(),
        grade_run.Setting(pathlib.Path("/nonexistent"), None, LIMITS),
    )
    assert result == {"failure": "the grader's process for it ended with code -11"}


def test_a_worker_stopped_by_two_threads_at_once_closes_its_connection_once(
    monkeypatch,
):
    # Ctrl-C: the grader's main thread stops every worker while the thread that sent a worker
    # its notebook sees the pipe end and stops it too; closing one descriptor twice raised
    # "OSError: [Errno 9] Bad file descriptor" and the grader ended with 1, not 130
    closes = []

    class SlowToClose:  # as multiprocessing's Connection: closed only once close() returns
        closed = False

        def close(self):
            closes.append(threading.current_thread().name)
            time.sleep(0.2)
            self.closed = True

    monkeypatch.setattr(
        grade_run.CONTEXT, "Pipe", lambda: (SlowToClose(), SlowToClose())
    )
    monkeypatch.setattr(grade_run.CONTEXT, "Process", EndedProcess)
    worker = grade_run.Worker()
    closes.clear()  # the child's end, closed in the parent
    start = threading.Barrier(2)

    def stop():
        start.wait()
        worker.stop()

    threads = [threading.Thread(target=stop, name=f"stopper-{i}") for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(10)
    assert len(closes) == 1, closes


@pytest.mark.infrastructure
def test_a_runner_reuses_its_workers_and_replaces_a_stopped_one(tmp_path):
    runner = grade_run.Runner(grade_run.Setting(tmp_path, None, LIMITS))
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1")])
    try:
        first = runner.run(notebook)
        second = runner.run(notebook)
        assert first["failure"] is None and second["failure"] is None
        assert len(runner._all) == 1  # one worker, used twice
        runner._all[0].stop()
        third = runner.run(notebook)
        assert third["failure"] is None and len(runner._all) == 2
        workers = list(runner._all)
    finally:
        runner.close()
    assert not any(worker.process.is_alive() for worker in workers)
    assert runner.run(notebook) == {"failure": "grading was stopped (Ctrl-C)"}
