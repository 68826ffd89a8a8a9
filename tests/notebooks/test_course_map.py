"""The start page's chapter map and the chapters' navigation cells (``tools/course_map.py``).

The map is generated from the chapters' own first cells and the navigation
cells from their order and titles; ``--check`` fails when either is stale.
Every link between notebooks resolves, in ``notebooks/`` and in the student
edition (the static site's links are checked in ``tests/infrastructure/test_static_site.py``),
and the start page is never taken for a chapter (the grader, nbgrader).
"""

import json
import pathlib
import re
import shutil
import subprocess
import sys

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import course_map  # noqa: E402
import editions  # noqa: E402

NOTEBOOKS = ROOT / "notebooks"
START = NOTEBOOKS / course_map.START_PAGE
CHAPTERS = course_map.chapters(NOTEBOOKS)
TOOL = [sys.executable, str(ROOT / "tools" / "course_map.py")]
#: A Markdown link to a relative file: ``[text](target)``, the target without an anchor.
LINK = re.compile(r"\[(?P<text>[^\]]+)\]\((?P<target>[^)#\s]+)(?:#[^)\s]*)?\)")


def markdown_links(notebook):
    """``(text, target)`` of every link to a file in the notebook's Markdown cells."""
    return [
        (match["text"], match["target"])
        for cell in notebook["cells"]
        if cell["cell_type"] == "markdown"
        for match in LINK.finditer("".join(cell["source"]))
        if "://" not in match["target"]
    ]


def read(path):
    return json.loads(path.read_text(encoding="utf-8"))


def cell_text(cell):
    return "".join(cell["source"])


# --- the committed notebooks ----------------------------------------------------------------------------------


def test_the_course_has_a_start_page_and_chapters_apart_from_it():
    assert START.is_file()
    assert START not in CHAPTERS and len(CHAPTERS) >= 2
    assert [path.name[:2] for path in CHAPTERS] == [
        f"{number:02d}" for number in range(1, len(CHAPTERS) + 1)
    ]


def test_the_map_and_the_navigation_are_up_to_date():
    """Fails after a chapter's title, time or prerequisites change until `python tools/course_map.py` runs."""
    result = subprocess.run([*TOOL, "--check"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_the_start_page_links_every_chapter_in_order_with_its_title_time_and_prerequisites():
    start = read(START)
    assert editions.chapter_title(start, START.stem).startswith("Start here")
    linked = [target for _, target in markdown_links(start)]
    assert linked == [path.name for path in CHAPTERS]
    (table,) = [
        cell_text(cell)
        for cell in start["cells"]
        if cell_text(cell).endswith(course_map.MAP_MARKER)
    ]
    rows = [line for line in table.splitlines() if line.startswith("| [")]
    for row, path in zip(rows, CHAPTERS, strict=True):
        opening = cell_text(read(path)["cells"][0])
        title = editions.chapter_title(read(path), path.stem)
        time = re.search(r"\*\*Time:\*\* (about [\d.]+ (?:minutes|hours?))", opening)
        assert row.startswith(f"| [{title}]({path.name}) | {time[1]} |"), row
        first_words = re.search(r"\*\*Prerequisites:\*\* (\S+ \S+)", opening)[1]
        assert f"| {first_words}" in row, row


def test_the_start_page_has_no_code_and_shares_no_cell_with_a_chapter():
    start = read(START)
    assert all(cell["cell_type"] == "markdown" for cell in start["cells"])
    headings = editions.markdown_headings(start)
    assert headings[0][0] == 1 and [level for level, _ in headings[1:]] == [2] * (
        len(headings) - 1
    ), f"one title, then sections: {headings}"
    for path in CHAPTERS:
        sources = {cell_text(cell) for cell in read(path)["cells"]}
        assert not sources & {cell_text(cell) for cell in start["cells"]}, path.name


def test_the_start_page_says_how_explorers_exercises_reset_and_documentation_work():
    text = "\n".join(cell_text(cell) for cell in read(START)["cells"])
    for needed in (
        "Run All Cells",
        "slider",
        "not solved yet",
        "hint",
        "Restart Kernel",
        "git restore",
        "help(twolink",
        "README.md",
        "CONTRIBUTING.md",
    ):
        assert needed in text, needed


@pytest.mark.parametrize(
    "number", range(len(CHAPTERS)), ids=[p.stem[:2] for p in CHAPTERS]
)
def test_each_chapter_links_the_start_page_first_and_its_neighbours_last(number):
    path = CHAPTERS[number]
    cells = read(path)["cells"]
    assert re.match(r"# Chapter \d+: ", cell_text(cells[0])), (
        "the title cell stays first"
    )
    top, end = cells[1], cells[-1]
    assert top["cell_type"] == end["cell_type"] == "markdown"
    marked = [cell for cell in cells if course_map.NAV_MARKER in cell_text(cell)]
    assert marked == [top, end], "two navigation cells: after the title and last"
    assert markdown_links({"cells": [top]}) == [
        (f"Back to {course_map.START_LINK_TEXT}", course_map.START_PAGE)
    ]
    links = dict(
        (text.split(":")[0], target)
        for text, target in markdown_links({"cells": [end]})
    )
    previous = CHAPTERS[number - 1].name if number else course_map.START_PAGE
    following = (
        CHAPTERS[number + 1].name
        if number + 1 < len(CHAPTERS)
        else course_map.START_PAGE
    )
    assert links["Previous"] == previous and links["Next"] == following
    for text, target in markdown_links({"cells": [end]}):
        if target != course_map.START_PAGE:
            chapter = int(target[:2])
            assert text.split(": ", 1)[1].startswith(f"Chapter {chapter}, "), text
    assert course_map.START_PAGE in links.values()
    assert not any(cell.get("metadata", {}).get("nbgrader") for cell in (top, end)), (
        "navigation cells are not nbgrader cells"
    )


@pytest.mark.parametrize(
    "path", [START, *CHAPTERS], ids=[p.stem[:2] for p in [START, *CHAPTERS]]
)
def test_every_link_between_notebooks_resolves(path, student_edition):
    for folder in (NOTEBOOKS, student_edition):
        for _, target in markdown_links(read(folder / path.name)):
            assert (folder / target).is_file(), f"{folder}/{path.name} links {target}"


def test_nbgrader_metadata_is_still_complete():
    result = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "nbgrader_cells.py"), "--check"],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_grader_never_takes_the_start_page_for_a_chapter():
    import grade

    chapters = grade.release_chapters()
    assert sorted(chapters) == [path.stem for path in CHAPTERS]
    start = nbformat.read(START, as_version=4)
    assert grade.match_chapter(start, START.name, chapters) is None
    # the shared navigation cell does not pull a chapter towards another one
    for path in CHAPTERS:
        notebook = nbformat.read(path, as_version=4)
        assert (
            grade.match_chapter(notebook, "renamed.ipynb", chapters).stem == path.stem
        )


# --- the tool, on a copy ----------------------------------------------------------------------------------------


@pytest.fixture
def course(tmp_path):
    """A copy of the committed notebooks' folder (the tool writes into it)."""
    folder = tmp_path / "notebooks"
    shutil.copytree(NOTEBOOKS, folder, ignore=shutil.ignore_patterns(".*"))
    return folder


def test_check_fails_on_a_stale_map_and_writing_fixes_it_once(course):
    chapter = course / CHAPTERS[1].name
    notebook = nbformat.read(chapter, as_version=4)
    notebook.cells[0].source = notebook.cells[0].source.replace(
        "**Time:** about", "**Time:** about 7 hours; before:"
    )
    nbformat.write(notebook, chapter)
    stale = subprocess.run(
        [*TOOL, "--check", "--folder", str(course)], capture_output=True, text=True
    )
    assert stale.returncode == 1 and course_map.START_PAGE in stale.stderr
    assert course_map.update(course) == [course / course_map.START_PAGE]
    assert "| about 7 hours |" in cell_text(
        read(course / course_map.START_PAGE)["cells"][1]
    )
    written = {path: path.read_bytes() for path in course.glob("*.ipynb")}
    assert course_map.update(course) == []
    assert {path: path.read_bytes() for path in course.glob("*.ipynb")} == written


def sources(path):
    return [
        (cell.cell_type, cell.source)
        for cell in nbformat.read(path, as_version=4).cells
    ]


def test_writing_inserts_missing_navigation_and_moves_a_misplaced_cell(course):
    chapter = course / CHAPTERS[2].name
    committed = nbformat.read(chapter, as_version=4)
    notebook = nbformat.read(chapter, as_version=4)
    del notebook.cells[1]  # the link to the start page
    end = notebook.cells.pop()  # the last cell moved into the middle, with old text
    end.source = f"- [Next: somewhere](99_gone.ipynb)\n\n{course_map.NAV_MARKER}"
    notebook.cells.insert(5, end)
    nbformat.write(notebook, chapter)
    assert course_map.update(course, check=True) == [chapter]
    course_map.update(course)
    assert sources(chapter) == [
        (cell.cell_type, cell.source) for cell in committed.cells
    ]
    kept = nbformat.read(chapter, as_version=4).cells
    assert [cell.id for cell in kept[2:-1]] == [
        cell.id for cell in committed.cells[2:-1]
    ]
    assert kept[1].id == end.id, "the navigation cell found is reused, id and all"


def test_a_chapter_without_time_or_prerequisites_is_named(course):
    chapter = course / CHAPTERS[0].name
    notebook = nbformat.read(chapter, as_version=4)
    notebook.cells[0].source = notebook.cells[0].source.replace(
        "**Prerequisites:**", ""
    )
    nbformat.write(notebook, chapter)
    with pytest.raises(
        ValueError, match=rf"{CHAPTERS[0].name}, first cell: no '\*\*Prerequisites"
    ):
        course_map.update(course, check=True)


def test_a_start_page_without_the_map_cell_is_refused(course):
    start = course / course_map.START_PAGE
    notebook = nbformat.read(start, as_version=4)
    notebook.cells = [
        cell for cell in notebook.cells if course_map.MAP_MARKER not in cell.source
    ]
    nbformat.write(notebook, start)
    with pytest.raises(
        ValueError, match="exactly one Markdown cell ending with the marker"
    ):
        course_map.update(course, check=True)


def test_first_clause_keeps_parentheses_and_maths_whole():
    assert (
        course_map.first_clause("chapter 4 ($a; b$) and 5; more")
        == "chapter 4 ($a; b$) and 5"
    )
    assert course_map.first_clause("none of the other chapters. Matrices") == (
        "none of the other chapters"
    )
    assert course_map.first_clause("no stop at all") == "no stop at all"
