"""Chapters 2 and 7 as a reader sees them: names defined before use, clean prose cells.

The text checks read the committed JSON.  (The figure checks for every
chapter are in ``tests/notebooks/test_figures.py``.)
"""

import json
import pathlib
import re

import pytest

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parents[2] / "notebooks"
CHAPTER_2 = "02_inverse_kinematics.ipynb"
CHAPTER_7 = "07_workspace_trajectories.ipynb"
CHAPTERS = [CHAPTER_2, CHAPTER_7]

SOLVER_NAMES = ("fminunc", "fmincon", "BFGS", "SLSQP", "Levenberg-Marquardt")


def cells(name):
    return json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))["cells"]


def text(cell):
    return "".join(cell["source"])


def test_chapter_2_defines_the_branch_names_before_using_them():
    content = cells(CHAPTER_2)
    definition = next(
        index
        for index, cell in enumerate(content)
        if cell["cell_type"] == "markdown" and "**down** is the" in text(cell)
    )
    first_use = next(
        index
        for index, cell in enumerate(content)
        if cell["cell_type"] == "code" and re.search(r"\bdown\b|\bup\b", text(cell))
    )
    assert definition < first_use, (
        f"'down'/'up' used in cell {first_use}, defined in cell {definition}"
    )


def test_chapter_2_explains_each_solver_name_before_the_chapter_relies_on_it():
    content = [
        text(cell) for cell in cells(CHAPTER_2) if cell["cell_type"] == "markdown"
    ]
    glossary = next(
        (
            index
            for index, cell in enumerate(content)
            if all(f"**{name}" in cell for name in SOLVER_NAMES[2:])
        ),
        None,
    )
    assert glossary is not None, (
        f"no markdown cell explains {', '.join(SOLVER_NAMES[2:])} (each in bold)"
    )
    for name in SOLVER_NAMES:
        first = next(index for index, cell in enumerate(content) if name in cell)
        explained_there = first == glossary or (
            name == "fminunc" and "MATLAB's minimiser `fminunc`" in content[first]
        )
        assert explained_there, (
            f"{name} first appears in markdown cell {first}, explained only in cell {glossary}"
        )


def test_chapter_7_has_no_set_unpacking_and_names_the_circle_it_draws():
    code = [text(cell) for cell in cells(CHAPTER_7) if cell["cell_type"] == "code"]
    assert not [
        line
        for source in code
        for line in source.splitlines()
        if re.match(r"\s*\(\w+,\)\s*=", line)
    ]
    assert not [
        source.splitlines()[0]
        for source in code
        if re.search(r"""["'][^"']*source circle""", source)
    ]


@pytest.mark.parametrize("name", CHAPTERS)
def test_the_introduction_says_where_real_robots_use_the_idea(name):
    assert "On real robots" in text(cells(name)[0]), (
        f"{name}: the introduction says nowhere where the idea is used"
    )


@pytest.mark.parametrize("name", CHAPTERS)
def test_no_markdown_cell_repeats_its_own_lines(name):
    content = cells(name)
    for index, cell in enumerate(content):
        if cell["cell_type"] != "markdown":
            continue
        lines = [
            line.strip() for line in text(cell).splitlines() if len(line.strip()) > 30
        ]
        repeated = {line for line in lines if lines.count(line) > 1}
        assert not repeated, (
            f"{name} markdown cell {index} repeats itself: {sorted(repeated)[:2]}"
        )
