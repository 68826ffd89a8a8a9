"""What a reader meets in each chapter: short cells, no private attributes, clean self-checks.

These read the committed notebooks' JSON (nothing is executed): nbval checks
that the stored outputs are what the code produces, these check that the
code and outputs are what a learner can follow.
"""

import json
import pathlib
import re

import pytest

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parents[2] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
MAX_CODE_LINES = 40

# `obj._name` (a private attribute or method), but not `__dunder__`, numbers like `1._5` or `_` alone.
PRIVATE_ACCESS = re.compile(r"[A-Za-z0-9_\)\]]\._[A-Za-z][A-Za-z0-9_]*")
PRIVATE_IMPORT = re.compile(
    r"^\s*from\s+twolink\S*\s+import\s+.*\b_[A-Za-z]", re.MULTILINE
)


@pytest.fixture(params=NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def notebook(request):
    return request.param, json.loads(request.param.read_text(encoding="utf-8"))


def code_cells(content):
    return [
        (index, cell)
        for index, cell in enumerate(content["cells"])
        if cell["cell_type"] == "code"
    ]


def source(cell):
    return "".join(cell["source"])


def test_no_code_cell_over_the_line_limit(notebook):
    path, content = notebook
    long_cells = []
    for index, cell in code_cells(content):
        lines = [line for line in source(cell).splitlines() if line.strip()]
        if len(lines) > MAX_CODE_LINES:
            long_cells.append(f"cell {index}: {len(lines)} lines")
    assert not long_cells, (
        f"{path.name}: code cells over {MAX_CODE_LINES} non-blank lines ({', '.join(long_cells)}): "
        "split computation, figure and prose, or move checks into the package"
    )


def test_no_private_attributes_or_names(notebook):
    path, content = notebook
    found = []
    for index, cell in code_cells(content):
        text = source(cell)
        for match in PRIVATE_ACCESS.finditer(text):
            if match.group(0).split(".", 1)[1].startswith("__"):
                continue
            found.append(f"cell {index}: {match.group(0)}")
        for match in PRIVATE_IMPORT.finditer(text):
            found.append(f"cell {index}: {match.group(0).strip()}")
    assert not found, (
        f"{path.name}: uses private names ({'; '.join(found)}): make what the chapter needs public"
    )


def test_self_checks_print_only_their_message(notebook):
    path, content = notebook
    stray = []
    for index, cell in code_cells(content):
        if "selfcheck." not in source(cell):
            continue
        # nbgrader's hidden score line (tools/nbgrader_cells.py) shows the parts right, one int
        scored = "### BEGIN HIDDEN TESTS" in source(cell)
        for output in cell.get("outputs", []):
            if output["output_type"] == "execute_result":
                if scored and "".join(output["data"].get("text/plain", "")).isdigit():
                    scored = False  # one such result, no more
                    continue
                stray.append(
                    f"cell {index}: {''.join(output['data'].get('text/plain', ''))[:40]!r}"
                )
    assert not stray, (
        f"{path.name}: self-check cells with a stray result output ({'; '.join(stray)}): end with `;`"
    )
