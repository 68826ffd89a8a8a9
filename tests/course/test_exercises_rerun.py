"""The chapters' exercises graded on hidden inputs (``RERUN``) and their forbidden calls (``FORBIDDEN``), checked
against the chapters, for every entry of ``answers/`` and of the small course of ``tests/_grading_course.py``.

For each ``Rerun``: the chapter's inputs cell binds exactly ``inputs``; the
references on them are the stored expected values; a draw binds the same names,
gives a reference for every value part but those worked on paper
(``PEN_AND_PAPER``), and the draws tell a typed-in answer from a computed one.
Every forbidden call names a callable of the two packages.
"""

import ast
import json
import pathlib
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path[:0] = [str(ROOT), str(ROOT / "tools"), str(ROOT / "tests")]
import _grading_course as course_9  # noqa: E402

import answers  # noqa: E402
from twolink import TwoLinkArm  # noqa: E402
from twolink_course import exercises as stored  # noqa: E402
from twolink_course.exercises import forbidden, judging  # noqa: E402


def chapter_cells(stem):
    path = ROOT / "notebooks" / f"{stem}.ipynb"
    return [
        "".join(cell["source"])
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]
        if cell["cell_type"] == "code"
    ]


def bound_by_inputs_cell(cells, number):
    """What the chapter's inputs cell of ``number`` binds, run after the chapter's import statements."""
    header = f"# Inputs of exercise {number}"
    index = next(
        i
        for i, source in enumerate(cells)
        if source.split("\n", 1)[0].strip() == header
    )
    namespace: dict = {}
    for source in cells[:index]:
        try:
            tree = ast.parse(source)
        except SyntaxError:
            continue
        imports = [
            node for node in tree.body if isinstance(node, (ast.Import, ast.ImportFrom))
        ]
        exec(compile(ast.Module(imports, []), "<imports>", "exec"), namespace)
    before = set(namespace)
    exec(cells[index], namespace)
    return {
        name: value
        for name, value in namespace.items()
        if name not in before and name != "__builtins__"
    }


def same(a, b):
    if isinstance(a, TwoLinkArm) or isinstance(b, TwoLinkArm):
        return a == b
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.shape(a) == np.shape(b) and np.array_equal(a, b)
    return type(a) is type(b) and a == b


def entries():
    """``(label, exercise, rerun, cells)`` of every RERUN entry: the repository's, then the small course's."""
    found = [  # the stored exercises: what answers/ computes (tests/course/test_exercises_stored.py)
        (
            f"answers-{number}",
            stored.get(number),
            rerun,
            chapter_cells(stored.get(number).chapter),
        )
        for number, rerun in sorted(answers.rerun_specs().items())
    ]
    small = {exercise.number: exercise for exercise in course_9.exercises()}
    cells = [
        cell["source"]
        for cell in course_9.chapter(course_9.RIGHT)["cells"]
        if cell["cell_type"] == "code"
    ]
    found += [
        (f"small-{number}", small[number], rerun, cells)
        for number, rerun in course_9.RERUN.items()
    ]
    return found


ENTRIES = entries()
#: Value parts worked on paper: no reference on other inputs (``answers.on_paper``).
ON_PAPER = answers.on_paper()
IDS = [label for label, *_ in ENTRIES]


@pytest.mark.parametrize("label, exercise, rerun, cells", ENTRIES, ids=IDS)
def test_the_inputs_cell_binds_exactly_the_rerun_s_inputs(
    label, exercise, rerun, cells
):
    bound = bound_by_inputs_cell(cells, exercise.number)
    assert sorted(bound) == sorted(rerun.inputs), label
    for name, value in rerun.inputs.items():
        assert same(bound[name], value), (label, name, bound[name], value)


@pytest.mark.parametrize("label, exercise, rerun, cells", ENTRIES, ids=IDS)
def test_the_references_on_the_visible_inputs_are_the_stored_answers(
    label, exercise, rerun, cells
):
    references = rerun.answers(rerun.inputs)
    for part in exercise.parts:
        if part.kind == "function" or (exercise.number, part.name) in ON_PAPER:
            continue
        assert judging.judge(part, references[part.name]).right, (label, part.name)


@pytest.mark.parametrize("label, exercise, rerun, cells", ENTRIES, ids=IDS)
def test_hidden_draws_are_valid_and_tell_a_typed_answer_from_a_computed_one(
    label, exercise, rerun, cells
):
    values = [
        part
        for part in exercise.parts
        if part.kind != "function" and (exercise.number, part.name) not in ON_PAPER
    ]
    for seed in range(5):
        draws = answers.hidden_draws(rerun, exercise.number, seed, 3)
        for part in values:
            misses = [
                not judging.judge_value(
                    part, part.expected, references[part.name]
                ).right
                for _, references in draws
            ]
            assert any(misses), (
                f"{label} {part.name}: seed {seed}'s draws do not tell the visible answer from a right one"
            )
            for _, references in draws:
                if part.kind != "text":  # a message (2.3's) is a text
                    assert np.all(
                        np.isfinite(np.asarray(references[part.name], dtype=float))
                    ), (label, part.name)


#: Forbidden calls are the course's own: the library's or the kit's (a source's worked solution).
PACKAGES = ("twolink", "twolink_course")
FORBIDDEN = [
    (key, path)
    for name in answers.chapter_names()
    for key, paths in sorted(getattr(answers.chapter(name), "FORBIDDEN", {}).items())
    for path in paths
] + [(key, path) for key, paths in course_9.FORBIDDEN.items() for path in paths]


@pytest.mark.parametrize(
    "key, path", FORBIDDEN, ids=[f"{k[0]}-{k[1]}-{p}" for k, p in FORBIDDEN]
)
def test_every_forbidden_call_names_a_callable_of_the_package(key, path):
    assert callable(forbidden.resolve(path)) and path.split(".")[0] in PACKAGES, (
        key,
        path,
    )


def test_a_rerun_entry_is_checked_when_made():
    with pytest.raises(
        TypeError, match="Rerun.inputs must be a dict of the inputs cell's names"
    ):
        answers.Rerun(
            inputs={"not a name": 1}, hidden=lambda rng: {}, answers=lambda given: {}
        )
    with pytest.raises(TypeError, match="Rerun.hidden must be a function"):
        answers.Rerun(inputs={}, hidden=None, answers=lambda given: {})


def test_a_forbidden_call_of_no_function_part_is_refused():
    with pytest.raises(
        KeyError, match="FORBIDDEN names .'9.1', 'p_ex1'., which is no function part"
    ):
        answers.with_forbidden(
            course_9.exercises(), {("9.1", "p_ex1"): ("twolink.kinematics.fk",)}
        )
    marked = answers.with_forbidden(course_9.exercises(), course_9.FORBIDDEN)
    assert marked[1].parts[0].forbidden == course_9.FORBIDDEN["9.2", "tip"]
