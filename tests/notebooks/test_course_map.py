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
from hypothesis import given
from hypothesis import strategies as st

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


def test_the_map_and_the_navigation_are_up_to_date(capsys):
    """Fails after a chapter's title, time or prerequisites change until `python tools/course_map.py` runs.

    The tool's ``main`` runs in this process (its command line, exit status and all, runs as a
    program in ``test_the_command_line_check_exits_1_naming_the_stale_notebooks_and_writes_nothing``).
    """
    assert course_map.main(["--check"]) == 0, capsys.readouterr().err


def test_the_start_page_links_every_chapter_in_order_with_its_title_time_and_prerequisites():
    start = read(START)
    assert editions.chapter_title(start, START.stem).startswith("Start here")
    (table,) = [
        cell_text(cell)
        for cell in start["cells"]
        if cell_text(cell).endswith(course_map.MAP_MARKER)
    ]
    linked = [
        target
        for _, target in markdown_links(
            {"cells": [{"cell_type": "markdown", "source": table}]}
        )
    ]
    assert linked == [path.name for path in CHAPTERS]
    # beside the chapters, the start page links the source record (no chapter)
    others = {target for _, target in markdown_links(start)} - set(linked)
    assert others == {"source_record.ipynb"}
    rows = [line for line in table.splitlines() if line.startswith("| [")]
    for row, path in zip(rows, CHAPTERS, strict=True):
        opening = cell_text(read(path)["cells"][0])
        title = editions.chapter_title(read(path), path.stem)
        time = course_map.time_text(course_map.chapter_time(path).main_minutes)
        assert row.startswith(f"| [{title}]({path.name}) | {time} |"), row
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


RECORD = NOTEBOOKS / "source_record.ipynb"


@pytest.mark.parametrize(
    "path",
    [START, *CHAPTERS, RECORD],
    ids=[p.stem[:2] for p in [START, *CHAPTERS]] + ["record"],
)
def test_every_link_between_notebooks_resolves(path, student_edition):
    for folder in (NOTEBOOKS, student_edition):
        for _, target in markdown_links(read(folder / path.name)):
            assert (folder / target).is_file(), f"{folder}/{path.name} links {target}"


def test_nbgrader_metadata_is_still_complete():
    """``python tools/nbgrader_cells.py --check``, as a program (the one test that runs it so)."""
    result = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "nbgrader_cells.py"), "--check"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_grader_never_takes_the_start_page_for_a_chapter():
    import grade
    import grade_read
    import grade_release

    chapters = grade_release.Course.read(ROOT / "notebooks", grade.REFERENCES).chapters
    assert sorted(chapters) == [path.stem for path in CHAPTERS]
    start = grade_read.read_returned(START)
    assert grade_release.match_chapter(start, START.name, chapters) is None
    # the shared navigation cell does not pull a chapter towards another one
    for path in CHAPTERS:
        returned = grade_read.read_returned(path)
        assert (
            grade_release.match_chapter(returned, "renamed.ipynb", chapters).stem
            == path.stem
        )


# --- the tool, on a copy ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def course_at_fixed_point(tmp_path_factory):
    """A copy of the committed notebooks' folder, brought up to date by the tool (which writes into it), once.

    Whether the committed notebooks are up to date is
    ``test_the_map_and_the_navigation_are_up_to_date``'s question; these tests start
    from the tool's fixed point.  Read-only: each test changes its own copy (``course``).
    """
    folder = tmp_path_factory.mktemp("course") / "notebooks"
    shutil.copytree(NOTEBOOKS, folder, ignore=shutil.ignore_patterns(".*"))
    course_map.update(folder)
    return folder


@pytest.fixture
def course(tmp_path, course_at_fixed_point):
    """This test's own copy of the course at the tool's fixed point (``course_at_fixed_point``)."""
    return shutil.copytree(course_at_fixed_point, tmp_path / "notebooks")


def test_check_fails_on_a_stale_time_and_writing_fixes_it_once(course, capsys):
    chapter = course / CHAPTERS[1].name
    notebook = nbformat.read(chapter, as_version=4)
    notebook.cells[0].source = course_map.TIME_PARAGRAPH.sub(
        "**Time:** about 7 hours; before: a guess.", notebook.cells[0].source
    )
    nbformat.write(notebook, chapter)
    assert course_map.main(["--check", "--folder", str(course)]) == 1
    assert CHAPTERS[1].name in capsys.readouterr().err
    assert course_map.update(course) == [chapter]
    opening = nbformat.read(chapter, as_version=4).cells[0].source
    assert course_map.chapter_time(chapter).paragraph() in opening
    assert "about 7 hours" not in opening
    written = {path: path.read_bytes() for path in course.glob("*.ipynb")}
    assert course_map.update(course) == []
    assert {path: path.read_bytes() for path in course.glob("*.ipynb")} == written


def test_the_command_line_check_exits_1_naming_the_stale_notebooks_and_writes_nothing(
    tmp_path,
):
    """``python tools/course_map.py --check``, as a program: a course of the start page and the
    first chapter alone has a stale map and a stale last navigation cell (a small course: the
    program builds only chapter 1's exercises)."""
    for path in (START, CHAPTERS[0]):
        shutil.copy(path, tmp_path)
    before = {path: path.read_bytes() for path in tmp_path.iterdir()}
    stale = subprocess.run(
        [*TOOL, "--check", "--folder", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert stale.returncode == 1, stale.stdout + stale.stderr
    named = [line.split(":")[0] for line in stale.stderr.splitlines()]
    assert named == [str(tmp_path / START.name), str(tmp_path / CHAPTERS[0].name)]
    assert {path: path.read_bytes() for path in tmp_path.iterdir()} == before


def test_a_longer_chapter_gets_a_longer_time_and_the_map_follows(course):
    chapter = course / CHAPTERS[0].name
    before = course_map.chapter_time(chapter)
    notebook = nbformat.read(chapter, as_version=4)
    prose = " ".join(["word"] * (30 * course_map.WORDS_PER_MINUTE))  # 30 minutes
    notebook.cells.insert(3, nbformat.v4.new_markdown_cell(prose))
    nbformat.write(notebook, chapter)
    course_map.update(course)
    after = course_map.chapter_time(chapter)
    assert after.main.words == before.main.words + 30 * course_map.WORDS_PER_MINUTE
    assert after.main_minutes in (before.main_minutes + 30, before.main_minutes + 35)
    assert after.casebook == before.casebook
    table = cell_text(read(course / course_map.START_PAGE)["cells"][1])
    assert f"| {course_map.time_text(after.main_minutes)} |" in table


def sources(path):
    return [
        (cell.cell_type, cell.source)
        for cell in nbformat.read(path, as_version=4).cells
    ]


def test_writing_inserts_missing_navigation_and_moves_a_misplaced_cell(course):
    chapter = course / CHAPTERS[2].name
    committed = nbformat.read(chapter, as_version=4)  # as the tool wrote it
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


# --- the time rule -----------------------------------------------------------------------------------


@pytest.mark.parametrize("path", CHAPTERS, ids=[p.stem[:2] for p in CHAPTERS])
def test_every_chapter_states_the_time_the_rule_gives(path):
    opening = cell_text(read(path)["cells"][0])
    time = course_map.chapter_time(path)
    assert course_map.TIME_PARAGRAPH.search(opening)[0] == time.paragraph()
    assert time.main_minutes % course_map.ROUND_TO_MINUTES == 0
    assert time.main.minutes <= time.main_minutes < time.main.minutes + 5


def test_the_start_page_states_the_rule_and_the_course_s_totals():
    (table,) = [
        cell_text(cell)
        for cell in read(START)["cells"]
        if cell_text(cell).endswith(course_map.MAP_MARKER)
    ]
    times = [course_map.chapter_time(path) for path in CHAPTERS]
    main = sum(time.main_minutes for time in times)
    casebooks = sum(time.casebook_minutes for time in times)
    assert " ".join(course_map.RULE_TEXT.split()) in " ".join(table.split())
    assert f"{course_map.time_text(main)} for the main lines" in table
    assert f"{course_map.time_text(casebooks)} more for the casebooks" in table


def test_the_rule_counts_what_a_reader_meets_and_leaves_out_generated_cells():
    cells = [
        nbformat.v4.new_markdown_cell(
            "# Chapter 9: X\n\n**Time:** about 3 hours.\n\nSix words <!-- hidden words here --> are read here."
        ),
        nbformat.v4.new_code_cell(
            "# Setup: installs twolink\nimport twolink\nimport os"
        ),
        nbformat.v4.new_markdown_cell(
            f"[Back]({course_map.START_PAGE})\n\n{course_map.NAV_MARKER}"
        ),
        nbformat.v4.new_code_cell(
            "# a comment\n\nx = 1\nview = explorer.Explorer(figure, update, {})"
        ),
        nbformat.v4.new_markdown_cell(
            f"{course_map.CASEBOOK_HEADING}\n\nThree more words."
        ),
        nbformat.v4.new_code_cell("y = 2"),
    ]
    notebook = nbformat.v4.new_notebook(cells=cells)
    time = course_map.chapter_time("01_x.ipynb", notebook)
    # "# Chapter 9: X" (4) + "Six words are read here." (5): the Time paragraph is not counted
    assert (time.main.words, time.main.code_lines, time.main.explorers) == (9, 2, 1)
    assert (time.casebook.words, time.casebook.code_lines) == (7, 1)
    value, function = course_map.exercise_parts(1)
    assert (time.main.value_parts, time.main.function_parts) == (value, function)


@given(
    words=st.integers(0, 20000),
    code=st.integers(0, 3000),
    value=st.integers(0, 20),
    function=st.integers(0, 10),
    explorers=st.integers(0, 5),
)
def test_the_rule_adds_up_and_rounds_up_to_five_minutes(
    words, code, value, function, explorers
):
    load = course_map.Workload(words, code, value, function, explorers)
    expected = words / 60 + code / 15 + 10 * value + 15 * function + 5 * explorers
    assert load.minutes == pytest.approx(expected)
    minutes = course_map.rounded_up(load.minutes)
    assert minutes % 5 == 0 and load.minutes - 1e-6 <= minutes < load.minutes + 5
    text = course_map.time_text(minutes)
    hours, rest = divmod(minutes, 60)
    assert text.startswith("about ") and (str(rest) in text or rest == 0)
    assert (f"{hours} hour" in text) == (hours > 0)


def test_exercise_parts_count_function_and_pen_and_paper_parts_apart():
    """Counted against the stored exercises' parts (what ``answers/`` computes: tests/course/test_exercises_stored.py)."""
    sys.path.insert(0, str(ROOT))
    import answers
    from twolink_course import exercises

    for number, path in enumerate(CHAPTERS, start=1):
        pen = set(getattr(answers.chapter(f"ch{number}"), "PEN_AND_PAPER", ()))
        parts = [
            (e.number, p)
            for e in exercises.all_exercises()
            if e.chapter == path.stem
            for p in e.parts
        ]
        assert parts, path.name
        heavy = sum(1 for n, p in parts if p.kind == "function" or (n, p.name) in pen)
        assert course_map.exercise_parts(number) == (len(parts) - heavy, heavy)
