"""The student edition: solutions stubbed, nothing shown in advance, notebooks still run, self-checks flip.

The whole edition (``tools/editions.py student``: the notebooks, the start
page, a twolink wheel and a zip of them, built once per test run and shared
with the browser's first-run test: ``student_edition_bundle`` in
``tests/conftest.py``) is unpacked away from the repository and chapter 1 run
in a fresh virtual environment without twolink and the widgets: its first cell
installs twolink from the wheel beside it, at the pinned versions.

Builds ``build/student``-style notebooks in a temporary folder and checks that
they store no self-check verdict ("correct" or otherwise), do not say that the
exercise cells hold worked solutions, and that no cell but a check cell reads
an answer a stub replaces; the committed notebook's stored self-check output
says "correct." (nbval, in the same test run, re-executes the committed
notebooks and compares those outputs; its chapter checks run each stub in the
chapter's kernel, where the self-check must say "not solved yet").
"""

import json
import os
import pathlib
import re
import subprocess
import sys
import zipfile

import _venvs
import nbformat
import pytest
from IPython.core.inputtransformer2 import TransformerManager
from jupyter_client import KernelManager
from jupyter_client.kernelspec import KernelSpecManager
from nbclient import NotebookClient

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import course_map  # noqa: E402
import editions  # noqa: E402
import install_cell  # noqa: E402

#: The chapters (the start page, which has no exercise, is checked on its own).
NOTEBOOKS = course_map.chapters(ROOT / "notebooks")
START_PAGE = ROOT / "notebooks" / course_map.START_PAGE


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


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_no_cell_reads_an_answer_the_student_edition_stubs(path, student_edition):
    """Only its check cell reads what a stub replaces by ``...``: the rest of the edition runs as the chapter does.

    Each stub itself makes its check say "not solved yet" (nbval's run of the
    chapter, ``::exercises``); chapter 1's edition runs whole, away from the
    repository, below.
    """
    student = nbformat.read(student_edition / path.name, as_version=4)
    assert "### BEGIN SOLUTION" not in json.dumps(student)
    stubbed = {}
    for index, cell in enumerate(student.cells):
        if cell.cell_type != "code":
            continue
        if editions.STUB_COMMENT in cell.source:
            for line in cell.source.splitlines():
                if line.rstrip().endswith(editions.STUB_COMMENT):
                    stubbed[line.split("=")[0].strip()] = index
            continue
        code = TransformerManager().transform_cell(cell.source)
        read = editions.loaded_names(code) & set(stubbed)
        assert not read or "selfcheck.check" in cell.source, (
            f"{path.name} cell {index} reads {sorted(read)}, which the student "
            f"edition stubs (cells {sorted({stubbed[name] for name in read})})"
        )
    assert stubbed, f"{path.name}: no stubbed answer"


def test_the_start_page_is_in_the_edition_and_speaks_to_the_student(student_edition):
    student = json.loads(
        (student_edition / START_PAGE.name).read_text(encoding="utf-8")
    )
    text = "\n".join("".join(cell["source"]) for cell in student["cells"])
    instructor = START_PAGE.read_text(encoding="utf-8")
    assert "worked solution" in instructor and "<!-- STUDENT:" in instructor
    assert "worked solution" not in text and "<!--" not in text.replace(
        course_map.MAP_MARKER, ""
    )
    assert "replace each `...` with code that computes it" in text


# --- the edition away from the repository, in a fresh environment ------------------------------------------------


class Headless(NotebookClient):
    """Runs a notebook without a page: the widgets' messages go unanswered."""

    def handle_comm_msg(self, outs, msg, cell_index):
        return None


def run_in_venv(python, notebook_path, kernels, env, timeout=600):
    """``notebook_path`` executed in its own folder by a kernel of ``python``'s venv, started with ``env``."""
    _venvs.kernel_spec(kernels, "fresh", python, "fresh venv")
    notebook = nbformat.read(notebook_path, as_version=4)
    manager = KernelManager(
        kernel_name="fresh",
        kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(kernels)]),
    )
    Headless(
        notebook,
        km=manager,
        kernel_name="fresh",
        timeout=timeout,
        allow_errors=True,
        resources={"metadata": {"path": str(notebook_path.parent)}},
    ).execute(env=env)
    return notebook


def fresh_environment(tmp_path, venv_dir):
    """The variables a learner's shell would have: this machine's, without this project's."""
    env = {
        key: value
        for key, value in os.environ.items()
        if not key.startswith(("PYTHON", "JUPYTER", "VIRTUAL_ENV", "PIP_", "MPL"))
        and key != install_cell.SOURCE_VARIABLE
    }
    env["PATH"] = f"{venv_dir / 'bin'}:/usr/bin:/bin"
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    return env


@pytest.mark.infrastructure
def test_the_edition_runs_away_from_the_repository_from_its_own_wheel(
    tmp_path, student_edition_bundle, widget_wheels
):
    """Chapter 1 of the unzipped edition, run whole in a kernel of a venv that lacks
    twolink and the widgets: its first cell installs them, from the wheel beside it
    and (offline) from ``widget_wheels``, at the versions of constraints.txt beside it.

    The one chapter run here, in a fresh kernel away from the repository: what the
    stubs change must leave the rest of the chapter running (nbval runs the
    instructor's chapters in the project's kernels).  The venv's other packages are
    this environment's, linked (``_venvs.bare_venv``): that pip resolves the course
    from the package index at these pins is what ``make install`` does before any test.
    """
    written = student_edition_bundle
    archive = written[-1]
    out_dir = written[0].parent  # make student's build/student
    assert archive == out_dir.with_name("student.zip")
    away = tmp_path / "away"
    with zipfile.ZipFile(archive) as bundle:
        bundle.extractall(away)
    edition = away / "student"
    names = sorted(path.name for path in edition.iterdir())
    (wheel,) = [name for name in names if name.endswith(".whl")]
    assert wheel.startswith("twolink-") and names == sorted(
        # every notebook: the start page, the chapters and the source record they link to
        [
            *(path.name for path in (ROOT / "notebooks").glob("*.ipynb")),
            wheel,
            "constraints.txt",
            "README.md",
        ]
    )
    readme = (edition / "README.md").read_text(encoding="utf-8")
    assert START_PAGE.name in readme and install_cell.RELOAD_LINE in readme
    assert {START_PAGE.name, *(path.name for path in NOTEBOOKS)} <= set(names)
    assert (edition / "constraints.txt").read_text() == (
        ROOT / "constraints.txt"
    ).read_text()

    try:
        python = _venvs.bare_venv(
            tmp_path,
            [*_venvs.requirements("twolink", "course"), "pip"],
            without=["twolink", *widget_wheels.names],
        )
    except (OSError, subprocess.CalledProcessError) as error:  # pragma: no cover
        pytest.skip(f"cannot create a virtual environment here: {error}")
    venv_dir = tmp_path / "venv"
    env = {**fresh_environment(tmp_path, venv_dir), **widget_wheels.pip_environment()}
    for module in ("twolink", "jupyterlab_widgets", "ipympl"):
        probe = subprocess.run(
            [str(python), "-c", f"import {module}"],
            capture_output=True,
            text=True,
            env=env,
            cwd=tmp_path,
            timeout=120,
        )
        assert f"No module named '{module}'" in probe.stderr, (
            f"the venv must lack {module}"
        )

    notebook = run_in_venv(
        python, edition / NOTEBOOKS[0].name, tmp_path / "kernels", env
    )
    errors = [
        output
        for cell in notebook.cells
        for output in cell.get("outputs", [])
        if output.output_type == "error"
    ]
    assert not errors, f"{errors[0].ename}: {errors[0].evalue}"
    install = next(
        cell for cell in notebook.cells if cell.source.startswith(install_cell.MARKER)
    )
    said = output_text(install)
    assert f"installing {wheel}[course] from {install_cell.FROM_WHEEL}" in said, said
    # the venv had no widgets: the one line that says to reload the page
    assert install_cell.RELOAD_LINE in said, said
    checks = selfcheck_cells(notebook)
    assert checks
    for cell in checks:
        text = output_text(cell)
        assert "not solved yet" in text and "correct." not in text, text
    # the cell installed twolink and ipympl into the venv (not linked to this environment's)
    located = subprocess.run(
        [
            str(python),
            "-c",
            "import twolink, ipympl; print(twolink.__file__, ipympl.__file__)",
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=120,
    ).stdout.split()
    assert len(located) == 2 and all(
        path.startswith(str(venv_dir / "lib")) for path in located
    ), located
    # the course's pinned versions, not the newest: pip was offered a higher ipympl
    pins = dict(
        line.split("==")
        for line in (ROOT / "constraints.txt").read_text().splitlines()
        if "==" in line and not line.startswith("#")
    )
    offered = {path.name for path in widget_wheels.folder.glob("ipympl-*.whl")}
    assert f"ipympl-{widget_wheels.decoys['ipympl']}-py3-none-any.whl" in offered
    assert f"ipympl-{pins['ipympl']}-py3-none-any.whl" in offered
    versions = subprocess.run(
        [
            str(python),
            "-c",
            "import importlib.metadata as m; "
            "print(*(m.version(n) for n in ('matplotlib', 'mujoco', 'numpy', 'ipympl')))",
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        timeout=120,
    ).stdout.split()
    assert versions == [
        pins[name] for name in ("matplotlib", "mujoco", "numpy", "ipympl")
    ]
