"""A chapter prints the same self-check lines with the grading switch on, and skips its heavy displays.

Chapter 7 (timings, explorers and videos) runs up to its last check cell in a
fresh kernel with ``TWOLINK_GRADING=1``, as ``make grade`` runs it; its check
lines must read as the chapter's stored ones, which nbval's run of the chapter
(the same ``make test``) proves to be what the chapter prints with the switch
off.  One graded run: the chapter is not run again with the switch off.

The lines are read from each check cell's stream outputs joined first: the
kernel sends what a cell prints in pieces on a timer (ipykernel's 0.2 s flush),
so one printed line can arrive as two outputs ("...correct." and "\\n").
"""

import os
import pathlib

import nbformat
import pytest
from nbclient import NotebookClient

from twolink_course import runmode

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHECK = "selfcheck.check("
#: The chapter: it times solvers, builds explorers and renders videos.
CHAPTER = ROOT / "notebooks" / "07_workspace_trajectories.ipynb"


class HeadlessClient(NotebookClient):
    """No widget front end, as the grader runs a chapter."""

    def handle_comm_msg(self, outs, msg, cell_index):
        return None


def _to_last_check(notebook):
    """The chapter up to its last check cell."""
    last = max(
        index
        for index, cell in enumerate(notebook.cells)
        if cell.cell_type == "code" and CHECK in cell.source
    )
    notebook.cells = notebook.cells[: last + 1]
    return notebook


def check_lines(notebook):
    """The lines the check cells printed, each cell's stream outputs joined before splitting."""
    return [
        line
        for cell in notebook.cells
        if cell.cell_type == "code" and CHECK in cell.source
        for line in "".join(
            "".join(output.get("text", ""))
            for output in cell.outputs
            if output.get("output_type") == "stream" and output.get("name") == "stdout"
        ).splitlines()
    ]


def _outputs_of(notebook, mime):
    return [
        output
        for cell in notebook.cells
        if cell.cell_type == "code"
        for output in cell.outputs
        if mime in output.get("data", {})
    ]


def test_a_printed_line_sent_in_two_pieces_is_one_line():
    cell = nbformat.v4.new_code_cell(
        'check = selfcheck.check("1.1", p)',
        outputs=[
            nbformat.v4.new_output(
                "stream", name="stdout", text="Exercise 1.1: correct."
            ),
            nbformat.v4.new_output(
                "stream", name="stdout", text="\nExercise 1.2: wrong\n"
            ),
        ],
    )
    notebook = nbformat.v4.new_notebook(cells=[cell])
    assert check_lines(notebook) == ["Exercise 1.1: correct.", "Exercise 1.2: wrong"]


@pytest.fixture(scope="module")
def graded():
    notebook = _to_last_check(nbformat.read(CHAPTER, as_version=4))
    for cell in notebook.cells:
        if cell.cell_type == "code":
            cell.outputs = []
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("MPLBACKEND", runmode.VARIABLE)
    }
    env[runmode.VARIABLE] = "1"
    HeadlessClient(
        notebook,
        timeout=300,
        kernel_name="python3",
        resources={"metadata": {"path": str(CHAPTER.parent)}},
    ).execute(env=env)
    return notebook


def test_the_graded_chapter_prints_the_stored_check_lines(graded):
    stored = check_lines(_to_last_check(nbformat.read(CHAPTER, as_version=4)))
    assert any("Exercise" in line for line in stored), stored  # the checks did print
    assert check_lines(graded) == stored


def test_the_graded_chapter_skips_its_heavy_displays(graded):
    taught = nbformat.read(CHAPTER, as_version=4)
    assert _outputs_of(taught, "image/png") and not _outputs_of(graded, "image/png")
    htmls = [
        "".join(output["data"]["text/html"])
        for output in _outputs_of(graded, "text/html")
    ]
    assert not any("<video" in text for text in htmls)
    assert any("interactive figure skipped while grading" in text for text in htmls)
    assert any("animation skipped while grading" in text for text in htmls)
    assert not _outputs_of(graded, "application/vnd.jupyter.widget-view+json")
