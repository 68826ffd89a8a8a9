"""Chapters 4 to 7 as a reader sees them: teaching code on the page, goals exercised, a summary to keep.

- the code a reader meets (non-blank, non-comment lines, the install cell left
  out) stays under each chapter's ceiling, about half of what it was; the
  counts are printed (``pytest -s``);
- an explorer is built in one short cell from its chapter's kit module
  (``twolink_course.explorers.chN``): what is drawn against what, no drawing
  code on the page;
- every learning goal names the exercises that practise it, each of those
  exists with its parts in ``answers/chN.py``, and every exercise is named by a goal;
- the main line ends with a one-page summary: the symbols, the main formulas
  and the package calls that implement them;
- each casebook entry links the item of the course's source record it rests
  on, the anchor named after the item (``[H4.3](source_record.ipynb#h4-3)``);
- no cell shows an nbval marker line: a cell whose output may differ between
  runs ("this run") carries nbval's tag ``nbval-ignore-output`` instead.

(The forward use of names is checked for every chapter in
``tests/notebooks/test_reading_structure.py``; the figures in nbval's run of each
chapter, ``notebooks/NN_x.ipynb::figures`` (``tests/notebooks/chapter_checks.py``).)
"""

import json
import pathlib
import re
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import outline  # noqa: E402

import answers  # noqa: E402

NOTEBOOK_DIR = ROOT / "notebooks"
CHAPTERS = {
    "04": "04_statics_wall.ipynb",
    "05": "05_lagrangian_dynamics.ipynb",
    "06": "06_spring_impedance_control.ipynb",
    "07": "07_workspace_trajectories.ipynb",
}
#: The code lines each chapter had before its machinery left the page (main line + casebook),
#: and the most it may have now: about half.
CODE_LINES_BEFORE = {"04": 948, "05": 1105, "06": 1946, "07": 1521}
CODE_LINES_CEILING = {"04": 480, "05": 570, "06": 990, "07": 790}
#: The first line of the generated install cell, not the chapter's code.
SETUP_CELL_START = "# Setup: installs twolink"
#: An explorer's cell: the figure object of the chapter's kit module and its controls.
MAX_EXPLORER_CELL_LINES = 16
GOAL = re.compile(r"^\d+\. (?P<text>.+?)(?=^\d+\. |\Z)", re.MULTILINE | re.DOTALL)
EXERCISES_NAMED = re.compile(
    r"\(exercises? (?P<numbers>\d+\.\d+(?:(?:, | and )\d+\.\d+)*)\)"
)
RECORD_LINK = re.compile(r"\[(?P<item>H\d\.\d+)\]\((?P<target>[^)]*)\)")
NBVAL_MARKER = re.compile(r"^\s*#\s*NBVAL_", re.MULTILINE)
IGNORE_OUTPUT_TAG = "nbval-ignore-output"


def cells(number):
    return json.loads((NOTEBOOK_DIR / CHAPTERS[number]).read_text(encoding="utf-8"))[
        "cells"
    ]


def text(cell):
    return "".join(cell["source"])


def code_lines(source):
    """Lines a reader reads as code: neither blank nor a comment."""
    return sum(
        1
        for line in source.splitlines()
        if line.strip() and not line.strip().startswith("#")
    )


def output_text(cell):
    pieces = []
    for output in cell.get("outputs", []):
        pieces.append("".join(output.get("text", "")))
        for kind in ("text/plain", "text/markdown"):
            pieces.append("".join(output.get("data", {}).get(kind, "")))
    return "".join(pieces)


@pytest.mark.parametrize("number", CHAPTERS)
def test_the_code_on_the_page_is_about_half_what_it_was(number):
    lines = sum(
        code_lines(text(cell))
        for cell in cells(number)
        if cell["cell_type"] == "code" and not text(cell).startswith(SETUP_CELL_START)
    )
    print(f"\nchapter {number}: {lines} code lines, {CODE_LINES_BEFORE[number]} before")
    assert lines <= CODE_LINES_CEILING[number] <= 0.52 * CODE_LINES_BEFORE[number]


@pytest.mark.parametrize("number", CHAPTERS)
def test_explorers_are_built_in_one_short_cell_from_the_chapter_s_kit_module(number):
    built = [
        text(cell)
        for cell in cells(number)
        if cell["cell_type"] == "code" and "explorer.Explorer(" in text(cell)
    ]
    assert built, f"chapter {number} builds no explorer"
    for source in built:
        lines = code_lines(source)
        assert lines <= MAX_EXPLORER_CELL_LINES, (number, lines)
        assert "def " not in source and "plot." not in source, source
        assert f"ch{int(number)}_" in source, (
            "the figure comes from the chapter's module"
        )


@pytest.mark.parametrize("number", CHAPTERS)
def test_every_learning_goal_names_the_exercises_that_practise_it(number):
    opening = text(cells(number)[0])
    goals_text = opening.split("## Learning goals", 1)[1].split("**Time:**", 1)[0]
    goals = [match["text"] for match in GOAL.finditer(goals_text)]
    assert len(goals) >= 4, goals
    module = answers.chapter(f"ch{int(number)}")
    exercises = {exercise.number: exercise for exercise in module.exercises()}
    practised = set()
    for goal in goals:
        named = EXERCISES_NAMED.search(" ".join(goal.split()))
        assert named, f"chapter {number}: a goal names no exercise: {goal.strip()!r}"
        numbers = re.split(r", | and ", named["numbers"])
        assert set(numbers) <= set(exercises), (number, numbers)
        assert all(exercises[n].parts for n in numbers)
        practised.update(numbers)
    assert practised == set(exercises), (
        f"chapter {number}: exercises no goal names: {set(exercises) - practised}"
    )


@pytest.mark.parametrize("number", CHAPTERS)
def test_the_main_line_ends_with_a_one_page_summary(number):
    chapter = outline.outline(NOTEBOOK_DIR / CHAPTERS[number])
    level_two = [h for h in chapter.headings if h.level == 2]
    assert [h.text for h in level_two[-2:]] == ["Summary", outline.CASEBOOK_HEADING]
    body = text(chapter.cells[level_two[-2].cell])
    assert "| symbol | meaning | unit |" in body, "a table of the symbols"
    assert "| formula | in words | package |" in body, (
        "formulas beside their package calls"
    )
    formulas = [line for line in body.splitlines() if line.startswith("| $")]
    assert len(formulas) >= 4
    with_calls = [line for line in formulas if line.rstrip(" |").endswith("`")]
    assert len(with_calls) >= 4, "each main formula names the package call"
    assert len(body.split()) <= 600, "one page"


@pytest.mark.parametrize("number", CHAPTERS)
def test_each_casebook_entry_links_its_source_record_anchor(number):
    chapter = outline.outline(NOTEBOOK_DIR / CHAPTERS[number])
    entries = chapter.entries()
    assert entries, f"chapter {number} has no casebook entry"
    for entry in entries:
        entry_text = "\n".join(
            text(cell) for cell in chapter.cells[entry.heading.cell : entry.end]
        )
        links = RECORD_LINK.findall(entry_text)
        assert links, f"chapter {number}, {entry.heading.text!r}: no linked record item"
        for item, target in links:
            anchor = item.lower().replace(".", "-")
            assert target == f"source_record.ipynb#{anchor}", (number, item, target)


@pytest.mark.parametrize("number", CHAPTERS)
def test_no_nbval_marker_line_and_varying_outputs_are_tagged(number):
    for index, cell in enumerate(cells(number)):
        if cell["cell_type"] != "code":
            continue
        assert not NBVAL_MARKER.search(text(cell)), (
            f"chapter {number} cell {index}: a visible nbval marker; tag the cell "
            f"{IGNORE_OUTPUT_TAG!r} instead"
        )
        if "this run" in output_text(cell).lower():
            assert IGNORE_OUTPUT_TAG in cell["metadata"].get("tags", []), (
                f"chapter {number} cell {index} prints a 'this run' result untagged"
            )
