"""The shipped exercise store: current with answers/, and every stored part judged fairly.

For every part of every stored exercise: the right value passes in each
equivalent form; each registered typical mistake gets its own diagnosis,
differs from the right answer and from the other mistakes by more than the
tolerance (the exercise's data can tell them apart); the hints come in at
least two tiers and none states the answer's value.
"""

import math
import pathlib
import re
import sys

import numpy as np
import pytest
import sympy as sp

from twolink import TwoLinkArm
from twolink_course.exercises import judging, stored

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import build_answers  # noqa: E402

import answers  # noqa: E402

PARTS = [
    (number, part)
    for number in stored.exercise_numbers()
    for part in stored.specification(number).parts
]
IDS = [f"{number}-{part.name}" for number, part in PARTS]


def test_the_store_holds_what_answers_computes():
    assert not build_answers.stale(), "run python tools/build_answers.py"


@pytest.mark.parametrize(
    "stored_value, computed, holds",
    [
        # another machine's round-off: an integrator's, a double pole split by 1e-8
        (
            [8.42559141412725, 1.4400809610383076],
            [8.425591414117237, 1.44008096104562],
            True,
        ),
        ([-162.4, -20.854858623843068], [-162.4, -20.854858953713844], True),
        ([[2e-13, -1879.98], [-8e-16, -64.7]], [[0.0, -1879.98], [0.0, -64.7]], True),
        # a changed answer, a changed shape or kind: stale
        ([1.0, 2.0], [1.0, 2.1], False),
        (2778.49, 2769.0, False),
        ([[1.0, 2.0]], [1.0, 2.0], False),
        ([1.0], [1.0, 2.0], False),
        (3, 3.0, False),
        (True, 1, False),
        ({"value": [0.0, 1.0]}, {"value": [0.0, 1.0], "unit": "m"}, False),
        ("down", "up", False),
    ],
)
def test_the_store_is_current_to_far_above_round_off(stored_value, computed, holds):
    assert build_answers.same(stored_value, computed) is holds


def test_no_module_of_the_package_holds_a_readable_reference():
    # the store is encoded: the expected values do not appear as text in the package
    text = "\n".join(
        path.read_text(encoding="utf-8")
        for package in ("twolink", "twolink_course")
        for path in (ROOT / package).rglob("*.py")
    )
    for _, part in PARTS:
        if part.kind in ("number", "vector", "matrix", "angles"):
            for value in np.ravel(part.expected):
                shown = f"{value:.6g}"
                if (
                    len(shown.strip("-0.").replace(".", "")) >= 4
                ):  # round numbers are everywhere
                    assert shown not in text, (part.name, value)


def equivalent_forms(part):
    expected = part.expected
    if part.kind == "number":
        forms = [
            expected,
            np.float64(expected),
            np.array([expected]),
            sp.Float(expected),
        ]
    elif part.kind in ("vector", "matrix", "angles"):
        array = np.array(expected)
        forms = [
            array,
            array.tolist(),
            tuple(map(tuple, array)) if array.ndim == 2 else tuple(array),
            sp.Matrix(array),
        ]
        if part.kind == "angles":
            forms.append(
                array + 2 * np.pi * np.array([1, -2])[: array.size].reshape(array.shape)
            )
    elif part.kind == "bool":
        forms = [expected, np.bool_(expected)]
    else:
        forms = [expected, f"  {expected}\n"] if part.kind == "text" else []
    if part.tolerance.significant and part.kind == "number":
        digits = part.tolerance.significant
        forms.append(float(f"{expected:.{digits}g}"))
    return forms


@pytest.mark.parametrize("number, part", PARTS, ids=IDS)
def test_the_right_answer_passes_in_every_equivalent_form(number, part):
    for form in equivalent_forms(part):
        verdict = judging.judge(part, form)
        assert verdict.right, (
            f"{number} {part.name}: {type(form).__name__} refused: {verdict.message}"
        )


def same(a, b):
    """Equal arguments: arms by their fields, arrays to round-off."""
    if isinstance(a, TwoLinkArm) or isinstance(b, TwoLinkArm):
        return a == b
    try:
        return bool(np.allclose(a, b))
    except (TypeError, ValueError):
        return a == b


def replaying(part, values):
    """A function that returns ``values[i]`` when called with visible case ``i``'s arguments."""
    cases = [judging._arguments(case, TwoLinkArm) for case in part.cases]

    def function(**arguments):
        for known, value in zip(cases, values):
            if known.keys() == arguments.keys() and all(
                same(known[name], arguments[name]) for name in known
            ):
                return value
        raise AssertionError("called with arguments of no visible case")

    return function


@pytest.mark.parametrize("number, part", PARTS, ids=IDS)
def test_each_typical_mistake_is_told_apart_and_named(number, part):
    for mistake in part.mistakes:
        answer = (
            replaying(part, mistake.value) if part.kind == "function" else mistake.value
        )
        verdict = judging.judge(part, answer)
        assert not verdict.right, (
            f"{number} {part.name}: the mistake {mistake.diagnosis!r} equals the right answer "
            "within the tolerance: change the exercise's data"
        )
        assert verdict.message == mistake.diagnosis, (
            f"{number} {part.name}: the mistake {mistake.diagnosis!r} is diagnosed as "
            f"{verdict.message!r} (an earlier mistake gives the same value on this data)"
        )


def value_texts(value):
    """How a value could be written in a hint: 3 to 6 significant digits, degrees too."""
    texts = set()
    for number in np.ravel(value):
        if (
            not isinstance(number, (int, float))
            or number == 0
            or math.isclose(abs(number), 1.0)
        ):
            continue
        for candidate in (number, math.degrees(number)):
            for digits in (3, 4, 5, 6):
                texts.add(f"{candidate:.{digits}g}")
    return {text for text in texts if len(text.strip("-0.")) >= 2}


@pytest.mark.parametrize("number, part", PARTS, ids=IDS)
def test_hints_come_in_tiers_and_never_state_the_value(number, part):
    assert len(part.hints) >= 2, (
        f"{number} {part.name}: at least a nudge and a more specific hint"
    )
    assert len(set(part.hints)) == len(part.hints)
    for hint in part.hints:
        numbers_in_hint = set(re.findall(r"-?\d+(?:\.\d+)?", hint))
        leaked = numbers_in_hint & value_texts(part.expected)
        assert not leaked, (
            f"{number} {part.name}: a hint states the value: {leaked} in {hint!r}"
        )


FUNCTION_PARTS = [(number, part) for number, part in PARTS if part.kind == "function"]


@pytest.mark.parametrize(
    "number, part", FUNCTION_PARTS, ids=[f"{n}-{p.name}" for n, p in FUNCTION_PARTS]
)
def test_a_function_fitted_to_the_visible_cases_fails_on_hidden_ones(number, part):
    visible = [
        (judging._arguments(case, TwoLinkArm), case.expected) for case in part.cases
    ]

    def probe_fitted(**arguments):
        # what probing the self-check can learn: the visible cases' answers
        for known, expected in visible:
            if known.keys() == arguments.keys() and all(
                same(known[name], arguments[name]) for name in known
            ):
                return expected
        return part.cases[0].expected

    assert judging.judge(part, probe_fitted).right, (
        "the probe should pass the visible cases"
    )
    hidden = answers.hidden_cases(number, part.name, seed=20261124)
    assert len(hidden) >= 10
    assert not {repr(c.arguments) for c in hidden} & {
        repr(c.arguments) for c in part.cases
    }
    assert not judging.judge_function(part, probe_fitted, hidden).right
    # and the seed decides the cases: another seed, other cases
    other = answers.hidden_cases(number, part.name, seed=7)
    assert [repr(c.arguments) for c in other] != [repr(c.arguments) for c in hidden]
