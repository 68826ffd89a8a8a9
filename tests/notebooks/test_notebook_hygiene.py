"""Committed notebooks are normalised, executed in order and free of errors.

nbval (run by the same `make test`) re-executes each notebook and compares
outputs; these checks catch what nbval does not: a notebook saved from a dirty
kernel, with widget state or timing metadata, with an error or a warning in
its stored output, or not passed through nbstripout.
"""

import json
import pathlib
import shutil
import subprocess
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))
import course_map  # noqa: E402

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parents[2] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))


def test_the_course_has_chapters():
    assert len(NOTEBOOKS) >= 1, f"no notebooks found in {NOTEBOOK_DIR}"


@pytest.fixture(params=NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def notebook(request):
    return request.param, json.loads(request.param.read_text(encoding="utf-8"))


def code_cells(content):
    return [cell for cell in content["cells"] if cell["cell_type"] == "code"]


def test_executed_top_to_bottom_in_one_kernel(notebook):
    path, content = notebook
    counts = [cell.get("execution_count") for cell in code_cells(content)]
    assert counts == list(range(1, len(counts) + 1)), (
        f"{path.name}: execution counts {counts[:8]}...: run `make notebooks` to re-execute it cleanly"
    )


def test_no_error_or_warning_outputs(notebook):
    path, content = notebook
    for index, cell in enumerate(content["cells"]):
        for output in cell.get("outputs", []):
            assert output["output_type"] != "error", (
                f"{path.name} cell {index}: stored error {output.get('ename')}"
            )
            if output["output_type"] == "stream":
                assert output["name"] != "stderr", (
                    f"{path.name} cell {index}: stderr output: {''.join(output['text'])[:200]}"
                )


def test_no_widget_state_or_timing_metadata(notebook):
    path, content = notebook
    assert "widgets" not in content["metadata"], (
        f"{path.name}: widget state in metadata (GitHub will not render it)"
    )
    for index, cell in enumerate(content["cells"]):
        assert "execution" not in cell.get("metadata", {}), (
            f"{path.name} cell {index}: timing metadata"
        )


def test_normalised_by_nbstripout(tmp_path):
    """One nbstripout (as ``make notebooks`` runs it) over copies of every notebook changes none."""
    copies = []
    for path in NOTEBOOKS:
        copies.append(tmp_path / path.name)
        shutil.copyfile(path, copies[-1])
    subprocess.run(
        [sys.executable, "-m", "nbstripout", "--keep-output", "--keep-count"]
        + [str(copy) for copy in copies],
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    changed = [
        path.name
        for path in NOTEBOOKS
        if (tmp_path / path.name).read_bytes() != path.read_bytes()
    ]
    assert not changed, f"{changed} are not normalised: run `make notebooks`"


def test_learning_goals_pitfalls_and_exercises(notebook):
    path, content = notebook
    if path not in course_map.chapters(NOTEBOOK_DIR):
        pytest.skip(
            f"{path.name} is not a chapter (tests/notebooks/test_course_map.py checks the start "
            "page, tests/notebooks/test_source_record.py the source record)"
        )
    markdown = "\n".join(
        "".join(cell["source"])
        for cell in content["cells"]
        if cell["cell_type"] == "markdown"
    )
    code = "\n".join("".join(cell["source"]) for cell in code_cells(content))
    assert "Learning goals" in markdown, f"{path.name}: no 'Learning goals' section"
    assert "Pitfall" in markdown, f"{path.name}: no Pitfall box"
    assert "### BEGIN SOLUTION" in code and "### END SOLUTION" in code, (
        f"{path.name}: no exercise solution markers"
    )
    assert code.count("### BEGIN SOLUTION") == code.count("### END SOLUTION")
    assert "../shared" not in code, (
        f"{path.name}: reads ../shared, which users and CI do not have"
    )
