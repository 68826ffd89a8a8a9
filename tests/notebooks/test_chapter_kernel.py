"""The chapter checks' verdicts (tests/notebooks/chapter_kernel.py), outside a kernel.

In ``make test`` they run in each chapter's own kernel during nbval's run
(``notebooks/NN_x.ipynb::figures`` and ``::exercises``;
``tests/infrastructure/test_chapter_checks.py`` runs them that way on a small
chapter).  Here each verdict is shown to fail on what it must refuse: an
explorer that breaks at the end of a control, a self-check that never ran or
was not all correct, a stub that passes, a function that fails hidden cases.
"""

import pathlib

import chapter_kernel
import matplotlib
import numpy as np
import pytest

from twolink import arms
from twolink_course import explorer, plot, selfcheck

matplotlib.use("Agg")

ROOT = pathlib.Path(__file__).resolve().parents[2]
SEED = 5_318_008


@pytest.fixture()
def record(monkeypatch):
    """A fresh record, as :func:`chapter_kernel.install` starts one (self-check unwrapped)."""
    fresh = chapter_kernel._Record()
    fresh.originals["check"] = selfcheck.check
    monkeypatch.setattr(chapter_kernel, "RECORD", fresh)
    return fresh


def _explorer(update_fails_at=None):
    figure, ax = explorer.explorer_figure(3.0, 3.0)
    plot.setup_axes(arms.osake, ax=ax)
    line = plot.draw_arm(arms.osake, [0.0, 0.0], ax=ax)

    def update(q1):
        if q1 == update_fails_at:
            raise ValueError("no such angle")
        plot.move_arm(line, arms.osake, np.radians([q1, 0.0]))

    controls = {"q1": explorer.slider("q1", "deg", 30, -180, 180, 5)}
    return explorer.Explorer(
        figure, update, controls, describe=lambda q1: f"The arm at {q1} deg."
    ), ax


def test_an_explorer_that_follows_its_controls_is_fine(record):
    view, _ = _explorer()
    record.explorers.append((4, view))
    report = chapter_kernel.figure_report()
    assert report == {"figures": 1, "problems": []}
    assert view.values == {"q1": 30}  # put back where the chapter left it


def test_an_explorer_that_fails_at_an_end_or_loses_a_label_is_reported(record):
    view, ax = _explorer(update_fails_at=180)
    ax.set_ylabel("y")
    record.explorers.append((4, view))
    problems = chapter_kernel.figure_report()["problems"]
    assert any(
        "code cell 4: explorer control q1 = 180: ValueError: no such angle" in problem
        for problem in problems
    ), problems
    assert any("y label 'y' has no quantity [unit]" in p for p in problems), problems


def _plan(number, stub, functions=()):
    from twolink_course import exercises

    parts = [part.name for part in exercises.get(number).parts]
    return [
        {"number": number, "parts": parts, "stub": stub, "functions": list(functions)}
    ]


def test_a_solved_exercise_with_a_stub_is_fine(record):
    q = np.radians([45.0, -30.0])
    record.verdicts["1.1"] = ["correct"]
    report = chapter_kernel.exercise_report(
        _plan("1.1", "p_tip_ex1 = ...  # your code here\n"),
        str(ROOT),
        SEED,
        namespace={"p_tip_ex1": arms.osake.fk(q)},
    )
    assert report == []


def test_a_check_that_never_ran_or_said_wrong_is_reported(record):
    plan = _plan("1.1", "p_tip_ex1 = ...\n")
    said = chapter_kernel.exercise_report(plan, str(ROOT), SEED, namespace={})
    assert said == ["exercise 1.1: its self-check never ran"]
    record.verdicts["1.1"] = ["wrong"]
    said = chapter_kernel.exercise_report(plan, str(ROOT), SEED, namespace={})
    assert said == ["exercise 1.1: the worked solution's self-check said ['wrong']"]


def test_a_stub_that_leaves_the_answer_is_reported(record):
    from twolink_course import exercises

    record.verdicts["1.1"] = ["correct"]
    # the worked solution's answer, still in the kernel when the stub runs
    namespace = {"p_tip_ex1": np.asarray(exercises.get("1.1").parts[0].expected)}
    said = chapter_kernel.exercise_report(
        _plan("1.1", "# a stub that forgot the answer\n"), str(ROOT), SEED, namespace
    )
    assert said == [
        "exercise 1.1: the student edition's stub made the check say ['correct']"
    ]


def test_a_function_fitted_to_the_visible_cases_fails_hidden_ones(record):
    from twolink_course import exercises

    record.verdicts["1.4"] = ["correct"]
    part = exercises.get("1.4").parts[0]

    def right(arm, q):  # written out: the exercise switches the package's fk off
        q1, q2 = np.asarray(q, dtype=float)
        return np.array(
            [
                arm.l1 * np.cos(q1) + arm.l2 * np.cos(q1 + q2),
                arm.l1 * np.sin(q1) + arm.l2 * np.sin(q1 + q2),
            ]
        )

    visible = {
        (case.arguments["arm"]["arm"]["l1"], case.arguments["arm"]["arm"]["l2"])
        + tuple(case.arguments["q"]): np.asarray(case.expected)
        for case in part.cases
    }

    def fitted(arm, q):  # the visible answers by heart, zeros elsewhere
        key = (float(arm.l1), float(arm.l2), *map(float, q))
        return visible.get(key, np.zeros(2))

    plan = _plan("1.4", "tip_position = ...\n", functions=["tip_position"])
    assert (
        chapter_kernel.exercise_report(
            plan, str(ROOT), SEED, namespace={"tip_position": right}
        )
        == []
    )
    said = chapter_kernel.exercise_report(
        plan, str(ROOT), SEED, namespace={"tip_position": fitted}
    )
    assert len(said) == 1 and said[0].startswith(
        "exercise 1.4: tip_position fails hidden cases"
    ), said
