"""Chapters 4 to 7's value exercises re-run on hidden inputs, as the grader runs them.

Each value exercise N.M of ``RERUN`` in ``answers/ch4.py`` ... ``ch7.py``:

- its inputs cell (first line ``# Inputs of exercise N.M``, assignments only) sits
  just before its solution cell and binds exactly the ``RERUN`` inputs, with the
  same values, and the references computed on them are the stored ones;
- the notebook's solution, re-run on two hidden draws (a seed the notebook never
  holds), gives the draw's references, while the visible answers typed in fail.

The cells run in this process, as a backward slice of the chapter (the code cells
that define what the solution reads), not in a kernel.
"""

import ast
import builtins
import contextlib
import dataclasses
import io
import json
import os
import pathlib
import sys

import numpy as np
import pytest
from IPython.core.inputtransformer2 import TransformerManager

from twolink_course import exercises
from twolink_course.exercises import judging

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import editions  # noqa: E402

import answers  # noqa: E402

#: A seed the notebooks never hold (the grader has its own).
HIDDEN_TEST_SEED = 5_318_008

NOTEBOOKS = {
    path.name[:2]: path for path in sorted((ROOT / "notebooks").glob("*.ipynb"))
}
SETUP_NAMES = set(dir(builtins))


def _cell_names(source):
    tree = ast.parse(source)
    stored, loaded = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            (stored if isinstance(node.ctx, ast.Store) else loaded).add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.AsyncFunctionDef)):
            stored.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            stored.update(
                (alias.asname or alias.name).split(".")[0] for alias in node.names
            )
        elif isinstance(node, ast.arg):
            stored.add(node.arg)
    return stored, loaded


def _exercise_cells(number):
    path = NOTEBOOKS[f"0{number.split('.')[0]}"]
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    for index, cell in enumerate(cells):
        source = "".join(cell["source"])
        if (
            cell["cell_type"] == "code"
            and source.startswith(f"# Exercise {number}")
            and editions.BEGIN in source
        ):
            return path, cells, index
    raise AssertionError(
        f"{path.name} has no solution cell starting '# Exercise {number}'"
    )


def _backward_slice(cells, index):
    """The code cells before ``cells[index]`` that define what it (transitively) reads, in order."""
    _, needed = _cell_names("".join(cells[index]["source"]))
    needed -= SETUP_NAMES
    chosen = []
    for cell in reversed(cells[:index]):
        if cell["cell_type"] != "code":
            continue
        source = TransformerManager().transform_cell(
            "".join(cell["source"])
        )  # IPython syntax (%pip) as Python
        if source.lstrip().startswith(("%", "!", "get_ipython()")):
            continue
        stored, loaded = _cell_names(source)
        if stored & needed:
            chosen.append(source)
            needed = (needed - stored) | (loaded - SETUP_NAMES)
    return chosen[::-1]


def _run(sources, namespace):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cwd = os.getcwd()
    os.chdir(ROOT / "notebooks")
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            for source in sources:
                exec(compile(source, "<notebook cell>", "exec"), namespace)
    finally:
        os.chdir(cwd)
        plt.close("all")


RERUN_CHAPTERS = ("ch4", "ch5", "ch6", "ch7")
RERUNS = {
    number: rerun
    for name in RERUN_CHAPTERS
    for number, rerun in getattr(answers.chapter(name), "RERUN", {}).items()
}


def _same_input(given, expected):
    if isinstance(expected, np.ndarray) or isinstance(given, np.ndarray):
        return np.array_equal(np.asarray(given), np.asarray(expected))
    return given == expected


def _judged(part, answer, expected):
    return judging.judge(dataclasses.replace(part, expected=expected), answer)


@pytest.mark.parametrize("number", sorted(RERUNS))
def test_the_inputs_cell_binds_the_rerun_inputs_just_before_the_solution(number):
    rerun = RERUNS[number]
    path, cells, index = _exercise_cells(number)
    inputs_cell = cells[index - 1]
    first, *rest = "".join(inputs_cell["source"]).splitlines()
    assert (
        inputs_cell["cell_type"] == "code" and first == f"# Inputs of exercise {number}"
    ), (
        f"{path.name}: the cell before exercise {number}'s solution is not its inputs cell"
    )
    body = ast.parse("\n".join(rest)).body
    assert all(
        isinstance(node, ast.Assign)
        and len(node.targets) == 1
        and isinstance(node.targets[0], ast.Name)
        for node in body
    ), (
        f"{path.name}: exercise {number}'s inputs cell holds only name = expression lines"
    )
    assert sorted(node.targets[0].id for node in body) == sorted(rerun.inputs)
    namespace = {}
    _run(_backward_slice(cells, index - 1) + ["\n".join(rest)], namespace)
    for name, value in rerun.inputs.items():
        assert _same_input(namespace[name], value), (number, name)
    references = rerun.answers(dict(rerun.inputs))
    parts = exercises.get(number).parts
    assert set(references) == {part.name for part in parts}
    for (
        part
    ) in parts:  # the re-run's references on the cell's inputs are the stored ones
        assert judging.judge(part, references[part.name]).right, (number, part.name)


@pytest.mark.parametrize("number", sorted(RERUNS))
def test_the_notebook_solution_computes_from_its_inputs_on_hidden_draws(number):
    # the grader's way: the answer cell re-run with inputs the notebook never holds
    rerun = RERUNS[number]
    path, cells, index = _exercise_cells(number)
    setup = {}
    _run(_backward_slice(cells, index), setup)
    solution = "".join(cells[index]["source"])
    visible = rerun.answers(dict(rerun.inputs))
    parts = exercises.get(number).parts
    rng = np.random.default_rng([HIDDEN_TEST_SEED, int(number.replace(".", ""))])
    for _ in range(2):
        hidden = rerun.hidden(rng)
        assert set(hidden) == set(rerun.inputs)
        assert not all(_same_input(hidden[n], rerun.inputs[n]) for n in hidden)
        expected = rerun.answers(hidden)
        namespace = {**setup, **hidden}
        _run([solution], namespace)
        for part in parts:
            verdict = _judged(part, namespace[part.name], expected[part.name])
            assert verdict.right, f"{path.name} {number} {part.name}: {verdict.message}"
        # the answers of the visible inputs, typed in, do not pass on this draw
        assert not all(
            _judged(part, visible[part.name], expected[part.name]).right
            for part in parts
        ), f"{number}: a hidden draw whose references equal the visible ones"
