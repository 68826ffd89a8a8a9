"""Verdicts, outside the student's process: each part judged from the data its probe published.

- A value part is judged on the notebook's own inputs against the stored
  specification (a typical mistake named, a miss described), then, where the
  exercise has draws of hidden inputs, on each draw against the reference the
  package computed here (:func:`twolink_course.exercises.judging.judge_value`);
  it passes only if right every time.
- A function part is judged on its visible calls, then on the hidden ones,
  from the values the function returned (a miss on a hidden call is told
  without its arguments); a forbidden call fails it, saying why.
- Every part of a notebook whose probe found something replaced (its
  fingerprints differ from those of a genuine kernel, started the same way)
  is ``tampered``; a probe that ran and published nothing too.

Each verdict has a message in words (for the feedback file) that never shows
a hidden input.
"""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from grade_plan import Plan

from twolink_course.exercises import forbidden, judging
from twolink_course.exercises.spec import ExerciseSpec, PartSpec

PASSED, WRONG, NOT_SOLVED, TAMPERED, FAILED = (
    "passed",
    "wrong",
    "not solved",
    "tampered",
    "failed to run",
)
RESULTS = (PASSED, NOT_SOLVED, WRONG, TAMPERED, FAILED)


@dataclasses.dataclass(frozen=True)
class Verdict:
    """One part's result and why, in words."""

    number: str
    part: str  # the part's label
    result: str
    message: str = ""

    @property
    def points(self) -> int:
        """One point for a part passed."""
        return int(self.result == PASSED)


def decoded(data: Any) -> Any:
    """An answer as the probe encoded it, back as a value :func:`judging.judge` reads (untrusted data: never evaluated).

    >>> decoded({"numbers": [1.0, "nan"]}), decoded({"unsolved": True}), decoded({"bool": False})
    (array([ 1., nan]), Ellipsis, False)
    >>> type(decoded({"unreadable": "DataFrame"})).__name__
    'DataFrame'
    """
    if not isinstance(data, dict):
        return _unreadable("object")
    try:
        if data.get("unsolved") is True or data.get("missing") is True:
            return ...
        if "bool" in data and isinstance(data["bool"], bool):
            return data["bool"]
        if "text" in data and isinstance(data["text"], str):
            return data["text"]
        if "numbers" in data:
            numbers = np.asarray(data["numbers"], dtype=float)
            return float(numbers) if numbers.ndim == 0 else numbers
        if "complex" in data:
            real, imaginary = data["complex"]
            return np.asarray(real, dtype=float) + 1j * np.asarray(
                imaginary, dtype=float
            )
        if "unreadable" in data:
            return _unreadable(str(data["unreadable"]))
    except (TypeError, ValueError, OverflowError):
        pass
    return _unreadable("object")


def _unreadable(name: str) -> Any:
    """An object whose type carries ``name``, so that the judge's message names what was given."""
    name = name if name.isidentifier() else "object"
    return type(name, (), {"__repr__": lambda self: f"<a {name}>"})()


def _signature(parameters: Any) -> inspect.Signature | None:
    """The signature the probe read from the student's function, or None."""
    if not isinstance(parameters, list):
        return None
    try:
        return inspect.Signature(
            [
                inspect.Parameter(
                    str(name),
                    getattr(inspect.Parameter, str(kind)),
                    default=None if has_default else inspect.Parameter.empty,
                )
                for name, kind, has_default in parameters
            ]
        )
    except (TypeError, ValueError, AttributeError):
        return None


def replay(results: Sequence[Any], parameters: Any = None) -> Callable[..., Any]:
    """A function returning ``results`` one call after another (a raised error raised again, by name),
    with the parameters the student's function has."""
    remaining = list(results)

    def replayed(**arguments: Any) -> Any:
        result = remaining.pop(0) if remaining else {"unreadable": "nothing"}
        if isinstance(result, dict) and "raised" in result:
            name = str(result["raised"])
            error = type(name if name.isidentifier() else "Exception", (Exception,), {})
            raise error(str(result.get("message", "")))
        return decoded(result)

    signature = _signature(parameters)
    if signature is not None:
        replayed.__signature__ = signature  # type: ignore[attr-defined]
    return replayed


def _unsolved(data: Any) -> bool:
    return (
        not isinstance(data, dict)
        or data.get("missing") is True
        or data.get("unsolved") is True
    )


def judge_function_part(
    part: PartSpec, data: Any, plan: Plan, number: str
) -> tuple[str, str]:
    """``(result, message)`` of a function part from what its probe published."""
    if _unsolved(data):
        return NOT_SOLVED, "not solved (the answer is left as ...)"
    calls = data.get("calls")
    if not isinstance(calls, list):
        return WRONG, "the probe found no return values"
    if len(calls) == 1 and isinstance(calls[0], dict) and calls[0].get("unsolved"):
        return NOT_SOLVED, "not solved (the answer is left as ...)"
    called = data.get("forbidden")
    if isinstance(called, str) and called in part.forbidden:
        return WRONG, forbidden.reason(called)
    key = (number, part.name)
    verdict = judging.judge_function(
        part,
        replay(calls, data.get("parameters")),
        plan.calls.get(key, part.cases),
        shown=plan.shown.get(key),
    )
    return (PASSED, "") if verdict.right else (WRONG, verdict.message)


def judge_value_part(
    part: PartSpec,
    data: Any,
    draws: Sequence[Any],
    references: Sequence[Mapping[str, Any]],
    inputs: Sequence[str],
) -> tuple[str, str]:
    """``(result, message)`` of a value part: on the notebook's inputs, then on each hidden draw."""
    if _unsolved(data):
        return NOT_SOLVED, "not solved (the answer is left as ...)"
    verdict = judging.judge(part, decoded(data))
    if not verdict.right:
        return WRONG, verdict.message
    names = ", ".join(inputs) or "its inputs"
    for index, reference in enumerate(references):
        draw = draws[index] if index < len(draws) else None
        if not isinstance(draw, dict) or not isinstance(draw.get("answers"), dict):
            return WRONG, (
                "right on the exercise's inputs, but your answer cell did not finish on "
                "other inputs the grader gave it (within the time limit per cell)"
            )
        if isinstance(draw.get("raised"), str):
            return WRONG, (
                f"right on the exercise's inputs, but your answer cell raised "
                f"{draw['raised']} on other inputs the grader gave it: compute every "
                f"answer from the inputs cell's names ({names})"
            )
        answer = draw["answers"].get(part.name)
        if _unsolved(answer):
            return WRONG, (
                f"right on the exercise's inputs, but your answer cell did not assign "
                f"{part.name} on other inputs the grader gave it"
            )
        again = judging.judge_value(part, decoded(answer), reference[part.name])
        if (
            not again.right
        ):  # how it misses is not told: it would say what the reference is
            return WRONG, (
                "right on the exercise's inputs but not on other inputs the grader gave "
                f"your answer cell: compute every answer from the inputs cell's names "
                f"({names}), not from numbers typed in"
            )
    return PASSED, ""


def tampering(
    probed: Sequence[str], reports: Mapping[str, Any], genuine: Mapping[str, str]
) -> list[str]:
    """The signs that the notebook changed what the probe relies on, in words (empty: none)."""
    signs: list[str] = []
    for number in probed:
        report = reports.get(number, {}).get("visible", "not run")
        if report == "silent" or (report != "not run" and not isinstance(report, dict)):
            signs.append(f"the probe after check {number} published nothing")
        elif isinstance(report, dict):
            found = report.get("fingerprints")
            if not isinstance(found, dict):
                signs.append(f"the probe after check {number} sent no fingerprints")
                continue
            changed = sorted(k for k, v in genuine.items() if found.get(k) != v)
            if changed:
                signs.append(
                    f"replaced before check {number}: {', '.join(changed[:4])}"
                )
    return signs


def verdicts(
    exercises: Sequence[ExerciseSpec],
    probed: Sequence[str],
    ran: Mapping[str, Any],
    plan: Plan,
    genuine: Mapping[str, str],
) -> tuple[list[Verdict], list[str]]:
    """One verdict per part of ``exercises``, and the signs of tampering found."""
    reports = ran.get("reports", {})
    if not isinstance(reports, dict):
        reports = {}
    signs = tampering(probed, reports, genuine)
    rows = []
    for exercise in exercises:
        found = reports.get(exercise.number, {})
        report = (
            found.get("visible", "not run") if isinstance(found, dict) else "not run"
        )
        draws = plan.draws.get(exercise.number, ())
        for part in exercise.parts:
            if signs:
                result, message = (
                    TAMPERED,
                    f"the notebook changed what grading relies on ({signs[0]})",
                )
            elif exercise.number not in probed:
                result, message = NOT_SOLVED, "no answer cell of this exercise found"
            elif not isinstance(report, dict):
                result, message = (
                    FAILED,
                    "the notebook stopped before this exercise's check",
                )
            else:
                answers = report.get("answers")
                data = answers.get(part.name) if isinstance(answers, dict) else None
                if part.kind == "function":
                    result, message = judge_function_part(
                        part, data, plan, exercise.number
                    )
                else:
                    rerun = [d for d in draws if part.name in d.references]
                    result, message = judge_value_part(
                        part,
                        data,
                        [found.get("draws", {}).get(i) for i in range(len(rerun))],
                        [draw.references for draw in rerun],
                        sorted(rerun[0].inputs) if rerun else [],
                    )
            rows.append(Verdict(exercise.number, part.label, result, message))
    return rows, signs


def methods(
    exercises: Sequence[ExerciseSpec],
    plan: Plan,
    reasons: Mapping[str, str] | None = None,
    on_paper: frozenset[tuple[str, str]] = frozenset(),
) -> list[tuple[str, str, str]]:
    """How each part is graded, in words: ``(exercise, part, how)``.

    ``reasons``: why an exercise without hidden inputs has none (a choice, a
    yes/no, a pen-and-paper result), by exercise number; ``on_paper``: the
    value parts worked on paper, as ``(exercise, part)`` (``answers.on_paper``).
    """
    found = []
    for exercise in exercises:
        for part in exercise.parts:
            key = (exercise.number, part.name)
            if part.kind == "function":
                how = f"its visible calls and {len(plan.calls.get(key, ())) - plan.shown.get(key, 0)} hidden ones"
                if part.forbidden:
                    how += (
                        ", with "
                        + ", ".join(forbidden.shown_name(p) for p in part.forbidden)
                        + " unavailable"
                    )
            elif any(
                part.name in d.references for d in plan.draws.get(exercise.number, ())
            ):
                how = f"the exercise's inputs and {len(plan.draws[exercise.number])} hidden draws of them"
            elif key in on_paper or plan.draws.get(exercise.number):
                how = "the exercise's inputs only (worked on paper: no reference on other inputs)"
            else:
                why = (reasons or {}).get(exercise.number, "no inputs cell to re-run")
                how = f"the exercise's inputs only ({why})"
            found.append((exercise.number, part.name, how))
    return found
