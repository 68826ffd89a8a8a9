"""The grader's probe (tools/grading_probe.py): answers encoded as plain data, a function called with its
forbidden calls unavailable, an answer cell re-run on other inputs, fingerprints that see replacements."""

import functools
import json
import pathlib
import sys
import types

import numpy as np
import pytest
import sympy as sp

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade_plan  # noqa: E402
import grade_verdicts  # noqa: E402
import grading_probe  # noqa: E402

from twolink import TwoLinkArm, arms  # noqa: E402
from twolink_course import exercises, selfcheck  # noqa: E402
from twolink_course.exercises import judging  # noqa: E402
from twolink_course.exercises.forbidden import unavailable  # noqa: E402


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
        (np.array([np.nan, np.inf, -np.inf]), {"numbers": ["nan", "inf", "-inf"]}),
        (sp.Symbol("x"), {"unreadable": "Symbol"}),
        (print, {"unreadable": "function"}),
        ({"a": 1}, {"unreadable": "dict"}),
    ],
)
def test_answers_are_encoded_as_plain_data(answer, encoded):
    assert grading_probe.encode(answer) == encoded
    json.dumps(encoded, allow_nan=False)  # plain data, valid JSON (no bare nan)


def test_what_the_probe_encodes_the_grader_decodes_to_the_same_verdict():
    part = exercises.get("1.1").parts[0]
    for answer in (
        np.array(part.expected),
        list(part.expected),
        np.array(part.expected) * 2,
        "tip",
        [np.nan, 1.0],
    ):
        assert (
            judging.judge(
                part, grade_verdicts.decoded(grading_probe.encode(answer))
            ).right
            == judging.judge(part, answer).right
        )


def test_huge_answers_and_long_texts_are_cut():
    assert grading_probe.encode(np.zeros(grading_probe.MAX_NUMBERS + 1)) == {
        "unreadable": f"array of {grading_probe.MAX_NUMBERS + 1} numbers"
    }
    assert len(grading_probe.encode("x" * 10**6)["text"]) == grading_probe.MAX_TEXT


CALLS = [
    {"arm": {"arm": {"l1": 1.0, "l2": 1.0}}, "q": [0.0, 0.0]},
    {"arm": {"arm": {"l1": 1.0, "l2": 1.0}}, "q": [2.0, 0.0]},
]


def test_a_function_is_called_on_each_request_and_its_errors_and_parameters_recorded():
    def tip(arm, q, scale=1.0):
        if q[0] > 1:
            raise ValueError("too far")
        return scale * np.array([arm.l1 + arm.l2, 0.0])

    assert grading_probe._calls(tip, CALLS, [], unavailable) == {
        "calls": [
            {"numbers": [2.0, 0.0]},
            {"raised": "ValueError", "message": "too far"},
        ],
        "parameters": [
            ["arm", "POSITIONAL_OR_KEYWORD", False],
            ["q", "POSITIONAL_OR_KEYWORD", False],
            ["scale", "POSITIONAL_OR_KEYWORD", True],
        ],
        "forbidden": None,
    }
    assert grading_probe._calls(..., CALLS, [], unavailable) == {
        "calls": [{"unsolved": True}]
    }


def test_a_forbidden_call_is_recorded_and_the_calls_stop():
    def tip(arm, q):
        try:
            return arm.fk(q)
        except Exception:
            return np.zeros(2)

    found = grading_probe._calls(tip, CALLS, ["twolink.arm.TwoLinkArm.fk"], unavailable)
    assert (
        found["forbidden"] == "twolink.arm.TwoLinkArm.fk" and len(found["calls"]) == 1
    )


def test_an_input_travels_as_data_and_comes_back_as_it_was():
    for value in (
        TwoLinkArm(1.0, 2.0, m1=3.0),
        np.radians([30.0, 45.0]),
        2.5,
        3,
        "down",
        None,
        (1.0, [2, 3]),
    ):
        back = grading_probe.decode_input(
            json.loads(json.dumps(grade_plan.encode_input(value)))
        )
        assert repr(back) == repr(value)


class Shell:
    """What the probe uses of IPython's shell: its namespace, cell transformation, events, the kernel."""

    def __init__(self, namespace):
        self.user_ns = namespace
        self.events = types.SimpleNamespace(callbacks={"post_run_cell": []})
        self.kernel = types.SimpleNamespace(
            session=types.SimpleNamespace(send=print, pack=repr, serialize=str)
        )
        self.display_pub = types.SimpleNamespace(publish=print)

    def transform_cell(self, source):
        return source


def test_the_answer_cell_is_rerun_on_each_draw_in_a_copy_of_the_namespace():
    namespace = {
        "np": np,
        "arm_ex1": arms.two_metre,
        "q_ex1": np.zeros(2),
        "p_ex1": "stale",
        "helper": 2.0,
    }
    draws = [
        grade_plan.encode_input(TwoLinkArm(1.0, 0.5)),
        grade_plan.encode_input(TwoLinkArm(3.0, 1.0)),
    ]
    rerun = {
        "source": "p_ex1 = helper * arm_ex1.fk(q_ex1)\nif arm_ex1.l1 > 2:\n    raise ValueError",
        "draws": [
            {"arm_ex1": draw, "q_ex1": grade_plan.encode_input(np.zeros(2))}
            for draw in draws
        ],
    }
    published = []
    grading_probe._rerun(
        Shell(namespace),
        "9.1",
        rerun,
        ["p_ex1", "reach_ex1"],
        lambda data: published.append(data[grading_probe.MIME]),
    )
    assert published[0] == {
        "exercise": "9.1",
        "draw": 0,
        "answers": {"p_ex1": {"numbers": [3.0, 0.0]}, "reach_ex1": {"missing": True}},
    }
    assert published[1]["raised"] == "ValueError" and published[1]["draw"] == 1
    assert (
        namespace["p_ex1"] == "stale" and namespace["arm_ex1"] is arms.two_metre
    )  # untouched


def test_fingerprints_change_when_a_watched_function_is_replaced(monkeypatch):
    shell = Shell({"selfcheck": selfcheck})
    genuine = grading_probe.fingerprints(shell)
    monkeypatch.setattr(selfcheck, "check", lambda *a, **k: None)
    changed = grading_probe.fingerprints(shell)
    assert [key for key in genuine if genuine[key] != changed[key]] == [
        "twolink_course.selfcheck.check"
    ]
    monkeypatch.undo()
    assert (
        grading_probe.fingerprints(Shell({"selfcheck": object()}))[
            "the notebook's selfcheck"
        ]
        == "something else"
    )


def test_a_replacement_made_with_functools_wraps_is_seen(monkeypatch):
    genuine = grading_probe.fingerprints(Shell({}))
    real = selfcheck.check

    @functools.wraps(real)
    def forged(*answers, **named):
        return real(*answers, **named)

    monkeypatch.setattr(selfcheck, "check", forged)
    assert (
        grading_probe.fingerprints(Shell({}))["twolink_course.selfcheck.check"]
        != genuine["twolink_course.selfcheck.check"]
    )
    # a cache around the genuine function (no code of its own) is known by what it wraps
    assert grading_probe.fingerprint(
        functools.cache(real)
    ) != grading_probe.fingerprint(functools.cache(forged))


def test_the_kernel_s_message_path_and_its_event_callbacks_are_watched():
    shell = Shell({})
    genuine = grading_probe.fingerprints(shell)
    shell.kernel.session.pack = lambda message: repr(
        message
    )  # rewriting what the kernel sends
    assert (
        grading_probe.fingerprints(shell)["kernel kernel.session.pack"]
        != genuine["kernel kernel.session.pack"]
    )
    shell = Shell({})

    def forge_report(result):
        return None

    shell.events.callbacks["post_run_cell"].append(forge_report)
    assert (
        "forge_report"
        in grading_probe.fingerprints(shell)[
            "kernel event callbacks of the notebook's own"
        ]
    )
    assert genuine["kernel event callbacks of the notebook's own"] == "[]"


def test_fingerprints_see_a_wrapper_that_behaves_the_same(monkeypatch):
    genuine = grading_probe.fingerprints()
    real = json.dumps
    monkeypatch.setattr(json, "dumps", lambda *a, **k: real(*a, **k))
    assert grading_probe.fingerprints()["json.dumps"] != genuine["json.dumps"]
    monkeypatch.setattr(
        sys, "setprofile", lambda hook: None
    )  # the forbidden-call guard blinded
    assert grading_probe.fingerprints()["sys.setprofile"] != genuine["sys.setprofile"]
