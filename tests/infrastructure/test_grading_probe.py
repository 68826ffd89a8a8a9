"""The grader's probe (tools/grading_probe.py): answers encoded as plain data, fingerprints that see replacements."""

import json
import pathlib
import sys

import numpy as np
import pytest
import sympy as sp

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402
import grading_probe  # noqa: E402

from twolink import TwoLinkArm  # noqa: E402
from twolink_course import selfcheck  # noqa: E402
from twolink_course.exercises import judging  # noqa: E402


@pytest.mark.parametrize(
    "answer, encoded",
    [
        (np.array([1.0, 2.5]), {"numbers": [1.0, 2.5]}),
        ((1, 2), {"numbers": [1.0, 2.0]}),
        (np.float64(0.5), {"numbers": 0.5}),
        (sp.sqrt(4), {"numbers": 2.0}),
        (
            sp.Matrix([[1, 0], [0, sp.Rational(1, 2)]]),
            {"numbers": [[1.0, 0.0], [0.0, 0.5]]},
        ),
        (np.bool_(True), {"bool": True}),
        ("  yes ", {"text": "  yes "}),
        (..., {"unsolved": True}),
        (None, {"unsolved": True}),
        (1 + 2j, {"complex": [1.0, 2.0]}),
        (sp.Symbol("x"), {"unreadable": "Symbol"}),
        (print, {"unreadable": "function"}),
        ({"a": 1}, {"unreadable": "dict"}),
    ],
)
def test_answers_are_encoded_as_plain_data(answer, encoded):
    assert grading_probe.encode(answer) == encoded
    json.dumps(encoded)  # plain data


def test_what_the_probe_encodes_the_grader_decodes_to_the_same_verdict():
    from twolink_course import exercises

    part = exercises.get("1.1").parts[0]
    for answer in (
        np.array(part.expected),
        list(part.expected),
        np.array(part.expected) * 2,
        "tip",
    ):
        assert (
            judging.judge(part, grade.decoded(grading_probe.encode(answer))).right
            == judging.judge(part, answer).right
        )


def test_huge_answers_and_long_texts_are_cut():
    assert grading_probe.encode(np.zeros(grading_probe.MAX_NUMBERS + 1)) == {
        "unreadable": f"array of {grading_probe.MAX_NUMBERS + 1} numbers"
    }
    assert len(grading_probe.encode("x" * 10**6)["text"]) == grading_probe.MAX_TEXT


def test_a_function_is_called_on_each_request_and_its_errors_recorded():
    def tip(arm, q):
        if q[0] > 1:
            raise ValueError("too far")
        return arm.fk(q)

    calls = [
        {"arm": {"arm": {"l1": 1.0, "l2": 1.0}}, "q": [0.0, 0.0]},
        {"arm": {"arm": {"l1": 1.0, "l2": 1.0}}, "q": [2.0, 0.0]},
    ]
    assert grading_probe._calls(tip, calls) == [
        {"numbers": TwoLinkArm(1.0, 1.0).fk([0.0, 0.0]).tolist()},
        {"raised": "ValueError", "message": "too far"},
    ]
    assert grading_probe._calls(..., calls) == [{"unsolved": True}]


def test_fingerprints_change_when_a_watched_function_is_replaced(monkeypatch):
    genuine = grading_probe.fingerprints({"selfcheck": selfcheck})
    monkeypatch.setattr(selfcheck, "check", lambda *a, **k: None)
    changed = grading_probe.fingerprints({"selfcheck": selfcheck})
    assert [key for key in genuine if genuine[key] != changed[key]] == [
        "twolink_course.selfcheck.check"
    ]
    monkeypatch.undo()
    assert (
        grading_probe.fingerprints({"selfcheck": object()})["the notebook's selfcheck"]
        == "something else"
    )


def test_fingerprints_see_a_wrapper_that_behaves_the_same(monkeypatch):
    genuine = grading_probe.fingerprints({})
    real = json.dumps
    monkeypatch.setattr(json, "dumps", lambda *a, **k: real(*a, **k))
    assert grading_probe.fingerprints({})["json.dumps"] != genuine["json.dumps"]


def test_the_probe_cell_runs_the_probe_source_in_a_namespace_of_its_own():
    request = {"exercise": "1.1", "names": ["p_tip_ex1"], "calls": {}}
    cell = grade.probe_cell(request)
    assert cell.id == "grader-probe-1-1" and grade.PROBE_TAG in cell.metadata["tags"]
    assert "del _grader_probe" in cell.source and repr(request) in cell.source
    compile(cell.source, "<probe cell>", "exec")  # valid Python as written
