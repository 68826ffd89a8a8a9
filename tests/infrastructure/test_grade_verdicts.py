"""What every notebook is asked (tools/grade_plan.py), the notebook built to ask it (tools/grade_build.py),
and the verdicts judged outside the kernel from the data the probe publishes (tools/grade_verdicts.py).

Everything here is data: no kernel runs.  The course is the small one of
``tests/_grading_course.py`` (a value exercise graded on hidden inputs, a
function with the package's one-liner forbidden, a yes/no answer) and, where
said, the repository's own chapters.
"""

import dataclasses
import json
import pathlib
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path[:0] = [str(ROOT), str(ROOT / "tools"), str(ROOT / "tests")]
import _grading_course as course_9  # noqa: E402
import grade_build  # noqa: E402
import grade_plan  # noqa: E402
import grade_read  # noqa: E402
import grade_release  # noqa: E402
import grade_verdicts  # noqa: E402
import grading_probe  # noqa: E402

import answers  # noqa: E402
from twolink import TwoLinkArm  # noqa: E402
from twolink_course.exercises import judging  # noqa: E402

PASSED, WRONG, NOT_SOLVED, TAMPERED, FAILED = (
    grade_verdicts.PASSED,
    grade_verdicts.WRONG,
    grade_verdicts.NOT_SOLVED,
    grade_verdicts.TAMPERED,
    grade_verdicts.FAILED,
)


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    folder = tmp_path_factory.mktemp("course")
    course_9.write_course(folder)
    return grade_release.Course.read(folder, course_9.REFERENCES)


@pytest.fixture(scope="module")
def plan(course):
    return grade_plan.Plan.drawn(course, seed=11, count=5, draws=3)


def spec(course, number):
    return next(e for e in course.exercises if e.number == number)


# ------------------------------------------------------------------ the plan


def test_the_plan_holds_visible_then_hidden_calls_and_draws_with_references(
    course, plan
):
    part = spec(course, "9.2").parts[0]
    calls = plan.calls["9.2", "tip"]
    assert calls[:3] == part.cases and len(calls) == 8 and plan.shown["9.2", "tip"] == 3
    draws = plan.draws["9.1"]
    assert len(draws) == 3
    for draw in draws:
        inputs = {
            name: grading_probe.decode_input(data) for name, data in draw.inputs.items()
        }
        assert set(inputs) == {"arm_ex1", "q_ex1"} and isinstance(
            inputs["arm_ex1"], TwoLinkArm
        )
        reference = course_9._answers_9_1(inputs)
        assert np.allclose(draw.references["p_ex1"], reference["p_ex1"])
    other = grade_plan.Plan.drawn(course, seed=12, count=5, draws=3)
    assert other.calls != plan.calls and other.draws != plan.draws
    assert repr(grade_plan.Plan.drawn(course, seed=11, count=5, draws=3)) == repr(plan)


def test_the_kernel_is_asked_with_inputs_never_with_references(course, plan):
    request = plan.request(spec(course, "9.1"), course_9.RIGHT["9.1"])
    text = repr(request)
    assert request["rerun"]["source"] == course_9.RIGHT["9.1"]
    for draw in plan.draws["9.1"]:
        for value in np.ravel(draw.references["p_ex1"]):
            assert f"{value:.6f}"[:-1] not in text  # no reference travels to the kernel
    assert plan.request(spec(course, "9.2"), None)["forbidden"] == {
        "tip": list(course_9.FORBIDDEN["9.2", "tip"])
    }
    assert "rerun" not in plan.request(spec(course, "9.3"), "faster_ex3 = True")


def test_a_draw_is_added_where_no_draw_tells_a_typed_answer_from_a_computed_one(course):
    """A draw that mostly repeats the visible inputs (as a yes/no or a count mostly gives the visible answer)."""
    visible = dict(course_9.RERUN["9.1"].inputs)

    def mostly_visible(rng):
        other = course_9._hidden_9_1(rng)
        return other if rng.uniform() < 0.2 else dict(visible)

    rerun = answers.Rerun(
        inputs=visible, hidden=mostly_visible, answers=course_9._answers_9_1
    )
    rigged = dataclasses.replace(course, reruns={"9.1": rerun})
    tip = spec(course, "9.1").parts[0]

    def told(references):
        return any(
            not judging.judge_value(tip, tip.expected, r["p_ex1"]).right
            for r in references
        )

    untold = [  # the first three draws alone: a typed-in tip passes on these seeds
        seed
        for seed in range(20)
        if not told(r for _, r in answers.hidden_draws(rerun, "9.1", seed, 3))
    ]
    assert untold
    for seed in range(20):
        draws = grade_plan.Plan.drawn(rigged, seed=seed, count=1, draws=3).draws["9.1"]
        assert len(draws) >= 3 and told(d.references for d in draws), seed
        assert (len(draws) > 3) == (seed in untold)


def test_an_input_the_kernel_cannot_be_given_is_refused_naming_it():
    with pytest.raises(TypeError, match="exercise 4.1's q_ex1 is a set"):
        grade_plan.encode_input({1.0}, "exercise 4.1's q_ex1")
    with pytest.raises(ValueError, match="must be finite"):
        grade_plan.encode_input(np.array([np.nan]), "x")
    arm = TwoLinkArm(1.5, 0.5, q_min=(-1.0, -2.0), q_max=(1.0, 2.0))
    assert grading_probe.decode_input(grade_plan.encode_input(arm)) == arm
    timings = {"closed form": 1e-6, "newton": (2e-5, 3)}  # an input by name (2.5's)
    assert grading_probe.decode_input(grade_plan.encode_input(timings)) == timings
    with pytest.raises(TypeError, match="is a dict: "):
        grade_plan.encode_input({1: 2.0}, "x")
    array = np.arange(6, dtype=np.int64).reshape(2, 3)
    back = grading_probe.decode_input(grade_plan.encode_input(array))
    assert back.dtype == array.dtype and np.array_equal(back, array)


def test_a_draw_that_binds_other_names_than_the_inputs_cell_is_refused():
    rerun = answers.Rerun(
        inputs={"q": 1.0}, hidden=lambda rng: {"p": 2.0}, answers=lambda given: {}
    )
    with pytest.raises(ValueError, match="binds \\['p'\\], the inputs cell \\['q'\\]"):
        answers.hidden_draws(rerun, "9.9", 1, 1)


# ------------------------------------------------------------------ the notebook built


def built(
    tmp_path, course, plan, tool="jupyterlab4", solutions=course_9.RIGHT, drop=()
):
    path = course_9.returned(tmp_path, f"{tool}.ipynb", solutions, tool=tool)
    data = json.loads(path.read_text(encoding="utf-8"))
    if drop:
        data["cells"] = [
            cell for cell in data["cells"] if "".join(cell["source"]) not in drop
        ]
    returned = grade_read.parse(json.dumps(data))
    return grade_build.build(returned, course.chapters[course_9.STEM], plan)


def probes(notebook):
    return [
        cell.metadata["twolink_probe"]
        for cell in notebook.cells
        if grade_build.PROBE_TAG in cell.metadata.get("tags", [])
    ]


def test_a_probe_takes_each_check_s_place_and_the_inputs_are_the_released_ones(
    tmp_path, course, plan
):
    result = built(tmp_path, course, plan)
    assert probes(result.notebook) == ["9.1", "9.2", "9.3"] == result.probed
    sources = [cell.source for cell in result.notebook.cells]
    assert course_9.INPUTS in sources
    assert not any(
        "selfcheck.check" in source for source in sources
    )  # the checks are not run
    assert result.notes == []
    # each built cell says which returned cell it is (numbered from 1, as the teacher's file)
    returned_cells = course_9.chapter(course_9.RIGHT)["cells"]
    for source, position in zip(sources, result.positions):
        if position is not None and source:
            assert source in returned_cells[position - 1]["source"]


def test_an_edited_inputs_cell_is_graded_as_released(tmp_path, course, plan):
    path = course_9.returned(tmp_path, "edited.ipynb", course_9.RIGHT)
    data = json.loads(path.read_text(encoding="utf-8"))
    inputs = next(cell for cell in data["cells"] if cell["source"] == course_9.INPUTS)
    inputs["source"] = course_9.INPUTS.replace("30.0", "0.0")
    result = grade_build.build(
        grade_read.parse(json.dumps(data)), course.chapters[course_9.STEM], plan
    )
    assert course_9.INPUTS in [cell.source for cell in result.notebook.cells]


def test_deleted_check_and_inputs_cells_are_put_back_and_said_so(
    tmp_path, course, plan
):
    result = built(
        tmp_path,
        course,
        plan,
        tool="colab",
        drop={course_9.CHECKS["9.2"], course_9.INPUTS},
    )
    assert probes(result.notebook) == ["9.1", "9.2", "9.3"]
    assert result.notes == [
        "the inputs cell of exercise 9.1 was missing: put back",
        "the check cell of exercise 9.2 was missing: put back",
    ]
    assert course_9.INPUTS in [cell.source for cell in result.notebook.cells]


def test_an_exercise_without_an_answer_cell_is_not_probed(tmp_path, course, plan):
    stub = course_9.STUBS["9.3"]
    result = built(
        tmp_path, course, plan, solutions={**course_9.RIGHT, "9.3": stub}, drop={stub}
    )
    assert probes(result.notebook) == ["9.1", "9.2"]
    assert result.notes == ["no answer cell of exercise 9.3 found"]


def test_the_probe_cell_runs_the_grader_s_own_probe_and_guard():
    source = grade_build.probe_source(
        {"exercise": "1.1", "names": [], "calls": {}, "forbidden": {}}
    )
    assert (
        repr(grade_build.PROBE_SOURCE) in source
        and repr(grade_build.GUARD_SOURCE) in source
    )
    compile(source, "<probe cell>", "exec")  # valid Python as written


# ------------------------------------------------------------------ verdicts from data


def report(answers_, draws=()):
    return {
        "visible": {"exercise": "9.1", "answers": answers_, "fingerprints": {}},
        "draws": dict(enumerate(draws)),
    }


def value_verdicts(course, plan, visible, draws):
    rows, _ = grade_verdicts.verdicts(
        [spec(course, "9.1")],
        ["9.1"],
        {"reports": {"9.1": report(visible, draws)}},
        plan,
        {},
    )
    return [(row.result, row.message) for row in rows]


def encoded(values):
    return {name: grading_probe.encode(value) for name, value in values.items()}


def test_a_value_part_passes_only_right_on_its_inputs_and_on_every_draw(course, plan):
    right = course_9._answers_9_1(
        {"arm_ex1": course_9.arms.two_metre, "q_ex1": course_9.Q_9_1}
    )
    on_draws = [{"answers": encoded(draw.references)} for draw in plan.draws["9.1"]]
    assert value_verdicts(course, plan, encoded(right), on_draws) == [(PASSED, "")] * 2
    # typed in (or read from the store, copied, forged): right on the inputs shown only
    typed = [{"answers": encoded(right)} for _ in plan.draws["9.1"]]
    for result, message in value_verdicts(course, plan, encoded(right), typed):
        assert result == WRONG and message.startswith(
            "right on the exercise's inputs but not on other inputs"
        )
        assert "(arm_ex1, q_ex1)" in message
    # one draw wrong is enough
    assert (
        value_verdicts(course, plan, encoded(right), [*on_draws[:2], typed[2]])[0][0]
        == WRONG
    )
    raised = [{"answers": {}, "raised": "ZeroDivisionError"}] * 3
    assert (
        "raised ZeroDivisionError on other inputs"
        in value_verdicts(course, plan, encoded(right), raised)[0][1]
    )
    assert (
        "did not finish"
        in value_verdicts(course, plan, encoded(right), on_draws[:1])[0][1]
    )
    assert value_verdicts(course, plan, {}, on_draws)[0][0] == NOT_SOLVED
    wrong = encoded({"p_ex1": [0.0, 0.0], "reach_ex1": float("nan")})
    (tip, tip_message), reach = value_verdicts(course, plan, wrong, on_draws)
    assert (
        tip == WRONG
        and tip_message.startswith("your tip is ")
        and "from the right point" in tip_message
    )
    assert reach == (WRONG, "your reach is nan (not a number): compute a finite number")


def test_a_hidden_draw_s_miss_is_not_described(course, plan):
    right = course_9._answers_9_1(
        {"arm_ex1": course_9.arms.two_metre, "q_ex1": course_9.Q_9_1}
    )
    close = [
        {"answers": encoded({k: np.asarray(v) + 0.01 for k, v in d.references.items()})}
        for d in plan.draws["9.1"]
    ]
    message = value_verdicts(course, plan, encoded(right), close)[0][1]
    assert "cm" not in message and "too" not in message


def test_a_part_worked_on_paper_is_judged_on_the_notebook_s_value_only(course):
    """``answers.on_paper()``: a value part of a re-run exercise with no reference on other inputs."""
    only_tip = course_9.answers.Rerun(
        inputs=dict(course_9.RERUN["9.1"].inputs),
        hidden=course_9._hidden_9_1,
        answers=lambda given: {"p_ex1": course_9._answers_9_1(given)["p_ex1"]},
    )
    with pytest.raises(
        KeyError,
        match=r"9.1: RERUN's answers\(\) gives no reference for \['reach_ex1'\]",
    ):
        grade_plan.Plan.drawn(
            dataclasses.replace(course, reruns={"9.1": only_tip}), seed=11, draws=3
        )
    on_paper = dataclasses.replace(
        course, reruns={"9.1": only_tip}, on_paper=frozenset({("9.1", "reach_ex1")})
    )
    plan = grade_plan.Plan.drawn(on_paper, seed=11, count=5, draws=3)
    assert all(set(draw.references) == {"p_ex1"} for draw in plan.draws["9.1"])
    right = course_9._answers_9_1(
        {"arm_ex1": course_9.arms.two_metre, "q_ex1": course_9.Q_9_1}
    )
    typed = [{"answers": encoded(right)} for _ in plan.draws["9.1"]]
    (tip, _), reach = value_verdicts(course, plan, encoded(right), typed)
    assert tip == WRONG and reach == (PASSED, "")  # the tip is still re-run
    wrong = {**right, "reach_ex1": 2 * right["reach_ex1"]}
    assert value_verdicts(course, plan, encoded(wrong), typed)[1][0] == WRONG
    found = {
        (n, p): how for n, p, how in grade_verdicts.methods(course.exercises, plan)
    }
    on_paper_only = grade_verdicts.methods(
        course.exercises[2:], plan, on_paper=frozenset({("9.3", "faster_ex3")})
    )
    assert on_paper_only == [
        (
            "9.3",
            "faster_ex3",
            "the exercise's inputs only (worked on paper: no reference on other inputs)",
        )
    ]
    assert found["9.1", "reach_ex1"] == (
        "the exercise's inputs only (worked on paper: no reference on other inputs)"
    )
    assert found["9.1", "p_ex1"] == "the exercise's inputs and 3 hidden draws of them"


def function_verdict(course, plan, data):
    exercise = spec(course, "9.2")
    found = {
        "visible": {"exercise": "9.2", "answers": {"tip": data}, "fingerprints": {}},
        "draws": {},
    }
    rows, _ = grade_verdicts.verdicts(
        [exercise], ["9.2"], {"reports": {"9.2": found}}, plan, {}
    )
    return rows[0].result, rows[0].message


def test_a_function_part_from_its_return_values_parameters_and_forbidden_calls(
    course, plan
):
    calls = plan.calls["9.2", "tip"]
    right = [{"numbers": list(map(float, case.expected))} for case in calls]
    parameters = [
        ["arm", "POSITIONAL_OR_KEYWORD", False],
        ["q", "POSITIONAL_OR_KEYWORD", False],
    ]
    assert function_verdict(
        course, plan, {"calls": right, "parameters": parameters}
    ) == (PASSED, "")
    fitted = right[:3] + [right[0]] * (
        len(calls) - 3
    )  # right on the visible calls only
    result, message = function_verdict(
        course, plan, {"calls": fitted, "parameters": parameters}
    )
    assert result == WRONG and message.startswith(
        "called with other arguments of the grader's (not shown)"
    )
    assert function_verdict(
        course, plan, {"calls": right[:1], "forbidden": "twolink.arm.TwoLinkArm.fk"}
    ) == (
        WRONG,
        "this exercise asks you to write it yourself: arm.fk is the package's answer",
    )
    renamed = [
        ["robot", "POSITIONAL_OR_KEYWORD", False],
        ["angles", "POSITIONAL_OR_KEYWORD", False],
    ]
    result, message = function_verdict(
        course,
        plan,
        {
            "calls": [{"raised": "TypeError", "message": "x"}] * len(calls),
            "parameters": renamed,
        },
    )
    assert message.endswith("rename robot to arm and angles to q")
    nan = [{"numbers": ["nan", "nan"]}] * len(calls)
    assert function_verdict(course, plan, {"calls": nan})[0] == WRONG
    assert (
        function_verdict(course, plan, {"calls": [{"unsolved": True}]})[0] == NOT_SOLVED
    )


def test_decoded_answers_are_data_never_code():
    assert grade_verdicts.decoded({"exec": "import os"}).__class__.__name__ == "object"
    assert np.isnan(grade_verdicts.decoded({"numbers": "nan"}))
    assert (
        grade_verdicts.decoded({"numbers": [[1, 2], [3]]}).__class__.__name__
        == "object"
    )


def test_tampering_marks_every_part_and_says_what(course, plan):
    genuine = {"twolink_course.selfcheck.check": "abc", "json.dumps": "def"}
    honest = {"answers": {}, "fingerprints": dict(genuine), "exercise": "9.1"}
    replaced = dict(
        honest, fingerprints={**genuine, "twolink_course.selfcheck.check": "zzz"}
    )
    rows, signs = grade_verdicts.verdicts(
        course.exercises,
        ["9.1", "9.2"],
        {"reports": {"9.1": {"visible": honest}, "9.2": {"visible": replaced}}},
        plan,
        genuine,
    )
    assert signs == ["replaced before check 9.2: twolink_course.selfcheck.check"]
    assert {row.result for row in rows} == {TAMPERED}
    rows, signs = grade_verdicts.verdicts(
        course.exercises,
        ["9.1"],
        {"reports": {"9.1": {"visible": "silent"}}},
        plan,
        genuine,
    )
    assert signs == ["the probe after check 9.1 published nothing"]
    rows, signs = grade_verdicts.verdicts(
        course.exercises,
        ["9.1", "9.2"],
        {"reports": {"9.1": {"visible": honest}, "9.2": {"visible": "not run"}}},
        plan,
        genuine,
    )
    assert not signs
    assert [row.result for row in rows if row.number == "9.2"] == [FAILED]
    assert [row.result for row in rows if row.number == "9.3"] == [NOT_SOLVED]


def test_the_note_of_how_each_part_is_graded(course, plan):
    found = {
        (n, p): how
        for n, p, how in grade_verdicts.methods(
            course.exercises, plan, {"9.3": "a yes/no"}
        )
    }
    assert found["9.1", "p_ex1"] == "the exercise's inputs and 3 hidden draws of them"
    assert (
        found["9.2", "tip"]
        == "its visible calls and 5 hidden ones, with arm.fk, kinematics.fk unavailable"
    )
    assert found["9.3", "faster_ex3"] == "the exercise's inputs only (a yes/no)"


def test_the_replayed_function_has_the_student_s_signature():
    function = grade_verdicts.replay(
        [], [["arm", "POSITIONAL_OR_KEYWORD", False], ["q", "KEYWORD_ONLY", True]]
    )
    assert str(judging.inspect.signature(function)) == "(arm, *, q=None)"
