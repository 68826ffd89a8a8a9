"""Every chapter as a student reads it: the main line first, the coursework in a casebook.

Each chapter opens with its goals, time and prerequisites; its main line
(numbered sections, Pitfalls, Exercises, Summary) reads without the casebook
and uses no name, section or exercise before the place that defines it; the
last section, ``## Casebook: the coursework``, holds what the source
coursework did, each entry naming the source-record item it rests on and
linked from the main line, in at most a quarter of the chapter's cells.
``python tools/outline.py`` prints the shares.
"""

import ast
import builtins
import pathlib
import re
import sys

import pytest
from IPython.core.inputtransformer2 import TransformerManager

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

import outline  # noqa: E402

CHAPTERS = outline.chapters()
IDS = [path.stem[:2] for path in CHAPTERS]
LINK = re.compile(r"\]\(#([^)\s]+)\)")
PITFALL_BOX = "> **Pitfall"
MAX_PITFALL_CHARACTERS = 800


@pytest.fixture(scope="module", params=CHAPTERS, ids=IDS)
def chapter(request):
    return outline.outline(request.param)


def markdown(cells):
    return [
        (index, outline.source(cell))
        for index, cell in enumerate(cells)
        if cell["cell_type"] == "markdown"
    ]


def test_the_chapter_opens_with_goals_time_and_prerequisites(chapter):
    opening = outline.source(chapter.cells[0])
    assert re.match(r"# Chapter \d+: ", opening), "cell 0 must start '# Chapter N: ...'"
    assert "## Learning goals" in opening
    assert re.search(r"\*\*Time:\*\*[^\n]*\d+\s*(minutes|hours?)\b", opening), (
        "the goals must give an estimated time: '**Time:** about N minutes'"
    )
    assert re.search(r"\*\*Prerequisites:\*\* *\S", opening), (
        "the goals must say what is assumed: '**Prerequisites:** ...'"
    )


def test_the_casebook_is_the_last_section_after_exercises_and_summary(chapter):
    assert chapter.casebook is not None, f"no '## {outline.CASEBOOK_HEADING}' section"
    top = [h for h in chapter.headings if h.level == 2]
    assert top[-1].text == outline.CASEBOOK_HEADING, (
        f"the casebook must be the last section, not {top[-1].text!r}"
    )
    names = [h.text for h in top]
    exercises = [
        i for i, name in enumerate(names) if re.match(r"\d+\. Exercises$", name)
    ]
    assert exercises, "no numbered '## N. Exercises' section"
    assert "Summary" in names, "no '## Summary' section"
    assert exercises[0] < names.index("Summary") < len(names) - 1


def test_the_casebook_takes_at_most_a_quarter_of_the_cells(chapter):
    share = chapter.casebook_share
    assert share <= outline.MAX_CASEBOOK_SHARE, (
        f"{chapter.path.name}: the casebook holds {share:.0%} of the cells "
        f"(at most {outline.MAX_CASEBOOK_SHARE:.0%})"
    )


def test_each_casebook_entry_names_its_source_record_and_the_main_line_links_it(
    chapter,
):
    entries = chapter.entries()
    assert entries, "the casebook has no '###' entries"
    main_links = {
        target
        for _, text in markdown(chapter.main_line)
        for target in LINK.findall(text)
    }
    for entry in entries:
        assert entry.records, (
            f"casebook entry {entry.heading.text!r} names no 'Source record: H<n>.<m>'"
        )
        assert entry.heading.id in main_links, (
            f"casebook entry {entry.heading.text!r} is linked from no main-line cell "
            f"(link it as [...](#{entry.heading.id}))"
        )


def test_every_link_to_a_heading_finds_it(chapter):
    ids = {heading.id for heading in chapter.headings}
    broken = [
        (index, target)
        for index, text in markdown(chapter.cells)
        for target in LINK.findall(text)
        if target not in ids
    ]
    assert not broken, f"links to headings that do not exist (cell, id): {broken}"


def test_pitfall_boxes_are_short(chapter):
    boxes = [
        (index, text)
        for index, text in markdown(chapter.main_line)
        if text.startswith(PITFALL_BOX)
    ]
    assert boxes, f"no main-line Pitfall box ('{PITFALL_BOX}: name.** ...')"
    long = [
        (index, len(text))
        for index, text in boxes
        if len(text) > MAX_PITFALL_CHARACTERS
    ]
    assert not long, (
        f"Pitfall boxes longer than {MAX_PITFALL_CHARACTERS} characters (cell, length): "
        f"{long}; the whole story belongs in the casebook"
    )


def _imports_sources(code):
    tree = ast.parse(TransformerManager().transform_cell(code))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import) and any(
            alias.name.startswith("twolink_course.sources") for alias in node.names
        ):
            return True
        if isinstance(node, ast.ImportFrom) and (
            (node.module or "").startswith("twolink_course.sources")
            or (
                node.module == "twolink_course"
                and any(a.name == "sources" for a in node.names)
            )
        ):
            return True
    return False


def test_the_main_line_code_does_not_import_the_sources(chapter):
    # a main-line use of a source module imported in the casebook is a forward
    # reference, which the next test catches
    offending = [
        (index, outline.source(cell).splitlines()[0])
        for index, cell in enumerate(chapter.main_line)
        if cell["cell_type"] == "code" and _imports_sources(outline.source(cell))
    ]
    assert not offending, (
        f"main-line code cells that import twolink_course.sources (cell, first line): {offending}"
    )


def _names(code):
    """The names a cell binds and the names it reads (IPython syntax transformed away)."""
    tree = ast.parse(TransformerManager().transform_cell(code))
    bound, read = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            (read if isinstance(node.ctx, ast.Load) else bound).add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            bound.add(node.name)
        elif isinstance(node, ast.arg):
            bound.add(node.arg)
        elif isinstance(node, ast.alias):
            bound.add((node.asname or node.name).split(".")[0])
        elif isinstance(node, ast.ExceptHandler) and node.name:
            bound.add(node.name)
    return bound, read - bound - set(dir(builtins))


def test_no_code_cell_uses_a_name_defined_only_later(chapter):
    code = [
        (index, _names(outline.source(cell)))
        for index, cell in enumerate(chapter.cells)
        if cell["cell_type"] == "code"
    ]
    forward = []
    for position, (index, (_, read)) in enumerate(code):
        earlier = set().union(*(bound for _, (bound, _) in code[:position]))
        for name in sorted(read - earlier):
            later = [i for i, (bound, _) in code[position + 1 :] if name in bound]
            if later:
                forward.append((index, name, later[0]))
    assert not forward, (
        f"names used before the cell that defines them (cell, name, defined in): {forward}"
    )


def test_the_main_line_refers_to_no_later_section_or_exercise(chapter):
    numbered = [
        (h.cell, int(match.group(1)))
        for h in chapter.headings
        if h.level == 2 and (match := re.match(r"(\d+)\. ", h.text))
    ]
    exercises = next(
        (
            h.cell
            for h in chapter.headings
            if h.level == 2 and h.text.endswith(". Exercises")
        ),
        len(chapter.cells),
    )
    forward = []
    for index, text in markdown(chapter.main_line)[1:]:
        current = max((number for cell, number in numbered if cell <= index), default=0)
        for match in re.finditer(r"\b[Ss]ections? (\d+)\b|§ ?(\d+)", text):
            target = int(match.group(1) or match.group(2))
            if target > current:
                forward.append((index, match.group(0)))
        if index < exercises:
            forward += [
                (index, match.group(0))
                for match in re.finditer(r"\b[Ee]xercises? \d+\.\d+", text)
            ]
    assert not forward, (
        f"main-line references to what comes later (cell, text): {forward}"
    )
