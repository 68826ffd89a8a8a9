"""One graded notebook, run isolated (tools/grade_run.py): what a kernel that misbehaves gets.

Tiny notebooks (no chapter), so each case costs a kernel's start: a kernel
that kills itself, stops itself, loops, floods its output, or runs well.
"""

import pathlib
import sys

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade_run  # noqa: E402
import sandbox  # noqa: E402

UNSAFE = sandbox.unavailable() is not None
LIMITS = grade_run.Limits(cell_seconds=3, notebook_seconds=15)


def ran(*sources, limits=LIMITS):
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source) for source in sources]
    )
    return grade_run.run_isolated(notebook, hidden=[], unsafe=UNSAFE, limits=limits)


def probe(number="1.1"):
    cell = nbformat.v4.new_code_cell(
        "from IPython.display import publish_display_data\n"
        f"publish_display_data({{{grade_run.grading_probe.MIME!r}: {{'exercise': {number!r}, 'answers': {{}}}}}})",
        metadata={"tags": [grade_run.PROBE_TAG]},
    )
    cell.id = f"grader-probe-{number.replace('.', '-')}"
    return cell


@pytest.mark.infrastructure
def test_a_kernel_that_runs_well_reports_its_probes_and_errors():
    notebook = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_code_cell("x = 1"),
            probe("1.1"),
            nbformat.v4.new_code_cell("1 / 0"),
            probe("1.2"),
        ]
    )
    result = grade_run.run_isolated(notebook, hidden=[], unsafe=UNSAFE, limits=LIMITS)
    assert result["failure"] is None
    assert result["reports"]["1.1"] == {"exercise": "1.1", "answers": {}}
    assert (
        result["reports"]["1.2"]["exercise"] == "1.2"
    )  # the error did not stop the run
    assert result["errors"] == ["cell 2: ZeroDivisionError: division by zero"]


@pytest.mark.infrastructure
@pytest.mark.skipif(
    UNSAFE,
    reason="without a sandbox a kernel that kills its process group kills the test",
)
def test_a_kernel_that_kills_itself_is_reported_dead():
    assert (
        ran("import os, signal\nos.killpg(0, signal.SIGKILL)", "print(2)")["failure"]
        == "the kernel died"
    )


@pytest.mark.infrastructure
@pytest.mark.skipif(
    UNSAFE,
    reason="a stopped kernel outside a sandbox would stop the test's process group",
)
def test_a_stopped_kernel_is_stopped_at_the_notebook_limit():
    result = ran("import os, signal\nos.kill(os.getpid(), signal.SIGSTOP)", "print(2)")
    assert result["failure"] == "stopped after 15 s (the notebook's time limit)"


@pytest.mark.infrastructure
def test_a_loop_is_interrupted_at_the_cell_limit_and_the_run_goes_on():
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell("while True:\n    pass"), probe("1.1")]
    )
    result = grade_run.run_isolated(notebook, hidden=[], unsafe=UNSAFE, limits=LIMITS)
    assert result["failure"] is None and result["reports"]["1.1"]["exercise"] == "1.1"
    assert result["errors"][0].startswith("cell 1: KeyboardInterrupt")


@pytest.mark.infrastructure
def test_an_output_flood_is_stopped_at_the_output_limit():
    result = ran("for _ in range(60):\n    print('x' * 1_000_000)")
    assert (
        result["failure"]
        == f"its outputs passed {grade_run.HeadlessClient.max_output_bytes} bytes (the output limit)"
    )


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

    class Died:
        exitcode = -11

        def __init__(self, **kwargs):
            pass

        def start(self):
            pass

        def is_alive(self):
            return False

        def join(self, timeout):
            pass

    monkeypatch.setattr(grade_run.CONTEXT, "Process", Died)
    result = grade_run.run_isolated(
        nbformat.v4.new_notebook(), hidden=[], unsafe=True, limits=LIMITS
    )
    assert result == {"failure": "the grader's process for it ended with code -11"}


@pytest.mark.infrastructure
def test_a_runner_reuses_its_workers_and_replaces_a_stopped_one():
    runner = grade_run.Runner()
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1")])
    try:
        first = runner.run(notebook, hidden=[], unsafe=True, limits=LIMITS)
        second = runner.run(notebook, hidden=[], unsafe=True, limits=LIMITS)
        assert first["failure"] is None and second["failure"] is None
        assert len(runner._all) == 1  # one worker, used twice
        runner._all[0].stop()
        third = runner.run(notebook, hidden=[], unsafe=True, limits=LIMITS)
        assert third["failure"] is None and len(runner._all) == 2
    finally:
        runner.close()
    assert not any(worker.process.is_alive() for worker in runner._all)
