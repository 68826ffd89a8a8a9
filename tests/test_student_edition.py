"""The student edition: solutions stubbed, nothing shown in advance, notebooks still run, self-checks flip.

Builds ``build/student``-style notebooks in a temporary folder and checks that
they store no self-check verdict ("correct" or otherwise) and do not say that
the exercise cells hold worked solutions; then executes each in a fresh kernel
and checks that every self-check says "not solved yet" on the stub, while the
committed notebook's stored self-check output says "correct." (nbval, in the
same test run, re-executes the committed notebooks and compares those outputs).
"""

import json
import pathlib
import re
import sys

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import editions  # noqa: E402

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


class HeadlessClient(NotebookClient):
    """Runs a notebook without emulating a widget front end.

    NotebookClient mimics JupyterLab's Output widget by routing output
    through comm messages; that emulation sometimes blocks forever on
    ``widgets.interactive`` cells (jupyter/nbclient#312).  Ignoring comm
    messages leaves widget output in the cell, which is all this test reads
    (the browser suite checks widgets in a real JupyterLab).
    """

    def handle_comm_msg(self, outs, msg, cell_index):
        return None


def selfcheck_cells(notebook):
    return [
        cell
        for cell in notebook["cells"]
        if cell["cell_type"] == "code" and "selfcheck.check" in "".join(cell["source"])
    ]


def output_text(cell):
    parts = []
    for output in cell.get("outputs", []):
        if output["output_type"] == "stream":
            parts.append("".join(output["text"]))
        elif "data" in output:
            parts.append("".join(output["data"].get("text/plain", "")))
    return "".join(parts)


def test_stub_replaces_each_block_with_the_names_it_assigns():
    source = "# Exercise 9.1\nx0 = 1\n### BEGIN SOLUTION\nq_up, q_down = 1, 2\np_tip = q_up + q_down\n### END SOLUTION\nprint(x0)\n"
    stubbed = editions.stub_source(source)
    assert (
        "q_up = ...  # your code here\nq_down = ...  # your code here\np_tip = ...  # your code here\n"
        in stubbed
    )
    assert "BEGIN SOLUTION" not in stubbed and "q_up + q_down" not in stubbed
    assert stubbed.startswith("# Exercise 9.1\nx0 = 1\n") and stubbed.endswith(
        "print(x0)\n"
    )


def test_stubs_ask_for_the_checked_answers_only():
    notebook = {
        "cells": [
            {
                "cell_type": "code",
                "source": "### BEGIN SOLUTION\nrho = 2.0\nradius_ex = rho * 3\n### END SOLUTION\n",
                "outputs": [],
                "execution_count": 1,
            },
            {"cell_type": "markdown", "source": "check it"},
            {
                "cell_type": "code",
                "source": "selfcheck.check('9.1', radius_ex)",
                "outputs": [],
                "execution_count": 2,
            },
        ]
    }
    student = editions.student_notebook(notebook)
    assert student["cells"][0]["source"] == "radius_ex = ...  # your code here\n"
    assert student["cells"][0]["execution_count"] is None
    assert notebook["cells"][0]["source"].startswith(
        "### BEGIN SOLUTION"
    )  # the original is untouched


def test_student_markdown_is_edition_aware():
    source = (
        "## Exercises\n\nEach exercise cell holds a worked solution between the markers; the cell after\n"
        "it checks the answer.\n\n<!-- BEGIN INSTRUCTOR -->For the teacher.<!-- END INSTRUCTOR -->"
        "<!-- STUDENT: For you. -->**Exercise 9.1.** Do it."
    )
    student = editions.student_markdown(source)
    assert (
        "worked solution" not in student
        and "For the teacher" not in student
        and "<!--" not in student
    )
    assert (
        "For you." in student
        and "**Exercise 9.1.** Do it." in student
        and "not solved yet" in student
    )
    assert editions.student_markdown("No markers here.") == "No markers here."


def test_indented_blocks_and_errors():
    stubbed = editions.stub_source(
        "if True:\n    ### BEGIN SOLUTION\n    angle = 3\n    ### END SOLUTION\n"
    )
    assert stubbed == "if True:\n    angle = ...  # your code here\n"
    with pytest.raises(ValueError, match="unbalanced"):
        editions.stub_source("### BEGIN SOLUTION\nx = 1\n")
    with pytest.raises(ValueError, match="assigns no name"):
        editions.stub_source("### BEGIN SOLUTION\nprint(1)\n### END SOLUTION\n")


def test_hidden_tests_are_removed_and_the_check_reads_as_before():
    check = 'correct_ex1 = selfcheck.check("9.1", radius_ex)'
    notebook = {
        "cells": [
            {
                "cell_type": "code",
                "source": "### BEGIN SOLUTION\nradius_ex = 2.0\n### END SOLUTION\n",
                "outputs": [],
                "execution_count": 1,
            },
            {
                "cell_type": "code",
                "source": check
                + "\n### BEGIN HIDDEN TESTS\ncorrect_ex1.score  # points\n### END HIDDEN TESTS",
                "outputs": [{"output_type": "execute_result", "data": {}}],
                "execution_count": 2,
            },
            {
                "cell_type": "code",
                "source": "x = 1\n### BEGIN HIDDEN TESTS\nassert x == 1\n### END HIDDEN TESTS\ny = 2\n",
                "outputs": [{"output_type": "stream", "name": "stdout", "text": "1"}],
                "execution_count": 3,
            },
        ]
    }
    student = editions.student_notebook(notebook)
    assert student["cells"][1]["source"] == check
    assert student["cells"][1]["outputs"] == []
    assert student["cells"][2]["source"] == "x = 1\ny = 2\n"
    assert student["cells"][2]["outputs"] == []  # its output may show what was hidden
    assert "HIDDEN" in notebook["cells"][1]["source"]  # the original is untouched
    with pytest.raises(ValueError, match="unbalanced hidden-test markers"):
        editions.strip_hidden_tests("x = 1\n### BEGIN HIDDEN TESTS\nx\n")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_no_hidden_test_reaches_the_student_edition(path, student_edition):
    instructor = json.loads(path.read_text(encoding="utf-8"))
    student = json.loads((student_edition / path.name).read_text(encoding="utf-8"))
    hidden = [
        "".join(cell["source"])
        for cell in instructor["cells"]
        if "### BEGIN HIDDEN TESTS" in "".join(cell["source"])
    ]
    assert len(hidden) == len(selfcheck_cells(instructor)), (
        f"{path.name}: every check cell ends with its hidden tests (tools/nbgrader_cells.py)"
    )
    hidden_lines = {
        line
        for source in hidden
        for line in editions.HIDDEN_BLOCK.search(source)[0].splitlines()
    }
    for cell in student["cells"]:
        source = "".join(cell["source"])
        assert "HIDDEN TESTS" not in source, source
        assert not hidden_lines & set(source.splitlines()), source
    checks = ["".join(cell["source"]).splitlines() for cell in selfcheck_cells(student)]
    assert all(len(lines) == 1 for lines in checks), checks


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_the_site_shows_check_cells_without_the_score_line(path):
    instructor = json.loads(path.read_text(encoding="utf-8"))
    shown = editions.without_hidden_tests(instructor)
    for before, after in zip(instructor["cells"], shown["cells"]):
        if "### BEGIN HIDDEN TESTS" not in "".join(before["source"]):
            assert after == before
            continue
        assert after["source"] == editions.strip_hidden_tests("".join(before["source"]))
        kinds = [output["output_type"] for output in before["outputs"]]
        assert kinds == ["stream", "execute_result"], kinds  # the verdicts, the score
        assert after["outputs"] == before["outputs"][:1]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_committed_solutions_pass_their_self_checks(path):
    notebook = json.loads(path.read_text(encoding="utf-8"))
    cells = selfcheck_cells(notebook)
    assert cells, f"{path.name} has no self-check cells"
    for cell in cells:
        text = output_text(cell)
        assert (
            "correct." in text
            and "not right yet" not in text
            and "not solved yet" not in text
        ), text


SELFCHECK_VERDICT = re.compile(
    r"Exercise \d+\.\d+[^\n]*: (correct|wrong|not right yet)"
)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_student_edition_shows_nothing_in_advance(path, student_edition):
    student = json.loads((student_edition / path.name).read_text(encoding="utf-8"))
    assert selfcheck_cells(student), f"{path.name} has no self-check cells"
    for cell in selfcheck_cells(student):
        assert cell["outputs"] == [] and cell["execution_count"] is None, "".join(
            cell["source"]
        )
    for cell in student["cells"]:
        text = output_text(cell) if cell["cell_type"] == "code" else ""
        assert not SELFCHECK_VERDICT.search(text), (
            f"{path.name} stores a self-check verdict: {text[:200]}"
        )
        if cell["cell_type"] == "markdown":
            markdown = "".join(cell["source"])
            assert "worked solution" not in markdown.lower(), (
                f"{path.name}: {markdown[:200]}"
            )
            assert "INSTRUCTOR -->" not in markdown and "<!-- STUDENT:" not in markdown


@pytest.mark.infrastructure
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_student_edition_runs_and_reports_not_solved(path, student_edition):
    student = nbformat.read(student_edition / path.name, as_version=4)
    assert "### BEGIN SOLUTION" not in json.dumps(student)
    HeadlessClient(
        student,
        timeout=180,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    ).execute()
    errors = [
        output
        for cell in student.cells
        for output in cell.get("outputs", [])
        if output.output_type == "error"
    ]
    assert not errors, (
        f"{path.name} student edition raised: {errors[0].ename}: {errors[0].evalue}"
    )
    for cell in selfcheck_cells(student):
        text = output_text(cell)
        assert "not solved yet" in text and "correct." not in text, (
            f"{path.name}: self-check passed on a stub: {text}"
        )
