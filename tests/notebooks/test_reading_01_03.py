"""Chapters 1 to 3 as a reader sees them: teaching code on the page, goals exercised, a summary to keep.

- the code a reader meets (non-blank, non-comment lines, the install cell left
  out) stays under each chapter's ceiling, about half of what it was; the
  counts are printed (``pytest -s``; ``python tools/course_map.py --times``
  prints the whole workload);
- an explorer is built in one short cell from its chapter's kit module
  (``twolink_course.explorers.chN``): what is drawn against what, no drawing
  code on the page;
- every learning goal names the exercises that practise it, and each of those
  exists (a part of it is in ``answers/chN.py``);
- the chapter ends its main line with a one-page summary: the symbols, the
  main formulas and the package calls that implement them;
- chapter 1 writes one name, ``T_0^2``, for the base-to-tip transform.

(The figure checks for every chapter are in ``tests/notebooks/test_figures.py``;
the forward use of names in ``tests/notebooks/test_reading_structure.py``.)
"""

import json
import pathlib
import re
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import course_map  # noqa: E402
import outline  # noqa: E402

import answers  # noqa: E402

NOTEBOOK_DIR = ROOT / "notebooks"
CHAPTERS = {
    "01": "01_dh_forward_kinematics.ipynb",
    "02": "02_inverse_kinematics.ipynb",
    "03": "03_jacobian_velocity.ipynb",
}
#: The code lines each chapter had before its machinery left the page (main line + casebook),
#: and the most it may have now: about half (chapter 3 a little more: it gained three
#: exercises and the derivation of the damped rates' bound).
CODE_LINES_BEFORE = {"01": 635, "02": 1296, "03": 966}
CODE_LINES_CEILING = {"01": 330, "02": 630, "03": 540}
#: An explorer's cell: the figure object of the chapter's kit module and its controls.
MAX_EXPLORER_CELL_LINES = 16
GOAL = re.compile(r"^\d+\. (?P<text>.+?)(?=^\d+\. |\Z)", re.MULTILINE | re.DOTALL)
EXERCISES_NAMED = re.compile(r"\(exercises? (?P<numbers>\d+\.\d+(?:, \d+\.\d+)*)\)")


def cells(number):
    return json.loads((NOTEBOOK_DIR / CHAPTERS[number]).read_text(encoding="utf-8"))[
        "cells"
    ]


def text(cell):
    return "".join(cell["source"])


def code_sources(name):
    content = json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))
    return [
        "".join(cell["source"])
        for cell in content["cells"]
        if cell["cell_type"] == "code"
    ]


@pytest.mark.parametrize("number", CHAPTERS)
def test_the_code_on_the_page_is_about_half_what_it_was(number):
    time = course_map.chapter_time(NOTEBOOK_DIR / CHAPTERS[number])
    lines = time.main.code_lines + time.casebook.code_lines
    print(
        f"\nchapter {number}: {lines} code lines ({time.main.code_lines} main line, "
        f"{time.casebook.code_lines} casebook), {CODE_LINES_BEFORE[number]} before"
    )
    assert lines <= CODE_LINES_CEILING[number] <= 0.56 * CODE_LINES_BEFORE[number]


@pytest.mark.parametrize("number", CHAPTERS)
def test_explorers_are_built_in_one_short_cell_from_the_chapter_s_kit_module(number):
    built = [
        text(cell)
        for cell in cells(number)
        if cell["cell_type"] == "code" and "explorer.Explorer(" in text(cell)
    ]
    assert built, f"chapter {number} builds no explorer"
    for source in built:
        lines = course_map.code_lines(source)
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
        numbers = named["numbers"].split(", ")
        assert set(numbers) <= set(exercises), (number, numbers)
        assert all(exercises[n].parts for n in numbers)
        practised.update(numbers)
    assert practised == set(exercises), (
        f"chapter {number}: exercises no goal names: {set(exercises) - practised}"
    )


@pytest.mark.parametrize("number", CHAPTERS)
def test_the_main_line_ends_with_a_one_page_summary(number):
    chapter = outline.outline(NOTEBOOK_DIR / CHAPTERS[number])
    (summary,) = [h for h in chapter.headings if h.level == 2 and h.text == "Summary"]
    body = text(chapter.cells[summary.cell])
    assert "| symbol | meaning |" in body, "a table of the symbols"
    assert "| formula | in the package |" in body, "formulas beside their package calls"
    table = body.split("| formula | in the package |", 1)[1].split("\n\n", 1)[0]
    formulas = [line for line in table.splitlines()[2:] if line.startswith("| ")]
    with_calls = [line for line in formulas if "`" in line.rsplit("|", 2)[-2]]
    assert len(formulas) >= 4 and len(with_calls) >= 0.75 * len(formulas), formulas
    assert len(body.split()) <= 600, "one page"


def test_chapter_1_names_the_transform_T_0_2_in_its_own_code():
    # the OSAKE source's name H_0^2 may appear in prose that attributes it; the course's own output says T_0^2
    offending = [
        source.splitlines()[0]
        for source in code_sources(CHAPTERS["01"])
        if re.search(r"H_0|H_\{?0|\bH_0?2", source)
    ]
    assert not offending, f"chapter 1 code still writes H_0^2 for T_0^2: {offending}"
