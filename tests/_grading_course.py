"""A small course for the grader's tests: one chapter, ``09_synthetic``, and its references.

The chapter has the three kinds of exercise the grader knows:

- 9.1, values computed from an inputs cell (``# Inputs of exercise 9.1``: an
  arm and two angles), graded on hidden draws of the inputs (``RERUN``): the
  tip ``p_ex1`` and its distance from the base ``reach_ex1``;
- 9.2, a function ``tip(arm, q)`` graded on hidden calls, the package's
  one-liner (``arm.fk``, ``kinematics.fk``) forbidden (``FORBIDDEN``);
- 9.3, a yes/no answer, graded on the notebook's own values only.

:func:`write_course` writes the instructor's chapter into a folder;
:func:`returned` writes a student's copy with chosen answers, in the saving
conventions of JupyterLab 4, JupyterLab 3, Colab, VS Code or nbformat 3;
:data:`REFERENCES` stands for the repository's ``answers`` package.  The
kernel's self-check does not know exercise 9.x (it is not in the store): each
check cell raises a ``KeyError`` there, which changes nothing of the grading
(the verdicts come from the probes).
"""

from __future__ import annotations

import copy
import json
import pathlib
import types
import uuid

import nbformat
import numpy as np

import answers
from twolink import TwoLinkArm, arms
from twolink_course.exercises.spec import Case, ExerciseSpec, PartSpec

STEM = "09_synthetic"
IMPORTS = "import numpy as np\nfrom twolink import TwoLinkArm, arms, kinematics\nfrom twolink_course import selfcheck"
TEACHING = "demo = np.linspace(0.0, 1.0, 5)\nprint(demo.sum())"
INPUTS = "# Inputs of exercise 9.1\narm_ex1 = arms.two_metre\nq_ex1 = np.radians([30.0, 45.0])"
RIGHT = {
    "9.1": "p_ex1 = arm_ex1.fk(q_ex1)\nreach_ex1 = float(np.hypot(*p_ex1))",
    "9.2": (
        "def tip(arm, q):\n"
        "    return np.array([arm.l1 * np.cos(q[0]) + arm.l2 * np.cos(q[0] + q[1]),\n"
        "                     arm.l1 * np.sin(q[0]) + arm.l2 * np.sin(q[0] + q[1])])"
    ),
    "9.3": "faster_ex3 = True",
}
STUBS = {
    "9.1": "p_ex1 = ...  # your code here\nreach_ex1 = ...  # your code here",
    "9.2": "tip = ...  # your code here",
    "9.3": "faster_ex3 = ...  # your code here",
}
CHECKS = {
    "9.1": 'correct_ex1 = selfcheck.check("9.1", p_ex1, reach_ex1)',
    "9.2": 'correct_ex2 = selfcheck.check("9.2", tip)',
    "9.3": 'correct_ex3 = selfcheck.check("9.3", faster_ex3)',
}
Q_9_1 = np.radians([30.0, 45.0])
TIP_CASES = (
    ((1.0, 2.0), (0.0, 0.0)),
    ((2.0, 2.0), (0.5, -1.0)),
    ((0.3, 1.7), (2.5, -1.0)),
)


def _tip_case(lengths: tuple[float, float], q: tuple[float, float]) -> Case:
    arm = TwoLinkArm(*lengths)
    return Case(
        {"arm": {"arm": {"l1": lengths[0], "l2": lengths[1]}}, "q": list(q)},
        arm.fk(np.asarray(q)).tolist(),
    )


def _answers_9_1(inputs: dict) -> dict:
    p = inputs["arm_ex1"].fk(inputs["q_ex1"])
    return {"p_ex1": p, "reach_ex1": float(np.hypot(*p))}


def _hidden_9_1(rng: np.random.Generator) -> dict:
    return {
        "arm_ex1": TwoLinkArm(*rng.uniform(0.5, 3.0, 2).round(2)),
        "q_ex1": rng.uniform(-np.pi, np.pi, 2).round(4),
    }


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises."""
    right = _answers_9_1({"arm_ex1": arms.two_metre, "q_ex1": Q_9_1})
    output = PartSpec("p", "tip", "vector", shape=(2,), unit="m", components=("x", "y"))
    return [
        ExerciseSpec(
            "9.1",
            STEM,
            (
                PartSpec(
                    "p_ex1",
                    "tip",
                    "vector",
                    expected=right["p_ex1"],
                    shape=(2,),
                    unit="m",
                    components=("x", "y"),
                ),
                PartSpec(
                    "reach_ex1",
                    "reach",
                    "number",
                    expected=right["reach_ex1"],
                    unit="m",
                ),
            ),
        ),
        ExerciseSpec(
            "9.2",
            STEM,
            (
                PartSpec(
                    "tip",
                    "tip(arm, q)",
                    "function",
                    cases=tuple(_tip_case(*case) for case in TIP_CASES),
                    output=output,
                ),
            ),
        ),
        ExerciseSpec(
            "9.3", STEM, (PartSpec("faster_ex3", "faster", "bool", expected=True),)
        ),
    ]


def hidden_tip_cases(rng: np.random.Generator, count: int) -> list[Case]:
    return [
        _tip_case(
            tuple(rng.uniform(0.1, 3.0, 2).round(3)),
            tuple(rng.uniform(-3.0, 3.0, 2).round(4)),
        )
        for _ in range(count)
    ]


HIDDEN = {("9.2", "tip"): hidden_tip_cases}
RERUN = {
    "9.1": answers.Rerun(
        inputs={"arm_ex1": arms.two_metre, "q_ex1": Q_9_1},
        hidden=_hidden_9_1,
        answers=_answers_9_1,
    )
}
FORBIDDEN = {("9.2", "tip"): ("twolink.arm.TwoLinkArm.fk", "twolink.kinematics.fk")}

REFERENCES = types.SimpleNamespace(
    all_exercises=lambda: answers.with_forbidden(exercises(), FORBIDDEN),
    rerun_specs=lambda: dict(RERUN),
    hidden_cases=lambda number, part, seed, count=20: HIDDEN[number, part](
        np.random.default_rng(seed), count
    ),
    hidden_draws=answers.hidden_draws,
)


def _code(source: str, grade_id: str | None = None, locked: bool = False) -> dict:
    metadata: dict = {}
    if grade_id is not None:
        kind = grade_id.split("_")[0]
        metadata["nbgrader"] = {
            "grade": kind == "check",
            "grade_id": grade_id,
            "locked": kind != "solution",
            "schema_version": 3,
            "solution": kind == "solution",
            "task": False,
            **(
                {"points": {"check_9_1": 2}.get(grade_id, 1)} if kind == "check" else {}
            ),
        }
    return {
        "cell_type": "code",
        "execution_count": None,
        "metadata": metadata,
        "outputs": [],
        "source": source,
        "id": uuid.uuid4().hex[:8],
    }


def chapter(solutions: dict[str, str]) -> dict:
    """The chapter as JSON data, each answer cell's source from ``solutions`` (by exercise)."""
    cells = [
        {
            "cell_type": "markdown",
            "metadata": {},
            "source": "# Chapter 9: a small chapter for the grader's tests",
            "id": "title",
        },
        _code(IMPORTS),
        _code(TEACHING),
        _code(INPUTS, "inputs_9_1"),
    ]
    for number in ("9.1", "9.2", "9.3"):
        cells.append(_code(solutions[number], f"solution_{number.replace('.', '_')}"))
        cells.append(_code(CHECKS[number], f"check_{number.replace('.', '_')}"))
    return {
        "cells": cells,
        "metadata": {
            "kernelspec": {
                "display_name": "Python 3 (ipykernel)",
                "language": "python",
                "name": "python3",
            }
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def write_course(folder: pathlib.Path) -> pathlib.Path:
    """The instructor's chapter (worked solutions between the markers) in ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    solutions = {
        n: f"### BEGIN SOLUTION\n{s}\n### END SOLUTION" for n, s in RIGHT.items()
    }
    path = folder / f"{STEM}.ipynb"
    path.write_text(json.dumps(chapter(solutions)), encoding="utf-8")
    return path


def as_saved(notebook: dict, tool: str) -> dict:
    """``notebook`` as ``tool`` saves it: ``"jupyterlab4"`` (as is), ``"jupyterlab3"`` (new ids,
    nbformat 4.4 metadata), ``"colab"`` (nbformat 4.0: no cell ids, Colab's metadata, nbgrader's
    dropped), ``"vscode"`` (no ids, VS Code's metadata, sources as lists of lines),
    ``"nbformat3"`` (worksheets, ``input``, ``prompt_number``)."""
    saved = copy.deepcopy(notebook)
    if tool == "jupyterlab4":
        return saved
    if tool == "jupyterlab3":
        for cell in saved["cells"]:
            cell["id"] = str(uuid.uuid4())
        saved["nbformat_minor"] = 5
        saved["metadata"]["language_info"] = {"name": "python", "version": "3.9.7"}
        return saved
    if tool == "colab":
        for cell in saved["cells"]:
            cell.pop("id", None)
            cell["metadata"] = {"id": uuid.uuid4().hex[:12]}
            if cell["cell_type"] == "code":
                cell["metadata"]["colab"] = {"base_uri": "https://localhost:8080/"}
                cell["metadata"]["outputId"] = str(uuid.uuid4())
        saved["nbformat_minor"] = 0
        saved["metadata"] = {
            "colab": {"provenance": [], "name": f"{STEM}.ipynb"},
            "kernelspec": {"name": "python3", "display_name": "Python 3"},
            "language_info": {"name": "python"},
        }
        return saved
    if tool == "vscode":
        for cell in saved["cells"]:
            cell.pop("id", None)
            cell["source"] = cell["source"].splitlines(keepends=True)
            if cell["cell_type"] == "code":
                cell["metadata"]["vscode"] = {"languageId": "python"}
        saved["nbformat_minor"] = 2
        saved["metadata"]["vscode"] = {"interpreter": {"hash": "0" * 64}}
        saved["metadata"]["orig_nbformat"] = 4
        return saved
    if tool == "nbformat3":
        node = nbformat.from_dict(copy.deepcopy(notebook))
        return json.loads(nbformat.writes(nbformat.convert(node, 3), version=3))
    raise ValueError(f"no tool {tool!r}")


def returned(
    folder: pathlib.Path,
    name: str,
    solutions: dict[str, str] | None = None,
    tool: str = "jupyterlab4",
    extra: str | None = None,
) -> pathlib.Path:
    """A student's returned chapter: the stubs, or ``solutions`` (by exercise), a cell ``extra``
    after the imports, saved as ``tool`` saves it."""
    notebook = chapter({**STUBS, **(solutions or {})})
    if extra is not None:
        notebook["cells"].insert(2, _code(extra))
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(as_saved(notebook, tool)), encoding="utf-8")
    return path
