"""twolink_course.runmode: the grading switch, read from TWOLINK_GRADING at each call, and
chapters whose self-checks print the same lines with the switch on as off.

What each heavy function does with the switch on is tested with it:
tests/course/test_plot.py (animation_html), tests/course/test_explorer.py, tests/course/test_inline.py
(figures) and tests/course/test_timing.py (median_time).
"""

import os
import pathlib

import nbformat
import pytest
from nbclient import NotebookClient

from twolink.errors import InputTypeError
from twolink_course import runmode

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHECK = "selfcheck.check("


@pytest.mark.parametrize(
    ("value", "expected"), [("1", True), ("0", False), ("", False), (None, False)]
)
def test_the_switch_is_read_from_the_environment_at_each_call(
    monkeypatch, value, expected
):
    monkeypatch.setenv(runmode.VARIABLE, "1" if not expected else "0")
    assert runmode.grading() is (not expected)  # read now, not at import
    if value is None:
        monkeypatch.delenv(runmode.VARIABLE)
    else:
        monkeypatch.setenv(runmode.VARIABLE, value)
    assert runmode.grading() is expected


@pytest.mark.parametrize(
    "value", ["yes", "true", "on", "2", " 1", "1 ", "01", "\n", "TRUE", "1\n0"]
)
def test_any_other_value_is_refused_naming_the_variable_and_its_values(
    monkeypatch, value
):
    monkeypatch.setenv(runmode.VARIABLE, value)
    with pytest.raises(ValueError) as caught:
        runmode.grading()
    message = str(caught.value)
    assert message.startswith("TWOLINK_GRADING must be")
    assert '"1"' in message and '"0"' in message and "unset" in message
    assert repr(value) in message


def test_a_long_value_is_quoted_in_part(monkeypatch):
    monkeypatch.setenv(runmode.VARIABLE, "x" * 5000)
    with pytest.raises(ValueError, match=r"got 'x{40}\.\.\.'$"):
        runmode.grading()


def test_the_skipped_note_names_what_and_the_switch():
    note = runmode.skipped_note("animation")
    assert note.startswith("animation skipped while grading")
    assert "TWOLINK_GRADING=1" in note
    for junk in ("", "  ", None, 3):
        with pytest.raises(InputTypeError, match="what must be a non-empty str"):
            runmode.skipped_note(junk)


class _Headless(NotebookClient):
    """No widget front end, as the grader runs a chapter."""

    def handle_comm_msg(self, outs, msg, cell_index):
        return None


def _run_to_last_check(path, switch):
    """The chapter up to its last check cell, outputs cleared, run in a fresh kernel."""
    notebook = nbformat.read(path, as_version=4)
    last = max(
        index
        for index, cell in enumerate(notebook.cells)
        if cell.cell_type == "code" and CHECK in cell.source
    )
    notebook.cells = notebook.cells[: last + 1]
    for cell in notebook.cells:
        if cell.cell_type == "code":
            cell.outputs = []
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("MPLBACKEND", runmode.VARIABLE)
    }
    if switch:
        env[runmode.VARIABLE] = "1"
    _Headless(
        notebook,
        timeout=300,
        kernel_name="python3",
        resources={"metadata": {"path": str(ROOT / "notebooks")}},
    ).execute(env=env)
    return notebook


def _check_lines(notebook):
    return [
        line
        for cell in notebook.cells
        if cell.cell_type == "code" and CHECK in cell.source
        for output in cell.outputs
        if output.get("output_type") == "stream"
        for line in "".join(output.get("text", "")).splitlines()
    ]


def _outputs_of(notebook, mime):
    return [
        output
        for cell in notebook.cells
        if cell.cell_type == "code"
        for output in cell.outputs
        if mime in output.get("data", {})
    ]


@pytest.mark.infrastructure
@pytest.mark.parametrize(
    "chapter",
    [
        "02_inverse_kinematics",
        "07_workspace_trajectories",
    ],  # timings, explorers, videos
)
def test_a_chapter_prints_the_same_self_check_lines_with_the_switch_on(chapter):
    path = ROOT / "notebooks" / f"{chapter}.ipynb"
    taught = _run_to_last_check(path, switch=False)
    graded = _run_to_last_check(path, switch=True)
    lines = _check_lines(taught)
    assert any("Exercise" in line for line in lines), lines  # the checks did print
    assert _check_lines(graded) == lines
    # and the switch did skip the heavy work: no picture, no video, no explorer canvas
    assert _outputs_of(taught, "image/png") and not _outputs_of(graded, "image/png")
    htmls = [
        "".join(output["data"]["text/html"])
        for output in _outputs_of(graded, "text/html")
    ]
    assert not any("<video" in text for text in htmls)
    assert any("interactive figure skipped while grading" in text for text in htmls)
    if chapter.startswith("07"):
        assert any("animation skipped while grading" in text for text in htmls)
    assert not _outputs_of(graded, "application/vnd.jupyter.widget-view+json")
