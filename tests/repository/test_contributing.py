"""CONTRIBUTING.md stays true: the names its recipes use exist where it says,
and its example exercise specification judges as the stored ones do."""

import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

from twolink import _validate as validate
from twolink import arms, budgets, ik
from twolink.ik import result, targets
from twolink_course.exercises import judging, spec

ROOT = Path(__file__).resolve().parents[2]
GUIDE = (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8")


def _section(title: str) -> str:
    start = GUIDE.index(f"## {title}\n")
    end = GUIDE.find("\n## ", start + 1)
    return GUIDE[start : end if end != -1 else None]


@pytest.mark.parametrize(
    ("module", "names"),
    [
        (spec, ["ExerciseSpec", "PartSpec", "Mistake", "Tolerance"]),
        (judging, ["judge"]),
        (targets, ["reachable_targets"]),
        (result, ["assemble_result", "one_answer_result", "IKResult"]),
        (validate, ["as_finite_scalar", "as_count", "as_flag"]),
        (budgets, ["EvaluationBudget"]),
    ],
)
def test_the_recipes_name_what_exists(module, names):
    for name in names:
        assert f"`{name}" in GUIDE or name in GUIDE, name
        assert hasattr(module, name), (
            f"{module.__name__}.{name} is named in CONTRIBUTING.md"
        )


def test_the_exercise_recipe_matches_the_test_tables():
    text = (ROOT / "tests" / "course" / "test_exercises.py").read_text(encoding="utf-8")
    for table in ("WRONG", "EQUIVALENT"):
        assert f"`{table}`" in _section("How to add an exercise")
        assert re.search(rf"^{table} = \{{", text, re.M), table
    assert (
        "check_close" not in GUIDE
    )  # the old helper, with the reference in the notebook


def test_the_example_specification_runs_as_written():
    block = re.search(
        r"```python\n( *def exercise_1_1.*?)```",
        _section("How to add an exercise"),
        re.S,
    )
    assert block, "the example specification is a python code block"
    namespace = {
        **vars(spec),
        "np": np,
        "arms": arms,
        "Q_1_1_DEG": (45.0, -30.0),
        "CHAPTER": "01_dh_forward_kinematics",
    }
    exec(textwrap.dedent(block.group(1)), namespace)
    (part,) = namespace["exercise_1_1"]().parts
    right = arms.osake.fk(np.radians([45.0, -30.0]))
    assert judging.judge(part, right).right
    assert judging.judge(part, arms.osake.fk([45.0, -30.0])).message.startswith(
        "this is the tip for the angles read as radians"
    )
    assert judging.judge(part, right + [0.1, 0.0]).message.startswith(
        "your tip position is"
    )


def test_every_solver_the_recipe_describes_returns_an_ikresult():
    """The recipe's contract holds for the solvers there are."""
    for name in ("closed_form", "newton", "minimize", "brute_force"):
        answer = getattr(ik, name)(arms.two_metre, [3.0, 1.0])
        assert isinstance(answer, ik.IKResult) and answer.success, name
