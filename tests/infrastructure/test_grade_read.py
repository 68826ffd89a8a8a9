"""Any notebook a student can return, read (tools/grade_read.py) and its exercise cells found (tools/grade_release.py).

The same answers saved by JupyterLab 4 and 3, Colab (no cell ids, nbgrader's
metadata dropped), VS Code (no ids, sources as lists of lines) and as
nbformat 3 read to the same cells, and each exercise's check, answer and
inputs cells are found in each, by ``grade_id`` or by content.
"""

import json
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path[:0] = [str(ROOT / "tools"), str(ROOT / "tests")]
import _grading_course as course_9  # noqa: E402
import grade_read  # noqa: E402
import grade_release  # noqa: E402

TOOLS = ("jupyterlab4", "jupyterlab3", "colab", "vscode", "nbformat3")


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    folder = tmp_path_factory.mktemp("course")
    course_9.write_course(folder)
    return grade_release.Course.read(folder, course_9.REFERENCES)


def saved(tmp_path, tool, solutions=course_9.RIGHT):
    return grade_read.read_returned(
        course_9.returned(tmp_path, f"{tool}.ipynb", solutions, tool=tool)
    )


def code(returned):
    return [cell.source for cell in returned.cells if cell.kind == "code"]


@pytest.mark.parametrize("tool", TOOLS)
def test_every_save_reads_to_the_same_code_cells(tmp_path, tool):
    assert code(saved(tmp_path, tool)) == code(saved(tmp_path, "jupyterlab4"))


@pytest.mark.parametrize("tool", TOOLS)
def test_each_exercise_s_cells_are_found_in_every_save(tmp_path, tool, course):
    returned = saved(tmp_path, tool)
    chapter = grade_release.match_chapter(returned, f"{tool}.ipynb", course.chapters)
    assert chapter is not None and chapter.stem == course_9.STEM
    reference = saved(tmp_path, "jupyterlab4")
    for exercise in chapter.exercises:
        found = grade_release.locate(returned.cells, exercise)
        assert found == grade_release.locate(reference.cells, exercise), (
            tool,
            exercise.number,
        )
        assert found.check is not None and found.solution is not None
    where = grade_release.locate(returned.cells, chapter.exercises[0])
    assert returned.cells[where.inputs].source == course_9.INPUTS
    ids = {cell.grade_id for cell in returned.cells} - {None}
    assert (ids == set()) if tool == "colab" else ("check_9_1" in ids)


def test_cells_are_found_by_grade_id_even_renumbered_and_moved(tmp_path, course):
    returned = saved(tmp_path, "jupyterlab4")
    cells = list(returned.cells)
    exercise = course.chapters[course_9.STEM].exercises[2]  # 9.3
    where = grade_release.locate(cells, exercise)
    # a student edits the check cell's text: its grade_id still says what it is
    cells[where.check] = grade_read.Cell("code", "print('checked')", "check_9_3")
    assert grade_release.locate(cells, exercise) == where


def test_an_answer_cell_is_found_by_the_answers_it_assigns(tmp_path, course):
    returned = saved(tmp_path, "colab")
    exercise = course.chapters[course_9.STEM].exercises[1]  # 9.2
    where = grade_release.locate(returned.cells, exercise)
    assert returned.cells[where.solution].source.startswith("def tip(arm, q):")


def test_a_renamed_notebook_is_its_chapter_and_an_essay_is_none(tmp_path, course):
    returned = saved(tmp_path, "colab")
    assert (
        grade_release.match_chapter(returned, "homework.ipynb", course.chapters).stem
        == course_9.STEM
    )
    essay = grade_read.parse(
        json.dumps(
            {
                "nbformat": 4,
                "nbformat_minor": 5,
                "metadata": {},
                "cells": [
                    {
                        "cell_type": "code",
                        "source": "print('hello')",
                        "metadata": {},
                        "outputs": [],
                    }
                ],
            }
        )
    )
    assert grade_release.match_chapter(essay, "07_x.ipynb", course.chapters) is None


@pytest.mark.parametrize(
    "text, reason",
    [
        ("not json", "not JSON"),
        ("[1, 2]", "not a notebook (its JSON is not an object)"),
        ('{"nbformat": 4, "cells": 3}', "not a notebook (no list of cells)"),
        ('{"nbformat": 9, "cells": []}', "not a notebook of nbformat 3 or 4"),
        (
            '{"nbformat": 4, "cells": [{"cell_type": "video", "source": ""}]}',
            "cell 1 is no code, Markdown or raw cell",
        ),
        ('{"nbformat": 4, "cells": [{"cell_type": "code"}]}', "cell 1 has no source"),
        (
            '{"nbformat": 4, "cells": [{"cell_type": "code", "source": 5}]}',
            "a cell's source is a int, not text",
        ),
    ],
)
def test_what_is_no_notebook_is_unreadable_with_the_reason(text, reason):
    with pytest.raises(
        grade_read.Unreadable, match=f"^{reason.replace('(', '.').replace(')', '.')}"
    ):
        grade_read.parse(text)


def test_outputs_are_never_read_so_a_notebook_of_outputs_costs_nothing(tmp_path):
    notebook = course_9.chapter(course_9.RIGHT)
    # 45 MB of outputs no schema would accept: the grader never looks at them
    notebook["cells"][1]["outputs"] = [
        {"output_type": "not a kind", "junk": "x" * 45_000_000}
    ]
    path = tmp_path / "big.ipynb"
    path.write_text(json.dumps(notebook), encoding="utf-8")
    returned = grade_read.read_returned(path)
    assert code(returned)[0] == course_9.IMPORTS


def test_the_edition_is_read_from_the_notebook_s_metadata():
    notebook = course_9.chapter(course_9.STUBS)
    notebook["metadata"]["twolink_edition"] = {"commit": "abc", "digest": "123"}
    assert grade_read.parse(json.dumps(notebook)).edition == {
        "commit": "abc",
        "digest": "123",
    }


def test_paths_that_are_not_regular_files_or_too_large_are_refused_unread(tmp_path):
    os.mkfifo(tmp_path / "fifo.ipynb")  # opening it would wait for a writer forever
    (tmp_path / "zeros.ipynb").symlink_to("/dev/zero")  # reading it never ends
    big = tmp_path / "big.ipynb"
    with big.open("wb") as handle:
        handle.truncate(1001)
    assert (
        grade_read.refusal(tmp_path / "fifo.ipynb")
        == "refused: not a regular file (a FIFO, a device or a socket)"
    )
    assert (
        grade_read.refusal(tmp_path / "zeros.ipynb")
        == "refused: a symbolic link, not a regular file"
    )
    with pytest.raises(
        grade_read.Unreadable, match="refused: 1001 bytes, more than 1000"
    ):
        grade_read.read_returned(big, max_bytes=1000)
    with pytest.raises(OSError):  # a path swapped for a link after it was checked
        grade_read.read_bytes(tmp_path / "zeros.ipynb")
